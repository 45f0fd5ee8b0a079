// `saagen validate`: every kind of file saagen writes, recognised by its marker: snippets
// (glslang, per file), WGSL modules (Tint, all in one run of the WebGPU runner), SPIR-V library
// modules and deferred-pass files.
#pragma once

#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/validate/validation.hpp"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace saagen {

// Validation of a binary or pass output found by `saagen validate DIR`: library modules
// (marker target "spirv") and deferred-pass files (deferred_pass.hpp). Throws saagen::Error
// when the marker names no SPIR-V or pass output.
bool is_spirv_or_pass_marker(const EmissionMarker& marker);
FileValidation validate_spirv_or_pass_file(const Catalogue& catalogue, const std::string& file_name, const std::string& content);

// Validates `files` (name, content), calling `each` with their results in the order given; a
// file whose marker names no known target or precision throws saagen::Error naming the file.
void validate_outputs(const Catalogue& catalogue, const std::vector<std::pair<std::string, std::string>>& files,
                      const std::function<void(const FileValidation&)>& each);

}  // namespace saagen
