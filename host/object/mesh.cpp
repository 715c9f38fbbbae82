#include "voxcd/host/object/mesh.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <unordered_map>

namespace voxcd {

namespace {

std::string fmt_point(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s << std::setprecision(9) << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

std::string lower_ext(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

Mesh load_assimp(const std::string& path) {
  Assimp::Importer imp;
  // Only positions matter: dropping the other components lets equal positions merge.
  imp.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                                     aiComponent_COLORS | aiComponent_TEXCOORDS |
                                                     aiComponent_BONEWEIGHTS | aiComponent_MATERIALS);
  // Faces are checked before any post-processing: a damaged file (a truncated PLY declares faces it does not
  // hold, and assimp gives them no vertices) would otherwise reach Triangulate, whose assertion aborts.
  const aiScene* raw = imp.ReadFile(path, aiProcess_ValidateDataStructure);
  if (!raw) throw MeshError(path + ": cannot load: " + imp.GetErrorString());
  for (unsigned i = 0; i < raw->mNumMeshes; ++i) {
    const aiMesh* am = raw->mMeshes[i];
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices == 0 || !face.mIndices)
        throw MeshError(path + ": face " + std::to_string(f) + " of mesh " + std::to_string(i) +
                        " has no vertices (is the file truncated?)");
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= am->mNumVertices)
          throw MeshError(path + ": face " + std::to_string(f) + " of mesh " + std::to_string(i) +
                          " has vertex index " + std::to_string(face.mIndices[k]) + " out of range (" +
                          std::to_string(am->mNumVertices) + " vertices)");
    }
  }
  const aiScene* sc = imp.ApplyPostProcessing(aiProcess_RemoveComponent | aiProcess_Triangulate |
                                              aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (!sc) throw MeshError(path + ": cannot load: " + imp.GetErrorString());
  Mesh m;
  m.name = path;
  std::vector<Eigen::Vector3d> points;  // of meshes without triangles: a point cloud when there are no triangles
  for (unsigned i = 0; i < sc->mNumMeshes; ++i) {
    const aiMesh* am = sc->mMeshes[i];
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) {
      for (unsigned v = 0; v < am->mNumVertices; ++v)
        points.emplace_back(am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z);
      continue;
    }
    const uint32_t base = uint32_t(m.vertices.size());
    for (unsigned v = 0; v < am->mNumVertices; ++v)
      m.vertices.emplace_back(am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z);
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines sorted into their own meshes are not surface
      m.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  if (m.triangles.empty()) m.vertices = std::move(points);
  return m;
}

// The vertices of a Wavefront OBJ file that has vertex lines and no face lines (assimp finds no mesh in it):
// a point cloud. Returns false when the file has faces or no vertices.
bool read_obj_points(const std::string& path, Mesh& m) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::vector<Eigen::Vector3d> pts;
  size_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key == "f" || key == "l" || key == "p") return false;
    if (key != "v") continue;
    double x, y, z;
    if (!(ls >> x >> y >> z))
      throw MeshError(path + ":" + std::to_string(lineno) + ": a vertex line needs three numbers");
    pts.emplace_back(x, y, z);
  }
  if (pts.empty()) return false;
  m.name = path;
  m.vertices = std::move(pts);
  m.triangles.clear();
  return true;
}

}  // namespace

void Mesh::bounds(Eigen::Vector3d& lo, Eigen::Vector3d& hi) const {
  lo = Eigen::Vector3d::Constant(HUGE_VAL);
  hi = Eigen::Vector3d::Constant(-HUGE_VAL);
  if (points_only()) {
    for (const auto& p : vertices)
      if (p.allFinite()) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    return;
  }
  for (const auto& t : triangles)
    for (uint32_t v : t) {
      lo = lo.cwiseMin(vertices[v]);
      hi = hi.cwiseMax(vertices[v]);
    }
}

double Mesh::volume() const {
  // Relative to the first vertex, so that far-from-origin meshes keep their precision.
  if (triangles.empty()) return 0;
  const Eigen::Vector3d o = vertices[triangles[0][0]];
  double v = 0;
  for (size_t t = 0; t < triangles.size(); ++t)
    v += (corner(t, 0) - o).dot((corner(t, 1) - o).cross(corner(t, 2) - o));
  return v / 6;
}

double Mesh::area() const {
  double a = 0;
  for (size_t t = 0; t < triangles.size(); ++t) a += (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0)).norm();
  return a / 2;
}

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
    // assimp's RAW variants: a colour before the corners (r g b, or r g b a), or a texture name after them.
    if (tok.size() == 10 || tok.size() == 12 || tok.size() == 13) {
      bool all = true;
      for (const std::string& w : tok) {
        char* end = nullptr;
        std::strtod(w.c_str(), &end);
        all = all && end != w.c_str() && *end == '\0';
      }
      if (tok.size() == 10 && !all) {
        char* end = nullptr;
        std::strtod(tok[9].c_str(), &end);
        if (end == tok[9].c_str() || *end != '\0') tok.pop_back();  // a texture name
      } else if (tok.size() != 10 && all) {
        tok.erase(tok.begin(), tok.begin() + long(tok.size() - 9));  // a colour
      }
    }
    double v[9];
    bool numeric = true;
    for (size_t i = 0; i < tok.size() && i < 9; ++i) {
      const char* s = tok[i].c_str();
      char* end = nullptr;
      errno = 0;
      v[i] = std::strtod(s, &end);
      if (end == s || *end != '\0' || errno == ERANGE) numeric = false;
    }
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

size_t weld(Mesh& m) {
  struct Hash {
    size_t operator()(const Eigen::Vector3d& p) const {
      size_t h = 1469598103934665603ull;
      for (int i = 0; i < 3; ++i) {
        double d = p[i] == 0 ? 0.0 : p[i];  // -0 and +0 are the same point
        uint64_t b;
        std::memcpy(&b, &d, 8);
        h = (h ^ b) * 1099511628211ull;
        h ^= h >> 29;
      }
      return h;
    }
  };
  struct Eq {
    bool operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const { return a == b; }
  };
  std::unordered_map<Eigen::Vector3d, uint32_t, Hash, Eq> index;
  index.reserve(m.vertices.size());
  std::vector<Eigen::Vector3d> out;
  std::vector<uint32_t> remap(m.vertices.size(), UINT32_MAX);
  size_t used = 0;
  for (auto& t : m.triangles)
    for (uint32_t& v : t) {
      if (v >= m.vertices.size())
        throw MeshError(m.name + ": triangle " + std::to_string(&t - m.triangles.data()) + " has vertex index " +
                        std::to_string(v) + " out of range (" + std::to_string(m.vertices.size()) + " vertices)");
      if (remap[v] == UINT32_MAX) {
        ++used;
        const Eigen::Vector3d& p = m.vertices[v];
        if (!p.allFinite()) {
          remap[v] = uint32_t(out.size());  // kept apart; validate() names it
          out.push_back(p);
        } else {
          auto [it, fresh] = index.emplace(p, uint32_t(out.size()));
          if (fresh) out.push_back(p);
          remap[v] = it->second;
        }
      }
      v = remap[v];
    }
  m.vertices = std::move(out);
  return used - m.vertices.size();
}

void validate(Mesh& m, MeshReport* report) {
  const std::string& n = m.name;
  if (m.triangles.empty()) throw MeshError(n + ": the mesh has no triangles");
  auto tri_name = [&](size_t t) { return "triangle " + std::to_string(t); };
  for (size_t t = 0; t < m.size(); ++t) {
    const auto& tr = m.triangles[t];
    for (uint32_t v : tr) {
      if (v >= m.vertices.size())
        throw MeshError(n + ": " + tri_name(t) + " has vertex index " + std::to_string(v) + " out of range");
      if (!m.vertices[v].allFinite())
        throw MeshError(n + ": " + tri_name(t) + " has a vertex that is not a finite number " +
                        fmt_point(m.vertices[v]));
    }
    if (tr[0] == tr[1] || tr[1] == tr[2] || tr[0] == tr[2])
      throw MeshError(n + ": " + tri_name(t) + " is degenerate (a repeated vertex at " +
                      fmt_point(m.vertices[tr[0] == tr[1] || tr[0] == tr[2] ? tr[0] : tr[1]]) + ")");
    const Eigen::Vector3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
    const double l2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if ((b - a).cross(c - a).squaredNorm() <= 1e-26 * l2 * l2)
      throw MeshError(n + ": " + tri_name(t) + " is degenerate (zero area: " + fmt_point(a) + " " + fmt_point(b) +
                      " " + fmt_point(c) + " are collinear)");
  }
  // Every undirected edge must be used exactly twice, once in each direction.
  struct Use {
    uint64_t key;  // lo << 32 | hi
    uint32_t tri;
    bool forward;  // lo -> hi in the triangle's winding
  };
  std::vector<Use> uses;
  uses.reserve(3 * m.size());
  for (size_t t = 0; t < m.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      const uint32_t lo = std::min(a, b), hi = std::max(a, b);
      uses.push_back({uint64_t(lo) << 32 | hi, uint32_t(t), a < b});
    }
  std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
    return x.key != y.key ? x.key < y.key : x.tri < y.tri;
  });
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    const uint32_t lo = uint32_t(uses[i].key >> 32), hi = uint32_t(uses[i].key);
    if (j - i == 2 && uses[i].forward != uses[i + 1].forward) {
      i = j;
      continue;
    }
    // Only a bad edge is worth formatting (formatting every edge would dominate the time of a large mesh).
    const std::string edge = "edge " + fmt_point(m.vertices[lo]) + "-" + fmt_point(m.vertices[hi]) +
                             " (vertices " + std::to_string(lo) + ", " + std::to_string(hi) + ")";
    std::string tris;
    for (size_t k = i; k < j && k < i + 4; ++k) tris += (k > i ? ", " : "") + std::to_string(uses[k].tri);
    if (j - i == 1)
      throw MeshError(n + ": the mesh is open: " + edge + " belongs to triangle " + tris + " only");
    if (j - i > 2)
      throw MeshError(n + ": the mesh is not manifold: " + edge + " is shared by " + std::to_string(j - i) +
                      " triangles (" + tris + (j - i > 4 ? ", ..." : "") + ")");
    if (uses[i].forward == uses[i + 1].forward)
      throw MeshError(n + ": inconsistent orientation: " + edge + " runs the same way in triangles " + tris);
    i = j;
  }
  bool flipped = false;
  if (m.volume() < 0) {
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    flipped = true;
  }
  if (report) {
    report->vertices = m.vertices.size();
    report->triangles = m.triangles.size();
    report->flipped = flipped;
  }
}

namespace {

// The bytes of a PLY scalar type, 0 for an unknown name.
size_t ply_type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

// assimp 5.2's PLY reader allocates and loops for the counts a file declares (elements, and each list's length)
// before it finds that the data ends: a count of 10^13 hangs it or exhausts memory. And it reads headers loosely
// (a misspelt format or property line still loads, with counts read from the wrong bytes). So the header must be
// exactly what the PLY format allows (ply, format ascii|binary_little_endian|binary_big_endian, comment, obj_info,
// element NAME COUNT, property TYPE NAME, property list TYPE TYPE NAME, end_header), and the body is walked as it
// describes: any count larger than what is left of the file can hold is refused. `text`: the whole file, whose
// first line is "ply" and which has an end_header line (checked before).
// A PLY header as check_ply accepted it.
struct PlyProperty {
  std::string name, type, count_type;  // count_type set: a list (its length's type, then the values' type)
  size_t size = 0, count_size = 0;     // bytes of a value and of a list's length
};
struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> props;
};
struct PlyHeader {
  std::string format;
  std::vector<PlyElement> elements;
  size_t body = 0;  // the first byte after the end_header line
};

PlyHeader check_ply(const std::string& path, const std::string& text) {
  using Property = PlyProperty;
  using Element = PlyElement;
  PlyHeader h;
  std::vector<Element>& elements = h.elements;
  std::string& format = h.format;
  size_t pos = 0;
  bool ended = false;
  for (int number = 1; pos < text.size() && !ended; ++number) {
    size_t next = text.find('\n', pos);
    if (next == std::string::npos) next = text.size();
    const std::string raw = text.substr(pos, next - pos);
    std::istringstream line(raw);
    pos = next + 1;
    auto bad = [&](const std::string& why) {
      std::string shown = raw.substr(0, 60);
      for (char& c : shown)
        if (!std::isprint(uint8_t(c))) c = '?';
      throw MeshError(path + ": line " + std::to_string(number) + " of the PLY header, '" + shown + "': " + why);
    };
    std::string word, rest;
    line >> word;
    // (A carriage return may end a line; inside one, assimp takes it as a line break and reads another header.)
    const size_t cr = raw.find('\r');
    if (cr != std::string::npos && cr + 1 != raw.size()) bad("a carriage return inside the line");
    if (word != "comment" && word != "obj_info")
      for (char c : raw)
        if ((uint8_t(c) < 0x20 && c != '\t' && c != '\r') || uint8_t(c) >= 0x7f)
          bad("a control or non-ASCII character outside a comment");
    if (number == 1 || word.empty() || word == "comment" || word == "obj_info") {
      continue;
    } else if (word == "format") {
      std::string version;
      line >> format >> version;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        bad("the format is not ascii, binary_little_endian or binary_big_endian");
    } else if (word == "element") {
      Element e;
      std::string count;
      line >> e.name >> count;
      if (e.name.empty() || count.empty() ||
          !std::all_of(count.begin(), count.end(), [](char c) { return std::isdigit(uint8_t(c)); }))
        bad("an element needs a name and a count");
      e.count = count.size() > 18 ? uint64_t(1) << 62 : std::stoull(count);
      elements.push_back(e);
    } else if (word == "property") {
      if (elements.empty()) bad("a property before any element");
      std::string type, name;
      line >> type;
      Property p;
      if (type == "list") {
        std::string ct, it;
        line >> ct >> it;
        p.count_type = ct;
        p.type = it;
        p.count_size = ply_type_size(ct);
        p.size = ply_type_size(it);
        if (!p.count_size || !p.size) bad("a list property needs two known types (char .. double, int8 .. float64)");
      } else {
        p.type = type;
        p.size = ply_type_size(type);
        if (!p.size) bad("unknown property type '" + type + "'");
      }
      line >> name;
      if (name.empty()) bad("a property needs a name");
      p.name = name;
      elements.back().props.push_back(p);
    } else if (word == "end_header") {
      ended = true;
    } else if (!elements.empty()) {
      // Before the first element, a line that is no PLY keyword is taken as a comment (old exporters, Blender 2.4's
      // among them, wrote "Created by ..." without the word); after it, it would change how the body is read.
      bad("not a PLY header line (ply, format, comment, obj_info, element, property, end_header)");
    }
  }
  if (!ended) throw MeshError(path + ": the PLY header has no end_header line (is the file truncated?)");
  if (format.empty()) throw MeshError(path + ": the PLY header has no format line");
  pos = std::min(pos, text.size());  // an end_header line without a newline: no body
  h.body = pos;
  const bool ascii = format == "ascii";
  const bool big = format == "binary_big_endian";
  auto refuse = [&](const Element& e, uint64_t count, const char* what, uint64_t room, const char* unit) {
    const std::string n = count >= uint64_t(1) << 62 ? "over 4e18" : std::to_string(count);
    throw MeshError(path + ": the PLY file declares " + n + " " + what + " in element '" + e.name +
                    "', more than the " + std::to_string(room) + " " + unit +
                    " can hold (is the file truncated or damaged?)");
  };
  if (ascii) {
    // assimp reads an ASCII element item from one line: an element needs a line an item, and a list's length
    // (the leading digits of its word, as assimp reads it) at most the words left on its line.
    uint64_t lines = 0;
    for (size_t i = pos; i < text.size(); ++i) {
      const uint8_t c = uint8_t(text[i]);
      lines += c == '\n';
      // assimp reads the body as C strings and skips what it does not know differently from a plain word split.
      if ((c < 0x20 && c != '\n' && c != '\r' && c != '\t') || c >= 0x7f)
        throw MeshError(path + ": byte " + std::to_string(i) + " of the ASCII PLY file is a control or non-ASCII " +
                        "character (" + std::to_string(c) + ")");
    }
    if (pos < text.size() && text.back() != '\n') ++lines;
    size_t at = pos;
    std::vector<std::pair<size_t, size_t>> words;  // of the current line, [begin, end) in text
    for (const Element& e : elements) {
      if (e.count > lines) refuse(e, e.count, "items", lines, "lines after them");
      lines -= e.count;
      for (uint64_t k = 0; k < e.count && at < text.size(); ++k) {
        size_t eol = text.find('\n', at);
        if (eol == std::string::npos) eol = text.size();
        const size_t cr = text.find('\r', at);
        if (cr != std::string::npos && cr + 1 < eol)
          throw MeshError(path + ": a carriage return inside item " + std::to_string(k) + " of element '" + e.name +
                          "' (assimp would read it as a line break)");
        words.clear();
        for (size_t i = at; i < eol;) {
          while (i < eol && std::isspace(uint8_t(text[i]))) ++i;
          const size_t b = i;
          while (i < eol && !std::isspace(uint8_t(text[i]))) ++i;
          if (i > b) words.emplace_back(b, i);
        }
        at = eol + 1;
        size_t w = 0;
        for (const Property& p : e.props) {
          if (w >= words.size()) break;
          if (!p.count_size) {
            ++w;
            continue;
          }
          const auto [b, end] = words[w++];
          uint64_t n = 0;
          for (size_t i = b; i < end && std::isdigit(uint8_t(text[i])); ++i)
            n = std::min<uint64_t>(n * 10 + uint64_t(text[i] - '0'), uint64_t(1) << 62);
          if (n > words.size() - w) refuse(e, n, "list values", words.size() - w, "words left on its line");
          w += size_t(n);
        }
      }
    }
    return h;
  }
  uint64_t at = pos;
  const uint64_t size = text.size();
  for (const Element& e : elements) {
    uint64_t least = 0;  // the bytes of one item, its lists empty (an item of no property counts as one byte)
    for (const Property& p : e.props) least += p.count_size ? p.count_size : p.size;
    if (e.count > (size - at) / std::max<uint64_t>(least, 1))
      refuse(e, e.count, "items", size - at, "bytes after them");
    for (uint64_t k = 0; k < e.count; ++k)
      for (const Property& p : e.props) {
        if (!p.count_size) {
          at += p.size;
          if (at > size) return h;
          continue;
        }
        if (at + p.count_size > size) return h;
        uint64_t n = 0;
        for (size_t i = 0; i < p.count_size; ++i) {
          const uint64_t byte = uint8_t(text[size_t(at + (big ? i : p.count_size - 1 - i))]);
          n = n << 8 | byte;
        }
        at += p.count_size;
        if (n > (size - at) / p.size) refuse(e, n, "list values", size - at, "bytes after them");
        at += n * p.size;
      }
  }
  return h;
}


// The value of one binary PLY scalar of `size` bytes at p: signed, unsigned or floating (`type` its name).
double ply_binary_value(const char* p, size_t size, const std::string& type, bool big) {
  uint64_t bits = 0;
  for (size_t i = 0; i < size; ++i) bits |= uint64_t(uint8_t(p[big ? size - 1 - i : i])) << (8 * i);
  if (type == "float" || type == "float32") {
    const uint32_t b = uint32_t(bits);
    float f;
    std::memcpy(&f, &b, 4);
    return f;
  }
  if (type == "double" || type == "float64") {
    double d;
    std::memcpy(&d, &bits, 8);
    return d;
  }
  const bool is_signed = type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" ||
                         type == "int32";
  if (is_signed && size < 8 && (bits >> (8 * size - 1)) & 1)
    return double(int64_t(bits | (~uint64_t(0) << (8 * size))));
  return double(bits);
}

// A PLY file read by this program, not by assimp (whose reader hangs or runs out of memory on damaged files: the
// fuzz_mesh findings in docs/robustness.md). check_ply has accepted the header and the counts. The element
// `vertex` gives the points (its properties x, y, z), the element `face` the polygons (its list vertex_indices or
// vertex_index), split into triangles as fans; every other element and property is read and skipped. ASCII: an
// item a line, as the format is written in practice.
Mesh read_ply(const std::string& path, const std::string& text) {
  const PlyHeader h = check_ply(path, text);
  using Prop = PlyProperty;
  using Elem = PlyElement;
  const std::vector<Elem>& elems = h.elements;
  const std::string& format = h.format;
  const size_t pos = h.body;
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  const Elem* vertex = nullptr;
  const Elem* face = nullptr;
  int px = -1, py = -1, pz = -1, pf = -1;
  for (const Elem& e : elems) {
    if (e.name == "vertex" && !vertex) {
      vertex = &e;
      for (size_t i = 0; i < e.props.size(); ++i) {
        if (!e.props[i].count_type.empty()) continue;
        if (e.props[i].name == "x") px = int(i);
        if (e.props[i].name == "y") py = int(i);
        if (e.props[i].name == "z") pz = int(i);
      }
    }
    if (e.name == "face" && !face) {
      face = &e;
      for (size_t i = 0; i < e.props.size(); ++i)
        if (!e.props[i].count_type.empty() &&
            (e.props[i].name == "vertex_indices" || e.props[i].name == "vertex_index"))
          pf = int(i);
    }
  }
  if (!vertex || px < 0 || py < 0 || pz < 0)
    throw MeshError(path + ": the PLY file has no element 'vertex' with properties x, y and z");
  // No face element: a point cloud.
  if (face && pf < 0) throw MeshError(path + ": the PLY file's element 'face' has no list vertex_indices");
  Mesh m;
  m.name = path;
  m.vertices.reserve(size_t(vertex->count));
  std::vector<uint64_t> poly;   // every face's indices, one after the other
  std::vector<uint32_t> sizes;  // and each face's count
  const size_t size = text.size();
  size_t at = pos;  // binary: the next byte; ASCII: the start of the next line
  for (const Elem& e : elems) {
    const bool is_vertex = &e == vertex, is_face = &e == face;
    std::vector<std::string> words;
    for (uint64_t k = 0; k < e.count; ++k) {
      const std::string where = "item " + std::to_string(k) + " of element '" + e.name + "'";
      double xyz[3] = {0, 0, 0};
      size_t w = 0;
      if (ascii) {
        if (at >= size) throw MeshError(path + ": the file ends before " + where + " (is the file truncated?)");
        size_t eol = text.find('\n', at);
        if (eol == std::string::npos) eol = size;
        std::istringstream line(text.substr(at, eol - at));
        at = eol + 1;
        words.clear();
        for (std::string word; line >> word;) words.push_back(word);
      }
      // The next value of the item: a word (ASCII) or `type`'s bytes (binary).
      auto value = [&](const std::string& type, const std::string& what) -> double {
        if (ascii) {
          if (w >= words.size())
            throw MeshError(path + ": " + where + " ends before its " + what + " (is the file truncated?)");
          const std::string& word = words[w++];
          char* end = nullptr;
          errno = 0;
          const double v = std::strtod(word.c_str(), &end);
          if (end == word.c_str() || *end != '\0')
            throw MeshError(path + ": " + where + ": its " + what + " '" + word.substr(0, 40) + "' is not a number");
          return v;
        }
        const size_t n = ply_type_size(type);
        if (at + n > size)
          throw MeshError(path + ": the file ends inside " + where + " (is the file truncated?)");
        const double v = ply_binary_value(text.data() + at, n, type, big);
        at += n;
        return v;
      };
      for (size_t i = 0; i < e.props.size(); ++i) {
        const Prop& pr = e.props[i];
        if (pr.count_type.empty()) {
          const double v = value(pr.type, "property " + pr.name);
          if (is_vertex && int(i) == px) xyz[0] = v;
          if (is_vertex && int(i) == py) xyz[1] = v;
          if (is_vertex && int(i) == pz) xyz[2] = v;
          continue;
        }
        const double count = value(pr.count_type, "list length of " + pr.name);
        if (!(count >= 0 && count == std::floor(count) && count <= double(size)))
          throw MeshError(path + ": " + where + ": the list length of " + pr.name + " is " + std::to_string(count));
        const bool indices = is_face && int(i) == pf;
        if (indices && count < 3)
          throw MeshError(path + ": face " + std::to_string(k) + " has " + std::to_string(uint64_t(count)) +
                          " vertices (a face needs at least 3)");
        for (uint64_t j = 0; j < uint64_t(count); ++j) {
          const double v = value(pr.type, "value " + std::to_string(j) + " of " + pr.name);
          if (!indices) continue;
          if (!(v >= 0 && v == std::floor(v) && v < double(vertex->count)))
            throw MeshError(path + ": face " + std::to_string(k) + " refers to vertex " + std::to_string(v) +
                            " of " + std::to_string(vertex->count));
          poly.push_back(uint64_t(v));
        }
        if (indices) sizes.push_back(uint32_t(count));
      }
      if (is_vertex) m.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
    }
  }
  size_t q = 0;
  for (uint32_t n : sizes) {
    for (uint32_t j = 1; j + 1 < n; ++j)
      m.triangles.push_back({uint32_t(poly[q]), uint32_t(poly[q + j]), uint32_t(poly[q + j + 1])});
    q += n;
  }
  return m;
}

}  // namespace

MeshReport prepare(Mesh& m) {
  MeshReport r;
  const size_t welded = weld(m);
  validate(m, &r);
  r.welded = welded;
  return r;
}

Mesh load_mesh(const std::string& path, MeshReport* report, const LoadOptions& opt) {
  Mesh m;
  if (lower_ext(path) == "raw") {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw MeshError(path + ": cannot open");
    m = parse_raw(in, path);
  } else {
    {
      std::ifstream probe(path, std::ios::binary);
      if (!probe) throw MeshError(path + ": cannot open");
      // assimp 5.2's PLY reader never returns from a header without an end_header line: one that is cut short, or
      // whose end_header runs on into other characters ("end_headerx", "xend_header"). Refuse those here.
      if (lower_ext(path) == "ply") {
        std::string head(1 << 16, '\0');
        probe.read(&head[0], std::streamsize(head.size()));
        head.resize(size_t(probe.gcount()));
        bool ended = false;
        for (size_t line = 0; line < head.size() && !ended;) {
          const size_t next = head.find('\n', line);
          const size_t word = head.find_first_not_of(" \t", line);
          ended = word != std::string::npos && word < next && head.compare(word, 10, "end_header") == 0 &&
                  (word + 10 == head.size() || std::isspace(static_cast<unsigned char>(head[word + 10])));
          line = next == std::string::npos ? head.size() : next + 1;
        }
        // assimp takes the magic word in any case ("pLy" too).
        const bool ply = head.size() >= 3 && std::tolower(uint8_t(head[0])) == 'p' &&
                         std::tolower(uint8_t(head[1])) == 'l' && std::tolower(uint8_t(head[2])) == 'y';
        if (ply && !ended)
          throw MeshError(path + ": the PLY header has no end_header line in its first " +
                          std::to_string(head.size()) + " bytes (is the file truncated?)");
        if (!ply) throw MeshError(path + ": not a PLY file (it does not start with 'ply')");
        probe.clear();
        probe.seekg(0);
        const std::string whole((std::istreambuf_iterator<char>(probe)), std::istreambuf_iterator<char>());
        m = read_ply(path, whole);
      }
      // assimp's OFF reader allocates for the counts its header declares before reading them: refuse counts the file
      // cannot hold (a vertex takes at least 5 bytes, "0 0 0", a face at least 7, "3 0 1 2").
      if (lower_ext(path) == "off") {
        probe.clear();
        probe.seekg(0, std::ios::end);
        const uint64_t size = uint64_t(std::max<std::streamoff>(probe.tellg(), 0));
        probe.seekg(0);
        std::string text(size_t(std::min<uint64_t>(size, 4096)), '\0');
        probe.read(&text[0], std::streamsize(text.size()));
        std::istringstream in(text);
        std::string tok;
        in >> tok;  // OFF, COFF, NOFF...: digits glued to the keyword are the first count to assimp
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
          // As assimp reads a count: the digits at the start of the word, whatever follows them ("12x" is 12).
          if (!std::isdigit(static_cast<unsigned char>(tok[0]))) break;
          uint64_t v = 0;
          for (size_t i = 0; i < tok.size() && std::isdigit(static_cast<unsigned char>(tok[i])); ++i)
            v = std::min<uint64_t>(v * 10 + uint64_t(tok[i] - '0'), uint64_t(1) << 60);
          n.push_back(v);
        }
        auto off_count = [](uint64_t v) {
          return v >= uint64_t(1) << 60 ? std::string("over 10^18") : std::to_string(v);
        };
        if (n.size() == 2 && (n[0] > size / 5 || n[1] > size / 7))
          throw MeshError(path + ": the OFF header declares " + off_count(n[0]) + " vertices and " + off_count(n[1]) +
                          " faces, more than its " + std::to_string(size) +
                          " bytes can hold (is the file truncated?)");
      }
    }
    if (lower_ext(path) == "obj") {
      try {
        m = load_assimp(path);
      } catch (const MeshError&) {
        if (!read_obj_points(path, m)) throw;
      }
    } else if (lower_ext(path) != "ply") {
      m = load_assimp(path);
    }
  }
  if (m.name.empty()) m.name = path;
  MeshReport r;
  if (opt.strict) {
    const size_t in_v = m.vertices.size(), in_t = m.triangles.size();
    r = prepare(m);
    r.input_vertices = in_v;
    r.input_triangles = in_t;
    r.closed = true;
  } else if (opt.repair) {
    r = repair(m);
  } else {
    r.input_vertices = r.vertices = m.vertices.size();
    r.input_triangles = r.triangles = m.triangles.size();
  }
  if (report) *report = r;
  return m;
}

}  // namespace voxcd
