// How a world runs (public: <voxcd/voxcd.h>): the definition a World is made from (host/api/world.h), after Box2D v3's
// b2WorldDef. A plain value with defaults, which the library's own runs extend with the scene and what is asked of the
// device (host/layers.txt lets host/scene include this header, and only this one, of host/api).
#pragma once

#include <string>

#include "voxcd/ref/types.h"

namespace voxcd {

struct WorldDef {
  double side = 100;                // bodies move in the cube [0, side]^3 and bounce off its walls
  bool walls = true;                // the cube's walls; false: open space (side then bounds nothing)
  bool response = true;             // the built-in response; false: touching pairs are found and reported only
  std::string broadphase = "grid";  // broadphase_names(): grid, the fastest at every N measured
  std::string backend = "cpu";      // device_backends()
  int lanes = 4;                    // lanes of the modelled device
  Mode mode = Mode::All;            // All: every contact; First: whether pairs touch; Count: hits only
  bool both_directions = true;      // also test B's shell in A's voxmap (as collide() and voxcd pair do)
  int distance_bits = 0;            // 4, 8, 16: a distance device (every object must carry such a field); 0: 2-bit
  double margin = 0;                // distance device: contacts within this distance outside, world units
  bool ccd = false;                 // continuous collision: no body passes through another (distance device)
  unsigned threads = 0;             // threads of every stage of a frame (0: every CPU); never changes the results
};

}  // namespace voxcd
