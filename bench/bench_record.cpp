// bench_record: the size of a recording per frame (simulate --record, docs/view.md) for the paper's environment at
// 256 and 65,536 objects, split into its parts (poses, pairs, contacts, the frame's counters), and what recording
// costs the run: the median time of a frame with and without it, measured in the same run.
//   build/bench/bench_record [--frames F] [--repeats R] [--objects N,N...]
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "voxcd/host/scene/record.h"
#include "voxcd/host/scene/simulate.h"

namespace voxcd::bench {
namespace {

struct Row {
  uint64_t objects = 0, frames = 0, head = 0, file = 0;
  double frame_bytes = 0, pose_bytes = 0, pair_bytes = 0, contact_bytes = 0;
  double plain = 0, recorded = 0;  // median wall seconds of a whole run (scene, frames) without and with recording
};

// Bytes of a frame record by docs/view.md's layout: record header and CRC, counters, poses, pairs, contacts.
uint64_t frame_record_bytes(const RecordedFrame& f) {
  return 8 + 4 + 168 + 4 + 28 * f.positions.size() + 4 + 9 * f.pairs.size() + 4 + 37 * f.contacts.size();
}

Row measure(uint64_t objects, uint64_t frames, int repeats, const std::string& path) {
  RunConfig req;
  req.types[0].count = objects;
  req.frames = frames;
  Row r;
  r.objects = objects;
  r.frames = frames;
  std::vector<double> plain, recorded;
  simulate(req);  // warm: the first run pays for page faults and caches the others do not
  for (int k = 0; k < repeats; ++k) {
    req.record.clear();
    plain.push_back(median_time(1, [&] { simulate(req); }));
    req.record = path;
    recorded.push_back(median_time(1, [&] { simulate(req); }));
  }
  r.plain = median(plain);
  r.recorded = median(recorded);
  const Recording rec = read_recording(path);
  r.file = std::filesystem::file_size(path);
  std::vector<double> sizes, poses, pairs, contacts;
  uint64_t frames_total = 0;
  for (const RecordedFrame& f : rec.frames) {
    sizes.push_back(double(frame_record_bytes(f)));
    poses.push_back(28.0 * double(f.positions.size()));
    pairs.push_back(9.0 * double(f.pairs.size()));
    contacts.push_back(37.0 * double(f.contacts.size()));
    frames_total += frame_record_bytes(f);
  }
  r.head = r.file - frames_total;
  if (rec.frames.size() != frames || r.head > r.file)
    throw std::runtime_error("the recording's size does not follow docs/view.md's layout");
  r.frame_bytes = median(sizes);
  r.pose_bytes = median(poses);
  r.pair_bytes = median(pairs);
  r.contact_bytes = median(contacts);
  return r;
}

int run(int argc, char** argv) {
  uint64_t frames = 30;
  int repeats = 5;
  std::vector<uint64_t> counts = {256, 65536};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--frames") frames = std::stoull(argv[i + 1]);
    else if (a == "--repeats") repeats = std::stoi(argv[i + 1]);
    else if (a == "--objects") {
      counts.clear();
      std::stringstream ss(argv[i + 1]);
      for (std::string c; std::getline(ss, c, ',');) counts.push_back(std::stoull(c));
    } else throw std::invalid_argument("unknown option " + a);
  }
  const std::string path = (std::filesystem::temp_directory_path() / "voxcd_bench_record.vxr").string();
  std::printf("%s\n\n", provenance(argc, argv).c_str());
  std::printf("| objects | frames | bytes per frame (median) | poses | pairs | contacts | counters and framing | "
              "types and bodies, once | file | run with / without recording |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (uint64_t n : counts) {
    const Row r = measure(n, frames, repeats, path);
    std::printf("| %llu | %llu | %.0f (%.1f per object) | %.0f | %.0f | %.0f | %.0f | %llu | %.2f MB | %.2f (%.3f s / %.3f s) |\n",
                (unsigned long long)r.objects, (unsigned long long)r.frames, r.frame_bytes,
                r.frame_bytes / double(r.objects), r.pose_bytes, r.pair_bytes, r.contact_bytes,
                192.0, (unsigned long long)r.head,
                double(r.file) / 1e6, r.recorded / r.plain, r.recorded, r.plain);
    std::fflush(stdout);
  }
  std::filesystem::remove(path);
  return 0;
}

}  // namespace
}  // namespace voxcd::bench

int main(int argc, char** argv) {
  try {
    return voxcd::bench::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_record: %s\n", e.what());
    return 2;
  }
}
