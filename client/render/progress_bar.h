#pragma once
// The live progress line of `sphctl watch` on a terminal: a bar with simulated time, ETA and
// throughput, redrawn in place; other events print above it.
#include <chrono>
#include <cstdio>
#include <string>

#include "sph/v1/service.pb.h"

namespace sph::ctl {

class ProgressBar {
 public:
  ProgressBar(std::FILE* out, std::string job_id) : out_(out), job_id_(std::move(job_id)) {}
  ~ProgressBar() { finish(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  void update(const v1::ProgressInfo& p);
  // Prints a whole line above the bar (state changes, checkpoints, ...).
  void message(const std::string& line);
  // Leaves the bar's last state on its own line.
  void finish();

 private:
  void draw(bool force);
  std::FILE* out_;
  std::string job_id_;
  v1::ProgressInfo last_;
  bool have_progress_ = false;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_draw_{};
};

// Columns of the terminal on `fd`, or 80 when unknown.
int terminal_width(int fd);

}  // namespace sph::ctl
