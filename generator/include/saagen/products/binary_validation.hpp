// `saagen validate` of the binary products: SPIR-V library modules and deferred-pass files,
// recognised by their markers.
#pragma once

#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/validate/validation.hpp"

#include <string>

namespace saagen {

// Validation of a binary or pass output found by `saagen validate DIR`: library modules
// (marker target "spirv") and deferred-pass files (deferred_pass.hpp). Throws saagen::Error
// when the marker names no SPIR-V or pass output.
bool is_spirv_or_pass_marker(const EmissionMarker& marker);
FileValidation validate_spirv_or_pass_file(const Catalogue& catalogue, const std::string& file_name, const std::string& content);

}  // namespace saagen
