#include "solver/bodies/spring_dashpot_contact.h"

#include <cstring>
#include <set>

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
void SpringDashpotContact<D>::evaluate(const NeighborList<D>& nl, const Comm& comm, double h) {
  auto& bs = bodies_.bodies();
  const std::size_t nb = bs.size();
  std::vector<RotationMatrix<D>> R(nb);
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
  const double reach = touch_range();
  const auto sums = exact_sum(
      nb * per,
      [&](auto emit) {
        // exact_sum runs this twice; both passes read history_ and build the same map.
        next_history_.clear();
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
            if (dist >= reach || dist == 0.0) continue;
            const Vec<D> e = d / dist;
            const Vec<D> vij = vi - vj;
            // Normal force along e, negative pushing apart: Glowinski's repulsion (Reder et
            // al. 2021 eq. 24) or the spring-dashpot of eq. 27.
            const double fn =
                repulsive()
                    ? -repulsion_.force(dist - dx_)
                    : k_ * (dist - dx_) +
                          pair_damping(body[i], s_.kind[*jp] == Kind::kRigid ? body[*jp] : -1) *
                              e.dot(vij);
            if (fn < 0.0) {
              f -= fn * e;
              touching += 1;
              if (friction()) {
                const PairKey key{s_.id[i], s_.id[*jp]};
                auto it = history_.find(key);
                Vec<D> delta = it == history_.end() ? Vec<D>::Zero() : it->second;
                delta -= delta.dot(e) * e;            // into the current tangent plane
                delta += h * (vij - vij.dot(e) * e);  // tangential relative motion
                Vec<D> ft = -kt_ * delta;
                const double cap = mu_ * -fn, mag = ft.norm();
                if (mag > cap) {  // sliding: Coulomb limit
                  ft *= cap / mag;
                  delta = -ft / kt_;
                }
                f += ft;
                next_history_[key] = delta;
              }
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
  if (friction() && h > 0) history_.swap(next_history_);
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
  impulse_.assign(bs.size(), Vec<D>::Zero());
  angular_impulse_.assign(bs.size(), AngVec<D>::Zero());
  auto contact_kick = [&](double tau) {
    for (std::size_t k = 0; k < bs.size(); ++k) {
      RigidBody<D>& b = bs[k];
      impulse_[k] += tau * b.contact_force;
      angular_impulse_[k] += tau * b.contact_torque;
      if (b.translates_freely()) b.velocity += tau / b.mass * b.contact_force;
      if (!b.rotates_freely()) continue;
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
    evaluate(nl, comm, h);
    contact_kick(0.5 * h);
  }
  for (std::size_t k = 0; k < bs.size(); ++k) {
    bs[k].mean_contact_force = dt > 0 ? Vec<D>(impulse_[k] / dt) : bs[k].contact_force;
    bs[k].mean_contact_torque = dt > 0 ? AngVec<D>(angular_impulse_[k] / dt) : bs[k].contact_torque;
  }
}

template <int D>
void SpringDashpotContact<D>::migrate_history(Halo<D>& halo) {
  if (!friction()) return;
  const auto& moved = halo.migrated_ids();
  std::map<ParticleId, std::size_t> dest;
  for (std::size_t r = 0; r < moved.size(); ++r)
    for (const ParticleId id : moved[r]) dest[id] = r;
  std::vector<std::vector<std::byte>> send(moved.size());
  for (auto it = history_.begin(); it != history_.end();) {
    const auto d = dest.find(it->first.first);
    if (d == dest.end()) {
      ++it;
      continue;
    }
    auto& buf = send[d->second];
    const std::size_t at = buf.size();
    buf.resize(at + 2 * sizeof(ParticleId) + sizeof(Vec<D>));
    std::memcpy(buf.data() + at, &it->first.first, sizeof(ParticleId));
    std::memcpy(buf.data() + at + sizeof(ParticleId), &it->first.second, sizeof(ParticleId));
    std::memcpy(buf.data() + at + 2 * sizeof(ParticleId), &it->second, sizeof(Vec<D>));
    it = history_.erase(it);
  }
  const auto got = halo.exchange_bytes(send);
  const std::size_t rec = 2 * sizeof(ParticleId) + sizeof(Vec<D>);
  for (const auto& buf : got)
    for (std::size_t at = 0; at + rec <= buf.size(); at += rec) {
      PairKey key;
      Vec<D> delta;
      std::memcpy(&key.first, buf.data() + at, sizeof(ParticleId));
      std::memcpy(&key.second, buf.data() + at + sizeof(ParticleId), sizeof(ParticleId));
      std::memcpy(static_cast<void*>(&delta), buf.data() + at + 2 * sizeof(ParticleId),
                  sizeof(Vec<D>));
      history_[key] = delta;
    }
}

template <int D>
void SpringDashpotContact<D>::prune_history() {
  std::set<ParticleId> owned;
  for (std::size_t i = 0; i < s_.owned(); ++i) owned.insert(s_.id[i]);
  for (auto it = history_.begin(); it != history_.end();)
    it = owned.count(it->first.first) ? std::next(it) : history_.erase(it);
}

template <int D>
void SpringDashpotContact<D>::save(CheckpointState& state, const Comm& comm) const {
  if (!friction()) return;
  const std::size_t rec = 2 * sizeof(ParticleId) + sizeof(Vec<D>);
  std::string mine(history_.size() * rec, '\0');
  std::size_t at = 0;
  for (const auto& [key, delta] : history_) {
    std::memcpy(mine.data() + at, &key.first, sizeof(ParticleId));
    std::memcpy(mine.data() + at + sizeof(ParticleId), &key.second, sizeof(ParticleId));
    std::memcpy(mine.data() + at + 2 * sizeof(ParticleId), &delta, sizeof(Vec<D>));
    at += rec;
  }
  const std::string all = comm.allgather(mine);
  for (std::size_t p = 0; p + rec <= all.size(); p += rec) {
    ParticleId r, j;
    Vec<D> delta;
    std::memcpy(&r, all.data() + p, sizeof(ParticleId));
    std::memcpy(&j, all.data() + p + sizeof(ParticleId), sizeof(ParticleId));
    std::memcpy(static_cast<void*>(&delta), all.data() + p + 2 * sizeof(ParticleId),
                sizeof(Vec<D>));
    const std::string k = "friction." + std::to_string(r) + "." + std::to_string(j) + ".";
    for (int a = 0; a < D; ++a) state[k + std::to_string(a)] = delta[a];
  }
}

template <int D>
void SpringDashpotContact<D>::load(const CheckpointState& state) {
  history_.clear();
  for (auto it = state.lower_bound("friction.");
       it != state.end() && it->first.rfind("friction.", 0) == 0; ++it) {
    // friction.<id_r>.<id_j>.<component>
    const std::string& k = it->first;
    const std::size_t a = k.find('.', 9), b = k.find('.', a + 1);
    const PairKey key{std::stoll(k.substr(9, a - 9)), std::stoll(k.substr(a + 1, b - a - 1))};
    history_[key][std::stoi(k.substr(b + 1))] = it->second;
  }
}

template class SpringDashpotContact<2>;
template class SpringDashpotContact<3>;

}  // namespace sph
