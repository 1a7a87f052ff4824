#pragma once
// Names of job states and attempt outcomes as users see and type them ("RUNNING").
#include <optional>
#include <string>
#include <string_view>

#include "sph/v1/service.pb.h"

namespace sph::service {

const char* state_name(v1::JobState s);
// Accepts "RUNNING", "running" or "JOB_STATE_RUNNING".
std::optional<v1::JobState> parse_state(std::string_view name);
bool is_terminal(v1::JobState s);

const char* outcome_name(v1::AttemptOutcome o);

}  // namespace sph::service
