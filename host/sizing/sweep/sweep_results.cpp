#include "voxcd/host/sizing/sweep/sweep_results.h"

#include <nlohmann/json.hpp>

namespace voxcd {

namespace {

constexpr const char* kFormatKey = "voxcd_sweep_results";

std::string header_line(const SweepSpec& s) {
  return nlohmann::ordered_json{{kFormatKey, 1}, {"sweep", nlohmann::ordered_json::parse(sweep_json(s))}}.dump();
}

// The row's point must be the point of s with its index.
void check_point(const SweepRow& r, const SweepSpec& s, const std::string& where) {
  if (r.point.index >= s.points())
    throw SweepError(where + ": point " + std::to_string(r.point.index) + " is not in the sweep (it has " +
                     std::to_string(s.points()) + " points)");
  const SweepPoint p = point_at(s, r.point.index);
  if (p.lanes != r.point.lanes || p.depth != r.point.depth || p.voxel_scale != r.point.voxel_scale || p.distance_bits != r.point.distance_bits ||
      p.accuracy != r.point.accuracy)
    throw SweepError(where + ": point " + std::to_string(p.index) + " is " + r.point.text() + ", but in this sweep " +
                     p.text());
}

}  // namespace

SweepResults::SweepResults(const std::string& path, const SweepSpec& s) : journal_(path) {
  std::vector<bool> seen(s.points(), false);
  auto wrong_header = [&](const std::string& line) {
    std::string theirs;
    try {
      const nlohmann::ordered_json j = nlohmann::ordered_json::parse(line);
      theirs = j.at(kFormatKey).dump(), theirs = j.at("sweep").dump();
    } catch (const std::exception&) {
      throw SweepError(path + " is not a voxcd sweep results file (its first line is not the header)");
    }
    throw SweepError(path + " holds the results of another sweep (" + theirs + "; this one is " + sweep_json(s) +
                     "): give another --results file, or the sweep it was made for");
  };
  read_journal_rows(journal_, path, header_line(s), wrong_header, [&](const std::string& line, const std::string& where) {
    SweepRow r = parse_sweep_row(line, where);
    check_point(r, s, where);
    if (seen[r.point.index]) return;
    seen[r.point.index] = true;
    finished_.push_back(std::move(r));
  });
  journal_.open(header_line(s));
}

void SweepResults::append(const SweepRow& r) { journal_.append(sweep_row_line(r)); }

}  // namespace voxcd
