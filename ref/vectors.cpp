#include "voxcd/ref/vectors.h"

#include <charconv>
#include <fstream>
#include <iterator>
#include <map>
#include <ostream>
#include <sstream>
#include <string_view>

#include "voxcd/ref/fixed.h"
#include "voxcd/ref/pipeline.h"

namespace voxcd {

namespace {

class Parser {
 public:
  Parser(const std::string& text, const std::string& name) : text_(text), name_(name) {}

  VectorFile run() {
    VectorFile f;
    f.path = name_;
    bool have_header = false, have_config = false, have_shell = false, have_map = false;
    while (next_line()) {
      const std::string_view kw = tok_[0];
      if (!have_header) {
        parse_header(f);
        have_header = true;
      } else if (kw == "config") {
        if (have_config) fail("a second config line");
        if (have_shell || have_map || !f.jobs.empty() || !f.expected.empty())
          fail("the config line must come before shell, map and job records");
        parse_config(f);
        have_config = true;
      } else if (kw == "shell") {
        if (have_shell) fail("a second shell section");
        have_shell = true;
        parse_shell(f);
      } else if (kw == "map") {
        if (have_map) fail("a second map section");
        have_map = true;
        parse_map(f);
      } else if (kw == "job") {
        parse_job(f);
      } else if (kw == "hit" || kw == "done") {
        f.expected.push_back(kw == "hit" ? parse_hit(f.config) : parse_done(f.config));
        f.expected_lines.push_back(line_);
      } else if (kw == "voxcd-vectors") {
        fail("a second 'voxcd-vectors' header");
      } else {
        fail("unknown record '" + std::string(kw) + "'");
      }
    }
    if (!have_header) {
      line_ = 0;
      fail("empty file: no 'voxcd-vectors 1' header");
    }
    check_jobs(f);
    return f;
  }

 private:
  // "voxcd-vectors 1", "voxcd-vectors 2" or "voxcd-vectors 3".
  void parse_header(VectorFile& f) {
    if (tok_[0] != "voxcd-vectors")
      fail("the file must start with 'voxcd-vectors 1', 2 or 3, found '" + std::string(tok_[0]) + "'");
    want(2);
    if (tok_[1] != "1" && tok_[1] != "2" && tok_[1] != "3")
      fail("unsupported vector format version '" + std::string(tok_[1]) + "' (this reads 1, 2 and 3)");
    version_ = tok_[1][0] - '0';
    f.version = version_;
  }

  // "hit TAG POINT X Y Z STATE [DIST]" (DIST from version 2).
  Record parse_hit(const DeviceConfig& cfg) {
    want(version_ == 1 ? 7 : 8);
    const uint32_t tag = u32(1, "TAG", cfg.TAGW);
    const uint32_t point = u32(2, "POINT", 32);
    const uint32_t x = u32(3, "X", cfg.DW), y = u32(4, "Y", cfg.DW), z = u32(5, "Z", cfg.DW);
    const uint32_t st = u32(6, "STATE", 2);
    const int64_t dist = version_ == 1 ? 0 : signed_field(7, "DIST", cfg.IW(), "IW");
    return Record::hit(tag, point, x, y, z, uint8_t(st), dist);
  }

  // "done TAG HITS [CYCLES]".
  Record parse_done(const DeviceConfig& cfg) {
    if (tok_.size() != 3 && tok_.size() != 4)
      fail("'done' takes TAG HITS [CYCLES]: " + std::to_string(tok_.size() - 1) + " fields");
    Record r = Record::done(u32(1, "TAG", cfg.TAGW), u32(2, "HITS", 32));
    if (tok_.size() == 4) r.cycles = u64(3, "CYCLES");
    return r;
  }

  // Jobs are checked against the memories the whole file loads.
  void check_jobs(const VectorFile& f) {
    for (size_t k = 0; k < f.jobs.size(); ++k) {
      try {
        validate_job(f.config, f.jobs[k], f.memory.shell.size(), f.memory.map.size());
      } catch (const JobError& e) {
        line_ = f.job_lines[k];
        fail(e.what());
      }
    }
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw VectorError(name_ + ":" + std::to_string(line_) + ": " + what);
  }

  // Next line with a record: tokens without comments. False at the end of the text.
  bool next_line() {
    while (pos_ < text_.size()) {
      size_t end = text_.find('\n', pos_);
      if (end == std::string::npos) end = text_.size();
      std::string_view line(text_.data() + pos_, end - pos_);
      pos_ = end + 1;
      ++line_;
      const size_t hash = line.find('#');
      if (hash != std::string_view::npos) line = line.substr(0, hash);
      tok_.clear();
      size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        size_t j = i;
        while (j < line.size() && !is_space(line[j])) ++j;
        if (j > i) tok_.push_back(line.substr(i, j - i));
        i = j;
      }
      if (!tok_.empty()) return true;
    }
    return false;
  }
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

  void want(size_t n) const {
    if (tok_.size() != n)
      fail("'" + std::string(tok_[0]) + "' takes " + std::to_string(n - 1) + " fields, found " +
           std::to_string(tok_.size() - 1));
  }

  int64_t s64(size_t i, const std::string& what) const {
    const std::string_view s = tok_[i];
    int64_t v = 0;
    const char* b = s.data();
    const char* e = s.data() + s.size();
    if (b != e && *b == '+') ++b;
    auto r = std::from_chars(b, e, v);
    if (r.ec == std::errc::result_out_of_range) fail(what + " '" + std::string(s) + "' does not fit 64 bits");
    if (r.ec != std::errc() || r.ptr != e) fail(what + " '" + std::string(s) + "' is not a decimal integer");
    return v;
  }
  uint64_t u64(size_t i, const std::string& what) const {
    const std::string_view s = tok_[i];
    uint64_t v = 0;
    auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec == std::errc::result_out_of_range) fail(what + " '" + std::string(s) + "' does not fit 64 bits");
    if (r.ec != std::errc() || r.ptr != s.data() + s.size())
      fail(what + " '" + std::string(s) + "' is not an unsigned decimal integer");
    return v;
  }
  uint32_t u32(size_t i, const std::string& what, int bits) const {
    const uint64_t v = u64(i, what);
    if (!fits_unsigned(v, std::min(bits, 32)))
      fail(what + " " + std::to_string(v) + " does not fit " + std::to_string(std::min(bits, 32)) + " bits");
    return uint32_t(v);
  }
  int64_t signed_field(size_t i, const std::string& what, int bits, const char* param) const {
    const int64_t v = s64(i, what);
    if (!fits_signed(v, bits))
      fail(what + " " + std::to_string(v) + " does not fit " + param + " = " + std::to_string(bits) +
           " bits (signed)");
    return v;
  }
  uint64_t count(const char* section, int addr_bits, const char* param) const {
    want(2);
    const uint64_t n = u64(1, std::string(section) + " count");
    if (n > (uint64_t{1} << addr_bits))
      fail(std::string(section) + " count " + std::to_string(n) + " exceeds the memory depth 2^" + param + " = " +
           std::to_string(uint64_t{1} << addr_bits));
    return n;
  }
  void section_line(const char* section, uint64_t k, uint64_t n, int start_line) {
    if (!next_line())
      fail(std::string("truncated: the ") + section + " section at line " + std::to_string(start_line) +
           " declares " + std::to_string(n) + " words, the file ends after " + std::to_string(k));
  }

  void parse_config(VectorFile& f) {
    if (tok_.size() % 2 != 1) fail("config takes NAME VALUE pairs");
    DeviceConfig c;
    std::map<std::string, int*> keys = {{"PW", &c.PW},     {"PF", &c.PF},   {"MW", &c.MW},   {"MF", &c.MF},
                                        {"TW", &c.TW},     {"DW", &c.DW},   {"MEMW", &c.MEMW}, {"LANES", &c.LANES},
                                        {"SAW", &c.SAW},   {"MAW", &c.MAW}, {"TAGW", &c.TAGW}, {"BANKS", &c.BANKS},
                                        {"DEPTH", &c.depth}};
    if (version_ >= 2) keys.insert({{"SB", &c.SB}, {"WB", &c.WB}});
    if (version_ >= 3) keys.insert({{"BL", &c.BL}, {"TX", &c.TX}});
    std::map<std::string, bool> seen;
    for (size_t i = 1; i + 1 < tok_.size(); i += 2) {
      const std::string k(tok_[i]);
      auto it = keys.find(k);
      if (it == keys.end() && version_ == 1 && (k == "SB" || k == "WB"))
        fail("config parameter " + k + " needs format version 2 ('voxcd-vectors 2')");
      if (it == keys.end() && version_ < 3 && (k == "BL" || k == "TX"))
        fail("config parameter " + k + " needs format version 3 ('voxcd-vectors 3')");
      if (it == keys.end()) fail("unknown config parameter '" + k + "'");
      if (seen[k]) fail("config parameter " + k + " given twice");
      seen[k] = true;
      const int64_t v = s64(i + 1, k);
      if (v < 0 || v > 1024) fail("config " + k + " = " + std::to_string(v) + " is out of range");
      *it->second = int(v);
    }
    try {
      c.validate();
    } catch (const ConfigError& e) {
      fail(e.what());
    }
    f.config = c;
    f.has_lanes = seen["LANES"];
    f.has_banks = seen["BANKS"];
    f.has_depth = seen["DEPTH"];
  }

  // Reads a memory section: its count line (at most 2^addr_bits words), then one line a word of `fields` fields
  // (`layout` names them in the error), each made a word by read() and appended to `words`.
  template <class Word, class Read>
  void memory_section(const char* section, int addr_bits, const char* param, size_t fields, const char* layout,
                      std::vector<Word>& words, Read read) {
    const int start = line_;
    const uint64_t n = count(section, addr_bits, param);
    words.reserve(n);
    for (uint64_t k = 0; k < n; ++k) {
      section_line(section, k, n, start);
      if (tok_.size() != fields)
        fail(std::string(section) + " word " + std::to_string(k) + " needs " + layout + ", found " +
             std::to_string(tok_.size()) + " (the " + section + " section at line " + std::to_string(start) +
             " declares " + std::to_string(n) + ")");
      words.push_back(read());
    }
  }

  void parse_shell(VectorFile& f) {
    const int pw = f.config.PW;
    memory_section("shell", f.config.SAW, "SAW", 3, "3 fields 'x y z'", f.memory.shell, [&] {
      ShellWord w;
      w.x = signed_field(0, "shell x", pw, "PW");
      w.y = signed_field(1, "shell y", pw, "PW");
      w.z = signed_field(2, "shell z", pw, "PW");
      return w;
    });
  }

  void parse_map(VectorFile& f) {
    const int memw = f.config.MEMW;
    const size_t digits = size_t(memw + 3) / 4;
    memory_section("map", f.config.MAW, "MAW", 1, "one hex field", f.memory.map, [&] {
      const std::string_view s = tok_[0];
      uint64_t v = 0;
      auto r = std::from_chars(s.data(), s.data() + s.size(), v, 16);
      if (r.ec == std::errc::result_out_of_range && r.ptr == s.data() + s.size())
        fail("map word '" + std::string(s) + "' is wider than MEMW = " + std::to_string(memw) + " bits");
      if (r.ec != std::errc() || r.ptr != s.data() + s.size())
        fail("map word '" + std::string(s) + "' is not a hex number");
      if (s.size() > digits || !fits_unsigned(v, memw))
        fail("map word '" + std::string(s) + "' is wider than MEMW = " + std::to_string(memw) + " bits");
      return v;
    });
  }

  void parse_job(VectorFile& f) {
    want(version_ == 1 ? 22 : version_ == 2 ? 23 : 26);
    const DeviceConfig& c = f.config;
    Job j;
    j.tag = u32(1, "TAG", c.TAGW);
    const auto mode = parse_mode(std::string(tok_[2]));
    if (!mode) fail("MODE '" + std::string(tok_[2]) + "' is not ALL, FIRST or COUNT");
    j.mode = *mode;
    const uint64_t mask = u64(3, "MASK");
    if (mask > 15) fail("MASK " + std::to_string(mask) + " is outside 0..15");
    j.hit_mask = uint8_t(mask);
    j.shell_base = u32(4, "SHELL_BASE", c.SAW);
    j.shell_count = u32(5, "SHELL_COUNT", c.SAW + 1);
    j.map_base = u32(6, "MAP_BASE", c.MAW);
    j.nx = u32(7, "NX", c.DW + 1);
    j.ny = u32(8, "NY", c.DW + 1);
    j.nz = u32(9, "NZ", c.DW + 1);
    static const char* mname[9] = {"M00", "M01", "M02", "M10", "M11", "M12", "M20", "M21", "M22"};
    for (int k = 0; k < 9; ++k) j.M[k / 3][k % 3] = signed_field(10 + k, mname[k], c.MW, "MW");
    static const char* tname[3] = {"T0", "T1", "T2"};
    for (int k = 0; k < 3; ++k) j.t[k] = signed_field(19 + k, tname[k], c.TW, "TW");
    if (version_ >= 2) j.threshold = signed_field(22, "THRESHOLD", c.distance() ? c.IW() : 64, "IW");
    if (version_ >= 3) {
      const uint64_t sparse = u64(23, "SPARSE");
      if (sparse > 3) fail("SPARSE " + std::to_string(sparse) + " is outside 0..3 (1: the map, 2: the shell)");
      j.sparse = uint8_t(sparse);
      j.brick_base = u32(24, "BRICK_BASE", c.MAW);
      j.brick_units = u32(25, "BRICK_UNITS", c.MAW + 1);
    }
    f.jobs.push_back(j);
    f.job_lines.push_back(line_);
  }

  const std::string& text_;
  std::string name_;
  size_t pos_ = 0;
  int line_ = 0;
  std::vector<std::string_view> tok_;
  int version_ = 1;
};

}  // namespace

VectorFile parse_vectors(const std::string& text, const std::string& name) { return Parser(text, name).run(); }

DeviceConfig parse_config_pairs(const std::string& pairs, const std::string& what) {
  if (pairs.find('\n') != std::string::npos) throw VectorError(what + ": one line of NAME VALUE pairs expected");
  const std::string prefix = what + ":2: ";
  try {
    return parse_vectors("voxcd-vectors 3\nconfig " + pairs + "\n", what).config;
  } catch (const VectorError& e) {
    const std::string m = e.what();
    throw VectorError(what + ": " + (m.rfind(prefix, 0) == 0 ? m.substr(prefix.size()) : m));
  }
}

VectorFile read_vectors(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw VectorError(path + ":0: cannot open the file");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw VectorError(path + ":0: read error");
  return parse_vectors(text, path);
}

int vector_version(const DeviceConfig& cfg) { return cfg.sparse() ? 3 : cfg.distance() ? 2 : 1; }

std::string job_line(const Job& j, int version) {
  std::ostringstream s;
  s << "job " << j.tag << ' ' << mode_name(j.mode) << ' ' << unsigned(j.hit_mask) << ' ' << j.shell_base << ' '
    << j.shell_count << ' ' << j.map_base << ' ' << j.nx << ' ' << j.ny << ' ' << j.nz;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) s << ' ' << j.M[i][k];
  for (int i = 0; i < 3; ++i) s << ' ' << j.t[i];
  if (version >= 2) s << ' ' << j.threshold;
  if (version >= 3) s << ' ' << unsigned(j.sparse) << ' ' << j.brick_base << ' ' << j.brick_units;
  return s.str();
}

void write_vectors(std::ostream& os, const DeviceConfig& cfg, bool write_lanes, const DeviceMemory& mem,
                   const std::vector<Job>& jobs, const std::vector<Record>& records) {
  const int version = vector_version(cfg);
  os << "voxcd-vectors " << version << '\n';
  os << "config PW " << cfg.PW << " PF " << cfg.PF << " MW " << cfg.MW << " MF " << cfg.MF << " TW " << cfg.TW
     << " DW " << cfg.DW << " MEMW " << cfg.MEMW;
  if (write_lanes) os << " LANES " << cfg.LANES;
  const DeviceConfig d;
  if (cfg.SAW != d.SAW) os << " SAW " << cfg.SAW;
  if (cfg.MAW != d.MAW) os << " MAW " << cfg.MAW;
  if (cfg.TAGW != d.TAGW) os << " TAGW " << cfg.TAGW;
  if (cfg.distance()) os << " SB " << cfg.SB << " WB " << cfg.WB;
  if (cfg.banked()) os << " BANKS " << cfg.BANKS;
  if (cfg.depth != 0) os << " DEPTH " << cfg.depth;
  if (cfg.sparse()) os << " BL " << cfg.BL;
  if (cfg.brick_lanes()) os << " TX " << cfg.TX;
  os << '\n';
  std::string buf;
  os << "shell " << mem.shell.size() << '\n';
  for (const ShellWord& w : mem.shell) {
    buf.clear();
    buf += std::to_string(w.x);
    buf += ' ';
    buf += std::to_string(w.y);
    buf += ' ';
    buf += std::to_string(w.z);
    buf += '\n';
    os << buf;
  }
  os << "map " << mem.map.size() << '\n';
  const int digits = (cfg.MEMW + 3) / 4;
  static const char* hex = "0123456789abcdef";
  for (uint64_t w : mem.map) {
    buf.assign(size_t(digits), '0');
    for (int d2 = digits - 1; d2 >= 0; --d2, w >>= 4) buf[size_t(d2)] = hex[w & 15];
    buf += '\n';
    os << buf;
  }
  size_t r = 0;
  for (const Job& j : jobs) {
    os << job_line(j, version) << '\n';
    while (r < records.size()) {
      const Record& rec = records[r++];
      os << rec.to_string(version >= 2) << '\n';
      if (rec.kind == Record::Done) break;
    }
  }
}

StreamDifference first_difference(const VectorFile& file, const std::vector<Record>& got, bool compare_cycles) {
  // The job each position of the stream belongs to, for the message.
  size_t job = 0;
  auto where = [&](size_t i) {
    std::ostringstream s;
    if (job < file.jobs.size())
      s << "job tag " << file.jobs[job].tag << " (job " << job << ", line " << file.job_lines[job] << ")";
    else
      s << "after the last job";
    if (i < file.expected.size()) s << ", expected record at line " << file.expected_lines[i];
    return s.str();
  };
  const size_t n = std::max(file.expected.size(), got.size());
  for (size_t i = 0; i < n; ++i) {
    const Record* e = i < file.expected.size() ? &file.expected[i] : nullptr;
    const Record* g = i < got.size() ? &got[i] : nullptr;
    if (e && g && e->same_as(*g, compare_cycles)) {
      if (e->kind == Record::Done) ++job;
      continue;
    }
    std::ostringstream s;
    s << where(i) << ": ";
    if (e && e->kind == Record::Hit) s << "point " << e->point << ": ";
    else if (g && g->kind == Record::Hit) s << "point " << g->point << ": ";
    const bool with_dist = file.version >= 2;
    s << "expected '" << (e ? e->to_string(with_dist) : std::string("end of stream")) << "', got '"
      << (g ? g->to_string(with_dist) : std::string("end of stream")) << "'";
    if (compare_cycles && e && g && e->kind == Record::Done && g->kind == Record::Done && e->hits == g->hits)
      s << " (cycles differ)";
    StreamDifference d;
    d.differs = true;
    d.job = job;
    d.tag = job < file.jobs.size() ? file.jobs[job].tag : 0;
    d.record = i;
    d.message = s.str();
    return d;
  }
  return {};
}

std::string compare_streams(const VectorFile& file, const std::vector<Record>& got, bool compare_cycles) {
  return first_difference(file, got, compare_cycles).message;
}

}  // namespace voxcd
