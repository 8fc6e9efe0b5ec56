// The isolated call (base/isolated_call.hpp): whatever the program does (crash, abort, allocate
// without end, loop for ever, throw, write to its output), the caller gets its answer or a clear
// IsolatedCallFailed with the right reason, and goes on. The program is a fresh process: nothing
// of the caller's (descriptors, blocked or ignored signals, raised limits) reaches it. The
// program here is tests/programs/isolated_probe.cpp.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
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

std::string probe(const IsolationLimits& limits, const std::vector<std::string>& args) {
  return call_isolated(limits, NIMBUS_ISOLATED_PROBE, args);
}

// Runs the probe and returns the failure's reason and message; fails the test if it answered.
std::pair<Reason, std::string> failure_of(const IsolationLimits& limits, const std::vector<std::string>& args) {
  try {
    probe(limits, args);
  } catch (const IsolatedCallFailed& e) {
    return {e.reason, e.what()};
  }
  ADD_FAILURE() << "the isolated call answered";
  return {Reason::ChildError, ""};
}

TEST(IsolatedCall, AnswerComesBackWhole) {
  // 8 MiB of every byte value, including NUL and the status bytes the protocol uses.
  const std::string answer = probe(small_limits(), {"pattern", std::to_string(size_t(8) << 20)});
  ASSERT_EQ(answer.size(), size_t(8) << 20);
  for (size_t i = 0; i < answer.size(); i += 4099) ASSERT_EQ(answer[i], char((i * 2654435761u) >> 13)) << i;
  EXPECT_EQ(probe(small_limits(), {"empty"}), "");
}

TEST(IsolatedCall, ASegfaultIsReportedAsACrash) {
  const auto [reason, message] = failure_of(small_limits(), {"segv"});
  EXPECT_EQ(reason, Reason::Crashed);
  EXPECT_NE(message.find(nimbus::test::kCrashesEndInAbort ? "SIGABRT" : "SIGSEGV"), std::string::npos) << message;
}

TEST(IsolatedCall, AnAbortIsReportedAsACrash) {
  const auto [reason, message] = failure_of(small_limits(), {"abort"});
  EXPECT_EQ(reason, Reason::Crashed);
  EXPECT_NE(message.find("SIGABRT"), std::string::npos) << message;
}

TEST(IsolatedCall, RunawayAllocationStopsAtTheMemoryLimit) {
  // 64 MiB blocks, touched, until something gives: the limit (256 MiB), not the machine.
  const auto [reason, message] = failure_of(small_limits(), {"allocate"});
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
  const auto [reason, message] = failure_of(small_limits(0.3), {"spin"});
  EXPECT_EQ(reason, Reason::TimedOut);
  EXPECT_NE(message.find("too long"), std::string::npos) << message;
}

TEST(IsolatedCall, TheTimerFiresEvenIfTheCallerBlocksOrIgnoresItsSignal) {
  // A caller (a render loop, a batch wrapper) may block SIGALRM or ignore it; exec keeps both.
  EXPECT_EXIT(
      {
        std::signal(SIGALRM, SIG_IGN);
        sigset_t alarm;
        sigemptyset(&alarm);
        sigaddset(&alarm, SIGALRM);
        sigaddset(&alarm, SIGXCPU);
        sigprocmask(SIG_BLOCK, &alarm, nullptr);
        bool timed_out = false;
        try {
          probe(small_limits(0.3), {"spin"});
        } catch (const IsolatedCallFailed& e) {
          timed_out = e.reason == Reason::TimedOut;
        }
        _exit(timed_out ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(IsolatedCall, AnAnswerLargerThanTheLimitIsRefused) {
  IsolationLimits l = small_limits();
  l.memory_bytes = uint64_t(96) << 20;  // the answer may hold at most this
  const auto [reason, message] = failure_of(l, {"bytes", std::to_string(size_t(120) << 20)});
  // Stopped by the answer file's size limit, or under ASan possibly by its abort on a failed new.
  EXPECT_TRUE(reason == Reason::OutOfMemory || (nimbus::test::kFailedNewAborts && reason == Reason::Crashed)) << message;
}

TEST(IsolatedCall, AnExceptionInTheProgramKeepsItsMessage) {
  const auto [reason, message] = failure_of(small_limits(), {"throw", "bad header"});
  EXPECT_EQ(reason, Reason::ChildError);
  EXPECT_EQ(message, "bad header");
}

TEST(IsolatedCall, TheProgramsOutputDoesNotReachTheCaller) {
  // The caller prints one error line; OpenVDB's warnings in the reader would add more.
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const std::string answer = probe(small_limits(), {"chatter"});
  const std::string out = testing::internal::GetCapturedStdout();
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(answer, "ok");
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
}

TEST(IsolatedCall, NoDescriptorOfTheCallerReachesTheProgram) {
  // A file the caller holds open without close-on-exec (an output being written, a socket).
  const int held = open("/proc/self/statm", O_RDONLY);
  ASSERT_GE(held, 0);
  const std::string answer = probe(small_limits(), {"limits"});
  close(held);
  // Standard streams (to /dev/null) and the answer file, nothing else; no core files either.
  EXPECT_EQ(answer.substr(answer.find(' ') + 1), "0 0,1,2,3") << answer;
}

TEST(IsolatedCall, LimitsTheProcessInheritedAreKeptNotRaised) {
  // A batch system's hard CPU limit below the call's time: the program must not try to raise it
  // (EPERM made every foreign file "damaged"). Run in a death-test child: hard limits stick.
  EXPECT_EXIT(
      {
        rlimit cpu{};
        getrlimit(RLIMIT_CPU, &cpu);
        cpu.rlim_cur = cpu.rlim_max = 100;
        setrlimit(RLIMIT_CPU, &cpu);
        // The answer starts with the hard CPU limit the program ran under (root could raise it).
        const std::string answer = probe(small_limits(300.0), {"limits"});
        _exit(answer.rfind("100 ", 0) == 0 ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(IsolatedCall, TheProgramMayUseThreads) {
  // A fresh process has a whole runtime (a forked copy had only the forking thread).
  EXPECT_EQ(probe(small_limits(), {"threads"}), "ok");
}

TEST(IsolatedCall, AProgramThatCannotStartIsAClearErrorNotACrash) {
  try {
    call_isolated(small_limits(), "/nonexistent/reader", {});
    ADD_FAILURE() << "a missing program answered";
  } catch (const IsolatedCallFailed& e) {
    ADD_FAILURE() << "reported as the input's fault: " << e.what();
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("/nonexistent/reader"), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file"), std::string::npos) << msg;
  }
}

TEST(IsolatedCall, TheProgramRunByHandSaysWhatItIsFor) {
  const int code = std::system((std::string(NIMBUS_ISOLATED_PROBE) + " pattern 5 2>/dev/null").c_str());
  ASSERT_TRUE(WIFEXITED(code));
  EXPECT_EQ(WEXITSTATUS(code), 2);
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
  EXPECT_THROW(probe(l, {"empty"}), std::invalid_argument);
  l = small_limits();
  l.memory_bytes = 0;
  EXPECT_THROW(probe(l, {"empty"}), std::invalid_argument);
}

}  // namespace
