// The back-pressure scoreboard shared by the RTL tests and the soak: the device's stream against ref/'s, record by
// record (a lost, duplicated or reordered record shows as the first mismatch), and every job's cycles equal to the
// always-ready prediction plus the stall cycles the device counted in the job's window. Also the exact comparison of
// an always-ready run, and the tests' seed.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "voxcd/ref/types.h"
#include "tests/seed.h"

namespace voxcd::test {

// `want` carries ref/'s cycles (annotate_cycles). Adds the device's counted stalls to `stalls`.
inline void scoreboard(const std::vector<Record>& want, const std::vector<Record>& got, const std::string& what,
                       uint64_t& stalls) {
  size_t job = 0;
  for (size_t i = 0; i < want.size(); ++i) {
    ASSERT_LT(i, got.size()) << what << ": the stream ends after " << got.size() << " of " << want.size()
                             << " records (lost from job " << job << ")";
    ASSERT_TRUE(got[i].same_as(want[i], false))
        << what << ": record " << i << " of job " << job << " (tag " << want[i].tag << "): expected '"
        << want[i].to_string() << "', got '" << got[i].to_string() << "'";
    if (want[i].kind != Record::Done) continue;
    ASSERT_TRUE(got[i].cycles && got[i].stalls) << what << ": job " << job << " carries no cycles or stalls";
    ASSERT_EQ(*got[i].cycles, *want[i].cycles + *got[i].stalls)
        << what << ": job " << job << " (tag " << want[i].tag << ") cycles " << *got[i].cycles << " = predicted "
        << *want[i].cycles << " + stalls " << *got[i].stalls << " does not hold";
    stalls += *got[i].stalls;
    ++job;
  }
  ASSERT_EQ(got.size(), want.size()) << what << ": records after the last expected one";
}

// With an always-ready consumer: every record exactly ref/'s, cycles included (`want` carries the timing model's),
// points as the model counts them and no stall. Fails on the first difference: the job, the record, both values.
inline void expect_exact(const std::vector<Record>& want, const std::vector<Record>& got, const std::string& what) {
  size_t job = 0;
  for (size_t i = 0; i < want.size() && i < got.size(); ++i) {
    ASSERT_TRUE(got[i].same_as(want[i], true))
        << what << ": job " << job << " (tag " << want[i].tag << ") record " << i << ": expected '"
        << want[i].to_string() << "', got '" << got[i].to_string() << "'";
    if (want[i].kind != Record::Done) continue;
    ASSERT_EQ(*got[i].points, *want[i].points) << what << ": job " << job << " points";
    ASSERT_EQ(*got[i].stalls, 0u) << what << ": job " << job << " stalls with an always-ready consumer";
    ++job;
  }
  ASSERT_EQ(got.size(), want.size()) << what << ": record count";
}

}  // namespace voxcd::test
