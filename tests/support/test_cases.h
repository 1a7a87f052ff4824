#pragma once
// Helpers for tests: load a case from cases/ and run it in-process.
#include <filesystem>
#include <string>

#include "case/load.h"
#include "solver/run/run_case.h"

namespace sph::test {

inline std::string source_dir() {
  return SPHD_SOURCE_DIR;
}

inline v1::Case load_case(const std::string& name) {
  return load_case_file(source_dir() + "/cases/" + name + ".textproto");
}

// The text of cases/NAME.textproto, for tests that edit a shipped case before parsing it.
inline std::string case_text(const std::string& name) {
  return read_text_file(source_dir() + "/cases/" + name + ".textproto");
}

// Replaces every `from` in `s` by `to`; returns how many (0: the text no longer holds it).
inline int replace_all(std::string& s, const std::string& from, const std::string& to) {
  int n = 0;
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
    ++n;
  }
  return n;
}

// Where output_dir(name) puts a run's files (without clearing it).
inline std::string output_dir_path(const std::string& name) {
  return std::string(SPHD_BINARY_DIR) + "/test-output/" + name;
}

// A fresh output directory under the build tree, unique per test.
inline std::string output_dir(const std::string& name) {
  const std::string dir = output_dir_path(name);
  std::filesystem::remove_all(dir);
  return dir;
}

inline RunOutcome run(const v1::Case& c, const std::string& out_dir,
                      MPI_Comm comm = MPI_COMM_WORLD) {
  RunOptions o;
  o.output_dir = out_dir;
  o.quiet = true;
  return run_case(c, comm, o);
}

}  // namespace sph::test
