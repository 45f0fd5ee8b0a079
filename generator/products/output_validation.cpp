#include "saagen/products/output_validation.hpp"

#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/products/deferred_pass.hpp"
#include "saagen/products/spirv_library.hpp"
#include "saagen/target/language.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/compiler.hpp"

#include <fmt/format.h>

namespace saagen {

bool is_spirv_or_pass_marker(const EmissionMarker& marker) { return !marker.target.is_snippet(); }

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
  const OutputKind kind = marker->target.kind;
  if (kind == OutputKind::spirv_library) {
    ValidationCheck check{"spirv library (universal 1.3, Linkage)", false, {}, 0};
    const auto words = words_of(check);
    if (!words.empty()) {
      std::vector<std::string> exports;
      const Catalogue& domain = domain_catalogue(catalogue, marker->domain);
      for (const std::string& name : public_functions(domain, marker->variants)) {
        if (!domain.find_function(name)->fragment_only) exports.push_back(prefixed_name(marker->prefix, name));
      }
      check.log = validate_spirv_library(words, exports);
      check.ok = check.log.empty();
      check.spirv_words = words.size();
    }
    validation.checks.push_back(std::move(check));
  } else if (kind == OutputKind::pass_spirv) {
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
    request.language = builtin_target(marker->target.table).language;  // a pass source: pass-<table>
    request.stage = ShaderStage::compute;
    request.client = ClientApi::vulkan;
    request.sources = {{file_name, content}};
    const CompileResult result = compile_to_spirv(request);
    validation.checks.push_back({"vulkan compute pass", result.ok, result.log, result.spirv.size()});
  }
  return validation;
}

namespace {

// A marker that names no known target or precision makes the file invalid: the message names it.
FileValidation validate_one(const Catalogue& catalogue, const std::string& name, const std::string& content) {
  try {
    const auto marker = find_marker(content);
    return marker && is_spirv_or_pass_marker(*marker) ? validate_spirv_or_pass_file(catalogue, name, content)
                                                      : validate_file(catalogue, name, content);
  } catch (const Error& error) {
    const std::string message = error.what();
    throw Error(message.rfind(name, 0) == 0 ? message : fmt::format("{}: bad saagen marker: {}", name, message));
  }
}

// Tint validates the files of a language glslang does not compile (WGSL), all in one run.
bool validated_by_tint(const std::string& content) {
  const auto marker = find_marker(content);
  if (!marker || is_spirv_or_pass_marker(*marker)) return false;
  const TargetSyntax* target = find_builtin_target(marker->target.table);
  return target && !target->language->compiled_in_process();
}

}  // namespace

void validate_outputs(const Catalogue& catalogue, const std::vector<std::pair<std::string, std::string>>& files,
                      const std::function<void(const FileValidation&)>& each) {
  std::vector<std::pair<std::string, std::string>> tint_files;
  for (const auto& file : files) {
    if (validated_by_tint(file.second)) tint_files.push_back(file);
  }
  std::vector<FileValidation> tint_validations;
  if (!tint_files.empty()) tint_validations = validate_wgsl_files(catalogue, tint_files);
  std::size_t next_tint = 0;
  for (const auto& [name, content] : files) {
    each(validated_by_tint(content) ? tint_validations[next_tint++] : validate_one(catalogue, name, content));
  }
}

}  // namespace saagen
