// The SAA quality trade table (see trade.hpp).
#include "saagen/measure/trade.hpp"

#include "trade_clips.hpp"
#include "trade_taa.hpp"

#include "saagen/measure/flip.hpp"
#include "saagen/measure/parallel.hpp"
#include "saagen/measure/video_vdp.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>

namespace saagen::measure {

namespace {

// Version 2 adds the payload's checksum: pixels overwritten under an intact header are a miss.
constexpr char kCacheMagic[8] = {'S', 'A', 'A', 'G', 'T', '0', '0', '2'};
// Bump when anything that changes ground-truth pixels without appearing in the key changes
// (shading model, sampler, scene code).
constexpr const char* kCacheFormat = "saagen-ground-truth-v2";

std::uint64_t fnv1a64(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

template <class T>
void append_pod(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <class T>
bool read_pod(std::istream& in, T& value) {
  return static_cast<bool>(in.read(reinterpret_cast<char*>(&value), sizeof(T)));
}

// The images' floats, in order: the payload the checksum covers.
std::string cache_payload(const GroundTruth& gt) {
  std::string payload;
  auto append_image = [&](const Image& image) {
    payload.append(reinterpret_cast<const char*>(image.pixels.data()), image.pixels.size() * sizeof(float));
  };
  for (const Image& image : gt.images) append_image(image);
  append_image(gt.coverage);
  return payload;
}

// A cache file: magic, key (size, bytes), width, height, image count, the payload's FNV-1a, payload.
std::string cache_bytes(const std::string& key, const GroundTruth& gt) {
  const std::string payload = cache_payload(gt);
  std::string out(kCacheMagic, 8);
  append_pod(out, static_cast<std::uint64_t>(key.size()));
  out += key;
  append_pod(out, static_cast<std::int32_t>(gt.coverage.width));
  append_pod(out, static_cast<std::int32_t>(gt.coverage.height));
  append_pod(out, static_cast<std::uint64_t>(gt.images.size()));
  append_pod(out, fnv1a64(payload));
  return out + payload;
}

// The ground truth a cache file holds for `key`; false (a miss) for anything else: another key,
// size or format, a short file, or a payload whose checksum does not match.
bool load_cache(const std::filesystem::path& path, const std::string& key, int width, int height, std::size_t count, GroundTruth& gt) {
  // Only a regular file is read: a FIFO (or device) planted at the name would block the open.
  std::error_code kind_error;
  if (!std::filesystem::is_regular_file(path, kind_error)) return false;
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  char magic[8];
  if (!in.read(magic, 8) || std::memcmp(magic, kCacheMagic, 8) != 0) return false;
  std::uint64_t key_size = 0;
  if (!read_pod(in, key_size) || key_size != key.size()) return false;
  std::string stored(key_size, '\0');
  if (!in.read(stored.data(), static_cast<std::streamsize>(key_size)) || stored != key) return false;
  std::int32_t w = 0, h = 0;
  std::uint64_t n = 0, checksum = 0;
  if (!read_pod(in, w) || !read_pod(in, h) || !read_pod(in, n) || !read_pod(in, checksum)) return false;
  if (w != width || h != height || n != count) return false;
  GroundTruth loaded;
  auto read_image = [&](Image& image) {
    image = Image(width, height);
    return static_cast<bool>(
        in.read(reinterpret_cast<char*>(image.pixels.data()), static_cast<std::streamsize>(image.pixels.size() * sizeof(float))));
  };
  loaded.images.resize(count);
  for (Image& image : loaded.images)
    if (!read_image(image)) return false;
  if (!read_image(loaded.coverage)) return false;
  if (in.peek() != std::char_traits<char>::eof()) return false;  // trailing bytes: not a file this wrote
  if (fnv1a64(cache_payload(loaded)) != checksum) return false;
  gt = std::move(loaded);
  return true;
}

// The library's own writer: a unique temporary beside the file, then a rename (readers never see
// a partial file).
void write_cache_file_directly(const std::filesystem::path& path, const std::string& bytes) {
  std::random_device rd;
  const std::filesystem::path temporary = path.string() + ".tmp" + std::to_string(rd()) + std::to_string(rd());
  std::error_code ec;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return;  // the cache is an optimisation: failing to write it is not an error
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
      out.close();
      std::filesystem::remove(temporary, ec);
      return;
    }
  }
  std::filesystem::rename(temporary, path, ec);
  if (ec) std::filesystem::remove(temporary, ec);
}

CacheFileWriter& cache_file_writer() {
  static CacheFileWriter writer = write_cache_file_directly;
  return writer;
}

void store_cache(const std::filesystem::path& path, const std::string& key, const GroundTruth& gt) {
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  cache_file_writer()(path, cache_bytes(key, gt));
}

// A ground truth that cannot be measured against: a non-finite pixel, or black in every material
// (every configuration would err by 0 and "win").
void check_ground_truth(const Scene& scene, const GroundTruth& gt, std::span<const Material> materials) {
  bool lit = false;
  for (std::size_t m = 0; m < gt.images.size(); ++m) {
    for (const float value : gt.images[m].pixels) {
      if (!std::isfinite(value)) {
        std::ostringstream s;
        s << "scene " << scene.name() << ": the ground truth at alpha " << materials[m].alpha
          << " holds a non-finite pixel; nothing can be measured against it (check the scene's geometry and material factors)";
        throw TradeError(s.str());
      }
      lit = lit || value != 0.0f;
    }
  }
  if (!lit)
    throw TradeError("scene " + std::string(scene.name()) +
                     ": the ground truth is black at every alpha (no lit surface in view: check the scene's scale, camera and light); "
                     "every configuration would err by 0");
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Cache

std::string ground_truth_cache_key(const Scene& scene, const GroundTruthSettings& settings, std::span<const Material> materials) {
  std::ostringstream s;
  s.precision(17);
  s << kCacheFormat << ";" << scene.describe() << ";size=" << settings.width << "x" << settings.height << ";strata=" << settings.strata
    << ";seed=" << settings.seed << ";filter_variance=" << settings.filter_variance << ";filter_truncation=" << settings.filter_truncation
    << ";F0=" << kFresnelF0 << ";materials=";
  for (const Material& m : materials) s << "(" << m.alpha << "," << (m.fresnel ? 1 : 0) << ")";
  return s.str();
}

void set_ground_truth_cache_writer(CacheFileWriter writer) {
  cache_file_writer() = writer ? std::move(writer) : CacheFileWriter(write_cache_file_directly);
}

std::string ground_truth_cache_file(const std::string& key) {
  char name[32];
  std::snprintf(name, sizeof name, "gt-%016llx.bin", static_cast<unsigned long long>(fnv1a64(key)));
  return name;
}

GroundTruth cached_ground_truth(const Scene& scene, const GroundTruthSettings& settings, std::span<const Material> materials,
                                const std::string& cache_dir, const SampleProgress& progress, bool* cache_hit) {
  if (cache_hit) *cache_hit = false;
  if (cache_dir.empty()) return render_ground_truth(scene, settings, materials, progress);
  const std::string key = ground_truth_cache_key(scene, settings, materials);
  const std::filesystem::path path = std::filesystem::path(cache_dir) / ground_truth_cache_file(key);
  GroundTruth gt;
  if (load_cache(path, key, settings.width, settings.height, materials.size(), gt)) {
    if (cache_hit) *cache_hit = true;
    return gt;
  }
  gt = render_ground_truth(scene, settings, materials, progress);
  store_cache(path, key, gt);
  return gt;
}

// ---------------------------------------------------------------------------------------------
// Table

std::vector<Material> trade_materials(const TradeConfig& config) {
  std::vector<Material> materials;
  for (double alpha : config.alphas)
    for (bool fresnel : config.fresnel_modes) materials.push_back({alpha, fresnel});
  return materials;
}

std::string configuration_id(Variant variant, NormalFeed feed, Prefilter prefilter, Lobe lobe, bool taa) {
  std::string id(variant_id(variant));
  if (feed == NormalFeed::geometric && !is_engine(variant) && variant != Variant::none) id += ":geometric";
  if (prefilter != Prefilter::none) id += "+" + std::string(prefilter_name(prefilter));
  if (taa) id += "+taa";
  if (lobe != Lobe::papers) id += "/" + std::string(lobe_name(lobe));
  return id;
}

std::string configuration_id(const TradeRow& row) { return configuration_id(row.variant, row.feed, row.prefilter, row.lobe, row.taa); }

bool scene_has_normal_map(SceneId id) { return scene_normal_detail(id) == NormalDetail::normal_map; }

bool scene_has_procedural_normals(SceneId id) { return scene_normal_detail(id) == NormalDetail::procedural; }

bool scene_has_normal_detail(SceneId id) { return scene_has_procedural_normals(id) || scene_has_normal_map(id); }

namespace {

// One row's configuration: a variant and the normal it reads.
struct RowKey {
  Variant variant;
  NormalFeed feed;
  Prefilter prefilter = Prefilter::none;
  Lobe lobe = Lobe::papers;
};

// Each key of a variant in config.lobe_variants once more per further lobe, after the papers'.
std::vector<RowKey> with_lobes(const TradeConfig& config, const std::vector<RowKey>& keys) {
  std::vector<RowKey> out;
  for (const RowKey& key : keys) {
    out.push_back(key);
    const bool has_lobes = std::find(config.lobe_variants.begin(), config.lobe_variants.end(), key.variant) != config.lobe_variants.end();
    if (!has_lobes) continue;
    for (Lobe lobe : config.lobes) {
      if (lobe == Lobe::papers) continue;
      RowKey with_lobe = key;
      with_lobe.lobe = lobe;
      out.push_back(with_lobe);
    }
  }
  return out;
}

// The rows of a scene, in config.variants order; a variant's feeds in config.feeds order. The
// baseline reads no normal; engines read their own; the geometric feed adds rows only where
// the scene's normals have detail the geometry lacks.
std::vector<RowKey> row_keys(const TradeConfig& config, SceneId scene) {
  std::vector<RowKey> keys;
  for (Variant v : config.variants) {
    if (v == Variant::none) {
      keys.push_back({v, NormalFeed::shading});
    } else if (is_engine(v)) {
      keys.push_back({v, engine_feed(v)});
    } else {
      for (NormalFeed feed : config.feeds)
        if (feed == NormalFeed::shading || scene_has_normal_detail(scene)) keys.push_back({v, feed});
    }
  }
  const bool procedural = scene_has_procedural_normals(scene);
  if (scene_has_normal_map(scene) || procedural)
    for (Variant v : config.prefiltered_variants)
      for (Prefilter prefilter : config.prefilters)
        if (!procedural || prefilter == Prefilter::lean)
          keys.push_back({v, v == Variant::none ? NormalFeed::shading : NormalFeed::geometric, prefilter});
  return with_lobes(config, keys);
}

// The configurations run under TAA: every row key, each lobe's included.
std::vector<TaaRowKey> taa_keys(const TradeConfig& config, SceneId scene) {
  std::vector<TaaRowKey> out;
  for (const RowKey& key : row_keys(config, scene)) out.push_back({key.variant, key.feed, key.prefilter, key.lobe});
  return out;
}

// The seeds of the animation's further ground truths: the second seed (verdict metrics against
// two references) and the third (the sanity suite's quarter-sample result); any fixed values
// unlike the first, which the cache keys record.
std::uint64_t second_seed(std::uint64_t seed) { return seed ^ 0x9e3779b97f4a7c15ULL; }
std::uint64_t third_seed(std::uint64_t seed) { return seed ^ 0xc2b2ae3d27d4eb4fULL; }

// The animation's ground-truth renders per frame, in units of one full-sample render: one per
// seed, and a quarter for the sanity suite's quarter-sample result.
double animation_ground_truths(const TradeConfig& config) {
  const int seeds = std::clamp(config.ground_truth_seeds, 1, 2);
  return seeds + (config.sanity && seeds == 2 && config.frames >= 2 ? 0.25 : 0.0);
}

// The sanity suite's results of one material (trade.hpp, SanityResult), frame by frame, from the
// second seed's frames and the quarter-sample ground truth's.
class SanityClips {
 public:
  // Frame t: `other` and `quarter` are the second seed's and the quarter-sample ground truth's
  // linear frames; `reference` the first seed's references.
  explicit SanityClips(bool keep_frames = false) {
    for (ClipRecorder& clip : clips_) clip.keep_frames = keep_frames;
  }
  void add(const Image& other, const Image& quarter, const SeedReference& reference, const SeedReference* previous_reference) {
    if (!first_) first_ = other;
    const Image& delayed = previous_ ? *previous_ : other;
    const Image inputs[] = {
        other, quarter, delayed, gaussian_pooled(other, kSanityBlurSigma), *first_, Image(other.width, other.height, 0.0f)};
    const std::span<const SeedReference> previous =
        previous_reference ? std::span(previous_reference, 1) : std::span<const SeedReference>();
    for (std::size_t i = 0; i < kSanityResults.size(); ++i) clips_[i].add(inputs[i], std::span(&reference, 1), previous);
    previous_ = other;
  }
  const Image& last(SanityResult result) const { return clips_[static_cast<std::size_t>(result)].previous_display; }
  ClipRecorder& clip(SanityResult result) { return clips_[static_cast<std::size_t>(result)]; }
  SanityRow row(SceneId scene, const Material& material, SanityResult result) const {
    const ClipRecorder& clip = clips_[static_cast<std::size_t>(result)];
    SanityRow row{scene, material.alpha, material.fresnel, result, 0.0, 0.0, 0.0, 0.0, clip.series};
    row.image_error = mean_interval(clip.series.image[0], 0.0).mean;
    row.flicker_error = mean_interval(clip.series.flicker[0], 0.0).mean;
    if (!clip.series.video[0].empty()) row.video_error = mean_interval(clip.series.video[0], 0.0).mean;
    if (!clip.series.lag[0].empty()) row.lag = mean_interval(clip.series.lag[0], 0.0).mean;
    return row;
  }

 private:
  std::array<ClipRecorder, kSanityResults.size()> clips_;
  std::optional<Image> first_, previous_;
};

// The video metric of a scene's clips (ClipRecorder::finish_video): each material's reference
// half once per ground truth (reference_clips[m]: the `seeds` seeds', then the quarter-sample
// one's where the sanity suite runs), then every row's clip (rows r = m * n_keys + k) against the
// seeds and, in quarter_clips[r], against the quarter, and the sanity results' (against the first
// seed, as their other metrics), on the configured threads.
void compare_clips(const TradeConfig& config, const std::vector<std::vector<ClipFrames>>& reference_clips, std::size_t n_keys,
                   std::size_t seeds, std::vector<ClipRecorder>& clips, std::vector<ClipRecorder>& quarter_clips,
                   std::vector<SanityClips>& sanity_clips) {
  const std::vector<std::vector<VideoVdpReference>> references = video_references(config, reference_clips);
  parallel_rows(static_cast<int>(clips.size()), config.threads, [&](int i) {
    const std::size_t r = static_cast<std::size_t>(i);
    const std::span<const VideoVdpReference> material(references[r / n_keys]);
    if (!quarter_clips.empty()) quarter_clips[r].series.video[0] = video_losses(material[seeds], clips[r].frames.grey());
    clips[r].finish_video(material.first(seeds));
  });
  parallel_rows(static_cast<int>(sanity_clips.size() * kSanityResults.size()), config.threads, [&](int i) {
    const std::size_t m = static_cast<std::size_t>(i) / kSanityResults.size();
    sanity_clips[m]
        .clip(kSanityResults[static_cast<std::size_t>(i) % kSanityResults.size()])
        .finish_video(std::span(references[m]).first(1));
  });
}

}  // namespace

FrameBuffers frame_buffers(const TradeConfig& config, SceneId id, const Scene& scene, int width, int height) {
  FrameBuffers buffers{render_gbuffer(scene, width, height, config.threads), std::nullopt};
  gather_quads(buffers.plain, config.threads);
  if (config.prefilter_lod_bias != 0.0 && scene_has_normal_map(id)) {
    buffers.prefiltered = render_gbuffer(scene, width, height, config.threads, config.prefilter_lod_bias);
    gather_quads(*buffers.prefiltered, config.threads);
  }
  return buffers;
}

TradeConfig sized_for_scene(const TradeConfig& config, SceneId id) {
  TradeConfig sized = config;
  for (const TradeSceneSize& size : config.scene_sizes) {
    if (size.scene != id) continue;
    sized.width = size.width;
    sized.height = size.height;
    sized.strata = size.strata;
    sized.flicker_width = size.flicker_width;
    sized.flicker_height = size.flicker_height;
    sized.flicker_strata = size.flicker_strata;
    break;
  }
  return sized;
}

GroundTruthSettings ground_truth_settings(const TradeConfig& sized, bool animation) {
  GroundTruthSettings settings;
  settings.width = animation ? sized.flicker_width : sized.width;
  settings.height = animation ? sized.flicker_height : sized.height;
  settings.strata = animation ? sized.flicker_strata : sized.strata;
  settings.seed = sized.seed;
  settings.threads = sized.threads;
  return settings;
}

TradeTable compute_trade_table(const TradeConfig& config, const TradeProgressFn& progress, const AnimationFrameFn& on_frame) {
  for (const SceneId id : config.scenes) {
    const TradeConfig sized = sized_for_scene(config, id);
    if (sized.width <= 0 || sized.height <= 0 || sized.strata <= 0)
      throw std::invalid_argument("trade table: bad main resolution or strata");
    if (sized.frames > 0 && (sized.flicker_width <= 0 || sized.flicker_height <= 0 || sized.flicker_strata <= 0))
      throw std::invalid_argument("trade table: bad flicker resolution or strata");
  }
  if (config.taa && config.frames < 2) throw std::invalid_argument("trade table: TAA rows need an animation of at least 2 frames");
  if (config.taa) check_taa_options(config.taa_options);

  TradeTable table;
  table.config = config;
  const std::vector<Material> materials = trade_materials(config);
  const std::size_t n_materials = materials.size();

  // Work units: ground-truth samples and 1-spp pixel shadings, at each scene's sizes.
  struct Sizes {
    std::uint64_t main_pixels, flicker_pixels, main_gt, flicker_gt;
  };
  const auto sizes_of = [&](SceneId id) {
    const TradeConfig sized = sized_for_scene(config, id);
    const std::uint64_t main_pixels = static_cast<std::uint64_t>(sized.width) * sized.height;
    const std::uint64_t flicker_pixels = static_cast<std::uint64_t>(sized.flicker_width) * sized.flicker_height;
    return Sizes{main_pixels, flicker_pixels, main_pixels * sized.strata * sized.strata,
                 flicker_pixels * sized.flicker_strata * sized.flicker_strata};
  };
  auto scene_work = [&](SceneId id) {
    const Sizes sizes = sizes_of(id);
    const std::uint64_t main_pixels = sizes.main_pixels, flicker_pixels = sizes.flicker_pixels;
    const std::uint64_t shading_per_frame = n_materials * row_keys(config, id).size();
    const std::uint64_t taa_shading = config.taa ? static_cast<std::uint64_t>(config.frames + taa_warmup(config)) * flicker_pixels *
                                                       n_materials * taa_keys(config, id).size()
                                                 : 0;
    return sizes.main_gt + main_pixels * shading_per_frame +
           (config.frames > 0
                ? config.frames * (static_cast<std::uint64_t>(animation_ground_truths(config) * static_cast<double>(sizes.flicker_gt)) +
                                   flicker_pixels * shading_per_frame)
                : 0) +
           taa_shading;
  };
  TradeProgress state;
  for (SceneId id : config.scenes) state.total += scene_work(id);
  auto report = [&](const std::string& stage, std::uint64_t done) {
    state.stage = stage;
    state.done = done;
    if (progress) progress(state);
  };

  std::uint64_t base = 0;
  // The checks (check_ground_truth) apply to the ground truths every metric reads: the main image
  // and the first seed's animation. The second seed's and the quarter-sample frames only estimate
  // the ground truth's noise and feed the sanity suite (`checked` false).
  auto ground_truth = [&](const Scene& scene, const GroundTruthSettings& settings, const std::string& stage, std::uint64_t base,
                          bool checked = true) {
    report(stage, base);
    bool hit = false;
    const auto start = std::chrono::steady_clock::now();
    GroundTruth gt = cached_ground_truth(
        scene, settings, materials, config.cache_dir, [&](std::uint64_t done, std::uint64_t) { report(stage, base + done); }, &hit);
    if (checked) check_ground_truth(scene, gt, materials);
    if (hit) {
      ++table.cache_hits;
    } else {
      ++table.cache_misses;
      table.ground_truth_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      table.ground_truth_samples += static_cast<std::uint64_t>(settings.width) * settings.height * settings.strata * settings.strata;
    }
    return gt;
  };
  // One image per worker: the rows of a frame run in parallel (for_each_row), each on one thread.
  auto shade = [&](const FrameBuffers& buffers, const RowKey& key, const Material& material) {
    return render_variant(buffers.for_prefilter(key.prefilter), key.variant, material, config.params, config.derivative, 1, key.feed,
                          key.prefilter, config.prefilter_scale, key.lobe);
  };
  // Runs body(r) for the n_materials x n_keys rows of a frame (r = m * n_keys + k) on the
  // configured threads; the progress advances `base` by pixels_per_row for each row done.
  // The images are small (FLIP's convolutions dominate), so rows, not pixels, are the unit.
  auto for_each_row = [&](std::size_t n_rows, std::uint64_t pixels_per_row, const std::string& stage,
                          const std::function<void(std::size_t r)>& body) {
    const std::uint64_t start = base;
    parallel_rows(
        static_cast<int>(n_rows), config.threads, [&](int r) { body(static_cast<std::size_t>(r)); },
        [&](int done) { report(stage, start + static_cast<std::uint64_t>(done) * pixels_per_row); });
    base = start + n_rows * pixels_per_row;
  };

  for (const SceneId id : config.scenes) {
    const std::string name(scene_name(id));
    const TradeConfig sized = sized_for_scene(config, id);
    const Sizes sizes = sizes_of(id);
    const std::uint64_t main_pixels = sizes.main_pixels, flicker_pixels = sizes.flicker_pixels;
    const GroundTruthSettings main_settings = ground_truth_settings(sized);
    const GroundTruthSettings flicker_settings = ground_truth_settings(sized, true);
    const std::vector<RowKey> keys = row_keys(config, id);
    const std::size_t n_keys = keys.size();

    // Frame 0 at the main resolution: ground truth, 1-spp images, image metrics.
    const Scene scene = make_scene(id, 0.0);
    const GroundTruth gt = ground_truth(scene, main_settings, "ground truth " + name, base);
    base += sizes.main_gt;
    report("1-spp variants " + name, base);
    const FrameBuffers gbuffer = frame_buffers(config, id, scene, sized.width, sized.height);
    const std::size_t first_row = table.rows.size();
    // FLIP's reference half once per material: [m] for LDR-FLIP, [n_materials + m] for HDR-FLIP.
    std::vector<std::optional<GreyFlipReference>> flip_references(config.flip ? 2 * n_materials : 0);
    parallel_rows(static_cast<int>(flip_references.size()), config.threads, [&](int i) {
      const std::size_t m = static_cast<std::size_t>(i) % n_materials;
      flip_references[static_cast<std::size_t>(i)] = i < static_cast<int>(n_materials)
                                                         ? GreyFlipReference(tonemapped(gt.images[m]), GreyFlipReference::Range::ldr)
                                                         : GreyFlipReference(gt.images[m], GreyFlipReference::Range::hdr);
    });
    std::vector<TradeRow> rows(n_materials * n_keys);
    std::vector<Image> images(config.keep_images ? rows.size() : 0);
    for_each_row(rows.size(), main_pixels, "1-spp variants " + name, [&](std::size_t r) {
      const std::size_t m = r / n_keys;
      const RowKey& key = keys[r % n_keys];
      Image image = shade(gbuffer, key, materials[m]);
      const ImageError e = compare_images(image, gt.images[m]);
      TradeRow& row = rows[r];
      row.variant = key.variant;
      row.feed = key.feed;
      row.prefilter = key.prefilter;
      row.lobe = key.lobe;
      row.scene = id;
      row.alpha = materials[m].alpha;
      row.fresnel = materials[m].fresnel;
      row.rmse_linear = e.rmse_linear;
      row.rmse_tonemapped = e.rmse_tonemapped;
      row.max_error = e.max_error;
      row.non_finite = e.non_finite;
      if (config.flip) {
        row.flip_ldr = flip_references[m]->mean_error(tonemapped(image));
        row.flip_hdr = flip_references[n_materials + m]->mean_error(image);
      }
      if (config.keep_images) images[r] = std::move(image);
    });
    table.rows.insert(table.rows.end(), rows.begin(), rows.end());
    if (config.keep_images) {
      for (std::size_t m = 0; m < n_materials; ++m) {
        ImageSet set;
        set.scene = id;
        set.material = materials[m];
        set.reference = gt.images[m];
        set.coverage = gt.coverage;
        for (std::size_t k = 0; k < n_keys; ++k)
          set.variants.push_back({keys[k].variant, keys[k].feed, keys[k].prefilter, keys[k].lobe, std::move(images[m * n_keys + k])});
        table.images.push_back(std::move(set));
      }
    }

    // Temporal metrics: the animation at the flicker resolution; TDE in display values,
    // the temporal standard deviations in linear and tonemapped values.
    if (config.frames > 0) {
      const int fw = sized.flicker_width, fh = sized.flicker_height;
      const std::size_t n_rows = n_materials * n_keys;
      std::vector<TemporalStats> reference_stats(n_materials, TemporalStats(fw, fh));
      std::vector<TemporalStats> reference_display(n_materials, TemporalStats(fw, fh));
      std::vector<TemporalStats> variant_stats(n_rows, TemporalStats(fw, fh));
      std::vector<TemporalStats> variant_display(n_rows, TemporalStats(fw, fh));
      std::vector<TemporalDifference> differences(n_rows);
      std::vector<Image> previous_reference(n_materials);  // display values of frame - 1
      std::vector<Image> previous_variant(n_rows);
      AnimationGroundTruths taa_truths;  // for the +taa rows
      // The verdict metrics (animation_error.hpp): each row's clip against each seed's frame.
      const int seeds = std::clamp(config.ground_truth_seeds, 1, 2);
      const bool sanity = config.sanity && seeds == 2 && config.frames >= 2;
      const bool video = config.video_metric;
      std::vector<ClipRecorder> clips(n_rows);
      for (ClipRecorder& clip : clips) clip.keep_frames = video;
      // Each row's clip against the quarter-sample ground truth (TradeRow::quarter_series), whose
      // previous frame per material is quarter_references[m].
      std::vector<ClipRecorder> quarter_clips(sanity ? n_rows : 0);
      std::vector<SeedReference> quarter_references(sanity ? n_materials : 0);
      std::vector<std::vector<SeedReference>> seed_references(n_materials);  // [m][seed], of the previous frame
      std::vector<SanityClips> sanity_clips(sanity ? n_materials : 0, SanityClips(video));
      std::vector<std::vector<ClipFrames>> reference_clips(video ? n_materials : 0,
                                                           std::vector<ClipFrames>(seeds + (sanity ? 1 : 0)));  // [m][seed], quarter
      const auto emit_frame = [&](std::size_t m, const std::string& clip, int frame, const Image& display) {
        if (on_frame) on_frame({id, materials[m].alpha, materials[m].fresnel, clip, frame, &display});
      };
      for (int frame = 0; frame < config.frames; ++frame) {
        const Scene moved = trade_animation_frame(sized, id, frame);
        const std::string stage = "flicker " + name + " frame " + std::to_string(frame + 1) + "/" + std::to_string(config.frames);
        const GroundTruth frame_gt = ground_truth(moved, flicker_settings, stage, base);
        if (config.taa) taa_truths.first.push_back(frame_gt.images);
        base += sizes.flicker_gt;
        std::optional<GroundTruth> other_gt, quarter_gt;
        if (seeds == 2) {
          GroundTruthSettings other = flicker_settings;
          other.seed = second_seed(flicker_settings.seed);
          other_gt = ground_truth(moved, other, stage, base, false);
          if (config.taa) taa_truths.second.push_back(other_gt->images);
          base += sizes.flicker_gt;
        }
        if (sanity) {
          GroundTruthSettings quarter = flicker_settings;
          quarter.seed = third_seed(flicker_settings.seed);
          quarter.strata = std::max(1, flicker_settings.strata / 2);
          quarter_gt = ground_truth(moved, quarter, stage, base, false);
          if (config.taa) taa_truths.quarter.push_back(quarter_gt->images);
          base += sizes.flicker_gt / 4;
        }
        const FrameBuffers frame_buffer = frame_buffers(config, id, moved, fw, fh);
        std::vector<Image> reference_frame(n_materials);
        std::vector<std::optional<GreyFlipReference>> flip_references(n_materials);  // the +taa rows' LDR-FLIP
        std::vector<std::vector<SeedReference>> frame_references(n_materials);
        for (std::size_t m = 0; m < n_materials; ++m) frame_references[m].resize(seeds);
        parallel_rows(static_cast<int>(n_materials * seeds), config.threads, [&](int i) {
          const std::size_t m = static_cast<std::size_t>(i) / seeds, seed = static_cast<std::size_t>(i) % seeds;
          const Image& linear = seed == 0 ? frame_gt.images[m] : other_gt->images[m];
          const SeedReference* previous = frame > 0 ? &seed_references[m][seed] : nullptr;
          frame_references[m][seed] = seed_reference(linear, previous, config.flip);
          if (video) reference_clips[m][seed].append(frame_references[m][seed].display);
        });
        std::vector<SeedReference> frame_quarter(quarter_references.size());
        parallel_rows(static_cast<int>(frame_quarter.size()), config.threads, [&](int i) {
          const std::size_t m = static_cast<std::size_t>(i);
          frame_quarter[m] = seed_reference(quarter_gt->images[m], frame > 0 ? &quarter_references[m] : nullptr, config.flip);
          if (video) reference_clips[m][seeds].append(frame_quarter[m].display);
        });
        for (std::size_t m = 0; m < n_materials; ++m) {
          const Image reference_tonemapped = tonemapped(frame_gt.images[m]);
          reference_frame[m] = frame_references[m][0].display;
          reference_stats[m].add(frame_gt.images[m]);
          reference_display[m].add(reference_tonemapped);
          if (config.taa) flip_references[m].emplace(reference_tonemapped, GreyFlipReference::Range::ldr);
          emit_frame(m, "ground-truth", frame, reference_frame[m]);
        }
        for_each_row(n_rows, flicker_pixels, stage, [&](std::size_t r) {
          const std::size_t m = r / n_keys;
          const Image image = shade(frame_buffer, keys[r % n_keys], materials[m]);
          const Image image_tonemapped = tonemapped(image);
          variant_stats[r].add(image);
          variant_display[r].add(image_tonemapped);
          Image display = display_image(image);
          if (sanity)
            quarter_clips[r].add_display(display, image_tonemapped, std::span(&frame_quarter[m], 1),
                                         frame > 0 ? std::span(&quarter_references[m], 1) : std::span<const SeedReference>());
          clips[r].add_display(std::move(display), image_tonemapped, frame_references[m],
                               frame > 0 ? std::span<const SeedReference>(seed_references[m]) : std::span<const SeedReference>());
          if (frame > 0) differences[r].add_pair(previous_variant[r], clips[r].previous_display, previous_reference[m], reference_frame[m]);
          previous_variant[r] = clips[r].previous_display;
        });
        if (sanity)
          parallel_rows(static_cast<int>(n_materials), config.threads, [&](int i) {
            const std::size_t m = static_cast<std::size_t>(i);
            sanity_clips[m].add(other_gt->images[m], quarter_gt->images[m], frame_references[m][0],
                                frame > 0 ? &seed_references[m][0] : nullptr);
          });
        for (std::size_t r = 0; r < n_rows; ++r)
          emit_frame(r / n_keys, configuration_id(table.rows[first_row + r]), frame, previous_variant[r]);
        for (std::size_t m = 0; m < sanity_clips.size(); ++m)
          for (SanityResult result : kSanityResults)
            emit_frame(m, "sanity:" + std::string(sanity_name(result)), frame, sanity_clips[m].last(result));
        previous_reference = std::move(reference_frame);
        seed_references = std::move(frame_references);
        quarter_references = std::move(frame_quarter);
        report(stage, base);
      }
      if (video) {
        report("video metric " + name, base);
        compare_clips(config, reference_clips, n_keys, static_cast<std::size_t>(seeds), clips, quarter_clips, sanity_clips);
      }
      for (std::size_t m = 0; m < n_materials; ++m) {
        const double reference_std = mean_temporal_stddev(reference_stats[m]);
        const double reference_std_display = mean_temporal_stddev(reference_display[m]);
        for (std::size_t k = 0; k < n_keys; ++k) {
          const std::size_t r = m * n_keys + k;
          TradeRow& row = table.rows[first_row + r];
          const TemporalError temporal = differences[r].mean();
          row.tde = temporal.tde;
          row.tde_excess_flicker = temporal.excess_flicker;
          row.tde_lost_motion = temporal.lost_motion;
          row.flicker = flicker(variant_stats[r], reference_stats[m]);
          row.temporal_stddev = mean_temporal_stddev(variant_stats[r]);
          row.reference_temporal_stddev = reference_std;
          row.temporal_stddev_display = mean_temporal_stddev(variant_display[r]);
          row.reference_temporal_stddev_display = reference_std_display;
          row.flicker_display = reference_std_display > 0.0 ? row.temporal_stddev_display / reference_std_display : 0.0;
          finish_verdict_metrics(clips[r], row);
          if (sanity) row.quarter_series = quarter_clips[r].series;
        }
        if (sanity)
          for (SanityResult result : kSanityResults) table.sanity.push_back(sanity_clips[m].row(id, materials[m], result));
      }
      if (config.taa) {
        const std::string stage = "taa " + name;
        const auto shaded = [&](std::uint64_t pixels) {
          base += pixels;
          report(stage, base);
        };
        append_taa_rows(sized, id, materials, taa_keys(config, id), taa_truths, table.rows, shaded,
                        config.keep_images ? &table.taa_images : nullptr);
      }
    }
  }
  report("done", state.total);
  return table;
}

// ---------------------------------------------------------------------------------------------
// Output

std::string format_trade_table(const TradeTable& table) {
  std::ostringstream s;
  char line[256];
  std::snprintf(line, sizeof line, "%-16s %6s %3s %-36s %12s %10s %12s %8s %8s %9s %9s %9s %10s %10s\n", "scene", "alpha", "F",
                "configuration", "rmse_linear", "rmse_tm", "max_error", "ldr_flip", "hdr_flip", "tde", "tde_excess", "tde_lost", "flicker",
                "flicker_tm");
  s << line;
  for (const TradeRow& r : table.rows) {
    std::snprintf(line, sizeof line,
                  "%-16s %6.4f %3s %-36s %12.5g %10.5f %12.5g %8.5f %8.5f %9.5f %9.5f %9.5f "
                  "%10.5f %10.4f%s\n",
                  std::string(scene_name(r.scene)).c_str(), r.alpha, r.fresnel ? "yes" : "no", configuration_id(r).c_str(), r.rmse_linear,
                  r.rmse_tonemapped, r.max_error, r.flip_ldr, r.flip_hdr, r.tde, r.tde_excess_flicker, r.tde_lost_motion, r.flicker,
                  r.flicker_display, r.non_finite ? "  (non-finite pixels)" : "");
    s << line;
  }
  return s.str();
}

std::string trade_table_csv(const TradeTable& table) {
  std::ostringstream s;
  s.precision(9);
  s << "scene,alpha,fresnel,variant,feed,prefilter,lobe,rmse_linear,rmse_tonemapped,max_error,flip_ldr,flip_hdr,"
       "tde,tde_excess_flicker,tde_lost_motion,flicker,temporal_stddev,reference_temporal_stddev,flicker_display,temporal_stddev_display,"
       "reference_temporal_stddev_display,non_finite\n";
  for (const TradeRow& r : table.rows)
    s << scene_name(r.scene) << "," << r.alpha << "," << (r.fresnel ? 1 : 0) << "," << variant_id(r.variant) << "," << feed_name(r.feed)
      << "," << prefilter_name(r.prefilter) << "," << lobe_name(r.lobe) << "," << r.rmse_linear << "," << r.rmse_tonemapped << ","
      << r.max_error << "," << r.flip_ldr << "," << r.flip_hdr << "," << r.tde << "," << r.tde_excess_flicker << "," << r.tde_lost_motion
      << "," << r.flicker << "," << r.temporal_stddev << "," << r.reference_temporal_stddev << "," << r.flicker_display << ","
      << r.temporal_stddev_display << "," << r.reference_temporal_stddev_display << "," << r.non_finite << "\n";
  return s.str();
}

}  // namespace saagen::measure
