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
  gather_quads(buffers.plain, config.threads, config.half_vector_frame);
  if (config.prefilter_lod_bias != 0.0 && scene_has_normal_map(id)) {
    buffers.prefiltered = render_gbuffer(scene, width, height, config.threads, config.prefilter_lod_bias);
    gather_quads(*buffers.prefiltered, config.threads, config.half_vector_frame);
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

namespace {

// The config's resolutions and strata (each scene's own, sized_for_scene) and TAA options,
// checked before anything renders.
void check_trade_config(const TradeConfig& config) {
  for (const SceneId id : config.scenes) {
    const TradeConfig sized = sized_for_scene(config, id);
    if (sized.width <= 0 || sized.height <= 0 || sized.strata <= 0)
      throw std::invalid_argument("trade table: bad main resolution or strata");
    if (sized.frames > 0 && (sized.flicker_width <= 0 || sized.flicker_height <= 0 || sized.flicker_strata <= 0))
      throw std::invalid_argument("trade table: bad flicker resolution or strata");
  }
  if (config.taa && config.frames < 2) throw std::invalid_argument("trade table: TAA rows need an animation of at least 2 frames");
  if (config.taa) check_taa_options(config.taa_options);
}

// A scene's pixels and ground-truth samples, at its own sizes: the progress's work units
// (ground-truth samples and 1-spp pixel shadings).
struct SceneSizes {
  std::uint64_t main_pixels, flicker_pixels, main_gt, flicker_gt;
};

SceneSizes scene_sizes(const TradeConfig& config, SceneId id) {
  const TradeConfig sized = sized_for_scene(config, id);
  const std::uint64_t main_pixels = static_cast<std::uint64_t>(sized.width) * sized.height;
  const std::uint64_t flicker_pixels = static_cast<std::uint64_t>(sized.flicker_width) * sized.flicker_height;
  return {main_pixels, flicker_pixels, main_pixels * sized.strata * sized.strata,
          flicker_pixels * sized.flicker_strata * sized.flicker_strata};
}

// The work units one scene takes: its ground truths and its rows' 1-spp shadings, TAA's included.
std::uint64_t scene_work(const TradeConfig& config, SceneId id, std::size_t n_materials) {
  const SceneSizes sizes = scene_sizes(config, id);
  const std::uint64_t shading_per_frame = n_materials * row_keys(config, id).size();
  const std::uint64_t taa_shading = config.taa ? static_cast<std::uint64_t>(config.frames + taa_warmup(config)) * sizes.flicker_pixels *
                                                     n_materials * taa_keys(config, id).size()
                                               : 0;
  const std::uint64_t animation =
      config.frames > 0
          ? config.frames * (static_cast<std::uint64_t>(animation_ground_truths(config) * static_cast<double>(sizes.flicker_gt)) +
                             sizes.flicker_pixels * shading_per_frame)
          : 0;
  return sizes.main_gt + sizes.main_pixels * shading_per_frame + animation + taa_shading;
}

// One compute_trade_table: the table it fills, its materials, the work done so far (`base`, in
// work units) and the progress it reports. Scene by scene: frame 0's rows (measure_still), then
// the animation's figures of the same rows (SceneAnimation), then the +taa rows.
class TradeRun {
 public:
  TradeRun(const TradeConfig& config, const TradeProgressFn& progress, const AnimationFrameFn& on_frame)
      : config_(config), progress_(progress), on_frame_(on_frame), materials_(trade_materials(config)) {
    table_.config = config;
    for (const SceneId id : config.scenes) state_.total += scene_work(config, id, materials_.size());
  }

  void measure_scene(SceneId id);

  TradeTable finish() {
    report("done", state_.total);
    return std::move(table_);
  }

 private:
  friend class SceneAnimation;

  void report(const std::string& stage, std::uint64_t done) {
    state_.stage = stage;
    state_.done = done;
    if (progress_) progress_(state_);
  }

  // The checks (check_ground_truth) apply to the ground truths every metric reads: the main image
  // and the first seed's animation. The second seed's and the quarter-sample frames only estimate
  // the ground truth's noise and feed the sanity suite (`checked` false).
  GroundTruth ground_truth(const Scene& scene, const GroundTruthSettings& settings, const std::string& stage, std::uint64_t at,
                           bool checked = true) {
    report(stage, at);
    bool hit = false;
    const auto start = std::chrono::steady_clock::now();
    GroundTruth gt = cached_ground_truth(
        scene, settings, materials_, config_.cache_dir, [&](std::uint64_t done, std::uint64_t) { report(stage, at + done); }, &hit);
    if (checked) check_ground_truth(scene, gt, materials_);
    if (hit) {
      ++table_.cache_hits;
    } else {
      ++table_.cache_misses;
      table_.ground_truth_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      table_.ground_truth_samples += static_cast<std::uint64_t>(settings.width) * settings.height * settings.strata * settings.strata;
    }
    return gt;
  }

  // One image per worker: the rows of a frame run in parallel (for_each_row), each on one thread.
  Image shade(const FrameBuffers& buffers, const RowKey& key, const Material& material) const {
    return render_variant(buffers.for_prefilter(key.prefilter), key.variant, material, config_.params, config_.derivative, 1, key.feed,
                          key.prefilter, config_.prefilter_scale, key.lobe);
  }

  // Runs body(r) for the n_materials x n_keys rows of a frame (r = m * n_keys + k) on the
  // configured threads; the progress advances `base` by pixels_per_row for each row done.
  // The images are small (FLIP's convolutions dominate), so rows, not pixels, are the unit.
  void for_each_row(std::size_t n_rows, std::uint64_t pixels_per_row, const std::string& stage,
                    const std::function<void(std::size_t r)>& body) {
    const std::uint64_t start = base_;
    parallel_rows(
        static_cast<int>(n_rows), config_.threads, [&](int r) { body(static_cast<std::size_t>(r)); },
        [&](int done) { report(stage, start + static_cast<std::uint64_t>(done) * pixels_per_row); });
    base_ = start + n_rows * pixels_per_row;
  }

  void measure_still(SceneId id, std::span<const RowKey> keys);

  const TradeConfig& config_;
  const TradeProgressFn& progress_;
  const AnimationFrameFn& on_frame_;
  const std::vector<Material> materials_;
  TradeTable table_;
  TradeProgress state_;
  std::uint64_t base_ = 0;
};

// Frame 0 at the main resolution: the ground truth, every row's 1-spp image and its image
// metrics; the scene's rows (material-major, then key order) are appended to the table.
void TradeRun::measure_still(SceneId id, std::span<const RowKey> keys) {
  const std::string name(scene_name(id));
  const TradeConfig sized = sized_for_scene(config_, id);
  const SceneSizes sizes = scene_sizes(config_, id);
  const std::size_t n_materials = materials_.size(), n_keys = keys.size();
  const Scene scene = make_scene(id, 0.0);
  const GroundTruth gt = ground_truth(scene, ground_truth_settings(sized), "ground truth " + name, base_);
  base_ += sizes.main_gt;
  report("1-spp variants " + name, base_);
  const FrameBuffers gbuffer = frame_buffers(config_, id, scene, sized.width, sized.height);
  // FLIP's reference half once per material: [m] for LDR-FLIP, [n_materials + m] for HDR-FLIP.
  std::vector<std::optional<GreyFlipReference>> flip_references(config_.flip ? 2 * n_materials : 0);
  parallel_rows(static_cast<int>(flip_references.size()), config_.threads, [&](int i) {
    const std::size_t m = static_cast<std::size_t>(i) % n_materials;
    flip_references[static_cast<std::size_t>(i)] = i < static_cast<int>(n_materials)
                                                       ? GreyFlipReference(tonemapped(gt.images[m]), GreyFlipReference::Range::ldr)
                                                       : GreyFlipReference(gt.images[m], GreyFlipReference::Range::hdr);
  });
  std::vector<TradeRow> rows(n_materials * n_keys);
  std::vector<Image> images(config_.keep_images ? rows.size() : 0);
  for_each_row(rows.size(), sizes.main_pixels, "1-spp variants " + name, [&](std::size_t r) {
    const std::size_t m = r / n_keys;
    const RowKey& key = keys[r % n_keys];
    Image image = shade(gbuffer, key, materials_[m]);
    const ImageError e = compare_images(image, gt.images[m]);
    TradeRow& row = rows[r];
    row.variant = key.variant;
    row.feed = key.feed;
    row.prefilter = key.prefilter;
    row.lobe = key.lobe;
    row.scene = id;
    row.alpha = materials_[m].alpha;
    row.fresnel = materials_[m].fresnel;
    row.rmse_linear = e.rmse_linear;
    row.rmse_tonemapped = e.rmse_tonemapped;
    row.max_error = e.max_error;
    row.non_finite = e.non_finite;
    if (config_.flip) {
      row.flip_ldr = flip_references[m]->mean_error(tonemapped(image));
      row.flip_hdr = flip_references[n_materials + m]->mean_error(image);
    }
    if (config_.keep_images) images[r] = std::move(image);
  });
  table_.rows.insert(table_.rows.end(), rows.begin(), rows.end());
  if (!config_.keep_images) return;
  for (std::size_t m = 0; m < n_materials; ++m) {
    ImageSet set;
    set.scene = id;
    set.material = materials_[m];
    set.reference = gt.images[m];
    set.coverage = gt.coverage;
    for (std::size_t k = 0; k < n_keys; ++k)
      set.variants.push_back({keys[k].variant, keys[k].feed, keys[k].prefilter, keys[k].lobe, std::move(images[m * n_keys + k])});
    table_.images.push_back(std::move(set));
  }
}

// The temporal figures of one scene's rows: the animation at the flicker resolution, frame by
// frame (TDE in display values, the temporal standard deviations in linear and tonemapped
// values), each row's clip against each ground-truth seed (the verdict metrics) and against the
// quarter-sample one, the sanity suite's results, and the ground truths the +taa rows read.
class SceneAnimation {
 public:
  SceneAnimation(TradeRun& run, SceneId id, std::span<const RowKey> keys, std::size_t first_row)
      : run_(run),
        config_(run.config_),
        id_(id),
        name_(scene_name(id)),
        sized_(sized_for_scene(run.config_, id)),
        sizes_(scene_sizes(run.config_, id)),
        settings_(ground_truth_settings(sized_, true)),
        keys_(keys),
        first_row_(first_row),
        n_materials_(run.materials_.size()),
        n_keys_(keys.size()),
        n_rows_(n_materials_ * n_keys_),
        seeds_(static_cast<std::size_t>(std::clamp(config_.ground_truth_seeds, 1, 2))),
        sanity_(config_.sanity && seeds_ == 2 && config_.frames >= 2),
        video_(config_.video_metric),
        reference_stats_(n_materials_, TemporalStats(sized_.flicker_width, sized_.flicker_height)),
        reference_display_(n_materials_, TemporalStats(sized_.flicker_width, sized_.flicker_height)),
        variant_stats_(n_rows_, TemporalStats(sized_.flicker_width, sized_.flicker_height)),
        variant_display_(n_rows_, TemporalStats(sized_.flicker_width, sized_.flicker_height)),
        differences_(n_rows_),
        previous_reference_(n_materials_),
        previous_variant_(n_rows_),
        clips_(n_rows_),
        quarter_clips_(sanity_ ? n_rows_ : 0),
        quarter_references_(sanity_ ? n_materials_ : 0),
        seed_references_(n_materials_),
        sanity_clips_(sanity_ ? n_materials_ : 0, SanityClips(video_)),
        reference_clips_(video_ ? n_materials_ : 0, std::vector<ClipFrames>(seeds_ + (sanity_ ? 1 : 0))) {
    for (ClipRecorder& clip : clips_) clip.keep_frames = video_;
  }

  void measure_frame(int frame);
  // Every row's temporal figures and verdict series, the sanity suite's rows, then the +taa rows.
  void finish();

 private:
  // The frame's ground truths: the first seed's, the second's and the quarter-sample one's (those
  // two where measured); the +taa rows keep them (taa_truths_).
  struct FrameTruths {
    GroundTruth first;
    std::optional<GroundTruth> other, quarter;
  };
  FrameTruths render_truths(const Scene& moved, const std::string& stage);
  // Each material's references of the frame for each seed, and for the quarter-sample ground truth.
  std::vector<std::vector<SeedReference>> seed_references(const FrameTruths& truths, int frame);
  std::vector<SeedReference> quarter_references(const FrameTruths& truths, int frame);
  void emit(std::size_t m, const std::string& clip, int frame, const Image& display) const {
    if (run_.on_frame_) run_.on_frame_({id_, run_.materials_[m].alpha, run_.materials_[m].fresnel, clip, frame, &display});
  }

  TradeRun& run_;
  const TradeConfig& config_;
  const SceneId id_;
  const std::string name_;
  const TradeConfig sized_;
  const SceneSizes sizes_;
  const GroundTruthSettings settings_;
  const std::span<const RowKey> keys_;
  const std::size_t first_row_, n_materials_, n_keys_, n_rows_, seeds_;
  const bool sanity_, video_;
  std::vector<TemporalStats> reference_stats_, reference_display_, variant_stats_, variant_display_;
  std::vector<TemporalDifference> differences_;
  std::vector<Image> previous_reference_;  // display values of frame - 1
  std::vector<Image> previous_variant_;
  // The verdict metrics (animation_error.hpp): each row's clip against each seed's frame.
  std::vector<ClipRecorder> clips_;
  // Each row's clip against the quarter-sample ground truth (TradeRow::quarter_series), whose
  // previous frame per material is quarter_references_[m].
  std::vector<ClipRecorder> quarter_clips_;
  std::vector<SeedReference> quarter_references_;
  std::vector<std::vector<SeedReference>> seed_references_;  // [m][seed], of the previous frame
  std::vector<SanityClips> sanity_clips_;
  std::vector<std::vector<ClipFrames>> reference_clips_;  // [m][seed], quarter
  AnimationGroundTruths taa_truths_;                      // for the +taa rows
};

SceneAnimation::FrameTruths SceneAnimation::render_truths(const Scene& moved, const std::string& stage) {
  FrameTruths truths{run_.ground_truth(moved, settings_, stage, run_.base_), std::nullopt, std::nullopt};
  if (config_.taa) taa_truths_.first.push_back(truths.first.images);
  run_.base_ += sizes_.flicker_gt;
  if (seeds_ == 2) {
    GroundTruthSettings other = settings_;
    other.seed = second_seed(settings_.seed);
    truths.other = run_.ground_truth(moved, other, stage, run_.base_, false);
    if (config_.taa) taa_truths_.second.push_back(truths.other->images);
    run_.base_ += sizes_.flicker_gt;
  }
  if (sanity_) {
    GroundTruthSettings quarter = settings_;
    quarter.seed = third_seed(settings_.seed);
    quarter.strata = std::max(1, settings_.strata / 2);
    truths.quarter = run_.ground_truth(moved, quarter, stage, run_.base_, false);
    if (config_.taa) taa_truths_.quarter.push_back(truths.quarter->images);
    run_.base_ += sizes_.flicker_gt / 4;
  }
  return truths;
}

std::vector<std::vector<SeedReference>> SceneAnimation::seed_references(const FrameTruths& truths, int frame) {
  std::vector<std::vector<SeedReference>> references(n_materials_, std::vector<SeedReference>(seeds_));
  parallel_rows(static_cast<int>(n_materials_ * seeds_), config_.threads, [&](int i) {
    const std::size_t m = static_cast<std::size_t>(i) / seeds_, seed = static_cast<std::size_t>(i) % seeds_;
    const Image& linear = seed == 0 ? truths.first.images[m] : truths.other->images[m];
    const SeedReference* previous = frame > 0 ? &seed_references_[m][seed] : nullptr;
    references[m][seed] = seed_reference(linear, previous, config_.flip);
    if (video_) reference_clips_[m][seed].append(references[m][seed].display);
  });
  return references;
}

std::vector<SeedReference> SceneAnimation::quarter_references(const FrameTruths& truths, int frame) {
  std::vector<SeedReference> references(quarter_references_.size());
  parallel_rows(static_cast<int>(references.size()), config_.threads, [&](int i) {
    const std::size_t m = static_cast<std::size_t>(i);
    references[m] = seed_reference(truths.quarter->images[m], frame > 0 ? &quarter_references_[m] : nullptr, config_.flip);
    if (video_) reference_clips_[m][seeds_].append(references[m].display);
  });
  return references;
}

void SceneAnimation::measure_frame(int frame) {
  const Scene moved = trade_animation_frame(sized_, id_, frame);
  const std::string stage = "flicker " + name_ + " frame " + std::to_string(frame + 1) + "/" + std::to_string(config_.frames);
  const FrameTruths truths = render_truths(moved, stage);
  const FrameBuffers frame_buffer = frame_buffers(config_, id_, moved, sized_.flicker_width, sized_.flicker_height);
  std::vector<std::vector<SeedReference>> frame_references = seed_references(truths, frame);
  std::vector<SeedReference> frame_quarter = quarter_references(truths, frame);
  std::vector<Image> reference_frame(n_materials_);
  for (std::size_t m = 0; m < n_materials_; ++m) {
    reference_frame[m] = frame_references[m][0].display;
    reference_stats_[m].add(truths.first.images[m]);
    reference_display_[m].add(tonemapped(truths.first.images[m]));
    emit(m, "ground-truth", frame, reference_frame[m]);
  }
  run_.for_each_row(n_rows_, sizes_.flicker_pixels, stage, [&](std::size_t r) {
    const std::size_t m = r / n_keys_;
    const Image image = run_.shade(frame_buffer, keys_[r % n_keys_], run_.materials_[m]);
    const Image image_tonemapped = tonemapped(image);
    variant_stats_[r].add(image);
    variant_display_[r].add(image_tonemapped);
    Image display = display_image(image);
    if (sanity_)
      quarter_clips_[r].add_display(display, image_tonemapped, std::span(&frame_quarter[m], 1),
                                    frame > 0 ? std::span(&quarter_references_[m], 1) : std::span<const SeedReference>());
    clips_[r].add_display(std::move(display), image_tonemapped, frame_references[m],
                          frame > 0 ? std::span<const SeedReference>(seed_references_[m]) : std::span<const SeedReference>());
    if (frame > 0) differences_[r].add_pair(previous_variant_[r], clips_[r].previous_display, previous_reference_[m], reference_frame[m]);
    previous_variant_[r] = clips_[r].previous_display;
  });
  if (sanity_)
    parallel_rows(static_cast<int>(n_materials_), config_.threads, [&](int i) {
      const std::size_t m = static_cast<std::size_t>(i);
      sanity_clips_[m].add(truths.other->images[m], truths.quarter->images[m], frame_references[m][0],
                           frame > 0 ? &seed_references_[m][0] : nullptr);
    });
  for (std::size_t r = 0; r < n_rows_; ++r)
    emit(r / n_keys_, configuration_id(run_.table_.rows[first_row_ + r]), frame, previous_variant_[r]);
  for (std::size_t m = 0; m < sanity_clips_.size(); ++m)
    for (SanityResult result : kSanityResults) emit(m, "sanity:" + std::string(sanity_name(result)), frame, sanity_clips_[m].last(result));
  previous_reference_ = std::move(reference_frame);
  seed_references_ = std::move(frame_references);
  quarter_references_ = std::move(frame_quarter);
  run_.report(stage, run_.base_);
}

void SceneAnimation::finish() {
  if (video_) {
    run_.report("video metric " + name_, run_.base_);
    compare_clips(config_, reference_clips_, n_keys_, seeds_, clips_, quarter_clips_, sanity_clips_);
  }
  for (std::size_t m = 0; m < n_materials_; ++m) {
    const double reference_std = mean_temporal_stddev(reference_stats_[m]);
    const double reference_std_display = mean_temporal_stddev(reference_display_[m]);
    for (std::size_t k = 0; k < n_keys_; ++k) {
      const std::size_t r = m * n_keys_ + k;
      TradeRow& row = run_.table_.rows[first_row_ + r];
      const TemporalError temporal = differences_[r].mean();
      row.tde = temporal.tde;
      row.tde_excess_flicker = temporal.excess_flicker;
      row.tde_lost_motion = temporal.lost_motion;
      row.flicker = flicker(variant_stats_[r], reference_stats_[m]);
      row.temporal_stddev = mean_temporal_stddev(variant_stats_[r]);
      row.reference_temporal_stddev = reference_std;
      row.temporal_stddev_display = mean_temporal_stddev(variant_display_[r]);
      row.reference_temporal_stddev_display = reference_std_display;
      row.flicker_display = reference_std_display > 0.0 ? row.temporal_stddev_display / reference_std_display : 0.0;
      finish_verdict_metrics(clips_[r], row);
      if (sanity_) row.quarter_series = quarter_clips_[r].series;
    }
    if (sanity_)
      for (SanityResult result : kSanityResults) run_.table_.sanity.push_back(sanity_clips_[m].row(id_, run_.materials_[m], result));
  }
  if (!config_.taa) return;
  const std::string stage = "taa " + name_;
  const auto shaded = [&](std::uint64_t pixels) {
    run_.base_ += pixels;
    run_.report(stage, run_.base_);
  };
  append_taa_rows(sized_, id_, run_.materials_, taa_keys(config_, id_), taa_truths_, run_.table_.rows, shaded,
                  config_.keep_images ? &run_.table_.taa_images : nullptr, run_.on_frame_);
}

void TradeRun::measure_scene(SceneId id) {
  const std::vector<RowKey> keys = row_keys(config_, id);
  const std::size_t first_row = table_.rows.size();
  measure_still(id, keys);
  if (config_.frames <= 0) return;
  SceneAnimation animation(*this, id, keys, first_row);
  for (int frame = 0; frame < config_.frames; ++frame) animation.measure_frame(frame);
  animation.finish();
}

}  // namespace

TradeTable compute_trade_table(const TradeConfig& config, const TradeProgressFn& progress, const AnimationFrameFn& on_frame) {
  check_trade_config(config);
  TradeRun run(config, progress, on_frame);
  for (const SceneId id : config.scenes) run.measure_scene(id);
  return run.finish();
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
