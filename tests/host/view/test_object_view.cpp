// The object page's data (host/view/object_view.h, docs/view.md "An object"): objects stored sparse give their grid,
// their states and field where the page is sent them, the bricks of the voxmap and of the distance field by level,
// within the limits (finest levels first), and the device memory of each part as `voxcd info` reports it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "tests/host/test_util.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/view/detail/sparse_view.h"
#include "voxcd/host/view/object_view.h"

namespace voxcd {
namespace {

using nlohmann::json;

std::vector<uint8_t> unbase64(const std::string& s) {
  static const std::string kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<uint8_t> out;
  uint32_t bits = 0;
  int n = 0;
  for (char c : s) {
    if (c == '=') break;
    bits = bits << 6 | uint32_t(kAlphabet.find(c));
    if ((n += 6) >= 8) out.push_back(uint8_t(bits >> (n -= 8)));
  }
  return out;
}

template <class T>
std::vector<T> decode(const json& j) {
  const std::vector<uint8_t> b = unbase64(j.get<std::string>());
  EXPECT_EQ(b.size() % sizeof(T), 0u);
  std::vector<T> v(b.size() / sizeof(T));
  std::copy(b.begin(), b.end(), reinterpret_cast<uint8_t*>(v.data()));
  return v;
}

// The object written to a file, as `voxcd view FILE` shows it.
json view_of_file(const ObjectFile& obj, const std::string& name, const view::ViewLimits& limits = {}) {
  const std::string path = test::tmp_path(name);
  write_object(path, obj);
  const view::ObjectView v = view::make_object_view(path, 0, 64, 0, 4.0);
  std::remove(path.c_str());
  return json::parse(view::object_view_json(v, limits));
}

ObjectFile shape_object(const std::string& shape, uint32_t resolution, ObjectStorage storage, int bits = 0) {
  ObjectOptions opt;
  opt.resolution = resolution;
  opt.distance_bits = bits;
  set_storage(opt, storage);
  std::string src;
  uint64_t hash = 0;
  MeshReport report;
  const Mesh mesh = load_source(shape, &src, &hash, &report);
  return make_object(mesh, src, hash, opt, &report);
}

// Table cell t of a grid of `coarse` cells per axis, from the page's (cx, cy, cz).
uint64_t cell_of(const std::vector<uint32_t>& xyz, size_t i, const std::array<uint64_t, 3>& coarse) {
  return xyz[3 * i] + coarse[0] * (xyz[3 * i + 1] + coarse[1] * uint64_t(xyz[3 * i + 2]));
}

TEST(ObjectView, SparseVoxmapAndShellGiveTheirBricksAndMemory) {
  const ObjectFile obj = shape_object("torus", 40, ObjectStorage::kSparse);
  ASSERT_TRUE(obj.voxmap_sparse() && obj.shell_sparse());
  const json j = view_of_file(obj, "view_sparse.vox");
  const SparseVoxmap& sm = obj.sparse_voxmap;
  EXPECT_EQ(j["dims"], json(sm.dims()));
  EXPECT_EQ(j["counts"]["surface"], sm.counts()[kSurface]);
  EXPECT_EQ(decode<uint64_t>(j["voxmap"]), sm.to_dense().words());
  EXPECT_EQ(j["storage"]["voxmap"], "sparse");
  EXPECT_EQ(j["storage"]["shell"], "sparse");
  EXPECT_TRUE(j["storage"]["distance"].is_null() && j["distance"].is_null() && j["bricks"]["distance"].is_null());
  // Device memory as voxcd info reports it: the dense voxmap in 64-bit words of 32 states, 9 bytes a shell point.
  const json& m = j["storage"]["memory"];
  EXPECT_EQ(m["voxmap"], json({{"stored", sm.bytes()}, {"dense", (sm.size() + 31) / 32 * 8}, {"sparse", sm.bytes()}}));
  EXPECT_EQ(m["shell"], json({{"stored", obj.sparse_shell.bytes()}, {"dense", obj.shell_count() * 9},
                              {"sparse", obj.sparse_shell.bytes()}}));
  // Every brick once, each a cell of code 3.
  const json& b = j["bricks"]["voxmap"];
  EXPECT_EQ(b["count"], sm.code_counts()[kCodeBrick]);
  EXPECT_EQ(b["sent"], b["count"]);
  EXPECT_EQ(b["edge"], 8);
  EXPECT_TRUE(b["stored"]);
  const std::vector<uint32_t> xyz = decode<uint32_t>(b["cells"]);
  ASSERT_EQ(xyz.size(), 3 * b["count"].get<size_t>());
  std::set<uint64_t> cells;
  for (size_t i = 0; i < xyz.size() / 3; ++i) cells.insert(cell_of(xyz, i, sm.coarse()));
  EXPECT_EQ(cells.size(), xyz.size() / 3);
  for (uint64_t t : cells) EXPECT_EQ(sm.code(t), kCodeBrick) << "cell " << t;
  EXPECT_EQ(j["shell"]["count"], obj.shell_count());
  EXPECT_EQ(j["shell"]["sent"], obj.shell_count());
  EXPECT_TRUE(j["notes"].empty()) << j["notes"];
}

TEST(ObjectView, SparseFieldGivesItsLevelsAndItsLevelZeroNodes) {
  const ObjectFile obj = shape_object("cube", 24, ObjectStorage::kSparse, 8);
  ASSERT_TRUE(obj.distance_sparse() && !obj.voxmap_sparse());
  const json j = view_of_file(obj, "view_field.vox");
  const SparseDistanceField& f = obj.sparse_distance;
  EXPECT_EQ(j["distance"]["storage"], "sparse");
  EXPECT_EQ(j["distance"]["bits"], 8);
  EXPECT_EQ(j["distance"]["nodes"], json({f.dims()[0] + 1, f.dims()[1] + 1, f.dims()[2] + 1}));
  EXPECT_EQ(decode<int16_t>(j["distance"]["q"]), dense_from_sparse(f).q);
  const json& b = j["bricks"]["distance"];
  EXPECT_EQ(b["count"], json(f.counts().bricks));
  EXPECT_EQ(b["sent"], b["count"]);
  ASSERT_GT(f.counts().bricks[1], 0u);  // the cube's edges refine
  const std::vector<uint32_t> xyz = decode<uint32_t>(b["cells"]);
  const std::vector<uint8_t> levels = decode<uint8_t>(b["levels"]);
  ASSERT_EQ(xyz.size(), 3 * levels.size());
  const std::array<uint64_t, 3> coarse = {f.cells()[0], f.cells()[1], f.cells()[2]};
  for (size_t i = 0; i < levels.size(); ++i) EXPECT_EQ(f.level(cell_of(xyz, i, coarse)), levels[i]) << "box " << i;
  // Memory: the field stored sparse and as a dense map; a dense voxmap's bricks are those it would have.
  const json& m = j["storage"]["memory"]["distance"];
  EXPECT_EQ(j["storage"]["distance"], "sparse");
  EXPECT_GT(m["sparse"], 0);
  EXPECT_EQ(m["stored"], m["sparse"]);
  EXPECT_GT(m["dense"], 0);
  EXPECT_NE(m["dense"], m["sparse"]);
  EXPECT_EQ(j["bricks"]["voxmap"]["stored"], false);
  EXPECT_EQ(j["bricks"]["voxmap"]["count"], SparseVoxmap::from_dense(obj.voxmap).code_counts()[kCodeBrick]);
}

TEST(ObjectView, ADenseFieldHasNoBricks) {
  const ObjectFile obj = shape_object("cube", 16, ObjectStorage::kDense, 8);
  const json j = view_of_file(obj, "view_dense.vox");
  EXPECT_EQ(j["distance"]["storage"], "dense");
  EXPECT_EQ(decode<int16_t>(j["distance"]["q"]), obj.distance.q);
  EXPECT_TRUE(j["bricks"]["distance"].is_null());
  EXPECT_TRUE(j["storage"]["memory"]["distance"]["sparse"].is_null());
  EXPECT_EQ(j["storage"]["memory"]["distance"]["stored"], j["storage"]["memory"]["distance"]["dense"]);
  EXPECT_TRUE(j["storage"]["memory"]["shell"]["sparse"].is_null());  // a shell on the surface has no sparse form
}

TEST(ObjectView, BoundedBoxesTakeTheFinestLevelsFirst) {
  using view::detail::bounded_boxes;
  const std::vector<uint8_t> levels = {0, 1, 0, 2, 0, 1, 0, 0, 3, 0};
  EXPECT_EQ(bounded_boxes(levels, 100), (std::vector<size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(bounded_boxes(levels, 0), std::vector<size_t>{});
  EXPECT_EQ(bounded_boxes(levels, 2), (std::vector<size_t>{3, 8}));        // levels 3 and 2 whole
  EXPECT_EQ(bounded_boxes(levels, 3), (std::vector<size_t>{1, 3, 8}));     // then every 2nd of level 1: its first
  EXPECT_EQ(bounded_boxes(levels, 6), (std::vector<size_t>{0, 1, 3, 5, 6, 8}));  // every 3rd of level 0's six
}

TEST(ObjectView, LimitsBoundWhatThePageIsSent) {
  const ObjectFile obj = shape_object("cube", 24, ObjectStorage::kSparse, 8);
  const std::array<uint64_t, 4> per_level = obj.sparse_distance.counts().bricks;  // 31 / 32 / 0 / 0
  ASSERT_GT(per_level[0], 8u);
  ASSERT_LT(per_level[1], 40u);
  view::ViewLimits limits;
  limits.boxes = 40;
  limits.shell_points = 100;
  limits.array_bytes = 1000;
  const json j = view_of_file(obj, "view_limits.vox", limits);
  // Level 1 whole, then every k-th of level 0 within the rest.
  const json& d = j["bricks"]["distance"];
  const uint64_t room = 40 - per_level[1], stride = (per_level[0] + room - 1) / room;
  EXPECT_EQ(d["sent"], json({(per_level[0] + stride - 1) / stride, per_level[1], 0, 0}));
  EXPECT_EQ(decode<uint8_t>(d["levels"]).size(), d["sent"][0].get<size_t>() + d["sent"][1].get<size_t>());
  EXPECT_LE(j["bricks"]["voxmap"]["sent"], 40);
  EXPECT_GT(j["bricks"]["voxmap"]["count"], 40);
  EXPECT_EQ(decode<uint32_t>(j["bricks"]["voxmap"]["cells"]).size(), 3 * j["bricks"]["voxmap"]["sent"].get<size_t>());
  EXPECT_EQ(j["bricks"]["limit"], 40);
  // The states and the nodes take more than 1000 bytes: not sent; the shell thinned to every k-th point.
  EXPECT_TRUE(j["voxmap"].is_null());
  EXPECT_TRUE(j["distance"]["q"].is_null());
  const size_t points = obj.shell_count(), k = (points + 99) / 100;
  EXPECT_EQ(j["shell"]["stride"], k);
  EXPECT_EQ(j["shell"]["sent"], (points + k - 1) / k);
  EXPECT_LE(j["shell"]["sent"], 100);
  EXPECT_EQ(decode<float>(j["shell"]["points"]).size(), 3 * j["shell"]["sent"].get<size_t>());
  EXPECT_EQ(j["limits"], json({{"boxes", 40}, {"shell_points", 100}, {"array_bytes", 1000}}));
  const std::string notes = j["notes"].dump();
  for (const char* said : {"voxmap's states take", "distance field's", "shell point in", "of the voxmap's",
                           "of the distance field's"})
    EXPECT_NE(notes.find(said), std::string::npos) << said << " in " << notes;
}

TEST(ObjectView, AVoxmapTooLargeForItsDenseFormShowsItsBricks) {
  // A rod 1,033 voxels long, from a mesh that is gone: no dense voxmap, no surface of it, its bricks.
  ObjectOptions opt;
  opt.resolution = 1030;
  set_storage(opt, ObjectStorage::kSparse);
  const ObjectFile obj = make_object(make_box({0, 0, 0}, {100, 1, 1}), "/nonexistent/rod.obj", 1, opt);
  const json j = view_of_file(obj, "view_rod.vox");
  EXPECT_GT(j["dims"][0], 1024);
  EXPECT_TRUE(j["voxmap"].is_null());
  EXPECT_EQ(j["surface"]["triangle_count"], 0);
  EXPECT_FALSE(j["surface"]["from_mesh"]);
  EXPECT_NE(j["surface"]["note"].get<std::string>().find("too large for its surface, drawing its bricks"),
            std::string::npos) << j["surface"]["note"];
  EXPECT_NE(j["notes"].dump().find("stored sparse on a grid larger than a dense voxmap"), std::string::npos);
  EXPECT_EQ(j["bricks"]["voxmap"]["count"], obj.sparse_voxmap.code_counts()[kCodeBrick]);
  EXPECT_GT(j["bricks"]["voxmap"]["count"], 0);
  EXPECT_EQ(j["counts"]["surface"], obj.sparse_voxmap.counts()[kSurface]);
}

}  // namespace
}  // namespace voxcd
