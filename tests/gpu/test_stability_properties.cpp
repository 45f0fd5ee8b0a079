// Property-based tests (rapidcheck) of the stability guarantees (stability_claims.hpp),
// on the double-precision reference and on the emitted code run through the harness.
//
// Each property is written once against an Evaluator: the reference (saagen::ref, Params{}:
// guarded, fp32 guard constants, and the half-precision constants too), or the emitted guarded
// fp32 code of a target on the Vulkan device, which evaluates a whole rapidcheck-generated batch
// (256..2048 elements or quads) in one compute dispatch. Properties, for every variant:
//  - Claims: outputs finite for finite inputs of any magnitude (0, denormals, 1e-30 .. FLT_MAX,
//    h_z = 0 or < 0, zero or non-orthogonal frames); saturating variants in [min(a, 1), 1] with
//    a' - a <= kappa; projected space in [saturate(a), 1]; forward-aniso A symmetric PSD with
//    A00 >= ax^2, A11 >= ay^2; BRDF values >= 0 (inputs in the BRDF domain of
//    stability_inputs.hpp).
//  - Monotone: scaling the derivatives by s >= 1 never lowers alpha'^2; for the roughness matrix
//    A(s d) - A(d) is PSD while s |d| <= DERIVATIVE_MAX, and its diagonal never decreases.
//  - Isotropy: deferred-max, -sum, -avg, -projected-space (and deferred-max's wrapper, whose tangent
//    frame is rotated about the normal) are invariant under rotation of the frame; the
//    forward-aniso matrix with ax = ay keeps its trace and largest eigenvalue. deferred-previous
//    is not invariant (a rectangle), shown by a counterexample.
//  - The guards change nothing where the paper form is fine (reference), and the emitted guarded
//    code matches the guarded reference on adversarial inputs (GPU).
//
// Built twice: test_stability_properties (the reference; SAAGEN_STABILITY_DEVICE 0, no Vulkan)
// and test_stability_properties_gpu (the emitted code on the device; SAAGEN_STABILITY_DEVICE 1).
#if SAAGEN_STABILITY_DEVICE
#include "support/gpu_support.hpp"
#else
#include "saagen/front/catalogue.hpp"
#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#endif
#include "stability_claims.hpp"
#include "stability_inputs.hpp"
#include "stability_names.hpp"
#include "support/reference_dispatch.hpp"

#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cfloat>
#include <map>
#include <memory>
#include <sstream>

namespace {

using namespace saagen::stability::short_names;

using Element = std::vector<double>;  // a core function's inputs, or a wrapper quad's fields (4 x stride)
using Values = std::vector<double>;   // one function output (1 to 3 components)

constexpr int kCpuCases = 2000;  // rapidcheck cases per CPU property (one element each)
constexpr int kGpuCases = 12;    // rapidcheck cases per GPU property (one batch each)
constexpr int kMinBatch = 256, kMaxBatch = 2048;

// Runs a rapidcheck property with `cases` successful cases (RC_PARAMS still sets seed etc.).
// Batches are not shrunk (each step would be a dispatch; the failure names its element anyway).
template <class Testable>
void check_property(const std::string& name, int cases, Testable&& testable, bool shrink = true) {
  rc::detail::TestParams params = rc::detail::configuration().testParams;
  params.maxSuccess = cases;
  params.disableShrinking = params.disableShrinking || !shrink;
  rc::detail::TestMetadata metadata;
  metadata.id = ::testing::UnitTest::GetInstance()->current_test_info()->name() + std::string("/") + name;
  metadata.description = name;
  const auto result = rc::detail::checkTestable(std::forward<Testable>(testable), metadata, params);
  if (!result.template is<rc::detail::SuccessResult>()) {
    std::ostringstream message;
    rc::detail::printResultMessage(result, message);
    ADD_FAILURE() << name << ": " << message.str();
  }
}

double as_float(double v) { return static_cast<double>(static_cast<float>(v)); }

// ---------------------------------------------------------------------------------------------
// Generators (every value fp32-representable, so that reference and device see the same input)

rc::Gen<double> gen_component() {
  return rc::gen::map(
      rc::gen::pair(rc::gen::oneOf(rc::gen::element(0.0, 1e-40, 1e-30, 1e-6, 1.0, 1e6, 1e9, 1e10, 1e19, 1e30, double(FLT_MAX)),
                                   rc::gen::map(rc::gen::inRange(-450, 385), [](int e) { return std::pow(10.0, e / 10.0); })),
                    rc::gen::arbitrary<bool>()),
      [](std::pair<double, bool> v) { return as_float(v.second ? -v.first : v.first); });
}

rc::Gen<double> gen_filter_alpha2() {
  return rc::gen::map(rc::gen::oneOf(rc::gen::element(0.0, 1.0, 4.0),
                                     rc::gen::map(rc::gen::inRange(-400, 1), [](int e) { return std::pow(10.0, e / 50.0); }),
                                     rc::gen::map(rc::gen::inRange(100, 401), [](int e) { return e / 100.0; })),
                      as_float);
}

rc::Gen<double> gen_brdf_alpha2() {
  return rc::gen::map(
      rc::gen::oneOf(rc::gen::element(1e-8, 1.0), rc::gen::map(rc::gen::inRange(-400, 1), [](int e) { return std::pow(10.0, e / 50.0); })),
      as_float);
}

Vec3 direction_from(double z, double phi) {
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

rc::Gen<double> gen_z() {
  return rc::gen::map(rc::gen::pair(rc::gen::oneOf(rc::gen::element(0.0, 1e-30, 1e-20, 1e-10, 1e-7, 1e-4, 1e-2, 1.0),
                                                   rc::gen::map(rc::gen::inRange(0, 1001), [](int k) { return k / 1000.0; })),
                                    rc::gen::arbitrary<bool>()),
                      [](std::pair<double, bool> v) { return v.second ? -v.first : v.first; });
}

rc::Gen<double> gen_angle() {
  return rc::gen::map(rc::gen::inRange(0, 3600), [](int k) { return k * std::numbers::pi / 1800.0; });
}

rc::Gen<Vec3> gen_direction() {
  return rc::gen::map(rc::gen::pair(gen_z(), gen_angle()), [](std::pair<double, double> v) { return direction_from(v.first, v.second); });
}

void push(Element& e, double v) { e.push_back(as_float(v)); }
void push(Element& e, Vec2 v) { push(e, v.x), push(e, v.y); }
void push(Element& e, Vec3 v) { push(e, v.x), push(e, v.y), push(e, v.z); }
void push(Element& e, Sym2 m) { push(e, m.xx), push(e, m.xy), push(e, m.yy); }

// Toksvig's mean-normal length: (0, 1] with its edges, and any finite value (stability_inputs.hpp).
rc::Gen<double> gen_mean_length() {
  return rc::gen::oneOf(rc::gen::element(0.0, 1e-45, 1e-30, 1e-7, 0.5, 1.0, 1.0 + 0x1p-23, 2.0),
                        rc::gen::map(rc::gen::inRange(0, 1001), [](int k) { return k / 1000.0; }), gen_component());
}

bool is_derivative(const std::string& name) {
  return name.rfind("dslope_", 0) == 0 || name.rfind("dproj_", 0) == 0 || name.rfind("dn_", 0) == 0;
}

// Adversarial inputs of a core/evaluate function (the domains of stability_inputs.hpp).
rc::Gen<Element> gen_core_element(const Function& f) {
  return rc::gen::exec([&f] {
    Element e;
    const bool brdf = stab::is_brdf(f);
    stab::Material material;
    if (brdf) {
      material.alpha2 = {*gen_brdf_alpha2(), *gen_brdf_alpha2()};
      material.a = {material.alpha2.x, 0.0, material.alpha2.y};
      const int kind = *rc::gen::inRange(0, 3);
      if (kind > 0) {
        const double trace = std::pow(10.0, *rc::gen::inRange(-80, 81) / 10.0);
        const double angle = *gen_angle(), ratio = kind == 1 ? *rc::gen::inRange(0, 101) / 100.0 : 0.0;
        const double l1 = trace / (1.0 + ratio), l2 = l1 * ratio, c = std::cos(angle), s = std::sin(angle);
        material.a = material.a + Sym2{l1 * c * c + l2 * s * s, (l1 - l2) * c * s, l1 * s * s + l2 * c * c};
      }
      material.tau = *rc::gen::element(0, 1, 2, 2) == 0 ? 0.0 : ref::ndf_clamp_tau(material.alpha2);
    }
    const Vec3 i = *gen_direction(), o = *gen_direction();
    for (const saagen::Parameter& p : f.parameters) {
      if (p.name == "alpha2") {
        if (brdf)
          p.type == "real" ? push(e, material.alpha2.x) : push(e, material.alpha2);
        else
          for (int k = 0; k < (p.type == "real" ? 1 : 2); ++k) push(e, *gen_filter_alpha2());
      } else if (is_derivative(p.name)) {
        for (std::uint32_t k = 0; k < saagen::component_count(p.type); ++k) push(e, *gen_component());
      } else if (p.name == "h") {
        const Vec3 sum = i + o;
        push(e, f.name.find("g2") != std::string::npos && ref::dot(sum, sum) > 0.0 ? ref::normalize(sum) : *gen_direction());
      } else if (p.name == "w" || p.name == "i") {
        push(e, i);
      } else if (p.name == "o") {
        push(e, o);
      } else if (p.name == "a") {
        push(e, material.a);
      } else if (p.name == "tau") {
        push(e, material.tau);
      } else if (p.name == "filtered") {
        p.type == "real" ? push(e, material.a.xx) : push(e, Vec2{material.a.xx, material.a.yy});
      } else if (p.name == "lobe") {
        for (double v : ref::ggx_filtered_lobe_isotropic(material.a.xx, material.alpha2.x)) push(e, v);
      } else if (p.name == "kernel") {
        push(e, material.a.xx - material.alpha2.x);
      } else if (p.name == "normal_ws") {
        push(e, *gen_direction());
      } else if (p.name == "light_ws") {
        push(e, i);
      } else if (p.name == "view_ws") {
        push(e, o);
      } else if (p.name == "tensor") {
        push(e, stab::material_tensor(material));
      } else if (p.name == "tensor_lobe") {
        for (double v : ref::deferred_aniso_lobe(ref::Params{}, stab::material_tensor(material), material.alpha2.x)) push(e, v);
      } else if (p.name == "covariance") {  // PSD, not bounded by kappa: trace 1e-8 .. 1e8
        const double trace = std::pow(10.0, *rc::gen::inRange(-80, 81) / 10.0);
        const double angle = *gen_angle(), ratio = *rc::gen::inRange(0, 101) / 100.0;
        const double l1 = trace / (1.0 + ratio), l2 = l1 * ratio, c = std::cos(angle), s = std::sin(angle);
        push(e, Sym2{l1 * c * c + l2 * s * s, (l1 - l2) * c * s, l1 * s * s + l2 * c * c});
      } else if (p.name == "tangent_ws" || p.name == "bitangent_ws") {
        push(e, *gen_direction());
      } else if (p.name == "mean_length") {
        push(e, *gen_mean_length());
      } else if (p.name == "slope_mean" || p.name == "slope_second") {
        for (std::uint32_t k = 0; k < saagen::component_count(p.type); ++k) push(e, *gen_component());
      } else {
        throw std::runtime_error("no generator for " + p.name);
      }
    }
    return e;
  });
}

// The fields of one wrapper quad: per-pixel unit-or-shorter vectors with adversarial
// differences, tangent frames that are orthonormal or degenerate, o = -i at some pixels.
rc::Gen<Element> gen_wrapper_quad(const Function& f) {
  return rc::gen::exec([&f] {
    const stab::Layout layout = stab::layout_of(f);
    const bool brdf = stab::is_brdf(f);
    const auto quad_vectors = [] {
      const Vec3 base = *gen_direction();
      const int mode = *rc::gen::inRange(0, 5);
      std::array<Vec3, 4> v;
      for (auto& x : v) {
        switch (mode) {
          case 0:
            x = base;
            break;
          case 1: {
            const Vec3 moved = base + std::pow(10.0, *rc::gen::inRange(-70, -9) / 10.0) * *gen_direction();
            x = ref::dot(moved, moved) > 0.0 ? ref::normalize(moved) : base;
            break;
          }
          case 2:
            x = *gen_direction();
            break;
          case 3:
            x = stab::with_z(base, *rc::gen::element(0.0, 1e-30, -1e-30, 1e-7, -1e-7, 1e-4, -1e-4));
            break;
          default:
            x = *rc::gen::element(0, 1) == 0 ? Vec3{} : (*rc::gen::inRange(0, 101) / 100.0) * base;
            break;
        }
      }
      return v;
    };
    const auto first = quad_vectors();
    auto second = quad_vectors();
    for (auto& v : second)
      if (*rc::gen::inRange(0, 8) == 0) v = -1.0 * first[&v - &second[0]];
    std::array<Vec3, 4> t, b;
    const int frame = *rc::gen::inRange(0, 4);
    const double twist = *gen_angle();
    for (int p = 0; p < 4; ++p) {
      const Vec3 n = first[p];
      if (frame == 0) {
        const Vec3 axis = std::fabs(n.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
        Vec3 u = ref::cross(axis, n);
        u = ref::dot(u, u) > 0.0 ? ref::normalize(u) : Vec3{1, 0, 0};
        const Vec3 w = ref::dot(n, n) > 0.0 ? ref::cross(ref::normalize(n), u) : Vec3{0, 1, 0};
        t[p] = std::cos(twist) * u + std::sin(twist) * w;
        b[p] = -std::sin(twist) * u + std::cos(twist) * w;
      } else if (frame == 1) {
        t[p] = Vec3{}, b[p] = *rc::gen::element(0, 1) == 0 ? Vec3{} : *gen_direction();
      } else if (frame == 2) {
        t[p] = n, b[p] = n;
      } else {
        t[p] = (*rc::gen::inRange(0, 101) / 100.0) * *gen_direction();
        b[p] = (*rc::gen::inRange(0, 101) / 100.0) * *gen_direction();
      }
    }
    const double alpha_a = brdf ? *gen_brdf_alpha2() : *gen_filter_alpha2();
    const double alpha_b = brdf ? *gen_brdf_alpha2() : *gen_filter_alpha2();
    Element e;
    e.reserve(4 * layout.stride);
    for (int p = 0; p < 4; ++p) {
      for (const saagen::Parameter& param : f.parameters) {
        if (param.name == "frag_coord") continue;
        if (param.name == "alpha2") {
          push(e, alpha_a);
          if (param.type == "real2") push(e, alpha_b);
        } else if (param.name == "half_ts" || param.name == "normal_ws" || param.name == "i") {
          push(e, first[p]);
        } else if (param.name == "o" || param.name == "half_ws") {
          push(e, second[p]);
        } else if (param.name == "tangent_ws") {
          push(e, t[p]);
        } else if (param.name == "bitangent_ws") {
          push(e, b[p]);
        }
      }
    }
    return e;
  });
}

rc::Gen<std::vector<Element>> gen_batch(rc::Gen<Element> element) {
  return rc::gen::exec([element] {
    const int n = *rc::gen::inRange(kMinBatch, kMaxBatch + 1);
    return *rc::gen::container<std::vector<Element>>(static_cast<std::size_t>(n), element);
  });
}

// ---------------------------------------------------------------------------------------------
// The reference of every wrapper on packed quads (the core functions' is
// saagen::test::core_function_reference).

using Reader = saagen::test::PackedReader<double>;

// pixel of a wrapper quad (fields pixel-major, `stride` each); plain ddx/ddy coarse as in the
// quad_compute kernels (their default).
Values reference_wrapper(const ref::Params& p, const Function& f, const Element& quad, int pixel) {
  const std::uint32_t stride = stab::layout_of(f).stride;
  std::map<std::string, Quad<Vec3>> vectors;
  double alpha2[2] = {quad[0], 0.0};
  std::uint32_t offset = 0;
  for (const saagen::Parameter& param : f.parameters) {
    if (param.name == "frag_coord") continue;
    const std::uint32_t count = saagen::component_count(param.type);
    if (param.name == "alpha2") {
      alpha2[0] = quad[offset];
      if (count == 2) alpha2[1] = quad[offset + 1];
    } else {
      const auto at = [&](int q) {
        const double* v = quad.data() + q * stride + offset;
        return Vec3{v[0], v[1], v[2]};
      };
      vectors[param.name] = {at(0), at(1), at(2), at(3)};
    }
    offset += count;
  }
  return saagen::test::wrapper_reference_on_quad(f.name, p, Vec2{alpha2[0], alpha2[1]}, vectors, pixel);
}

bool is_wrapper(const Function& f) { return f.role == saagen::FunctionRole::fragment; }

// ---------------------------------------------------------------------------------------------
// Evaluators: the reference, or the emitted code on the device. A batch of core inputs gives one
// output per element; a batch of wrapper quads gives four (pixels 0..3 of each quad).

class Evaluator {
 public:
  virtual ~Evaluator() = default;
  virtual std::vector<Values> run(const Function& f, const std::vector<Element>& batch) = 0;
  virtual std::string name() const = 0;
  // Relative rounding unit of the arithmetic (fp32 on the device, double in the reference).
  virtual double unit() const = 0;
  // DERIVATIVE_MAX of the evaluated form (fp32 or half constants).
  virtual double derivative_max() const { return ref::kGuardConstantsFp32.derivative_max; }
};

class ReferenceEvaluator : public Evaluator {
 public:
  explicit ReferenceEvaluator(ref::Params params) : params_(params) {}
  std::vector<Values> run(const Function& f, const std::vector<Element>& batch) override {
    std::vector<Values> out;
    for (const Element& e : batch) {
      if (!is_wrapper(f))
        out.push_back(saagen::test::core_function_reference(f.name, params_, e.data()));
      else
        for (int p = 0; p < 4; ++p) out.push_back(reference_wrapper(params_, f, e, p));
    }
    return out;
  }
  std::string name() const override { return params_.half_precision ? "reference (half guard constants)" : "reference"; }
  double unit() const override { return 0x1p-53; }
  double derivative_max() const override { return params_.guard_constants().derivative_max; }

 private:
  ref::Params params_;
};

#if SAAGEN_STABILITY_DEVICE
// One program per function, built once with buffers for the largest batch; wrappers run in a
// quad_compute kernel whose emulated image is 2 * kMaxBatch pixels wide and 2 high (quad q holds
// pixels x = 2q, 2q + 1 of rows 0 and 1).
class DeviceEvaluator : public Evaluator {
 public:
  explicit DeviceEvaluator(std::string target) : target_(std::move(target)) {}
  std::vector<Values> run(const Function& f, const std::vector<Element>& batch) override {
    Program& program = program_for(f);
    const std::uint32_t stride = program.layout.stride;
    std::vector<float> input(program.input_floats, 0.0f);
    if (batch.size() * (is_wrapper(f) ? 4 : 1) * stride > program.input_floats) throw std::runtime_error("batch too large");
    std::uint32_t lanes = 0;
    if (!is_wrapper(f)) {
      for (std::size_t e = 0; e < batch.size(); ++e)
        for (std::uint32_t k = 0; k < stride; ++k) input[e * stride + k] = static_cast<float>(batch[e][k]);
      lanes = static_cast<std::uint32_t>(batch.size());
    } else {
      for (std::size_t q = 0; q < batch.size(); ++q)
        for (int p = 0; p < 4; ++p) {
          const std::uint32_t index = stab::quad_pixel_index(static_cast<std::uint32_t>(q), p, kWidth);
          for (std::uint32_t k = 0; k < stride; ++k) input[std::size_t{index} * stride + k] = static_cast<float>(batch[q][p * stride + k]);
        }
      lanes = static_cast<std::uint32_t>(batch.size()) * 4;
    }
    program.program->write_buffer(0, std::as_bytes(std::span(input)));
    program.program->set_groups({(lanes + 63) / 64, 1, 1});
    const auto out = program.program->run().buffer_as<float>(1);
    std::vector<Values> result;
    for (std::size_t e = 0; e < batch.size(); ++e) {
      for (int p = 0; p < (is_wrapper(f) ? 4 : 1); ++p) {
        const std::size_t index = is_wrapper(f) ? stab::quad_pixel_index(static_cast<std::uint32_t>(e), p, kWidth) : e;
        Values v;
        for (std::uint32_t k = 0; k < program.outputs; ++k) v.push_back(out[index * program.outputs + k]);
        result.push_back(std::move(v));
      }
    }
    return result;
  }
  std::string name() const override { return target_ + " on " + saagen::test::gpu().info().name; }
  double unit() const override { return 0x1p-24; }

 private:
  static constexpr std::uint32_t kWidth = 2 * kMaxBatch;
  struct Program {
    std::unique_ptr<saagen::harness::ComputeProgram> program;
    stab::Layout layout;
    std::uint32_t outputs = 0;
    std::size_t input_floats = 0;
  };
  Program& program_for(const Function& f) {
    auto found = programs_.find(f.name);
    if (found != programs_.end()) return found->second;
    const saagen::Variant* variant = nullptr;
    for (const saagen::Variant& v : Catalogue::builtin().variants())
      if (std::find(v.functions.begin(), v.functions.end(), f.name) != v.functions.end()) {
        variant = &v;
        break;
      }
    const auto file = saagen::test::emit_variant(target_, variant->id);
    Program program;
    program.layout = stab::layout_of(f);
    program.outputs = saagen::component_count(f.return_type);
    saagen::KernelRequest request;
    std::size_t elements = 2 * kMaxBatch;  // the monotone and rotation properties run pairs
    if (is_wrapper(f)) {
      request.kind = saagen::KernelKind::quad_compute;
      request.width = kWidth;
      request.output_stride = program.outputs;
      request.body = stab::wrapper_body(f, program.layout.stride);
      elements = std::size_t{kWidth} * 2;
    } else {
      request.body = saagen::load_call_store_body(Catalogue::builtin(), f.name, request);
    }
    program.input_floats = elements * program.layout.stride;
    saagen::harness::ComputeRun run;
    run.shader.spirv = saagen::test::compile_kernel(file, request);
    run.buffers = {saagen::harness::input_buffer(0, std::vector<float>(program.input_floats, 0.0f)),
                   saagen::harness::output_buffer<float>(1, elements * program.outputs)};
    run.groups = {1, 1, 1};
    program.program = std::make_unique<saagen::harness::ComputeProgram>(saagen::test::gpu(), run);
    return programs_.emplace(f.name, std::move(program)).first->second;
  }
  std::string target_;
  std::map<std::string, Program> programs_;
};
#endif

// ---------------------------------------------------------------------------------------------
// Properties

std::string show(const Element& e) {
  std::string text;
  for (double v : e) text += fmt::format("{}{:.9g}", text.empty() ? "" : ", ", v);
  return "(" + text + ")";
}

// alpha2 of output k (element e, pixel p) as the claims need it.
std::vector<double> alpha2_of(const Function& f, const Element& e, int pixel) {
  const stab::Layout layout = stab::layout_of(f);
  std::vector<double> a;
  for (std::uint32_t k = 0; k < layout.alpha2_count; ++k) a.push_back(e[pixel * layout.stride + layout.alpha2_offset + k]);
  return a;
}

// Every output keeps the function's claim.
void claims_hold(Evaluator& evaluator, const Function& f, const std::vector<Element>& batch) {
  const auto out = evaluator.run(f, batch);
  const int per = is_wrapper(f) ? 4 : 1;
  for (std::size_t e = 0; e < batch.size(); ++e) {
    for (int p = 0; p < per; ++p) {
      const Values& v = out[e * per + p];
      const auto verdict = stab::judge(stab::claim_of(f.name), 0.18, alpha2_of(f, batch[e], is_wrapper(f) ? p : 0), v, true);
      if (!verdict.ok()) {
        RC_FAIL(fmt::format("{} {}: {} for inputs {} (pixel {}) -> {}", evaluator.name(), f.name, verdict.why, show(batch[e]), p, show(v)));
      }
    }
  }
}

// Scales every derivative component by s (fp32, magnitude capped at FLT_MAX).
Element scaled_derivatives(const Function& f, const Element& e, double s) {
  Element scaled = e;
  std::uint32_t offset = 0;
  for (const saagen::Parameter& p : f.parameters) {
    const std::uint32_t count = saagen::component_count(p.type);
    if (is_derivative(p.name))
      for (std::uint32_t k = 0; k < count; ++k) {
        double& v = scaled[offset + k];
        v = std::copysign(std::min(std::fabs(as_float(v * s)), double(FLT_MAX)), v);
      }
    offset += count;
  }
  return scaled;
}

double max_abs_derivative(const Function& f, const Element& e) {
  double m = 0.0;
  std::uint32_t offset = 0;
  for (const saagen::Parameter& p : f.parameters) {
    const std::uint32_t count = saagen::component_count(p.type);
    if (is_derivative(p.name))
      for (std::uint32_t k = 0; k < count; ++k) m = std::max(m, std::fabs(e[offset + k]));
    offset += count;
  }
  return m;
}

// Whether any non-zero derivative component is an fp32 subnormal (|v| < FLT_MIN = 2^-126).
// There fp32 rounding is absolute (a multiple of 2^-149), not relative: s d rounds to d itself
// for the smallest ones, so the scaled input is not s times the input and the relative rounding
// bound below does not apply.
bool has_subnormal_derivative(const Function& f, const Element& e) {
  std::uint32_t offset = 0;
  for (const saagen::Parameter& p : f.parameters) {
    const std::uint32_t count = saagen::component_count(p.type);
    if (is_derivative(p.name))
      for (std::uint32_t k = 0; k < count; ++k)
        if (e[offset + k] != 0.0 && std::fabs(e[offset + k]) < double(FLT_MIN)) return true;
    offset += count;
  }
  return false;
}

double sym2_min_eigenvalue(double xx, double xy, double yy) { return 0.5 * (xx + yy) - std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy); }

// alpha'^2 (each component) never decreases when the derivatives grow by s in [1, 16]; the
// roughness matrix grows in the PSD order while s |d| <= DERIVATIVE_MAX, its diagonal always.
void monotone_in_derivatives(Evaluator& evaluator, const Function& f, const std::vector<Element>& batch, const std::vector<int>& scales) {
  std::vector<Element> pairs;
  for (std::size_t e = 0; e < batch.size(); ++e) {
    pairs.push_back(batch[e]);
    pairs.push_back(scaled_derivatives(f, batch[e], scales[e] / 16.0));
  }
  const auto out = evaluator.run(f, pairs);
  const double slack = 4.0 * evaluator.unit();
  // deferred-aniso's tensor of s^2 Delta^T Delta, scaled by min(1, kappa / tr), is s^2 K until its
  // trace reaches kappa and constant beyond: it grows in the PSD order
  // (continuous at the bound), and only as long as the derivatives scale as a whole (no component
  // clamped at DERIVATIVE_MAX, which turns them); its diagonal follows from that order, with the
  // same slack (rounding turns the eigenvectors by a few units of 2^-24, which moves a diagonal
  // entry by that much times the eigenvalue gap, not times the entry).
  const bool tensor = stab::claim_of(f.name) == stab::Claim::kernel_tensor;
  const bool matrix = stab::claim_of(f.name) == stab::Claim::roughness_matrix || tensor;
  for (std::size_t e = 0; e < batch.size(); ++e) {
    const Values& low = out[2 * e];
    const Values& high = out[2 * e + 1];
    const std::string what = fmt::format("{} {}: inputs {} scaled by {}: {} -> {}", evaluator.name(), f.name, show(batch[e]),
                                         scales[e] / 16.0, show(low), show(high));
    if (!matrix) {
      for (std::size_t k = 0; k < low.size(); ++k)
        if (high[k] < low[k] - slack * std::max(1.0, low[k])) RC_FAIL(what);
      continue;
    }
    // The Vulkan spec lets a device flush denormal results of any operation to zero (Precision
    // and Operation of SPIR-V Instructions), so an entry below FLT_MIN may be off by FLT_MIN in
    // absolute terms: two entries of the difference, each from both matrices, 4 FLT_MIN.
    const double flushed = 4.0 * double(FLT_MIN);
    const bool scaled_whole =
        max_abs_derivative(f, pairs[2 * e + 1]) <= evaluator.derivative_max() && !has_subnormal_derivative(f, pairs[2 * e]);
    // deferred-aniso's tensor: the fp32 inputs s d are rounded (u = 2^-24, whatever the
    // evaluator's own rounding), which moves det(Delta) by up to 4u |du| |dv| and so the smaller
    // eigenvalue det(Delta)^2 / l1 by up to 8u |det(Delta)| <= 4u tr(Delta^T Delta): 8u times the
    // unclamped trace T = 2 sigma^2 tr(Delta^T Delta) of K covers it, before any clamp (the
    // property says nothing once 8u T exceeds kappa, derivatives beyond ~1e3).
    double tensor_slack = 0.0;
    if (tensor) {
      if (!scaled_whole) continue;
      Reader terms(pairs[2 * e + 1].data());
      tensor_slack = 8.0 * 0x1p-24 * (*saagen::test::deferred_aniso_reference(f.name, ref::Params{}, terms, true))[0];
      const double turned = 0x1p-20 * (high[0] + high[2] + low[0] + low[2]) + tensor_slack + flushed;
      if (high[0] < low[0] - turned || high[2] < low[2] - turned) RC_FAIL(what);
    } else if (high[0] < low[0] * (1.0 - slack) - flushed || high[2] < low[2] * (1.0 - slack) - flushed) {
      RC_FAIL(what);
    }
    if (scaled_whole) {
      // Weyl: rounding the entries (fp32 inputs s d, and the arithmetic) moves the smallest
      // eigenvalue of the difference by at most a few units of 2^-24 times their size, plus the
      // denormal flush above.
      const double lambda = sym2_min_eigenvalue(high[0] - low[0], high[1] - low[1], high[2] - low[2]);
      if (lambda < -0x1p-20 * (high[0] + high[2] + low[0] + low[2]) - tensor_slack - flushed) RC_FAIL(what);
    }
  }
}

Vec3 rotate(Vec3 v, Vec3 axis, double angle) {  // Rodrigues
  const double c = std::cos(angle), s = std::sin(angle);
  return c * v + s * ref::cross(axis, v) + (1.0 - c) * ref::dot(axis, v) * axis;
}

// The isotropic core functions give the same alpha'^2 when the frame turns: deferred_max's
// tangent-plane derivatives rotate by an angle, the world-space derivatives of the tangent-free
// forms by a 3D rotation; forward-aniso with ax = ay keeps trace and largest eigenvalue.
void invariant_under_rotation(Evaluator& evaluator, const Function& f, const std::vector<Element>& batch, const std::vector<Vec3>& axes,
                              const std::vector<double>& angles) {
  std::vector<Element> pairs;
  for (std::size_t e = 0; e < batch.size(); ++e) {
    Element turned = batch[e];
    std::uint32_t offset = 0;
    for (const saagen::Parameter& p : f.parameters) {
      const std::uint32_t count = saagen::component_count(p.type);
      if (p.name == "alpha2" && count == 2) turned[offset + 1] = turned[offset];  // isotropic material
      if (is_derivative(p.name)) {
        if (count == 2) {
          const double c = std::cos(angles[e]), s = std::sin(angles[e]), x = turned[offset], y = turned[offset + 1];
          turned[offset] = as_float(c * x - s * y), turned[offset + 1] = as_float(s * x + c * y);
        } else {
          const Vec3 v = rotate({turned[offset], turned[offset + 1], turned[offset + 2]}, axes[e], angles[e]);
          turned[offset] = as_float(v.x), turned[offset + 1] = as_float(v.y), turned[offset + 2] = as_float(v.z);
        }
      }
      offset += count;
    }
    Element original = batch[e];
    if (stab::layout_of(f).alpha2_count == 2) original[stab::layout_of(f).alpha2_offset + 1] = original[stab::layout_of(f).alpha2_offset];
    pairs.push_back(original);
    pairs.push_back(turned);
  }
  const auto out = evaluator.run(f, pairs);
  // The turned inputs are rounded to fp32 (a relative 2^-24 per component) before either
  // evaluator sees them; 2^-20 covers that and the device's own rounding.
  const double tolerance = 0x1p-20 + 64.0 * evaluator.unit();
  for (std::size_t e = 0; e < batch.size(); ++e) {
    const Values& a = out[2 * e];
    const Values& b = out[2 * e + 1];
    const std::string what = fmt::format("{} {}: inputs {} turned by {} rad: {} vs {}", evaluator.name(), f.name, show(pairs[2 * e]),
                                         angles[e], show(a), show(b));
    // Products below FLT_MIN underflow (or flush) on the device: 1e-35 absolute covers the
    // matrix entries. The eigenvalue of deferred_max squares numbers of its own size (the half
    // difference and m01), which underflow for eigenvalues below sqrt(FLT_MIN) = 1.1e-19: its
    // absolute error reaches that size, 2 sigma^2 1.1e-19 in alpha'^2, so 1e-18 there.
    if (a.size() == 1) {
      if (std::fabs(a[0] - b[0]) > tolerance * std::max(a[0], b[0]) + 1e-18) RC_FAIL(what);
    } else {
      const double trace_a = a[0] + a[2], trace_b = b[0] + b[2];
      if (std::fabs(trace_a - trace_b) > tolerance * std::max(trace_a, trace_b) + 1e-35) RC_FAIL(what);
      const double top_a = trace_a - sym2_min_eigenvalue(a[0], a[1], a[2]), top_b = trace_b - sym2_min_eigenvalue(b[0], b[1], b[2]);
      if (std::fabs(top_a - top_b) > 4.0 * tolerance * std::max(trace_a, trace_b) + 1e-35) RC_FAIL(what);
    }
  }
}

// Adversarial derivatives are capped for the rotation property so that a rotated vector stays
// representable (|R d| = |d| may exceed FLT_MAX componentwise otherwise), and magnitudes below
// 1e-30 are flushed to 0: rotating an fp32 denormal and rounding it back changes it by up to 100 %.
Element capped(const Element& e, double cap) {
  Element c = e;
  for (double& v : c) v = std::fabs(v) < 1e-30 ? 0.0 : std::copysign(std::min(std::fabs(v), cap), v);
  return c;
}

bool isotropic(const Function& f) {
  return f.name == "deferred_max" || f.name == "deferred_max_tangent_free" || f.name == "deferred_sum" || f.name == "deferred_avg" ||
         f.name == "deferred_projected_space" || f.name.rfind("forward_aniso_", 0) == 0;
}

bool filter(const Function& f) { return !stab::is_brdf(f); }

#if SAAGEN_STABILITY_DEVICE
// deferred_aniso_fragment's magnitude scale on a quad of normals (4 x 3 values): the unclamped
// trace 2 sigma^2 (|ddx n|^2 + |ddy n|^2) is at most 2 sigma^2 times twice the largest squared
// difference of two of the quad's normals, whatever derivative (coarse or fine) the device takes.
double wrapper_tensor_scale(const Element& quad) {
  double largest = 0.0;
  for (int p = 0; p < 4; ++p)
    for (int q = 0; q < 4; ++q) {
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k) d2 += (quad[3 * p + k] - quad[3 * q + k]) * (quad[3 * p + k] - quad[3 * q + k]);
      largest = std::max(largest, d2);
    }
  return 2.0 * ref::Params{}.sigma2 * 2.0 * largest;
}

// The device matches the guarded reference on adversarial finite inputs (the reference mirrors
// every guard): |gpu - ref| <= 4e-6 for alpha^2 outputs (fp32 rounding of a kernel that is then
// clamped to kappa <= 1: a few units of 2^-24 relative, far below 4e-6), 1e-5 (A00 + A11) for the
// matrix entries.
void matches_guarded_reference(Evaluator& device, const Function& f, const std::vector<Element>& batch) {
  ReferenceEvaluator reference{ref::Params{}};
  const auto got = device.run(f, batch);
  const auto expected = reference.run(f, batch);
  const int per = is_wrapper(f) ? 4 : 1;
  for (std::size_t k = 0; k < got.size(); ++k) {
    const Values& g = got[k];
    const Values& x = expected[k];
    double bound = g.size() == 3 ? 1e-5 * (std::fabs(x[0]) + std::fabs(x[2])) + 1e-30 : 4e-6;
    // Prefiltering: LEAN's E[s s^T] - E[s]^2 cancels, so fp32 rounding is relative to the terms.
    Reader terms(batch[k / per].data());
    if (const auto scale = saagen::test::prefilter_reference(f.name, ref::Params{}, terms, true)) {
      bound = std::max(bound, 2e-5 * *std::max_element(scale->begin(), scale->end()));
    }
    // deferred-aniso's tensor: rounding relative to the unclamped trace 2 sigma^2 (|dx|^2 + |dy|^2)
    // (reference_dispatch.hpp): the frame built in fp32 is off by eps, which a derivative's
    // component along n (adversarial inputs have any) carries into K.
    Reader tensor_terms(batch[k / per].data());
    if (const auto scale = saagen::test::deferred_aniso_reference(f.name, ref::Params{}, tensor_terms, true)) {
      bound = std::max(bound, 2e-5 * *std::max_element(scale->begin(), scale->end()));
    }
    if (f.name == "deferred_aniso_fragment") bound = std::max(bound, 2e-5 * wrapper_tensor_scale(batch[k / per]));
    for (std::size_t c = 0; c < g.size(); ++c) {
      if (!(std::fabs(g[c] - x[c]) <= bound))
        RC_FAIL(fmt::format("{} {}: inputs {} (pixel {}): device {} vs reference {}", device.name(), f.name, show(batch[k / per]), k % per,
                            show(g), show(x)));
    }
  }
}

#endif

std::vector<const Function*> public_functions(const saagen::Variant& variant) {
  std::vector<const Function*> functions;
  for (const std::string& name : variant.functions) functions.push_back(Catalogue::builtin().find_function(name));
  return functions;
}

// All properties of one function, with `cases` rapidcheck cases of `batch` elements.
void check_function(Evaluator& evaluator, const Function& f, int cases, bool batches) {
  const auto element = is_wrapper(f) ? gen_wrapper_quad(f) : gen_core_element(f);
  const auto batch_of = [=] { return batches ? *gen_batch(element) : std::vector<Element>{*element}; };
  const auto check = [&](const std::string& name, auto property) { check_property(name, cases, property, !batches); };
  check(f.name + " claims", [&] { claims_hold(evaluator, f, batch_of()); });
  if (!is_wrapper(f) && filter(f)) {
    check(f.name + " monotone", [&] {
      const auto batch = batch_of();
      const auto scales = *rc::gen::container<std::vector<int>>(batch.size(), rc::gen::inRange(16, 257));
      monotone_in_derivatives(evaluator, f, batch, scales);
    });
  }
  if (!is_wrapper(f) && isotropic(f)) {
    check(f.name + " rotation invariant", [&] {
      auto batch = batch_of();
      // A rotated vector must stay representable, and the roughness matrix (not saturated) must
      // stay below DERIVATIVE_MAX, whose componentwise clamp is not rotation invariant.
      const bool matrix = stab::claim_of(f.name) == stab::Claim::roughness_matrix;
      for (Element& e : batch) e = capped(e, matrix ? 0.5 * evaluator.derivative_max() : 1e30);
      const auto axes = *rc::gen::container<std::vector<Vec3>>(batch.size(), rc::gen::map(gen_direction(), [](Vec3 v) {
                                                                 return ref::dot(v, v) > 0.0 ? ref::normalize(v) : Vec3{0, 0, 1};
                                                               }));
      const auto angles = *rc::gen::container<std::vector<double>>(batch.size(), gen_angle());
      invariant_under_rotation(evaluator, f, batch, axes, angles);
    });
  }
}

#if !SAAGEN_STABILITY_DEVICE
// ---------------------------------------------------------------------------------------------
// CPU: the reference, every variant.

class ReferenceProperties : public ::testing::TestWithParam<std::string> {};

TEST_P(ReferenceProperties, EveryPublicFunctionKeepsItsClaims) {
  const saagen::Variant& variant = *Catalogue::builtin().find_variant(GetParam());
  for (const bool half : {false, true}) {
    ref::Params params;
    params.half_precision = half;
    ReferenceEvaluator evaluator(params);
    for (const Function* f : public_functions(variant)) check_function(evaluator, *f, kCpuCases, false);
  }
}

// Where the paper form has nothing to guard (|h_z| >= SLOPE_MIN_Z, derivatives within
// DERIVATIVE_MAX, normals of length >= 1e-3, cosines >= LAMBDA_MIN_Z, well-conditioned A), the
// guarded reference equals the paper form exactly: guards only act where the paper form breaks.
TEST_P(ReferenceProperties, GuardsChangeNothingWhereThePaperFormIsFine) {
  const saagen::Variant& variant = *Catalogue::builtin().find_variant(GetParam());
  ref::Params paper;
  paper.guards = false;
  ReferenceEvaluator guarded_evaluator{ref::Params{}}, paper_evaluator{paper};
  for (const Function* f : public_functions(variant)) {
    check_property(f->name + " guards inactive", kCpuCases, [&] {
      Element e = is_wrapper(*f) ? *gen_wrapper_quad(*f) : *gen_core_element(*f);
      // Move the inputs into the region where no guard acts.
      std::uint32_t offset = 0;
      const std::uint32_t stride = stab::layout_of(*f).stride;
      for (int p = 0; p < (is_wrapper(*f) ? 4 : 1); ++p) {
        offset = p * stride;
        for (const saagen::Parameter& param : f->parameters) {
          if (param.name == "frag_coord") continue;
          const std::uint32_t count = saagen::component_count(param.type);
          if (is_derivative(param.name))
            for (std::uint32_t k = 0; k < count; ++k) e[offset + k] = std::copysign(std::min(std::fabs(e[offset + k]), 1e9), e[offset + k]);
          const bool matrix_input = param.name == "a" || param.name == "tensor" || param.name == "covariance";
          if (count == 3 && !matrix_input) {
            Vec3 v{e[offset], e[offset + 1], e[offset + 2]};
            if (!is_derivative(param.name)) {
              // unit vectors with z >= 0.01 (slopes, cosines and Lambda away from their guards)
              v = ref::dot(v, v) > 1e-6 ? ref::normalize(v) : Vec3{0, 0, 1};
              v = stab::with_z(v, std::max(std::fabs(v.z), 0.01));
              e[offset] = as_float(v.x), e[offset + 1] = as_float(v.y), e[offset + 2] = as_float(v.z);
            }
          }
          if (matrix_input) {  // well conditioned: a00 = a11 = 2 + |a01|
            e[offset + 1] = std::clamp(e[offset + 1], -1.0, 1.0);
            e[offset] = e[offset + 2] = as_float(2.0 + std::fabs(e[offset + 1]));
          }
          if (param.name == "tau") e[offset] = std::max(e[offset], 1e-20);
          // Toksvig's L in [1e-3, 1]; LEAN moments of a covariance with variances >= 0.01 and
          // |correlation| <= 0.5 around a mean within +-1 (no clamp acts).
          if (param.name == "mean_length") e[offset] = std::clamp(std::fabs(e[offset]), 1e-3, 1.0);
          if (param.name == "slope_mean")
            for (std::uint32_t k = 0; k < 2; ++k) e[offset + k] = std::clamp(e[offset + k], -1.0, 1.0);
          if (param.name == "slope_second") {
            const double mx = e[offset - 2], my = e[offset - 1];
            const double xx = std::clamp(std::fabs(e[offset]), 0.01, 1e4), yy = std::clamp(std::fabs(e[offset + 2]), 0.01, 1e4);
            const double limit = 0.5 * std::sqrt(xx * yy);
            e[offset + 1] = std::clamp(e[offset + 1], -limit, limit) + mx * my;
            e[offset] = xx + mx * mx, e[offset + 2] = yy + my * my;
          }
          offset += count;
        }
      }
      // deferred-previous's wrapper divides by the z of the quad-average normal in each pixel's
      // frame: keep it >= SLOPE_MIN_Z (i and o with z >= 0.01 never sum to zero: no other case).
      if (f->name == "deferred_previous_fragment" || f->name == "deferred_max_fragment") {
        const auto at = [&](int q, int k) { return Vec3{e[q * stride + k], e[q * stride + k + 1], e[q * stride + k + 2]}; };
        const Quad<Vec3> n{at(0, 1), at(1, 1), at(2, 1), at(3, 1)};
        const Quad<Vec2> frag{{0.5, 0.5}, {1.5, 0.5}, {0.5, 1.5}, {1.5, 1.5}};
        for (int q = 0; q < 4; ++q) {
          const Vec3 average = ref::quad_average_normal_quad(n, frag, q);
          RC_PRE(std::fabs(ref::dot(average, n[q])) >= 1e-3 && ref::dot(average, average) >= 1e-6);
        }
      }
      const auto a = guarded_evaluator.run(*f, {e});
      const auto b = paper_evaluator.run(*f, {e});
      // Equal up to double rounding. The guarded Beckmann matrix exponent is reordered,
      // (h.xy^T adj h.xy / det) / h_z^2 against the paper's s^T adj s / det: exp turns an
      // exponent rounding error d into a relative error d, and d ~ e cond(A) 2^-53 <= 1e-5 for
      // exponents e <= 120 (values above 1e-40 / prefactor) and cond(A) <= 1e9; values below
      // 1e-40 (0 in fp32, where the emitted code runs) are compared in absolute terms.
      // The guarded Beckmann NDF also takes exp(-x) as 0 past EXP_ARG_MAX = 104 (0 in fp32
      // anyway): what it drops is below e^-104 / (pi sqrt(tau) h_z^4) / (4 i.z o.z) <=
      // 6.8e-46 / (pi 1e-10 1e-8) / 4e-4 < 1e-14 here (tau >= 1e-20, cosines >= 0.01).
      // The tail-preserving filtered GGX evaluates a Beckmann core: the same bound (also through
      // deferred-aniso's lighting pass).
      const bool beckmann = f->name.find("beckmann") != std::string::npos || f->name.find("filtered_matrix") != std::string::npos ||
                            f->name.find("filtered_axis") != std::string::npos || f->name.find("tail_filtered") != std::string::npos ||
                            f->name.find("filtered_lobe") != std::string::npos || f->name.rfind("deferred_aniso_brdf", 0) == 0;
      const double relative = beckmann ? 1e-5 : 1e-12;
      for (std::size_t k = 0; k < a.size(); ++k)
        for (std::size_t c = 0; c < a[k].size(); ++c)
          if (!(std::fabs(a[k][c] - b[k][c]) <= relative * std::fabs(b[k][c]) + 1e-40) && !(beckmann && a[k][c] == 0.0 && b[k][c] < 1e-14))
            RC_FAIL(fmt::format("{}: inputs {}: guarded {} vs paper {}", f->name, show(e), show(a[k]), show(b[k])));
    });
  }
}

INSTANTIATE_TEST_SUITE_P(EveryVariant, ReferenceProperties, ::testing::ValuesIn([] {
                           std::vector<std::string> ids;
                           for (const saagen::Variant& v : Catalogue::builtin().variants()) ids.push_back(v.id);
                           return ids;
                         }()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

// deferred_max_fragment: rotating every pixel's tangent frame about its normal by one angle
// leaves alpha'^2 unchanged (the projected normals rotate, Sigma's eigenvalues do not).
TEST(ReferenceIsotropy, DeferredMaxWrapperIgnoresTheTangentFrameOrientation) {
  check_property("deferred_max_fragment frame rotation", kCpuCases, [] {
    const ref::Params p;
    const Vec3 base = ref::normalize(*gen_direction() + Vec3{0, 0, 1.5});
    const double step = std::pow(10.0, *rc::gen::inRange(-40, 0) / 10.0), angle = *gen_angle();
    Vec3 n[4], t[4], b[4], t2[4], b2[4];
    for (int q = 0; q < 4; ++q) {
      n[q] = ref::normalize(base + step * *gen_direction());
      const Vec3 u = ref::normalize(ref::cross(Vec3{0.3, 0.9, 0.1}, n[q]));
      t[q] = u, b[q] = ref::cross(n[q], u);
      t2[q] = std::cos(angle) * t[q] + std::sin(angle) * b[q];
      b2[q] = -std::sin(angle) * t[q] + std::cos(angle) * b[q];
    }
    const Quad<Vec2> frag{{0.5, 0.5}, {1.5, 0.5}, {0.5, 1.5}, {1.5, 1.5}};
    const double alpha2 = *gen_filter_alpha2();
    for (int pixel = 0; pixel < 4; ++pixel) {
      const double a = ref::deferred_max_fragment_quad(p, alpha2, {n[0], n[1], n[2], n[3]}, {t[0], t[1], t[2], t[3]},
                                                       {b[0], b[1], b[2], b[3]}, frag, pixel);
      const double c = ref::deferred_max_fragment_quad(p, alpha2, {n[0], n[1], n[2], n[3]}, {t2[0], t2[1], t2[2], t2[3]},
                                                       {b2[0], b2[1], b2[2], b2[3]}, frag, pixel);
      // Double rounding of the projected normals (~1e-16 absolute) enters the kernel as
      // 2 sigma^2 2 |d| 1e-16 with |d| >= 1e-4 here: 1e-18 absolute covers it.
      RC_ASSERT(std::fabs(a - c) <= 1e-12 * a + 1e-18);
    }
  });
}

// deferred-previous is not rotation invariant: its rectangle's maximum width depends on the
// frame. A derivative along the tangent gives width |d|, the same derivative at 45 degrees
// width |d| / sqrt(2), so the kernel halves.
TEST(ReferenceIsotropy, DeferredPreviousDependsOnTheFrameOrientation) {
  const ref::Params p;
  const double aligned = ref::deferred_previous(p, 0.0, {0.1, 0.0}, {0.0, 0.0});
  const double turned = ref::deferred_previous(p, 0.0, {0.1 / std::sqrt(2.0), 0.1 / std::sqrt(2.0)}, {0.0, 0.0});
  EXPECT_DOUBLE_EQ(aligned, 2.0 * 0.25 * 0.01);
  EXPECT_NEAR(turned, aligned / 2.0, 1e-15);
}

#else
// ---------------------------------------------------------------------------------------------
// GPU: the emitted guarded fp32 code of every variant and target, in batches.

struct DeviceCase {
  std::string target;
  std::string variant;
};
void PrintTo(const DeviceCase& c, std::ostream* os) { *os << c.target << " " << c.variant; }

class DeviceProperties : public ::testing::TestWithParam<DeviceCase> {};

TEST_P(DeviceProperties, EmittedCodeKeepsItsClaimsAndMatchesTheGuardedReference) {
  const DeviceCase& c = GetParam();
  DeviceEvaluator device(c.target);
  for (const Function* f : public_functions(*Catalogue::builtin().find_variant(c.variant))) {
    check_function(device, *f, kGpuCases, true);
    // Core filters only: a wrapper's outputs are differences of its inputs, whose conditioning
    // test_gpu_fragment bounds; the sweep and the claims above cover the wrappers' guards.
    if (filter(*f) && !is_wrapper(*f)) {
      const auto element = gen_core_element(*f);
      check_property(
          f->name + " matches the guarded reference", kGpuCases, [&] { matches_guarded_reference(device, *f, *gen_batch(element)); },
          false);
    }
  }
}

std::vector<DeviceCase> device_cases() {
  std::vector<DeviceCase> cases;
  for (const std::string target : {"glsl", "hlsl"})
    for (const saagen::Variant& v : Catalogue::builtin().variants()) cases.push_back({target, v.id});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryVariant, DeviceProperties, ::testing::ValuesIn(device_cases()), [](const auto& info) {
  std::string name = info.param.target + "_" + info.param.variant;
  for (char& ch : name) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return name;
});
#endif

}  // namespace
