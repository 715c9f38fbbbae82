#include "voxcd/ref/vector_gen.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "voxcd/ref/fixed.h"
#include "voxcd/ref/float_model.h"
#include "voxcd/ref/detail/vector_gen_sparse.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"

namespace voxcd {

namespace {

struct MapDesc {
  uint32_t base, nx, ny, nz;
  bool sparse = false;  // a sparse map: its bricks at brick_base (brick_units units)
  uint32_t brick_base = 0, brick_units = 0;
};
struct Block {
  uint32_t base, count;
  double centre[3];
  double extent;        // largest axis extent, in voxels
  bool sparse = false;  // shell words of a sparse shell (count words)
};

class Generator {
 public:
  explicit Generator(const GenerateOptions& o) : opt_(o), cfg_(o.config), rng_(o.seed) { cfg_.validate(); }

  GeneratedVectors run() {
    GeneratedVectors g;
    g.config = cfg_;
    make_maps(g.memory);
    if (cfg_.sparse()) make_sparse_maps(g.memory);
    make_shell(g.memory);
    if (cfg_.sparse()) make_sparse_shell(g.memory);
    if (aims_at("job.map.top")) add_top_map(g.memory);
    if (aims_at("job.shell.top") || aims_at("job.points.max")) add_top_block(g.memory);
    mem_ = &g.memory;
    for (size_t k = 0; k < opt_.jobs; ++k) {
      const bool aimed = !opt_.aim.empty() && k % 2 == 1;
      g.jobs.push_back(aimed ? aimed_job(uint32_t(k), opt_.aim[(k / 2) % opt_.aim.size()]) : make_job(uint32_t(k)));
    }
    return g;
  }

 private:
  uint64_t uni(uint64_t lo, uint64_t hi) { return std::uniform_int_distribution<uint64_t>(lo, hi)(rng_); }
  int64_t sint(int64_t lo, int64_t hi) { return std::uniform_int_distribution<int64_t>(lo, hi)(rng_); }
  double real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  bool chance(double p) { return std::bernoulli_distribution(p)(rng_); }

  uint32_t dim_max() const { return uint32_t(std::min<uint64_t>(cfg_.max_dim(), 1u << 20)); }
  uint32_t clip_dim(uint64_t d) const { return uint32_t(std::max<uint64_t>(1, std::min<uint64_t>(d, dim_max()))); }

  // Words of a map of these dimensions under cfg_ (states or distances).
  uint64_t words_of(const MapDesc& m) const {
    Job j;
    j.nx = m.nx;
    j.ny = m.ny;
    j.nz = m.nz;
    return map_words(cfg_, j);
  }

  void make_maps(DeviceMemory& mem) {
    if (cfg_.distance()) return make_distance_maps(mem);
    const uint64_t spw = uint64_t(cfg_.states_per_word());
    std::vector<std::array<uint64_t, 3>> dims = {
        {1, 1, 1}, {37, 5, 3}, {16, 16, 16}, {33, 17, 9}, {uni(1, 40), uni(1, 40), uni(1, 40)},
        {uni(1, 12), uni(1, 12), uni(1, 12)}, {cfg_.max_dim(), 2, 1}, {1, cfg_.max_dim(), 1}};
    uint64_t next = uni(0, 5);  // maps do not start at word 0
    for (auto& d : dims) {
      MapDesc m{0, clip_dim(d[0]), clip_dim(d[1]), clip_dim(d[2])};
      const uint64_t words = (uint64_t(m.nx) * m.ny * m.nz + spw - 1) / spw;
      if (next + words > cfg_.map_depth()) continue;
      m.base = uint32_t(next);
      maps_.push_back(m);
      next += words + uni(0, 3);
    }
    next = std::min<uint64_t>(next, cfg_.map_depth());
    // Garbage everywhere first, so a read of a wrong word shows.
    const uint64_t word_mask = cfg_.MEMW >= 64 ? ~uint64_t{0} : (uint64_t{1} << cfg_.MEMW) - 1;
    mem.map.resize(next);
    for (auto& w : mem.map) w = rng_() & word_mask;
    // Every fill pattern appears in every run; which map gets which varies with the seed.
    const int shift = int(uni(0, 4));
    for (size_t k = 0; k < maps_.size(); ++k) fill_map(mem, maps_[k], int((k + size_t(shift)) % 5));
  }

  void fill_map(DeviceMemory& mem, const MapDesc& m, int pattern) {
    const uint64_t spw = uint64_t(cfg_.states_per_word());
    const uint64_t n = uint64_t(m.nx) * m.ny * m.nz;
    for (uint64_t i = 0; i < n; ++i) {
      const uint64_t x = i % m.nx, y = (i / m.nx) % m.ny, z = i / (uint64_t(m.nx) * m.ny);
      uint64_t s = 0;
      switch (pattern) {
        case 0: s = uni(0, 3); break;                       // every state, reserved included
        case 1: s = chance(0.05) ? uni(1, 2) : 0; break;    // sparse
        case 2: {                                           // a solid box: surface around interior
          const bool edge = x == 0 || y == 0 || z == 0 || x + 1 == m.nx || y + 1 == m.ny || z + 1 == m.nz;
          s = edge ? kSurface : kInterior;
          break;
        }
        case 3: s = (x + y + z) % 2 ? kSurface : kEmpty; break;  // checkerboard
        default: s = chance(0.5) ? kInterior : kReserved; break;
      }
      const uint64_t word = m.base + i / spw, shift = 2 * (i % spw);
      mem.map[word] = (mem.map[word] & ~(uint64_t{3} << shift)) | (s << shift);
    }
  }

  // Distance maps: the same sizes, each on a bank boundary, filled with node values (docs/conformance.md).
  void make_distance_maps(DeviceMemory& mem) {
    std::vector<std::array<uint64_t, 3>> dims = {
        {1, 1, 1}, {37, 5, 3}, {16, 16, 16}, {33, 17, 9}, {uni(1, 40), uni(1, 40), uni(1, 40)},
        {uni(1, 12), uni(1, 12), uni(1, 12)}, {cfg_.max_dim(), 2, 1}, {1, cfg_.max_dim(), 1}};
    uint64_t next = 8 * uni(0, 2);
    for (auto& d : dims) {
      MapDesc m{0, clip_dim(d[0]), clip_dim(d[1]), clip_dim(d[2])};
      const uint64_t words = words_of(m);
      if (next + words > cfg_.map_depth()) continue;
      m.base = uint32_t(next);
      maps_.push_back(m);
      next += words + 8 * uni(0, 1);
    }
    next = std::min<uint64_t>(next, cfg_.map_depth());
    if (maps_.empty())
      throw std::invalid_argument("no distance map fits the voxmap memory of 2^MAW = " +
                                  std::to_string(cfg_.map_depth()) + " words");
    const uint64_t word_mask = cfg_.MEMW >= 64 ? ~uint64_t{0} : (uint64_t{1} << cfg_.MEMW) - 1;
    mem.map.resize(next);
    for (auto& w : mem.map) w = rng_() & word_mask;  // garbage, also in the slots that hold no node
    const int shift = int(uni(0, 5));
    for (size_t k = 0; k < maps_.size(); ++k) fill_distance_map(mem, maps_[k], int((k + size_t(shift)) % 6));
  }

  // Node values: 0 uniform over the whole SB range; 1 a sphere's distance, clamped to the band (far inside and
  // far outside); 2 only the two clamped extremes; 3 a linear ramp through the band; 4 alternating extremes (the
  // widest products); 5 the values around the band's edges (+-(max-1), max, min, min+1).
  void fill_distance_map(DeviceMemory& mem, const MapDesc& m, int pattern) {
    const int64_t qmax = (int64_t{1} << (cfg_.SB - 1)) - 1, qmin = -qmax - 1;
    const uint64_t vmask = (uint64_t{1} << cfg_.SB) - 1;
    Job j;
    j.map_base = m.base;
    j.nx = m.nx;
    j.ny = m.ny;
    j.nz = m.nz;
    const double c[3] = {m.nx / 2.0, m.ny / 2.0, m.nz / 2.0};
    const double r = std::max(0.5, std::min({m.nx, m.ny, m.nz}) / 3.0);
    const double step = std::max(1.0, double(qmax) / 4.0);  // a band of about 4 voxels
    for (uint64_t Z = 0; Z <= m.nz; ++Z)
      for (uint64_t Y = 0; Y <= m.ny; ++Y)
        for (uint64_t X = 0; X <= m.nx; ++X) {
          int64_t q = 0;
          switch (pattern) {
            case 0: q = sint(qmin, qmax); break;
            case 1: {
              const double d = std::sqrt((X - c[0]) * (X - c[0]) + (Y - c[1]) * (Y - c[1]) + (Z - c[2]) * (Z - c[2]));
              q = std::clamp<int64_t>(int64_t(std::llround((d - r) * step)), qmin, qmax);
              break;
            }
            case 2: q = chance(0.5) ? qmin : qmax; break;
            case 3: q = std::clamp<int64_t>(int64_t(X) + int64_t(Y) - int64_t(Z) - 8, qmin, qmax); break;
            case 4: q = (X + Y + Z) % 2 ? qmax : qmin; break;
            default: {
              const int64_t v[] = {qmax, qmax - 1, qmin, qmin + 1, 0, -1};
              q = v[uni(0, 5)];
              break;
            }
          }
          const NodeAddress a = node_address(cfg_, j, X, Y, Z);
          const uint64_t sh = uint64_t(cfg_.SB) * a.slot;
          mem.map[a.word] = (mem.map[a.word] & ~(vmask << sh)) | ((uint64_t(q) & vmask) << sh);
        }
  }

  // A sparse device's sparse maps (ref/detail/vector_gen_sparse.h), after the dense ones, with garbage between and
  // around them: sizes from a single cell to more cells than a table word holds, every pattern.
  void make_sparse_maps(DeviceMemory& mem) {
    const uint64_t B = brick_edge(cfg_);
    std::vector<std::array<uint64_t, 3>> dims = {
        {1, 1, 1}, {B, B, B}, {3 * B + 1, B - 1, 2}, {37, 17, 9}, {uni(1, 40), uni(1, 40), uni(1, 40)},
        {uni(1, 24), uni(1, 24), uni(1, 24)}, {std::min<uint64_t>(cfg_.max_dim(), 96), 2 * B, 3}};
    const uint64_t word_mask = cfg_.MEMW >= 64 ? ~uint64_t{0} : (uint64_t{1} << cfg_.MEMW) - 1;
    const int shift = int(uni(0, detail::kSparseMapPatterns - 1));
    uint64_t next = mem.map.size() + uni(1, 9);
    for (size_t k = 0; k < dims.size(); ++k) {
      detail::SparseMapPlan plan;
      const int pattern = int((k + size_t(shift)) % detail::kSparseMapPatterns);
      const size_t before = mem.map.size();
      if (!detail::add_sparse_map(cfg_, rng_, clip_dim(dims[k][0]), clip_dim(dims[k][1]), clip_dim(dims[k][2]),
                                  pattern, next, cfg_.map_depth(), mem.map, plan))
        continue;
      for (size_t w = before; w < mem.map.size(); ++w)
        if (w < plan.map_base || (w >= plan.map_base + table_words(cfg_, sparse_job(plan)) && w < plan.brick_base))
          mem.map[w] = rng_() & word_mask;  // garbage before and between
      maps_.push_back({plan.map_base, plan.nx, plan.ny, plan.nz, true, plan.brick_base, plan.brick_units});
      next = mem.map.size() + uni(0, 5);
    }
  }

  static Job sparse_job(const detail::SparseMapPlan& p) {
    Job j;
    j.nx = p.nx, j.ny = p.ny, j.nz = p.nz;
    return j;
  }

  // A sparse device's sparse shells: blocks of every pattern.
  void make_sparse_shell(DeviceMemory& mem) {
    const size_t room = cfg_.shell_depth() > mem.shell.size() ? cfg_.shell_depth() - mem.shell.size() : 0;
    for (int pattern = 0; pattern < detail::kSparseShellPatterns; ++pattern) {
      const size_t words = std::min<size_t>(room / detail::kSparseShellPatterns, 120);
      if (words == 0) return;
      std::vector<ShellWord> block = detail::sparse_shell_block(cfg_, rng_, pattern, words);
      if (block.empty()) continue;
      Job j;
      j.shell_base = uint32_t(mem.shell.size());
      j.shell_count = uint32_t(block.size());
      const std::vector<ShellWord> pts = shell_points(cfg_, block, Job{0, Mode::All, 0, 0, j.shell_count});
      const size_t first = blocks_.size();
      add_block(mem, block);
      if (blocks_.size() == first) continue;
      Block& b = blocks_.back();
      b.sparse = true;
      extent_of(pts, b);
    }
  }

  // A block's centre and extent from its points (a sparse block's words are not points).
  void extent_of(const std::vector<ShellWord>& pts, Block& b) const {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    b.extent = 0;
    for (int i = 0; i < 3; ++i) b.centre[i] = 0;
    for (const ShellWord& w : pts)
      for (int i = 0; i < 3; ++i) {
        const double v = to_double(w[i], cfg_.PF);
        b.centre[i] += v / double(pts.size());
        lo[i] = std::min(lo[i], v);
        hi[i] = std::max(hi[i], v);
      }
    for (int i = 0; i < 3; ++i) b.extent = pts.empty() ? 0 : std::max(b.extent, hi[i] - lo[i]);
  }

  // Raw shell coordinate for a real value, clipped into PW.
  int64_t raw(double v) const {
    const FixedFormat f = point_format(cfg_);
    const double c = std::clamp(v, f.min_value(), f.max_value());
    return quantize(c, f, "generated point");
  }

  void add_block(DeviceMemory& mem, const std::vector<ShellWord>& pts) {
    if (pts.empty()) return;
    if (mem.shell.size() + pts.size() > cfg_.shell_depth())
      throw std::invalid_argument("generated shell blocks need " + std::to_string(mem.shell.size() + pts.size()) +
                                  " words; the shell memory holds 2^SAW = " + std::to_string(cfg_.shell_depth()));
    Block b{uint32_t(mem.shell.size()), uint32_t(pts.size()), {0, 0, 0}, 0};
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const ShellWord& w : pts) {
      for (int i = 0; i < 3; ++i) {
        const double v = to_double(w[i], cfg_.PF);
        b.centre[i] += v / double(pts.size());
        lo[i] = std::min(lo[i], v);
        hi[i] = std::max(hi[i], v);
      }
      mem.shell.push_back(w);
    }
    for (int i = 0; i < 3; ++i) b.extent = std::max(b.extent, hi[i] - lo[i]);
    blocks_.push_back(b);
  }

  // The directed blocks' sizes (faces, extremes, wide, ends): in full where the shell memory holds them beside the
  // cloud, else each shrunk in the same proportion to what is left (a small derived configuration's memory); a cloud
  // the memory cannot hold is an error (add_block).
  int fixed_count(int full) const {
    const size_t fixed = 400 + 64 + 800 + (cfg_.distance() ? 400 : 0), depth = cfg_.shell_depth();
    if (opt_.cloud_points + fixed <= depth || opt_.cloud_points >= depth) return full;
    return std::max(1, int(uint64_t(full) * (depth - opt_.cloud_points) / fixed));
  }

  void make_shell(DeviceMemory& mem) {
    const int64_t one = int64_t{1} << cfg_.PF;
    const FixedFormat pf = point_format(cfg_);
    // A cloud around a map of up to ~40 voxels.
    std::vector<ShellWord> cloud;
    for (size_t k = 0; k < opt_.cloud_points; ++k)
      cloud.push_back({raw(real(-3, 43)), raw(real(-3, 43)), raw(real(-3, 43))});
    add_block(mem, cloud);
    // Voxel faces and their neighbours: integers, +-1 ulp, +-1/4, +-1/2.
    std::vector<ShellWord> faces;
    const int64_t offs[] = {0, 1, -1, one / 4, -one / 4, one / 2, -one / 2};
    for (int k = 0; k < fixed_count(400); ++k) {
      ShellWord w;
      int64_t c[3];
      for (int i = 0; i < 3; ++i) {
        const int64_t v = sint(-1, 17) * one + offs[uni(0, 6)];
        c[i] = std::clamp(v, pf.min_raw(), pf.max_raw());
      }
      w = {c[0], c[1], c[2]};
      faces.push_back(w);
    }
    add_block(mem, faces);
    // Full-range coordinates.
    std::vector<ShellWord> extremes;
    const int64_t ex[] = {pf.min_raw(), pf.max_raw(), 0, -1, 1, pf.min_raw() + 1, pf.max_raw() - 1, -one / 4};
    for (int k = 0; k < fixed_count(64); ++k) extremes.push_back({ex[uni(0, 7)], ex[uni(0, 7)], ex[uni(0, 7)]});
    add_block(mem, extremes);
    // A wide cloud across the whole 2^DW range.
    std::vector<ShellWord> wide;
    const double span = double(cfg_.max_dim());
    for (int k = 0; k < fixed_count(800); ++k) wide.push_back({raw(real(-10, span + 10)), raw(real(-2, 4)), raw(real(-2, 3))});
    add_block(mem, wide);
    if (cfg_.distance()) {
      // Weights at their ends: points on nodes (fraction 0), one ulp above, and one ulp below the next node
      // (fraction 2^WB - 1 under an identity pose).
      std::vector<ShellWord> ends;
      const int64_t fr[] = {0, 1, one - 1, one / 2, one - (one >> std::min(cfg_.PF, cfg_.WB))};
      for (int k = 0; k < fixed_count(400); ++k) {
        int64_t c[3];
        for (int i = 0; i < 3; ++i) c[i] = std::clamp(sint(-1, 17) * one + fr[uni(0, 4)], pf.min_raw(), pf.max_raw());
        ends.push_back({c[0], c[1], c[2]});
      }
      add_block(mem, ends);
    }
  }

  static void rotation(std::mt19937_64& rng, double R[3][3]) {
    // A uniformly random rotation from a random unit quaternion.
    std::normal_distribution<double> n(0, 1);
    double q[4];
    double len = 0;
    do {
      for (double& c : q) c = n(rng);
      len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    } while (len < 1e-9);
    for (double& c : q) c /= len;
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) R[i][j] = r[i][j];
  }

  void random_pose(const Block& b, const MapDesc& m, Job& j) {
    FloatPose pose;
    const int kind = int(uni(0, 9));
    double R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    double s = 1.0;
    if (kind <= 1) {
      // Identity or a signed axis permutation: quarter and half turns, entries exactly +-1.
      if (kind == 1) {
        int perm[3] = {0, 1, 2};
        std::shuffle(perm, perm + 3, rng_);
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k) R[i][k] = perm[i] == k ? (chance(0.5) ? 1.0 : -1.0) : 0.0;
      }
    } else {
      rotation(rng_, R);
      // Mostly shrink the block to about the map's size, so that many points land inside.
      const double md = double(std::min({m.nx, m.ny, m.nz})) + 1.0;
      const double fit = std::clamp(md / std::max(1.0, b.extent), 0.02, 1.0);
      s = chance(0.2) ? 1.0 : real(0.6, 1.4) * (chance(0.8) ? fit : 1.0);
    }
    // Within the matrix format: a narrow one (MW = MF + 1, as voxcd size derives when scale ratios are below 1)
    // cannot hold +1, so a turn's +1 entries become its largest value there. Unchanged for MW >= MF + 2.
    const FixedFormat mfmt = matrix_format(cfg_);
    const double mlo = std::max(-1.95, mfmt.min_value()), mhi = std::min(1.95, mfmt.max_value());
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) pose.M[i][k] = std::clamp(R[i][k] * s, mlo, mhi);
    // Bring the block's centre near the map's centre, with jitter, or place it exactly on faces / -1/4.
    const double mc[3] = {m.nx / 2.0, m.ny / 2.0, m.nz / 2.0};
    for (int i = 0; i < 3; ++i) {
      double mb = 0;
      for (int k = 0; k < 3; ++k) mb += pose.M[i][k] * b.centre[k];
      if (kind == 0)
        pose.t[i] = double(sint(-2, 2)) + (chance(0.3) ? -0.25 : 0.0);
      else
        pose.t[i] = mc[i] - mb + real(-0.3, 0.3) * std::max(1.0, double(i == 0 ? m.nx : i == 1 ? m.ny : m.nz));
    }
    if (kind == 2 && chance(0.5)) {
      // Far away, or a whole multiple of 2^DW away: would alias into the grid if indices were truncated.
      const int axis = int(uni(0, 2));
      pose.t[axis] += double(cfg_.max_dim()) * double(sint(1, 3)) * (chance(0.5) ? 1 : -1);
    }
    const FixedFormat tf = translation_format(cfg_);
    for (double& v : pose.t) v = std::clamp(v, tf.min_value(), tf.max_value());
    quantize_pose(cfg_, pose, j);
  }

  void extreme_pose(Job& j) {
    const FixedFormat mf = matrix_format(cfg_), tf = translation_format(cfg_);
    const int64_t mv[] = {mf.min_raw(), mf.max_raw(), 0, int64_t{1} << cfg_.MF, -(int64_t{1} << cfg_.MF), 1, -1};
    std::vector<int64_t> tv = {tf.min_raw(), tf.max_raw(), 0, -1};
    const int64_t far = int64_t(cfg_.max_dim()) << std::min(cfg_.TF(), 40);
    if (fits_signed(far, cfg_.TW)) tv.push_back(far);  // exactly 2^DW voxels: aliases if truncated to DW bits
    if (cfg_.TF() >= 2) tv.push_back(-(int64_t{1} << (cfg_.TF() - 2)));  // -1/4 voxel
    for (auto& row : j.M)
      for (auto& e : row) {
        const int64_t v = mv[uni(0, 6)];
        e = fits_signed(v, cfg_.MW) ? v : 0;
      }
    for (auto& e : j.t) e = tv[uni(0, tv.size() - 1)];
  }

  // A distance job's threshold and, sometimes, a translation one ulp below an integer (fractions of 2^WB - 1):
  // 0, the extremes of IW, a node value's exact multiple, one unit either side, or random.
  void distance_fields(Job& j) {
    const int iw = cfg_.IW();
    const int64_t tmax = iw >= 64 ? INT64_MAX : (int64_t{1} << (iw - 1)) - 1, tmin = -tmax - 1;
    const int64_t unit = int64_t{1} << (3 * cfg_.WB);  // one node unit at full weight
    const int64_t qmax = (int64_t{1} << (cfg_.SB - 1)) - 1;
    switch (uni(0, 7)) {
      case 0: j.threshold = 0; break;
      case 1: j.threshold = tmax; break;
      case 2: j.threshold = tmin; break;
      case 3: j.threshold = sint(-qmax, qmax) * unit; break;
      case 4: j.threshold = sint(-2, 2); break;
      case 5: j.threshold = (qmax - 1) * unit + sint(-1, 1); break;
      default: j.threshold = sint(tmin / 2, tmax / 2); break;
    }
    if (chance(0.15)) {
      const FixedFormat tf = translation_format(cfg_);
      for (auto& e : j.t) {
        // One ulp below an integer, in 128 bits (TF can be 63): a signed left shift of a negative value, or past
        // 64 bits, is undefined.
        const Acc v = Acc(sint(-1, 8)) * (Acc(1) << cfg_.TF()) - 1;
        if (v >= Acc(tf.min_raw()) && v <= Acc(tf.max_raw())) e = int64_t(v);
      }
    }
  }

  Job make_job(uint32_t index) {
    Job j;
    j.tag = uint32_t(index & cfg_.max_tag());
    const uint64_t mr = uni(0, 7);
    j.mode = mr < 4 ? Mode::All : mr < 6 ? Mode::First : Mode::Count;
    j.hit_mask = chance(0.5) ? kDefaultHitMask : uint8_t(uni(0, 15));
    const MapDesc& m = maps_[uni(0, maps_.size() - 1)];
    j.map_base = m.base;
    j.nx = m.nx;
    j.ny = m.ny;
    j.nz = m.nz;
    if (m.sparse) {
      j.sparse |= kSparseMap;
      j.brick_base = m.brick_base;
      j.brick_units = m.brick_units;
    }
    const Block& b = blocks_[uni(0, blocks_.size() - 1)];
    if (b.sparse) j.sparse |= kSparseShell;
    // Shell window: empty, one point, around a lane boundary, or random.
    const uint64_t L = uint64_t(cfg_.LANES);
    uint64_t count = 0;
    switch (uni(0, 5)) {
      case 0: count = chance(0.5) ? 0 : 1; break;
      case 1: count = std::min<uint64_t>(b.count, L * uni(1, 4) + uint64_t(sint(-1, 1))); break;
      case 2: count = b.count; break;
      default: count = uni(0, std::min<uint64_t>(b.count, 300)); break;
    }
    count = std::min<uint64_t>(count, b.count);
    j.shell_base = uint32_t(b.base + uni(0, b.count - count));
    j.shell_count = uint32_t(count);
    if (chance(0.08))
      extreme_pose(j);
    else
      random_pose(b, m, j);
    if (cfg_.distance()) distance_fields(j);
    return j;
  }

  // ---- Coverage-directed jobs (GenerateOptions::aim) ----

  bool aims_at(const std::string& bin) const {
    return std::find(opt_.aim.begin(), opt_.aim.end(), bin) != opt_.aim.end();
  }

  // A copy of the first dense map of more than one word at the top of the voxmap memory (on a bank boundary for a
  // distance map), the words between garbage: its addresses' upper bits (job.map.top).
  void add_top_map(DeviceMemory& mem) {
    const uint64_t word_mask = cfg_.MEMW >= 64 ? ~uint64_t{0} : (uint64_t{1} << cfg_.MEMW) - 1;
    for (const MapDesc& m : maps_) {
      const uint64_t words = words_of(m);
      if (m.sparse || words < 2 || m.base + words > mem.map.size()) continue;
      uint64_t base = cfg_.map_depth() - words;
      if (cfg_.distance()) base &= ~uint64_t{7};
      if (base < mem.map.size()) return;  // the memory is full already
      const size_t old = mem.map.size();
      mem.map.resize(base + words);
      for (size_t w = old; w < base; ++w) mem.map[w] = rng_() & word_mask;
      std::copy(mem.map.begin() + m.base, mem.map.begin() + m.base + words, mem.map.begin() + base);
      MapDesc top = m;
      top.base = uint32_t(base);
      top_map_ = maps_.size();
      maps_.push_back(top);
      return;
    }
  }

  // A dense job of every shell word, each point a hit at one voxel (ALL or COUNT): its counts' and point indices' top
  // bits (job.points.max); false when the shell memory is not full (add_top_block fills it).
  bool every_point_hits(Job& j, uint32_t index) {
    if (mem_->shell.size() != cfg_.shell_depth()) return false;
    j.sparse &= uint8_t(~kSparseShell);
    j.mode = index % 4 == 1 ? Mode::All : Mode::Count;
    j.shell_base = 0;
    j.shell_count = uint32_t(cfg_.shell_depth());
    j.hit_mask = 0xF;
    j.threshold = cfg_.IW() >= 64 ? INT64_MAX : (int64_t{1} << (cfg_.IW() - 1)) - 1;
    return pin_points(j, 0, 0, false);
  }

  // A copy of the faces block at the top of the shell memory, zero words between (job.shell.top).
  void add_top_block(DeviceMemory& mem) {
    for (const Block& b : blocks_) {
      if (b.sparse || b.count < 2) continue;
      const uint64_t base = cfg_.shell_depth() - b.count;
      if (base < mem.shell.size()) return;
      const std::vector<ShellWord> pts(mem.shell.begin() + b.base, mem.shell.begin() + b.base + b.count);
      mem.shell.resize(base, ShellWord{0, 0, 0});
      top_block_ = blocks_.size();
      add_block(mem, pts);
      return;
    }
  }

  // Every point of j at one voxel: M = 0 and t its place, voxel `index` on `axis` and the map's middle on the others
  // (a fraction below that voxel's floor when `fraction` is set); false when t does not fit TW.
  bool pin_points(Job& j, int axis, int64_t index, bool fraction) {
    const int64_t n[3] = {int64_t(j.nx), int64_t(j.ny), int64_t(j.nz)};
    for (auto& row : j.M)
      for (auto& e : row) e = 0;
    for (int i = 0; i < 3; ++i) {
      // A product, not a shift: the index may be negative.
      const Acc corner = Acc(i == axis ? index : n[i] / 2) * (Acc(1) << cfg_.TF());
      const Acc v = corner + (i == axis && fraction ? Acc(1) : Acc(0));
      if (v < Acc(translation_format(cfg_).min_raw()) || v > Acc(translation_format(cfg_).max_raw())) return false;
      j.t[i] = int64_t(v);
    }
    if (j.shell_count == 0) j.shell_count = 1;
    return true;
  }

  // The points of j as ref/ looks them up.
  std::vector<Lookup> lookups(const Job& j) const {
    std::vector<Lookup> out;
    for (const ShellWord& p : job_points(cfg_, mem_->shell, j)) out.push_back(look_up(cfg_, mem_->map, j, p));
    return out;
  }

  // A FIRST job over a dense block whose first hit is its point `pos`: the window starts pos points before the
  // block's first hit under a random pose (with every_state, every inside point is a hit).
  bool first_at(Job& j, uint32_t pos, bool every_state) {
    const Block& b = blocks_[uni(0, blocks_.size() - 1)];
    if (b.sparse || pos >= uint32_t(cfg_.dense_slot_points())) return false;
    j.mode = Mode::First;
    if (every_state) {  // every inside point a hit: any state, any distance
      j.hit_mask = 0xF;
      j.threshold = cfg_.IW() >= 64 ? INT64_MAX : (int64_t{1} << (cfg_.IW() - 1)) - 1;
    }
    j.sparse &= uint8_t(~kSparseShell);
    j.shell_base = b.base;
    j.shell_count = b.count;
    const std::vector<Lookup> all = lookups(j);
    const auto hit = std::find_if(all.begin(), all.end(), [](const Lookup& l) { return l.hit; });
    const uint32_t h = uint32_t(hit - all.begin());  // the block's first hit
    if (hit == all.end() || h < pos) return false;
    j.shell_base = b.base + h - pos;
    j.shell_count = b.count - (h - pos);
    return true;
  }

  // A distance job's threshold below, at or above the D of its inside points (at: the first inside point's D).
  bool threshold_for(Job& j, const std::string& where) {
    if (!cfg_.distance()) return false;
    const int iw = cfg_.IW();
    const int64_t tmax = iw >= 64 ? INT64_MAX : (int64_t{1} << (iw - 1)) - 1;
    if (where == "below") j.threshold = tmax;   // D <= tmax: every inside point below or at
    if (where == "above") j.threshold = -tmax - 1;
    if (where != "at") return true;
    for (const Lookup& l : lookups(j))
      if (l.loc.inside) {
        j.threshold = l.dist;
        return true;
      }
    return false;
  }

  // A job for stimulus bin `bin`: the first of a few random jobs the bin's template can turn into one that hits it;
  // a random job when none can.
  Job aimed_job(uint32_t index, const std::string& bin) {
    const size_t dot = bin.find('.'), dot2 = bin.find('.', dot + 1);
    const std::string kind = bin.substr(0, dot), what = bin.substr(dot + 1, dot2 - dot - 1);
    const std::string rest = dot2 == std::string::npos ? "" : bin.substr(dot2 + 1);
    const int axis = what == "x" ? 0 : what == "y" ? 1 : what == "z" ? 2 : -1;
    for (int attempt = 0; attempt < 40; ++attempt) {
      Job j = make_job(index);
      const int64_t n = axis == 0 ? j.nx : axis == 1 ? j.ny : j.nz;
      bool ok = false;
      if (kind == "face") {
        const int64_t k = rest == "-1" ? -1 : rest == "0" ? 0 : rest == "n-1" ? n - 1 : n;
        ok = pin_points(j, axis, k, false);
      } else if (kind == "far") {
        const int64_t span = int64_t{1} << cfg_.DW;  // n <= span: index span + 1 reads voxel 1 if truncated
        ok = n > 1 && (pin_points(j, axis, span + 1, false) || pin_points(j, axis, 1 - span, false));
      } else if (kind == "floor") {
        ok = cfg_.TF() >= 1 && pin_points(j, axis, -1, true);  // -1 + one ulp: a negative coordinate's floor
      } else if (kind == "first") {
        ok = first_at(j, uint32_t(std::stoul(rest)), attempt >= 10);
      } else if (kind == "distance") {
        ok = threshold_for(j, what);
      } else if (kind == "job" && what == "points") {
        ok = every_point_hits(j, index);
      } else if (kind == "job" && rest == "top") {
        if (what == "tag") {
          j.tag = uint32_t(cfg_.max_tag() - (index & (cfg_.max_tag() >> 1)));  // in the upper half
          ok = true;
        } else if (what == "map") {
          ok = top_map_ < maps_.size() && j.map_base == maps_[top_map_].base;
        } else {
          ok = top_block_ < blocks_.size() && j.shell_base >= blocks_[top_block_].base;
        }
      } else if (kind == "job") {
        ok = (what == "map" ? j.sparse_map() : j.sparse_shell()) == (rest == "sparse");
      }
      if (ok) return j;
    }
    return make_job(index);
  }

  GenerateOptions opt_;
  DeviceConfig cfg_;
  std::mt19937_64 rng_;
  const DeviceMemory* mem_ = nullptr;
  size_t top_map_ = SIZE_MAX, top_block_ = SIZE_MAX;  // the copies at the top of the memories (aimed), if any
  std::vector<MapDesc> maps_;
  std::vector<Block> blocks_;
};

}  // namespace

bool aimable_bin(const std::string& name) {
  static const char* const kFixed[] = {"distance.below", "distance.at",     "distance.above", "job.map.dense",
                                       "job.map.sparse", "job.shell.dense", "job.shell.sparse", "job.map.top",
                                       "job.shell.top",  "job.tag.top",     "job.points.max"};
  for (const char* f : kFixed)
    if (name == f) return true;
  for (const char* a : {"x", "y", "z"}) {
    const std::string axis = a;
    for (const char* k : {"-1", "0", "n-1", "n"})
      if (name == "face." + axis + "." + k) return true;
    if (name == "far." + axis + ".wraps" || name == "floor." + axis + ".negative") return true;
  }
  const std::string first = "first.position.";
  return name.size() > first.size() && name.compare(0, first.size(), first) == 0 && name.size() <= first.size() + 2 &&
         name.find_first_not_of("0123456789", first.size()) == std::string::npos;
}

GeneratedVectors generate_vectors(const GenerateOptions& opt) {
  for (const std::string& a : opt.aim)
    if (!aimable_bin(a))
      throw std::invalid_argument("no template aims at the stimulus bin '" + a + "' (docs/verification.md)");
  return Generator(opt).run();
}

}  // namespace voxcd
