// The cell-linked neighbour list (with periodic ghosts from the halo on one rank) against a
// brute-force search with minimum-image distances.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <set>

#include "solver/core/kernel.h"
#include "solver/core/neighbor_list.h"
#include "solver/core/pair_kernel.h"
#include "solver/parallel/halo.h"

namespace sph {
namespace {

// The grid and the halo of a run on one rank (periodic images are ghosts it sends itself).
template <int D>
struct OneRank {
  OneRank(const Vec<D>& lo, const Vec<D>& hi, double cell, const std::array<bool, D>& periodic)
      : grid(lo, hi, cell, periodic), halo(grid, comm) {
    std::vector<std::int64_t> counts(static_cast<size_t>(grid.total()), 1);
    halo.set_decomposition(Decomposition<D>(grid, 1, counts));
  }
  CellGrid<D> grid;
  Comm comm{MPI_COMM_WORLD};
  Halo<D> halo;
};

template <int D>
void check_against_brute_force(const std::array<bool, D>& periodic, int seed) {
  const double rc = 0.3;
  Vec<D> lo = Vec<D>::Zero(), hi = Vec<D>::Constant(1.7);
  OneRank<D> one(lo, hi, rc, periodic);
  const CellGrid<D>& grid = one.grid;
  Halo<D>& halo = one.halo;
  ASSERT_EQ(one.comm.size(), 1);

  ParticleStore<D> s;
  const int n = D == 2 ? 600 : 1500;
  s.resize(static_cast<size_t>(n), static_cast<size_t>(n));
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::uniform_real_distribution<double> u(0.0, 1.7);
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < D; ++a) s.x[static_cast<size_t>(i)][a] = u(rng);
    s.kind[static_cast<size_t>(i)] = Kind::kFluid;
    s.id[static_cast<size_t>(i)] = i;
  }
  halo.migrate(s);
  halo.build_ghosts(s);
  NeighborList<D> nl;
  nl.build(s, grid, halo.ghost_box(), rc);

  for (std::size_t i = 0; i < s.owned(); ++i) {
    std::multiset<std::int64_t> expect, got;
    for (std::size_t j = 0; j < s.owned(); ++j) {
      if (j == i) continue;
      Vec<D> d = s.x[i] - s.x[j];
      for (int a = 0; a < D; ++a)
        if (periodic[a]) d[a] -= 1.7 * std::round(d[a] / 1.7);
      if (d.norm() < rc) expect.insert(s.id[j]);
    }
    for (const std::uint32_t* j = nl.begin(i); j != nl.end(i); ++j) {
      EXPECT_LT((s.x[i] - s.x[*j]).norm(), rc);
      got.insert(s.id[*j]);
    }
    ASSERT_EQ(got, expect) << "particle " << s.id[i];
  }
}

TEST(NeighborList, MatchesBruteForce2D) {
  check_against_brute_force<2>({false, false}, 1);
}
TEST(NeighborList, MatchesBruteForce2DPeriodic) {
  check_against_brute_force<2>({true, true}, 2);
}
TEST(NeighborList, MatchesBruteForce3DPeriodicX) {
  check_against_brute_force<3>({true, false, false}, 3);
}

// The lists of mixed kinds against brute force at the positions in s (minimum image along
// periodic axes): walls and rigid particles list their fluid neighbours first, then (with
// rigid_all) the rigid ones (walls) or all non-fluid ones (rigid particles); rigid particles
// also get their contact candidates (other bodies and walls within the contact range).
void expect_mixed_lists(const ParticleStore<2>& s, const NeighborList<2>& nl,
                        const std::vector<std::int32_t>& body, double rc, double range,
                        bool rigid_all, bool walls, const std::array<bool, 2>& periodic,
                        double length) {
  const std::size_t n = s.owned();
  for (std::size_t i = 0; i < n; ++i) {
    std::multiset<std::int64_t> fluid, rest, contacts;
    for (std::size_t j = 0; j < n; ++j) {
      Vec<2> d = s.x[i] - s.x[j];
      for (int a = 0; a < 2; ++a)
        if (periodic[static_cast<size_t>(a)]) d[a] -= length * std::round(d[a] / length);
      const double r = d.norm();
      if (j == i) continue;
      const bool jf = s.kind[j] == Kind::kFluid;
      // Every list: the fluid neighbours first, then (for fluid particles always, for the
      // others as rigid_all asks) the walls and rigid particles.
      if (r < rc && jf) fluid.insert(s.id[j]);
      if (r < rc && !jf &&
          (s.kind[i] == Kind::kFluid ||
           (rigid_all && (s.kind[i] == Kind::kRigid ||
                          (s.kind[i] == Kind::kWall && s.kind[j] == Kind::kRigid)))))
        rest.insert(s.id[j]);
      if (r < range && s.kind[i] == Kind::kRigid && !jf &&
          ((s.kind[j] == Kind::kRigid && body[j] != body[i]) ||
           (s.kind[j] == Kind::kWall && walls)))
        contacts.insert(s.id[j]);
    }
    std::multiset<std::int64_t> got_fluid, got_rest, got_contacts;
    for (const std::uint32_t* j = nl.begin(i); j != nl.fluid_end(i); ++j)
      got_fluid.insert(s.id[*j]);
    for (const std::uint32_t* j = nl.fluid_end(i); j != nl.end(i); ++j) got_rest.insert(s.id[*j]);
    for (const std::uint32_t* j = nl.contacts_begin(i); j != nl.contacts_end(i); ++j)
      got_contacts.insert(s.id[*j]);
    ASSERT_EQ(got_fluid, fluid) << "particle " << i << " rigid_all " << rigid_all;
    ASSERT_EQ(got_rest, rest) << "particle " << i << " rigid_all " << rigid_all;
    ASSERT_EQ(got_contacts, contacts) << "particle " << i << " walls " << walls;
  }
}

// 700 particles of mixed kinds on [0, 1.7]^2; body[i] is particle i's body (-1: none). No
// fluid lies beyond x = 1, so the walls there have rigid neighbours and no fluid ones.
void mixed_particles(ParticleStore<2>& s, std::vector<std::int32_t>& body) {
  const std::size_t n = 700;
  s.resize(n, n);
  body.assign(n, -1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.7);
  for (std::size_t i = 0; i < n; ++i) {
    s.x[i] = Vec<2>(u(rng), u(rng));
    s.id[i] = static_cast<std::int64_t>(i);
    const int k = static_cast<int>(i % 5);
    s.kind[i] = k < 2 ? (s.x[i][0] < 1 ? Kind::kFluid : Kind::kRigid)
                      : (k < 4 ? Kind::kRigid : Kind::kWall);
    if (s.kind[i] == Kind::kRigid) body[i] = static_cast<std::int32_t>(i % 3);
  }
}

// mixed_particles() on one rank, periodic along x, with their ghosts; body covers the ghosts
// too (each the body of the particle it images).
void mixed_particles_with_ghosts(OneRank<2>& one, ParticleStore<2>& s,
                                 std::vector<std::int32_t>& body) {
  mixed_particles(s, body);
  one.halo.migrate(s);
  one.halo.build_ghosts(s);
  for (std::size_t k = s.owned(); k < s.size(); ++k)
    body.push_back(body[static_cast<std::size_t>(s.id[k])]);
}

// Candidates refined with every particle back where they were searched (ghosts refreshed)
// are a fresh search's lists there, pair for pair: same order, same fluid part, same contacts.
::testing::AssertionResult refined_where_searched_is_fresh(ParticleStore<2>& s, OneRank<2>& one,
                                                           NeighborList<2>& nl,
                                                           const std::vector<Vec<2>>& searched,
                                                           const ContactQuery& q, double rc,
                                                           double range, bool rigid_all) {
  std::copy(searched.begin(), searched.end(), s.x.data());
  one.halo.refresh_ghosts(s);
  nl.refine(s, rc, range);
  NeighborList<2> fresh;
  fresh.build(s, one.grid, one.halo.ghost_box(), rc, &q, rigid_all);
  for (std::size_t i = 0; i < s.owned(); ++i) {
    if (!std::equal(nl.begin(i), nl.end(i), fresh.begin(i), fresh.end(i)))
      return ::testing::AssertionFailure() << "list of particle " << i;
    if (nl.fluid_end(i) - nl.begin(i) != fresh.fluid_end(i) - fresh.begin(i))
      return ::testing::AssertionFailure() << "fluid neighbours of particle " << i;
    if (!std::equal(nl.contacts_begin(i), nl.contacts_end(i), fresh.contacts_begin(i),
                    fresh.contacts_end(i)))
      return ::testing::AssertionFailure() << "contacts of particle " << i;
  }
  return ::testing::AssertionSuccess();
}

TEST(NeighborList, MixedKindsMatchBruteForce) {
  const double rc = 0.3, range = 0.12;
  OneRank<2> one(Vec<2>(0, 0), Vec<2>(1.7, 1.7), rc, {false, false});
  const CellGrid<2>& grid = one.grid;
  Halo<2>& halo = one.halo;
  ParticleStore<2> s;
  std::vector<std::int32_t> body;
  mixed_particles(s, body);
  halo.build_ghosts(s);
  for (const bool rigid_all : {false, true}) {
    for (const bool walls : {false, true}) {
      ContactQuery q{body.data(), range, walls};
      NeighborList<2> nl;
      nl.build(s, grid, halo.ghost_box(), rc, &q, rigid_all);
      expect_mixed_lists(s, nl, body, rc, range, rigid_all, walls, {false, false}, 1.7);
    }
  }
}

// Verlet lists: candidates within rc + skin at the positions of the search, refined after
// every particle moved up to just under half the skin (some of them out through the periodic
// boundary, where they are not wrapped back until the next search) and the ghosts were
// refreshed, give exactly the lists of the new positions; the order is the candidates'.
TEST(NeighborList, RefinedCandidatesMatchBruteForceAfterMoving) {
  const double rc = 0.3, range = 0.12, skin = 0.08;
  const std::array<bool, 2> periodic = {true, false};
  OneRank<2> one(Vec<2>(0, 0), Vec<2>(1.7, 1.7), rc + skin, periodic);
  const CellGrid<2>& grid = one.grid;
  Halo<2>& halo = one.halo;
  ParticleStore<2> s;
  std::vector<std::int32_t> body;
  mixed_particles(s, body);
  halo.migrate(s);
  halo.build_ghosts(s);
  // Bodies of the owned particles and of their periodic images.
  for (std::size_t k = s.owned(); k < s.size(); ++k)
    body.push_back(body[static_cast<std::size_t>(s.id[k])]);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(0.0, 2 * std::numbers::pi);
  std::uniform_real_distribution<double> length(0.0, 0.4999 * skin);
  for (const bool rigid_all : {false, true}) {
    for (const bool walls : {false, true}) {
      ContactQuery q{body.data(), range, walls};
      NeighborList<2> nl;
      nl.build_candidates(s, grid, halo.ghost_box(), rc, skin, &q, rigid_all);
      const std::vector<Vec<2>> searched(s.x.data(), s.x.data() + s.owned());
      std::size_t outside = 0;
      for (std::size_t i = 0; i < s.owned(); ++i) {
        const double a = angle(rng), l = length(rng);
        s.x[i] = searched[i] + l * Vec<2>(std::cos(a), std::sin(a));
        outside += s.x[i][0] < 0 || s.x[i][0] >= 1.7;
      }
      halo.refresh_ghosts(s);
      nl.refine(s, rc, range);
      EXPECT_GT(outside, 0u) << "no particle crossed the periodic boundary";
      expect_mixed_lists(s, nl, body, rc, range, rigid_all, walls, periodic, 1.7);
      // The refined lists keep the candidates' order, which is canonical at the searched
      // positions: refined there, they are a fresh search's lists, pair for pair.
      ASSERT_TRUE(refined_where_searched_is_fresh(s, one, nl, searched, q, rc, range, rigid_all));
    }
  }
}

// The pair kernel taken from the squared distances refine() wrote as it tested the
// candidates (the Verlet path of every step) equals, to the bit, the one evaluated from the
// positions of the refined lists; and it refuses squared distances no refine() wrote or that it
// took already.
TEST(NeighborList, RefinedSquaredDistancesGiveThePairKernelOfThePositions) {
  const double rc = 0.3, range = 0.12, skin = 0.08;
  OneRank<2> one(Vec<2>(0, 0), Vec<2>(1.7, 1.7), rc + skin, {true, false});
  ParticleStore<2> s;
  std::vector<std::int32_t> body;
  mixed_particles_with_ghosts(one, s, body);
  ContactQuery q{body.data(), range, true};
  NeighborList<2> nl;
  nl.build_candidates(s, one.grid, one.halo.ghost_box(), rc, skin, &q, true);
  const QuinticSpline<2> kernel(rc / 3);
  PairKernel<2> fused(PairKernel<2>::Storage::kTable), direct(PairKernel<2>::Storage::kTable);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> step(-0.11 * skin, 0.11 * skin);
  for (int round = 0; round < 3; ++round) {  // the spare room of r2 is reused
    for (std::size_t i = 0; i < s.owned(); ++i) s.x[i] += Vec<2>(step(rng), step(rng));
    one.halo.refresh_ghosts(s);
    fused.refine(nl, s, rc, range);
    ASSERT_GT(nl.pairs(), 1000u);
    ASSERT_LT(nl.pairs(), nl.candidate_pairs()) << "no candidate was left out";
    fused.prepare_refined(s, nl, kernel);
    direct.prepare(s, nl, kernel);
    for (std::size_t i = 0; i < s.owned(); ++i) {
      const PairValues a = fused.of(nl, i), b = direct.of(nl, i);
      for (std::ptrdiff_t e = 0; e < nl.end(i) - nl.begin(i); ++e) {
        ASSERT_EQ(a.r[e], b.r[e]) << "particle " << i << " pair " << e;
        ASSERT_EQ(a.w[e], b.w[e]);
        ASSERT_EQ(a.dw[e], b.dw[e]);
        ASSERT_EQ(a.r[e], (s.x[i] - s.x[nl.begin(i)[e]]).norm());
      }
    }
  }
  // Once taken, the square roots are not taken again.
  EXPECT_THROW(fused.prepare_refined(s, nl, kernel), std::logic_error);
  nl.refine(s, rc, range);  // without the squared distances
  EXPECT_THROW(fused.prepare_refined(s, nl, kernel), std::logic_error);
}

// The compact pair kernel (PAIR_KERNEL_COMPACT) keeps W and (dW/dr) / r in single precision
// (storage a third of the table's): from a fresh list its values are the double table's W and
// dW/dr / r rounded once (relative 2^-24), and of() gives the exact r with them; from the Verlet
// path (squared distances kept in single precision) W and dW/dr are within 2^-23 of the largest
// |W| and |dW/dr| the kernel takes.
TEST(NeighborList, CompactPairKernelIsTheTableRoundedToSinglePrecision) {
  const double rc = 0.3, range = 0.12, skin = 0.08;
  OneRank<2> one(Vec<2>(0, 0), Vec<2>(1.7, 1.7), rc + skin, {true, false});
  ParticleStore<2> s;
  std::vector<std::int32_t> body;
  mixed_particles_with_ghosts(one, s, body);
  ContactQuery q{body.data(), range, true};
  const QuinticSpline<2> kernel(rc / 3);
  double w_max = 0, dw_max = 0;
  for (double r = 0; r < rc; r += 1e-4) {
    w_max = std::max(w_max, std::abs(kernel.W(r)));
    dw_max = std::max(dw_max, std::abs(kernel.dW(r)));
  }
  PairKernel<2> table, compact(PairKernel<2>::Storage::kCompact);
  double worst_fresh = 0, worst_r = 0, worst_w = 0, worst_dw = 0;
  for (const bool verlet : {false, true}) {
    NeighborList<2> nl;
    if (verlet) {
      nl.build_candidates(s, one.grid, one.halo.ghost_box(), rc, skin, &q, true);
      std::mt19937 rng(11);
      std::uniform_real_distribution<double> step(-0.11 * skin, 0.11 * skin);
      for (std::size_t i = 0; i < s.owned(); ++i) s.x[i] += Vec<2>(step(rng), step(rng));
      one.halo.refresh_ghosts(s);
      compact.refine(nl, s, rc, range);
      compact.prepare_refined(s, nl, kernel);
    } else {
      nl.build(s, one.grid, one.halo.ghost_box(), rc, &q, true);
      compact.prepare(s, nl, kernel);
    }
    table.prepare(s, nl, kernel);
    ASSERT_GT(nl.pairs(), 1000u);
    for (std::size_t i = 0; i < s.owned(); ++i) {
      const PairValues a = compact.of(nl, i), b = table.of(nl, i);
      const CompactPairValues c = compact.compact_of(nl, i);
      for (std::ptrdiff_t e = 0; e < nl.end(i) - nl.begin(i); ++e) {
        worst_r = std::max(worst_r, std::abs(a.r[e] - b.r[e]) / b.r[e]);
        if (verlet) {
          worst_w = std::max(worst_w, std::abs(a.w[e] - b.w[e]) / w_max);
          worst_dw = std::max(worst_dw, std::abs(a.dw[e] - b.dw[e]) / dw_max);
        } else {
          ASSERT_EQ(c.w[e], static_cast<float>(b.w[e])) << "particle " << i << " pair " << e;
          ASSERT_EQ(c.dw_r[e], static_cast<float>(b.dw[e] / b.r[e]));
          ASSERT_EQ(a.w[e], static_cast<double>(c.w[e]));
          if (b.w[e] != 0)
            worst_fresh = std::max(worst_fresh, std::abs(a.w[e] - b.w[e]) / std::abs(b.w[e]));
          if (b.dw[e] != 0)
            worst_fresh = std::max(worst_fresh, std::abs(a.dw[e] - b.dw[e]) / std::abs(b.dw[e]));
        }
      }
    }
    EXPECT_LT(static_cast<double>(compact.bytes()), 0.4 * static_cast<double>(table.bytes()));
  }
  std::printf(
      "compact pair kernel: fresh W and dW/dr within %.3g relative; r within %.3g relative; Verlet "
      "W within %.3g of max |W|, dW/dr within %.3g of max |dW/dr|\n",
      worst_fresh, worst_r, worst_w, worst_dw);
  EXPECT_EQ(worst_r, 0.0);  // from the positions, as the table's
  // W rounded once; dW/dr = ((dW/dr) / r rounded) r, two roundings.
  EXPECT_LE(worst_fresh, std::ldexp(1.0, -23));
  EXPECT_LE(worst_w, std::ldexp(1.0, -23));
  EXPECT_LE(worst_dw, std::ldexp(1.0, -23));
}

// Particles that change kind between fluid and rigid, or body, where they stand (phase
// transitions) after candidates listed with rigid_all: sorted again by the kinds now, the
// candidates give exactly the lists of the new kinds after moving, and, refined at the
// positions searched at, a fresh search's lists pair for pair (a resumed run's).
TEST(NeighborList, ReclassifiedCandidatesFollowPhaseChanges) {
  const double rc = 0.3, range = 0.12, skin = 0.08;
  const std::array<bool, 2> periodic = {true, false};
  OneRank<2> one(Vec<2>(0, 0), Vec<2>(1.7, 1.7), rc + skin, periodic);
  const CellGrid<2>& grid = one.grid;
  Halo<2>& halo = one.halo;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(0.0, 2 * std::numbers::pi);
  std::uniform_real_distribution<double> length(0.0, 0.4999 * skin);
  for (const bool walls : {false, true}) {
    ParticleStore<2> s;
    std::vector<std::int32_t> body;
    mixed_particles(s, body);
    halo.migrate(s);
    halo.build_ghosts(s);
    auto image_bodies = [&] {  // the owned particles' bodies onto their periodic images
      body.resize(s.owned());
      for (std::size_t k = s.owned(); k < s.size(); ++k)
        body.push_back(body[static_cast<std::size_t>(s.id[k])]);
    };
    image_bodies();
    ContactQuery q{body.data(), range, walls};
    NeighborList<2> nl;
    nl.build_candidates(s, grid, halo.ghost_box(), rc, skin, &q, true);
    const std::vector<Vec<2>> searched(s.x.data(), s.x.data() + s.owned());
    // Every 7th fluid particle freezes into body 0, every 4th rigid one melts, body 1 merges
    // into body 2 (its contacts with 2 end) and body 0 above y = 0.85 becomes body 3 (a split:
    // contacts between the halves begin).
    std::size_t froze = 0, melted = 0;
    for (std::size_t i = 0; i < s.owned(); ++i) {
      if (s.kind[i] == Kind::kFluid && i % 7 == 0) {
        s.kind[i] = Kind::kRigid;
        body[i] = 0;
        ++froze;
      } else if (s.kind[i] == Kind::kRigid && i % 4 == 0) {
        s.kind[i] = Kind::kFluid;
        body[i] = -1;
        ++melted;
      } else if (s.kind[i] == Kind::kRigid && body[i] == 1) {
        body[i] = 2;
      } else if (s.kind[i] == Kind::kRigid && body[i] == 0 && s.x[i][1] > 0.85) {
        body[i] = 3;
      }
    }
    ASSERT_GT(froze, 10u);
    ASSERT_GT(melted, 10u);
    image_bodies();
    q.body = body.data();
    for (std::size_t i = 0; i < s.owned(); ++i) {
      const double a = angle(rng), l = length(rng);
      s.x[i] = searched[i] + l * Vec<2>(std::cos(a), std::sin(a));
    }
    halo.refresh_ghosts(s);
    nl.reclassify_candidates(s, &q, skin);
    nl.refine(s, rc, range);
    expect_mixed_lists(s, nl, body, rc, range, true, walls, periodic, 1.7);
    ASSERT_TRUE(refined_where_searched_is_fresh(s, one, nl, searched, q, rc, range, true));
  }
}

// Candidates listed without rigid_all leave out what a change of kind would need.
TEST(NeighborList, ReclassifyingNeedsCandidatesOfEveryKind) {
  const double rc = 0.3, skin = 0.08;
  OneRank<2> one(Vec<2>(0, 0), Vec<2>(1.7, 1.7), rc + skin, {false, false});
  ParticleStore<2> s;
  std::vector<std::int32_t> body;
  mixed_particles(s, body);
  one.halo.build_ghosts(s);
  NeighborList<2> nl;
  nl.build_candidates(s, one.grid, one.halo.ghost_box(), rc, skin, nullptr, false);
  EXPECT_THROW(nl.reclassify_candidates(s, nullptr, skin), std::logic_error);
}

TEST(NeighborList, OrderIsCanonical) {
  // The same particles stored in two different orders give the same neighbour id sequences,
  // fluid neighbours and walls alike.
  OneRank<2> one(Vec<2>(0, 0), Vec<2>(1, 1), 0.25, {false, false});
  const CellGrid<2>& grid = one.grid;
  Halo<2>& halo = one.halo;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec<2>> pos(300);
  for (auto& p : pos) p = Vec<2>(u(rng), u(rng));
  auto sequences = [&](bool reversed) {
    ParticleStore<2> s;
    s.resize(pos.size(), pos.size());
    for (std::size_t k = 0; k < pos.size(); ++k) {
      const std::size_t i = reversed ? pos.size() - 1 - k : k;
      s.x[i] = pos[k];
      s.id[i] = static_cast<std::int64_t>(k);
      s.kind[i] = k % 4 == 0 ? Kind::kWall : Kind::kFluid;
    }
    halo.build_ghosts(s);
    NeighborList<2> nl;
    nl.build(s, grid, halo.ghost_box(), 0.25);
    std::vector<std::vector<std::int64_t>> out(pos.size());
    for (std::size_t i = 0; i < s.owned(); ++i)
      for (const std::uint32_t* j = nl.begin(i); j != nl.end(i); ++j)
        out[static_cast<size_t>(s.id[i])].push_back(s.id[*j]);
    return out;
  };
  EXPECT_EQ(sequences(false), sequences(true));
}

}  // namespace
}  // namespace sph
