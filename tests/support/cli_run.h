// Test support for the command-line tests (tests/stages/test_cli*.cpp, tests/common/app): running a stage
// program as a user would (CONTRACT: options in, one summary line out, one error line and
// an exit code on bad input) and checking the shape of its errors.
#pragma once

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pt_test {

struct Run {
  int code;         // the exit code, -1 if a signal ended the program
  std::string err;  // what it wrote on stderr
  std::string out;  // what it wrote on stdout
};

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A scratch folder of this test process: temp/<prefix>_<pid>.
inline std::filesystem::path scratch_dir(const std::string& prefix) {
  std::filesystem::path dir = std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs `program args` with the environment assignments `env` in front, output kept in `dir`.
inline Run run_program(const std::string& program, const std::string& args, const std::string& env,
                       const std::filesystem::path& dir) {
  std::string cmd = env + " " + program + " " + args + " >" + (dir / "stdout").string() + " 2>" +
                    (dir / "stderr").string() + " </dev/null";
  int status = std::system(cmd.c_str());
  return Run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_file(dir / "stderr"), read_file(dir / "stdout")};
}

// A PID that no process has now: a child that has exited and been reaped (for the
// temporary files of killed runs).
inline long dead_pid() {
  pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return long(child);
}

// How many times `word` occurs in `text` (overlapping occurrences counted).
inline int occurrences(const std::string& text, const std::string& word) {
  int n = 0;
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

inline int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// The contract's shape of an error: exit code, one line naming the program, key words.
inline void check_error(const Run& r, const std::string& program, int code, const std::string& words) {
  INFO("stderr: " << r.err);
  CHECK(r.code == code);
  CHECK(lines(r.err) == 1);
  CHECK(r.err.rfind(program + ": ", 0) == 0);
  CHECK(r.err.find(words) != std::string::npos);
}

}  // namespace pt_test
