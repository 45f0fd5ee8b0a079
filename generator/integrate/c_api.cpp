// The C API (saagen/saagen.h): every call catches what the library throws and turns it into the
// thread-local one-line error; no exception crosses the interface.
#include "saagen/emit/emitter.hpp"
#include "saagen/emit/engines.hpp"
#include "saagen/emit/listing.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/integrate/include_handler.hpp"
#include "saagen/saagen.h"
#include "saagen/scene/manifest.hpp"
#include "saagen/scene/planner.hpp"

#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

struct saagen_files {
  std::vector<std::string> names;
  std::vector<std::string> texts;
};

namespace {

thread_local std::string last_error;

char* copy_out(const std::string& text) {
  char* copy = static_cast<char*>(std::malloc(text.size() + 1));
  if (!copy) throw std::bad_alloc();
  std::memcpy(copy, text.c_str(), text.size() + 1);
  return copy;
}

// Runs `body`, recording a failure as the last error; true on success.
template <typename Body>
bool guarded_call(Body&& body) {
  try {
    body();
    last_error.clear();
    return true;
  } catch (const saagen::Error& error) {
    last_error = error.what();
  } catch (const std::bad_alloc&) {
    last_error = "out of memory";
  } catch (const std::exception& error) {
    last_error = saagen::one_line(std::string("internal error: ") + error.what());
  }
  return false;
}

bool null_argument(const char* what) {
  last_error = std::string(what) + " is NULL; pass a valid pointer";
  return true;
}

}  // namespace

extern "C" {

const char* saagen_version(void) {
  static const std::string version(saagen::version());
  return version.c_str();
}

const char* saagen_last_error(void) { return last_error.c_str(); }

void saagen_free(char* text) { std::free(text); }

int saagen_list_json(const char* prefix, const char* domain, char** out_json) {
  if (!out_json && null_argument("out_json")) return -1;
  std::string json;
  const bool ok = guarded_call([&] {
    const std::string chosen_prefix = prefix ? prefix : "saa_";
    saagen::validate_prefix(chosen_prefix);
    json =
        saagen::catalogue_json(saagen::Catalogue::builtin(), chosen_prefix, saagen::find_domain(domain ? domain : "alpha2").kind).dump(2);
    *out_json = copy_out(json);
  });
  return ok ? 0 : -1;
}

int saagen_emit(const char* request, char** out_file_name, char** out_text) {
  if (!request && null_argument("request")) return -1;
  if (!out_text && null_argument("out_text")) return -1;
  const bool ok = guarded_call([&] {
    std::string name = request;
    if (!saagen::is_saagen_include(name)) name = "saagen/" + name;
    const saagen::EmittedFile file = saagen::resolve_include(name, {});
    char* text = copy_out(file.content);
    if (out_file_name) {
      try {
        *out_file_name = copy_out(file.file_name);
      } catch (...) {
        std::free(text);
        throw;
      }
    }
    *out_text = text;
  });
  return ok ? 0 : -1;
}

saagen_files* saagen_emit_manifest(const char* manifest_toml, const char* source_name) {
  if (!manifest_toml && null_argument("manifest_toml")) return nullptr;
  saagen_files* result = nullptr;
  guarded_call([&] {
    const saagen::Manifest manifest =
        saagen::parse_manifest(manifest_toml, source_name ? source_name : "manifest", saagen::Catalogue::builtin());
    const saagen::Catalogue& catalogue = saagen::scene_catalogue(manifest, saagen::Catalogue::builtin());
    const saagen::ScenePlan plan = saagen::plan_scene(catalogue, manifest);
    auto files = std::make_unique<saagen_files>();
    for (saagen::EmittedFile& file : saagen::emit_scene(catalogue, manifest, plan)) {
      files->names.push_back(std::move(file.file_name));
      files->texts.push_back(std::move(file.content));
    }
    result = files.release();
  });
  return result;
}

size_t saagen_files_count(const saagen_files* files) { return files ? files->names.size() : 0; }

const char* saagen_files_name(const saagen_files* files, size_t index) {
  return files && index < files->names.size() ? files->names[index].c_str() : nullptr;
}

const char* saagen_files_text(const saagen_files* files, size_t index) {
  return files && index < files->texts.size() ? files->texts[index].c_str() : nullptr;
}

void saagen_files_free(saagen_files* files) { delete files; }

}  // extern "C"
