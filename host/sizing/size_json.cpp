// The JSON report of `voxcd size` (size_json): what is asked, the widths, the measured frames and the costs.
#include <nlohmann/json.hpp>
#include <string>

#include "voxcd/host/sizing/digits.h"
#include "voxcd/host/sizing/detail/energy_report.h"
#include "voxcd/host/sizing/detail/storage_report.h"
#include "voxcd/host/sizing/size.h"
#include "voxcd/ref/banks.h"

namespace voxcd {

namespace {
nlohmann::ordered_json depth_json(const SizeReport& r) {
  const DepthChoice& d = *r.depth;
  nlohmann::ordered_json j;
  j["depth"] = d.depth();
  j["mhz"] = d.row.mhz;
  j["source"] = d.row.source;
  j["estimate"] = d.row.estimate();
  j["why"] = d.why();
  j["measured_config"] = d.row.config;
  j["stand_in"] = d.stand_in.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(d.stand_in);
  j["table"] = d.table;
  j["shallower"] = nlohmann::ordered_json::array();
  for (const TimingRow& row : d.shallower) j["shallower"].push_back({{"depth", row.depth}, {"mhz", row.mhz}});
  if (r.asic)
    j["area_mm2"] = {{"value", r.asic->area_mm2}, {"of", "this configuration (yosys + abc onto OSU 0.18 um)"},
                     {"cells", r.asic->cells}, {"seconds", r.asic->seconds}};
  else if (r.asic_row)
    j["area_mm2"] = {{"value", *r.asic_row->area_mm2}, {"of", "the timing table's configuration"},
                     {"config", r.asic_row->config}};
  else
    j["area_mm2"] = nullptr;
  j["block_rams"] = {{"count", r.rams->count}, {"unit", r.rams->unit},
                     {"available", r.rams->available ? nlohmann::ordered_json(r.rams->available) : nullptr}};
  return j;
}
}  // namespace

namespace {

using json = nlohmann::ordered_json;

// The scene and what is asked: objects, accuracy, rate, clock, frames, and each type.
void add_request_json(json& j, const SizeReport& r) {
  j = {{"scene", r.file}, {"objects", r.objects}, {"accuracy", r.accuracy}, {"rate_hz", r.rate},
       {"clock_mhz", r.clock.mhz}, {"clock_source", r.clock.source}, {"clock_estimate", r.clock.estimate},
       {"frames", r.frames}};
  for (const auto& t : r.scene.types)
    j["types"].push_back({{"name", t->name},
                          {"voxel", t->voxmap().voxel()},
                          {"voxmap", t->voxmap().dims()},
                          {"shell_points", t->shell().size()},
                          {"shell_spacing", t->shell().frame().voxel}});
}

// The configuration, the extents it holds, the fixed-point error and the contacts' bound.
void add_widths_json(json& j, const SizeReport& r) {
  const Scene& scene = r.scene;
  const DeviceConfig& c = r.config;
  j["config"] = {{"PW", c.PW}, {"PF", c.PF},     {"MW", c.MW},   {"MF", c.MF},   {"TW", c.TW},    {"DW", c.DW},
                 {"MEMW", c.MEMW}, {"LANES", c.LANES}, {"SAW", c.SAW}, {"MAW", c.MAW}, {"TAGW", c.TAGW},
                 {"SB", c.SB},     {"WB", c.WB},   {"BANKS", c.BANKS}, {"DEPTH", c.depth}, {"BL", c.BL}};
  j["config_text"] = c.to_string();
  j["extents"] = {{"max_point", r.extents.max_point},
                  {"max_ratio", r.extents.max_ratio},
                  {"max_translation", r.extents.max_translation},
                  {"max_dim", r.extents.max_dim}};
  j["error"] = r.error;
  const auto& wp = r.extents.pairs.at(r.worst_pair);
  j["worst_pair"] = {scene.types[wp.a]->name, scene.types[wp.b]->name};
  const ContactTerms& t = r.contact_terms;
  json convex = json::array();
  for (bool v : r.convex) convex.push_back(v);
  j["contact"] = {{"requested", r.contact_accuracy > 0 ? json(r.contact_accuracy) : nullptr},
                  {"bound", r.contact_error},
                  {"voxmap", {{"SB", r.kind.SB}, {"WB", r.kind.WB}, {"band", r.kind.band}, {"step", r.kind.step()}}},
                  {"worst_type", scene.types.at(r.contact_type)->name},
                  {"terms_voxels", {{"cell", t.cell}, {"quantisation", t.quantisation}, {"weights", t.weights},
                                    {"interpolation", t.interpolation}}},
                  {"convex", convex}};
}

// The measured frames: budget, cycles per lane count, per frame, rate, memory, depth, latency and target.
void add_frames_json(json& j, const SizeReport& r) {
  j["cycle_budget"] = r.budget;
  for (const auto& m : r.lanes)
    j["lanes_measured"].push_back({{"lanes", m.lanes}, {"max_cycles", m.max_cycles}, {"mean_cycles", m.mean_cycles}});
  const LaneMeasure& m = r.chosen();
  j["per_frame"] = {{"pairs", m.pairs}, {"tested", m.tested}, {"lookups", m.lookups}, {"hits", m.hits}};
  j["cycles_per_frame"] = {{"max", m.max_cycles}, {"mean", m.mean_cycles}};
  // At clock_mhz (clock_source above); null when the frames needed no device cycles.
  j["modelled_rate_hz"] = m.max_cycles ? json(r.modelled_rate()) : nullptr;
  j["memory_bits"] = {{"shell", r.shell_bits()}, {"voxmap", r.map_bits()}, {"total", r.shell_bits() + r.map_bits()}};
  j["depth"] = depth_of(r.config);
  j["latency_cycles"] = r.latency();
  j["latency_ns"] = r.latency_ns();
  j["target"] = r.target.empty() ? json(nullptr) : json(r.target);
  j["depth_choice"] = r.depth ? depth_json(r) : json(nullptr);
  j["words_used"] = {{"shell", r.shell_words}, {"voxmap", r.map_words}};
  detail::add_energy_json(j, r);
  j["storage"] = detail::storage_json(r);
}

// The yosys cost, the banks against copies, and the default widths' cost (null where not measured).
void add_costs_json(json& j, const SizeReport& r) {
  if (r.cost)
    j["cost"] = {{"target", "xilinx 7-series (synth_xilinx)"}, {"luts", r.cost->luts}, {"ffs", r.cost->ffs},
                 {"dsps", r.cost->dsps}, {"brams", r.cost->brams}, {"yosys", r.cost->version},
                 {"seconds", r.cost->seconds}};
  else
    j["cost"] = nullptr;
  j["banked"] = nullptr;
  if (r.banked) {
    const SizeReport::Banked& b = *r.banked;
    j["banked"] = {{"config_text", b.config.to_string()},
                   {"banks", b.config.BANKS},
                   {"voxmap_bits", b.map_bits()},
                   {"voxmap_bits_saved", r.map_bits() - b.map_bits()},
                   {"cycles_per_frame", {{"max", b.measure.max_cycles}, {"mean", b.measure.mean_cycles}}},
                   {"meets_budget", b.meets()},
                   {"cycle_budget", b.budget},
                   {"clock_mhz", b.clock.mhz},
                   {"clock_source", b.clock.source},
                   {"clock_estimate", b.clock.estimate}};
    if (b.cost)
      j["banked"]["cost"] = {{"luts", b.cost->luts}, {"ffs", b.cost->ffs}, {"dsps", b.cost->dsps},
                             {"brams", b.cost->brams}};
  }
  if (r.default_cost)
    j["default_widths_cost"] = {{"config", r.default_widths().to_string()}, {"luts", r.default_cost->luts},
                                {"ffs", r.default_cost->ffs}, {"dsps", r.default_cost->dsps},
                                {"brams", r.default_cost->brams}};
}

}  // namespace

std::string size_json(const SizeReport& r) {
  json j;
  add_request_json(j, r);
  add_widths_json(j, r);
  add_frames_json(j, r);
  add_costs_json(j, r);
  return j.dump(2) + "\n";
}

}  // namespace voxcd
