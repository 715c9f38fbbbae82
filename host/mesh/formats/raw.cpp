// The paper's RAW triangle format (and assimp's variants of it): nine numbers a line.
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>

#include "voxcd/host/mesh/formats/formats.h"

namespace voxcd {

namespace {

bool is_number(const std::string& w) {
  char* end = nullptr;
  std::strtod(w.c_str(), &end);
  return end != w.c_str() && *end == '\0';
}

// assimp's RAW variants: a colour before the corners (r g b, or r g b a), or a texture name after them.
void drop_colour_or_texture(std::vector<std::string>& tok) {
  if (tok.size() != 10 && tok.size() != 12 && tok.size() != 13) return;
  bool all = true;
  for (const std::string& w : tok) all = all && is_number(w);
  if (tok.size() == 10 && !all) {
    if (!is_number(tok[9])) tok.pop_back();  // a texture name
  } else if (tok.size() != 10 && all) {
    tok.erase(tok.begin(), tok.begin() + long(tok.size() - 9));  // a colour
  }
}

// The first nine words as numbers; false when one is not a number (or overflows).
bool read_numbers(const std::vector<std::string>& tok, double (&v)[9]) {
  bool numeric = true;
  for (size_t i = 0; i < tok.size() && i < 9; ++i) {
    const char* s = tok[i].c_str();
    char* end = nullptr;
    errno = 0;
    v[i] = std::strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE) numeric = false;
  }
  return numeric;
}

}  // namespace

Mesh parse_raw(std::istream& in, const std::string& name) {
  Mesh m;
  m.name = name;
  std::string line;
  size_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream ls(line);
    std::vector<std::string> tok;
    for (std::string w; ls >> w;) tok.push_back(w);
    drop_colour_or_texture(tok);
    double v[9];
    const bool numeric = read_numbers(tok, v);
    if (tok.size() == 1 && !numeric) continue;  // an object name
    const std::string where = name + ":" + std::to_string(lineno) + ": ";
    if (!numeric) throw MeshError(where + "expected nine numbers (x1 y1 z1 x2 y2 z2 x3 y3 z3), found '" + line + "'");
    if (tok.size() != 9)
      throw MeshError(where + "expected nine numbers per triangle, found " + std::to_string(tok.size()) +
                      (tok.size() < 9 ? " (truncated?)" : ""));
    const uint32_t base = uint32_t(m.vertices.size());
    for (int k = 0; k < 3; ++k) m.vertices.emplace_back(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
    m.triangles.push_back({base, base + 1, base + 2});
  }
  if (in.bad()) throw MeshError(name + ": read error");
  return m;
}

void write_raw(const Mesh& m, std::ostream& out) {
  out << std::setprecision(17);
  for (size_t t = 0; t < m.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = m.corner(t, k);
      out << p.x() << ' ' << p.y() << ' ' << p.z() << (k < 2 ? ' ' : '\n');
    }
  }
}

Mesh formats::read_raw(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshError(path + ": cannot open");
  return parse_raw(in, path);
}

}  // namespace voxcd
