// Shared voxmap banks (docs/contract.md, "Shared voxmap banks"): when the lanes share one voxmap memory split into
// banks, the lanes of a slot that read different words of one bank take turns, and the slot reaches the hit test
// that many cycles later. These functions count those cycles from the addresses, for the cycle model.
//
// A 2-bit device with BANKS = B has B banks, word w in bank w % B; a distance device has 8 parity banks split B
// ways, 8B in all, word w in bank w % 8B, and each of its lanes reads the 8 words of its cell's nodes.
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// Rounds a slot's reads take: the largest number of distinct words any one bank is asked for (word w is in bank
// w % banks); 1 when no lane reads (lanes outside the map read nothing). `words` holds every word the lanes read.
uint64_t bank_rounds(int banks, const std::vector<uint64_t>& words);

// The banks of cfg's voxmap memory: BANKS on a 2-bit device, 8 * BANKS on a distance device (0 with a copy per lane).
int memory_banks(const DeviceConfig& cfg);

// Rounds of one slot (lane group) `g` of a job: bank_rounds of the words its points read. 1 on a device with a copy
// per lane. The job must be valid for the shell memory (validate_job).
uint64_t slot_rounds(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job, uint64_t g);

// Bank conflict cycles of a job's first `groups` slots: the sum over them of slot_rounds - 1.
uint64_t job_bank_conflicts(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job,
                            uint64_t groups);

// The slots of a job whose reads reach the banks before its completion: all of them, or for a FIRST job that hit
// (done_hits > 0) those up to the slot of its hit (`hits` summarises its records, job_hits).
uint64_t read_groups(const DeviceConfig& cfg, const Job& job, const JobHits& hits, uint32_t done_hits);

// Rounds the slot behind a FIRST job's hit may still take before the hit stops its reads: 0 on a 2-bit device (the
// hit is seen at the slot register after the read, R5, before the slot behind it reads), the slot registers between
// the read and the hit test on a distance device (its hit is known only after the interpolation).
uint64_t first_read_window(const DeviceConfig& cfg);

// A job's bank conflict cycles (BankCycles, ref/timing.h): those of its read groups, and for a FIRST job that hit, the
// empty slots its later slots left during first_read_window.
BankCycles job_bank_cycles(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job,
                           const JobHits& hits, uint32_t done_hits);

// Every job's bank cycles, given the stream `records` that ref/ produced for them. Throws std::invalid_argument when
// the stream does not belong to the jobs.
std::vector<BankCycles> bank_cycles(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                                    const std::vector<Job>& jobs, const std::vector<Record>& records);
// Every job's bank conflict cycles (BankCycles::conflicts): what the device's conflict counter counts for it.
std::vector<uint64_t> bank_conflicts(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                                     const std::vector<Job>& jobs, const std::vector<Record>& records);

}  // namespace voxcd
