// voxcd info: what an object file holds (dimensions, voxel size, states, shell, device memory), as text or JSON,
// and optionally its picture.
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

struct InfoArgs {
  std::string file;
  bool json = false;
  std::string png;
};

// The object's mesh for the picture, when it can be had again unchanged: a built-in shape, or the source file
// with the same hash. Otherwise the picture shows the shell points alone.
bool source_mesh(const ObjectFile& obj, Mesh& mesh, std::string& why_not) {
  try {
    if (obj.source.rfind("shape:", 0) == 0) {
      mesh = make_shape(obj.source.substr(6));
      return true;
    }
    if (hash_file(obj.source) != obj.source_hash) {
      why_not = obj.source + " has changed since the object was made";
      return false;
    }
    mesh = load_mesh(obj.source);
    return true;
  } catch (const std::exception& e) {
    why_not = e.what();
    return false;
  }
}

int info_cmd(const InfoArgs& a) {
  const ObjectFile obj = read_object(a.file, ObjectRead::kStored);  // the picture makes the dense forms it needs
  if (!a.png.empty()) {
    Mesh mesh;
    std::string why_not;
    const bool have = source_mesh(obj, mesh, why_not);
    if (!have) std::cerr << "voxcd info: drawing the shell without its mesh: " << why_not << '\n';
    write_object_picture(a.png, obj, have ? &mesh : nullptr);
  }
  std::cout << (a.json ? object_json(a.file, obj) : object_text(a.file, obj));
  return 0;
}

}  // namespace

void add_info(CLI::App& app) {
  auto a = std::make_shared<InfoArgs>();
  CLI::App* c = app.add_subcommand("info", "Describe an object file: dimensions, voxel size, voxels per state, "
                                           "shell points and device memory");
  c->add_option("file", a->file, "Object file (written by voxcd voxelize)")->required();
  c->add_flag("--json", a->json, "Print JSON (keys dims, voxel_size, empty, surface, interior, shell_points, ...)");
  c->add_option("--png", a->png, "Also write a picture: voxmap slices and the shell over the mesh");
  c->callback([a] { exit_code() = info_cmd(*a); });
}

}  // namespace voxcd::cli
