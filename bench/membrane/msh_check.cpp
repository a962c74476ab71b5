// Times the structural check of a gmsh .msh file (membrane/io/msh_check.hpp)
// that readGmsh runs before gmsh's own reader: checkMshText on the file's
// bytes already in memory (the check alone) and checkMshFile (reading the
// file too). Wall times are the best of the repetitions (the machine is
// shared: the best is the least disturbed) and the median; CPU time is the
// mean per check (less sensitive to other load than wall time).
// Usage: membrane_msh_check FILE.msh [REPS]
// bench/membrane/msh_check.sh meshes cases/meshes/square.geo finely in the
// four formats and runs this on each.
#include "membrane/io/msh_check.hpp"
#include "timing.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using lamina::bench::timeIt;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: membrane_msh_check FILE.msh [REPS]\n");
    return 2;
  }
  const std::string file = argv[1];
  const int reps = argc > 2 ? std::max(1, std::atoi(argv[2])) : 10;
  std::ifstream in(file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::printf("%s: %zu bytes\n", file.c_str(), text.size());
  timeIt("checkMshText", reps, [&] { lamina::membrane::checkMshText(text, file); });
  timeIt("checkMshFile", reps, [&] { lamina::membrane::checkMshFile(file); });
  return 0;
}
