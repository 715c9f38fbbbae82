// The text of the exception a test expects: shared by the suites that check error messages.
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <string>

namespace voxcd::test {

// The text of the exception E that fn throws; a failure when it throws nothing or something else.
template <class E, class Fn>
std::string error_text(Fn&& fn) {
  try {
    fn();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw another type: " << e.what();
    return "";
  }
  ADD_FAILURE() << "threw nothing";
  return "";
}

}  // namespace voxcd::test
