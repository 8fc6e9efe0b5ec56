// The isolated child (base/isolated_call.hpp): whatever the work does (crash, abort, allocate
// without end, loop for ever, throw), the caller gets its answer or a clear IsolatedCallFailed
// with the right reason, and goes on.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <cstdlib>
#include <vector>

#include "nimbus/base/isolated_call.hpp"
#include "nimbus/base/memory.hpp"
#include "support/sanitizer.hpp"

namespace {

using nimbus::call_isolated;
using nimbus::IsolatedCallFailed;
using nimbus::IsolationLimits;
using Reason = IsolatedCallFailed::Reason;

IsolationLimits small_limits(double seconds = 60.0) {
  IsolationLimits l;
  l.memory_bytes = uint64_t(256) << 20;
  l.seconds = seconds;
  return l;
}

// Runs `work` isolated and returns the failure's reason and message; fails the test if it answered.
std::pair<Reason, std::string> failure_of(const IsolationLimits& limits, const std::function<void(std::string&)>& work) {
  try {
    call_isolated(limits, work);
  } catch (const IsolatedCallFailed& e) {
    return {e.reason, e.what()};
  }
  ADD_FAILURE() << "the isolated call answered";
  return {Reason::ChildError, ""};
}

TEST(IsolatedCall, AnswerComesBackWhole) {
  // 8 MiB of every byte value, including NUL and the status bytes the protocol uses.
  const std::string answer = call_isolated(small_limits(), [](std::string& out) {
    out.resize(size_t(8) << 20);
    for (size_t i = 0; i < out.size(); ++i) out[i] = char((i * 2654435761u) >> 13);
  });
  ASSERT_EQ(answer.size(), size_t(8) << 20);
  for (size_t i = 0; i < answer.size(); i += 4099) ASSERT_EQ(answer[i], char((i * 2654435761u) >> 13)) << i;
  EXPECT_EQ(call_isolated(small_limits(), [](std::string&) {}), "");
}

TEST(IsolatedCall, ASegfaultIsReportedAsACrash) {
  const auto [reason, message] = failure_of(small_limits(), [](std::string&) { std::raise(SIGSEGV); });
  EXPECT_EQ(reason, Reason::Crashed);
  EXPECT_NE(message.find("SIGSEGV"), std::string::npos) << message;
}

TEST(IsolatedCall, AnAbortIsReportedAsACrash) {
  const auto [reason, message] = failure_of(small_limits(), [](std::string&) { std::abort(); });
  EXPECT_EQ(reason, Reason::Crashed);
  EXPECT_NE(message.find("SIGABRT"), std::string::npos) << message;
}

TEST(IsolatedCall, RunawayAllocationStopsAtTheMemoryLimit) {
  // 64 MiB blocks, touched, until something gives: the limit (256 MiB), not the machine.
  const auto [reason, message] = failure_of(small_limits(), [](std::string& out) {
    std::vector<std::vector<char>> blocks;
    for (int i = 0; i < 4096; ++i) blocks.emplace_back(size_t(64) << 20, char(i));
    out = "allocated 256 GiB";
  });
  if (nimbus::test::kFailedNewAborts) {  // stopped at the limit by ASan's abort (sanitizer.hpp)
    EXPECT_EQ(reason, Reason::Crashed) << message;
    EXPECT_NE(message.find("SIGABRT"), std::string::npos) << message;
    return;
  }
  EXPECT_EQ(reason, Reason::OutOfMemory);
  EXPECT_NE(message.find("memory"), std::string::npos) << message;
  EXPECT_NE(message.find("0.25 GiB"), std::string::npos) << message;
}

TEST(IsolatedCall, AnEndlessLoopStopsAtTheTimeLimit) {
  const auto [reason, message] = failure_of(small_limits(0.3), [](std::string&) {
    volatile uint64_t n = 0;
    for (;;) n = n + 1;
  });
  EXPECT_EQ(reason, Reason::TimedOut);
  EXPECT_NE(message.find("too long"), std::string::npos) << message;
}

TEST(IsolatedCall, AnAnswerLargerThanTheLimitIsRefused) {
  IsolationLimits l = small_limits();
  l.memory_bytes = uint64_t(96) << 20;  // the answer may hold at most this
  const auto [reason, message] = failure_of(l, [](std::string& out) { out.assign(size_t(120) << 20, 'x'); });
  EXPECT_EQ(reason, nimbus::test::kFailedNewAborts ? Reason::Crashed : Reason::OutOfMemory) << message;
}

TEST(IsolatedCall, AnExceptionInTheChildKeepsItsMessage) {
  const auto [reason, message] = failure_of(small_limits(), [](std::string&) { throw std::runtime_error("bad header"); });
  EXPECT_EQ(reason, Reason::ChildError);
  EXPECT_EQ(message, "bad header");
}

TEST(IsolatedCall, TheChildsWritesDoNotReachTheParent) {
  // The child's memory is its own: what it changes here is lost when it ends.
  static int touched = 0;
  call_isolated(small_limits(), [](std::string&) { touched = 42; });
  EXPECT_EQ(touched, 0);
}

TEST(IsolatedCall, LimitsTheProcessInheritedAreKeptNotRaised) {
  // A batch system's hard CPU limit below the call's time: the child must not try to raise it
  // (EPERM made every foreign file "damaged"). Run in a death-test child: hard limits stick.
  EXPECT_EXIT(
      {
        rlimit cpu{};
        getrlimit(RLIMIT_CPU, &cpu);
        cpu.rlim_cur = cpu.rlim_max = 100;
        setrlimit(RLIMIT_CPU, &cpu);
        IsolationLimits l = small_limits(300.0);
        // The answer: the hard CPU limit the work ran under (root could raise it; it must not).
        const std::string answer = call_isolated(l, [](std::string& out) {
          rlimit r{};
          getrlimit(RLIMIT_CPU, &r);
          out = std::to_string(r.rlim_max);
        });
        const bool ok = answer == "100";
        _exit(ok ? 0 : 1);  // no static destructors: a forked child has no TBB workers to join
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(IsolatedCall, AvailableMemoryHonoursTheAddressSpaceLimit) {
  // ulimit -v 200 MB more than in use: a request for 1 GiB must be refused before allocating,
  // whatever the machine has free.
  EXPECT_EXIT(
      {
        std::ifstream statm("/proc/self/statm");
        uint64_t pages = 0;
        statm >> pages;
        const uint64_t used = pages * uint64_t(sysconf(_SC_PAGE_SIZE));
        rlimit as{};
        getrlimit(RLIMIT_AS, &as);
        as.rlim_cur = used + (uint64_t(200) << 20);
        setrlimit(RLIMIT_AS, &as);
        const bool ok = nimbus::available_memory_bytes() <= (uint64_t(200) << 20);
        bool refused = false;
        try {
          nimbus::ensure_fits_in_memory(uint64_t(1) << 28, 4, "a test grid");
        } catch (const nimbus::OutOfMemoryRequest&) {
          refused = true;
        }
        _exit(ok && refused ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(IsolatedCall, BadLimitsAreRefused) {
  IsolationLimits l = small_limits();
  l.seconds = 0.0;
  EXPECT_THROW(call_isolated(l, [](std::string&) {}), std::invalid_argument);
  l = small_limits();
  l.memory_bytes = 0;
  EXPECT_THROW(call_isolated(l, [](std::string&) {}), std::invalid_argument);
}

}  // namespace
