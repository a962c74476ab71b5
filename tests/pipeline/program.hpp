#pragma once
/// @file program.hpp
/// @brief Running the built programs as a user would, for the pipeline
/// tests: a command's exit code and output, whole-file reads and writes.

#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace lamina::test {

namespace fs = std::filesystem;

/// Where the programs are built.
inline const fs::path kBin = fs::path(LAMINA_BINARY_DIR) / "bin";
/// The runnable cases of the source tree.
inline const fs::path kCases = fs::path(LAMINA_SOURCE_DIR) / "cases";

/// Exit code and combined output of a command.
struct Result {
  int code;
  std::string output; // stdout + stderr
};

/// Runs @p command through the shell.
inline Result run(const std::string& command) {
  const fs::path log =
      fs::temp_directory_path() / ("lamina_bad_input_" + std::to_string(::getpid()) + ".log");
  const int status = std::system((command + " > '" + log.string() + "' 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  fs::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

/// Starts @p argv[0] with @p argv, its output discarded, without waiting
/// (to signal it mid-run); @return its pid (-1 when it could not start).
inline pid_t spawn(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const auto& a : argv)
    args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  const int rc = ::posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

/// @return the content of @p p ("" if absent)
inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Writes @p text to @p p.
inline void write(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

/// @return a fresh, empty folder under the temporary directory, named by
/// @p prefix, the process and the running test (removed first if present)
inline fs::path freshTestDir(const std::string& prefix) {
  const fs::path dir =
      fs::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()) + "_" +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// @return whether @p program was built
inline bool have(const std::string& program) {
  return fs::exists(kBin / program);
}

} // namespace lamina::test
