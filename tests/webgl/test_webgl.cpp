// The GLSL ES 3.00 target run in WebGL2 (headless Chromium, ANGLE on SwiftShader; driven by
// tests/webgl/run_functions.mjs through puppeteer-core) against the double-precision reference:
// every core function of every variant on the inputs of test_gpu_core (core_cases.hpp: every
// 8th of its 131072 at a rotating offset, 16384 per function), and every fragment wrapper on the analytic sphere of
// test_gpu_fragment (wrapper_cases.hpp) with real quad derivatives; each emitted in highp (fp32)
// and mediump (fp16). Inputs come in as an RGBA32F texture, results go out to RGBA32F render
// targets (EXT_color_buffer_float) read back as floats.
//
// Bounds, from the GLSL ES 3.00 specification:
//  - highp (section 4.5.1, "Range and Precision"): IEEE single precision, a / b within 2.5 ULP,
//    inversesqrt 2 ULP, exp/exp2 (3 + 2|x|) ULP, the rest correctly rounded or inherited: the
//    Vulkan table that the Vulkan suites' bounds are derived from, so the same bounds apply
//    (core: 2e-5 * S, core_cases.hpp; wrappers: 16 ulps of the condition + 2e-5 |f|,
//    wrapper_cases.hpp).
//  - mediump (section 4.5.2, the precision table): relative precision 2^-10 and magnitudes in
//    [2^-14, 2^14]. Running error analysis of n <= 16 operations (the filters' <= 12 plus the
//    2.5-ULP division and 2-ULP sqrt) gives gamma_16 = 16 * 2^-10 relative to the magnitude
//    scale S, and each operation may flush a result below 2^-14 to zero: 16 * 2^-14 absolute
//    (outputs are alpha^2 in [0, 1]). The wrappers' inputs are rounded to mediump at the call:
//    16 ulps of 2^-10 times the condition. The BRDFs are run in highp only: mediump's range
//    (2^14) cannot hold D = 1 / (pi alpha^2 ...) below alpha ~ 0.01, which the inputs reach.
// ES lets plain dFdx/dFdy be fine or coarse (section 8.9); the device's choice is probed, and
// the reference takes the same (for the quad average too: ES has no dFdxFine).
//
// Glints: every glint function in highp with the dictionary as a sampler2DArray (RGBA16F, its
// MIP chain, linear filters, mirrored repeat) on texture unit 1: the core ones on 4096 of
// test_glints_gpu's inputs (64 x 64 pixels, one element each), the wrappers on its 64 x 64
// surface with the probed plain derivatives, against the double reference within the bounds of
// web_glints.hpp (the Vulkan proofs' bounds, derived in glint_support.hpp). Not in mediump: the
// glint functions have no derived half-precision bound.
#include "support/core_cases.hpp"
#include "support/web_glints.hpp"
#include "support/web_runs.hpp"
#include "support/web_support.hpp"
#include "support/wrapper_cases.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/target/resources.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
namespace ref = saagen::ref;
using saagen::Catalogue;
using saagen::test::Worst;

constexpr std::uint32_t kCoreSide = 128;  // core results: a 128 x 128 target, one element per pixel
constexpr std::uint32_t kCoreElements = kCoreSide * kCoreSide;
constexpr std::uint32_t kInputTextureWidth = 1024;  // texels (4 floats) per row
constexpr double kMediumpUlp = 0x1p-10;             // ES 3.00 4.5.2: relative precision
constexpr double kMediumpFlush = 0x1p-14;           // ES 3.00 4.5.2: smallest magnitude
constexpr double kMediumpOperations = 16.0;

// The skeleton around an emitted file: default precisions for the skeleton's own declarations
// (the emitted functions state theirs), the input texture, one RGBA32F output, and saagen_pass
// selecting which 4 of a pixel's outputs this draw writes.
const char* const kPrologue =
    "#version 300 es\n"
    "precision highp float;\n"
    "precision highp int;\n"
    "uniform highp sampler2D saagen_input;\n"
    "uniform int saagen_pass;\n"
    "layout(location = 0) out highp vec4 saagen_output;\n";

std::string epilogue(const std::string& body, std::uint32_t width, std::uint32_t input_stride) {
  return fmt::format(
      "highp float saagen_load(int element, int i)\n"
      "{{\n"
      "    int f = element * {1} + i;\n"
      "    int t = f / 4;\n"
      "    return texelFetch(saagen_input, ivec2(t % {2}, t / {2}), 0)[f % 4];\n"
      "}}\n"
      "#define SAAGEN_LOAD(i) saagen_load(saagen_index, int(i))\n"
      "#define SAAGEN_STORE(i, v) if (int(i) / 4 == saagen_pass) saagen_output[int(i) % 4] = (v)\n"
      "void main()\n"
      "{{\n"
      "    vec2 saagen_frag_coord = gl_FragCoord.xy;\n"
      "    int saagen_index = int(saagen_frag_coord.y) * {0} + int(saagen_frag_coord.x);\n"
      "    saagen_output = vec4(0.0);\n"
      "{3}}}\n",
      width, std::max<std::uint32_t>(input_stride, 1), kInputTextureWidth, body);
}

saagen::EmittedFile emit(const std::string& variant, const std::string& precision) {
  saagen::EmitOptions options;
  options.target = "gles";
  options.variants = {variant};
  options.precision = saagen::parse_precision(precision);
  return saagen::emit_variants(Catalogue::builtin(), options).front();
}

// The shader running `body` (template dialect) after the emitted file of `catalogue`'s functions,
// with the declarations of the resources they sample (`resources`) before it.
std::string shader_source(const saagen::EmittedFile& file, const std::string& body, std::uint32_t width, std::uint32_t input_stride,
                          const Catalogue& catalogue = Catalogue::builtin(), const std::string& resources = "") {
  saagen::NameMap names;
  for (const saagen::Function& function : catalogue.functions()) names[function.name] = saagen::prefixed_name("saa_", function.name);
  const std::string printed = saagen::print_glue(saagen::builtin_target("gles"), catalogue, body, names, saagen::kernel_glue_symbols());
  return std::string(kPrologue) + resources + file.content + epilogue(printed, width, input_stride);
}

enum class Kind { core, wrapper, probe };

struct Case {
  std::string id;
  Kind kind = Kind::core;
  std::string variant, function, precision;
};

bool is_brdf(const std::string& function) {
  return function.find("brdf") != std::string::npos || function.find("ndf") != std::string::npos ||
         function.find("lambda") != std::string::npos || function.find("g2") != std::string::npos;
}

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (const std::string precision : {"fp32", "fp16"}) {
    std::set<std::string> seen;  // a function public in several variants runs once
    for (const saagen::Variant& variant : Catalogue::builtin().variants()) {
      for (const std::string& name : variant.functions) {
        const saagen::Function& function = *Catalogue::builtin().find_function(name);
        if ((precision == "fp16" && is_brdf(name)) || !seen.insert(name).second) continue;
        const bool wrapper = function.role == saagen::FunctionRole::fragment;
        if (function.fragment_only && !wrapper) continue;
        const Kind kind = wrapper ? Kind::wrapper : Kind::core;
        cases.push_back({fmt::format("{}_{}", precision == "fp32" ? "highp" : "mediump", name), kind, variant.id, name, precision});
      }
    }
  }
  return cases;
}

// Everything the browser needs for one case, written to `directory`; returns its cases.json entry.
nlohmann::json write_case(const fs::path& directory, const Case& c, std::vector<float>& inputs) {
  const saagen::EmittedFile file = emit(c.variant, c.precision);
  nlohmann::json entry{{"id", c.id}};
  if (c.kind == Kind::probe) {
    entry["shader"] = shader_source(file, "    SAAGEN_STORE(0, ddx(saagen_frag_coord.x * saagen_frag_coord.y));\n", 4, 0);
    entry["width"] = entry["height"] = 4;
    entry["passes"] = 1;
    return entry;
  }
  const saagen::Function& function = *Catalogue::builtin().find_function(c.function);
  if (c.kind == Kind::wrapper) {
    namespace w = saagen::test::wrappers;
    entry["shader"] = shader_source(file, std::string(w::scene_body) + w::wrapper_call(function), w::width, 0);
    entry["width"] = w::width;
    entry["height"] = w::height;
    entry["passes"] = (w::stride + 3) / 4;
    return entry;
  }
  saagen::KernelRequest request;
  const std::string body = saagen::load_call_store_body(Catalogue::builtin(), c.function, request);
  inputs = saagen::test::subsampled_core_inputs(function, kCoreElements);
  inputs.resize(((inputs.size() + 4 * kInputTextureWidth - 1) / (4 * kInputTextureWidth)) * 4 * kInputTextureWidth, 0.0f);
  std::ofstream(directory / (c.id + ".in.f32"), std::ios::binary)
      .write(reinterpret_cast<const char*>(inputs.data()), static_cast<std::streamsize>(inputs.size() * sizeof(float)));
  entry["shader"] = shader_source(file, body, kCoreSide, request.input_stride);
  entry["input"] = c.id + ".in.f32";
  entry["input_width"] = kInputTextureWidth;
  entry["input_height"] = inputs.size() / (4 * kInputTextureWidth);
  entry["width"] = entry["height"] = kCoreSide;
  entry["passes"] = 1;
  return entry;
}

// Every glint function in highp: the core ones, and each variant's wrappers with the probed derivatives.
std::vector<saagen::test::web_glints::Case> glint_cases() {
  return saagen::test::web_glints::cases("highp_", {{"highp_", ref::Derivative::fine}});
}

// The cases.json entry of a glint case, with the dictionary `texture` (web_glints::write_dictionary)
// as the uniform the emitted declaration names.
nlohmann::json write_glint_case(const fs::path& directory, const saagen::test::web_glints::Case& c, const nlohmann::json& texture,
                                std::vector<float>& inputs) {
  namespace wg = saagen::test::web_glints;
  const Catalogue& catalogue = saagen::glints::catalogue();
  saagen::EmitOptions options;
  options.target = "gles";
  options.variants = {c.variant};
  const saagen::EmittedFile file = saagen::glints::emit(options).front();
  const saagen::TargetSyntax target = saagen::builtin_target("gles").with_prefix("saa_", saagen::macro_prefix("saa_"));
  const std::string resources = saagen::resource_declarations(target, catalogue, catalogue.find_variant(c.variant)->functions);
  nlohmann::json entry{{"id", c.id}, {"width", wg::side}, {"height", wg::side}, {"passes", 1}};
  entry["texture"] = texture;
  entry["texture"]["uniform"] = "saagen_glint_dictionary";  // targets/gles.json's declaration
  if (c.wrapper) {
    entry["shader"] = shader_source(file, wg::wrapper_body(c.variant), wg::side, 0, catalogue, resources);
    return entry;
  }
  saagen::KernelRequest request;
  const std::string body = saagen::load_call_store_body(catalogue, c.function, request);
  inputs = saagen::test::glint::packed_inputs(*catalogue.find_function(c.function), wg::elements);
  std::vector<float> padded = inputs;
  padded.resize(((padded.size() + 4 * kInputTextureWidth - 1) / (4 * kInputTextureWidth)) * 4 * kInputTextureWidth, 0.0f);
  std::ofstream(directory / (c.id + ".in.f32"), std::ios::binary)
      .write(reinterpret_cast<const char*>(padded.data()), static_cast<std::streamsize>(padded.size() * sizeof(float)));
  entry["shader"] = shader_source(file, body, wg::side, request.input_stride, catalogue, resources);
  entry["input"] = c.id + ".in.f32";
  entry["input_width"] = kInputTextureWidth;
  entry["input_height"] = padded.size() / (4 * kInputTextureWidth);
  return entry;
}

// Runs every case in the browser once per process; the results by case id (RGBA floats per
// pixel and pass: pass-major).
struct BrowserRun {
  std::map<std::string, std::vector<float>> outputs;
  std::map<std::string, std::vector<float>> inputs;
  std::string error;
};

const BrowserRun& browser_run() {
  static const BrowserRun run = [] {
    BrowserRun result;
    const fs::path directory = fs::temp_directory_path() / fmt::format("saagen-webgl-{}", ::getpid());
    fs::create_directories(directory);
    nlohmann::json cases = nlohmann::json::array();
    std::vector<Case> all = all_cases();
    all.push_back({"probe_derivative", Kind::probe, "deferred-sum", "", "fp32"});
    const auto write = [&](const Case& c, std::vector<float>& inputs) { return write_case(directory, c, inputs); };
    saagen::test::add_runner_entries(all, write, cases, result.inputs);
    const nlohmann::json texture = saagen::test::web_glints::write_dictionary(directory);
    const auto write_glint = [&](const saagen::test::web_glints::Case& c, std::vector<float>& inputs) {
      return write_glint_case(directory, c, texture, inputs);
    };
    saagen::test::add_runner_entries(glint_cases(), write_glint, cases, result.inputs);
    std::ofstream(directory / "cases.json") << cases.dump();
    const std::string command = fmt::format("node '{}/tests/webgl/run_functions.mjs' '{}'", SAAGEN_SOURCE_DIR, directory.string());
    if (std::system(command.c_str()) != 0) {
      result.error = "the browser run failed: " + command;
      return result;
    }
    for (const nlohmann::json& entry : cases) {
      const std::string id = entry.at("id").get<std::string>();
      std::vector<float> values = saagen::test::read_floats(directory / (id + ".out.f32"));
      if (values.empty()) continue;
      result.outputs[id] = std::move(values);
    }
    fs::remove_all(directory);
    return result;
  }();
  return run;
}

const std::vector<float>& outputs_of(const std::string& id) {
  const BrowserRun& run = browser_run();
  if (!run.error.empty()) throw std::runtime_error(run.error);
  const auto found = run.outputs.find(id);
  if (found == run.outputs.end()) throw std::runtime_error("no browser output for " + id);
  return found->second;
}

// ES allows either; the reference's coarse takes the quad's first row and column.
ref::Derivative browser_plain_derivative() {
  const auto& out = outputs_of("probe_derivative");
  // Pixel (0, 1), channel 0: fine gives its own row's x-difference of x*y, 1.5; coarse row 0's, 0.5.
  const float value = out[(1 * 4 + 0) * 4];
  if (value != 1.5f && value != 0.5f)
    throw std::runtime_error(fmt::format("plain dFdx is neither fine nor coarse as the reference takes it: {}", value));
  const ref::Derivative mode = value == 1.5f ? ref::Derivative::fine : ref::Derivative::coarse;
  static const bool printed = (std::cout << "[ webgl2   ] plain dFdx/dFdy: " << (value == 1.5f ? "fine" : "coarse") << "\n", true);
  (void)printed;
  return mode;
}

const char* plain_derivative_name() { return browser_plain_derivative() == ref::Derivative::fine ? "fine" : "coarse"; }

class InWebGl2 : public ::testing::TestWithParam<Case> {};

TEST_P(InWebGl2, MatchesTheDoublePrecisionReferenceWithinTheEsPrecisionBounds) {
  const Case& c = GetParam();
  const bool mediump = c.precision == "fp16";
  // A half-precision emission carries the half guard constants (Params::half_precision).
  const ref::Params params{.sigma2 = 0.25, .kappa = 0.18, .guards = true, .half_precision = mediump};
  const auto& out = outputs_of(c.id);
  Worst worst;
  if (c.kind == Kind::core) {
    const auto bound = [&](double scale) {
      return mediump ? kMediumpOperations * (kMediumpUlp * scale + kMediumpFlush) : saagen::test::core::rounding_bound * scale + 1e-30;
    };
    // One RGBA pixel (4 floats) per element.
    worst = saagen::test::core_worst(c.function, params, kCoreElements, browser_run().inputs.at(c.id), out, 4, bound);
  } else {
    namespace w = saagen::test::wrappers;
    const ref::Derivative mode = browser_plain_derivative();
    // Re-interleave the passes (4 floats each) into the wrapper suite's per-pixel layout.
    const std::size_t pixels = std::size_t{w::width} * w::height;
    std::vector<float> fields(pixels * w::stride);
    for (std::size_t pixel = 0; pixel < pixels; ++pixel) {
      for (std::uint32_t k = 0; k < w::stride; ++k) fields[pixel * w::stride + k] = out[(k / 4) * pixels * 4 + pixel * 4 + k % 4];
    }
    const saagen::Function& function = *Catalogue::builtin().find_function(c.function);
    const auto comparison = w::reference_with_bounds(c.function, saagen::component_count(function.return_type), fields, mode, mode, params);
    for (std::size_t k = 0; k < comparison.got.size(); ++k) {
      double bound = comparison.bound[k];
      if (mediump) {
        // The highp bound's terms with mediump's unit: 16 ulps (2^-24) of the condition become
        // 16 ulps of 2^-10, the filter's own rounding as for the core functions.
        const double condition_part = std::max(0.0, bound - 2e-5 * std::fabs(comparison.expected[k]) - 1e-30);
        bound =
            condition_part * std::ldexp(1.0, 14) + kMediumpOperations * (kMediumpUlp * std::fabs(comparison.expected[k]) + kMediumpFlush);
      }
      worst.add(comparison.got[k], comparison.expected[k], bound);
    }
  }
  const std::string what =
      fmt::format("{} {} ({}, {})", mediump ? "mediump" : "highp", c.function, c.variant,
                  c.kind == Kind::wrapper ? fmt::format("fragment quads, {} dFdx", plain_derivative_name()) : std::string("16384 inputs"));
  std::cout << "[ webgl2   ] " << worst.summary(what) << "\n";
  EXPECT_GT(worst.count, 0u);
  EXPECT_EQ(worst.failing, 0u) << worst.summary(what);
}

class GlintsInWebGl2 : public ::testing::TestWithParam<saagen::test::web_glints::Case> {};

TEST_P(GlintsInWebGl2, MatchTheDoublePrecisionReferenceWithinTheSamplerAndFp32Bounds) {
  namespace wg = saagen::test::web_glints;
  const wg::Case& c = GetParam();
  const auto& out = outputs_of(c.id);
  ASSERT_EQ(out.size(), std::size_t{wg::side} * wg::side * 4);
  saagen::KernelRequest request;
  if (!c.wrapper) (void)saagen::load_call_store_body(saagen::glints::catalogue(), c.function, request);
  const std::vector<float> no_inputs;
  const auto found = browser_run().inputs.find(c.id);
  const ref::Derivative mode = c.wrapper ? browser_plain_derivative() : ref::Derivative::fine;
  const auto reference = wg::comparison(c, found == browser_run().inputs.end() ? no_inputs : found->second, request.input_stride, mode);
  EXPECT_EQ(reference.outside, 0u) << "the exact-LOD reference lies outside [low, high]: the lookups' bound is not monotone";
  for (const wg::FunctionResult& function : wg::compare(c, out, 4, reference)) {
    const std::string what =
        fmt::format("highp {} ({}, {})", function.function, c.variant,
                    c.wrapper ? fmt::format("fragment quads, {} dFdx", plain_derivative_name()) : fmt::format("{} inputs", wg::elements));
    std::cout << "[ webgl2   ] " << function.worst.summary(what) << "\n";
    EXPECT_EQ(function.worst.failing, 0u) << function.worst.summary(what);
    EXPECT_GT(function.nonzero, function.worst.count / 2) << what << ": the inputs do not hit the lobes";
  }
}

INSTANTIATE_TEST_SUITE_P(EveryGlintFunction, GlintsInWebGl2, ::testing::ValuesIn(glint_cases()),
                         [](const auto& info) { return info.param.id; });

INSTANTIATE_TEST_SUITE_P(EveryFunction, InWebGl2, ::testing::ValuesIn(all_cases()), [](const auto& info) {
  std::string name = info.param.id;
  for (char& ch : name) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return name;
});

}  // namespace
