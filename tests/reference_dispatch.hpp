// Shared by the suites that compare emitted code with the double reference: reading packed fp32
// inputs back as doubles, and evaluating a fragment wrapper's reference on a 2x2 quad by name.
#pragma once

#include "saagen/reference/reference.hpp"

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace saagen::test {

// Reads packed fp32 inputs back as doubles, in parameter order.
class FloatReader {
 public:
  explicit FloatReader(const float* data) : data_(data) {}
  double real() { return data_[next_++]; }
  ref::Vec2 vec2() { const double x = real(); return {x, real()}; }
  ref::Vec3 vec3() { const double x = real(), y = real(); return {x, y, real()}; }
  ref::Sym2 sym2() { const double x = real(), y = real(); return {x, y, real()}; }

 private:
  const float* data_;
  std::size_t next_ = 0;
};

inline std::vector<double> output_values(double v) { return {v}; }
inline std::vector<double> output_values(ref::Vec2 v) { return {v.x, v.y}; }
inline std::vector<double> output_values(ref::Sym2 m) { return {m.xx, m.xy, m.yy}; }

// The reference of fragment wrapper `name` at `pixel` of the first quad (pixel centres at .5),
// given the quad values of its vector parameters by parameter name (half_ts, normal_ws,
// tangent_ws, bitangent_ws, i, o).
inline std::vector<double> wrapper_reference_on_quad(const std::string& name, const ref::Params& p, ref::Vec2 alpha2,
                                                     std::map<std::string, ref::Quad<ref::Vec3>>& vectors, int pixel,
                                                     ref::Derivative mode = ref::Derivative::coarse) {
  const ref::Quad<ref::Vec2> frag{{0.5, 0.5}, {1.5, 0.5}, {0.5, 1.5}, {1.5, 1.5}};
  const auto& h = vectors["half_ts"];
  const auto& n = vectors["normal_ws"];
  if (name == "forward_aniso_slope_fragment") return output_values(ref::forward_aniso_slope_fragment_quad(p, alpha2, h, pixel, mode));
  if (name == "forward_aniso_projected_fragment") return output_values(ref::forward_aniso_projected_fragment_quad(p, alpha2, h, pixel, mode));
  if (name == "forward_axis_slope_fragment") return output_values(ref::forward_axis_slope_fragment_quad(p, alpha2, h, pixel, mode));
  if (name == "forward_axis_projected_fragment") return output_values(ref::forward_axis_projected_fragment_quad(p, alpha2, h, pixel, mode));
  if (name == "deferred_previous_fragment") {
    return output_values(ref::deferred_previous_fragment_quad(p, alpha2.x, n, vectors["tangent_ws"], vectors["bitangent_ws"], frag, pixel, mode));
  }
  if (name == "deferred_max_fragment") {
    return output_values(ref::deferred_max_fragment_quad(p, alpha2.x, n, vectors["tangent_ws"], vectors["bitangent_ws"], frag, pixel, mode));
  }
  if (name == "deferred_max_tangent_free_fragment") return output_values(ref::deferred_max_tangent_free_fragment_quad(p, alpha2.x, n, pixel, mode));
  if (name == "deferred_sum_fragment") return output_values(ref::deferred_sum_fragment_quad(p, alpha2.x, n, pixel, mode));
  if (name == "deferred_avg_fragment") return output_values(ref::deferred_avg_fragment_quad(p, alpha2.x, n, pixel, mode));
  if (name == "deferred_projected_space_fragment") return output_values(ref::deferred_projected_space_fragment_quad(p, alpha2.x, n, pixel, mode));
  if (name == "ggx_brdf_filtered_fragment") return output_values(ref::ggx_brdf_filtered_fragment_quad(p, vectors["i"], vectors["o"], alpha2, pixel, mode));
  if (name == "beckmann_brdf_filtered_fragment") {
    return output_values(ref::beckmann_brdf_filtered_fragment_quad(p, vectors["i"], vectors["o"], alpha2, pixel, mode));
  }
  throw std::runtime_error("no reference for " + name);
}

}  // namespace saagen::test
