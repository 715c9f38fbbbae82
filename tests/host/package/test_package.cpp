// Where the package finds its own files (host/package/paths.h): the build tree is laid out as an installed prefix.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "voxcd/host/package/paths.h"

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Package, RtlDirHoldsEveryFileOfTheListAsTheSourceTreeHasIt) {
  namespace fs = std::filesystem;
  const std::string dir = voxcd::rtl_dir();
  EXPECT_EQ(fs::path(dir).filename(), "rtl");
  EXPECT_NE(dir.find("share/voxcd/rtl"), std::string::npos) << dir;
  const std::vector<std::string> files = voxcd::rtl_files(dir);
  // Every file the source tree's list names, in its order.
  std::vector<std::string> listed;
  {
    std::ifstream in(std::string(VOXCD_SOURCE_RTL) + "/voxcd.f");
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line.rfind("//", 0) != 0) listed.push_back(line);
  }
  ASSERT_GE(listed.size(), 4u);
  ASSERT_EQ(files.size(), listed.size());
  for (size_t i = 0; i < files.size(); ++i) EXPECT_EQ(fs::path(files[i]).filename(), listed[i]);
  // The package and the assertion macros before every module that uses them, the device before the AXI top.
  const auto at = [&](const std::string& name) {
    return std::find(listed.begin(), listed.end(), name) - listed.begin();
  };
  EXPECT_LT(at("voxcd_arch_pkg.sv"), at("voxcd_lane.sv"));
  EXPECT_LT(at("voxcd_arch_pkg.sv"), at("voxcd_device.sv"));
  EXPECT_LT(at("voxcd_assert.svh"), at("voxcd_ram.sv"));
  EXPECT_LT(at("voxcd_params.svh"), at("voxcd_lane.sv"));
  EXPECT_LT(at("voxcd_device.sv"), at("voxcd_axi.sv"));
  for (const std::string& f : files) {
    const std::string source = std::string(VOXCD_SOURCE_RTL) + "/" + fs::path(f).filename().string();
    EXPECT_EQ(slurp(f), slurp(source)) << f << " is not a copy of " << source;
  }
}

TEST(Package, RtlFileListErrorsNameTheList) {
  namespace fs = std::filesystem;
  const fs::path tmp = fs::temp_directory_path() / "voxcd_test_package";
  fs::create_directories(tmp);
  try {
    voxcd::rtl_files((tmp / "nowhere").string());
    FAIL() << "no error for a missing list";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere/voxcd.f"), std::string::npos) << e.what();
  }
  std::ofstream(tmp / "voxcd.f") << "// only comments\n\n   \n";
  try {
    voxcd::rtl_files(tmp.string());
    FAIL() << "no error for a list without files";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("names no file"), std::string::npos) << e.what();
  }
  std::ofstream(tmp / "voxcd.f") << "// a list\n  a.sv  \nsub/b.sv\n";
  const auto files = voxcd::rtl_files(tmp.string());
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0], (tmp / "a.sv").string());
  EXPECT_EQ(files[1], (tmp / "sub/b.sv").string());
  fs::remove_all(tmp);
}

}  // namespace
