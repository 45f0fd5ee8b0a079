// The adversarial sweep on lavapipe. Every public function of every variant, for every
// target, runs over 2^20 (> 10^6) adversarial inputs (stability_inputs.hpp) in its guarded form
// (saagen's default emission) and in the unguarded paper form, on the same inputs, each with the
// device's min/max/clamp and with NaN-propagating ones ("strict": strict_nan_prelude, which
// exposes a NaN that lavapipe's min(NaN, x) = x would hide). Core and
// evaluate functions run in compute kernels (load_call_store_body); fragment wrappers run in
// quad-emulating compute kernels (2x2 quads of a 1024 x 1024 image, per-pixel fields loaded from
// the buffer, plain ddx/ddy coarse).
//
// Every output is judged with the function's claim (stability_claims.hpp) and counted as
// non-finite or out of bound, split by input class: finite inputs (the claim's domain) and
// inputs with an Inf/NaN component (nothing is claimed). The test prints one table per variant
// and target (docs/STABILITY.md) and fails on any guarded violation with finite inputs, under
// either semantics; the unguarded counts show what each guard prevents.
#include "stability_claims.hpp"
#include "stability_inputs.hpp"
#include "support/gpu_support.hpp"

#include <chrono>

namespace {

namespace ref = saagen::ref;
namespace stab = saagen::stability;
using saagen::Catalogue;

constexpr std::uint32_t kElements = 1u << 20;  // per function, target and form
constexpr std::uint32_t kWidth = 1024;         // the emulated image of the wrapper kernels
constexpr std::uint32_t kNonFiniteOneIn = 8;   // elements (quads) with an injected Inf/NaN

struct Counts {
  std::uint64_t inputs = 0, non_finite = 0, out_of_bound = 0;
  std::uint64_t violations() const { return non_finite + out_of_bound; }
};

struct Tally {
  Counts finite;                      // every input component finite (the claim's domain)
  Counts non_finite;                  // some input component +-Inf or NaN
  std::vector<std::string> examples;  // the first guarded violations with finite inputs
};

// The inputs of one function: the buffer, and per element whether an input was non-finite.
struct SweepInputs {
  std::vector<float> data;
  std::vector<std::uint8_t> non_finite;  // per element (pixel)
  stab::Layout layout;
  std::uint32_t outputs = 0;
};

SweepInputs core_inputs(const saagen::Function& function, std::uint64_t seed) {
  SweepInputs in;
  in.layout = stab::layout_of(function);
  in.outputs = saagen::component_count(function.return_type);
  in.data.reserve(std::size_t{kElements} * in.layout.stride);
  in.non_finite.resize(kElements);
  stab::Rng rng(seed);
  for (std::uint32_t e = 0; e < kElements; ++e) {
    stab::pack_core_element(function, rng, in.data);
    if (rng.chance(kNonFiniteOneIn)) {
      stab::inject_non_finite(rng, in.data.data() + std::size_t{e} * in.layout.stride, in.layout.stride);
      in.non_finite[e] = 1;
    }
  }
  return in;
}

SweepInputs wrapper_inputs(const saagen::Function& wrapper, std::uint64_t seed) {
  SweepInputs in;
  in.layout = stab::layout_of(wrapper);
  in.outputs = saagen::component_count(wrapper.return_type);
  const std::uint32_t stride = in.layout.stride;
  in.data.assign(std::size_t{kElements} * stride, 0.0f);
  in.non_finite.resize(kElements);
  stab::Rng rng(seed);
  std::vector<float> pixels[4];
  for (std::uint32_t quad = 0; quad < kElements / 4; ++quad) {
    for (auto& p : pixels) p.clear();
    stab::pack_wrapper_quad(wrapper, rng, pixels);
    const bool inject = rng.chance(kNonFiniteOneIn);
    const int victim = static_cast<int>(rng.below(4));
    for (int p = 0; p < 4; ++p) {
      const std::uint32_t index = stab::quad_pixel_index(quad, p, kWidth);
      std::copy(pixels[p].begin(), pixels[p].end(), in.data.begin() + std::size_t{index} * stride);
      if (inject && p == victim) stab::inject_non_finite(rng, in.data.data() + std::size_t{index} * stride, stride);
      in.non_finite[index] = inject;
    }
  }
  return in;
}

std::string describe_element(const SweepInputs& in, std::uint32_t e, const float* out) {
  std::string text = "inputs (";
  for (std::uint32_t k = 0; k < in.layout.stride; ++k)
    text += fmt::format("{}{:.9g}", k ? ", " : "", in.data[std::size_t{e} * in.layout.stride + k]);
  text += ") -> (";
  for (std::uint32_t k = 0; k < in.outputs; ++k) text += fmt::format("{}{:.9g}", k ? ", " : "", out[std::size_t{e} * in.outputs + k]);
  return text + ")";
}

// A wrapper's pixel with the fields of its whole quad (the derivatives read them all).
std::string describe_pixel(const SweepInputs& in, std::uint32_t index, const float* out) {
  const std::uint32_t x = index % kWidth, y = index / kWidth;
  std::string text = fmt::format("pixel ({}, {}) ", x, y) + describe_element(in, index, out) + "; quad:";
  for (int p = 0; p < 4; ++p) {
    const std::uint32_t q = (y & ~1u) * kWidth + (x & ~1u) + (p & 1) + (p >> 1) * kWidth;
    text += fmt::format(" [{}] (", p);
    for (std::uint32_t k = 0; k < in.layout.stride; ++k)
      text += fmt::format("{}{:.9g}", k ? ", " : "", in.data[std::size_t{q} * in.layout.stride + k]);
    text += ")";
  }
  return text;
}

// The dispatch of one function over its inputs, the same in each of the four forms but for the
// shader: the input buffer is built once per function, not once per form.
struct Dispatch {
  saagen::KernelRequest request;
  saagen::harness::ComputeRun run;
};

Dispatch prepare_dispatch(const saagen::Function& function, const SweepInputs& in) {
  Dispatch dispatch;
  saagen::KernelRequest& request = dispatch.request;
  if (function.role == saagen::FunctionRole::fragment) {
    request.kind = saagen::KernelKind::quad_compute;
    request.width = kWidth;
    request.output_stride = in.outputs;
    request.body = stab::wrapper_body(function, in.layout.stride);
  } else {
    request.body = saagen::load_call_store_body(Catalogue::builtin(), function.name, request);
  }
  dispatch.run.buffers.push_back(saagen::harness::input_buffer(0, in.data));
  dispatch.run.buffers.push_back(saagen::harness::output_buffer<float>(1, std::size_t{kElements} * in.outputs));
  dispatch.run.groups = {kElements / request.workgroup_size, 1, 1};
  return dispatch;
}

// Runs `function` (a core/evaluate function or a wrapper) of `file` over the inputs and judges
// every output.
Tally sweep(const saagen::EmittedFile& file, const saagen::Function& function, const SweepInputs& in, Dispatch& dispatch,
            bool keep_examples) {
  const bool wrapper = function.role == saagen::FunctionRole::fragment;
  dispatch.run.shader.spirv = saagen::test::compile_kernel(file, dispatch.request);
  const auto result = saagen::harness::run_compute(saagen::test::gpu(), dispatch.run);
  const auto out = result.buffer_as<float>(1);

  const stab::Claim claim = stab::claim_of(function.name);
  const double kappa = 0.18;
  Tally tally;
  double alpha2[2] = {0.0, 0.0}, values[3];
  for (std::uint32_t e = 0; e < kElements; ++e) {
    const float* element = in.data.data() + std::size_t{e} * in.layout.stride;
    for (std::uint32_t k = 0; k < in.layout.alpha2_count; ++k) alpha2[k] = element[in.layout.alpha2_offset + k];
    for (std::uint32_t k = 0; k < in.outputs; ++k) values[k] = out[std::size_t{e} * in.outputs + k];
    const stab::Verdict verdict = stab::judge(claim, kappa, {alpha2, in.layout.alpha2_count}, {values, in.outputs});
    Counts& counts = in.non_finite[e] ? tally.non_finite : tally.finite;
    ++counts.inputs;
    counts.non_finite += verdict.non_finite;
    counts.out_of_bound += verdict.out_of_bound;
    if (keep_examples && !in.non_finite[e] && !verdict.ok() && tally.examples.size() < 5) {
      tally.examples.push_back(stab::judge(claim, kappa, {alpha2, in.layout.alpha2_count}, {values, in.outputs}, true).why + ": " +
                               (wrapper ? describe_pixel(in, e, out.data()) : describe_element(in, e, out.data())));
    }
  }
  return tally;
}

struct SweepCase {
  std::string target;
  std::string variant;
};

void PrintTo(const SweepCase& c, std::ostream* os) { *os << c.target << " " << c.variant; }

class AdversarialSweep : public ::testing::TestWithParam<SweepCase> {};

std::string counts_cell(const Counts& c) { return fmt::format("{:>7} {:>7} {:>8}", c.inputs, c.non_finite, c.out_of_bound); }

// The four forms each function runs in: guarded or paper, with the device's min/max/clamp or
// with NaN-propagating ones (strict_nan_prelude).
struct Form {
  bool guards;
  bool strict;
  std::string name() const { return std::string(guards ? "guarded" : "paper") + (strict ? " strict" : ""); }
};
constexpr Form kForms[] = {{true, false}, {true, true}, {false, false}, {false, true}};

TEST_P(AdversarialSweep, GuardedFormKeepsEveryClaimOnFiniteInputs) {
  const SweepCase& c = GetParam();
  const saagen::Variant& variant = *Catalogue::builtin().find_variant(c.variant);
  saagen::EmittedFile files[4];
  for (int f = 0; f < 4; ++f) {
    files[f] = saagen::test::emit_variant(c.target, c.variant, "fp32", kForms[f].guards);
    if (kForms[f].strict) files[f].content = stab::strict_nan_prelude(c.target) + files[f].content;
  }
  const auto start = std::chrono::steady_clock::now();

  std::string table = fmt::format(
      "\n[ sweep    ] {} {}: {} inputs per function and form; columns per input class: inputs, non-finite outputs, out-of-bound outputs\n",
      c.target, c.variant, kElements);
  table += fmt::format("[ sweep    ] {:<36} {:<14} | {:^25} | {:^25}\n", "function", "form", "finite inputs", "non-finite inputs");
  Counts variant_totals[4][2];  // [form][class]
  std::vector<std::string> failures;
  std::uint64_t seed = 1469598103934665603ull;  // FNV-1a of the variant id: reproducible seeds
  for (const char ch : c.variant) seed = (seed ^ static_cast<unsigned char>(ch)) * 1099511628211ull;
  for (const std::string& name : variant.functions) {
    const saagen::Function& function = *Catalogue::builtin().find_function(name);
    const bool wrapper = function.role == saagen::FunctionRole::fragment;
    const SweepInputs in = wrapper ? wrapper_inputs(function, ++seed) : core_inputs(function, ++seed);
    Dispatch dispatch = prepare_dispatch(function, in);
    for (int f = 0; f < 4; ++f) {
      const Form& form = kForms[f];
      const Tally tally = sweep(files[f], function, in, dispatch, form.guards);
      table += fmt::format("[ sweep    ] {:<36} {:<14} | {} | {}\n", name, form.name(), counts_cell(tally.finite),
                           counts_cell(tally.non_finite));
      for (int cls = 0; cls < 2; ++cls) {
        const Counts& from = cls == 0 ? tally.finite : tally.non_finite;
        Counts& to = variant_totals[f][cls];
        to.inputs += from.inputs, to.non_finite += from.non_finite, to.out_of_bound += from.out_of_bound;
      }
      if (form.guards && tally.finite.violations() > 0) {
        failures.push_back(fmt::format("{} {} {}: {} non-finite and {} out-of-bound outputs on finite inputs ({})", c.target, name,
                                       form.name(), tally.finite.non_finite, tally.finite.out_of_bound,
                                       stab::describe(stab::claim_of(name))));
        for (const std::string& example : tally.examples) failures.push_back("    " + example);
      }
    }
  }
  for (int f = 0; f < 4; ++f) {
    table += fmt::format("[ sweep    ] {:<36} {:<14} | {} | {}\n", "TOTAL " + c.variant, kForms[f].name(),
                         counts_cell(variant_totals[f][0]), counts_cell(variant_totals[f][1]));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << table << fmt::format("[ sweep    ] {:.1f} s\n", seconds);
  for (const std::string& failure : failures) ADD_FAILURE() << failure;
}

std::vector<SweepCase> sweep_cases() {
  std::vector<SweepCase> cases;
  for (const std::string target : {"glsl", "hlsl"}) {
    for (const saagen::Variant& variant : Catalogue::builtin().variants()) cases.push_back({target, variant.id});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryVariant, AdversarialSweep, ::testing::ValuesIn(sweep_cases()), [](const auto& info) {
  std::string name = info.param.target + "_" + info.param.variant;
  for (char& ch : name) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return name;
});

}  // namespace
