// Test support for the interrupt tests (issue: reliability): waiting until a forked child
// runs the stage program and has installed its signal handlers, so that a signal sent "at a
// random moment of the render" cannot arrive before the program can catch it (on a loaded
// machine start-up takes longer than any fixed delay). Linux: reads /proc/PID.
#pragma once

#include <sys/types.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace pt_test {

// Waits (up to 60 s) until process `pid` runs `program` (the forked test process before exec
// has Catch's own handlers) and catches signal `signo` (bit signo-1 of SigCgt in
// /proc/PID/status); or until it has ended (a program that crashed as it started: waitid
// without reaping it, so that the caller's waitpid then reports it at once, not after 60 s).
inline void wait_for_handler(pid_t pid, const std::string& program, int signo) {
  namespace fs = std::filesystem;
  const fs::path exe = fs::canonical(program);
  for (int i = 0; i < 6000; i++) {
    std::error_code ec;
    siginfo_t ended{};
    if (::waitid(P_PID, id_t(pid), &ended, WEXITED | WNOHANG | WNOWAIT) == 0 && ended.si_pid == pid) return;
    if (fs::read_symlink("/proc/" + std::to_string(pid) + "/exe", ec) == exe) {
      std::ifstream status("/proc/" + std::to_string(pid) + "/status");
      std::string line;
      while (std::getline(status, line)) {
        if (line.rfind("SigCgt:", 0) == 0 && (std::stoull(line.substr(7), nullptr, 16) >> (signo - 1)) & 1u) return;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace pt_test
