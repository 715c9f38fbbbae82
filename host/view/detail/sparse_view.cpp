#include "voxcd/host/view/detail/sparse_view.h"

#include <array>
#include <string>

#include "voxcd/host/object/storage_figures.h"
#include "voxcd/host/detail/base64.h"

namespace voxcd::view::detail {

namespace {

using nlohmann::json;

const char* form(bool sparse) { return sparse ? "sparse" : "dense"; }

json forms_json(bool sparse, uint64_t dense_bytes, const json& sparse_bytes) {
  return {{"stored", sparse ? sparse_bytes : json(dense_bytes)}, {"dense", dense_bytes}, {"sparse", sparse_bytes}};
}

json distance_memory_json(const DistanceFigures& d) {
  if (!d.present) return nullptr;
  return forms_json(d.sparse, d.dense.bytes, d.sparse ? json(d.stored.bytes) : json(nullptr));
}

// Per level, the stride its boxes are taken at (0: none), finest level first, within `limit` boxes in all.
std::array<size_t, 4> level_strides(const std::vector<uint8_t>& levels, size_t limit) {
  std::array<size_t, 4> count{}, stride{};
  for (uint8_t l : levels) ++count[l];
  size_t room = limit;
  for (int l = 3; l >= 0 && room > 0; --l) {
    if (count[size_t(l)] == 0) continue;
    const size_t s = (count[size_t(l)] + room - 1) / room;
    stride[size_t(l)] = s;
    room -= (count[size_t(l)] + s - 1) / s;
    if (s > 1) break;
  }
  return stride;
}

// Table cells t = cx + C0 (cy + C1 cz) as (cx, cy, cz) u32 triples, base64, of those chosen.
std::string cells_base64(const std::vector<uint64_t>& cells, const std::array<uint64_t, 3>& coarse,
                         const std::vector<size_t>& chosen) {
  std::vector<uint32_t> xyz;
  xyz.reserve(3 * chosen.size());
  for (size_t i : chosen) {
    const uint64_t t = cells[i];
    xyz.insert(xyz.end(), {uint32_t(t % coarse[0]), uint32_t(t / coarse[0] % coarse[1]),
                           uint32_t(t / coarse[0] / coarse[1])});
  }
  return base64(xyz);
}

json voxmap_bricks_json(const SparseVoxmap& sm, bool stored, size_t limit) {
  std::vector<uint64_t> cells;
  for (uint64_t t = 0; t < sm.cells(); ++t)
    if (sm.code(t) == kCodeBrick) cells.push_back(t);
  const std::vector<size_t> chosen = bounded_boxes(std::vector<uint8_t>(cells.size(), 0), limit);
  return {{"edge", sm.edge()}, {"stored", stored}, {"count", cells.size()}, {"sent", chosen.size()},
          {"cells", cells_base64(cells, sm.coarse(), chosen)}};
}

json distance_bricks_json(const SparseDistanceField& f, size_t limit) {
  std::vector<uint64_t> cells;
  std::vector<uint8_t> levels;
  for (uint64_t t = 0; t < f.codes().size(); ++t)
    if (f.level(t) >= 0) cells.push_back(t), levels.push_back(uint8_t(f.level(t)));
  const std::vector<size_t> chosen = bounded_boxes(levels, limit);
  std::vector<uint8_t> sent_levels;
  std::array<uint64_t, 4> sent{};
  for (size_t i : chosen) sent_levels.push_back(levels[i]), ++sent[levels[i]];
  const auto& c = f.cells();
  return {{"edge", SparseDistanceField::kEdge}, {"count", f.counts().bricks}, {"sent", sent},
          {"cells", cells_base64(cells, {c[0], c[1], c[2]}, chosen)}, {"levels", base64(sent_levels)}};
}

}  // namespace

std::vector<size_t> bounded_boxes(const std::vector<uint8_t>& levels, size_t limit) {
  const std::array<size_t, 4> stride = level_strides(levels, limit);
  std::array<size_t, 4> seen{};
  std::vector<size_t> out;
  for (size_t i = 0; i < levels.size(); ++i) {
    const uint8_t l = levels[i];
    if (stride[l] && seen[l]++ % stride[l] == 0) out.push_back(i);
  }
  return out;
}

json storage_view_json(const ObjectFile& o) {
  const StorageFigures f = storage_figures(o);
  const DistanceFigures d = distance_figures(o);
  const json sparse_shell = f.shell_has_sparse ? json(f.sparse_shell) : json(nullptr);
  const json memory = {{"voxmap", forms_json(f.voxmap_sparse, f.dense_voxmap, f.sparse_voxmap())},
                       {"shell", forms_json(f.shell_sparse, f.dense_shell, sparse_shell)},
                       {"distance", distance_memory_json(d)}};
  return {{"voxmap", form(f.voxmap_sparse)}, {"shell", form(f.shell_sparse)},
          {"distance", d.present ? json(form(d.sparse)) : json(nullptr)}, {"memory", memory}};
}

json bricks_view_json(const ObjectFile& o, size_t limit, json& notes) {
  json j = {{"limit", limit}, {"distance", nullptr}};
  if (o.voxmap_sparse())
    j["voxmap"] = voxmap_bricks_json(o.sparse_voxmap, true, limit);
  else
    j["voxmap"] = voxmap_bricks_json(SparseVoxmap::from_dense(o.voxmap), false, limit);
  if (j["voxmap"]["sent"] != j["voxmap"]["count"])
    notes.push_back(j["voxmap"]["sent"].dump() + " of the voxmap's " + j["voxmap"]["count"].dump() +
                    " bricks are drawn (every k-th: at most " + std::to_string(limit) + " are sent)");
  if (!o.distance_sparse()) return j;
  j["distance"] = distance_bricks_json(o.sparse_distance, limit);
  const auto sum = [](const json& a) {
    uint64_t t = 0;
    for (const json& x : a) t += x.get<uint64_t>();
    return t;
  };
  if (sum(j["distance"]["sent"]) != sum(j["distance"]["count"]))
    notes.push_back(std::to_string(sum(j["distance"]["sent"])) + " of the distance field's " +
                    std::to_string(sum(j["distance"]["count"])) + " bricks are drawn (at most " +
                    std::to_string(limit) + " are sent: the finest levels first, then every k-th of the next)");
  return j;
}

}  // namespace voxcd::view::detail
