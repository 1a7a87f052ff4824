#include "solver/parallel/halo.h"

#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>

namespace sph {
namespace {

template <int D>
std::vector<ICoord<D>> periodic_shifts(const std::array<bool, D>& periodic) {
  std::vector<ICoord<D>> out;
  int total = 1;
  for (int a = 0; a < D; ++a) total *= 3;
  for (int k = 0; k < total; ++k) {
    ICoord<D> s;
    int r = k;
    bool ok = true;
    for (int a = 0; a < D; ++a) {
      s[a] = r % 3 - 1;
      r /= 3;
      if (s[a] != 0 && !periodic[a]) ok = false;
    }
    if (ok) out.push_back(s);
  }
  return out;
}

}  // namespace

template <int D>
void Halo<D>::set_decomposition(Decomposition<D> d) {
  decomp_ = std::move(d);
  targets_.clear();
  const CellBox<D>& mine = my_box();
  for (int r = 0; r < comm_.size(); ++r) {
    CellBox<D> theirs = decomp_.box(r);
    for (int a = 0; a < D; ++a) {
      --theirs.lo[a];
      ++theirs.hi[a];
    }
    for (const auto& s : periodic_shifts<D>(grid_.periodic)) {
      const bool zero = std::all_of(s.begin(), s.end(), [](int v) { return v == 0; });
      if (r == comm_.rank() && zero) continue;
      // Cells c of my box with c + s*n inside their expanded box.
      CellBox<D> cells;
      Vec<D> shift;
      for (int a = 0; a < D; ++a) {
        cells.lo[a] = std::max(mine.lo[a], theirs.lo[a] - s[a] * grid_.n[a]);
        cells.hi[a] = std::min(mine.hi[a], theirs.hi[a] - s[a] * grid_.n[a]);
        shift[a] = s[a] * grid_.length[a];
      }
      if (!cells.empty()) targets_.push_back({r, cells, shift});
    }
  }
  // Peers: the ranks targeted above, and those that target this rank, found by the same
  // rule evaluated from their side (their box against this rank's expanded box).
  CellBox<D> mine_grown = mine;
  for (int a = 0; a < D; ++a) {
    --mine_grown.lo[a];
    ++mine_grown.hi[a];
  }
  std::vector<char> peer(static_cast<size_t>(comm_.size()), 0);
  for (const Target& t : targets_) peer[static_cast<size_t>(t.rank)] = 1;
  for (int r = 0; r < comm_.size(); ++r) {
    if (r == comm_.rank()) continue;
    const CellBox<D>& theirs = decomp_.box(r);
    for (const auto& s : periodic_shifts<D>(grid_.periodic)) {
      CellBox<D> cells;
      for (int a = 0; a < D; ++a) {
        cells.lo[a] = std::max(theirs.lo[a], mine_grown.lo[a] - s[a] * grid_.n[a]);
        cells.hi[a] = std::min(theirs.hi[a], mine_grown.hi[a] - s[a] * grid_.n[a]);
      }
      if (!cells.empty()) peer[static_cast<size_t>(r)] = 1;
    }
  }
  peers_.clear();
  for (int r = 0; r < comm_.size(); ++r)
    if (r != comm_.rank() && peer[static_cast<size_t>(r)]) peers_.push_back(r);
}

template <int D>
void Halo<D>::lay_out_recv_buffer() {
  recv_displ_.assign(recv_bytes_.size(), 0);
  std::size_t total = 0;
  for (std::size_t r = 0; r < recv_bytes_.size(); ++r) {
    recv_displ_[r] = static_cast<int>(total);
    total += static_cast<std::size_t>(recv_bytes_[r]);
  }
  recv_buf_.resize(total);
}

template <int D>
void Halo<D>::exchange() {
  const int P = comm_.size();
  std::vector<int> send_bytes(static_cast<size_t>(P)), send_displ(static_cast<size_t>(P));
  std::size_t total = 0;
  for (int r = 0; r < P; ++r) {
    send_bytes[static_cast<size_t>(r)] = static_cast<int>(send_buf_[static_cast<size_t>(r)].size());
    send_displ[static_cast<size_t>(r)] = static_cast<int>(total);
    total += send_buf_[static_cast<size_t>(r)].size();
  }
  if (total > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::runtime_error("halo exchange over 2 GiB from one rank: use more ranks");
  std::vector<std::byte> flat(total);
  for (int r = 0; r < P; ++r)
    if (!send_buf_[static_cast<size_t>(r)].empty())
      std::memcpy(flat.data() + send_displ[static_cast<size_t>(r)],
                  send_buf_[static_cast<size_t>(r)].data(),
                  send_buf_[static_cast<size_t>(r)].size());
  const double t0 = MPI_Wtime();
  recv_bytes_.assign(static_cast<size_t>(P), 0);
  MPI_Alltoall(send_bytes.data(), 1, MPI_INT, recv_bytes_.data(), 1, MPI_INT, comm_.raw());
  lay_out_recv_buffer();
  MPI_Alltoallv(flat.data(), send_bytes.data(), send_displ.data(), MPI_BYTE, recv_buf_.data(),
                recv_bytes_.data(), recv_displ_.data(), MPI_BYTE, comm_.raw());
  comm_seconds_ += MPI_Wtime() - t0;
}

template <int D>
void Halo<D>::exchange_with_peers(bool recv_sizes_known) {
  const int P = comm_.size(), me = comm_.rank();
  constexpr int kCountTag = 7301, kDataTag = 7302;
  for (const int r : peers_)
    if (send_buf_[static_cast<size_t>(r)].size() >
        static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw std::runtime_error("halo exchange over 2 GiB to one rank: use more ranks");
  const double t0 = MPI_Wtime();
  if (!recv_sizes_known) {
    recv_bytes_.assign(static_cast<size_t>(P), 0);
    peer_counts_.assign(2 * peers_.size(), 0);
    requests_.clear();
    for (std::size_t k = 0; k < peers_.size(); ++k) {
      requests_.emplace_back();
      MPI_Irecv(&peer_counts_[k], 1, MPI_INT, peers_[k], kCountTag, comm_.raw(), &requests_.back());
    }
    for (std::size_t k = 0; k < peers_.size(); ++k) {
      peer_counts_[peers_.size() + k] =
          static_cast<int>(send_buf_[static_cast<size_t>(peers_[k])].size());
      requests_.emplace_back();
      MPI_Isend(&peer_counts_[peers_.size() + k], 1, MPI_INT, peers_[k], kCountTag, comm_.raw(),
                &requests_.back());
    }
    MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
    for (std::size_t k = 0; k < peers_.size(); ++k)
      recv_bytes_[static_cast<size_t>(peers_[k])] = peer_counts_[k];
    recv_bytes_[static_cast<size_t>(me)] =
        static_cast<int>(send_buf_[static_cast<size_t>(me)].size());
  }
  lay_out_recv_buffer();
  requests_.clear();
  for (const int r : peers_) {
    requests_.emplace_back();
    MPI_Irecv(recv_buf_.data() + recv_displ_[static_cast<size_t>(r)],
              recv_bytes_[static_cast<size_t>(r)], MPI_BYTE, r, kDataTag, comm_.raw(),
              &requests_.back());
  }
  for (const int r : peers_) {
    auto& buf = send_buf_[static_cast<size_t>(r)];
    requests_.emplace_back();
    MPI_Isend(buf.data(), static_cast<int>(buf.size()), MPI_BYTE, r, kDataTag, comm_.raw(),
              &requests_.back());
  }
  // Periodic images of this rank's own particles travel by copy.
  const auto& self = send_buf_[static_cast<size_t>(me)];
  if (!self.empty())
    std::memcpy(recv_buf_.data() + recv_displ_[static_cast<size_t>(me)], self.data(), self.size());
  MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  comm_seconds_ += MPI_Wtime() - t0;
}

template <int D>
void Halo<D>::pack(const ParticleStore<D>& s, const std::vector<ColumnBase*>& cols,
                   bool shift_positions) {
  const int P = comm_.size();
  send_buf_.resize(static_cast<size_t>(P));
  for (int r = 0; r < P; ++r) {
    const auto& idx = send_idx_[static_cast<size_t>(r)];
    auto& buf = send_buf_[static_cast<size_t>(r)];
    std::size_t bytes = 0;
    for (const ColumnBase* c : cols) bytes += c->elem_bytes() * idx.size();
    buf.resize(bytes);
    std::byte* out = buf.data();
    for (const ColumnBase* c : cols) {
      const std::size_t e = c->elem_bytes();
      const std::byte* src = c->bytes();
      if (shift_positions && c == &s.x) {
        const auto& sh = send_shift_[static_cast<size_t>(r)];
        for (std::size_t k = 0; k < idx.size(); ++k) {
          const Vec<D> xs = s.x[idx[k]] + sh[k];
          std::memcpy(out, &xs, e);
          out += e;
        }
      } else {
        for (const std::uint32_t i : idx) {
          std::memcpy(out, src + i * e, e);
          out += e;
        }
      }
    }
  }
}

template <int D>
void Halo<D>::unpack(const std::vector<ColumnBase*>& cols, std::size_t first) {
  std::size_t dst = first;
  for (int r = 0; r < comm_.size(); ++r) {
    const std::size_t n = static_cast<std::size_t>(recv_particles_[static_cast<size_t>(r)]);
    if (n == 0) continue;  // memcpy from a null pointer is undefined even for 0 bytes
    const std::byte* in = recv_buf_.data() + recv_displ_[static_cast<size_t>(r)];
    for (ColumnBase* c : cols) {
      const std::size_t e = c->elem_bytes();
      std::memcpy(c->bytes() + dst * e, in, n * e);
      in += n * e;
    }
    dst += n;
  }
}

template <int D>
void Halo<D>::migrate(ParticleStore<D>& s) {
  s.drop_ghosts();
  const int P = comm_.size(), me = comm_.rank();
  send_idx_.assign(static_cast<size_t>(P), {});
  send_shift_.assign(static_cast<size_t>(P), {});
  std::vector<std::uint32_t> keep;
  keep.reserve(s.owned());
  const CellBox<D>& mine = my_box();
  for (std::size_t i = 0; i < s.owned(); ++i) {
    Vec<D>& x = s.x[i];
    for (int a = 0; a < D; ++a) {
      if (!grid_.periodic[a]) continue;
      if (x[a] < grid_.lo[a] || x[a] >= grid_.lo[a] + grid_.length[a]) {
        // A prescribed wall may be many periods away; fluid particles are at most one.
        double r = std::fmod(x[a] - grid_.lo[a], grid_.length[a]);
        if (r < 0) r += grid_.length[a];
        x[a] = grid_.lo[a] + r;
      }
    }
    const ICoord<D> c = grid_.canonical(grid_.coord(x));
    const int owner = mine.contains(c) ? me : decomp_.owner(c);
    if (owner == me)
      keep.push_back(static_cast<std::uint32_t>(i));
    else
      send_idx_[static_cast<size_t>(owner)].push_back(static_cast<std::uint32_t>(i));
  }
  migrated_ids_.assign(static_cast<size_t>(P), {});
  for (int r = 0; r < P; ++r)
    for (const std::uint32_t i : send_idx_[static_cast<size_t>(r)])
      migrated_ids_[static_cast<size_t>(r)].push_back(s.id[i]);
  std::vector<ColumnBase*> cols;
  for (const auto& c : s.columns())
    if (c->persistent()) cols.push_back(c.get());
  pack(s, cols, false);
  exchange();
  // Particle counts follow from bytes: every migrated particle carries the same columns.
  const std::size_t per = s.persistent_bytes_per_particle();
  recv_particles_.assign(static_cast<size_t>(P), 0);
  std::size_t incoming = 0;
  for (int r = 0; r < P; ++r) {
    recv_particles_[static_cast<size_t>(r)] =
        static_cast<int>(static_cast<std::size_t>(recv_bytes_[static_cast<size_t>(r)]) / per);
    incoming += static_cast<std::size_t>(recv_particles_[static_cast<size_t>(r)]);
  }
  if (keep.size() != s.owned()) s.reorder_owned(keep);
  const std::size_t n0 = s.owned();
  s.resize(n0 + incoming, n0 + incoming);
  unpack(cols, n0);
}

template <int D>
void Halo<D>::build_ghosts(ParticleStore<D>& s) {
  s.drop_ghosts();
  const int P = comm_.size();
  send_idx_.assign(static_cast<size_t>(P), {});
  send_shift_.assign(static_cast<size_t>(P), {});
  if (!targets_.empty()) {
    const CellBox<D>& mine = my_box();
    for (std::size_t i = 0; i < s.owned(); ++i) {
      // Canonical like in migrate(): a wall particle exactly on (or beyond) the domain's
      // upper edge lies in the clamped last cell, and its neighbours on other ranks need it.
      const ICoord<D> c = grid_.canonical(grid_.coord(s.x[i]));
      // Interior cells are needed by nobody: skip the target scan for them.
      bool interior = true;
      for (int a = 0; a < D; ++a)
        if (c[a] <= mine.lo[a] || c[a] >= mine.hi[a] - 1) interior = false;
      if (interior) continue;
      for (const Target& t : targets_) {
        if (!t.cells.contains(c)) continue;
        send_idx_[static_cast<size_t>(t.rank)].push_back(static_cast<std::uint32_t>(i));
        send_shift_[static_cast<size_t>(t.rank)].push_back(t.shift);
      }
    }
  }
  std::vector<ColumnBase*> cols;
  for (const auto& c : s.columns())
    if (c->ghost()) cols.push_back(c.get());
  std::size_t per = 0;
  for (const ColumnBase* c : cols) per += c->elem_bytes();
  pack(s, cols, true);
  exchange_with_peers(false);
  recv_particles_.assign(static_cast<size_t>(P), 0);
  std::size_t incoming = 0;
  for (int r = 0; r < P; ++r) {
    recv_particles_[static_cast<size_t>(r)] =
        static_cast<int>(static_cast<std::size_t>(recv_bytes_[static_cast<size_t>(r)]) / per);
    incoming += static_cast<std::size_t>(recv_particles_[static_cast<size_t>(r)]);
  }
  const std::size_t n0 = s.owned();
  s.resize(n0 + incoming, n0);
  unpack(cols, n0);
}

template <int D>
void Halo<D>::set_recv_bytes(const std::vector<ColumnBase*>& cols) {
  std::size_t per = 0;
  for (const ColumnBase* c : cols) per += c->elem_bytes();
  recv_bytes_.resize(static_cast<size_t>(comm_.size()));
  for (int r = 0; r < comm_.size(); ++r)
    recv_bytes_[static_cast<size_t>(r)] =
        static_cast<int>(per * static_cast<std::size_t>(recv_particles_[static_cast<size_t>(r)]));
}

template <int D>
void Halo<D>::update(ParticleStore<D>& s, std::initializer_list<ColumnBase*> list) {
  std::vector<ColumnBase*> cols(list);
  pack(s, cols, true);  // positions, if listed, shifted for periodic images as when built
  set_recv_bytes(cols);
  exchange_with_peers(true);
  unpack(cols, s.owned());
}

template <int D>
void Halo<D>::refresh_ghosts(ParticleStore<D>& s) {
  std::vector<ColumnBase*> cols;
  for (const auto& c : s.columns())
    if (c->ghost()) cols.push_back(c.get());
  pack(s, cols, true);
  set_recv_bytes(cols);
  exchange_with_peers(true);
  unpack(cols, s.owned());
}

template <int D>
std::vector<std::vector<std::byte>> Halo<D>::exchange_bytes(
    const std::vector<std::vector<std::byte>>& send) {
  send_buf_ = send;
  exchange();
  std::vector<std::vector<std::byte>> out(static_cast<size_t>(comm_.size()));
  for (int r = 0; r < comm_.size(); ++r) {
    const std::byte* b = recv_buf_.data() + recv_displ_[static_cast<size_t>(r)];
    out[static_cast<size_t>(r)].assign(b, b + recv_bytes_[static_cast<size_t>(r)]);
  }
  return out;
}

template class Halo<2>;
template class Halo<3>;

}  // namespace sph
