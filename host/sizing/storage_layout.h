// How a scene's object types lie in a device's memories, dense or sparse (docs/size.md, "Sparse or dense"): the
// words DeviceImage places for each type, a map's table and its bricks apart (a sparse device reads them at two
// ports, the table port and the brick port), and the memories that hold them with their block RAMs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "voxcd/host/object/object_type.h"
#include "voxcd/host/sizing/block_rams.h"
#include "voxcd/ref/config.h"

namespace voxcd {

// One type's words as DeviceImage places it on a device.
struct TypeWords {
  std::string name;
  bool map_sparse = false, shell_sparse = false;  // map_is_sparse, shell_is_sparse on that device
  uint64_t table = 0;    // what the table port reads: a dense map's words, or a sparse map's table
  uint64_t bricks = 0;   // what the brick port reads: a sparse map's bricks (0 for a dense map)
  uint64_t padding = 0;  // a distance map's words up to its bank boundaries
  uint64_t shell = 0;    // shell words: one a point, or a sparse shell's brick and origin words
  uint64_t map() const { return table + bricks + padding; }
};

// The types' words, each type's and their sums; the sums are the words of the image of all the types.
struct LayoutWords {
  std::vector<TypeWords> types;
  uint64_t table = 0, bricks = 0, padding = 0, shell = 0;
  uint64_t map() const { return table + bricks + padding; }
};

// The types placed one after another in one DeviceImage on cfg, each shell in the order the pair tests place it
// (shell_order), at the largest memories (SAW 24, MAW 28) so that any scene's types fit; CapacityError as
// DeviceImage::add throws it.
LayoutWords layout_words(const DeviceConfig& cfg, const std::vector<const ObjectType*>& types);

// A memory and what it takes on the FPGA targets, counted from its shape (memory_blocks, block_rams.h): an estimate,
// not a synthesis.
struct LayoutMemory {
  std::string what;
  MemoryShape shape;
  double ramb36 = 0;  // xilinx-7: RAMB36 (a RAMB18 a half), all `shape.count` of them
  double ebr = 0;     // iCE40: SB_RAM40_4K (4 kbit), all of them
};

// The memories as the RTL builds cfg (memory_shapes): the shell banks and the voxmap memories, on a sparse device
// each with two read ports holding tables and bricks together.
std::vector<LayoutMemory> built_memories(const DeviceConfig& cfg);

// The voxmap memories if the table port's words and the brick port's words each had memories of their own (one read
// port each, the fewest words a power of two that hold them, a copy per lane or cfg's banks, parity banks on a
// distance device): "table memory" (tables, dense maps and the padding) and "brick memory" (none without bricks).
// Not what the RTL builds (built_memories): the alternative of two simple dual-port memories.
std::vector<LayoutMemory> split_memories(const DeviceConfig& cfg, const LayoutWords& w);

// Where the block RAM counts come from, for reports.
inline constexpr const char* kBlockRamSource =
    "estimate: counted from the memories' shapes by host/sizing/block_rams.cpp, not synthesised (RAMB36 on xilinx-7, "
    "EBR = SB_RAM40_4K of 4 kbit on iCE40)";

}  // namespace voxcd
