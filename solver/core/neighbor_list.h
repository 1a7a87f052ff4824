#pragma once
// Cell-linked neighbour search producing a compact (CSR) neighbour list per step, shared by
// every pass over pairs in that step (density, wall extrapolation, forces). The list of a
// particle is in canonical order: its fluid neighbours, then the others, each in the order of
// the 5^D half cells around it and ascending global id within each half cell. Sums over neighbours
// are therefore evaluated in the same order whatever the rank count or memory order, which makes
// results independent of the decomposition.
#include <cstdint>
#include <vector>

#include "solver/core/cell_grid.h"
#include "solver/core/particle_store.h"

namespace sph {

// Contact candidates of rigid particles: particles of other bodies (and walls) nearer than
// `range` (Fuchs 2021 eq. 27 acts below dx; the margin covers the motion within one step).
struct ContactQuery {
  const std::int32_t* body = nullptr;  // body index per particle (owned and ghosts)
  double range = 0;
  bool walls = true;
};

template <int D>
class NeighborList {
 public:
  // Bins all particles of `s` (owned and ghosts) into the cells of `box` (this rank's cells
  // plus the ghost layer) and builds the neighbour lists of the owned particles. Fluid
  // particles get all neighbours within rc. Wall and rigid particles get their fluid
  // neighbours (all the wall condition needs) and, with `rigid_all`, rigid particles also
  // their other neighbours after those (conduction inside and between bodies) and wall
  // particles their rigid neighbours after those (the Dirichlet mirror of conduction).
  void build(const ParticleStore<D>& s, const CellGrid<D>& grid, const CellBox<D>& box, double rc,
             const ContactQuery* contact = nullptr, bool rigid_all = false);
  // Verlet lists: as build(), but keeps the pairs within rc + skin (contact candidates within
  // their range + skin) as candidates, in the canonical order of the positions now. refine()
  // then makes the lists of a later step from them. The grid's cells must be at least
  // rc + skin wide.
  void build_candidates(const ParticleStore<D>& s, const CellGrid<D>& grid, const CellBox<D>& box,
                        double rc, double skin, const ContactQuery* contact = nullptr,
                        bool rigid_all = false);
  // The lists of the current positions: the candidates within rc (contacts within
  // contact_range), in the candidates' order. Exact while no particle has moved half the skin
  // since build_candidates(), and the particles (owned and ghosts) are the same, in the same
  // rows.
  void refine(const ParticleStore<D>& s, double rc, double contact_range);
  // As refine(), and writes the squared distance of every pair kept into r2, parallel to the
  // lists (grown with them), as it tests them, so that the pair kernel need not gather the
  // positions of every pair again (PairKernel::refine). Real is double or float.
  template <class Real>
  void refine(const ParticleStore<D>& s, double rc, double contact_range, std::vector<Real>& r2);
  // After particles changed kind between fluid and rigid, or body, where they stand (a phase
  // transition, Fuchs 2021 eq. 29; ghosts refreshed): sorts every candidate list again into
  // its fluid and other neighbours by the kinds now and lists the contact candidates of the
  // rigid particles now among them (those within contact->range + 2 skin of the positions now
  // hold every pair that can come within range before the next search). Exact only for
  // candidates built with rigid_all, which list every kind around fluid and rigid particles
  // and rigid ones around walls (phase transitions come with conduction or diffusion, which
  // asks for that), so that no change of kind takes a particle out of them; throws otherwise.
  // refine() then makes the lists that candidates built at the positions searched at, with
  // the kinds and bodies now, would give, so a run resumed there goes on to the bit.
  void reclassify_candidates(const ParticleStore<D>& s, const ContactQuery* contact, double skin);

  const std::uint32_t* begin(std::size_t i) const { return cur_.nbr.data() + cur_.start[i]; }
  // Position of particle i's list in the storage (tables parallel to the lists use it).
  std::size_t first(std::size_t i) const { return cur_.start[i]; }
  // Counts the builds and refinements, so a table made from one list can tell it is stale.
  std::uint64_t generation() const { return generation_; }
  // Counts the searches alone (build(), build_candidates(), reclassify_candidates()): the
  // candidates below, and a table made from them, last until it changes.
  std::uint64_t search_generation() const { return search_generation_; }
  // The lists of the last search: the Verlet candidates (pairs within rc + skin of the
  // positions searched at), or the lists themselves where build() made them. Fluid
  // neighbours first, in canonical order, as in the lists.
  const std::uint32_t* candidates_fluid_end(std::size_t i) const {
    const Lists& L = verlet_ ? cand_ : cur_;
    return L.nbr.data() + L.fluid_end[i];
  }
  const std::uint32_t* candidates_end(std::size_t i) const {
    const Lists& L = verlet_ ? cand_ : cur_;
    return L.nbr.data() + L.start[i + 1];
  }
  const std::uint32_t* end(std::size_t i) const { return cur_.nbr.data() + cur_.start[i + 1]; }
  // The end of the fluid neighbours, which come first in every list (in canonical order, as
  // do the others after them).
  const std::uint32_t* fluid_end(std::size_t i) const {
    return cur_.nbr.data() + cur_.fluid_end[i];
  }
  std::size_t pairs() const { return cur_.pairs; }
  // Owned particles the lists were made for.
  std::size_t listed() const { return cur_.start.empty() ? 0 : cur_.start.size() - 1; }
  std::size_t candidate_pairs() const { return cand_.pairs; }
  // Contact candidates of owned rigid particle i (empty without a ContactQuery).
  const std::uint32_t* contacts_begin(std::size_t i) const {
    return cur_.contact_start.empty() ? nullptr : cur_.contact_nbr.data() + cur_.contact_start[i];
  }
  const std::uint32_t* contacts_end(std::size_t i) const {
    return cur_.contact_start.empty() ? nullptr
                                      : cur_.contact_nbr.data() + cur_.contact_start[i + 1];
  }
  std::size_t contact_pairs() const {
    return cur_.contact_start.empty() ? 0 : cur_.contact_start.back();
  }
  // Smallest distance between contact candidates on this rank (infinity if none).
  double min_contact_distance() const { return cur_.min_contact; }
  std::size_t bytes() const {
    return cur_.bytes() + cand_.bytes() +
           (others_.capacity() + slot_.capacity()) * sizeof(std::uint32_t) +
           (cell_start_.capacity() + cell_items_.capacity() + cell_of_.capacity()) *
               sizeof(std::uint32_t) +
           cell_kinds_.capacity();
  }

  // Calls fn(j) for every particle (owned or ghost) in the 3^D cells around the global cell
  // c, which must lie in this rank's box (not in the ghost layer). Canonical order.
  template <class Fn>
  void for_each_near(const ICoord<D>& c, Fn&& fn) const {
    // The 3^D cells are 6^D half cells, in rows of six adjacent along x.
    ICoord<D> l;
    for (int a = 0; a < D; ++a) l[a] = 2 * (c[a] - box_.lo[a]) - 2;
    for (int dz = 0; dz < (D == 3 ? 6 : 1); ++dz)
      for (int dy = 0; dy < 6; ++dy) {
        std::size_t lin = static_cast<std::size_t>(l[0]) +
                          static_cast<std::size_t>(dims_[0]) * static_cast<std::size_t>(l[1] + dy);
        if constexpr (D == 3)
          lin += static_cast<std::size_t>(dims_[0]) * static_cast<std::size_t>(dims_[1]) *
                 static_cast<std::size_t>(l[2] + dz);
        for (std::uint32_t q = cell_start_[lin]; q < cell_start_[lin + 6]; ++q) fn(cell_items_[q]);
      }
  }

 private:
  // Neighbour lists in CSR form: per owned particle its pairs (fluid ones first), and its
  // contact candidates.
  struct Lists {
    std::vector<std::uint32_t> start, fluid_end;
    std::vector<std::uint32_t> nbr;  // storage; the first `pairs` entries are the lists
    std::vector<std::uint32_t> contact_start, contact_nbr;
    std::size_t pairs = 0;
    double min_contact = 0;
    std::size_t bytes() const {
      return (start.capacity() + fluid_end.capacity() + nbr.capacity() + contact_start.capacity() +
              contact_nbr.capacity()) *
             sizeof(std::uint32_t);
    }
  };
  template <class Real, bool kSquaredDistances>
  void refine_lists(const ParticleStore<D>& s, double rc, double contact_range,
                    std::vector<Real>* r2);
  void build_into(Lists& out, const ParticleStore<D>& s, const CellGrid<D>& grid,
                  const CellBox<D>& box, double rc, const ContactQuery* contact, bool rigid_all);

  CellBox<D> box_;
  ICoord<D> dims_{};              // half cells of box_ along each axis
  Vec<D> half_ = Vec<D>::Zero();  // half-cell size
  std::vector<std::uint32_t> cell_start_, cell_items_, cell_of_;
  std::vector<std::uint8_t> cell_kinds_;
  std::vector<std::uint32_t> others_;
  std::vector<std::uint32_t> slot_;  // position of each particle in cell_items_ (reclassify)
  Lists cur_;                        // the lists the passes read
  Lists cand_;                       // Verlet candidates (build_candidates)
  double cand_range_ = 0;            // rc + skin of cand_
  bool cand_rigid_all_ = false;      // cand_ built with rigid_all
  std::uint64_t generation_ = 0;
  std::uint64_t search_generation_ = 0;
  bool verlet_ = false;  // the last search made candidates (build_candidates)
};

// The owned particles (all inside `box`) ordered by (cell, id): the memory order that keeps
// neighbours close.
template <int D>
std::vector<std::uint32_t> owned_cell_order(const ParticleStore<D>& s, const CellGrid<D>& grid,
                                            const CellBox<D>& box);

}  // namespace sph
