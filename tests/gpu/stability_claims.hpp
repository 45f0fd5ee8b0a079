// What every public function of every variant guarantees (docs/STABILITY.md), as code.
// The property tests (test_stability_properties), the adversarial sweep (test_stability_sweep)
// and the half-precision test (test_precision) judge outputs with these claims.
//
// A claim holds for FINITE inputs inside the function's domain (kDomain below); for inputs with
// an Inf or NaN component nothing is claimed (GLSL/HLSL min, max and clamp are undefined for
// NaN), and the unguarded paper form (EmitOptions::guards = false) claims nothing at all: the
// sweep only counts what they do.
//
// Tolerances are fp32 rounding, stated once here:
//  - kKappaSlack: out - alpha^2 <= kappa + 2^-22. fl(a + k) exceeds a + k by at most half an ulp
//    of a value below 2 (2^-24), and KAPPA itself is the fp32 rounding of kappa (|0.18f - 0.18| =
//    7.2e-9 < 2^-26); 2^-22 covers both with a factor 3 to spare.
//  - kProjectedSlack: the projected-space form ends with a division (a + ks) / (1 + ks), whose
//    rounding (1 ulp correctly rounded; Vulkan allows 2.5) and that of the two sums can put the
//    result up to ~3 ulps of 1 below alpha^2 or above 1 in exact terms: 2^-22 is 4 ulps of 1.
//  - kPsdSlack, kPsdUnderflow: det(A) = A00 A11 - A01^2 >= -2^-20 A00 A11 - 2^-122 (A00 + A11).
//    Each entry of the kernel is a sum of two products, rounded; by Cauchy-Schwarz
//    (|du.x du.y| + |dv.x dv.y|)^2 <= K00 K11, so the rounding errors can make A01^2 exceed
//    A00 A11 by at most ~(4 gamma_2 + 2 u) A00 A11 = ~10 u A00 A11 with u = 2^-24: 2^-20 = 16 u.
//    Products below FLT_MIN = 2^-126 underflow (or flush to zero, which Vulkan allows): K11 can
//    come out 0 while its exact value is up to 2 sigma^2 * 2 FLT_MIN <= 16 FLT_MIN (sigma^2 <= 4),
//    and A01^2 <= A00 K11 then exceeds A00 A11 by at most 16 FLT_MIN A00 = 2^-122 A00.
//  - kTensorSlack: deferred-aniso's tensor trace K00 + K11 <= kappa (the bound), so each
//    diagonal entry <= kappa and the off-diagonal <= kappa / 2, plus 2^-21. The factor
//    kappa / max(kappa / (2 sigma^2), tr) rounds the quotient, the trace and the division (the
//    maximum is exact), each entry's product once more and the sum of the two diagonal entries
//    once, with a rounded SIGMA2 and KAPPA: 7 units of 2^-24 of kappa <= 1, 2^-21 = 8. Its PSD
//    check is kPsdSlack's: one factor times Delta^T Delta, whose entries are as above.
#pragma once

#include "saagen/reference/reference.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <string_view>

namespace saagen::stability {

enum class Claim {
  roughness_matrix,       // forward-aniso-*: A finite, A00 >= ax^2, A11 >= ay^2, det(A) >= -(rounding)
  saturated,              // forward-axis-*, deferred-{previous,max,sum,avg}: min(a, 1) <= out <= 1, out - a <= kappa
  projected_space,        // deferred-projected-space: a = saturate(alpha^2) <= out <= 1, out - a <= kappa
  brdf_value,             // NDFs, G2, BRDFs: finite, >= 0
  smith_lambda,           // Lambdas: finite, >= kLambdaFloor (Walter's Beckmann fit dips below 0)
  clamp_tau,              // ndf_clamp_tau: finite, >= 0
  variance,               // toksvig_variance: finite, >= 0
  covariance,             // lean_covariance, deferred_aniso_covariance: finite, diagonal >= 0, det >= -(rounding)
  prefiltered,            // prefilter_toksvig(_sum), prefilter_lean_sum: min(a, 1) <= out <= 1 (the texture term is not clamped)
  prefiltered_projected,  // prefilter_*_projected: saturate(a) <= out <= 1 (+-2^-22)
  kernel_tensor,          // deferred_aniso(_fragment): finite, K00, K11 >= 0, K00 + K11 <= kappa, |K01| <= kappa / 2, det K >= -(rounding)
  isotropic_lobe,         // ggx_filtered_lobe_isotropic, deferred_aniso_lobe: finite, alpha^2 lambda > 0, 0 < w <= 1, 1 / (4 m) or
                          // 1 / sqrt(det 2 M) > 0, 0 <= f / 2 <= 0.0861 (+2^-8)
  tensor_roughness,  // deferred_aniso_roughness(_with_covariance): finite, A00, A11 >= alpha^2, det A >= -(rounding) (for PSD tensor and
                     // covariance)
};

inline constexpr double kKappaSlack = 0x1p-22;
inline constexpr double kProjectedSlack = 0x1p-22;
inline constexpr double kPsdSlack = 0x1p-20;
inline constexpr double kPsdUnderflow = 0x1p-122;
inline constexpr double kTensorSlack = 0x1p-21;
// kLobeSlack: ggx_filtered_lobe_isotropic's and deferred_aniso_lobe's w = u / (u lambda) <= 1 (u lambda >= u) and f / 2 =
// w (0.264335 - 0.20302 w) in [0, 0.08605] (its peak at w = 0.651), each after a division that
// Vulkan bounds to 2.5 ulps, in half precision too (the precision test judges fp16 results):
// 2.5 ulps of 1 in fp16 are 2.5 x 2^-10 < 2^-8.
inline constexpr double kLobeSlack = 0x1p-8;
// Walter et al.'s rational Lambda fit has numerator roots at a = 1.5498 and 1.6296, so for
// 1.5498 < a < 1.6 it is slightly negative: its minimum is -6.0e-5 (at a = 1.585); GGX's Lambda
// is >= 0 up to rounding of -0.5 + x with x >= 0.5.
inline constexpr double kLambdaFloor = -1e-4;

inline Claim claim_of(std::string_view function) {
  const auto starts = [&](std::string_view prefix) { return function.substr(0, prefix.size()) == prefix; };
  if (starts("forward_aniso_") || function == "prefilter_lean" || starts("prefilter_lean_aniso")) return Claim::roughness_matrix;
  if (function == "toksvig_variance") return Claim::variance;
  if (function == "lean_covariance" || function == "deferred_aniso_covariance") return Claim::covariance;
  if (starts("prefilter_") && function.ends_with("_projected")) return Claim::prefiltered_projected;
  if (starts("prefilter_")) return Claim::prefiltered;
  if (function == "deferred_aniso" || function == "deferred_aniso_fragment") return Claim::kernel_tensor;
  if (function == "deferred_aniso_roughness" || function == "deferred_aniso_roughness_with_covariance") return Claim::tensor_roughness;
  if (function == "deferred_aniso_lobe") return Claim::isotropic_lobe;
  if (function.rfind("deferred_aniso_brdf", 0) == 0) return Claim::brdf_value;
  if (starts("deferred_projected_space")) return Claim::projected_space;
  if (starts("forward_axis_") || starts("deferred_")) return Claim::saturated;
  if (function == "ndf_clamp_tau") return Claim::clamp_tau;
  if (function == "ggx_filtered_lobe_isotropic") return Claim::isotropic_lobe;
  if (function.find("_lambda_") != std::string_view::npos) return Claim::smith_lambda;
  return Claim::brdf_value;
}

inline std::string_view describe(Claim claim) {
  switch (claim) {
    case Claim::roughness_matrix:
      return "finite; A00 >= ax^2, A11 >= ay^2; PSD: det A >= -2^-20 A00 A11 - 2^-122 (A00 + A11)";
    case Claim::saturated:
      return "finite; min(a,1) <= a' <= 1; a' - a <= kappa";
    case Claim::projected_space:
      return "finite; saturate(a) <= a' <= 1 (+-2^-22); a' - a <= kappa";
    case Claim::brdf_value:
      return "finite; >= 0";
    case Claim::smith_lambda:
      return "finite; >= -1e-4";
    case Claim::clamp_tau:
      return "finite; >= 0";
    case Claim::variance:
      return "finite; >= 0";
    case Claim::covariance:
      return "finite; S00, S11 >= 0; det S >= -2^-20 S00 S11 - 2^-122 (S00 + S11)";
    case Claim::prefiltered:
      return "finite; min(a,1) <= a' <= 1 (texture term unclamped)";
    case Claim::prefiltered_projected:
      return "finite; saturate(a) <= a' <= 1 (+-2^-22)";
    case Claim::kernel_tensor:
      return "finite; K00, K11 in [0, kappa], |K01| <= kappa / 2 (+2^-21); PSD: det K >= -2^-20 K00 K11 - 2^-122 (K00 + K11)";
    case Claim::isotropic_lobe:
      return "finite; alpha^2 lambda > 0; 0 < w <= 1; 1 / (4 m) or 1 / sqrt(det 2 M) > 0; 0 <= f / 2 <= 0.0861 (+-2^-8)";
    case Claim::tensor_roughness:
      return "finite; A00, A11 >= alpha^2; PSD: det A >= -2^-20 A00 A11 - 2^-122 (A00 + A11)";
  }
  return "";
}

// The filters' alpha^2 inputs: the function's `alpha2` parameter (1 or 2 values).
struct Verdict {
  bool non_finite = false;
  bool out_of_bound = false;
  std::string why;  // filled when asked, for the first failure a test reports
  bool ok() const { return !non_finite && !out_of_bound; }
};

inline Verdict judge(Claim claim, double kappa, std::span<const double> alpha2, std::span<const double> out, bool explain = false) {
  Verdict verdict;
  for (double v : out) {
    if (!std::isfinite(v)) verdict.non_finite = true;
  }
  if (verdict.non_finite) {
    if (explain) verdict.why = "non-finite output";
    return verdict;
  }
  const auto fail = [&](const char* what) {
    verdict.out_of_bound = true;
    if (explain && verdict.why.empty()) verdict.why = what;
  };
  switch (claim) {
    case Claim::roughness_matrix: {
      if (out[0] < alpha2[0]) fail("A00 < ax^2");
      if (out[2] < alpha2[1]) fail("A11 < ay^2");
      if (out[0] * out[2] - out[1] * out[1] < -kPsdSlack * out[0] * out[2] - kPsdUnderflow * (out[0] + out[2])) {
        fail("det A < 0 beyond rounding");
      }
      break;
    }
    case Claim::saturated: {
      for (std::size_t k = 0; k < out.size(); ++k) {
        const double a = alpha2[k];
        if (out[k] < std::min(a, 1.0)) fail("a' < min(a, 1)");
        if (out[k] > 1.0) fail("a' > 1");
        if (out[k] - a > kappa + kKappaSlack) fail("a' - a > kappa");
      }
      break;
    }
    case Claim::projected_space: {
      const double a = ref::saturate(alpha2[0]);
      if (out[0] < a - kProjectedSlack) fail("a' < saturate(a)");
      if (out[0] > 1.0 + kProjectedSlack) fail("a' > 1");
      if (out[0] - a > kappa + kProjectedSlack) fail("a' - a > kappa");
      break;
    }
    case Claim::kernel_tensor: {
      if (out[0] < 0.0 || out[2] < 0.0) fail("negative K00 or K11");
      if (out[0] + out[2] > kappa + kTensorSlack) fail("K00 + K11 > kappa");
      if (std::fabs(out[1]) > 0.5 * kappa + kTensorSlack) fail("|K01| > kappa / 2");
      if (out[0] * out[2] - out[1] * out[1] < -kPsdSlack * out[0] * out[2] - kPsdUnderflow * (out[0] + out[2])) {
        fail("det K < 0 beyond rounding");
      }
      break;
    }
    case Claim::isotropic_lobe: {
      if (!(out[0] > 0.0)) fail("alpha^2 lambda <= 0");
      if (!(out[1] > 0.0) || out[1] > 1.0 + kLobeSlack) fail("w outside (0, 1]");
      if (!(out[2] > 0.0)) fail("1 / (4 m) or 1 / sqrt(det 2 M) <= 0");
      if (out[3] < -kLobeSlack || out[3] > 0.0861 + kLobeSlack) fail("f / 2 outside [0, 0.0861]");
      break;
    }
    case Claim::tensor_roughness: {
      if (out[0] < alpha2[0] || out[2] < alpha2[0]) fail("A00 or A11 < alpha^2");
      if (out[0] * out[2] - out[1] * out[1] < -kPsdSlack * out[0] * out[2] - kPsdUnderflow * (out[0] + out[2])) {
        fail("det A < 0 beyond rounding");
      }
      break;
    }
    case Claim::covariance: {
      if (out[0] < 0.0 || out[2] < 0.0) fail("negative variance");
      if (out[0] * out[2] - out[1] * out[1] < -kPsdSlack * out[0] * out[2] - kPsdUnderflow * (out[0] + out[2])) {
        fail("det S < 0 beyond rounding");
      }
      break;
    }
    case Claim::prefiltered: {
      const double a = alpha2[0];
      if (out[0] < std::min(a, 1.0)) fail("a' < min(a, 1)");
      if (out[0] > 1.0) fail("a' > 1");
      break;
    }
    case Claim::prefiltered_projected: {
      const double a = ref::saturate(alpha2[0]);
      if (out[0] < a - kProjectedSlack) fail("a' < saturate(a)");
      if (out[0] > 1.0 + kProjectedSlack) fail("a' > 1");
      break;
    }
    case Claim::variance:
    case Claim::brdf_value:
    case Claim::clamp_tau:
      if (out[0] < 0.0) fail("negative");
      break;
    case Claim::smith_lambda:
      if (out[0] < kLambdaFloor) fail("Lambda < -1e-4");
      break;
  }
  return verdict;
}

}  // namespace saagen::stability
