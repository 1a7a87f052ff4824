#include "solver/bodies/restitution_contact.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <tuple>
#include <utility>

#include "solver/bodies/restitution_impulse.h"

namespace sph {

namespace {
template <class T>
void put(std::string& buf, const T& v) {
  const std::size_t at = buf.size();
  buf.resize(at + sizeof(T));
  std::memcpy(buf.data() + at, static_cast<const void*>(&v), sizeof(T));
}
template <class T>
void take(const std::string& buf, std::size_t& at, T& v) {
  std::memcpy(static_cast<void*>(&v), buf.data() + at, sizeof(T));
  at += sizeof(T);
}
}  // namespace

template <int D>
std::vector<typename RestitutionContact<D>::Pair> RestitutionContact<D>::gather(
    const NeighborList<D>& nl, const Comm& comm) const {
  const auto& body = bodies_.body_index();
  std::string mine;
  for (std::size_t i = 0; i < s_.owned(); ++i) {
    if (s_.kind[i] != Kind::kRigid) continue;
    for (const std::uint32_t* jp = nl.contacts_begin(i); jp != nl.contacts_end(i); ++jp) {
      const std::uint32_t j = *jp;
      std::int32_t partner;
      if (s_.kind[j] == Kind::kRigid) {
        if (body[j] <= body[i]) continue;  // each pair of bodies once, from the lower body
        partner = body[j];
      } else {
        partner = -1 - (wall_index_ ? static_cast<std::int32_t>((*wall_index_)[j]) : 0);
      }
      put(mine, s_.id[i]);
      put(mine, s_.id[j]);
      put(mine, body[i]);
      put(mine, partner);
      for (int a = 0; a < D; ++a) put(mine, s_.x[i][a]);
      for (int a = 0; a < D; ++a) put(mine, s_.x[j][a]);
      for (int a = 0; a < D; ++a) put(mine, s_.v[j][a]);
    }
  }
  const std::string all = comm.allgather(mine);
  constexpr std::size_t rec =
      2 * sizeof(ParticleId) + 2 * sizeof(std::int32_t) + 3 * D * sizeof(double);
  std::vector<Pair> pairs;
  pairs.reserve(all.size() / rec);
  for (std::size_t at = 0; at + rec <= all.size();) {
    Pair p;
    take(all, at, p.id_r);
    take(all, at, p.id_other);
    take(all, at, p.body);
    take(all, at, p.partner);
    for (int a = 0; a < D; ++a) take(all, at, p.x_r[a]);
    for (int a = 0; a < D; ++a) take(all, at, p.x_other[a]);
    for (int a = 0; a < D; ++a) take(all, at, p.v_wall[a]);
    pairs.push_back(p);
  }
  // The order of the ids (and of the positions, for periodic images of one particle) is the
  // same for any decomposition.
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    if (a.id_r != b.id_r) return a.id_r < b.id_r;
    if (a.id_other != b.id_other) return a.id_other < b.id_other;
    for (int k = 0; k < D; ++k)
      if (a.x_other[k] != b.x_other[k]) return a.x_other[k] < b.x_other[k];
    return false;
  });
  return pairs;
}

template <int D>
std::int64_t RestitutionContact<D>::resolve(const std::vector<Pair>& pairs, double dt) {
  auto& bs = bodies_.bodies();
  impulse_.assign(bs.size(), Vec<D>::Zero());
  angular_impulse_.assign(bs.size(), AngVec<D>::Zero());
  std::vector<std::int64_t> contacts(bs.size(), 0);
  // Contacts in the order of their first pair's ids.
  std::map<std::pair<std::int32_t, std::int32_t>, std::size_t> slot;
  std::vector<std::vector<std::size_t>> members;
  std::vector<std::pair<std::int32_t, std::int32_t>> keys;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto key = std::make_pair(pairs[k].body, pairs[k].partner);
    const auto [it, fresh] = slot.emplace(key, members.size());
    if (fresh) {
      members.emplace_back();
      keys.push_back(key);
    }
    members[it->second].push_back(k);
  }
  std::vector<char> hit(members.size(), 0);
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    bool any = false;
    for (std::size_t m = 0; m < members.size(); ++m) {
      RigidBody<D>& p = bs[static_cast<std::size_t>(keys[m].first)];
      RigidBody<D>* q =
          keys[m].second >= 0 ? &bs[static_cast<std::size_t>(keys[m].second)] : nullptr;
      if (!p.active() || (q && !q->active())) continue;
      Vec<D> normal = Vec<D>::Zero(), point = Vec<D>::Zero(), v_wall = Vec<D>::Zero();
      int n = 0;
      for (const std::size_t k : members[m]) {
        const Pair& pr = pairs[k];
        const Vec<D> d = pr.x_r - pr.x_other;
        const double dist = d.norm();
        if (dist == 0.0) continue;
        const Vec<D> e = d / dist;
        const Vec<D> v = point_velocity<D>(&p, pr.x_r, Vec<D>::Zero()) -
                         point_velocity<D>(q, pr.x_other, pr.v_wall);
        // Touching now, or would touch within the step (Reder et al. 2021 sec. 2.4).
        if (dist - dx_ >= dt * std::max(0.0, -v.dot(e))) continue;
        normal += e;
        point += 0.5 * (pr.x_r + pr.x_other);
        v_wall += pr.v_wall;
        ++n;
      }
      const double len = normal.norm();
      if (n == 0 || len == 0.0) continue;
      normal /= len;
      point /= n;
      v_wall /= n;
      const double scale =
          point_velocity<D>(&p, point, v_wall).norm() + point_velocity<D>(q, point, v_wall).norm();
      const ImpulseOutcome<D> out = collide<D>(p, q, point, normal, v_wall, e_, mu_, 1e-12 * scale);
      if (!out.applied) continue;
      any = true;
      hit[m] = 1;
      impulse_[static_cast<std::size_t>(keys[m].first)] += out.impulse;
      angular_impulse_[static_cast<std::size_t>(keys[m].first)] +=
          moment<D>(Vec<D>(point - p.com), out.impulse);
      if (q) {
        impulse_[static_cast<std::size_t>(keys[m].second)] -= out.impulse;
        angular_impulse_[static_cast<std::size_t>(keys[m].second)] -=
            moment<D>(Vec<D>(point - q->com), out.impulse);
      }
    }
    if (!any) break;
  }
  std::int64_t total = 0;
  for (std::size_t m = 0; m < members.size(); ++m) {
    if (!hit[m]) continue;
    ++total;
    ++contacts[static_cast<std::size_t>(keys[m].first)];
    if (keys[m].second >= 0) ++contacts[static_cast<std::size_t>(keys[m].second)];
  }
  for (std::size_t k = 0; k < bs.size(); ++k) {
    // The impulses as the mean force over the step (what the fluid's wall condition sees,
    // capped like the spring-dashpot's: RigidBody::mean_contact_force).
    bs[k].contact_force = dt > 0 ? Vec<D>(impulse_[k] / dt) : Vec<D>(Vec<D>::Zero());
    bs[k].contact_torque =
        dt > 0 ? AngVec<D>(angular_impulse_[k] / dt) : AngVec<D>(AngVec<D>::Zero());
    bs[k].mean_contact_force = bs[k].contact_force;
    bs[k].mean_contact_torque = bs[k].contact_torque;
    bs[k].contacts = contacts[k];
  }
  return total;
}

template <int D>
void RestitutionContact<D>::drift(const NeighborList<D>& nl, double dt, int, double t_end,
                                  const Comm& comm) {
  resolve(gather(nl, comm), dt);
  bodies_.drift(dt, t_end);
}

template class RestitutionContact<2>;
template class RestitutionContact<3>;

}  // namespace sph
