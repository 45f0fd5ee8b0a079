// The machine-readable catalogue (`saagen list --json`): the contract engines and tests read.
#pragma once

#include "saagen/domain.hpp"
#include "saagen/front/catalogue.hpp"

#include <nlohmann/json.hpp>

#include <string_view>

namespace saagen {

// Every variant with its functions' emitted names and parameters (dialect types plus their
// spelling in each built-in target), and every emission option with its default and range.
// `domain` (saagen/emit/engines.hpp) lists the functions as emitted with that roughness domain; the
// listing states it ("roughness_domain"), each variant's domains, and the domains and presets.
nlohmann::json catalogue_json(const Catalogue& catalogue, std::string_view prefix, Domain domain = Domain::alpha2);

}  // namespace saagen
