#pragma once
// One hard-body collision by impulses: the restitution law of Johnson & Tezduyar 1996 as
// Reder et al. 2021 eqs. (25a-b) (two bodies) and (26) (a wall, m_q -> infinity) give it,
// written for the velocities at the contact point c so it holds for bodies that rotate and
// for contacts off the line of centres (for spheres and disks touching on that line it is
// eq. 25 exactly). With n the unit normal pointing from q to p and
//   v_n = ((U_p + w_p x r_p) - (U_q + w_q x r_q)) . n,   r = c - x_com,
// approaching (v_n < 0), p gets the impulse j_n n and q its opposite, with
//   j_n = -(1 + e) v_n / K_n,  K_n = 1/m_p + 1/m_q + n . [(I_p^-1 (r_p x n)) x r_p + (q)],
// so that the normal relative velocity after is -e v_n and the total momentum is unchanged.
// A body whose translation (rotation) is held has 1/m = 0 (I^-1 = 0); a wall has both.
// Optional Coulomb friction: a tangential impulse against the tangential slip after the
// normal impulse, the one that stops it (j_t = |v_t| / K_t) capped at mu j_n.
#include <algorithm>

#include "solver/bodies/rigid_body.h"

namespace sph {

template <int D>
struct ImpulseOutcome {
  bool applied = false;
  Vec<D> impulse = Vec<D>::Zero();  // on p (q gets -impulse)
};

// The velocity of body b's material point at c (a null body: the wall's velocity v_wall).
template <int D>
inline Vec<D> point_velocity(const RigidBody<D>* b, const Vec<D>& c, const Vec<D>& v_wall) {
  return b ? Vec<D>(b->velocity + cross<D>(b->omega, Vec<D>(c - b->com))) : v_wall;
}

// 1/m_eff of b along the unit vector u at c (0 for a wall).
template <int D>
inline double inverse_effective_mass(const RigidBody<D>* b, const Vec<D>& c, const Vec<D>& u) {
  if (!b) return 0;
  const Vec<D> r = c - b->com;
  return b->inverse_mass() + u.dot(cross<D>(b->inverse_inertia_if_free(moment<D>(r, u)), r));
}

// Adds impulse J at c to b (nothing for a wall or a held degree of freedom).
template <int D>
inline void apply_impulse(RigidBody<D>* b, const Vec<D>& c, const Vec<D>& J) {
  if (!b) return;
  if (b->translates_freely()) b->velocity += J / b->mass;
  if (!b->rotates_freely()) return;
  const AngVec<D> m = moment<D>(Vec<D>(c - b->com), J);
  if constexpr (D == 2) {
    b->omega += b->inverse_inertia(m);
  } else {
    b->angular_momentum += m;
    b->update_omega();
  }
}

// The collision of p with q (null: a wall moving at v_wall) at c along n (from q to p), with
// restitution e and friction coefficient mu. Does nothing unless they approach faster than
// `tolerance`.
template <int D>
inline ImpulseOutcome<D> collide(RigidBody<D>& p, RigidBody<D>* q, const Vec<D>& c, const Vec<D>& n,
                                 const Vec<D>& v_wall, double e, double mu, double tolerance = 0) {
  ImpulseOutcome<D> out;
  const Vec<D> vrel = point_velocity<D>(&p, c, v_wall) - point_velocity<D>(q, c, v_wall);
  const double vn = vrel.dot(n);
  if (vn >= -tolerance) return out;
  const double kn = inverse_effective_mass<D>(&p, c, n) + inverse_effective_mass<D>(q, c, n);
  if (kn <= 0) return out;               // neither can move along n
  const double jn = -(1 + e) * vn / kn;  // Reder et al. 2021 eqs. 25-26
  out.applied = true;
  out.impulse = jn * n;
  apply_impulse<D>(&p, c, out.impulse);
  apply_impulse<D>(q, c, Vec<D>(-out.impulse));
  if (mu > 0) {
    const Vec<D> v = point_velocity<D>(&p, c, v_wall) - point_velocity<D>(q, c, v_wall);
    const Vec<D> vt = v - v.dot(n) * n;
    const double slip = vt.norm();
    if (slip > 0) {
      const Vec<D> t = vt / slip;
      const double kt = inverse_effective_mass<D>(&p, c, t) + inverse_effective_mass<D>(q, c, t);
      if (kt > 0) {
        const Vec<D> Jt = -std::min(slip / kt, mu * jn) * t;  // Coulomb: |J_t| <= mu J_n
        apply_impulse<D>(&p, c, Jt);
        apply_impulse<D>(q, c, Vec<D>(-Jt));
        out.impulse += Jt;
      }
    }
  }
  return out;
}

}  // namespace sph
