// shaderc's include interface for saagen snippets (saagen/integrate/shaderc_includer.hpp).
#include "saagen/integrate/shaderc_includer.hpp"

#include "saagen/error.hpp"

#include <string>

namespace saagen {
namespace {

// One result and the strings it points into; its user_data marks it as saagen's.
struct OwnedResult {
  shaderc_include_result result{};
  std::string name;
  std::string content;
};

shaderc_include_result* make_result(std::string name, std::string content) {
  auto* owned = new OwnedResult{{}, std::move(name), std::move(content)};
  owned->result = {owned->name.c_str(), owned->name.size(), owned->content.c_str(), owned->content.size(), owned};
  return &owned->result;
}

}  // namespace

ShadercIncluder::ShadercIncluder(IncludeOptions defaults, std::unique_ptr<shaderc::CompileOptions::IncluderInterface> fallback)
    : defaults_(std::move(defaults)), fallback_(std::move(fallback)) {}

shaderc_include_result* ShadercIncluder::GetInclude(const char* requested_source, shaderc_include_type type, const char* requesting_source,
                                                    size_t include_depth) {
  if (!is_saagen_include(requested_source)) {
    if (fallback_) return fallback_->GetInclude(requested_source, type, requesting_source, include_depth);
    return own(make_result("", std::string(requested_source) + ": not a saagen include, and no fallback includer was given"));
  }
  try {
    return own(make_result(requested_source, resolve_include(requested_source, defaults_).content));
  } catch (const Error& error) {
    return own(make_result("", error.what()));  // an empty source name: shaderc reports the content as the error
  }
}

shaderc_include_result* ShadercIncluder::own(shaderc_include_result* result) {
  owned_.insert(result);
  return result;
}

void ShadercIncluder::ReleaseInclude(shaderc_include_result* data) {
  if (!data) return;
  if (owned_.erase(data)) {
    delete static_cast<OwnedResult*>(data->user_data);
  } else if (fallback_) {
    fallback_->ReleaseInclude(data);
  }
}

}  // namespace saagen
