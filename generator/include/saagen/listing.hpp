// The machine-readable catalogue (`saagen list --json`): the contract engines and tests read.
#pragma once

#include "saagen/catalogue.hpp"

#include <nlohmann/json.hpp>

#include <string_view>

namespace saagen {

// Every variant with its functions' emitted names and parameters (dialect types plus their
// spelling in each built-in target), and every emission option with its default and range.
nlohmann::json catalogue_json(const Catalogue& catalogue, std::string_view prefix);

}  // namespace saagen
