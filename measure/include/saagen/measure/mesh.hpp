// saagen ground-truth renderer: triangle meshes with smooth vertex normals, and the torus-knot
// tube they are used for.
//
// A TriangleMesh is what engines draw: per-vertex position, unit normal, unit tangent and uv,
// interpolated with the barycentric coordinates of the hit. Intersection: Moller-Trumbore
// (Moller & Trumbore 1997) in double precision, double-sided, through a bounding volume
// hierarchy (axis-aligned boxes, built once in the constructor: binned surface-area-heuristic
// splits (Wald 2007) to leaves of at most 8 triangles, median splits where no SAH plane
// separates the centroids; traversal nearest child first). Of two hits at the same distance
// the lower triangle index wins, so the BVH and the brute-force loop (intersect_brute_force)
// return the same hit, whatever the tree's shape: a different build changes no image.
//
// Hit frame (SurfaceHit): geometric normal = shading normal = normalize(sum w_i n_i) (the
// interpolated vertex normal, not the face normal); tangent = the interpolated vertex tangent
// made orthogonal to it (Gram-Schmidt), bitangent = n x t; uv = sum w_i uv_i; dpdu, dpdv = the
// triangle's constant partials, the solution of p_i - p_2 = dpdu (u_i - u_2) + dpdv (v_i - v_2)
// for i = 0, 1 (Pharr, Jakob & Humphreys, PBRT 3rd ed., Sec. 3.6.2).
#pragma once

#include "saagen/measure/shape.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace saagen::measure {

struct MeshVertex {
  Vec3 position;
  Vec3 normal;   // unit
  Vec3 tangent;  // unit, orthogonal to normal
  Vec2 uv;
  // glTF's TANGENT.w (MikkTSpace's sign): bitangent = sign (n x t). The hit's bitangent_sign is
  // the sign of the barycentric mean of its vertices' signs.
  double tangent_sign = 1.0;
};

class TriangleMesh final : public Shape {
 public:
  // label: the numbers the mesh was generated from (part of describe()). objects: per
  // triangle, the connected surface it belongs to (SurfaceHit::object; a glTF primitive, a draw
  // call, whose quads never share pixels with another's); empty: all 0.
  TriangleMesh(std::string label, std::vector<MeshVertex> vertices, std::vector<std::array<int, 3>> triangles,
               std::vector<int> objects = {});

  bool intersect(const Ray& ray, double t_min, SurfaceHit& hit) const override;
  // The same nearest hit by testing every triangle (tests).
  bool intersect_brute_force(const Ray& ray, double t_min, SurfaceHit& hit) const;
  // Label, counts and a 64-bit hash of every vertex and index.
  std::string describe() const override;

  const std::vector<MeshVertex>& vertices() const { return vertices_; }
  const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }
  int bvh_nodes() const { return static_cast<int>(nodes_.size()); }
  int bvh_depth() const { return depth_; }

  // Möller-Trumbore: the distance and barycentrics (b1, b2) of a hit on triangle `index` with
  // t_min < t < t_max; false otherwise (or for a ray in the triangle's plane).
  bool hit_triangle(int index, const Ray& ray, double t_min, double t_max, double& t, double& b1, double& b2) const;
  // The hit record of triangle `index` where the ray meets its plane, inside the triangle or
  // not (barycentrics extrapolated: a GPU's helper invocation); false for a ray parallel to the
  // plane, meeting it at t <= 0, or an extrapolated normal of zero length.
  bool extrapolate(int index, const Ray& ray, SurfaceHit& hit) const;
  // The hit record of a triangle hit (see the top of this file).
  void fill_hit(int index, const Ray& ray, double t, double b1, double b2, SurfaceHit& hit) const;

 private:
  struct Box {
    Vec3 lo{1e300, 1e300, 1e300};
    Vec3 hi{-1e300, -1e300, -1e300};
  };
  struct Edges {  // Moller-Trumbore's p0, e1 = p1 - p0, e2 = p2 - p0
    Vec3 p0, e1, e2;
  };
  struct Node {
    double box[6];  // lo.x, lo.y, lo.z, hi.x, hi.y, hi.z
    int first = 0;  // leaf: first entry of order_; interior: index of the right child
    int count = 0;  // leaf: number of triangles; 0 for an interior node (left child = this + 1)
  };
  int build(int begin, int end, int depth, const std::vector<Vec3>& centroids, const std::vector<Box>& boxes);
  struct SahPlane {  // between bins first_right_bin - 1 and first_right_bin along axis
    int axis = 0;
    double lo = 0.0;     // the centroids' lower bound along axis
    double scale = 0.0;  // bins per unit length
    int first_right_bin = 0;
    int bin_of(Vec3 centroid) const;
  };
  bool sah_split(int begin, int end, const Box& box, const Box& centroid_box, const std::vector<Vec3>& centroids,
                 const std::vector<Box>& boxes, SahPlane& plane) const;
  Box triangle_box(int index) const;
  static bool hit_edges(const Edges& g, const Ray& ray, double t_min, double t_max, double& t, double& b1, double& b2);

  std::string label_;
  std::vector<MeshVertex> vertices_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<int> objects_;       // per triangle, or empty
  std::vector<Edges> edges_;       // per triangle
  std::vector<int> order_;         // triangle indices in BVH leaf order
  std::vector<Edges> leaf_edges_;  // edges_ in leaf order
  std::vector<Node> nodes_;
  int depth_ = 0;
  std::uint64_t hash_ = 0;
};

// The (p, q) torus knot c(phi) = ((R + a cos(q phi)) cos(p phi), (R + a cos(q phi)) sin(p phi),
// a sin(q phi)), phi in [0, 2 pi), wrapped in a tube of radius rho. The offset from the core
// circle, a N1 with N1 = cos(q phi) e_r + sin(q phi) e_z, is orthogonal to c'(phi) (expand
// c' = -a q sin(q phi) e_r + p (R + a cos(q phi)) e_phi + a q cos(q phi) e_z), so (T, N1, N2 =
// T x N1), T = c' / |c'|, is a smooth periodic frame along the curve. Tube surface
// S(u, v) = c(2 pi u) + rho (cos(2 pi v) N1 + sin(2 pi v) N2); its exact normal is
// cos(2 pi v) N1 + sin(2 pi v) N2 (a canal surface's normal is the radial direction, valid
// while rho < 1 / curvature) and T is a tangent along the curve.
struct TorusKnot {
  int p = 2;
  int q = 3;
  double major = 1.0;    // R
  double offset = 0.45;  // a
  double tube = 0.2;     // rho
  int segments = 512;    // along the curve
  int sides = 24;        // around the tube

  Vec3 curve(double phi) const;
  Vec3 curve_derivative(double phi) const;  // dc/dphi
  Vec3 point(Vec2 uv) const;                // S(u, v)
  Vec3 normal(Vec2 uv) const;               // exact unit normal
  Vec3 tangent(Vec2 uv) const;              // T(2 pi u)
  std::string describe() const;

  // (segments + 1) x (sides + 1) vertices (the closing ring and column repeat the first ones'
  // positions and frames exactly, with u = 1 or v = 1), two triangles per quad.
  TriangleMesh mesh() const;
};

}  // namespace saagen::measure
