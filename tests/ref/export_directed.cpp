// Writes every directed case as a conformance vector file (with its hand-derived expectations) into DIR, so
// the command line and every backend can run them as files written by someone else would be.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "voxcd/ref/vectors.h"
#include "tests/ref/directed_cases.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: export_directed DIR\n";
    return 2;
  }
  std::filesystem::create_directories(argv[1]);
  for (const auto& c : voxcd::testing::directed_cases()) {
    const std::string path = std::string(argv[1]) + "/directed_" + c.name + ".vec";
    std::ofstream out(path);
    out << "# directed case " << c.name << ": expectations derived by hand (tests/ref/directed_cases.cpp)\n";
    voxcd::write_vectors(out, c.config, false, c.memory, c.jobs, c.expected);
    if (!out) {
      std::cerr << "cannot write " << path << '\n';
      return 1;
    }
  }
  return 0;
}
