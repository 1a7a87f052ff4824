#include "solver/io/result_file.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>

namespace sph {
namespace {

// Writes the connectivity of snapshots of `total` particles unless an earlier snapshot of that
// count did; this caller writes rows [offset, offset + local). Collective over the file.
void write_polyvertex(hid_t file, std::uint64_t total, std::uint64_t offset, std::uint64_t local) {
  const std::string name = polyvertex_dataset(total);
  if (h5::exists(file, name)) return;
  h5::open_or_create_group(file, "/xdmf");
  std::vector<std::int64_t> vertices(local);
  for (std::uint64_t i = 0; i < local; ++i) vertices[i] = static_cast<std::int64_t>(offset + i);
  h5::write_rows(file, name, H5T_NATIVE_INT64, total, offset, local, 1, vertices.data());
}

}  // namespace

ResultFile::ResultFile(const Comm& comm, const std::string& dir)
    : comm_(comm), dir_(dir), h5_(dir + "/result.h5"), xmf_(dir + "/result.xmf") {
  fields_ = {{"velocity", 3, "Float", 8}, {"density", 1, "Float", 8}, {"pressure", 1, "Float", 8},
             {"mass", 1, "Float", 8},     {"id", 1, "Int", 8},        {"kind", 1, "UChar", 1},
             {"material", 1, "UInt", 2}};
}

void ResultFile::put(const std::string& name, const std::vector<double>& row,
                     std::vector<std::uint64_t> shape) {
  if (declaring_) {
    std::uint64_t n = 1;
    for (const std::uint64_t d : shape) n *= d;
    if (n != row.size())
      throw std::logic_error("series " + name + ": a sample of " + std::to_string(row.size()) +
                             " values for a declared shape of " + std::to_string(n));
    series_[name].row = std::move(shape);
    return;
  }
  const auto it = series_.find(name);
  if (it == series_.end())
    throw std::logic_error("series " + name + " was sampled but not declared");
  Series& s = it->second;
  s.pending.insert(s.pending.end(), row.begin(), row.end());
  ++s.pending_rows;
}

void ResultFile::set_meta(const std::map<std::string, std::string>& kv) {
  h5::Handle f = h5::open_file(h5_, comm_.raw(), false);
  h5::Handle g = h5::open_or_create_group(f, "/meta");
  for (const auto& [k, v] : kv) h5::write_attribute(g, k, v);
}

void ResultFile::create(const std::map<std::string, std::string>& meta) {
  if (comm_.root()) std::filesystem::create_directories(dir_);
  comm_.barrier();
  {
    h5::Handle f = h5::open_file(h5_, comm_.raw(), true);
    h5::Handle g = h5::open_or_create_group(f, "/meta");
    for (const auto& [k, v] : meta) h5::write_attribute(g, k, v);
    h5::open_or_create_group(f, "/snapshots");
    // Empty series so readers find every declared series even before the first sample.
    for (const auto& [name, s] : series_)
      h5::append_rows(f, "/series/" + name, s.row, {}, 0, comm_.root());
  }
  snapshots_.clear();
  if (comm_.root()) write_xdmf_on_root();
}

bool ResultFile::carry_over(const std::string& previous, double t,
                            const std::map<std::string, std::string>& meta) {
  namespace fs = std::filesystem;
  int ok = 0;
  if (comm_.root()) {
    std::error_code ec;
    fs::create_directories(dir_, ec);
    const bool same = fs::exists(previous) && fs::exists(h5_) && fs::equivalent(previous, h5_, ec);
    if (!previous.empty() && fs::exists(previous)) {
      ok = 1;
      if (!same) ok = fs::copy_file(previous, h5_, fs::copy_options::overwrite_existing, ec) && !ec;
    }
  }
  // The surgery on the copied file (deleting what came after t) is done by the root alone:
  // on several ranks every metadata change must be collective and identical, and the
  // deletions and shrinks here deadlocked 4 ranks in H5Fclose.
  std::vector<double> kept_time;
  std::vector<std::uint64_t> kept_count;
  if (comm_.root() && ok) {
    try {
      h5::Handle f = h5::open_file(h5_, MPI_COMM_SELF, false);
      const double eps = 1e-12 * std::max(1.0, std::abs(t));
      // Snapshots after t belong to the lost part of the earlier attempt.
      for (int k = 0;; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "/snapshots/%06d", k);
        if (!h5::exists(f, name)) break;
        h5::Handle g(H5Gopen2(f, name, H5P_DEFAULT), H5Gclose, name);
        const double ts = h5::read_double_attribute(g, "time");
        const auto count = static_cast<std::uint64_t>(h5::read_int_attribute(g, "count"));
        if (ts > t + eps) {
          g.reset();
          h5::check(H5Ldelete(f, name, H5P_DEFAULT), std::string("delete ") + name);
        } else {
          kept_time.push_back(ts);
          kept_count.push_back(count);
          // A result written before the connectivity was: result.xmf names it now.
          write_polyvertex(f, count, 0, count);
        }
      }
      // Rows sampled after t go too. A series keeps as many rows as its group's time column
      // has up to t (groups without one, like the phase counters, are sampled with the
      // diagnostics); every count is read before anything is truncated, so no series is cut
      // by a time column that was already cut.
      std::map<std::string, std::uint64_t> keep;  // time column -> rows up to t
      auto clock_of = [&](const std::string& full) {
        const std::string own = full.substr(0, full.rfind('/')) + "/time";
        return h5::exists(f, own) ? own : std::string("/series/diagnostics/time");
      };
      for (const auto& [name, s] : series_) {
        const std::string clock = clock_of("/series/" + name);
        if (keep.count(clock) || !h5::exists(f, clock)) continue;
        const auto times = h5::read_vector(f, clock);
        std::uint64_t n = 0;
        while (n < times.size() && times[n] <= t + eps) ++n;
        keep[clock] = n;
      }
      for (const auto& [name, s] : series_) {
        const std::string full = "/series/" + name, clock = clock_of(full);
        if (!h5::exists(f, full) || !keep.count(clock)) {
          h5::append_rows(f, full, s.row, {}, 0, true);
          continue;
        }
        h5::truncate_rows(f, full, keep.at(clock));
      }
      h5::Handle g = h5::open_or_create_group(f, "/meta");
      for (const auto& [k, v] : meta) h5::write_attribute(g, k, v);
    } catch (const h5::Error&) {
      ok = 0;
    }
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm_.raw());
  // Every rank learns the kept snapshots (a prefix: snapshot times increase).
  std::uint64_t n = kept_time.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm_.raw());
  kept_time.resize(n);
  kept_count.resize(n);
  MPI_Bcast(kept_time.data(), static_cast<int>(n), MPI_DOUBLE, 0, comm_.raw());
  MPI_Bcast(kept_count.data(), static_cast<int>(n), MPI_UINT64_T, 0, comm_.raw());
  snapshots_.clear();
  for (std::uint64_t k = 0; k < n; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "/snapshots/%06d", static_cast<int>(k));
    snapshots_.push_back({name, kept_time[k], kept_count[k]});
  }
  int all = 0;
  MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, comm_.raw());
  if (!all) {
    create(meta);
    return false;
  }
  if (comm_.root()) write_xdmf_on_root();
  return true;
}

void ResultFile::flush_into(hid_t file) {
  for (auto& [name, s] : series_) {
    h5::append_rows(file, "/series/" + name, s.row, s.pending, s.pending_rows, comm_.root());
    s.pending.clear();
    s.pending_rows = 0;
  }
}

void ResultFile::flush() {
  h5::Handle f = h5::open_file(h5_, comm_.raw(), false);
  flush_into(f);
}

template <int D>
void ResultFile::write_snapshot(const ParticleStore<D>& s, double t, std::int64_t step) {
  const std::uint64_t local = s.owned();
  std::uint64_t offset = 0, total = 0;
  MPI_Exscan(&local, &offset, 1, MPI_UINT64_T, MPI_SUM, comm_.raw());
  if (comm_.root()) offset = 0;
  MPI_Allreduce(&local, &total, 1, MPI_UINT64_T, MPI_SUM, comm_.raw());

  char name[32];
  std::snprintf(name, sizeof name, "/snapshots/%06zu", snapshots_.size());
  {
    h5::Handle f = h5::open_file(h5_, comm_.raw(), false);
    h5::Handle g = h5::open_or_create_group(f, name);
    h5::write_attribute(g, "time", t);
    h5::write_attribute(g, "step", static_cast<std::int64_t>(step));
    h5::write_attribute(g, "count", static_cast<std::int64_t>(total));
    // Vectors are written with three components (z = 0 in 2D) for ParaView.
    std::vector<double> buf(3 * local, 0.0);
    auto vec3 = [&](const Column<Vec<D>>& c, const char* field) {
      for (std::uint64_t i = 0; i < local; ++i)
        for (int a = 0; a < D; ++a) buf[3 * i + static_cast<std::uint64_t>(a)] = c[i][a];
      h5::write_rows(g, field, H5T_NATIVE_DOUBLE, total, offset, local, 3, buf.data());
    };
    vec3(s.x, "position");
    vec3(s.v, "velocity");
    h5::write_rows(g, "density", H5T_NATIVE_DOUBLE, total, offset, local, 1, s.rho.data());
    h5::write_rows(g, "pressure", H5T_NATIVE_DOUBLE, total, offset, local, 1, s.p.data());
    h5::write_rows(g, "mass", H5T_NATIVE_DOUBLE, total, offset, local, 1, s.m.data());
    h5::write_rows(g, "id", H5T_NATIVE_INT64, total, offset, local, 1, s.id.data());
    h5::write_rows(g, "kind", H5T_NATIVE_UINT8, total, offset, local, 1, s.kind.data());
    h5::write_rows(g, "material", H5T_NATIVE_UINT16, total, offset, local, 1, s.material.data());
    for (const auto& x : extra_)
      h5::write_rows(g, x.column->name(), x.type, total, offset, local, 1, x.column->bytes());
    g.reset();
    write_polyvertex(f, total, offset, local);
    flush_into(f);
  }
  snapshots_.push_back({name, t, total});
  if (comm_.root()) write_xdmf_on_root();
}

void ResultFile::write_xdmf_on_root() const {
  std::vector<XdmfField> fields = fields_;
  for (const auto& f : extra_) fields.push_back({f.column->name(), 1, f.xdmf_type, f.precision});
  write_xdmf(xmf_, std::filesystem::path(h5_).filename().string(), snapshots_, fields);
}

template void ResultFile::write_snapshot<2>(const ParticleStore<2>&, double, std::int64_t);
template void ResultFile::write_snapshot<3>(const ParticleStore<3>&, double, std::int64_t);

}  // namespace sph
