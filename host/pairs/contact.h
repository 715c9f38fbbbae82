// A pair test's contacts (public: <voxcd/voxcd.h>): each contact, and a pair's result with its counts.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace voxcd {

// One contact: a shell point of one object that lies in a voxel of the other whose state is in the hit mask, or
// (distance device) where the other's interpolated distance is at most the margin.
struct Contact {
  uint32_t pair = 0;          // index of the request
  bool a_in_b = true;         // the shell is A's and the voxmap B's (else the reverse)
  uint32_t point = 0;         // index of the shell point in its object's shell
  Eigen::Vector3d position;   // the shell point, world coordinates
  // Its object's outward surface normal there, world coordinates. Distance device: the other object's field
  // gradient there, negated and normalised (the direction that outward normal has at a contact; the shell's own
  // normal where the gradient vanishes).
  Eigen::Vector3d normal;
  std::array<uint32_t, 3> voxel = {0, 0, 0};  // the voxel (cell) of the other object's voxmap it lies in
  uint8_t state = 0;          // that voxel's state (0 on a distance device)
  // Penetration into the other object, world units: the voxel estimate (docs/pairs.md); on a distance device the
  // interpolated distance negated (positive inside, negative for a contact within the margin outside).
  double depth = 0;
};

// The result of one pair query, as collide() returns it (host/api/collide.h).
struct Contacts {
  std::vector<Contact> contacts;  // A in B first, then B in A; each in ascending point order
  uint32_t hits = 0;              // over both directions (COUNT: the count; FIRST: up to 1 per direction)
  uint64_t lookups = 0;           // shell points submitted
  // Device cycles of the pair's jobs, where the backend models them (FrameStats::device_cycles, Python's
  // "device_cycles"; `cycles` before).
  uint64_t device_cycles = 0;
};
// The same type by the name the library's pair tests use (host/pairs/).
using PairResult = Contacts;

}  // namespace voxcd
