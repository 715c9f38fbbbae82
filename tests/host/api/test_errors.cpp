// The errors of the public API (<voxcd/host/api/errors.h>, docs/api.md "Errors"): every error type derives from
// voxcd::Error (still a std::runtime_error), says where, and the API's own errors reach a caller by name.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <type_traits>

#include <voxcd/voxcd.h>

#include "tests/host/test_util.h"
#include "voxcd/host/device/timing_table.h"
#include "voxcd/host/regress/campaign.h"
#include "voxcd/host/regress/coverage.h"
#include "voxcd/host/sizing/energy_table.h"
#include "voxcd/host/sizing/sweep/sweep.h"

namespace voxcd {
namespace {

template <class... E>
constexpr bool all_errors() {
  return (... && (std::is_base_of_v<Error, E> && !std::is_same_v<Error, E>));
}

// Every error type of host/ and ref/, the public ones and the tool's (campaigns, sweeps, tables).
static_assert(all_errors<RangeError, ConfigError, JobError, VectorError, MeshError, ObjectFileError, CapacityError,
                         DeviceError, SceneFileError, OptionError, PlacementError, RecordError, SizeError,
                         TimingTableError, EnergyTableError, SweepError, CampaignError, CoverageError>());
static_assert(std::is_base_of_v<std::runtime_error, Error>, "catch (const std::runtime_error&) still catches them");

// The type fn throws is E, and Error gives its message and where.
template <class E, class Fn>
Error caught(Fn&& fn) {
  try {
    fn();
  } catch (const E& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw another type: " << e.what();
    return Error("");
  }
  ADD_FAILURE() << "threw nothing";
  return Error("");
}

TEST(Errors, WhereIsTheMessagesLeadingPlace) {
  EXPECT_EQ(Error("mixed.json: types[1].voxel: -1 is outside (0, 1e+12]").where(), "mixed.json: types[1].voxel");
  EXPECT_EQ(Error("a.vec:12: bad config line").where(), "a.vec:12");
  EXPECT_EQ(Error("x.vxo: cannot open").where(), "x.vxo");
  EXPECT_EQ(Error("T0 = -4e9 does not fit signed 48-bit").where(), "");
  EXPECT_EQ(Error("could not place instance 3: no site").where(), "");
  EXPECT_EQ(Error("message", "given").where(), "given");
  EXPECT_EQ(Error("").where(), "");
  // OptionError names its settings; PlacementError the body.
  const OptionError o({"voxel", "resolution"}, "give one of them");
  EXPECT_STREQ(o.what(), "voxel, resolution: give one of them");
  EXPECT_EQ(o.where(), "voxel, resolution");
  EXPECT_EQ(PlacementError(1, 7, 6, 0.5).where(), "type 1 instance 7");
  const SizeError z("rate", 2.5, "needs 2.5 times the lanes");
  EXPECT_STREQ(z.prefixed("s.json: cannot be met: ").what(), "s.json: cannot be met: rate: needs 2.5 times the lanes");
  EXPECT_EQ(z.prefixed("s.json: ").constraint, "rate");
}

TEST(Errors, TheApisErrorsByName) {
  const std::string missing = test::tmp_path("errors_missing.vxo");
  std::remove(missing.c_str());
  EXPECT_EQ(caught<MeshError>([&] { Object::load(missing); }).where(), missing);
  const std::string bad = test::tmp_path("errors_bad.vxo");
  std::ofstream(bad) << "VOXCDOBJ not really";
  EXPECT_EQ(caught<ObjectFileError>([&] { Object::load(bad); }).where(), bad);
  const std::string scene = test::tmp_path("errors_scene.json");
  std::ofstream(scene) << R"({"types": [{"shape": "cube", "voxel": -1}]})";
  EXPECT_EQ(caught<SceneFileError>([&] { World::scene(scene); }).where(), scene + ": types[0].voxel");
  WorldDef def;
  def.side = -1;
  EXPECT_EQ(caught<OptionError>([&] { World w(def); }).where(), "side");
  const Object cube = Object::load("cube");
  Pose nan;
  nan.translation = {std::nan(""), 0, 0};
  caught<RangeError>([&] { collide(cube, Pose{}, cube, nan); });
  CollideOptions o;
  o.backend = "no-such-backend";
  caught<DeviceError>([&] { collide(cube, Pose{}, cube, Pose{}, o); });
  SizeOptions so;
  so.clock_mhz = -1;
  EXPECT_EQ(caught<OptionError>([&] { size_device(VOXCD_SCENES_DIR "/small.json", so); }).where(), "clock_mhz");
  so.clock_mhz = 0;
  so.accuracy = 1e-12;
  caught<SizeError>([&] { size_device(VOXCD_SCENES_DIR "/small.json", so); });
  // And all of them as Error.
  caught<Error>([&] { Object::load(missing); });
}

}  // namespace
}  // namespace voxcd
