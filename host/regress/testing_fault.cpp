#include "voxcd/host/regress/testing_fault.h"

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <thread>

namespace voxcd {

void testing_fault(const std::string& variable, const std::string& unit, uint64_t item) {
  const char* text = std::getenv(variable.c_str());
  if (!text || !*text) return;
  const std::string t = text;
  const size_t colon = t.find(':');
  const std::string kind = t.substr(0, colon);
  uint64_t at = 0;
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no item");
    size_t used = 0;
    at = std::stoull(t.substr(colon + 1), &used);
    if (used != t.size() - colon - 1 || (kind != "fail" && kind != "hang" && kind != "exit"))
      throw std::invalid_argument("bad");
  } catch (const std::exception&) {
    throw std::runtime_error(variable + " is '" + t + "', expected fail:" + unit + ", hang:" + unit + " or exit:" + unit);
  }
  if (at != item) return;
  if (kind == "fail") throw std::runtime_error("planted fault (" + variable + "=" + t + ")");
  if (kind == "exit") std::_Exit(3);
  for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
}

}  // namespace voxcd
