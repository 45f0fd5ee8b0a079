// Normal-map prefiltering: the tool's MIP chain against the reference NormalMap's moments, the
// analytic Toksvig and LEAN values, the combination with the screen-space kernel (kappa clamps
// the kernel only), the roughness domains, and `saagen texture prefilter` as a whole process.
//
// Rounding bound of the stored levels: the tool and measure::NormalMap compute the same double
// sums in the same order, so a stored value is round(x) with x within ~1e-15 of the reference
// value r; round-to-nearest puts it within half an ulp: |stored - r| <= 2^-11 |r| (half; 2^-24 for
// float32) + 1e-12 for the double-level difference and values in the subnormal range.
#include "support/cli_support.hpp"

#include "saagen/advice.hpp"
#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/measure/normal_map.hpp"
#include "saagen/measure/trade.hpp"
#include "saagen/products/prefilter.hpp"
#include "saagen/reference/reference.hpp"

#include <nlohmann/json.hpp>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstring>

namespace {

namespace fs = std::filesystem;
namespace pf = saagen::prefilter;
namespace ref = saagen::ref;
using ref::Sym2;
using ref::Vec2;
using ref::Vec3;

constexpr double kHalfUlp = 0x1p-11;
constexpr double kFloatUlp = 0x1p-24;

pf::NormalImage image_of(int width, int height, const std::vector<Vec3>& normals) {
  pf::NormalImage image{width, height, {}};
  for (const Vec3& n : normals) image.normals.insert(image.normals.end(), {n.x, n.y, n.z});
  return image;
}

// A bumpy, anisotropic height field: sums of sines (periodic on the unit square).
std::vector<Vec3> bumpy_normals(int size) {
  return saagen::measure::normals_from_gradient(size, [](Vec2 uv) {
    const double tau = 6.283185307179586;
    return Vec2{0.8 * std::cos(tau * 3 * uv.x) + 0.3 * std::cos(tau * (5 * uv.x + 2 * uv.y)),
                0.2 * std::cos(tau * uv.y) + 0.3 * std::cos(tau * (5 * uv.x + 2 * uv.y))};
  });
}

double value_at(const saagen::Ktx2Image& image, std::size_t level, std::size_t index) {
  const auto& bytes = image.levels[level];
  if (image.type_size == 2) return saagen::glints::from_half(static_cast<std::uint16_t>(bytes[2 * index] | bytes[2 * index + 1] << 8));
  float f = 0.0f;
  std::memcpy(&f, bytes.data() + 4 * index, 4);
  return f;
}

saagen::Ktx2Image round_trip(const std::vector<pf::Level>& levels, const pf::Options& options) {
  const auto bytes = saagen::write_ktx2(pf::prefilter_ktx2(levels, options));
  return saagen::read_ktx2(bytes);
}

std::string key_value(const saagen::Ktx2Image& image, const std::string& key) {
  for (const auto& [k, v] : image.key_values)
    if (k == key) return v;
  return {};
}

TEST(PrefilterLevels, ToksvigMatchesTheReferenceNormalMapWithinHalfRounding) {
  const int width = 16, height = 8;  // non-square: the longer side keeps halving alone
  auto normals = bumpy_normals(16);
  normals.resize(static_cast<std::size_t>(width) * height);
  const saagen::measure::NormalMap map(width, height, normals);
  const auto levels = pf::build_levels(image_of(width, height, normals));
  ASSERT_EQ(static_cast<int>(levels.size()), map.levels());
  for (const bool float32 : {false, true}) {
    for (const saagen::Domain domain : {saagen::Domain::alpha2, saagen::Domain::alpha, saagen::Domain::perceptual}) {
      const pf::Options options{pf::Method::toksvig, domain, 0.3, float32};
      const auto image = round_trip(levels, options);
      ASSERT_EQ(image.vk_format, float32 ? 100u : 76u);
      ASSERT_EQ(image.levels.size(), levels.size());
      double worst = 0.0;
      for (int level = 0; level < map.levels(); ++level)
        for (int y = 0; y < map.height(level); ++y)
          for (int x = 0; x < map.width(level); ++x) {
            const double length = ref::length(map.texel(level, x, y).mean_normal);
            const double expected = pf::from_alpha2(ref::prefilter_toksvig(ref::Params{}, pf::to_alpha2(0.3, domain), length), domain);
            const double got = value_at(image, level, static_cast<std::size_t>(y) * map.width(level) + x);
            const double bound = (float32 ? kFloatUlp : kHalfUlp) * std::fabs(expected) + 1e-12;
            worst = std::max(worst, std::fabs(got - expected) / bound);
            ASSERT_LE(std::fabs(got - expected), bound) << "level " << level << " texel " << x << "," << y;
          }
      std::cout << "[ worst    ] toksvig " << saagen::to_string(domain) << (float32 ? " r32f" : " r16f") << ": " << worst
                << " of the bound\n";
    }
  }
}

TEST(PrefilterLevels, LeanMomentsMatchTheReferenceNormalMapWithinFloatRounding) {
  const int size = 16;
  const auto normals = bumpy_normals(size);
  const saagen::measure::NormalMap map(size, size, normals);
  const auto image = round_trip(pf::build_levels(image_of(size, size, normals)), pf::Options{pf::Method::lean});
  ASSERT_EQ(image.vk_format, 109u);
  ASSERT_EQ(image.layers, 2u);
  for (int level = 0; level < map.levels(); ++level) {
    const std::size_t texels = static_cast<std::size_t>(map.width(level)) * map.height(level);
    for (int y = 0; y < map.height(level); ++y)
      for (int x = 0; x < map.width(level); ++x) {
        const auto& t = map.texel(level, x, y);
        const std::size_t i = static_cast<std::size_t>(y) * map.width(level) + x;
        const double expected[5] = {t.slope_mean.x, t.slope_mean.y, t.slope_second.xx, t.slope_second.yy, t.slope_second.xy};
        const double got[5] = {value_at(image, level, 4 * i), value_at(image, level, 4 * i + 1), value_at(image, level, 4 * i + 2),
                               value_at(image, level, 4 * i + 3), value_at(image, level, 4 * (texels + i))};
        for (int k = 0; k < 5; ++k)
          ASSERT_LE(std::fabs(got[k] - expected[k]), kFloatUlp * std::fabs(expected[k]) + 1e-12) << level << " " << k;
      }
  }
  const auto json = nlohmann::json::parse(key_value(image, "saagen.prefilter"));
  EXPECT_EQ(json["method"], "lean");
  EXPECT_EQ(json["layers"][0][2], "E[x^2]");
  EXPECT_EQ(json["layers"][1][0], "E[xy]");
}

// Two normals at +-theta about z (a 2x2 checkerboard): the level-1 mean normal is (0, 0, cos
// theta), so Toksvig's variance is (1 - cos) / cos = sec theta - 1, which tends to the slopes'
// per-axis mean variance tr(Sigma) / 2 = tan^2 theta / 2 as theta -> 0.
TEST(Toksvig, TwoNormalsAtPlusMinusThetaGiveTheAnalyticVariance) {
  for (const double theta : {0.05, 0.3, 0.6}) {
    const Vec3 a{std::sin(theta), 0.0, std::cos(theta)}, b{-std::sin(theta), 0.0, std::cos(theta)};
    const auto levels = pf::build_levels(image_of(2, 2, {a, b, b, a}));
    const auto image = round_trip(levels, pf::Options{pf::Method::toksvig, saagen::Domain::alpha2, 0.0, true});
    const double variance = 1.0 / std::cos(theta) - 1.0;
    EXPECT_NEAR(ref::toksvig_variance(ref::Params{}, std::cos(theta)), variance, 1e-15);
    EXPECT_NEAR(value_at(image, 1, 0), std::min(1.0, 2.0 * variance), kFloatUlp * 2.0 * variance + 1e-15) << theta;
    const double lean_half_trace = 0.5 * std::tan(theta) * std::tan(theta);
    if (theta == 0.05) {
      EXPECT_NEAR(variance / lean_half_trace, 1.0, 1e-3);  // 2 cos / (1 + cos)
    }
  }
  // L = 0 (opposite normals cancel) is guarded: finite, and the roughness saturates.
  EXPECT_TRUE(std::isfinite(ref::toksvig_variance(ref::Params{}, 0.0)));
  EXPECT_EQ(ref::prefilter_toksvig(ref::Params{}, 0.1, 0.0), 1.0);
  EXPECT_EQ(pf::toksvig_alpha2(0.1, 0.0), 1.0);
}

// --- The engines' bakes (docs/PREFILTER.md) ------------------------------------------------------

// A 2x2 level of normals (+-0.6, 0, 0.8): level 1 holds the mean (0, 0, 0.8), L = 0.8. By hand:
//   Toksvig (1 - L) / L = 0.25: a' = a + 0.5;
//   vMF kappa = (2.4 - 0.512) / (1 - 0.64) = 1.888 / 0.36 = 5.2444...;
//   filament-vmf a' = a + 2 / kappa = a + 0.72 / 1.888 = a + 0.38135593220339;
//   hdrp 1 / (2 kappa) = 0.0953389... is above the cap: a' = a + 0.0625;
//   unreal V = 0.25 - 4e-5 = 0.24996, B = 2 V (a - 1): a = 0 gives 0.49992 / 1.49992 =
//   0.33330310950; a = 0.25 gives B = -0.37494, a' = 0.62494 / 1.37494 = 0.45452165912.
TEST(EnginePrefilters, HandComputedRoughnessOfAKnownLevel) {
  const Vec3 a{0.6, 0.0, 0.8}, b{-0.6, 0.0, 0.8};
  const auto levels = pf::build_levels(image_of(2, 2, {a, b, b, a}));
  struct Case {
    pf::Method method;
    double base, expected;
  };
  const Case cases[] = {{pf::Method::toksvig, 0.0, 0.5},
                        {pf::Method::toksvig, 0.25, 0.75},
                        {pf::Method::filament_vmf, 0.0, 0.72 / 1.888},
                        {pf::Method::filament_vmf, 0.25, 0.25 + 0.72 / 1.888},
                        {pf::Method::hdrp, 0.0, 0.0625},
                        {pf::Method::hdrp, 0.25, 0.3125},
                        {pf::Method::unreal, 0.0, 0.49992 / 1.49992},
                        {pf::Method::unreal, 0.25, 0.62494 / 1.37494}};
  EXPECT_NEAR(pf::vmf_kappa(0.8), 1.888 / 0.36, 1e-14);
  for (const Case& c : cases) {
    const auto image = round_trip(levels, pf::Options{c.method, saagen::Domain::alpha2, c.base, true});
    ASSERT_EQ(image.levels.size(), 2u);
    EXPECT_NEAR(value_at(image, 0, 0), c.base, kFloatUlp * c.base) << pf::to_string(c.method);  // L = 1: the base
    EXPECT_NEAR(value_at(image, 1, 0), c.expected, kFloatUlp * c.expected + 1e-7) << pf::to_string(c.method) << " " << c.base;
    EXPECT_NEAR(pf::method_alpha2(c.method, c.base, 0.8), c.expected, 1e-14) << pf::to_string(c.method);
    EXPECT_EQ(nlohmann::json::parse(key_value(image, "saagen.prefilter"))["method"], std::string(pf::to_string(c.method)));
  }
  // --scale multiplies the addition: Toksvig at half strength adds 0.25 at L = 0.8.
  pf::Options half{pf::Method::toksvig, saagen::Domain::alpha2, 0.25, true};
  half.scale = 0.5;
  EXPECT_NEAR(value_at(round_trip(levels, half), 1, 0), 0.5, kFloatUlp * 0.5);
  EXPECT_EQ(nlohmann::json::parse(key_value(round_trip(levels, half), "saagen.prefilter"))["scale"], 0.5);
  // Below the HDRP cap (L = 0.95): kappa = 1.992625 / 0.0975, 1 / (2 kappa) = 0.0975 / 3.98525.
  EXPECT_NEAR(pf::method_alpha2(pf::Method::hdrp, 0.1, 0.95), 0.1 + 0.0975 / 3.98525, 1e-14);
  EXPECT_NEAR(pf::method_alpha2(pf::Method::filament_vmf, 0.1, 0.95), 0.1 + 0.195 / 1.992625, 1e-14);
}

// The library's bakes are the reference's (reference/prefilter.hpp), and Unreal's composite is
// T&K 2021's projected-space addition of twice its variance.
TEST(EnginePrefilters, LibraryMatchesTheReferenceOverLengthsAndRoughness) {
  for (double length = 0.0; length <= 1.0; length += 1.0 / 64.0)
    for (const double base : {0.0, 1e-4, 0.01, 0.09, 0.5, 1.0}) {
      const double l = std::min(length, 1.0);
      EXPECT_NEAR(pf::method_alpha2(pf::Method::unreal, base, l), ref::unreal_composite_alpha2(base, l), 1e-15) << l << " " << base;
      EXPECT_NEAR(pf::method_alpha2(pf::Method::filament_vmf, base, l), ref::filament_vmf_alpha2(base, l), 1e-15) << l << " " << base;
      EXPECT_NEAR(pf::method_alpha2(pf::Method::hdrp, base, l), ref::hdrp_texture_alpha2(base, l), 1e-15) << l << " " << base;
      if (l > 0.0) {
        const double variance = std::max((1.0 - l) / l - 4e-5, 0.0);
        EXPECT_NEAR(ref::unreal_composite_alpha2(base, l), ref::projected_space_add(base, 2.0 * variance), 1e-14) << l << " " << base;
      }
      for (const pf::Method method : {pf::Method::toksvig, pf::Method::unreal, pf::Method::filament_vmf, pf::Method::hdrp}) {
        const double value = pf::method_alpha2(method, base, l);
        EXPECT_TRUE(value >= base - 1e-15 && value <= 1.0) << pf::to_string(method) << " " << l << " " << base;
      }
    }
}

// For a small spread (L = 1 - e) the added alpha^2 is 2e for Toksvig, Filament and Unreal (at
// a = 0) and e / 2 for HDRP: the factor of 4 between the engines.
TEST(EnginePrefilters, SmallSpreadRatiosToToksvig) {
  const double e = 1e-3, l = 1.0 - e;
  const double toksvig = pf::method_alpha2(pf::Method::toksvig, 0.0, l);
  EXPECT_NEAR(pf::method_alpha2(pf::Method::filament_vmf, 0.0, l) / toksvig, 1.0, 3e-3);
  EXPECT_NEAR(pf::method_alpha2(pf::Method::hdrp, 0.0, l) / toksvig, 0.25, 1e-3);
  EXPECT_NEAR(pf::method_alpha2(pf::Method::unreal, 0.0, l) / toksvig, 1.0, 0.05);  // 4e-5 bias and the projection
}

// Four slopes chosen by hand: E[s] and E[s s^T] by hand, Sigma = E[s s^T] - E[s] E[s]^T.
TEST(Lean, CovarianceOfAKnownMapIsExact) {
  const Vec2 slopes[4] = {{0.5, 0.0}, {-0.25, 0.25}, {0.0, -0.5}, {0.25, 0.75}};
  std::vector<Vec3> normals;
  for (const Vec2 s : slopes) normals.push_back(ref::normalize(Vec3{-s.x, -s.y, 1.0}));
  const auto levels = pf::build_levels(image_of(2, 2, normals));
  const Vec2 mean{levels[1].slope_mean[0], levels[1].slope_mean[1]};
  const Sym2 second{levels[1].slope_second[0], levels[1].slope_second[1], levels[1].slope_second[2]};
  // E[s] = (0.125, 0.125); Sigma: E[x^2] = 0.09375 -> 0.078125, E[xy] = 0.03125 -> 0.015625,
  // E[y^2] = 0.21875 -> 0.203125 (the slopes come back from the unit normals to ~1e-16).
  EXPECT_NEAR(mean.x, 0.125, 1e-15);
  EXPECT_NEAR(mean.y, 0.125, 1e-15);
  const Sym2 covariance = ref::lean_covariance(ref::Params{}, mean, second);
  EXPECT_NEAR(covariance.xx, 0.078125, 1e-14);
  EXPECT_NEAR(covariance.xy, 0.015625, 1e-14);
  EXPECT_NEAR(covariance.yy, 0.203125, 1e-14);
  const Sym2 a = ref::prefilter_lean(ref::Params{}, {0.01, 0.04}, mean, second);
  EXPECT_NEAR(a.xx, 0.01 + 2 * 0.078125, 1e-14);
  EXPECT_NEAR(a.xy, 2 * 0.015625, 1e-14);
  EXPECT_NEAR(a.yy, 0.04 + 2 * 0.203125, 1e-14);
  // Isotropic: alpha^2 + tr(Sigma) (same E|s - E s|^2), no derivatives.
  EXPECT_NEAR(ref::prefilter_lean_sum(ref::Params{}, 0.01, mean, second, {}, {}), 0.01 + 0.28125, 1e-14);
  // Cancellation can make E[s s^T] - E[s]^2 slightly indefinite: the guard clamps it to PSD.
  const Sym2 clamped = ref::lean_covariance(ref::Params{}, {1.0, 1.0}, {1.0 - 1e-9, 1.0 + 1e-3, 1.0});
  EXPECT_EQ(clamped.xx, 0.0);
  EXPECT_EQ(clamped.xy, 0.0);
}

TEST(Combination, MonotoneInRoughnessSpreadAndDerivatives) {
  const ref::Params p;
  const Vec3 small{0.05, 0.0, 0.0}, large{0.3, 0.1, 0.0}, zero{};
  for (const double a : {0.0, 0.01, 0.2, 0.7}) {
    double previous_sum = -1.0, previous_projected = -1.0;
    for (const double l : {1.0, 0.999, 0.99, 0.95, 0.8, 0.5, 0.1}) {  // a shorter mean normal: more spread
      const double sum = ref::prefilter_toksvig_sum(p, a, l, small, zero);
      const double projected = ref::prefilter_toksvig_projected(p, a, l, small, zero);
      EXPECT_GE(sum, previous_sum);
      EXPECT_GE(projected, previous_projected);
      EXPECT_GE(sum, a);
      EXPECT_LE(sum, 1.0);
      EXPECT_GE(ref::prefilter_toksvig_sum(p, a, l, large, zero), sum);
      EXPECT_GE(ref::prefilter_toksvig_sum(p, a + 0.01, l, small, zero), sum);
      previous_sum = sum, previous_projected = projected;
    }
    double previous = -1.0;
    for (const double scale : {0.0, 1e-3, 0.01, 0.1, 1.0}) {  // a wider slope covariance
      const Sym2 second{0.01 + 0.4 * scale, 0.005 + 0.1 * scale, 0.0025 + 0.2 * scale};
      const double value = ref::prefilter_lean_projected(p, a, {0.1, 0.05}, second, small, zero);
      EXPECT_GE(value, previous);
      previous = value;
    }
  }
}

TEST(Combination, KappaClampsOnlyTheScreenSpaceKernel) {
  const ref::Params p;
  const Vec3 huge{100.0, 0.0, 0.0}, zero{};
  const double a = 0.01, l = 0.8, texture_term = 2.0 * (1.0 - l) / l;  // 0.5 > kappa
  // The texture term alone exceeds kappa and is kept whole.
  EXPECT_DOUBLE_EQ(ref::prefilter_toksvig(p, a, l), a + texture_term);
  // A huge kernel adds exactly kappa on top of it.
  EXPECT_DOUBLE_EQ(ref::prefilter_toksvig_sum(p, a, l, huge, zero), ref::saturate(a + texture_term + p.kappa));
  // Projected space: p' = p + texture + kappa.
  const double pp = a / (1.0 - a) + texture_term + p.kappa;
  EXPECT_NEAR(ref::prefilter_toksvig_projected(p, a, l, huge, zero), pp / (1.0 + pp), 1e-15);
  // LEAN: tr(Sigma_tex) = 0.6 unclamped, kernel clamped.
  const Sym2 second{0.4, 0.0, 0.2};
  EXPECT_DOUBLE_EQ(ref::prefilter_lean_sum(p, 0.1, {}, second, huge, zero), ref::saturate(0.1 + 0.6 + p.kappa));
  EXPECT_DOUBLE_EQ(ref::prefilter_lean_sum(p, 0.1, {}, second, zero, zero), 0.7);
  // The forward matrix: A = diag(alpha^2) + 2 (Sigma_screen + Sigma_tex), no clamp at all.
  const Sym2 with_texture = ref::prefilter_lean_aniso_slope(p, {0.01, 0.02}, {}, second, {0.5, 0.0}, {0.0, 0.25});
  const Sym2 screen_only = ref::forward_aniso_slope(p, {0.01, 0.02}, {0.5, 0.0}, {0.0, 0.25});
  EXPECT_DOUBLE_EQ(with_texture.xx, screen_only.xx + 0.8);
  EXPECT_DOUBLE_EQ(with_texture.yy, screen_only.yy + 0.4);
  // With no spread (L = 1, zero covariance) every form is the screen-space variant.
  const Vec3 d{0.2, 0.1, 0.0};
  EXPECT_DOUBLE_EQ(ref::prefilter_toksvig_sum(p, 0.05, 1.0, d, zero), ref::deferred_sum(p, 0.05, d, zero));
  EXPECT_DOUBLE_EQ(ref::prefilter_toksvig_projected(p, 0.05, 1.0, d, zero), ref::deferred_projected_space(p, 0.05, d, zero));
}

TEST(Domains, RoundTrip) {
  for (const saagen::Domain domain : {saagen::Domain::alpha2, saagen::Domain::alpha, saagen::Domain::perceptual}) {
    for (int k = 0; k <= 100; ++k) {
      const double value = k / 100.0;
      EXPECT_NEAR(pf::from_alpha2(pf::to_alpha2(value, domain), domain), value, 1e-15);
      EXPECT_NEAR(pf::to_alpha2(pf::from_alpha2(value, domain), domain), value, 1e-15);
    }
  }
  EXPECT_DOUBLE_EQ(pf::to_alpha2(0.5, saagen::Domain::perceptual), 0.0625);  // alpha = r^2, alpha^2 = r^4
  EXPECT_EQ(saagen::find_domain("alpha").kind, saagen::Domain::alpha);
  EXPECT_THROW(saagen::find_domain("roughness"), saagen::Error);
  EXPECT_THROW(pf::parse_method("vmf"), saagen::Error);
}

// --- `saagen texture prefilter` as a process ---------------------------------------------------

class TexturePrefilterCli : public saagen::test::CliTest {
 protected:
  // An 8-bit RGB PNG of the bumpy normals (n = 2 c - 1, c = round(255 (n + 1) / 2)).
  fs::path write_png(const std::string& name, int width, int height, const std::vector<Vec3>& normals) const {
    std::vector<unsigned char> pixels;
    for (const Vec3& n : normals)
      for (double c : {n.x, n.y, n.z}) pixels.push_back(static_cast<unsigned char>(std::lround(255.0 * (c + 1.0) / 2.0)));
    const fs::path path = scratch_ / name;
    EXPECT_NE(stbi_write_png(path.string().c_str(), width, height, 3, pixels.data(), width * 3), 0);
    return path;
  }

  static std::vector<std::uint8_t> bytes_of(const fs::path& path) {
    const std::string text = saagen::test::read_text(path);
    return {text.begin(), text.end()};
  }

  void expect_one_line_failure(const saagen::test::CliRun& run, const fs::path& output) const {
    EXPECT_EQ(run.exit_code, 1) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_EQ(run.err.rfind("saagen: error: ", 0), 0u) << run.err;
    EXPECT_FALSE(fs::exists(output));
    for (const auto& entry : fs::directory_iterator(scratch_))
      EXPECT_EQ(entry.path().filename().string().find("saagen-tmp"), std::string::npos);
  }
};

// `glints lean` reads normal maps with texture prefilter's reader: the same 8-bit normals as a PNG
// and as a binary PPM give the same LEAN moments (the PPM decoding n = 2 c / 255 - 1 is the PNG's
// n = 2 (c / 255) - 1; doubling is exact, so both normalise the same doubles), to one float ulp.
TEST_F(TexturePrefilterCli, GlintsLeanReadsThePngAsItsPpm) {
  const int size = 8;
  const auto normals = bumpy_normals(size);
  const fs::path png = write_png("normals.png", size, size, normals);
  std::string ppm = "P6\n8 8\n255\n";
  for (const Vec3& n : normals)
    for (double c : {n.x, n.y, n.z}) ppm += static_cast<char>(std::lround(255.0 * (c + 1.0) / 2.0));
  std::ofstream(scratch_ / "normals.ppm", std::ios::binary) << ppm;
  const fs::path from_png = scratch_ / "png.ktx2", from_ppm = scratch_ / "ppm.ktx2";
  const auto png_run = saagen({"glints", "lean", png.string(), "-o", from_png.string()});
  const auto ppm_run = saagen({"glints", "lean", (scratch_ / "normals.ppm").string(), "-o", from_ppm.string()});
  ASSERT_EQ(png_run.exit_code, 0) << png_run.err;
  ASSERT_EQ(ppm_run.exit_code, 0) << ppm_run.err;
  const auto a = saagen::read_ktx2(bytes_of(from_png)), b = saagen::read_ktx2(bytes_of(from_ppm));
  ASSERT_EQ(a.levels.size(), 4u);
  ASSERT_EQ(a.levels.size(), b.levels.size());
  for (std::size_t level = 0; level < a.levels.size(); ++level) {
    ASSERT_EQ(a.levels[level].size(), b.levels[level].size());
    for (std::size_t at = 0; at + 4 <= a.levels[level].size(); at += 4) {
      float x = 0, y = 0;
      std::memcpy(&x, a.levels[level].data() + at, 4);
      std::memcpy(&y, b.levels[level].data() + at, 4);
      EXPECT_LE(std::abs(x - y), std::ldexp(std::max(std::abs(x), std::abs(y)), -23) + 1e-30) << "level " << level << " byte " << at;
    }
  }
  // Neither format: one line naming the file and the formats read.
  std::ofstream(scratch_ / "normals.txt") << "not an image";
  const auto refused = saagen({"glints", "lean", (scratch_ / "normals.txt").string(), "-o", (scratch_ / "txt.ktx2").string()});
  expect_one_line_failure(refused, scratch_ / "txt.ktx2");
  EXPECT_NE(refused.err.find("normals.txt: neither a PNG, a KTX2 nor a binary PPM (P6) file"), std::string::npos) << refused.err;
}

TEST_F(TexturePrefilterCli, PngToKtx2RoundTrip) {
  const int size = 8;
  const auto normals = bumpy_normals(size);
  const fs::path input = write_png("normals.png", size, size, normals), output = scratch_ / "out" / "rough.ktx2";
  const auto run = saagen({"texture", "prefilter", input.string(), "-o", output.string(), "--method", "toksvig", "--domain", "perceptual",
                           "--roughness", "0.4"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto image = saagen::read_ktx2(bytes_of(output));
  EXPECT_EQ(image.vk_format, 76u);
  EXPECT_EQ(image.width, 8u);
  ASSERT_EQ(image.levels.size(), 4u);
  const auto json = nlohmann::json::parse(key_value(image, "saagen.prefilter"));
  EXPECT_EQ(json["method"], "toksvig");
  EXPECT_EQ(json["domain"], "perceptual");
  EXPECT_EQ(json["format"], "R16_SFLOAT");
  EXPECT_DOUBLE_EQ(json["base_roughness"].get<double>(), 0.4);
  // The library on the decoded PNG gives the same file, byte for byte.
  const auto decoded = pf::read_normal_map(bytes_of(input), "normals.png");
  const auto expected =
      saagen::write_ktx2(pf::prefilter_ktx2(pf::build_levels(decoded), {pf::Method::toksvig, saagen::Domain::perceptual, 0.4}));
  EXPECT_EQ(bytes_of(output), expected);
  EXPECT_NEAR(value_at(image, 0, 0), 0.4, kHalfUlp);  // level 0: no spread, the base roughness
  for (std::size_t level = 1; level < image.levels.size(); ++level) EXPECT_GE(value_at(image, level, 0), 0.4 - kHalfUlp);
  // Running again leaves the file alone; a file saagen did not write is not replaced.
  const auto again =
      saagen({"texture", "prefilter", input.string(), "-o", output.string(), "--domain", "perceptual", "--roughness", "0.4"});
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("unchanged"), std::string::npos) << again.out;
  // Both runs say how to sample the map and the bake: saagen's advice, the LOD bias.
  EXPECT_NE(again.out.find("\nsample    " + std::string(saagen::advice::kPrefilterSamplingText) + "\n"), std::string::npos) << again.out;
  const fs::path foreign = scratch_ / "foreign.ktx2";
  std::ofstream(foreign) << "not saagen's";
  const auto refused = saagen({"texture", "prefilter", input.string(), "-o", foreign.string()});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_EQ(saagen::test::read_text(foreign), "not saagen's");
  EXPECT_EQ(saagen({"texture", "prefilter", input.string(), "-o", foreign.string(), "--force"}).exit_code, 0);
}

// Every method name the CLI takes, and the glTF layout: R8G8B8A8_UNORM, G = perceptual roughness
// of the bake at every level (rounded to 8 bits: within half a step, 0.5 / 255), B = --metallic,
// R = A = 255, linear transfer in the DFD (KTX2's basic descriptor, as glTF requires of
// metallicRoughnessTexture).
TEST_F(TexturePrefilterCli, EngineMethodsAndTheGltfLayout) {
  const int size = 8;
  const auto normals = bumpy_normals(size);
  const fs::path input = write_png("normals.png", size, size, normals);
  const auto levels = pf::build_levels(pf::read_normal_map(bytes_of(input), "normals.png"));
  for (const char* method : {"toksvig", "unreal", "filament-vmf", "hdrp", "lean"}) {
    const fs::path out = scratch_ / (std::string(method) + ".ktx2");
    const auto run = saagen({"texture", "prefilter", input.string(), "-o", out.string(), "--method", method, "--roughness", "0.3"});
    ASSERT_EQ(run.exit_code, 0) << method << ": " << run.err;
    EXPECT_EQ(nlohmann::json::parse(key_value(saagen::read_ktx2(bytes_of(out)), "saagen.prefilter"))["method"], method);
  }
  const fs::path gltf = scratch_ / "mr.ktx2";
  const auto run = saagen({"texture", "prefilter", input.string(), "-o", gltf.string(), "--method", "filament-vmf", "--roughness", "0.3",
                           "--gltf", "--metallic", "1"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto image = saagen::read_ktx2(bytes_of(gltf));
  EXPECT_EQ(image.vk_format, 37u);
  EXPECT_EQ((image.dfd[3] >> 16) & 0xFFu, 1u);  // transferFunction LINEAR
  ASSERT_EQ(image.levels.size(), levels.size());
  const double base = pf::to_alpha2(0.3, saagen::Domain::perceptual);
  for (std::size_t level = 0; level < levels.size(); ++level) {
    ASSERT_EQ(image.levels[level].size(), 4 * levels[level].mean_normal.size() / 3);
    for (std::size_t t = 0; t < levels[level].mean_normal.size() / 3; ++t) {
      const double* m = &levels[level].mean_normal[3 * t];
      const double r =
          pf::from_alpha2(pf::method_alpha2(pf::Method::filament_vmf, base, std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2])),
                          saagen::Domain::perceptual);
      const std::uint8_t* texel = &image.levels[level][4 * t];
      EXPECT_EQ(texel[0], 255);
      EXPECT_NEAR(texel[1] / 255.0, r, 0.5 / 255.0 + 1e-12) << level << " " << t;
      EXPECT_EQ(texel[2], 255);
      EXPECT_EQ(texel[3], 255);
    }
  }
  const auto json = nlohmann::json::parse(key_value(image, "saagen.prefilter"));
  EXPECT_EQ(json["format"], "R8G8B8A8_UNORM");
  EXPECT_EQ(json["output_domain"], "perceptual");
  EXPECT_EQ(json["channels"][1], "perceptual roughness");
  // LEAN has no roughness channel to lay out; an unknown method lists the five.
  const fs::path refused = scratch_ / "refused.ktx2";
  expect_one_line_failure(saagen({"texture", "prefilter", input.string(), "-o", refused.string(), "--method", "lean", "--gltf"}), refused);
  const auto unknown = saagen({"texture", "prefilter", input.string(), "-o", refused.string(), "--method", "vmf"});
  expect_one_line_failure(unknown, refused);
  EXPECT_NE(unknown.err.find("toksvig, lean, unreal, filament-vmf, hdrp"), std::string::npos) << unknown.err;
  expect_one_line_failure(saagen({"texture", "prefilter", input.string(), "-o", refused.string(), "--gltf", "--metallic", "2"}), refused);
  expect_one_line_failure(saagen({"texture", "prefilter", input.string(), "-o", refused.string(), "--method", "lean", "--scale", "0.5"}),
                          refused);
}

TEST_F(TexturePrefilterCli, Ktx2InputToLeanMoments) {
  const int size = 4;
  const auto normals = bumpy_normals(size);
  saagen::Ktx2Image input;
  input.vk_format = 109;
  input.type_size = 4;
  input.width = input.height = size;
  input.levels.emplace_back();
  for (const Vec3& n : normals)
    for (double c : {n.x, n.y, n.z, 1.0}) {
      const float f = static_cast<float>(c);
      std::uint8_t b[4];
      std::memcpy(b, &f, 4);
      input.levels[0].insert(input.levels[0].end(), b, b + 4);
    }
  const fs::path in_path = scratch_ / "normals.ktx2", out_path = scratch_ / "lean.ktx2";
  const auto bytes = saagen::write_ktx2(input);
  std::ofstream(in_path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  const auto run = saagen({"texture", "prefilter", in_path.string(), "-o", out_path.string(), "--method", "lean"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto image = saagen::read_ktx2(bytes_of(out_path));
  EXPECT_EQ(image.vk_format, 109u);
  EXPECT_EQ(image.levels.size(), 3u);
  const Vec2 s = saagen::measure::normal_slope(normals[0]);
  EXPECT_NEAR(value_at(image, 0, 0), s.x, 1e-6 * (1.0 + std::fabs(s.x)));  // float32 input rounding
  EXPECT_NEAR(value_at(image, 0, 2), s.x * s.x, 1e-6 * (1.0 + s.x * s.x));
}

TEST_F(TexturePrefilterCli, BadInputsFailWithOneLineAndNoOutput) {
  const fs::path output = scratch_ / "out.ktx2";
  // Not a power of two.
  const fs::path odd = write_png("odd.png", 6, 4, std::vector<Vec3>(24, Vec3{0, 0, 1}));
  expect_one_line_failure(saagen({"texture", "prefilter", odd.string(), "-o", output.string()}), output);
  // Not a normal map: a mid-grey image decodes to nearly zero vectors.
  std::vector<unsigned char> grey(4 * 4 * 3, 128);
  const fs::path grey_path = scratch_ / "grey.png";
  ASSERT_NE(stbi_write_png(grey_path.string().c_str(), 4, 4, 3, grey.data(), 12), 0);
  expect_one_line_failure(saagen({"texture", "prefilter", grey_path.string(), "-o", output.string()}), output);
  // Missing file, and a file that is neither PNG nor KTX2.
  expect_one_line_failure(saagen({"texture", "prefilter", (scratch_ / "missing.png").string(), "-o", output.string()}), output);
  std::ofstream(scratch_ / "text.png") << "hello";
  expect_one_line_failure(saagen({"texture", "prefilter", (scratch_ / "text.png").string(), "-o", output.string()}), output);
  // Bad options.
  const fs::path good = write_png("good.png", 4, 4, std::vector<Vec3>(16, Vec3{0, 0, 1}));
  expect_one_line_failure(saagen({"texture", "prefilter", good.string(), "-o", output.string(), "--method", "vmf"}), output);
  expect_one_line_failure(saagen({"texture", "prefilter", good.string(), "-o", output.string(), "--roughness", "1.5"}), output);
}

}  // namespace

// The advice's LOD bias is the one the trade's prefiltered rows are measured with.
TEST(Advice, TheTradeMeasuresTheAdvisedLodBias) {
  EXPECT_EQ(saagen::measure::TradeConfig{}.prefilter_lod_bias, static_cast<double>(saagen::advice::kPrefilterLodBias));
}
