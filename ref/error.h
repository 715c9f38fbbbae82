// The errors voxcd throws, rooted in one base (public: <voxcd/ref/error.h>, and through <voxcd/voxcd.h>):
// catch (const voxcd::Error& e) for every one, e.what() for the message, e.where() for the place it names. The
// device contract's own errors are here too, since ref/ depends on nothing of the host; the host library's are in
// <voxcd/host/api/errors.h>, each declared by the folder that throws it.
#pragma once

#include <stdexcept>
#include <string>

namespace voxcd {

// Bad input that voxcd refuses: what() says what is wrong, where() where (a file, with its line or byte; an option;
// a scene file's key), "" when the message names no place. A std::runtime_error: catching that still works.
class Error : public std::runtime_error {
 public:
  // where(): the message's leading places, the segments before ": " that hold no space ("mixed.json: types[1].voxel"
  // of "mixed.json: types[1].voxel: -1 is outside (0, 1e+12]"; "run.vxr" of "run.vxr: cannot open").
  explicit Error(const std::string& what);
  Error(const std::string& what, std::string where);
  const std::string& where() const noexcept { return where_; }

 private:
  std::string where_;
};

// The leading places of a message, as Error(what) takes them.
std::string leading_places(const std::string& message);

// A value that does not fit its fixed-point format (or is not a finite number).
struct RangeError : Error {
  using Error::Error;
};

// A configuration that no device can have (a width out of range, MEMW not a power of two, ...).
struct ConfigError : Error {
  using Error::Error;
};

// A job the device cannot run: a field too wide for its format, a shell or map outside the loaded memory, a map
// dimension of 0 or above 2^DW. The message names the job's tag and the field.
struct JobError : Error {
  using Error::Error;
};

// A malformed conformance vector file; the message starts with "FILE:LINE: ".
struct VectorError : Error {
  using Error::Error;
};

}  // namespace voxcd
