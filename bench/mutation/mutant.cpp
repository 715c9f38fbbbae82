// voxcd_mut(k), the DPI-C import of the mutant schema (bench/mutation/schema.py): true for the one mutant this process
// runs, VOXCD_MUTANT (unset or 0: none, the RTL as it is). With VOXCD_MUTANT_REACHED=FILE the process appends to FILE
// at exit the mutants whose site it evaluated (one number a line): a mutant never reached is not elaborated in any
// configuration the suite runs.
#include <svdpi.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace {

constexpr unsigned kMaxMutants = 1u << 16;

unsigned selected() {
  static const unsigned k = [] {
    const char* s = std::getenv("VOXCD_MUTANT");
    return s ? unsigned(std::strtoul(s, nullptr, 10)) : 0u;
  }();
  return k;
}

// The sites evaluated, kept only when VOXCD_MUTANT_REACHED names a file.
struct Reached {
  const char* path = std::getenv("VOXCD_MUTANT_REACHED");
  std::array<std::atomic<bool>, kMaxMutants> seen{};
  ~Reached() {
    if (!path) return;
    if (std::FILE* f = std::fopen(path, "a")) {
      for (unsigned k = 0; k < kMaxMutants; ++k)
        if (seen[k].load(std::memory_order_relaxed)) std::fprintf(f, "%u\n", k);
      std::fclose(f);
    }
  }
};
Reached reached;

}  // namespace

extern "C" svBit voxcd_mut(unsigned int k) {
  if (reached.path && k < kMaxMutants) reached.seen[k].store(true, std::memory_order_relaxed);
  return k == selected();
}
