#include "solver/bodies/body_regrouping.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <unordered_map>

namespace sph {
namespace {

// Union-find whose roots are the smallest index of each set, so the partition and its
// numbering depend only on the (id-ordered) records, not on the order links are found.
struct MinRootSets {
  std::vector<std::size_t> parent;
  explicit MinRootSets(std::size_t n) : parent(n) {
    std::iota(parent.begin(), parent.end(), std::size_t{0});
  }
  std::size_t find(std::size_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

template <int D>
RotationMatrix<D> rotation_of(const RigidBody<D>& b) {
  return b.orientation.matrix();
}

}  // namespace

template <int D>
std::string BodyRegrouping<D>::run(ParticleStore<D>& s, RigidBodies<D>& bodies,
                                   const std::vector<std::int64_t>& involved, const Comm& comm,
                                   const Column<std::int64_t>* solidified,
                                   std::int64_t* merged) const {
  auto& bs = bodies.bodies();
  auto& body = bodies.body_index();
  auto& accel = bodies.particle_acceleration();
  std::string mine;
  const auto& fluid_force = bodies.fluid_force();
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (s.kind[i] != Kind::kRigid) continue;
    const std::int32_t k = body[i];
    if (k >= 0 && !involved[static_cast<std::size_t>(k)]) continue;
    Record rec{s.id[i],
               k,
               s.material[i],
               static_cast<std::uint8_t>(merges(s.material[i])),
               static_cast<std::uint8_t>(solidified && (*solidified)[i] != 0),
               s.m[i],
               s.x[i],
               s.v[i],
               fluid_force[i]};
    mine.append(reinterpret_cast<const char*>(&rec), sizeof rec);
  }
  const std::string all = comm.allgather(mine);
  std::vector<Record> recs(all.size() / sizeof(Record));
  if (!recs.empty())  // memcpy to a null pointer is undefined even for 0 bytes
    std::memcpy(static_cast<void*>(recs.data()), all.data(), recs.size() * sizeof(Record));
  std::sort(recs.begin(), recs.end(), [](const Record& a, const Record& b) { return a.id < b.id; });
  std::int64_t merged_here = 0;
  if (std::string error = regroup(recs, involved, bodies, merged_here); !error.empty())
    return error;
  if (merged) *merged += merged_here;

  // The new body index, body-frame offset and rigid velocity (eq. 40) of the owned particles.
  auto& offset = bodies.offset();
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (s.kind[i] != Kind::kRigid) continue;
    const std::int32_t k = body[i];
    if (k >= 0 && !involved[static_cast<std::size_t>(k)]) continue;
    const auto it = std::lower_bound(recs.begin(), recs.end(), s.id[i],
                                     [](const Record& r, ParticleId id) { return r.id < id; });
    const RigidBody<D>& b = bs[static_cast<std::size_t>(it->old_body)];  // now: the new body
    body[i] = it->old_body;
    const Vec<D> r = s.x[i] - b.com;
    offset[i] = rotation_of(b).transpose() * r;
    s.v[i] = b.velocity + cross<D>(b.omega, r);
    accel[i] = b.acceleration + cross<D>(b.angular_acceleration, r) +
               cross<D>(b.omega, cross<D>(b.omega, r));
  }
  return {};
}

template <int D>
std::map<std::size_t, std::vector<std::size_t>> BodyRegrouping<D>::pieces_of(
    const std::vector<Record>& recs) const {
  const std::size_t n = recs.size();
  std::map<std::size_t, std::vector<std::size_t>> pieces;
  if (pieces_ == Pieces::kWhole) {
    std::map<std::int32_t, std::size_t> first;  // old body -> its first record
    for (std::size_t a = 0; a < n; ++a) {
      if (recs[a].old_body < 0)
        throw std::logic_error("BodyRegrouping: a particle without a body among whole bodies");
      const auto it = first.try_emplace(recs[a].old_body, a).first;
      pieces[it->second].push_back(a);
    }
    return pieces;
  }
  const double jr = join_radius_;
  // Links within the join radius: same body, or one of the two new (cell hashing), or both
  // of one merging material with one of them solidified during the run (merge_touching).
  MinRootSets sets(n);
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells;
  auto key = [&](const Vec<D>& x, const std::array<int, 3>& d) {
    std::int64_t k = 0;
    for (int a = 0; a < D; ++a)
      k = k * 2097152 + (static_cast<std::int64_t>(std::floor(x[a] / jr)) + d[a] + 1048576);
    return k;
  };
  for (std::size_t a = 0; a < n; ++a) cells[key(recs[a].x, {0, 0, 0})].push_back(a);
  const double jr2 = jr * jr;
  for (std::size_t a = 0; a < n; ++a)
    for (int dz = (D == 3 ? -1 : 0); dz <= (D == 3 ? 1 : 0); ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells.find(key(recs[a].x, {dx, dy, dz}));
          if (it == cells.end()) continue;
          for (const std::size_t b : it->second) {
            if (b <= a) continue;
            const Record &ra = recs[a], &rb = recs[b];
            const bool linkable = ra.old_body == rb.old_body || ra.old_body < 0 ||
                                  rb.old_body < 0 ||
                                  (ra.merges && rb.merges && ra.material == rb.material &&
                                   (ra.solidified || rb.solidified));
            if (linkable && (recs[a].x - recs[b].x).squaredNorm() < jr2) sets.unite(a, b);
          }
        }
  // Pieces in order of their smallest id.
  for (std::size_t a = 0; a < n; ++a) pieces[sets.find(a)].push_back(a);
  return pieces;
}

template <int D>
std::string BodyRegrouping<D>::regroup(std::vector<Record>& recs,
                                       const std::vector<std::int64_t>& involved,
                                       RigidBodies<D>& bodies, std::int64_t& merged) const {
  auto& bs = bodies.bodies();
  const std::size_t n = recs.size(), nb_old = bs.size();
  const auto pieces = pieces_of(recs);

  // Which piece keeps an old body: the one holding most of its mass (ties: the first piece).
  std::map<std::int32_t, std::pair<double, std::size_t>> main_piece;  // body -> (mass, root)
  for (const auto& [root, members] : pieces) {
    std::map<std::int32_t, double> share;
    for (const std::size_t a : members)
      if (recs[a].old_body >= 0) share[recs[a].old_body] += recs[a].m;
    for (const auto& [k, m] : share) {
      auto it = main_piece.find(k);
      if (it == main_piece.end() || m > it->second.first) main_piece[k] = {m, root};
    }
  }
  // Old bodies that merged into another: each kept body has one main piece, and a piece
  // keeping several is one body made of them.
  std::set<std::size_t> keeping;
  for (const auto& [k, share] : main_piece) keeping.insert(share.second);
  merged = static_cast<std::int64_t>(main_piece.size() - keeping.size());
  const double self = RigidBodies<D>::self_inertia_per_mass(dx_);
  std::vector<RigidBody<D>> old(bs);  // states before the regrouping
  // Every involved body is emptied first (one that melted completely stays so); its pieces
  // fill slots again below.
  for (std::size_t k = 0; k < nb_old; ++k)
    if (involved[k]) {
      bs[k].mass = 0;
      bs[k].particles = 0;
    }

  std::vector<std::int32_t> slot_of_record(n, -1);
  for (const auto& [root, members] : pieces) {
    // The old bodies this piece keeps: those whose main piece it is. The slot goes to a body
    // that does not move freely (a fixed or prescribed body stays so), else the heaviest.
    std::int32_t slot = -1;
    bool only_one_old = true, has_new = false;
    std::int32_t first_old = -1;
    for (const std::size_t a : members) {
      const std::int32_t k = recs[a].old_body;
      if (k < 0) {
        has_new = true;
        continue;
      }
      if (first_old < 0) first_old = k;
      if (k != first_old) only_one_old = false;
      if (main_piece.at(k).second != root) continue;
      if (slot < 0) {
        slot = k;
        continue;
      }
      const RigidBody<D>& cand = old[static_cast<std::size_t>(k)];
      const RigidBody<D>& cur = old[static_cast<std::size_t>(slot)];
      const bool cand_fixed = cand.motion != BodyMotion::kFree,
                 cur_fixed = cur.motion != BodyMotion::kFree;
      if ((cand_fixed && !cur_fixed) || (cand_fixed == cur_fixed && cand.mass > cur.mass)) slot = k;
    }
    RigidBody<D> nbody;
    if (slot >= 0) {
      nbody = old[static_cast<std::size_t>(slot)];
    } else {
      // A new body: from new particles only, or a minor piece broken off an old body. It
      // takes the first slot that melting emptied, so that melting and freezing again and
      // again needs slots for the bodies that exist at once, not for all there ever were. Not
      // a case body's slot (a checkpoint restores those with the case's motion and name), nor
      // one that a piece of this regrouping keeps.
      std::size_t free = bs.size();
      for (std::size_t k = bodies.case_bodies(); k < bs.size(); ++k)
        if (bs[k].particles == 0 && !main_piece.contains(static_cast<std::int32_t>(k))) {
          free = k;
          break;
        }
      if (free == bs.size() && bs.size() >= max_bodies_) {
        return "regrouping bodies needs more than " + std::to_string(max_bodies_) +
               " bodies at once (" + slots_field_ + ")";
      }
      if (first_old >= 0) {
        nbody = old[static_cast<std::size_t>(first_old)];  // inherits motion and path
        nbody.source = old[static_cast<std::size_t>(first_old)].source;
      } else {
        nbody = RigidBody<D>();
        nbody.orientation = Orientation<D>();
      }
      nbody.serial = bodies.next_serial();
      nbody.name = "body_" + std::to_string(nbody.serial);
      slot = static_cast<std::int32_t>(free);
      if (free == bs.size()) bs.push_back(nbody);
    }
    // Mass properties of the piece (eqs. 20-23 with Remark 13), in id order.
    double M = 0;
    Vec<D> mx = Vec<D>::Zero(), P = Vec<D>::Zero(), F = Vec<D>::Zero();
    std::map<std::int32_t, double> taken;  // mass taken from each old body
    for (const std::size_t a : members) {
      M += recs[a].m;
      mx += recs[a].m * recs[a].x;
      P += recs[a].m * recs[a].v;
      F += recs[a].f;
      if (recs[a].old_body >= 0) taken[recs[a].old_body] += recs[a].m;
    }
    const Vec<D> c = mx / M;
    Eigen::Matrix<double, RigidBodies<D>::A, RigidBodies<D>::A> Iw;
    Iw.setZero();
    AngVec<D> L = AngVec<D>::Zero(), T = AngVec<D>::Zero();
    for (const std::size_t a : members) {
      const Vec<D> r = recs[a].x - c;
      const double m = recs[a].m;
      T += moment<D>(r, recs[a].f);
      if constexpr (D == 2) {
        Iw(0, 0) += m * (r.squaredNorm() + self);
      } else {
        for (int p = 0; p < 3; ++p)
          for (int q = 0; q < 3; ++q)
            Iw(p, q) += m * ((p == q ? r.squaredNorm() + self : 0.0) - r[p] * r[q]);
      }
      L += moment<D>(r, m * recs[a].v);
      if (recs[a].old_body >= 0)
        L += m * self * old[static_cast<std::size_t>(recs[a].old_body)].omega;
    }
    const bool pure = !has_new && only_one_old;
    const RotationMatrix<D> R = nbody.orientation.matrix();
    nbody.mass = M;
    nbody.particles = static_cast<std::int64_t>(members.size());
    if constexpr (D == 2)
      nbody.inertia_body = Iw;
    else
      nbody.inertia_body = R.transpose() * Iw * R;
    if (nbody.motion == BodyMotion::kFixed) {
      nbody.velocity.setZero();
      nbody.omega.setZero();
    } else if (pure) {
      // Eq. 29: rigid motion with the unchanged angular velocity.
      const RigidBody<D>& o = old[static_cast<std::size_t>(first_old)];
      const Vec<D> d = c - o.com;
      nbody.velocity = o.velocity + cross<D>(o.omega, d);
      nbody.omega = o.omega;
      // The same rigid motion's acceleration at the new centre (the old one's is kept).
      nbody.acceleration = o.acceleration + cross<D>(o.angular_acceleration, d) +
                           cross<D>(o.omega, cross<D>(o.omega, d));
      nbody.angular_acceleration = o.angular_acceleration;
    } else {
      nbody.velocity = P / M;
      if constexpr (D == 2)
        nbody.omega = AngVec<D>(L[0] / Iw(0, 0));
      else
        nbody.omega = Iw.ldlt().solve(L);
    }
    // A prescribed path places the centre at center(t) + Rot(t) (com0 - center0) (MotionPath),
    // and a prescribed body's orientation is Rot(t): the new centre's com0 is the old one
    // shifted by the move taken back into the path's frame at t = 0.
    nbody.com0 += R.transpose() * (c - nbody.com);
    nbody.com = c;
    nbody.fluid_force = F;
    nbody.fluid_torque = T;
    // Its particles' levers belong to the old bodies' centres: the new body's first kick takes
    // the whole torque explicitly, the next force evaluation gives it its own damping.
    nbody.fluid_torque_rest = T;
    nbody.spin_damping.setZero();
    nbody.contact_force.setZero();
    nbody.contact_torque.setZero();
    nbody.contacts = 0;
    nbody.mean_contact_force.setZero();
    nbody.mean_contact_torque.setZero();
    for (const auto& [k, m] : taken) {
      const RigidBody<D>& o = old[static_cast<std::size_t>(k)];
      nbody.mean_contact_force += (m / o.mass) * o.mean_contact_force;
      nbody.mean_contact_torque += (m / o.mass) * o.mean_contact_torque;
    }
    if constexpr (D == 3) nbody.angular_momentum = Iw * nbody.omega;
    bs[static_cast<std::size_t>(slot)] = nbody;
    for (const std::size_t a : members) slot_of_record[a] = slot;
  }
  for (std::size_t a = 0; a < n; ++a) recs[a].old_body = slot_of_record[a];
  return {};
}

template class BodyRegrouping<2>;
template class BodyRegrouping<3>;

}  // namespace sph
