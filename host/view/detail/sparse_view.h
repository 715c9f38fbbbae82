// The object page's sparse structure (docs/view.md): the voxmap's bricks and the distance field's bricks by level as
// boxes, at most a bound of each, and what each part takes in device memory in both forms
// (host/object/storage_figures.h, the figures `voxcd info` prints).
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "voxcd/host/object/object_file.h"

namespace voxcd::view::detail {

// Of boxes at `levels` (0 to 3), the indices (ascending) of at most `limit`: every box of the finest levels that fit
// whole, then every k-th of the next finer level (k the smallest stride that keeps within the limit), none coarser.
std::vector<size_t> bounded_boxes(const std::vector<uint8_t>& levels, size_t limit);

// {"voxmap", "shell", "distance": "dense" | "sparse" (distance null without a field), "memory": per part
// {"stored", "dense", "sparse"} in bytes, null where a form has no figure}.
nlohmann::json storage_view_json(const ObjectFile& o);

// {"limit", "voxmap": {"edge", "stored", "count", "sent", "cells"}, "distance": {"edge", "count", "sent", "cells",
// "levels"} or null}: cells as u32 (cx, cy, cz) triples in base64, a field's levels one byte a box; a note in
// `notes` for each structure of more than `limit` bricks.
nlohmann::json bricks_view_json(const ObjectFile& o, size_t limit, nlohmann::json& notes);

}  // namespace voxcd::view::detail
