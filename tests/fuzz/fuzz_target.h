#pragma once
// The libFuzzer entry points every fuzz target defines (tests/fuzz/README.md). Built with
// clang and -fsanitize=fuzzer they are driven by libFuzzer; built with any compiler and
// replay_main.cc they replay saved inputs as a regression test.
#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv);
// libFuzzer's own byte-level mutator, for inputs the structure-aware one cannot parse; the
// replay build never mutates.
extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size);

namespace sph::fuzz {
// A finding: prints what broke and aborts, so libFuzzer saves the input (and a replay fails).
[[noreturn]] void fail(const char* what, const std::string& detail);
}  // namespace sph::fuzz
