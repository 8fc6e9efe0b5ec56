// Private: what call_isolated (isolated_call.cpp) and serve_isolated_call (isolated_serve.cpp)
// agree on. The program is started as
//   PROGRAM --isolated-call MEMORY_BYTES ARGS...
// with its answer file (a memfd) as descriptor 3. It writes one status byte, then the body.
#pragma once

namespace nimbus::isolated {

inline constexpr int kAnswerFd = 3;
inline constexpr const char* kMarker = "--isolated-call";

// The status byte that starts the answer file.
inline constexpr char kAnswer = 'K';      // body: the answer
inline constexpr char kError = 'E';       // body: the exception's message
inline constexpr char kNoMemory = 'M';    // std::bad_alloc; no body
inline constexpr char kExecFailed = 'X';  // written by the forked child when exec fails; body: errno as text

}  // namespace nimbus::isolated
