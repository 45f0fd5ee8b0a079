// The roughness domain as a typed value: what `--domain`, manifests, include queries, markers and
// the C API give as text is converted once, where it is read (find_domain in
// saagen/emit/engines.hpp, the marker parser), and the library compares these values, never text.
#pragma once

#include <optional>
#include <string_view>

namespace saagen {

// Roughness in and out of the emitted functions, in the order of templates/engines.json's
// "domains" (the deferred pass's flag values): alpha^2 (the templates' own), alpha (GGX/Beckmann
// width), perceptual r with alpha = r^2 (Burley 2012: glTF, Filament, Unreal), smoothness 1 - r (Unity).
enum class Domain { alpha2, alpha, perceptual, smoothness };

// The id the text forms use: "alpha2", "alpha", "perceptual", "smoothness".
constexpr std::string_view to_string(Domain domain) {
  switch (domain) {
    case Domain::alpha2:
      return "alpha2";
    case Domain::alpha:
      return "alpha";
    case Domain::perceptual:
      return "perceptual";
    case Domain::smoothness:
      return "smoothness";
  }
  return "alpha2";
}

// The domain an id names, or nothing.
constexpr std::optional<Domain> domain_named(std::string_view id) {
  for (const Domain domain : {Domain::alpha2, Domain::alpha, Domain::perceptual, Domain::smoothness}) {
    if (to_string(domain) == id) return domain;
  }
  return std::nullopt;
}

}  // namespace saagen
