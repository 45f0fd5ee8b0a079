// The glints on a Vulkan device (lavapipe in CI): the dictionary bound as a sampled 1D array image
// with its MIP chain (RGBA16F, LINEAR/LINEAR/LINEAR, MIRRORED_REPEAT), read with explicit
// gradients in compute shaders.
//   - GlintSamplerOnGpu: textureGrad / textureLod against the software sampler of the reference,
//     texel by texel; the energy of the filtered distributions measured on the device.
//   - GlintSnippetOnGpu: the emitted glint functions (GLSL and HLSL; GGAA and the textureLod
//     baseline; SDF, BRDF, LEAN) against the double-precision reference.
//
// Error bounds (docs/GLINTS.md, "Precision"): the device evaluates in fp32; the bound of each
// element is its sensitivity to fp32-sized perturbations of the inputs, estimated from the
// reference itself: B = 3 max_k |f(x (1 + e_k)) - f(x)| + 4e-6 |f(x)| + 1e-12 scale, over six
// random sign patterns e_k with |e_k| = 2^-21 per input component. This covers the rounding of
// u * width, of the cell coordinates, of the rotation and of the sampler's arithmetic (backward
// errors of a few ulps), and grows by itself where a discontinuity (a cell, a LOD or the edge of
// the dictionary) lies within rounding distance.
// Added to it, T = max |f' - f| over the reference f' whose transcendentals sit at either end of
// what the Vulkan specification allows ("Precision and Operation of SPIR-V Instructions"): the
// footprint LOD's log2(size) off by 3 ulp (|log2 size| 3 2^-23; 2^-21 absolute inside [0.5, 2]),
// the cell scale exp2(x), x = log_density / (2 ln 2) - level (up to ~14), and the EWA weights
// exp(-2 r^2), off by a factor 1 +- (3 + 2|x|) 2^-23 (g::Dictionary::log2_side, exp2_side): up
// to ~30 ulp, far more than the 2^-21 input perturbations cover. Plus T_trig, the same for each
// cell's rotation: cos and sin within 2^-11 absolute of the exact value in [-pi, pi] (the
// snippet's angle lies in that range; outside it the spec bounds nothing), every cell's product
// at the low or high end of that box (g::Dictionary::trig_side). SwiftShader uses about 0.4 of
// that allowance (1.9e-4), lavapipe 1e-7. Division (2.5 ulp), inversesqrt (2 ulp) and sqrt
// (inherited) stay within the 4e-6 |f| term and the perturbations.
//
// The sampler itself is held to what the Vulkan specification lets any implementation do
// (ref::glints::SamplerTolerance, from the device's mipmapPrecisionBits and
// subTexelPrecisionBits): lambda anywhere in [log2 rho - 2^-mip, log2 rho + 1/2 + 2^-mip]
// ("Scale Factor Operation, Level-of-Detail Operation and Image Level(s) Selection": f_x <=
// sqrt(2) |m_ux| in 1D), level weights snapped to 2^-mipmapPrecisionBits, the texel coordinate
// to 2^-subTexelPrecisionBits. The reference is evaluated at both ends of that range (every
// lookup at its low, then its high end: the glint functions are non-negative sums of products of
// non-negative lookups) and the device must lie in between, plus the fp32 bound above. On
// lavapipe a second, tighter check uses lavapipe's own LOD arithmetic (0.5 fastlog2(rho^2),
// measured, docs/GLINTS.md) with the fp32 bound alone.
#include "glint_support.hpp"

#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <functional>
#include <iostream>
#include <map>
#include <random>
#include <saagen/harness/harness.hpp>

namespace {

namespace g = saagen::ref::glints;
namespace hx = saagen::harness;
using saagen::ref::Sym2;
using saagen::ref::Vec2;
using saagen::ref::Vec3;

hx::VulkanContext& gpu() {
  static hx::VulkanContext context;
  return context;
}

bool on_lavapipe() { return gpu().info().name.find("llvmpipe") != std::string::npos; }

// The spec's sampler freedom on this device (its reported precision limits).
const g::SamplerTolerance& spec_tolerance() {
  static const g::SamplerTolerance tolerance = [] {
    const auto& limits = gpu().limits();
    const g::SamplerTolerance t =
        g::vulkan_sampler_tolerance(static_cast<int>(limits.mipmapPrecisionBits), static_cast<int>(limits.subTexelPrecisionBits));
    std::cout << fmt::format(
        "[ sampler  ] {}: mipmapPrecisionBits {}, subTexelPrecisionBits {}: lambda in [log2 rho - {}, log2 rho + {}], "
        "level weight +-{}, texel coordinate +-{}\n",
        gpu().info().name, limits.mipmapPrecisionBits, limits.subTexelPrecisionBits, t.lod_below, t.lod_above, t.level_weight,
        t.texel_weight);
    return t;
  }();
  return tolerance;
}

// Per element: the interval [low, high] a conforming device may return, widened by the fp32
// bound, as the (centre, half-width) pair compare_with_bounds takes.
void push_interval(std::vector<double>& expected, std::vector<double>& bounds, double low, double high, double fp32_bound) {
  if (low > high) std::swap(low, high);
  expected.push_back(0.5 * (low + high));
  bounds.push_back(0.5 * (high - low) + fp32_bound);
}

// The default dictionary as a combined image sampler at (set 0, binding).
hx::ImageBinding dictionary_binding(std::uint32_t binding) {
  const auto& texture = saagen::test::default_texture();
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

// ---------------------------------------------------------------------------------------------
// The sampler alone

struct Query {
  float u, layer, a, b;  // textureGrad: a = du/dx, b = du/dy; textureLod: a = lod, b = NaN
};

std::vector<float> run_queries(const std::vector<Query>& queries) {
  hx::ComputeRun run;
  run.shader = hx::shader_desc(hx::Language::glsl, hx::Stage::compute, R"(#version 450
layout(local_size_x = 64) in;
layout(set = 0, binding = 2) uniform sampler1DArray dictionary;
layout(std430, set = 0, binding = 0) readonly buffer Queries { vec4 queries[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Results { vec4 results[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  vec4 q = queries[i];
  results[i] = isnan(q.w) ? textureLod(dictionary, q.xy, q.z) : textureGrad(dictionary, q.xy, q.z, q.w);
}
)");
  run.images = {dictionary_binding(2)};
  run.buffers = {hx::input_buffer(0, queries), hx::output_buffer<float>(1, 4 * queries.size())};
  run.groups = {static_cast<std::uint32_t>(queries.size() / 64)};
  return hx::run_compute(gpu(), run).buffer_as<float>(1);
}

g::Texel reference_query(const Query& q, g::LodModel model) {
  const auto& texture = saagen::test::default_reference_texture();
  if (std::isnan(q.b)) return g::texture_lod(texture, q.u, q.layer, q.a);
  return g::texture_grad(texture, q.u, q.layer, q.a, q.b, model);
}

g::TexelRange reference_range(const Query& q) {
  const auto& texture = saagen::test::default_reference_texture();
  if (std::isnan(q.b)) return g::texture_lod_range(texture, q.u, q.layer, q.a, spec_tolerance());
  return g::texture_grad_range(texture, q.u, q.layer, q.a, q.b, spec_tolerance());
}

TEST(GlintSamplerOnGpu, TextureGradAndLodMatchTheSoftwareSampler) {
  // The spec check on every device; on lavapipe also the tight check with its LOD model.
  const bool lavapipe = on_lavapipe();
  const g::LodModel model = lavapipe ? g::LodModel::lavapipe : g::LodModel::exact;
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Query> queries;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  while (queries.size() < 32768) {
    const float u = static_cast<float>(-2.5 + 5.0 * unit(random));
    const float layer = static_cast<float>(std::floor(768.0 * unit(random)));
    if (queries.size() % 4 == 0) {
      queries.push_back({u, layer, static_cast<float>(-1.0 + 9.0 * unit(random)), nan});
    } else {
      const double gradient = std::exp2(-3.0 + 12.0 * unit(random)) / 64.0;
      const double ratio = -1.5 + 3.0 * unit(random);
      queries.push_back({u, layer, static_cast<float>(gradient), static_cast<float>(gradient * ratio)});
    }
  }
  const auto got = run_queries(queries);
  std::vector<double> expected, bounds, exact_model_error, spec_expected, spec_bounds;
  for (const Query& q : queries) {
    const g::TexelRange range = reference_range(q);
    const g::Texel value = reference_query(q, model);
    g::Texel spread{};
    for (double su : {-1.0, 1.0}) {
      for (double sg : {-1.0, 1.0}) {
        Query p = q;
        p.u = static_cast<float>(q.u * (1.0 + su * 0x1.0p-22));
        p.a = static_cast<float>(q.a * (1.0 + sg * 0x1.0p-22));
        if (!std::isnan(q.b)) p.b = static_cast<float>(q.b * (1.0 - sg * 0x1.0p-22));
        const g::Texel perturbed = reference_query(p, model);
        for (int c = 0; c < 4; ++c) spread[c] = std::max(spread[c], std::fabs(perturbed[c] - value[c]));
      }
    }
    const g::Texel exact = reference_query(q, g::LodModel::exact);
    for (int c = 0; c < 4; ++c) {
      const double fp32 = 2.0 * spread[c] + 2e-6 * std::fabs(value[c]) + 1e-9;
      expected.push_back(value[c]);
      bounds.push_back(fp32);
      exact_model_error.push_back(std::fabs(exact[c] - value[c]));
      push_interval(spec_expected, spec_bounds, range.low[c], range.high[c], fp32);
    }
  }
  const auto describe = [&](std::size_t i) {
    const Query& q = queries[i / 4];
    return fmt::format("u {} layer {} {} {} {}", q.u, q.layer, std::isnan(q.b) ? "lod" : "grad", q.a, q.b);
  };
  const auto spec =
      hx::compare_with_bounds(got, spec_expected, spec_bounds, "dictionary textureGrad/textureLod (Vulkan spec sampler rules)", describe);
  std::cout << "[ sampler  ] spec: " << spec.summary() << "\n";
  EXPECT_EQ(spec.failing, 0u) << spec.summary();
  if (!lavapipe) return;
  const auto report = hx::compare_with_bounds(got, expected, bounds, "dictionary textureGrad/textureLod (lavapipe LOD model)", describe);
  double worst_abs = 0.0;
  for (std::size_t i = 0; i < got.size(); ++i) worst_abs = std::max(worst_abs, std::fabs(got[i] - expected[i]));
  std::cout << "[ sampler  ] device " << gpu().info().name << ", LOD model " << (model == g::LodModel::lavapipe ? "lavapipe" : "exact")
            << ": " << report.summary() << "\n"
            << "[ sampler  ] max |device - reference| = " << worst_abs
            << " (texel values up to ~10); the exact log2 LOD would differ by up to "
            << *std::max_element(exact_model_error.begin(), exact_model_error.end()) << "\n";
  EXPECT_EQ(report.failing, 0u) << report.summary();
}

TEST(GlintSamplerOnGpu, FilteredDistributionsIntegrateToOneOnTheDevice) {
  // Trapezoidal rule over u in [-1, 1], step 1/128 (exact for the linear reconstruction).
  const int steps = 256;
  const double lambdas[] = {-2.0, 0.0, 0.5, 1.7, 3.0, 4.4, 6.0, 8.0};
  const int layers[] = {0, 47, 48, 300, 719, 767};
  std::vector<Query> queries;
  for (double lambda : lambdas) {
    for (int layer : layers) {
      for (int k = 0; k <= steps; ++k) {
        const double g = std::exp2(lambda) / 64.0;
        queries.push_back(
            {static_cast<float>(-1.0 + 2.0 * k / steps), static_cast<float>(layer), static_cast<float>(g), static_cast<float>(-0.5 * g)});
      }
    }
  }
  while (queries.size() % 64 != 0) queries.push_back({0.0f, 0.0f, 0.0f, 0.0f});
  const auto got = run_queries(queries);
  const double range = saagen::test::default_dictionary().params.range();
  double worst = 0.0;
  std::size_t index = 0;
  for (std::size_t l = 0; l < std::size(lambdas); ++l) {
    for (std::size_t layer = 0; layer < std::size(layers); ++layer) {
      double sums[4] = {};
      for (int k = 0; k <= steps; ++k, ++index) {
        for (int c = 0; c < 4; ++c) sums[c] += (k == 0 || k == steps ? 0.5 : 1.0) * got[4 * index + c];
      }
      for (double sum : sums) worst = std::max(worst, std::fabs(range * sum * 2.0 / steps - 1.0));
    }
  }
  std::cout << "[ energy   ] on the device: max |integral - 1| of 192 filtered distributions (8 LODs from -2 to 8) = " << worst << "\n";
  EXPECT_LT(worst, 5e-4);  // the half rounding of the texels (see GlintDictionary.EveryDistributionIntegratesToOne)
}

// ---------------------------------------------------------------------------------------------
// The emitted functions

struct Scenario {
  Vec2 slope, uv, duv_dx, duv_dy, dh_dx, dh_dy, mean;
  Vec3 i, o;
  g::Roughness roughness;
  double log_density = 15.0;
  Vec2 alpha;  // LEAN inputs
  Sym2 second;
};

Vec3 unit_vector(double z, double phi) {
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

std::vector<Scenario> scenarios(std::size_t count) {
  std::mt19937_64 random(20210504);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const g::Params params;
  const double x_max = g::dictionary_range(params);
  std::vector<Scenario> all;
  while (all.size() < count) {
    Scenario s;
    s.roughness = {0.03 + 0.47 * unit(random), 0.03 + 0.47 * unit(random), -0.95 + 1.9 * unit(random)};
    if (all.size() % 5 == 0) s.roughness.rho = 0.0;
    s.log_density = 10.0 + 10.0 * unit(random);
    // Footprint: l_P uniform in [-0.5, 16] (clamped at both ends), random shape.
    const double lod = -0.5 + 16.5 * unit(random);
    const double size = std::exp2(lod - s.log_density * 0.721347520444482);
    // One in eight beyond the 8:1 anisotropy clamp (2020 Alg. 1 line 4), the rest up to 5:1.
    const double angle = 6.283185307179586 * unit(random);
    const double shape = all.size() % 8 == 1 ? 0.01 + 0.11 * unit(random) : 0.2 + 0.8 * unit(random);
    s.duv_dx = {size * std::cos(angle), size * std::sin(angle)};
    s.duv_dy = {-shape * size * std::sin(angle + 0.3), shape * size * std::cos(angle + 0.3)};
    // Three in four near the uv origin; one in four anywhere in [-0.2, 1.2]^2, where the cell
    // coordinate uv * density^(1/2) reaches 2^14 and fp32 keeps ~1e-3 of a cell: the bound
    // (sensitivity to the inputs' rounding) widens there, by itself.
    if (all.size() % 4 == 0)
      s.uv = {-0.2 + 1.4 * unit(random), -0.2 + 1.4 * unit(random)};
    else
      s.uv = {0.002 * unit(random), 0.002 * unit(random)};
    // A half vector whose slope lands inside the dictionary (so that lobes are hit).
    const double radius = 0.9 * x_max * std::sqrt(unit(random)), phi = 6.283185307179586 * unit(random);
    const Vec2 q{radius * std::cos(phi), radius * std::sin(phi)};
    // slope = A q with A of Eq. 18
    const double c = std::sqrt(1.0 - s.roughness.rho * s.roughness.rho);
    s.slope = {(s.roughness.alpha_x * c * q.x + s.roughness.rho * s.roughness.alpha_x * q.y) / params.alpha_dict,
               s.roughness.alpha_y * q.y / params.alpha_dict};
    s.mean = all.size() % 3 == 0 ? Vec2{0.0, 0.0} : Vec2{0.1 * (unit(random) - 0.5), 0.1 * (unit(random) - 0.5)};
    // Directions with that half-vector slope (plus the mean slope, which the BRDF subtracts).
    const Vec2 full = s.slope + s.mean;
    const Vec3 h = saagen::ref::normalize(Vec3{-full.x, -full.y, 1.0});
    const Vec3 o = unit_vector(0.05 + 0.95 * unit(random), 6.283185307179586 * unit(random));
    const double oh = saagen::ref::dot(o, h);
    const Vec3 i = 2.0 * oh * h - o;
    if (oh < 0.05 || i.z < 0.02) continue;
    s.i = i;
    s.o = o;
    // GGAA kernels from a tenth of a texel to the whole range: lambda in [-3, 8].
    const double kernel = std::exp2(-3.0 + 11.0 * unit(random)) * x_max / (64.0 * params.kernel_scale) * 0.5 *
                          (s.roughness.alpha_x + s.roughness.alpha_y) / params.alpha_dict;
    const double dangle = 6.283185307179586 * unit(random);
    s.dh_dx = {kernel * std::cos(dangle), kernel * std::sin(dangle)};
    s.dh_dy = {-0.6 * kernel * std::sin(dangle), 0.4 * kernel * std::cos(dangle)};
    s.alpha = {0.02 + 0.4 * unit(random), 0.02 + 0.4 * unit(random)};
    const Vec2 mean{0.3 * (unit(random) - 0.5), 0.3 * (unit(random) - 0.5)};
    const double vx = 0.05 * unit(random), vy = 0.05 * unit(random), r = -0.9 + 1.8 * unit(random);
    s.second = {vx + mean.x * mean.x, r * std::sqrt(vx * vy) + mean.x * mean.y, vy + mean.y * mean.y};
    s.mean = all.size() % 7 == 0 ? mean : s.mean;
    all.push_back(s);
  }
  return all;
}

void push(std::vector<float>& out, double v) { out.push_back(static_cast<float>(v)); }
void push(std::vector<float>& out, Vec2 v) { push(out, v.x), push(out, v.y); }
void push(std::vector<float>& out, Vec3 v) { push(out, v.x), push(out, v.y), push(out, v.z); }

void pack(const saagen::Function& function, const Scenario& s, std::vector<float>& out) {
  for (const saagen::Parameter& parameter : function.parameters) {
    const std::string& name = parameter.name;
    if (name == "slope")
      push(out, s.slope);
    else if (name == "uv")
      push(out, s.uv);
    else if (name == "duv_dx")
      push(out, s.duv_dx);
    else if (name == "duv_dy")
      push(out, s.duv_dy);
    else if (name == "dh_dx")
      push(out, s.dh_dx);
    else if (name == "dh_dy")
      push(out, s.dh_dy);
    else if (name == "roughness")
      push(out, Vec3{s.roughness.alpha_x, s.roughness.alpha_y, s.roughness.rho});
    else if (name == "log_density")
      push(out, s.log_density);
    else if (name == "i")
      push(out, s.i);
    else if (name == "o")
      push(out, s.o);
    else if (name == "mean_slope" || name == "mean")
      push(out, s.mean);
    else if (name == "alpha")
      push(out, s.alpha);
    else if (name == "second")
      push(out, Vec3{s.second.xx, s.second.xy, s.second.yy});
    else
      throw std::runtime_error("no input for parameter " + name + " of " + function.name);
  }
}

// Reads packed fp32 inputs back as doubles.
class Inputs {
 public:
  explicit Inputs(std::vector<double> data) : data_(std::move(data)) {}
  double real() { return data_.at(next_++); }
  Vec2 vec2() {
    const double x = real();
    return {x, real()};
  }
  Vec3 vec3() {
    const double x = real(), y = real();
    return {x, y, real()};
  }
  g::Roughness roughness() {
    const Vec3 v = vec3();
    return {v.x, v.y, v.z};
  }

 private:
  std::vector<double> data_;
  std::size_t next_ = 0;
};

using ReferenceFunction = std::function<std::vector<double>(Inputs&)>;

std::map<std::string, ReferenceFunction> reference_functions(const g::Dictionary& d) {
  std::map<std::string, ReferenceFunction> table;
  table["glint_sdf"] = [d](Inputs& in) {
    const Vec2 slope = in.vec2(), uv = in.vec2(), dx = in.vec2(), dy = in.vec2();
    const g::Roughness r = in.roughness();
    return std::vector<double>{g::sdf(d, slope, uv, dx, dy, r, in.real())};
  };
  table["glint_sdf_filtered"] = [d](Inputs& in) {
    const Vec2 slope = in.vec2(), hx_ = in.vec2(), hy = in.vec2(), uv = in.vec2(), dx = in.vec2(), dy = in.vec2();
    const g::Roughness r = in.roughness();
    return std::vector<double>{g::sdf_filtered(d, slope, hx_, hy, uv, dx, dy, r, in.real())};
  };
  table["glint_brdf"] = [d](Inputs& in) {
    const Vec3 i = in.vec3(), o = in.vec3();
    const Vec2 mean = in.vec2(), uv = in.vec2(), dx = in.vec2(), dy = in.vec2();
    const g::Roughness r = in.roughness();
    return std::vector<double>{g::brdf(d, i, o, mean, uv, dx, dy, r, in.real())};
  };
  table["glint_brdf_filtered"] = [d](Inputs& in) {
    const Vec3 i = in.vec3(), o = in.vec3();
    const Vec2 mean = in.vec2(), hx_ = in.vec2(), hy = in.vec2(), uv = in.vec2(), dx = in.vec2(), dy = in.vec2();
    const g::Roughness r = in.roughness();
    return std::vector<double>{g::brdf_filtered(d, i, o, mean, hx_, hy, uv, dx, dy, r, in.real())};
  };
  table["lean_roughness"] = [](Inputs& in) {
    const Vec2 alpha = in.vec2(), mean = in.vec2();
    const Vec3 second = in.vec3();
    const g::Roughness r = g::lean_roughness(alpha, mean, Sym2{second.x, second.y, second.z});
    return std::vector<double>{r.alpha_x, r.alpha_y, r.rho};
  };
  return table;
}

struct SnippetCase {
  std::string target;
  std::string variant;
  std::string function;
  // Emission options other than the defaults (the reference gets the same).
  double relative_area = 1.0;
  double max_anisotropy = 8.0;
};

void PrintTo(const SnippetCase& c, std::ostream* os) { *os << c.target << " " << c.function; }

g::Dictionary configured(g::Dictionary dictionary, const SnippetCase& c) {
  dictionary.params.relative_area = c.relative_area;
  dictionary.params.max_anisotropy = c.max_anisotropy;
  return dictionary;
}

class GlintSnippetOnGpu : public ::testing::TestWithParam<SnippetCase> {};

TEST_P(GlintSnippetOnGpu, MatchesTheDoublePrecisionReference) {
  const SnippetCase& c = GetParam();
  constexpr std::size_t count = 16384;
  static const std::vector<Scenario> all = scenarios(count);
  const saagen::Catalogue& catalogue = saagen::glints::catalogue();
  const saagen::Function& function = *catalogue.find_function(c.function);

  saagen::EmitOptions options;
  options.target = c.target;
  options.variants = {c.variant};
  options.option_values = {{"glint_relative_area", c.relative_area}, {"glint_max_anisotropy", c.max_anisotropy}};
  const auto file = saagen::glints::emit(options).front();
  saagen::KernelRequest request;
  request.body = saagen::load_call_store_body(catalogue, c.function, request);
  const auto compiled = saagen::compile_to_spirv(saagen::kernel_compile_request(catalogue, file.file_name, file.content, request));
  ASSERT_TRUE(compiled.ok) << compiled.log;

  std::vector<float> inputs;
  for (const Scenario& s : all) pack(function, s, inputs);
  ASSERT_EQ(inputs.size(), count * request.input_stride);
  hx::ComputeRun run;
  run.shader.spirv = compiled.spirv;
  run.images = {dictionary_binding(2)};
  run.buffers = {hx::input_buffer(0, inputs), hx::output_buffer<float>(1, count * request.output_stride)};
  run.groups = {static_cast<std::uint32_t>(count / request.workgroup_size)};
  const auto got = hx::run_compute(gpu(), run).buffer_as<float>(1);

  // Nominal: the exact LOD rule. Low / high: every lookup at the end of what the spec allows.
  // On lavapipe, the tight check feeds the reference lavapipe's LOD arithmetic.
  const bool lavapipe = on_lavapipe();
  g::Dictionary dictionary = configured(saagen::test::default_reference_dictionary(g::LodModel::exact), c);
  const auto reference = reference_functions(dictionary).at(c.function);
  g::Dictionary low_dictionary = dictionary, high_dictionary = dictionary;
  low_dictionary.tolerance = high_dictionary.tolerance = &spec_tolerance();
  low_dictionary.side = -1;
  high_dictionary.side = 1;
  const auto low_reference = reference_functions(low_dictionary).at(c.function);
  const auto high_reference = reference_functions(high_dictionary).at(c.function);
  const auto lavapipe_reference =
      reference_functions(configured(saagen::test::default_reference_dictionary(g::LodModel::lavapipe), c)).at(c.function);
  // The reference with the footprint's log2 and the cell scale's exp2 at either end of the
  // spec's allowance (g::Dictionary::log2_side, exp2_side), for the transcendental term.
  std::vector<ReferenceFunction> transcendental_references;
  for (const int log2_side : {-1, 1}) {
    for (const int exp2_side : {-1, 1}) {
      g::Dictionary d = configured(saagen::test::default_reference_dictionary(lavapipe ? g::LodModel::lavapipe : g::LodModel::exact), c);
      d.log2_side = log2_side;
      d.exp2_side = exp2_side;
      transcendental_references.push_back(reference_functions(d).at(c.function));
    }
  }
  // And at either end of the spec's cos / sin allowance for every cell's rotation
  // (g::Dictionary::trig_side).
  std::vector<ReferenceFunction> trig_references;
  for (const int trig_side : {-1, 1}) {
    g::Dictionary d = configured(saagen::test::default_reference_dictionary(lavapipe ? g::LodModel::lavapipe : g::LodModel::exact), c);
    d.trig_side = trig_side;
    trig_references.push_back(reference_functions(d).at(c.function));
  }
  std::vector<double> spec_expected, spec_bounds;
  std::size_t outside = 0;  // nominal outside [low, high]: the monotonicity the bound relies on
  std::mt19937_64 random(99);
  std::vector<double> expected, bounds;
  double worst_relative = 0.0;
  for (std::size_t e = 0; e < count; ++e) {
    std::vector<double> x(inputs.begin() + e * request.input_stride, inputs.begin() + (e + 1) * request.input_stride);
    Inputs in(x), low_in(x), high_in(x);
    const auto nominal = reference(in);
    const auto low = low_reference(low_in), high = high_reference(high_in);
    Inputs lavapipe_in(x);
    const auto value = lavapipe ? lavapipe_reference(lavapipe_in) : nominal;
    std::vector<double> spread(value.size(), 0.0);
    for (int k = 0; k < 6; ++k) {
      std::vector<double> p = x;
      for (double& v : p) v *= 1.0 + ((random() & 1) ? 0x1.0p-21 : -0x1.0p-21);
      Inputs perturbed_in(p);
      const auto perturbed = (lavapipe ? lavapipe_reference : reference)(perturbed_in);
      for (std::size_t m = 0; m < value.size(); ++m) spread[m] = std::max(spread[m], std::fabs(perturbed[m] - value[m]));
    }
    std::vector<double> transcendental(value.size(), 0.0), trig(value.size(), 0.0);
    for (const ReferenceFunction& f : transcendental_references) {
      Inputs t_in(x);
      const auto shifted = f(t_in);
      for (std::size_t m = 0; m < value.size(); ++m) transcendental[m] = std::max(transcendental[m], std::fabs(shifted[m] - value[m]));
    }
    for (const ReferenceFunction& f : trig_references) {
      Inputs t_in(x);
      const auto shifted = f(t_in);
      for (std::size_t m = 0; m < value.size(); ++m) trig[m] = std::max(trig[m], std::fabs(shifted[m] - value[m]));
    }
    for (std::size_t m = 0; m < value.size(); ++m) {
      // lavapipe's cos and sin are within 1e-7 of the exact value: its tight check leaves
      // the spec's 2^-11 allowance (trig) out.
      const double fp32 = 3.0 * spread[m] + transcendental[m] + 4e-6 * std::fabs(value[m]) + 1e-12;
      const double lo = std::min(low[m], high[m]), hi = std::max(low[m], high[m]);
      outside += nominal[m] < lo - fp32 || nominal[m] > hi + fp32;
      push_interval(spec_expected, spec_bounds, lo, hi, fp32 + trig[m]);
      expected.push_back(value[m]);
      bounds.push_back(fp32);
      const double got_value = got[e * request.output_stride + m];
      if (std::fabs(value[m]) > 1e-3) worst_relative = std::max(worst_relative, std::fabs(got_value - value[m]) / std::fabs(value[m]));
    }
  }
  std::size_t nonzero = 0;
  for (double v : expected) nonzero += v != 0.0;
  // How tight the comparison is: quantiles of the relative error and of the relative bound over
  // the outputs above 1e-6 of the largest one.
  std::vector<double> relative_errors, relative_bounds;
  const double largest =
      *std::max_element(expected.begin(), expected.end(), [](double a, double b) { return std::fabs(a) < std::fabs(b); });
  for (std::size_t k = 0; k < expected.size(); ++k) {
    if (std::fabs(expected[k]) <= 1e-6 * std::fabs(largest)) continue;
    relative_errors.push_back(std::fabs(got[k] - expected[k]) / std::fabs(expected[k]));
    relative_bounds.push_back(bounds[k] / std::fabs(expected[k]));
  }
  const auto quantile = [](std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * (v.size() - 1))];
  };
  std::cout << fmt::format(
      "[ quantile ] relative error 50/99/99.9 %: {:.2e} {:.2e} {:.2e}; relative bound 50/99/99.9 %: {:.2e} {:.2e} {:.2e}\n",
      quantile(relative_errors, 0.5), quantile(relative_errors, 0.99), quantile(relative_errors, 0.999), quantile(relative_bounds, 0.5),
      quantile(relative_bounds, 0.99), quantile(relative_bounds, 0.999));
  const auto spec =
      hx::compare_with_bounds(got, spec_expected, spec_bounds, fmt::format("{} {} (Vulkan spec sampler rules)", c.target, c.function));
  std::cout << "[ spec     ] " << spec.summary() << "\n";
  EXPECT_EQ(spec.failing, 0u) << spec.summary();
  EXPECT_EQ(outside, 0u) << "the exact-LOD reference lies outside [low, high]: the lookups' bound is not monotone";
  EXPECT_GT(nonzero, expected.size() / 2);  // the inputs do hit lobes
  if (!lavapipe) return;
  const auto report = hx::compare_with_bounds(got, expected, bounds, fmt::format("{} {} (lavapipe LOD model)", c.target, c.function));
  std::cout << "[ worst    ] " << report.summary() << "\n[ worst    ] max relative error (|expected| > 1e-3): " << worst_relative << "; "
            << nonzero << " of " << expected.size() << " outputs non-zero\n";
  EXPECT_EQ(report.failing, 0u) << report.summary();
}

// ---------------------------------------------------------------------------------------------
// The fragment wrappers: ddx/ddy taken in 2x2 quads (the harness's quad_compute kernel: subgroup
// quad operations stand in for the derivative instructions, fine differences as lavapipe's plain
// ddx), against the reference fed the same quad differences.

// Per-pixel inputs, a smooth function of the pixel centre (a curved, moving glinty surface),
// polynomials so that the device computes them to fp32 rounding (no cos / sin allowance);
// with ln density 19 the footprint's LOD is about 1.6 (two levels of cells are mixed).
struct PixelInputs {
  Vec3 i, o;
  Vec2 uv;
};

PixelInputs pixel_inputs(Vec2 p) {
  PixelInputs in;
  in.uv = {0.0123 + 2.3e-4 * p.x + 1e-6 * p.x * p.y, 0.0311 + 1.9e-4 * p.y};
  in.i = saagen::ref::normalize(Vec3{0.3 + 0.2 * (0.03 * p.x - 4e-4 * p.x * p.x), -0.2 + 0.15 * (1.0 - 5e-4 * p.y * p.y), 1.0});
  in.o = saagen::ref::normalize(Vec3{-0.25 + 0.1 * (1.0 - 3e-4 * p.x * p.y), 0.2 + 0.12 * (0.04 * p.y - 5e-4 * p.y * p.y), 1.0});
  return in;
}

constexpr const char* wrapper_body = R"(    real2 p = saagen_frag_coord;
    real2 uv = real2(0.0123 + 2.3e-4 * p.x + 1e-6 * p.x * p.y, 0.0311 + 1.9e-4 * p.y);
    real3 i = normalize(real3(0.3 + 0.2 * (0.03 * p.x - 4e-4 * p.x * p.x), -0.2 + 0.15 * (1.0 - 5e-4 * p.y * p.y), 1.0));
    real3 o = normalize(real3(-0.25 + 0.1 * (1.0 - 3e-4 * p.x * p.y), 0.2 + 0.12 * (0.04 * p.y - 5e-4 * p.y * p.y), 1.0));
    real3 roughness = real3(0.2, 0.15, 0.3);
    real2 mean_slope = real2(0.02, -0.01);
    SAAGEN_STORE(0, glint_brdf_filtered_fragment(i, o, mean_slope, uv, roughness, 19.0));
    SAAGEN_STORE(1, glint_brdf_filtered_slope_fragment(i, o, mean_slope, uv, roughness, 19.0));
)";

constexpr const char* baseline_wrapper_body = R"(    real2 p = saagen_frag_coord;
    real2 uv = real2(0.0123 + 2.3e-4 * p.x + 1e-6 * p.x * p.y, 0.0311 + 1.9e-4 * p.y);
    real3 i = normalize(real3(0.3 + 0.2 * (0.03 * p.x - 4e-4 * p.x * p.x), -0.2 + 0.15 * (1.0 - 5e-4 * p.y * p.y), 1.0));
    real3 o = normalize(real3(-0.25 + 0.1 * (1.0 - 3e-4 * p.x * p.y), 0.2 + 0.12 * (0.04 * p.y - 5e-4 * p.y * p.y), 1.0));
    SAAGEN_STORE(0, glint_brdf_fragment(i, o, real2(0.02, -0.01), uv, real3(0.2, 0.15, 0.3), 19.0));
)";

TEST(GlintFragmentOnGpu, WrappersMatchTheReferenceFedTheSameQuads) {
  constexpr std::uint32_t width = 64, height = 64, pixels = width * height;
  const bool lavapipe = on_lavapipe();
  const g::Dictionary dictionary = saagen::test::default_reference_dictionary(lavapipe ? g::LodModel::lavapipe : g::LodModel::exact);
  g::Dictionary low_dictionary = saagen::test::default_reference_dictionary(g::LodModel::exact), high_dictionary = low_dictionary;
  low_dictionary.tolerance = high_dictionary.tolerance = &spec_tolerance();
  low_dictionary.side = -1;
  high_dictionary.side = 1;
  std::vector<g::Dictionary> transcendental_dictionaries;
  for (const int log2_side : {-1, 1}) {
    for (const int exp2_side : {-1, 1}) {
      g::Dictionary d = dictionary;
      d.log2_side = log2_side;
      d.exp2_side = exp2_side;
      transcendental_dictionaries.push_back(d);
    }
  }
  for (const int trig_side : {-1, 1}) {
    g::Dictionary d = dictionary;
    d.trig_side = trig_side;
    transcendental_dictionaries.push_back(d);
  }
  const g::Roughness roughness{0.2, 0.15, 0.3};
  const Vec2 mean{0.02, -0.01};
  for (const std::string target : {"glsl", "hlsl"}) {
    for (const bool filtered : {true, false}) {
      saagen::EmitOptions options;
      options.target = target;
      options.variants = {filtered ? "glints-ggaa" : "glints"};
      const auto file = saagen::glints::emit(options).front();
      saagen::KernelRequest request;
      request.kind = saagen::KernelKind::quad_compute;
      request.body = filtered ? wrapper_body : baseline_wrapper_body;
      request.output_stride = filtered ? 2 : 1;
      request.width = width;
      request.plain_derivative = saagen::PlainDerivative::fine;
      const auto compiled =
          saagen::compile_to_spirv(saagen::kernel_compile_request(saagen::glints::catalogue(), file.file_name, file.content, request));
      ASSERT_TRUE(compiled.ok) << compiled.log;
      hx::ComputeRun run;
      run.shader.spirv = compiled.spirv;
      run.images = {dictionary_binding(2)};
      run.buffers = {hx::input_buffer(0, std::vector<float>{0.0f}), hx::output_buffer<float>(1, pixels * request.output_stride)};
      run.groups = {pixels / request.workgroup_size};
      const auto got = hx::run_compute(gpu(), run).buffer_as<float>(1);

      // The reference: per-pixel values in double, fine quad differences, the core BRDF.
      std::mt19937_64 random(5);
      std::vector<double> expected, bounds, spec_expected, spec_bounds;
      for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < width; ++x) {
          const auto at = [&](std::uint32_t px, std::uint32_t py) { return pixel_inputs({px + 0.5, py + 0.5}); };
          const PixelInputs self = at(x, y);
          const std::uint32_t x0 = x & ~1u, y0 = y & ~1u;
          const PixelInputs left = at(x0, y), right = at(x0 + 1, y), top = at(x, y0), bottom = at(x, y0 + 1);
          const auto projected = [](const PixelInputs& p) { return saagen::ref::normalize(p.i + p.o).xy(); };
          const auto slope = [](const PixelInputs& p) { return g::half_slope(p.i, p.o); };
          const Vec2 duv_dx = right.uv - left.uv, duv_dy = bottom.uv - top.uv;
          const auto evaluate = [&](int which, double jitter_scale, std::mt19937_64& rng, const g::Dictionary& dictionary) {
            // The device's fp32 rounding of the per-pixel values (relative 2^-21 on
            // each input, as in GlintSnippetOnGpu), of their differences (absolute,
            // 2^-22 of the operands) and of the internal log_density * 1 / (2 ln 2).
            const auto sign = [&] { return (rng() & 1) ? 1.0 : -1.0; };
            const auto relative = [&](double v) { return v * (1.0 + sign() * jitter_scale * 0x1.0p-21); };
            const auto rel2 = [&](Vec2 v) { return Vec2{relative(v.x), relative(v.y)}; };
            const auto rel3 = [&](Vec3 v) { return Vec3{relative(v.x), relative(v.y), relative(v.z)}; };
            const auto jitter = [&](Vec2 v, double magnitude) {
              return Vec2{v.x + sign() * jitter_scale * magnitude, v.y + sign() * jitter_scale * magnitude};
            };
            const Vec3 i = rel3(self.i), o = rel3(self.o);
            const Vec2 uv = rel2(self.uv);
            const double log_density = relative(19.0);
            const Vec2 dx = jitter(duv_dx, std::max(std::fabs(self.uv.x), std::fabs(self.uv.y)) * 0x1.0p-22);
            const Vec2 dy = jitter(duv_dy, std::max(std::fabs(self.uv.x), std::fabs(self.uv.y)) * 0x1.0p-22);
            if (which == 2) return g::brdf(dictionary, i, o, mean, uv, dx, dy, roughness, log_density);
            const Vec2 hdx = which == 0 ? projected(right) - projected(left) : slope(right) - slope(left);
            const Vec2 hdy = which == 0 ? projected(bottom) - projected(top) : slope(bottom) - slope(top);
            return g::brdf_filtered(dictionary, i, o, mean, jitter(hdx, 0x1.0p-22), jitter(hdy, 0x1.0p-22), uv, dx, dy, roughness,
                                    log_density);
          };
          for (int which : filtered ? std::vector<int>{0, 1} : std::vector<int>{2}) {
            const double value = evaluate(which, 0.0, random, dictionary);
            double spread = 0.0;
            for (int k = 0; k < 6; ++k) spread = std::max(spread, std::fabs(evaluate(which, 1.0, random, dictionary) - value));
            // The spec's log2 / exp2 allowances (the first four dictionaries), then its
            // cos / sin allowance (the last two; see the file's comment).
            double transcendental = 0.0, trig = 0.0;
            for (std::size_t k = 0; k < transcendental_dictionaries.size(); ++k) {
              double& term = k < 4 ? transcendental : trig;
              term = std::max(term, std::fabs(evaluate(which, 0.0, random, transcendental_dictionaries[k]) - value));
            }
            const double fp32 = 3.0 * spread + transcendental + 4e-6 * std::fabs(value) + 1e-12;
            expected.push_back(value);
            bounds.push_back(fp32);  // lavapipe's tight check: its cos / sin are within 1e-7
            push_interval(spec_expected, spec_bounds, evaluate(which, 0.0, random, low_dictionary),
                          evaluate(which, 0.0, random, high_dictionary), fp32 + trig);
          }
        }
      }
      std::size_t nonzero = 0;
      for (double v : expected) nonzero += v > 0.0;
      const std::string what =
          fmt::format("{} {}", target, filtered ? "glint_brdf_filtered_fragment + _slope_fragment" : "glint_brdf_fragment");
      const auto spec = hx::compare_with_bounds(got, spec_expected, spec_bounds, what + " (Vulkan spec sampler rules)");
      std::cout << "[ fragment ] " << spec.summary() << "; " << nonzero << " of " << expected.size() << " non-zero\n";
      EXPECT_EQ(spec.failing, 0u) << spec.summary();
      EXPECT_GT(nonzero, expected.size() / 2);
      if (!lavapipe) continue;
      const auto report = hx::compare_with_bounds(got, expected, bounds, what + " (lavapipe LOD model)");
      std::cout << "[ fragment ] " << report.summary() << "\n";
      EXPECT_EQ(report.failing, 0u) << report.summary();
    }
  }
}

std::vector<SnippetCase> snippet_cases() {
  std::vector<SnippetCase> cases;
  for (const std::string target : {"glsl", "hlsl"}) {
    cases.push_back({target, "glints", "glint_sdf"});
    cases.push_back({target, "glints", "glint_brdf"});
    cases.push_back({target, "glints-ggaa", "glint_sdf_filtered"});
    cases.push_back({target, "glints-ggaa", "glint_brdf_filtered"});
    cases.push_back({target, "glints-ggaa", "lean_roughness"});
  }
  // The relative area (half the cells empty) and a lower anisotropy clamp.
  cases.push_back({"glsl", "glints-ggaa", "glint_sdf_filtered", 0.5, 4.0});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryFunction, GlintSnippetOnGpu, ::testing::ValuesIn(snippet_cases()), [](const auto& info) {
  const bool defaults = info.param.relative_area == 1.0 && info.param.max_anisotropy == 8.0;
  return info.param.target + "_" + info.param.function + (defaults ? "" : "_area_half_anisotropy_4");
});

}  // namespace
