// Running yosys on the device's RTL (voxcd size --cost, voxcd sweep --cost): a copy of an RTL file list's sources in
// a fresh temporary directory, one script, and the file the script writes.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "voxcd/ref/config.h"

namespace voxcd::detail {

struct YosysRun {
  std::string output;   // the text of the file the script wrote
  std::string command;  // the whole script, as yosys -p got it
  double seconds = 0;
};

// Runs `yosys -p "read_verilog -sv <the sources of rtl_dir's voxcd.f>; <script>"` in a temporary directory (removed
// afterwards), with the `files` ({name, text}) written there first, and returns the text of `output`, a file the
// script writes there. std::runtime_error when the sources cannot be copied, yosys is missing or fails (with the end
// of its log), or it did not write `output`.
YosysRun run_yosys(const std::string& rtl_dir, const std::string& script, const std::string& output,
                   const std::vector<std::pair<std::string, std::string>>& files = {});

// "Yosys 0.23 (git sha1 ...)", or "" when yosys cannot be run.
std::string yosys_version();

// "chparam -set PW 24 ... -set BANKS 0 [-set Depth D] voxcd_device": every parameter of cfg (the depth only when it
// is not 0, the one depth every RTL has).
std::string chparam_device(const DeviceConfig& cfg);

}  // namespace voxcd::detail
