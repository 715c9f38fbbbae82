// bench_sysc_platform: simulation speed of one SystemC target batch after batch inside one platform (sysc/platform.h),
// as a virtual platform that links voxcd_sysc sees it: no server process, no socket, the same HostCpu transactions as
// the sysc backends. The same generated jobs as bench_sysc; every batch's stream and cycles must equal ref's. SystemC
// elaborates once per process, so each target is its own run (docs/systemc.md gives both):
//   bench_sysc_platform --target tlm|rtl [--seed S] [--jobs N] [--cloud P] [--lanes L] [--batches B]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/sysc/platform.h"

using namespace voxcd;
using namespace voxcd::sysc;

int sc_main(int argc, char** argv) {
  uint64_t seed = 1;
  size_t jobs = 300, cloud = 4000, batches = 0;
  int lanes = 4;
  std::string target;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    const unsigned long long n = std::strtoull(v.c_str(), nullptr, 0);
    if (a == "--target") target = v;
    else if (a == "--seed") seed = n;
    else if (a == "--jobs") jobs = n;
    else if (a == "--cloud") cloud = n;
    else if (a == "--lanes") lanes = int(n);
    else if (a == "--batches") batches = n;
    else target = "?";
  }
  const auto kind = parse_target(target);
  if (!kind) {
    std::fprintf(stderr, "usage: bench_sysc_platform --target tlm|rtl [--seed S] [--jobs N] [--cloud P] [--lanes L] "
                         "[--batches B]\n");
    return 2;
  }
  if (batches == 0) batches = *kind == TargetKind::Tlm ? 2000 : 15;
  GenerateOptions g;
  g.seed = seed;
  g.jobs = jobs;
  g.cloud_points = cloud;
  g.config.LANES = lanes;
  const GeneratedVectors v = generate_vectors(g);
  std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
  annotate_cycles(v.config, v.jobs, want);
  uint64_t points = 0, cycles = 0;
  for (const Job& j : v.jobs) points += j.shell_count;
  for (const Record& r : want) cycles += r.kind == Record::Done ? *r.cycles : 0;

  PlatformOptions opt;
  opt.target = *kind;
  opt.config = v.config;
  Platform platform("platform", opt);
  platform.execute([&](HostCpu& cpu) { cpu.load(v.memory); });
  // The descriptors encoded once and the records kept as the device gives them, as the sysc server does.
  std::vector<uint8_t> descriptors(v.jobs.size() * kJobBytes), records;
  for (size_t i = 0; i < v.jobs.size(); ++i) encode_job(v.jobs[i], &descriptors[i * kJobBytes]);
  std::vector<double> ms;
  bool equal = true;
  std::vector<Record> got;
  for (size_t b = 0; b < batches; ++b) {
    const auto t0 = std::chrono::steady_clock::now();
    platform.execute([&](HostCpu& cpu) { cpu.run_encoded(descriptors.data(), v.jobs.size(), records); });
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    got.resize(records.size() / kRecordBytes);
    for (size_t i = 0; i < got.size(); ++i) decode_record(&records[i * kRecordBytes], got[i]);
    equal = equal && got.size() == want.size();
    for (size_t i = 0; equal && i < got.size(); ++i) equal = got[i].same_as(want[i], true);
  }
  const double first = ms[0];
  std::sort(ms.begin() + 1, ms.end());
  const size_t rest = ms.size() - 1;
  const double median = rest ? (rest % 2 ? ms[1 + rest / 2] : 0.5 * (ms[rest / 2] + ms[rest / 2 + 1])) : first;
  const double best = rest ? ms[1] : first;
  std::printf("bench_sysc_platform: target %s, seed %llu, %zu jobs, %llu lookups, %llu device cycles, LANES %d, %zu "
              "batches\n",
              target.c_str(), (unsigned long long)seed, v.jobs.size(), (unsigned long long)points,
              (unsigned long long)cycles, lanes, batches);
  std::printf("first batch %.3f ms; batches after it: median %.4f ms, best %.4f ms; streams and cycles %s\n", first,
              median, best, equal ? "equal ref's" : "DIFFER from ref's");
  return equal ? 0 : 1;
}
