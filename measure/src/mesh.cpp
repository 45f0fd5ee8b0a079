// Triangle meshes with a BVH, and the torus-knot tube (see mesh.hpp).
#include "saagen/measure/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace saagen::measure {

using ref::cross;
using ref::dot;
using ref::kPi;
using ref::normalize;

namespace {

constexpr int kLeafSize = 4;               // the median split's leaves
constexpr int kMaxLeafSize = 8;            // the SAH's leaves
constexpr int kSahBins = 32;               // per axis (Wald 2007 finds 16-32 as good as a full sweep)
constexpr double kSahTraversalCost = 1.0;  // relative to one triangle test
constexpr int kSahMaxDepth = 32;           // below, median splits: 4 million triangles end by depth 32 + 22
constexpr int kMaxDepth = 60;              // the traversal stack holds at most depth + 1 entries

Vec3 component_min(Vec3 a, Vec3 b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
Vec3 component_max(Vec3 a, Vec3 b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
double axis_value(Vec3 v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

// FNV-1a over raw bytes.
void hash_bytes(std::uint64_t& h, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= bytes[i];
    h *= 0x100000001b3ULL;
  }
}

void hash_vec(std::uint64_t& h, Vec3 v) {
  const double c[3] = {v.x, v.y, v.z};
  hash_bytes(h, c, sizeof c);
}

// A ray prepared for slab tests: origin, 1 / direction, and per axis the offset (0 or 3) of
// the box plane it enters through (the low plane for a positive direction).
struct SlabRay {
  double origin[3];
  double inv[3];
  int near[3];
  explicit SlabRay(const Ray& ray) {
    const double d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
    const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
    for (int a = 0; a < 3; ++a) {
      origin[a] = o[a];
      inv[a] = 1.0 / d[a];
      near[a] = inv[a] < 0.0 ? 3 : 0;
    }
  }
};

// Slab test (Kay & Kajiya 1986) of a box stored as (lo.x, lo.y, lo.z, hi.x, hi.y, hi.z): the
// entry distance of the ray into the box when it overlaps (t_min, t_max), +inf otherwise. A NaN
// (0 * inf, an origin on a slab of a parallel ray) leaves the interval unchanged.
double box_entry(const double* box, const SlabRay& r, double t_min, double t_max) {
  double t0 = t_min, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    const double near = (box[r.near[a] + a] - r.origin[a]) * r.inv[a];
    const double far = (box[3 - r.near[a] + a] - r.origin[a]) * r.inv[a];
    if (near > t0) t0 = near;
    if (far < t1) t1 = far;
  }
  return t0 <= t1 ? t0 : HUGE_VAL;
}

}  // namespace

TriangleMesh::TriangleMesh(std::string label, std::vector<MeshVertex> vertices, std::vector<std::array<int, 3>> triangles,
                           std::vector<int> objects)
    : label_(std::move(label)), vertices_(std::move(vertices)), triangles_(std::move(triangles)), objects_(std::move(objects)) {
  if (!objects_.empty() && objects_.size() != triangles_.size()) throw std::invalid_argument("TriangleMesh: one object per triangle");
  const int n_vertices = static_cast<int>(vertices_.size());
  for (const auto& tri : triangles_)
    for (int i : tri)
      if (i < 0 || i >= n_vertices) throw std::invalid_argument("TriangleMesh: bad index");
  hash_ = 0xcbf29ce484222325ULL;
  for (const MeshVertex& v : vertices_) {
    hash_vec(hash_, v.position);
    hash_vec(hash_, v.normal);
    hash_vec(hash_, v.tangent);
    hash_vec(hash_, {v.uv.x, v.uv.y, 0.0});
    // Only a mirrored tangent frame is hashed, so that meshes without any keep their hash.
    if (v.tangent_sign != 1.0) hash_bytes(hash_, &v.tangent_sign, sizeof v.tangent_sign);
  }
  for (const auto& tri : triangles_) hash_bytes(hash_, tri.data(), sizeof(int) * 3);
  if (!objects_.empty()) hash_bytes(hash_, objects_.data(), sizeof(int) * objects_.size());

  std::vector<Vec3> centroids(triangles_.size());
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    const auto& tri = triangles_[i];
    centroids[i] = (vertices_[tri[0]].position + vertices_[tri[1]].position + vertices_[tri[2]].position) / 3.0;
  }
  order_.resize(triangles_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
  edges_.resize(triangles_.size());
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    const Vec3 p0 = vertices_[triangles_[i][0]].position;
    edges_[i] = {p0, vertices_[triangles_[i][1]].position - p0, vertices_[triangles_[i][2]].position - p0};
  }
  std::vector<Box> boxes(triangles_.size());
  for (std::size_t i = 0; i < triangles_.size(); ++i) boxes[i] = triangle_box(static_cast<int>(i));
  nodes_.reserve(2 * triangles_.size() + 1);
  if (!triangles_.empty()) build(0, static_cast<int>(triangles_.size()), 1, centroids, boxes);
  if (depth_ >= kMaxDepth) throw std::invalid_argument("TriangleMesh: BVH too deep");
  leaf_edges_.resize(order_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) leaf_edges_[i] = edges_[order_[i]];
}

TriangleMesh::Box TriangleMesh::triangle_box(int index) const {
  Box b;
  for (int i : triangles_[index]) {
    b.lo = component_min(b.lo, vertices_[i].position);
    b.hi = component_max(b.hi, vertices_[i].position);
  }
  return b;
}

int TriangleMesh::SahPlane::bin_of(Vec3 centroid) const {
  return std::min(kSahBins - 1, static_cast<int>((axis_value(centroid, axis) - lo) * scale));
}

namespace {

// Half the surface area of a box: the surface area heuristic's measure of how likely a ray
// that meets the parent meets it (MacDonald & Booth 1990).
double half_area(Vec3 lo, Vec3 hi) {
  const Vec3 d = hi - lo;
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

}  // namespace

// The binned SAH split of order_[begin, end) (Wald 2007, "On fast construction of SAH-based
// bounding volume hierarchies", Sec. 3): kSahBins equal bins of the centroids' bounds per axis;
// of the kSahBins - 1 planes between bins on each axis the one of least
// area(left) n(left) + area(right) n(right). Returns false where no plane leaves triangles on
// both sides (all centroids in one bin) or where a leaf of at most kMaxLeafSize triangles costs
// no more than the split (cost of a traversal step kSahTraversalCost, of a triangle test 1).
bool TriangleMesh::sah_split(int begin, int end, const Box& box, const Box& centroid_box, const std::vector<Vec3>& centroids,
                             const std::vector<Box>& boxes, SahPlane& plane) const {
  struct Bin {
    Box box;
    int count = 0;
  };
  const int count = end - begin;
  double best_cost = HUGE_VAL;
  for (int a = 0; a < 3; ++a) {
    const double lo = axis_value(centroid_box.lo, a), extent = axis_value(centroid_box.hi, a) - lo;
    if (!(extent > 0.0)) continue;
    const SahPlane binning{a, lo, kSahBins / extent, 0};
    Bin bins[kSahBins];
    for (int i = begin; i < end; ++i) {
      const auto t = static_cast<std::size_t>(order_[static_cast<std::size_t>(i)]);
      const int k = binning.bin_of(centroids[t]);
      bins[k].count++;
      bins[k].box.lo = component_min(bins[k].box.lo, boxes[t].lo);
      bins[k].box.hi = component_max(bins[k].box.hi, boxes[t].hi);
    }
    // right_cost[k]: area x count of bins k..kSahBins-1.
    double right_cost[kSahBins];
    Box right;
    int right_count = 0;
    for (int k = kSahBins - 1; k > 0; --k) {
      right.lo = component_min(right.lo, bins[k].box.lo);
      right.hi = component_max(right.hi, bins[k].box.hi);
      right_count += bins[k].count;
      right_cost[k] = right_count > 0 ? half_area(right.lo, right.hi) * right_count : 0.0;
    }
    Box left;
    int left_count = 0;
    for (int k = 0; k + 1 < kSahBins; ++k) {  // the plane between bins k and k + 1
      left.lo = component_min(left.lo, bins[k].box.lo);
      left.hi = component_max(left.hi, bins[k].box.hi);
      left_count += bins[k].count;
      if (left_count == 0 || left_count == count) continue;
      const double cost = half_area(left.lo, left.hi) * left_count + right_cost[k + 1];
      if (cost < best_cost) {
        best_cost = cost;
        plane = binning;
        plane.first_right_bin = k + 1;
      }
    }
  }
  if (best_cost == HUGE_VAL) return false;
  const double parent_area = half_area(box.lo, box.hi);
  const double split_cost = kSahTraversalCost + (parent_area > 0.0 ? best_cost / parent_area : count);
  return !(count <= kMaxLeafSize && count <= split_cost);
}

// Builds the subtree of order_[begin, end) and returns its node index (depth-first layout: the
// left child directly follows its parent). Binned SAH splits (sah_split) down to kSahMaxDepth;
// below it, and where no SAH split pays, median splits along the longest axis of the
// centroids' bounds, to leaves of at most kLeafSize triangles.
int TriangleMesh::build(int begin, int end, int depth, const std::vector<Vec3>& centroids, const std::vector<Box>& boxes) {
  depth_ = std::max(depth_, depth);
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Box box, centroid_box;
  for (int i = begin; i < end; ++i) {
    const auto t = static_cast<std::size_t>(order_[static_cast<std::size_t>(i)]);
    box.lo = component_min(box.lo, boxes[t].lo);
    box.hi = component_max(box.hi, boxes[t].hi);
    centroid_box.lo = component_min(centroid_box.lo, centroids[t]);
    centroid_box.hi = component_max(centroid_box.hi, centroids[t]);
  }
  const double bounds[6] = {box.lo.x, box.lo.y, box.lo.z, box.hi.x, box.hi.y, box.hi.z};
  std::copy(bounds, bounds + 6, nodes_[index].box);
  const auto make_leaf = [&] {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  };
  if (end - begin <= 1) return make_leaf();
  SahPlane plane;
  int middle = -1;
  if (depth < kSahMaxDepth && sah_split(begin, end, box, centroid_box, centroids, boxes, plane)) {
    const auto first = order_.begin() + begin;
    const auto split = std::stable_partition(
        first, order_.begin() + end, [&](int t) { return plane.bin_of(centroids[static_cast<std::size_t>(t)]) < plane.first_right_bin; });
    middle = begin + static_cast<int>(split - first);  // both sides hold triangles (sah_split)
  } else if (depth < kSahMaxDepth && end - begin <= kMaxLeafSize) {
    return make_leaf();  // the SAH prefers this leaf
  }
  if (middle < 0) {
    if (end - begin <= kLeafSize) return make_leaf();
    // Median split along the longest axis of the centroids' bounds.
    const Vec3 extent = centroid_box.hi - centroid_box.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    middle = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end, [&](int a, int b) {
      const double ca = axis_value(centroids[static_cast<std::size_t>(a)], axis),
                   cb = axis_value(centroids[static_cast<std::size_t>(b)], axis);
      return ca < cb || (ca == cb && a < b);
    });
  }
  build(begin, middle, depth + 1, centroids, boxes);
  const int right = build(middle, end, depth + 1, centroids, boxes);
  nodes_[index].first = right;
  nodes_[index].count = 0;
  return index;
}

bool TriangleMesh::hit_triangle(int index, const Ray& ray, double t_min, double t_max, double& t, double& b1, double& b2) const {
  const Edges& g = edges_[index];
  return hit_edges(g, ray, t_min, t_max, t, b1, b2);
}

bool TriangleMesh::hit_edges(const Edges& g, const Ray& ray, double t_min, double t_max, double& t, double& b1, double& b2) {
  // Moller-Trumbore: solve o + t d = (1 - b1 - b2) p0 + b1 p1 + b2 p2 by Cramer's rule with
  // e1 = p1 - p0, e2 = p2 - p0, s = o - p0: det = e1 . (d x e2), b1 = s . (d x e2) / det,
  // b2 = d . (s x e1) / det, t = e2 . (s x e1) / det.
  const Vec3 p0 = g.p0, e1 = g.e1, e2 = g.e2;
  const Vec3 pvec = cross(ray.direction, e2);
  const double det = dot(e1, pvec);
  if (det == 0.0) return false;
  const double inv = 1.0 / det;
  const Vec3 s = ray.origin - p0;
  b1 = dot(s, pvec) * inv;
  if (b1 < 0.0 || b1 > 1.0) return false;
  const Vec3 qvec = cross(s, e1);
  b2 = dot(ray.direction, qvec) * inv;
  if (b2 < 0.0 || b1 + b2 > 1.0) return false;
  t = dot(e2, qvec) * inv;
  return t > t_min && t < t_max;
}

void TriangleMesh::fill_hit(int index, const Ray& ray, double t, double b1, double b2, SurfaceHit& hit) const {
  const auto& tri = triangles_[index];
  const MeshVertex& v0 = vertices_[tri[0]];
  const MeshVertex& v1 = vertices_[tri[1]];
  const MeshVertex& v2 = vertices_[tri[2]];
  const double b0 = 1.0 - b1 - b2;
  hit.t = t;
  hit.position = ray.origin + t * ray.direction;
  hit.normal = normalize(b0 * v0.normal + b1 * v1.normal + b2 * v2.normal);
  const Vec3 tangent = b0 * v0.tangent + b1 * v1.tangent + b2 * v2.tangent;
  hit.tangent = normalize(tangent - dot(tangent, hit.normal) * hit.normal);
  hit.bitangent = cross(hit.normal, hit.tangent);
  hit.object = objects_.empty() ? 0 : objects_[static_cast<std::size_t>(index)];
  hit.bitangent_sign = b0 * v0.tangent_sign + b1 * v1.tangent_sign + b2 * v2.tangent_sign < 0.0 ? -1.0 : 1.0;
  hit.alpha_scale = 1.0;
  hit.triangle = index;
  hit.geometric_normal = hit.normal;
  hit.geometric_tangent = hit.tangent;
  hit.geometric_bitangent = hit.bitangent;
  hit.uv = b0 * v0.uv + b1 * v1.uv + b2 * v2.uv;
  // PBRT 3 Sec. 3.6.2: [dp02 dp12] = [dpdu dpdv] [duv02 duv12].
  const Vec2 duv02 = v0.uv - v2.uv, duv12 = v1.uv - v2.uv;
  const Vec3 dp02 = v0.position - v2.position, dp12 = v1.position - v2.position;
  const double det = duv02.x * duv12.y - duv02.y * duv12.x;
  if (det != 0.0) {
    const double inv = 1.0 / det;
    hit.dpdu = inv * (duv12.y * dp02 - duv02.y * dp12);
    hit.dpdv = inv * (duv02.x * dp12 - duv12.x * dp02);
  } else {
    hit.dpdu = hit.dpdv = Vec3{};
  }
}

bool TriangleMesh::extrapolate(int index, const Ray& ray, SurfaceHit& hit) const {
  if (index < 0 || index >= static_cast<int>(triangles_.size())) return false;
  // Moller-Trumbore's Cramer solution without the barycentric bounds.
  const Edges& g = edges_[static_cast<std::size_t>(index)];
  const Vec3 pvec = cross(ray.direction, g.e2);
  const double det = dot(g.e1, pvec);
  if (det == 0.0) return false;
  const double inv = 1.0 / det;
  const Vec3 s = ray.origin - g.p0;
  const Vec3 qvec = cross(s, g.e1);
  const double b1 = dot(s, pvec) * inv, b2 = dot(ray.direction, qvec) * inv, t = dot(g.e2, qvec) * inv;
  if (!(t > 0.0)) return false;
  const auto& tri = triangles_[static_cast<std::size_t>(index)];
  const double b0 = 1.0 - b1 - b2;
  const Vec3 normal = b0 * vertices_[tri[0]].normal + b1 * vertices_[tri[1]].normal + b2 * vertices_[tri[2]].normal;
  if (!(ref::length(normal) > 1e-12)) return false;
  fill_hit(index, ray, t, b1, b2, hit);
  return std::isfinite(hit.tangent.x) && std::isfinite(hit.tangent.y) && std::isfinite(hit.tangent.z);
}

bool TriangleMesh::intersect(const Ray& ray, double t_min, SurfaceHit& hit) const {
  if (nodes_.empty()) return false;
  const SlabRay slab(ray);
  double best = HUGE_VAL, best_b1 = 0.0, best_b2 = 0.0;
  double best_limit = HUGE_VAL;  // nextafter(best): an equal-distance hit still counts
  int best_index = -1;
  // Nodes whose box starts at or before the best hit may still hold an equal-distance hit
  // with a lower index (the tie rule), hence <= below.
  struct Entry {
    int node;
    double t;  // where the ray enters the node's box
  };
  Entry stack[kMaxDepth + 4];
  int top = 0;
  const double t_root = box_entry(nodes_[0].box, slab, t_min, HUGE_VAL);
  if (t_root == HUGE_VAL) return false;
  stack[top++] = {0, t_root};
  while (top > 0) {
    const Entry entry = stack[--top];
    if (entry.t > best) continue;  // a nearer hit was found since the box was pushed
    const Node& node = nodes_[entry.node];
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int index = order_[i];
        double t, b1, b2;
        if (!hit_edges(leaf_edges_[i], ray, t_min, best_limit, t, b1, b2)) continue;
        if (t < best || index < best_index) {
          best = t;
          best_limit = std::nextafter(t, HUGE_VAL);
          best_b1 = b1;
          best_b2 = b2;
          best_index = index;
        }
      }
      continue;
    }
    const int left = entry.node + 1, right = node.first;
    const double t_left = box_entry(nodes_[left].box, slab, t_min, best);
    const double t_right = box_entry(nodes_[right].box, slab, t_min, best);
    // Push the farther child first so that the nearer one is visited next.
    const bool left_first = t_left <= t_right;
    const int near = left_first ? left : right, far = left_first ? right : left;
    const double t_near = left_first ? t_left : t_right, t_far = left_first ? t_right : t_left;
    if (t_far != HUGE_VAL) stack[top++] = {far, t_far};
    if (t_near != HUGE_VAL) stack[top++] = {near, t_near};
  }
  if (best_index < 0) return false;
  fill_hit(best_index, ray, best, best_b1, best_b2, hit);
  return true;
}

bool TriangleMesh::intersect_brute_force(const Ray& ray, double t_min, SurfaceHit& hit) const {
  double best = HUGE_VAL, best_b1 = 0.0, best_b2 = 0.0;
  int best_index = -1;
  for (int index = 0; index < static_cast<int>(triangles_.size()); ++index) {
    double t, b1, b2;
    if (!hit_triangle(index, ray, t_min, HUGE_VAL, t, b1, b2)) continue;
    if (t < best) {  // ascending index: on a tie the lower index stays
      best = t;
      best_b1 = b1;
      best_b2 = b2;
      best_index = index;
    }
  }
  if (best_index < 0) return false;
  fill_hit(best_index, ray, best, best_b1, best_b2, hit);
  return true;
}

std::string TriangleMesh::describe() const {
  std::ostringstream s;
  s << "mesh(" << label_ << ",vertices=" << vertices_.size() << ",triangles=" << triangles_.size() << ",hash=" << std::hex << hash_ << ")";
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Torus knot

Vec3 TorusKnot::curve(double phi) const {
  const double ring = major + offset * std::cos(q * phi);
  return {ring * std::cos(p * phi), ring * std::sin(p * phi), offset * std::sin(q * phi)};
}

Vec3 TorusKnot::curve_derivative(double phi) const {
  const double ring = major + offset * std::cos(q * phi);
  const double ring_d = -offset * q * std::sin(q * phi);
  return {ring_d * std::cos(p * phi) - p * ring * std::sin(p * phi), ring_d * std::sin(p * phi) + p * ring * std::cos(p * phi),
          offset * q * std::cos(q * phi)};
}

Vec3 TorusKnot::tangent(Vec2 uv) const { return normalize(curve_derivative(2.0 * kPi * uv.x)); }

Vec3 TorusKnot::normal(Vec2 uv) const {
  const double phi = 2.0 * kPi * uv.x, psi = 2.0 * kPi * uv.y;
  // N1 = cos(q phi) e_r + sin(q phi) e_z, e_r = (cos p phi, sin p phi, 0); N2 = T x N1.
  const Vec3 n1{std::cos(q * phi) * std::cos(p * phi), std::cos(q * phi) * std::sin(p * phi), std::sin(q * phi)};
  const Vec3 n2 = cross(tangent(uv), n1);
  return std::cos(psi) * n1 + std::sin(psi) * n2;
}

Vec3 TorusKnot::point(Vec2 uv) const { return curve(2.0 * kPi * uv.x) + tube * normal(uv); }

std::string TorusKnot::describe() const {
  std::ostringstream s;
  s.precision(17);
  s << "torus_knot(p=" << p << ",q=" << q << ",R=" << major << ",a=" << offset << ",rho=" << tube << ",segments=" << segments
    << ",sides=" << sides << ")";
  return s.str();
}

TriangleMesh TorusKnot::mesh() const {
  const int columns = sides + 1;
  std::vector<MeshVertex> vertices(static_cast<std::size_t>(segments + 1) * columns);
  for (int i = 0; i <= segments; ++i)
    for (int j = 0; j <= sides; ++j) {
      // The closing ring/column copies the first one's geometry (no crack from rounding
      // of cos(2 pi k)); only its uv differs.
      const Vec2 geometry_uv{static_cast<double>(i % segments) / segments, static_cast<double>(j % sides) / sides};
      MeshVertex& v = vertices[static_cast<std::size_t>(i) * columns + j];
      v.position = point(geometry_uv);
      v.normal = normal(geometry_uv);
      v.tangent = tangent(geometry_uv);
      v.uv = {static_cast<double>(i) / segments, static_cast<double>(j) / sides};
    }
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(static_cast<std::size_t>(segments) * sides * 2);
  for (int i = 0; i < segments; ++i)
    for (int j = 0; j < sides; ++j) {
      const int a = i * columns + j, b = (i + 1) * columns + j;
      triangles.push_back({a, b, b + 1});
      triangles.push_back({a, b + 1, a + 1});
    }
  return TriangleMesh(describe(), std::move(vertices), std::move(triangles));
}

}  // namespace saagen::measure
