#pragma once
// Surface tension as a continuum surface force (Brackbill, Kothe, Zemach 1992) in the SPH form
// of Adami, Hu, Adams 2010, "A new surface-tension formulation for multi-phase SPH using a
// reproducing divergence approximation", J. Comput. Phys. 229, 5011 (A10 below):
//
//   pass 1 (every fluid particle of a material with surface tension):
//     grad c_i = 1/V_i sum_j (V_i^2 + V_j^2) c~_ij grad W_ij,
//     c~_ij = (rho_j c_i + rho_i c_j) / (rho_i + rho_j)      (A10, the density-weighted colour)
//   with the colour c = 1 on the particle's own phase and 0 on the other. Written as
//   c~_ij - c_i = rho_i / (rho_i + rho_j) (c_j - c_i), which differs from A10 by
//   c_i sum_j (V_i^2 + V_j^2) grad W_ij, zero for a full support, so that only pairs across an
//   interface contribute and the bulk gets an exact zero instead of lattice noise. The density
//   weight gives the heavy phase of a large density ratio the whole jump of c (the light one
//   almost none), which keeps the force off the light phase (A10).
//   Each interface contributes with its own coefficient, G_i = sum_k sigma_{ik} grad c_i^{ik},
//   and the unit normal n_i = G_i / |G_i| points into the particle's own phase. A particle
//   has a normal only where |grad c_i| > 0.01 / h (the filter of Morris 2000: the normals of
//   particles far from the interface are noise); the others get n = 0;
//   halo update of n;
//   pass 2: curvature by a reproducing divergence over the neighbours with a normal. A10's
//     div n_i = d sum_j (n_i - n_j) . grad W_ij V_j / sum_j r_ij . grad W_ij V_j
//   is exact for a linear field on an isotropic neighbourhood; the neighbours with a normal
//   form a band across the interface, narrower than the kernel along it, where it reads the
//   curvature high. Its tensor form div n_i = tr(N M^-1), with N = sum_j V_j (n_j - n_i) (x)
//   grad W_ij and M = sum_j V_j (x_j - x_i) (x) grad W_ij (the moment matrix of Bonet & Lok
//   1999), is exact for a linear field on any neighbourhood and is used wherever M is well
//   conditioned;
//   -div n_i is the curvature of the level set of the colour through x_i (positive for a
//   convex drop of the particle's phase), which lies a depth d_i inside the own phase; the
//   force needs the interface's: kappa_i = kappa_level / (1 + kappa_level d_i) (a circle of
//   radius R has level sets of radius R - d). d_i comes from the own phase's share c_i of the
//   kernel support (Shepard, i itself included) through the planar profile c(d) of the
//   kernel. Without it the force-weighted curvature of a band lying on one side of the
//   interface reads high by about d / R: at density ratio 1000 the colour weight puts the
//   whole band in the heavy drop, and the static Laplace jump read +7.3% at R/dx = 20
//   (+3.7% with it; docs/surface_tension.md). Then
//     a_i += kappa_i G_i / rho_i              (the CSF force sigma kappa grad c per volume)
//   accumulated into a^{n+1}. A neighbour of the other phase enters with -n_j: the normals
//   of both phases point into their own phase, so across a fluid-fluid interface they are
//   opposite, and -n_j is A10's single normal field seen from particle i's side. Both sides
//   get kappa G of the same sign, as in A10, and the integral of the force across the
//   interface is sigma kappa: in 2D the Laplace jump p_in - p_out = sigma / R.
//
// Free surfaces (a pair whose material_b is empty: the fluid against void) use the same two
// passes with the void's colour 0 taken where the kernel support is empty
// (solver/physics/surface_tension_free_surface.h has the why and the equations).
//
// Static contact angle (Breinlinger, Polfer, Hashibon, Moseler 2013,
// J. Comput. Phys. 243): a particle with a normal whose nearest wall neighbour belongs to a wall
// with an angle theta has its normal replaced by n = -cos(theta) n_w + sin(theta) t, where n_w =
// -sum_j V_w grad W_ij over its wall neighbours (unit, pointing out of the wall) and t the unit
// tangent along the wall in the plane of n and n_w; theta is measured through the named material,
// 180 - theta through the other. The curvature of the turned normals bends the interface towards
// the angle. The magnitude |G| is kept. At a solid without an angle (a wall not named, a rigid
// body) the normal is turned the same way with theta = 90 degrees, neutral wetting, with n_w
// from every wall and rigid neighbour: the colour function counts fluid neighbours only, so
// next to a solid the unturned normal points into it and the force drives the fluid into the
// solid (a melted particle at the bottom of a grain on a hot floor was pushed into the grain).
// At a free surface the normal is left as it is and a contact-line force pulls the line to the
// angle instead (contact_line_force below; Huber et al. 2016).
//
// Deterministic and rank independent: the sums run over the neighbour list in its canonical
// order; the normals of ghosts come from their owners.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "case/materials.h"
#include "solver/core/kernel.h"
#include "solver/core/pair_access.h"
#include "solver/core/types.h"
#include "solver/physics/surface_tension_free_surface.h"
#include "solver/seam/unit.h"
#include "sph/v1/case.pb.h"

namespace sph {

template <int D>
class SurfaceTension final : public Unit<D> {
 public:
  static constexpr const char* kName = "surface_tension";
  // A particle has a normal where |grad c| h exceeds this (Morris 2000).
  static constexpr double kNormalThreshold = 0.01;
  // det M / (tr M / d)^d below which the curvature takes A10's scalar divergence instead of
  // the full tensor one (M nearly singular).
  static constexpr double kMinMomentRatio = 0.05;
  // A particle whose own phase fills less than this share of its kernel support (itself left
  // out) is not on a resolved interface: a lone particle or a cluster of a few is a drop of
  // radius about dx, whose curvature 1/dx and colour gradient 1/dx give an acceleration
  // sigma / (rho dx^2) that no time step of the flow resolves. It gets no normal and no force.
  static constexpr double kMinOwnSupport = 0.2;
  // 1 + kappa_level d below which the level set is too far from the interface to map its
  // curvature onto it (the depth correction is left out there).
  static constexpr double kMinShrink = 0.5;

  // wall_index: which wall of the case each wall particle is (null without walls).
  SurfaceTension(const v1::Case& c, const std::vector<MaterialParams>& materials,
                 ParticleStore<D>& particles, double h, double wall_volume, double cfl_factor,
                 const Column<std::uint16_t>* wall_index);

  const char* name() const override { return kName; }
  PhaseMask phases() const override { return phase_bit(StepPhase::kForces); }
  void run(StepPhase phase, StepContext<D>& ctx) override;
  double max_time_step() const override { return max_dt_; }
  void declare_output(ResultFile& result) override;
  void sample(ResultFile& result, const StepContext<D>& ctx) override;

  // sigma of materials a and b, 0 without tension.
  double sigma(std::size_t a, std::size_t b) const { return sigma_[a * nm_ + b]; }
  // sigma of material a against void (a free surface), 0 without.
  double free_surface_sigma(std::size_t a) const { return sigma_void_[a]; }

 private:
  struct ContactAngle {
    bool set = false;
    double cos_own = 0, sin_own = 0;      // theta through `through`
    double cos_other = 0, sin_other = 0;  // 180 - theta through any other material
    std::uint16_t through = kNoMaterial;
  };
  // The passes over pairs, on the pair kernel's double values or its compact table
  // (solver/core/pair_access.h).
  template <bool kCompact>
  void sweep(StepContext<D>& ctx);
  template <bool kCompact>
  void normals(StepContext<D>& ctx);
  template <bool kCompact>
  void curvature_and_force(StepContext<D>& ctx);
  template <bool kCompact>
  void free_surface_curvature(StepContext<D>& ctx, std::size_t i);
  template <bool kCompact>
  void smoothed_curvature_and_force(StepContext<D>& ctx);
  void contact_line_force(ParticleStore<D>& s, std::size_t i, const Vec<D>& mean_normal) const;
  template <class K>
  void tabulate_depth(const K& kernel);
  // The depth below a planar interface at which the own phase fills the share `colour` of
  // the kernel support (0 at 1/2, negative below).
  double planar_depth(double colour) const;

  std::size_t nm_ = 0;                 // materials
  std::vector<double> sigma_;          // nm x nm
  std::vector<char> active_;           // per material: some interface has tension
  std::vector<double> sigma_void_;     // per material: sigma against void, 0 without
  bool any_free_ = false;              // some material has a free surface
  std::vector<ContactAngle> contact_;  // per wall of the case
  std::vector<ContactAngle> solid_;    // per material: at rigid bodies made of it
  double wall_volume_ = 0, min_gradient_ = 0, self_weight_ = 0;
  std::vector<double> depth_of_colour_;  // planar_depth() at colours 0.5 + 0.5 k / (size - 1)
  double max_dt_ = std::numeric_limits<double>::infinity();
  const Column<std::uint16_t>* wall_index_ = nullptr;
  Column<Vec<D>>& normal_;     // unit normal into the own phase, 0 where none (ghosts too)
  Column<Vec<D>>& gradient_;   // G_i = sum_k sigma_ik grad c_i^ik [N/m^2], owned
  Column<double>& curvature_;  // kappa_i [1/m], owned (a snapshot field)
  Column<double>& depth_;      // d_i [m], owned: depth inside the own phase
  // With a free surface: the curvature before its average over the neighbours (ghosts too).
  Column<double>* raw_curvature_ = nullptr;
  Column<double>* gradient_norm_ = nullptr;  // |G_j| (ghosts too), the average's weight
  // With a free surface, at its particles next to a solid: the solid's colour gradient (its
  // unit normal times the contact-line delta; 0 elsewhere) and cos theta_eq, owned.
  Column<Vec<D>>* solid_gradient_ = nullptr;
  Column<double>* cos_equilibrium_ = nullptr;
};

template <int D>
SurfaceTension<D>::SurfaceTension(const v1::Case& c, const std::vector<MaterialParams>& materials,
                                  ParticleStore<D>& particles, double h, double wall_volume,
                                  double cfl_factor, const Column<std::uint16_t>* wall_index)
    : nm_(materials.size()),
      sigma_(nm_ * nm_, 0.0),
      active_(nm_, 0),
      sigma_void_(nm_, 0.0),
      contact_(static_cast<std::size_t>(c.walls_size())),
      solid_(c.surface_tension().bodies_size() > 0 ? nm_ : 0),
      wall_volume_(wall_volume),
      min_gradient_(kNormalThreshold / h),
      wall_index_(wall_index),
      normal_(particles.template add<Vec<D>>("surface_tension_normal", kName, false)),
      gradient_(particles.template add<Vec<D>>("surface_tension_gradient", kName, false)),
      curvature_(particles.template add<double>("surface_tension_curvature", kName, false)),
      depth_(particles.template add<double>("surface_tension_depth", kName, false)) {
  if (c.kernel() == v1::WENDLAND_C2)
    tabulate_depth(WendlandC2<D>(h));
  else
    tabulate_depth(QuinticSpline<D>(h));
  const auto& st = c.surface_tension();
  for (const auto& p : st.pairs()) {
    const auto a = static_cast<std::size_t>(material_index(materials, p.material_a()));
    if (p.material_b().empty()) {
      sigma_void_[a] = p.sigma();
      active_[a] = 1;
      any_free_ = true;
      max_dt_ = std::min(max_dt_,
                         cfl_factor * free_surface_capillary_step(materials[a].rho0, h, p.sigma()));
      continue;
    }
    const auto o = static_cast<std::size_t>(material_index(materials, p.material_b()));
    sigma_[a * nm_ + o] = sigma_[o * nm_ + a] = p.sigma();
    active_[a] = active_[o] = 1;
    // Capillary waves of wave number k have omega^2 = sigma k^3 / (rho_a + rho_b): the bound
    // of Brackbill 1992 with their mean density, (rho_a + rho_b) / 2, resolves the shortest,
    // k = pi / h, as A10 does.
    const double rho_mean = 0.5 * (materials[a].rho0 + materials[o].rho0);
    max_dt_ = std::min(
        max_dt_,
        cfl_factor * 0.25 * std::sqrt(rho_mean * h * h * h / (2.0 * std::numbers::pi * p.sigma())));
  }
  if (any_free_) {
    raw_curvature_ = &particles.template add<double>("surface_tension_raw_curvature", kName, false);
    gradient_norm_ = &particles.template add<double>("surface_tension_gradient_norm", kName, false);
    solid_gradient_ =
        &particles.template add<Vec<D>>("surface_tension_solid_gradient", kName, false);
    cos_equilibrium_ = &particles.template add<double>("surface_tension_cos_eq", kName, false);
  }
  const auto angle = [&](double degrees, const std::string& liquid) {
    ContactAngle ca;
    ca.set = true;
    const double theta = degrees * std::numbers::pi / 180.0;
    ca.cos_own = std::cos(theta);
    ca.sin_own = std::sin(theta);
    ca.cos_other = -ca.cos_own;  // cos(pi - theta)
    ca.sin_other = ca.sin_own;
    ca.through = static_cast<std::uint16_t>(material_index(materials, liquid));
    return ca;
  };
  for (const auto& w : st.walls())
    for (int k = 0; k < c.walls_size(); ++k)
      if (c.walls(k).name() == w.wall())
        contact_[static_cast<std::size_t>(k)] = angle(w.contact_angle(), w.material());
  for (const auto& b : st.bodies())
    solid_[static_cast<std::size_t>(material_index(materials, b.solid_material()))] =
        angle(b.contact_angle(), b.material());
}

// The share of the kernel support on the own side of a planar interface at depth d is
// c(d) = 1/2 + int_0^d w1(z) dz, w1 the kernel integrated over the plane z = const (a line in
// 2D, a disk in 3D). Tabulated once by the trapezoidal rule and inverted on a uniform grid of c.
template <int D>
template <class K>
void SurfaceTension<D>::tabulate_depth(const K& kernel) {
  self_weight_ = kernel.W(0.0);
  const double rc = kernel.support_radius();
  constexpr int kZ = 2000, kPlane = 400, kColours = 1001;
  std::vector<double> z(kZ + 1), cumulative(kZ + 1, 0.0), w1(kZ + 1);
  for (int k = 0; k <= kZ; ++k) {
    z[k] = rc * k / kZ;
    const double L = std::sqrt(std::max(rc * rc - z[k] * z[k], 0.0));
    double sum = 0;
    for (int q = 0; q <= kPlane; ++q) {
      const double p = L * q / kPlane, wq = (q == 0 || q == kPlane) ? 0.5 : 1.0;
      const double w = kernel.W(std::sqrt(z[k] * z[k] + p * p));
      sum += wq * (D == 2 ? 2.0 * w : 2.0 * std::numbers::pi * p * w);
    }
    w1[k] = sum * L / kPlane;
    if (k > 0) cumulative[k] = cumulative[k - 1] + 0.5 * (w1[k] + w1[k - 1]) * (z[k] - z[k - 1]);
  }
  const double half = cumulative[kZ];  // 1/2 up to the quadrature error: normalise by it
  depth_of_colour_.assign(kColours, 0.0);
  int k = 0;
  for (int q = 0; q < kColours; ++q) {
    const double target = 0.5 * q / (kColours - 1);  // c - 1/2 scaled to the half mass
    const double want = target / 0.5 * half;
    while (k < kZ && cumulative[k + 1] < want) ++k;
    if (k >= kZ) {
      depth_of_colour_[q] = rc;
      continue;
    }
    const double span = cumulative[k + 1] - cumulative[k];
    depth_of_colour_[q] =
        z[k] + (span > 0 ? (want - cumulative[k]) / span : 0.0) * (z[k + 1] - z[k]);
  }
}

template <int D>
double SurfaceTension<D>::planar_depth(double colour) const {
  const double u = std::abs(colour - 0.5) * 2.0 * static_cast<double>(depth_of_colour_.size() - 1);
  const auto k =
      static_cast<std::size_t>(std::min(u, static_cast<double>(depth_of_colour_.size() - 1)));
  const double d = k + 1 < depth_of_colour_.size()
                       ? depth_of_colour_[k] + (u - static_cast<double>(k)) *
                                                   (depth_of_colour_[k + 1] - depth_of_colour_[k])
                       : depth_of_colour_.back();
  return colour < 0.5 ? -d : d;
}

template <int D>
void SurfaceTension<D>::run(StepPhase /*phase*/, StepContext<D>& ctx) {
  with_pair_form(ctx.pairs, [&](auto compact) { sweep<decltype(compact)::value>(ctx); });
}

template <int D>
template <bool kCompact>
void SurfaceTension<D>::sweep(StepContext<D>& ctx) {
  normals<kCompact>(ctx);
  ctx.halo.update(ctx.particles, {&normal_});
  curvature_and_force<kCompact>(ctx);
  if (raw_curvature_ != nullptr) {
    for (std::size_t i = 0; i < ctx.particles.owned(); ++i)
      (*gradient_norm_)[i] = normal_[i].isZero() ? 0.0 : gradient_[i].norm();
    ctx.halo.update(ctx.particles, {raw_curvature_, gradient_norm_});
    smoothed_curvature_and_force<kCompact>(ctx);
  }
}

template <int D>
template <bool kCompact>
void SurfaceTension<D>::normals(StepContext<D>& ctx) {
  ParticleStore<D>& s = ctx.particles;
  const NeighborList<D>& nl = ctx.neighbors;
  const Vec<D>* x = s.x.data();
  const double* rho = s.rho.data();
  const double* m = s.m.data();
  const Kind* kind = s.kind.data();
  const std::uint16_t* mat = s.material.data();
  const double Vw = wall_volume_;
  const bool contact = !contact_.empty() && wall_index_ != nullptr;
  const ContactAngle neutral = [] {
    ContactAngle a;
    a.set = true;
    a.cos_own = a.cos_other = 0.0;
    a.sin_own = a.sin_other = 1.0;
    return a;
  }();
  for (std::size_t i = 0; i < s.owned(); ++i) {
    normal_[i] = Vec<D>::Zero();
    gradient_[i] = Vec<D>::Zero();
    curvature_[i] = 0;
    if (raw_curvature_ != nullptr) {
      (*raw_curvature_)[i] = 0;
      (*solid_gradient_)[i] = Vec<D>::Zero();
    }
    depth_[i] = 0;
    if (kind[i] != Kind::kFluid || !active_[mat[i]]) continue;
    const std::uint16_t mi = mat[i];
    const double* sig = sigma_.data() + mi * nm_;
    const double sig_void = sigma_void_[mi];
    const bool free = sig_void > 0;
    // 1/V_i sum_j (V_i^2 + V_j^2) grad W_ij over everything present, times V_i: A10's colour
    // gradient with the void's colour 0 (surface_tension_free_surface.h).
    Vec<D> present = Vec<D>::Zero();
    const Vec<D> xi = x[i];
    const double rhoi = rho[i], Vi = m[i] / rhoi, Vi2 = Vi * Vi;
    Vec<D> g = Vec<D>::Zero();  // sum over the interfaces of grad c times V_i
    Vec<D> G = Vec<D>::Zero();  // the same, each interface times its sigma
    const auto pairs = pairs_of<kCompact>(ctx.pairs, nl, i);
    std::size_t k = 0;
    // sum_j V_j W_ij over the own phase's neighbours and over all of them
    double own_support = 0, support = 0;
    const std::uint32_t* const fluid_end = nl.fluid_end(i);
    for (const std::uint32_t* jp = nl.begin(i); jp != fluid_end; ++jp, ++k) {
      const std::uint32_t j = *jp;
      const Vec<D> xij = xi - x[j];
      const double VWj = m[j] / rho[j] * pairs.W(k);
      support += VWj;
      if (mat[j] == mi) own_support += VWj;
      if (pairs.coincident(k, xij)) continue;
      const Vec<D> gradW = pairs.dwdr_r(k) * xij;
      const double Vj = m[j] / rho[j], s2 = Vi2 + Vj * Vj;
      if (free) present += s2 * gradW;
      const std::uint16_t mj = mat[j];
      if (mj == mi || sig[mj] == 0.0) continue;
      // (c~_ij - c_i) with c_i = 1, c_j = 0: towards the own phase.
      const Vec<D> t = (s2 * rhoi / (rhoi + rho[j])) * gradW;
      g -= t;
      G -= sig[mj] * t;
    }
    const double fluid_support = support;
    // The solids around i (walls and rigid particles: the list's dummies) and the angle of the
    // nearest solid: a wall's own or a rigid body's material's, else neutral.
    double nearest = std::numeric_limits<double>::infinity();
    const ContactAngle* angle = nullptr;
    Vec<D> wall_normal = Vec<D>::Zero();
    for (const std::uint32_t* jp = fluid_end; jp != nl.end(i); ++jp, ++k) {
      const std::uint32_t j = *jp;
      const Vec<D> xij = xi - x[j];
      support += Vw * pairs.W(k);
      if (pairs.coincident(k, xij)) continue;
      wall_normal -= pairs.times_dwdr_over_r(Vw, k) * xij;
      if (free) present += pairs.times_dwdr_over_r(Vi2 + Vw * Vw, k) * xij;
      const double r = pairs.distance(k, xij);
      if (r < nearest) {
        nearest = r;
        const ContactAngle* own = contact && kind[j] == Kind::kWall ? &contact_[(*wall_index_)[j]]
                                  : !solid_.empty() && kind[j] == Kind::kRigid ? &solid_[mat[j]]
                                                                               : nullptr;
        angle = own != nullptr && own->set ? own : &neutral;
      }
    }
    // Own phase's share of the fluid in the kernel support, i itself included (Shepard).
    const double self = Vi * self_weight_;
    g /= Vi;
    G /= Vi;
    double filled = support;  // what the own-support criterion compares with
    double weight = 1;        // of the normal in the neighbours' curvature (free surfaces)
    if (!free) {
      depth_[i] = planar_depth((own_support + self) / (fluid_support + self));
    } else {
      // The void fills what the present particles leave empty of the kernel's unit integral.
      const double void_share = std::max(0.0, 1.0 - (support + self));
      depth_[i] = planar_depth((own_support + self) / (fluid_support + self + void_share));
      filled = support + void_share;
      const double w = free_surface_weight(void_share);
      // A particle at an interface with another fluid keeps its full weight.
      if (!(g.norm() > min_gradient_)) weight = w;
      if (w > 0) {
        const Vec<D> cv = (w / Vi) * present;  // grad c towards the own phase, void c = 0
        g += cv;
        G += sig_void * cv;
      }
    }
    const double gn = G.norm();
    if (!(g.norm() > min_gradient_) || !(gn > 0) || own_support < kMinOwnSupport * filled) continue;
    Vec<D> n = G / gn;
    if (free && angle != nullptr) {
      // At a free surface the normal keeps its own direction next to a solid; the contact-line
      // force (contact_line_force) pulls the line to the angle instead.
      if (!wall_normal.isZero()) {
        (*solid_gradient_)[i] = wall_normal;
        (*cos_equilibrium_)[i] = mi == angle->through ? angle->cos_own : angle->cos_other;
      }
      angle = nullptr;
    }
    if (angle != nullptr) {
      const double wn = wall_normal.norm();
      if (wn > 0) {
        const Vec<D> nw = wall_normal / wn;
        Vec<D> t = n - n.dot(nw) * nw;
        const double tn = t.norm();
        if (!(tn > 0)) continue;  // n along the solid's normal: no tangent to turn it to
        t /= tn;
        const bool own = mi == angle->through;
        n = -(own ? angle->cos_own : angle->cos_other) * nw +
            (own ? angle->sin_own : angle->sin_other) * t;
        G = gn * n;
      }
    }
    normal_[i] = free ? Vec<D>(weight * n) : n;
    gradient_[i] = G;
  }
}

template <int D>
template <bool kCompact>
void SurfaceTension<D>::curvature_and_force(StepContext<D>& ctx) {
  ParticleStore<D>& s = ctx.particles;
  const NeighborList<D>& nl = ctx.neighbors;
  const Vec<D>* x = s.x.data();
  const double* rho = s.rho.data();
  const double* m = s.m.data();
  const std::uint16_t* mat = s.material.data();
  const Vec<D>* normal = normal_.data();
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (normal[i].isZero()) continue;  // no interface here (walls and bodies never have one)
    if (any_free_) {
      free_surface_curvature<kCompact>(ctx, i);
      continue;
    }
    const Vec<D> ni = normal[i];
    const std::uint16_t mi = mat[i];
    const Vec<D> xi = x[i];
    // N = sum_j V_j (n_j - n_i) (x) grad W_ij and M = sum_j V_j (x_j - x_i) (x) grad W_ij over
    // the neighbours with a normal: for a linear field n_j - n_i = A (x_j - x_i), N = A M.
    Mat<D> N = Mat<D>::Zero(), M = Mat<D>::Zero();
    const auto pairs = pairs_of<kCompact>(ctx.pairs, nl, i);
    std::size_t k = 0;
    for (const std::uint32_t* jp = nl.begin(i); jp != nl.fluid_end(i); ++jp, ++k) {
      const std::uint32_t j = *jp;
      const Vec<D>& nj = normal[j];
      const Vec<D> xji = x[j] - xi;
      if (pairs.coincident(k, xji) || nj.isZero()) continue;
      const Vec<D> VgradW = pairs.times_dwdr_over_r(-(m[j] / rho[j]), k) * xji;  // V_j grad W_ij
      const Vec<D> nji = mat[j] == mi ? Vec<D>(nj - ni) : Vec<D>(-nj - ni);
      N.noalias() += nji * VgradW.transpose();
      M.noalias() += xji * VgradW.transpose();
    }
    // div n = tr(A) = tr(N M^-1); A10's d tr(N) / tr(M) where M is nearly singular (few
    // neighbours with a normal, all on one line).
    const double trM = M.trace();
    if (!(trM > 0)) continue;
    const double det = M.determinant(), iso = std::pow(trM / D, D);
    const double div =
        det > kMinMomentRatio * iso ? (N * M.inverse()).trace() : D * N.trace() / trM;
    // -div n is the curvature of the level set through x_i, a depth d_i inside the own phase:
    // kappa_level = kappa / (1 - kappa d) in 2D (each principal curvature in 3D), so the
    // interface's kappa = kappa_level / (1 + kappa_level d).
    const double level = -div, shrink = 1 + level * depth_[i];
    const double kappa = shrink > kMinShrink ? level / shrink : level;
    curvature_[i] = kappa;
    s.a[i] += (kappa / rho[i]) * gradient_[i];  // forces accumulate (solver/seam/unit.h)
  }
}

// The curvature pass in a case with a free surface (surface_tension_free_surface.h): the
// normals carry their weight w_j (1 at a fluid-fluid interface) as their length, each
// neighbour enters N and M with it, and the divergence is the surface divergence
// tr(A) - n.(A n): the normals of the particles deeper in the band come from smaller, noisier
// gradients, and the shrinking normal component of their mean would otherwise read as
// curvature (measured: the outermost row of a free drop at 1.16-1.30 / R).
template <int D>
template <bool kCompact>
void SurfaceTension<D>::free_surface_curvature(StepContext<D>& ctx, std::size_t i) {
  ParticleStore<D>& s = ctx.particles;
  const NeighborList<D>& nl = ctx.neighbors;
  const Vec<D>* x = s.x.data();
  const double* rho = s.rho.data();
  const double* m = s.m.data();
  const std::uint16_t* mat = s.material.data();
  const Vec<D>* normal = normal_.data();
  const Vec<D> ni = normal[i].normalized();
  const std::uint16_t mi = mat[i];
  const Vec<D> xi = x[i];
  Mat<D> N = Mat<D>::Zero(), M = Mat<D>::Zero();
  const auto pairs = pairs_of<kCompact>(ctx.pairs, nl, i);
  std::size_t k = 0;
  for (const std::uint32_t* jp = nl.begin(i); jp != nl.fluid_end(i); ++jp, ++k) {
    const std::uint32_t j = *jp;
    const Vec<D>& nj = normal[j];
    const Vec<D> xji = x[j] - xi;
    if (pairs.coincident(k, xji) || nj.isZero()) continue;
    const double wj = nj.norm();
    // w_j V_j grad W_ij
    const Vec<D> VgradW = pairs.times_dwdr_over_r(-wj * (m[j] / rho[j]), k) * xji;
    const Vec<D> uj = nj / wj;
    const Vec<D> nji = mat[j] == mi ? Vec<D>(uj - ni) : Vec<D>(-uj - ni);
    N.noalias() += nji * VgradW.transpose();
    M.noalias() += xji * VgradW.transpose();
  }
  const double trM = M.trace();
  if (!(trM > 0)) return;
  const double det = M.determinant(), iso = std::pow(trM / D, D);
  double div = 0;
  if (det > kMinMomentRatio * iso) {
    const Mat<D> A = N * M.inverse();
    div = A.trace() - ni.dot(A * ni);
  } else {
    div = D * N.trace() / trM;
  }
  const double level = -div, shrink = 1 + level * depth_[i];
  (*raw_curvature_)[i] = shrink > kMinShrink ? level / shrink : level;
}

// The curvature of the interface at i as the Shepard average of the raw curvatures over i and
// its neighbours with a normal, each weighted by |G_j| V_j W_ij (surface_tension_free_surface.h:
// on a free surface the raw curvature carries the particle-scale roughness of the surface);
// then the force, a_i += kappa_i G_i / rho_i.
template <int D>
template <bool kCompact>
void SurfaceTension<D>::smoothed_curvature_and_force(StepContext<D>& ctx) {
  ParticleStore<D>& s = ctx.particles;
  const NeighborList<D>& nl = ctx.neighbors;
  const double* rho = s.rho.data();
  const double* m = s.m.data();
  const Vec<D>* normal = normal_.data();
  const double* raw = raw_curvature_->data();
  const double* gnorm = gradient_norm_->data();
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (normal[i].isZero()) continue;
    const double self = gnorm[i] * m[i] / rho[i] * self_weight_;
    double sum = self * raw[i], weight = self;
    // At a wall, also the mean normal over i and its neighbours with one, weighted as the
    // curvature (|G_j| V_j W_ij): it gives the apparent angle.
    const bool at_wall = !(*solid_gradient_)[i].isZero();
    Vec<D> mean = Vec<D>::Zero();
    if (at_wall) mean = self * normal[i].normalized();
    const auto pairs = pairs_of<kCompact>(ctx.pairs, nl, i);
    std::size_t k = 0;
    for (const std::uint32_t* jp = nl.begin(i); jp != nl.fluid_end(i); ++jp, ++k) {
      const std::uint32_t j = *jp;
      if (normal[j].isZero()) continue;
      const double wj = gnorm[j] * m[j] / rho[j] * pairs.W(k);
      sum += wj * raw[j];
      weight += wj;
      if (at_wall) mean += wj * normal[j].normalized();
    }
    const double kappa = sum / weight;
    curvature_[i] = kappa;
    s.a[i] += (kappa / rho[i]) * gradient_[i];  // forces accumulate (solver/seam/unit.h)
    if (at_wall) contact_line_force(s, i, mean);
  }
}

// The contact-line force at a free surface (docs/surface_tension.md, "Contact angles at a free
// surface"): Huber et al. 2016 (J. Comput. Phys. 310, 459), eq. (40) with the static angle,
//   f = sigma (cos theta_eq - cos theta) nu delta_cl,
// nu the unit vector along the solid, normal to the contact line, away from the liquid, theta
// the apparent angle through the liquid, from the mean normal n: cos theta = -n . n_w (n_w
// out of the solid). The line delta is the product of the two surfaces' deltas: |G| / sigma
// (the colour jump of the free surface, all on the liquid's side) and 2 |grad c_solid| (the
// solid's colour gradient, half of whose jump lies on the fluid's side); two planes crossing
// at theta carry 1 / sin theta of that product per unit line, so times sin theta the force
// integrates to sigma (cos theta_eq - cos theta) per unit length of contact line: Young's
// balance sigma_sg - sigma_sl = sigma cos theta_eq against the free surface's pull.
template <int D>
void SurfaceTension<D>::contact_line_force(ParticleStore<D>& s, std::size_t i,
                                           const Vec<D>& mean_normal) const {
  const Vec<D> solid = (*solid_gradient_)[i];
  const double ws = solid.norm(), mn = mean_normal.norm();
  if (!(mn > 0)) return;
  const Vec<D> nw = solid / ws, n = mean_normal / mn;
  Vec<D> t = n - n.dot(nw) * nw;  // along the solid, into the liquid
  const double tn = t.norm();
  if (!(tn > 0)) return;
  const double cos_app = -n.dot(nw), sin_app = tn;
  const double f = ((*cos_equilibrium_)[i] - cos_app) * sin_app * 2 * ws * (*gradient_norm_)[i];
  s.a[i] -= (f / (tn * s.rho[i])) * t;
}

template <int D>
void SurfaceTension<D>::declare_output(ResultFile& result) {
  result.add_field(curvature_);
}

template <int D>
void SurfaceTension<D>::sample(ResultFile& result, const StepContext<D>& ctx) {
  std::int64_t count = 0;
  double largest = 0;
  for (std::size_t i = 0; i < ctx.particles.owned(); ++i) {
    if (normal_[i].isZero()) continue;
    ++count;
    largest = std::max(largest, std::abs(curvature_[i]));
  }
  // Integer sums and maxima: the same on every rank count.
  result.put("surface_tension/interface_particles", static_cast<double>(ctx.comm.sum(count)));
  result.put("surface_tension/max_curvature", ctx.comm.max(largest));
}

}  // namespace sph
