#pragma once
// Particle migration and ghost exchange between rank subdomains, including periodic images.
// One code path for any rank count: on one rank, periodic images are simply ghosts sent to
// itself. A ghost layer is one cell (>= r_c) wide around each subdomain.
#include <initializer_list>
#include <vector>

#include "solver/core/particle_store.h"
#include "solver/parallel/comm.h"
#include "solver/parallel/decomposition.h"

namespace sph {

template <int D>
class Halo {
 public:
  Halo(const CellGrid<D>& grid, const Comm& comm) : grid_(grid), comm_(comm) {}

  void set_decomposition(Decomposition<D> d);
  const Decomposition<D>& decomposition() const { return decomp_; }
  const CellBox<D>& my_box() const { return decomp_.box(comm_.rank()); }
  // Cells of this rank's box plus the ghost layer.
  CellBox<D> ghost_box() const {
    CellBox<D> b = my_box();
    for (int a = 0; a < D; ++a) {
      --b.lo[a];
      ++b.hi[a];
    }
    return b;
  }

  // Wraps periodic coordinates of owned particles into the domain, drops the ghosts, and
  // sends owned particles that left this subdomain to their owners with all persistent
  // columns.
  void migrate(ParticleStore<D>& s);
  // Appends ghost copies of the owned particles that neighbouring subdomains need (periodic
  // images shifted by the domain length) with all `ghost` columns.
  void build_ghosts(ParticleStore<D>& s);
  // Refreshes the listed columns of the ghosts made by the last build_ghosts() (positions
  // shifted as then).
  void update(ParticleStore<D>& s, std::initializer_list<ColumnBase*> cols);
  // Sends all `ghost` columns again to the ghosts of the last build_ghosts() (positions shifted
  // as then): the same ghosts, in the same rows, with the owners' state now. Between two
  // searches of a Verlet list the ghosts must stay those the candidates were listed among.
  void refresh_ghosts(ParticleStore<D>& s);

  // Ids of the particles the last migrate() sent away, per destination rank (state kept by
  // units outside the particle columns, such as contact histories, follows them).
  const std::vector<std::vector<ParticleId>>& migrated_ids() const { return migrated_ids_; }
  // Exchanges per-rank byte buffers (send[r] to rank r); returns what arrived, by source.
  std::vector<std::vector<std::byte>> exchange_bytes(
      const std::vector<std::vector<std::byte>>& send);

  // Seconds spent in MPI exchanges since the last call (for the communication share).
  double take_comm_seconds() {
    const double t = comm_seconds_;
    comm_seconds_ = 0;
    return t;
  }

 private:
  struct Target {
    int rank;
    CellBox<D> cells;  // cells of this rank's box the target needs
    Vec<D> shift;      // added to positions (periodic image)
  };
  // Exchanges per-rank byte buffers with every rank (MPI_Alltoallv); received bytes per source
  // rank land in recv_buf_. For migration, where any rank may receive from any other.
  void exchange();
  // The same with the ghost peers only (point-to-point, non-blocking): a rank waits for its
  // neighbours, not for every rank. recv_sizes_known: recv_bytes_ already holds what each peer
  // sends (a refresh of the ghosts the last build_ghosts() made); otherwise sizes go first.
  void exchange_with_peers(bool recv_sizes_known);
  // recv_displ_ and the size of recv_buf_ from recv_bytes_ (sources in rank order).
  void lay_out_recv_buffer();
  // recv_bytes_ for a refresh of the listed columns of the last build_ghosts()'s ghosts.
  void set_recv_bytes(const std::vector<ColumnBase*>& cols);
  void pack(const ParticleStore<D>& s, const std::vector<ColumnBase*>& cols, bool shift_positions);
  void unpack(const std::vector<ColumnBase*>& cols, std::size_t first);

  CellGrid<D> grid_;
  Comm comm_;
  Decomposition<D> decomp_;
  std::vector<Target> targets_;
  // Ranks other than this one that ghosts go to or come from, ascending (set_decomposition).
  std::vector<int> peers_;
  std::vector<MPI_Request> requests_;
  std::vector<int> peer_counts_;
  std::vector<std::vector<std::uint32_t>> send_idx_;  // per destination rank
  std::vector<std::vector<Vec<D>>> send_shift_;       // per destination rank
  std::vector<int> recv_particles_;                   // per source rank
  std::vector<std::vector<std::byte>> send_buf_;
  std::vector<std::byte> recv_buf_;
  std::vector<int> recv_bytes_, recv_displ_;
  std::vector<std::vector<ParticleId>> migrated_ids_;
  double comm_seconds_ = 0;
};

}  // namespace sph
