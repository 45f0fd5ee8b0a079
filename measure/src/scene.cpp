// Analytic scenes of the ground-truth renderer (see scene.hpp).
#include "saagen/measure/scene.hpp"

#include "saagen/measure/height_field.hpp"
#include "saagen/measure/mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace saagen::measure {

using ref::cross;
using ref::dot;
using ref::kPi;
using ref::length;
using ref::normalize;

namespace {

std::string format_vec(Vec3 v) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << v.x << "," << v.y << "," << v.z << ")";
  return s.str();
}

// Real roots of the depressed cubic s^3 + p s + q = 0, each polished by Newton steps.
int solve_depressed_cubic(double p, double q, std::array<double, 3>& roots) {
  int n = 0;
  if (p == 0.0 && q == 0.0) {
    roots[n++] = 0.0;
  } else {
    // Discriminant of the depressed cubic, -(4 p^3 + 27 q^2): > 0 means three real roots.
    const double discriminant = -(4.0 * p * p * p + 27.0 * q * q);
    if (discriminant > 0.0) {
      // Trigonometric form (p < 0): s_k = 2 sqrt(-p/3) cos(theta/3 - 2 pi k / 3),
      // cos(theta) = (3q / (2p)) sqrt(-3/p).
      const double m = 2.0 * std::sqrt(-p / 3.0);
      const double c = std::clamp(3.0 * q / (p * m), -1.0, 1.0);
      const double theta = std::acos(c) / 3.0;
      for (int k = 0; k < 3; ++k) roots[n++] = m * std::cos(theta - 2.0 * kPi * k / 3.0);
    } else {
      // One real root (Cardano): u^3 = -q/2 -+ sqrt(q^2/4 + p^3/27), root u - p / (3u),
      // taking the sign that avoids cancellation.
      const double d = std::sqrt(std::max(0.0, 0.25 * q * q + p * p * p / 27.0));
      const double u = std::cbrt(q > 0.0 ? -0.5 * q - d : -0.5 * q + d);
      roots[n++] = u != 0.0 ? u - p / (3.0 * u) : 0.0;
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int it = 0; it < 2; ++it) {
      const double s = roots[i];
      const double derivative = 3.0 * s * s + p;
      if (derivative == 0.0) break;
      roots[i] = s - ((s * s + p) * s + q) / derivative;
    }
  }
  std::sort(roots.begin(), roots.begin() + n);
  return n;
}

// A root of f in [a, b], where f(a) and f(b) have opposite signs: Newton steps that stay inside
// the shrinking bracket, bisection otherwise.
template <class F, class DF>
double bracketed_root(F&& f, DF&& df, double a, double b, double fa) {
  double x = 0.5 * (a + b);
  for (int it = 0; it < 100; ++it) {
    const double fx = f(x);
    if (fx == 0.0) return x;
    if ((fx < 0.0) == (fa < 0.0)) {
      a = x;
      fa = fx;
    } else {
      b = x;
    }
    const double dfx = df(x);
    double next = dfx != 0.0 ? x - fx / dfx : 0.5 * (a + b);
    if (!(next > a && next < b)) next = 0.5 * (a + b);
    if (std::fabs(next - x) <= 1e-15 * std::max(1.0, std::fabs(x)) || b - a <= 1e-15) return next;
    x = next;
  }
  return x;
}

// The geometric frame equal to the shading frame (shapes without a separate base surface).
void copy_shading_frame_to_geometric(SurfaceHit& hit) {
  hit.geometric_normal = hit.normal;
  hit.geometric_tangent = hit.tangent;
  hit.geometric_bitangent = hit.bitangent;
}

// An angle in (-pi, pi] as a fraction of a turn in [0, 1).
double turn_fraction(double angle) {
  const double f = angle / (2.0 * kPi);
  return f < 0.0 ? f + 1.0 : f;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Rigid transforms

Rigid Rigid::rotation(Vec3 axis, double angle) {
  const Vec3 k = normalize(axis);
  const double c = std::cos(angle), s = std::sin(angle);
  // Rodrigues: R v = v c + (k x v) s + k (k . v)(1 - c), applied to the unit axes.
  auto rotate = [&](Vec3 v) { return c * v + s * cross(k, v) + ((1.0 - c) * dot(k, v)) * k; };
  Rigid r;
  r.col_x = rotate({1.0, 0.0, 0.0});
  r.col_y = rotate({0.0, 1.0, 0.0});
  r.col_z = rotate({0.0, 0.0, 1.0});
  return r;
}

Rigid Rigid::translate(Vec3 t) {
  Rigid r;
  r.translation = t;
  return r;
}

Rigid compose(const Rigid& a, const Rigid& b) {
  Rigid r;
  r.col_x = a.apply_vector(b.col_x);
  r.col_y = a.apply_vector(b.col_y);
  r.col_z = a.apply_vector(b.col_z);
  r.translation = a.apply_point(b.translation);
  return r;
}

// ---------------------------------------------------------------------------------------------
// Sphere

Vec3 Sphere::stereographic_tangent(Vec3 n) {
  // Inverse stereographic projection from the pole -z: n(u, w) = (2u, 2w, 1 - u^2 - w^2) /
  // (1 + u^2 + w^2). dn/du is proportional to (1 + w^2 - u^2, -2uw, -2u); with
  // u = a / (1 + c), w = b / (1 + c) and a factor (1 + c)^2 this is the expression below.
  const double one_c = 1.0 + n.z;
  const Vec3 t{one_c * one_c + n.y * n.y - n.x * n.x, -2.0 * n.x * n.y, -2.0 * n.x * one_c};
  // Remove the rounding residue of t . n before normalising.
  return normalize(t - dot(t, n) * n);
}

bool Sphere::intersect(const Ray& ray, double t_min, SurfaceHit& hit) const {
  // |o + t d|^2 = r^2 with |d| = 1: t^2 + 2 b t + c = 0, b = o.d, c = |o|^2 - r^2.
  const double b = dot(ray.origin, ray.direction);
  const double c = dot(ray.origin, ray.origin) - radius_ * radius_;
  const double discriminant = b * b - c;
  if (discriminant < 0.0) return false;
  const double root = std::sqrt(discriminant);
  // Roots -b -+ root; q = -b - sign(b) root avoids cancellation, the other root is c / q.
  const double q = b > 0.0 ? -b - root : -b + root;
  double t0 = q, t1 = q != 0.0 ? c / q : q;
  if (t0 > t1) std::swap(t0, t1);
  double t = t0;
  if (!(t > t_min)) {
    t = t1;
    if (!(t > t_min)) return false;
  }
  hit.t = t;
  hit.position = ray.origin + t * ray.direction;
  hit.normal = normalize(hit.position);
  hit.tangent = stereographic_tangent(hit.normal);
  hit.bitangent = cross(hit.normal, hit.tangent);
  hit.object = 0;
  copy_shading_frame_to_geometric(hit);
  set_uv(hit);
  return true;
}

void Sphere::set_uv(SurfaceHit& hit) const {
  // p = r (sin(theta) sin(phi), cos(theta), sin(theta) cos(phi)), u = phi / (2 pi) + 1/2,
  // v = 1 - theta / pi: dp/dphi = (z, 0, -x), dp/dtheta = (y x / rho, -rho, y z / rho).
  const Vec3 p = hit.position;
  const double rho = std::hypot(p.x, p.z);
  const double theta = std::acos(std::clamp(p.y / radius_, -1.0, 1.0));
  hit.uv = {std::atan2(p.x, p.z) / (2.0 * kPi) + 0.5, 1.0 - theta / kPi};
  hit.dpdu = (2.0 * kPi) * Vec3{p.z, 0.0, -p.x};
  hit.dpdv = rho > 0.0 ? kPi * Vec3{-p.y * p.x / rho, rho, -p.y * p.z / rho} : Vec3{};
}

std::string Sphere::describe() const {
  std::ostringstream s;
  s.precision(17);
  s << "sphere(r=" << radius_ << ",tangent=stereographic(-z))";
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Torus

bool Torus::intersect(const Ray& ray, double t_min, SurfaceHit& hit) const {
  const Vec3 d = ray.direction;
  // Parameterise from the point of closest approach to the centre, o = origin + t0 d, so that
  // o . d = 0 and |o + s d|^2 = |o|^2 + s^2.
  const double t0 = -dot(ray.origin, d);
  const Vec3 o = ray.origin + t0 * d;
  const double oo = dot(o, o);
  // Bounding sphere, enlarged by 0.1 % so that its boundary never coincides with the torus's
  // outer equator (where a root would sit exactly on the end of the search interval).
  const double bound = 1.001 * (major_ + minor_);
  if (oo >= bound * bound) return false;  // misses the bounding sphere
  const double half_chord = std::sqrt(bound * bound - oo);
  const double s_lo = std::max(-half_chord, t_min - t0);
  const double s_hi = half_chord;
  if (!(s_lo < s_hi)) return false;

  // f(s) = (|p|^2 + R^2 - r^2)^2 - 4 R^2 (px^2 + pz^2) = s^4 + c2 s^2 + c1 s + c0.
  const double r2 = major_ * major_;
  const double a = oo + r2 - minor_ * minor_;
  const double q2 = d.x * d.x + d.z * d.z;
  const double q1 = 2.0 * (o.x * d.x + o.z * d.z);
  const double q0 = o.x * o.x + o.z * o.z;
  const double c2 = 2.0 * a - 4.0 * r2 * q2;
  const double c1 = -4.0 * r2 * q1;
  const double c0 = a * a - 4.0 * r2 * q0;
  auto f = [&](double s) {
    const double s2 = s * s;
    return (s2 + c2) * s2 + c1 * s + c0;
  };
  auto df = [&](double s) { return (4.0 * s * s + 2.0 * c2) * s + c1; };

  // f is monotone between consecutive critical points (roots of f'/4 = s^3 + c2/2 s + c1/4),
  // so every real root is bracketed by two consecutive breakpoints.
  std::array<double, 3> critical{};
  const int n_critical = solve_depressed_cubic(0.5 * c2, 0.25 * c1, critical);
  std::array<double, 5> breaks{};
  int n_breaks = 0;
  breaks[n_breaks++] = s_lo;
  for (int i = 0; i < n_critical; ++i)
    if (critical[i] > s_lo && critical[i] < s_hi) breaks[n_breaks++] = critical[i];
  breaks[n_breaks++] = s_hi;

  double f_left = f(breaks[0]);
  for (int i = 0; i + 1 < n_breaks; ++i) {
    const double left = breaks[i], right = breaks[i + 1];
    const double f_right = f(right);
    double s = 0.0;
    bool found = false;
    if (f_left == 0.0 && left > s_lo) {
      s = left;
      found = true;
    } else if ((f_left > 0.0 && f_right < 0.0) || (f_left < 0.0 && f_right > 0.0)) {
      s = bracketed_root(f, df, left, right, f_left);
      found = true;
    }
    if (found && t0 + s > t_min) {
      hit.t = t0 + s;
      hit.position = ray.origin + hit.t * d;
      const Vec3 p = hit.position;
      const double ring = std::sqrt(p.x * p.x + p.z * p.z);
      const Vec3 centre{major_ * p.x / ring, 0.0, major_ * p.z / ring};
      hit.normal = normalize(p - centre);
      hit.tangent = normalize(Vec3{-p.z, 0.0, p.x});
      hit.bitangent = cross(hit.normal, hit.tangent);
      hit.object = 0;
      copy_shading_frame_to_geometric(hit);
      set_uv(hit);
      return true;
    }
    f_left = f_right;
  }
  return false;
}

void Torus::set_uv(SurfaceHit& hit) const {
  // p = ((R + r cos psi) cos phi, r sin psi, (R + r cos psi) sin phi):
  // dp/dphi = (-z, 0, x), dp/dpsi = (-y x / rho, rho - R, -y z / rho), rho = sqrt(x^2 + z^2).
  const Vec3 p = hit.position;
  const double rho = std::hypot(p.x, p.z);
  hit.uv = {turn_fraction(std::atan2(p.z, p.x)), turn_fraction(std::atan2(p.y, rho - major_))};
  hit.dpdu = (2.0 * kPi) * Vec3{-p.z, 0.0, p.x};
  hit.dpdv = (2.0 * kPi) * Vec3{-p.y * p.x / rho, rho - major_, -p.y * p.z / rho};
}

std::string Torus::describe() const {
  std::ostringstream s;
  s.precision(17);
  s << "torus(R=" << major_ << ",r=" << minor_ << ")";
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Row of tubes

bool TubeRow::intersect(const Ray& ray, double t_min, SurfaceHit& hit) const {
  const Vec3 o = ray.origin, d = ray.direction;
  const double a = d.y * d.y + d.z * d.z;
  if (a <= 1e-300) return false;  // parallel to the axes
  bool found = false;
  double best = 0.0;
  int best_k = 0;
  for (int k = 0; k < count_; ++k) {
    // (oy + t dy - yk)^2 + (oz + t dz)^2 = r^2: a t^2 + 2 b t + c = 0.
    const double oy = o.y - axis_y(k);
    const double b = oy * d.y + o.z * d.z;
    const double c = oy * oy + o.z * o.z - radius_ * radius_;
    const double discriminant = b * b - a * c;
    if (discriminant < 0.0) continue;
    const double root = std::sqrt(discriminant);
    const double q = b > 0.0 ? -b - root : -b + root;
    // Smaller root: entry into the infinite cylinder (the outer surface).
    const double t = q != 0.0 ? std::min(q / a, c / q) : q / a;
    if (!(t > t_min)) continue;
    if (found && t >= best) continue;
    if (std::fabs(o.x + t * d.x) > half_length_) continue;
    found = true;
    best = t;
    best_k = k;
  }
  if (!found) return false;
  hit.t = best;
  hit.position = o + best * d;
  hit.normal = normalize(Vec3{0.0, hit.position.y - axis_y(best_k), hit.position.z});
  hit.tangent = {1.0, 0.0, 0.0};
  hit.bitangent = cross(hit.normal, hit.tangent);
  hit.object = best_k;
  copy_shading_frame_to_geometric(hit);
  // p = (x, y_k + r cos psi, r sin psi): dp/dx = e_x, dp/dpsi = (0, -z, y - y_k).
  const double dy = hit.position.y - axis_y(best_k);
  hit.uv = {(hit.position.x + half_length_) / (2.0 * half_length_), turn_fraction(std::atan2(hit.position.z, dy))};
  hit.dpdu = {2.0 * half_length_, 0.0, 0.0};
  hit.dpdv = (2.0 * kPi) * Vec3{0.0, -hit.position.z, dy};
  return true;
}

std::string TubeRow::describe() const {
  std::ostringstream s;
  s.precision(17);
  s << "tubes(n=" << count_ << ",r=" << radius_ << ",spacing=" << spacing_ << ",half_length=" << half_length_ << ")";
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Bump-mapped plane

double BumpPlane::height(double x, double y) const {
  double h = 0.0;
  for (const SineWave& w : waves_) h += w.amplitude * std::sin(w.wave_vector.x * x + w.wave_vector.y * y + w.phase);
  return h;
}

Vec2 BumpPlane::gradient(double x, double y) const {
  Vec2 g{};
  for (const SineWave& w : waves_) {
    const double c = w.amplitude * std::cos(w.wave_vector.x * x + w.wave_vector.y * y + w.phase);
    g = g + c * w.wave_vector;
  }
  return g;
}

Vec3 BumpPlane::normal(double x, double y) const {
  const Vec2 g = gradient(x, y);
  return normalize(Vec3{-g.x, -g.y, 1.0});
}

bool BumpPlane::intersect(const Ray& ray, double t_min, SurfaceHit& hit) const {
  if (!(ray.direction.z < 0.0)) return false;  // seen from +z only
  const double t = -ray.origin.z / ray.direction.z;
  if (!(t > t_min)) return false;
  const Vec3 p = ray.origin + t * ray.direction;
  if (std::fabs(p.x) > half_size_ || std::fabs(p.y) > half_size_) return false;
  hit.t = t;
  hit.position = {p.x, p.y, 0.0};
  hit.normal = normal(p.x, p.y);
  hit.tangent = normalize(Vec3{1.0, 0.0, 0.0} - hit.normal.x * hit.normal);
  hit.bitangent = cross(hit.normal, hit.tangent);
  hit.object = 0;
  hit.geometric_normal = {0.0, 0.0, 1.0};
  hit.geometric_tangent = {1.0, 0.0, 0.0};
  hit.geometric_bitangent = {0.0, 1.0, 0.0};
  const double size = 2.0 * half_size_;
  hit.uv = {(p.x + half_size_) / size, (p.y + half_size_) / size};
  hit.dpdu = {size, 0.0, 0.0};
  hit.dpdv = {0.0, size, 0.0};
  return true;
}

SlopeMoments BumpPlane::slope_moments(Vec2 centre, Sym2 covariance) const {
  // g(k) = exp(-k^T S k / 2): the Gaussian's characteristic function (see scene.hpp).
  auto attenuation = [&](Vec2 k) {
    return std::exp(-0.5 * (covariance.xx * k.x * k.x + 2.0 * covariance.xy * k.x * k.y + covariance.yy * k.y * k.y));
  };
  auto phase = [&](const SineWave& w) { return w.wave_vector.x * centre.x + w.wave_vector.y * centre.y + w.phase; };
  SlopeMoments m;
  for (std::size_t j = 0; j < waves_.size(); ++j) {
    const SineWave& wj = waves_[j];
    const double theta_j = phase(wj);
    m.mean = m.mean + (wj.amplitude * std::cos(theta_j) * attenuation(wj.wave_vector)) * wj.wave_vector;
    for (std::size_t l = j; l < waves_.size(); ++l) {
      const SineWave& wl = waves_[l];
      const double theta_l = phase(wl);
      const double c = 0.5 * wj.amplitude * wl.amplitude *
                       (std::cos(theta_j - theta_l) * attenuation(wj.wave_vector - wl.wave_vector) +
                        std::cos(theta_j + theta_l) * attenuation(wj.wave_vector + wl.wave_vector));
      // The pair (j, l) and (l, j) together: c (k_j k_l^T + k_l k_j^T); the diagonal once.
      const Vec2 kj = wj.wave_vector, kl = wl.wave_vector;
      const double weight = l == j ? 1.0 : 2.0;
      const Sym2 outer{kj.x * kl.x, 0.5 * (kj.x * kl.y + kj.y * kl.x), kj.y * kl.y};
      m.second = m.second + (weight * c) * outer;
    }
  }
  return m;
}

std::optional<SlopeMoments> BumpPlane::footprint_slope_moments(Vec2 uv, Sym2 footprint) const {
  // uv = (x + half) / size on both axes (intersect): x = size uv - half, S_x = size^2 S_uv.
  const double size = 2.0 * half_size_;
  return slope_moments({size * uv.x - half_size_, size * uv.y - half_size_}, (size * size) * footprint);
}

std::string BumpPlane::describe() const {
  std::ostringstream s;
  s.precision(17);
  s << "bump_plane(half=" << half_size_;
  for (const SineWave& w : waves_)
    s << ",wave(" << w.wave_vector.x << "," << w.wave_vector.y << "," << w.amplitude << "," << w.phase << ")";
  s << ")";
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Camera and light

Ray Camera::generate(double fx, double fy, int width, int height) const { return CameraFilm(*this, width, height).ray(fx, fy); }

CameraFilm::CameraFilm(const Camera& camera, int width, int height)
    : position_(camera.position),
      forward_(normalize(camera.look_at - camera.position)),
      right_(normalize(cross(forward_, camera.up))),
      true_up_(cross(right_, forward_)),
      jitter_(camera.jitter),
      tan_half_(std::tan(0.5 * camera.fov_y_degrees * kPi / 180.0)),
      aspect_(static_cast<double>(width) / height),
      width_(width),
      height_(height) {}

Ray CameraFilm::ray(double fx, double fy) const {
  const double sx = (2.0 * (fx + jitter_.x) / width_ - 1.0) * tan_half_ * aspect_;
  const double sy = (1.0 - 2.0 * (fy + jitter_.y) / height_) * tan_half_;
  return {position_, normalize(forward_ + sx * right_ + sy * true_up_)};
}

std::optional<Vec2> Camera::project(Vec3 p, int width, int height) const {
  const Vec3 forward = normalize(look_at - position);
  const Vec3 right = normalize(cross(forward, up));
  const Vec3 true_up = cross(right, forward);
  const Vec3 d = p - position;
  const double depth = dot(d, forward);
  if (!(depth > 0.0)) return std::nullopt;
  const double tan_half = std::tan(0.5 * fov_y_degrees * kPi / 180.0);
  const double aspect = static_cast<double>(width) / height;
  // generate's sx, sy are the film offsets of the direction at unit depth along forward.
  const double sx = dot(d, right) / depth, sy = dot(d, true_up) / depth;
  return Vec2{0.5 * width * (sx / (tan_half * aspect) + 1.0) - jitter.x, 0.5 * height * (1.0 - sy / tan_half) - jitter.y};
}

Camera Camera::panned(double right_pixels, double up_pixels, int height) const {
  const Vec3 to_target = look_at - position;
  const Vec3 forward = normalize(to_target);
  const Vec3 right = normalize(cross(forward, up));
  const Vec3 true_up = cross(right, forward);
  // Film height at the look-at distance d: 2 d tan(fov / 2), over `height` pixels.
  const double pixel = 2.0 * length(to_target) * std::tan(0.5 * fov_y_degrees * kPi / 180.0) / height;
  const Vec3 offset = pixel * (right_pixels * right + up_pixels * true_up);
  Camera c = *this;
  c.position = position + offset;
  c.look_at = look_at + offset;
  return c;
}

Camera Camera::cropped(int size, int full_size) const {
  Camera c = *this;
  const double tan_half = std::tan(0.5 * fov_y_degrees * kPi / 180.0);
  c.fov_y_degrees = 2.0 * std::atan(tan_half * static_cast<double>(size) / full_size) * 180.0 / kPi;
  return c;
}

void Light::at(Vec3 p, Vec3& to_light, double& irradiance) const {
  if (kind == Kind::directional) {
    to_light = vector;
    irradiance = intensity;
  } else {
    const Vec3 d = vector - p;
    const double d2 = dot(d, d);
    to_light = d / std::sqrt(d2);
    irradiance = intensity / d2;
  }
}

// ---------------------------------------------------------------------------------------------
// Scenes

namespace {
// The texture frame of a hit (MikkTSpace's per-pixel form): t = dpdu made orthogonal to the
// geometric normal, b = n x t.
void set_texture_frame(SurfaceHit& hit) {
  const Vec3 n = hit.geometric_normal;
  hit.geometric_tangent = normalize(hit.dpdu - dot(hit.dpdu, n) * n);
  hit.geometric_bitangent = cross(n, hit.geometric_tangent);
}

// NormalMap::bilinear(0, uv).normal without the other moments (the same arithmetic in the same
// order, so the same bits): Vulkan's bilinear weights from uv * size - 0.5, repeat addressing.
Vec3 bilinear_level0_normal(const NormalMap& map, Vec2 uv) {
  const double fx = uv.x * map.width(0) - 0.5, fy = uv.y * map.height(0) - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy);
  const double ax = fx - x0, ay = fy - y0;
  const int ix = static_cast<int>(x0), iy = static_cast<int>(y0);
  return ((1.0 - ax) * (1.0 - ay)) * map.texel(0, ix, iy).normal + (ax * (1.0 - ay)) * map.texel(0, ix + 1, iy).normal +
         ((1.0 - ax) * ay) * map.texel(0, ix, iy + 1).normal + (ax * ay) * map.texel(0, ix + 1, iy + 1).normal;
}
}  // namespace

Scene::Scene(std::string name, std::shared_ptr<const Shape> shape, Rigid placement, Camera camera, Light light, Vec3 pivot,
             double rotation_radians)
    : name_(std::move(name)),
      shape_(std::move(shape)),
      placement_(placement),
      camera_(camera),
      light_(light),
      pivot_(pivot),
      rotation_(rotation_radians) {
  // Animation: rotate about the vertical axis through the pivot, after the placement.
  const Rigid spin =
      compose(Rigid::translate(pivot_), compose(Rigid::rotation({0.0, 1.0, 0.0}, rotation_), Rigid::translate(-1.0 * pivot_)));
  object_to_world_ = compose(spin, placement_);
}

Scene Scene::with_camera(const Camera& camera) const {
  Scene copy = *this;
  copy.camera_ = camera;
  return copy;
}

Scene Scene::with_surface_materials(std::shared_ptr<const SurfaceMaterials> surfaces) const {
  Scene copy = *this;
  copy.surfaces_ = std::move(surfaces);
  return copy;
}

const NormalMap* Scene::normal_map_at(const SurfaceHit& hit) const {
  if (!surfaces_) return normal_map_.get();
  const SurfaceTextures* textures = surfaces_->at(hit.object);
  return textures ? textures->normal_map.get() : nullptr;
}

const ScalarMap* Scene::roughness_map_at(const SurfaceHit& hit) const {
  if (!surfaces_) return nullptr;
  const SurfaceTextures* textures = surfaces_->at(hit.object);
  return textures ? textures->roughness_map.get() : nullptr;
}

bool Scene::has_normal_map() const {
  if (normal_map_) return true;
  if (surfaces_)
    for (const SurfaceTextures& textures : surfaces_->by_object)
      if (textures.normal_map) return true;
  return false;
}

Scene Scene::with_normal_map(std::shared_ptr<const NormalMap> map, Vec2 tiling, std::string source) const {
  Scene copy = *this;
  copy.normal_map_ = std::move(map);
  copy.tiling_ = tiling;
  copy.normal_map_source_ = std::move(source);
  return copy;
}

bool Scene::intersect_surface(const Ray& ray, SurfaceHit& hit) const {
  const Ray local{object_to_world_.inverse_point(ray.origin), object_to_world_.inverse_vector(ray.direction)};
  if (!shape_->intersect(local, 0.0, hit)) return false;
  finish_surface_hit(hit);
  return true;
}

bool Scene::per_triangle_quads() const { return surfaces_ != nullptr || dynamic_cast<const TriangleMesh*>(shape_.get()) != nullptr; }

bool Scene::extrapolate_surface(const SurfaceHit& shaded, const Ray& ray, SurfaceHit& hit) const {
  const auto* mesh = dynamic_cast<const TriangleMesh*>(shape_.get());
  if (!mesh || shaded.triangle < 0) return false;
  const Ray local{object_to_world_.inverse_point(ray.origin), object_to_world_.inverse_vector(ray.direction)};
  if (!mesh->extrapolate(shaded.triangle, local, hit)) return false;
  finish_surface_hit(hit);
  return true;
}

void Scene::finish_surface_hit(SurfaceHit& hit) const {
  hit.position = object_to_world_.apply_point(hit.position);
  hit.normal = object_to_world_.apply_vector(hit.normal);
  hit.tangent = object_to_world_.apply_vector(hit.tangent);
  hit.bitangent = object_to_world_.apply_vector(hit.bitangent);
  hit.geometric_normal = object_to_world_.apply_vector(hit.geometric_normal);
  hit.geometric_tangent = object_to_world_.apply_vector(hit.geometric_tangent);
  hit.geometric_bitangent = object_to_world_.apply_vector(hit.geometric_bitangent);
  // Texture units: uv' = tiling uv, so dp/du' = (dp/du) / tiling.x (likewise for v).
  hit.uv = tiling_ * hit.uv;
  hit.dpdu = object_to_world_.apply_vector(hit.dpdu) / tiling_.x;
  hit.dpdv = object_to_world_.apply_vector(hit.dpdv) / tiling_.y;
  if (surfaces_) return;  // the mesh's own texture frame and bitangent sign (SurfaceMaterials)
  if (normal_map_) {
    set_texture_frame(hit);
    hit.normal = hit.geometric_normal;
    hit.tangent = hit.geometric_tangent;
    hit.bitangent = hit.geometric_bitangent;
  }
  hit.bitangent_sign = dot(hit.geometric_bitangent, hit.dpdv) < 0.0 ? -1.0 : 1.0;
}

bool Scene::intersect(const Ray& ray, SurfaceHit& hit) const {
  if (!intersect_surface(ray, hit)) return false;
  if (const NormalMap* map = normal_map_at(hit)) apply_normal_map(hit, bilinear_level0_normal(*map, hit.uv));
  if (const ScalarMap* roughness = roughness_map_at(hit)) hit.alpha_scale = roughness_alpha_scale(roughness->bilinear(0, hit.uv));
  if (const SurfaceTextures* textures = surface_textures_at(hit)) {
    hit.weight = textures->weight * (textures->weight_map ? ref::saturate(textures->weight_map->bilinear(0, hit.uv)) : 1.0);
    hit.coat = textures->coat * (textures->coat_map ? ref::saturate(textures->coat_map->bilinear(0, hit.uv)) : 1.0);
  }
  return true;
}

std::optional<SlopeMoments> Scene::footprint_slope_moments(const SurfaceHit& hit, Sym2 uv_footprint) const {
  // Texture units are tiling x the shape's uv (finish_surface_hit): back to the shape's.
  const Vec2 uv{hit.uv.x / tiling_.x, hit.uv.y / tiling_.y};
  const Sym2 footprint{uv_footprint.xx / (tiling_.x * tiling_.x), uv_footprint.xy / (tiling_.x * tiling_.y),
                       uv_footprint.yy / (tiling_.y * tiling_.y)};
  return shape_->footprint_slope_moments(uv, footprint);
}

void Scene::apply_normal_map(SurfaceHit& hit, Vec3 normal_ts) {
  // TBN: tangent-space x along +u (t), y along +v (s b), z along the geometric normal.
  const Vec3 t = hit.geometric_tangent;
  const Vec3 n =
      normalize(normal_ts.x * t + (hit.bitangent_sign * normal_ts.y) * hit.geometric_bitangent + normal_ts.z * hit.geometric_normal);
  hit.normal = n;
  hit.tangent = normalize(t - dot(t, n) * n);
  hit.bitangent = cross(n, hit.tangent);
}

std::string Scene::describe() const {
  std::ostringstream s;
  s.precision(17);
  s << "scene=" << name_ << ";shape=" << shape_->describe() << ";placement=" << format_vec(placement_.col_x) << format_vec(placement_.col_y)
    << format_vec(placement_.col_z) << format_vec(placement_.translation) << ";camera=" << format_vec(camera_.position)
    << format_vec(camera_.look_at) << format_vec(camera_.up) << camera_.fov_y_degrees << "deg"
    << ";light=" << (light_.kind == Light::Kind::directional ? "dir" : "point") << format_vec(light_.vector) << light_.intensity
    << ";pivot=" << format_vec(pivot_) << ";rotation=" << rotation_;
  // A jittered camera (taa.hpp) renders other pixels; the key of an unjittered one is unchanged.
  if (camera_.jitter.x != 0.0 || camera_.jitter.y != 0.0) s << ";jitter=(" << camera_.jitter.x << "," << camera_.jitter.y << ")";
  if (normal_map_)
    s << ";normal_map=" << normal_map_->describe() << ",tiling=(" << tiling_.x << "," << tiling_.y << "),source=" << normal_map_source_;
  if (surfaces_) s << ";surfaces=" << surfaces_->description;
  return s.str();
}

double roughness_alpha_scale(double g) {
  const double clamped = ref::min(ref::max(g, 1.0 / 255.0), 1.0);
  return clamped * clamped;
}

}  // namespace saagen::measure
