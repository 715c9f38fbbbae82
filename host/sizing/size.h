// Sizing a device for a scene (`voxcd size`): the smallest widths that hold the scene's extents and meet the
// requested accuracy through the error bound of docs/contract.md, the smallest memories that hold the scene's
// object types as the host packs them (DeviceImage), and the fewest lanes that meet the requested frame rate
// through ref/'s cycle model on the scene's measured frames; with the cost of that configuration from yosys.
// docs/size.md derives each step.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/device/clock.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/sizing/asic_cost.h"
#include "voxcd/host/sizing/block_rams.h"
#include "voxcd/host/sizing/contact_bound.h"
#include "voxcd/host/sizing/depth.h"
#include "voxcd/host/sizing/energy_table.h"
#include "voxcd/host/sizing/errors.h"
#include "voxcd/host/sizing/size_options.h"
#include "voxcd/host/sizing/storage_layout.h"
#include "voxcd/host/device/timing_table.h"
#include "voxcd/ref/config.h"

namespace voxcd {

// What the widths must hold, measured from the scene's object types.
struct SceneExtents {
  double max_point = 0;        // largest shell coordinate of any type, in its shell spacings (max_j |p_j|)
  double max_ratio = 0;        // largest shell spacing of A over voxel of B, any ordered pair: the largest |M_ij|
  double max_translation = 0;  // bound on |t_i| in B's voxels for any two bodies in the cube (grown by a radius)
  uint32_t max_dim = 1;        // largest voxmap dimension
  // Per ordered pair (A's shell in B's map): B's voxel, A's largest shell coordinate and A's shell spacing over
  // B's voxel (the bound's inputs).
  struct Pair {
    uint32_t a = 0, b = 0;
    double voxel_b = 0, max_point_a = 0, ratio = 0;
  };
  std::vector<Pair> pairs;
};
SceneExtents scene_extents(const Scene& scene);

// The fixed-point path's error bound for the scene's pairs on cfg, in world units: the largest over ordered pairs of
// voxel_B * (3 * 2^-(MF+1) * max|p_A| + 2^-(TF+1)): shell words are exact half-integers from PF 1 on, so the
// point term is 0; with PF 0 it is added (|Mq_i|_1 * 2^-(PF+1), |Mq_i|_1 <= 3 (ratio + 2^-(MF+1))). `worst` gets
// the index of the pair that gives it.
double size_error_bound(const DeviceConfig& cfg, const SceneExtents& e, size_t* worst = nullptr);

// How far outside the other object's surface a contact can lie on cfg with voxmaps of kind k, world units: the
// largest over ordered pairs (A's shell in B's voxmap) of voxel_B * contact_terms(k, convex[B]).total() plus the
// pair's fixed-point bound. `worst_type` gets the B that gives it, `worst_terms` its terms.
double contact_error_bound(const DeviceConfig& cfg, const SceneExtents& e, const VoxmapKind& k,
                           const std::vector<bool>& convex, size_t* worst_type = nullptr,
                           ContactTerms* worst_terms = nullptr);

// The memories' bits: the shell memory 2^SAW x 3 PW, and the voxmap memory 2^MAW x MEMW with one copy per lane (one
// in all with shared banks, DeviceConfig::BANKS).
uint64_t shell_memory_bits(const DeviceConfig& cfg);
uint64_t map_memory_bits(const DeviceConfig& cfg);

// The smallest PW, PF, MW, MF, TW, DW for the extents and accuracy (world units), with at least min_tf translation
// fraction bits (a distance device's WB <= TF), and on a sparse device (base.BL > 0) PW at least 24 (its shell word
// holds a shell brick: 3 PW >= 72); MEMW, TAGW, LANES, SAW, MAW, SB, WB and BL as in `base`. SizeError
// "accuracy" when even the widest formats (MW 32, TW 64) cannot meet it, "extent" when the scene's coordinates need
// more than PW 32 or TW 64.
DeviceConfig derive_widths(const SceneExtents& e, double accuracy, DeviceConfig base = {}, int min_tf = 0);

// cfg with the smallest SAW and MAW into which DeviceImage packs the types (type_shell_words, type_map_words: on a
// sparse device a type stored sparse as its sparse words; SAW at least log2(LANES), one row per shell bank);
// SizeError "memory" naming the amount when the largest memories (SAW 24, MAW 28) are too small.
DeviceConfig derive_memory(DeviceConfig cfg, const Scene& scene);

// The scene's frames measured on the cpu backend at one lane count (ref/'s cycle model).
struct LaneMeasure {
  int lanes = 0;
  uint64_t max_cycles = 0;  // the largest frame
  double mean_cycles = 0;
  double pairs = 0, tested = 0, lookups = 0, hits = 0;  // per frame
};
// The simulation options the sizing steps run a scene file's scene with: its broadphase, mode, directions, voxmaps
// and ccd on the cpu backend with the whole configuration cfg.
RunConfig sizing_sim_options(const RunConfig& f, const DeviceConfig& cfg);
LaneMeasure measure_frames(const Scene& scene, const RunConfig& f, const DeviceConfig& cfg, uint64_t frames);

// yosys synth_xilinx (7-series) of voxcd_device with every parameter of cfg set by chparam, from the files of
// rtl_dir's voxcd.f ("" = the package's RTL, host/package/paths.h).
struct YosysCost {
  uint64_t luts = 0, ffs = 0, dsps = 0;
  double brams = 0;  // RAMB36 units (a RAMB18 is a half)
  double seconds = 0;
  std::string version, command;
};
// Throws std::runtime_error when yosys is missing or fails (with the end of its log).
YosysCost yosys_cost(const DeviceConfig& cfg, const std::string& rtl_dir = "");
// The package's RTL directory (share/voxcd/rtl), or "" when it cannot be found (yosys_cost then says where it looked).
std::string default_rtl_dir();

// What is asked of the device (SizeOptions: 0 takes the scene file's value, or its default) and how it is sized.
// contact_accuracy (contact_bound.h) chooses the voxmap kind (2-bit states, or SB, WB and band) to meet it; 0: the
// scene file's "contact_accuracy", and without it the scene file's own distance_bits and band. With cost, the
// configuration and its default widths are synthesised too (SizeReport::cost, default_cost; yosys_cost's errors).
struct SizeRequest : SizeOptions {
  // The clock with where it was given; unset: clock_mhz when not 0 ("given by SizeOptions::clock_mhz"), else the
  // scene file's "clock", else each candidate configuration's own (clock_for: measured, or an estimate that says so).
  std::optional<DeviceClock> clock;
  std::string rtl_dir;  // the RTL for cost ("" = the package's)
  // How the types are stored (docs/size.md, "Sparse or dense"): kDense or kSparse fixes it; kAuto, or unset with no
  // "storage" in the scene file (or its "auto"), sizes both and takes the one of less device memory.
  std::optional<ObjectStorage> storage;
  std::string storage_source = "SizeRequest::storage";  // how reports name it ("--storage")
  // The implementation target (timing_targets(): "asic-osu018", "ice40-hx8k", "ice40-up5k", "xilinx-7") whose
  // measured clocks choose the pipeline depth: the shallowest that meets the clock (choose_depth, for each lane count
  // tried from the rows measured at it when the table has some; without a clock given, the default depth's).
  // "": the default depth, no choice. With cost, the configuration's standard-cell area at 0.18 um is synthesised too (asic_cost).
  std::string target;
  std::optional<TimingTable> timing;  // the table to choose from; unset: builtin_timing_table()
  std::optional<EnergyTable> energy;  // the energy per lookup (SizeReport::energy); unset: builtin_energy_table()
};

// The scene's types in one storage, sized whole (docs/size.md, "Sparse or dense"): stored dense on a dense device, or
// stored sparse (each part in its smaller form with "auto") on a sparse device (BL > 0) with its own widths (PW >= 24),
// memories and lanes measured on its own frames.
struct StorageLayout {
  ObjectStorage storage = ObjectStorage::kDense;  // how the scene's types were stored (make_scene)
  std::string failed;     // not empty: this storage cannot be met, and why (the SizeError's text)
  DeviceConfig config;    // the derived configuration
  LaneMeasure measure;    // its largest and mean frame at config.LANES
  LayoutWords words;      // DeviceImage's words of the types on config
  bool met() const { return failed.empty(); }
  uint64_t memory_bits() const { return shell_memory_bits(config) + map_memory_bits(config); }
  uint64_t memory_bytes() const { return memory_bits() / 8; }
};

// Dense or sparse: both layouts and which one the report is of.
struct StorageChoice {
  StorageLayout dense, sparse;
  bool chose_sparse = false;
  std::string fixed_by;  // "--storage" or the scene file's "storage" when they fixed it; "": the smaller memory chose
  const StorageLayout& chosen() const { return chose_sparse ? sparse : dense; }
  const StorageLayout& other() const { return chose_sparse ? dense : sparse; }
  std::string why() const;  // "the smaller device memory: 26624 bytes against 57344 stored dense", ...
};

struct SizeReport {
  std::string file;
  Scene scene;  // as sized: the scene file's, or remade with the voxmap kind chosen for contact_accuracy
  double accuracy = 0, rate = 0;
  // The clock of the budget and the modelled rate, with its source: the given one (clock_given), else the
  // configuration's (clock_for).
  DeviceClock clock;
  std::optional<DeviceClock> clock_given;  // the request's clock, or the scene file's "clock"
  // The voxmap kind and how far outside the other surface a contact can lie with it, world units (the largest over
  // the types as B of voxel_B * terms + the fixed-point bound of the worst pair into B).
  double contact_accuracy = 0;  // requested (0: not requested; the scene file's kind is reported)
  VoxmapKind kind;
  double contact_error = 0;
  size_t contact_type = 0;      // the B that gives contact_error
  ContactTerms contact_terms;   // its terms, voxels of B
  std::vector<bool> convex;     // per type
  uint64_t frames = 0, objects = 0;
  DeviceConfig config;
  SceneExtents extents;
  double error = 0;          // predicted worst-case error, world units (size_error_bound)
  size_t worst_pair = 0;     // index into extents.pairs
  uint64_t shell_words = 0, map_words = 0;  // the packed image (storage.chosen().words)
  StorageChoice storage;     // dense or sparse; config, lanes and memory above are those of storage.chosen()
  uint64_t budget = 0;       // cycles per frame the rate allows at the clock (of config)
  std::vector<LaneMeasure> lanes;  // every lane count measured, ascending; the last is config.LANES
  const LaneMeasure& chosen() const { return lanes.back(); }
  double modelled_rate() const;   // clock / largest frame's cycles (0 when the frames needed no device cycles)
  uint64_t shell_bits() const;    // 2^SAW x 3 PW
  uint64_t map_bits() const;      // 2^MAW x MEMW, one copy per lane (a distance device's 8 banks share the 2^MAW)
  std::optional<YosysCost> cost;
  // The chosen configuration with shared voxmap banks instead of a copy per lane (BANKS = LANES: LANES banks, or 8 x
  // LANES on a distance device; devices with more than one lane): the same frames measured again, its memory, and
  // its cost when synthesised.
  struct Banked {
    DeviceConfig config;
    LaneMeasure measure;
    DeviceClock clock;    // its own clock (the given one, else clock_for(config))
    uint64_t budget = 0;  // cycles per frame the rate allows at that clock
    std::optional<YosysCost> cost;
    uint64_t map_bits() const { return map_memory_bits(config); }
    bool meets() const { return measure.max_cycles <= budget; }
  };
  std::optional<Banked> banked;
  // The same LANES, SAW, MAW, SB, WB and BL at the default widths, synthesised the same way (the peer for the cost).
  std::optional<YosysCost> default_cost;
  DeviceConfig default_widths() const;
  // With a target: the chosen depth and why, the timing table's asic-osu018 measurement nearest the configuration at
  // that depth (nearest_row: the area of the table's configuration, when the table has one), the block RAMs the configuration takes on the target, and
  // with cost the configuration's own standard-cell area.
  std::string target;
  std::optional<DepthChoice> depth;
  std::optional<TimingRow> asic_row;
  std::optional<BlockRams> rams;
  std::optional<AsicCost> asic;
  // The energy of a frame and the power at the requested rate (docs/size.md, "Energy and power"): the mean frame's
  // lookups (chosen().lookups, the average power's) x the energy per lookup of config (lookup_energy: measured for
  // the same logic on the simulate scene's stimulus, else an estimate from the nearest row that says so).
  LookupEnergy energy;
  double frame_energy_j() const { return chosen().lookups * energy.pj * 1e-12; }
  double frame_energy_7nm_j() const { return chosen().lookups * energy.pj_7nm * 1e-12; }  // a projection
  double power_w() const { return frame_energy_j() * rate; }                               // at the requested rate
  double power_7nm_w() const { return frame_energy_7nm_j() * rate; }
  // Cycles from a job's acceptance to its first record on the pins (latency_cycles) and that time at the clock, ns.
  int latency() const { return latency_cycles(config); }
  double latency_ns() const { return latency() * 1e3 / clock.mhz; }
};

// The whole derivation (with the costs when req.cost) for the scene made from f (make_scene(f)); with a contact
// accuracy the scene is made again with the chosen voxmap kind, and in each storage it is not stored in (both
// layouts are sized, StorageChoice). SizeError when a constraint cannot be met (in the storage fixed, or in neither);
// SceneFileError from the scene; MeshError from a type's mesh (its convexity).
SizeReport derive_size(const RunConfig& f, const Scene& scene, const SizeRequest& req);

// The text and JSON reports of `voxcd size`.
std::string size_text(const SizeReport& r);
std::string size_json(const SizeReport& r);

}  // namespace voxcd
