// Test support for the loader tests (tests/common/scene): what the code under test writes on
// stderr, caught from file descriptor 2 for the life of the object (warnings of the glTF
// loader are one line each, and a test counts them). A capture starts with warn_once's
// memory cleared: the count does not depend on which tests ran before in the process.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <string>

#include "common/base/error.h"

namespace pt_test {

class StderrCapture {
 public:
  StderrCapture() : file_(std::tmpfile()) {
    pt::forget_warnings_given();
    std::fflush(stderr);
    saved_ = dup(2);
    dup2(fileno(file_), 2);
  }
  ~StderrCapture() {
    restore();
    std::fclose(file_);
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  // Everything written so far; ends the capture.
  std::string text() {
    restore();
    std::rewind(file_);
    std::string out;
    for (int c; (c = std::fgetc(file_)) != EOF;) out += char(c);
    return out;
  }

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    dup2(saved_, 2);
    close(saved_);
    saved_ = -1;
  }
  std::FILE* file_;
  int saved_ = -1;
};

}  // namespace pt_test
