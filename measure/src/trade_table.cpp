// The trade's data (see trade_table.hpp): the configuration ids, the default variants, finding a
// row, the sanity results' names and the animation's frames.
#include "saagen/measure/trade_table.hpp"

namespace saagen::measure {

std::string configuration_id(Variant variant, NormalFeed feed, Prefilter prefilter, Lobe lobe, bool taa) {
  std::string id(variant_id(variant));
  if (feed == NormalFeed::geometric && !is_engine(variant) && variant != Variant::none) id += ":geometric";
  if (prefilter != Prefilter::none) id += "+" + std::string(prefilter_name(prefilter));
  if (taa) id += "+taa";
  if (lobe != Lobe::papers) id += "/" + std::string(lobe_name(lobe));
  return id;
}

std::string configuration_id(const TradeRow& row) { return configuration_id(row.variant, row.feed, row.prefilter, row.lobe, row.taa); }

std::vector<Variant> default_trade_variants() {
  std::vector<Variant> variants(all_variants().begin(), all_variants().end());
  variants.insert(variants.end(), all_engines().begin(), all_engines().end());
  return variants;
}

const TradeRow* TradeTable::find(Variant variant, SceneId scene, double alpha, bool fresnel, NormalFeed feed, Prefilter prefilter,
                                 Lobe lobe, bool taa) const {
  for (const TradeRow& row : rows)
    if (row.variant == variant && row.scene == scene && row.alpha == alpha && row.fresnel == fresnel && row.feed == feed &&
        row.prefilter == prefilter && row.lobe == lobe && row.taa == taa)
      return &row;
  return nullptr;
}

std::string_view sanity_name(SanityResult result) {
  switch (result) {
    case SanityResult::other_seed:
      return "other-seed";
    case SanityResult::quarter_samples:
      return "quarter-samples";
    case SanityResult::delayed:
      return "delayed";
    case SanityResult::blurred:
      return "blurred";
    case SanityResult::frozen:
      return "frozen";
    case SanityResult::no_highlight:
      return "no-highlight";
  }
  return "?";
}

Scene trade_animation_frame(const TradeConfig& config, SceneId id, int frame) {
  const Scene rotated = make_scene(id, frame * config.rotation_degrees_per_frame * ref::kPi / 180.0);
  const double steps = frame - 0.5 * (config.frames - 1);  // centred on the unpanned view
  return rotated.with_camera(
      rotated.camera().panned(steps * config.pan_pixels_per_frame.x, steps * config.pan_pixels_per_frame.y, config.flicker_height));
}

}  // namespace saagen::measure
