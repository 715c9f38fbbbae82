// The PLY header and the counts it declares, checked against the file before anything is allocated for them.
#include "voxcd/host/mesh/formats/ply_header.h"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <utility>

#include "voxcd/host/mesh/mesh.h"

namespace voxcd::formats {

namespace {

// One header line, numbered from 1, for the errors that name it.
struct HeaderLine {
  const std::string& path;
  const std::string& raw;
  int number;
  [[noreturn]] void bad(const std::string& why) const {
    std::string shown = raw.substr(0, 60);
    for (char& c : shown)
      if (!std::isprint(uint8_t(c))) c = '?';
    throw MeshError(path + ": line " + std::to_string(number) + " of the PLY header, '" + shown + "': " + why);
  }
};

// Characters assimp would read differently: a carriage return inside the line (it takes one as a line break and
// reads another header line) and, outside comments, control or non-ASCII characters.
void check_characters(const HeaderLine& l, const std::string& word) {
  const size_t cr = l.raw.find('\r');
  if (cr != std::string::npos && cr + 1 != l.raw.size()) l.bad("a carriage return inside the line");
  if (word == "comment" || word == "obj_info") return;
  for (char c : l.raw)
    if ((uint8_t(c) < 0x20 && c != '\t' && c != '\r') || uint8_t(c) >= 0x7f)
      l.bad("a control or non-ASCII character outside a comment");
}

PlyElement parse_element(const HeaderLine& l, std::istringstream& line) {
  PlyElement e;
  std::string count;
  line >> e.name >> count;
  if (e.name.empty() || count.empty() ||
      !std::all_of(count.begin(), count.end(), [](char c) { return std::isdigit(uint8_t(c)); }))
    l.bad("an element needs a name and a count");
  e.count = count.size() > 18 ? uint64_t(1) << 62 : std::stoull(count);
  return e;
}

PlyProperty parse_property(const HeaderLine& l, std::istringstream& line) {
  std::string type, name;
  line >> type;
  PlyProperty p;
  if (type == "list") {
    line >> p.count_type >> p.type;
    p.count_size = ply_type_size(p.count_type);
    p.size = ply_type_size(p.type);
    if (!p.count_size || !p.size) l.bad("a list property needs two known types (char .. double, int8 .. float64)");
  } else {
    p.type = type;
    p.size = ply_type_size(type);
    if (!p.size) l.bad("unknown property type '" + type + "'");
  }
  line >> name;
  if (name.empty()) l.bad("a property needs a name");
  p.name = name;
  return p;
}

// Reads one header line into h; true at end_header.
bool parse_line(const HeaderLine& l, PlyHeader& h) {
  std::istringstream line(l.raw);
  std::string word;
  line >> word;
  check_characters(l, word);
  if (l.number == 1 || word.empty() || word == "comment" || word == "obj_info") return false;
  if (word == "format") {
    std::string version;
    line >> h.format >> version;
    if (h.format != "ascii" && h.format != "binary_little_endian" && h.format != "binary_big_endian")
      l.bad("the format is not ascii, binary_little_endian or binary_big_endian");
  } else if (word == "element") {
    h.elements.push_back(parse_element(l, line));
  } else if (word == "property") {
    if (h.elements.empty()) l.bad("a property before any element");
    h.elements.back().props.push_back(parse_property(l, line));
  } else if (word == "end_header") {
    return true;
  } else if (!h.elements.empty()) {
    // Before the first element, a line that is no PLY keyword is taken as a comment (old exporters, Blender 2.4's
    // among them, wrote "Created by ..." without the word); after it, it would change how the body is read.
    l.bad("not a PLY header line (ply, format, comment, obj_info, element, property, end_header)");
  }
  return false;
}

PlyHeader parse_header(const std::string& path, const std::string& text) {
  PlyHeader h;
  size_t pos = 0;
  bool ended = false;
  for (int number = 1; pos < text.size() && !ended; ++number) {
    size_t next = text.find('\n', pos);
    if (next == std::string::npos) next = text.size();
    const std::string raw = text.substr(pos, next - pos);
    pos = next + 1;
    ended = parse_line(HeaderLine{path, raw, number}, h);
  }
  if (!ended) throw MeshError(path + ": the PLY header has no end_header line (is the file truncated?)");
  if (h.format.empty()) throw MeshError(path + ": the PLY header has no format line");
  h.body = std::min(pos, text.size());  // an end_header line without a newline: no body
  return h;
}

[[noreturn]] void refuse(const std::string& path, const PlyElement& e, uint64_t count, const char* what, uint64_t room,
                         const char* unit) {
  const std::string n = count >= uint64_t(1) << 62 ? "over 4e18" : std::to_string(count);
  throw MeshError(path + ": the PLY file declares " + n + " " + what + " in element '" + e.name + "', more than the " +
                  std::to_string(room) + " " + unit + " can hold (is the file truncated or damaged?)");
}

// The lines of an ASCII body; refuses bytes assimp reads differently from a plain word split (it reads the body as C
// strings and skips what it does not know).
uint64_t ascii_body_lines(const std::string& path, const std::string& text, size_t pos) {
  uint64_t lines = 0;
  for (size_t i = pos; i < text.size(); ++i) {
    const uint8_t c = uint8_t(text[i]);
    lines += c == '\n';
    if ((c < 0x20 && c != '\n' && c != '\r' && c != '\t') || c >= 0x7f)
      throw MeshError(path + ": byte " + std::to_string(i) + " of the ASCII PLY file is a control or non-ASCII " +
                      "character (" + std::to_string(c) + ")");
  }
  if (pos < text.size() && text.back() != '\n') ++lines;
  return lines;
}

// The words of text[at, eol), as [begin, end) pairs.
void split_words(const std::string& text, size_t at, size_t eol, std::vector<std::pair<size_t, size_t>>& words) {
  words.clear();
  for (size_t i = at; i < eol;) {
    while (i < eol && std::isspace(uint8_t(text[i]))) ++i;
    const size_t b = i;
    while (i < eol && !std::isspace(uint8_t(text[i]))) ++i;
    if (i > b) words.emplace_back(b, i);
  }
}

// One ASCII item's line: each list's length (the leading digits of its word, as assimp reads it) at most the words
// left on the line.
void check_ascii_item(const std::string& path, const std::string& text, const PlyElement& e,
                      const std::vector<std::pair<size_t, size_t>>& words) {
  size_t w = 0;
  for (const PlyProperty& p : e.props) {
    if (w >= words.size()) break;
    if (!p.count_size) {
      ++w;
      continue;
    }
    const auto [b, end] = words[w++];
    uint64_t n = 0;
    for (size_t i = b; i < end && std::isdigit(uint8_t(text[i])); ++i)
      n = std::min<uint64_t>(n * 10 + uint64_t(text[i] - '0'), uint64_t(1) << 62);
    if (n > words.size() - w) refuse(path, e, n, "list values", words.size() - w, "words left on its line");
    w += size_t(n);
  }
}

// assimp reads an ASCII element item from one line: an element needs a line an item.
void check_ascii_body(const std::string& path, const std::string& text, const PlyHeader& h) {
  uint64_t lines = ascii_body_lines(path, text, h.body);
  size_t at = h.body;
  std::vector<std::pair<size_t, size_t>> words;
  for (const PlyElement& e : h.elements) {
    if (e.count > lines) refuse(path, e, e.count, "items", lines, "lines after them");
    lines -= e.count;
    for (uint64_t k = 0; k < e.count && at < text.size(); ++k) {
      size_t eol = text.find('\n', at);
      if (eol == std::string::npos) eol = text.size();
      const size_t cr = text.find('\r', at);
      if (cr != std::string::npos && cr + 1 < eol)
        throw MeshError(path + ": a carriage return inside item " + std::to_string(k) + " of element '" + e.name +
                        "' (assimp would read it as a line break)");
      split_words(text, at, eol, words);
      at = eol + 1;
      check_ascii_item(path, text, e, words);
    }
  }
}

// Walks a binary body item by item; returns early (without error) where the file ends, which the reader reports.
void check_binary_body(const std::string& path, const std::string& text, const PlyHeader& h) {
  const bool big = h.format == "binary_big_endian";
  uint64_t at = h.body;
  const uint64_t size = text.size();
  for (const PlyElement& e : h.elements) {
    uint64_t least = 0;  // the bytes of one item, its lists empty (an item of no property counts as one byte)
    for (const PlyProperty& p : e.props) least += p.count_size ? p.count_size : p.size;
    if (e.count > (size - at) / std::max<uint64_t>(least, 1)) refuse(path, e, e.count, "items", size - at, "bytes after them");
    for (uint64_t k = 0; k < e.count; ++k)
      for (const PlyProperty& p : e.props) {
        if (!p.count_size) {
          at += p.size;
          if (at > size) return;
          continue;
        }
        if (at + p.count_size > size) return;
        uint64_t n = 0;
        for (size_t i = 0; i < p.count_size; ++i)
          n = n << 8 | uint8_t(text[size_t(at + (big ? i : p.count_size - 1 - i))]);
        at += p.count_size;
        if (n > (size - at) / p.size) refuse(path, e, n, "list values", size - at, "bytes after them");
        at += n * p.size;
      }
  }
}

}  // namespace

size_t ply_type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

PlyHeader check_ply(const std::string& path, const std::string& text) {
  const PlyHeader h = parse_header(path, text);
  if (h.format == "ascii")
    check_ascii_body(path, text, h);
  else
    check_binary_body(path, text, h);
  return h;
}

}  // namespace voxcd::formats
