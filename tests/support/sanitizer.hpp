// What a sanitized build changes for tests of memory limits.
#pragma once

namespace nimbus::test {

// Under AddressSanitizer a failed operator new aborts the process (SIGABRT with the tests'
// ASAN_OPTIONS abort_on_error=1) where glibc's throws std::bad_alloc, whatever
// allocator_may_return_null says (google/sanitizers#295). A child stopped at its memory limit then
// ends as a crash rather than as an out-of-memory answer: stopped all the same.
//
// Likewise a program started fresh installs ASan's own crash handlers: its segmentation fault is
// an ASan report, then an abort.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kFailedNewAborts = true;
inline constexpr bool kCrashesEndInAbort = true;
#else
inline constexpr bool kFailedNewAborts = false;
inline constexpr bool kCrashesEndInAbort = false;
#endif

}  // namespace nimbus::test
