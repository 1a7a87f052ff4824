// Fuzz target: a case as text, through everything the server does with a submitted case
// before it stores it (parse, validate with the server's default limits, estimate, the
// canonical text). Findings: a crash or sanitizer report anywhere in that path, a case that
// validates but whose estimate breaks the limits it was checked against or is not finite, a
// stored text that does not parse back to the same case, or none within the bound the server
// refuses beyond (server/api/stored_case_text.h).
#include <google/protobuf/stubs/logging.h>
#include <google/protobuf/text_format.h>
#include <google/protobuf/util/message_differencer.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "case/estimate.h"
#include "case/load.h"
#include "case/validate.h"
#include "server/api/stored_case_text.h"
#include "tests/fuzz/fuzz_target.h"
#include "tests/fuzz/proto_mutator.h"

namespace {

using sph::fuzz::fail;

// The server's defaults (server/config.h).
sph::ValidationLimits server_limits() {
  sph::ValidationLimits limits;
  limits.max_particles = 2e7;
  limits.max_memory_bytes = 64.0 * 1073741824.0;
  return limits;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  google::protobuf::SetLogHandler(nullptr);  // parse errors of mutated text are expected
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sph::v1::Case c;
  try {
    c = sph::parse_case_text(text);
  } catch (const sph::CaseLoadError& e) {
    if (std::strlen(e.what()) == 0) fail("a parse error without a message", text);
    return 0;
  }
  const auto limits = server_limits();
  const auto errors = sph::validate_case(c, limits);
  for (const auto& e : errors)
    if (e.message.empty()) fail("a validation error without a message", e.field);
  if (!errors.empty()) return 0;
  const sph::CaseEstimate estimate = sph::estimate_case(c);
  if (!std::isfinite(estimate.total()) || estimate.total() < 1 ||
      estimate.total() > limits.max_particles)
    fail("an accepted case estimated outside the particle limit", std::to_string(estimate.total()));
  if (!std::isfinite(estimate.bytes) || estimate.bytes > limits.max_memory_bytes)
    fail("an accepted case estimated outside the memory limit", std::to_string(estimate.bytes));
  const auto stored_or = sph::server::api::stored_case_text(c, size);
  if (!stored_or)
    fail("an accepted case has no stored text within its bound",
         std::to_string(sph::case_to_text(c).size()) + " canonical bytes from " +
             std::to_string(size));
  const std::string& stored = *stored_or;
  sph::v1::Case again;
  try {
    again = sph::parse_case_text(stored);
  } catch (const sph::CaseLoadError& e) {
    fail("the canonical text does not parse", e.what());
  }
  // NaN never equals itself; validation refuses non-finite numbers, so equality must hold.
  google::protobuf::util::MessageDifferencer differ;
  std::string differences;
  differ.ReportDifferencesToString(&differences);
  if (!differ.Compare(c, again)) fail("the stored text is another case", differences);
  return 0;
}

// Mostly a structural change of a case that parses (see proto_mutator.h), otherwise bytes.
extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size,
                                               std::size_t max_size, unsigned int seed) {
  std::mt19937_64 rng(seed);
  sph::v1::Case c;
  google::protobuf::TextFormat::Parser parser;
  parser.SetRecursionLimit(200);
  if (rng() % 4 != 0 &&
      parser.ParseFromString(std::string(reinterpret_cast<const char*>(data), size), &c)) {
    const int changes = 1 + static_cast<int>(rng() % 3);
    for (int i = 0; i < changes; ++i) sph::fuzz::mutate_message(c, rng);
    std::string out;
    google::protobuf::TextFormat::Printer printer;
    printer.SetSingleLineMode(rng() % 2 == 0);
    if (printer.PrintToString(c, &out) && out.size() <= max_size) {
      std::memcpy(data, out.data(), out.size());
      return out.size();
    }
  }
  return LLVMFuzzerMutate(data, size, max_size);
}
