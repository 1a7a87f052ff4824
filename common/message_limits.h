#pragma once
// One size limit for the service's gRPC messages, on the server and on every client channel
// (sphctl, worker pools). A case is accepted only if it fits the messages that carry it later:
// Submit brings it, Claim hands it to a pool and GetJob shows it, each with the job's other
// fields beside it. With a larger receive limit on the server than on the clients, a case
// could be accepted and then never be claimed.
#include <cstddef>

namespace sph::service {

inline constexpr int kMaxMessageBytes = 64 << 20;
// The case text (as the server stores it, normalised) leaves room for the rest of a message.
inline constexpr std::size_t kMaxCaseTextBytes = 48 << 20;
// Texts that come back in every listed job or event are bounded where they enter.
inline constexpr std::size_t kMaxCancelReasonBytes = 1024;
inline constexpr std::size_t kMaxFinishMessageBytes = 4096;  // longer ones are cut, not refused
inline constexpr std::size_t kMaxListedTextBytes = 1024;

}  // namespace sph::service
