// The viewer's pair page (`voxcd view A B`): two objects, B at a pose in A's frame, and their contacts, recomputed by
// the tool whenever the page changes the pose (docs/view.md).
#pragma once

#include <array>
#include <memory>
#include <stdexcept>
#include <string>

#include "voxcd/host/pairs/collide.h"

namespace voxcd::view {

// B's pose in A's frame as the page edits it: translation, then degrees about x, y and z.
using PairPose = std::array<double, 6>;

// Any pose `voxcd pair --pose` takes (parse_pose: 3, 6, 7, 12 or 16 numbers, or the tool's JSON), as the page's six
// numbers: 3 and 6 numbers as given, the others with their rotation in degrees (euler_degrees). std::invalid_argument
// saying what is wrong with `s` ("'x' in '1,x,3' is not a number", "'1,2' has 2 numbers; give 3 (tx,ty,tz), ...").
PairPose parse_pair_pose(const std::string& s);

struct PairViewOptions {
  double voxel = 0;          // 0: the larger mesh's longest side / resolution
  uint32_t resolution = 32;
  int distance_bits = 0;
  double band = 4.0;
  double margin = 0;
  std::string backend = "cpu";
  bool both_directions = true;  // as `voxcd pair`: both shells in the other's voxmap
};

class PairView {
 public:
  // Loads both objects as `voxcd pair` does. MeshError, ObjectFileError, CapacityError as loading throws them.
  PairView(const std::string& a, const std::string& b, const PairViewOptions& opt);
  // A pose that puts B beside A, their bounding spheres overlapping by a quarter.
  PairPose default_pose() const;
  // The page's data: {"kind": "pair", "a": ..., "b": ..., "result": contacts_json(pose)}.
  std::string page_json(const PairPose& pose);
  // The contacts at `pose`: {"pose": [...], "hits", "lookups", "device_cycles", "contacts": [{shell, point,
  // position, normal, depth}]}; RangeError for a pose that does not fit the fixed-point formats.
  std::string contacts_json(const PairPose& pose);

 private:
  std::string a_name_, b_name_;
  std::shared_ptr<ObjectType> a_, b_;
  std::unique_ptr<PairCollider> collider_;
  PairOptions opt_;
  std::string backend_;
};

}  // namespace voxcd::view
