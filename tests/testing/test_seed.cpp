// tests/seed.h: VOXCD_SEED as every random test reads it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>

#include "tests/seed.h"

namespace voxcd::test {
namespace {

TEST(Seed, ParsesDecimalAndHexadecimal) {
  EXPECT_EQ(parse_seed("0"), 0u);
  EXPECT_EQ(parse_seed("20261129"), 20261129u);
  EXPECT_EQ(parse_seed("0x10"), 16u);
  EXPECT_EQ(parse_seed("18446744073709551615"), 18446744073709551615ull);
}

TEST(Seed, RefusesWhatIsNotAnUnsignedNumber) {
  for (const char* bad : {"", "seven", "12abc", "-1", "+3", "18446744073709551616", " 5"}) {
    EXPECT_THROW(parse_seed(bad), std::invalid_argument) << "'" << bad << "'";
  }
  try {
    parse_seed("12abc");
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("VOXCD_SEED: '12abc'"), std::string::npos) << e.what();
  }
}

TEST(Seed, EnvironmentReplacesTheDefault) {
  ::unsetenv("VOXCD_SEED");
  EXPECT_EQ(seed(41), 41u);
  ::setenv("VOXCD_SEED", "977", 1);
  EXPECT_EQ(seed(41), 977u);
  ::unsetenv("VOXCD_SEED");
}

}  // namespace
}  // namespace voxcd::test
