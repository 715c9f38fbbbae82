// OFF: assimp's reader, behind a check of the counts its header declares.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <vector>

#include "voxcd/host/mesh/formats/formats.h"

namespace voxcd::formats {

namespace {

// The first two counts of an OFF header as assimp reads them: OFF, COFF, NOFF... then the digits at the start of each
// word, whatever follows them ("12x" is 12); digits glued to the keyword are the first count. Comments skipped.
std::vector<uint64_t> off_counts(const std::string& text) {
  std::istringstream in(text);
  std::string tok;
  in >> tok;
  std::vector<uint64_t> n;
  const size_t digits = tok.find_first_of("0123456789");
  bool glued = digits != std::string::npos;
  if (glued) tok = tok.substr(digits);
  while (n.size() < 2 && (glued || in >> tok)) {
    glued = false;
    if (tok[0] == '#') {
      std::getline(in, tok);
      continue;
    }
    if (!std::isdigit(static_cast<unsigned char>(tok[0]))) break;
    uint64_t v = 0;
    for (size_t i = 0; i < tok.size() && std::isdigit(static_cast<unsigned char>(tok[i])); ++i)
      v = std::min<uint64_t>(v * 10 + uint64_t(tok[i] - '0'), uint64_t(1) << 60);
    n.push_back(v);
  }
  return n;
}

std::string off_count(uint64_t v) { return v >= uint64_t(1) << 60 ? std::string("over 10^18") : std::to_string(v); }

}  // namespace

// assimp's OFF reader allocates for the counts its header declares before reading them: refuse counts the file
// cannot hold (a vertex takes at least 5 bytes, "0 0 0", a face at least 7, "3 0 1 2").
Mesh read_off(const std::string& path) {
  std::ifstream probe(path, std::ios::binary | std::ios::ate);
  if (!probe) throw MeshError(path + ": cannot open");
  const uint64_t size = uint64_t(std::max<std::streamoff>(probe.tellg(), 0));
  probe.seekg(0);
  std::string text(size_t(std::min<uint64_t>(size, 4096)), '\0');
  probe.read(&text[0], std::streamsize(text.size()));
  const std::vector<uint64_t> n = off_counts(text);
  if (n.size() == 2 && (n[0] > size / 5 || n[1] > size / 7))
    throw MeshError(path + ": the OFF header declares " + off_count(n[0]) + " vertices and " + off_count(n[1]) +
                    " faces, more than its " + std::to_string(size) + " bytes can hold (is the file truncated?)");
  return read_assimp(path);
}

}  // namespace voxcd::formats
