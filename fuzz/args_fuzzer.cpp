/// @file args_fuzzer.cpp
/// @brief libFuzzer target: the argument lists of `homogenize` (--path,
/// --tangent-rates, the linear run) and `materials drive`, run in-process
/// through the programs' own command-line functions (homogenize/cli.hpp,
/// materials/cli.hpp) on a tiny GVBO cell. The input is split into words at
/// white space; a first word "materials" selects `materials drive`, anything
/// else `homogenize CELL`. Property: every input ends in an exit code (0, 1,
/// 2 or 3) with a message; an exception that is not a lamina::Error or a
/// command-line error escapes (UnexpectedErrors::Rethrow) and is a finding,
/// as is a crash or a sanitizer report.
///
/// Each input is kept cheap and confined: the cell is 2 to 4 voxels a side
/// (--resolution, from the input's length), --steps is 2 and --threads 1
/// (the target adds them: an input naming them again is a command-line
/// error), every '/' of a word becomes '_' so that files are only created
/// in the process's scratch folder (the working directory, emptied after
/// each input, the working directory only while it runs), and HOME, XDG_*
/// and LAMINA_LIBRARY point there too.

#include "fuzz_input.hpp"
#include "homogenize/cli.hpp"
#include "materials/cli.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

/// The tiny cell: a hard sphere in GVBO soft domains (polyurea.toml's phases).
constexpr const char* kCell = R"([cell]
resolution = 2
size = 20e-9

[[phases]]
name = "soft"
catalog = "polyurea-soft"

[[phases]]
name = "hard"
catalog = "polyurea-hard"

[[inclusions]]
phase = "hard"
shape = "sphere"
radius = 0.3
placement = "single"
volume_fraction = 0.19
)";

/// The process's scratch folder ($TMPDIR/lamina-fuzz-<pid>/args, as the
/// other targets'); the environment points every default file there.
const fs::path& workDir() {
  static const lamina::fuzz::ScratchDir scratch; // removed at exit
  static const fs::path dir = [] {
    const fs::path d = scratch.path / "args";
    fs::create_directories(d);
    for (const char* var : {"HOME", "XDG_DATA_HOME", "XDG_CACHE_HOME", "XDG_CONFIG_HOME"})
      ::setenv(var, d.c_str(), 1);
    ::setenv("LAMINA_LIBRARY", (d / "library.toml").c_str(), 1);
    ::unsetenv("LAMINA_CATALOG");
    std::ofstream(d / "cell.toml") << kCell;
    return d;
  }();
  return dir;
}

/// The scratch folder as the working directory while the object lives (an
/// input's relative paths land there); libFuzzer's own (the corpus and
/// artifact paths are relative to it) is restored after.
struct InScratch {
  explicit InScratch(const fs::path& dir) : home(fs::current_path()) { fs::current_path(dir); }
  ~InScratch() { fs::current_path(home); }
  InScratch(const InScratch&) = delete;
  InScratch& operator=(const InScratch&) = delete;
  fs::path home;
};

/// Removes everything the last input created (all but the cell file).
void clean(const fs::path& dir) {
  std::error_code ec;
  std::vector<fs::path> made;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().filename() != "cell.toml")
      made.push_back(e.path());
  for (const auto& p : made)
    fs::remove_all(p, ec);
}

/// The words of @p text (at most 64 of at most 256 characters, '/' -> '_').
std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string w;
  while (out.size() < 64 && in >> w) {
    std::replace(w.begin(), w.end(), '/', '_');
    out.push_back(w.substr(0, 256));
  }
  return out;
}

/// Runs @p run on @p args as argv (argv[0] first).
template <class Run>
int runArgs(std::vector<std::string> args, Run&& run) {
  std::vector<char*> argv;
  for (std::string& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  return run(static_cast<int>(args.size()), argv.data());
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using lamina::UnexpectedErrors;
  const fs::path& dir = workDir();
  std::vector<std::string> w = words(lamina::fuzz::text(data, size));
  const bool materials = !w.empty() && w.front() == "materials";
  if (materials)
    w.erase(w.begin());
  int code = 0;
  const InScratch in_scratch(dir);
  lamina::fuzz::guarded([&] {
    if (materials) {
      std::vector<std::string> args{"materials", "drive"};
      args.insert(args.end(), w.begin(), w.end());
      for (const char* a : {"--steps", "2"})
        args.emplace_back(a);
      code = runArgs(args, [](int argc, char** argv) {
        return lamina::materials::runProgram(argc, argv, UnexpectedErrors::Rethrow);
      });
    } else {
      static lamina::homogenize::MpiSession mpi(nullptr, nullptr); // serial (fuzz build: no MPI)
      std::vector<std::string> args{"homogenize", "cell.toml"};
      args.insert(args.end(), w.begin(), w.end());
      const std::string resolution = std::to_string(2 + size % 3);
      for (const char* a :
           {"--resolution", resolution.c_str(), "--steps", "2", "--threads", "1", "--quiet"})
        args.emplace_back(a);
      code = runArgs(args, [](int argc, char** argv) {
        return lamina::homogenize::runProgram(argc, argv, mpi, UnexpectedErrors::Rethrow);
      });
    }
  });
  clean(dir);
  if (code < 0 || code > 3)
    std::abort(); // an exit code no lamina program gives
  return 0;
}
