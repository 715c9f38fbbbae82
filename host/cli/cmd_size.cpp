// voxcd size: the smallest device for a scene file at a requested accuracy and frame rate (widths, memories,
// lanes, and with --target the pipeline depth for the clock), with its predicted error, cycles per frame, latency,
// memory and, with --cost, its yosys cost. docs/size.md.
#include <iostream>

#include "voxcd/host/cli/commands.h"
#include "voxcd/host/sizing/size.h"

namespace voxcd::cli {

namespace {

struct SizeArgs {
  std::string file;
  SizeRequest req;
  std::string timing_table;  // --timing-table when given
  std::string storage;       // --storage when given
  bool json = false;
};

int size_cmd(const SizeArgs& a, const CLI::App& cmd) {
  const RunConfig f = read_scene_file(a.file);
  print_notes(f, "size");
  const Scene scene = make_scene(f);
  SizeRequest req = a.req;
  if (cmd.count("--clock")) req.clock = clock_option(req.clock_mhz, "--clock");
  if (cmd.count("--storage")) {
    req.storage = parse_storage(a.storage);
    req.storage_source = "--storage";
  }
  if (!a.timing_table.empty()) {
    if (req.target.empty()) throw CLI::ValidationError("--timing-table", "needs --target (the table chooses a depth for it)");
    req.timing = read_timing_table(a.timing_table);
  }
  SizeReport r;
  try {
    r = derive_size(f, scene, req);
  } catch (const SizeError& e) {
    std::cerr << "voxcd size: " << a.file << ": cannot be met: " << e.what() << '\n';
    return 3;
  }
  std::cout << (a.json ? size_json(r) : size_text(r));
  return 0;
}

}  // namespace

void add_size(CLI::App& app) {
  auto a = std::make_shared<SizeArgs>();
  a->req.rtl_dir = default_rtl_dir();
  CLI::App* c = app.add_subcommand(
      "size", "The smallest device for a scene file: widths from its extents and the accuracy, memories from its "
              "object types, lanes from the frame rate through the cycle model (docs/size.md)");
  c->add_option("scene", a->file, "A scene file (docs/scenes.md)")->required()->check(CLI::ExistingFile);
  c->add_option("--accuracy", a->req.accuracy, "Largest error of the fixed-point path, world units (default: the "
                                               "scene file's)")
      ->check(CLI::PositiveNumber);
  c->add_option("--contact-accuracy", a->req.contact_accuracy,
                "How far outside the other object's surface a contact may lie, world units: chooses the voxmaps "
                "(2-bit states, or distance voxmaps' SB, WB and band) (default: the scene file's, or its voxmaps)")
      ->check(CLI::PositiveNumber);
  c->add_option("--rate", a->req.rate, "Frames per second (default: the scene file's)")->check(CLI::PositiveNumber);
  c->add_option("--clock", a->req.clock_mhz,
                "Device clock, MHz (default: " + default_clock_help("the derived configuration") + ")");
  c->add_option("--target", a->req.target,
                "Choose the pipeline depth for the clock on this target: the shallowest whose measured clock meets it "
                "(the timing table of bench/timing.sh, docs/size.md); reports its latency, area at 0.18 um and block RAMs")
      ->check(CLI::IsMember(timing_targets()));
  c->add_option("--timing-table", a->timing_table,
                "The timing table to choose the depth from (default: the one built in, host/device/timing.tsv)")
      ->check(CLI::ExistingFile);
  c->add_option("--storage", a->storage,
                "dense or sparse: size the device for the types stored so; auto: size both and take the one of less "
                "device memory, each part of a sparse type in its smaller form (default: the scene file's "
                "\"storage\", else both with the types stored sparse; docs/size.md, \"Sparse or dense\")")
      ->check(CLI::IsMember({"auto", "dense", "sparse"}));
  c->add_option("--frames", a->req.frames, "Frames simulated to measure cycles (default: the scene file's)")
      ->check(CLI::Range(uint64_t{1}, kMaxFrames));
  c->add_flag("--cost", a->req.cost,
              "Also synthesise the configuration, and the default widths at its LANES, SAW and MAW, with yosys "
              "(synth_xilinx) for LUTs, FFs, DSPs and block RAMs; about 10 s each");
  c->add_option("--rtl", a->req.rtl_dir, "The directory of the RTL file list voxcd.f for --cost (default: the installed package's)")->capture_default_str();
  c->add_flag("--json", a->json, "Print the report as JSON");
  c->callback([a, c] { exit_code() = size_cmd(*a, *c); });
}

}  // namespace voxcd::cli
