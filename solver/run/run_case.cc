#include "solver/run/run_case.h"

#include <filesystem>

#include "case/validate.h"
#include "solver/core/kernel.h"
#include "solver/io/hdf5.h"
#include "solver/run/simulation.h"

namespace sph {

const char* to_string(RunStatus s) {
  switch (s) {
    case RunStatus::kCompleted:
      return "completed";
    case RunStatus::kCancelled:
      return "cancelled";
    case RunStatus::kInterrupted:
      return "interrupted";
    case RunStatus::kUnstable:
      return "unstable";
    case RunStatus::kError:
      return "error";
  }
  return "error";
}

namespace {
template <int D, class K>
RunOutcome run_with(const v1::Case& c, const Comm& comm, const RunOptions& o) {
  Simulation<D, K> sim(c, comm, o);
  return sim.run();
}
}  // namespace

RunOutcome run_case(const v1::Case& c, MPI_Comm comm_raw, const RunOptions& options) {
  RunOutcome out;
  h5::silence_errors();
  const auto errors = validate_case(c);
  if (!errors.empty()) {
    out.status = RunStatus::kError;
    out.message = "invalid case: " + join_errors(errors);
    return out;
  }
  if (options.output_dir.empty()) {
    out.status = RunStatus::kError;
    out.message = "no output directory given";
    return out;
  }
  try {
    const Comm comm(comm_raw);
    // Result metadata is written collectively: every rank must pass the same strings, so
    // rank 0's are the ones used (callers often know them on rank 0 only).
    RunOptions o = options;
    o.case_text = comm.broadcast(o.case_text);
    o.output_dir = comm.broadcast(o.output_dir);
    std::string flat;
    for (const auto& [k, v] : o.metadata) flat += k + '\0' + v + '\0';
    flat = comm.broadcast(flat);
    o.metadata.clear();
    for (std::size_t pos = 0; pos < flat.size();) {
      const std::size_t a = flat.find('\0', pos), b = flat.find('\0', a + 1);
      o.metadata[flat.substr(pos, a - pos)] = flat.substr(a + 1, b - a - 1);
      pos = b + 1;
    }
    if (comm.root()) std::filesystem::create_directories(o.output_dir);
    comm.barrier();
    const bool wendland = c.kernel() == v1::WENDLAND_C2;
    if (c.dimension() == 2)
      return wendland ? run_with<2, WendlandC2<2>>(c, comm, o)
                      : run_with<2, QuinticSpline<2>>(c, comm, o);
    return wendland ? run_with<3, WendlandC2<3>>(c, comm, o)
                    : run_with<3, QuinticSpline<3>>(c, comm, o);
  } catch (const std::exception& e) {
    out.status = RunStatus::kError;
    out.message = e.what();
  }
  return out;
}

}  // namespace sph
