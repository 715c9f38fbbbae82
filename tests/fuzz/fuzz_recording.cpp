// Fuzz target: the recording reader (parse_recording, what voxcd view and read_recording read). RecordError is the
// documented error and must start with the name given; a recording that reads holds what its records promise: every
// frame has a pose per body, a flag per pair, and contacts on touching pairs only.
#include <string>

#include "voxcd/host/scene/record.h"
#include "tests/fuzz/fuzz_common.h"

using namespace voxcd;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string name = "fuzz.vxr";
  Recording r;
  try {
    r = parse_recording(std::string(reinterpret_cast<const char*>(data), size), name);
  } catch (const RecordError& e) {
    fuzz::expect_prefix(e.what(), name + ":", "RecordError");
    return 0;
  }
  if (r.truncated) fuzz::expect_prefix(r.note, name + ": truncated at byte", "the truncation note");
  for (const RecordedFrame& f : r.frames) {
    if (f.positions.size() != r.body_types.size() || f.rotations.size() != r.body_types.size() ||
        f.pair_flags.size() != f.pairs.size())
      fuzz::finding(name + ": a frame's poses or flags do not match its bodies or pairs");
    for (const RecordedContact& c : f.contacts)
      if (c.pair >= f.pairs.size() || !(f.pair_flags[c.pair] & kPairTouching))
        fuzz::finding(name + ": a contact on a pair that is not touching");
  }
  return 0;
}
