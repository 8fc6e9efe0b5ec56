// Reading grids from untrusted VDB files in the isolated reader program (vdb_isolated.hpp).
#include "vdb_isolated.hpp"

#include <unistd.h>

#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <system_error>

#include "nimbus/base/isolated_call.hpp"
#include "vdb_common.hpp"
#include "vdb_open.hpp"
#include "vdb_seal.hpp"

namespace nimbus::volume::detail {
namespace {

constexpr const char* kReaderName = "nimbus-vdb-reader";

// A positive number from the environment, or `fallback`; std::invalid_argument naming it.
double env_number(const char* name, double fallback) {
  const char* text = std::getenv(name);
  if (!text) return fallback;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(v > 0.0 && v < 1e7))
    throw std::invalid_argument(std::string(name) + ": '" + text + "' must be a number > 0");
  return v;
}

bool is_program(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec) && access(p.c_str(), X_OK) == 0;
}

}  // namespace

static std::mutex g_program_mutex;
static std::filesystem::path g_program;  // set_vdb_reader_program

std::filesystem::path vdb_reader_program() {
  if (const char* set = std::getenv("NIMBUS_VDB_READER")) {
    if (!is_program(set))
      throw std::invalid_argument(std::string("NIMBUS_VDB_READER: '") + set + "' is not an executable file");
    return set;
  }
  {
    const std::lock_guard<std::mutex> lock(g_program_mutex);
    if (!g_program.empty() && is_program(g_program)) return g_program;
  }
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path beside = ec ? std::filesystem::path() : self.parent_path() / kReaderName;
  if (!beside.empty() && is_program(beside)) return beside;
#ifdef NIMBUS_VDB_READER_BUILD_PATH
  if (is_program(NIMBUS_VDB_READER_BUILD_PATH)) return NIMBUS_VDB_READER_BUILD_PATH;
#endif
  throw std::runtime_error(std::string("cannot find ") + kReaderName + ", the program that reads foreign VDB files (looked beside " +
                           (beside.empty() ? std::string("this program") : self.string()) +
                           "); install it there or set NIMBUS_VDB_READER to its path");
}

GridsRead read_grids(const std::filesystem::path& path, const GridRequest& request, const VdbReadLimits& limits) {
  const std::string file = path.string();
  check_regular_file(path);
  init_openvdb();
  if (check_vdb_seal(path) == Seal::Verified) {  // nimbus's own file, intact: read here
    OpenedVdb vdb = open_vdb(path, /*seal_verified=*/true);
    GridsRead out;
    out.read = read_chosen_grids(vdb, path, request);
    out.metadata = std::move(vdb.metadata);
    out.grids = std::move(vdb.grids);
    out.checksum_verified = vdb.checksum_verified;
    return out;
  }

  IsolationLimits il;
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(path, ec);
  il.memory_bytes = limits.memory_bytes ? limits.memory_bytes
                                        : uint64_t(env_number("NIMBUS_READ_MEMORY_GB", 0.0) * double(uint64_t(1) << 30));
  if (il.memory_bytes == 0) il.memory_bytes = isolation_memory_for_file(ec ? 0 : size);
  // 20 s, and 1 s more per 5 MB of file: a sound file reads at hundreds of MB/s, while a 10 KB
  // hostile one kept OpenVDB's readTopology busy for 75 CPU seconds.
  il.seconds = limits.seconds > 0.0 ? limits.seconds
                                    : env_number("NIMBUS_READ_SECONDS", 20.0 + double(ec ? 0 : size) / 5e6);
  std::vector<std::string> args{file};  // the program starts in this directory: same path, same messages
  for (std::string& w : request_to_words(request)) args.push_back(std::move(w));
  std::string answer;
  try {
    answer = call_isolated(il, vdb_reader_program(), args);
  } catch (const IsolatedCallFailed& e) {
    using R = IsolatedCallFailed::Reason;
    const char* hint = e.reason == R::OutOfMemory ? "; if the file is sound, raise NIMBUS_READ_MEMORY_GB"
                       : e.reason == R::TimedOut  ? "; if the file is sound, raise NIMBUS_READ_SECONDS"
                                                  : "";
    throw std::runtime_error(file + ": " + one_line(e.what()) + hint);
  } catch (const std::exception& e) {  // the reader program could not be found or started
    throw std::runtime_error(file + ": cannot read it: " + one_line(e.what()));
  }
  try {
    return decode_answer(answer);
  } catch (const GridNotFound&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw std::runtime_error(file + ": its grids do not fit in memory");
  } catch (const std::exception& e) {
    const std::string what = one_line(e.what());
    if (what.rfind(file, 0) == 0) throw std::runtime_error(what);
    throw std::runtime_error(file + ": " + what);
  }
}

}  // namespace nimbus::volume::detail

namespace nimbus::volume {

void set_vdb_reader_program(const std::filesystem::path& program) {
  const std::lock_guard<std::mutex> lock(detail::g_program_mutex);
  detail::g_program = program;
}

}  // namespace nimbus::volume
