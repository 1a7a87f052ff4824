#pragma once
// --json output: protobuf's canonical JSON mapping with the .proto field names (snake_case).
// Note that proto3 JSON writes 64-bit integers as strings.
#include <google/protobuf/message.h>

#include <string>

namespace sph::ctl {

std::string to_json(const google::protobuf::Message& message, bool multiline = false);

}  // namespace sph::ctl
