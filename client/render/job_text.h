#pragma once
// Human-readable text for jobs and events (the non-JSON output of sphctl).
#include <cstdint>
#include <string>

#include "sph/v1/service.pb.h"

namespace sph::ctl {

std::string format_bytes(double bytes);            // "12.3 MiB"
std::string format_duration(double seconds);       // "1:02:03", "0:05", "?" when negative
std::string format_count(double n);                // "1.23M", "456k", "789"
std::string format_time_ms(std::int64_t unix_ms);  // local "2024-05-01 12:00:03", "-" for 0

// "4 levels, refined by 1.414 from the case's dx" or "3 levels, dx = 0.04 0.02 0.01".
std::string study_summary(const v1::StudySpec& spec);

// One line of progress (a study's starts with "level 2/4 (dx = ..., ladder 31.0%) "): "step 1200  t
// = 0.12/0.5 s (24.0%)  dt = 1e-4  3.4M p-steps/s  ETA 0:12".
std::string progress_summary(const v1::ProgressInfo& p);

// `sphctl status`: a block of lines.
std::string describe_job(const v1::Job& job);

// `sphctl list`: a header and rows.
std::string job_table_header();
std::string job_table_row(const v1::Job& job);

// `sphctl watch` on a pipe: one line per event.
std::string event_line(const v1::JobEvent& event);

}  // namespace sph::ctl
