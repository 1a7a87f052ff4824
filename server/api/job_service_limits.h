#pragma once
// What one submit and all unfinished jobs together may ask for (server/config.h).

namespace sph::server::api {

struct JobServiceLimits {
  double max_particles = 0;         // per case, 0 = no limit
  double max_memory_bytes = 0;      // per case (estimate_case().bytes), 0 = no limit
  double max_queued_jobs = 0;       // queued + running jobs, 0 = no limit
  double max_queued_particles = 0;  // their estimated particles, 0 = no limit
  int max_streams_per_client = 256;
};

}  // namespace sph::server::api
