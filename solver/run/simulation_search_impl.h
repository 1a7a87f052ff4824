#pragma once
// Simulation<D, K>: particles to their ranks and neighbours. Migration, ghosts, the
// neighbour lists (fresh, as needed with a Verlet skin, at the reference positions after a
// resume or rebalance, after a change of kind) and load balancing
// (solver/parallel/load_balance.h).
// Included only by simulation_impl.h.

namespace sph {

template <int D, class K>
void Simulation<D, K>::decompose_by_histogram() {
  halo_.set_decomposition(balanced_decomposition<D>(s_, grid_, comm_, nullptr));
}

template <int D, class K>
void Simulation<D, K>::exchange_and_search(Search mode) {
  // Counted: searches that every rank count makes alike (not a rebalance's or a resume's).
  const bool counted = mode != Search::kAtReference;
  if (skin_ == 0) mode = Search::kFresh;  // the lists of the positions now are all there is
  bool refreshed = false;
  if (mode == Search::kKindsChanged) {
    {
      Timer tm(timer("halo_exchange"));
      halo_.refresh_ghosts(s_);
    }
    Timer tm(timer("neighbor_search"));
    const ContactQuery q = contact_query();
    nl_.reclassify_candidates(s_, contact_ ? &q : nullptr, skin_);
    refreshed = true;  // refined below
  }
  if (mode == Search::kAsNeeded) {
    Timer tm(timer("neighbor_search"));
    mode = moved_half_the_skin() ? Search::kFresh : Search::kAsNeeded;
  }
  if (mode == Search::kFresh) {
    {
      Timer tm(timer("halo_exchange"));
      migrate();
      // Keep owned particles in cell order so neighbours are close in memory.
      if (step_ - reordered_at_ >= 25) {
        s_.reorder_owned(owned_cell_order(s_, grid_, halo_.my_box()));
        reordered_at_ = step_;
      }
      if (searched_at_) std::copy(s_.x.data(), s_.x.data() + s_.owned(), searched_at_->data());
      halo_.build_ghosts(s_);
    }
    if (counted) ++searches_;
    search_candidates();
  } else if (mode == Search::kAtReference) {
    // Ghosts and candidates as the last search made them: everything placed by the positions
    // it searched at, then the positions now refreshed on the ghosts.
    auto swap_positions = [&] {
      for (std::size_t i = 0; i < s_.owned(); ++i) std::swap(s_.x[i], (*searched_at_)[i]);
    };
    {
      Timer tm(timer("halo_exchange"));
      swap_positions();
      migrate();
      // A rebalance brings particles from other ranks at the end of the rows: back in cell
      // order (by the positions searched at), or every pass misses the cache until the next
      // reordering search.
      s_.reorder_owned(owned_cell_order(s_, grid_, halo_.my_box()));
      reordered_at_ = step_;
      halo_.build_ghosts(s_);
    }
    search_candidates();
    Timer tm(timer("halo_exchange"));
    swap_positions();
    halo_.refresh_ghosts(s_);
  } else if (!refreshed) {
    Timer tm(timer("halo_exchange"));
    halo_.refresh_ghosts(s_);
  }
  if (skin_ > 0) {
    Timer tm(timer("neighbor_search"));
    pk_.refine(nl_, s_, rc_, contact_ ? contact_->candidate_range() : 0.0);
  }
  Timer tm(timer("pair_kernel"));
  if (skin_ > 0)
    pk_.prepare_refined(s_, nl_, kernel_);
  else
    pk_.prepare(s_, nl_, kernel_);
}

template <int D, class K>
ContactQuery Simulation<D, K>::contact_query() const {
  if (!contact_) return {};
  return ContactQuery{bodies_->body_index().data(), contact_->candidate_range(),
                      contact_->with_walls()};
}

// The lists (without a skin) or the Verlet candidates of the positions in s_.x.
template <int D, class K>
void Simulation<D, K>::search_candidates() {
  Timer tm(timer("neighbor_search"));
  const ContactQuery q = contact_query();
  const ContactQuery* query = contact_ ? &q : nullptr;
  if (skin_ > 0)
    nl_.build_candidates(s_, grid_, halo_.ghost_box(), rc_, skin_, query, rigid_all());
  else
    nl_.build(s_, grid_, halo_.ghost_box(), rc_, query, rigid_all());
}

template <int D, class K>
bool Simulation<D, K>::moved_half_the_skin() {
  double largest = 0;
  for (std::size_t i = 0; i < s_.owned(); ++i) {
    Vec<D> d = s_.x[i] - (*searched_at_)[i];
    for (int a = 0; a < D; ++a) {
      // A wall moved by a prescribed motion (or a body placed from its centre) may be whole
      // periods from where it was searched; its ghosts were sent as images of that place.
      if (!grid_.periodic[a] || !(std::abs(d[a]) > 0.5 * grid_.length[a])) continue;
      const double shift = std::round(d[a] / grid_.length[a]) * grid_.length[a];
      s_.x[i][a] -= shift;
      d[a] -= shift;
    }
    largest = std::max(largest, d.squaredNorm());
  }
  return comm_.max(largest) >= 0.25 * skin_ * skin_;
}

// Particles to their owners, with the contact history that belongs to them.
template <int D, class K>
void Simulation<D, K>::migrate() {
  halo_.migrate(s_);
  if (contact_) contact_->migrate_history(halo_);
}

template <int D, class K>
void Simulation<D, K>::maybe_rebalance() {
  // The lists are those of the owned particles now: every caller searched since the last
  // migration.
  const NeighborList<D>* lists = opt_.balance_by_kind ? nullptr : &nl_;
  imbalance_ = work_imbalance(s_, comm_, lists);
  if (comm_.size() <= 1 || imbalance_ <= kRebalanceImbalance) return;
  {
    Timer tm(timer("halo_exchange"));
    const std::vector<std::int64_t> work = global_work_histogram(s_, grid_, comm_, lists);
    Decomposition<D> balanced(grid_, comm_.size(), work);
    if (decomposition_imbalance(balanced, grid_, work) > imbalance_ - kRebalanceGain) return;
    ++rebalances_;
    halo_.set_decomposition(std::move(balanced));
    s_.drop_ghosts();
  }
  // Migration reorders the owned rows and the ghosts change: the next step's contact drift
  // and the probes read the neighbour list before that step searches again. The pairs and
  // their order stay those of the last search, whatever the decomposition.
  exchange_and_search(Search::kAtReference);
  imbalance_ = work_imbalance(s_, comm_, lists);
}

}  // namespace sph
