// The paper's N-body environment as a whole: frames per second on one core for each broadphase, with the paper's
// shape and accuracy (the 36-face polytope, voxel of one world unit, density 2.5%, momentum up to 10% of the radius
// per frame), against the number of objects; and the modelled device's frame rate from its cycles at the device
// clock (the clock of its configuration, measured or an estimate that says so; or --clock MHZ), which the table and
// the CSV name with its source. Writes Markdown
// to stdout (and to --out FILE).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "bench/bench_common.h"
#include "voxcd/host/scene/scene.h"

using namespace voxcd;

int main(int argc, char** argv) {
  const std::string provenance = bench::provenance(argc, argv);
  std::string out_path;
  int repeats = 3;
  uint64_t frames = 300;
  std::optional<DeviceClock> given_clock;  // --clock
  std::vector<size_t> counts = {2, 8, 32, 64, 128, 256, 1024, 4096};
  std::vector<std::string> prunings = broadphase_names();
  double fixed_voxel = 0;  // 0: voxel (64/N)^(1/3)
  bool midphase = true;
  std::string csv_path;
  // "a,b,c" -> items; an empty item is an error naming the option.
  auto split = [](const std::string& list, const char* what) {
    std::vector<std::string> items;
    std::stringstream in(list);
    std::string item;
    while (std::getline(in, item, ','))
      if (item.empty()) throw std::invalid_argument(std::string(what) + ": empty item in '" + list + "'");
      else items.push_back(item);
    if (items.empty()) throw std::invalid_argument(std::string(what) + " is empty");
    return items;
  };
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--out") && i + 1 < argc) out_path = argv[++i];
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) frames = uint64_t(std::atoll(argv[++i]));
    else if (!std::strcmp(argv[i], "--max-objects") && i + 1 < argc) {
      const size_t m = size_t(std::atoll(argv[++i]));
      counts.erase(std::remove_if(counts.begin(), counts.end(), [&](size_t c) { return c > m; }), counts.end());
    } else if (!std::strcmp(argv[i], "--counts") && i + 1 < argc) {
      counts.clear();
      try {
        for (const auto& c : split(argv[++i], "--counts")) {
          size_t used = 0;
          const long long v = std::stoll(c, &used);
          if (used != c.size() || v < 1) throw std::invalid_argument("--counts: '" + c + "' is not a positive count");
          counts.push_back(size_t(v));
        }
      } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_simulate: %s\n", e.what());
        return 2;
      }
    } else if (!std::strcmp(argv[i], "--prunings") && i + 1 < argc) {
      try {
        prunings = split(argv[++i], "--prunings");
      } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_simulate: %s\n", e.what());
        return 2;
      }
      const std::vector<std::string> known = broadphase_names();
      for (const auto& p : prunings)
        if (std::find(known.begin(), known.end(), p) == known.end()) {
          std::fprintf(stderr, "bench_simulate: --prunings: unknown broadphase '%s'\n", p.c_str());
          return 2;
        }
    } else if (!std::strcmp(argv[i], "--voxel") && i + 1 < argc) {
      fixed_voxel = std::atof(argv[++i]);
      if (!(fixed_voxel > 0) || !std::isfinite(fixed_voxel)) {
        std::fprintf(stderr, "bench_simulate: --voxel: '%s' is not a positive size\n", argv[i]);
        return 2;
      }
    } else if (!std::strcmp(argv[i], "--clock") && i + 1 < argc) {
      try {
        given_clock = bench::clock_arg(argv[++i]);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_simulate: %s\n", e.what());
        return 2;
      }
    } else if (!std::strcmp(argv[i], "--no-midphase")) {
      midphase = false;
    } else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) {
      csv_path = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: bench_simulate [--out FILE] [--repeats N] [--frames F] [--max-objects N] [--counts N,N,..] "
                   "[--prunings NAME,..] [--voxel S] [--clock MHZ] [--no-midphase] [--csv FILE]\n");
      return 2;
    }
  }
  // The pruning whose pairs and device cycles the table reports (the same stream for every broadphase).
  const std::string dev_pruning =
      std::find(prunings.begin(), prunings.end(), "sap") != prunings.end() ? "sap" : prunings.front();
  // The device: 4 lanes at the default widths, its memories grown to fit the objects (the clock does not depend on
  // them); a row whose device is another configuration is marked with its own clock.
  bench::RowClocks clocks(given_clock, DeviceConfig{});
  const DeviceClock& clock = clocks.heading();
  std::ostringstream csv;
  csv << bench::clock_csv_lines(clock) << "objects,pruning,hz,pairs_tested,device_cycles,device_hz\n";
  std::ostringstream md;
  md << provenance << "\n\n";
  md << "Frames per second (median of " << repeats << " runs of " << frames
     << " frames; each repeat runs every broadphase in turn) of `voxcd simulate` on the cpu backend with one thread: the paper's 36-face polytope, "
     << (fixed_voxel > 0 ? "voxel " + bench::fmt("%g", fixed_voxel) + " at every N (the objects shrink as N grows)"
                         : std::string("voxel (64/N)^(1/3) (1 at N = 64: the same voxmap at every N)"))
     << ", density 2.5%, ALL contacts, one direction"
     << (midphase ? "" : ", no mid-phase (every broadphase pair goes to the device, as in the paper)")
     << ". Device: cycles per frame of the same job streams from the "
        "exact timing model, 4 lanes, and the frame rate they allow at "
     << clock.text() << ".\n\n| objects |";
  for (const auto& p : prunings) md << " " << p << " (Hz) |";
  md << " pairs tested on the device per frame (" << dev_pruning << (midphase ? ", after the mid-phase" : "") << ") | device cycles per frame | device frame rate (Hz at " << clock.mhz << " MHz) |\n|---|";
  for (size_t i = 0; i < prunings.size(); ++i) md << "---|";
  md << "---|---|---|\n";
  for (size_t n : counts) {
    md << "| " << n << " |";
    double pairs = 0, cycles = 0;
    DeviceConfig dev_config;  // the device of dev_pruning's run
    // The quadratic broadphases are measured up to 1024 objects.
    auto runs = [&](const std::string& p) { return !((p == "all" || p == "sphere") && n > 1024); };
    RunConfig spec;
    spec.types[0].count = n;
    // The same resolution per object at every N (objects shrink as N grows at a fixed density): voxel 1 at the
    // paper's 64 objects.
    spec.types[0].voxel = fixed_voxel > 0 ? fixed_voxel : std::cbrt(64.0 / double(n));
    // Repeats outermost: each repeat runs every broadphase in turn, so a burst of load on this shared machine falls
    // on all of them alike rather than on one.
    std::vector<std::vector<double>> rates(prunings.size());
    for (int r = 0; r < repeats; ++r)
      for (size_t k = 0; k < prunings.size(); ++k) {
        const std::string& p = prunings[k];
        if (!runs(p)) continue;
        RunConfig opt;
        opt.broadphase = p;
        opt.threads = 1;
        opt.midphase = midphase;
        Simulation sim(make_scene(spec), opt);
        double t = 0;
        uint64_t pr = 0, cy = 0;
        for (uint64_t f = 0; f < frames; ++f) {
          const FrameStats st = sim.step();
          t += st.seconds();
          pr += st.tested;
          cy += st.device_cycles;
        }
        rates[k].push_back(double(frames) / t);
        if (p == dev_pruning)
          pairs = double(pr) / double(frames), cycles = double(cy) / double(frames), dev_config = sim.device_config();
      }
    const DeviceClock row_clock = clocks.of(dev_config);
    for (size_t k = 0; k < prunings.size(); ++k) {
      const std::string& p = prunings[k];
      if (!runs(p)) {
        md << " - |";
        continue;
      }
      const double hz = bench::median(rates[k]);
      char b[64];
      std::snprintf(b, sizeof b, " %.0f |", hz);
      md << b;
      std::fprintf(stderr, "%zu objects, %s: %.0f Hz\n", n, p.c_str(), hz);
      csv << n << "," << p << "," << hz << "," << (p == dev_pruning ? bench::fmt("%g", pairs) : "") << ","
          << (p == dev_pruning ? bench::fmt("%g", cycles) : "") << ","
          << (p == dev_pruning && cycles > 0 ? bench::fmt("%g", row_clock.rate(cycles)) : "") << "\n";
    }
    // Frames without device cycles have no device rate ("-"), not a rate of frames that took no time.
    char b[160];
    std::snprintf(b, sizeof b, " %.1f | %.0f | %s |\n", pairs, cycles,
                  cycles > 0 ? (bench::fmt("%.0f", row_clock.rate(cycles)) + clocks.mark(row_clock)).c_str() : "-");
    md << b;
  }
  md << clocks.notes();
  md << "\nMachine: " << bench::machine_description() << ". The frame time is the sum of the stages (integration, "
        "bounds, broadphase, pair tests, response), as `voxcd simulate` reports it.\n";
  std::cout << md.str();
  if (!out_path.empty()) std::ofstream(out_path) << md.str();
  if (!csv_path.empty() && !(std::ofstream(csv_path) << csv.str())) {
    std::fprintf(stderr, "bench_simulate: cannot write %s\n", csv_path.c_str());
    return 1;
  }
  return 0;
}
