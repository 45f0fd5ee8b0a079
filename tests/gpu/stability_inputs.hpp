// Adversarial inputs for the stability sweep and the precision test, packed in the
// parameter order of a function (as saagen::load_call_store_body loads them) or of a fragment
// wrapper's per-pixel fields (every parameter except frag_coord, pixels in quads).
//
// The domains (docs/STABILITY.md) the generators draw from:
//  - filter alpha^2: 0, or alpha^2 with alpha log-uniform in [1e-4, 1], or in (1, 4] (saturated);
//  - derivatives: every component any finite fp32 value: 0, denormals, 1e-30 ... FLT_MAX, either sign;
//  - directions: unit vectors whose z is 0, +-1e-30, +-1e-20, +-1e-10, +-1e-7, +-1e-4, +-1e-2,
//    +-1 or uniform, either sign (h_z -> 0, exactly 0, back-facing);
//  - BRDF roughness: ax^2, ay^2 in [1e-8, 1] (alpha in [1e-4, 1]); A = diag(ax^2, ay^2) + S, S a
//    full-rank or rank-1 (near-singular A: the tau clamp) PSD kernel of trace up to kMaxKernel;
//    tau = ax^2 ay^2 (ndf_clamp_tau), 0, or det(A) times [0.5, 1.5];
//  - wrapper fields: per-pixel unit vectors that are equal, slightly or wildly different across
//    the quad, cross h_z = 0 inside the quad, are zero or shorter than 1; tangent frames that are
//    orthonormal, zero, parallel to the normal, or arbitrary (non-orthogonal, length <= 1);
//    BRDF wrappers also get o = -i (a zero half vector) at some pixels.
// A non-finite input (+-Inf or NaN in some component) is injected into 1 element (quad) in 8.
#pragma once

#include "saagen/front/catalogue.hpp"
#include "saagen/reference/reference.hpp"
#include "saagen/validate/kernels.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace saagen::stability {

namespace ref = saagen::ref;

// Largest trace of the kernel S added to diag(ax^2, ay^2) in the BRDF roughness matrices: what
// forward_aniso_* returns for derivatives up to 1e4 per pixel (2 sigma^2 |Delta|^2 with
// sigma^2 = 0.25).
inline constexpr double kMaxKernel = 1e8;

// xoshiro256** (Blackman & Vigna), seeded through splitmix64: fast and reproducible.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    for (auto& word : state_) {
      seed += 0x9E3779B97F4A7C15ull;
      std::uint64_t z = seed;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      word = z ^ (z >> 31);
    }
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1p-53; }
  double uniform(double low, double high) { return low + (high - low) * uniform(); }
  std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>((next() >> 32) * n >> 32); }
  bool chance(std::uint32_t one_in) { return below(one_in) == 0; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4];
};

inline constexpr float kFloatMax = std::numeric_limits<float>::max();

// A finite fp32 value of adversarial magnitude and either sign.
inline double adversarial_component(Rng& rng) {
  static constexpr float specials[] = {0.0f, 1e-40f, 1e-30f, 1e-6f, 1e-3f, 1.0f, 1e3f, 1e6f, 1e9f, 1e10f, 1e19f, 1e20f, 1e30f, kFloatMax};
  double magnitude;
  switch (rng.below(4)) {
    case 0:
      magnitude = specials[rng.below(std::size(specials))];
      break;
    case 1:
      magnitude = std::pow(10.0, rng.uniform(-6.0, 1.0));
      break;  // typical per-pixel changes
    default:
      magnitude = std::min<double>(std::pow(10.0, rng.uniform(-45.0, 38.6)), kFloatMax);
      break;
  }
  return static_cast<float>(rng.chance(2) ? -magnitude : magnitude);
}

inline double non_finite_value(Rng& rng) {
  switch (rng.below(3)) {
    case 0:
      return std::numeric_limits<double>::infinity();
    case 1:
      return -std::numeric_limits<double>::infinity();
    default:
      return std::numeric_limits<double>::quiet_NaN();
  }
}

// alpha^2 of a filter: 0, alpha^2 for alpha log-uniform in [1e-4, 1], 1, or (1, 4].
inline double filter_alpha2(Rng& rng) {
  switch (rng.below(10)) {
    case 0:
      return 0.0;
    case 1:
      return 1.0;
    case 2:
      return rng.uniform(1.0, 4.0);
    default: {
      const double alpha = std::pow(10.0, rng.uniform(-4.0, 0.0));
      return alpha * alpha;
    }
  }
}

// alpha^2 of a BRDF: alpha log-uniform in [1e-4, 1], or exactly 1e-8 or 1.
inline double brdf_alpha2(Rng& rng) {
  switch (rng.below(10)) {
    case 0:
      return 1e-8;
    case 1:
      return 1.0;
    default: {
      const double alpha = std::pow(10.0, rng.uniform(-4.0, 0.0));
      return alpha * alpha;
    }
  }
}

// A unit vector whose z is adversarial: 0, tiny, +-1 or uniform, either sign.
// Toksvig's mean-normal length L: its domain (0, 1] with 0, subnormals and 1 exactly, and also
// any finite value (L > 1 from rounding, negative from a broken texture).
inline double adversarial_mean_length(Rng& rng) {
  static constexpr double specials[] = {0.0, 1e-45, 1e-38, 1e-30, 1e-7, 0.5, 1.0 - 0x1p-24, 1.0, 1.0 + 0x1p-23, 2.0};
  switch (rng.below(4)) {
    case 0:
      return specials[rng.below(std::size(specials))];
    case 1:
      return adversarial_component(rng);
    default:
      return rng.uniform();
  }
}

inline ref::Vec3 adversarial_direction(Rng& rng) {
  static constexpr double zs[] = {0.0, 1e-30, 1e-20, 1e-10, 1e-7, 1e-4, 1e-2, 1.0};
  double z = rng.chance(2) ? zs[rng.below(std::size(zs))] : rng.uniform();
  if (rng.chance(2)) z = -z;
  const double phi = rng.chance(8) ? 0.5 * std::numbers::pi * rng.below(4) : rng.uniform(0.0, 2.0 * std::numbers::pi);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// A realistic unit direction in the upper hemisphere (z >= z_min), for the precision test.
inline ref::Vec3 upper_direction(Rng& rng, double z_min) {
  const double z = rng.uniform(z_min, 1.0);
  const double phi = rng.uniform(0.0, 2.0 * std::numbers::pi);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

inline ref::Vec3 random_unit(Rng& rng) {
  const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2.0 * std::numbers::pi);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// The material of one BRDF input: (ax^2, ay^2), the roughness matrix A and tau.
struct Material {
  ref::Vec2 alpha2;
  ref::Sym2 a;
  double tau = 0.0;
};

// A = diag(ax^2, ay^2) + S: S zero, full rank, or rank 1 (A near-singular relative to its size),
// of trace up to max_kernel; tau = ax^2 ay^2 mostly, else 0 or det(A) times [0.5, 1.5].
inline Material adversarial_material(Rng& rng, double max_kernel = kMaxKernel) {
  Material m;
  m.alpha2 = {brdf_alpha2(rng), rng.chance(3) ? 0.0 : brdf_alpha2(rng)};
  if (m.alpha2.y == 0.0) m.alpha2.y = m.alpha2.x;
  m.a = {m.alpha2.x, 0.0, m.alpha2.y};
  const std::uint32_t kind = rng.below(3);
  if (kind != 0) {
    const double trace = std::pow(10.0, rng.uniform(-8.0, std::log10(max_kernel)));
    const double angle = rng.uniform(0.0, std::numbers::pi);
    const double c = std::cos(angle), s = std::sin(angle);
    const double ratio = kind == 1 ? rng.uniform() : 0.0;  // second eigenvalue / first
    const double l1 = trace / (1.0 + ratio), l2 = l1 * ratio;
    m.a = m.a + ref::Sym2{l1 * c * c + l2 * s * s, (l1 - l2) * c * s, l1 * s * s + l2 * c * c};
  }
  switch (rng.below(6)) {
    case 0:
      m.tau = 0.0;
      break;
    case 1:
      m.tau = ref::sym2_determinant(m.a) * rng.uniform(0.5, 1.5);
      break;
    default:
      m.tau = ref::ndf_clamp_tau(m.alpha2);
      break;
  }
  return m;
}

// Packs floats; every value is rounded to fp32 on the way in.
struct Packer {
  std::vector<float>& out;
  void real(double v) { out.push_back(static_cast<float>(v)); }
  void vec2(ref::Vec2 v) { real(v.x), real(v.y); }
  void vec3(ref::Vec3 v) { real(v.x), real(v.y), real(v.z); }
  void sym2(ref::Sym2 m) { real(m.xx), real(m.xy), real(m.yy); }
};

// The parameters a kernel loads from the input buffer for `function` (frag_coord excluded: the
// kernel passes its own) and the offset of `alpha2` among them (-1 when there is none).
struct Layout {
  std::uint32_t stride = 0;
  int alpha2_offset = -1;
  std::uint32_t alpha2_count = 0;
};

inline Layout layout_of(const Function& function) {
  Layout layout;
  for (const Parameter& parameter : function.parameters) {
    if (parameter.name == "frag_coord") continue;
    const std::uint32_t count = saagen::component_count(parameter.type);
    if (parameter.name == "alpha2") layout.alpha2_offset = static_cast<int>(layout.stride), layout.alpha2_count = count;
    layout.stride += count;
  }
  return layout;
}

// deferred-aniso's lighting pass (deferred_aniso_roughness, deferred_aniso_brdf): evaluated with
// the material's alpha^2 as the BRDFs are, on the tensor the geometry pass wrote.
inline bool is_tensor_lighting(const Function& function) {
  return function.role == FunctionRole::evaluate && function.name.rfind("deferred_aniso_", 0) == 0;
}

inline bool is_brdf(const Function& function) {
  return function.name.find("ggx") != std::string::npos || function.name.find("beckmann") != std::string::npos ||
         function.name == "ndf_clamp_tau" || is_tensor_lighting(function);
}

// The kernel S of the material's A = diag(alpha^2) + S, deferred-aniso's tensor.
inline ref::Sym2 material_tensor(const Material& material) { return material.a - ref::Sym2{material.alpha2.x, 0.0, material.alpha2.y}; }

// Packs a parameter that a BRDF input's material and directions i, o give (i or w, o, A, tau,
// A's diagonal as `filtered` (its xx where one filtered alpha^2 is taken), the kernel's xx as
// `kernel`, the kernel S as `tensor`, the isotropic lobe of (A's xx, alpha^2) as `lobe`, deferred-aniso's
// lobe of (S, alpha^2) as `tensor_lobe`); false for any other. Shared by the adversarial inputs here and the precision test's realistic
// ones.
inline bool pack_material_parameter(const Parameter& parameter, const Material& material, ref::Vec3 i, ref::Vec3 o, Packer& pack) {
  const std::string& name = parameter.name;
  if (name == "w" || name == "i")
    pack.vec3(i);
  else if (name == "o")
    pack.vec3(o);
  else if (name == "a")
    pack.sym2(material.a);
  else if (name == "tau")
    pack.real(material.tau);
  else if (name == "filtered" && parameter.type == "real")
    pack.real(material.a.xx);
  else if (name == "filtered")
    pack.vec2({material.a.xx, material.a.yy});
  else if (name == "lobe")
    for (double v : ref::ggx_filtered_lobe_isotropic(material.a.xx, material.alpha2.x)) pack.real(v);
  else if (name == "kernel")
    pack.real(material.a.xx - material.alpha2.x);
  else if (name == "tensor")
    // The PSD kernel S of A = diag(alpha^2) + S: the lighting pass's claims hold for any PSD
    // tensor, not only the kappa-clamped one deferred_aniso writes.
    pack.sym2(material_tensor(material));
  else if (name == "tensor_lobe")
    for (double v : ref::deferred_aniso_lobe(ref::Params{}, material_tensor(material), material.alpha2.x)) pack.real(v);
  else
    return false;
  return true;
}

// One element of adversarial inputs for a core/evaluate function, appended to `out`.
inline void pack_core_element(const Function& function, Rng& rng, std::vector<float>& out) {
  Packer pack{out};
  const Material material = adversarial_material(rng);
  const ref::Vec3 i = adversarial_direction(rng), o = adversarial_direction(rng);
  for (const Parameter& parameter : function.parameters) {
    const std::string& name = parameter.name;
    if (pack_material_parameter(parameter, material, i, o, pack)) continue;
    if (name == "alpha2") {
      if (is_brdf(function))
        parameter.type == "real" ? pack.real(material.alpha2.x) : pack.vec2(material.alpha2);
      else
        for (std::uint32_t k = 0; k < (parameter.type == "real" ? 1u : 2u); ++k) pack.real(filter_alpha2(rng));
    } else if (name.rfind("dslope_", 0) == 0 || name.rfind("dproj_", 0) == 0 || name.rfind("dn_", 0) == 0) {
      const std::uint32_t count = parameter.type == "real2" ? 2 : 3;
      for (std::uint32_t k = 0; k < count; ++k) pack.real(adversarial_component(rng));
    } else if (name == "h") {
      // G2 gets the half vector of its i and o; the NDFs any direction.
      const ref::Vec3 sum = i + o;
      pack.vec3(function.name.find("g2") != std::string::npos && ref::dot(sum, sum) > 0.0 ? ref::normalize(sum)
                                                                                          : adversarial_direction(rng));
    } else if (name == "normal_ws") {
      pack.vec3(adversarial_direction(rng));
    } else if (name == "light_ws") {
      pack.vec3(i);
    } else if (name == "view_ws") {
      pack.vec3(o);
    } else if (name == "covariance") {
      // deferred_aniso_covariance's output: PSD and unbounded by kappa (another material's kernel).
      const Material texture = adversarial_material(rng);
      pack.sym2(texture.a - ref::Sym2{texture.alpha2.x, 0.0, texture.alpha2.y});
    } else if (name == "tangent_ws" || name == "bitangent_ws") {
      pack.vec3(adversarial_direction(rng));
    } else if (name == "mean_length") {
      pack.real(adversarial_mean_length(rng));
    } else if (name == "slope_mean" || name == "slope_second") {
      for (std::uint32_t k = 0; k < (name == "slope_mean" ? 2u : 3u); ++k) pack.real(adversarial_component(rng));
    } else {
      throw std::runtime_error("no adversarial generator for parameter " + name + " of " + function.name);
    }
  }
}

// Replaces one or two of the `stride` floats at `element` with +-Inf or NaN.
inline void inject_non_finite(Rng& rng, float* element, std::uint32_t stride) {
  const std::uint32_t count = rng.chance(4) ? 2 : 1;
  for (std::uint32_t k = 0; k < count; ++k) element[rng.below(stride)] = static_cast<float>(non_finite_value(rng));
}

// ---------------------------------------------------------------------------------------------
// Wrappers: per-pixel fields of a quad (pixel p at quad position (p & 1, p >> 1)).

inline ref::Vec3 with_z(ref::Vec3 v, double z) {
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), xy = std::sqrt(v.x * v.x + v.y * v.y);
  if (xy == 0.0) return {r, 0.0, z};
  return {v.x / xy * r, v.y / xy * r, z};
}

// Four per-pixel unit-or-shorter vectors with adversarial differences.
inline void quad_vectors(Rng& rng, ref::Vec3 out[4]) {
  const ref::Vec3 base = adversarial_direction(rng);
  const std::uint32_t mode = rng.below(6);
  for (int p = 0; p < 4; ++p) {
    switch (mode) {
      case 0:
        out[p] = base;
        break;   // zero derivatives
      case 1: {  // smooth: differences from 1e-7 to 0.1
        const double step = std::pow(10.0, rng.uniform(-7.0, -1.0));
        const ref::Vec3 moved = base + step * random_unit(rng);
        out[p] = ref::dot(moved, moved) > 0.0 ? ref::normalize(moved) : base;
        break;
      }
      case 2:
        out[p] = adversarial_direction(rng);
        break;   // unrelated pixels
      case 3: {  // h_z crosses 0 inside the quad
        static constexpr double zs[] = {0.0, 1e-30, -1e-30, 1e-7, -1e-7, 1e-4, -1e-4, 1e-2};
        out[p] = with_z(base, zs[rng.below(std::size(zs))]);
        break;
      }
      case 4:
        out[p] = rng.chance(2) ? ref::Vec3{} : base;
        break;  // zero vectors
      default:
        out[p] = rng.uniform() * (rng.chance(2) ? base : adversarial_direction(rng));
        break;  // shorter than 1
    }
  }
}

// A tangent/bitangent for normal n: orthonormal, zero, parallel to n, or arbitrary (length <= 1).
inline void quad_frames(Rng& rng, const ref::Vec3 n[4], ref::Vec3 t[4], ref::Vec3 b[4]) {
  const std::uint32_t mode = rng.below(5);
  const double twist = rng.uniform(0.0, 2.0 * std::numbers::pi);
  for (int p = 0; p < 4; ++p) {
    const std::uint32_t pixel_mode = mode == 4 ? rng.below(4) : mode;
    switch (pixel_mode) {
      case 0: {  // orthonormal frame around n (any n, also zero or short)
        const ref::Vec3 axis = std::fabs(n[p].z) < 0.9 ? ref::Vec3{0, 0, 1} : ref::Vec3{1, 0, 0};
        ref::Vec3 u = ref::cross(axis, n[p]);
        u = ref::dot(u, u) > 0.0 ? ref::normalize(u) : ref::Vec3{1, 0, 0};
        const ref::Vec3 v = ref::dot(n[p], n[p]) > 0.0 ? ref::cross(ref::normalize(n[p]), u) : ref::Vec3{0, 1, 0};
        const double angle = twist + 1e-3 * p;
        t[p] = std::cos(angle) * u + std::sin(angle) * v;
        b[p] = -std::sin(angle) * u + std::cos(angle) * v;
        break;
      }
      case 1:
        t[p] = rng.chance(2) ? ref::Vec3{} : random_unit(rng), b[p] = ref::Vec3{};
        break;  // zero
      case 2:
        t[p] = n[p], b[p] = n[p];
        break;  // parallel to n
      default:
        t[p] = rng.uniform() * random_unit(rng), b[p] = rng.uniform() * random_unit(rng);
        break;
    }
  }
}

// The per-pixel fields of one quad of a wrapper, appended pixel after pixel; the caller places
// pixels in the image. Filters get a per-quad filter alpha^2; BRDF wrappers a BRDF alpha^2.
inline void pack_wrapper_quad(const Function& wrapper, Rng& rng, std::vector<float> pixels[4]) {
  ref::Vec3 first[4], second[4], t[4], b[4];
  quad_vectors(rng, first);
  bool have_second = false;
  double alpha2[2] = {filter_alpha2(rng), filter_alpha2(rng)};
  if (is_brdf(wrapper)) alpha2[0] = brdf_alpha2(rng), alpha2[1] = brdf_alpha2(rng);
  for (const Parameter& parameter : wrapper.parameters) {
    if (parameter.name == "o" || parameter.name == "half_ws") {
      quad_vectors(rng, second);
      for (int p = 0; p < 4; ++p)
        if (rng.chance(8)) second[p] = -1.0 * first[p];  // o = -i: a zero half vector
      have_second = true;
    }
  }
  (void)have_second;
  quad_frames(rng, first, t, b);
  for (int p = 0; p < 4; ++p) {
    Packer pack{pixels[p]};
    for (const Parameter& parameter : wrapper.parameters) {
      const std::string& name = parameter.name;
      if (name == "frag_coord") continue;
      if (name == "alpha2") {
        pack.real(alpha2[0]);
        if (parameter.type == "real2") pack.real(alpha2[1]);
      } else if (name == "half_ts" || name == "normal_ws" || name == "i") {
        pack.vec3(first[p]);
      } else if (name == "o" || name == "half_ws") {
        pack.vec3(second[p]);
      } else if (name == "tangent_ws") {
        pack.vec3(t[p]);
      } else if (name == "bitangent_ws") {
        pack.vec3(b[p]);
      } else {
        throw std::runtime_error("no adversarial generator for parameter " + name + " of " + wrapper.name);
      }
    }
  }
}

// Pixel index (row-major, width `width`) of pixel p of quad q, quads in row-major order.
inline std::uint32_t quad_pixel_index(std::uint32_t quad, int p, std::uint32_t width) {
  const std::uint32_t quads_per_row = width / 2;
  const std::uint32_t x = 2 * (quad % quads_per_row) + (p & 1), y = 2 * (quad / quads_per_row) + (p >> 1);
  return y * width + x;
}

// A kernel body for a wrapper in a quad_compute kernel: every parameter but frag_coord loaded
// from this pixel's fields, frag_coord from the kernel, every result component stored.
inline std::string wrapper_body(const Function& wrapper, std::uint32_t stride) {
  std::string body, arguments;
  std::uint32_t offset = 0;
  for (const Parameter& parameter : wrapper.parameters) {
    if (!arguments.empty()) arguments += ", ";
    if (parameter.name == "frag_coord") {
      arguments += parameter.type + "(saagen_frag_coord)";  // converts in half-precision forms
      continue;
    }
    const std::uint32_t count = saagen::component_count(parameter.type);
    std::string loads;
    for (std::uint32_t k = 0; k < count; ++k) {
      if (k) loads += ", ";
      loads += "SAAGEN_LOAD(saagen_index * " + std::to_string(stride) + " + " + std::to_string(offset++) + ")";
    }
    body += "    " + parameter.type + " saagen_arg_" + parameter.name + " = " + parameter.type + "(" + loads + ");\n";
    arguments += "saagen_arg_" + parameter.name;
  }
  body += "    " + wrapper.return_type + " saagen_result = " + wrapper.name + "(" + arguments + ");\n";
  const std::uint32_t results = saagen::component_count(wrapper.return_type);
  for (std::uint32_t k = 0; k < results; ++k) {
    body += "    SAAGEN_STORE(" + std::to_string(k) + ", saagen_result" + (results == 1 ? std::string() : std::string(".") + "xyzw"[k]) +
            ");\n";
  }
  return body;
}

// ---------------------------------------------------------------------------------------------
// NaN-propagating min, max and clamp. GLSL and SPIR-V leave min/max/clamp undefined for NaN, and
// lavapipe (like D3D) returns the other operand, which hides a NaN the paper form computes
// (min(NaN, KAPPA) = KAPPA). Prepended to an emitted file, this prelude redefines min, max,
// clamp (and HLSL saturate) to return NaN whenever an operand is NaN (IEEE 754-2019 minimum /
// maximum): the strictest behaviour an implementation may have. A form whose outputs stay
// finite under it never forms a NaN that a min/max/clamp would have to hide.
inline std::string strict_nan_prelude(const std::string& target) {
  const bool glsl = target == "glsl";
  const std::string f1 = "float", f2 = glsl ? "vec2" : "float2", f3 = glsl ? "vec3" : "float3";
  std::string text = "// saagen stability sweep: NaN-propagating min/max/clamp\n";
  for (const char* op : {"min", "max"}) {
    const std::string name = std::string("saagen_strict_") + op;
    text += "float " + name + "(float a, float b) { return (isnan(a) || isnan(b)) ? a + b : " + op + "(a, b); }\n";
    text += f2 + " " + name + "(" + f2 + " a, " + f2 + " b) { return " + f2 + "(" + name + "(a.x, b.x), " + name + "(a.y, b.y)); }\n";
    text += f3 + " " + name + "(" + f3 + " a, " + f3 + " b) { return " + f3 + "(" + name + "(a.x, b.x), " + name + "(a.y, b.y), " + name +
            "(a.z, b.z)); }\n";
    text += f2 + " " + name + "(" + f2 + " a, float b) { return " + name + "(a, " + f2 + "(b, b)); }\n";
    text += f3 + " " + name + "(" + f3 + " a, float b) { return " + name + "(a, " + f3 + "(b, b, b)); }\n";
  }
  for (const std::string& type : {f1, f2, f3}) {
    text += type + " saagen_strict_clamp(" + type + " x, " + type + " lo, " + type +
            " hi) { return saagen_strict_min(saagen_strict_max(x, lo), hi); }\n";
    if (type != f1) {
      text +=
          type + " saagen_strict_clamp(" + type + " x, float lo, float hi) { return saagen_strict_min(saagen_strict_max(x, lo), hi); }\n";
    }
  }
  text += "#define min(a, b) saagen_strict_min(a, b)\n#define max(a, b) saagen_strict_max(a, b)\n";
  text += "#define clamp(x, lo, hi) saagen_strict_clamp(x, lo, hi)\n";
  if (!glsl) text += "#define saturate(x) saagen_strict_clamp(x, 0.0, 1.0)\n";
  (void)f1;
  return text;
}

}  // namespace saagen::stability
