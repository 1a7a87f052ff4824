// The machine's memory-bandwidth ceiling for the scaling benchmark (not a test): a STREAM-like
// triad a[i] = b[i] + s c[i] (McCalpin's STREAM, "Triad") on 1 and on T threads, each thread
// touching its own part first so that its pages sit near its core. The ratio of the two
// bandwidths bounds the speed-up of any loop that is limited by memory traffic, which the SPH
// pair loops largely are (issue #40: reach the target efficiency or within 10% of this cap).
//
//   bench_stream [--threads T] [--mib M]     (M: size of each of the three arrays, default 256)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

namespace {

// Best bandwidth (GB/s, counting 24 bytes per element: two loads, one store) of `repeats`
// triads over n elements split evenly among `threads` threads.
double triad_bandwidth(std::size_t n, int threads, int repeats) {
  std::vector<double> a(n), b(n), c(n);
  const auto chunk = [&](int t) {
    const std::size_t lo = n * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads);
    const std::size_t hi = n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(threads);
    return std::pair{lo, hi};
  };
  const auto run_all = [&](auto&& body) {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(body, t);
    for (auto& th : pool) th.join();
  };
  run_all([&](int t) {
    const auto [lo, hi] = chunk(t);
    for (std::size_t i = lo; i < hi; ++i) {
      a[i] = 0.0;
      b[i] = 1.0;
      c[i] = 2.0;
    }
  });
  double best = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    run_all([&](int t) {
      const auto [lo, hi] = chunk(t);
      const double s = 3.0;
      for (std::size_t i = lo; i < hi; ++i) a[i] = b[i] + s * c[i];
    });
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::max(best, 24.0 * static_cast<double>(n) / sec / 1e9);
  }
  // Keeps the triad from being optimised away.
  if (a[n / 2] != 7.0) std::fprintf(stderr, "triad gave %g, expected 7\n", a[n / 2]);
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = static_cast<int>(std::thread::hardware_concurrency());
  double mib = 256;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--threads")
      threads = std::max(1, std::atoi(argv[i + 1]));
    else if (a == "--mib")
      mib = std::max(1.0, std::atof(argv[i + 1]));
  }
  const auto n = static_cast<std::size_t>(mib * 1024 * 1024 / sizeof(double));
  const double one = triad_bandwidth(n, 1, 10);
  const double all = triad_bandwidth(n, threads, 10);
  std::printf("bench_stream triad arrays=3x%.0f MiB\n", mib);
  std::printf("  1 thread           %8.2f GB/s\n", one);
  std::printf("  %-2d threads         %8.2f GB/s\n", threads, all);
  std::printf("  bandwidth ratio    %8.2f  (ceiling of the speed-up of a memory-bound loop)\n",
              all / one);
  return 0;
}
