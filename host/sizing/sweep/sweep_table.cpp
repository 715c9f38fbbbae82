#include "voxcd/host/sizing/sweep/sweep_table.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

namespace voxcd {

namespace {

std::string g(double v, int precision = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", precision, v);
  return buf;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string kbit(uint64_t bits) { return g(double(bits) / 1024.0, 5); }

// A row's clock: its own, or the sweep's for a row of a results file made before rows had one.
DeviceClock row_clock(const SweepTable& t, const SweepRow& r) {
  if (r.clock_mhz > 0) return DeviceClock{r.clock_mhz, r.clock_source, r.clock_estimate};
  return DeviceClock{t.clock, t.spec.clock_source, false};
}

// Where the sweep's rates' clock comes from: the sweep's clock's source, or each point's configuration.
constexpr const char* kOwnClocks =
    "each point's own clock (measured for its configuration, or an estimate: docs/hardware.md, \"The default clock\")";
std::string clock_source(const SweepTable& t) { return t.clock > 0 ? t.spec.clock_source : kOwnClocks; }

}  // namespace

std::vector<bool> pareto_front(const std::vector<std::array<double, 3>>& pts) {
  std::vector<bool> front(pts.size(), true);
  for (size_t i = 0; i < pts.size(); ++i)
    for (size_t j = 0; j < pts.size() && front[i]; ++j) {
      if (i == j) continue;
      bool no_worse = true, better = false;
      for (int k = 0; k < 3; ++k) {
        no_worse &= pts[j][k] <= pts[i][k];
        better |= pts[j][k] < pts[i][k];
      }
      if (no_worse && better) front[i] = false;
    }
  return front;
}

void finish_table(SweepTable& t) {
  std::sort(t.rows.begin(), t.rows.end(),
            [](const SweepRow& a, const SweepRow& b) { return a.point.index < b.point.index; });
  std::vector<std::array<double, 3>> pts;
  std::vector<size_t> which;
  for (size_t i = 0; i < t.rows.size(); ++i) {
    t.rows[i].pareto = false;
    if (!t.rows[i].ok()) continue;
    pts.push_back({t.rows[i].contact_bound, double(t.rows[i].max_cycles), double(t.rows[i].memory_bits())});
    which.push_back(i);
  }
  const std::vector<bool> front = pareto_front(pts);
  for (size_t k = 0; k < which.size(); ++k) t.rows[which[k]].pareto = front[k];
}

std::string sweep_csv(const SweepTable& t) {
  std::ostringstream o;
  o << "point,lanes,depth,voxel_scale,distance_bits,accuracy,status,config,error_bound,contact_bound,"
       "contact_measured,contacts_checked,latency_cycles,max_cycles,mean_cycles,rate_fps,shell_bits,map_bits,memory_bits,luts,ffs,dsps,brams,"
       "pareto,clock_mhz,clock_source,clock_estimate\n";
  for (const SweepRow& r : t.rows) {
    o << r.point.index << ',' << r.point.lanes << ',' << r.point.depth << ',' << g(r.point.voxel_scale) << ',' << r.point.distance_bits
      << ',' << g(r.point.accuracy) << ',' << csv_field(r.status) << ',' << csv_field(r.config) << ',';
    if (r.ok())
      o << g(r.error_bound) << ',' << g(r.contact_bound) << ',' << g(r.contact_measured) << ',' << r.contacts_checked
        << ',' << r.latency << ',' << r.max_cycles << ',' << g(r.mean_cycles) << ',' << g(r.rate) << ',' << r.shell_bits << ','
        << r.map_bits << ',' << r.memory_bits() << ',';
    else
      o << ",,,,,,,,,,,";
    if (r.cost)
      o << r.cost->luts << ',' << r.cost->ffs << ',' << r.cost->dsps << ',' << g(r.cost->brams) << ',';
    else
      o << ",,,,";
    const DeviceClock c = row_clock(t, r);
    o << (r.pareto ? 1 : 0) << ',';
    if (r.ok()) o << g(c.mhz) << ',' << csv_field(c.source) << ',' << (c.estimate ? 1 : 0);
    else o << ",,";
    o << '\n';
  }
  return o.str();
}

std::string sweep_table_json(const SweepTable& t) {
  nlohmann::ordered_json j;
  j["scene"] = t.spec.scene;
  j["points"] = t.spec.points();
  j["lists"] = {{"lanes", t.spec.lanes}, {"depth", t.spec.depths}, {"voxel_scale", t.spec.voxel_scales},
                {"distance_bits", t.spec.distance_bits}, {"accuracy", t.spec.accuracies}};
  j["frames"] = t.frames;
  j["sample_frames"] = t.spec.sample_frames;
  // The sweep's clock when it gives one; null: each row's own (its clock_mhz, clock_source and clock_estimate).
  j["clock_mhz"] = t.clock > 0 ? nlohmann::ordered_json(t.clock) : nlohmann::ordered_json(nullptr);
  j["clock_from"] = clock_source(t);  // the name before clock_source; the same text
  j["clock_source"] = clock_source(t);
  j["pareto_axes"] = {"contact_bound", "max_cycles", "memory_bits"};
  for (const SweepRow& r : t.rows) {
    nlohmann::ordered_json row = nlohmann::ordered_json::parse(sweep_row_line(r));
    row.erase("rank");
    row.erase("seconds");
    if (row["cost"].is_object()) row["cost"].erase("seconds");
    if (r.ok()) {
      const DeviceClock c = row_clock(t, r);
      row["clock_mhz"] = c.mhz, row["clock_source"] = c.source, row["clock_estimate"] = c.estimate;
    }
    row["memory_bits"] = r.memory_bits();
    row["point_text"] = r.point.text();
    row["pareto"] = r.pareto;
    row["timing"] = {{"rank", r.rank}, {"seconds", r.seconds}};
    j["rows"].push_back(row);
  }
  if (t.rows.empty()) j["rows"] = nlohmann::ordered_json::array();
  j["complete"] = t.rows.size() == t.spec.points();
  j["timing"] = {{"ranks", t.ranks}, {"seconds", t.seconds}, {"from_results_file", t.from_file}};
  return j.dump(2) + "\n";
}

std::string sweep_text(const SweepTable& t) {
  std::ostringstream o;
  const SweepSpec& s = t.spec;
  o << "voxcd sweep: " << s.scene << ": " << s.points() << " points (" << s.lanes.size() << " lanes x "
    << s.depths.size() << " depths x " << s.voxel_scales.size() << " voxel scales x " << s.distance_bits.size() << " distance bits x "
    << s.accuracies.size() << " accuracies), " << t.frames << " frames each (" << s.sample_frames
    << " checked against the meshes); frames/s at "
    << (t.clock > 0 ? "clock " + g(t.clock) + " MHz (" + s.clock_source + ")"
                    : "each point's own clock (listed with its configuration)")
    << "\n";
  char line[512];
  std::snprintf(line, sizeof line, "%5s %5s %5s %6s %4s %9s %10s %10s %10s %9s %10s %10s %10s %s\n", "point", "lanes",
                "depth", "voxel", "dist", "accuracy", "error", "contact", "measured", "cycles", "mean", "frames/s", "kbit",
                "front");
  o << line;
  for (const SweepRow& r : t.rows) {
    if (!r.ok()) {
      std::snprintf(line, sizeof line, "%5llu %5d %5d %6s %4d %9s  %s\n", (unsigned long long)r.point.index,
                    r.point.lanes, r.point.depth, ("x" + g(r.point.voxel_scale, 3)).c_str(), r.point.distance_bits, g(r.point.accuracy, 3).c_str(),
                    r.status.c_str());
      o << line;
      continue;
    }
    std::snprintf(line, sizeof line, "%5llu %5d %5d %6s %4d %9s %10s %10s %10s %9llu %10s %10s %10s %s\n",
                  (unsigned long long)r.point.index, r.point.lanes, r.point.depth, ("x" + g(r.point.voxel_scale, 3)).c_str(),
                  r.point.distance_bits, g(r.point.accuracy, 3).c_str(), g(r.error_bound, 4).c_str(),
                  g(r.contact_bound, 4).c_str(), g(r.contact_measured, 4).c_str(), (unsigned long long)r.max_cycles,
                  g(r.mean_cycles, 6).c_str(), g(r.rate, 6).c_str(), kbit(r.memory_bits()).c_str(),
                  r.pareto ? "*" : "");
    o << line;
    if (r.cost)
      o << "      cost: " << r.cost->luts << " LUTs, " << r.cost->ffs << " FFs, " << r.cost->dsps << " DSPs, "
        << g(r.cost->brams) << " block RAMs (RAMB36)\n";
  }
  o << "configurations:\n";
  for (const SweepRow& r : t.rows)
    if (r.ok())
      o << "  " << r.point.index << ": " << r.config
        << (t.clock > 0 ? std::string() : "; clock " + row_clock(t, r).text()) << "\n";
  std::string front;
  for (const SweepRow& r : t.rows)
    if (r.pareto) front += (front.empty() ? "" : ", ") + std::to_string(r.point.index);
  o << "Pareto front (*: no other point has a smaller or equal contact bound, cycles and memory with one smaller): "
    << (front.empty() ? "none" : "points " + front) << "\n";
  if (t.rows.size() < s.points())
    o << "incomplete: " << t.rows.size() << " of " << s.points() << " points; rerun with the same --results file "
      << "to run the others\n";
  o << "ranks " << t.ranks << ", " << g(t.seconds, 4) << " s; " << t.from_file << " of " << t.rows.size()
    << " points from the results file\n";
  return o.str();
}

}  // namespace voxcd
