// Interrupts that keep the work (see interrupt.h).
#include "common/render/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstring>

namespace pt {

namespace {

std::atomic<int> g_signal{0};
char g_in_progress[4096] = {0};  // read by the handler: a plain buffer, no allocation

void on_signal(int signo) {
  if (g_signal.exchange(signo) != 0) {
    // The second signal: leave now, without a half-written file.
    if (g_in_progress[0]) ::unlink(g_in_progress);
    ::_exit(128 + signo);
  }
  const char note[] = "\ninterrupted: finishing the pass in flight and writing the samples done so far "
                      "(again to quit at once)\n";
  ssize_t ignored = ::write(2, note, sizeof note - 1);
  (void)ignored;
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

int interrupt_signal() { return g_signal.load(); }

void set_file_in_progress(const char* path) {
  // The handler may run at any moment: hide the old name, write the new one behind its
  // first byte, then show it by writing the first byte.
  std::size_t n = std::min(std::strlen(path), sizeof g_in_progress - 1);
  g_in_progress[0] = 0;
  if (n == 0) return;
  std::memcpy(g_in_progress + 1, path + 1, n - 1);
  g_in_progress[n] = 0;
  g_in_progress[0] = path[0];
}

}  // namespace pt
