// bench_memory: the machine's memory bandwidth, the limit of the per-body passes of a frame at 10^6 bodies
// (docs/simulate.md, "Against the goals"). Read (eight independent sums), write (fill) and copy over arrays of
// --mib MiB each (default 512, far beyond the caches), on 1 and 2 threads (each thread its half); bytes moved per
// second, the median of --repeats runs (default 7). Copy counts the bytes read and written.
// Usage: bench_memory [--mib M] [--repeats R]
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

uint64_t read_sum(const uint64_t* p, size_t n) {
  uint64_t s[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (size_t i = 0; i + 8 <= n; i += 8)
    for (int k = 0; k < 8; ++k) s[k] += p[i + size_t(k)];
  return s[0] ^ s[1] ^ s[2] ^ s[3] ^ s[4] ^ s[5] ^ s[6] ^ s[7];
}

// Seconds of one pass of `kind` (0 read, 1 write, 2 copy) over a and b on `threads` threads.
double pass(int kind, std::vector<uint64_t>& a, std::vector<uint64_t>& b, unsigned threads, uint64_t round) {
  const size_t n = a.size();
  std::vector<uint64_t> sums(threads);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> ts;
  for (unsigned t = 0; t < threads; ++t)
    ts.emplace_back([&, t] {
      const size_t lo = n * t / threads, hi = n * (t + 1) / threads;
      if (kind == 0) sums[t] = read_sum(a.data() + lo, hi - lo);
      if (kind == 1) std::fill(b.begin() + std::ptrdiff_t(lo), b.begin() + std::ptrdiff_t(hi), round);
      if (kind == 2) std::memcpy(b.data() + lo, a.data() + lo, (hi - lo) * sizeof(uint64_t));
    });
  for (auto& t : ts) t.join();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (kind == 0 && sums[0] == 42) std::puts("");  // the sums are used
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  size_t mib = 512;
  int repeats = 7;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--mib" || a == "--repeats") && i + 1 < argc) {
      const long v = std::strtol(argv[++i], nullptr, 10);
      if (v < 1) {
        std::fprintf(stderr, "bench_memory: %s must be a positive integer\n", a.c_str());
        return 2;
      }
      if (a == "--mib") mib = size_t(v);
      else repeats = int(v);
    } else {
      std::fprintf(stderr, "usage: bench_memory [--mib M] [--repeats R]\n");
      return 2;
    }
  }
  const size_t n = mib * (size_t(1) << 20) / sizeof(uint64_t);
  std::vector<uint64_t> a(n, 1), b(n, 2);
  const char* names[] = {"read", "write", "copy (read + write)"};
  std::printf("| pass | 1 thread (GB/s) | 2 threads (GB/s) |\n|---|--:|--:|\n");
  for (int kind = 0; kind < 3; ++kind) {
    double rate[2];
    for (unsigned threads = 1; threads <= 2; ++threads) {
      std::vector<double> s;
      for (int r = 0; r < repeats; ++r) s.push_back(pass(kind, a, b, threads, uint64_t(r)));
      std::sort(s.begin(), s.end());
      const double bytes = double(n) * sizeof(uint64_t) * (kind == 2 ? 2 : 1);
      rate[threads - 1] = bytes / s[s.size() / 2] / 1e9;
    }
    std::printf("| %s | %.1f | %.1f |\n", names[kind], rate[0], rate[1]);
  }
  std::printf("\nArrays of %zu MiB, medians of %d passes.\n", mib, repeats);
}
