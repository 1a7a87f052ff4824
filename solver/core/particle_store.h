#pragma once
// Structure-of-arrays particle storage made of named columns. Particles [0, owned) are owned
// by this rank and evolved here; [owned, size) are ghost copies received from neighbouring
// subdomains (or periodic images). The core columns exist in every run; a physics unit adds
// the columns it needs when it is built, so a case without, say, heat conduction carries no
// temperature storage (per-column byte counts are reported by memory_by_owner()).
//
// Column roles:
//  - persistent columns hold state that survives a step: they move with a particle when it
//    migrates to another rank and are written to checkpoints;
//  - the remaining columns are scratch, recomputed every step (neighbour sums, wall values).
// Ghosts receive the `ghost` columns when they are built each step; a unit that needs a
// column on ghosts later in the step (e.g. density after summation) refreshes it with
// Halo::update() at that point. That is how a unit declares its ghost data dependencies.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "solver/core/types.h"

namespace sph {

class ColumnBase {
 public:
  ColumnBase(std::string name, std::string owner, bool persistent, std::size_t elem_bytes)
      : name_(std::move(name)),
        owner_(std::move(owner)),
        persistent_(persistent),
        ghost_(persistent),
        elem_bytes_(elem_bytes) {}
  virtual ~ColumnBase() = default;
  const std::string& name() const { return name_; }
  const std::string& owner() const { return owner_; }
  bool persistent() const { return persistent_; }
  // Sent to ghosts when they are built (default: the persistent columns). Columns that
  // ghosts need only later in a step are refreshed by Halo::update() instead.
  bool ghost() const { return ghost_; }
  void set_ghost(bool g) { ghost_ = g; }
  // A persistent column added after checkpoints of its case were already written: resuming
  // from one that lacks it starts the column at zero instead of refusing the checkpoint.
  bool zero_if_absent() const { return zero_if_absent_; }
  void set_zero_if_absent(bool z) { zero_if_absent_ = z; }
  std::size_t elem_bytes() const { return elem_bytes_; }
  virtual void resize(std::size_t n) = 0;
  virtual std::size_t capacity_bytes() const = 0;
  virtual std::byte* bytes() = 0;
  virtual const std::byte* bytes() const = 0;
  // dst[i] = src[perm[i]] for i < perm.size(); the column is then perm.size() long.
  virtual void permute(const std::vector<std::uint32_t>& perm) = 0;
  virtual void release_unused() = 0;  // capacity down to the size

 private:
  std::string name_, owner_;
  bool persistent_, ghost_, zero_if_absent_ = false;
  std::size_t elem_bytes_;
};

template <class T>
class Column final : public ColumnBase {
  // Columns are copied bytewise (MPI buffers, checkpoints): plain data or fixed-size Eigen
  // vectors, which are not formally trivially copyable but are plain arrays of doubles.
  static_assert(std::is_trivially_destructible_v<T> && std::is_standard_layout_v<T>,
                "columns are copied bytewise");

 public:
  Column(std::string name, std::string owner, bool persistent)
      : ColumnBase(std::move(name), std::move(owner), persistent, sizeof(T)) {}
  T* data() { return v_.data(); }
  const T* data() const { return v_.data(); }
  T& operator[](std::size_t i) { return v_[i]; }
  const T& operator[](std::size_t i) const { return v_[i]; }
  std::size_t size() const { return v_.size(); }
  // New elements are zero (Eigen vectors are not zeroed by their default constructor). Grows
  // by an eighth beyond n, not by std::vector's doubling: ghosts and migrants change the
  // size a little at each search, and doubling would reserve twice the particles on every
  // rank that ever received one.
  void resize(std::size_t n) override {
    const std::size_t old = v_.size();
    if (n > v_.capacity()) v_.reserve(n + n / 8);
    v_.resize(n);
    if (n > old) std::memset(static_cast<void*>(v_.data() + old), 0, (n - old) * sizeof(T));
  }
  std::size_t capacity_bytes() const override { return v_.capacity() * sizeof(T); }
  void release_unused() override { v_.shrink_to_fit(); }
  std::byte* bytes() override { return reinterpret_cast<std::byte*>(v_.data()); }
  const std::byte* bytes() const override { return reinterpret_cast<const std::byte*>(v_.data()); }
  // The permuted copy replaces the column and the old one is freed: one column's copy at a
  // time, not a second copy of every column kept between reorderings.
  void permute(const std::vector<std::uint32_t>& perm) override {
    std::vector<T> next;
    next.reserve(std::max(v_.capacity(), perm.size()));  // the room resize() made for ghosts
    next.resize(perm.size());
    for (std::size_t i = 0; i < perm.size(); ++i) next[i] = v_[perm[i]];
    v_.swap(next);
  }
  void fill(const T& value) { std::fill(v_.begin(), v_.end(), value); }

 private:
  std::vector<T> v_;
};

template <int D>
class ParticleStore {
  // Declared first: the core column references below are initialised from them.
  std::vector<std::unique_ptr<ColumnBase>> columns_;
  std::map<std::string, std::size_t> index_;
  std::size_t size_ = 0, owned_ = 0;

 public:
  ParticleStore();
  ParticleStore(const ParticleStore&) = delete;
  ParticleStore& operator=(const ParticleStore&) = delete;

  std::size_t size() const { return size_; }
  std::size_t owned() const { return owned_; }
  std::size_t ghosts() const { return size_ - owned_; }

  // Adds a column (or returns the existing one of that name and type).
  template <class T>
  Column<T>& add(const std::string& name, const std::string& owner, bool persistent) {
    if (auto it = index_.find(name); it != index_.end()) return get<T>(name);
    auto col = std::make_unique<Column<T>>(name, owner, persistent);
    col->resize(size_);
    Column<T>& ref = *col;
    index_[name] = columns_.size();
    columns_.push_back(std::move(col));
    return ref;
  }
  template <class T>
  Column<T>& get(const std::string& name) {
    return dynamic_cast<Column<T>&>(*columns_.at(index_.at(name)));
  }
  bool has(const std::string& name) const { return index_.count(name) != 0; }
  ColumnBase& column(const std::string& name) { return *columns_.at(index_.at(name)); }
  const std::vector<std::unique_ptr<ColumnBase>>& columns() const { return columns_; }

  // Resizes every column; new particles are zero-initialised by the caller.
  void resize(std::size_t size, std::size_t owned);
  // Drops all ghosts.
  void drop_ghosts() { resize(owned_, owned_); }
  // Every column's capacity down to its size: once the scene is built and on its ranks, so
  // that the room its construction grew into is not kept for the run.
  void release_unused() {
    for (auto& c : columns_) c->release_unused();
  }
  // Keeps the owned particles listed in `order` (in that order); ghosts are dropped.
  void reorder_owned(const std::vector<std::uint32_t>& order);

  // Bytes per column owner ("core", "transport_velocity", ...), capacities included.
  std::map<std::string, std::size_t> memory_by_owner() const;
  std::size_t persistent_bytes_per_particle() const;

  // Core columns.
  Column<Vec<D>>& x;    // position
  Column<Vec<D>>& v;    // velocity (fluid: evolved; wall/rigid: prescribed motion)
  Column<Vec<D>>& a;    // acceleration from the last force evaluation (KDK needs a^n)
  Column<double>& rho;  // density (walls: Adami 2012 eq. 28, recomputed each step)
  Column<double>& p;    // pressure (walls: Adami 2012 eq. 27)
  Column<double>& m;    // mass
  Column<Kind>& kind;
  Column<std::uint16_t>& material;
  Column<ParticleId>& id;  // global id, unique and stable for the run
};

}  // namespace sph
