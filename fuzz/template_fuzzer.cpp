// libFuzzer target: the template dialect. The input is parsed as one template file (parser,
// checks, linking); an accepted catalogue is emitted for GLSL and HLSL, guarded and unguarded,
// and every output must be ASCII with a marker that reads back. The tokenizer must give back its
// input exactly. Rejected templates must fail with one line.
#include "fuzz_support.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/front/dialect.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace {

constexpr const char* target = "template_fuzzer";

void check_tokenizer(std::string_view text) {
  std::string joined;
  for (const saagen::dialect::Token& token : saagen::dialect::tokenize(text)) joined += token.text;
  if (joined != text) saagen::fuzz::finding(target, "tokens do not concatenate to the input", text.substr(0, 80));
}

void check_file(const saagen::EmittedFile& file) {
  for (char c : file.content) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte != '\n' && (byte < 0x20 || byte >= 0x7f))
      saagen::fuzz::finding(target, "non-ASCII or control byte in emitted output", file.file_name);
  }
  const auto marker = saagen::find_marker(file.content);
  if (!marker || marker->variants != file.marker.variants) saagen::fuzz::finding(target, "marker does not read back", file.file_name);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  check_tokenizer(text);
  saagen::Catalogue catalogue;
  try {
    catalogue = saagen::Catalogue::parse({{"fuzz.saa", text}});
  } catch (const saagen::Error& error) {
    saagen::fuzz::check_message(target, error.what(), "");
    return 0;
  }
  for (const char* language : {"glsl", "hlsl"}) {
    for (const bool guards : {true, false}) {
      saagen::EmitOptions options;
      options.target = language;
      options.guards = guards;
      try {
        for (const saagen::EmittedFile& file : saagen::emit_variants(catalogue, options)) check_file(file);
      } catch (const saagen::Error& error) {
        saagen::fuzz::check_message(target, error.what(), "");
      }
    }
  }
  return 0;
}
