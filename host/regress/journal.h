// Journal: a file of lines that only grows, each line flushed to the disk (fsync) before append returns, so that a
// run stopped at any point finds every line it finished. The results files of `voxcd regress` (results_file) and
// `voxcd sweep` (sizing/sweep_results) are journals with a header line and a parser of their own.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace voxcd {

class Journal {
 public:
  // Reads the complete lines of `path` (a missing file has none; a last line without its newline, left by a writer
  // stopped mid-line, is not one) and changes nothing, so that the caller can check them first.
  explicit Journal(std::string path);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  // The complete lines the file held, without their newlines.
  const std::vector<std::string>& lines() const { return lines_; }
  // Opens the file for appending: cuts an unfinished last line, and writes `header` as the first line when the file
  // held no complete line. std::runtime_error naming the file when it cannot.
  void open(const std::string& header);
  // Appends `line` and its newline and flushes them to the disk; std::runtime_error naming the file when it cannot.
  void append(const std::string& line);

 private:
  std::string path_;
  std::vector<std::string> lines_;
  size_t keep_ = 0;    // bytes of complete lines
  size_t size_ = 0;    // bytes in the file
  int fd_ = -1;
};

// The lines of a results journal (regress's and sweep's --results files): the first must be `header`, else
// wrong_header(first line) is called (it throws, saying whose file it is); every other line is given to
// row(line, where), where = "path:N" (N from 1), in order.
void read_journal_rows(const Journal& journal, const std::string& path, const std::string& header,
                       const std::function<void(const std::string&)>& wrong_header,
                       const std::function<void(const std::string&, const std::string&)>& row);

}  // namespace voxcd
