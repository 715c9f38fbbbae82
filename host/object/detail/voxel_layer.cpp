#include "voxcd/host/object/detail/voxel_layer.h"

#include <algorithm>

#include "voxcd/ref/sparse.h"

namespace voxcd::detail {

namespace {

// Where the layer lies: its planes of z, its coarse cells, and a voxel's cell and bit within the cell.
struct Layer {
  uint32_t z0 = 0, z1 = 0;  // planes [z0, z1) of the grid
  uint32_t bl = 3, b = 8;
  uint64_t cx = 1, cy = 1, cz = 1;  // cells per axis
  size_t cells() const { return size_t(cx * cy * cz); }
  size_t cell(uint32_t x, uint32_t y, uint32_t z) const {
    return size_t((x >> bl) + cx * ((y >> bl) + cy * ((z - z0) >> bl)));
  }
  uint64_t bit(uint32_t x, uint32_t y, uint32_t z) const {
    const uint32_t m = b - 1;
    return (x & m) + b * ((y & m) + uint64_t(b) * (z & m));
  }
};

Layer layer_of(const LayerJob& job, size_t layer) {
  Layer l;
  l.bl = uint32_t(job.bl);
  l.b = uint32_t{1} << job.bl;
  l.z0 = uint32_t(layer * job.height);
  l.z1 = std::min(job.gp.dims[2], uint32_t(l.z0 + job.height));
  l.cx = (job.gp.dims[0] + l.b - 1) / l.b;
  l.cy = (job.gp.dims[1] + l.b - 1) / l.b;
  l.cz = (l.z1 - l.z0 + l.b - 1) / l.b;
  return l;
}

// One bit per voxel of the cells that have any set: the layer's surface voxels.
class CellBits {
 public:
  CellBits(size_t cells, uint64_t words) : slot_(cells, UINT32_MAX), words_(words) {}
  void set(size_t cell, uint64_t i) {
    if (slot_[cell] == UINT32_MAX) {
      slot_[cell] = uint32_t(bits_.size() / words_);
      bits_.resize(bits_.size() + words_, 0);
    }
    bits_[slot_[cell] * words_ + (i >> 6)] |= uint64_t{1} << (i & 63);
  }
  const uint64_t* of(size_t cell) const { return slot_[cell] == UINT32_MAX ? nullptr : &bits_[slot_[cell] * words_]; }
  bool test(size_t cell, uint64_t i) const {
    const uint64_t* w = of(cell);
    return w && (w[i >> 6] >> (i & 63)) & 1;
  }

 private:
  std::vector<uint32_t> slot_;
  uint64_t words_;
  std::vector<uint64_t> bits_;
};

// The runs of voxels [lo, hi) of each column (y + ny * (z - z0)) whose centres have W >= 1: sorted, apart.
struct Runs {
  std::vector<uint32_t> start;
  std::vector<std::pair<uint32_t, uint32_t>> runs;
  const std::pair<uint32_t, uint32_t>* first_after(size_t col, uint32_t x) const {  // the first run with hi > x
    return std::upper_bound(runs.data() + start[col], runs.data() + start[col + 1], x,
                            [](uint32_t v, const std::pair<uint32_t, uint32_t>& r) { return v < r.second; });
  }
  bool inside(size_t col, uint32_t x) const {
    const auto* r = first_after(col, x);
    return r != runs.data() + start[col + 1] && r->first <= x;
  }
};

Runs interior_runs(const LayerJob& job, const ColumnCrossings& cc) {
  Runs r;
  std::vector<size_t> col_of;
  walk_columns(job.mesh->name, job.gp, cc, [&](size_t c, uint64_t lo, uint64_t hi) {
    if (!col_of.empty() && col_of.back() == c && r.runs.back().second >= lo) {
      r.runs.back().second = std::max(r.runs.back().second, uint32_t(hi));  // touching runs merge
      return;
    }
    col_of.push_back(c);
    r.runs.push_back({uint32_t(lo), uint32_t(hi)});
  });
  r.start.assign(cc.columns() + 1, 0);
  for (size_t c : col_of) ++r.start[c + 1];
  for (size_t c = 0; c < cc.columns(); ++c) r.start[c + 1] += r.start[c];
  return r;
}

// Per cell: how many of its B^2 columns a run covers whole (full), and whether a run covers part of one (touched).
struct Coverage {
  std::vector<uint16_t> full;
  std::vector<uint8_t> touched;
};

Coverage coverage(const Layer& l, const GridPlacement& gp, const Runs& r) {
  const size_t rows = size_t(l.cy * l.cz), stride = size_t(l.cx + 1);
  std::vector<int32_t> diff(rows * stride, 0);
  Coverage cov;
  cov.touched.assign(l.cells(), 0);
  const uint32_t ny = gp.dims[1];
  for (size_t col = 0; col + 1 < r.start.size(); ++col) {
    const uint32_t y = uint32_t(col % ny), z = uint32_t(col / ny) + l.z0;
    const size_t row = size_t((y >> l.bl) + l.cy * ((z - l.z0) >> l.bl));
    for (uint32_t k = r.start[col]; k < r.start[col + 1]; ++k) {
      const auto [lo, hi] = r.runs[k];
      const int64_t first = (int64_t(lo) + l.b - 1) >> l.bl, last = (int64_t(hi) >> l.bl) - 1;  // covered whole
      if (first <= last) {
        ++diff[row * stride + size_t(first)];
        --diff[row * stride + size_t(last + 1)];
      }
      for (int64_t c : {int64_t(lo >> l.bl), int64_t((hi - 1) >> l.bl)})
        if (c < first || c > last) cov.touched[row * size_t(l.cx) + size_t(c)] = 1;
    }
  }
  cov.full.assign(l.cells(), 0);
  for (size_t row = 0; row < rows; ++row) {
    int32_t run = 0;
    for (size_t c = 0; c < l.cx; ++c) cov.full[row * l.cx + c] = uint16_t(run += diff[row * stride + c]);
  }
  return cov;
}

// A voxel whose state the near-hole refinement changed from the integer fill's.
struct Override {
  size_t cell;
  uint64_t bit;
  bool inside;
  bool operator<(const Override& o) const { return cell != o.cell ? cell < o.cell : bit < o.bit; }
};

// The caps' winding number near holes (voxelize's refine_near_holes on this layer's blocks of 8^3).
void refine(const LayerJob& job, const Layer& l, const ColumnCrossings& cc, const CellBits& surface, const Runs& runs,
            std::vector<Override>& out, LayerCells& res) {
  constexpr uint32_t kBlock = 8;
  const auto& d = job.gp.dims;
  for (uint32_t z0 = l.z0; z0 < l.z1; z0 += kBlock)
    for (uint32_t y0 = 0; y0 < d[1]; y0 += kBlock)
      for (uint32_t x0 = 0; x0 < d[0]; x0 += kBlock) {
        const std::array<uint32_t, 3> lo = {x0, y0, z0};
        const std::array<uint32_t, 3> hi = {std::min(x0 + kBlock, d[0]), std::min(y0 + kBlock, d[1]),
                                            std::min(z0 + kBlock, d[2])};
        job.field->uncertain_voxels(lo, hi, kUncertainLow, [&](uint32_t x, uint32_t y, uint32_t z, double nr, double b) {
          const size_t cell = l.cell(x, y, z);
          const uint64_t bit = l.bit(x, y, z);
          if (surface.test(cell, bit)) return;
          ++res.evaluated;
          const double w = near_hole_winding(*job.field, cc, x, y, z, nr, b);
          if (w >= kUncertainLow && w <= kUncertainHigh) ++res.uncertain;
          const bool inside = w >= 0.5;
          if (inside != runs.inside(cc.column(y, z), x)) out.push_back({cell, bit, inside});
        });
      }
  std::sort(out.begin(), out.end());
}

void put_state(uint64_t* w, uint64_t i, uint8_t s) {
  w[i >> 5] = (w[i >> 5] & ~(uint64_t{3} << (2 * (i & 31)))) | uint64_t(s) << (2 * (i & 31));
}

// What the layer knows, for building its cells.
struct LayerState {
  const Layer& l;
  const GridPlacement& gp;
  const CellBits& surface;
  const Runs& runs;
  const Coverage& cov;
  const std::vector<Override>& overrides;
};

// The states of cell (cx, cy, czl) of the layer: the fill's runs, then the refinement's changes, then the surface.
void cell_states(const LayerState& s, uint64_t cx, uint64_t cy, uint64_t czl, const Override* ov, const Override* oe,
                 uint64_t* w) {
  const Layer& l = s.l;
  const uint32_t x0 = uint32_t(cx << l.bl), xe = std::min(s.gp.dims[0], x0 + l.b);
  for (uint32_t fz = 0; fz < l.b; ++fz) {
    const uint32_t z = l.z0 + uint32_t(czl << l.bl) + fz;
    if (z >= l.z1) break;
    for (uint32_t fy = 0; fy < l.b; ++fy) {
      const uint32_t y = uint32_t(cy << l.bl) + fy;
      if (y >= s.gp.dims[1]) break;
      const size_t col = size_t(y) + size_t(s.gp.dims[1]) * (z - l.z0);
      const auto* end = s.runs.runs.data() + s.runs.start[col + 1];
      for (const auto* r = s.runs.first_after(col, x0); r != end && r->first < xe; ++r)
        for (uint32_t x = std::max(r->first, x0); x < std::min(r->second, xe); ++x)
          put_state(w, l.bit(x, y, z), kInterior);
    }
  }
  for (; ov != oe; ++ov) put_state(w, ov->bit, ov->inside ? kInterior : kEmpty);
  const size_t cell = size_t(cx + l.cx * (cy + l.cy * czl));
  if (const uint64_t* sb = s.surface.of(cell))
    for (uint64_t k = 0; k < (uint64_t(l.b) * l.b * l.b + 63) / 64; ++k)
      for (uint64_t m = sb[k]; m; m &= m - 1) put_state(w, k * 64 + uint64_t(__builtin_ctzll(m)), kSurface);
}

// Every cell of the layer in table order: uniform where the fill, the refinement and the surface agree on the whole
// cell, else its states (reduced to a uniform code when they are all one).
void emit_cells(const LayerState& s, uint64_t words, LayerCells& res) {
  const Layer& l = s.l;
  res.codes.assign(l.cells(), kEmpty);
  std::vector<uint64_t> w(words);
  const Override* ov = s.overrides.data();
  const Override* oend = ov + s.overrides.size();
  const uint32_t b2 = l.b * l.b;
  for (uint64_t czl = 0, cell = 0; czl < l.cz; ++czl)
    for (uint64_t cy = 0; cy < l.cy; ++cy)
      for (uint64_t cx = 0; cx < l.cx; ++cx, ++cell) {
        const Override* oe = ov;
        while (oe != oend && oe->cell == cell) ++oe;
        if (!s.surface.of(cell) && ov == oe) {
          if (s.cov.full[cell] == b2) { res.codes[cell] = kInterior; continue; }  // whole columns: inside the grid
          if (s.cov.full[cell] == 0 && !s.cov.touched[cell]) continue;
        }
        std::fill(w.begin(), w.end(), 0);
        cell_states(s, cx, cy, czl, ov, oe, w.data());
        ov = oe;
        const uint64_t same = (w[0] & 3) * 0x5555555555555555ull;
        if (std::all_of(w.begin(), w.end(), [&](uint64_t v) { return v == same; })) {
          res.codes[cell] = uint8_t(same & 3);
          continue;
        }
        res.codes[cell] = kCodeBrick;
        res.bricks.insert(res.bricks.end(), w.begin(), w.end());
      }
}

}  // namespace

LayerCells voxelize_layer(const LayerJob& job, size_t layer, ThreadPool& pool) {
  const Layer l = layer_of(job, layer);
  const ZWindow win{l.z0, int64_t(l.z1) - 1};
  const uint64_t voxels = uint64_t{1} << (3 * l.bl);
  CellBits surface(l.cells(), (voxels + 63) / 64);
  layer_surface(*job.mesh, *job.gm, job.gp, job.surface->begin(layer), job.surface->count(layer), win,
                [&](uint32_t, uint32_t x, uint32_t y, uint32_t z) { surface.set(l.cell(x, y, z), l.bit(x, y, z)); });
  LayerCells res;
  Runs runs;
  std::vector<Override> overrides;
  ColumnCrossings cc;
  if (job.chain) {
    cc = column_crossings(*job.chain, *job.gm, job.gp, pool, win, job.chain_items->begin(layer),
                          job.chain_items->count(layer));
    runs = interior_runs(job, cc);
    if (job.field) refine(job, l, cc, surface, runs, overrides, res);
  } else {
    runs.start.assign(size_t(job.gp.dims[1]) * (l.z1 - l.z0) + 1, 0);
  }
  const Coverage cov = coverage(l, job.gp, runs);
  emit_cells(LayerState{l, job.gp, surface, runs, cov, overrides}, voxels / 32, res);
  return res;
}

}  // namespace voxcd::detail
