#include "voxcd/host/regress/coverage.h"

#include <fcntl.h>
#include <fnmatch.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>

#include "voxcd/ref/vector_gen.h"

extern char** environ;

namespace voxcd {

namespace fs = std::filesystem;

namespace {

// One point of Verilator's coverage data, as the source has it (instances merged).
struct Point {
  std::string kind;  // line, branch, toggle, functional
  std::string file;  // file name (no directory)
  int line = 0;
  std::string what;  // the point's comment: "if", "else", "block", a signal bit, or the bin's name
  uint64_t count = 0;
};

struct Waiver {
  std::string kind, file, pattern, reason, text;
  int lo = 0, hi = 0;  // lines, or with bits the bit range of a toggle waiver
  bool bits = false;
  int at = 0;  // line of the waiver file
  bool used = false;
};

// Runs argv[0] (searched on PATH) with its output into `log`; its exit status, or -1 when it could not start.
int run_program(const std::vector<std::string>& args, const std::string& log) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) return -1;
  int status = 0;
  if (::waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The value of key `k` in a coverage point's key string ("\001k\002value\001...").
std::string field(const std::string& key, const std::string& k) {
  const std::string tag = "\001" + k + "\002";
  const size_t b = key.find(tag);
  if (b == std::string::npos) return "";
  const size_t v = b + tag.size();
  return key.substr(v, key.find('\001', v) - v);
}

// A functional bin's name: its place below the model's top ("TOP.voxcd.g_banks.u_shared_banks.u_table_rounds.CoverX" ->
// "g_banks.u_shared_banks.u_table_rounds.CoverX"), generate indices as [*].
std::string bin_name(const std::string& hier) {
  std::string h = hier;
  for (int i = 0; i < 2; ++i) {
    const size_t dot = h.find('.');
    if (dot != std::string::npos) h = h.substr(dot + 1);
  }
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"__BRA__", "["}, {"__KET__", "]"}}) {
    for (size_t p = h.find(from); p != std::string::npos; p = h.find(from, p)) h.replace(p, from.size(), to);
  }
  return h;
}

// Points of a merged coverage data file, instances of a source point summed.
std::vector<Point> read_points(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw CoverageError("cannot read the merged coverage data " + path);
  std::map<std::tuple<std::string, std::string, int, std::string, std::string>, Point> merged;
  std::string line;
  while (std::getline(in, line)) {
    if (line.size() < 4 || line.compare(0, 3, "C '") != 0) continue;
    const size_t end = line.rfind('\'');
    if (end <= 3) continue;
    const std::string key = line.substr(3, end - 3);
    Point p;
    const std::string page = field(key, "page");
    p.kind = page.rfind("v_line", 0) == 0     ? "line"
             : page.rfind("v_branch", 0) == 0 ? "branch"
             : page.rfind("v_toggle", 0) == 0 ? "toggle"
             : page.rfind("v_user", 0) == 0   ? "functional"
                                              : "";
    if (p.kind.empty()) continue;
    p.file = fs::path(field(key, "f")).filename().string();
    p.line = std::atoi(field(key, "l").c_str());
    p.what = p.kind == "functional" ? bin_name(field(key, "h")) : field(key, "o");
    p.count = std::strtoull(line.c_str() + end + 1, nullptr, 10);
    const std::string column = p.kind == "line" || p.kind == "branch" ? field(key, "n") : "";
    const int at = p.kind == "toggle" || p.kind == "functional" ? 0 : p.line;
    Point& m = merged[{p.kind, p.file, at, column, p.what}];
    if (m.kind.empty()) m = p;
    else m.count += p.count;
  }
  std::vector<Point> out;
  for (auto& [k, p] : merged) out.push_back(std::move(p));
  return out;
}

// The waiver file: "KIND PLACE REASON" lines (docs/verification.md, "Waivers"); # comments.
std::vector<Waiver> read_waivers(const std::string& path) {
  std::vector<Waiver> out;
  if (path.empty()) return out;
  std::ifstream in(path);
  if (!in) throw CoverageError("cannot read the coverage waivers " + path);
  std::string line;
  for (int at = 1; std::getline(in, line); ++at) {
    const size_t hash = line.find('#');
    const std::string body = line.substr(0, hash);
    std::istringstream s(body);
    Waiver w;
    std::string place;
    if (!(s >> w.kind)) continue;
    const std::string where = path + ":" + std::to_string(at) + ": ";
    if (!(s >> place)) throw CoverageError(where + "a waiver is KIND PLACE REASON; this line has no place");
    std::getline(s >> std::ws, w.reason);
    if (w.reason.empty()) throw CoverageError(where + "the waiver of " + place + " gives no reason");
    w.at = at;
    w.text = w.kind + " " + place;
    if (w.kind == "bin") {
      w.pattern = place;
    } else if (w.kind == "line" || w.kind == "branch" || w.kind == "toggle") {
      const size_t colon = place.find(':');
      if (colon == std::string::npos) throw CoverageError(where + place + ": expected FILE:LINE[-LINE] or FILE:SIGNAL");
      w.file = place.substr(0, colon);
      const std::string rest = place.substr(colon + 1);
      if (w.kind == "toggle") {
        // SIGNAL[LO-HI]: bits LO..HI of the signals SIGNAL matches; else a pattern of the whole point name.
        const size_t open = rest.rfind('[');
        int lo = 0, hi = 0, used = 0;
        if (open != std::string::npos && std::sscanf(rest.c_str() + open, "[%d-%d]%n", &lo, &hi, &used) == 2 &&
            open + size_t(used) == rest.size()) {
          if (lo < 0 || hi < lo) throw CoverageError(where + place + ": not a bit range (LO-HI, LO <= HI)");
          w.pattern = rest.substr(0, open);
          w.lo = lo, w.hi = hi, w.bits = true;
        } else {
          w.pattern = rest;
        }
      } else if (std::sscanf(rest.c_str(), "%d-%d", &w.lo, &w.hi) == 2 ||
                 (std::sscanf(rest.c_str(), "%d", &w.lo) == 1 && (w.hi = w.lo))) {
        if (w.lo < 1 || w.hi < w.lo) throw CoverageError(where + place + ": not a line range");
      } else {
        throw CoverageError(where + place + ": expected FILE:LINE or FILE:LINE-LINE");
      }
    } else {
      throw CoverageError(where + "unknown waiver kind '" + w.kind + "' (line, branch, toggle or bin)");
    }
    out.push_back(std::move(w));
  }
  return out;
}

// A toggle point "NAME[BIT]" whose NAME matches w's pattern and BIT lies in w's range.
bool toggle_bit_in(const Waiver& w, const std::string& what) {
  const size_t open = what.rfind('[');
  int bit = 0, used = 0;
  if (open == std::string::npos || std::sscanf(what.c_str() + open, "[%d]%n", &bit, &used) != 1 ||
      open + size_t(used) != what.size())
    return false;
  return bit >= w.lo && bit <= w.hi && ::fnmatch(w.pattern.c_str(), what.substr(0, open).c_str(), 0) == 0;
}

bool waives(Waiver& w, const Point& p) {
  bool match = false;
  if (w.kind == "bin") match = p.kind == "functional" && ::fnmatch(w.pattern.c_str(), p.what.c_str(), 0) == 0;
  else if (w.kind != p.kind || w.file != p.file) match = false;
  else if (w.kind == "toggle" && w.bits) match = toggle_bit_in(w, p.what);
  else if (w.kind == "toggle") match = ::fnmatch(w.pattern.c_str(), p.what.c_str(), 0) == 0;
  else match = p.line >= w.lo && p.line <= w.hi;
  if (match) w.used = true;
  return match;
}

// The stimulus bins of every shard, summed.
void add_stimulus_bins(const fs::path& file, std::map<std::string, uint64_t>& bins) {
  std::ifstream in(file);
  std::string name;
  uint64_t count = 0;
  while (in >> name >> count) bins[name] += count;
}

// Merges the data files with verilator_coverage into merged.dat and coverage.info.
void merge_data(const fs::path& d, const std::vector<std::string>& data) {
  std::vector<std::string> args = {"verilator_coverage", "--write", (d / "merged.dat").string(), "--write-info",
                                   (d / "coverage.info").string()};
  args.insert(args.end(), data.begin(), data.end());
  const std::string log = (d / "merge.log").string();
  std::remove(log.c_str());
  const int rc = run_program(args, log);
  if (rc != 0)
    throw CoverageError(rc < 0 ? "cannot run verilator_coverage (the Debian package verilator has it)"
                               : "verilator_coverage failed merging " + std::to_string(data.size()) +
                                     " files; its output is in " + log);
}

}  // namespace

std::vector<std::string> aimable_holes(const std::string& bins_txt) {
  std::ifstream in(bins_txt);
  if (!in) throw CoverageError("cannot read " + bins_txt + " (run a campaign with --coverage first)");
  std::vector<std::string> out;
  std::string name;
  uint64_t count = 0;
  while (in >> name >> count)
    if (count == 0 && aimable_bin(name)) out.push_back(name);
  return out;
}

double CoverageCount::percent() const { return hit + missed == 0 ? 100.0 : 100.0 * double(hit) / double(hit + missed); }

CoverageReport merge_coverage(const std::string& dir, const std::string& waivers_path) {
  CoverageReport r;
  r.dir = dir;
  const fs::path d(dir);
  std::vector<std::string> data;
  std::vector<fs::path> bin_files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(d, ec)) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() == ".dat" && name != "merged.dat") data.push_back(e.path().string());
    if (e.path().extension() == ".bins") bin_files.push_back(e.path());
  }
  if (ec) throw CoverageError("cannot read the coverage directory " + dir + ": " + ec.message());
  if (data.empty())
    throw CoverageError(dir + " holds no coverage data (*.dat): run a campaign with the rtl backend and --coverage");
  std::sort(data.begin(), data.end());
  r.data_files = data.size();
  std::vector<Waiver> waivers = read_waivers(waivers_path);
  merge_data(d, data);
  const int html = run_program({"genhtml", "--quiet", "--ignore-errors", "source", "--output-directory",
                                (d / "html").string(), (d / "coverage.info").string()},
                               (d / "genhtml.log").string());
  if (html != 0)
    r.notes.push_back(html < 0 ? "no HTML report: genhtml is not installed (the Debian package lcov has it)"
                               : "no HTML report: genhtml failed (" + (d / "genhtml.log").string() + ")");

  std::vector<Point> points = read_points((d / "merged.dat").string());
  std::map<std::string, uint64_t> stimulus;
  for (const fs::path& f : bin_files) add_stimulus_bins(f, stimulus);
  for (const auto& [name, count] : stimulus) points.push_back({"functional", "stimulus", 0, name, count});
  for (const Point& p : points) {
    const std::string file = p.file;
    CoverageCount& k = r.kinds[p.kind];
    CoverageCount& f = r.files[file][p.kind];
    if (p.kind == "functional") r.bins[p.what] += p.count;
    bool waived = false;
    for (Waiver& w : waivers) waived = waives(w, p) || waived;
    if (p.count > 0) {
      ++k.hit, ++f.hit;
    } else if (waived) {
      ++k.waived, ++f.waived;
    } else {
      ++k.missed, ++f.missed;
      if (p.kind == "functional") r.empty_bins.push_back(p.what);
      else r.missed_points.push_back(p.file + ":" + std::to_string(p.line) + " " + p.kind + " " + p.what);
    }
  }
  std::sort(r.empty_bins.begin(), r.empty_bins.end());
  for (const Waiver& w : waivers)
    if (!w.used) r.stale_waivers.push_back(waivers_path + ":" + std::to_string(w.at) + ": " + w.text);

  std::ofstream bins(d / "bins.txt");
  for (const auto& [name, count] : r.bins) bins << name << ' ' << count << '\n';
  std::ofstream missed(d / "missed.txt");
  for (const std::string& m : r.missed_points) missed << m << '\n';
  std::ofstream summary(d / "summary.txt");
  summary << r.text();
  if (!bins || !missed || !summary) throw CoverageError("cannot write the coverage reports in " + dir);
  return r;
}

std::string CoverageReport::text() const {
  std::ostringstream o;
  char buf[160];
  o << "coverage of rtl/: " << data_files << " coverage data files merged in " << dir << "\n";
  for (const char* kind : {"line", "branch", "toggle", "functional"}) {
    const auto it = kinds.find(kind);
    if (it == kinds.end()) {
      o << "  " << kind << ": not counted by these models"
        << (std::string(kind) == "toggle" ? " (build them with -DVOXCD_RTL_COVERAGE_FULL=ON)" : "") << "\n";
      continue;
    }
    const CoverageCount& c = it->second;
    std::snprintf(buf, sizeof buf, "  %-10s %6.2f%%  (%llu hit, %llu waived, %llu missed)\n", kind, c.percent(),
                  (unsigned long long)c.hit, (unsigned long long)c.waived, (unsigned long long)c.missed);
    o << buf;
  }
  o << "by file (line / branch / toggle / functional, %):\n";
  for (const auto& [file, ks] : files) {
    std::snprintf(buf, sizeof buf, "  %-26s", file.c_str());
    o << buf;
    for (const char* kind : {"line", "branch", "toggle", "functional"}) {
      const auto it = ks.find(kind);
      if (it == ks.end()) {
        o << "       -";
      } else {
        std::snprintf(buf, sizeof buf, " %7.2f", it->second.percent());
        o << buf;
      }
    }
    o << "\n";
  }
  o << "functional bins still empty: " << empty_bins.size() << "\n";
  for (const std::string& b : empty_bins) o << "  " << b << "\n";
  if (!stale_waivers.empty()) {
    o << "waivers that match no point: " << stale_waivers.size() << "\n";
    for (const std::string& w : stale_waivers) o << "  " << w << "\n";
  }
  for (const std::string& n : notes) o << "note: " << n << "\n";
  o << "reports: " << dir << "/coverage.info (lcov), " << dir << "/html/index.html, " << dir << "/bins.txt, " << dir
    << "/missed.txt\n";
  return o.str();
}

}  // namespace voxcd
