#pragma once
// Thin helpers over an MPI communicator. Every collective the solver makes goes through here,
// so the 1-rank and N-rank runs share one code path.
#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

namespace sph {

class Comm {
 public:
  explicit Comm(MPI_Comm c) : comm_(c) {
    MPI_Comm_rank(c, &rank_);
    MPI_Comm_size(c, &size_);
  }
  MPI_Comm raw() const { return comm_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  double max(double v) const {
    MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, comm_);
    return v;
  }
  double min(double v) const {
    MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MIN, comm_);
    return v;
  }
  double sum(double v) const {
    MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_SUM, comm_);
    return v;
  }
  std::int64_t sum(std::int64_t v) const {
    MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT64_T, MPI_SUM, comm_);
    return v;
  }
  std::int64_t max(std::int64_t v) const {
    MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT64_T, MPI_MAX, comm_);
    return v;
  }
  std::int64_t min(std::int64_t v) const {
    MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT64_T, MPI_MIN, comm_);
    return v;
  }
  void max_inplace(std::vector<double>& v) const {
    MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_MAX, comm_);
  }
  void sum_inplace(std::vector<double>& v) const {
    MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM, comm_);
  }
  void sum_inplace(std::vector<std::int64_t>& v) const {
    MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_INT64_T, MPI_SUM, comm_);
  }
  void barrier() const { MPI_Barrier(comm_); }
  // Rank 0's string on every rank.
  std::string broadcast(std::string s) const {
    std::int64_t n = static_cast<std::int64_t>(s.size());
    MPI_Bcast(&n, 1, MPI_INT64_T, 0, comm_);
    s.resize(static_cast<size_t>(n));
    MPI_Bcast(s.data(), static_cast<int>(n), MPI_CHAR, 0, comm_);
    return s;
  }
  // Every rank's bytes concatenated in rank order, on every rank.
  std::string allgather(const std::string& mine) const {
    int n = static_cast<int>(mine.size());
    std::vector<int> sizes(static_cast<size_t>(size_)), displ(static_cast<size_t>(size_), 0);
    MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, comm_);
    int total = 0;
    for (int r = 0; r < size_; ++r) {
      displ[static_cast<size_t>(r)] = total;
      total += sizes[static_cast<size_t>(r)];
    }
    std::string out(static_cast<size_t>(total), '\0');
    MPI_Allgatherv(mine.data(), n, MPI_CHAR, out.data(), sizes.data(), displ.data(), MPI_CHAR,
                   comm_);
    return out;
  }
  // The first non-empty string in rank order, on every rank.
  std::string first_non_empty(const std::string& s) const {
    int mine = s.empty() ? size_ : rank_;
    int who = mine;
    MPI_Allreduce(&mine, &who, 1, MPI_INT, MPI_MIN, comm_);
    if (who == size_) return {};
    std::int64_t n = rank_ == who ? static_cast<std::int64_t>(s.size()) : 0;
    MPI_Bcast(&n, 1, MPI_INT64_T, who, comm_);
    std::string out = rank_ == who ? s : std::string(static_cast<size_t>(n), '\0');
    MPI_Bcast(out.data(), static_cast<int>(n), MPI_CHAR, who, comm_);
    return out;
  }

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
};

}  // namespace sph
