// Progress of a long step on stderr, shared by the commands (generate, render).
#pragma once
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace nimbus::cli {

// Progress on stderr once a step has run for a second: a plain line per update when stderr
// is not a terminal, an updating line when it is.
class Progress {
 public:
  explicit Progress(std::string what) : what_(std::move(what)), start_(clock::now()), tty_(::isatty(2)) {}
  void update(double fraction) {
    const auto now = clock::now();
    if (now - start_ < std::chrono::seconds(1) || now - last_ < std::chrono::milliseconds(tty_ ? 200 : 1000)) return;
    last_ = now;
    std::fprintf(stderr, tty_ ? "\r%s: %3.0f %%" : "%s: %3.0f %%\n", what_.c_str(), 100.0 * fraction);
    shown_ = true;
  }
  ~Progress() {
    if (shown_ && tty_) std::fprintf(stderr, "\r%s: done  \n", what_.c_str());
  }

 private:
  using clock = std::chrono::steady_clock;
  std::string what_;
  clock::time_point start_, last_{};
  bool tty_, shown_ = false;
};

}  // namespace nimbus::cli
