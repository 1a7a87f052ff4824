// The total Lagrangian SPH operators (solver/elastic/total_lagrangian.h) on lattice blocks,
// with the solver's own particle store, halo, neighbour list and kernels: the deformation
// gradient and its rate are exact for linear fields on every particle, interior and boundary
// alike; the internal forces of a uniformly deformed block sum to zero and vanish in its
// interior; a stretched bar pulls its ends inwards with the force P A across any section.
// Then the unit that runs them (solver/elastic/elastic_solid.h) on the same blocks: its
// accelerations, time-step bound, gravity, constraints and guards; and its hourglass control
// (solver/elastic/hourglass_control.h): zero for affine deformations and rotations, momentum
// and angular momentum conserved, a checkerboard mode held at the frequency it predicts.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "case/materials.h"
#include "solver/core/anisotropic_kernel.h"
#include "solver/core/kernel.h"
#include "solver/core/neighbor_list.h"
#include "solver/core/pair_kernel.h"
#include "solver/elastic/elastic_law.h"
#include "solver/elastic/elastic_solid.h"
#include "solver/elastic/hourglass_control.h"
#include "solver/elastic/total_lagrangian.h"
#include "solver/io/hdf5.h"
#include "solver/io/result_file.h"
#include "solver/parallel/halo.h"

namespace sph {
namespace {

constexpr double kDx = 0.002;
constexpr double kRho0 = 1000.0;

// A block of n[0] x n[1] (x n[2]) lattice particles of body 0, reference positions
// X = (i + 1/2) dx, placed at x = map(X) with velocity vel(x); next to it along +x a block of
// body 1 and below it a wall layer, both at rest, whose reference positions and (for the
// walls) body index would make them reference neighbours if the operators did not tell bodies
// and kinds apart; above it a fluid layer. One rank, no periodic axes.
template <int D, class K>
struct Block {
  using Map = std::function<Vec<D>(const Vec<D>&)>;
  Block(const std::array<int, D>& n, const Map& map, const Map& vel, double h = 1.3 * kDx)
      : kernel(h),
        rc(kernel.support_radius()),
        grid(Vec<D>::Constant(-12 * kDx), hi(n), rc, std::array<bool, D>{}),
        halo(grid, comm),
        X(s.template add<Vec<D>>("elastic_reference_position", "test", true)),
        body(s.template add<std::uint16_t>("elastic_body", "test", true)),
        PB(s.template add<Mat<D>>("elastic_stress_b", "test", false)) {
    std::vector<std::int64_t> counts(static_cast<std::size_t>(grid.total()), 1);
    halo.set_decomposition(Decomposition<D>(grid, 1, counts));
    for (int a = 0; a < D; ++a) extent[a] = n[static_cast<std::size_t>(a)] * kDx;
    std::vector<Vec<D>> pos, ref;
    std::vector<Kind> kinds;
    std::vector<std::uint16_t> bodies;
    auto add = [&](const Vec<D>& r, const Vec<D>& x, Kind k, std::uint16_t b) {
      ref.push_back(r);
      pos.push_back(x);
      kinds.push_back(k);
      bodies.push_back(b);
    };
    std::array<int, 3> lo3{-3, -3, D == 3 ? -3 : 0}, hi3{n[0] + 8, n[1] + 3, D == 3 ? n[2] + 3 : 1};
    for (int k = lo3[2]; k < hi3[2]; ++k)
      for (int j = lo3[1]; j < hi3[1]; ++j)
        for (int i = lo3[0]; i < hi3[0]; ++i) {
          const int idx[3] = {i, j, k};
          Vec<D> r;
          bool inside = true;
          for (int a = 0; a < D; ++a) {
            r[a] = (idx[a] + 0.5) * kDx;
            inside = inside && idx[a] >= 0 && idx[a] < n[static_cast<std::size_t>(a)];
          }
          if (inside) {
            add(r, map(r), Kind::kElastic, 0);
          } else if (j < 0 && i < n[0]) {
            add(r, r, Kind::kWall, 0);
          } else if (i >= n[0] && j >= 0 && j < n[1]) {
            add(r, r, Kind::kElastic, 1);
          } else if (j >= n[1]) {
            add(r, r, Kind::kFluid, 0);
          }
        }
    s.resize(pos.size(), pos.size());
    for (std::size_t p = 0; p < pos.size(); ++p) {
      s.x[p] = pos[p];
      s.v[p] = kinds[p] == Kind::kElastic && bodies[p] == 0 ? vel(pos[p]) : Vec<D>::Zero();
      s.kind[p] = kinds[p];
      s.id[p] = static_cast<ParticleId>(p);
      s.m[p] = kRho0 * std::pow(kDx, D);
      s.material[p] = 0;
      X[p] = ref[p];
      body[p] = bodies[p];
    }
    halo.migrate(s);
    halo.build_ghosts(s);
    nl.build(s, grid, halo.ghost_box(), rc);
    refs.build(s, nl, X.data(), body.data(), inv_rho0.data(), kernel);
  }
  static Vec<D> hi(const std::array<int, D>& n) {
    Vec<D> v;
    for (int a = 0; a < D; ++a) v[a] = (n[static_cast<std::size_t>(a)] + 14) * kDx;
    return v;
  }
  bool of_block(std::size_t i) const { return s.kind[i] == Kind::kElastic && body[i] == 0; }
  // Distance of the reference position from the block's surface.
  double depth(std::size_t i) const {
    double d = 1e300;
    for (int a = 0; a < D; ++a) d = std::min({d, X[i][a], extent[a] - X[i][a]});
    return d;
  }

  K kernel;
  double rc;
  CellGrid<D> grid;
  Comm comm{MPI_COMM_WORLD};
  Halo<D> halo;
  ParticleStore<D> s;
  Column<Vec<D>>& X;
  Column<std::uint16_t>& body;
  Column<Mat<D>>& PB;
  NeighborList<D> nl;
  ReferenceNeighbors<D> refs;
  std::vector<double> inv_rho0{1.0 / kRho0};
  Vec<D> extent;
};

template <int D>
Mat<D> deformation() {
  Mat<D> A;
  if constexpr (D == 2)
    A << 1.1, 0.2, -0.05, 0.95;
  else
    A << 1.1, 0.2, 0.0, -0.05, 0.95, 0.1, 0.03, -0.08, 1.04;
  return A;
}

template <int D>
Mat<D> velocity_gradient() {
  Mat<D> L;
  if constexpr (D == 2)
    L << 0.3, -1.2, 0.7, -0.4;
  else
    L << 0.3, -1.2, 0.5, 0.7, -0.4, 0.2, -0.6, 0.1, 0.9;
  return L;
}

// x = A X + c and v = L x + w: F = A and dF/dt = L A on every particle of the block.
template <int D, class K>
void linear_fields_are_exact(const char* kernel_name, const std::array<int, D>& n) {
  const Mat<D> A = deformation<D>(), L = velocity_gradient<D>();
  const Vec<D> c = Vec<D>::Constant(0.3 * kDx), w = Vec<D>::Constant(-0.02);
  Block<D, K> b(
      n, [&](const Vec<D>& X) -> Vec<D> { return A * X + c; },
      [&](const Vec<D>& x) -> Vec<D> { return L * x + w; });
  double err_f[2] = {0, 0}, err_df[2] = {0, 0};
  int count[2] = {0, 0};
  std::size_t fewest = 1000, most = 0;
  double worst_conditioning = 1.0;
  for (std::size_t i = 0; i < b.s.owned(); ++i) {
    if (!b.of_block(i)) continue;
    const ReferenceSums<D> sums =
        reference_sums<D>(b.refs, i, b.X.data(), b.s.x.data(), b.s.v.data());
    const Mat<D> B = sums.moment.inverse();
    const Mat<D> F = sums.position * B, dF = sums.velocity * B;
    const int boundary = b.depth(i) < b.rc ? 1 : 0;
    ++count[boundary];
    err_f[boundary] = std::max(err_f[boundary], (F - A).cwiseAbs().maxCoeff());
    err_df[boundary] = std::max(err_df[boundary], (dF - L * A).cwiseAbs().maxCoeff());
    fewest = std::min(fewest, b.refs.size(i));
    most = std::max(most, b.refs.size(i));
    worst_conditioning = std::min(worst_conditioning, moment_conditioning<D>(sums.moment));
  }
  std::printf(
      "%dD %s, %d interior and %d boundary particles (%zu to %zu reference neighbours, "
      "conditioning >= %.3f): max |F - A| interior %.2e boundary %.2e; max |dF/dt - L A| "
      "interior %.2e boundary %.2e\n",
      D, kernel_name, count[0], count[1], fewest, most, worst_conditioning, err_f[0], err_f[1],
      err_df[0], err_df[1]);
  EXPECT_GT(count[0], 0);
  EXPECT_GT(count[1], 0);
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT(err_f[k], 1e-12);
    EXPECT_LT(err_df[k], 1e-12);
  }
}

TEST(TotalLagrangian, LinearDeformationGivesExactDeformationGradient2D) {
  linear_fields_are_exact<2, WendlandC2<2>>("Wendland C2", {12, 9});
  linear_fields_are_exact<2, QuinticSpline<2>>("quintic", {12, 9});
}

TEST(TotalLagrangian, LinearDeformationGivesExactDeformationGradient3D) {
  linear_fields_are_exact<3, WendlandC2<3>>("Wendland C2", {9, 8, 7});
}

// P B of every particle of the block under the uniform deformation A, ghosts refreshed as the
// unit does; then the internal force of each particle.
template <int D, class K>
std::vector<Vec<D>> internal_forces(Block<D, K>& b, const ElasticConstants& c, const Mat<D>& A) {
  const Mat<D> P = first_piola<D>(c, A, Mat<D>::Zero());
  for (std::size_t i = 0; i < b.s.owned(); ++i) {
    b.PB[i] = Mat<D>::Zero();
    if (!b.of_block(i)) continue;
    const ReferenceSums<D> sums =
        reference_sums<D>(b.refs, i, b.X.data(), b.s.x.data(), b.s.v.data());
    b.PB[i] = P * sums.moment.inverse();
  }
  b.halo.update(b.s, {&b.PB});
  std::vector<Vec<D>> f(b.s.owned(), Vec<D>::Zero());
  for (std::size_t i = 0; i < b.s.owned(); ++i)
    if (b.of_block(i)) f[i] = internal_force<D>(b.refs, i, b.PB.data(), b.s.m[i] / kRho0);
  return f;
}

// Internal forces of a uniformly deformed block: they sum to zero (each pair's terms are
// opposite), and in the deep interior (two supports from the surface: every neighbour has a
// full support, so the same B) the corrected gradients of the lattice cancel. Their virial is
// the stress times the volume, sum_a f_a (x) X_a = -P sum_a V0_a, exactly: symmetrised over the
// pairs it is -1/2 sum_a V0_a P B_a M_a^T - (the same over b), and M_a is symmetric with
// B_a = M_a^-1.
template <int D>
void uniform_deformation_conserves_momentum(const std::array<int, D>& n) {
  const Mat<D> A = deformation<D>();
  Block<D, WendlandC2<D>> b(
      n, [&](const Vec<D>& X) -> Vec<D> { return A * X; },
      [](const Vec<D>&) -> Vec<D> { return Vec<D>::Zero(); });
  const ElasticConstants c =
      ElasticConstants::from(2.0e6, 0.3975, kRho0, ElasticLawKind::kSaintVenantKirchhoff);
  const std::vector<Vec<D>> f = internal_forces(b, c, A);
  Vec<D> total = Vec<D>::Zero();
  Mat<D> virial = Mat<D>::Zero();
  double magnitude = 0, largest = 0, interior = 0, volume = 0;
  int deep = 0;
  for (std::size_t i = 0; i < b.s.owned(); ++i) {
    if (!b.of_block(i)) continue;
    total += f[i];
    virial += f[i] * b.X[i].transpose();
    volume += b.s.m[i] / kRho0;
    magnitude += f[i].norm();
    largest = std::max(largest, f[i].norm());
    if (b.depth(i) >= 2.0 * b.rc) {
      ++deep;
      interior = std::max(interior, f[i].norm());
    }
  }
  const Mat<D> P = first_piola<D>(c, A, Mat<D>::Zero());
  const double err_virial = (virial + volume * P).norm() / (volume * P.norm());
  std::printf(
      "%dD uniform deformation: |sum f| / sum |f| = %.2e; %d deep interior particles, "
      "max |f| there / max |f| = %.2e; virial + P V relative %.2e\n",
      D, total.norm() / magnitude, deep, interior / largest, err_virial);
  EXPECT_GT(deep, 0);
  EXPECT_LT(total.norm(), 1e-13 * magnitude);
  EXPECT_LT(interior, 1e-12 * largest);
  EXPECT_LT(err_virial, 1e-12);
}

TEST(TotalLagrangian, UniformDeformationConservesMomentum2D) {
  uniform_deformation_conserves_momentum<2>({16, 14});
}

TEST(TotalLagrangian, UniformDeformationConservesMomentum3D) {
  uniform_deformation_conserves_momentum<3>({13, 12, 12});
}

// ASPH (solver/core/anisotropic_kernel.h; ReferenceNeighbors::build_anisotropic): a plate
// lattice of ratio r (r dx along the plate, dx through its thickness: r = 4 in 2D, 2 in 3D),
// each particle with the plate's kernel map (h through the thickness, r h along the plate),
// searched with the longest semi-axis as the unit's run does. F and
// dF/dt exact for linear fields at every particle, surfaces and corners included; under a
// uniform deformation the internal forces with P B^T (P-II eq. 32; B is not symmetric near the
// surfaces here) sum to zero and vanish in the interior.
template <int D>
void anisotropic_plate(double r, int n_plane, int n_thick) {
  const double h = 1.3 * kDx;
  const WendlandC2<D> iso(h);
  const double rc = r * iso.support_radius();
  // The thickness along the last axis, n_plane particles r dx apart along the others.
  Vec<D> hi, spacing, normal = Vec<D>::Zero();
  normal[D - 1] = 1;
  for (int a = 0; a < D; ++a) {
    spacing[a] = a == D - 1 ? kDx : r * kDx;
    hi[a] = (a == D - 1 ? n_thick : n_plane) * spacing[a];
  }
  CellGrid<D> grid(Vec<D>::Constant(-0.01), hi + Vec<D>::Constant(0.01), rc, std::array<bool, D>{});
  Comm comm{MPI_COMM_WORLD};
  Halo<D> halo(grid, comm);
  std::vector<std::int64_t> counts(static_cast<std::size_t>(grid.total()), 1);
  halo.set_decomposition(Decomposition<D>(grid, 1, counts));
  ParticleStore<D> s;
  auto& X = s.template add<Vec<D>>("elastic_reference_position", "test", true);
  auto& body = s.template add<std::uint16_t>("elastic_body", "test", true);
  auto& G = s.template add<Mat<D>>("elastic_kernel_map", "test", true);
  auto& PB = s.template add<Mat<D>>("elastic_stress_b", "test", false);
  const Mat<D> A = deformation<D>(), L = velocity_gradient<D>();
  const Mat<D> Gp = plate_anisotropy_map<D>(r * h, h, normal);
  const int nz = D == 3 ? n_thick : 1, ny = D == 3 ? n_plane : n_thick;
  const int count = n_plane * ny * nz;
  s.resize(static_cast<std::size_t>(count), static_cast<std::size_t>(count));
  std::size_t p = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < n_plane; ++i, ++p) {
        const int idx[3] = {i, j, k};
        for (int a = 0; a < D; ++a) X[p][a] = (idx[a] + 0.5) * spacing[a];
        s.x[p] = A * X[p] + Vec<D>::Constant(1e-4);
        s.v[p] = L * s.x[p];
        s.kind[p] = Kind::kElastic;
        s.id[p] = static_cast<ParticleId>(p);
        s.m[p] = kRho0 * spacing.prod();
        s.material[p] = 0;
        body[p] = 0;
        G[p] = Gp;
      }
  halo.migrate(s);
  halo.build_ghosts(s);
  NeighborList<D> nl;
  nl.build(s, grid, halo.ghost_box(), rc);
  ReferenceNeighbors<D> refs;
  const std::vector<double> inv_rho0{1.0 / kRho0};
  refs.build_anisotropic(s, nl, X.data(), body.data(), inv_rho0.data(), G.data(),
                         AnisotropicKernel<D, WendlandC2<D>>());
  const ElasticConstants c =
      ElasticConstants::from(2.0e6, 0.3975, kRho0, ElasticLawKind::kSaintVenantKirchhoff);
  const Mat<D> P = first_piola<D>(c, A, Mat<D>::Zero());
  double err_f = 0, err_df = 0, asym = 0;
  std::size_t fewest = 1000, most = 0;
  for (std::size_t i = 0; i < s.owned(); ++i) {
    const ReferenceSums<D> sums = reference_sums<D>(refs, i, X.data(), s.x.data(), s.v.data());
    const Mat<D> B = sums.moment.inverse();
    err_f = std::max(err_f, (sums.position * B - A).cwiseAbs().maxCoeff());
    err_df = std::max(err_df, (sums.velocity * B - L * A).cwiseAbs().maxCoeff());
    asym = std::max(asym, (B - B.transpose()).cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff());
    fewest = std::min(fewest, refs.size(i));
    most = std::max(most, refs.size(i));
    PB[i] = P * B.transpose();
  }
  halo.update(s, {&PB});
  Vec<D> total = Vec<D>::Zero(), scale = Vec<D>::Zero();
  double interior = 0;
  int deep_count = 0;
  for (std::size_t i = 0; i < s.owned(); ++i) {
    const Vec<D> f = internal_force<D>(refs, i, PB.data(), s.m[i] / kRho0);
    total += f;
    scale = scale.cwiseMax(f.cwiseAbs());
    // Its support and its neighbours' complete: two supports from every face.
    bool deep = true;
    for (int a = 0; a < D; ++a) {
      const double e = a == D - 1 ? 2 * 2 * h : 2 * rc;
      deep = deep && X[i][a] > e && X[i][a] < hi[a] - e;
    }
    if (deep) interior = std::max(interior, f.norm()), ++deep_count;
  }
  const double force_scale = scale.norm();
  std::printf(
      "%dD ASPH plate r = %g, %d particles (%zu to %zu reference neighbours; B asymmetric up to "
      "%.2g): max |F - A| %.2e, max |dF/dt - L A| %.2e; internal forces under P B^T sum to %.2e "
      "of their largest, %d interior ones %.2e\n",
      D, r, count, fewest, most, asym, err_f, err_df, total.norm() / force_scale, deep_count,
      interior / force_scale);
  EXPECT_LT(err_f, 1e-12);
  EXPECT_LT(err_df, 1e-12);
  EXPECT_LT(total.norm(), 1e-12 * force_scale);
  EXPECT_GT(deep_count, 0);
  EXPECT_LT(interior, 1e-10 * force_scale);
}

TEST(TotalLagrangian, AnisotropicPlateLinearFieldsAndUniformStress2D) {
  anisotropic_plate<2>(4, 24, 16);
}

TEST(TotalLagrangian, AnisotropicPlateLinearFieldsAndUniformStress3D) {
  anisotropic_plate<3>(2, 12, 12);
}

// A bar stretched along x by 1% (uniaxial strain, P_xx > 0): its end particles accelerate
// inwards, and the forces on the particles of the half beyond a section, which the other half
// exerts across it, sum to -P_xx times the section's area. To rounding: where the bar is the
// same along x (more than r_c from its ends), a pair at offset d crosses the section at
// d_x / dx positions, so the pairs across it sum to (1/dx) sum over one column of
// V0_a P B_a sum_b V0_b (X_a - X_b)_x grad0 W_ab = -(1/dx) sum V0_a P B_a M_a e_x = -P e_x A
// (M_a is symmetric and B_a its inverse), and likewise for the B_b half.
template <int D>
void stretched_bar_contracts(const std::array<int, D>& n) {
  Mat<D> A = Mat<D>::Identity();
  A(0, 0) = 1.01;
  Block<D, WendlandC2<D>> b(
      n, [&](const Vec<D>& X) -> Vec<D> { return A * X; },
      [](const Vec<D>&) -> Vec<D> { return Vec<D>::Zero(); });
  const ElasticConstants c =
      ElasticConstants::from(2.0e6, 0.3975, kRho0, ElasticLawKind::kSaintVenantKirchhoff);
  const Mat<D> P = first_piola<D>(c, A, Mat<D>::Zero());
  const std::vector<Vec<D>> f = internal_forces(b, c, A);
  double left_end = 1e300, right_end = -1e300;
  Vec<D> right_half = Vec<D>::Zero();
  for (std::size_t i = 0; i < b.s.owned(); ++i) {
    if (!b.of_block(i)) continue;
    const double ax = f[i][0] / b.s.m[i];
    if (b.X[i][0] < kDx) left_end = std::min(left_end, ax);
    if (b.X[i][0] > b.extent[0] - kDx) right_end = std::max(right_end, ax);
    if (b.X[i][0] > 0.5 * b.extent[0]) right_half += f[i];
  }
  double area = 1;
  for (int a = 1; a < D; ++a) area *= b.extent[a];
  const double expect = -P(0, 0) * area;
  const double err = std::abs(right_half[0] / expect - 1.0);
  std::printf(
      "%dD bar stretched 1%%: a_x at the left end >= %.4g, at the right end <= %.4g m/s^2; "
      "force across the middle section %.6g N, -P_xx A = %.6g N (error %.2e), "
      "transverse %.2e N\n",
      D, left_end, right_end, right_half[0], expect, err, right_half.tail(D - 1).norm());
  EXPECT_GT(left_end, 0.0);
  EXPECT_LT(right_end, 0.0);
  EXPECT_LT(err, 1e-12);
  EXPECT_LT(right_half.tail(D - 1).norm(), 1e-12 * std::abs(expect));
}

TEST(TotalLagrangian, StretchedBarContracts2D) {
  stretched_bar_contracts<2>({40, 6});
}

TEST(TotalLagrangian, StretchedBarContracts3D) {
  stretched_bar_contracts<3>({20, 5, 5});
}

// The elastic solid unit on a block of the tests above: a case with one SOLID material of the
// plate benchmark and the blocks' two elastic bodies, built as make_units builds it.
struct UnitCase {
  UnitCase(bool gravity, bool clamp) {
    auto* m = c.add_materials();
    m->set_name("plate");
    m->set_phase(v1::SOLID);
    m->set_density(kRho0);
    m->set_youngs_modulus(2.0e6);
    m->set_poisson_ratio(0.3975);
    auto* e = c.add_elastic_bodies();
    e->set_name("bar");
    e->set_material("plate");
    if (clamp) e->add_constraints();
    auto* beside = c.add_elastic_bodies();  // the blocks' body 1
    beside->set_name("beside");
    beside->set_material("plate");
    if (gravity) c.mutable_gravity()->mutable_acceleration()->set_y(-9.81);
    c.mutable_time()->set_cfl_factor(0.5);
    mats = resolve_materials(c);
  }
  v1::Case c;
  std::vector<MaterialParams> mats;
  std::vector<FluidConstants> fluids;
};

template <int D>
struct UnitOnBlock {
  using Solid = ElasticSolid<D, WendlandC2<D>>;
  UnitOnBlock(Block<D, WendlandC2<D>>& b, const UnitCase& uc)
      : unit(UnitBuildContext<D>{uc.c, uc.mats, uc.fluids, b.s, kDx, 1.3 * kDx, std::pow(kDx, D),
                                 b.kernel.W(0.0), uc.c.time().cfl_factor(), nullptr}),
        ctx{b.s, b.nl, pairs, b.halo, b.comm, 0.0, 0.0, 0} {
    pairs.prepare(b.s, b.nl, b.kernel);
    auto& constraint = b.s.template get<std::int32_t>("elastic_constraint");
    for (std::size_t i = 0; i < b.s.size(); ++i) constraint[i] = -1;
    for (std::size_t i = 0; i < b.s.owned(); ++i) b.s.a[i] = Vec<D>::Zero();
  }
  PairKernel<D> pairs;
  Solid unit;
  StepContext<D> ctx;
};

// A stretched bar: the unit's accelerations are the operators' internal forces over the mass,
// and its time-step bound is thesis eq. 33 with the largest of them and the stretched sound speed.
TEST(ElasticSolidUnit, AcceleratesAsTheOperatorsAndBoundsTheStep) {
  Mat<2> A = Mat<2>::Identity();
  A(0, 0) = 1.01;
  Block<2, WendlandC2<2>> b(
      {40, 6}, [&](const Vec<2>& X) -> Vec<2> { return A * X; },
      [](const Vec<2>&) -> Vec<2> { return Vec<2>::Zero(); });
  const UnitCase uc(false, false);
  UnitOnBlock<2> u(b, uc);
  EXPECT_EQ(u.unit.phases(), phase_bit(StepPhase::kForces));
  u.unit.run(StepPhase::kForces, u.ctx);
  EXPECT_EQ(u.unit.check(u.ctx), "");
  const ElasticConstants& law = u.unit.constants(0);
  const std::vector<Vec<2>> f = internal_forces(b, law, A);
  double err = 0, largest = 0;
  for (std::size_t i = 0; i < b.s.owned(); ++i) {
    if (b.s.kind[i] != Kind::kElastic) {
      EXPECT_EQ(b.s.a[i], Vec<2>::Zero());
      continue;
    }
    if (!b.of_block(i)) continue;
    largest = std::max(largest, b.s.a[i].norm());
    err = std::max(err, (b.s.a[i] - f[i] / b.s.m[i]).norm());
  }
  const double h = 1.3 * kDx;
  // The sound speed of Saint Venant-Kirchhoff grows with the Green strain: c sqrt(1 + 3 |E|).
  const double strain = (0.5 * (A.transpose() * A - Mat<2>::Identity())).norm();
  const double expect_dt =
      0.5 * 0.6 *
      std::min(std::sqrt(h / largest), h / (law.sound_speed * std::sqrt(1 + 3 * strain)));
  std::printf(
      "unit on a stretched bar: max |a - f/m| / max |a| = %.2e; dt bound %.6g s "
      "(eq. 33: %.6g s)\n",
      err / largest, u.unit.max_time_step(), expect_dt);
  EXPECT_LT(err, 1e-10 * largest);
  EXPECT_NEAR(u.unit.max_time_step(), expect_dt, 1e-13 * expect_dt);  // F = A to round-off
}

// At rest under gravity every particle falls with g (the internal forces of F = I vanish);
// clamped particles (constraint 0, no motion) get a = 0 and are put back at their reference
// position at rest; those of constraint 1 (moving at 0.2 m/s along x) get a = 0 and are put
// where the motion takes them, X + 0.2 t e_x, with its velocity.
template <int D>
void gravity_and_constraints(const std::array<int, D>& n) {
  Block<D, WendlandC2<D>> b(
      n, [](const Vec<D>& X) -> Vec<D> { return X; },
      [](const Vec<D>&) -> Vec<D> { return Vec<D>::Zero(); });
  UnitCase uc(true, true);
  uc.c.mutable_elastic_bodies(0)
      ->add_constraints()
      ->mutable_motion()
      ->mutable_velocity_x()
      ->set_constant(0.2);
  UnitOnBlock<D> u(b, uc);
  EXPECT_EQ(u.unit.phases(),
            phases(StepPhase::kAfterDrift, StepPhase::kForces, StepPhase::kConstraints));
  auto& constraint = b.s.template get<std::int32_t>("elastic_constraint");
  std::size_t held = 0, moved = 0;
  for (std::size_t i = 0; i < b.s.owned(); ++i) {
    if (!b.of_block(i)) continue;
    if (b.X[i][0] < kDx) {
      constraint[i] = 0;
      ++held;
    } else if (b.X[i][0] > b.extent[0] - kDx) {
      constraint[i] = 1;
      ++moved;
    }
  }
  u.unit.run(StepPhase::kForces, u.ctx);
  Vec<D> g = Vec<D>::Zero();
  g[1] = -9.81;
  double err = 0;
  for (std::size_t i = 0; i < b.s.owned(); ++i)
    if (b.of_block(i)) err = std::max(err, (b.s.a[i] - g).norm());
  u.unit.run(StepPhase::kConstraints, u.ctx);
  for (std::size_t i = 0; i < b.s.owned(); ++i)
    if (b.of_block(i) && constraint[i] >= 0) {
      EXPECT_EQ(b.s.a[i], Vec<D>::Zero());
      b.s.x[i] += Vec<D>::Constant(1e-4);
      b.s.v[i] = Vec<D>::Constant(0.3);
    }
  u.ctx.t = 0.5;
  u.unit.run(StepPhase::kAfterDrift, u.ctx);
  double err_moved = 0;
  for (std::size_t i = 0; i < b.s.owned(); ++i) {
    if (!b.of_block(i) || constraint[i] < 0) continue;
    Vec<D> x = b.X[i], v = Vec<D>::Zero();
    if (constraint[i] == 1) {
      x[0] += 0.2 * 0.5;
      v[0] = 0.2;
    }
    err_moved = std::max({err_moved, (b.s.x[i] - x).norm(), (b.s.v[i] - v).norm()});
    if (constraint[i] == 0) {
      EXPECT_EQ(b.s.x[i], b.X[i]);
      EXPECT_EQ(b.s.v[i], Vec<D>::Zero());
    }
  }
  std::printf(
      "%dD block at rest under gravity: max |a - g| = %.2e m/s^2; %zu clamped and %zu "
      "moving particles, max error of their x and v %.2e\n",
      D, err, held, moved, err_moved);
  std::size_t section = 1;
  for (int a = 1; a < D; ++a) section *= static_cast<std::size_t>(n[static_cast<std::size_t>(a)]);
  EXPECT_EQ(held, section);
  EXPECT_EQ(moved, section);
  EXPECT_LT(err, 1e-6 * 9.81);
  EXPECT_LT(err_moved, 1e-15);
}

TEST(ElasticSolidUnit, GravityAndConstraints2D) {
  gravity_and_constraints<2>({10, 6});
}

TEST(ElasticSolidUnit, GravityAndConstraints3D) {
  gravity_and_constraints<3>({8, 5, 4});
}

// The series of a block deformed by A and moving at w: the displacement (A - I) X of the particle
// nearest each observation point (one point on a particle, one halfway between two, which
// goes to the smaller id), the kinetic energy M |w|^2 / 2 and the strain energy V Psi(A),
// read back from the result file.
TEST(ElasticSolidUnit, SeriesOfDisplacementAndEnergies) {
  const Mat<2> A = deformation<2>();
  const Vec<2> w(0.3, -0.1);
  Block<2, WendlandC2<2>> b(
      {12, 8}, [&](const Vec<2>& X) -> Vec<2> { return A * X; },
      [&](const Vec<2>&) -> Vec<2> { return w; });
  UnitCase uc(false, false);
  auto* on = uc.c.mutable_elastic_bodies(0)->add_observation_points();
  on->set_x(5.5 * kDx);
  on->set_y(3.5 * kDx);
  auto* between = uc.c.mutable_elastic_bodies(0)->add_observation_points();
  between->set_x(3.0 * kDx);
  between->set_y(0.5 * kDx);
  UnitOnBlock<2> u(b, uc);
  u.unit.run(StepPhase::kForces, u.ctx);
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("elastic_series_" + std::to_string(::getpid())))
          .string();
  {
    ResultFile result(b.comm, dir);
    result.declare([&] { u.unit.sample(result, u.ctx); });
    result.create({});
    u.unit.sample(result, u.ctx);
    result.flush();
  }
  const h5::Handle f = h5::open_file(dir + "/result.h5", MPI_COMM_SELF, false);
  const std::vector<double> shown = h5::read_vector(f, "/series/elastic/bar/displacement");
  const std::vector<double> ke = h5::read_vector(f, "/series/elastic/bar/kinetic_energy");
  const std::vector<double> se = h5::read_vector(f, "/series/elastic/bar/strain_energy");
  ASSERT_EQ(shown.size(), 4u);
  ASSERT_EQ(ke.size(), 1u);
  ASSERT_EQ(se.size(), 1u);
  const Vec<2> expect_on = (A - Mat<2>::Identity()) * Vec<2>(5.5 * kDx, 3.5 * kDx);
  const Vec<2> expect_between = (A - Mat<2>::Identity()) * Vec<2>(2.5 * kDx, 0.5 * kDx);
  const double err_shown = std::max((Vec<2>(shown[0], shown[1]) - expect_on).norm(),
                                    (Vec<2>(shown[2], shown[3]) - expect_between).norm());
  const double n = 12 * 8, V = kDx * kDx;
  const ElasticConstants& law = u.unit.constants(0);
  const double expect_ke = 0.5 * n * kRho0 * V * w.squaredNorm();
  const double expect_se = n * V * strain_energy_density<2>(law, A);
  std::printf(
      "series: displacement error %.2e m; kinetic energy %.9g J (%.9g), strain energy "
      "%.9g J (%.9g), relative errors %.2e, %.2e\n",
      err_shown, ke[0], expect_ke, se[0], expect_se, std::abs(ke[0] / expect_ke - 1),
      std::abs(se[0] / expect_se - 1));
  EXPECT_LT(err_shown, 1e-15);
  EXPECT_LT(std::abs(ke[0] / expect_ke - 1), 1e-14);
  EXPECT_LT(std::abs(se[0] / expect_se - 1), 1e-12);
  std::filesystem::remove_all(dir);
}

// The guards: a mirrored block (det F = -1) is inverted; a single row of particles has its
// reference neighbours on a line, a singular correction matrix. Both name the body and the
// particle.
TEST(ElasticSolidUnit, GuardsNameInvertedAndTornParticles) {
  const UnitCase uc(false, false);
  {
    Block<2, WendlandC2<2>> b(
        {8, 6}, [](const Vec<2>& X) -> Vec<2> { return Vec<2>(0.02 - X[0], X[1]); },
        [](const Vec<2>&) -> Vec<2> { return Vec<2>::Zero(); });
    UnitOnBlock<2> u(b, uc);
    u.unit.run(StepPhase::kForces, u.ctx);
    const std::string why = u.unit.check(u.ctx);
    std::printf("mirrored block: %s\n", why.c_str());
    EXPECT_NE(why.find("elastic body bar: inverted particle (det F = -1"), std::string::npos);
    EXPECT_NE(why.find("at particle id"), std::string::npos);
  }
  {
    Block<2, WendlandC2<2>> b(
        {8, 1}, [](const Vec<2>& X) -> Vec<2> { return X; },
        [](const Vec<2>&) -> Vec<2> { return Vec<2>::Zero(); });
    UnitOnBlock<2> u(b, uc);
    u.unit.run(StepPhase::kForces, u.ctx);
    const std::string why = u.unit.check(u.ctx);
    std::printf("one row of particles: %s\n", why.c_str());
    EXPECT_NE(why.find("elastic body bar: singular correction matrix"), std::string::npos);
  }
}

// Hourglass control (solver/elastic/hourglass_control.h, Ganzenmueller 2015). The material of
// the tests above with alpha = 1: k = alpha E / 2 per side of a pair.
constexpr double kHourglassE = 2.0e6, kHourglassAlpha = 1.0;

template <int D>
std::vector<MaterialParams> hourglass_materials(v1::Case& c) {
  auto* m = c.add_materials();
  m->set_name("plate");
  m->set_phase(v1::SOLID);
  m->set_density(kRho0);
  m->set_youngs_modulus(kHourglassE);
  m->set_poisson_ratio(0.3975);
  m->set_hourglass_control(kHourglassAlpha);
  return resolve_materials(c);
}

// F of every particle of block body 0 (identity elsewhere), ghosts refreshed as the unit does,
// then the hourglass force on each.
template <int D, class K>
std::vector<Vec<D>> hourglass_forces(Block<D, K>& b, Column<Mat<D>>& F) {
  v1::Case c;
  const std::vector<MaterialParams> mats = hourglass_materials<D>(c);
  const HourglassControl<D> hg(c, mats, b.kernel, kDx);
  EXPECT_TRUE(hg.active());
  EXPECT_EQ(hg.stiffness(0), 0.5 * kHourglassAlpha * kHourglassE);
  for (std::size_t i = 0; i < b.s.owned(); ++i) {
    F[i] = Mat<D>::Identity();
    if (!b.of_block(i)) continue;
    const ReferenceSums<D> sums =
        reference_sums<D>(b.refs, i, b.X.data(), b.s.x.data(), b.s.v.data());
    F[i] = sums.position * sums.moment.inverse();
  }
  b.halo.update(b.s, {&F});
  std::vector<Vec<D>> f(b.s.owned(), Vec<D>::Zero());
  for (std::size_t i = 0; i < b.s.owned(); ++i)
    if (b.of_block(i))
      f[i] = hg.force(b.refs, i, b.X.data(), b.s.x.data(), F.data(), b.s.m.data(),
                      b.s.material.data(), b.inv_rho0.data(), b.kernel);
  return f;
}

// The scale of one particle's hourglass force were every pair off by its own length:
// k V0 sum_b V0_b W / |X_ab|^2 |X_ab|, bounded by k V0 S r_c with S the lattice sum.
template <int D, class K>
double hourglass_force_scale(const Block<D, K>& b) {
  return 0.5 * kHourglassAlpha * kHourglassE * std::pow(kDx, D) *
         HourglassControl<D>::lattice_sum(b.kernel, kDx) * b.rc;
}

template <int D>
Mat<D> rotation() {
  const double a = 0.5, c = std::cos(a), s = std::sin(a);
  Mat<D> R = Mat<D>::Identity();
  if constexpr (D == 2) {
    R << c, -s, s, c;
  } else {
    Mat<D> Rz, Rx;
    Rz << c, -s, 0, s, c, 0, 0, 0, 1;
    Rx << 1, 0, 0, 0, c, -s, 0, s, c;
    R = Rx * Rz;
  }
  return R;
}

// For x = A X + c, for a rigid rotation x = R X + c and for both (R A), F is exact on every
// particle, boundary ones too, so every pair lies where F predicts: no hourglass force.
template <int D>
void hourglass_force_vanishes_for_affine_maps(const std::array<int, D>& n) {
  const Vec<D> c = Vec<D>::Constant(0.3 * kDx);
  const Mat<D> maps[3] = {deformation<D>(), rotation<D>(), rotation<D>() * deformation<D>()};
  const char* names[3] = {"linear deformation", "rigid rotation", "rotated deformation"};
  for (int k = 0; k < 3; ++k) {
    const Mat<D> A = maps[k];
    Block<D, WendlandC2<D>> b(
        n, [&](const Vec<D>& X) -> Vec<D> { return A * X + c; },
        [](const Vec<D>&) -> Vec<D> { return Vec<D>::Zero(); });
    auto& F = b.s.template add<Mat<D>>("elastic_deformation_gradient", "test", false);
    const std::vector<Vec<D>> f = hourglass_forces(b, F);
    double largest = 0;
    for (std::size_t i = 0; i < b.s.owned(); ++i)
      if (b.of_block(i)) largest = std::max(largest, f[i].norm());
    const double scale = hourglass_force_scale(b);
    std::printf("%dD hourglass force under a %s: max |f| / (k V0 S r_c) = %.2e\n", D, names[k],
                largest / scale);
    EXPECT_LT(largest, 1e-12 * scale) << names[k];
  }
}

TEST(HourglassControl, VanishesForAffineDeformationAndRotation2D) {
  hourglass_force_vanishes_for_affine_maps<2>({12, 9});
}

TEST(HourglassControl, VanishesForAffineDeformationAndRotation3D) {
  hourglass_force_vanishes_for_affine_maps<3>({8, 7, 6});
}

// Every particle of a deformed block moved by a random 10% of dx: the hourglass forces sum to
// zero and so do their moments about the origin (each pair's two terms are opposite and along
// x_ab), to round-off.
template <int D>
void hourglass_force_conserves_momenta(const std::array<int, D>& n) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> jitter(-0.1 * kDx, 0.1 * kDx);
  const Mat<D> A = deformation<D>();
  Block<D, WendlandC2<D>> b(
      n,
      [&](const Vec<D>& X) -> Vec<D> {
        Vec<D> x = A * X;
        for (int a = 0; a < D; ++a) x[a] += jitter(rng);
        return x;
      },
      [](const Vec<D>&) -> Vec<D> { return Vec<D>::Zero(); });
  auto& F = b.s.template add<Mat<D>>("elastic_deformation_gradient", "test", false);
  const std::vector<Vec<D>> f = hourglass_forces(b, F);
  Vec<D> total = Vec<D>::Zero();
  Vec<3> moment = Vec<3>::Zero();
  double magnitude = 0, moment_magnitude = 0;
  for (std::size_t i = 0; i < b.s.owned(); ++i) {
    if (!b.of_block(i)) continue;
    total += f[i];
    magnitude += f[i].norm();
    Vec<3> x3 = Vec<3>::Zero(), f3 = Vec<3>::Zero();
    for (int a = 0; a < D; ++a) x3[a] = b.s.x[i][a], f3[a] = f[i][a];
    moment += x3.cross(f3);
    moment_magnitude += x3.norm() * f3.norm();
  }
  std::printf(
      "%dD block jittered by 10%% of dx: hourglass forces sum |f| = %.4g N, |sum f| / sum |f| = "
      "%.2e, |sum x x f| / sum |x| |f| = %.2e\n",
      D, magnitude, total.norm() / magnitude, moment.norm() / moment_magnitude);
  EXPECT_GT(magnitude, 1e-3 * hourglass_force_scale(b));
  EXPECT_LT(total.norm(), 1e-13 * magnitude);
  EXPECT_LT(moment.norm(), 1e-13 * moment_magnitude);
}

TEST(HourglassControl, ConservesMomentumAndAngularMomentum2D) {
  hourglass_force_conserves_momenta<2>({12, 9});
}

TEST(HourglassControl, ConservesMomentumAndAngularMomentum3D) {
  hourglass_force_conserves_momenta<3>({8, 7, 6});
}

// The checkerboard u_a = u (-1)^(i + j (+ k)) is a zero-energy mode of the scheme: in the deep
// interior F = I exactly (the neighbours' displacements are even under b -> -b, the kernel
// gradients odd), so the elastic force does not see it. The hourglass force does: with
// eps = -(u_a - u_b), 2u_a for the neighbours of the other colour, 0 for the same colour,
//   f_a = -4 k V0 sum_odd V0 W / X^2 (u_a . e) e = -(2 alpha E / D) V0 S_odd u_a
// to first order in u (the second moment of a cubic lattice shell is isotropic), S_odd the
// lattice sum over the other colour: a spring that gives the mode omega^2 = 2 alpha E S_odd /
// (D rho0).
template <int D>
double other_colour_sum(const WendlandC2<D>& kernel) {
  const double rc = kernel.support_radius();
  const int n = static_cast<int>(std::ceil(rc / kDx));
  double s = 0;
  for (int k = D == 3 ? -n : 0; k <= (D == 3 ? n : 0); ++k)
    for (int j = -n; j <= n; ++j)
      for (int i = -n; i <= n; ++i) {
        const double r2 = kDx * kDx * (i * i + j * j + k * k);
        if ((i + j + k) % 2 == 0 || !(r2 < rc * rc)) continue;
        s += std::pow(kDx, D) * kernel.W(std::sqrt(r2)) / r2;
      }
  return s;
}

template <int D>
int colour(const Vec<D>& X) {
  int sum = 0;
  for (int a = 0; a < D; ++a) sum += static_cast<int>(std::floor(X[a] / kDx));
  return sum % 2 == 0 ? 1 : -1;
}

template <int D>
void checkerboard_meets_a_spring(const std::array<int, D>& n) {
  Vec<D> u = Vec<D>::Zero();
  u[0] = 1e-5 * kDx;
  u[1] = -0.6e-5 * kDx;
  Block<D, WendlandC2<D>> b(
      n, [&](const Vec<D>& X) -> Vec<D> { return X + colour<D>(X) * u; },
      [](const Vec<D>&) -> Vec<D> { return Vec<D>::Zero(); });
  auto& F = b.s.template add<Mat<D>>("elastic_deformation_gradient", "test", false);
  const std::vector<Vec<D>> f = hourglass_forces(b, F);
  const double spring =
      2 * kHourglassAlpha * kHourglassE / D * std::pow(kDx, D) * other_colour_sum<D>(b.kernel);
  double err_F = 0, err_f = 0, boundary = -std::numeric_limits<double>::infinity();
  int deep = 0;
  for (std::size_t i = 0; i < b.s.owned(); ++i) {
    if (!b.of_block(i)) continue;
    const Vec<D> expect = -spring * colour<D>(b.X[i]) * u;
    if (b.depth(i) >= 2.0 * b.rc) {
      ++deep;
      err_F = std::max(err_F, (F[i] - Mat<D>::Identity()).cwiseAbs().maxCoeff());
      err_f = std::max(err_f, (f[i] - expect).norm() / expect.norm());
    } else {
      // Near the surface the mode is not one of zero energy; the force still opposes it.
      boundary = std::max(boundary, f[i].dot(colour<D>(b.X[i]) * u));
    }
  }
  std::printf(
      "%dD checkerboard of amplitude 1e-5 dx, %d deep particles: max |F - I| = %.2e, hourglass "
      "force vs -(2 alpha E / D) V0 S_odd u relative %.2e; largest f . u near the surface %.2e "
      "N m\n",
      D, deep, err_F, err_f, boundary);
  EXPECT_GT(deep, 0);
  EXPECT_LT(err_F, 1e-12);
  EXPECT_LT(err_f, 1e-4);
  EXPECT_LT(boundary, 0.0);
}

TEST(HourglassControl, CheckerboardModeMeetsASpring2D) {
  checkerboard_meets_a_spring<2>({16, 14});
}

TEST(HourglassControl, CheckerboardModeMeetsASpring3D) {
  checkerboard_meets_a_spring<3>({12, 12, 12});
}

// The unit on a block set moving in the checkerboard mode, v_a = v0 (-1)^(i + j) e_x, and
// advanced by kick-drift-kick with its own step bound: without hourglass control nothing holds
// the deep interior back and its checkerboard displacement grows as v0 t; with alpha = 1 it
// swings as (v0 / omega) sin(omega t), omega^2 = 2 alpha E S_odd / (D rho0), and comes back.
TEST(HourglassControl, HoldsTheCheckerboardModeOfTheUnit) {
  const double v0 = 1e-3;
  WendlandC2<2> kernel(1.3 * kDx);
  const double omega =
      std::sqrt(2 * kHourglassAlpha * kHourglassE * other_colour_sum<2>(kernel) / (2 * kRho0));
  const double period = 2 * std::numbers::pi / omega;
  struct Swing {
    double largest = 0, at_end = 0, first_return = 0;
    long steps = 0;
  };
  const auto swing = [&](bool control) {
    Block<2, WendlandC2<2>> b(
        {30, 30}, [](const Vec<2>& X) -> Vec<2> { return X; },
        [&](const Vec<2>& x) -> Vec<2> { return Vec<2>(v0 * colour<2>(x), 0.0); });
    UnitCase uc(false, false);
    if (control) uc.c.mutable_materials(0)->set_hourglass_control(kHourglassAlpha);
    uc.mats = resolve_materials(uc.c);
    UnitOnBlock<2> u(b, uc);
    Swing out;
    double t = 0, previous = 0;
    const auto amplitude = [&] {
      double sum = 0;
      int count = 0;
      for (std::size_t i = 0; i < b.s.owned(); ++i)
        if (b.of_block(i) && b.depth(i) >= 2.0 * b.rc) {
          sum += colour<2>(b.X[i]) * (b.s.x[i][0] - b.X[i][0]);
          ++count;
        }
      return sum / count;
    };
    const auto forces = [&] {
      for (std::size_t i = 0; i < b.s.owned(); ++i) b.s.a[i] = Vec<2>::Zero();
      u.unit.run(StepPhase::kForces, u.ctx);
      EXPECT_EQ(u.unit.check(u.ctx), "");
    };
    forces();
    while (t < 0.75 * period) {
      const double dt = u.unit.max_time_step();
      for (std::size_t i = 0; i < b.s.owned(); ++i)
        if (b.s.kind[i] == Kind::kElastic && b.body[i] == 0) {
          b.s.v[i] += 0.5 * dt * b.s.a[i];
          b.s.x[i] += dt * b.s.v[i];
        }
      b.halo.refresh_ghosts(b.s);
      forces();
      for (std::size_t i = 0; i < b.s.owned(); ++i)
        if (b.s.kind[i] == Kind::kElastic && b.body[i] == 0) b.s.v[i] += 0.5 * dt * b.s.a[i];
      t += dt;
      ++out.steps;
      const double now = amplitude();
      out.largest = std::max(out.largest, now);
      if (out.first_return == 0 && previous > 0 && now <= 0)
        out.first_return = t - dt * now / (now - previous);
      previous = now;
    }
    out.at_end = previous;
    return out;
  };
  const Swing free = swing(false), held = swing(true);
  std::printf(
      "checkerboard mode v0 = %g m/s, hourglass period 2 pi / omega = %.4g s: without control "
      "the deep interior drifts to %.3g m at t = 0.75 T (v0 t = %.3g m, %ld steps); with "
      "alpha = 1 it swings to %.3g m (v0 / omega = %.3g m) and back through 0 at t = %.4g s "
      "(T / 2 = %.4g s, %ld steps)\n",
      v0, period, free.at_end, v0 * 0.75 * period, free.steps, held.largest, v0 / omega,
      held.first_return, 0.5 * period, held.steps);
  EXPECT_GT(free.at_end, 0.9 * v0 * 0.75 * period);
  EXPECT_NEAR(held.largest, v0 / omega, 0.05 * v0 / omega);
  EXPECT_NEAR(held.first_return, 0.5 * period, 0.05 * period);
  EXPECT_LT(held.at_end, 0.0);
}

}  // namespace
}  // namespace sph
