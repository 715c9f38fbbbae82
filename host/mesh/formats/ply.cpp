// PLY, ASCII or binary, read by this program, not by assimp (whose reader hangs or runs out of memory on damaged
// files: the fuzz_mesh findings in docs/robustness.md). check_ply accepts the header and the counts first. The
// element `vertex` gives the points (its properties x, y, z), the element `face` the polygons (its list
// vertex_indices or vertex_index), split into triangles as fans; every other element and property is read and
// skipped. ASCII: an item a line, as the format is written in practice.
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "voxcd/host/mesh/formats/formats.h"
#include "voxcd/host/mesh/formats/ply_header.h"

namespace voxcd::formats {

namespace {

// The value of one binary PLY scalar of `size` bytes at p: signed, unsigned or floating (`type` its name).
double binary_value(const char* p, size_t size, const std::string& type, bool big) {
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
  if (is_signed && size < 8 && (bits >> (8 * size - 1)) & 1) return double(int64_t(bits | (~uint64_t(0) << (8 * size))));
  return double(bits);
}

// Where the mesh is in the elements: the vertex element and its x, y, z; the face element and its index list.
struct Layout {
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  int px = -1, py = -1, pz = -1, pf = -1;
};

Layout find_layout(const std::string& path, const PlyHeader& h) {
  Layout l;
  for (const PlyElement& e : h.elements) {
    if (e.name == "vertex" && !l.vertex) {
      l.vertex = &e;
      for (size_t i = 0; i < e.props.size(); ++i) {
        if (!e.props[i].count_type.empty()) continue;
        if (e.props[i].name == "x") l.px = int(i);
        if (e.props[i].name == "y") l.py = int(i);
        if (e.props[i].name == "z") l.pz = int(i);
      }
    }
    if (e.name == "face" && !l.face) {
      l.face = &e;
      for (size_t i = 0; i < e.props.size(); ++i)
        if (!e.props[i].count_type.empty() && (e.props[i].name == "vertex_indices" || e.props[i].name == "vertex_index"))
          l.pf = int(i);
    }
  }
  if (!l.vertex || l.px < 0 || l.py < 0 || l.pz < 0)
    throw MeshError(path + ": the PLY file has no element 'vertex' with properties x, y and z");
  // No face element: a point cloud.
  if (l.face && l.pf < 0) throw MeshError(path + ": the PLY file's element 'face' has no list vertex_indices");
  return l;
}

// The body's values in order: words of an item's line (ASCII) or bytes (binary).
class BodyReader {
 public:
  BodyReader(const std::string& path, const std::string& text, const PlyHeader& h)
      : path_(path), text_(text), at_(h.body), ascii_(h.format == "ascii"), big_(h.format == "binary_big_endian") {}

  // Starts item k of e (`where` names it in errors).
  void start_item(const std::string& where) {
    where_ = where;
    if (!ascii_) return;
    if (at_ >= text_.size()) throw MeshError(path_ + ": the file ends before " + where + " (is the file truncated?)");
    size_t eol = text_.find('\n', at_);
    if (eol == std::string::npos) eol = text_.size();
    std::istringstream line(text_.substr(at_, eol - at_));
    at_ = eol + 1;
    words_.clear();
    w_ = 0;
    for (std::string word; line >> word;) words_.push_back(word);
  }

  // The next value of the item, of PLY type `type`; `what` names it in errors.
  double value(const std::string& type, const std::string& what) {
    if (ascii_) return word(what);
    const size_t n = ply_type_size(type);
    if (at_ + n > text_.size())
      throw MeshError(path_ + ": the file ends inside " + where_ + " (is the file truncated?)");
    const double v = binary_value(text_.data() + at_, n, type, big_);
    at_ += n;
    return v;
  }

  const std::string& where() const { return where_; }

 private:
  double word(const std::string& what) {
    if (w_ >= words_.size())
      throw MeshError(path_ + ": " + where_ + " ends before its " + what + " (is the file truncated?)");
    const std::string& word = words_[w_++];
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0')
      throw MeshError(path_ + ": " + where_ + ": its " + what + " '" + word.substr(0, 40) + "' is not a number");
    return v;
  }

  const std::string& path_;
  const std::string& text_;
  size_t at_;
  bool ascii_, big_;
  std::string where_;
  std::vector<std::string> words_;
  size_t w_ = 0;
};

// Faces as read: every face's indices one after the other, and each face's count.
struct Polygons {
  std::vector<uint64_t> indices;
  std::vector<uint32_t> sizes;
};

// Reads list property pr of item k; keeps its values when it is the face's index list.
void read_list(BodyReader& in, const std::string& path, const PlyProperty& pr, uint64_t k, bool indices,
               uint64_t vertices, size_t file_size, Polygons& poly) {
  const double count = in.value(pr.count_type, "list length of " + pr.name);
  if (!(count >= 0 && count == std::floor(count) && count <= double(file_size)))
    throw MeshError(path + ": " + in.where() + ": the list length of " + pr.name + " is " + std::to_string(count));
  if (indices && count < 3)
    throw MeshError(path + ": face " + std::to_string(k) + " has " + std::to_string(uint64_t(count)) +
                    " vertices (a face needs at least 3)");
  for (uint64_t j = 0; j < uint64_t(count); ++j) {
    const double v = in.value(pr.type, "value " + std::to_string(j) + " of " + pr.name);
    if (!indices) continue;
    if (!(v >= 0 && v == std::floor(v) && v < double(vertices)))
      throw MeshError(path + ": face " + std::to_string(k) + " refers to vertex " + std::to_string(v) + " of " +
                      std::to_string(vertices));
    poly.indices.push_back(uint64_t(v));
  }
  if (indices) poly.sizes.push_back(uint32_t(count));
}

// Reads every item of element e: the vertex element's points into m, the face element's polygons into poly.
void read_element(BodyReader& in, const std::string& path, const PlyElement& e, const Layout& l, size_t file_size,
                  Mesh& m, Polygons& poly) {
  const bool is_vertex = &e == l.vertex, is_face = &e == l.face;
  for (uint64_t k = 0; k < e.count; ++k) {
    in.start_item("item " + std::to_string(k) + " of element '" + e.name + "'");
    double xyz[3] = {0, 0, 0};
    for (size_t i = 0; i < e.props.size(); ++i) {
      const PlyProperty& pr = e.props[i];
      if (!pr.count_type.empty()) {
        read_list(in, path, pr, k, is_face && int(i) == l.pf, l.vertex->count, file_size, poly);
        continue;
      }
      const double v = in.value(pr.type, "property " + pr.name);
      if (is_vertex && int(i) == l.px) xyz[0] = v;
      if (is_vertex && int(i) == l.py) xyz[1] = v;
      if (is_vertex && int(i) == l.pz) xyz[2] = v;
    }
    if (is_vertex) m.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
  }
}

Mesh read_ply_text(const std::string& path, const std::string& text) {
  const PlyHeader h = check_ply(path, text);
  const Layout l = find_layout(path, h);
  Mesh m;
  m.name = path;
  m.vertices.reserve(size_t(l.vertex->count));
  Polygons poly;
  BodyReader in(path, text, h);
  for (const PlyElement& e : h.elements) read_element(in, path, e, l, text.size(), m, poly);
  size_t q = 0;
  for (uint32_t n : poly.sizes) {
    for (uint32_t j = 1; j + 1 < n; ++j)
      m.triangles.push_back({uint32_t(poly.indices[q]), uint32_t(poly.indices[q + j]), uint32_t(poly.indices[q + j + 1])});
    q += n;
  }
  return m;
}

// A header without an end_header line (cut short, or one whose end_header runs on into other characters,
// "end_headerx", "xend_header") is refused from the first 64 KiB, before the file is read whole (assimp 5.2's reader
// never returned from one). The magic word is taken in any case ("pLy" too), as assimp takes it.
void probe_header(const std::string& path, std::istream& probe) {
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
  const bool ply = head.size() >= 3 && std::tolower(uint8_t(head[0])) == 'p' && std::tolower(uint8_t(head[1])) == 'l' &&
                   std::tolower(uint8_t(head[2])) == 'y';
  if (ply && !ended)
    throw MeshError(path + ": the PLY header has no end_header line in its first " + std::to_string(head.size()) +
                    " bytes (is the file truncated?)");
  if (!ply) throw MeshError(path + ": not a PLY file (it does not start with 'ply')");
}

}  // namespace

Mesh read_ply(const std::string& path) {
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw MeshError(path + ": cannot open");
  probe_header(path, probe);
  probe.clear();
  probe.seekg(0);
  const std::string whole((std::istreambuf_iterator<char>(probe)), std::istreambuf_iterator<char>());
  return read_ply_text(path, whole);
}

}  // namespace voxcd::formats
