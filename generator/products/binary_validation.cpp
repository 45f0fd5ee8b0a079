#include "saagen/products/binary_validation.hpp"

#include "saagen/error.hpp"
#include "saagen/products/deferred_pass.hpp"
#include "saagen/products/spirv_library.hpp"
#include "saagen/validate/compiler.hpp"

#include <fmt/format.h>

namespace saagen {

bool is_spirv_or_pass_marker(const EmissionMarker& marker) {
  return marker.target == spirv_library_target || marker.target == deferred_pass_glsl_target ||
         marker.target == deferred_pass_hlsl_target || marker.target == deferred_pass_spirv_target;
}

FileValidation validate_spirv_or_pass_file(const Catalogue& catalogue, const std::string& file_name, const std::string& content) {
  const auto marker = find_marker(content);
  if (!marker || !is_spirv_or_pass_marker(*marker)) throw Error(fmt::format("{}: no SPIR-V or pass marker", file_name));
  FileValidation validation{file_name, {}};
  const auto words_of = [&](ValidationCheck& check) -> std::vector<std::uint32_t> {
    try {
      return spirv_words_from_bytes(content);
    } catch (const Error& error) {
      check.log = error.what();
      return {};
    }
  };
  if (marker->target == spirv_library_target) {
    ValidationCheck check{"spirv library (universal 1.3, Linkage)", false, {}, 0};
    const auto words = words_of(check);
    if (!words.empty()) {
      std::vector<std::string> exports;
      for (const std::string& name : public_functions(catalogue, marker->variants)) {
        if (!catalogue.find_function(name)->fragment_only) exports.push_back(prefixed_name(marker->prefix, name));
      }
      check.log = validate_spirv_library(words, exports);
      check.ok = check.log.empty();
      check.spirv_words = words.size();
    }
    validation.checks.push_back(std::move(check));
  } else if (marker->target == deferred_pass_spirv_target) {
    ValidationCheck check{"vulkan compute pass", false, {}, 0};
    const auto words = words_of(check);
    if (!words.empty()) {
      check.log = validate_spirv(words, ClientApi::vulkan);
      check.ok = check.log.empty();
      check.spirv_words = words.size();
    }
    validation.checks.push_back(std::move(check));
  } else {
    CompileRequest request;
    request.language = marker->target == deferred_pass_hlsl_target ? SourceLanguage::hlsl : SourceLanguage::glsl;
    request.stage = ShaderStage::compute;
    request.client = ClientApi::vulkan;
    request.sources = {{file_name, content}};
    const CompileResult result = compile_to_spirv(request);
    validation.checks.push_back({"vulkan compute pass", result.ok, result.log, result.spirv.size()});
  }
  return validation;
}

}  // namespace saagen
