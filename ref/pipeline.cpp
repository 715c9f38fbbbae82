#include "voxcd/ref/pipeline.h"

#include <sstream>

#include "voxcd/ref/fixed.h"
#include "voxcd/ref/sparse.h"

namespace voxcd {

Transformed transform(const DeviceConfig& /*cfg*/, const Job& job, const ShellWord& p) {
  Transformed r;
  for (int i = 0; i < 3; ++i) {
    Acc a = Acc(job.t[i]);
    for (int j = 0; j < 3; ++j) a += Acc(job.M[i][j]) * Acc(p[j]);
    r.acc[i] = a;
  }
  return r;
}

Located locate(const DeviceConfig& cfg, const Job& job, const Transformed& t) {
  Located l{};
  const uint64_t n[3] = {job.nx, job.ny, job.nz};
  l.inside = true;
  for (int i = 0; i < 3; ++i) {
    // Arithmetic right shift of a signed value is floor division by 2^TF (defined in C++20, and what GCC and
    // Clang do in C++17).
    const Acc idx = t.acc[i] >> cfg.TF();
    l.index[i] = static_cast<int64_t>(idx);
    if (idx < 0 || idx >= Acc(n[i])) l.inside = false;
  }
  if (l.inside && !job.sparse_map()) {
    const uint64_t x = uint64_t(l.index[0]), y = uint64_t(l.index[1]), z = uint64_t(l.index[2]);
    l.linear = x + n[0] * (y + n[1] * z);
    const uint64_t spw = uint64_t(cfg.states_per_word());
    l.word = uint64_t(job.map_base) + l.linear / spw;
    l.slot = uint32_t(l.linear % spw);
  }
  return l;
}

uint8_t fetch_state(const DeviceConfig& /*cfg*/, const std::vector<uint64_t>& map, const Located& l) {
  if (l.word >= map.size()) {
    throw JobError("voxmap read at word " + std::to_string(l.word) + " is outside the loaded map of " +
                   std::to_string(map.size()) + " words");
  }
  return uint8_t((map[l.word] >> (2 * l.slot)) & 3u);
}

bool hit_test(uint8_t hit_mask, bool inside, uint8_t state) { return inside && ((hit_mask >> state) & 1u); }

namespace {
uint64_t half_extent(uint32_t n) { return (uint64_t{n} >> 1) + 1; }
uint64_t ceil_div(uint64_t a, uint64_t b) { return (a + b - 1) / b; }
}  // namespace

NodeAddress node_address(const DeviceConfig& cfg, const Job& job, uint64_t X, uint64_t Y, uint64_t Z) {
  const uint64_t hx = half_extent(job.nx), hy = half_extent(job.ny);
  const uint64_t bank = (X & 1) | (Y & 1) << 1 | (Z & 1) << 2;
  const uint64_t h = (X >> 1) + hx * ((Y >> 1) + hy * (Z >> 1));
  const uint64_t npw = uint64_t(cfg.nodes_per_word());
  return {uint64_t(job.map_base) + 8 * (h / npw) + bank, uint32_t(h % npw)};
}

uint64_t map_words(const DeviceConfig& cfg, const Job& job) {
  if (job.sparse_map()) return table_words(cfg, job);
  if (!cfg.distance()) {
    const uint64_t spw = uint64_t(cfg.states_per_word());
    return ceil_div(job.voxels(), spw);
  }
  const uint64_t halves = half_extent(job.nx) * half_extent(job.ny) * half_extent(job.nz);
  return 8 * ceil_div(halves, uint64_t(cfg.nodes_per_word()));
}

Nodes fetch_nodes(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& job, const Located& l) {
  Nodes n{};
  const uint64_t mask = (uint64_t{1} << cfg.SB) - 1;
  for (int c = 0; c < 8; ++c) {
    const NodeAddress a = node_address(cfg, job, uint64_t(l.index[0]) + (c & 1), uint64_t(l.index[1]) + (c >> 1 & 1),
                                       uint64_t(l.index[2]) + (c >> 2 & 1));
    if (a.word >= map.size()) {
      throw JobError("voxmap read at word " + std::to_string(a.word) + " is outside the loaded map of " +
                     std::to_string(map.size()) + " words");
    }
    const uint64_t raw = (map[a.word] >> (uint64_t(cfg.SB) * a.slot)) & mask;
    // Two's complement: the top bit of the SB-bit field is the sign.
    n.q[c] = (raw >> (cfg.SB - 1)) ? int64_t(raw) - int64_t(mask) - 1 : int64_t(raw);
  }
  return n;
}

Fractions fractions(const DeviceConfig& cfg, const Transformed& t) {
  Fractions f{};
  const Acc one = Acc(1) << cfg.WB;
  for (int i = 0; i < 3; ++i) f.f[i] = int64_t((t.acc[i] >> (cfg.TF() - cfg.WB)) & (one - 1));
  return f;
}

int64_t interpolate(const DeviceConfig& cfg, const Nodes& n, const Fractions& f) {
  const Acc one = Acc(1) << cfg.WB;
  Acc d = 0;
  for (int c = 0; c < 8; ++c) {
    Acc w = 1;
    for (int i = 0; i < 3; ++i) w *= ((c >> i) & 1) ? Acc(f.f[i]) : one - Acc(f.f[i]);
    d += Acc(n.q[c]) * w;
  }
  return int64_t(d);  // |d| <= 2^(SB-1) * 2^(3*WB) <= 2^63: fits IW <= 64 bits
}

bool distance_hit(int64_t threshold, bool inside, int64_t dist) { return inside && dist <= threshold; }

namespace {

uint64_t read_word(const std::vector<uint64_t>& map, uint64_t w) {
  if (w >= map.size())
    throw JobError("voxmap read at word " + std::to_string(w) + " is outside the loaded map of " +
                   std::to_string(map.size()) + " words");
  return map[w];
}

int64_t signed_field(uint64_t raw, int bits) {
  const uint64_t mask = (uint64_t{1} << bits) - 1;
  raw &= mask;
  return (raw >> (bits - 1)) ? int64_t(raw) - int64_t(mask) - 1 : int64_t(raw);
}

}  // namespace

TableRef table_ref(const DeviceConfig& cfg, const Job& job, const Located& l) {
  const CoarseDims c = coarse_dims(cfg, job);
  const uint64_t cx = uint64_t(l.index[0]) >> cfg.BL, cy = uint64_t(l.index[1]) >> cfg.BL,
                 cz = uint64_t(l.index[2]) >> cfg.BL;
  const uint64_t t = cx + c.c[0] * (cy + c.c[1] * cz), cpw = table_cells_per_word(cfg);
  return {uint64_t(job.map_base) + t / cpw, uint32_t(t % cpw)};
}

Cell read_cell(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& job, const TableRef& r) {
  const uint64_t w = read_word(map, r.word);
  const int cw = code_bits(cfg), half = cfg.MEMW / 2;
  const uint64_t code_mask = (uint64_t{1} << cw) - 1;
  uint64_t u = half >= 64 ? 0 : w >> half;  // the rank (MEMW <= 64: half <= 32)
  for (uint32_t j = 0; j < r.slot; ++j) u += code_units(cfg, uint8_t((w >> (cw * j)) & code_mask));
  Cell c{uint8_t((w >> (cw * r.slot)) & code_mask), -1, 0};
  c.level = code_level(cfg, c.code);
  if (c.level < 0) {
    if (cfg.distance() && c.code != kCodeDeep) c.code = kCodeFar;  // codes past the levels read as code 0
    return c;
  }
  if (u + code_units(cfg, c.code) > job.brick_units) return Cell{0, -1, 0};  // past the job's bricks: code 0
  c.first = uint64_t(job.brick_base) + u * unit_words(cfg);
  return c;
}

BrickRef brick_ref(const DeviceConfig& cfg, const Cell& c, const Located& l) {
  const uint64_t m = brick_edge(cfg) - 1;
  const uint64_t i = (uint64_t(l.index[0]) & m) | (uint64_t(l.index[1]) & m) << cfg.BL |
                     (uint64_t(l.index[2]) & m) << (2 * cfg.BL);
  const uint64_t spw = uint64_t(cfg.states_per_word());
  return {c.first + i / spw, uint32_t(i % spw)};
}

uint8_t sparse_state(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Cell& c, const Located& l) {
  if (c.level < 0) return c.code;
  const BrickRef b = brick_ref(cfg, c, l);
  return uint8_t((read_word(map, b.word) >> (2 * b.slot)) & 3u);
}

SubCell sub_cell(const DeviceConfig& cfg, const Cell& c, const Located& l, const Transformed& t) {
  SubCell s{};
  const int level = c.level < 0 ? 0 : c.level;
  const int tf = cfg.TF();
  const Acc frac_mask = (Acc(1) << tf) - 1, weight_mask = (Acc(1) << cfg.WB) - 1;
  const uint64_t m = brick_edge(cfg) - 1;
  for (int i = 0; i < 3; ++i) {
    // The point's position in its cell, TF fraction bits: its voxel within the cell, then the fraction.
    const Acc a = (Acc(uint64_t(l.index[i]) & m) << tf) | (t.acc[i] & frac_mask);
    s.X[i] = uint64_t(a >> (tf - level));
    s.f.f[i] = int64_t((a >> (tf - level - cfg.WB)) & weight_mask);
  }
  return s;
}

NodeAddress brick_node_address(const DeviceConfig& cfg, const Cell& c, uint64_t X, uint64_t Y, uint64_t Z) {
  const uint64_t h_ext = level_half_extent(cfg, c.level);
  const uint64_t bank = (X & 1) | (Y & 1) << 1 | (Z & 1) << 2;
  const uint64_t h = (X >> 1) + h_ext * ((Y >> 1) + h_ext * (Z >> 1));
  const uint64_t npw = uint64_t(cfg.nodes_per_word());
  return {c.first + 8 * (h / npw) + bank, uint32_t(h % npw)};
}

Nodes brick_nodes(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Cell& c, const SubCell& s) {
  Nodes n{};
  if (c.level < 0) {
    const int64_t q = c.code == kCodeDeep ? -(int64_t{1} << (cfg.SB - 1)) : (int64_t{1} << (cfg.SB - 1)) - 1;
    for (int64_t& v : n.q) v = q;
    return n;
  }
  for (int k = 0; k < 8; ++k) {
    const NodeAddress a = brick_node_address(cfg, c, s.X[0] + (k & 1), s.X[1] + (k >> 1 & 1), s.X[2] + (k >> 2 & 1));
    n.q[k] = signed_field(read_word(map, a.word) >> (uint64_t(cfg.SB) * a.slot), cfg.SB);
  }
  return n;
}

Lookup look_up(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& job, const ShellWord& p) {
  Lookup r;
  const Transformed tr = transform(cfg, job, p);
  r.loc = locate(cfg, job, tr);
  if (cfg.distance()) {
    if (r.loc.inside) {
      if (job.sparse_map()) {
        const Cell c = read_cell(cfg, map, job, table_ref(cfg, job, r.loc));
        const SubCell s = sub_cell(cfg, c, r.loc, tr);
        r.dist = interpolate(cfg, brick_nodes(cfg, map, c, s), s.f);
      } else {
        r.dist = interpolate(cfg, fetch_nodes(cfg, map, job, r.loc), fractions(cfg, tr));
      }
    }
    r.hit = distance_hit(job.threshold, r.loc.inside, r.dist);
  } else {
    if (r.loc.inside)
      r.state = job.sparse_map() ? sparse_state(cfg, map, read_cell(cfg, map, job, table_ref(cfg, job, r.loc)), r.loc)
                                 : fetch_state(cfg, map, r.loc);
    r.hit = hit_test(job.hit_mask, r.loc.inside, r.state);
  }
  return r;
}

std::vector<ShellWord> job_points(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job) {
  if (job.sparse_shell()) return shell_points(cfg, shell, job);
  return std::vector<ShellWord>(shell.begin() + job.shell_base, shell.begin() + job.shell_base + job.shell_count);
}

namespace {

[[noreturn]] void job_fail(const Job& job, const std::string& what) {
  throw JobError("job tag " + std::to_string(job.tag) + ": " + what);
}

std::string dims_name(int i) { return i == 0 ? "nx" : i == 1 ? "ny" : "nz"; }

// The end of a sparse map's brick words, or 0 for a dense map.
uint64_t bricks_end(const DeviceConfig& cfg, const Job& job) {
  return job.sparse_map() ? uint64_t(job.brick_base) + brick_words(cfg, job) : 0;
}

// The rules of a sparse map or shell, and of a dense map's brick fields (validate_job's, with messages).
void validate_sparse(const DeviceConfig& cfg, const Job& job, uint64_t loaded_map_words) {
  if (job.sparse > (kSparseMap | kSparseShell))
    job_fail(job, "sparse = " + std::to_string(job.sparse) + " has bits other than 1 (map) and 2 (shell)");
  if (job.sparse && !cfg.sparse())
    job_fail(job, std::string("a sparse ") + (job.sparse_map() ? "map" : "shell") +
                      " on a device without sparse maps and shells (BL = 0)");
  if (!job.sparse_map()) {
    if (job.brick_base != 0 || job.brick_units != 0)
      job_fail(job, "brick_base " + std::to_string(job.brick_base) + " and brick_units " +
                        std::to_string(job.brick_units) + " of a dense map: both must be 0");
    return;
  }
  if (!fits_unsigned(job.brick_base, cfg.MAW))
    job_fail(job, "brick_base " + std::to_string(job.brick_base) + " does not fit MAW = " + std::to_string(cfg.MAW));
  if (cfg.distance() && job.brick_base % 8 != 0)
    job_fail(job, "brick_base " + std::to_string(job.brick_base) +
                      " of a sparse distance map is not on a bank boundary (a multiple of 8)");
  if (bricks_end(cfg, job) > loaded_map_words)
    job_fail(job, "brick words [" + std::to_string(job.brick_base) + ", " + std::to_string(bricks_end(cfg, job)) +
                      ") of " + std::to_string(job.brick_units) + " units go past the " +
                      std::to_string(loaded_map_words) + " loaded voxmap words");
}

}  // namespace

void validate_job(const DeviceConfig& cfg, const Job& job, uint64_t shell_words, uint64_t loaded_map_words) {
  if (!fits_unsigned(job.tag, cfg.TAGW))
    job_fail(job, "tag does not fit TAGW = " + std::to_string(cfg.TAGW) + " bits");
  if (job.mode != Mode::All && job.mode != Mode::First && job.mode != Mode::Count)
    job_fail(job, "mode " + std::to_string(unsigned(job.mode)) + " is not ALL, FIRST or COUNT");
  if (job.hit_mask > 15) job_fail(job, "hit mask " + std::to_string(job.hit_mask) + " is outside 0..15");
  if (!fits_unsigned(job.shell_base, cfg.SAW))
    job_fail(job, "shell_base " + std::to_string(job.shell_base) + " does not fit SAW = " + std::to_string(cfg.SAW));
  if (uint64_t(job.shell_count) > cfg.shell_depth())
    job_fail(job, "shell_count " + std::to_string(job.shell_count) + " exceeds the shell memory depth 2^SAW = " +
                      std::to_string(cfg.shell_depth()));
  const uint64_t shell_end = uint64_t(job.shell_base) + job.shell_count;
  if (shell_end > shell_words)
    job_fail(job, "shell words [" + std::to_string(job.shell_base) + ", " + std::to_string(shell_end) +
                      ") go past the " + std::to_string(shell_words) + " loaded shell words");
  if (!fits_unsigned(job.map_base, cfg.MAW))
    job_fail(job, "map_base " + std::to_string(job.map_base) + " does not fit MAW = " + std::to_string(cfg.MAW));
  const uint64_t n[3] = {job.nx, job.ny, job.nz};
  for (int i = 0; i < 3; ++i) {
    if (n[i] < 1 || n[i] > cfg.max_dim())
      job_fail(job, dims_name(i) + " = " + std::to_string(n[i]) + " is outside 1..2^DW = " +
                        std::to_string(cfg.max_dim()));
  }
  if (cfg.distance() && job.map_base % 8 != 0)
    job_fail(job, "map_base " + std::to_string(job.map_base) +
                      " of a distance voxmap is not on a bank boundary (a multiple of 8)");
  validate_sparse(cfg, job, loaded_map_words);
  const uint64_t map_end = uint64_t(job.map_base) + map_words(cfg, job);
  if (map_end > loaded_map_words)
    job_fail(job, "voxmap words [" + std::to_string(job.map_base) + ", " + std::to_string(map_end) +
                      ") for a " + std::to_string(job.nx) + "x" + std::to_string(job.ny) + "x" +
                      std::to_string(job.nz) + (cfg.distance() ? " distance" : "") +
                      (job.sparse_map() ? " sparse map's table" : " map") + " go past the " +
                      std::to_string(loaded_map_words) + " loaded voxmap words");
  if (cfg.distance()) {
    if (!fits_signed(job.threshold, cfg.IW()))
      job_fail(job, "threshold " + std::to_string(job.threshold) + " does not fit IW = SB + 3*WB = " +
                        std::to_string(cfg.IW()) + " bits (signed)");
  } else if (job.threshold != 0) {
    job_fail(job, "threshold " + std::to_string(job.threshold) + " on a 2-bit voxmap (SB = 2): it must be 0");
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (!fits_signed(job.M[i][j], cfg.MW))
        job_fail(job, "M" + std::to_string(i) + std::to_string(j) + " = " + std::to_string(job.M[i][j]) +
                          " does not fit MW = " + std::to_string(cfg.MW) + " bits");
    }
    if (!fits_signed(job.t[i], cfg.TW))
      job_fail(job, "T" + std::to_string(i) + " = " + std::to_string(job.t[i]) + " does not fit TW = " +
                        std::to_string(cfg.TW) + " bits");
  }
}

uint32_t job_faults(const DeviceConfig& cfg, const Job& job, uint64_t shell_words, uint64_t loaded_map_words) {
  uint32_t f = 0;
  if ((job.mode != Mode::All && job.mode != Mode::First && job.mode != Mode::Count) || job.hit_mask > 15)
    f |= kFaultMode;
  if (!fits_unsigned(job.tag, cfg.TAGW)) f |= kFaultTag;
  if (!fits_unsigned(job.shell_base, cfg.SAW) || uint64_t(job.shell_count) > cfg.shell_depth() ||
      uint64_t(job.shell_base) + job.shell_count > shell_words || (job.sparse_shell() && !cfg.sparse()))
    f |= kFaultShell;
  const uint64_t n[3] = {job.nx, job.ny, job.nz};
  bool dims_ok = true;
  for (uint64_t v : n) dims_ok = dims_ok && v >= 1 && v <= cfg.max_dim();
  if (!dims_ok) f |= kFaultDims;
  if (!fits_unsigned(job.map_base, cfg.MAW) || (cfg.distance() && job.map_base % 8 != 0) ||
      (dims_ok && uint64_t(job.map_base) + map_words(cfg, job) > loaded_map_words))
    f |= kFaultMap;
  if (job.sparse_map()
          ? !cfg.sparse() || !fits_unsigned(job.brick_base, cfg.MAW) || (cfg.distance() && job.brick_base % 8 != 0) ||
                bricks_end(cfg, job) > loaded_map_words
          : job.brick_base != 0 || job.brick_units != 0)
    f |= kFaultMap;
  if (job.sparse > (kSparseMap | kSparseShell)) f |= kFaultMode;  // a flag the job cannot have
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      if (!fits_signed(job.M[i][j], cfg.MW)) f |= kFaultPose;
    if (!fits_signed(job.t[i], cfg.TW)) f |= kFaultPose;
  }
  if (cfg.distance() ? !fits_signed(job.threshold, cfg.IW()) : job.threshold != 0) f |= kFaultThreshold;
  return f;
}

void validate_memory(const DeviceConfig& cfg, const DeviceMemory& mem) {
  if (mem.shell.size() > cfg.shell_depth())
    throw JobError(std::to_string(mem.shell.size()) + " shell words do not fit the shell memory of 2^SAW = " +
                   std::to_string(cfg.shell_depth()) + " words");
  if (mem.map.size() > cfg.map_depth())
    throw JobError(std::to_string(mem.map.size()) + " voxmap words do not fit the voxmap memory of 2^MAW = " +
                   std::to_string(cfg.map_depth()) + " words");
  for (size_t k = 0; k < mem.shell.size(); ++k) {
    const ShellWord& p = mem.shell[k];
    for (int i = 0; i < 3; ++i) {
      if (!fits_signed(p[i], cfg.PW))
        throw JobError("shell word " + std::to_string(k) + " coordinate " + std::to_string(i) + " = " +
                       std::to_string(p[i]) + " does not fit PW = " + std::to_string(cfg.PW) + " bits");
    }
  }
  for (size_t k = 0; k < mem.map.size(); ++k) {
    if (!fits_unsigned(mem.map[k], cfg.MEMW))
      throw JobError("voxmap word " + std::to_string(k) + " has bits above MEMW = " + std::to_string(cfg.MEMW));
  }
}

void run_job(const DeviceConfig& cfg, const DeviceMemory& mem, const Job& job, std::vector<Record>& out) {
  uint32_t hits = 0;
  const std::vector<ShellWord> points = job_points(cfg, mem.shell, job);
  for (uint32_t k = 0; k < points.size(); ++k) {
    const Lookup r = look_up(cfg, mem.map, job, points[k]);
    if (!r.hit) continue;
    ++hits;
    if (job.mode != Mode::Count) {
      out.push_back(Record::hit(job.tag, k, uint32_t(r.loc.index[0]), uint32_t(r.loc.index[1]),
                                uint32_t(r.loc.index[2]), r.state, r.dist));
    }
    if (job.mode == Mode::First) break;
  }
  out.push_back(Record::done(job.tag, hits));
}

std::vector<Record> run_stream(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs) {
  cfg.validate();
  validate_memory(cfg, mem);
  for (const Job& j : jobs) validate_job(cfg, j, mem.shell.size(), mem.map.size());
  std::vector<Record> out;
  for (const Job& j : jobs) run_job(cfg, mem, j, out);
  return out;
}

}  // namespace voxcd
