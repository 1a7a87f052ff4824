#include "common/job_state.h"

#include <algorithm>
#include <cctype>

namespace sph::service {

const char* state_name(v1::JobState s) {
  switch (s) {
    case v1::JOB_STATE_QUEUED:
      return "QUEUED";
    case v1::JOB_STATE_RUNNING:
      return "RUNNING";
    case v1::JOB_STATE_SUCCEEDED:
      return "SUCCEEDED";
    case v1::JOB_STATE_FAILED:
      return "FAILED";
    case v1::JOB_STATE_CANCELLED:
      return "CANCELLED";
    default:
      return "UNSPECIFIED";
  }
}

std::optional<v1::JobState> parse_state(std::string_view name) {
  std::string upper(name);
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::toupper(ch)); });
  if (upper.rfind("JOB_STATE_", 0) == 0) upper = upper.substr(10);
  for (v1::JobState s : {v1::JOB_STATE_QUEUED, v1::JOB_STATE_RUNNING, v1::JOB_STATE_SUCCEEDED,
                         v1::JOB_STATE_FAILED, v1::JOB_STATE_CANCELLED})
    if (upper == state_name(s)) return s;
  return std::nullopt;
}

bool is_terminal(v1::JobState s) {
  return s == v1::JOB_STATE_SUCCEEDED || s == v1::JOB_STATE_FAILED || s == v1::JOB_STATE_CANCELLED;
}

const char* outcome_name(v1::AttemptOutcome o) {
  switch (o) {
    case v1::ATTEMPT_COMPLETED:
      return "COMPLETED";
    case v1::ATTEMPT_FAILED:
      return "FAILED";
    case v1::ATTEMPT_CANCELLED:
      return "CANCELLED";
    case v1::ATTEMPT_INTERRUPTED:
      return "INTERRUPTED";
    case v1::ATTEMPT_LEASE_EXPIRED:
      return "LEASE_EXPIRED";
    default:
      return "RUNNING";
  }
}

}  // namespace sph::service
