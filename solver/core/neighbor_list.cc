#include "solver/core/neighbor_list.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sph {

namespace {

// At least n entries, with 1/8 spare when it grows (reserved first: resize() alone would
// double the capacity); never shrunk, so that sizes changing from step to step neither
// reallocate nor fill.
template <class T>
void grow_to(std::vector<T>& v, std::size_t n) {
  if (v.size() >= n) return;
  const std::size_t c = std::max(n, v.size() + v.size() / 8);
  v.reserve(c);
  v.resize(c);
}

}  // namespace

template <int D>
void NeighborList<D>::build(const ParticleStore<D>& s, const CellGrid<D>& grid,
                            const CellBox<D>& box, double rc, const ContactQuery* contact,
                            bool rigid_all) {
  build_into(cur_, s, grid, box, rc, contact, rigid_all);
  verlet_ = false;
}

template <int D>
void NeighborList<D>::build_candidates(const ParticleStore<D>& s, const CellGrid<D>& grid,
                                       const CellBox<D>& box, double rc, double skin,
                                       const ContactQuery* contact, bool rigid_all) {
  ContactQuery wider;
  if (contact) {
    wider = *contact;
    wider.range += skin;
  }
  build_into(cand_, s, grid, box, rc + skin, contact ? &wider : nullptr, rigid_all);
  cand_range_ = rc + skin;
  cand_rigid_all_ = rigid_all;
  verlet_ = true;
}

template <int D>
void NeighborList<D>::reclassify_candidates(const ParticleStore<D>& s, const ContactQuery* contact,
                                            double skin) {
  const std::size_t owned = s.owned();
  if (cand_.start.size() != owned + 1)
    throw std::logic_error("neighbour candidates are of other particles: build them again");
  if (!cand_rigid_all_)
    throw std::logic_error("candidates without rigid_all miss particles that change kind");
  ++search_generation_;
  if (contact && contact->range + skin > cand_range_)
    throw std::logic_error("contact range beyond the neighbour candidates");
  const Kind* kind = s.kind.data();
  const Vec<D>* x = s.x.data();
  const double cr = contact ? contact->range + 2.0 * skin : 0.0, cr2 = cr * cr;
  // The scan of build_into() visits the half cells in ascending linear index (rows in z, then
  // y, then x) and each cell's particles in the order of cell_items_: the canonical order of
  // a list is the ascending position of its particles in cell_items_, which is unchanged since
  // the candidates were listed.
  if (cell_items_.size() != s.size())
    throw std::logic_error("neighbour candidates are of other particles: build them again");
  slot_.resize(cell_items_.size());
  for (std::size_t q = 0; q < cell_items_.size(); ++q)
    slot_[cell_items_[q]] = static_cast<std::uint32_t>(q);
  const std::uint32_t* slot = slot_.data();
  std::uint32_t* cand = cand_.nbr.data();
  cand_.contact_nbr.clear();
  // Contact candidates are listed only for a contact query (no room taken without one).
  if (contact)
    cand_.contact_start.assign(owned + 1, 0);
  else
    cand_.contact_start.clear();
  for (std::size_t i = 0; i < owned; ++i) {
    // Both parts of the list are in canonical order: merged, they are the whole list in that
    // order, which is then split again by the kinds now (fluid first).
    const std::uint32_t b = cand_.start[i], f = cand_.fluid_end[i], e = cand_.start[i + 1];
    if (others_.size() < 2 * std::size_t{e - b}) others_.resize(2 * std::size_t{e - b});
    std::uint32_t* merged = others_.data();
    std::uint32_t* other = merged + (e - b);
    std::merge(cand + b, cand + f, cand + f, cand + e, merged,
               [slot](std::uint32_t u, std::uint32_t v) { return slot[u] < slot[v]; });
    std::uint32_t m = b, o = 0;
    for (std::uint32_t q = 0; q < e - b; ++q) {
      const std::uint32_t j = merged[q];
      const bool fluid = kind[j] == Kind::kFluid;
      cand[m] = j;
      m += fluid;
      other[o] = j;
      o += !fluid;
    }
    cand_.fluid_end[i] = m;
    std::copy(other, other + o, cand + m);
    if (contact && kind[i] == Kind::kRigid) {
      const Vec<D> xi = x[i];
      for (std::uint32_t q = m; q < e; ++q) {
        const std::uint32_t j = cand[q];
        const Kind kj = kind[j];
        if (((kj == Kind::kRigid && contact->body[j] != contact->body[i]) ||
             (kj == Kind::kWall && contact->walls)) &&
            (xi - x[j]).squaredNorm() < cr2)
          cand_.contact_nbr.push_back(j);
      }
    }
    if (contact) cand_.contact_start[i + 1] = static_cast<std::uint32_t>(cand_.contact_nbr.size());
  }
}

template <int D>
void NeighborList<D>::refine(const ParticleStore<D>& s, double rc, double contact_range) {
  refine_lists<double, false>(s, rc, contact_range, nullptr);
}

template <int D>
template <class Real>
void NeighborList<D>::refine(const ParticleStore<D>& s, double rc, double contact_range,
                             std::vector<Real>& r2) {
  refine_lists<Real, true>(s, rc, contact_range, &r2);
}

template <int D>
template <class Real, bool kSquaredDistances>
void NeighborList<D>::refine_lists(const ParticleStore<D>& s, double rc, double contact_range,
                                   std::vector<Real>* r2) {
  ++generation_;
  const std::size_t owned = s.owned();
  if (cand_.start.size() != owned + 1)
    throw std::logic_error("neighbour candidates are of other particles: build them again");
  Lists& o = cur_;
  o.start.resize(owned + 1);
  o.fluid_end.resize(owned);
  const bool contacts = !cand_.contact_start.empty();
  if (contacts)
    o.contact_start.resize(owned + 1);
  else
    o.contact_start.clear();
  if (o.contact_nbr.size() < cand_.contact_nbr.size())
    o.contact_nbr.resize(cand_.contact_nbr.size());
  // The pairs kept last time, for a start (the first refinement after a search grows them).
  grow_to(o.nbr, std::max(o.pairs, cand_.pairs / 2));
  if constexpr (kSquaredDistances) grow_to(*r2, o.nbr.size());
  const Vec<D>* x = s.x.data();
  const double rc2 = rc * rc, cr2 = contact_range * contact_range;
  const std::uint32_t* cand = cand_.nbr.data();
  std::uint32_t* out = o.nbr.data();
  Real* r2_out = kSquaredDistances ? r2->data() : nullptr;
  std::size_t m = 0, mc = 0;
  double min_contact = std::numeric_limits<double>::infinity();
  o.start[0] = 0;
  if (contacts) o.contact_start[0] = 0;
  for (std::size_t i = 0; i < owned; ++i) {
    const Vec<D> xi = x[i];
    // Branch-free, as in the search: every candidate is written, the count advances for the
    // pairs kept. The fluid neighbours stay first.
    const std::uint32_t f = cand_.fluid_end[i], e = cand_.start[i + 1];
    // Room for all of i's candidates past the pairs kept so far: the lists (and the squared
    // distances) grow with the pairs kept, not with the candidates, which a Verlet skin makes
    // up to twice as many (a lattice at rest, h = dx).
    if (o.nbr.size() < m + (e - cand_.start[i])) {
      grow_to(o.nbr, m + (e - cand_.start[i]));
      out = o.nbr.data();
      if constexpr (kSquaredDistances) {
        grow_to(*r2, o.nbr.size());
        r2_out = r2->data();
      }
    }
    // The squared distance, as the pair kernel would compute it (PairKernel::distances), is
    // written with the index and kept with it.
    const auto test = [&](std::uint32_t q) {
      const std::uint32_t j = cand[q];
      const double d2 = (xi - x[j]).squaredNorm();
      out[m] = j;
      if constexpr (kSquaredDistances) r2_out[m] = static_cast<Real>(d2);
      m += static_cast<std::size_t>(d2 < rc2);
    };
    for (std::uint32_t q = cand_.start[i]; q < f; ++q) test(q);
    o.fluid_end[i] = static_cast<std::uint32_t>(m);
    for (std::uint32_t q = f; q < e; ++q) test(q);
    o.start[i + 1] = static_cast<std::uint32_t>(m);
    if (!contacts) continue;
    for (std::uint32_t q = cand_.contact_start[i]; q < cand_.contact_start[i + 1]; ++q) {
      const std::uint32_t j = cand_.contact_nbr[q];
      const double d2c = (xi - x[j]).squaredNorm();
      if (d2c < cr2) {
        o.contact_nbr[mc++] = j;
        min_contact = std::min(min_contact, std::sqrt(d2c));
      }
    }
    o.contact_start[i + 1] = static_cast<std::uint32_t>(mc);
  }
  o.pairs = m;
  o.min_contact = min_contact;
}

template <int D>
void NeighborList<D>::build_into(Lists& L, const ParticleStore<D>& s, const CellGrid<D>& grid,
                                 const CellBox<D>& box, double rc, const ContactQuery* contact,
                                 bool rigid_all) {
  box_ = box;
  ++generation_;
  ++search_generation_;
  // Half cells: the box's cells split in two along every axis. The 5^D half cells around a
  // particle cover (2.5 r_c)^D instead of the (3 r_c)^D of the 3^D cells, 42% fewer candidates
  // in 3D before the half cells that lie wholly beyond r_c are left out (below). They are global
  // like the cells, so the canonical order stays independent of the decomposition.
  std::size_t ncell = 1;
  for (int a = 0; a < D; ++a) {
    dims_[a] = 2 * (box.hi[a] - box.lo[a]);
    half_[a] = 0.5 * grid.cell[a];
    ncell *= static_cast<std::size_t>(dims_[a]);
  }
  const std::size_t n = s.size();
  cell_of_.resize(n);
  cell_start_.assign(ncell + 1, 0);
  // Per half cell: whether it holds fluid (bit 0) or rigid particles (bit 1), so that walls and
  // rigid particles with nothing to list around them are passed over without a scan.
  cell_kinds_.assign(ncell, 0);
  const Vec<D>* x = s.x.data();
  const Kind* kind = s.kind.data();
  const ParticleId* id = s.id.data();
  const std::size_t owned_n = s.owned();
  for (std::size_t i = 0; i < n; ++i) {
    const ICoord<D> c = grid.half_bin(x[i]);
    // Owned particles belong to the interior cells (the ghost layer is two half cells deep);
    // clamping keeps a corrupted position (reported by the stability guard at the end of the
    // step) from indexing outside.
    const int margin = i < owned_n ? 2 : 0;
    std::size_t lin = 0;
    for (int a = D - 1; a >= 0; --a)
      lin =
          lin * static_cast<std::size_t>(dims_[a]) +
          static_cast<std::size_t>(std::clamp(c[a] - 2 * box.lo[a], margin, dims_[a] - 1 - margin));
    cell_of_[i] = static_cast<std::uint32_t>(lin);
    ++cell_start_[lin + 1];
    cell_kinds_[lin] |=
        static_cast<std::uint8_t>(kind[i] == Kind::kFluid                                ? 1
                                  : kind[i] == Kind::kRigid || kind[i] == Kind::kElastic ? 2
                                                                                         : 0);
  }
  for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_items_.resize(n);
  {
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      cell_items_[fill[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
  }
  // Ascending id within each cell (insertion sort: cells are small and nearly sorted because
  // owned particles are kept in cell order).
  for (std::size_t c = 0; c < ncell; ++c) {
    std::uint32_t* b = cell_items_.data() + cell_start_[c];
    std::uint32_t* e = cell_items_.data() + cell_start_[c + 1];
    for (std::uint32_t* p = b + 1; p < e; ++p) {
      const std::uint32_t v = *p;
      std::uint32_t* q = p;
      while (q > b && id[*(q - 1)] > id[v]) {
        *q = *(q - 1);
        --q;
      }
      *q = v;
    }
  }

  // The stencil as rows of five half cells along x, which are adjacent in the linear index,
  // so each row is one contiguous range of cell_items_. Fixed order (z, then y, then x).
  constexpr int kRows = D == 2 ? 5 : 25;
  long long rows[kRows];
  int row_dy[kRows], row_dz[kRows];
  {
    int k = 0;
    const long long sy = dims_[0], sz = D == 3 ? static_cast<long long>(dims_[0]) * dims_[1] : 0;
    for (int dz = (D == 3 ? -2 : 0); dz <= (D == 3 ? 2 : 0); ++dz)
      for (int dy = -2; dy <= 2; ++dy) {
        row_dy[k] = dy;
        row_dz[k] = dz;
        rows[k++] = dz * sz + dy * sy - 2;
      }
  }
  const Vec<D> grid_lo = grid.lo;

  const double rc2 = rc * rc;
  const double cr2 = contact ? contact->range * contact->range : 0.0;
  const std::size_t owned = s.owned();
  L.start.resize(owned + 1);
  L.fluid_end.resize(owned);
  L.pairs = 0;
  L.start[0] = 0;
  if (contact)
    L.contact_start.assign(owned + 1, 0);
  else
    L.contact_start.clear();
  L.contact_nbr.clear();
  L.min_contact = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < owned; ++i) {
    const long long ci = cell_of_[i];
    const bool fluid = kind[i] == Kind::kFluid;
    const bool rigid = kind[i] == Kind::kRigid;
    const bool contacts = contact && rigid;
    // Elastic particles list every neighbour: their fluid ones for the wall condition and
    // the coupling, the others for the total Lagrangian sums over their own body.
    const bool all = fluid || (rigid && rigid_all) || kind[i] == Kind::kElastic;
    // With conduction, a wall's Dirichlet mirror value averages the rigid and elastic particles
    // around it too (see ScalarDiffusion::extrapolate_walls), so walls list them after their fluid.
    const bool wall_rigid = rigid_all && kind[i] == Kind::kWall;
    if (!fluid && !contacts && !all) {
      // A wall that lists rigid particles must not be skipped beside a body with no fluid
      // near: its Dirichlet mirror would have nothing to average and fall back to the wall
      // value, so the body drew about half the flux (Conduction.SolidSlabOnADirichletWallErfc).
      const std::uint8_t wanted = wall_rigid ? 3 : 1;
      bool any = false;
      for (int k = 0; k < kRows && !any; ++k)
        for (int d = 0; d < 5 && !any; ++d)
          any = (cell_kinds_[static_cast<std::size_t>(ci + rows[k] + d)] & wanted) != 0;
      if (!any) {
        L.start[i + 1] = L.fluid_end[i] = static_cast<std::uint32_t>(L.pairs);
        if (contact) L.contact_start[i + 1] = static_cast<std::uint32_t>(L.contact_nbr.size());
        continue;
      }
    }
    // Of each row only the half cells that reach within r_c of the particle are scanned: a
    // row is skipped when its gap across y (and z) is r_c or more, and its ends along x are
    // trimmed where the gap along x adds up with it to r_c or more (22% fewer candidates than
    // whole rows in 3D, 14% in 2D, for particles spread evenly over their half cell). Every
    // particle left out lies at least r_c away, so the lists and their order are unchanged.
    // Gaps are measured from the faces of the particle's own half cell, so a particle clamped
    // into an edge half cell (a wall particle beyond a non-periodic edge) only gets smaller
    // gaps.
    const Vec<D> xi = x[i];
    // The half cell is the one the stencil is centred on (ci, from the binning above).
    double below[D], above[D];  // to the own half cell's faces
    long long rest = ci;
    for (int a = 0; a < D; ++a) {
      const long long l = rest % dims_[a];
      rest /= dims_[a];
      const double face = grid_lo[a] + half_[a] * static_cast<double>(l + 2 * box.lo[a]);
      below[a] = xi[a] - face;
      above[a] = face + half_[a] - xi[a];
    }
    auto gap2 = [&](int axis, int d) {
      const double g = d > 0   ? above[axis] + (d - 1) * half_[axis]
                       : d < 0 ? below[axis] + (-d - 1) * half_[axis]
                               : 0.0;
      return g > 0 ? g * g : 0.0;
    };
    std::uint32_t row_begin[kRows], row_end[kRows];
    std::size_t candidates = 0;
    for (int k = 0; k < kRows; ++k) {
      const double g2 = gap2(1, row_dy[k]) + (D == 3 ? gap2(2, row_dz[k]) : 0.0);
      const long long c = ci + rows[k] + 2;  // the row's half cell level with the particle in x
      if (g2 >= rc2) {
        row_begin[k] = row_end[k] = 0;
        continue;
      }
      int first = -2, last = 2;
      while (first < 0 && gap2(0, first) + g2 >= rc2) ++first;
      while (last > 0 && gap2(0, last) + g2 >= rc2) --last;
      row_begin[k] = cell_start_[static_cast<std::size_t>(c + first)];
      row_end[k] = cell_start_[static_cast<std::size_t>(c + last + 1)];
      candidates += row_end[k] - row_begin[k];
    }
    if (L.pairs + candidates > std::numeric_limits<std::uint32_t>::max())
      throw std::runtime_error("over 2^32 neighbour pairs on one rank: use more ranks");
    grow_to(L.nbr, L.pairs + candidates);
    if (others_.size() < candidates) others_.resize(candidates);
    // Branch-free appends: every candidate is written and the counts advance only for the
    // neighbours kept (a data-dependent branch here mispredicts often once the particles are
    // disordered). Fluid neighbours go to `out`; rigid or all non-fluid ones, as required, to
    // `other`, which follows them.
    std::uint32_t* out = L.nbr.data() + L.pairs;
    std::uint32_t* other = others_.data();
    std::size_t m = 0, o = 0;
    const std::uint32_t self = static_cast<std::uint32_t>(i);
    for (int k = 0; k < kRows; ++k) {
      const std::uint32_t q_end = row_end[k];
      for (std::uint32_t q = row_begin[k]; q < q_end; ++q) {
        const std::uint32_t j = cell_items_[q];
        const double r2 = (xi - x[j]).squaredNorm();
        const Kind kj = kind[j];
        const bool near = (r2 < rc2) & (j != self);
        const bool to_out = kj == Kind::kFluid;
        out[m] = j;
        m += static_cast<std::size_t>(near & to_out);
        other[o] = j;
        o += static_cast<std::size_t>(
            near & !to_out &
            (all | (wall_rigid & ((kj == Kind::kRigid) | (kj == Kind::kElastic)))));
        if (contacts && kj != Kind::kFluid && j != self && r2 < cr2 &&
            ((kj == Kind::kRigid && contact->body[j] != contact->body[i]) ||
             (kj == Kind::kWall && contact->walls))) {
          L.contact_nbr.push_back(j);
          L.min_contact = std::min(L.min_contact, std::sqrt(r2));
        }
      }
    }
    // Fluid neighbours first: the wall condition stops there, and loops over a fluid
    // particle's neighbours treat the fluid ones and the dummies apart, without a test per pair.
    L.pairs += m;
    L.fluid_end[i] = static_cast<std::uint32_t>(L.pairs);
    std::copy(other, other + o, out + m);
    L.pairs += o;
    L.start[i + 1] = static_cast<std::uint32_t>(L.pairs);
    if (contact) L.contact_start[i + 1] = static_cast<std::uint32_t>(L.contact_nbr.size());
  }
}

template <int D>
std::vector<std::uint32_t> owned_cell_order(const ParticleStore<D>& s, const CellGrid<D>& grid,
                                            const CellBox<D>& box) {
  std::vector<std::pair<std::int64_t, ParticleId>> key(s.owned());
  for (std::size_t i = 0; i < s.owned(); ++i) {
    const ICoord<D> c = grid.bin(s.x[i]);
    std::int64_t lin = 0;
    for (int a = D - 1; a >= 0; --a)
      lin = lin * (box.hi[a] - box.lo[a]) +
            std::clamp(c[a] - box.lo[a], 0, box.hi[a] - box.lo[a] - 1);
    key[i] = {lin, s.id[i]};
  }
  std::vector<std::uint32_t> order(s.owned());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
  return order;
}

template class NeighborList<2>;
template class NeighborList<3>;
template void NeighborList<2>::refine(const ParticleStore<2>&, double, double,
                                      std::vector<double>&);
template void NeighborList<3>::refine(const ParticleStore<3>&, double, double,
                                      std::vector<double>&);
template void NeighborList<2>::refine(const ParticleStore<2>&, double, double, std::vector<float>&);
template void NeighborList<3>::refine(const ParticleStore<3>&, double, double, std::vector<float>&);
template std::vector<std::uint32_t> owned_cell_order<2>(const ParticleStore<2>&, const CellGrid<2>&,
                                                        const CellBox<2>&);
template std::vector<std::uint32_t> owned_cell_order<3>(const ParticleStore<3>&, const CellGrid<3>&,
                                                        const CellBox<3>&);

}  // namespace sph
