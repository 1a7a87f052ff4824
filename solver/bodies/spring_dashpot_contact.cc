#include "solver/bodies/spring_dashpot_contact.h"

namespace sph {

template <int D>
void SpringDashpotContact<D>::snapshot_step_start() {
  const auto& bs = bodies_.bodies();
  com0_.resize(bs.size());
  R0_.resize(bs.size());
  for (std::size_t k = 0; k < bs.size(); ++k) {
    com0_[k] = bs[k].com;
    R0_[k] = bs[k].orientation.matrix();
  }
}

template <int D>
void SpringDashpotContact<D>::evaluate(const NeighborList<D>& nl, const Comm& comm) {
  auto& bs = bodies_.bodies();
  const std::size_t nb = bs.size();
  std::vector<Mat<D>> R(nb);
  std::vector<Vec<D>> shift(nb);
  for (std::size_t k = 0; k < nb; ++k) {
    R[k] = bs[k].orientation.matrix();
    shift[k] = bs[k].com - com0_[k];
  }
  const auto& body = bodies_.body_index();
  const auto& off = bodies_.offset();
  // Current position and velocity of a rigid particle (owned or ghost) from its body.
  auto state = [&](std::uint32_t i, Vec<D>& x, Vec<D>& v) {
    const std::size_t k = static_cast<std::size_t>(body[i]);
    const Vec<D> r = R[k] * off[i];
    x = s_.x[i] + shift[k] + (R[k] - R0_[k]) * off[i];
    v = bs[k].velocity + cross<D>(bs[k].omega, r);
  };
  constexpr int A = RigidBodies<D>::A;
  const std::size_t per = D + A + 1;
  const auto sums = exact_sum(
      nb * per,
      [&](auto emit) {
        for (std::size_t i = 0; i < s_.owned(); ++i) {
          if (s_.kind[i] != Kind::kRigid || nl.contacts_begin(i) == nl.contacts_end(i)) continue;
          Vec<D> xi, vi;
          state(static_cast<std::uint32_t>(i), xi, vi);
          Vec<D> f = Vec<D>::Zero();
          double touching = 0;
          for (const std::uint32_t* jp = nl.contacts_begin(i); jp != nl.contacts_end(i); ++jp) {
            Vec<D> xj = s_.x[*jp], vj = s_.v[*jp];  // walls: as at the start of the step
            if (s_.kind[*jp] == Kind::kRigid) state(*jp, xj, vj);
            const Vec<D> d = xi - xj;
            const double dist = d.norm();
            if (dist >= dx_ || dist == 0.0) continue;
            const Vec<D> e = d / dist;
            const double fn = k_ * (dist - dx_) + d_ * e.dot(vi - vj);  // eq. 27
            if (fn < 0.0) {
              f -= fn * e;
              touching += 1;
            }
          }
          const std::size_t k = static_cast<std::size_t>(body[i]);
          const AngVec<D> m = moment<D>(R[k] * off[i], f);
          for (int a = 0; a < D; ++a) emit(k * per + static_cast<size_t>(a), f[a]);
          for (int a = 0; a < A; ++a) emit(k * per + D + static_cast<size_t>(a), m[a]);
          emit(k * per + D + A, touching);
        }
      },
      comm);
  for (std::size_t k = 0; k < nb; ++k) {
    for (int a = 0; a < D; ++a) bs[k].contact_force[a] = sums[k * per + static_cast<size_t>(a)];
    for (int a = 0; a < A; ++a)
      bs[k].contact_torque[a] = sums[k * per + D + static_cast<size_t>(a)];
    bs[k].contacts = static_cast<std::int64_t>(std::llround(sums[k * per + D + A]));
  }
}

template <int D>
void SpringDashpotContact<D>::drift(const NeighborList<D>& nl, double dt, int substeps,
                                    double t_end, const Comm& comm) {
  snapshot_step_start();
  auto& bs = bodies_.bodies();
  const double h = dt / substeps;
  auto contact_kick = [&](double tau) {
    for (RigidBody<D>& b : bs) {
      if (!b.moves_freely()) continue;
      b.velocity += tau / b.mass * b.contact_force;
      if constexpr (D == 2) {
        b.omega += tau * b.inverse_inertia(b.contact_torque);
      } else {
        b.angular_momentum += tau * b.contact_torque;
        b.update_omega();
      }
    }
  };
  // The contact force at the start of the step is that of the end of the previous one.
  for (int k = 0; k < substeps; ++k) {
    contact_kick(0.5 * h);
    bodies_.drift(h, t_end - dt + (k + 1) * h);
    evaluate(nl, comm);
    contact_kick(0.5 * h);
  }
}

template class SpringDashpotContact<2>;
template class SpringDashpotContact<3>;

}  // namespace sph
