// voxcd view: a recording, a scene file, an object file, a mesh or a pair of objects in a browser. Serves the page
// on 127.0.0.1 and prints its URL, or writes it as one self-contained HTML file (docs/view.md).
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>

#include "voxcd/host/cli/commands.h"
#include "voxcd/host/detail/text_file.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/report/object_report.h"
#include "voxcd/host/scene/record.h"
#include "voxcd/host/scene/simulate.h"
#include "voxcd/host/detail/base64.h"
#include "voxcd/host/view/object_view.h"
#include "voxcd/host/view/page.h"
#include "voxcd/host/view/pair_view.h"
#include "voxcd/host/view/server.h"

namespace voxcd::cli {

using report::json_text;

namespace {

struct ViewArgs {
  std::vector<std::string> files;
  CLI::App* app = nullptr;
  uint16_t port = 0;
  std::string html;
  double timeout = 0;
  uint64_t frames = 0;
  view::PairViewOptions pair;  // a pair's, and an object's voxel, resolution (when given) and distance field
  std::string pose;
};

std::string slurp(const std::string& path) {
  std::optional<std::string> bytes = detail::read_text_file(path);
  if (!bytes) throw std::runtime_error(path + ": cannot open");
  return std::move(*bytes);
}

bool is_scene_file(const std::string& path) {
  const std::filesystem::path p(path);
  return p.extension() == ".json" && std::filesystem::is_regular_file(p);
}

// Serves the page with `data` answering /data/... (or writes --html with `inline_data`) and returns 0.
int show(const ViewArgs& a, const std::string& what, const std::function<std::string()>& inline_data,
         const std::function<std::optional<view::HttpResponse>(const view::HttpRequest&)>& data) {
  view::check_three();
  if (!a.html.empty()) {
    std::ofstream out(a.html, std::ios::binary);
    const std::string page = view::self_contained_html(inline_data());
    if (!out.write(page.data(), std::streamsize(page.size())) || !out.flush())
      throw std::runtime_error(a.html + ": cannot write the page");
    std::printf("voxcd view: %s -> %s (%zu bytes, one self-contained file)\n", what.c_str(), a.html.c_str(), page.size());
    return 0;
  }
  view::HttpServer server(a.port);
  std::printf("voxcd view: %s at http://127.0.0.1:%u/ (Ctrl-C stops)\n", what.c_str(), unsigned(server.port()));
  std::fflush(stdout);
  server.serve(
      [&](const view::HttpRequest& r) {
        if (auto f = view::page_file(r.path)) return *f;
        if (auto d = data(r)) return *d;
        return view::HttpResponse{404, "text/plain; charset=utf-8", r.path + ": no such page"};
      },
      a.timeout);
  return 0;
}

view::HttpResponse json_response(std::string body) {
  return {200, "application/json", std::move(body)};
}

int view_recording(const ViewArgs& a, const std::string& file, const std::string& shown_name) {
  const Recording rec = read_recording(file);  // refuses what the page could not show, with the reason
  if (rec.truncated) std::fprintf(stderr, "voxcd view: %s\n", rec.note.c_str());
  const std::string what = "recording " + shown_name + " (" + std::to_string(rec.body_types.size()) + " bodies, " +
                           std::to_string(rec.frames.size()) + " frames)";
  const std::string info = json_text({{"kind", "recording"}, {"name", shown_name}, {"url", "data/recording.vxr"}});
  return show(
      a, what,
      [&] {
        const std::string bytes = slurp(file);
        return json_text({{"kind", "recording"},
                          {"name", shown_name},
                          {"bytes", view::detail::base64(bytes.data(), bytes.size())}});
      },
      [&](const view::HttpRequest& r) -> std::optional<view::HttpResponse> {
        if (r.path == "/data/info") return json_response(info);
        // Read again at each request: a recording still being written shows its new frames.
        if (r.path == "/data/recording.vxr") return view::HttpResponse{200, "application/octet-stream", slurp(file)};
        return std::nullopt;
      });
}

int view_scene(const ViewArgs& a, const std::string& file) {
  char tmpl[] = "/tmp/voxcd-view-XXXXXX";
  const int fd = mkstemp(tmpl);
  if (fd < 0) throw std::runtime_error("view: cannot make a temporary file for the recording");
  ::close(fd);
  struct Remove {
    std::string path;
    ~Remove() { std::filesystem::remove(path); }
  } remove{tmpl};
  RunConfig options;
  options.where = file;
  if (a.frames) options.frames = a.frames, options.given["frames"] = SettingSource{"", "frames"};
  options.record = tmpl;
  const RunConfig config = run_config(options);
  print_notes(config, "view");
  const SimulationSummary s = simulate(config);
  std::printf("voxcd view: simulated %llu frames of %s\n", (unsigned long long)s.config.frames, file.c_str());
  return view_recording(a, tmpl, file);
}

int view_object(const ViewArgs& a, const std::string& file) {
  const uint32_t res = a.app->count("--resolution") ? a.pair.resolution : 64;
  const view::ObjectView v = view::make_object_view(file, a.pair.voxel, res, a.pair.distance_bits, a.pair.band);
  const std::string data = view::object_view_json(v);
  const auto& d = v.object.voxmap_grid().dims;
  const std::string what = "object " + file + " (voxmap " + std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" +
                           std::to_string(d[2]) + ", " + std::to_string(v.object.shell_count()) + " shell points)";
  if (!v.note.empty()) std::fprintf(stderr, "voxcd view: %s\n", v.note.c_str());
  return show(a, what, [&] { return data; },
              [&](const view::HttpRequest& r) -> std::optional<view::HttpResponse> {
                if (r.path == "/data/info") return json_response(data);
                return std::nullopt;
              });
}

int view_pair(const ViewArgs& a) {
  view::PairView pv(a.files[0], a.files[1], a.pair);
  view::PairPose pose = pv.default_pose();
  if (!a.pose.empty()) {
    try {
      pose = view::parse_pair_pose(a.pose);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError("--pose", e.what());
    }
  }
  return show(a, "pair " + a.files[0] + " and " + a.files[1], [&] { return pv.page_json(pose); },
              [&](const view::HttpRequest& r) -> std::optional<view::HttpResponse> {
                if (r.path == "/data/info") return json_response(pv.page_json(pose));
                if (r.path == "/api/pair") {
                  const std::string key = "pose=";
                  if (r.query.rfind(key, 0) != 0) throw std::invalid_argument("/api/pair: give ?pose=tx,ty,tz,rx,ry,rz");
                  view::PairPose p;
                  try {
                    p = view::parse_pair_pose(r.query.substr(key.size()));
                  } catch (const std::invalid_argument& e) {
                    throw std::invalid_argument(std::string("pose: ") + e.what());
                  }
                  return json_response(pv.contacts_json(p));
                }
                return std::nullopt;
              });
}

// Refuses the options given that do not apply to what is shown (`what`), rather than ignore them.
void only(const ViewArgs& a, const std::string& what, const std::vector<std::string>& allowed) {
  for (const char* o : {"--frames", "--voxel", "--resolution", "--distance-bits", "--band", "--pose", "--backend",
                        "--both", "--margin"})
    if (a.app->count(o) && std::find(allowed.begin(), allowed.end(), o) == allowed.end())
      throw CLI::ValidationError(o, "does not apply to " + what);
}

int view_cmd(const ViewArgs& a) {
  const std::vector<std::string> object = {"--voxel", "--resolution", "--distance-bits", "--band"};
  if (a.files.size() == 2) {
    std::vector<std::string> pair = object;
    pair.insert(pair.end(), {"--pose", "--backend", "--both", "--margin"});
    only(a, "a pair", pair);
    return view_pair(a);
  }
  const std::string& f = a.files[0];
  if (is_recording(f)) return only(a, "a recording (" + f + ")", {}), view_recording(a, f, f);
  if (is_scene_file(f)) return only(a, "a scene file (" + f + ")", {"--frames"}), view_scene(a, f);
  only(a, "one object (" + f + ")", object);
  return view_object(a, f);
}

}  // namespace

void add_view(CLI::App& app) {
  auto a = std::make_shared<ViewArgs>();
  CLI::App* c = app.add_subcommand(
      "view", "Show a recording (simulate --record), a scene file, an object file, a mesh or shape, or a pair of "
              "objects in a browser: serves the page on 127.0.0.1 and prints its URL (docs/view.md)");
  a->app = c;
  c->add_option("files", a->files,
                "A recording, a scene file (simulated and recorded first), an object file, a mesh or a built-in "
                "shape; or two objects for a pair")
      ->required()
      ->expected(1, 2)
      ->check(CLI::ExistingFile | CLI::IsMember(shape_names()));
  c->add_option("--port", a->port, "Port on 127.0.0.1 (default: a free one)");
  c->add_option("--html", a->html, "Write one self-contained HTML file instead of serving (no pose editing for a pair)");
  c->add_option("--timeout", a->timeout, "Stop serving after this many seconds (0: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  c->add_option("--frames", a->frames, "Scene file: frames to simulate (default: the file's)")->check(CLI::PositiveNumber);
  CLI::Option* voxel = c->add_option("--voxel", a->pair.voxel, "Meshes and shapes: voxel size, world units")
                           ->check(CLI::PositiveNumber);
  CLI::Option* res = c->add_option("--resolution", a->pair.resolution,
                                   "Meshes and shapes: voxels along the longest side (default 64; 32 for a pair)")
                         ->check(CLI::Range(kMinVoxelsAcross, kMaxVoxelsAcross));
  voxel->excludes(res);
  res->excludes(voxel);
  c->add_option("--distance-bits", a->pair.distance_bits, "Meshes and shapes: also a distance field of B bits (4, 8, 16)")
      ->check(CLI::IsMember(kDistanceBits));
  c->add_option("--band", a->pair.band, "Band of the distance field, voxels")->check(CLI::PositiveNumber)->capture_default_str();
  c->add_option("--pose", a->pose,
                "Pair: B's first pose in A's frame, as voxcd pair --pose: tx,ty,tz[,rx,ry,rz] (degrees), "
                "tx,ty,tz,qw,qx,qy,qz, a 3x4 or 4x4 matrix (12 or 16 numbers, row-major) or the pose JSON voxcd pair "
                "prints");
  c->add_option("--backend", a->pair.backend, "Pair: device backend")->capture_default_str();
  c->add_flag("--both,!--no-both", a->pair.both_directions,
              "Pair: test both directions (the default, as voxcd pair) or, with --no-both, A's shell in B's voxmap "
              "only");
  c->add_option("--margin", a->pair.margin, "Pair on a distance device: contacts within this distance")->capture_default_str();
  c->callback([a] { exit_code() = view_cmd(*a); });
}

}  // namespace voxcd::cli
