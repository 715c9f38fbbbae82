// The object file's sparse sections (version 5): a sparse voxmap, a sparse shell, and the reserved section of a sparse
// distance field (docs/objects.md, "The object file").
#include <algorithm>
#include <string>
#include <vector>

#include "voxcd/host/object/detail/object_io.h"
#include "voxcd/ref/sparse.h"

namespace voxcd::detail {

namespace {

// The sparse distance section's kinds.
constexpr uint32_t kDistanceAbsent = 0, kDistanceSparseField = 1;

}  // namespace

void put_sparse_voxmap(Writer& w, const SparseVoxmap& sm) {
  w.put(uint32_t(sm.bl()));
  const auto c = sm.counts();
  w.put(c[kEmpty]);
  w.put(c[kSurface]);
  w.put(c[kInterior]);
  w.put(sm.cells());
  w.put(uint64_t(sm.code_words().size()));
  w.put_array(sm.code_words().data(), sm.code_words().size());
  w.put(sm.bricks());
  w.put_array(sm.brick_data().data(), sm.brick_data().size());
}

namespace {

// The cells' codes, checked: the word count, and no bits past the last cell.
std::vector<uint64_t> read_codes(Reader& r, const SparseVoxmap& sm) {
  if (const uint64_t cells = r.get<uint64_t>("the sparse voxmap's cell count"); cells != sm.cells())
    r.bad("the sparse voxmap's cell count " + std::to_string(cells) + " does not match its grid and BL (" +
          std::to_string(sm.cells()) + ")");
  const uint64_t words = r.get<uint64_t>("the sparse voxmap's code word count");
  if (words != (sm.cells() + 31) / 32)
    r.bad("the sparse voxmap's code word count " + std::to_string(words) + " does not match its cells (" +
          std::to_string((sm.cells() + 31) / 32) + ")");
  std::vector<uint64_t> codes(words);
  r.get_array(codes.data(), words, "the sparse voxmap's codes");
  if (const uint64_t used = sm.cells() % 32; used && codes.back() >> (2 * used)) {
    r.field = r.pos - 8;
    r.bad("the sparse voxmap's last code word has bits set beyond its last cell");
  }
  return codes;
}

}  // namespace

void read_sparse_voxmap(Reader& r, const GridPlacement& g, SparseVoxmap& sm) {
  const uint32_t bl = r.get<uint32_t>("the sparse voxmap's BL");
  if (bl < uint32_t(kMinBrickLog) || bl > uint32_t(kMaxBrickLog))
    r.bad("the sparse voxmap's BL " + std::to_string(bl) + " is not " + std::to_string(kMinBrickLog) + ".." +
          std::to_string(kMaxBrickLog));
  uint64_t counts[3];
  const size_t counts_at = r.pos;
  for (auto& c : counts) c = r.get<uint64_t>("the state counts");
  SparseVoxmap out(g, int(bl));
  const std::vector<uint64_t> codes = read_codes(r, out);
  const uint64_t bricks = r.get<uint64_t>("the sparse voxmap's brick count");
  uint64_t want = 0;
  for (uint64_t w : codes) want += uint64_t(__builtin_popcountll(w & (w >> 1) & 0x5555555555555555ull));
  if (bricks != want)
    r.bad("the sparse voxmap's brick count " + std::to_string(bricks) + " does not match its codes (" +
          std::to_string(want) + " bricks)");
  r.need(bricks, "the sparse voxmap's bricks", out.brick_words() * 8);
  const size_t bricks_at = r.pos;
  std::vector<uint64_t> words(out.brick_words());
  for (uint64_t t = 0, b = 0; t < out.cells(); ++t) {
    const uint8_t c = uint8_t((codes[t >> 5] >> (2 * (t & 31))) & 3);
    if (c == kCodeBrick) {
      std::memcpy(words.data(), r.buf.data() + bricks_at + b * out.brick_words() * 8, words.size() * 8);
      if (const char* p = out.brick_problem(t, words.data())) {
        r.field = bricks_at + b * out.brick_words() * 8;
        r.bad("brick " + std::to_string(b) + " (cell " + std::to_string(t) + ") has " + p);
      }
      ++b;
    }
    out.append(c, words.data());
  }
  r.pos += bricks * out.brick_words() * 8;
  const auto n = out.counts();
  if (n[kEmpty] != counts[0] || n[kSurface] != counts[1] || n[kInterior] != counts[2]) {
    r.field = counts_at;
    r.bad("state counts do not match the sparse voxmap");
  }
  sm = std::move(out);
}

void put_sparse_shell(Writer& w, const SparseShell& s) {
  put_grid(w, s.grid);
  w.put(uint64_t(s.bricks.size()));
  w.put_array(s.bricks.data(), s.bricks.size());
  w.put_array(s.masks.data(), s.masks.size());
  w.put(uint64_t(s.size()));
  w.put_array(s.normals.data(), s.normals.size());
}

namespace {

// Every brick's voxels inside the shell grid, no brick twice, no empty mask; returns the points.
uint64_t check_bricks(Reader& r, const SparseShell& s, size_t bricks_at, size_t masks_at) {
  uint64_t points = 0;
  std::vector<uint64_t> keys(s.bricks.size());
  for (size_t k = 0; k < s.bricks.size(); ++k) {
    if (s.masks[k] == 0) {
      r.field = masks_at + 8 * k;
      r.bad("shell brick " + std::to_string(k) + " has no point");
    }
    const auto& b = s.bricks[k];
    for (int a = 0; a < 3; ++a) {
      uint32_t reach = 0;  // the brick's highest voxel along a
      for (uint64_t m = s.masks[k]; m; m &= m - 1) {
        const uint32_t i = uint32_t(__builtin_ctzll(m));
        reach = std::max(reach, a == 0 ? (i & 3) : a == 1 ? ((i >> 2) & 3) : (i >> 4));
      }
      if (uint64_t(b[a]) * kShellBrickEdge + reach >= s.grid.dims[a]) {
        r.field = bricks_at + 6 * k;
        r.bad("shell brick " + std::to_string(k) + " has a point outside the shell grid");
      }
    }
    keys[k] = uint64_t(b[2]) << 32 | uint64_t(b[1]) << 16 | b[0];
    points += uint64_t(__builtin_popcountll(s.masks[k]));
  }
  std::sort(keys.begin(), keys.end());
  if (std::adjacent_find(keys.begin(), keys.end()) != keys.end()) {
    r.field = bricks_at;
    r.bad("the sparse shell holds a brick twice");
  }
  return points;
}

}  // namespace

void read_sparse_shell(Reader& r, SparseShell& s) {
  s.grid = get_grid(r, "the shell grid");
  const uint64_t n = r.get<uint64_t>("the shell brick count");
  r.need(n, "the shell bricks", 6 + 8);
  s.bricks.resize(n);
  s.masks.resize(n);
  const size_t bricks_at = r.pos;
  r.get_array(s.bricks.data(), n, "the shell bricks");
  const size_t masks_at = r.pos;
  r.get_array(s.masks.data(), n, "the shell bricks' masks");
  const uint64_t points = check_bricks(r, s, bricks_at, masks_at);
  if (const uint64_t np = r.get<uint64_t>("the shell point count"); np != points)
    r.bad("the shell point count " + std::to_string(np) + " does not match its bricks (" + std::to_string(points) +
          " points)");
  s.normals.resize(points);
  r.get_array(s.normals.data(), points, "the shell normals");
}

void put_sparse_distance(Writer& w, const ObjectFile& obj) {
  if (!obj.distance_sparse()) {
    w.put(kDistanceAbsent);
    w.put(uint64_t{0});
    return;
  }
  std::vector<uint8_t> bytes;
  write_sparse_field(bytes, obj.sparse_distance);
  w.put(kDistanceSparseField);
  w.put(uint64_t(bytes.size()));
  w.put_array(bytes.data(), bytes.size());
}

void read_sparse_distance(Reader& r, ObjectFile& obj) {
  const uint32_t kind = r.get<uint32_t>("the sparse distance section's kind");
  const uint64_t bytes = r.get<uint64_t>("the sparse distance section's length");
  if (kind == kDistanceAbsent) {
    if (bytes != 0) r.bad("an absent sparse distance section has a length of " + std::to_string(bytes) + ", not 0");
    return;
  }
  if (kind != kDistanceSparseField) r.bad("unknown sparse distance section kind " + std::to_string(kind));
  r.need(bytes, "the sparse distance field");
  const size_t at = r.pos;
  obj.sparse_distance = read_sparse_field(reinterpret_cast<const uint8_t*>(r.buf.data()) + at, size_t(bytes),
                                          r.path + ": the sparse distance section from byte " + std::to_string(at));
  r.pos = at + size_t(bytes);
  const auto& d = obj.sparse_distance.dims();
  const auto& g = obj.voxmap_grid().dims;
  if (d != g)
    r.bad("the sparse distance field's " + std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" +
          std::to_string(d[2]) + " cells do not match the voxmap's grid");
}

}  // namespace voxcd::detail
