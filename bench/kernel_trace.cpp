// kernel_trace: how large the deferred (normal-derivative) SAA kernels are next to the forward
// kernel of the projected half vector, per pixel of every scene (docs/DEFERRED_KERNEL.md).
//
//   kernel_trace [--size N] [--alpha A] [--images]     (defaults: 128, 0.01)
//
// For every hit pixel of the G-buffer (render_gbuffer, shading feed, coarse ddx/ddy as the
// 1-spp renderer takes them) it computes, in the alpha^2 domain:
//   forward   tr(A - diag(alpha^2)) / 2 of forward-aniso-projected (T&K 2019 Sec. 3.2): the
//             isotropic equivalent of the kernel matrix 2 Sigma;
//   deferred  filtered alpha^2 - alpha^2 of deferred-sum (T&K 2019 Eq. 4), deferred-avg (Eq. 5),
//             deferred-max (Eq. 1) and deferred-projected-space (T&K 2021), with kappa = 1e30 so
//             that the kappa clamp never acts (the saturate to [0, 1] still does: counted);
//   candidates deferred forms that also read n.h, which a deferred pass has per light:
//             sigma^2 (n.h)^2 (|dn_x|^2 + |dn_y|^2) and sigma^2 (n.h) (|dn_x|^2 + |dn_y|^2);
//   diagnostics the forward kernel with the world half vector held fixed (only the frame moves),
//             and with it held fixed in a frame parallel-transported from the pixel's own (only
//             the normal tilts; no twist of the tangent about n).
// Per scene and pooled it prints the statistics of each form's ratio to the forward kernel, and
// the least-squares constant c (in log space) with which c * basis tracks the forward kernel for
// the bases |dn_x|^2 + |dn_y|^2, (n.h)^2 (...) and (n.h) (...). Markdown on stdout.
//
// --images adds an image check: per scene and alpha (0.01, 0.05, 0.1; no Fresnel), LDR-FLIP and
// tonemapped RMSE against a 256-spp ground truth of the same size of the 1-spp images of no SAA,
// forward-aniso-projected, deferred-avg, deferred-sum (kappa = 0.18), the two candidates
// (saturate(alpha^2 + min(kernel, kappa))), the forward kernel's isotropic equivalent
// (kappa-clamped) and the matrix candidate diag(alpha^2) + 2 sigma^2 (n.h)^2 Dn^T Dn (Dn: the
// rows dn_x, dn_y in the tangent plane), shaded as shade_pixel shades them, once with the
// papers' GGX of the filtered roughness (checked against render_variant) and once with the
// tail-preserving filtered GGX (ggx_brdf_filtered_matrix / _axis, brdf.hpp).
#include "saagen/measure/flip.hpp"
#include "saagen/measure/render.hpp"
#include "saagen/reference/brdf.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace {

namespace measure = saagen::measure;
namespace ref = saagen::ref;
using ref::Quad;
using ref::Sym2;
using ref::Vec2;
using ref::Vec3;

constexpr ref::Derivative kMode = ref::Derivative::coarse;
// Kernels below this are zero (a quad whose partners all lie off the surface, a flat quad).
constexpr double kPositive = 1e-14;

struct Options {
  int size = 128;
  double alpha = 0.01;
  bool images = false;
};

// Every kernel of one pixel, alpha^2 domain, before the kappa clamp.
struct PixelKernels {
  double forward = 0.0;              // tr(A - diag(alpha^2)) / 2, forward-aniso-projected
  double forward_eigen_ratio = 0.0;  // lambda_min / lambda_max of A - diag(alpha^2) (0: a line)
  double frame_only = 0.0;           // the same with the world half vector held fixed
  double tilt_only = 0.0;            // ... and the frame parallel-transported (no twist)
  double normal_sum = 0.0;           // |dn_x|^2 + |dn_y|^2 (world-space shading normal, coarse)
  double half_z = 0.0;               // n.h
  double deferred_sum = 0.0;
  double deferred_avg = 0.0;
  double deferred_max = 0.0;
  double deferred_projected_space = 0.0;
  bool saturated = false;  // a deferred form hit saturate's 1
};

// v rotated by the smallest rotation that takes unit `from` to unit `to` (Rodrigues):
// c v + w x v + (w.v) w / (1 + c), c = from.to, w = from x to.
Vec3 rotate_between(Vec3 from, Vec3 to, Vec3 v) {
  const double c = ref::dot(from, to);
  const Vec3 w = ref::cross(from, to);
  return c * v + ref::cross(w, v) + (ref::dot(w, v) / (1.0 + c)) * w;
}

// tr(A - diag(alpha^2)) / 2 = sigma^2 (|d h.xy/dx|^2 + |d h.xy/dy|^2) from forward-aniso-projected
// (T&K 2019 Sec. 3.2) on a quad of tangent-space half vectors.
double forward_isotropic_kernel(const ref::Params& params, double alpha2, const Quad<Vec3>& half_ts, int pixel) {
  const Sym2 a = ref::forward_aniso_projected_fragment_quad(params, {alpha2, alpha2}, half_ts, pixel, kMode);
  return 0.5 * ref::trace(a - Sym2{alpha2, 0.0, alpha2});
}

// lambda_min / lambda_max of the forward kernel matrix 2 Sigma (1: isotropic, 0: one direction).
double forward_eigen_ratio(const ref::Params& params, double alpha2, const Quad<Vec3>& half_ts, int pixel) {
  const Sym2 a = ref::forward_aniso_projected_fragment_quad(params, {alpha2, alpha2}, half_ts, pixel, kMode);
  const Sym2 kernel = a - Sym2{alpha2, 0.0, alpha2};
  const double largest = ref::sym2_max_eigenvalue(kernel);
  return largest > kPositive ? (ref::trace(kernel) - largest) / largest : 1.0;
}

// The world half vector of the shaded pixel expressed in every quad pixel's own frame.
Quad<Vec3> half_in_partner_frames(const measure::QuadFields& q, Vec3 half_ws) {
  return ref::map_indexed(q.normal, [&](Vec3 n, int p) { return ref::to_tangent_space(half_ws, q.tangent[p], q.bitangent[p], n); });
}

// The world half vector of the shaded pixel in frames parallel-transported from the shaded
// pixel's frame to each partner's normal: only the tilt of the normal changes the coordinates.
Quad<Vec3> half_in_transported_frames(const measure::QuadFields& q, Vec3 half_ws) {
  const Vec3 n0 = q.normal[q.pixel], t0 = q.tangent[q.pixel], b0 = q.bitangent[q.pixel];
  return ref::map(q.normal,
                  [&](Vec3 n) { return ref::to_tangent_space(half_ws, rotate_between(n0, n, t0), rotate_between(n0, n, b0), n); });
}

// Filtered alpha^2 minus alpha^2 of every deferred form, kappa out of the way.
void add_deferred_kernels(const measure::QuadFields& q, double alpha2, PixelKernels& k) {
  ref::Params unclamped;
  unclamped.kappa = 1e30;
  const double sum = ref::deferred_sum_fragment_quad(unclamped, alpha2, q.normal, q.pixel, kMode);
  const double avg = ref::deferred_avg_fragment_quad(unclamped, alpha2, q.normal, q.pixel, kMode);
  const double max = ref::deferred_max_fragment_quad(unclamped, alpha2, q.normal, q.tangent, q.bitangent, q.frag_coord, q.pixel, kMode);
  const double projected = ref::deferred_projected_space_fragment_quad(unclamped, alpha2, q.normal, q.pixel, kMode);
  k.deferred_sum = sum - alpha2;
  k.deferred_avg = avg - alpha2;
  k.deferred_max = max - alpha2;
  k.deferred_projected_space = projected - alpha2;
  k.saturated = std::max({sum, avg, max}) >= 1.0;
}

PixelKernels pixel_kernels(const measure::GBuffer& gbuffer, int x, int y, double alpha2) {
  const measure::PixelFields& f = gbuffer.at(x, y);
  const measure::QuadFields q = measure::gather_quad(gbuffer, x, y);
  const ref::Params params;
  const Vec3 half_ws = ref::normalize(f.to_light + f.to_view);
  PixelKernels k;
  k.forward = forward_isotropic_kernel(params, alpha2, q.half_ts, q.pixel);
  k.forward_eigen_ratio = forward_eigen_ratio(params, alpha2, q.half_ts, q.pixel);
  k.frame_only = forward_isotropic_kernel(params, alpha2, half_in_partner_frames(q, half_ws), q.pixel);
  k.tilt_only = forward_isotropic_kernel(params, alpha2, half_in_transported_frames(q, half_ws), q.pixel);
  const Vec3 dn_dx = ref::ddx(q.normal, q.pixel, kMode), dn_dy = ref::ddy(q.normal, q.pixel, kMode);
  k.normal_sum = ref::dot(dn_dx, dn_dx) + ref::dot(dn_dy, dn_dy);
  k.half_z = f.half_ts.z;
  add_deferred_kernels(q, alpha2, k);
  return k;
}

std::vector<PixelKernels> scene_kernels(const measure::Scene& scene, const Options& options) {
  const measure::GBuffer gbuffer = measure::render_gbuffer(scene, options.size, options.size);
  std::vector<PixelKernels> kernels;
  for (int y = 0; y < gbuffer.height; ++y)
    for (int x = 0; x < gbuffer.width; ++x)
      if (gbuffer.at(x, y).hit) kernels.push_back(pixel_kernels(gbuffer, x, y, options.alpha * options.alpha));
  return kernels;
}

// ---------------------------------------------------------------------------------------------
// The forms compared with the forward kernel

using KernelOf = std::function<double(const PixelKernels&)>;

struct Form {
  std::string name;
  KernelOf kernel;
};

std::vector<Form> compared_forms() {
  const double sigma2 = ref::Params{}.sigma2;
  return {
      {"deferred-sum (Eq. 4)", [](const PixelKernels& k) { return k.deferred_sum; }},
      {"deferred-avg (Eq. 5)", [](const PixelKernels& k) { return k.deferred_avg; }},
      {"deferred-max (Eq. 1)", [](const PixelKernels& k) { return k.deferred_max; }},
      {"deferred-projected-space", [](const PixelKernels& k) { return k.deferred_projected_space; }},
      {"candidate: sigma^2 (n.h)^2 S", [sigma2](const PixelKernels& k) { return sigma2 * k.half_z * k.half_z * k.normal_sum; }},
      {"candidate: sigma^2 (n.h) S", [sigma2](const PixelKernels& k) { return sigma2 * k.half_z * k.normal_sum; }},
      {"diagnostic: forward, h fixed", [](const PixelKernels& k) { return k.frame_only; }},
      {"diagnostic: forward, h fixed, no twist", [](const PixelKernels& k) { return k.tilt_only; }},
  };
}

// Bases b whose constant c (c b ~ forward kernel) is fitted.
std::vector<Form> fitted_bases() {
  return {
      {"S", [](const PixelKernels& k) { return k.normal_sum; }},
      {"(n.h)^2 S", [](const PixelKernels& k) { return k.half_z * k.half_z * k.normal_sum; }},
      {"(n.h) S", [](const PixelKernels& k) { return k.half_z * k.normal_sum; }},
  };
}

// ---------------------------------------------------------------------------------------------
// Statistics

double median(std::vector<double> values) {
  if (values.empty()) return NAN;
  const std::size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  const double upper = values[middle];
  if (values.size() % 2) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + middle));
}

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return values.empty() ? NAN : sum / static_cast<double>(values.size());
}

double standard_deviation(const std::vector<double>& values) {
  const double m = mean(values);
  double sum = 0.0;
  for (double v : values) sum += (v - m) * (v - m);
  return values.size() < 2 ? NAN : std::sqrt(sum / static_cast<double>(values.size() - 1));
}

struct RatioStats {
  std::size_t pixels = 0;  // both kernels positive: the ratio statistics
  double median_ratio = NAN;
  double mean_ratio = NAN;
  double median_log = NAN;
  double mean_log = NAN;
  double sd_log = NAN;
  double over_twice = NAN;  // fraction with form > 2 forward, of the pixels where either is positive
};

RatioStats ratio_stats(const std::vector<PixelKernels>& kernels, const KernelOf& form) {
  std::vector<double> ratios, logs;
  std::size_t either_positive = 0, over_twice = 0;
  for (const PixelKernels& k : kernels) {
    const double value = form(k);
    if (value <= kPositive && k.forward <= kPositive) continue;
    ++either_positive;
    if (value > 2.0 * k.forward) ++over_twice;
    if (value <= kPositive || k.forward <= kPositive) continue;
    ratios.push_back(value / k.forward);
    logs.push_back(std::log(value / k.forward));
  }
  RatioStats s;
  s.pixels = ratios.size();
  s.median_ratio = median(ratios);
  s.mean_ratio = mean(ratios);
  s.median_log = median(logs);
  s.mean_log = mean(logs);
  s.sd_log = standard_deviation(logs);
  s.over_twice = either_positive ? static_cast<double>(over_twice) / static_cast<double>(either_positive) : NAN;
  return s;
}

struct ConstantFit {
  double constant = NAN;     // exp(mean(ln forward - ln basis))
  double residual_sd = NAN;  // sd of ln forward - ln(c basis): how well c basis tracks the forward kernel
  std::size_t pixels = 0;
};

// Least squares in log space: ln c minimises sum (ln forward - ln c - ln basis)^2.
ConstantFit fit_constant(const std::vector<PixelKernels>& kernels, const KernelOf& basis) {
  std::vector<double> log_quotients;
  for (const PixelKernels& k : kernels) {
    const double b = basis(k);
    if (b > kPositive && k.forward > kPositive) log_quotients.push_back(std::log(k.forward / b));
  }
  return {std::exp(mean(log_quotients)), standard_deviation(log_quotients), log_quotients.size()};
}

// ---------------------------------------------------------------------------------------------
// Output

struct SceneCounts {
  std::size_t hit = 0;
  std::size_t zero_forward = 0;
  std::size_t zero_normal = 0;
  std::size_t saturated = 0;
  double median_eigen_ratio = NAN;  // of the pixels with a positive forward kernel
};

SceneCounts scene_counts(const std::vector<PixelKernels>& kernels) {
  SceneCounts c;
  c.hit = kernels.size();
  std::vector<double> eigen_ratios;
  for (const PixelKernels& k : kernels) {
    if (k.forward > kPositive) eigen_ratios.push_back(k.forward_eigen_ratio);
    c.zero_forward += k.forward <= kPositive;
    c.zero_normal += k.normal_sum <= kPositive;
    c.saturated += k.saturated;
  }
  c.median_eigen_ratio = median(eigen_ratios);
  return c;
}

void print_ratio_table(std::string_view title, const std::vector<PixelKernels>& kernels) {
  const SceneCounts c = scene_counts(kernels);
  std::cout << fmt::format(
      "### {}\n\n{} hit pixels; forward kernel zero at {}, |dn|^2 zero at {}; "
      "a deferred form saturated (alpha'^2 = 1) at {}; median lambda_min / lambda_max of the "
      "forward kernel matrix {:.3f}.\n\n",
      title, c.hit, c.zero_forward, c.zero_normal, c.saturated, c.median_eigen_ratio);
  std::cout << "| form | pixels | median r | mean r | median ln r | mean ln r | sd ln r | r > 2 |\n"
               "|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Form& form : compared_forms()) {
    const RatioStats s = ratio_stats(kernels, form.kernel);
    std::cout << fmt::format("| {} | {} | {:.3f} | {:.3f} | {:+.3f} | {:+.3f} | {:.3f} | {:.1f} % |\n", form.name, s.pixels, s.median_ratio,
                             s.mean_ratio, s.median_log, s.mean_log, s.sd_log, 100.0 * s.over_twice);
  }
  std::cout << "\n";
}

void print_fit_row(std::string_view title, const std::vector<PixelKernels>& kernels) {
  std::cout << fmt::format("| {} |", title);
  for (const Form& basis : fitted_bases()) {
    const ConstantFit fit = fit_constant(kernels, basis.kernel);
    std::cout << fmt::format(" {:.4f} | {:.3f} |", fit.constant, fit.residual_sd);
  }
  std::cout << "\n";
}

void print_fit_header() {
  std::cout << "### Best constant c (least squares in log space): c * basis ~ forward tr(2 Sigma) / 2\n\n|"
               " scene |";
  for (const Form& basis : fitted_bases()) std::cout << fmt::format(" c for {} | sd ln |", basis.name);
  std::cout << "\n|---|";
  for (std::size_t i = 0; i < fitted_bases().size(); ++i) std::cout << "---:|---:|";
  std::cout << "\n";
}

Options parse_options(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--images") {
      options.images = true;
      continue;
    }
    if (i + 1 >= argc) throw std::invalid_argument(fmt::format("{} needs a value", arg));
    if (arg == "--size")
      options.size = std::atoi(argv[++i]);
    else if (arg == "--alpha")
      options.alpha = std::atof(argv[++i]);
    else
      throw std::invalid_argument(fmt::format("unknown option {}", arg));
  }
  if (options.size < 2 || options.alpha < 0.0 || options.alpha > 1.0)
    throw std::invalid_argument("--size must be >= 2 and --alpha in [0, 1]");
  return options;
}

struct SceneKernels {
  std::string name;
  std::vector<PixelKernels> kernels;
};

std::vector<SceneKernels> every_scene_kernels(const Options& options) {
  std::vector<SceneKernels> scenes;
  auto add = [&](measure::SceneId id) {
    scenes.push_back({std::string(measure::scene_name(id)), scene_kernels(measure::make_scene(id), options)});
  };
  for (measure::SceneId id : measure::all_scenes()) add(id);
  for (measure::SceneId id : measure::content_scenes()) add(id);
  return scenes;
}

// ---------------------------------------------------------------------------------------------
// Image check

// The lobe the filtered roughness is evaluated with: the papers' GGX of the filtered roughness,
// or the tail-preserving filtered GGX (brdf.hpp: a GGX lobe of the unfiltered shape plus a
// Beckmann core carrying the kernel, fitted to the exact convolution).
enum class ImageLobe { papers, tail };

// The filtered roughness of one method at one pixel: a matrix (forward) or alpha'^2.
struct Filtered {
  bool matrix = false;
  Sym2 a;
  double alpha2 = 0.0;
};

double lobe_brdf(ImageLobe lobe, const measure::PixelFields& f, const Filtered& filtered, double alpha2) {
  const Vec2 unfiltered{alpha2, alpha2};
  if (filtered.matrix)
    return lobe == ImageLobe::papers ? ref::ggx_brdf_matrix(f.light_ts, f.view_ts, filtered.a, ref::ndf_clamp_tau(unfiltered))
                                     : ref::ggx_brdf_filtered_matrix(f.light_ts, f.view_ts, filtered.a, unfiltered);
  const Vec2 isotropic{filtered.alpha2, filtered.alpha2};
  return lobe == ImageLobe::papers ? ref::ggx_brdf_axis(f.light_ts, f.view_ts, isotropic)
                                   : ref::ggx_brdf_filtered_axis(f.light_ts, f.view_ts, isotropic, unfiltered);
}

// Eq. 5 with sigma^2 replaced by sigma^2 (n.h)^power: the candidates for power 1 and 2
// (saturate(alpha^2 + min(sigma^2 (n.h)^power (|dn_x|^2 + |dn_y|^2), kappa))).
double candidate_alpha2(const measure::QuadFields& q, double half_z, double power, double alpha2) {
  ref::Params params;
  params.sigma2 *= std::pow(std::max(half_z, 0.0), power);
  return ref::deferred_avg_fragment_quad(params, alpha2, q.normal, q.pixel, kMode);
}

// The forward kernel reduced to its isotropic equivalent tr(2 Sigma) / 2, kappa-clamped as the
// deferred forms are: how much of the forward form's advantage is its anisotropy.
double forward_isotropised_alpha2(const measure::QuadFields& q, double alpha2) {
  const ref::Params params;
  const double kernel = forward_isotropic_kernel(params, alpha2, q.half_ts, q.pixel);
  return ref::saturate(alpha2 + std::min(kernel, params.kappa));
}

// The first-order tilt part of the forward kernel, which a deferred pass can form without a
// tangent: A = diag(alpha^2) + 2 sigma^2 (n.h)^2 Dn^T Dn, Dn the rows (dn_x, dn_y) in the
// tangent plane (any orthonormal (t, b) there: the BRDF is evaluated in the same frame).
Sym2 candidate_matrix(const measure::QuadFields& q, double half_z, double alpha2) {
  const ref::Params params;
  const Vec3 t = q.tangent[q.pixel], b = q.bitangent[q.pixel];
  const Vec3 dn_dx = ref::ddx(q.normal, q.pixel, kMode), dn_dy = ref::ddy(q.normal, q.pixel, kMode);
  const Sym2 rows = ref::sym2_from_derivative_rows({ref::dot(dn_dx, t), ref::dot(dn_dx, b)}, {ref::dot(dn_dy, t), ref::dot(dn_dy, b)});
  return Sym2{alpha2, 0.0, alpha2} + (2.0 * params.sigma2 * half_z * half_z) * rows;
}

// The methods the image check compares, in column order.
const std::vector<std::string>& image_methods() {
  static const std::vector<std::string> names{"none",
                                              "forward-aniso-projected",
                                              "deferred-avg",
                                              "deferred-sum",
                                              "candidate (n.h)^2",
                                              "candidate (n.h)",
                                              "forward tr/2, isotropic",
                                              "candidate matrix (n.h)^2"};
  return names;
}

Filtered method_roughness(std::size_t method, const measure::PixelFields& f, const measure::QuadFields& q, double alpha2) {
  const ref::Params params;
  switch (method) {
    case 0:
      return {false, {}, alpha2};
    case 1:
      return {true, ref::forward_aniso_projected_fragment_quad(params, {alpha2, alpha2}, q.half_ts, q.pixel, kMode), 0.0};
    case 2:
      return {false, {}, ref::deferred_avg_fragment_quad(params, alpha2, q.normal, q.pixel, kMode)};
    case 3:
      return {false, {}, ref::deferred_sum_fragment_quad(params, alpha2, q.normal, q.pixel, kMode)};
    case 4:
      return {false, {}, candidate_alpha2(q, f.half_ts.z, 2.0, alpha2)};
    case 5:
      return {false, {}, candidate_alpha2(q, f.half_ts.z, 1.0, alpha2)};
    case 6:
      return {false, {}, forward_isotropised_alpha2(q, alpha2)};
    default:
      return {true, candidate_matrix(q, f.half_ts.z, alpha2), 0.0};
  }
}

// One 1-spp image per method, shaded as shade_pixel shades (renderer.hpp; no Fresnel).
std::vector<measure::Image> method_images(const measure::GBuffer& gbuffer, double alpha, ImageLobe lobe) {
  const double alpha2 = alpha * alpha;
  std::vector<measure::Image> images(image_methods().size(), measure::Image(gbuffer.width, gbuffer.height));
  for (int y = 0; y < gbuffer.height; ++y)
    for (int x = 0; x < gbuffer.width; ++x) {
      const measure::PixelFields& f = gbuffer.at(x, y);
      if (!f.hit) continue;
      const measure::QuadFields q = measure::gather_quad(gbuffer, x, y);
      for (std::size_t m = 0; m < images.size(); ++m) {
        const Filtered filtered = method_roughness(m, f, q, alpha2);
        const double brdf = m == 0 ? ref::ggx_brdf_axis(f.light_ts, f.view_ts, {alpha2, alpha2}) : lobe_brdf(lobe, f, filtered, alpha2);
        images[m].at(x, y) = static_cast<float>(measure::specular_radiance(brdf, f.light_ts, f.view_ts, f.irradiance, false));
      }
    }
  return images;
}

double largest_relative_difference(const measure::Image& a, const measure::Image& b) {
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    largest = std::max(largest, std::fabs(double(a.pixels[i]) - b.pixels[i]) / (1.0 + std::fabs(double(b.pixels[i]))));
  return largest;
}

// The papers-lobe images must be the renderer's own (render_variant) for the catalogue variants.
void check_against_renderer(const measure::GBuffer& gbuffer, double alpha, const std::vector<measure::Image>& images) {
  const measure::Variant variants[] = {measure::Variant::none, measure::Variant::forward_aniso_projected, measure::Variant::deferred_avg,
                                       measure::Variant::deferred_sum};
  for (std::size_t m = 0; m < std::size(variants); ++m) {
    const double d = largest_relative_difference(images[m], measure::render_variant(gbuffer, variants[m], {alpha, false}));
    if (d > 1e-5) throw std::runtime_error(fmt::format("{} differs from render_variant by {}", image_methods()[m], d));
  }
}

void print_image_check(const Options& options, ImageLobe lobe, std::string_view lobe_title) {
  const std::vector<double> alphas{0.01, 0.05, 0.1};
  std::vector<measure::Material> materials;
  for (double alpha : alphas) materials.push_back({alpha, false});
  measure::GroundTruthSettings settings;
  settings.width = settings.height = options.size;
  settings.strata = 16;
  std::cout << fmt::format(
      "### Image check, {}: LDR-FLIP / tonemapped RMSE against a {}-spp ground truth, {} x {}, "
      "no Fresnel, kappa = {}\n\n| scene | alpha |",
      lobe_title, settings.strata * settings.strata, options.size, options.size, ref::Params{}.kappa);
  for (const std::string& name : image_methods()) std::cout << " " << name << " |";
  std::cout << "\n|---|---:|";
  for (std::size_t i = 0; i < image_methods().size(); ++i) std::cout << "---:|";
  std::cout << "\n";
  std::vector<measure::SceneId> ids(measure::all_scenes().begin(), measure::all_scenes().end());
  ids.insert(ids.end(), measure::content_scenes().begin(), measure::content_scenes().end());
  for (measure::SceneId id : ids) {
    const measure::Scene scene = measure::make_scene(id);
    const measure::GroundTruth truth = measure::render_ground_truth(scene, settings, materials);
    const measure::GBuffer gbuffer = measure::render_gbuffer(scene, options.size, options.size);
    for (std::size_t m = 0; m < alphas.size(); ++m) {
      const std::vector<measure::Image> images = method_images(gbuffer, alphas[m], lobe);
      if (lobe == ImageLobe::papers) check_against_renderer(gbuffer, alphas[m], images);
      const measure::Image reference_display = tonemapped(truth.images[m]);
      std::cout << fmt::format("| {} | {} |", measure::scene_name(id), alphas[m]);
      for (const measure::Image& image : images) {
        const double flip = measure::ldr_flip_mean_grey(reference_display, tonemapped(image));
        const double rmse = measure::compare_images(image, truth.images[m]).rmse_tonemapped;
        std::cout << fmt::format(" {:.4f} / {:.4f} |", flip, rmse);
      }
      std::cout << std::endl;
    }
  }
  std::cout << "\n";
}

}  // namespace

int main(int argc, char** argv) try {
  const Options options = parse_options(argc, argv);
  const std::vector<SceneKernels> scenes = every_scene_kernels(options);
  std::cout << fmt::format(
      "## Kernel trace: {} x {}, alpha = {}, sigma^2 = {}, coarse derivatives, shading "
      "normal; r = form / forward, forward = tr(A - diag(alpha^2)) / 2 of "
      "forward-aniso-projected, S = |dn_x|^2 + |dn_y|^2\n\n",
      options.size, options.size, options.alpha, ref::Params{}.sigma2);
  std::vector<PixelKernels> pooled;
  for (const SceneKernels& scene : scenes) {
    print_ratio_table(scene.name, scene.kernels);
    pooled.insert(pooled.end(), scene.kernels.begin(), scene.kernels.end());
  }
  print_ratio_table("all scenes pooled (pixels of every scene)", pooled);
  print_fit_header();
  for (const SceneKernels& scene : scenes) print_fit_row(scene.name, scene.kernels);
  print_fit_row("**pooled**", pooled);
  std::cout << "\n";
  if (options.images) {
    print_image_check(options, ImageLobe::papers, "papers' GGX lobe");
    print_image_check(options, ImageLobe::tail, "tail-preserving filtered GGX lobe (Beckmann core)");
  }
  return 0;
} catch (const std::exception& e) {
  std::cerr << "kernel_trace: " << e.what() << "\n";
  return 1;
}
