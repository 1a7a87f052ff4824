// Geometry from signed-distance grids (proto DistanceGrid): the interpolated inside test, the
// mass properties of a body filled from a grid against the exact shape, reading the grid from
// an HDF5 file through the case loader, and the errors that name a bad grid's field.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <random>

#include "case/distance_grid/distance_grid_shape.h"
#include "case/lattice.h"
#include "case/load.h"
#include "case/validate.h"

namespace sph {
namespace {

using V = Eigen::Vector3d;

std::string temp(const std::string& name) {
  return (std::filesystem::path(::testing::TempDir()) / name).string();
}

// The grid of `sdf` with `n` nodes along each of `dim` axes, spacing h, first node at o.
v1::DistanceGrid sample(int dim, const std::array<int, 3>& n, double h, const V& o,
                        const std::function<double(const V&)>& sdf) {
  v1::DistanceGrid g;
  for (int a = 0; a < dim; ++a) g.add_counts(static_cast<std::uint32_t>(n[a]));
  g.mutable_origin()->set_x(o.x());
  g.mutable_origin()->set_y(o.y());
  g.mutable_origin()->set_z(o.z());
  g.set_spacing(h);
  for (int k = 0; k < (dim == 3 ? n[2] : 1); ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        g.add_values(static_cast<float>(sdf(o + h * V(i, j, dim == 3 ? k : 0))));
  return g;
}

// A body filled from the grid of a sphere (3D) or disk (2D) of radius 1 at 20 particles across
// has the exact shape's volume and centroid within 1%, with the grid as fine as the lattice
// (0.1) or twice as fine, and its second moment within 1% with the finer grid. The interpolant of a
// convex distance lies above it between nodes, by at most spacing^2 / (8 R) per axis, so the grid's
// shape is slightly smaller; the lattice walk of the exact ball on the same lattice shows what is
// the lattice's own error.
TEST(DistanceGrid, FilledSphereAndDiskKeepTheExactMassProperties) {
  const V c(0.031, 0.017, -0.043);  // off the lattice's symmetry
  for (const int dim : {2, 3})
    for (const double h : {0.1, 0.05}) {
      const V centre = dim == 3 ? c : V(c.x(), c.y(), 0);
      const auto sdf = [&](const V& p) { return (p - centre).norm() - 1.0; };
      const int n_nodes = static_cast<int>(std::lround(2.6 / h)) + 1;
      const DistanceGridShape grid(
          sample(dim, {n_nodes, n_nodes, n_nodes}, h, V(-1.3, -1.3, dim == 3 ? -1.3 : 0), sdf),
          dim);
      v1::Ball b;
      b.mutable_center()->set_x(centre.x());
      b.mutable_center()->set_y(centre.y());
      b.mutable_center()->set_z(centre.z());
      b.set_radius(1.0);
      v1::Shape exact_shape;
      *exact_shape.mutable_ball() = b;
      const auto ball = compile_shape(exact_shape, dim, 0.3);
      LatticeSpec spec;
      spec.dim = dim;
      spec.dx = 0.1;
      struct Fill {
        double n = 0, second = 0;
        V sum = V::Zero();
      };
      const auto fill = [&](const Shape& shape) {
        Fill f;
        for_each_lattice_point(shape, spec, ball->bounds().inflated(0.2), [&](const Point3& p) {
          f.n += 1;
          f.sum += p;
          f.second += (p - centre).squaredNorm();  // sum |r|^2 over the plane or space
        });
        return f;
      };
      const Fill g = fill(grid), e = fill(*ball);
      const double dv = std::pow(0.1, dim), pi = std::numbers::pi;
      // Disk: area pi, polar moment pi / 2. Sphere: 4 pi / 3, and sum |r|^2 dV = 4 pi / 5.
      const double exact_volume = dim == 3 ? 4 * pi / 3 : pi;
      const double exact_second = dim == 3 ? 4 * pi / 5 : pi / 2;
      const double ev = g.n * dv / exact_volume - 1, es = g.second * dv / exact_second - 1;
      const double ec = (g.sum / g.n - centre).norm();
      std::printf(
          "%dD, grid %.2f: %.0f particles (exact ball on the lattice: %.0f), volume error "
          "%+.3f%% (ball %+.3f%%), second moment %+.3f%% (ball %+.3f%%), centroid off "
          "by %.2e\n",
          dim, h, g.n, e.n, 100 * ev, 100 * (e.n * dv / exact_volume - 1), 100 * es,
          100 * (e.second * dv / exact_second - 1), ec);
      EXPECT_LT(std::abs(ev), 0.01);
      // A grid as coarse as the lattice shrinks the sphere's radius by about 0.2%: its moment
      // (which goes as R^5) is off by up to 1.5% there, within 1% at half the spacing.
      EXPECT_LT(std::abs(es), h < 0.075 ? 0.01 : 0.015);
      EXPECT_LT(ec, 0.01);
    }
}

// Between the nodes the interpolant keeps the sign of the exact distance wherever that is
// farther from the surface than the interpolation error bound, spacing^2 / (8 R) per axis.
TEST(DistanceGrid, InsideTestMatchesTheExactShapeAwayFromTheSurface) {
  // The smallest radius of curvature of the surface is the hole's, 1 - 0.7.
  const double h = 0.1, margin = 3 * h * h / (8 * 0.3);
  const auto sdf = [](const V& p) {  // a torus, R = 1, r = 0.7 around z, cut by nothing
    const double q = std::hypot(p.x(), p.y()) - 1.0;
    return std::hypot(q, p.z()) - 0.7;
  };
  const DistanceGridShape shape(sample(3, {41, 41, 19}, h, V(-2, -2, -0.9), sdf), 3);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  int tested = 0, wrong = 0;
  double worst = 0;
  for (int k = 0; k < 20000; ++k) {
    const V p(u(rng), u(rng), 0.5 * u(rng));
    const double d = sdf(p), g = shape.distance(p);
    // Near the surface, away from the distance's kinks at the tube's core and the axis.
    if (std::abs(d) < 0.2) worst = std::max(worst, std::abs(g - d));
    if (std::abs(d) < margin) continue;
    ++tested;
    wrong += shape.contains(p) != (d < 0);
  }
  std::printf(
      "torus on a %.1f grid: %d of %d points misclassified; largest |interpolated - "
      "exact| within 0.2 of the surface %.2e (bound 3 h^2/(8 r) = %.2e)\n",
      h, wrong, tested, worst, margin);
  EXPECT_EQ(wrong, 0);
  EXPECT_LT(worst, margin);
  EXPECT_GT(tested, 15000);
  // Outside the grid: outside the shape, and the farther, the larger.
  EXPECT_GT(shape.distance(Point3(5, 0, 0)), shape.distance(Point3(3, 0, 0)));
  EXPECT_GT(shape.distance(Point3(0, 0, 3)), 0);
}

// Writes `values` ([nz][ny][nx] or [ny][nx], C order) as dataset `name` of a new HDF5 file.
void write_h5(const std::string& path, const std::string& name, const std::vector<hsize_t>& dims,
              const std::vector<float>& values) {
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t s = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t d =
      H5Dcreate2(f, name.c_str(), H5T_IEEE_F32LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(d, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(d);
  H5Sclose(s);
  H5Fclose(f);
}

std::string case_text(int dim, const std::string& grid) {
  return "name: \"sdf\" dimension: " + std::to_string(dim) +
         " dx: 0.01\n"
         "domain { lo { x: -0.1 y: -0.1 z: -0.1 } hi { x: 0.1 y: 0.1 z: 0.1 } }\n"
         "materials { name: \"water\" density: 1000 eos { kind: TAIT sound_speed: 10 } }\n"
         "materials { name: \"steel\" phase: SOLID density: 7800 }\n"
         "fluids { name: \"water\" material: \"water\" shape { box { lo { x: -0.1 y: -0.1 z: "
         "-0.1 } hi { x: 0.1 y: 0.1 z: 0.1 } } } }\n"
         "bodies { name: \"part\" material: \"steel\" shape { distance_grid { " +
         grid + " } } }\ntime { end_time: 1 }\n";
}

v1::Case load_text(const std::string& text) {
  const std::string path = temp("sdf_case.textproto");
  std::ofstream(path) << text;
  return load_case_file(path);
}

// A body read from an HDF5 grid in millimetres: the loader inlines it with counts in x, y, z
// order, validation accepts it, and the inside lies where the file puts it (an ellipsoid with
// different semi-axes along the three axes, on a grid of different counts along them).
TEST(DistanceGrid, CaseBodyFromHdf5FileInlinesAndValidates) {
  const int nx = 13, ny = 11, nz = 9;
  const double h = 10;  // mm
  const V o(-60, -50, -40), axes(40, 30, 20);
  std::vector<float> values;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const V p = o + h * V(i, j, k);
        // Not an exact distance, but negative inside the ellipsoid and about mm-scaled.
        values.push_back(static_cast<float>(20 * (p.cwiseQuotient(axes).norm() - 1)));
      }
  write_h5(temp("part_mm.h5"), "sdf", {nz, ny, nx}, values);
  const v1::Case c =
      load_text(case_text(3,
                          "file: \"part_mm.h5\" origin { x: -60 y: -50 z: -40 } spacing: "
                          "10 scale: 0.001"));
  const auto& g = c.bodies(0).shape().distance_grid();
  EXPECT_TRUE(g.file().empty());
  ASSERT_EQ(g.counts_size(), 3);
  EXPECT_EQ(g.counts(0), 13u);
  EXPECT_EQ(g.counts(1), 11u);
  EXPECT_EQ(g.counts(2), 9u);
  for (const auto& e : validate_case(c)) ADD_FAILURE() << e.field << ": " << e.message;
  const auto shape = compile_shape(c.bodies(0).shape(), 3, 0.03);
  // Just inside and just outside each semi-axis (0.04, 0.03, 0.02 m).
  EXPECT_TRUE(shape->contains(Point3(0.037, 0, 0)));
  EXPECT_FALSE(shape->contains(Point3(0.043, 0, 0)));
  EXPECT_TRUE(shape->contains(Point3(0, 0.027, 0)));
  EXPECT_FALSE(shape->contains(Point3(0, 0.033, 0)));
  EXPECT_TRUE(shape->contains(Point3(0, 0, 0.018)));
  EXPECT_FALSE(shape->contains(Point3(0, 0, 0.022)));

  // What the loader refuses, each naming the field and the file's problem.
  const auto load_error = [&](const std::string& grid) {
    try {
      load_text(case_text(3, grid));
    } catch (const CaseLoadError& e) {
      return std::string(e.what());
    }
    return std::string("(loaded)");
  };
  const std::string field = "bodies[0].shape.distance_grid.file: ";
  std::string m = load_error("file: \"missing.h5\" spacing: 1");
  std::printf("missing: %s\n", m.c_str());
  EXPECT_EQ(m.find(field), 0u) << m;
  EXPECT_NE(m.find("no such file"), std::string::npos) << m;
  std::ofstream(temp("not_hdf5.h5")) << "x y z\n";
  m = load_error("file: \"not_hdf5.h5\" spacing: 1");
  std::printf("not HDF5: %s\n", m.c_str());
  EXPECT_NE(m.find("is not an HDF5 file"), std::string::npos) << m;
  m = load_error("file: \"part_mm.h5\" dataset: \"phi\" spacing: 1");
  std::printf("no dataset: %s\n", m.c_str());
  EXPECT_NE(m.find("has no dataset 'phi'"), std::string::npos) << m;
  write_h5(temp("flat.h5"), "sdf", {ny, nx}, std::vector<float>(nx * ny, 1.0f));
  m = load_error("file: \"flat.h5\" spacing: 1");
  std::printf("wrong rank: %s\n", m.c_str());
  EXPECT_NE(m.find("has 2 axes; a 3D case needs 3"), std::string::npos) << m;
  {
    // A dataset of 101 x 100 x 100 nodes, chunked and never written, so the file stays small.
    const hid_t f = H5Fcreate(temp("huge.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t dims[3] = {101, 100, 100}, chunk[3] = {10, 10, 10};
    const hid_t s = H5Screate_simple(3, dims, nullptr);
    const hid_t p = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(p, 3, chunk);
    const hid_t d = H5Dcreate2(f, "sdf", H5T_IEEE_F32LE, s, H5P_DEFAULT, p, H5P_DEFAULT);
    H5Dclose(d);
    H5Pclose(p);
    H5Sclose(s);
    H5Fclose(f);
  }
  m = load_error("file: \"huge.h5\" spacing: 1");
  std::printf("too large: %s\n", m.c_str());
  EXPECT_NE(m.find("the limit is 1000000 grid nodes per case"), std::string::npos) << m;
}

// Inline grid fields out of range, each refused with the field named.
TEST(DistanceGrid, BadInlineGridFieldsAreNamed) {
  const auto errors_for = [](int dim, const std::string& grid) {
    std::map<std::string, std::string> out;
    for (const auto& e : validate_case(parse_case_text(case_text(dim, grid))))
      out[e.field] = e.message;
    return out;
  };
  // 3 x 3 nodes 0.02 apart around the origin, negative in the middle only.
  const std::string ok2 =
      "counts: [3, 3] origin { x: -0.02 y: -0.02 } spacing: 0.02 values: [1, 1, 1, 1, -1, 1, 1, "
      "1, 1]";
  auto e = errors_for(2, ok2);
  for (const auto& [f, msg] : e)
    if (f.find("distance_grid") != std::string::npos) ADD_FAILURE() << f << ": " << msg;
  const std::string f = "bodies[0].shape.distance_grid";
  e = errors_for(3, ok2);
  EXPECT_NE(e[f + ".counts"].find("one count per dimension of the case (3); it has 2"),
            std::string::npos);
  e = errors_for(2, "counts: [3, 1] spacing: 0.02 values: [1, -1, 1]");
  EXPECT_NE(e[f + ".counts[1]"].find(">= 2"), std::string::npos);
  e = errors_for(2, "counts: [3, 3] spacing: 0.02 values: [1, 1, 1, 1, -1, 1, 1, 1]");
  EXPECT_NE(e[f + ".values"].find("one value per node, 9 by counts; it has 8"), std::string::npos);
  e = errors_for(2,
                 "counts: [3, 3] origin { x: -0.02 y: -0.02 } spacing: 0.02 values: [1, 1, 1, "
                 "1, nan, 1, 1, 1, 1]");
  EXPECT_NE(e[f + ".values[4]"].find("finite"), std::string::npos);
  e = errors_for(2,
                 "counts: [3, 3] origin { x: -0.02 y: -0.02 } spacing: 0.02 values: [1, 1, 1, "
                 "1, 1, 1, 1, 1, 1]");
  EXPECT_NE(e[f + ".values"].find("nowhere negative"), std::string::npos) << e[f + ".values"];
  e = errors_for(2,
                 "counts: [3, 3] origin { x: -0.02 y: -0.02 } spacing: 0.02 values: [1, 1, 1, "
                 "-1, -1, 1, 1, 1, 1]");
  EXPECT_NE(e[f + ".values"].find("1 nodes on the grid's boundary are <= 0"), std::string::npos)
      << e[f + ".values"];
  e = errors_for(2, "counts: [3, 3] spacing: 0 values: [1, 1, 1, 1, -1, 1, 1, 1, 1]");
  EXPECT_NE(e[f + ".spacing"].find("> 0"), std::string::npos) << e[f + ".spacing"];
  e = errors_for(2, ok2 + " scale: -2");
  EXPECT_NE(e[f + ".scale"].find("> 0"), std::string::npos) << e[f + ".scale"];
  e = errors_for(2,
                 "counts: [3, 3] origin { x: 5 y: 5 } spacing: 0.02 values: [1, 1, 1, 1, -1, "
                 "1, 1, 1, 1]");
  EXPECT_NE(e[f].find("outside the domain"), std::string::npos) << e[f];
  e = errors_for(2, "file: \"part.h5\" spacing: 1");
  EXPECT_NE(e[f + ".file"].find("inlined"), std::string::npos) << e[f + ".file"];
  for (const auto& [field, msg] : e) std::printf("  %s: %s\n", field.c_str(), msg.c_str());
}

}  // namespace
}  // namespace sph
