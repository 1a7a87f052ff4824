// Geometry from files: STL reading, the inside test of a mesh (rays through its edges and
// vertices included), its exact mass properties, and bodies filled from meshes against them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <random>

#include "case/lattice.h"
#include "case/load.h"
#include "case/mesh/mesh_shape.h"
#include "case/mesh/triangle_mesh.h"
#include "case/validate.h"

namespace sph {
namespace {

using V = Eigen::Vector3d;

TriangleMesh unit_cube() {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k) m.vertices.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  // Two triangles a face, counter-clockwise seen from outside.
  const std::uint32_t f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                 {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : f) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

// Icosahedron subdivided `levels` times, vertices on the sphere of radius r, outward.
TriangleMesh icosphere(int levels, double r) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  TriangleMesh m;
  for (const V& v : {V(-1, t, 0), V(1, t, 0), V(-1, -t, 0), V(1, -t, 0), V(0, -1, t), V(0, 1, t),
                     V(0, -1, -t), V(0, 1, -t), V(t, 0, -1), V(t, 0, 1), V(-t, 0, -1), V(-t, 0, 1)})
    m.vertices.push_back(v.normalized());
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    const auto middle = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      return mid[key] = static_cast<std::uint32_t>(m.vertices.size() - 1);
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    for (const auto& tr : m.triangles) {
      const std::uint32_t a = middle(tr[0], tr[1]), b = middle(tr[1], tr[2]),
                          c = middle(tr[2], tr[0]);
      next.push_back({tr[0], a, c});
      next.push_back({tr[1], b, a});
      next.push_back({tr[2], c, b});
      next.push_back({a, b, c});
    }
    m.triangles = std::move(next);
  }
  for (auto& v : m.vertices) v *= r;
  return m;
}

// Torus of radii R (centre line) and r (tube) about the z axis, nu x nv quads, outward.
TriangleMesh torus(double R, double r, int nu, int nv) {
  TriangleMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      m.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u),
                              (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  const auto id = [&](int i, int j) {
    return static_cast<std::uint32_t>(((i + nu) % nu) * nv + (j + nv) % nv);
  };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

void write_binary_stl(const std::string& path, const TriangleMesh& m, const char* header) {
  std::ofstream out(path, std::ios::binary);
  char h[80] = {};
  std::snprintf(h, sizeof h, "%s", header);
  out.write(h, 80);
  const auto n = static_cast<std::uint32_t>(m.triangles.size());
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : m.triangles) {
    float rec[12] = {};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a)
        rec[3 + 3 * k + a] = static_cast<float>(m.vertices[t[static_cast<std::size_t>(k)]][a]);
    out.write(reinterpret_cast<const char*>(rec), sizeof rec);
    const std::uint16_t attr = 0;
    out.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

void write_ascii_stl(const std::string& path, const TriangleMesh& m) {
  std::ofstream out(path);
  out << "solid cube\n";
  for (const auto& t : m.triangles) {
    out << "  facet normal 0 0 0\n    outer loop\n";
    for (auto i : t)
      out << "      vertex " << m.vertices[i].x() << " " << m.vertices[i].y() << " "
          << m.vertices[i].z() << "\n";
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid cube\n";
}

std::string temp(const std::string& name) {
  return (std::filesystem::path(::testing::TempDir()) / name).string();
}

TEST(TriangleMesh, CubeInsideTestThroughEdgesAndVertices) {
  const MeshShape cube(unit_cube());
  // Rays along +x from these points run exactly through the faces' diagonals, edges and
  // vertices of the triangulation; each must count the surface once from inside and an even
  // number of times (winding 0) from outside.
  int checked = 0;
  for (double y : {0.0, 0.25, 0.5, 0.75, 1.0})
    for (double z : {0.0, 0.25, 0.5, 0.75, 1.0})
      for (double x : {-1.0, 0.5, 2.0}) {
        const bool on_boundary = y == 0.0 || y == 1.0 || z == 0.0 || z == 1.0;
        const int w = cube.winding_number(V(x, y, z));
        if (x != 0.5) {
          EXPECT_EQ(w, 0) << x << " " << y << " " << z;
        } else if (!on_boundary) {
          EXPECT_EQ(w, 1) << x << " " << y << " " << z;
        }
        ++checked;
      }
  EXPECT_EQ(checked, 75);
  EXPECT_NEAR(cube.distance(V(0.5, 0.5, 0.5)), -0.5, 1e-15);
  EXPECT_NEAR(cube.distance(V(2, 0.5, 0.5)), 1.0, 1e-15);
  EXPECT_NEAR(cube.distance(V(2, 2, 0.5)), std::sqrt(2.0), 1e-15);
  const MassProperties mp = mass_properties(unit_cube());
  std::printf("unit cube: volume %.15g (1), I_xx %.15g (1/6), centroid (%g, %g, %g)\n", mp.volume,
              mp.inertia(0, 0), mp.centroid.x(), mp.centroid.y(), mp.centroid.z());
  EXPECT_NEAR(mp.volume, 1.0, 1e-14);
  EXPECT_NEAR(mp.inertia(0, 0), 1.0 / 6, 1e-14);
  EXPECT_NEAR(mp.inertia(0, 1), 0.0, 1e-14);
  EXPECT_NEAR((mp.centroid - V(0.5, 0.5, 0.5)).norm(), 0.0, 1e-14);
}

TEST(TriangleMesh, SphereMeshInsideTestMatchesItsFacesAndEitherOrientation) {
  const TriangleMesh sphere = icosphere(3, 1.0);
  TriangleMesh inward = sphere;
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  const MeshShape out(sphere), in(inward);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  int wrong = 0, tested = 0;
  for (int k = 0; k < 20000; ++k) {
    const V p(u(rng), u(rng), u(rng));
    // The polyhedron is convex: inside iff behind every face's plane.
    double worst = -1e300;
    for (const auto& t : sphere.triangles) {
      const V &a = sphere.vertices[t[0]], &b = sphere.vertices[t[1]], &c = sphere.vertices[t[2]];
      worst = std::max(worst, (b - a).cross(c - a).normalized().dot(p - a));
    }
    if (std::abs(worst) < 1e-12) continue;
    ++tested;
    const bool inside = worst < 0;
    wrong += (out.winding_number(p) == 1) != inside;
    wrong += (in.winding_number(p) == -1) != inside;
    wrong += out.contains(p) != inside;
  }
  std::printf("icosphere (1280 triangles): %d of %d points misclassified\n", wrong, tested);
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(tested, 19000);
}

TEST(TriangleMesh, TorusInsideTestMatchesTheTorus) {
  const double R = 1, r = 0.4;
  const MeshShape shape(torus(R, r, 96, 48));
  // The mesh lies within the chord sagitta of the torus: points farther than that from the
  // torus surface must be classified as the torus classifies them.
  const double sagitta =
      (R + r) * (1 - std::cos(std::numbers::pi / 96)) + r * (1 - std::cos(std::numbers::pi / 48));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  int wrong = 0, tested = 0;
  for (int k = 0; k < 20000; ++k) {
    const V p(u(rng), u(rng), 0.5 * u(rng));
    const double d = std::hypot(std::hypot(p.x(), p.y()) - R, p.z()) - r;
    if (std::abs(d) < 2 * sagitta) continue;
    ++tested;
    wrong += shape.contains(p) != (d < 0);
  }
  std::printf("torus (9216 triangles): %d of %d points misclassified (margin %.2e)\n", wrong,
              tested, 2 * sagitta);
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(tested, 15000);
}

// A body filled from a mesh on the lattice (20 particles across) has the mesh's volume,
// centroid and inertia within 1%.
void expect_fill_matches_mesh(const TriangleMesh& m, double dx, const char* name) {
  const MeshShape shape(m);
  const MassProperties exact = mass_properties(m);
  LatticeSpec spec;
  spec.dim = 3;
  spec.dx = dx;
  double n = 0;
  V sum = V::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for_each_lattice_point(shape, spec, shape.bounds().inflated(dx), [&](const Point3& p) {
    n += 1;
    sum += p;
    second += p * p.transpose();
  });
  const double dv = dx * dx * dx, volume = n * dv;
  const V c = sum / n;
  // Inertia about the centroid: I = tr(S) 1 - S, S = sum (p - c)(p - c)^T dV.
  const Eigen::Matrix3d S = (second / n - c * c.transpose()) * volume;
  const Eigen::Matrix3d I = S.trace() * Eigen::Matrix3d::Identity() - S;
  const double ev = volume / exact.volume - 1;
  const double ei = (I - exact.inertia).norm() / exact.inertia.norm();
  const double ec = (c - exact.centroid).norm() / std::cbrt(exact.volume);
  std::printf("%s: %.0f particles, volume error %+.3f%%, inertia error %.3f%%, centroid %.2e\n",
              name, n, 100 * ev, 100 * ei, ec);
  EXPECT_LT(std::abs(ev), 0.01) << name;
  EXPECT_LT(ei, 0.01) << name;
  EXPECT_LT(ec, 0.01) << name;
}

TEST(TriangleMesh, FilledSphereAndTorusKeepTheMeshMassProperties) {
  TriangleMesh s = icosphere(4, 1.0);
  for (auto& v : s.vertices) v += V(0.031, 0.017, -0.043);
  expect_fill_matches_mesh(s, 0.1, "icosphere");
  // Shifted off the lattice's symmetry so that the fill is not aligned by construction.
  TriangleMesh t = torus(1.0, 0.5, 96, 48);
  for (auto& v : t.vertices) v += V(0.013, -0.021, 0.007);
  expect_fill_matches_mesh(t, 0.05, "torus");
}

TEST(TriangleMesh, BinaryAndAsciiStlReadWeldedAndClosed) {
  const TriangleMesh cube = unit_cube();
  // A binary file whose header starts with "solid", as some exporters write.
  write_binary_stl(temp("cube_binary.stl"), cube, "solid exported as binary");
  write_ascii_stl(temp("cube_ascii.stl"), cube);
  for (const char* name : {"cube_binary.stl", "cube_ascii.stl"}) {
    v1::TriangleMesh p;
    read_stl(temp(name), 1000, p);
    EXPECT_EQ(p.vertices_size(), 24) << name;  // 8 welded vertices
    EXPECT_EQ(p.triangles_size(), 36) << name;
    const TriangleMesh m = mesh_from_proto(p);
    EXPECT_TRUE(check_topology(m).closed_and_oriented()) << name;
    EXPECT_NEAR(mass_properties(m).volume, 1.0, 1e-12) << name;
  }
  // Too many triangles: refused after the header.
  v1::TriangleMesh p;
  try {
    read_stl(temp("cube_binary.stl"), 11, p);
    ADD_FAILURE() << "expected a refusal";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("12 triangles; the limit is 11"), std::string::npos)
        << e.what();
  }
  // Truncated: the header announces more than the file holds.
  {
    std::ifstream in(temp("cube_binary.stl"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(temp("cube_cut.stl"), std::ios::binary) << bytes.substr(0, bytes.size() - 30);
  }
  try {
    read_stl(temp("cube_cut.stl"), 1000, p);
    ADD_FAILURE() << "expected a refusal";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cube_cut.stl"), std::string::npos) << e.what();
  }
}

TEST(TriangleMesh, TopologyNamesHolesAndFlippedTriangles) {
  TriangleMesh holed = unit_cube();
  holed.triangles.pop_back();
  EXPECT_EQ(check_topology(holed).open_edges, 3u);
  TriangleMesh flipped = unit_cube();
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_EQ(check_topology(flipped).flipped_edges, 3u);
  EXPECT_TRUE(check_topology(torus(1, 0.3, 12, 8)).closed_and_oriented());
}

// A wall read from an STL file in millimetres, through the case loader and validation.
TEST(TriangleMesh, CaseWallFromStlFileInlinesAndValidates) {
  TriangleMesh cube = unit_cube();
  for (auto& v : cube.vertices) v *= 100.0;  // 100 mm
  write_binary_stl(temp("tank_mm.stl"), cube, "tank");
  TriangleMesh holed = cube;
  holed.triangles.pop_back();
  write_binary_stl(temp("holed_mm.stl"), holed, "holed");
  const auto case_text = [](const std::string& file, const std::string& scale) {
    return "name: \"mesh\" dimension: 3 dx: 0.01\n"
           "domain { lo { x: -0.05 y: -0.05 z: -0.05 } hi { x: 0.15 y: 0.15 z: 0.15 } }\n"
           "materials { name: \"water\" density: 1000 eos { kind: TAIT sound_speed: 10 } }\n"
           "fluids { name: \"water\" material: \"water\" shape { box { lo { x: 0.02 y: 0.02 z: "
           "0.02 } hi { x: 0.08 y: 0.08 z: 0.05 } } } }\n"
           "time { end_time: 1 }\n"
           "walls { name: \"tank\" shape { shell { inner { mesh { file: \"" +
           file + "\" " + scale + " } } } } }\n";
  };
  const auto load = [&](const std::string& text) {
    const std::string path = temp("mesh_case.textproto");
    std::ofstream(path) << text;
    return load_case_file(path);
  };
  const v1::Case ok = load(case_text("tank_mm.stl", "scale: 0.001"));
  EXPECT_TRUE(ok.walls(0).shape().shell().inner().mesh().file().empty());
  EXPECT_EQ(ok.walls(0).shape().shell().inner().mesh().triangles_size(), 36);
  const auto errors = validate_case(ok);
  for (const auto& e : errors) ADD_FAILURE() << e.field << ": " << e.message;

  const auto message_of = [](const std::vector<FieldError>& errs, const std::string& field) {
    for (const auto& e : errs)
      if (e.field == field) return e.message;
    return std::string();
  };
  // The file in millimetres without a scale: a 100 m tank around a 0.2 m domain.
  const std::string units = message_of(validate_case(load(case_text("tank_mm.stl", ""))),
                                       "walls[0].shape.shell.inner.mesh");
  std::printf("without scale: %s\n", units.c_str());
  EXPECT_NE(units.find("other units"), std::string::npos) << units;
  const std::string hole =
      message_of(validate_case(load(case_text("holed_mm.stl", "scale: 0.001"))),
                 "walls[0].shape.shell.inner.mesh");
  std::printf("holed: %s\n", hole.c_str());
  EXPECT_NE(hole.find("3 edges belong to one triangle only"), std::string::npos) << hole;
  try {
    load(case_text("missing.stl", ""));
    ADD_FAILURE() << "expected a load error";
  } catch (const CaseLoadError& e) {
    EXPECT_NE(std::string(e.what()).find("walls[0].shape.shell.inner.mesh.file"), std::string::npos)
        << e.what();
  }
}

// Inline mesh fields out of range, each refused with the field named.
TEST(TriangleMesh, BadInlineMeshFieldsAreNamed) {
  const auto errors_for = [](int dim, const std::string& mesh) {
    const std::string text =
        "name: \"m\" dimension: " + std::to_string(dim) +
        " dx: 0.1\n"
        "domain { lo { x: -1 y: -1 z: -1 } hi { x: 2 y: 2 z: 2 } }\n"
        "materials { name: \"water\" density: 1000 eos { kind: TAIT sound_speed: 10 } }\n"
        "fluids { name: \"w\" material: \"water\" shape { box { lo { x: 0 y: 0 z: 0 } hi { "
        "x: 0.5 y: 0.5 z: 0.5 } } } }\n"
        "walls { name: \"part\" shape { mesh { " +
        mesh + " } } }\ntime { end_time: 1 }\n";
    std::map<std::string, std::string> out;
    for (const auto& e : validate_case(parse_case_text(text))) out[e.field] = e.message;
    return out;
  };
  // One triangle of the unit cube's corners: valid fields, but not a closed surface.
  const std::string tri = "vertices: [0, 0, 0, 1, 0, 0, 0, 1, 0] triangles: [0, 1, 2]";
  auto e = errors_for(3, tri + " scale: -1");
  EXPECT_NE(e["walls[0].shape.mesh.scale"].find("> 0"), std::string::npos);
  e = errors_for(3, "vertices: [0, 0, 0, 1, 0, 0, 0, 1, 0] triangles: [0, 1, 3]");
  EXPECT_NE(e["walls[0].shape.mesh.triangles[2]"].find("not below the 3 vertices"),
            std::string::npos);
  e = errors_for(3, "vertices: [0, 0, 0, 1, 0] triangles: [0, 1, 2]");
  EXPECT_NE(e["walls[0].shape.mesh.vertices"].find("three coordinates"), std::string::npos);
  e = errors_for(3, tri);
  EXPECT_NE(e["walls[0].shape.mesh"].find("3 edges belong to one triangle only"),
            std::string::npos);
  e = errors_for(2, tri);
  EXPECT_NE(e["walls[0].shape.mesh"].find("only in 3D"), std::string::npos);
  e = errors_for(3, "file: \"part.stl\"");
  EXPECT_NE(e["walls[0].shape.mesh.file"].find("inlined"), std::string::npos);
  for (const auto& [f, m] : e) std::printf("  %s: %s\n", f.c_str(), m.c_str());
}

// A 2D wall section from a polyline file, inlined into polygon.vertices.
TEST(GeometryFiles, PolygonFromFileInlinesAndFills) {
  std::ofstream(temp("section.xy")) << "# an L-shaped section\n0 0\n2 0\n2 1\n1 1\n1 2\n0 2\n";
  const std::string path = temp("polygon_case.textproto");
  std::ofstream(path) << "name: \"poly\" dimension: 2 dx: 0.1\n"
                         "domain { lo { x: -1 y: -1 } hi { x: 3 y: 3 } }\n"
                         "materials { name: \"water\" density: 1000 eos { kind: TAIT "
                         "sound_speed: 10 } }\n"
                         "fluids { name: \"block\" material: \"water\" shape { polygon { file: "
                         "\"section.xy\" } } }\n"
                         "time { end_time: 1 }\n";
  const v1::Case c = load_case_file(path);
  ASSERT_EQ(c.fluids(0).shape().polygon().vertices_size(), 6);
  EXPECT_TRUE(c.fluids(0).shape().polygon().file().empty());
  for (const auto& e : validate_case(c)) ADD_FAILURE() << e.field << ": " << e.message;
  const auto shape = compile_shape(c.fluids(0).shape(), 2, 0.3);
  LatticeSpec spec;
  spec.dx = 0.1;
  int n = 0;
  for_each_lattice_point(*shape, spec, shape->bounds(), [&](const Point3&) { ++n; });
  EXPECT_EQ(n, 300);  // area 3 at 100 points per unit area
}

}  // namespace
}  // namespace sph
