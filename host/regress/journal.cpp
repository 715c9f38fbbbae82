#include "voxcd/host/regress/journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "voxcd/host/detail/text_file.h"

namespace voxcd {

namespace {

std::runtime_error system_error(const std::string& what, const std::string& path) {
  return std::runtime_error(what + " " + path + ": " + std::strerror(errno));
}

// Writes all of `bytes` to fd; false on an error.
bool write_all(int fd, const std::string& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += size_t(n);
  }
  return true;
}

}  // namespace

Journal::Journal(std::string path) : path_(std::move(path)) {
  std::string text = detail::read_text_file(path_).value_or("");
  size_ = text.size();
  const size_t nl = text.rfind('\n');
  keep_ = nl == std::string::npos ? 0 : nl + 1;
  text.resize(keep_);
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines_.push_back(std::move(line));
}

Journal::~Journal() {
  if (fd_ >= 0) ::close(fd_);
}

void Journal::open(const std::string& header) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT, 0644);
  if (fd_ < 0) throw system_error("cannot open the results file", path_);
  if ((keep_ != size_ || keep_ == 0) && ::ftruncate(fd_, off_t(keep_)) != 0)
    throw system_error("cannot cut the unfinished last line of", path_);
  if (::lseek(fd_, 0, SEEK_END) < 0) throw system_error("cannot seek in", path_);
  if (keep_ == 0) append(header);
}

void Journal::append(const std::string& line) {
  if (!write_all(fd_, line + "\n") || ::fsync(fd_) != 0) throw system_error("cannot write the results file", path_);
}

void read_journal_rows(const Journal& journal, const std::string& path, const std::string& header,
                       const std::function<void(const std::string&)>& wrong_header,
                       const std::function<void(const std::string&, const std::string&)>& row) {
  const std::vector<std::string>& lines = journal.lines();
  for (size_t n = 1; n <= lines.size(); ++n) {
    if (n == 1) {
      if (lines[0] != header) wrong_header(lines[0]);
      continue;
    }
    row(lines[n - 1], path + ":" + std::to_string(n));
  }
}

}  // namespace voxcd
