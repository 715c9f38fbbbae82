#include "voxcd/ref/error.h"

#include <utility>

namespace voxcd {

std::string leading_places(const std::string& message) {
  size_t end = 0, from = 0;
  for (;;) {
    const size_t colon = message.find(": ", from);
    if (colon == std::string::npos || colon == from) break;
    if (message.find_first_of(" \t\n", from) < colon) break;
    end = colon;
    from = colon + 2;
  }
  return message.substr(0, end);
}

Error::Error(const std::string& what) : std::runtime_error(what), where_(leading_places(what)) {}

Error::Error(const std::string& what, std::string where) : std::runtime_error(what), where_(std::move(where)) {}

}  // namespace voxcd
