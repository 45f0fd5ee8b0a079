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

// The animation's ground truths the +taa rows are measured against, [frame][material] at the
// flicker resolution (frames 0 .. config.frames - 1): the first seed's, the second seed's (empty
// when one was rendered) and the sanity suite's quarter-sample one's (empty without the suite).
// The verdict metrics read both seeds, as the trade's other rows'; the quarter-sample one gives
// each row its quarter_series, so that the verdict under TAA judges the ground truth's sample
// bias as it does without (report/comparison.hpp, bias_limited).
struct AnimationGroundTruths {
  std::vector<std::vector<Image>> first, second, quarter;
};

// The +taa rows of scene `id`, material-major then key order, appended to `rows`.
// shaded(pixels) reports 1-spp shading work. When `images` is given, each material's last frame
// (its ground truth and every key's resolved image) is appended to it (TradeTable::taa_images).
// on_frame (where set) is handed every row's resolved frame of the animation, as the trade's
// other rows' (its clip named by the +taa configuration id).
void append_taa_rows(const TradeConfig& config, SceneId id, std::span<const Material> materials, std::span<const TaaRowKey> keys,
                     const AnimationGroundTruths& truths, std::vector<TradeRow>& rows,
                     const std::function<void(std::uint64_t pixels)>& shaded, std::vector<ImageSet>* images = nullptr,
                     const AnimationFrameFn& on_frame = {});

}  // namespace saagen::measure
