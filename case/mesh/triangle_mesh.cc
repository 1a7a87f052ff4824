#include "case/mesh/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace sph {
namespace {

// Welds vertices while a file is read: equal coordinates (bit for bit) become one vertex.
class Welder {
 public:
  explicit Welder(v1::TriangleMesh& out) : out_(out) {}
  std::uint32_t index(double x, double y, double z) {
    const auto [it, fresh] =
        ids_.try_emplace({x, y, z}, static_cast<std::uint32_t>(out_.vertices_size() / 3));
    if (fresh) {
      out_.add_vertices(x);
      out_.add_vertices(y);
      out_.add_vertices(z);
    }
    return it->second;
  }

 private:
  v1::TriangleMesh& out_;
  std::map<std::array<double, 3>, std::uint32_t> ids_;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("STL file '" + path + "': " + what);
}

void read_binary(std::ifstream& in, const std::string& path, std::uint32_t count,
                 v1::TriangleMesh& out) {
  Welder weld(out);
  char rec[50];
  for (std::uint32_t t = 0; t < count; ++t) {
    if (!in.read(rec, sizeof rec))
      fail(path, "ends after " + std::to_string(t) + " of the " + std::to_string(count) +
                     " triangles its header announces");
    float xyz[9];
    std::memcpy(xyz, rec + 12, sizeof xyz);  // after the facet normal, which we recompute
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(xyz[3 * k]) || !std::isfinite(xyz[3 * k + 1]) ||
          !std::isfinite(xyz[3 * k + 2]))
        fail(path, "triangle " + std::to_string(t) + " has a coordinate that is not a number");
      out.add_triangles(weld.index(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]));
    }
  }
}

void read_ascii(std::ifstream& in, const std::string& path, std::size_t max_triangles,
                v1::TriangleMesh& out) {
  Welder weld(out);
  std::string word;
  int corners = 0;
  std::size_t line_words = 0;
  while (in >> word) {
    if (++line_words > 32 * (max_triangles + 1))  // a facet is 21 words
      fail(path,
           "is longer than an ASCII STL of " + std::to_string(max_triangles) + " triangles can be");
    if (word == "vertex") {
      double x, y, z;
      if (!(in >> x >> y >> z) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        fail(path, "a 'vertex' is not followed by three numbers (triangle " +
                       std::to_string(out.triangles_size() / 3) + ")");
      if (out.triangles_size() / 3 >= static_cast<int>(max_triangles) && corners == 0)
        fail(path, "has more than " + std::to_string(max_triangles) +
                       " triangles, all the case's limit of mesh triangles leaves for it");
      out.add_triangles(weld.index(x, y, z));
      corners = (corners + 1) % 3;
    } else if (word == "endloop" && corners != 0) {
      fail(path, "a facet has " + std::to_string(corners) + " vertices, not 3");
    }
  }
  if (corners != 0) fail(path, "ends inside a facet");
  if (out.triangles_size() == 0) fail(path, "holds no triangles (neither binary nor ASCII STL)");
}

}  // namespace

TriangleMesh mesh_from_proto(const v1::TriangleMesh& m) {
  const double scale = m.has_scale() ? m.scale() : 1.0;
  const Eigen::Vector3d offset(m.offset().x(), m.offset().y(), m.offset().z());
  TriangleMesh out;
  out.vertices.reserve(static_cast<std::size_t>(m.vertices_size() / 3));
  for (int i = 0; i + 2 < m.vertices_size(); i += 3)
    out.vertices.push_back(
        scale * Eigen::Vector3d(m.vertices(i), m.vertices(i + 1), m.vertices(i + 2)) + offset);
  out.triangles.reserve(static_cast<std::size_t>(m.triangles_size() / 3));
  for (int i = 0; i + 2 < m.triangles_size(); i += 3)
    out.triangles.push_back({m.triangles(i), m.triangles(i + 1), m.triangles(i + 2)});
  return out;
}

void read_stl(const std::string& path, std::size_t max_triangles, v1::TriangleMesh& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot be read");
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  in.seekg(0);
  char header[84] = {};
  in.read(header, sizeof header);
  std::uint32_t count = 0;
  std::memcpy(&count, header + 80, sizeof count);
  // A binary file is exactly 84 + 50 n bytes long; ASCII files start with "solid", but so do
  // the headers of some binary ones, so the length decides.
  if (in && size == 84 + 50 * static_cast<std::uint64_t>(count)) {
    if (count > max_triangles)
      fail(path, "has " + std::to_string(count) + " triangles; the limit is " +
                     std::to_string(max_triangles) +
                     " (what the case's limit of mesh triangles leaves for it)");
    if (count == 0) fail(path, "holds no triangles");
    read_binary(in, path, count, out);
    return;
  }
  if (std::strncmp(header, "solid", 5) != 0)
    fail(path, "is neither binary STL (" + std::to_string(size) + " bytes, not 84 + 50 x " +
                   std::to_string(count) + ") nor ASCII STL (no leading 'solid')");
  in.clear();
  in.seekg(0);
  read_ascii(in, path, max_triangles, out);
}

MeshTopology check_topology(const TriangleMesh& m) {
  MeshTopology top;
  // Directed edge (a, b) -> how often it occurs; a closed, consistently oriented surface has
  // every edge once in each direction.
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(3 * m.triangles.size());
  const auto key = [](std::uint32_t a, std::uint32_t b) {
    return (static_cast<std::uint64_t>(a) << 32) | b;
  };
  for (const auto& t : m.triangles) {
    const auto& a = m.vertices[t[0]];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
        (m.vertices[t[1]] - a).cross(m.vertices[t[2]] - a).squaredNorm() == 0.0) {
      ++top.degenerate;
    }
    for (int k = 0; k < 3; ++k) ++directed[key(t[k], t[(k + 1) % 3])];
  }
  for (const auto& [k, n] : directed) {
    const auto a = static_cast<std::uint32_t>(k >> 32), b = static_cast<std::uint32_t>(k);
    const auto rev = directed.find(key(b, a));
    const int back = rev == directed.end() ? 0 : rev->second;
    if (a > b && back > 0) continue;  // the pair is counted once, from its smaller end
    if (n + back > 2)
      ++top.nonmanifold_edges;
    else if (n == 2 || back == 2)
      ++top.flipped_edges;
    else if (back == 0)
      ++top.open_edges;
  }
  return top;
}

MassProperties mass_properties(const TriangleMesh& m) {
  // Eberly 2002, sec. 3: the ten integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, zx over the
  // solid, each a sum over triangles of a polynomial in the vertex coordinates.
  const auto sub = [](double w0, double w1, double w2, double& f1, double& f2, double& f3,
                      double& g0, double& g1, double& g2) {
    const double t0 = w0 + w1, t1 = w0 * w0, t2 = t1 + w1 * t0;
    f1 = t0 + w2;
    f2 = t2 + w2 * f1;
    f3 = w0 * t1 + w1 * t2 + w2 * f2;
    g0 = f2 + w0 * (f1 + w0);
    g1 = f2 + w1 * (f1 + w1);
    g2 = f2 + w2 * (f1 + w2);
  };
  double in[10] = {};
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d &p0 = m.vertices[t[0]], &p1 = m.vertices[t[1]], &p2 = m.vertices[t[2]];
    const Eigen::Vector3d d = (p1 - p0).cross(p2 - p0);
    double f1x, f2x, f3x, g0x, g1x, g2x, f1y, f2y, f3y, g0y, g1y, g2y, f1z, f2z, f3z, g0z, g1z, g2z;
    sub(p0.x(), p1.x(), p2.x(), f1x, f2x, f3x, g0x, g1x, g2x);
    sub(p0.y(), p1.y(), p2.y(), f1y, f2y, f3y, g0y, g1y, g2y);
    sub(p0.z(), p1.z(), p2.z(), f1z, f2z, f3z, g0z, g1z, g2z);
    in[0] += d.x() * f1x;
    in[1] += d.x() * f2x;
    in[2] += d.y() * f2y;
    in[3] += d.z() * f2z;
    in[4] += d.x() * f3x;
    in[5] += d.y() * f3y;
    in[6] += d.z() * f3z;
    in[7] += d.x() * (p0.y() * g0x + p1.y() * g1x + p2.y() * g2x);
    in[8] += d.y() * (p0.z() * g0y + p1.z() * g1y + p2.z() * g2y);
    in[9] += d.z() * (p0.x() * g0z + p1.x() * g1z + p2.x() * g2z);
  }
  constexpr double mult[10] = {1.0 / 6,  1.0 / 24, 1.0 / 24,  1.0 / 24,  1.0 / 60,
                               1.0 / 60, 1.0 / 60, 1.0 / 120, 1.0 / 120, 1.0 / 120};
  for (int i = 0; i < 10; ++i) in[i] *= mult[i];
  MassProperties mp;
  mp.volume = in[0];
  if (mp.volume == 0.0) return mp;
  const Eigen::Vector3d c(in[1] / in[0], in[2] / in[0], in[3] / in[0]);
  mp.centroid = c;
  const double v = in[0];
  Eigen::Matrix3d& I = mp.inertia;
  I(0, 0) = in[5] + in[6] - v * (c.y() * c.y() + c.z() * c.z());
  I(1, 1) = in[4] + in[6] - v * (c.z() * c.z() + c.x() * c.x());
  I(2, 2) = in[4] + in[5] - v * (c.x() * c.x() + c.y() * c.y());
  I(0, 1) = I(1, 0) = -(in[7] - v * c.x() * c.y());
  I(1, 2) = I(2, 1) = -(in[8] - v * c.y() * c.z());
  I(0, 2) = I(2, 0) = -(in[9] - v * c.z() * c.x());
  return mp;
}

}  // namespace sph
