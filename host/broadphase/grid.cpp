// A uniform grid rebuilt every frame, in levels by box size. A level's cell is at least as wide as the largest box
// in it, so two of its boxes can overlap only when the cells of their lower corners are neighbours; each box
// goes into the one cell of its lower corner (a counting sort), and each box is tested against the boxes of its
// own cell that follow it and of the 13 neighbouring cells that follow its cell (five runs of cells, contiguous
// in memory). Boxes more than twice the median size of a level go up to the next level, built the same way from
// what is left; each of them is also tested against the boxes of every lower level in the cells its box covers.
// Every level holds at most half of the boxes of the level below, so there are at most log2(n) levels.
// O(n + k) a frame for boxes of similar sizes (at most 16 cells a box), whatever the motion. The only thing kept
// between frames is the order of the first level's entries, the order in which the next frame visits its boxes when
// they are all in that level again (visit_in_last_order): its sort then writes nearly in sequence.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "voxcd/host/broadphase/detail/common.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd::detail {
namespace {

class UniformGrid final : public BroadphaseBase {
 public:
  UniformGrid() : BroadphaseBase("grid", "box") {}

  void update(const std::vector<BodyBounds>& bodies, uint64_t frame) override {
    const uint32_t n = uint32_t(bodies.size());
    flatten(bodies, frame);
    if (out_.empty()) out_.resize(1);
    for (auto& o : out_) o.value.n = 0, o.value.tests = 0;
    size_t used = 0;
    // ids_[0, m): the boxes not yet placed in a level.
    for (uint32_t m = n; m > 0; ++used) {
      if (levels_.size() == used) levels_.emplace_back();
      Level& lv = levels_[used];
      m = build(lv, m, used == 0 && m == n);
      pairs_within(lv);
      // The boxes left over are larger than the level's cell: each against the level's boxes it can reach (and,
      // as it goes up, against every later level it does not end in).
      for (uint32_t k = 0; k < m; ++k) pairs_with(lv, ids_[k], out_[0].value);
    }
    // Every part's pairs, sorted: the same pairs in the same order whatever the parts.
    uint64_t tests = 0;
    size_t total = 0;
    for (const auto& o : out_) tests += o.value.tests, total += o.value.n;
    if (pool_ && total >= kParallelSort) {
      sort_on_pool(n, total);
    } else {
      Found& first = out_[0].value;
      first.keys.resize(std::max(first.keys.size(), total));
      for (size_t p = 1, at = first.n; p < out_.size(); ++p) {
        const Found& o = out_[p].value;
        std::copy(o.keys.begin(), o.keys.begin() + std::ptrdiff_t(o.n), first.keys.begin() + std::ptrdiff_t(at));
        at += o.n;
      }
      first.keys.resize(total);
      sort_pairs(first.keys, tmp_, n, pairs_);
    }
    stats_ = {tests, pairs_.size()};
  }

 private:
  // Pairs found (keys[0, n)) and tests made, by one part of the search.
  struct Found {
    std::vector<uint64_t> keys;
    size_t n = 0;
    uint64_t tests = 0;
  };

  // The parts' keys sorted on the pool as one bucket sort by first body (bucket (a B) >> 32 for first body a and
  // B = (buckets << 32) / n: ascending in a, below `buckets`): each part counts its keys per bucket, then puts them
  // in their bucket's place (part after part within a bucket), then each bucket is sorted on its own and written to
  // its place in pairs_. The same pairs in the same order as one sort.
  void sort_on_pool(uint32_t n, size_t total) {
    const size_t parts = out_.size(), buckets = kBucketsPerThread * size_t(pool_->size());
    const uint64_t scale = (uint64_t(buckets) << 32) / n;
    auto bucket_of = [scale](uint64_t key) { return size_t(((key >> 32) * scale) >> 32); };
    if (count_.size() < parts) count_.resize(parts);
    pool_->parallel_for(parts, [&](size_t p) {
      std::vector<uint32_t>& cnt = count_[p].value;
      cnt.assign(buckets, 0);
      const Found& f = out_[p].value;
      for (size_t i = 0; i < f.n; ++i) ++cnt[bucket_of(f.keys[i])];
    });
    bucket_places(parts, buckets, total);
    keys_.resize(total);
    tmp_.resize(total);
    pool_->parallel_for(parts, [&](size_t p) {
      std::vector<uint32_t>& at = count_[p].value;
      const Found& f = out_[p].value;
      for (size_t i = 0; i < f.n; ++i) keys_[at[bucket_of(f.keys[i])]++] = f.keys[i];
    });
    pairs_.resize(total);
    pool_->parallel_for(buckets, [&](size_t b) {
      const size_t from = bucket_at_[b], k = bucket_at_[b + 1] - from;
      const uint64_t* sorted = sort_keys(keys_.data() + from, tmp_.data() + from, k, n);
      for (size_t i = 0; i < k; ++i) pairs_[from + i] = {uint32_t(sorted[i] >> 32), uint32_t(sorted[i])};
    });
  }
  // Where bucketed items go, buckets in order and parts in order within a bucket: count_[p].value[b] (part p's
  // items in bucket b) becomes the place of the first of them, bucket_at_[b] the start of bucket b (of `total`).
  void bucket_places(size_t parts, size_t buckets, size_t total) {
    bucket_at_.resize(buckets + 1);
    for (size_t b = 0, at = 0; b < buckets; ++b) {
      bucket_at_[b] = at;
      for (size_t p = 0; p < parts; ++p) {
        uint32_t& c = count_[p].value[b];
        const uint32_t k = c;
        c = uint32_t(at);
        at += k;
      }
    }
    bucket_at_[buckets] = total;
  }

  struct Entry {
    FlatBox box;
    uint32_t id;
    uint32_t cell;  // in the level (its coordinates follow from box.lo again: coord())
  };
  struct Level {
    double origin[3] = {0, 0, 0};
    double inv = 0;      // 1 / cell width (0: one cell along every axis)
    int dims[3] = {1, 1, 1};
    std::vector<uint32_t> start;  // start[c] .. start[c + 1]: cell c's boxes in `entries`
    std::vector<Entry> entries;   // in cell order, then in the order visited (build())
  };

  // The cell coordinate of x along axis a: monotonic in x and clamped to the grid, so that two lower corners at
  // most a cell width apart get coordinates at most one apart (the width is a millionth above the largest box,
  // far beyond the rounding of the subtraction and the product).
  static int coord(const Level& lv, double x, int a) {
    const double f = (x - lv.origin[a]) * lv.inv;
    if (!(f > 0)) return 0;
    return f >= lv.dims[a] - 1 ? lv.dims[a] - 1 : int(f);
  }

  // Builds a level from ids_[0, m): the boxes up to twice the median size go into it, the rest are moved to the
  // front of ids_ (their count is returned). The passes over the boxes run on the pool in ranges, each range's
  // results joined in range order (the same level whatever the ranges).
  uint32_t build(Level& lv, uint32_t m, bool first) {
    // The first level of every box (the usual case: sizes within a factor of two) needs no split: all of them, in
    // body order, with the range flatten() found.
    const double limit = size_limit(m);
    const SmallBoxes sb = first && limit >= sizes_[1] ? every_box() : split_by_size(m, limit);
    const uint64_t cells = size_cells(lv, sb);
    if (first) visit_in_last_order(lv, sb.large == 0);
    // Counting sort of the small boxes by cell, stable (in small_ order within a cell).
    const uint32_t s = uint32_t(small_.size());
    lv.entries.resize(s);
    cell_tmp_.resize(s);
    entry_tmp_.resize(s);
    if (!pool_ || s < kParallelCells)
      sort_by_cell(lv, cells);
    else
      sort_by_cell_on_pool(lv, cells);
    return sb.large;
  }

  // When the first level holds every body, as it did in the last frame with as many bodies, its boxes are visited in
  // the order of the last frame's entries (small_ becomes that order): bodies move little between frames, so the
  // sort by cell then writes its entries nearly in sequence rather than to random places. Only the order within a
  // cell changes, and with it neither the pairs (sorted at the end) nor the tests counted.
  void visit_in_last_order(const Level& lv, bool all) {
    const uint32_t s = uint32_t(small_.size());
    if (all && last_all_ == s && lv.entries.size() == s)
      for (uint32_t k = 0; k < s; ++k) small_[k] = lv.entries[k].id;
    last_all_ = all ? s : 0;  // what the entries will hold once this level is built
  }

  // Every box checked, flattened and sized (its largest side), on the pool in ranges of bodies (the lowest range
  // that throws names the first bad body, as one thread would); per range the smallest and largest size and the
  // range of the lower corners, joined into sizes_ and all_.
  void flatten(const std::vector<BodyBounds>& bodies, uint64_t frame) {
    const uint32_t n = uint32_t(bodies.size());
    box_.resize(n);
    ids_.resize(n);
    size_.resize(n);
    const Ranges r = pool_ranges(pool_, n, kGrainBodies);
    if (span_.size() < r.parts) span_.resize(r.parts);
    for_ranges(pool_, r, [&](size_t part, size_t b, size_t e) {
      Span& sp = span_[part].value;
      sp = Span{};
      for (size_t i = b; i < e; ++i) {
        check_body(bodies[i], name_, i, frame);
        const FlatBox f = flat(bodies[i].box);
        box_[i] = f;
        ids_[i] = uint32_t(i);
        size_[i] = std::max({f.hi[0] - f.lo[0], f.hi[1] - f.lo[1], f.hi[2] - f.lo[2]});
        sp.smallest = std::min(sp.smallest, size_[i]);
        sp.largest = std::max(sp.largest, size_[i]);
        for (int a = 0; a < 3; ++a) sp.lo[a] = std::min(sp.lo[a], f.lo[a]), sp.hi[a] = std::max(sp.hi[a], f.lo[a]);
      }
    });
    sizes_[0] = HUGE_VAL, sizes_[1] = 0;
    all_ = SmallBoxes{};
    for (int a = 0; a < 3; ++a) all_.lo[a] = HUGE_VAL, all_.hi[a] = -HUGE_VAL;
    for (size_t p = 0; p < r.parts; ++p) {
      const Span& sp = span_[p].value;
      sizes_[0] = std::min(sizes_[0], sp.smallest), sizes_[1] = std::max(sizes_[1], sp.largest);
      for (int a = 0; a < 3; ++a) all_.lo[a] = std::min(all_.lo[a], sp.lo[a]), all_.hi[a] = std::max(all_.hi[a], sp.hi[a]);
    }
    all_.width = sizes_[1];
  }

  // The size of a box: its largest side (size_, by body). The level takes boxes up to twice the median of
  // ids_[0, m) when the sizes differ by more than a factor of two, else all. The first level's smallest and largest
  // come from flatten().
  double size_limit(uint32_t m) {
    double smallest = sizes_[0], largest = sizes_[1];
    if (m != box_.size()) {
      smallest = HUGE_VAL, largest = 0;
      for (uint32_t k = 0; k < m; ++k) smallest = std::min(smallest, size_[ids_[k]]), largest = std::max(largest, size_[ids_[k]]);
    }
    if (!(largest > 2 * smallest)) return largest;
    sorted_.resize(m);
    for (uint32_t k = 0; k < m; ++k) sorted_[k] = size_[ids_[k]];
    std::nth_element(sorted_.begin(), sorted_.begin() + m / 2, sorted_.end());
    return 2 * sorted_[m / 2];
  }

  // What the split leaves for the level: the largest small box, the range of the small ones' lower corners.
  struct SmallBoxes {
    uint32_t large = 0;
    double width = 0, lo[3], hi[3];
  };

  SmallBoxes every_box() {
    small_.resize(box_.size());
    for (uint32_t k = 0; k < small_.size(); ++k) small_[k] = k;
    return all_;
  }

  // Split: the small ones (size <= limit, which includes the median and everything below) into small_, in order;
  // the large ones to the front of ids_. Per range its small and large ones, joined in range order.
  SmallBoxes split_by_size(uint32_t m, double limit) {
    const Ranges r = pool_ranges(pool_, m, kGrainSplit);
    if (split_.size() < r.parts) split_.resize(r.parts);
    for_ranges(pool_, r, [&](size_t part, size_t b, size_t e) {
      Split& sp = split_[part].value;
      sp.small.clear();
      sp.large.clear();
      sp.width = 0;
      for (int a = 0; a < 3; ++a) sp.lo[a] = HUGE_VAL, sp.hi[a] = -HUGE_VAL;
      for (size_t k = b; k < e; ++k) {
        const uint32_t id = ids_[k];
        if (size_[id] > limit) {
          sp.large.push_back(id);
          continue;
        }
        sp.small.push_back(id);
        sp.width = std::max(sp.width, size_[id]);
        const FlatBox& box = box_[id];
        for (int a = 0; a < 3; ++a) sp.lo[a] = std::min(sp.lo[a], box.lo[a]), sp.hi[a] = std::max(sp.hi[a], box.lo[a]);
      }
    });
    SmallBoxes out;
    for (int a = 0; a < 3; ++a) out.lo[a] = HUGE_VAL, out.hi[a] = -HUGE_VAL;
    small_.clear();
    for (size_t p = 0; p < r.parts; ++p) {
      const Split& sp = split_[p].value;
      small_.insert(small_.end(), sp.small.begin(), sp.small.end());
      for (uint32_t id : sp.large) ids_[out.large++] = id;
      out.width = std::max(out.width, sp.width);
      for (int a = 0; a < 3; ++a) out.lo[a] = std::min(out.lo[a], sp.lo[a]), out.hi[a] = std::max(out.hi[a], sp.hi[a]);
    }
    return out;
  }

  // The cell: the largest box and a millionth, and no finer than about kCellsPerBox cells a box over the range of
  // the lower corners. Sets the level's origin, inverse width and dimensions; returns its cell count.
  uint64_t size_cells(Level& lv, const SmallBoxes& sb) {
    const uint32_t s = uint32_t(small_.size());
    double range[3], span = sb.width, volume = 1;
    for (int a = 0; a < 3; ++a) {
      lv.origin[a] = sb.lo[a];
      range[a] = sb.hi[a] - sb.lo[a];
      span = std::max(span, range[a]);
    }
    // (An axis along which every corner and box is flat counts as a thousandth of the widest one.)
    for (int a = 0; a < 3; ++a) volume *= std::max({range[a], sb.width, 1e-3 * span});
    double cw = sb.width * (1 + 1e-6);
    const double coarse = std::cbrt(volume / (kCellsPerBox * double(s)));
    if (!(cw >= coarse)) cw = coarse;
    lv.inv = cw > 0 && std::isfinite(cw) ? 1 / cw : 0;
    for (int a = 0; a < 3; ++a) {
      const double d = std::floor(range[a] * lv.inv) + 1;
      lv.dims[a] = d >= 1 && d < 1 << 20 ? int(d) : 1;
      if (!(d >= 1 && d < 1 << 20)) lv.inv = 0;
    }
    if (lv.inv == 0) lv.dims[0] = lv.dims[1] = lv.dims[2] = 1;
    return uint64_t(lv.dims[0]) * lv.dims[1] * lv.dims[2];
  }

  // Small box k's cell into cell_tmp_, its entry into entry_tmp_ (read from box_ once, in small_'s order, which need
  // not be the bodies').
  void find_cell(const Level& lv, uint32_t k) {
    // small_'s order is the last frame's cells', not the bodies': box_ is read at random, so a few boxes ahead are
    // fetched while this one is placed (both of its cache lines).
    if (k + kAhead < small_.size()) {
      const char* ahead = reinterpret_cast<const char*>(&box_[small_[k + kAhead]]);
      __builtin_prefetch(ahead);
      __builtin_prefetch(ahead + sizeof(FlatBox) - 1);
    }
    const FlatBox& box = box_[small_[k]];
    int q[3];
    for (int a = 0; a < 3; ++a) q[a] = coord(lv, box.lo[a], a);
    cell_tmp_[k] = uint32_t((q[0] * lv.dims[1] + q[1]) * lv.dims[2] + q[2]);
    entry_tmp_[k] = {box, small_[k], cell_tmp_[k]};
  }

  // Counts in start[c + 1], which becomes the place of cell c's next box as the boxes are placed, and so ends as the
  // start of cell c + 1 (no second array of places to clear and fill).
  void sort_by_cell(Level& lv, uint64_t cells) {
    const uint32_t s = uint32_t(small_.size());
    lv.start.assign(cells + 1, 0);
    for (uint32_t k = 0; k < s; ++k) {
      find_cell(lv, k);
      ++lv.start[cell_tmp_[k] + 1];
    }
    for (uint64_t c = 0, at = 0; c < cells; ++c) {
      const uint32_t k = lv.start[c + 1];
      lv.start[c + 1] = uint32_t(at);
      at += k;
    }
    for (uint32_t k = 0; k < s; ++k) place(lv, k, lv.start[cell_tmp_[k] + 1]++);
  }

  // On the pool, in buckets of consecutive cells (bucket c * B / cells of cell c): each range of boxes finds their
  // cells and counts them per bucket; the buckets' places follow (range by range within a bucket); each range puts
  // its boxes in their buckets, in order; each bucket counts its cells' boxes, writes its cells' starts and places
  // its boxes. The same order as sort_by_cell.
  void sort_by_cell_on_pool(Level& lv, uint64_t cells) {
    const uint32_t s = uint32_t(small_.size());
    const size_t buckets = 4 * size_t(pool_->size());
    auto bucket_of = [&](uint64_t c) { return size_t(c * buckets / cells); };
    auto first_cell = [&](size_t b) { return (uint64_t(b) * cells + buckets - 1) / buckets; };
    const Ranges r2 = pool_ranges(pool_, s, kGrainCells);
    if (count_.size() < r2.parts) count_.resize(r2.parts);
    pool_->parallel_for(r2.parts, [&](size_t part) {
      std::vector<uint32_t>& cnt = count_[part].value;
      cnt.assign(buckets, 0);
      for (size_t k = r2.begin(part); k < r2.end(part); ++k) {
        find_cell(lv, uint32_t(k));
        ++cnt[bucket_of(cell_tmp_[k])];
      }
    });
    bucket_places(r2.parts, buckets, s);
    order_.resize(s);
    pool_->parallel_for(r2.parts, [&](size_t part) {
      std::vector<uint32_t>& at = count_[part].value;
      for (size_t k = r2.begin(part); k < r2.end(part); ++k) order_[at[bucket_of(cell_tmp_[k])]++] = uint32_t(k);
    });
    lv.start.resize(cells + 1);
    lv.start[0] = 0;
    // Each bucket its cells' counts, then places, in start[c + 1] (as sort_by_cell): start[c0 + 1 .. c1] are its own.
    pool_->parallel_for(buckets, [&](size_t b) {
      const uint64_t c0 = first_cell(b), c1 = first_cell(b + 1);
      uint32_t* at_cell = lv.start.data() + 1;
      std::fill(at_cell + c0, at_cell + c1, 0u);
      for (size_t i = bucket_at_[b]; i < bucket_at_[b + 1]; ++i) ++at_cell[cell_tmp_[order_[i]]];
      uint32_t at = uint32_t(bucket_at_[b]);
      for (uint64_t c = c0; c < c1; ++c) {
        const uint32_t n = at_cell[c];
        at_cell[c] = at;
        at += n;
      }
      // (Where a box a few ahead will go is fetched first: in the first frame, or after a shuffle, those places are
      // random.)
      const size_t i1 = bucket_at_[b + 1];
      for (size_t i = bucket_at_[b]; i < i1; ++i) {
        if (i + kAhead < i1) __builtin_prefetch(lv.entries.data() + at_cell[cell_tmp_[order_[i + kAhead]]], 1);
        const uint32_t k = order_[i];
        place(lv, k, at_cell[cell_tmp_[k]]++);
      }
    });
  }

  // Small box k (its entry in entry_tmp_) to entry p of the level.
  void place(Level& lv, uint32_t k, uint32_t p) {
    lv.entries[p] = entry_tmp_[k];
  }

  // Box e against the entries [from, to). Without a branch on the outcome (which the scenes make hard to
  // predict): every candidate's key is written, and the count advances only for an overlap.
  static void test_run(const Entry& e, const Entry* entries, uint32_t from, uint32_t to, Found& f) {
    if (from >= to) return;
    f.tests += to - from;
    if (f.keys.size() < f.n + (to - from)) f.keys.resize(2 * (f.n + (to - from)));
    uint64_t* out = f.keys.data() + f.n;
    size_t k = 0;
    for (uint32_t q = from; q < to; ++q) {
      out[k] = pair_key(e.id, entries[q].id);
      k += overlaps(e.box, entries[q].box);
    }
    f.n += k;
  }

  // Every overlapping pair of a level's boxes, once: each box against the rest of its cell and the cells after it
  // among its 26 neighbours, which are five runs of consecutive cells: (x, y, z+1), (x, y+1, z-1..z+1) and
  // (x+1, y-1..y+1, z-1..z+1).
  // On the pool in ranges of entries, each into a part of out_ (part 0 continues the search's first list).
  void pairs_within(const Level& lv) {
    const uint32_t s = uint32_t(lv.entries.size());
    const Ranges r = pool_ranges(pool_, s, kGrainEntries, 8);
    if (out_.size() < r.parts) out_.resize(r.parts);
    for_ranges(pool_, r, [&](size_t part, size_t b, size_t e) {
      pairs_within(lv, uint32_t(b), uint32_t(e), out_[part].value);
    });
  }
  void pairs_within(const Level& lv, uint32_t first, uint32_t end, Found& f) {
    const Entry* en = lv.entries.data();
    const uint32_t* st = lv.start.data();
    const int dy = lv.dims[1], dz = lv.dims[2];
    for (uint32_t p = first; p < end; ++p) {
      const Entry& e = en[p];
      const int c = int(e.cell);
      const int x = coord(lv, e.box.lo[0], 0), y = coord(lv, e.box.lo[1], 1), z = coord(lv, e.box.lo[2], 2);
      // The same cell after p, and (x, y, z+1).
      test_run(e, en, p + 1, st[z + 1 < dz ? c + 2 : c + 1], f);
      const int z0 = z > 0 ? z - 1 : 0, z1 = z + 1 < dz ? z + 1 : z;
      auto row = [&](int rx, int ry) {
        const int base = (rx * dy + ry) * dz;
        test_run(e, en, st[base + z0], st[base + z1 + 1], f);
      };
      if (y + 1 < dy) row(x, y + 1);
      if (x + 1 < lv.dims[0]) {
        if (y > 0) row(x + 1, y - 1);
        row(x + 1, y);
        if (y + 1 < dy) row(x + 1, y + 1);
      }
    }
  }

  // Body `id` (larger than the level's cell) against the level's boxes whose lower corner lies in a cell its box
  // can reach: from one cell below its own lower corner's to its upper corner's, on every axis.
  void pairs_with(const Level& lv, uint32_t id, Found& f) {
    const FlatBox& b = box_[id];
    int c0[3], c1[3];
    for (int a = 0; a < 3; ++a) {
      c0[a] = std::max(coord(lv, b.lo[a], a) - 1, 0);
      c1[a] = coord(lv, b.hi[a], a);
    }
    const Entry e{b, id, 0};
    const Entry* en = lv.entries.data();
    for (int x = c0[0]; x <= c1[0]; ++x)
      for (int y = c0[1]; y <= c1[1]; ++y) {
        const int base = (x * lv.dims[1] + y) * lv.dims[2];
        test_run(e, en, lv.start[base + c0[2]], lv.start[base + c1[2] + 1], f);
      }
  }

  // Finer cells test fewer boxes but cost more to clear and count; 16 measured best on the paper's scene at 256
  // and 1024 bodies (bench_broadphase, 1 to 16 tried).
  static constexpr double kCellsPerBox = 16;
  // Parts of the pool's loops (each a few microseconds): bodies checked and flattened, boxes split by size and
  // placed in cells, entries searched (about 50 ns each at 16 cells a box).
  static constexpr size_t kGrainBodies = 512, kGrainSplit = 512, kGrainCells = 64, kGrainEntries = 32;
  static constexpr size_t kParallelSort = 16384;  // pairs of a frame sorted on the pool (in buckets of first bodies)
  static constexpr size_t kBucketsPerThread = 8;
  static constexpr size_t kParallelCells = 1024;  // boxes of a level sorted by cell on the pool
  static constexpr size_t kAhead = 16;            // boxes (or their places) fetched ahead of the one read
  std::vector<FlatBox> box_;
  std::vector<uint32_t> ids_, small_, cell_tmp_;
  std::vector<double> size_, sorted_;  // size_: by body
  double sizes_[2] = {0, 0};           // the smallest and largest box
  uint32_t last_all_ = 0;              // the first level holds every one of this many bodies (0: not so)
  struct Split {
    std::vector<uint32_t> small, large;
    double width = 0, lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  };
  struct Span {
    double smallest = HUGE_VAL, largest = 0, lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  };
  std::vector<PartSlot<Span>> span_;
  SmallBoxes all_;  // every box: the largest, the range of the lower corners
  std::vector<PartSlot<Split>> split_;
  std::vector<Entry> entry_tmp_;
  std::vector<Level> levels_;
  std::vector<PartSlot<Found>> out_;  // the pairs of this frame, per part of the search
  // sort_on_pool: where each bucket starts in keys_ and pairs_; the keys by bucket.
  std::vector<size_t> bucket_at_;
  std::vector<uint64_t> keys_;
  // build's sort on the pool: per range of boxes its counts (then places) per bucket; the boxes by bucket.
  std::vector<PartSlot<std::vector<uint32_t>>> count_;
  std::vector<uint32_t> order_;
  std::vector<uint64_t> tmp_;
};

}  // namespace

std::unique_ptr<Broadphase> make_grid() { return std::make_unique<UniformGrid>(); }

}  // namespace voxcd::detail
