#include "voxcd/ref/address_map.h"

#include <cstring>

namespace voxcd::sysc {

void encode_job(const Job& job, uint8_t* out) {
  std::memset(out, 0, kJobBytes);
  put_le(out + 0x00, job.tag, 4);
  out[0x04] = uint8_t(job.mode);
  out[0x05] = job.hit_mask;
  put_le(out + 0x08, job.shell_base, 4);
  put_le(out + 0x0c, job.shell_count, 4);
  put_le(out + 0x10, job.map_base, 4);
  put_le(out + 0x14, job.nx, 4);
  put_le(out + 0x18, job.ny, 4);
  put_le(out + 0x1c, job.nz, 4);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) put_le(out + 0x20 + 4 * (3 * i + j), uint64_t(job.M[i][j]), 4);
  for (int i = 0; i < 3; ++i) put_le(out + 0x48 + 8 * i, uint64_t(job.t[i]), 8);
  put_le(out + 0x60, uint64_t(job.threshold), 8);
  out[0x06] = job.sparse;
  put_le(out + 0x44, job.brick_units, 4);
  put_le(out + 0x68, job.brick_base, 4);
}

bool decode_job(const uint8_t* in, Job& job, std::string& why) {
  // The reserved bytes as whole words first; the loops below name the first one that is set.
  const uint64_t reserved = uint64_t(in[0x07]) | get_le(in + 0x6c, 4) | get_le(in + 0x70, 8) | get_le(in + 0x78, 8);
  if (reserved != 0) {
    if (in[0x07] != 0) {
      why = "reserved descriptor byte 7 is not zero";
      return false;
    }
    for (size_t b = 0x6c; b < kJobBytes; ++b)
      if (in[b] != 0) {
        why = "reserved descriptor byte " + std::to_string(b) + " is not zero";
        return false;
      }
  }
  if (in[0x04] > 2) {
    why = "mode " + std::to_string(in[0x04]) + " is not 0 (ALL), 1 (FIRST) or 2 (COUNT)";
    return false;
  }
  // Every field is set below.
  job.tag = uint32_t(get_le(in + 0x00, 4));
  job.mode = Mode(in[0x04]);
  job.hit_mask = in[0x05];
  job.shell_base = uint32_t(get_le(in + 0x08, 4));
  job.shell_count = uint32_t(get_le(in + 0x0c, 4));
  job.map_base = uint32_t(get_le(in + 0x10, 4));
  job.nx = uint32_t(get_le(in + 0x14, 4));
  job.ny = uint32_t(get_le(in + 0x18, 4));
  job.nz = uint32_t(get_le(in + 0x1c, 4));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) job.M[i][j] = int32_t(uint32_t(get_le(in + 0x20 + 4 * (3 * i + j), 4)));
  for (int i = 0; i < 3; ++i) job.t[i] = int64_t(get_le(in + 0x48 + 8 * i, 8));
  job.threshold = int64_t(get_le(in + 0x60, 8));
  job.sparse = in[0x06];
  job.brick_units = uint32_t(get_le(in + 0x44, 4));
  job.brick_base = uint32_t(get_le(in + 0x68, 4));
  return true;
}

void encode_record(const Record& rec, uint8_t* out) {
  std::memset(out, 0, kRecordBytes);
  put_le(out + 0x04, rec.tag, 4);
  if (rec.kind == Record::Hit) {
    out[0] = kKindHit;
    out[1] = rec.state;
    put_le(out + 0x08, rec.point, 4);
    put_le(out + 0x0c, rec.x, 4);
    put_le(out + 0x10, rec.y, 4);
    put_le(out + 0x14, rec.z, 4);
    put_le(out + 0x18, uint64_t(rec.dist), 8);
  } else {
    out[0] = kKindDone;
    put_le(out + 0x08, rec.hits, 4);
    put_le(out + 0x0c, rec.points.value_or(0), 4);
    put_le(out + 0x10, rec.cycles.value_or(0), 8);
    put_le(out + 0x18, rec.stalls.value_or(0), 8);
  }
}

bool decode_record(const uint8_t* in, Record& rec) {
  if (in[0] != kKindHit && in[0] != kKindDone) return false;
  // Field by field rather than through Record::hit / Record::done: the same record without a temporary.
  rec.tag = uint32_t(get_le(in + 0x04, 4));
  if (in[0] == kKindHit) {
    rec.kind = Record::Hit;
    rec.point = uint32_t(get_le(in + 0x08, 4));
    rec.x = uint32_t(get_le(in + 0x0c, 4));
    rec.y = uint32_t(get_le(in + 0x10, 4));
    rec.z = uint32_t(get_le(in + 0x14, 4));
    rec.state = in[1];
    rec.dist = int64_t(get_le(in + 0x18, 8));
    rec.hits = 0;
    rec.cycles.reset();
    rec.points.reset();
    rec.stalls.reset();
  } else {
    rec.kind = Record::Done;
    rec.point = rec.x = rec.y = rec.z = 0;
    rec.state = 0;
    rec.dist = 0;
    rec.hits = uint32_t(get_le(in + 0x08, 4));
    rec.points = get_le(in + 0x0c, 4);
    rec.cycles = get_le(in + 0x10, 8);
    rec.stalls = get_le(in + 0x18, 8);
  }
  return true;
}

bool decode_error_record(const uint8_t* in, uint32_t& tag, uint32_t& faults) {
  if (in[0] != kKindError) return false;
  tag = uint32_t(get_le(in + 0x04, 4));
  faults = uint32_t(get_le(in + 0x08, 4));
  return true;
}

uint64_t config_word0(const DeviceConfig& c) {
  return uint64_t(c.PW) | uint64_t(c.PF) << 8 | uint64_t(c.MW) << 16 | uint64_t(c.MF) << 24 | uint64_t(c.TW) << 32 |
         uint64_t(c.DW) << 40 | uint64_t(c.MEMW) << 48 | uint64_t(c.LANES) << 56;
}

uint64_t config_word1(const DeviceConfig& c) {
  return uint64_t(c.SAW) | uint64_t(c.MAW) << 8 | uint64_t(c.TAGW) << 16 | uint64_t(c.SB) << 24 | uint64_t(c.WB) << 32 |
         uint64_t(c.BANKS) << 40 | uint64_t(c.depth) << 48 | uint64_t(c.BL) << 56;
}

}  // namespace voxcd::sysc
