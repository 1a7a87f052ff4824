#include "case/mesh/mesh_shape.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace sph {
namespace {

constexpr std::uint32_t kLeafTriangles = 4;

// Squared distance from p to the triangle abc (Ericson 2005, Real-Time Collision Detection,
// sec. 5.1.5: the Voronoi region of p among the vertices, edges and face).
double squared_distance_to_triangle(const Point3& p, const Point3& a, const Point3& b,
                                    const Point3& c) {
  const Point3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
  const Point3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (ap - d1 / (d1 - d3) * ab).squaredNorm();
  const Point3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (ap - d2 / (d2 - d6) * ac).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (bp - (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b)).squaredNorm();
  const double denom = 1 / (va + vb + vc);
  return (ap - vb * denom * ab - vc * denom * ac).squaredNorm();
}

double squared_distance_to_box(const Point3& p, const Aabb& b) {
  return (b.lo - p).cwiseMax(p - b.hi).cwiseMax(0.0).squaredNorm();
}

// Which side of the edge u -> v the point p lies on, in the (y, z) plane a ray along +x
// projects to: +1 left, -1 right. Computed from the lexicographically smaller end, so the
// two triangles sharing an edge get the same value up to sign, and a point exactly on the
// line is moved off it by a fixed infinitesimal shift (Edelsbrunner & Muecke 1990, simulation
// of simplicity): every ray then crosses a closed surface an even number of times, through
// edges and vertices too, and the count is the same however the mesh is triangulated.
int side(const Point3& u, const Point3& v, const Point3& p, double& area) {
  const bool forward = u.y() < v.y() || (u.y() == v.y() && u.z() < v.z());
  const Point3& s = forward ? u : v;
  const Point3& e = forward ? v : u;
  double o = (e.y() - s.y()) * (p.z() - s.z()) - (e.z() - s.z()) * (p.y() - s.y());
  if (!forward) o = -o;
  area = o;
  if (o > 0) return 1;
  if (o < 0) return -1;
  // p shifted by (eps, eps^2) in (y, z): the sign of the cross product of (v - u) with it.
  if (v.z() != u.z()) return v.z() < u.z() ? 1 : -1;
  return v.y() > u.y() ? 1 : -1;
}

}  // namespace

MeshShape::MeshShape(TriangleMesh mesh, double exact_within)
    : mesh_(std::move(mesh)), exact_within_(exact_within) {
  const auto n = static_cast<std::uint32_t>(mesh_.triangles.size());
  if (n == 0) return;
  std::vector<Point3> centroids(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const auto& tri = mesh_.triangles[t];
    centroids[t] = (mesh_.vertices[tri[0]] + mesh_.vertices[tri[1]] + mesh_.vertices[tri[2]]) / 3.0;
  }
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0u);
  nodes_.reserve(2 * (n / kLeafTriangles + 1));
  build(0, n, centroids);
}

std::uint32_t MeshShape::build(std::uint32_t first, std::uint32_t count,
                               const std::vector<Point3>& centroids) {
  const auto id = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Aabb box, mid;
  for (std::uint32_t i = first; i < first + count; ++i) {
    const auto& tri = mesh_.triangles[order_[i]];
    for (int k = 0; k < 3; ++k) box.grow(mesh_.vertices[tri[static_cast<std::size_t>(k)]]);
    mid.grow(centroids[order_[i]]);
  }
  nodes_[id].box = box;
  if (count <= kLeafTriangles) {
    nodes_[id].first = first;
    nodes_[id].count = count;
    return id;
  }
  // Median split of the centroids along the longest axis of their box.
  int axis = 0;
  const Point3 ext = mid.hi - mid.lo;
  if (ext.y() > ext[axis]) axis = 1;
  if (ext.z() > ext[axis]) axis = 2;
  const std::uint32_t half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half,
                   order_.begin() + first + count, [&](std::uint32_t a, std::uint32_t b) {
                     return centroids[a][axis] < centroids[b][axis] ||
                            (centroids[a][axis] == centroids[b][axis] && a < b);
                   });
  const std::uint32_t left = build(first, half, centroids);
  const std::uint32_t right = build(first + half, count - half, centroids);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

double MeshShape::cost() const {
  // The ray's walk over the hierarchy (measured: 50 boxes' work for 192 triangles); the
  // nearest-triangle search, where it runs, only near the surface.
  return 8 + 6 * std::log2(1.0 + static_cast<double>(mesh_.triangles.size()));
}

double MeshShape::unsigned_distance(const Point3& p, double cap) const {
  if (nodes_.empty()) return cap;
  double best = cap < 1e150 ? cap * cap : 1e300;
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (squared_distance_to_box(p, n.box) >= best) continue;
    if (n.count > 0) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const auto& t = mesh_.triangles[order_[i]];
        best = std::min(best,
                        squared_distance_to_triangle(p, mesh_.vertices[t[0]], mesh_.vertices[t[1]],
                                                     mesh_.vertices[t[2]]));
      }
      continue;
    }
    // The nearer child last, so that it is visited first and prunes the other.
    const double dl = squared_distance_to_box(p, nodes_[n.left].box);
    const double dr = squared_distance_to_box(p, nodes_[n.right].box);
    if (top + 2 > 64) continue;  // deeper than a median split of 2^32 triangles can reach
    if (dl < dr) {
      stack[top++] = n.right;
      stack[top++] = n.left;
    } else {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  return std::min(cap, std::sqrt(best));
}

// +-1 when the ray from p along +x crosses triangle `tri` (the sign is the triangle's
// orientation seen along the ray), 0 otherwise.
int MeshShape::crossing(std::uint32_t tri, const Point3& p) const {
  const auto& t = mesh_.triangles[tri];
  const Point3 &a = mesh_.vertices[t[0]], &b = mesh_.vertices[t[1]], &c = mesh_.vertices[t[2]];
  double wc, wa, wb;  // twice the projected areas opposite c, a and b
  const int s0 = side(a, b, p, wc), s1 = side(b, c, p, wa), s2 = side(c, a, p, wb);
  if (s0 != s1 || s1 != s2) return 0;
  const double sum = wa + wb + wc;
  // The crossing's x from the barycentric weights; a triangle seen edge-on (sum 0) has none
  // of its own: its neighbours', by the shift above, count the ray once.
  if (sum == 0.0) return 0;
  const double x = (wa * a.x() + wb * b.x() + wc * c.x()) / sum;
  return x > p.x() ? s0 : 0;
}

int MeshShape::winding_number(const Point3& p) const {
  if (nodes_.empty()) return 0;
  int w = 0;
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (n.box.hi.x() < p.x() || p.y() < n.box.lo.y() || p.y() > n.box.hi.y() ||
        p.z() < n.box.lo.z() || p.z() > n.box.hi.z())
      continue;
    if (n.count > 0) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) w += crossing(order_[i], p);
    } else if (top + 2 <= 64) {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  return w;
}

double MeshShape::distance(const Point3& p) const {
  const bool inside = winding_number(p) != 0;
  if (exact_within_ > 0) {
    const double d = unsigned_distance(p, exact_within_);
    return inside ? -d : d;
  }
  // Only the sign is needed: outside, the distance to the bounding box is a lower bound;
  // inside, the smallest negative number is.
  if (inside) return -std::numeric_limits<double>::denorm_min();
  return std::max(std::sqrt(squared_distance_to_box(p, nodes_[0].box)),
                  std::numeric_limits<double>::denorm_min());
}

}  // namespace sph
