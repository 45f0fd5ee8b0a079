// The WGSL target on a real WebGPU implementation: Dawn for Node (npm package `webgpu`) on
// SwiftShader's Vulkan, driven by harness/webgpu/run.mjs, which the whole binary runs once.
//  - Tint: every variant (the glinty BRDFs included) in every form -- fp32, fp16 where the adapter
//    offers shader-f16, unguarded, every roughness domain -- and the bundles of the example
//    manifest, each inside a fragment and a compute entry point that call every public function
//    (saagen::validate_wgsl_files): zero errors and zero warnings, uniformity analysis included.
//  - Compute: every core function of every variant on 16384 of test_gpu_core's inputs (every 8th
//    of its 131072, at a rotating offset) against the double-precision reference.
//  - Fragment: every fragment wrapper on the analytic sphere of test_gpu_fragment, with the
//    module's plain dpdx/dpdy spelt dpdxFine and then dpdxCoarse (real quad derivatives), against
//    the reference fed the shader's fp32 fields as 2x2 quads with the same derivative.
//  - Glints: every glint function with the dictionary bound as a texture_2d_array (the runner's
//    "texture"): the core ones in compute on 4096 of test_glints_gpu's inputs, the wrappers in
//    fragment (dpdxFine, then dpdxCoarse) on its 64 x 64 surface, against the double reference
//    within the bounds of web_glints.hpp (the Vulkan proofs' bounds, derived in glint_support.hpp).
//
// Bounds. WGSL's floating-point accuracy (W3C WGSL, section 15.7.4 "Floating Point Accuracy"):
// f32 +, -, * correctly rounded; x / y within 2.5 ULP (|y| in [2^-126, 2^126]); inverseSqrt 2 ULP,
// sqrt inherited from 1.0 / inverseSqrt(x); exp and exp2 3 + 2|x| ULP; log and log2 3 ULP (2^-21
// absolute in [0.5, 2]); pow inherited from exp2(y * log2(x)); the rest correctly rounded or
// inherited. That is the Vulkan table (Vulkan 1.3, "Precision and Operation of SPIR-V
// Instructions") from which the Vulkan suites' bounds are derived, so the same bounds apply:
// core functions 2e-5 * S (core_cases.hpp), wrappers 16 ulps of the condition + 2e-5 |f|
// (wrapper_cases.hpp).
#include "support/core_cases.hpp"
#include "support/web_glints.hpp"
#include "support/web_runs.hpp"
#include "support/web_support.hpp"
#include "support/wrapper_cases.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/harness/webgpu.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/kernels.hpp"
#include "saagen/validate/validation.hpp"

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
using saagen::test::read_floats;
using saagen::test::wgsl_options;
using saagen::test::Worst;

constexpr std::uint32_t kCoreElements = 16384;

saagen::EmittedFile emit(const std::string& variant, const std::string& precision = "fp32") {
  saagen::EmitOptions options;
  options.target = "wgsl";
  options.variants = {variant};
  options.precision = saagen::parse_precision(precision);
  return saagen::emit_variants(Catalogue::builtin(), options).front();
}

enum class Kind { core, wrapper };

struct Case {
  std::string id;
  Kind kind = Kind::core;
  std::string variant, function;
  ref::Derivative derivative = ref::Derivative::fine;  // wrappers: what plain dpdx/dpdy are spelt as
};

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  std::set<std::string> seen;  // a function public in several variants runs once
  for (const saagen::Variant& variant : Catalogue::builtin().variants()) {
    for (const std::string& name : variant.functions) {
      const saagen::Function& function = *Catalogue::builtin().find_function(name);
      if (!seen.insert(name).second) continue;
      if (function.role == saagen::FunctionRole::fragment) {
        cases.push_back({"fine_" + name, Kind::wrapper, variant.id, name, ref::Derivative::fine});
        cases.push_back({"coarse_" + name, Kind::wrapper, variant.id, name, ref::Derivative::coarse});
      } else if (!function.fragment_only) {
        cases.push_back({"core_" + name, Kind::core, variant.id, name});
      }
    }
  }
  return cases;
}

// The runner job of one case; its inputs are written to `directory`.
nlohmann::json job_for(const fs::path& directory, const Case& c, std::vector<float>& inputs) {
  const saagen::EmittedFile file = emit(c.variant);
  const saagen::Function& function = *Catalogue::builtin().find_function(c.function);
  saagen::KernelRequest request;
  nlohmann::json job{{"id", c.id}};
  if (c.kind == Kind::wrapper) {
    namespace w = saagen::test::wrappers;
    request.kind = saagen::KernelKind::fragment;
    request.width = w::width;
    request.output_stride = w::stride;
    request.body = std::string(w::scene_body) + w::wrapper_call(function);
    request.redirect_plain_derivatives = true;
    request.plain_derivative = c.derivative == ref::Derivative::fine ? saagen::PlainDerivative::fine : saagen::PlainDerivative::coarse;
    job["kind"] = "fragment";
    job["width"] = w::width;
    job["height"] = w::height;
    job["output_floats"] = std::size_t{w::width} * w::height * w::stride;
  } else {
    request.kind = saagen::KernelKind::compute;
    request.body = saagen::load_call_store_body(Catalogue::builtin(), c.function, request);
    inputs = saagen::test::subsampled_core_inputs(function, kCoreElements);
    std::ofstream(directory / (c.id + ".in.f32"), std::ios::binary)
        .write(reinterpret_cast<const char*>(inputs.data()), static_cast<std::streamsize>(inputs.size() * sizeof(float)));
    job["kind"] = "compute";
    job["input"] = c.id + ".in.f32";
    job["invocations"] = kCoreElements;
    job["output_floats"] = std::size_t{kCoreElements} * request.output_stride;
  }
  job["code"] = saagen::joined_source(saagen::kernel_sources(Catalogue::builtin(), file.file_name, file.content, request));
  return job;
}

// Every glint function: the core ones in compute, the wrappers in fragment with dpdxFine and dpdxCoarse.
std::vector<saagen::test::web_glints::Case> glint_cases() {
  return saagen::test::web_glints::cases("core_", {{"fine_", ref::Derivative::fine}, {"coarse_", ref::Derivative::coarse}});
}

// The runner job of one glint case, with the dictionary `texture` (web_glints::write_dictionary).
nlohmann::json glint_job_for(const fs::path& directory, const saagen::test::web_glints::Case& c, const nlohmann::json& texture,
                             std::vector<float>& inputs) {
  namespace wg = saagen::test::web_glints;
  const saagen::Catalogue& catalogue = saagen::glints::catalogue();
  saagen::EmitOptions options;
  options.target = "wgsl";
  options.variants = {c.variant};
  const saagen::EmittedFile file = saagen::glints::emit(options).front();
  saagen::KernelRequest request;
  nlohmann::json job{{"id", c.id}, {"texture", texture}};
  if (c.wrapper) {
    request.kind = saagen::KernelKind::fragment;
    request.width = wg::side;
    request.output_stride = static_cast<std::uint32_t>(c.wrappers.size());
    request.body = wg::wrapper_body(c.variant);
    request.redirect_plain_derivatives = true;
    request.plain_derivative = c.derivative == ref::Derivative::fine ? saagen::PlainDerivative::fine : saagen::PlainDerivative::coarse;
    job["kind"] = "fragment";
    job["width"] = job["height"] = wg::side;
    job["output_floats"] = std::size_t{wg::side} * wg::side * request.output_stride;
  } else {
    request.kind = saagen::KernelKind::compute;
    request.body = saagen::load_call_store_body(catalogue, c.function, request);
    inputs = saagen::test::glint::packed_inputs(*catalogue.find_function(c.function), wg::elements);
    std::ofstream(directory / (c.id + ".in.f32"), std::ios::binary)
        .write(reinterpret_cast<const char*>(inputs.data()), static_cast<std::streamsize>(inputs.size() * sizeof(float)));
    job["kind"] = "compute";
    job["input"] = c.id + ".in.f32";
    job["invocations"] = wg::elements;
    job["output_floats"] = wg::elements * request.output_stride;
  }
  job["code"] = saagen::joined_source(saagen::kernel_sources(catalogue, file.file_name, file.content, request));
  return job;
}

// Every WGSL file the Tint suite validates: each variant in each form, and the manifest bundles.
std::vector<std::pair<std::string, std::string>> files_to_validate(bool with_f16) {
  std::vector<std::pair<std::string, std::string>> files;
  const Catalogue& every_variant = saagen::glints::catalogue();
  const auto add = [&](saagen::EmitOptions options) {
    options.target = "wgsl";
    for (saagen::EmittedFile& file : saagen::emit_variants(every_variant, options))
      files.emplace_back(file.file_name, std::move(file.content));
  };
  add(wgsl_options());
  if (with_f16) add(wgsl_options("fp16"));
  add(wgsl_options("fp32", false));
  for (const char* domain : {"alpha", "perceptual", "smoothness"}) {
    add(wgsl_options("fp32", true, domain));
    if (with_f16) add(wgsl_options("fp16", true, domain));
  }
  // Several variants in one module, with the naga_oil header a module importer strips.
  const saagen::EmitOptions options = wgsl_options();
  const std::vector<std::string> variants = {"forward-aniso-projected", "deferred-sum", "brdf-ggx", "deferred-max"};
  const saagen::BundleRequest request{"scene", saagen::public_functions(Catalogue::builtin(), variants), variants, {}};
  files.emplace_back("saa_scene.wgsl", saagen::emit_bundle(Catalogue::builtin(), options, request).content);
  return files;
}

struct RunnerRun {
  nlohmann::json results;
  std::map<std::string, std::vector<float>> outputs;
  std::map<std::string, std::vector<float>> inputs;
  std::string error;
};

const RunnerRun& runner_run() {
  static const RunnerRun run = [] {
    RunnerRun result;
    const fs::path directory = fs::temp_directory_path() / fmt::format("saagen-wgsl-test-{}", ::getpid());
    fs::create_directories(directory);
    nlohmann::json jobs = nlohmann::json::array();
    const std::vector<Case> cases = all_cases();
    const auto job = [&](const Case& c, std::vector<float>& inputs) { return job_for(directory, c, inputs); };
    saagen::test::add_runner_entries(cases, job, jobs, result.inputs);
    const nlohmann::json texture = saagen::test::web_glints::write_dictionary(directory);
    const auto glints = glint_cases();
    const auto glint_job = [&](const saagen::test::web_glints::Case& c, std::vector<float>& inputs) {
      return glint_job_for(directory, c, texture, inputs);
    };
    saagen::test::add_runner_entries(glints, glint_job, jobs, result.inputs);
    try {
      result.results = saagen::harness::run_webgpu_jobs(jobs, directory);
    } catch (const saagen::Error& error) {
      result.error = error.what();
    }
    for (const Case& c : cases) result.outputs[c.id] = read_floats(directory / (c.id + ".out.f32"));
    for (const auto& c : glints) result.outputs[c.id] = read_floats(directory / (c.id + ".out.f32"));
    fs::remove_all(directory);
    return result;
  }();
  return run;
}

const nlohmann::json& result_of(const std::string& id) {
  const RunnerRun& run = runner_run();
  if (!run.error.empty()) throw std::runtime_error(run.error);
  for (const auto& result : run.results.at("results")) {
    if (result.at("id") == id) return result;
  }
  throw std::runtime_error("the runner returned no result for " + id);
}

bool adapter_has_f16() {
  const auto& features = runner_run().results.value("features", nlohmann::json::array());
  return std::find(features.begin(), features.end(), "shader-f16") != features.end();
}

class OnWebGpu : public ::testing::TestWithParam<Case> {};

TEST_P(OnWebGpu, MatchesTheDoublePrecisionReferenceWithinTheWgslAccuracyBounds) {
  const Case& c = GetParam();
  const nlohmann::json& result = result_of(c.id);
  ASSERT_FALSE(result.contains("error")) << c.id << ": " << result.dump();
  const std::vector<float>& out = runner_run().outputs.at(c.id);
  const ref::Params params{.sigma2 = 0.25, .kappa = 0.18, .guards = true};
  Worst worst;
  if (c.kind == Kind::core) {
    saagen::KernelRequest request;
    (void)saagen::load_call_store_body(Catalogue::builtin(), c.function, request);
    ASSERT_EQ(out.size(), std::size_t{kCoreElements} * request.output_stride);
    const auto bound = [](double scale) { return saagen::test::core::rounding_bound * scale + 1e-30; };
    worst = saagen::test::core_worst(c.function, params, kCoreElements, runner_run().inputs.at(c.id), out, request.output_stride, bound);
  } else {
    namespace w = saagen::test::wrappers;
    ASSERT_EQ(out.size(), std::size_t{w::width} * w::height * w::stride);
    const saagen::Function& function = *Catalogue::builtin().find_function(c.function);
    // The quad average of deferred-previous/-max takes dpdxFine as written: fine.
    const auto comparison = w::reference_with_bounds(c.function, saagen::component_count(function.return_type), out, c.derivative,
                                                     ref::Derivative::fine, params);
    for (std::size_t k = 0; k < comparison.got.size(); ++k) worst.add(comparison.got[k], comparison.expected[k], comparison.bound[k]);
  }
  const std::string what =
      fmt::format("{} ({}, {})", c.function, c.variant,
                  c.kind == Kind::wrapper ? (c.derivative == ref::Derivative::fine ? "fragment, dpdxFine" : "fragment, dpdxCoarse")
                                          : "compute, 16384 inputs");
  std::cout << "[ webgpu   ] " << worst.summary(what) << "\n";
  EXPECT_GT(worst.count, 0u);
  EXPECT_EQ(worst.failing, 0u) << worst.summary(what);
}

INSTANTIATE_TEST_SUITE_P(EveryFunction, OnWebGpu, ::testing::ValuesIn(all_cases()), [](const auto& info) { return info.param.id; });

class GlintsOnWebGpu : public ::testing::TestWithParam<saagen::test::web_glints::Case> {};

TEST_P(GlintsOnWebGpu, MatchTheDoublePrecisionReferenceWithinTheSamplerAndFp32Bounds) {
  namespace wg = saagen::test::web_glints;
  const wg::Case& c = GetParam();
  const nlohmann::json& result = result_of(c.id);
  ASSERT_FALSE(result.contains("error")) << c.id << ": " << result.dump();
  const std::vector<float>& out = runner_run().outputs.at(c.id);
  saagen::KernelRequest request;
  if (c.wrapper) {
    request.output_stride = static_cast<std::uint32_t>(c.wrappers.size());
  } else {
    (void)saagen::load_call_store_body(saagen::glints::catalogue(), c.function, request);
  }
  const std::size_t items = c.wrapper ? std::size_t{wg::side} * wg::side : wg::elements;
  ASSERT_EQ(out.size(), items * request.output_stride);
  const std::vector<float> no_inputs;
  const auto found = runner_run().inputs.find(c.id);
  const auto reference =
      wg::comparison(c, found == runner_run().inputs.end() ? no_inputs : found->second, request.input_stride, c.derivative);
  EXPECT_EQ(reference.outside, 0u) << "the exact-LOD reference lies outside [low, high]: the lookups' bound is not monotone";
  for (const wg::FunctionResult& function : wg::compare(c, out, request.output_stride, reference)) {
    const std::string what = fmt::format("{} ({}, {})", function.function, c.variant,
                                         c.wrapper ? (c.derivative == ref::Derivative::fine ? "fragment, dpdxFine" : "fragment, dpdxCoarse")
                                                   : fmt::format("compute, {} inputs", wg::elements));
    std::cout << "[ webgpu   ] " << function.worst.summary(what) << "\n";
    EXPECT_EQ(function.worst.failing, 0u) << function.worst.summary(what);
    EXPECT_GT(function.nonzero, function.worst.count / 2) << what << ": the inputs do not hit the lobes";
  }
}

INSTANTIATE_TEST_SUITE_P(EveryGlintFunction, GlintsOnWebGpu, ::testing::ValuesIn(glint_cases()),
                         [](const auto& info) { return info.param.id; });

TEST(WebGpuAdapter, IsDawnOnSwiftShader) {
  const RunnerRun& run = runner_run();
  ASSERT_TRUE(run.error.empty()) << run.error;
  std::cout << "[ webgpu   ] adapter " << run.results.value("adapter", nlohmann::json::object()).dump() << "; shader-f16 "
            << (adapter_has_f16() ? "offered" : "not offered") << "\n";
}

TEST(Tint, ValidatesEveryVariantInEveryFormWithoutErrorsOrWarnings) {
  ASSERT_TRUE(runner_run().error.empty()) << runner_run().error;
  const auto files = files_to_validate(adapter_has_f16());
  saagen::harness::install_webgpu_runner();
  const auto validations = saagen::validate_wgsl_files(saagen::glints::catalogue(), files);
  ASSERT_EQ(validations.size(), files.size());
  std::size_t modules = 0;
  for (const saagen::FileValidation& validation : validations) {
    EXPECT_TRUE(validation.ok()) << validation.summary() << "\n" << (validation.checks.empty() ? "" : validation.checks.front().log);
    EXPECT_EQ(validation.checks.size(), 2u) << validation.file_name;
    modules += validation.checks.size();
  }
  std::cout << "[ tint     ] " << files.size() << " WGSL files, " << modules << " modules (fragment + compute entry points) compiled\n";
}

TEST(Tint, ReportsAnErrorAtTheLineOfTheEmittedFile) {
  saagen::EmittedFile file = emit("deferred-sum");
  // A type error in the emitted text: an f32 local initialised with a vec2.
  const std::string broken_line = "    let saagen_broken: f32 = vec2<f32>(1.0, 2.0);\n";
  const auto body = file.content.find("{\n", file.content.find("fn saa_deferred_sum(")) + 2;
  file.content.insert(body, broken_line);
  const int line = static_cast<int>(std::count(file.content.begin(), file.content.begin() + static_cast<long>(body), '\n')) + 1;
  saagen::harness::install_webgpu_runner();
  const auto validations = saagen::validate_wgsl_files(Catalogue::builtin(), {{"broken.wgsl", file.content}});
  ASSERT_EQ(validations.size(), 1u);
  EXPECT_FALSE(validations[0].ok());
  EXPECT_NE(validations[0].summary().find(fmt::format("broken.wgsl:{}:", line)), std::string::npos) << validations[0].summary();
}

TEST(Tint, NeedsAnInstalledRunner) {
  saagen::install_webgpu_runner(nullptr);
  try {
    saagen::validate_wgsl_files(Catalogue::builtin(), {{"saa_deferred_sum.wgsl", emit("deferred-sum").content}});
    ADD_FAILURE() << "validated WGSL without a runner";
  } catch (const saagen::Error& error) {
    EXPECT_NE(std::string(error.what()).find("installed none"), std::string::npos) << error.what();
  }
  saagen::harness::install_webgpu_runner();
}

TEST(Tint, RefusesADerivativeInNonUniformControlFlow) {
  // The uniformity analysis is on: a wrapper called under a branch on a per-pixel value fails.
  const saagen::EmittedFile file = emit("deferred-sum");
  const std::string module = file.content +
                             "@fragment\nfn saagen_nonuniform(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {\n"
                             "    var r: f32 = 0.0;\n"
                             "    if p.x > 8.0 { r = saa_deferred_sum_fragment(0.1, normalize(p.xyz)); }\n"
                             "    return vec4<f32>(r);\n}\n";
  nlohmann::json jobs = nlohmann::json::array();
  jobs.push_back({{"id", "nonuniform"},
                  {"kind", "compile"},
                  {"code", module},
                  {"entry_points", nlohmann::json::array({{{"stage", "fragment"}, {"name", "saagen_nonuniform"}}})}});
  const fs::path directory = fs::temp_directory_path() / fmt::format("saagen-wgsl-uniformity-{}", ::getpid());
  fs::create_directories(directory);
  const nlohmann::json results = saagen::harness::run_webgpu_jobs(jobs, directory);
  fs::remove_all(directory);
  const std::string text = results.at("results").at(0).dump();
  EXPECT_NE(text.find("uniform"), std::string::npos) << text;
}

}  // namespace
