// Limits on what nimbus reads from files and stdin, so that hostile input (a huge file,
// /dev/zero, a FIFO, 100,000 nested brackets) fails with one clear line before any parser runs
// away. The limits are documented in docs/reliability.md ("Input limits").
#pragma once
#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>
#include <string_view>

namespace nimbus {

// JSON files read whole (--params, sky files, view states, viewer scripts): at most 16 MiB,
// arrays and objects nested at most 64 deep. The shipped presets nest 4 deep and weigh 4 KiB.
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{16} << 20;
inline constexpr int kMaxJsonDepth = 64;

// Text read line by line from stdin (nimbus airlight's CSV rows): at most 4096 bytes a line,
// 1,000,000 lines and 64 MiB in all.
inline constexpr std::size_t kMaxStdinLineBytes = 4096;
inline constexpr std::size_t kMaxStdinLines = 1'000'000;
inline constexpr std::size_t kMaxStdinBytes = std::size_t{64} << 20;

// A value echoed in an error message: at most this many characters, then "...".
inline constexpr std::size_t kEchoChars = 40;

// The whole of the regular file `path`. std::runtime_error "<where>: ..." (`where` names the
// file as its caller's messages do: "--params p.json", "sky file 'p.json'") when it is missing,
// not a regular file (a directory, FIFO, device or socket: refused before it is opened, so a
// FIFO cannot block), unreadable, or larger than `max_bytes` (checked from its size before
// reading, and again while reading, for a file that grows).
std::string read_regular_file(const std::string& path, const std::string& where,
                              std::uintmax_t max_bytes = kMaxInputFileBytes);

// std::runtime_error "<what> '<path>': is a FIFO, not a regular file" when `path` exists and is
// not a regular file (a directory, FIFO, device or socket), for inputs that other readers open
// (VDB, EXR): a FIFO would block them, a device feed them without end. A missing file passes,
// for the reader to report.
void refuse_special_file(const std::string& path, const std::string& what);

// std::runtime_error "<what>: JSON nested deeper than <max_depth> levels" when `text` opens more
// than max_depth arrays or objects inside one another (brackets in strings do not count). A
// linear scan, cheap enough to run before every parse.
void check_json_depth(std::string_view text, const std::string& what, int max_depth = kMaxJsonDepth);

// Reads one line (without its '\n', and a '\r' before it) into `line`, at most `max_bytes`.
enum class LineRead { Line, End, TooLong };
LineRead read_line_limited(std::istream& in, std::string& line, std::size_t max_bytes = kMaxStdinLineBytes);

// `text` as an error message may echo it: its first kEchoChars characters then "..." when
// longer, control characters as '?', so one hostile value stays one short line.
std::string echo(std::string_view text, std::size_t max_chars = kEchoChars);

}  // namespace nimbus
