#pragma once
// A structure-aware mutation of a protobuf message for the fuzzers: one change that keeps the
// message well formed, so the fuzzer explores what validation and the handlers do with
// strange but parseable input instead of stopping at the parser. Debian has no
// libprotobuf-mutator; this is the small part of it the fuzzers need.
#include <google/protobuf/message.h>

#include <random>

namespace sph::fuzz {

// Changes one thing somewhere in `m`: a scalar set to an edge value (0, -1, 1e-300, 1e300,
// NaN, inf, the type's extremes), a string emptied, doubled or made long, an enum set to any
// number, a message field set, cleared or descended into, a repeated field grown by a copy of
// one of its elements (so shape trees nest deeper) or shrunk.
void mutate_message(google::protobuf::Message& m, std::mt19937_64& rng);

}  // namespace sph::fuzz
