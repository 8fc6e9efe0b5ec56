// Shared by the fuzz harnesses (tests/fuzz/fuzz_*.cpp), built two ways: with clang's libFuzzer
// (-DNIMBUS_FUZZ=ON, scripts/fuzz.sh) and with the normal compiler into replay programs that run
// every corpus file once (replay_main.cpp, the Fuzz.*Replay tests).
#pragma once
#include <cxxabi.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>
#include <typeinfo>

namespace nimbus::fuzz {

// A broken promise of the code under test that is not a crash by itself (an exception of the
// wrong type, a message that does not name the input or spans lines): reported like a crash, so
// that libFuzzer keeps the input and the replay fails.
[[noreturn]] inline void contract_failure(const std::string& what) {
  std::fprintf(stderr, "nimbus fuzz: contract broken: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

// One file the harness rewrites for every input (the readers under test take paths). It lives in
// $NIMBUS_FUZZ_TMPDIR, else $TMPDIR, else /tmp, is named after the process, and is removed when
// the process exits normally.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& suffix) {
    const char* dir = std::getenv("NIMBUS_FUZZ_TMPDIR");
    if (!dir || !*dir) dir = std::getenv("TMPDIR");
    if (!dir || !*dir) dir = "/tmp";
    path_ = std::string(dir) + "/nimbus-fuzz-" + std::to_string(::getpid()) + suffix;
  }
  ~ScratchFile() { ::unlink(path_.c_str()); }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  const std::string& path() const { return path_; }

  void write(std::string_view bytes) const {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    if (!f) {
      std::perror(path_.c_str());
      std::abort();  // the harness itself cannot work: not a finding, but never silent
    }
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size()) std::abort();
    if (std::fclose(f) != 0) std::abort();
  }

 private:
  std::string path_;
};

// The exception's dynamic type, demangled ("nlohmann::json_abi_v3_11_2::detail::type_error").
inline std::string type_name(const std::exception& e) {
  int status = 0;
  char* name = abi::__cxa_demangle(typeid(e).name(), nullptr, nullptr, &status);
  std::string out = status == 0 && name ? name : typeid(e).name();
  std::free(name);
  return out;
}

inline bool one_line(std::string_view s) { return !s.empty() && s.find('\n') == std::string_view::npos; }

}  // namespace nimbus::fuzz
