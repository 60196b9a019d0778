// Catch2's implementation (runner, reporters, matchers), compiled once for every test program
// (catch_runner.h). Wide enough that Catch2 never wraps a failure message inside a number
// ("9.\n66671").
//
// A test that dies of a signal (a wrong index in a renderer thread: SIGSEGV) is reported here,
// not by Catch2: its handler is not safe when two threads fault at once (it wrote the report
// twice over itself, or died of SIGABRT instead). Ours writes one line, "FATAL SIGSEGV in test
// "NAME"", to stderr from the first thread to fault, then lets the signal kill the program as
// it would have. With PT_TEST_RUNNING_FILE set, each test's name is also written to that file
// as the test starts, unbuffered: tools/grade_lab.py names the test a submission crashed in.
#define CATCH_CONFIG_CONSOLE_WIDTH 400
#define CATCH_CONFIG_RUNNER
#define CATCH_CONFIG_NO_POSIX_SIGNALS
#define CATCH_CONFIG_EXTERNAL_INTERFACES
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "tests/catch_runner.h"

namespace {

char running_test[1024] = "";  // the test started last, for the signal handler (read only there)
std::atomic<int> fault_state{0};  // 0: no fault yet; 1: the first thread is writing its line; 2: written

// PT_TEST_RUNNING_FILE, opened once (-1: not set, or not writable).
int running_file() {
  static const int fd = [] {
    const char* path = std::getenv("PT_TEST_RUNNING_FILE");
    return path && *path ? open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644) : -1;
  }();
  return fd;
}

struct RunningTest : Catch::TestEventListenerBase {
  using TestEventListenerBase::TestEventListenerBase;
  void testCaseStarting(Catch::TestCaseInfo const& info) override {
    const std::size_t n = std::min(info.name.size(), sizeof running_test - 1);
    std::memcpy(running_test, info.name.data(), n);
    running_test[n] = '\0';
    if (const int fd = running_file(); fd >= 0) {  // the name alone, replacing the last one
      const std::string line = info.name + "\n";
      if (ftruncate(fd, 0) != 0 || pwrite(fd, line.data(), line.size(), 0) != static_cast<ssize_t>(line.size()))
        std::fprintf(stderr, "PT_TEST_RUNNING_FILE: could not write the running test's name\n");
    }
  }
};

void put(const char* s) {
  for (std::size_t left = std::strlen(s); left > 0;) {
    const ssize_t n = write(STDERR_FILENO, s, left);
    if (n <= 0) return;
    s += n;
    left -= static_cast<std::size_t>(n);
  }
}

struct Fatal {
  int signal;
  const char* name;
};
constexpr Fatal kFatal[] = {{SIGSEGV, "SIGSEGV"}, {SIGBUS, "SIGBUS"}, {SIGFPE, "SIGFPE"},
                            {SIGILL, "SIGILL"},   {SIGABRT, "SIGABRT"}};

// Async-signal-safe: write(2), sigaction and raise only. The threads that fault after the first
// wait for its line (a bounded spin), then every one dies of its own signal.
void on_fatal(int sig) {
  int expected = 0;
  if (fault_state.compare_exchange_strong(expected, 1)) {
    const char* name = "a fatal signal";
    for (const Fatal& f : kFatal)
      if (f.signal == sig) name = f.name;
    put("FATAL ");
    put(name);
    put(running_test[0] ? " in test \"" : " outside any test");
    if (running_test[0]) {
      put(running_test);
      put("\"");
    }
    put("\n");
    fault_state.store(2);
  } else {
    for (long spin = 0; spin < 100000000 && fault_state.load() != 2; ++spin) {
    }
  }
  struct sigaction dfl = {};
  dfl.sa_handler = SIG_DFL;
  sigaction(sig, &dfl, nullptr);
  raise(sig);
}

// The handlers, on an alternate stack for the main thread (a stack overflow there still gets
// its line; another thread's overflow dies of SIGSEGV without it).
void install_fatal_handlers() {
  static char alt_stack[64 * 1024];
  stack_t ss = {};
  ss.ss_sp = alt_stack;
  ss.ss_size = sizeof alt_stack;
  sigaltstack(&ss, nullptr);
  struct sigaction sa = {};
  sa.sa_handler = on_fatal;
  sa.sa_flags = SA_ONSTACK;
  sigemptyset(&sa.sa_mask);
  for (const Fatal& f : kFatal) sigaction(f.signal, &sa, nullptr);
}

}  // namespace

CATCH_REGISTER_LISTENER(RunningTest)

int pt::test::run_catch(int argc, char* argv[]) {
  install_fatal_handlers();
  return Catch::Session().run(argc, argv);
}
