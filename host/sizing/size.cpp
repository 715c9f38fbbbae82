// Sizing a device for a scene (derive_size): the widths, memories, lanes, storage, depth and costs; the reports are
// size_text.cpp and size_json.cpp.
#include "voxcd/host/sizing/size.h"

#include "voxcd/host/package/paths.h"

#include <algorithm>
#include <cmath>

#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/sizing/digits.h"
#include "voxcd/host/sizing/detail/energy_report.h"
#include "voxcd/host/sizing/detail/yosys_run.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/types.h"

namespace voxcd {

namespace {

std::string fmt(double v, int precision = 4) { return detail::digits_text(v, precision); }

bool fits(double v, int width, int frac) {
  int64_t raw;
  return width >= 2 && width <= 64 && try_quantize(v, FixedFormat{width, frac}, &raw) &&
         try_quantize(-v, FixedFormat{width, frac}, &raw);
}

// Smallest signed width (from 2) that holds +-v with `frac` fraction bits; 65 when none up to 64 does.
int width_for(double v, int frac) {
  for (int w = std::max(2, frac + 1); w <= 64; ++w)
    if (fits(v, w, frac)) return w;
  return 65;
}

// The smallest MW for MF (entries up to +-ratio; an entry of a rotation can be exactly +-1 times the ratio).
int mw_for(const SceneExtents& e, int mf) { return std::max(mf + 1, width_for(e.max_ratio, mf)); }

// The smallest TW for TF, at least one integer bit above TF, and with an accumulator that holds the index range.
int tw_for(const SceneExtents& e, DeviceConfig cfg) {
  cfg.TW = std::max(cfg.TF() + 1, width_for(e.max_translation, cfg.TF()));
  while (cfg.TW <= 64 && cfg.index_width() < cfg.DW + 1) ++cfg.TW;
  return cfg.TW;
}

}  // namespace

SceneExtents scene_extents(const Scene& scene) {
  SceneExtents e;
  const size_t n = scene.types.size();
  std::vector<uint64_t> bodies(n, 0);
  for (const Body& b : scene.bodies) ++bodies.at(b.type);
  std::vector<double> max_point(n, 0);
  double rmax = 0;
  for (size_t i = 0; i < n; ++i) {
    const ObjectType& t = *scene.types[i];
    max_point[i] = t.shell().max_grid_coordinate();  // cell centres, or surface points (PointShell::coords)
    e.max_point = std::max(e.max_point, max_point[i]);
    for (uint32_t d : t.voxmap().dims()) e.max_dim = std::max(e.max_dim, d);
    rmax = std::max(rmax, t.radius);
  }
  // Two bodies' sphere centres lie in the cube grown by the largest radius (the walls turn a body back once its
  // sphere crosses one), so their distance is at most sqrt(3) (side + 2 rmax).
  const double span = std::sqrt(3.0) * (scene.side + 2 * rmax);
  for (uint32_t a = 0; a < n; ++a)
    for (uint32_t b = 0; b < n; ++b) {
      if (bodies[a] == 0 || bodies[b] == 0 || (a == b && bodies[a] < 2)) continue;
      const ObjectType &ta = *scene.types[a], &tb = *scene.types[b];
      const GridFrame sa = ta.shell().frame(), mb = tb.voxmap().grid().frame();
      SceneExtents::Pair p{a, b, mb.voxel, max_point[a], sa.voxel / mb.voxel};
      e.pairs.push_back(p);
      e.max_ratio = std::max(e.max_ratio, sa.voxel / mb.voxel);
      // t = (R_B^T (R_A o_A + x_A - x_B) - o_B) / v_B with x = c - R centre: |t_i| <= |t|.
      const double t = (sa.origin.norm() + mb.origin.norm() + ta.centre.norm() + tb.centre.norm() + span) / mb.voxel;
      e.max_translation = std::max(e.max_translation, t);
    }
  return e;
}

namespace {
// The fixed-point path's bound for one ordered pair, world units (size_error_bound).
double pair_error_bound(const DeviceConfig& cfg, const SceneExtents::Pair& p) {
  double v = 3 * std::ldexp(1.0, -(cfg.MF + 1)) * p.max_point_a + std::ldexp(1.0, -(cfg.TF() + 1));
  if (cfg.PF < 1) v += 3 * (p.ratio + std::ldexp(1.0, -(cfg.MF + 1))) * std::ldexp(1.0, -(cfg.PF + 1));
  return v * p.voxel_b;
}
}  // namespace

double size_error_bound(const DeviceConfig& cfg, const SceneExtents& e, size_t* worst) {
  double err = 0;
  for (size_t k = 0; k < e.pairs.size(); ++k) {
    const double v = pair_error_bound(cfg, e.pairs[k]);
    if (v > err || k == 0) {
      err = v;
      if (worst) *worst = k;
    }
  }
  return err;
}

double contact_error_bound(const DeviceConfig& cfg, const SceneExtents& e, const VoxmapKind& k,
                           const std::vector<bool>& convex, size_t* worst_type, ContactTerms* worst_terms) {
  double worst = -1;
  for (const auto& p : e.pairs) {
    const ContactTerms t = contact_terms(k, convex.at(p.b));
    const double v = p.voxel_b * t.total() + pair_error_bound(cfg, p);
    if (v > worst) {
      worst = v;
      if (worst_type) *worst_type = p.b;
      if (worst_terms) *worst_terms = t;
    }
  }
  return std::max(0.0, worst);
}

uint64_t shell_memory_bits(const DeviceConfig& cfg) { return cfg.shell_depth() * uint64_t(3 * cfg.PW); }
uint64_t map_memory_bits(const DeviceConfig& cfg) {
  return cfg.map_depth() * uint64_t(cfg.MEMW) * uint64_t(cfg.voxmap_copies());
}

DeviceConfig derive_widths(const SceneExtents& e, double accuracy, DeviceConfig cfg, int min_tf) {
  if (!(accuracy > 0) || !std::isfinite(accuracy))
    throw std::invalid_argument("accuracy must be a positive number of world units");
  // Shell words are voxel centres, half-integers of the shell spacing: PF 1 holds them exactly.
  cfg.PF = 1;
  cfg.PW = width_for(e.max_point, cfg.PF);
  if (cfg.sparse()) cfg.PW = std::max(cfg.PW, 24);  // a shell word holds a shell brick: 3 PW >= 72
  if (cfg.PW > 32)
    throw SizeError("extent", e.max_point / std::ldexp(1.0, 30),
                    "shell coordinates up to " + fmt(e.max_point) + " spacings need PW " + std::to_string(cfg.PW) +
                        " bits, above the largest 32");
  cfg.DW = 1;
  while ((uint64_t{1} << cfg.DW) < e.max_dim) ++cfg.DW;
  // The smallest MF whose bound meets the accuracy, among those whose MW and TW exist.
  int best_mf = -1;
  double best_err = 0;
  for (int mf = std::max(0, min_tf - cfg.PF); mf <= 31; ++mf) {
    cfg.MF = mf;
    cfg.MW = mw_for(e, mf);
    if (cfg.MW > 32) break;
    cfg.TW = tw_for(e, cfg);
    if (cfg.TW > 64) break;
    best_mf = mf;
    best_err = size_error_bound(cfg, e);
    if (best_err <= accuracy) return cfg;
  }
  if (best_mf < 0)
    throw SizeError("extent", e.max_translation,
                    "translations up to " + fmt(e.max_translation) + " voxels need more than TW 64 bits");
  throw SizeError("accuracy", best_err / accuracy,
                  "the widest formats (MF " + std::to_string(best_mf) + ", limited by MW <= 32 and TW <= 64) bound the "
                  "error at " + fmt(best_err) + " world units; " + fmt(accuracy) + " requested is " +
                  fmt(best_err / accuracy) + " times finer");
}

DeviceConfig derive_memory(DeviceConfig cfg, const Scene& scene) {
  // Count what the host's packing needs (DeviceImage places types back to back), then check it with the packing.
  uint64_t shell = 0, words = 0;
  for (const auto& t : scene.types) {
    shell += type_shell_words(cfg, *t);
    words += type_map_words(cfg, *t) + (cfg.distance() ? 7 : 0);  // a distance map starts on a bank boundary
  }
  cfg.SAW = 1;
  while (cfg.SAW < 24 && (cfg.shell_depth() < shell || (1 << cfg.SAW) < cfg.LANES)) ++cfg.SAW;
  cfg.MAW = 1;
  while (cfg.MAW < 28 && cfg.map_depth() < words) ++cfg.MAW;
  if (cfg.shell_depth() < shell)
    throw SizeError("memory", double(shell) / double(cfg.shell_depth()),
                    "the object types need " + std::to_string(shell) + " shell words; the largest shell memory "
                    "(SAW 24) holds " + std::to_string(cfg.shell_depth()) + ", " +
                        fmt(double(shell) / double(cfg.shell_depth())) + " times too few");
  if (cfg.map_depth() < words)
    throw SizeError("memory", double(words) / double(cfg.map_depth()),
                    "the object types need " + std::to_string(words) + " voxmap words; the largest voxmap memory "
                    "(MAW 28) holds " + std::to_string(cfg.map_depth()) + ", " +
                        fmt(double(words) / double(cfg.map_depth())) + " times too few");
  DeviceImage image(cfg);
  // CapacityError here would be a bug in the counts above.
  for (const auto& t : scene.types) image.add(*t, shell_order(cfg, *t));
  return cfg;
}

RunConfig sizing_sim_options(const RunConfig& f, const DeviceConfig& cfg) {
  RunConfig opt = f;
  opt.backend = "cpu";
  opt.device = cfg;
  opt.lanes = cfg.LANES;
  opt.margin = 0;
  opt.threads = 0;
  opt.midphase = opt.cull = true;
  opt.exchange = nullptr;
  opt.record.clear();
  return opt;
}

LaneMeasure measure_frames(const Scene& scene, const RunConfig& f, const DeviceConfig& cfg, uint64_t frames) {
  Simulation sim(scene, sizing_sim_options(f, cfg));
  LaneMeasure m;
  m.lanes = cfg.LANES;
  uint64_t total = 0, pairs = 0, tested = 0, lookups = 0, hits = 0;
  for (uint64_t k = 0; k < frames; ++k) {
    const FrameStats s = sim.step();
    total += s.device_cycles;
    m.max_cycles = std::max(m.max_cycles, s.device_cycles);
    pairs += s.pairs, tested += s.tested, lookups += s.lookups, hits += s.hits;
  }
  const double F = double(frames);
  m.mean_cycles = double(total) / F;
  m.pairs = double(pairs) / F, m.tested = double(tested) / F, m.lookups = double(lookups) / F;
  m.hits = double(hits) / F;
  return m;
}

std::string default_rtl_dir() {
  try {
    return rtl_dir();
  } catch (const std::runtime_error&) {
    return "";  // yosys_cost looks again and says where
  }
}

YosysCost yosys_cost(const DeviceConfig& cfg, const std::string& dir) {
  // The same method as bench/rtl_cost.sh's xilinx rows.
  const detail::YosysRun run = detail::run_yosys(
      dir.empty() ? rtl_dir() : dir,
      detail::chparam_device(cfg) + "; synth_xilinx -noiopad -top voxcd_device; flatten; tee -q -o stat.json stat -json",
      "stat.json");
  YosysCost c;
  c.command = run.command;
  c.seconds = run.seconds;
  nlohmann::json stat;
  try {
    stat = nlohmann::json::parse(run.output);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("yosys: cannot read its statistics: ") + e.what());
  }
  const nlohmann::json& cells = stat.contains("design") ? stat["design"]["num_cells_by_type"]
                                                        : stat["modules"].begin().value()["num_cells_by_type"];
  for (const auto& [name, n] : cells.items()) {
    const uint64_t k = n.get<uint64_t>();
    if (name.size() == 4 && name.rfind("LUT", 0) == 0 && name[3] >= '1' && name[3] <= '6') c.luts += k;
    if (name.rfind("FD", 0) == 0) c.ffs += k;
    if (name == "DSP48E1") c.dsps += k;
    if (name == "RAMB36E1") c.brams += double(k);
    if (name == "RAMB18E1") c.brams += 0.5 * double(k);
  }
  c.version = detail::yosys_version();
  return c;
}

double SizeReport::modelled_rate() const {
  return clock.rate(double(chosen().max_cycles));
}
DeviceConfig SizeReport::default_widths() const {
  DeviceConfig d;  // the default widths, with the configuration's lanes, memories, voxmap values and bricks
  for (int DeviceConfig::*kept : {&DeviceConfig::LANES, &DeviceConfig::SAW, &DeviceConfig::MAW, &DeviceConfig::SB,
                                  &DeviceConfig::WB, &DeviceConfig::BL})
    d.*kept = config.*kept;
  return d;
}
uint64_t SizeReport::shell_bits() const { return shell_memory_bits(config); }
uint64_t SizeReport::map_bits() const { return map_memory_bits(config); }

namespace {

// The voxmap kind: chosen for the contact accuracy (the scene made again with it when it differs from the file's),
// or the scene file's own. Fills r.kind, r.convex and r.scene, and returns the scene file as sized.
RunConfig choose_kind(SizeReport& r, const RunConfig& f, const Scene& scene) {
  r.convex = types_convex(f);
  RunConfig sized = f;
  r.scene = scene;
  if (r.contact_accuracy <= 0) {
    r.kind = f.distance_bits ? VoxmapKind{f.distance_bits, DeviceConfig{}.WB, f.band} : VoxmapKind{};
    return sized;
  }
  r.kind = choose_voxmap(scene, r.convex, r.contact_accuracy, r.accuracy, band_for_motion(scene, f), f.ccd);
  sized.distance_bits = r.kind.distance() ? r.kind.SB : 0;
  if (r.kind.distance()) sized.band = r.kind.band;
  else sized.given.erase("band");  // the file's band is of the distance fields this scene no longer has
  if (sized.distance_bits != f.distance_bits || sized.band != f.band) r.scene = make_scene(sized);
  return sized;
}

// r.contact_error: the largest over ordered pairs (A's shell in B's voxmap) of voxel_B * the kind's terms over B
// plus the pair's fixed-point bound.
void bound_contacts(SizeReport& r) {
  r.contact_error = contact_error_bound(r.config, r.extents, r.kind, r.convex, &r.contact_type, &r.contact_terms);
}

// The clock of cfg: the one given, else the configuration's own (measured, or an estimate that says so).
DeviceClock clock_at(const SizeReport& r, const DeviceConfig& cfg) {
  return r.clock_given ? *r.clock_given : clock_for(cfg);
}

// The depth for the clock on req.target (r.target, r.depth, r.asic_row) among the rows of base's lanes, and base at
// that depth. Without a clock given, the clock to meet is the default depth's.
DeviceConfig choose_target_depth(SizeReport& r, const SizeRequest& req, const DeviceConfig& base) {
  const TimingTable& table = req.timing ? *req.timing : builtin_timing_table();
  r.target = req.target;
  r.depth = choose_depth(table, req.target, clock_at(r, at_depth(base, 0)).mhz, base);
  const DeviceConfig cfg = at_depth(base, r.depth->depth());
  r.asic_row.reset();
  const TimingRow* row = nearest_row(table, "asic-osu018", cfg);
  if (row && row->depth == cfg.depth && row->area_mm2) r.asic_row = *row;
  return cfg;
}

}  // namespace

namespace {

// What is asked: the request's values, or the scene file's where it gives none.
void take_request(SizeReport& r, const RunConfig& f, const Scene& input_scene, const SizeRequest& req) {
  r.file = f.where;
  r.accuracy = req.accuracy > 0 ? req.accuracy : accuracy_or_default(f, input_scene);
  r.contact_accuracy = req.contact_accuracy > 0 ? req.contact_accuracy : f.contact_accuracy;
  r.rate = req.rate > 0 ? req.rate : f.rate;
  r.clock_given = req.clock                ? req.clock
                  : req.clock_mhz != 0 ? given_clock(req.clock_mhz, "SizeOptions::clock_mhz")
                                       : f.clock;
  r.frames = req.frames > 0 ? req.frames : f.frames;
}

// cfg at `lanes`: with a target at the depth for the clock (choose_target_depth), its memories grown to fit.
DeviceConfig at_lanes(SizeReport& r, const Scene& scene, const SizeRequest& req, DeviceConfig cfg, int lanes) {
  cfg.LANES = lanes;
  if (!req.target.empty()) cfg = choose_target_depth(r, req, cfg);
  return derive_memory(cfg, scene);
}

// The fewest lanes (a power of two, as the RTL is built) whose largest measured frame fits the cycle budget at that
// configuration's clock (r.clock, r.budget), each count measured into r.lanes with its memories; cfg at that count.
// SizeError "rate" when 64 lanes do not.
DeviceConfig choose_lanes(SizeReport& r, const Scene& scene, const RunConfig& sized, DeviceConfig cfg,
                          const SizeRequest& req) {
  for (int lanes = 1; lanes <= 64; lanes *= 2) {
    cfg = at_lanes(r, scene, req, cfg, lanes);
    r.clock = clock_at(r, cfg);
    const double budget = r.clock.mhz * 1e6 / r.rate;
    r.budget = uint64_t(std::floor(budget));
    r.lanes.push_back(measure_frames(scene, sized, cfg, r.frames));
    if (double(r.lanes.back().max_cycles) <= budget) return cfg;
  }
  const LaneMeasure& m = r.lanes.back();
  const double best = r.clock.rate(double(m.max_cycles));
  throw SizeError("rate", r.rate / best,
                  "64 lanes take " + std::to_string(m.max_cycles) + " cycles for the largest of " +
                      std::to_string(r.frames) + " frames, " + fmt(best) + " frames per second at " +
                      r.clock.text() + "; " + fmt(r.rate, 8) + " requested is " + fmt(r.rate / best) +
                      " times faster");
}

// Copies against banks: the same frames with one voxmap in LANES banks (8 x LANES on a distance device: each parity
// bank split LANES ways), where the memory has that many words.
void measure_banked(SizeReport& r, const Scene& scene, const RunConfig& sized) {
  DeviceConfig shared = r.config;
  shared.BANKS = r.config.LANES;
  if (r.config.LANES < 2 || int64_t(memory_banks(shared)) > (int64_t{1} << std::min(r.config.MAW, 28))) return;
  SizeReport::Banked b;
  b.config = shared;
  b.measure = measure_frames(scene, sized, b.config, r.frames);
  b.clock = clock_at(r, b.config);
  b.budget = uint64_t(std::floor(b.clock.mhz * 1e6 / r.rate));
  r.banked = b;
}

// The block RAMs on the target, and with req.cost the syntheses (the standard-cell area with a target).
void add_costs(SizeReport& r, const SizeRequest& req) {
  if (r.depth) r.rams = block_rams(r.config, r.target);
  if (req.cost && r.depth) r.asic = asic_cost(r.config, r.depth->clock_mhz, req.rtl_dir);
  if (!req.cost) return;
  r.cost = yosys_cost(r.config, req.rtl_dir);
  r.default_cost = yosys_cost(r.default_widths(), req.rtl_dir);
  if (r.banked) r.banked->cost = yosys_cost(r.banked->config, req.rtl_dir);
}

}  // namespace

namespace {

// The BL of the scene's bricks (make_scene stores every type with the host's one), or the host's choice when no type
// is stored sparse.
int scene_bl(const Scene& scene, bool distance) {
  for (const auto& t : scene.types) {
    const ObjectFile& o = t->object;
    if (distance && o.distance_sparse()) return SparseDistanceField::kBrickLog;
    if (!distance && o.voxmap_sparse()) return o.sparse_voxmap.bl();
  }
  return kDefaultBrickLog;
}

// The head (what is asked, the voxmap kind, the scene as `run` stores it) sized in one storage: the scene stored as
// `stored_as`, on a sparse device when `sparse`; its widths, lanes (its own frames) and memories.
SizeReport derive_layout(SizeReport r, RunConfig run, ObjectStorage stored_as, bool sparse, const SizeRequest& req) {
  if (run.storage != stored_as) {
    run.storage = stored_as;
    r.scene = make_scene(run);
  }
  r.objects = r.scene.bodies.size();
  r.extents = scene_extents(r.scene);
  DeviceConfig base;
  base.SB = r.kind.SB;
  base.WB = r.kind.WB;
  if (sparse) base.BL = scene_bl(r.scene, r.kind.distance());
  // A distance device's weights fit TF (WB <= TF), a sparse one's a level-3 brick's too (WB + 3 <= TF).
  const int min_tf = r.kind.distance() ? r.kind.WB + (sparse ? 3 : 0) : 0;
  const DeviceConfig widths = derive_widths(r.extents, r.accuracy, base, min_tf);
  r.error = size_error_bound(widths, r.extents, &r.worst_pair);
  r.config = choose_lanes(r, r.scene, run, widths, req);
  r.config.validate();
  std::vector<const ObjectType*> types;
  for (const auto& t : r.scene.types) types.push_back(t.get());
  StorageLayout& l = sparse ? r.storage.sparse : r.storage.dense;
  l.storage = stored_as;
  l.config = r.config;
  l.measure = r.chosen();
  l.words = layout_words(r.config, types);
  r.shell_words = l.words.shell;
  r.map_words = l.words.map();
  bound_contacts(r);
  return r;
}

// Which storage is fixed and by what (SizeRequest::storage, else the scene file's "storage"; "auto" fixes none), and
// how the sparse layout stores the types: sparse, or each part in its smaller form when "auto" was asked for.
struct StoragePlan {
  std::optional<ObjectStorage> fixed;
  std::string fixed_by;
  ObjectStorage sparse = ObjectStorage::kSparse;
};

StoragePlan storage_plan(const RunConfig& f, const SizeRequest& req) {
  StoragePlan p;
  std::optional<ObjectStorage> asked;
  std::string by;
  if (req.storage) {
    asked = req.storage;
    by = req.storage_source;
  } else if (f.given.count("storage")) {
    asked = f.storage;
    by = f.where + "'s \"storage\"";
  }
  if (asked == ObjectStorage::kAuto) {
    p.sparse = ObjectStorage::kAuto;
  } else if (asked) {
    p.fixed = asked;
    p.fixed_by = by;
  }
  return p;
}

// One layout's derivation: its report, or why it cannot be met.
struct Attempt {
  std::optional<SizeReport> report;
  std::optional<SizeError> error;
  StorageLayout layout(bool sparse, ObjectStorage storage) const {
    if (report) return sparse ? report->storage.sparse : report->storage.dense;
    StorageLayout l;
    l.storage = storage;
    l.failed = error->what();
    return l;
  }
};

Attempt attempt_layout(const SizeReport& head, const RunConfig& run, ObjectStorage stored_as, bool sparse,
                       const SizeRequest& req) {
  Attempt a;
  try {
    a.report = derive_layout(head, run, stored_as, sparse, req);
  } catch (const SizeError& e) {
    a.error = e;
  }
  return a;
}

// Neither layout can be met: the dense one's error, with the sparse one's reason when it differs.
SizeError neither_met(const SizeError& dense, const SizeError& sparse) {
  const std::string what = std::string(dense.what()).substr(dense.constraint.size() + 2);
  if (std::string(dense.what()) == sparse.what()) return dense;
  return SizeError(dense.constraint, dense.factor, what + "; stored sparse on a sparse device: " + sparse.what());
}

// The report of the layout taken (the fixed one, else the one met, else the one of less device memory; dense on a
// tie: it has fewer pipeline registers) with both layouts in r.storage.
SizeReport choose_storage(const StoragePlan& plan, const Attempt& dense, const Attempt& sparse) {
  bool take_sparse = false;
  if (plan.fixed) {
    const Attempt& a = *plan.fixed == ObjectStorage::kSparse ? sparse : dense;
    if (a.error) throw *a.error;
    take_sparse = *plan.fixed == ObjectStorage::kSparse;
  } else if (!dense.report && !sparse.report) {
    throw neither_met(*dense.error, *sparse.error);
  } else {
    take_sparse = !dense.report || (sparse.report && sparse.report->storage.sparse.memory_bits() <
                                                         dense.report->storage.dense.memory_bits());
  }
  SizeReport r = take_sparse ? *sparse.report : *dense.report;
  r.storage.dense = dense.layout(false, ObjectStorage::kDense);
  r.storage.sparse = sparse.layout(true, plan.sparse);
  r.storage.chose_sparse = take_sparse;
  r.storage.fixed_by = plan.fixed_by;
  return r;
}

}  // namespace

std::string StorageChoice::why() const {
  const StorageLayout &c = chosen(), &o = other();
  const std::string other_name = chose_sparse ? "dense" : "sparse";
  const std::string against =
      std::to_string(c.memory_bytes()) + " bytes of device memory" +
      (o.met() ? " against " + std::to_string(o.memory_bytes()) + " stored " + other_name
               : "; stored " + other_name + " it cannot be met (" + o.failed + ")");
  if (!fixed_by.empty()) return "fixed by " + fixed_by + ": " + against;
  if (!o.met()) return "the only storage that can be met: " + against;
  if (c.memory_bytes() == o.memory_bytes()) return "equal memory, so the dense device (fewer registers): " + against;
  return "the smaller device memory: " + against;
}

SizeReport derive_size(const RunConfig& f, const Scene& input_scene, const SizeRequest& req) {
  SizeReport head;
  take_request(head, f, input_scene, req);
  const RunConfig sized = choose_kind(head, f, input_scene);
  const StoragePlan plan = storage_plan(f, req);
  const Attempt dense = attempt_layout(head, sized, ObjectStorage::kDense, false, req);
  const Attempt sparse = attempt_layout(head, sized, plan.sparse, true, req);
  SizeReport r = choose_storage(plan, dense, sparse);
  r.energy = lookup_energy(r.config, req.energy ? *req.energy : builtin_energy_table());
  measure_banked(r, r.scene, sized);
  add_costs(r, req);
  return r;
}

}  // namespace voxcd
