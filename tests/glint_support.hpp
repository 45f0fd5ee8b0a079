// Shared plumbing for the glint suites: the default dictionary (generated once per
// process), its texture as the reference's software sampler sees it, and helpers.
#pragma once

#include "saagen/products/glints.hpp"
#include "saagen/reference/glints.hpp"

#include <cstdint>
#include <vector>

namespace saagen::test {

// The dictionary with the paper's defaults (N = 192, L = 16, R = 64, alpha = 0.5), generated once.
inline const glints::Dictionary& default_dictionary() {
  static const glints::Dictionary dictionary = glints::generate_dictionary({});
  return dictionary;
}

inline const glints::DictionaryTexture& default_texture() {
  static const glints::DictionaryTexture texture = glints::dictionary_texture(default_dictionary(), true);
  return texture;
}

// The half texels as doubles: exactly what the GPU filters (lavapipe filters RGBA16F in fp32).
inline ref::glints::Texture1DArray reference_texture(const glints::DictionaryTexture& texture) {
  ref::glints::Texture1DArray result;
  result.width = static_cast<int>(texture.width);
  result.layers = static_cast<int>(texture.layers);
  for (const auto& level : texture.levels) {
    std::vector<double> values(level.size());
    for (std::size_t k = 0; k < level.size(); ++k) values[k] = glints::from_half(level[k]);
    result.levels.push_back(std::move(values));
  }
  return result;
}

inline const ref::glints::Texture1DArray& default_reference_texture() {
  static const ref::glints::Texture1DArray texture = reference_texture(default_texture());
  return texture;
}

inline ref::glints::Dictionary default_reference_dictionary(ref::glints::LodModel model = ref::glints::LodModel::exact) {
  ref::glints::Dictionary dictionary;
  dictionary.texture = &default_reference_texture();
  dictionary.lod_model = model;
  return dictionary;
}

}  // namespace saagen::test
