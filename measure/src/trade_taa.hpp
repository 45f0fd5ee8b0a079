// The trade's +taa rows (trade.hpp, TradeConfig::taa): the configurations of a scene resolved
// by the TAA of taa.hpp over the animation, measured after a warm-up.
#pragma once

#include "saagen/measure/trade_table.hpp"

#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace saagen::measure {

// The G-buffers of one frame, their quad inputs gathered (gather_quads): the implicit LOD's, and
// on a normal-mapped scene with a bias the prefiltered rows' (TradeConfig::prefilter_lod_bias).
struct FrameBuffers {
  GBuffer plain;
  std::optional<GBuffer> prefiltered;
  const GBuffer& for_prefilter(Prefilter prefilter) const { return prefilter != Prefilter::none && prefiltered ? *prefiltered : plain; }
};
FrameBuffers frame_buffers(const TradeConfig& config, SceneId id, const Scene& scene, int width, int height);

// One configuration to run under TAA (a trade row's key).
struct TaaRowKey {
  Variant variant;
  NormalFeed feed;
  Prefilter prefilter;
  Lobe lobe = Lobe::papers;
};

// The warm-up of a configuration: taa_warmup_frames, or one jitter cycle when 0.
int taa_warmup(const TradeConfig& config);

// The +taa rows of scene `id`, material-major then key order, appended to `rows`.
// reference_frames[f][m]: the ground truth of animation frame f (0 .. config.frames - 1) for
// material m at the flicker resolution; second_seed_frames the same with the second ground-truth
// seed (empty when one was rendered): the verdict metrics read both, as the trade's other rows'.
// shaded(pixels) reports 1-spp shading work. When
// `images` is given, each material's last frame (its ground truth and every key's resolved
// image) is appended to it (TradeTable::taa_images).
void append_taa_rows(const TradeConfig& config, SceneId id, std::span<const Material> materials, std::span<const TaaRowKey> keys,
                     const std::vector<std::vector<Image>>& reference_frames, const std::vector<std::vector<Image>>& second_seed_frames,
                     std::vector<TradeRow>& rows, const std::function<void(std::uint64_t pixels)>& shaded,
                     std::vector<ImageSet>* images = nullptr);

}  // namespace saagen::measure
