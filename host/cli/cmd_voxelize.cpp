// voxcd voxelize: a mesh file or a built-in shape to an object file (voxmap, point shell), optionally a picture.
#include <cmath>
#include <iostream>

#include "voxcd/host/cli/commands.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/report/object_report.h"

namespace voxcd::cli {

using report::object_json;
using report::object_text;
using report::write_object_picture;

namespace {

// A positive finite number, with a message that says so (CLI::PositiveNumber prints the whole double range).
const CLI::Validator kPositive(
    [](std::string& v) -> std::string {
      try {
        size_t used = 0;
        const double d = std::stod(v, &used);
        if (used == v.size() && std::isfinite(d) && d > 0) return "";
      } catch (const std::exception&) {
      }
      return "'" + v + "' is not a positive finite number";
    },
    "POSITIVE");

// The node value widths a distance device has (docs/contract.md, "Distance voxmaps").
const CLI::Validator kDistanceBitsCheck(
    [](std::string& v) -> std::string {
      for (int b : kDistanceBits)
        if (v == std::to_string(b)) return "";
      return "'" + v + "' is not " + distance_bits_text() + " (bits per node value)";
    },
    "4|8|16");

struct VoxelizeArgs {
  std::string input;
  ObjectOptions object;  // the voxel, shell, threads and distance field
  std::string storage = "auto";
  bool strict = false;
  std::string output;
  std::string png;
  bool json = false;
};

int voxelize_cmd(const VoxelizeArgs& a) {
  std::string source;
  uint64_t hash = 0;
  MeshReport report;
  const Mesh mesh = load_source(a.input, &source, &hash, &report, LoadOptions{a.strict});
  ObjectOptions opt = a.object;
  // A sparse object's memory grows with its surface: it may be up to kMaxSparseVoxelsAcross voxels across.
  set_storage(opt, *parse_storage(a.storage));
  const ObjectFile obj = make_object(mesh, source, hash, opt, &report);
  write_object(a.output, obj);
  if (!a.png.empty()) write_object_picture(a.png, obj, &mesh);
  std::cout << (a.json ? object_json(a.output, obj) : object_text(a.output, obj));
  return 0;
}

}  // namespace

void add_voxelize(CLI::App& app) {
  auto a = std::make_shared<VoxelizeArgs>();
  const std::string shapes = comma_list(shape_names());
  CLI::App* c = app.add_subcommand("voxelize", "Voxelise a mesh file or a built-in shape into an object file "
                                               "(voxmap and point shell, docs/objects.md)");
  c->add_option("input", a->input,
                "MESH|SHAPE: a mesh file (.raw, or any format assimp reads: OBJ, STL, PLY, OFF, glTF, ...) or a "
                "built-in shape (" + shapes + ")")
      ->required();
  CLI::Option* voxel = c->add_option("--voxel", a->object.voxel, "Voxel edge length in mesh units")->check(kPositive);
  CLI::Option* res = c->add_option("--resolution", a->object.resolution,
                                   "Voxels along the model's longest side (instead of --voxel; at least 4)")
                         ->check(CLI::Range(1u, 1u << 20));
  voxel->excludes(res);
  res->excludes(voxel);
  c->add_flag("--strict", a->strict,
              "Refuse any mesh that is not a closed, edge-manifold, consistently oriented surface (no repair)");
  c->add_option("-o,--output", a->output, "Object file to write")->required();
  c->add_option("--png", a->png, "Also write a picture: voxmap slices and the shell over the mesh");
  c->add_option("--shell-ratio", a->object.shell_ratio, "Voxel size / shell spacing (the paper's rule: sqrt(2))")
      ->check(kPositive)
      ->capture_default_str();
  c->add_option("--threads", a->object.threads, "Worker threads (0: one per hardware thread)")->capture_default_str();
  c->add_flag("--json", a->json, "Describe the written object as JSON (as `voxcd info --json`)");
  c->add_option("--storage", a->storage,
                "auto: the voxmap and the shell each dense or sparse, whichever takes less device memory (sparse "
                "objects up to 4096 voxels across); dense; sparse (docs/objects.md, \"Sparse objects\")")
      ->check(CLI::IsMember({"auto", "dense", "sparse"}))
      ->capture_default_str();
  CLI::Option* bits =
      c->add_option("--distance-bits", a->object.distance_bits,
                    "Also store the signed distance field at the voxmap's nodes, quantised to 4, 8 or 16 bits over "
                    "the band (object file version 3; the shell then lies on the surface)")
          ->check(kDistanceBitsCheck);
  c->add_option("--band", a->object.band, "Half-width of the distance field's band in voxels (with --distance-bits): "
                                   "the step is band / 2^(bits-1)")
      ->check(kPositive)
      ->needs(bits)
      ->capture_default_str();
  c->callback([a, voxel, res] {
    if (!*voxel && !*res) throw CLI::RequiredError("--voxel or --resolution");
    exit_code() = voxelize_cmd(*a);
  });
}

}  // namespace voxcd::cli
