#include "tests/ref/directed_cases.h"

#include <functional>

namespace voxcd::testing {

namespace {

constexpr int64_t kOne = int64_t{1} << 16;      // +1.0 in the default matrix format (MF = 16)
constexpr int64_t kP = int64_t{1} << 8;         // one voxel in the default point format (PF = 8)
constexpr int64_t kT = int64_t{1} << 24;        // one voxel in the default translation format (TF = 24)

// A map of nx*ny*nz voxels at word `base` of a memory of `words` words filled with `garbage` elsewhere, whose
// voxel (x, y, z) has state f(x, y, z). Default MEMW = 64: 32 states per word.
void put_map(DeviceMemory& mem, uint32_t base, uint32_t nx, uint32_t ny, uint32_t nz,
             const std::function<uint8_t(uint32_t, uint32_t, uint32_t)>& f, uint64_t garbage = 0) {
  const uint64_t n = uint64_t(nx) * ny * nz;
  const uint64_t end = base + (n + 31) / 32;
  if (mem.map.size() < end) mem.map.resize(end, garbage);
  for (uint64_t w = base; w < end; ++w) mem.map[w] = 0;
  for (uint32_t z = 0; z < nz; ++z)
    for (uint32_t y = 0; y < ny; ++y)
      for (uint32_t x = 0; x < nx; ++x) {
        const uint64_t i = x + uint64_t(nx) * (y + uint64_t(ny) * z);
        mem.map[base + i / 32] |= uint64_t(f(x, y, z) & 3) << (2 * (i % 32));
      }
}

Job job(uint32_t tag, Mode mode, uint32_t shell_base, uint32_t shell_count, uint32_t map_base, uint32_t nx,
        uint32_t ny, uint32_t nz) {
  Job j;
  j.tag = tag;
  j.mode = mode;
  j.shell_base = shell_base;
  j.shell_count = shell_count;
  j.map_base = map_base;
  j.nx = nx;
  j.ny = ny;
  j.nz = nz;
  j.M[0][0] = j.M[1][1] = j.M[2][2] = kOne;
  return j;
}

ShellWord pt(double x, double y, double z) {
  return ShellWord{int64_t(x * kP), int64_t(y * kP), int64_t(z * kP)};
}

Record H(uint32_t tag, uint32_t point, uint32_t x, uint32_t y, uint32_t z, uint8_t s) {
  return Record::hit(tag, point, x, y, z, s);
}
Record D(uint32_t tag, uint32_t hits) { return Record::done(tag, hits); }

std::vector<DirectedCase> build() {
  std::vector<DirectedCase> cs;
  auto add = [&](std::string name) -> DirectedCase& {
    cs.push_back(DirectedCase{});
    cs.back().name = std::move(name);
    return cs.back();
  };
  const auto all_surface = [](uint32_t, uint32_t, uint32_t) -> uint8_t { return kSurface; };

  {  // A point exactly on a voxel face belongs to the voxel above it; one ulp below, to the one below.
    DirectedCase& c = add("01_point_on_voxel_face");
    put_map(c.memory, 0, 8, 8, 8, all_surface);
    c.memory.shell = {pt(3, 2, 1), ShellWord{3 * kP - 1, 2 * kP, 1 * kP}, pt(0, 0, 0), pt(7.5, 7.5, 7.5),
                      pt(8, 0, 0)};
    c.jobs = {job(1, Mode::All, 0, 5, 0, 8, 8, 8)};
    c.expected = {H(1, 0, 3, 2, 1, 1), H(1, 1, 2, 2, 1, 1), H(1, 2, 0, 0, 0, 1), H(1, 3, 7, 7, 7, 1), D(1, 4)};
  }
  {  // -1/4 of a voxel floors to voxel -1 (a miss) even though voxel 0 is filled; +1/4 is voxel 0.
    DirectedCase& c = add("02_minus_quarter_is_voxel_minus_one");
    put_map(c.memory, 0, 4, 4, 4, all_surface);
    c.memory.shell = {pt(-0.25, 0, 0), pt(0, -0.25, 0), pt(0, 0, -0.25), pt(0.25, 0.25, 0.25),
                      ShellWord{-1, 0, 0}};
    Job a = job(2, Mode::All, 0, 5, 0, 4, 4, 4);
    Job b = job(3, Mode::All, 0, 1, 0, 4, 4, 4);  // the translation alone puts the point at -1/4
    b.t[0] = -kT / 4;
    c.memory.shell.push_back(pt(0, 0, 0));
    b.shell_base = 5;
    c.jobs = {a, b};
    c.expected = {H(2, 3, 0, 0, 0, 1), D(2, 1), D(3, 0)};
  }
  {  // Matrix entries of exactly +1.0 and -1.0: x' = -x + 5, y' = z, z' = y.
    DirectedCase& c = add("03_matrix_entries_plus_minus_one");
    put_map(c.memory, 0, 8, 8, 8, [](uint32_t x, uint32_t y, uint32_t z) -> uint8_t {
      return x == 4 && y == 3 && z == 2 ? kInterior : kEmpty;
    });
    c.memory.shell = {pt(0.5, 2.5, 3.5), pt(1.5, 2.5, 3.5)};
    Job j = job(4, Mode::All, 0, 2, 0, 8, 8, 8);
    j.M[0][0] = -kOne; j.M[0][1] = 0;    j.M[0][2] = 0;
    j.M[1][0] = 0;     j.M[1][1] = 0;    j.M[1][2] = kOne;
    j.M[2][0] = 0;     j.M[2][1] = kOne; j.M[2][2] = 0;
    j.t[0] = 5 * kT;
    c.jobs = {j};
    // p0 -> (4.5, 3.5, 2.5): voxel (4, 3, 2). p1 -> (3.5, 3.5, 2.5): voxel (3, 3, 2), empty.
    c.expected = {H(4, 0, 4, 3, 2, 2), D(4, 1)};
  }
  {  // Quarter and half turns about each axis: p' = R p + (4, 4, 4) for p = (1.5, 0.5, 0.5), worked out by hand.
    DirectedCase& c = add("04_quarter_and_half_turns");
    put_map(c.memory, 0, 9, 9, 9, all_surface);
    c.memory.shell = {pt(1.5, 0.5, 0.5)};
    struct Turn {
      int R[3][3];
      uint32_t v[3];
    };
    const Turn turns[] = {
        {{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {5, 3, 4}},   // x 90:  (1.5, -0.5, 0.5) + 4
        {{{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}, {5, 3, 3}},  // x 180: (1.5, -0.5, -0.5) + 4
        {{{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}}, {4, 4, 2}},   // y 90:  (0.5, 0.5, -1.5) + 4
        {{{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}}, {2, 4, 3}},  // y 180: (-1.5, 0.5, -0.5) + 4
        {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}, {3, 5, 4}},   // z 90:  (-0.5, 1.5, 0.5) + 4
        {{{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}}, {2, 3, 4}},  // z 180: (-1.5, -0.5, 0.5) + 4
    };
    uint32_t tag = 10;
    for (const Turn& tr : turns) {
      Job j = job(tag, Mode::All, 0, 1, 0, 9, 9, 9);
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) j.M[i][k] = tr.R[i][k] * kOne;
      for (int i = 0; i < 3; ++i) j.t[i] = 4 * kT;
      c.jobs.push_back(j);
      c.expected.push_back(H(tag, 0, tr.v[0], tr.v[1], tr.v[2], kSurface));
      c.expected.push_back(D(tag, 1));
      ++tag;
    }
  }
  {  // A translation far outside the grid, in both directions, at the ends of the translation format.
    DirectedCase& c = add("05_translation_far_outside");
    put_map(c.memory, 0, 4, 4, 4, all_surface);
    c.memory.shell = {pt(0.5, 0.5, 0.5)};
    Job a = job(20, Mode::All, 0, 1, 0, 4, 4, 4);
    a.t[0] = (int64_t{1} << 47) - 1;  // largest TW = 48 value: about +8.4 million voxels
    Job b = job(21, Mode::All, 0, 1, 0, 4, 4, 4);
    b.t[1] = -(int64_t{1} << 47);
    Job d = job(22, Mode::All, 0, 1, 0, 4, 4, 4);
    d.t[2] = 1000 * kT;
    c.jobs = {a, b, d};
    c.expected = {D(20, 0), D(21, 0), D(22, 0)};
  }
  {  // Indices that would alias into the grid if truncated to DW = 10 bits: 1024 + 3 and -1024 + 3 and 2048.
    DirectedCase& c = add("06_index_that_would_alias_if_truncated");
    put_map(c.memory, 0, 16, 16, 16, all_surface);
    c.memory.shell = {pt(3.5, 3.5, 3.5)};
    int64_t offs[] = {1024, -1024, 2048, 4096 * 1024};
    uint32_t tag = 30;
    for (int64_t o : offs) {
      for (int axis = 0; axis < 3; ++axis) {
        Job j = job(tag, Mode::All, 0, 1, 0, 16, 16, 16);
        j.t[axis] = o * kT;
        c.jobs.push_back(j);
        c.expected.push_back(D(tag, 0));
        ++tag;
      }
    }
    Job ok = job(tag, Mode::All, 0, 1, 0, 16, 16, 16);  // the untranslated point does hit
    c.jobs.push_back(ok);
    c.expected.push_back(H(tag, 0, 3, 3, 3, 1));
    c.expected.push_back(D(tag, 1));
  }
  {  // Every field at the ends of its range: the accumulator must not overflow, the far point must miss.
    DirectedCase& c = add("07_full_range_fields");
    put_map(c.memory, 0, 1024, 2, 1, all_surface);
    const int64_t pmin = -(int64_t{1} << 23), pmax = (int64_t{1} << 23) - 1;
    c.memory.shell = {ShellWord{pmin, pmin, pmin}, ShellWord{pmax, pmax, pmax}, ShellWord{pmax, pmin, 0}};
    Job a = job(40, Mode::All, 0, 3, 0, 1024, 2, 1);
    for (auto& row : a.M)
      for (auto& e : row) e = -(int64_t{1} << 17);  // -2.0
    for (auto& e : a.t) e = (int64_t{1} << 47) - 1;
    Job b = a;
    b.tag = 41;
    for (auto& row : b.M)
      for (auto& e : row) e = (int64_t{1} << 17) - 1;  // 2 - 2^-16
    for (auto& e : b.t) e = -(int64_t{1} << 47);
    // The one that lands inside: M00 = -2.0 (the format's minimum) on x = -32768 voxels (the point format's
    // minimum) gives +65536 voxels; t0 = -65530.5 voxels brings it to 5.5: voxel 5.
    c.memory.shell.push_back(ShellWord{pmin, kP / 2, kP / 2});
    Job d = job(42, Mode::All, 3, 1, 0, 1024, 2, 1);
    d.M[0][0] = -(int64_t{1} << 17);
    d.t[0] = -65530 * kT - kT / 2;
    c.jobs = {a, b, d};
    c.expected = {D(40, 0), D(41, 0), H(42, 0, 5, 0, 0, 1), D(42, 1)};
  }
  {  // A 1x1x1 map: only points in [0, 1)^3 hit.
    DirectedCase& c = add("08_single_voxel_map");
    put_map(c.memory, 0, 1, 1, 1, [](uint32_t, uint32_t, uint32_t) -> uint8_t { return kInterior; });
    c.memory.shell = {pt(0.5, 0.5, 0.5), pt(1, 0, 0), pt(0, 0, 0), ShellWord{kP - 1, kP - 1, kP - 1},
                      pt(0, 1, 0), pt(0, 0, 1), ShellWord{0, 0, -1}};
    c.jobs = {job(50, Mode::All, 0, 7, 0, 1, 1, 1)};
    c.expected = {H(50, 0, 0, 0, 0, 2), H(50, 2, 0, 0, 0, 2), H(50, 3, 0, 0, 0, 2), D(50, 3)};
  }
  {  // Odd dimensions 37x5x3: linear index x + 37*(y + 5*z) across word boundaries, each voxel's state
     // (x + 2y + 3z) % 4, looked up at the corners and at linear indices 31, 32, 63, 64 and 554 (the last).
    DirectedCase& c = add("09_odd_dimensions_37x5x3");
    auto st = [](uint32_t x, uint32_t y, uint32_t z) -> uint8_t { return uint8_t((x + 2 * y + 3 * z) % 4); };
    put_map(c.memory, 0, 37, 5, 3, st);
    const uint32_t probes[][3] = {{0, 0, 0}, {36, 0, 0}, {0, 4, 0}, {0, 0, 2}, {36, 4, 2},
                                  {31, 0, 0}, {32, 0, 0}, {26, 1, 0}, {27, 1, 0}, {36, 3, 2}};
    for (const auto& p : probes) c.memory.shell.push_back(pt(p[0] + 0.5, p[1] + 0.5, p[2] + 0.5));
    Job j = job(60, Mode::All, 0, uint32_t(c.memory.shell.size()), 0, 37, 5, 3);
    j.hit_mask = 0xF;  // every state, so every probe reports the state it read
    c.jobs = {j};
    uint32_t k = 0;
    for (const auto& p : probes) c.expected.push_back(H(60, k++, p[0], p[1], p[2], st(p[0], p[1], p[2])));
    c.expected.push_back(D(60, k));
  }
  {  // A map that starts mid-memory, between words of garbage: only its own words are read.
    DirectedCase& c = add("10_map_mid_memory");
    c.memory.map.assign(7, ~uint64_t{0});  // garbage: every state 3
    put_map(c.memory, 7, 5, 5, 5, [](uint32_t x, uint32_t y, uint32_t z) -> uint8_t {
      return x == 4 && y == 4 && z == 4 ? kSurface : kEmpty;
    });
    c.memory.map.push_back(~uint64_t{0});  // and after
    c.memory.shell = {pt(0.5, 0.5, 0.5), pt(4.5, 4.5, 4.5), pt(2.5, 2.5, 2.5)};
    Job j = job(70, Mode::All, 0, 3, 7, 5, 5, 5);
    j.hit_mask = 0xE;  // surface, interior and reserved: garbage would show as state 3
    c.jobs = {j};
    c.expected = {H(70, 1, 4, 4, 4, 1), D(70, 1)};
  }
  {  // An empty shell completes with zero hits in every mode.
    DirectedCase& c = add("11_empty_shell");
    put_map(c.memory, 0, 2, 2, 2, all_surface);
    c.memory.shell = {pt(0.5, 0.5, 0.5)};
    c.jobs = {job(80, Mode::All, 0, 0, 0, 2, 2, 2), job(81, Mode::First, 1, 0, 0, 2, 2, 2),
              job(82, Mode::Count, 0, 0, 0, 2, 2, 2)};
    c.expected = {D(80, 0), D(81, 0), D(82, 0)};
  }
  {  // ALL, FIRST and COUNT on the same ten points, three of which (2, 5, 7) hit.
    DirectedCase& c = add("12_every_mode");
    put_map(c.memory, 0, 10, 1, 1, [](uint32_t x, uint32_t, uint32_t) -> uint8_t {
      return x == 2 || x == 5 ? kSurface : x == 7 ? kInterior : kEmpty;
    });
    for (int k = 0; k < 10; ++k) c.memory.shell.push_back(pt(k + 0.5, 0.5, 0.5));
    c.jobs = {job(90, Mode::All, 0, 10, 0, 10, 1, 1), job(91, Mode::First, 0, 10, 0, 10, 1, 1),
              job(92, Mode::Count, 0, 10, 0, 10, 1, 1), job(93, Mode::First, 3, 7, 0, 10, 1, 1),
              job(94, Mode::First, 8, 2, 0, 10, 1, 1)};
    c.expected = {H(90, 2, 2, 0, 0, 1), H(90, 5, 5, 0, 0, 1), H(90, 7, 7, 0, 0, 2), D(90, 3),
                  H(91, 2, 2, 0, 0, 1), D(91, 1),
                  D(92, 3),
                  H(93, 2, 5, 0, 0, 1), D(93, 1),  // point index is relative to shell_base
                  D(94, 0)};
  }
  {  // Every hit mask 0..15 over voxels of states 0, 1, 2 and 3: bit s of the mask makes state s a hit.
    DirectedCase& c = add("13_every_hit_mask");
    put_map(c.memory, 0, 4, 1, 1, [](uint32_t x, uint32_t, uint32_t) -> uint8_t { return uint8_t(x); });
    for (int k = 0; k < 4; ++k) c.memory.shell.push_back(pt(k + 0.5, 0.5, 0.5));
    for (uint32_t mask = 0; mask < 16; ++mask) {
      Job j = job(100 + mask, Mode::All, 0, 4, 0, 4, 1, 1);
      j.hit_mask = uint8_t(mask);
      c.jobs.push_back(j);
      uint32_t n = 0;
      for (uint32_t s = 0; s < 4; ++s)
        if (mask & (1u << s)) {
          c.expected.push_back(H(100 + mask, s, s, 0, 0, uint8_t(s)));
          ++n;
        }
      c.expected.push_back(D(100 + mask, n));
    }
  }
  {  // Jobs back to back on different maps and shells, tags repeated: the stream keeps submission order.
    DirectedCase& c = add("14_back_to_back_jobs");
    put_map(c.memory, 0, 3, 3, 3, all_surface);
    put_map(c.memory, 1, 2, 2, 2, [](uint32_t, uint32_t, uint32_t) -> uint8_t { return kInterior; });
    for (int k = 0; k < 9; ++k) c.memory.shell.push_back(pt(k % 3 + 0.5, k / 3 + 0.5, 0.5));
    c.jobs = {job(7, Mode::All, 0, 9, 0, 3, 3, 3), job(7, Mode::Count, 0, 9, 1, 2, 2, 2),
              job(8, Mode::First, 4, 5, 1, 2, 2, 2), job(7, Mode::All, 8, 1, 1, 2, 2, 2)};
    for (uint32_t k = 0; k < 9; ++k) c.expected.push_back(H(7, k, k % 3, k / 3, 0, 1));
    c.expected.push_back(D(7, 9));
    c.expected.push_back(D(7, 4));                      // points 0, 1, 3, 4 fall in the 2x2x2 map
    c.expected.push_back(H(8, 0, 1, 1, 0, 2));          // shell word 4 = (1.5, 1.5): first of 4..8 inside
    c.expected.push_back(D(8, 1));
    c.expected.push_back(D(7, 0));                      // shell word 8 = (2.5, 2.5) is outside the 2x2x2 map
  }
  {  // Lane-sized and odd shells: 1, 3, 4, 5, 8, 9, 17 points, all hits, so every lane position is checked.
    DirectedCase& c = add("15_shell_sizes_around_lanes");
    put_map(c.memory, 0, 32, 1, 1, all_surface);
    for (int k = 0; k < 32; ++k) c.memory.shell.push_back(pt(k + 0.5, 0.5, 0.5));
    uint32_t tag = 120;
    for (uint32_t n : {1u, 3u, 4u, 5u, 8u, 9u, 17u}) {
      const uint32_t base = n % 7;
      c.jobs.push_back(job(tag, Mode::All, base, n, 0, 32, 1, 1));
      for (uint32_t k = 0; k < n; ++k) c.expected.push_back(H(tag, k, base + k, 0, 0, 1));
      c.expected.push_back(D(tag, n));
      ++tag;
    }
  }
  return cs;
}

}  // namespace

const std::vector<DirectedCase>& directed_cases() {
  static const std::vector<DirectedCase> cases = build();
  return cases;
}

}  // namespace voxcd::testing
