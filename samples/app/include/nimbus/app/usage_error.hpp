// Bad input from the user: the error kind of every app-library check that names a flag or a file.
// The nimbus program exits 2 on it (samples/cli/main.cpp); a Python binding raises ValueError.
#pragma once
#include <stdexcept>

namespace nimbus::app {

struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

}  // namespace nimbus::app
