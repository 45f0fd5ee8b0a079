// The exact filtered GGX slope density by quadrature, shared by the filtered-GGX tests: GGX(A0)
// is the scale mixture integral_0^inf e^-w N(0, A0 / (2w)) dw of Gaussians, so GGX(A0) convolved
// with N(0, Sigma) is integral_0^inf e^-w N(s; A0 / (2w) + Sigma) dw (docs/FILTERED_GGX.md), taken
// here in u = ln w with step 0.04 over [-60, 5).
#pragma once

#include "saagen/reference/reference.hpp"

#include <cmath>

namespace saagen::test {

inline double gaussian2(saagen::ref::Sym2 c, double x, double y) {
  const double det = c.xx * c.yy - c.xy * c.xy;
  const double q = (c.yy * x * x - 2.0 * c.xy * x * y + c.xx * y * y) / det;
  return std::exp(-0.5 * q) / (2.0 * saagen::ref::kPi * std::sqrt(det));
}

// A0 = diag(alpha2), Sigma the kernel's per-axis covariance (K / 2).
inline double anisotropic_slope_density(saagen::ref::Vec2 alpha2, saagen::ref::Sym2 sigma, double x, double y) {
  double sum = 0.0;
  constexpr double kStep = 0.04;
  for (double u = -60.0; u < 5.0; u += kStep) {
    const double w = std::exp(u);
    const saagen::ref::Sym2 c{alpha2.x / (2.0 * w) + sigma.xx, sigma.xy, alpha2.y / (2.0 * w) + sigma.yy};
    sum += w * std::exp(-w) * gaussian2(c, x, y);
  }
  return sum * kStep;
}

}  // namespace saagen::test
