// libFuzzer target: scene manifest parser, planner and bundle emitter.
#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/scene/manifest.hpp"
#include "saagen/scene/planner.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace {

[[noreturn]] void finding(const char* what, std::string_view detail) {
  std::fprintf(stderr, "manifest_fuzzer: %s: %.*s\n", what, static_cast<int>(detail.size()), detail.data());
  std::abort();
}

void check_file(const saagen::EmittedFile& file) {
  for (char c : file.content) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte != '\n' && (byte < 0x20 || byte >= 0x7f)) finding("non-ASCII or control byte in emitted output", file.file_name);
  }
  const auto marker = saagen::find_marker(file.content);
  if (!marker) finding("emitted file has no readable marker", file.file_name);
  if (marker->functions != file.marker.functions || marker->variants != file.marker.variants || marker->prefix != file.marker.prefix) {
    finding("marker does not read back", file.file_name);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const saagen::Catalogue& catalogue = saagen::Catalogue::builtin();
  try {
    const saagen::Manifest manifest = saagen::parse_manifest(text, "fuzz.toml", catalogue);
    const saagen::ScenePlan plan = saagen::plan_scene(catalogue, manifest);
    if (plan.materials.size() != manifest.materials.size()) finding("plan lost a material", manifest.source_name);
    for (const saagen::EmittedFile& file : saagen::emit_scene(catalogue, manifest, plan)) check_file(file);
  } catch (const saagen::Error& error) {
    const std::string_view message = error.what();
    if (message.rfind("fuzz.toml:", 0) != 0) finding("error without the manifest's position", message);
    if (message.find('\n') != std::string_view::npos) finding("error message spans lines", message);
  }
  return 0;
}
