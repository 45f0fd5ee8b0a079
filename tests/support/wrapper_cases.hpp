// The fragment wrappers' scene and reference, shared by the suites that run the wrappers with
// real quad derivatives (test_gpu_fragment: Vulkan; test_webgl: WebGL2). The shader computes an
// analytic sphere's fields per pixel (scene_body), calls the wrapper (wrapper_call) and stores the
// fields next to the result; the reference is fed the same fp32 fields as 2x2 quads.
//
// Bound per output: 16 ulps * sum_k |df/dx_k| |x_k| + 2e-5 |f| + 1e-30, the first-order
// componentwise condition bound over every fp32 input field component x_k of the four pixels of
// the quad that the wrapper reads (partials by finite differences of the reference). The
// shader's roundings before the differences (normalize, the frame change, the slope division:
// about 8 ulps mapped back to its inputs) act like input perturbations, which the quad
// differences then amplify; 16 ulps is twice that. 2e-5 |f| is the rounding of the filter
// itself (test_gpu_core).
#pragma once

#include "reference_dispatch.hpp"

#include "saagen/front/catalogue.hpp"
#include "saagen/reference/reference.hpp"
#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace saagen::test::wrappers {

namespace ref = saagen::ref;
using ref::Quad;
using ref::Vec2;
using ref::Vec3;

inline constexpr std::uint32_t width = 128, height = 128;
inline constexpr std::uint32_t result_offset = 23;  // fields first, then up to 3 result floats
inline constexpr std::uint32_t stride = 26;

// Scene: a sphere of radius 58 px centred at (64, 60), light direction (0.3, 0.5, 0.8), view
// along +z, alpha^2 = (0.0025, 0.0009).
inline const Vec2 material_alpha2{0.0025, 0.0009};

// Field layout per pixel: n 0-2, t 3-5, b 6-8, half_ts 9-11, i_ts 12-14, o_ts 15-17, frag 18-19,
// half_ws 20-22.
inline const char* const scene_body = R"(
    real2 centre = real2(64.0, 60.0);
    real2 p = (saagen_frag_coord - centre) / 58.0;
    // Beyond 0.95 of the radius the field continues radially, so every quad sees a smooth field
    // and the frame below never degenerates.
    p = p * min(1.0, sqrt(0.9 / max(dot(p, p), 1e-8)));
    real3 n = normalize(real3(p.x, -p.y, sqrt(1.0 - dot(p, p))));
    real3 t = normalize(real3(n.z, 0.0, -n.x));
    real3 b = cross(n, t);
    real3 light = normalize(real3(0.3, 0.5, 0.8));
    real3 view = real3(0.0, 0.0, 1.0);
    real3 i_ts = real3(dot(light, t), dot(light, b), dot(light, n));
    real3 o_ts = real3(dot(view, t), dot(view, b), dot(view, n));
    real3 half_ts = normalize(i_ts + o_ts);
    real3 half_ws = normalize(light + view);
    real2 alpha2 = real2(0.0025, 0.0009);  // material_alpha2
    SAAGEN_STORE(0, n.x); SAAGEN_STORE(1, n.y); SAAGEN_STORE(2, n.z);
    SAAGEN_STORE(3, t.x); SAAGEN_STORE(4, t.y); SAAGEN_STORE(5, t.z);
    SAAGEN_STORE(6, b.x); SAAGEN_STORE(7, b.y); SAAGEN_STORE(8, b.z);
    SAAGEN_STORE(9, half_ts.x); SAAGEN_STORE(10, half_ts.y); SAAGEN_STORE(11, half_ts.z);
    SAAGEN_STORE(12, i_ts.x); SAAGEN_STORE(13, i_ts.y); SAAGEN_STORE(14, i_ts.z);
    SAAGEN_STORE(15, o_ts.x); SAAGEN_STORE(16, o_ts.y); SAAGEN_STORE(17, o_ts.z);
    SAAGEN_STORE(18, saagen_frag_coord.x); SAAGEN_STORE(19, saagen_frag_coord.y);
    SAAGEN_STORE(20, half_ws.x); SAAGEN_STORE(21, half_ws.y); SAAGEN_STORE(22, half_ws.z);
)";

// The wrapper call, its arguments chosen by parameter name, and the stores of its result.
inline std::string wrapper_call(const saagen::Function& wrapper) {
  static const std::map<std::string, std::string> argument_for_parameter = {{"half_ts", "half_ts"}, {"half_ws", "half_ws"},
                                                                            {"normal_ws", "n"},     {"tangent_ws", "t"},
                                                                            {"bitangent_ws", "b"},  {"frag_coord", "saagen_frag_coord"},
                                                                            {"i", "i_ts"},          {"o", "o_ts"}};
  std::string arguments;
  for (const saagen::Parameter& parameter : wrapper.parameters) {
    if (!arguments.empty()) arguments += ", ";
    if (parameter.name == "alpha2")
      arguments += parameter.type == "real" ? "alpha2.x" : "alpha2";
    else
      arguments += argument_for_parameter.at(parameter.name);
  }
  std::string body = fmt::format("    {} saagen_result = {}({});\n", wrapper.return_type, wrapper.name, arguments);
  const std::uint32_t count = saagen::component_count(wrapper.return_type);
  for (std::uint32_t k = 0; k < count; ++k) {
    body += fmt::format("    SAAGEN_STORE({}, saagen_result{});\n", result_offset + k, count == 1 ? "" : std::string(".") + "xyzw"[k]);
  }
  return body;
}

struct PixelFields {
  Vec3 n, t, b, half_ts, i_ts, o_ts;
  Vec2 frag;
  Vec3 half_ws;
};

inline PixelFields fields_at(const std::vector<float>& out, std::uint32_t x, std::uint32_t y) {
  const float* f = out.data() + (std::size_t{y} * width + x) * stride;
  const auto vec3 = [&](int k) { return Vec3{f[k], f[k + 1], f[k + 2]}; };
  return {vec3(0), vec3(3), vec3(6), vec3(9), vec3(12), vec3(15), Vec2{f[18], f[19]}, vec3(20)};
}

// The vector fields (n, t, b, half_ts, i_ts, o_ts, half_ws) each wrapper reads.
inline std::vector<Vec3 PixelFields::*> fields_read_by(const std::string& wrapper) {
  if (wrapper.ends_with("_transported_fragment")) return {&PixelFields::half_ws, &PixelFields::n, &PixelFields::t, &PixelFields::b};
  if (wrapper.rfind("forward_", 0) == 0) return {&PixelFields::half_ts};
  if (wrapper == "deferred_previous_fragment" || wrapper == "deferred_max_fragment")
    return {&PixelFields::n, &PixelFields::t, &PixelFields::b};
  if (wrapper.rfind("deferred_", 0) == 0) return {&PixelFields::n};
  return {&PixelFields::i_ts, &PixelFields::o_ts};
}

inline double& component(Vec3& v, int k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }

template <class T, class Field>
inline Quad<T> quad_of(const std::vector<PixelFields>& quad, Field field) {
  return {field(quad[0]), field(quad[1]), field(quad[2]), field(quad[3])};
}

// The reference of a wrapper at one pixel of a quad: the shared dispatch
// (reference_dispatch.hpp, wrapper_reference_on_quad) fed the quad's fields.
// `average`: how the quad-average normal of deferred-previous/-max takes its derivatives.
// `p`: the emission's constants (the half guard constants for a half-precision file).
inline std::vector<double> reference_wrapper(const std::string& name, const std::vector<PixelFields>& q, int pixel, ref::Derivative mode,
                                             ref::Derivative average = ref::Derivative::fine, const ref::Params& p = {}) {
  const Vec2 alpha2 = material_alpha2;
  const auto n = quad_of<Vec3>(q, [](const PixelFields& f) { return f.n; });
  const auto t = quad_of<Vec3>(q, [](const PixelFields& f) { return f.t; });
  const auto b = quad_of<Vec3>(q, [](const PixelFields& f) { return f.b; });
  const auto h = quad_of<Vec3>(q, [](const PixelFields& f) { return f.half_ts; });
  const auto h_ws = quad_of<Vec3>(q, [](const PixelFields& f) { return f.half_ws; });
  const auto i = quad_of<Vec3>(q, [](const PixelFields& f) { return f.i_ts; });
  const auto o = quad_of<Vec3>(q, [](const PixelFields& f) { return f.o_ts; });
  const auto frag = quad_of<Vec2>(q, [](const PixelFields& f) { return f.frag; });
  std::map<std::string, Quad<Vec3>> vectors = {{"half_ts", h},      {"half_ws", h_ws}, {"normal_ws", n}, {"tangent_ws", t},
                                               {"bitangent_ws", b}, {"i", i},          {"o", o}};
  return wrapper_reference_on_quad(name, p, alpha2, vectors, pixel, mode, average, frag);
}

// A run's per-pixel results next to the reference fed the run's own fields, with the bound of the
// file comment per output.
struct WrapperComparison {
  std::vector<float> got;
  std::vector<double> expected, bound;
};

inline WrapperComparison reference_with_bounds(const std::string& wrapper, std::uint32_t outputs_per_pixel, const std::vector<float>& out,
                                               ref::Derivative mode, ref::Derivative average = ref::Derivative::fine,
                                               const ref::Params& params = {}) {
  WrapperComparison comparison;
  auto& got = comparison.got;
  auto& expected = comparison.expected;
  auto& bound = comparison.bound;
  for (std::uint32_t qy = 0; qy < height; qy += 2) {
    for (std::uint32_t qx = 0; qx < width; qx += 2) {
      std::vector<PixelFields> quad;
      for (int pixel = 0; pixel < 4; ++pixel) quad.push_back(fields_at(out, qx + (pixel & 1), qy + (pixel >> 1)));
      std::vector<std::vector<double>> values, condition;
      for (int pixel = 0; pixel < 4; ++pixel) {
        values.push_back(reference_wrapper(wrapper, quad, pixel, mode, average, params));
        condition.emplace_back(values.back().size(), 0.0);
      }
      // sum_k |df/dx_k| |x_k| by one-sided differences with a relative step of 1e-7.
      for (int source = 0; source < 4; ++source) {
        for (Vec3 PixelFields::*field : fields_read_by(wrapper)) {
          for (int k = 0; k < 3; ++k) {
            auto moved = quad;
            double& x = component(moved[source].*field, k);
            const double original = x, step = 1e-7 * std::max(std::fabs(original), 1e-6);
            x = original + step;
            for (int pixel = 0; pixel < 4; ++pixel) {
              const auto shifted = reference_wrapper(wrapper, moved, pixel, mode, average, params);
              for (std::size_t j = 0; j < shifted.size(); ++j) {
                condition[pixel][j] += std::fabs(shifted[j] - values[pixel][j]) / step * std::fabs(original);
              }
            }
          }
        }
      }
      for (int pixel = 0; pixel < 4; ++pixel) {
        const std::uint32_t x = qx + (pixel & 1), y = qy + (pixel >> 1);
        for (std::uint32_t k = 0; k < outputs_per_pixel; ++k) {
          got.push_back(out[(std::size_t{y} * width + x) * stride + result_offset + k]);
          expected.push_back(values[pixel][k]);
          bound.push_back(16.0 * std::ldexp(condition[pixel][k], -24) + 2e-5 * std::fabs(values[pixel][k]) + 1e-30);
        }
      }
    }
  }
  return comparison;
}

}  // namespace saagen::test::wrappers
