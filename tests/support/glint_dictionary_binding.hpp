// The glint dictionary bound as the glint snippets read it on Vulkan: a combined image sampler of a
// 1D array image (RGBA16F, its MIP chain), linear filters and mirrored repeat. Shared by the glint
// tests on the device (test_glints_gpu) and bench_glints, so that both time and check one binding.
#pragma once

#include "saagen/products/glints.hpp"

#include <cstdint>
#include <saagen/harness/harness.hpp>

namespace saagen::test {

// `texture` as the combined image sampler at (set 0, binding).
inline saagen::harness::ImageBinding glint_dictionary_binding(const saagen::glints::DictionaryTexture& texture, std::uint32_t binding) {
  namespace hx = saagen::harness;
  hx::ImageBinding image;
  image.binding = binding;
  image.image.kind = hx::ImageKind::image_1d_array;
  image.image.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  image.image.width = texture.width;
  image.image.layers = texture.layers;
  for (const auto& level : texture.levels) image.image.levels.push_back(hx::to_bytes(level));
  image.sampler.mag_filter = image.sampler.min_filter = VK_FILTER_LINEAR;
  image.sampler.mipmap_mode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  image.sampler.address(VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT);
  return image;
}

}  // namespace saagen::test
