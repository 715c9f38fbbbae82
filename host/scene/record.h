// Recordings of a run (docs/view.md gives the byte layout): the object types once (their mesh, or their voxmap's
// surface, and their point shell), each body's type, then per frame every body's pose, the broadphase pairs with
// which of them were tested and touching, every contact, and the frame's statistics. Written as the run goes, a
// whole record at a time, so a reader sees whole frames while the file grows; `voxcd view` replays it.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/scene/errors.h"
#include "voxcd/host/scene/scene.h"

namespace voxcd {

// The format version this library writes and reads; a file of another version is refused.
constexpr uint32_t kRecordVersion = 1;

// An object type as recorded: bounds and grid in its own frame, the surface it is drawn with and its point shell.
struct RecordedType {
  std::string name;
  double voxel = 0;
  std::array<double, 3> origin = {0, 0, 0};  // the voxmap's corner
  std::array<uint32_t, 3> dims = {0, 0, 0};  // the voxmap's voxels per axis
  std::array<double, 3> lo = {0, 0, 0}, hi = {0, 0, 0}, centre = {0, 0, 0};
  double radius = 0;
  bool from_mesh = true;  // the surface is the mesh the type was voxelised from; false: its voxmap's surface
  std::vector<std::array<float, 3>> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<std::array<float, 3>> shell_points, shell_normals;
};

// A contact as recorded: `pair` indexes the frame's broadphase pairs; a_in_b: the shell was the first body's.
struct RecordedContact {
  uint32_t pair = 0;
  bool a_in_b = true;
  uint32_t point = 0;  // the shell point's index in its type's shell
  std::array<float, 3> position = {0, 0, 0}, normal = {0, 0, 0};
  float depth = 0;
};

// Bits of RecordedFrame::pair_flags.
constexpr uint8_t kPairTested = 1, kPairTouching = 2;

struct RecordedFrame {
  FrameStats stats;  // every field as the run returned it
  // Per body, world = rotation * local + position: the run's doubles rounded to float; rotation w, x, y, z.
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<float, 4>> rotations;
  std::vector<BodyPair> pairs;       // the broadphase's, in its order
  std::vector<uint8_t> pair_flags;   // per pair: kPairTested, kPairTouching
  std::vector<RecordedContact> contacts;
};

struct Recording {
  uint32_t version = kRecordVersion;
  std::string run;  // the run's settings as a JSON object (docs/view.md lists its keys)
  std::vector<RecordedType> types;
  std::vector<uint32_t> body_types;  // per body, its index in `types`
  std::vector<RecordedFrame> frames;
  // Set when the file ends inside a record (a run still writing, or one cut short): `note` says where and how many
  // whole frames were read.
  bool truncated = false;
  std::string note;
};

// Writes a recording as a Simulation runs: the types and bodies when made, then one record per frame() call,
// flushed whole, so that a reader sees whole frames while the run goes on. RecordError naming the file on any
// write failure.
class RecordWriter {
 public:
  // `run`: the run's settings as a JSON object ("{}" when there is nothing to say).
  RecordWriter(const std::string& path, const Simulation& sim, const std::string& run = "{}");
  ~RecordWriter();
  RecordWriter(const RecordWriter&) = delete;
  RecordWriter& operator=(const RecordWriter&) = delete;
  // The frame `sim` has just stepped: poses, pairs, contacts and `st`.
  void frame(const Simulation& sim, const FrameStats& st);
  uint64_t bytes() const { return bytes_; }    // written so far
  uint64_t frames() const { return frames_; }  // frame records written so far
  void close();                                // flushes and closes; RecordError when that fails

 private:
  void put(uint32_t kind, const std::string& payload);
  std::string path_;
  std::FILE* f_ = nullptr;
  std::string buf_;
  uint64_t bytes_ = 0, frames_ = 0;
};

// Reads a whole recording, up to its last whole frame (Recording::truncated and note when it ends inside a record).
// RecordError naming the file and byte for a file that is not a recording, of another version, cut short before
// its first frame, or whose records do not check (CRC, sizes, indices).
Recording read_recording(const std::string& path);
// The same from bytes in memory; `name` names them in messages.
Recording parse_recording(const std::string& bytes, const std::string& name);

// True when the file starts with a recording's magic (whatever its version).
bool is_recording(const std::string& path);

// The run record of a `voxcd simulate` run: its settings as resolved (docs/view.md lists the keys).
struct SimulationSummary;
std::string record_settings(const SimulationSummary& s);

// The recorded form of a type: its mesh in its own frame when it has one, else its voxmap's surface.
RecordedType recorded_type(const ObjectType& t);

}  // namespace voxcd
