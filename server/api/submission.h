#pragma once
// Accepting a submitted case: everything Submit checks, hashes and stores, apart from the gRPC
// call that carries it. Nothing is stored for a request that is refused.
#include <grpcpp/server_context.h>
#include <grpcpp/support/status.h>

#include "server/api/auth.h"
#include "server/api/job_service_limits.h"
#include "server/store/job_store.h"
#include "sph/v1/service.pb.h"

namespace sph::server::api {

struct Submission {
  store::JobStore& store;
  const TokenCheck& auth;
  const JobServiceLimits& limits;
};

// Checks the request (token, request id, case text, validation with the limits, the stored
// text's bound, the study ladder), stores the job (or finds the one an earlier submit with the
// same request id stored) and fills `response`. Refusals name the field; the fields of the
// case that failed validation are also added as `sph-invalid-field` trailing metadata.
grpc::Status accept_submission(const Submission& s, grpc::ServerContextBase& context,
                               const v1::SubmitRequest& request, v1::SubmitResponse& response);

}  // namespace sph::server::api
