// Errors and warnings as the contract (README.md) wants them: one line that names the problem and
// what to do, and an exit code (2 bad option, 3 bad scene, 4 no device, 5 output).
// Not part of the article: the machinery every stage's main() shares.
#pragma once

#include <stdexcept>
#include <string>

namespace pt {

enum ExitCode : int {
  kExitOk = 0,
  kExitBadOption = 2,
  kExitBadScene = 3,
  kExitNoDevice = 4,
  kExitOutput = 5,
};

// Thrown anywhere below main(); pt::run_guarded() (common/app/app.h) prints what() and returns code.
class Error : public std::runtime_error {
 public:
  Error(int code, const std::string& message) : std::runtime_error(message), code_(code) {}
  int code() const { return code_; }

 private:
  int code_;
};

// Prints "warning: <message>" on stderr the first time a message is given.
void warn_once(const std::string& message);
// Forgets the messages warn_once gave, so that each is printed again: for a test that counts
// a loader's warnings whatever tests ran before it in the same process.
void forget_warnings_given();

}  // namespace pt
