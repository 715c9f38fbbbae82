#include "voxcd/host/sizing/detail/yosys_run.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "voxcd/host/detail/text_file.h"
#include "voxcd/host/package/paths.h"

namespace voxcd::detail {

namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path;
  TempDir() {
    char tmpl[] = "/tmp/voxcd-yosys-XXXXXX";
    if (!mkdtemp(tmpl)) throw std::runtime_error("yosys: cannot make a temporary directory");
    path = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string log_tail(const fs::path& log) {
  std::ifstream in(log);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::string tail;
  for (size_t i = lines.size() > 10 ? lines.size() - 10 : 0; i < lines.size(); ++i) tail += "\n  " + lines[i];
  return tail;
}

}  // namespace

YosysRun run_yosys(const std::string& rtl_dir, const std::string& script, const std::string& output,
                   const std::vector<std::pair<std::string, std::string>>& files) {
  const TempDir tmp;
  for (const auto& [name, text] : files) {
    std::ofstream out(tmp.path / name, std::ios::binary);
    out << text;
    if (!out.flush()) throw std::runtime_error("yosys: cannot write " + (tmp.path / name).string());
  }
  std::string read = "read_verilog -sv";
  for (const std::string& src : rtl_files(rtl_dir)) {
    const fs::path f = fs::path(src).filename();
    if (f.extension() == ".vlt") continue;  // Verilator's lint waivers, not Verilog
    std::error_code ec;
    fs::copy_file(src, tmp.path / f, ec);
    if (ec) throw std::runtime_error("yosys: cannot copy " + src + ": " + ec.message());
    read += " " + f.string();
  }
  YosysRun r;
  r.command = read + "; " + script;
  const std::string cmd = "cd '" + tmp.path.string() + "' && yosys -q -l yosys.log -p '" + r.command + "' >/dev/null 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (rc != 0)
    throw std::runtime_error("yosys failed (is the Debian package yosys installed?); the end of its log:" +
                             log_tail(tmp.path / "yosys.log"));
  const std::optional<std::string> text = read_text_file((tmp.path / output).string());
  if (!text) throw std::runtime_error("yosys: the script wrote no " + output);
  r.output = *text;
  return r;
}

std::string yosys_version() {
  std::string version;
  FILE* v = popen("yosys -V 2>&1", "r");
  if (v) {
    char buf[256] = {0};
    if (fgets(buf, sizeof buf, v)) version = buf;
    pclose(v);
  }
  while (!version.empty() && (version.back() == '\n' || version.back() == '\r')) version.pop_back();
  return version;
}

std::string chparam_device(const DeviceConfig& cfg) {
  std::ostringstream c;
  c << "chparam -set PW " << cfg.PW << " -set PF " << cfg.PF << " -set MW " << cfg.MW << " -set MF " << cfg.MF
    << " -set TW " << cfg.TW << " -set DW " << cfg.DW << " -set MEMW " << cfg.MEMW << " -set LANES " << cfg.LANES
    << " -set SAW " << cfg.SAW << " -set MAW " << cfg.MAW << " -set TAGW " << cfg.TAGW << " -set SB " << cfg.SB
    << " -set WB " << cfg.WB << " -set BANKS " << cfg.BANKS;
  if (cfg.depth > 0) c << " -set Depth " << cfg.depth;
  if (cfg.sparse()) c << " -set BL " << cfg.BL;
  if (cfg.brick_lanes()) c << " -set TX " << cfg.TX;
  c << " voxcd_device";
  return c.str();
}

}  // namespace voxcd::detail
