#include "voxcd/ref/sparse.h"

#include <stdexcept>
#include <string>

#include "voxcd/ref/fixed.h"

namespace voxcd {

namespace {
uint64_t ceil_div(uint64_t a, uint64_t b) { return (a + b - 1) / b; }
using U128 = unsigned __int128;
U128 low_bits(int n) { return n >= 128 ? ~U128(0) : (U128(1) << n) - 1; }
int64_t sign_extend(uint64_t v, int bits) {
  const uint64_t m = bits >= 64 ? ~uint64_t(0) : (uint64_t{1} << bits) - 1;
  v &= m;
  return (bits < 64 && (v >> (bits - 1)) & 1) ? int64_t(v) - int64_t(m) - 1 : int64_t(v);
}
// v wrapped to a PW-bit two's complement value.
int64_t wrap(int64_t v, int bits) { return sign_extend(uint64_t(v), bits); }
}  // namespace

int code_bits(const DeviceConfig& cfg) { return cfg.distance() ? 4 : 2; }

uint64_t table_cells_per_word(const DeviceConfig& cfg) { return uint64_t(cfg.MEMW) / (2 * uint64_t(code_bits(cfg))); }

CoarseDims coarse_dims(const DeviceConfig& cfg, const Job& job) {
  const uint64_t b = brick_edge(cfg);
  return {{ceil_div(job.nx, b), ceil_div(job.ny, b), ceil_div(job.nz, b)}};
}

uint64_t table_words(const DeviceConfig& cfg, const Job& job) {
  return ceil_div(coarse_dims(cfg, job).cells(), table_cells_per_word(cfg));
}

uint64_t level_half_extent(const DeviceConfig& cfg, int level) { return (brick_edge(cfg) << level) / 2 + 1; }

uint64_t level_words(const DeviceConfig& cfg, int level) {
  const uint64_t h = level_half_extent(cfg, level);
  return 8 * ceil_div(h * h * h, uint64_t(cfg.nodes_per_word()));
}

uint64_t unit_words(const DeviceConfig& cfg) {
  if (cfg.distance()) return level_words(cfg, 0);
  const uint64_t b = brick_edge(cfg);
  return 2 * b * b * b / uint64_t(cfg.MEMW);
}

uint64_t level_units(const DeviceConfig& cfg, int level) { return ceil_div(level_words(cfg, level), unit_words(cfg)); }

int code_level(const DeviceConfig& cfg, uint8_t code) {
  if (!cfg.distance()) return code == kCodeBrick ? 0 : -1;
  return code >= kCodeLevel0 && code <= kCodeLevel0 + kMaxLevel ? int(code) - kCodeLevel0 : -1;
}

uint64_t code_units(const DeviceConfig& cfg, uint8_t code) {
  const int l = code_level(cfg, code);
  if (l < 0) return 0;
  // A 2-bit brick is one unit (the contract's table); level_units counts distance nodes, which a 2-bit brick has not.
  return cfg.distance() ? level_units(cfg, l) : 1;
}

uint64_t table_units(const DeviceConfig& cfg, const std::vector<uint8_t>& codes) {
  uint64_t u = 0;
  for (uint8_t c : codes) u += code_units(cfg, c);
  return u;
}

std::vector<uint64_t> table_image(const DeviceConfig& cfg, const std::vector<uint8_t>& codes) {
  const uint64_t cpw = table_cells_per_word(cfg);
  const int cw = code_bits(cfg), half = cfg.MEMW / 2;
  const uint64_t max_code = cfg.distance() ? kCodeLevel0 + kMaxLevel : kCodeBrick;
  std::vector<uint64_t> words(ceil_div(codes.size(), cpw), 0);
  uint64_t units = 0;
  for (uint64_t t = 0; t < codes.size(); ++t) {
    if (codes[t] > max_code)
      throw std::invalid_argument("table_image: cell " + std::to_string(t) + " has code " +
                                  std::to_string(codes[t]) + ", not one of 0.." + std::to_string(max_code));
    uint64_t& w = words[t / cpw];
    if (t % cpw == 0) {
      if (!fits_unsigned(units, half))
        throw std::invalid_argument("table_image: the rank " + std::to_string(units) + " of table word " +
                                    std::to_string(t / cpw) + " does not fit MEMW/2 = " + std::to_string(half) +
                                    " bits");
      w = units << half;
    }
    w |= uint64_t(codes[t]) << (cw * (t % cpw));
    units += code_units(cfg, codes[t]);
  }
  return words;
}

U128 shell_bits(const DeviceConfig& cfg, const ShellWord& w) {
  const U128 m = low_bits(cfg.PW);
  return (U128(uint64_t(w.x)) & m) | (U128(uint64_t(w.y)) & m) << cfg.PW | (U128(uint64_t(w.z)) & m) << (2 * cfg.PW);
}

ShellWord shell_word_of_bits(const DeviceConfig& cfg, U128 bits) {
  const U128 m = low_bits(cfg.PW);
  ShellWord w;
  w.x = sign_extend(uint64_t(bits & m), cfg.PW);
  w.y = sign_extend(uint64_t(bits >> cfg.PW & m), cfg.PW);
  w.z = sign_extend(uint64_t(bits >> (2 * cfg.PW) & m), cfg.PW);
  return w;
}

bool is_origin_word(const DeviceConfig& cfg, const ShellWord& w) { return (shell_bits(cfg, w) >> (3 * cfg.PW - 1)) & 1; }

ShellWord origin_word(const DeviceConfig& cfg, int64_t x, int64_t y, int64_t z) {
  if (!fits_signed(x, cfg.PW) || !fits_signed(y, cfg.PW) || !fits_signed(z, cfg.PW - 1))
    throw std::invalid_argument("origin_word: (" + std::to_string(x) + ", " + std::to_string(y) + ", " +
                                std::to_string(z) + ") does not fit an origin word (x, y: PW = " +
                                std::to_string(cfg.PW) + " bits, z: PW - 1 bits, signed)");
  const U128 m = low_bits(cfg.PW);
  const U128 bits = (U128(uint64_t(x)) & m) | (U128(uint64_t(y)) & m) << cfg.PW |
                    (U128(uint64_t(z)) & low_bits(cfg.PW - 1)) << (2 * cfg.PW) | U128(1) << (3 * cfg.PW - 1);
  return shell_word_of_bits(cfg, bits);
}

ShellWord brick_word(const DeviceConfig& cfg, uint64_t mask, const int step[3]) {
  U128 bits = mask;
  for (int i = 0; i < 3; ++i) {
    if (step[i] < -2 || step[i] > 1)
      throw std::invalid_argument("brick_word: step " + std::to_string(step[i]) + " is outside -2..1");
    bits |= U128(uint64_t(step[i]) & 3) << (64 + 2 * i);
  }
  return shell_word_of_bits(cfg, bits);
}

uint64_t brick_mask(const DeviceConfig& cfg, const ShellWord& w) { return uint64_t(shell_bits(cfg, w)); }

void brick_step(const DeviceConfig& cfg, const ShellWord& w, int step[3]) {
  const U128 bits = shell_bits(cfg, w);
  for (int i = 0; i < 3; ++i) step[i] = int(sign_extend(uint64_t(bits >> (64 + 2 * i)) & 3, 2));
}

std::vector<ShellWord> shell_points(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job,
                                    std::vector<uint32_t>* word_points) {
  std::vector<ShellWord> out;
  if (word_points) word_points->assign(job.shell_count, 0);
  int64_t o[3] = {0, 0, 0};
  const int64_t half = cfg.PF > 0 ? int64_t{1} << (cfg.PF - 1) : 0;
  const int64_t brick = int64_t{kShellBrick} << cfg.PF;
  for (uint32_t k = 0; k < job.shell_count; ++k) {
    const ShellWord& w = shell[job.shell_base + k];
    const U128 bits = shell_bits(cfg, w);
    if ((bits >> (3 * cfg.PW - 1)) & 1) {
      o[0] = sign_extend(uint64_t(bits & low_bits(cfg.PW)), cfg.PW);
      o[1] = sign_extend(uint64_t(bits >> cfg.PW & low_bits(cfg.PW)), cfg.PW);
      o[2] = sign_extend(uint64_t(bits >> (2 * cfg.PW) & low_bits(cfg.PW - 1)), cfg.PW - 1);
      continue;
    }
    int step[3];
    brick_step(cfg, w, step);
    for (int i = 0; i < 3; ++i) o[i] = wrap(o[i] + step[i] * brick, cfg.PW);
    const uint64_t mask = uint64_t(bits);
    for (int b = 0; b < 64; ++b) {
      if (!((mask >> b) & 1)) continue;
      const int64_t d[3] = {b & 3, (b >> 2) & 3, b >> 4};
      ShellWord p;
      p.x = wrap(o[0] + (d[0] << cfg.PF) + half, cfg.PW);
      p.y = wrap(o[1] + (d[1] << cfg.PF) + half, cfg.PW);
      p.z = wrap(o[2] + (d[2] << cfg.PF) + half, cfg.PW);
      out.push_back(p);
    }
    if (word_points) (*word_points)[k] = uint32_t(__builtin_popcountll(mask));
  }
  return out;
}

}  // namespace voxcd
