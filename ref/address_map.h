// The device's address map (docs/systemc.md is the prose): register, memory, job and result windows, and the byte
// layout of job descriptors and result records. Part of the device contract: the SystemC targets (sysc/), their
// initiators, the host's sysc backends (host/device/sysc.cpp) and the AXI top (rtl/voxcd_axi.sv) all speak it; no
// SystemC. Its names are in voxcd::sysc, where initiators have always found them (sysc/address_map.h includes this).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd::sysc {

// Windows (byte addresses; all data little-endian).
constexpr uint64_t kRegBase = 0x0000'0000;     // 64-bit registers, 8-byte accesses
constexpr uint64_t kRegSize = 0x0000'1000;
constexpr uint64_t kJobBase = 0x0001'0000;     // write whole job descriptors at offset 0: they are staged
constexpr uint64_t kJobSize = 0x0001'0000;
constexpr uint64_t kResultBase = 0x0002'0000;  // read whole result records at offset 0: they are popped
constexpr uint64_t kResultSize = 0x0001'0000;
constexpr uint64_t kShellBase = 0x1000'0000;   // shell word k at kShellBase + 16 k (write only)
constexpr uint64_t kMapBase = 0x2000'0000;     // voxmap word k at kMapBase + 8 k (write only)
constexpr uint64_t kShellStride = 16;
constexpr uint64_t kMapStride = 8;

// Registers: offsets in the register window.
enum Reg : uint64_t {
  kRegId = 0x00,           // RO: kDeviceId
  kRegConfig0 = 0x08,      // RO: PW | PF<<8 | MW<<16 | MF<<24 | TW<<32 | DW<<40 | MEMW<<48 | LANES<<56
  kRegConfig1 = 0x10,      // RO: SAW | MAW<<8 | TAGW<<16 | SB<<24 | WB<<32 | BANKS<<40 | DEPTH<<48 | BL<<56
  kRegClockPs = 0x18,      // RO: clock period in picoseconds
  kRegStatus = 0x20,       // RO: kStatus* bits
  kRegStaged = 0x28,       // RO: jobs staged and not yet launched
  kRegResultCount = 0x30,  // RO: result records readable now
  kRegRun = 0x38,          // WO: any value launches the staged jobs as one batch
  kRegJobsDone = 0x40,     // RO: counters since reset, updated as completion records become readable
  kRegHits = 0x48,
  kRegPoints = 0x50,
  kRegCycles = 0x58,       // sum of the completion records' cycles
  kRegStalls = 0x60,
  kRegShellWords = 0x68,   // RO: shell words loaded (one past the highest written)
  kRegMapWords = 0x70,     // RO: voxmap words loaded
  kRegDropped = 0x78,      // RO: job descriptors refused (the AXI top, rtl/voxcd_axi.sv: malformed frames, and
                           // descriptors it answers with an error record; the SystemC targets refuse them with an
                           // error response instead, and read 0 here)
  kRegConflicts = 0x80,    // RO: bank conflict cycles since reset (shared voxmap banks, BANKS > 0; else 0)
};
constexpr uint64_t kDeviceId = 0x766f'7863'6400'0001;  // "voxcd", version 1
// STATUS bits.
constexpr uint64_t kStatusBusy = 1;     // a launched batch has not finished (its last completion is not readable)
constexpr uint64_t kStatusResults = 2;  // result records are readable
constexpr uint64_t kStatusStaged = 4;   // jobs are staged
constexpr uint64_t kStatusFault = 8;    // the RTL failed an assertion (RTL target only; other accesses then fail)

// Job descriptor: kJobBytes bytes.
//   0x00 u32 tag      0x04 u8 mode (0 ALL, 1 FIRST, 2 COUNT)   0x05 u8 hit mask
//   0x06 u8 sparse (bit 0: the map is sparse, bit 1: the shell is sparse; bits 2..7 set: a refused job, as
//        validate_job refuses it, the AXI top's error record bit 1)   0x07 u8 zero
//   0x08 u32 shell_base   0x0c u32 shell_count (a sparse shell: its words)   0x10 u32 map_base   0x14 u32 nx
//   0x18 u32 ny   0x1c u32 nz   0x20 i32 M[3][3], row-major   0x44 u32 brick_units   0x48 i64 t[3]
//   0x60 i64 threshold (0 on a 2-bit device)   0x68 u32 brick_base   0x6c .. 0x7f zero
// (docs/contract.md, "Sparse voxmaps and shells": sparse, brick_base and brick_units are 0 for a dense job, so a dense
// job's descriptor is what it was before sparse devices.)
constexpr size_t kJobBytes = 128;
// Result record: kRecordBytes bytes.
//   0x00 u8 kind (0 none, 1 hit, 2 done, 3 error)   0x01 u8 state (hit)   0x02 u16 zero   0x04 u32 tag
//   hit:   0x08 u32 point   0x0c u32 x   0x10 u32 y   0x14 u32 z   0x18 i64 dist (0 on a 2-bit device)
//   done:  0x08 u32 hits    0x0c u32 points   0x10 u64 cycles   0x18 u64 stalls
//   error: 0x08 u32 faults (a refused descriptor, the AXI top only: the tag as the descriptor has it and the rules
//          it breaks, kFaultDescriptor and ref/pipeline.h's JobFault bits)   0x0c .. 0x1f zero
constexpr size_t kRecordBytes = 32;
enum RecordKind : uint8_t { kKindNone = 0, kKindHit = 1, kKindDone = 2, kKindError = 3 };
// An error record's fault bit for a descriptor with a reserved byte set (the other bits: ref/pipeline.h, JobFault).
constexpr uint32_t kFaultDescriptor = 1;
// The fault bits of an error record (kind 3); false (and faults untouched) for any other record.
bool decode_error_record(const uint8_t* in, uint32_t& tag, uint32_t& faults);

void encode_job(const Job& job, uint8_t* out);
// Decodes a descriptor; false (and `why`) when a reserved byte is not zero or the mode is not 0..2. The sparse byte is
// decoded whole: bits 2..7 are refused by validate_job.
bool decode_job(const uint8_t* in, Job& job, std::string& why);
void encode_record(const Record& rec, uint8_t* out);
// Decodes one record slot; false for an empty slot (kind 0) or an error record (kind 3: decode_error_record).
bool decode_record(const uint8_t* in, Record& rec);

uint64_t config_word0(const DeviceConfig& cfg);
uint64_t config_word1(const DeviceConfig& cfg);

// Little-endian helpers. On a little-endian host the whole words are copied (the compiler does not merge the byte
// loop into one load or store, and descriptors and records are decoded per word on every batch).
inline void put_le(uint8_t* p, uint64_t v, int bytes) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  if (bytes == 8) return void(std::memcpy(p, &v, 8));
  if (bytes == 4) {
    const uint32_t w = uint32_t(v);
    return void(std::memcpy(p, &w, 4));
  }
#endif
  for (int i = 0; i < bytes; ++i) p[i] = uint8_t(v >> (8 * i));
}
inline uint64_t get_le(const uint8_t* p, int bytes) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  if (bytes == 8) {
    uint64_t v;
    std::memcpy(&v, p, 8);
    return v;
  }
  if (bytes == 4) {
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
  }
#endif
  uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= uint64_t(p[i]) << (8 * i);
  return v;
}

}  // namespace voxcd::sysc
