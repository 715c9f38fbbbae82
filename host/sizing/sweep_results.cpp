#include "voxcd/host/sizing/sweep_results.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace voxcd {

namespace {

constexpr const char* kFormatKey = "voxcd_sweep_results";

std::string header_line(const SweepSpec& s) {
  return std::string("{\"") + kFormatKey + "\":1,\"sweep\":" + sweep_json(s) + "}";
}

std::string system_error(const std::string& what, const std::string& path) {
  return what + " " + path + ": " + std::strerror(errno);
}

bool write_all(int fd, const std::string& s) {
  size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += size_t(n);
  }
  return true;
}

// The row's point must be the point of s with its index.
void check_point(const SweepRow& r, const SweepSpec& s, const std::string& where) {
  if (r.point.index >= s.points())
    throw SweepError(where + ": point " + std::to_string(r.point.index) + " is not in the sweep (it has " +
                     std::to_string(s.points()) + " points)");
  const SweepPoint p = point_at(s, r.point.index);
  if (p.lanes != r.point.lanes || p.voxel_scale != r.point.voxel_scale || p.distance_bits != r.point.distance_bits ||
      p.accuracy != r.point.accuracy)
    throw SweepError(where + ": point " + std::to_string(p.index) + " is " + r.point.text() + ", but in this sweep " +
                     p.text());
}

}  // namespace

SweepResults::SweepResults(const std::string& path, const SweepSpec& s) : path_(path) {
  std::string text;
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      std::ostringstream ss;
      ss << in.rdbuf();
      text = ss.str();
    }
  }
  // A writer stopped mid-line leaves a last line without its newline: it never counted.
  const size_t nl = text.rfind('\n');
  const size_t keep = nl == std::string::npos ? 0 : nl + 1;
  const bool cut = keep != text.size();
  text.resize(keep);
  std::vector<bool> seen(s.points(), false);
  std::istringstream lines(text);
  std::string line;
  size_t n = 0;
  while (std::getline(lines, line)) {
    ++n;
    const std::string where = path + ":" + std::to_string(n);
    if (n == 1) {
      if (line == header_line(s)) continue;
      std::string theirs;
      try {
        const nlohmann::ordered_json j = nlohmann::ordered_json::parse(line);
        theirs = j.at(kFormatKey).dump(), theirs = j.at("sweep").dump();
      } catch (const std::exception&) {
        throw SweepError(path + " is not a voxcd sweep results file (its first line is not the header)");
      }
      throw SweepError(path + " holds the results of another sweep (" + theirs + "; this one is " + sweep_json(s) +
                       "): give another --results file, or the sweep it was made for");
    }
    SweepRow r = parse_sweep_row(line, where);
    check_point(r, s, where);
    if (seen[r.point.index]) continue;
    seen[r.point.index] = true;
    finished_.push_back(std::move(r));
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT, 0644);
  if (fd_ < 0) throw std::runtime_error(system_error("cannot open the results file", path));
  if ((cut || keep == 0) && ::ftruncate(fd_, off_t(keep)) != 0)
    throw std::runtime_error(system_error("cannot cut the unfinished last line of", path));
  if (::lseek(fd_, 0, SEEK_END) < 0) throw std::runtime_error(system_error("cannot seek in", path));
  if (keep == 0 && (!write_all(fd_, header_line(s) + "\n") || ::fsync(fd_) != 0))
    throw std::runtime_error(system_error("cannot write the results file", path));
}

SweepResults::~SweepResults() {
  if (fd_ >= 0) ::close(fd_);
}

void SweepResults::append(const SweepRow& r) {
  if (!write_all(fd_, sweep_row_line(r) + "\n") || ::fsync(fd_) != 0)
    throw std::runtime_error(system_error("cannot write the results file", path_));
}

}  // namespace voxcd
