// The glslang includer (saagen/integrate/glslang_includer.hpp): saagen's include names resolved
// through resolve_include, every other name passed to the fallback includer.
#include "saagen/integrate/glslang_includer.hpp"

#include "saagen/error.hpp"

#include <memory>
#include <string>

namespace saagen {

namespace {

// The storage an IncludeResult points into, freed by releaseInclude.
struct IncludeStorage {
  std::string text;
};

glslang::TShader::Includer::IncludeResult* make_result(const std::string& name, std::string text) {
  auto storage = std::make_unique<IncludeStorage>(IncludeStorage{std::move(text)});
  const char* data = storage->text.data();
  const std::size_t size = storage->text.size();
  return new glslang::TShader::Includer::IncludeResult(name, data, size, storage.release());
}

}  // namespace

GlslangIncluder::GlslangIncluder(IncludeOptions defaults, glslang::TShader::Includer* fallback)
    : defaults_(std::move(defaults)), fallback_(fallback) {}

GlslangIncluder::IncludeResult* GlslangIncluder::resolve(const char* header_name) {
  IncludeResult* result = nullptr;
  try {
    EmittedFile file = resolve_include(header_name, defaults_);
    result = make_result(header_name, std::move(file.content));
  } catch (const Error& error) {
    result = make_result("", error.what());  // an empty name: glslang reports the text as the error
  }
  owned_.insert(result);
  return result;
}

GlslangIncluder::IncludeResult* GlslangIncluder::includeSystem(const char* header_name, const char* includer_name, size_t depth) {
  if (is_saagen_include(header_name)) return resolve(header_name);
  return fallback_ ? fallback_->includeSystem(header_name, includer_name, depth) : nullptr;
}

GlslangIncluder::IncludeResult* GlslangIncluder::includeLocal(const char* header_name, const char* includer_name, size_t depth) {
  if (is_saagen_include(header_name)) return resolve(header_name);
  return fallback_ ? fallback_->includeLocal(header_name, includer_name, depth) : nullptr;
}

void GlslangIncluder::releaseInclude(IncludeResult* result) {
  if (!result) return;
  if (owned_.erase(result)) {
    delete static_cast<IncludeStorage*>(result->userData);
    delete result;
  } else if (fallback_) {
    fallback_->releaseInclude(result);
  }
}

}  // namespace saagen
