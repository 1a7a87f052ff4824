#include "solver/boundaries/particle_ledger.h"

#include <algorithm>
#include <cstring>

namespace sph {

template <int D>
typename ParticleLedger<D>::Totals ParticleLedger<D>::apply(
    ParticleStore<D>& s, const std::vector<std::uint32_t>& parents,
    const std::vector<std::uint32_t>& doomed, std::vector<std::int64_t>& tallies,
    const Comm& comm) {
  // Each rank's message, as int64: [parents, deleted, tallies..., parent ids...].
  const std::size_t head = 2 + tallies.size();
  std::vector<std::int64_t> mine(head + parents.size());
  mine[0] = static_cast<std::int64_t>(parents.size());
  mine[1] = static_cast<std::int64_t>(doomed.size());
  std::copy(tallies.begin(), tallies.end(), mine.begin() + 2);
  for (std::size_t k = 0; k < parents.size(); ++k) mine[head + k] = s.id[parents[k]];
  const std::string all = comm.allgather(
      std::string(reinterpret_cast<const char*>(mine.data()), mine.size() * sizeof(std::int64_t)));
  std::vector<std::int64_t> words(all.size() / sizeof(std::int64_t));
  std::memcpy(words.data(), all.data(), words.size() * sizeof(std::int64_t));

  Totals out;
  std::fill(tallies.begin(), tallies.end(), 0);
  std::vector<ParticleId> ids;  // every rank's parents
  for (std::size_t pos = 0; pos < words.size();) {
    const auto n = static_cast<std::size_t>(words[pos]);
    out.deleted += words[pos + 1];
    for (std::size_t k = 0; k < tallies.size(); ++k) tallies[k] += words[pos + 2 + k];
    ids.insert(ids.end(), words.begin() + static_cast<std::ptrdiff_t>(pos + head),
               words.begin() + static_cast<std::ptrdiff_t>(pos + head + n));
    pos += head + n;
  }
  std::sort(ids.begin(), ids.end());
  out.created = static_cast<std::int64_t>(ids.size());
  const ParticleId base = next_id_;
  next_id_ += out.created;
  if (parents.empty() && doomed.empty()) {
    out.first_new = s.owned();
    return out;
  }

  // Copies: every column, row by row, then the new ids.
  s.drop_ghosts();
  const std::size_t n0 = s.owned(), n1 = n0 + parents.size();
  s.resize(n1, n1);
  for (const auto& c : s.columns()) {
    const std::size_t e = c->elem_bytes();
    std::byte* b = c->bytes();
    for (std::size_t k = 0; k < parents.size(); ++k)
      std::memcpy(b + (n0 + k) * e, b + static_cast<std::size_t>(parents[k]) * e, e);
  }
  for (std::size_t k = 0; k < parents.size(); ++k) {
    const ParticleId parent = s.id[n0 + k];
    s.id[n0 + k] = base + (std::lower_bound(ids.begin(), ids.end(), parent) - ids.begin());
  }
  out.first_new = n0;
  if (doomed.empty()) return out;

  // Deletions: keep every other row in order (the copies stay last).
  std::vector<char> drop(n1, 0);
  for (const std::uint32_t i : doomed) drop[i] = 1;
  std::vector<std::uint32_t> keep;
  keep.reserve(n1 - doomed.size());
  for (std::size_t i = 0; i < n1; ++i)
    if (!drop[i]) keep.push_back(static_cast<std::uint32_t>(i));
  s.reorder_owned(keep);
  out.first_new = n0 - doomed.size();
  return out;
}

template <int D>
void ParticleLedger<D>::save(CheckpointState& state, const std::string& key) const {
  state[key] = static_cast<double>(next_id_);  // exact below 2^53
}

template <int D>
void ParticleLedger<D>::load(const CheckpointState& state, const std::string& key) {
  next_id_ = static_cast<ParticleId>(state_value(state, key));
}

template class ParticleLedger<2>;
template class ParticleLedger<3>;

}  // namespace sph
