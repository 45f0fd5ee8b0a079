// The deferred roughness-limiter compute pass (saagen/products/deferred_pass.hpp), emitted as
// GLSL, HLSL, SPIR-V and a C/C++ header, run on the Vulkan device (lavapipe) over G-buffers
// rendered by the issue-4 renderer (saagen::measure: sphere, torus, tubes, bump_plane; 96 x 96,
// and the sphere at an odd 75 x 61 for the borders) and compared pixel by pixel with the
// double-precision reference: ref::deferred_*_fragment_quad on the quad (x & ~1, y & ~1) of the
// same fp32 G-buffer texels, partners past the right/bottom edge clamped to the edge texel (the
// pass's documented border rule), plain derivatives fine (and coarse where the pass is emitted
// with --derivatives coarse).
//
// The reference decodes the texels as the pass does (unorm decode, renormalisation, the
// tangent's Gram-Schmidt and the bitangent sign, the roughness domain) in double precision.
// Bound per pixel, as test_gpu_fragment's: 16 ulps * sum_k |df/dx_k| |x_k| + 2e-5 |f| + 1e-30,
// x_k every decoded normal / tangent / bitangent component of the four quad pixels (partials by
// one-sided differences of the reference): the pass's fp32 decode rounds each by a few ulps
// before the quad differences amplify it. r16f outputs add one fp16 ulp (2^-10 |f|): Vulkan lets
// the conversion to a 16-bit float format round to nearest or towards zero (lavapipe truncates).
#include "host_compiler.hpp"
#include "support/deferred_pass_runner.hpp"
#include "support/gpu_support.hpp"
#include "support/reference_dispatch.hpp"

#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/measure/renderer.hpp"
#include "saagen/measure/scene.hpp"
#include "saagen/products/output_validation.hpp"
#include "saagen/products/spirv_library.hpp"
#include "saagen/reference/reference.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
namespace ref = saagen::ref;
namespace abi = saagen::deferred_pass_abi;
using ref::Quad;
using ref::Vec2;
using ref::Vec3;
using saagen::Catalogue;

// ---------------------------------------------------------------------------------------------
// G-buffers from the issue-4 renderer

struct TestGBuffer {
  std::string name;
  saagen::test::GBufferImages images;
};

// Material roughness alpha varies across the image so that alpha2 is a per-pixel input.
double material_alpha(std::uint32_t x, std::uint32_t y) { return 0.03 + 0.25 * (0.5 + 0.5 * std::sin(0.21 * x + 0.13 * y)); }

float encode_roughness(double alpha, std::uint32_t domain) {
  if (domain == abi::domain_alpha) return static_cast<float>(alpha);
  if (domain == abi::domain_perceptual) return static_cast<float>(std::sqrt(alpha));
  if (domain == abi::domain_smoothness) return static_cast<float>(1.0 - std::sqrt(alpha));
  return static_cast<float>(alpha * alpha);
}

struct Encoding {
  std::uint32_t domain = abi::domain_alpha2;
  std::uint32_t channel = 0;
  bool normal_unorm = false;
  bool tangent_unorm = false;
  std::uint32_t flags() const {
    return domain | (normal_unorm ? abi::flag_normal_unorm : 0u) | (tangent_unorm ? abi::flag_tangent_unorm : 0u);
  }
};

TestGBuffer render(saagen::measure::SceneId id, int width, int height, const Encoding& encoding) {
  const auto scene = saagen::measure::make_scene(id);
  const auto gbuffer = saagen::measure::render_gbuffer(scene, width, height);
  TestGBuffer out{fmt::format("{} {}x{}", saagen::measure::scene_name(id), width, height), {}};
  auto& images = out.images;
  images.width = static_cast<std::uint32_t>(width);
  images.height = static_cast<std::uint32_t>(height);
  const auto encode_vector = [](Vec3 v, bool unorm) { return unorm ? Vec3{v.x * 0.5 + 0.5, v.y * 0.5 + 0.5, v.z * 0.5 + 0.5} : v; };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const auto& f = gbuffer.at(x, y);
      // No surface: a zero normal and tangent (encoded), as a cleared G-buffer holds.
      const Vec3 n = encode_vector(f.hit ? f.normal : Vec3{}, encoding.normal_unorm);
      const Vec3 t = encode_vector(f.hit ? f.tangent : Vec3{}, encoding.tangent_unorm);
      // The renderer's frame is right-handed, b = n x t: sign +1.
      images.normal.insert(images.normal.end(), {float(n.x), float(n.y), float(n.z), 1.0f});
      images.tangent.insert(images.tangent.end(), {float(t.x), float(t.y), float(t.z), 1.0f});
      std::array<float, 4> roughness = {0.9f, 0.8f, 0.7f, 0.6f};  // the other channels must not be read
      roughness[encoding.channel] = encode_roughness(material_alpha(x, y), encoding.domain);
      images.roughness.insert(images.roughness.end(), roughness.begin(), roughness.end());
    }
  }
  return out;
}

const std::vector<TestGBuffer>& standard_gbuffers() {
  static const std::vector<TestGBuffer> all = [] {
    std::vector<TestGBuffer> list;
    for (const auto id : saagen::measure::all_scenes()) list.push_back(render(id, 96, 96, {}));
    list.push_back(render(saagen::measure::SceneId::sphere, 75, 61, {}));  // odd: partial tiles, clamped partners
    return list;
  }();
  return all;
}

// ---------------------------------------------------------------------------------------------
// The reference

struct Decoded {
  Vec3 n, t, b;
};

Vec3 texel3(const std::vector<float>& image, std::uint32_t width, std::uint32_t x, std::uint32_t y) {
  const float* p = image.data() + (std::size_t{y} * width + x) * 4;
  return {p[0], p[1], p[2]};
}

Vec3 unit_or_zero(Vec3 v) { return v * (1.0 / std::sqrt(std::max(ref::dot(v, v), 1e-30))); }

Decoded decode(const saagen::test::GBufferImages& g, std::uint32_t x, std::uint32_t y, const Encoding& e) {
  const auto unorm = [](Vec3 v) { return Vec3{2.0 * v.x - 1.0, 2.0 * v.y - 1.0, 2.0 * v.z - 1.0}; };
  Vec3 n = texel3(g.normal, g.width, x, y);
  if (e.normal_unorm) n = unorm(n);
  n = unit_or_zero(n);
  Vec3 t = texel3(g.tangent, g.width, x, y);
  if (e.tangent_unorm) t = unorm(t);
  t = unit_or_zero(t - ref::dot(n, t) * n);
  const double sign = g.tangent[(std::size_t{y} * g.width + x) * 4 + 3] < 0.0f ? -1.0 : 1.0;
  return {n, t, sign * ref::cross(n, t)};
}

double decode_alpha2(const saagen::test::GBufferImages& g, std::uint32_t x, std::uint32_t y, const Encoding& e) {
  const double r = g.roughness[(std::size_t{y} * g.width + x) * 4 + e.channel];
  if (e.domain == abi::domain_alpha) return r * r;
  if (e.domain == abi::domain_perceptual) return (r * r) * (r * r);
  if (e.domain == abi::domain_smoothness) return ((1.0 - r) * (1.0 - r)) * ((1.0 - r) * (1.0 - r));
  return r;
}

double encode_output(double alpha2, std::uint32_t domain) {
  if (domain == abi::domain_alpha) return std::sqrt(alpha2);
  if (domain == abi::domain_perceptual) return std::sqrt(std::sqrt(alpha2));
  if (domain == abi::domain_smoothness) return 1.0 - std::sqrt(std::sqrt(alpha2));
  return alpha2;
}

// The pass's output at `pixel` of a quad of decoded fields.
double reference_pass(const std::string& wrapper, double alpha2, const std::array<Decoded, 4>& q, const Quad<Vec2>& frag, int pixel,
                      ref::Derivative mode, std::uint32_t domain) {
  const ref::Params p;
  const Quad<Vec3> n{q[0].n, q[1].n, q[2].n, q[3].n};
  const Quad<Vec3> t{q[0].t, q[1].t, q[2].t, q[3].t};
  const Quad<Vec3> b{q[0].b, q[1].b, q[2].b, q[3].b};
  // The shared dispatch of the wrappers' references (support/reference_dispatch.hpp); the
  // deferred wrappers read alpha2.x, and the quad average takes fine derivatives (the default).
  std::map<std::string, Quad<Vec3>> vectors = {{"normal_ws", n}, {"tangent_ws", t}, {"bitangent_ws", b}};
  const double filtered =
      saagen::test::wrapper_reference_on_quad(wrapper, p, {alpha2, alpha2}, vectors, pixel, mode, ref::Derivative::fine, frag).at(0);
  return encode_output(filtered, domain);
}

double& component(Vec3& v, int k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }

struct Expected {
  std::vector<double> values;
  std::vector<double> bounds;
};

Expected reference_image(const saagen::DeferredPassKind& kind, const saagen::test::GBufferImages& g, const Encoding& e,
                         ref::Derivative mode, bool half_output) {
  Expected out;
  out.values.resize(std::size_t{g.width} * g.height);
  out.bounds.resize(out.values.size());
  for (std::uint32_t qy = 0; qy < g.height; qy += 2) {
    for (std::uint32_t qx = 0; qx < g.width; qx += 2) {
      std::array<Decoded, 4> quad;
      Quad<Vec2> frag;
      for (int i = 0; i < 4; ++i) {
        // Past the edge: the edge texel (the pass clamps its reads), the lane's own frag coord.
        const std::uint32_t x = qx + (i & 1), y = qy + (i >> 1);
        quad[i] = decode(g, std::min(x, g.width - 1), std::min(y, g.height - 1), e);
      }
      frag = {Vec2{qx + 0.5, qy + 0.5}, Vec2{qx + 1.5, qy + 0.5}, Vec2{qx + 0.5, qy + 1.5}, Vec2{qx + 1.5, qy + 1.5}};
      for (int pixel = 0; pixel < 4; ++pixel) {
        const std::uint32_t x = qx + (pixel & 1), y = qy + (pixel >> 1);
        if (x >= g.width || y >= g.height) continue;
        const double alpha2 = decode_alpha2(g, x, y, e);
        const double value = reference_pass(kind.wrapper, alpha2, quad, frag, pixel, mode, e.domain);
        double condition = 0.0;
        for (int source = 0; source < 4; ++source) {
          for (Vec3 Decoded::*field : {&Decoded::n, &Decoded::t, &Decoded::b}) {
            if (!kind.tangents && field != &Decoded::n) continue;
            for (int k = 0; k < 3; ++k) {
              auto moved = quad;
              double& xk = component(moved[source].*field, k);
              const double original = xk, step = 1e-7 * std::max(std::fabs(original), 1e-6);
              xk = original + step;
              condition +=
                  std::fabs(reference_pass(kind.wrapper, alpha2, moved, frag, pixel, mode, e.domain) - value) / step * std::fabs(original);
            }
          }
        }
        const std::size_t index = std::size_t{y} * g.width + x;
        out.values[index] = value;
        out.bounds[index] =
            16.0 * std::ldexp(condition, -24) + (2e-5 + (half_output ? std::ldexp(1.0, -10) : 0.0)) * std::fabs(value) + 1e-30;
      }
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Emission and running

saagen::DeferredPass emit_pass(const std::string& id, saagen::PlainDerivative derivatives = saagen::PlainDerivative::fine,
                               const std::string& format = "r32f") {
  saagen::DeferredPassOptions options;
  options.passes = {id};
  options.derivatives = derivatives;
  options.output_format = format;
  return saagen::emit_deferred_passes(Catalogue::builtin(), options).front();
}

std::vector<std::uint32_t> spirv_of(const saagen::DeferredPass& pass, const std::string& language) {
  if (language == "glsl") return pass.spirv;  // the emitted .spv, compiled from the .comp
  saagen::CompileRequest request;
  request.language = saagen::SourceLanguage::named("hlsl");
  request.stage = saagen::ShaderStage::compute;
  request.sources = {{pass.stem + ".hlsl", pass.source("hlsl")}};
  const auto result = saagen::compile_to_spirv(request);
  if (!result.ok) throw std::runtime_error(pass.stem + ".hlsl does not compile:\n" + result.log);
  return result.spirv;
}

saagen::harness::CompareReport run_and_compare(const saagen::DeferredPass& pass, const std::vector<std::uint32_t>& spirv,
                                               const TestGBuffer& gbuffer, const Encoding& encoding, ref::Derivative mode,
                                               const std::string& what, VkFormat format = VK_FORMAT_R32_SFLOAT) {
  saagen::test::DeferredPassRunner runner(saagen::test::gpu(), spirv, pass.kind.tangents, format, gbuffer.images.width,
                                          gbuffer.images.height);
  runner.upload(gbuffer.images);
  const saagen::DeferredPassConstants constants{gbuffer.images.width, gbuffer.images.height, encoding.channel, encoding.flags()};
  const auto got = runner.run(constants).output;
  const Expected expected = reference_image(pass.kind, gbuffer.images, encoding, mode, format == VK_FORMAT_R16_SFLOAT);
  const std::uint32_t width = gbuffer.images.width;
  return saagen::harness::compare_with_bounds(got, expected.values, expected.bounds, what, [width](std::size_t index) {
    return fmt::format("pixel ({}, {})", index % width, index / width);
  });
}

void require_quads() {
  ASSERT_TRUE(saagen::test::gpu().info().subgroup.supports(VK_SUBGROUP_FEATURE_QUAD_BIT, VK_SHADER_STAGE_COMPUTE_BIT))
      << "the device has no subgroup quad operations in compute: " << saagen::test::gpu().info().subgroup.describe();
}

// ---------------------------------------------------------------------------------------------
// Emission tests (no device)

TEST(DeferredPass, EveryDeferredWrapperHasAPassWithFourFiles) {
  const auto kinds = saagen::deferred_pass_kinds(Catalogue::builtin());
  std::vector<std::string> ids;
  for (const auto& kind : kinds) ids.push_back(kind.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"deferred-previous", "deferred-max", "deferred-max-tangent-free", "deferred-sum", "deferred-avg",
                                           "deferred-projected-space"}));
  const auto passes = saagen::emit_deferred_passes(Catalogue::builtin(), {});
  ASSERT_EQ(passes.size(), kinds.size());
  for (const auto& pass : passes) {
    const auto files = pass.files();
    ASSERT_EQ(files.size(), 4u);
    EXPECT_EQ(files[0].first, pass.stem + ".comp");
    EXPECT_EQ(files[3].first, pass.stem + ".h");
    for (const auto& [name, content] : files) {
      const auto marker = saagen::find_marker(content);
      ASSERT_TRUE(marker.has_value()) << name;
      EXPECT_TRUE(saagen::is_spirv_or_pass_marker(*marker)) << name;
      EXPECT_EQ(marker->functions, std::vector<std::string>{pass.kind.wrapper});
      const auto validation = saagen::validate_spirv_or_pass_file(Catalogue::builtin(), name, content);
      if (name.ends_with(".h")) continue;
      EXPECT_TRUE(validation.ok()) << validation.summary();
    }
    // The tangent G-buffer is bound exactly by the passes whose wrapper takes a frame.
    EXPECT_EQ(pass.source("glsl").find("binding = 3") != std::string::npos, pass.kind.tangents) << pass.stem;
    EXPECT_EQ(pass.source("hlsl").find("vk::binding(3, 0)") != std::string::npos, pass.kind.tangents) << pass.stem;
    EXPECT_EQ(pass.kind.tangents, pass.kind.id == "deferred-previous" || pass.kind.id == "deferred-max");
    // The header describes the interface and embeds the words.
    EXPECT_NE(pass.header.find("typedef struct saa_pass_constants"), std::string::npos);
    EXPECT_NE(pass.header.find("#define SAA_PASS_BINDING_OUTPUT 2u"), std::string::npos);
    EXPECT_NE(pass.header.find(fmt::format("{}_spv_word_count = {};", pass.stem, pass.spirv.size())), std::string::npos);
    std::string macro = pass.stem;
    for (char& ch : macro) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    EXPECT_NE(pass.header.find(fmt::format("#define {}_USES_TANGENT {}", macro, pass.kind.tangents ? 1 : 0)), std::string::npos);
    EXPECT_EQ(saagen::validate_spirv(pass.spirv, saagen::ClientApi::vulkan), "");
    std::cout << fmt::format("[ size     ] {:<40} {:>6} bytes {:>5} instructions\n", pass.stem + ".spv", pass.spirv.size() * 4,
                             saagen::count_spirv_instructions(pass.spirv));
  }
  static_assert(sizeof(saagen::DeferredPassConstants) == 16);
}

TEST(DeferredPass, OptionsAreDeterministicAndChecked) {
  const auto a = emit_pass("deferred-sum"), b = emit_pass("deferred-sum");
  EXPECT_EQ(a.files(), b.files());
  const auto coarse = emit_pass("deferred-sum", saagen::PlainDerivative::coarse);
  EXPECT_NE(coarse.source("glsl").find("#define dFdx(v) dFdxCoarse(v)"), std::string::npos);
  EXPECT_NE(a.source("glsl").find("#define dFdx(v) dFdxFine(v)"), std::string::npos);
  EXPECT_NE(a.source("hlsl").find("#define ddx(v) ddx_fine(v)"), std::string::npos);
  const auto half = emit_pass("deferred-sum", saagen::PlainDerivative::fine, "r16f");
  EXPECT_NE(half.source("glsl").find("binding = 2, r16f"), std::string::npos);
  EXPECT_NE(half.header.find("VK_FORMAT_R16_SFLOAT"), std::string::npos);
  saagen::DeferredPassOptions options;
  options.passes = {"deferred-nothing"};
  EXPECT_THROW(saagen::emit_deferred_passes(Catalogue::builtin(), options), saagen::Error);
  options.passes = {};
  options.output_format = "rgba8";
  EXPECT_THROW(saagen::emit_deferred_passes(Catalogue::builtin(), options), saagen::Error);
  options.output_format = "r32f";
  options.prefix = "gl_bad";
  EXPECT_THROW(saagen::emit_deferred_passes(Catalogue::builtin(), options), saagen::Error);
}

int run_command(const std::string& command) { return std::system((command + " > /dev/null 2>&1").c_str()); }

TEST(DeferredPass, CliWritesValidatesAndTheHeaderCompilesAsCppAndC) {
  SAAGEN_SKIP_WITHOUT_HOST_COMPILER(SAAGEN_TEST_CXX_COMPILER);
  const fs::path directory = fs::temp_directory_path() / fmt::format("saagen_pass_cli_{}", ::getpid());
  fs::remove_all(directory);
  const std::string cli = SAAGEN_CLI_PATH;
  ASSERT_EQ(run_command(fmt::format("{} pass -v deferred-sum -v deferred-max -o {}", cli, directory.string())), 0);
  const auto sum = emit_pass("deferred-sum");
  for (const auto& [name, content] : sum.files()) {
    std::ifstream stream(directory / name, std::ios::binary);
    std::ostringstream bytes;
    bytes << stream.rdbuf();
    EXPECT_EQ(bytes.str(), content) << name;
  }
  EXPECT_EQ(run_command(fmt::format("{} validate {}", cli, directory.string())), 0);
  EXPECT_NE(run_command(fmt::format("{} pass -v deferred-sum --derivatives sideways -o {}", cli, directory.string())), 0);
  EXPECT_NE(run_command(fmt::format("{} pass -v deferred-nothing -o {}", cli, directory.string())), 0);

  std::ofstream(directory / "main.cpp") << R"(#include "saa_pass_deferred_sum.h"
#include "saa_pass_deferred_max.h"
static_assert(sizeof(saa_pass_constants) == 16, "push constants");
static_assert(saa_pass_deferred_sum_spv[0] == 0x07230203u, "magic");
static_assert(SAA_PASS_DEFERRED_MAX_USES_TANGENT == 1 && SAA_PASS_DEFERRED_SUM_USES_TANGENT == 0, "tangents");
int main() { saa_pass_constants c{1920, 1080, 3, SAA_PASS_DOMAIN_PERCEPTUAL}; return SAA_PASS_GROUPS(c.width) == 240u ? 0 : 1; }
)";
  std::ofstream(directory / "main.c") << "#include \"saa_pass_deferred_sum.h\"\n"
                                         "int main(void) { saa_pass_constants c = {8, 8, 0, SAA_PASS_FLAG_NORMAL_UNORM}; "
                                         "return (int)(c.flags != 4u || saa_pass_deferred_sum_spv_word_count == 0); }\n";
  const std::string compiler = SAAGEN_TEST_CXX_COMPILER;
  EXPECT_EQ(
      run_command(fmt::format("cd {} && {} -std=c++17 -Wall -Wextra -Werror -o main main.cpp && ./main", directory.string(), compiler)), 0);
  EXPECT_EQ(run_command(fmt::format("cd {} && {} -x c -std=c99 -Wall -Werror -o mainc main.c && ./mainc", directory.string(), compiler)),
            0);
  fs::remove_all(directory);
}

// ---------------------------------------------------------------------------------------------
// The pass on the device against the reference

struct PassCase {
  std::string pass;
  std::string language;  // glsl (the emitted .spv) or hlsl (the emitted .hlsl, compiled by glslang)
};

void PrintTo(const PassCase& c, std::ostream* os) { *os << c.language << " " << c.pass; }

class PassOnGpu : public ::testing::TestWithParam<PassCase> {};

TEST_P(PassOnGpu, MatchesTheReferenceOnRenderedGBuffers) {
  require_quads();
  const PassCase& c = GetParam();
  const auto pass = emit_pass(c.pass);
  const auto spirv = spirv_of(pass, c.language);
  for (const TestGBuffer& gbuffer : standard_gbuffers()) {
    const auto report = run_and_compare(pass, spirv, gbuffer, {}, ref::Derivative::fine,
                                        fmt::format("{} {} on {} (fine)", c.language, pass.stem, gbuffer.name));
    std::cout << "[ worst    ] " << report.summary() << "\n";
    EXPECT_EQ(report.failing, 0u) << report.summary();
  }
}

std::vector<PassCase> pass_cases() {
  std::vector<PassCase> cases;
  for (const std::string language : {"glsl", "hlsl"}) {
    for (const auto& kind : saagen::deferred_pass_kinds(Catalogue::builtin())) cases.push_back({kind.id, language});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryPass, PassOnGpu, ::testing::ValuesIn(pass_cases()), [](const auto& info) {
  std::string name = info.param.language + "_" + info.param.pass;
  for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
});

TEST(DeferredPassOnGpu, CoarseDerivativesMatchTheCoarseReference) {
  require_quads();
  for (const std::string id : {"deferred-previous", "deferred-sum"}) {
    const auto pass = emit_pass(id, saagen::PlainDerivative::coarse);
    for (const std::string language : {"glsl", "hlsl"}) {
      for (const std::size_t index : {std::size_t{0}, standard_gbuffers().size() - 1}) {
        const TestGBuffer& gbuffer = standard_gbuffers()[index];
        const auto report = run_and_compare(pass, spirv_of(pass, language), gbuffer, {}, ref::Derivative::coarse,
                                            fmt::format("{} {} on {} (coarse)", language, pass.stem, gbuffer.name));
        std::cout << "[ worst    ] " << report.summary() << "\n";
        EXPECT_EQ(report.failing, 0u) << report.summary();
      }
    }
  }
}

TEST(DeferredPassOnGpu, RoughnessDomainsChannelsAndUnormEncodings) {
  require_quads();
  const std::vector<Encoding> encodings = {
      {abi::domain_alpha, 2, false, false},
      {abi::domain_perceptual, 3, true, true},
      {abi::domain_alpha2, 1, true, false},
      {abi::domain_smoothness, 0, false, true},
  };
  // The flag values are the indices of roughness_domains(), whose conversions the pass calls.
  ASSERT_EQ(saagen::roughness_domains().size(), 4u);
  EXPECT_EQ(saagen::roughness_domains()[abi::domain_alpha].id, "alpha");
  EXPECT_EQ(saagen::roughness_domains()[abi::domain_perceptual].id, "perceptual");
  EXPECT_EQ(saagen::roughness_domains()[abi::domain_smoothness].id, "smoothness");
  for (const std::string id : {"deferred-max", "deferred-projected-space"}) {
    const auto pass = emit_pass(id);
    for (const Encoding& encoding : encodings) {
      const TestGBuffer gbuffer = render(saagen::measure::SceneId::torus, 64, 58, encoding);
      const auto report = run_and_compare(pass, pass.spirv, gbuffer, encoding, ref::Derivative::fine,
                                          fmt::format("glsl {} on {} (domain {}, channel {}, flags {})", pass.stem, gbuffer.name,
                                                      encoding.domain, encoding.channel, encoding.flags()));
      std::cout << "[ worst    ] " << report.summary() << "\n";
      EXPECT_EQ(report.failing, 0u) << report.summary();
    }
  }
}

TEST(DeferredPassOnGpu, HalfFloatOutput) {
  require_quads();
  const auto pass = emit_pass("deferred-avg", saagen::PlainDerivative::fine, "r16f");
  const TestGBuffer& gbuffer = standard_gbuffers()[1];
  const auto report = run_and_compare(pass, pass.spirv, gbuffer, {}, ref::Derivative::fine,
                                      fmt::format("glsl {} r16f on {}", pass.stem, gbuffer.name), VK_FORMAT_R16_SFLOAT);
  std::cout << "[ worst    ] " << report.summary() << "\n";
  EXPECT_EQ(report.failing, 0u) << report.summary();
}

}  // namespace
