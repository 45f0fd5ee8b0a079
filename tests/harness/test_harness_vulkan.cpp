// Tests of the headless Vulkan harness (harness/) on the default device, lavapipe.
//
// When no Vulkan device is available, creating the context throws and the tests fail with the
// harness's message (so CI=true runs cannot pass silently without a device). Select another
// device with SAAGEN_VK_DEVICE=<name substring>. Two facts hold for lavapipe alone and are
// checked only there: the default device is lavapipe (skipped where lavapipe is not installed),
// and its sqrt is correctly rounded (elsewhere sqrt is held to the specification's precision).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <saagen/harness/harness.hpp>
#include <string>
#include <tuple>
#include <vector>

namespace {

using namespace saagen::harness;

// Sets (or unsets, with nullopt) an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, std::optional<std::string> value) : name_(name) {
    if (const char* old = std::getenv(name)) previous_ = old;
    if (value) {
      ::setenv(name, value->c_str(), 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (previous_) {
      ::setenv(name_, previous_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> previous_;
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// The device every run test uses (SAAGEN_VK_DEVICE is honoured). Created once per process and
// destroyed by a gtest environment before main returns: left to static destruction at exit,
// vkDestroyDevice on SwiftShader joins worker threads after the driver's own statics are gone,
// and the process died with SIGSEGV after every test had passed.
std::unique_ptr<VulkanContext> shared;

class SharedContextEnvironment : public ::testing::Environment {
 public:
  void TearDown() override { shared.reset(); }
};
const bool shared_context_environment = [] {
  ::testing::AddGlobalTestEnvironment(new SharedContextEnvironment);
  return true;
}();

VulkanContext& context() {
  if (!shared) {
    shared = std::make_unique<VulkanContext>();
    std::cout << "[harness] " << shared->info().summary() << "\n";
  }
  return *shared;
}

bool on_lavapipe() { return contains(lowercase(context().info().name), "llvmpipe"); }

// GLSL sqrt on any device: Vulkan "Precision and Operation of SPIR-V Instructions": sqrt is
// "inherited from 1.0 / inversesqrt()", inversesqrt is 2 ULP, x / y (here 1.0 / y) 2.5 ULP. An
// ULP of a normal float is at most 2^-23 of it, so the result is r (1 + e2) / (1 + e1) with
// |e1| <= 2 2^-23, |e2| <= 2.5 2^-23: relative error <= 4.5 2^-23 + O(2^-46) (4.51 covers it).
Tolerance sqrt_tolerance() { return Tolerance{0.0, 4.51 * 0x1.0p-23}; }

ShaderDesc glsl_compute(const std::string& source) { return shader_desc(Language::glsl, Stage::compute, source); }

// Deterministic floats in [lo, hi).
std::vector<float> random_floats(std::size_t count, float lo, float hi, unsigned seed) {
  std::mt19937 engine(seed);
  std::uniform_real_distribution<float> distribution(lo, hi);
  std::vector<float> values(count);
  for (float& value : values) value = distribution(engine);
  return values;
}

std::uint32_t groups_for(std::size_t count, std::uint32_t group_size) {
  return static_cast<std::uint32_t>((count + group_size - 1) / group_size);
}

// ---------------------------------------------------------------------------------------------
// Device selection

bool lavapipe_installed() {
  for (const std::string& name : VulkanContext::available_devices())
    if (contains(lowercase(name), "llvmpipe")) return true;
  return false;
}

std::string device_list() {
  std::string list;
  for (const std::string& name : VulkanContext::available_devices()) list += (list.empty() ? "" : "; ") + name;
  return list;
}

// The name with every other letter's case swapped ("NVIDIA H200" -> "nViDiA h200").
std::string mixed_case(std::string name) {
  for (std::size_t i = 0; i < name.size(); i += 2) {
    const auto c = static_cast<unsigned char>(name[i]);
    name[i] = static_cast<char>(std::isupper(c) ? std::tolower(c) : std::toupper(c));
  }
  return name;
}

TEST(HarnessDevice, DefaultIsLavapipe) {
  if (!lavapipe_installed())
    GTEST_SKIP() << "a lavapipe fact: lavapipe (llvmpipe, mesa-vulkan-drivers) is not among this machine's Vulkan devices ("
                 << device_list() << "), so the default is the first CPU device or the first device";
  ContextOptions options;
  options.read_environment = false;  // the default, whatever SAAGEN_VK_DEVICE says
  VulkanContext ctx(options);
  const DeviceInfo& info = ctx.info();
  std::cout << "[harness] " << info.summary() << "\n";
  EXPECT_TRUE(contains(lowercase(info.name), "llvmpipe")) << info.name;
  EXPECT_EQ(info.type, VK_PHYSICAL_DEVICE_TYPE_CPU);
  EXPECT_GE(info.api_version, VK_API_VERSION_1_1);
  EXPECT_TRUE(info.fragment_stores_and_atomics) << "needed by fragment runs that write storage buffers";
  EXPECT_GE(info.subgroup.size, 4u);
  EXPECT_GE(info.max_push_constants_size, 128u);
}

// Every device of the machine, each by its name in mixed case.
TEST(HarnessDevice, SelectsByCaseInsensitiveName) {
  ScopedEnv env(device_env_var, "no-such-device");  // an explicit name wins over the environment
  for (const std::string& name : VulkanContext::available_devices()) {
    VulkanContext ctx(ContextOptions{mixed_case(name)});
    EXPECT_TRUE(contains(lowercase(ctx.info().name), lowercase(name))) << ctx.info().name << " for " << mixed_case(name);
  }
}

TEST(HarnessDevice, SelectsFromEnvironment) {
  for (const std::string& name : VulkanContext::available_devices()) {
    ScopedEnv env(device_env_var, mixed_case(name));
    VulkanContext ctx;
    EXPECT_TRUE(contains(lowercase(ctx.info().name), lowercase(name))) << ctx.info().name << " for " << mixed_case(name);
  }
}

TEST(HarnessDevice, UnknownNameListsAvailableDevices) {
  const std::vector<std::string> available = VulkanContext::available_devices();
  ASSERT_FALSE(available.empty());
  for (const bool through_env : {false, true}) {
    ScopedEnv env(device_env_var, through_env ? std::optional<std::string>("no-such-gpu") : std::nullopt);
    try {
      VulkanContext ctx(ContextOptions{through_env ? "" : "no-such-gpu"});
      FAIL() << "expected an unknown-device error, got " << ctx.info().name;
    } catch (const std::runtime_error& error) {
      const std::string message = error.what();
      EXPECT_TRUE(contains(message, "Vulkan device 'no-such-gpu' not found")) << message;
      EXPECT_TRUE(contains(message, "SAAGEN_VK_DEVICE")) << message;
      EXPECT_TRUE(contains(message, "available devices: " + available.front())) << message;
    }
  }
}

TEST(HarnessDevice, MissingDriverSaysWhatToInstall) {
  // The loader reads these at instance creation; pointing them at nothing hides every driver.
  ScopedEnv icd("VK_ICD_FILENAMES", "/nonexistent/saagen_icd.json");
  ScopedEnv drivers("VK_DRIVER_FILES", "/nonexistent/saagen_icd.json");
  try {
    VulkanContext ctx;
    FAIL() << "expected no device, got " << ctx.info().name;
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_TRUE(contains(message, "no Vulkan device found")) << message;
    EXPECT_TRUE(contains(message, "install mesa-vulkan-drivers")) << message;
  }
}

TEST(HarnessDevice, TakesDeviceFlagFromArgv) {
  std::string storage[] = {"prog", "--device", "llvm", "--gtest_filter=x", "--device=other"};
  char* argv[] = {storage[0].data(), storage[1].data(), storage[2].data(), storage[3].data(), storage[4].data(), nullptr};
  int argc = 5;
  EXPECT_EQ(take_device_flag(argc, argv), "other");  // the last one wins
  ASSERT_EQ(argc, 2);
  EXPECT_EQ(std::string(argv[1]), "--gtest_filter=x");
  EXPECT_EQ(argv[2], nullptr);
}

// ---------------------------------------------------------------------------------------------
// Compute

constexpr std::size_t large_count = 100000;

TEST(HarnessCompute, GlslFmaAndSqrtMatchTheCpuToTheirPrecision) {
  const ShaderDesc shader = glsl_compute(R"(#version 450
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) readonly buffer A { float a[]; };
layout(set = 0, binding = 1) readonly buffer B { float b[]; };
layout(set = 0, binding = 2) readonly buffer C { float c[]; };
layout(set = 0, binding = 3) writeonly buffer Fma { float fma_out[]; };
layout(set = 0, binding = 4) writeonly buffer Sqrt { float sqrt_out[]; };
layout(push_constant) uniform Params { uint count; } params;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= params.count) return;
  fma_out[i] = fma(a[i], b[i], c[i]);
  sqrt_out[i] = sqrt(abs(a[i]));
}
)");
  const std::vector<float> a = random_floats(large_count, -100.0f, 100.0f, 1);
  const std::vector<float> b = random_floats(large_count, -100.0f, 100.0f, 2);
  const std::vector<float> c = random_floats(large_count, -1.0e4f, 1.0e4f, 3);

  ComputeRun run;
  run.shader = shader;
  run.buffers = {input_buffer(0, a), input_buffer(1, b), input_buffer(2, c), output_buffer<float>(3, large_count),
                 output_buffer<float>(4, large_count)};
  run.push_constants = value_bytes(static_cast<std::uint32_t>(large_count));
  run.groups = {groups_for(large_count, 64)};
  const RunResult result = run_compute(context(), run);

  std::vector<double> fused(large_count);
  std::vector<double> unfused(large_count);
  std::vector<double> expected_sqrt(large_count);
  for (std::size_t i = 0; i < large_count; ++i) {
    fused[i] = std::fma(a[i], b[i], c[i]);       // the float overload: a*b+c rounded once
    const volatile float product = a[i] * b[i];  // volatile: rounded to float, never contracted
    unfused[i] = product + c[i];
    expected_sqrt[i] = std::sqrt(std::fabs(a[i]));
  }
  auto describe = [&](std::size_t i) { return "a=" + std::to_string(a[i]) + " b=" + std::to_string(b[i]) + " c=" + std::to_string(c[i]); };
  // Vulkan does not require GLSL fma() (GLSL.std.450 Fma) to be fused: its precision is that of
  // OpFMul followed by OpFAdd (guaranteed fusion needs VK_KHR_shader_fma). Lavapipe in Mesa 22.3
  // rounds twice. So the device must match one of the two CPU models exactly, for every
  // element, and the test reports which.
  const std::vector<float> got_fma = result.buffer_as<float>(3);
  const CompareReport fused_report = compare(got_fma, fused, {}, "glsl fma vs fused", describe);
  const CompareReport unfused_report = compare(got_fma, unfused, {}, "glsl fma vs mul+add", describe);
  EXPECT_EQ(fused_report.compared, large_count);
  EXPECT_TRUE(fused_report.ok() || unfused_report.ok()) << fused_report.summary() << "\n" << unfused_report.summary();
  std::cout << "[harness] GLSL fma() on " << context().info().name << " is "
            << (fused_report.ok()     ? "fused (one rounding)"
                : unfused_report.ok() ? "mul+add (two roundings)"
                                      : "neither")
            << "\n";
  // sqrt is exact on lavapipe (llvm.sqrt -> vsqrtps, correctly rounded): a lavapipe fact.
  // Elsewhere, the specification's precision (sqrt_tolerance).
  const CompareReport sqrt_report =
      compare(result.buffer_as<float>(4), expected_sqrt, on_lavapipe() ? Tolerance{} : sqrt_tolerance(), "glsl sqrt", describe);
  EXPECT_TRUE(sqrt_report.ok()) << sqrt_report.summary();
  EXPECT_GT(result.timing.pipeline_create_ms, 0.0);
  ASSERT_EQ(result.timing.host_ms.size(), 1u);
}

TEST(HarnessCompute, HlslSqrtMatchesTheCpuToItsPrecision) {
  const ShaderDesc shader = shader_desc(Language::hlsl, Stage::compute, R"(
struct Params { uint count; };
[[vk::push_constant]] ConstantBuffer<Params> params;
[[vk::binding(0, 0)]] StructuredBuffer<float> input_values;
[[vk::binding(1, 0)]] RWStructuredBuffer<float> output_values;

[numthreads(64, 1, 1)]
void cs_main(uint3 id : SV_DispatchThreadID) {
  if (id.x >= params.count) return;
  output_values[id.x] = sqrt(input_values[id.x]) * 0.5f + 1.0f;
}
)",
                                        "cs_main");
  const std::vector<float> x = random_floats(large_count, 0.0f, 1.0e6f, 4);
  ComputeRun run;
  run.shader = shader;
  run.buffers = {input_buffer(0, x), output_buffer<float>(1, large_count)};
  run.push_constants = value_bytes(static_cast<std::uint32_t>(large_count));
  run.groups = {groups_for(large_count, 64)};
  const RunResult result = run_compute(context(), run);

  std::vector<double> expected(large_count);
  // Evaluated in float, step by step, as the shader does: *0.5 is exact, so no contraction can
  // change the result even if the compiler fused the multiply-add.
  for (std::size_t i = 0; i < large_count; ++i) expected[i] = std::sqrt(x[i]) * 0.5f + 1.0f;
  // Exact on lavapipe (a lavapipe fact). Elsewhere: sqrt's relative error (sqrt_tolerance) on
  // s / 2 <= r = s / 2 + 1, plus the two correctly rounded additions (the device's and the
  // reference's) differing by at most one ulp of r <= 2^-23 r.
  Tolerance tolerance;
  if (!on_lavapipe()) tolerance.rel_tol = sqrt_tolerance().rel_tol + 0x1.0p-23;
  const CompareReport report =
      compare(result.buffer_as<float>(1), expected, tolerance, "hlsl sqrt", [&](std::size_t i) { return "x=" + std::to_string(x[i]); });
  EXPECT_EQ(report.compared, large_count);
  EXPECT_TRUE(report.ok()) << report.summary();
}

TEST(HarnessCompute, SpecialisationReuseAndTiming) {
  ComputeRun run;
  run.shader = glsl_compute(R"(#version 450
layout(local_size_x = 32) in;
layout(constant_id = 0) const float scale = 1.0;
layout(constant_id = 1) const int offset = 0;
layout(set = 0, binding = 0) buffer Values { float values[]; };
layout(set = 0, binding = 1) writeonly buffer Out { float result[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  result[i] = values[i] * scale + float(offset);
}
)");
  run.shader.spec_constants = {SpecConstant::from_float(0, 3.0f), SpecConstant::from_int(1, -2)};
  const std::size_t count = 256;
  std::vector<float> inputs(count);
  for (std::size_t i = 0; i < count; ++i) inputs[i] = static_cast<float>(i);
  run.buffers = {input_buffer(0, inputs), output_buffer<float>(1, count)};
  run.groups = {groups_for(count, 32)};

  ComputeProgram program(context(), run);
  RunOptions options;
  options.repetitions = 3;
  const RunResult first = program.run(options);
  const std::vector<float> out = first.buffer_as<float>(1);
  for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(out[i], 3.0f * static_cast<float>(i) - 2.0f) << i;

  ASSERT_EQ(first.timing.host_ms.size(), 3u);
  for (double ms : first.timing.host_ms) EXPECT_GT(ms, 0.0);
  if (context().info().timestamps_supported()) {
    ASSERT_EQ(first.timing.gpu_ms.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_GE(first.timing.gpu_ms[i], 0.0);
      // The timestamps are taken inside the submission the host clock brackets.
      EXPECT_LE(first.timing.gpu_ms[i], first.timing.host_ms[i] + 0.5);
    }
  } else {
    EXPECT_TRUE(first.timing.gpu_ms.empty());
  }
  std::cout << "[harness] 256-element dispatch: host median " << Timing::median(first.timing.host_ms) << " ms, gpu median "
            << Timing::median(first.timing.gpu_ms) << " ms, pipeline " << first.timing.pipeline_create_ms << " ms\n";

  // The same pipeline with new inputs, without GPU timestamps.
  std::vector<float> halves(count, 0.5f);
  program.write_buffer(0, to_bytes(halves));
  options = {};
  options.gpu_timestamps = false;
  const RunResult second = program.run(options);
  EXPECT_TRUE(second.timing.gpu_ms.empty());
  const std::vector<float> out2 = second.buffer_as<float>(1);
  EXPECT_EQ(out2.front(), -0.5f);
  EXPECT_EQ(out2.back(), -0.5f);
  EXPECT_THROW(second.buffer(0), std::out_of_range);  // inputs are not read back
}

// ---------------------------------------------------------------------------------------------
// Fragment derivatives and their compute emulation with subgroup quad operations

constexpr std::uint32_t fb_size = 64;
constexpr float field_scale = 1.0f / 64.0f;

struct Derivatives {
  std::vector<float> f;  // f at each pixel, row-major
  std::vector<float> ddx_fine, ddy_fine, ddx_coarse, ddy_coarse;
  std::vector<float> ddx_default, ddy_default;  // dFdx / dFdy (fragment only)
};

// f(x, y) = x*x*y at pixel centres, in fp32; see field() in the shaders.
Derivatives render_derivatives() {
  FragmentRun run;
  run.fragment = shader_desc(Language::glsl, Stage::fragment, R"(#version 450
layout(push_constant) uniform Params { float scale; } params;
layout(location = 0) out vec4 value;    // (frag x, frag y, f, 0)
layout(location = 1) out vec4 fine;     // (dFdxFine, dFdyFine, dFdx, dFdy)
layout(location = 2) out vec4 coarse;   // (dFdxCoarse, dFdyCoarse, 0, 1)
layout(set = 0, binding = 0) writeonly buffer Stored { float stored[]; };  // f again, per pixel
float field(vec2 p) { return p.x * p.x * p.y; }
void main() {
  float f = field(gl_FragCoord.xy * params.scale);
  stored[uint(gl_FragCoord.y) * 64u + uint(gl_FragCoord.x)] = f;
  value = vec4(gl_FragCoord.xy, f, 0.0);
  fine = vec4(dFdxFine(f), dFdyFine(f), dFdx(f), dFdy(f));
  coarse = vec4(dFdxCoarse(f), dFdyCoarse(f), 0.0, 1.0);
}
)");
  run.width = run.height = fb_size;
  run.color_formats = {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT};
  run.push_constants = value_bytes(field_scale);
  run.buffers = {output_buffer<float>(0, std::size_t{fb_size} * fb_size)};
  RunOptions options;
  options.repetitions = 2;
  const RunResult result = run_fragment(context(), run, options);
  EXPECT_EQ(result.attachments.size(), 3u);
  EXPECT_EQ(result.timing.host_ms.size(), 2u);
  EXPECT_EQ(result.timing.gpu_ms.size(), context().info().timestamps_supported() ? 2u : 0u);
  // The fragment stage's storage-buffer writes hold the same f as the attachment.
  const std::vector<float> stored = result.buffer_as<float>(0);

  Derivatives d;
  for (std::uint32_t y = 0; y < fb_size; ++y) {
    for (std::uint32_t x = 0; x < fb_size; ++x) {
      EXPECT_EQ(result.attachments[0].at(x, y, 0), x + 0.5f);
      EXPECT_EQ(result.attachments[0].at(x, y, 1), y + 0.5f);
      d.f.push_back(result.attachments[0].at(x, y, 2));
      EXPECT_EQ(stored[y * fb_size + x], d.f.back());
      d.ddx_fine.push_back(result.attachments[1].at(x, y, 0));
      d.ddy_fine.push_back(result.attachments[1].at(x, y, 1));
      d.ddx_default.push_back(result.attachments[1].at(x, y, 2));
      d.ddy_default.push_back(result.attachments[1].at(x, y, 3));
      d.ddx_coarse.push_back(result.attachments[2].at(x, y, 0));
      d.ddy_coarse.push_back(result.attachments[2].at(x, y, 1));
    }
  }
  return d;
}

// Expected derivatives from the fp32 values of f: fine = difference within the pixel's row
// (ddx) or column (ddy) of its 2x2 quad; coarse = the same differences taken at the quad's
// top-left pixel (top row for ddx, left column for ddy), shared by the whole quad.
struct QuadDifferences {
  std::vector<double> ddx_fine, ddy_fine, ddx_coarse, ddy_coarse;
};

QuadDifferences quad_differences(const std::vector<float>& f) {
  auto at = [&f](std::uint32_t x, std::uint32_t y) { return f[y * fb_size + x]; };
  QuadDifferences q;
  for (std::uint32_t y = 0; y < fb_size; ++y) {
    for (std::uint32_t x = 0; x < fb_size; ++x) {
      const std::uint32_t x0 = x & ~1u;
      const std::uint32_t y0 = y & ~1u;
      q.ddx_fine.push_back(at(x0 + 1, y) - at(x0, y));  // fp32 subtraction, like the device
      q.ddy_fine.push_back(at(x, y0 + 1) - at(x, y0));
      q.ddx_coarse.push_back(at(x0 + 1, y0) - at(x0, y0));
      q.ddy_coarse.push_back(at(x0, y0 + 1) - at(x0, y0));
    }
  }
  return q;
}

std::string pixel_label(std::size_t index) {
  return "(x " + std::to_string(index % fb_size) + ", y " + std::to_string(index / fb_size) + ")";
}

TEST(HarnessFragment, DerivativesAreQuadDifferences) {
  const Derivatives d = render_derivatives();
  // f itself against an fp32 CPU evaluation of the same expression.
  std::vector<double> expected_f;
  for (std::uint32_t y = 0; y < fb_size; ++y) {
    for (std::uint32_t x = 0; x < fb_size; ++x) {
      const float px = (x + 0.5f) * field_scale;
      const float py = (y + 0.5f) * field_scale;
      expected_f.push_back(px * px * py);
    }
  }
  const CompareReport f_report = compare(d.f, expected_f, {}, "f", pixel_label);
  EXPECT_TRUE(f_report.ok()) << f_report.summary();

  const QuadDifferences q = quad_differences(d.f);
  // The field makes the two coarse models distinguishable: ddx changes down a quad, ddy across.
  ASSERT_NE(q.ddx_fine[1 * fb_size + 0], q.ddx_coarse[1 * fb_size + 0]);
  ASSERT_NE(q.ddy_fine[0 * fb_size + 1], q.ddy_coarse[0 * fb_size + 1]);

  // Fine derivatives: exactly the difference within the pixel's quad row / column.
  const CompareReport ddx_fine = compare(d.ddx_fine, q.ddx_fine, {}, "dFdxFine", pixel_label);
  const CompareReport ddy_fine = compare(d.ddy_fine, q.ddy_fine, {}, "dFdyFine", pixel_label);
  EXPECT_TRUE(ddx_fine.ok()) << ddx_fine.summary();
  EXPECT_TRUE(ddy_fine.ok()) << ddy_fine.summary();

  // Coarse derivatives: Vulkan allows one value per quad (here: taken at the top-left pixel) or
  // the fine value. Each device must follow one model everywhere.
  const bool coarse_top_left = compare(d.ddx_coarse, q.ddx_coarse, {}).ok() && compare(d.ddy_coarse, q.ddy_coarse, {}).ok();
  const bool coarse_is_fine = compare(d.ddx_coarse, q.ddx_fine, {}).ok() && compare(d.ddy_coarse, q.ddy_fine, {}).ok();
  const bool default_is_fine = compare(d.ddx_default, q.ddx_fine, {}).ok() && compare(d.ddy_default, q.ddy_fine, {}).ok();
  const bool default_is_coarse = compare(d.ddx_default, d.ddx_coarse, {}).ok() && compare(d.ddy_default, d.ddy_coarse, {}).ok();
  std::cout << "[harness] on " << context().info().name << ": dFdxCoarse/dFdyCoarse are "
            << (coarse_is_fine    ? "per-pixel (= fine)"
                : coarse_top_left ? "per quad, from the top-left pixel"
                                  : "neither")
            << "; dFdx/dFdy are "
            << (default_is_fine     ? "fine"
                : default_is_coarse ? "coarse"
                                    : "neither")
            << "\n";
  EXPECT_TRUE(coarse_top_left || coarse_is_fine)
      << compare(d.ddx_coarse, q.ddx_coarse, {}, "dFdxCoarse vs top-left", pixel_label).summary() << "\n"
      << compare(d.ddx_coarse, q.ddx_fine, {}, "dFdxCoarse vs fine", pixel_label).summary();
  EXPECT_TRUE(default_is_fine || default_is_coarse);
  if (contains(lowercase(context().info().name), "llvmpipe")) {
    // Documented lavapipe behaviour (Mesa 22.3): gallivm computes every derivative per pixel
    // row/column of the quad, so coarse == fine == default.
    EXPECT_TRUE(coarse_is_fine);
    EXPECT_TRUE(default_is_fine);
  }
}

TEST(HarnessCompute, SubgroupQuadDerivativesMatchFragment) {
  const SubgroupInfo& subgroup = context().info().subgroup;
  ASSERT_TRUE(subgroup.supports(VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_QUAD_BIT, VK_SHADER_STAGE_COMPUTE_BIT))
      << context().info().name << " does not support subgroup quad operations in compute shaders (" << subgroup.describe()
      << "): 2x2-quad derivatives cannot be emulated in compute on this device";
  ASSERT_EQ(subgroup.size % 4, 0u) << subgroup.describe();

  ComputeRun run;
  run.shader = glsl_compute(R"(#version 450
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_quad : require
layout(local_size_x = 64) in;
layout(push_constant) uniform Params { float scale; uint width; } params;
layout(set = 0, binding = 0) writeonly buffer Out { vec4 derivatives[]; };  // per pixel
float field(vec2 p) { return p.x * p.x * p.y; }
void main() {
  // Quads are 4 consecutive subgroup invocations; lane bit 0 is x, bit 1 is y within the quad.
  uint linear = gl_WorkGroupID.x * gl_WorkGroupSize.x + gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
  uint lane = gl_SubgroupInvocationID & 3u;
  uint quad = linear >> 2;
  uint quads_per_row = params.width / 2u;
  uint x = (quad % quads_per_row) * 2u + (lane & 1u);
  uint y = (quad / quads_per_row) * 2u + (lane >> 1u);
  float f = field((vec2(x, y) + 0.5) * params.scale);
  float horizontal = subgroupQuadSwapHorizontal(f);
  float vertical = subgroupQuadSwapVertical(f);
  float ddx_fine = (lane & 1u) != 0u ? f - horizontal : horizontal - f;
  float ddy_fine = (lane & 2u) != 0u ? f - vertical : vertical - f;
  float top_left = subgroupQuadBroadcast(f, 0u);
  float ddx_coarse = subgroupQuadBroadcast(f, 1u) - top_left;
  float ddy_coarse = subgroupQuadBroadcast(f, 2u) - top_left;
  derivatives[y * params.width + x] = vec4(ddx_fine, ddy_fine, ddx_coarse, ddy_coarse);
}
)");
  struct Params {
    float scale;
    std::uint32_t width;
  };
  const std::size_t pixels = std::size_t{fb_size} * fb_size;
  run.buffers = {output_buffer<float>(0, 4 * pixels)};
  run.push_constants = value_bytes(Params{field_scale, fb_size});
  run.groups = {groups_for(pixels, 64)};
  const std::vector<float> out = run_compute(context(), run).buffer_as<float>(0);

  // Fine: must equal the fragment shader's dFdxFine/dFdyFine bit for bit. Coarse (emulated
  // with the top-left convention): must equal the top-left quad differences of the fragment's f
  // (on lavapipe the fragment's own dFdxCoarse is per pixel, see DerivativesAreQuadDifferences).
  const Derivatives fragment = render_derivatives();
  const QuadDifferences model = quad_differences(fragment.f);
  const std::vector<double> fine_x(fragment.ddx_fine.begin(), fragment.ddx_fine.end());
  const std::vector<double> fine_y(fragment.ddy_fine.begin(), fragment.ddy_fine.end());
  const std::vector<double>* expected_columns[4] = {&fine_x, &fine_y, &model.ddx_coarse, &model.ddy_coarse};
  const char* names[4] = {"quad ddx fine vs dFdxFine", "quad ddy fine vs dFdyFine", "quad ddx coarse vs top-left",
                          "quad ddy coarse vs top-left"};
  for (int column = 0; column < 4; ++column) {
    std::vector<float> got(pixels);
    for (std::size_t i = 0; i < pixels; ++i) got[i] = out[4 * i + column];
    const CompareReport report = compare(got, *expected_columns[column], {}, names[column], pixel_label);
    EXPECT_EQ(report.compared, pixels);
    EXPECT_TRUE(report.ok()) << report.summary();
  }
}

// ---------------------------------------------------------------------------------------------
// Sampled images

// Texel value of (level, layer, x): all four channels identify it.
std::array<float, 4> texel_id(std::uint32_t level, std::uint32_t layer, std::uint32_t x) {
  return {static_cast<float>(level), static_cast<float>(layer), static_cast<float>(x), static_cast<float>(1000 * level + 100 * layer + x)};
}

TEST(HarnessImage, Sampled1DArrayWithMipsNearest) {
  constexpr std::uint32_t width = 16, layers = 3, levels = 5;  // 16, 8, 4, 2, 1
  ImageBinding image;
  image.binding = 0;
  image.image.kind = ImageKind::image_1d_array;
  image.image.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  image.image.width = width;
  image.image.layers = layers;
  for (std::uint32_t level = 0; level < levels; ++level) {
    std::vector<float> texels;
    for (std::uint32_t layer = 0; layer < layers; ++layer) {
      for (std::uint32_t x = 0; x < (width >> level); ++x) {
        for (float v : texel_id(level, layer, x)) texels.push_back(v);
      }
    }
    image.image.levels.push_back(to_bytes(texels));
  }
  image.sampler.address(VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT);  // nearest filter and mip mode by default

  // Queries (u, layer, level, mode): mode 0 = textureLod, 1 = textureGrad with a gradient whose
  // footprint is 2^level texels of level 0.
  struct Query {
    float u, layer, level, mode;
  };
  std::vector<Query> queries;
  std::vector<std::array<float, 4>> expected;
  for (std::uint32_t level = 0; level < levels; ++level) {
    const std::uint32_t level_width = width >> level;
    for (std::uint32_t layer = 0; layer < layers; ++layer) {
      for (std::uint32_t x = 0; x < level_width; ++x) {
        const float centre = (static_cast<float>(x) + 0.5f) / static_cast<float>(level_width);
        for (float mode : {0.0f, 1.0f}) {
          queries.push_back({centre, static_cast<float>(layer), static_cast<float>(level), mode});
          expected.push_back(texel_id(level, layer, x));
          // Mirrored repeat: u in (1, 2) reads texel (w - 1 - x).
          queries.push_back({2.0f - centre, static_cast<float>(layer), static_cast<float>(level), mode});
          expected.push_back(texel_id(level, layer, x));
          queries.push_back({1.0f + centre, static_cast<float>(layer), static_cast<float>(level), mode});
          expected.push_back(texel_id(level, layer, level_width - 1 - x));
        }
      }
    }
  }

  ComputeRun run;
  run.shader = glsl_compute(R"(#version 450
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler1DArray image;
layout(set = 0, binding = 1) readonly buffer Queries { vec4 queries[]; };
layout(set = 0, binding = 2) writeonly buffer Results { vec4 results[]; };
layout(push_constant) uniform Params { uint count; float width; } params;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= params.count) return;
  vec4 q = queries[i];
  vec2 coord = vec2(q.x, q.y);
  if (q.w == 0.0) {
    results[i] = textureLod(image, coord, q.z);
  } else {
    float gradient = exp2(q.z) / params.width;  // lod = log2(|dPdx| * width) = level
    results[i] = textureGrad(image, coord, gradient, 0.0);
  }
}
)");
  run.images = {image};
  run.buffers = {input_buffer(1, queries), output_buffer<float>(2, 4 * queries.size())};
  struct Params {
    std::uint32_t count;
    float width;
  };
  run.push_constants = value_bytes(Params{static_cast<std::uint32_t>(queries.size()), static_cast<float>(width)});
  run.groups = {groups_for(queries.size(), 64)};
  const std::vector<float> got = run_compute(context(), run).buffer_as<float>(2);

  std::vector<double> flat_expected;
  for (const auto& texel : expected) flat_expected.insert(flat_expected.end(), texel.begin(), texel.end());
  const CompareReport report = compare(got, flat_expected, {}, "1D array texels", [&](std::size_t i) {
    const Query& q = queries[i / 4];
    return "(u " + std::to_string(q.u) + ", layer " + std::to_string(q.layer) + ", level " + std::to_string(q.level) +
           (q.mode == 0.0f ? ", textureLod)" : ", textureGrad)");
  });
  EXPECT_EQ(report.compared, 4 * queries.size());
  EXPECT_TRUE(report.ok()) << report.summary();
}

TEST(HarnessImage, Sampled2DHalfFloatLinear) {
  // 4x2 RGBA16F image, 2 levels; sampled with bilinear filtering at texel centres (exact texel)
  // and half-way between two texels of a row (their average, exact in fp16/fp32).
  ImageBinding image;
  image.binding = 0;
  image.image.kind = ImageKind::image_2d;
  image.image.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  image.image.width = 4;
  image.image.height = 2;
  auto level_bytes = [](std::uint32_t w, std::uint32_t h, float base) {
    std::vector<std::uint16_t> halves;
    for (std::uint32_t y = 0; y < h; ++y) {
      for (std::uint32_t x = 0; x < w; ++x) {
        for (float v : {base + static_cast<float>(x), base + 10.0f * static_cast<float>(y), base, 1.0f}) {
          halves.push_back(float_to_half(v));
        }
      }
    }
    return to_bytes(halves);
  };
  image.image.levels = {level_bytes(4, 2, 0.0f), level_bytes(2, 1, 100.0f)};
  image.sampler.mag_filter = image.sampler.min_filter = VK_FILTER_LINEAR;

  ComputeRun run;
  run.shader = glsl_compute(R"(#version 450
layout(local_size_x = 4) in;
layout(set = 0, binding = 0) uniform sampler2D image;
layout(set = 0, binding = 1) writeonly buffer Results { vec4 results[]; };
void main() {
  results[0] = textureLod(image, vec2(1.5 / 4.0, 0.5 / 2.0), 0.0);  // texel (1, 0)
  results[1] = textureLod(image, vec2(2.0 / 4.0, 1.5 / 2.0), 0.0);  // between (1, 1) and (2, 1)
  results[2] = textureLod(image, vec2(0.75, 0.5), 1.0);             // level 1 texel (1, 0)
  results[3] = textureLod(image, vec2(0.5, 0.5), 1.0);              // between level 1 texels
}
)");
  run.images = {image};
  run.buffers = {output_buffer<float>(1, 16)};
  const std::vector<float> got = run_compute(context(), run).buffer_as<float>(1);
  const std::vector<double> expected = {1.0, 0.0, 0.0, 1.0, 1.5, 10.0, 0.0, 1.0, 101.0, 100.0, 100.0, 1.0, 100.5, 100.0, 100.0, 1.0};
  const CompareReport report = compare(got, expected, {}, "RGBA16F bilinear");
  EXPECT_TRUE(report.ok()) << report.summary();
}

// ---------------------------------------------------------------------------------------------
// Host-only helpers

TEST(HarnessCompare, ToleranceNanAndInfinity) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> got = {1.0f, 2.0f, nan, inf, -inf, nan, 5.0f, 100.5f};
  const std::vector<double> expected = {
      1.0, 2.001, 3.0, static_cast<double>(inf), static_cast<double>(-inf), std::nan(""), static_cast<double>(inf), 100.0};
  const CompareReport report = compare(got, expected, {0.01, 0.001}, "mixed", [](std::size_t i) { return "label" + std::to_string(i); });
  EXPECT_EQ(report.compared, 8u);
  // Fail: NaN for 3.0 (#2), 5 for +inf (#6), 100.5 for 100 (0.5 > 0.01 + 0.1). Pass: the rest.
  EXPECT_EQ(report.failing, 3u);
  EXPECT_EQ(report.worst_index, 2u);  // the first infinite error
  EXPECT_TRUE(std::isinf(report.worst_normalised_error));
  EXPECT_EQ(report.worst_label, "label2");
  EXPECT_TRUE(contains(report.summary(), "mixed: 3 of 8 failing")) << report.summary();
  EXPECT_TRUE(contains(report.summary(), "worst #2 label2: got nan, expected 3")) << report.summary();

  const std::vector<float> close = {100.05f};
  const std::vector<double> hundred = {100.0};
  const CompareReport within = compare(close, hundred, {0.01, 0.001});
  EXPECT_TRUE(within.ok()) << within.summary();
  EXPECT_NEAR(within.worst_normalised_error, (100.05f - 100.0) / 0.11, 1e-9);
  EXPECT_FALSE(compare(close, hundred, {}).ok());  // zero tolerance means exact
  EXPECT_THROW(compare(close, expected, {}), std::invalid_argument);
}

TEST(HarnessErrors, VulkanFailuresNameFunctionAndResult) {
  EXPECT_NO_THROW(check_vk(VK_SUCCESS, "vkCreateBuffer(device, &info, nullptr, &buffer)"));
  try {
    check_vk(VK_ERROR_DEVICE_LOST, "vkQueueWaitIdle(context.queue())");  // what SAAGEN_VK_CHECK passes
    FAIL() << "expected a throw";
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), "vkQueueWaitIdle failed: VK_ERROR_DEVICE_LOST");
  }
  EXPECT_EQ(vk_result_name(VK_ERROR_OUT_OF_DEVICE_MEMORY), "VK_ERROR_OUT_OF_DEVICE_MEMORY");
  EXPECT_EQ(vk_result_name(static_cast<VkResult>(-12345)), "VkResult(-12345)");
}

TEST(HarnessErrors, BadDescriptionsAreRejectedBeforeVulkan) {
  ImageBinding image;
  image.image.kind = ImageKind::image_2d;
  image.image.width = 4;
  image.image.height = 4;
  image.image.levels = {Bytes(4 * 4 * 16), Bytes(10)};  // level 1 should hold 2*2*16 bytes
  ComputeRun run;
  run.shader.spirv = {0x07230203u, 0x00010300u, 0u, 1u, 0u};  // never reached
  run.images = {image};
  try {
    ComputeProgram program(context(), run);
    FAIL() << "expected a description error";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()), "sampled image at binding 0: level 1 has 10 bytes, expected 64");
  }
  run.images.clear();
  run.buffers = {output_buffer<float>(3, 4), output_buffer<float>(3, 4)};
  EXPECT_THROW(ComputeProgram(context(), run), std::invalid_argument);  // binding 3 twice
  run.buffers = {output_buffer<float>(0, 4)};
  run.push_constants = Bytes(6);
  EXPECT_THROW(ComputeProgram(context(), run), std::invalid_argument);  // not a multiple of 4
}

TEST(HarnessBytes, HalfConversionRoundTripsAndRounds) {
  for (std::uint32_t bits = 0; bits < 0x10000u; ++bits) {
    const float value = half_to_float(static_cast<std::uint16_t>(bits));
    if (std::isnan(value)) continue;
    ASSERT_EQ(float_to_half(value), bits) << bits;
  }
  EXPECT_EQ(half_to_float(0x3c00u), 1.0f);
  EXPECT_EQ(half_to_float(0x0001u), std::ldexp(1.0f, -24));             // smallest subnormal
  EXPECT_EQ(float_to_half(1.0f + std::ldexp(1.0f, -11)), 0x3c00u);      // tie -> even (down)
  EXPECT_EQ(float_to_half(1.0f + 3 * std::ldexp(1.0f, -11)), 0x3c02u);  // tie -> even (up)
  EXPECT_EQ(float_to_half(65520.0f), 0x7c00u);                          // rounds to infinity
  EXPECT_EQ(float_to_half(std::ldexp(1.0f, -25)), 0x0000u);             // tie with zero -> zero
  EXPECT_EQ(float_to_half(std::ldexp(1.5f, -25)), 0x0001u);
  EXPECT_TRUE(std::isnan(half_to_float(float_to_half(std::nanf("")))));
}

}  // namespace
