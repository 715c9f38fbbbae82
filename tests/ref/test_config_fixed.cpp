// DeviceConfig validation and quantisation: round to nearest, ties away from zero; no wrap, no clamp.
#include <gtest/gtest.h>

#include <random>

#include <cmath>
#include <limits>

#include "voxcd/ref/config.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/float_model.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

TEST(Config, DefaultsAreTheDesignDefaults) {
  const DeviceConfig c;
  EXPECT_EQ(c.PW, 24);
  EXPECT_EQ(c.PF, 8);
  EXPECT_EQ(c.MW, 18);
  EXPECT_EQ(c.MF, 16);
  EXPECT_EQ(c.TW, 48);
  EXPECT_EQ(c.DW, 10);
  EXPECT_EQ(c.MEMW, 64);
  EXPECT_EQ(c.LANES, 4);
  EXPECT_EQ(c.TF(), 24);
  EXPECT_NO_THROW(c.validate());
  // Three 18 x 24-bit products sum to 44 bits; the 48-bit translation dominates, plus one for the sum: 49.
  EXPECT_EQ(c.acc_width(), 49);
}

TEST(Config, RejectsImpossibleWidths) {
  auto bad = [](auto mutate, const char* needle) {
    DeviceConfig c;
    mutate(c);
    try {
      c.validate();
      ADD_FAILURE() << "accepted " << c.to_string();
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  bad([](DeviceConfig& c) { c.MEMW = 48; }, "MEMW = 48 is not a power of two");
  bad([](DeviceConfig& c) { c.MEMW = 128; }, "MEMW");
  bad([](DeviceConfig& c) { c.PF = 24; }, "PF");
  bad([](DeviceConfig& c) { c.TW = 24; }, "TW = 24 leaves no integer bit");
  bad([](DeviceConfig& c) { c.LANES = 0; }, "LANES");
  bad([](DeviceConfig& c) { c.DW = 0; }, "DW");
  bad([](DeviceConfig& c) { c.MW = 40; }, "MW");
  bad([](DeviceConfig& c) { c.TX = 1; }, "TX = 1 (brick lanes) needs a sparse device (BL > 0)");
  bad([](DeviceConfig& c) { c.TX = 2; c.BL = 3; }, "TX = 2 is not 0");
}

// Brick lanes (TX 1) change timing, never results: the same widths, another configuration, its own text.
TEST(Config, BrickLanesAreATimingParameter) {
  DeviceConfig c;
  c.BL = 3;
  DeviceConfig b = c;
  b.TX = 1;
  b.validate();
  EXPECT_TRUE(b.same_widths(c));
  EXPECT_NE(b, c);
  EXPECT_EQ(b.to_string(), c.to_string() + " TX 1");
  EXPECT_EQ(b.dense_slot_points(), 1);
  EXPECT_EQ(c.dense_slot_points(), c.LANES);
}

TEST(Quantize, RoundsHalfAwayFromZero) {
  const FixedFormat f{8, 2};  // quarter steps, [-32, 31.75]
  EXPECT_EQ(quantize(0.125, f, "v"), 1);     // exactly half an ulp: away from zero
  EXPECT_EQ(quantize(-0.125, f, "v"), -1);
  EXPECT_EQ(quantize(0.375, f, "v"), 2);     // 1.5 ulp -> 2
  EXPECT_EQ(quantize(-0.625, f, "v"), -3);   // -2.5 ulp -> -3
  EXPECT_EQ(quantize(0.1249999, f, "v"), 0);
  EXPECT_EQ(quantize(31.75, f, "v"), 127);
  EXPECT_EQ(quantize(-32.0, f, "v"), -128);
  EXPECT_EQ(quantize(31.8, f, "v"), 127);    // rounds down to the maximum: fits
}

TEST(Quantize, OutOfRangeIsAnErrorNamingValueAndFormat) {
  const FixedFormat f{18, 16};
  EXPECT_EQ(quantize(1.0, f, "M00"), 65536);  // +1.0 is representable: a 90 degree turn must work
  EXPECT_EQ(quantize(-2.0, f, "M00"), -131072);
  for (double v : {2.0, 1.9999999, -2.0000077, 1e300, std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    try {
      quantize(v, f, "M12");
      ADD_FAILURE() << v << " was accepted";
    } catch (const RangeError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("M12 = "), std::string::npos) << m;
      EXPECT_NE(m.find("signed 18-bit with 16 fraction bits"), std::string::npos) << m;
    }
  }
  // 1.99999237 = (2^17 - 0.5) / 2^16 rounds up to 2^17: does not fit, never wraps to -2.
  EXPECT_THROW(quantize((131072 - 0.5) / 65536.0, f, "M"), RangeError);
  EXPECT_EQ(quantize((131072 - 0.5001) / 65536.0, f, "M"), 131071);
}

TEST(Quantize, TryQuantizeAgreesWithQuantize) {
  std::mt19937_64 rng(test::seed(9));
  std::uniform_real_distribution<double> u(-3, 3);
  const FixedFormat f{18, 16};
  for (int k = 0; k < 100000; ++k) {
    double v = u(rng);
    if (k % 3 == 0) v = std::ldexp(std::round(std::ldexp(v, 17)), -17);  // half-ulp ties
    int64_t got = 12345;
    const bool ok = try_quantize(v, f, &got);
    try {
      EXPECT_EQ(quantize(v, f, "v"), got);
      EXPECT_TRUE(ok) << v;
    } catch (const RangeError&) {
      EXPECT_FALSE(ok) << v;
      EXPECT_EQ(got, 12345) << "untouched on failure";
    }
  }
  int64_t r = 0;
  EXPECT_FALSE(try_quantize(std::numeric_limits<double>::quiet_NaN(), f, &r));
}

TEST(Quantize, SixtyFourBitFormatHasNoUndefinedConversion) {
  const FixedFormat f{64, 0};
  EXPECT_THROW(quantize(9.3e18, f, "t"), RangeError);  // above 2^63
  EXPECT_EQ(quantize(-9223372036854775808.0, f, "t"), std::numeric_limits<int64_t>::min());
}

TEST(Quantize, PoseFailureLeavesTheJobUntouched) {
  DeviceConfig cfg;
  Job j;
  j.M[0][0] = 7;
  j.t[2] = 9;
  FloatPose p;
  p.t[1] = std::nan("");
  try {
    quantize_pose(cfg, p, j);
    ADD_FAILURE() << "NaN translation accepted";
  } catch (const RangeError& e) {
    EXPECT_NE(std::string(e.what()).find("T1 = nan"), std::string::npos) << e.what();
  }
  EXPECT_EQ(j.M[0][0], 7);
  EXPECT_EQ(j.t[2], 9);
  p.t[1] = 1e7;  // 10^7 voxels does not fit TW = 48 with TF = 24 (max about 8.4e6)
  EXPECT_THROW(quantize_pose(cfg, p, j), RangeError);
  p.t[1] = 8e6;
  EXPECT_NO_THROW(quantize_pose(cfg, p, j));
  EXPECT_EQ(j.t[1], int64_t(8e6) << 24);
}

TEST(FitsSigned, Edges) {
  EXPECT_TRUE(fits_signed(127, 8));
  EXPECT_FALSE(fits_signed(128, 8));
  EXPECT_TRUE(fits_signed(-128, 8));
  EXPECT_FALSE(fits_signed(-129, 8));
  EXPECT_TRUE(fits_unsigned(1023, 10));
  EXPECT_FALSE(fits_unsigned(1024, 10));
}

}  // namespace
}  // namespace voxcd
