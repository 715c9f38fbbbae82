// What a sparse lookup's two dependent reads cost on this processor, apart from the kernels (docs/device-speed.md,
// "Sparse maps and shells"): nanoseconds per group of eight random reads from an in-cache table (its CPU time, the
// best of the repeats), one read a lane (a dense lookup) and two dependent ones (a sparse lookup: the second read's
// address from the first's result), by AVX-512 gathers and by scalar loads. Needs AVX-512 (it says so otherwise).
//   bench_gather [--repeats N]
#include <immintrin.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "bench/bench_common.h"

namespace {

enum Kind { kGather, kScalar, kGatherGather, kScalarScalar, kCount };
const char* const kNames[kCount] = {"one read, gather", "one read, scalar loads", "two dependent reads, gathers",
                                    "two dependent reads, scalar loads"};

// GCC 12's intrinsics fill unused lanes from a self-initialised "undefined" vector, which -Wmaybe-uninitialized
// reports once inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

// Sums the words read for every group of eight indices, as `kind` reads them.
__attribute__((target("avx512f,avx512vl,avx512dq"), noinline)) uint64_t run(const uint64_t* table,
                                                                            const int32_t* idx, size_t n, Kind kind) {
  __m512i acc = _mm512_setzero_si512();
  const uint32_t* t32 = reinterpret_cast<const uint32_t*>(table);
  const __m256i low = _mm256_set1_epi32(4095);
  for (size_t k = 0; k < n; k += 8) {
    const __m256i i = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx + k));
    alignas(32) int32_t a[8];
    _mm256_store_si256(reinterpret_cast<__m256i*>(a), i);
    __m512i v;
    if (kind == kGather) {
      v = _mm512_i32gather_epi64(i, reinterpret_cast<const long long*>(table), 8);
    } else if (kind == kScalar) {
      v = _mm512_setr_epi64(int64_t(table[a[0]]), int64_t(table[a[1]]), int64_t(table[a[2]]), int64_t(table[a[3]]),
                            int64_t(table[a[4]]), int64_t(table[a[5]]), int64_t(table[a[6]]), int64_t(table[a[7]]));
    } else if (kind == kGatherGather) {
      const __m256i e = _mm256_and_si256(_mm256_i32gather_epi32(reinterpret_cast<const int*>(table), i, 4), low);
      v = _mm512_i32gather_epi64(e, reinterpret_cast<const long long*>(table), 8);
    } else {
      v = _mm512_setr_epi64(int64_t(table[t32[a[0]] & 4095]), int64_t(table[t32[a[1]] & 4095]),
                            int64_t(table[t32[a[2]] & 4095]), int64_t(table[t32[a[3]] & 4095]),
                            int64_t(table[t32[a[4]] & 4095]), int64_t(table[t32[a[5]] & 4095]),
                            int64_t(table[t32[a[6]] & 4095]), int64_t(table[t32[a[7]] & 4095]));
    }
    acc = _mm512_add_epi64(acc, v);
  }
  alignas(64) uint64_t out[8];
  _mm512_store_si512(out, acc);
  return out[0] + out[7];
}
#pragma GCC diagnostic pop

}  // namespace

int main(int argc, char** argv) {
  int repeats = 9;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: bench_gather [--repeats N]\n");
      return 2;
    }
  }
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("avx512f") || !__builtin_cpu_supports("avx512vl") ||
      !__builtin_cpu_supports("avx512dq")) {
    std::printf("bench_gather: this processor has no AVX-512\n");
    return 0;
  }
  std::mt19937 rng(1);
  std::vector<uint64_t> table(8192);  // 64 KiB: in cache
  for (uint64_t& w : table) w = rng() & 4095;
  std::vector<int32_t> idx(1 << 16);
  for (int32_t& i : idx) i = int32_t(rng() % 4096);
  std::printf("%s\n\n| reads | ns per group of eight (best of %d) |\n|---|--:|\n",
              voxcd::bench::provenance(argc, argv).c_str(), repeats);
  uint64_t sink = 0;
  for (int k = 0; k < kCount; ++k) {
    double best = 1e30;
    for (int r = 0; r < repeats; ++r) {
      const double t0 = voxcd::bench::thread_cpu_seconds();
      for (int rep = 0; rep < 50; ++rep) sink += run(table.data(), idx.data(), idx.size(), Kind(k));
      best = std::min(best, (voxcd::bench::thread_cpu_seconds() - t0) * 1e9 / (50.0 * double(idx.size() / 8)));
    }
    std::printf("| %s | %.2f |\n", kNames[k], best);
  }
  voxcd::bench::keep(sink);
  return 0;
}
