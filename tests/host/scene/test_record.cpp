// Recordings (host/scene/record.h, docs/view.md): a run read back equals the run (poses, pairs, contacts, statistics),
// a recording is readable while it is written, a truncated file is read up to its last whole frame with a note, and
// another format version, a damaged record or another file is refused with a message naming the file and byte.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "tests/host/test_util.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxmap_surface.h"
#include "voxcd/host/scene/record.h"
#include "voxcd/host/scene/simulate.h"

namespace voxcd {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A dense scene, so that pairs touch within a few frames.
Scene dense_scene() {
  RunConfig spec;
  spec.types[0].count = 48;
  spec.density = 0.09;
  spec.side = 40;
  spec.speed = 0.3;
  spec.seed = 7;
  return make_scene(spec);
}

// What a frame should read back as: the run's state after the step, as the recording rounds it.
struct Expected {
  FrameStats stats;
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<float, 4>> rotations;
  std::vector<BodyPair> pairs, tested;
  std::vector<PairResult> results;
};

Expected expect(const Simulation& sim, const FrameStats& st) {
  Expected e{st, {}, {}, sim.broadphase().pairs(), sim.tested_pairs(), sim.results()};
  for (const Body& b : sim.scene().bodies) {
    const auto& t = b.pose.translation;
    const auto& q = b.pose.rotation;
    e.positions.push_back({float(t.x()), float(t.y()), float(t.z())});
    e.rotations.push_back({float(q.w()), float(q.x()), float(q.y()), float(q.z())});
  }
  return e;
}

void check_frame(const Expected& e, const RecordedFrame& f) {
  EXPECT_EQ(f.stats.frame, e.stats.frame);
  EXPECT_EQ(f.stats.contacts, e.stats.contacts);
  EXPECT_EQ(f.stats.device_cycles, e.stats.device_cycles);
  EXPECT_EQ(f.stats.lookups, e.stats.lookups);
  EXPECT_EQ(f.stats.t_narrow, e.stats.t_narrow);
  EXPECT_EQ(f.positions, e.positions);
  EXPECT_EQ(f.rotations, e.rotations);
  ASSERT_EQ(f.pairs, e.pairs);
  // The tested pairs are the flagged ones, in order; touching where the run had hits; contacts in the run's order.
  std::vector<BodyPair> tested;
  std::vector<size_t> at;
  for (size_t i = 0; i < f.pairs.size(); ++i)
    if (f.pair_flags[i] & kPairTested) tested.push_back(f.pairs[i]), at.push_back(i);
  ASSERT_EQ(tested, e.tested);
  size_t k = 0;
  for (size_t q = 0; q < e.results.size(); ++q) {
    EXPECT_EQ(bool(f.pair_flags[at[q]] & kPairTouching), e.results[q].hits > 0);
    for (const Contact& c : e.results[q].contacts) {
      ASSERT_LT(k, f.contacts.size());
      const RecordedContact& r = f.contacts[k++];
      EXPECT_EQ(r.pair, at[q]);
      EXPECT_EQ(r.a_in_b, c.a_in_b);
      EXPECT_EQ(r.point, c.point);
      EXPECT_EQ(r.position, (std::array<float, 3>{float(c.position.x()), float(c.position.y()), float(c.position.z())}));
      EXPECT_EQ(r.normal, (std::array<float, 3>{float(c.normal.x()), float(c.normal.y()), float(c.normal.z())}));
      EXPECT_EQ(r.depth, float(c.depth));
    }
  }
  EXPECT_EQ(k, f.contacts.size());
}

// Records `frames` frames of the dense scene to `path`; returns what each frame should read back as.
std::vector<Expected> record_run(const std::string& path, int frames) {
  Simulation sim(dense_scene(), RunConfig{});
  RecordWriter w(path, sim, "{\"test\": true}");
  std::vector<Expected> out;
  for (int f = 0; f < frames; ++f) {
    const FrameStats st = sim.step();
    w.frame(sim, st);
    out.push_back(expect(sim, st));
  }
  w.close();
  return out;
}

TEST(Record, RoundTripEqualsTheRun) {
  const std::string path = test::tmp_path("roundtrip.vxr");
  const std::vector<Expected> run = record_run(path, 20);
  const Recording r = read_recording(path);
  EXPECT_FALSE(r.truncated);
  EXPECT_EQ(r.run, "{\"test\": true}");
  ASSERT_EQ(r.frames.size(), 20u);
  ASSERT_EQ(r.body_types.size(), 48u);
  ASSERT_EQ(r.types.size(), 1u);
  EXPECT_TRUE(r.types[0].from_mesh);
  EXPECT_EQ(r.types[0].triangles.size(), make_shape("polytope36").triangles.size());
  EXPECT_GT(r.types[0].shell_points.size(), 0u);
  uint64_t contacts = 0;
  for (size_t f = 0; f < run.size(); ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    check_frame(run[f], r.frames[f]);
    contacts += r.frames[f].contacts.size();
  }
  EXPECT_GT(contacts, 0u) << "the scene should touch within 20 frames: the contacts are not tested";
}

TEST(Record, SimulateRecordsWhatItSums) {
  const std::string path = test::tmp_path("simulate.vxr");
  RunConfig c;
  c.types[0].count = 64;
  c.frames = 12;
  c.density = 0.09;
  c.record = path;
  const SimulationSummary s = simulate(c);
  const Recording r = read_recording(path);
  ASSERT_EQ(r.frames.size(), 12u);
  SimulationTotals t;
  for (const RecordedFrame& f : r.frames) t.add(f.stats);
  EXPECT_EQ(t.pairs, s.totals.pairs);
  EXPECT_EQ(t.contacts, s.totals.contacts);
  EXPECT_EQ(t.cycles, s.totals.cycles);
  EXPECT_NE(r.run.find("\"objects\":64"), std::string::npos) << r.run;
  EXPECT_NE(r.run.find("\"backend\":\"cpu\""), std::string::npos) << r.run;
}

TEST(Record, ReadableWhileWritten) {
  const std::string path = test::tmp_path("live.vxr");
  Simulation sim(dense_scene(), RunConfig{});
  RecordWriter w(path, sim);
  EXPECT_EQ(read_recording(path).frames.size(), 0u);
  for (int f = 0; f < 3; ++f) w.frame(sim, sim.step());
  Recording r = read_recording(path);
  EXPECT_EQ(r.frames.size(), 3u);
  EXPECT_FALSE(r.truncated);
  w.frame(sim, sim.step());
  EXPECT_EQ(read_recording(path).frames.size(), 4u);
  EXPECT_EQ(w.frames(), 4u);
  EXPECT_EQ(w.bytes(), slurp(path).size());
}

TEST(Record, TruncatedFileIsReadUpToItsLastWholeFrame) {
  const std::string path = test::tmp_path("cut.vxr");
  record_run(path, 5);
  const std::string bytes = slurp(path);
  const Recording whole = parse_recording(bytes, "whole.vxr");
  // Cut inside the last frame record: in its CRC and in its payload.
  for (size_t cut : {size_t(1), size_t(9), size_t(40)}) {
    const Recording r = parse_recording(bytes.substr(0, bytes.size() - cut), "cut.vxr");
    EXPECT_TRUE(r.truncated);
    EXPECT_EQ(r.frames.size(), 4u);
    EXPECT_NE(r.note.find("cut.vxr: truncated at byte " + std::to_string(bytes.size() - cut)), std::string::npos)
        << r.note;
    EXPECT_NE(r.note.find("read 4 whole frames"), std::string::npos) << r.note;
    EXPECT_EQ(r.frames[3].positions, whole.frames[3].positions);
  }
  // Cut inside the header records: nothing to show.
  try {
    parse_recording(bytes.substr(0, 40), "head.vxr");
    FAIL() << "a recording cut before its bodies was read";
  } catch (const RecordError& e) {
    EXPECT_STREQ(e.what(), "head.vxr: ends at byte 40 before its types and bodies were written: nothing to show");
  }
}

TEST(Record, OtherVersionIsRefused) {
  const std::string path = test::tmp_path("v2.vxr");
  record_run(path, 2);
  std::string bytes = slurp(path);
  bytes[8] = 2;
  try {
    parse_recording(bytes, "v2.vxr");
    FAIL() << "a version 2 recording was read";
  } catch (const RecordError& e) {
    EXPECT_STREQ(e.what(), "v2.vxr: a recording of format version 2; this voxcd reads version 1 (docs/view.md)");
  }
}

TEST(Record, DamagedOrForeignFilesAreRefused) {
  const std::string path = test::tmp_path("damaged.vxr");
  record_run(path, 2);
  std::string bytes = slurp(path);
  bytes[bytes.size() - 20] ^= 0x40;  // inside the last frame's payload
  try {
    parse_recording(bytes, "damaged.vxr");
    FAIL() << "a damaged recording was read";
  } catch (const RecordError& e) {
    EXPECT_NE(std::string(e.what()).find("frame record fails its CRC-32"), std::string::npos) << e.what();
  }
  EXPECT_THROW(
      {
        try {
          parse_recording("solid cube\n", "cube.stl");
        } catch (const RecordError& e) {
          EXPECT_STREQ(e.what(), "cube.stl: not a voxcd recording (it does not start with VOXCDREC)");
          throw;
        }
      },
      RecordError);
  EXPECT_FALSE(is_recording(test::tmp_path("no-such-file.vxr")));
  EXPECT_TRUE(is_recording(path));
}

TEST(Record, TypeWithoutItsMeshIsDrawnByItsVoxmapSurface) {
  ObjectOptions o;
  o.resolution = 8;
  const Mesh cube = make_shape("cube");
  ObjectType t = make_object_type(make_object(cube, "shape:cube", 0, o), "cube");
  const RecordedType with = recorded_type([&] {
    ObjectType m = t;
    m.mesh = std::make_shared<const Mesh>(cube);
    return m;
  }());
  EXPECT_TRUE(with.from_mesh);
  EXPECT_EQ(with.triangles.size(), cube.triangles.size());
  const RecordedType without = recorded_type(t);
  EXPECT_FALSE(without.from_mesh);
  EXPECT_EQ(without.triangles.size(), voxmap_surface(t.voxmap()).triangles.size());
}

TEST(VoxmapSurface, ClosedOutwardAndOnTheVoxelsFaces) {
  GridPlacement g;
  g.dims = {3, 2, 2};
  g.voxel = 0.5;
  g.origin = Eigen::Vector3d(1, 2, 3);
  Voxmap v(g);
  for (uint32_t z = 0; z < 2; ++z)
    for (uint32_t y = 0; y < 2; ++y)
      for (uint32_t x = 0; x < 2; ++x) v.set(v.index(x, y, z), x == 0 ? kSurface : kInterior);
  Mesh m = voxmap_surface(v);
  // A 2x2x2 block: 6 sides of 4 faces, two triangles each; its volume, outward.
  EXPECT_EQ(m.triangles.size(), 48u);
  EXPECT_NEAR(m.volume(), 8 * 0.125, 1e-12);
  EXPECT_EQ(m.vertices.size(), 26u);  // the corners on the block's surface, shared
  MeshReport r = prepare(m);
  EXPECT_FALSE(r.flipped);
  EXPECT_TRUE(voxmap_surface(Voxmap(g)).triangles.empty());
}

}  // namespace
}  // namespace voxcd

namespace voxcd {
namespace {

// A frame whose broadphase finds no pair tests none (the recorder found a frame that tested a pair of body 0 with
// itself: the mid-phase's count of an unvisited range was never set).
TEST(Simulation, FrameWithoutPairsTestsNone) {
  RunConfig spec;
  spec.types[0].count = 2;
  Simulation sim(make_scene(spec), RunConfig{});
  for (int f = 0; f < 3; ++f) {
    const FrameStats st = sim.step();
    ASSERT_EQ(sim.broadphase().pairs().size(), st.pairs);
    if (st.pairs == 0) {
      EXPECT_EQ(st.tested, 0u);
      EXPECT_TRUE(sim.tested_pairs().empty());
      EXPECT_EQ(st.lookups, 0u);
    }
  }
}

}  // namespace
}  // namespace voxcd
