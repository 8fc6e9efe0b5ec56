// A program for the isolated-call tests (tests/cpu/test_isolated_call.cpp): started by
// call_isolated, it does what its first word asks, so that every way a reader can end is tried.
//   pattern N      answer N bytes of a fixed pattern (every byte value)
//   empty          answer nothing
//   segv | abort   crash
//   allocate       64 MiB blocks, touched, until something gives
//   spin           loop for ever
//   bytes N        answer N bytes of 'x'
//   throw MESSAGE  throw std::runtime_error(MESSAGE)
//   chatter        write to stdout and stderr, answer "ok"
//   limits         answer the hard RLIMIT_CPU, RLIMIT_CORE's soft limit, and the open descriptors
//   threads        start 4 threads that allocate, join them, answer "ok"
#include <dirent.h>
#include <sys/resource.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "nimbus/base/isolated_call.hpp"

namespace {

std::string open_descriptors() {
  std::string out;
  DIR* dir = opendir("/proc/self/fd");
  if (!dir) return "?";
  const int own = dirfd(dir);
  while (const dirent* e = readdir(dir)) {
    if (e->d_name[0] == '.' || std::atoi(e->d_name) == own) continue;
    out += std::string(out.empty() ? "" : ",") + e->d_name;
  }
  closedir(dir);
  return out;
}

void probe(const std::vector<std::string>& args, std::string& out) {
  const std::string what = args.empty() ? "" : args[0];
  const auto n = [&] { return size_t(std::stoull(args.at(1))); };
  if (what == "pattern") {
    out.resize(n());
    for (size_t i = 0; i < out.size(); ++i) out[i] = char((i * 2654435761u) >> 13);
  } else if (what == "empty") {
  } else if (what == "segv") {
    std::raise(SIGSEGV);
  } else if (what == "abort") {
    std::abort();
  } else if (what == "allocate") {
    std::vector<std::vector<char>> blocks;
    for (int i = 0; i < 4096; ++i) blocks.emplace_back(size_t(64) << 20, char(i));
    out = "allocated 256 GiB";
  } else if (what == "spin") {
    volatile unsigned long long k = 0;
    for (;;) k = k + 1;
  } else if (what == "bytes") {
    out.assign(n(), 'x');
  } else if (what == "throw") {
    throw std::runtime_error(args.at(1));
  } else if (what == "chatter") {
    std::cout << "probe on stdout" << std::endl;
    std::cerr << "probe on stderr" << std::endl;
    std::printf("printf on stdout\n");
    std::fflush(stdout);
    out = "ok";
  } else if (what == "limits") {
    rlimit cpu{}, core{};
    getrlimit(RLIMIT_CPU, &cpu);
    getrlimit(RLIMIT_CORE, &core);
    out = std::to_string(cpu.rlim_max) + " " + std::to_string(core.rlim_cur) + " " + open_descriptors();
  } else if (what == "threads") {
    std::vector<std::thread> threads;
    std::vector<long> sums(4, 0);
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([&sums, t] {
        for (int i = 0; i < 1000; ++i) sums[size_t(t)] += std::vector<char>(size_t(1) << 16, char(i & 1))[size_t(i)];
      });
    for (std::thread& t : threads) t.join();
    out = sums == std::vector<long>(4, 500) ? "ok" : "wrong sums";
  } else {
    throw std::invalid_argument("unknown probe '" + what + "'");
  }
}

}  // namespace

int main(int argc, char** argv) { return nimbus::serve_isolated_call(argc, argv, probe); }
