// The text report of `voxcd size` (size_text): the scene, the widths, the measured frames, energy, storage, the depth
// choice and the costs, one block of lines each.
#include <ostream>
#include <sstream>
#include <string>

#include "voxcd/host/sizing/digits.h"
#include "voxcd/host/sizing/detail/energy_report.h"
#include "voxcd/host/sizing/detail/storage_report.h"
#include "voxcd/host/sizing/size.h"
#include "voxcd/ref/banks.h"

namespace voxcd {

namespace {

std::string fmt(double v, int precision = 4) { return detail::digits_text(v, precision); }

}  // namespace

using detail::bits_text;

namespace {
// "0.5 * (0.01562 quantisation + 0.01172 weights + 0.385 interpolation) + 0.007629 fixed-point"
std::string contact_terms_text(const SizeReport& r) {
  const ContactTerms& t = r.contact_terms;
  const double voxel = r.scene.types.at(r.contact_type)->voxmap().voxel();
  const double fixed = r.contact_error - voxel * t.total();
  std::string s = fmt(voxel) + " * ";
  if (!r.kind.distance())
    s += fmt(t.cell) + " (a hit voxel's diagonal)";
  else
    s += "(" + fmt(t.quantisation) + " quantisation + " + fmt(t.weights) + " weights + " + fmt(t.interpolation) +
         " interpolation)";
  return s + " + " + fmt(fixed) + " fixed-point";
}
}  // namespace

namespace {
// "16 RAMB36 (ice40...)": the block RAMs' count and unit.
std::string rams_text(const SizeReport& r) {
  std::string shapes;
  for (const MemoryShape& m : memory_shapes(r.config))
    shapes += (shapes.empty() ? "" : ", ") + std::to_string(m.count) + " x " + m.what + " " + std::to_string(m.words) +
              " x " + std::to_string(m.width) + " bit" + (m.read_ports > 1 ? " (2 read ports)" : "");
  std::string s = fmt(r.rams->count) + " " + r.rams->unit + " on " + r.target + " (" + shapes + ")";
  if (r.rams->available > 0)
    s += r.rams->count <= r.rams->available ? "; the part has " + std::to_string(r.rams->available)
                                            : "; more than the part's " + std::to_string(r.rams->available);
  return s;
}

// The lines of the depth choice (with a target): depth, area and block RAMs.
std::string depth_lines(const SizeReport& r) {
  std::ostringstream o;
  const DepthChoice& d = *r.depth;
  o << "depth           " << d.depth() << " on " << r.target << " for " << fmt(d.clock_mhz, 6) << " MHz (" << d.why()
    << "; " << d.row.source << ", " << d.table << ")\n";
  if (r.asic)
    o << "area            " << fmt(r.asic->area_mm2) << " mm^2 of standard cells at 0.18 um for this configuration at "
      << "depth " << d.depth() << " (yosys + abc onto OSU 0.18 um for " << fmt(r.asic->clock_mhz, 6) << " MHz, "
      << r.asic->cells << " cells, " << fmt(r.asic->seconds, 3) << " s; RAMs not included)\n";
  else if (r.asic_row)
    o << "area            " << fmt(*r.asic_row->area_mm2) << " mm^2 of standard cells at 0.18 um at depth "
      << d.depth() << " for the timing table's configuration (" << r.asic_row->config
      << "; RAMs not included); --cost synthesises this one\n";
  else
    o << "area            none in the timing table at depth " << d.depth() << "; --cost synthesises this one\n";
  o << "block RAMs      " << rams_text(r) << "\n";
  return o.str();
}
}  // namespace

namespace {

// The head: the scene, what is asked, and each type.
void scene_lines(std::ostream& o, const SizeReport& r) {
  const Scene& scene = r.scene;
  o << "voxcd size: " << r.file << ": " << r.objects << " objects of " << scene.types.size() << " type"
    << (scene.types.size() > 1 ? "s" : "") << "; accuracy " << fmt(r.accuracy) << " world units, " << fmt(r.rate, 8)
    << " frames/s at " << r.clock.text() << "\n";
  for (const auto& t : scene.types) {
    const auto& d = t->voxmap().dims();
    o << "  type " << t->name << ": voxel " << fmt(t->voxmap().voxel()) << ", voxmap " << d[0] << "x" << d[1] << "x"
      << d[2] << ", " << t->shell().size() << " shell points at spacing " << fmt(t->shell().frame().voxel) << "\n";
  }
}

// The configuration, its widths and what they hold, the fixed-point error and the contacts' bound.
void width_lines(std::ostream& o, const SizeReport& r) {
  const Scene& scene = r.scene;
  const DeviceConfig& c = r.config;
  const auto& wp = r.extents.pairs.at(r.worst_pair);
  o << "configuration   " << c.to_string() << "\n";
  o << "widths          PW " << c.PW << " PF " << c.PF << ": shell coordinates up to " << fmt(r.extents.max_point)
    << " spacings, exact (half-integers)" << (c.sparse() ? ", and at least 24 for a shell brick a word" : "")
    << "; MW " << c.MW << " MF " << c.MF << ": matrix entries up to "
    << fmt(r.extents.max_ratio) << "; TW " << c.TW << ": translations up to " << fmt(r.extents.max_translation)
    << " voxels; DW " << c.DW << ": voxmaps up to " << r.extents.max_dim << " voxels\n";
  o << "error           " << fmt(r.error) << " world units at most (" << fmt(r.accuracy) << " requested; worst pair "
    << scene.types[wp.a]->name << " in " << scene.types[wp.b]->name << ": voxel_B * (3 * 2^-" << c.MF + 1 << " * "
    << fmt(wp.max_point_a) << " + 2^-" << c.TF() + 1 << "))\n";
  const ObjectType& b = *scene.types.at(r.contact_type);
  o << "contacts        within " << fmt(r.contact_error) << " world units of the other surface with " << r.kind.text()
    << " ("
    << (r.contact_accuracy > 0 ? fmt(r.contact_accuracy) + " requested"
                               : std::string("the scene file's voxmaps; --contact-accuracy chooses them"))
    << "; worst type " << b.name << (r.convex.at(r.contact_type) ? ", convex" : ", not convex") << ": "
    << contact_terms_text(r) << ")\n";
}

// The measured frames: per frame, cycles per lane count, frame rate, latency and memory.
void frame_lines(std::ostream& o, const SizeReport& r) {
  const DeviceConfig& c = r.config;
  const LaneMeasure& m = r.chosen();
  o << "per frame       " << fmt(m.pairs) << " broadphase pairs, " << fmt(m.tested) << " tested, " << fmt(m.lookups)
    << " lookups, " << fmt(m.hits) << " hits (mean of " << r.frames << " frames on the cpu backend)\n";
  o << "cycles          ";
  for (size_t i = 0; i < r.lanes.size(); ++i)
    o << (i ? ", " : "") << "LANES " << r.lanes[i].lanes << ": " << r.lanes[i].max_cycles;
  o << " (largest frame; budget " << r.budget << " at " << fmt(r.rate, 8) << " frames/s)\n";
  if (m.max_cycles == 0)
    o << "frame rate      none from the device: the frames needed no device cycles (LANES " << c.LANES << ")\n";
  else
    o << "frame rate      " << fmt(r.modelled_rate(), 6) << " frames/s with LANES " << c.LANES << " (largest frame "
      << m.max_cycles << " cycles, mean " << fmt(m.mean_cycles, 6) << ") at " << r.clock.text() << "\n";
  o << "latency         " << r.latency() << " cycles (" << fmt(r.latency_ns(), 4)
    << " ns) from a job's acceptance to its first record on the pins, at depth " << depth_of(c) << "\n";
  o << "memory          shell 2^" << c.SAW << " x " << 3 * c.PW << " bit = " << bits_text(r.shell_bits())
    << " (" << r.shell_words << " words used), voxmap 2^" << c.MAW << " x " << c.MEMW << " bit x " << c.voxmap_copies()
    << (c.banked() ? " (shared banks)" : " lane copies") << " = " << bits_text(r.map_bits()) << " (" << r.map_words
    << " words used" << (c.sparse() ? ", two read ports: table and bricks" : "") << "); total "
    << bits_text(r.shell_bits() + r.map_bits()) << "\n";
}

// Shared banks against copies: memory, cycles, the budget, and their cost when synthesised.
void banked_lines(std::ostream& o, const SizeReport& r) {
  const SizeReport::Banked& b = *r.banked;
  const LaneMeasure& m = r.chosen();
  const uint64_t copies = r.map_bits(), shared = b.map_bits();
  const double more = m.max_cycles ? double(b.measure.max_cycles) / double(m.max_cycles) - 1 : 0;
  o << "banks           BANKS " << b.config.BANKS << " (one voxmap shared in " << memory_banks(b.config)
    << " banks instead of " << r.config.LANES << " copies): voxmap " << bits_text(shared) << " instead of "
    << bits_text(copies) << " (saves " << bits_text(copies - shared) << "); largest frame " << b.measure.max_cycles
    << " cycles instead of " << m.max_cycles << " (" << (more >= 0 ? "+" : "") << fmt(100 * more, 3)
    << "%, bank conflicts), mean " << fmt(b.measure.mean_cycles, 6) << "; "
    << (b.meets() ? "meets" : "misses") << " the budget of " << b.budget << " cycles"
    << (b.clock.text() == r.clock.text() ? "" : " at " + b.clock.text()) << "\n";
  if (b.cost)
    o << "banks cost      " << b.cost->luts << " LUTs, " << b.cost->ffs << " FFs, " << b.cost->dsps << " DSPs, "
      << fmt(b.cost->brams) << " block RAMs (RAMB36) with BANKS " << b.config.BANKS << ", against "
      << fmt(r.cost->brams) << " with copies\n";
}

// The yosys cost, the banks, and the default widths' cost against it.
void cost_lines(std::ostream& o, const SizeReport& r) {
  if (r.cost)
    o << "cost            " << r.cost->luts << " LUTs, " << r.cost->ffs << " FFs, " << r.cost->dsps << " DSPs, "
      << fmt(r.cost->brams) << " block RAMs (RAMB36) for Xilinx 7-series (yosys synth_xilinx, " << r.cost->version
      << ", " << fmt(r.cost->seconds, 3) << " s)\n";
  else
    o << "cost            not synthesised (add --cost to run yosys)\n";
  if (r.banked) banked_lines(o, r);
  if (!r.default_cost) return;
  const DeviceConfig d = r.default_widths();
  o << "default widths  " << r.default_cost->luts << " LUTs, " << r.default_cost->ffs << " FFs, "
    << r.default_cost->dsps << " DSPs, " << fmt(r.default_cost->brams) << " block RAMs for " << d.to_string()
    << " (shell 2^" << d.SAW << " x " << 3 * d.PW << " bit); derived/default LUTs "
    << fmt(double(r.cost->luts) / double(std::max<uint64_t>(1, r.default_cost->luts)), 3) << ", DSPs "
    << fmt(double(r.cost->dsps) / double(std::max<uint64_t>(1, r.default_cost->dsps)), 3) << ", block RAMs "
    << fmt(r.cost->brams / std::max(0.5, r.default_cost->brams), 3) << "\n";
}

}  // namespace

std::string size_text(const SizeReport& r) {
  std::ostringstream o;
  scene_lines(o, r);
  width_lines(o, r);
  frame_lines(o, r);
  detail::energy_lines(o, r);
  detail::storage_lines(o, r);
  if (r.depth) o << depth_lines(r);
  cost_lines(o, r);
  return o.str();
}

}  // namespace voxcd
