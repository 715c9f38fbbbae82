// Internal to formats/ply.cpp: a PLY file's header, and the check that its counts fit the file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace voxcd::formats {

struct PlyProperty {
  std::string name, type, count_type;  // count_type set: a list (its length's type, then the values' type)
  size_t size = 0, count_size = 0;     // bytes of a value and of a list's length
};
struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> props;
};
// A PLY header as check_ply accepted it.
struct PlyHeader {
  std::string format;
  std::vector<PlyElement> elements;
  size_t body = 0;  // the first byte after the end_header line
};

// The bytes of a PLY scalar type, 0 for an unknown name.
size_t ply_type_size(const std::string& t);

// assimp 5.2's PLY reader allocates and loops for the counts a file declares (elements, and each list's length)
// before it finds that the data ends: a count of 10^13 hangs it or exhausts memory. And it reads headers loosely
// (a misspelt format or property line still loads, with counts read from the wrong bytes). So the header must be
// exactly what the PLY format allows (ply, format ascii|binary_little_endian|binary_big_endian, comment, obj_info,
// element NAME COUNT, property TYPE NAME, property list TYPE TYPE NAME, end_header), and the body is walked as it
// describes: any count larger than what is left of the file can hold is refused (MeshError naming `path`). `text`:
// the whole file, whose first line is "ply" and which has an end_header line (checked before).
PlyHeader check_ply(const std::string& path, const std::string& text);

}  // namespace voxcd::formats
