// Shared voxmap banks (docs/contract.md, "Shared voxmap banks"): when the lanes share one voxmap memory split into
// BANKS banks, the lanes of a slot that read different words of one bank take turns, and the slot reaches the
// hit test that many cycles later. These functions count those cycles from the addresses, for the cycle model.
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// Rounds a slot's reads take: the largest number of distinct words any one bank is asked for (word w is in bank
// w % BANKS); 1 when no lane reads (lanes outside the map read nothing). `words` holds each reading lane's word.
uint64_t bank_rounds(int banks, const std::vector<uint64_t>& words);

// Bank conflict cycles of a job's first `groups` slots (lane groups): the sum over them of bank_rounds - 1. 0 on a
// device with a copy per lane. The job must be valid for the shell memory (validate_job).
uint64_t job_bank_conflicts(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job,
                            uint64_t groups);

// The slots of a job whose reads reach the banks: all of them, or for a FIRST job that hit (done_hits > 0) those
// up to the slot of its hit (`hits` summarises its records, job_hits).
uint64_t read_groups(const DeviceConfig& cfg, const Job& job, const JobHits& hits, uint32_t done_hits);

// Every job's bank conflict cycles, given the stream `records` that ref/ produced for them: all of a job's slots,
// or for a FIRST job that hit, its slots up to the one of its hit (the slots issued behind the hit are squashed
// before they read). Throws std::invalid_argument when the stream does not belong to the jobs.
std::vector<uint64_t> bank_conflicts(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                                     const std::vector<Job>& jobs, const std::vector<Record>& records);

}  // namespace voxcd
