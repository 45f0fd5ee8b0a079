// Meeting engines where they are: roughness domains and engine presets.
//
// Both are data (templates/engines.json); the conversion formulas are template functions
// (templates/05-domains.saa). A domain catalogue is the built-in catalogue plus, for every public
// function whose first parameter is `alpha2` and whose result has that parameter's type (a
// scalar or per-axis roughness), a wrapper `<function>_<domain>` that takes and returns the
// engine's value:  <domain>_from_alpha2(<function>(alpha2_from_<domain>(x), ...)).
#pragma once

#include "saagen/domain.hpp"
#include "saagen/front/catalogue.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {

struct RoughnessDomain {
  Domain kind = Domain::alpha2;
  std::string id;           // alpha2, alpha, perceptual, smoothness (to_string(kind))
  std::string parameter;    // the wrappers' parameter name, e.g. perceptual_roughness
  std::string meaning;      // one line for headers and listings
  std::string engines;      // who stores it
  std::string to_alpha2;    // template function x -> alpha^2 (empty for alpha2)
  std::string from_alpha2;  // template function alpha^2 -> x (empty for alpha2)
};

// Every domain, alpha2 first. One definition shared by `emit --domain`, manifests, the include
// handlers, the C API and `texture prefilter --domain`.
const std::vector<RoughnessDomain>& roughness_domains();
// Throws saagen::Error "<option> 'x' is not a roughness domain; use alpha2, alpha, ...": the
// conversion of a domain's text, where it is read.
const RoughnessDomain& find_domain(std::string_view id, std::string_view option = "--domain");
const RoughnessDomain& roughness_domain(Domain domain);
// "alpha2, alpha, perceptual, smoothness"
std::string domain_ids();

struct Preset {
  std::string id;
  std::string engine;   // the engine and the source file of its form
  std::string variant;  // a catalogue variant id
  double sigma2 = 0.0;
  double kappa = 0.0;
  Domain domain = Domain::alpha2;  // the roughness the engine stores
  std::string normal;              // which normal the engine feeds
  std::string form;                // the engine's formula, in words
};

const std::vector<Preset>& presets();
// Throws saagen::Error "<option> 'x' is not a preset; use hdrp, ...".
const Preset& find_preset(std::string_view id, std::string_view option = "--preset");
std::string preset_ids();

// True when `function` converts: its first parameter is `alpha2` and its result has its type.
bool takes_and_returns_roughness(const Function& function);
// True when some public function of the variant converts.
bool variant_has_roughness_io(const Catalogue& catalogue, const Variant& variant);
// "<function>_<domain>": the wrapper's unprefixed name.
std::string domain_function_name(std::string_view function, Domain domain);

// The catalogue for emission in `domain`: `catalogue` itself for alpha2; for another domain the
// built-in catalogue with the wrappers added and, in each variant with roughness in and out, the
// wrappers in place of the functions they wrap (variants without are left as they are). Cached;
// throws saagen::Error for an unknown domain or a non-built-in catalogue.
const Catalogue& domain_catalogue(const Catalogue& catalogue, Domain domain);

}  // namespace saagen
