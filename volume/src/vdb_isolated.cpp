// Reading grids from untrusted VDB files in a child process (vdb_isolated.hpp).
//
// The child's answer: one kind byte, then
//   'K': u8 checksum_verified, u32 metadata count, per entry (str key, u8 type, value),
//        u32 grid count, per grid (str name, str value type), then OpenVDB's stream of the
//        chosen grids (io::Stream, active-mask compression, half floats kept as stored);
//   'G': a GridNotFound message;   'R': any other error message.
// Strings are u32 length + bytes; numbers little-endian as in memory (same machine).
#include "vdb_isolated.hpp"

#include <openvdb/io/Stream.h>

#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "nimbus/base/isolated_call.hpp"
#include "vdb_common.hpp"
#include "vdb_open.hpp"
#include "vdb_seal.hpp"

namespace nimbus::volume::detail {
namespace {

struct Writer {
  std::string& out;
  template <class T>
  void put(T v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void str(const std::string& s) {
    put(uint32_t(s.size()));
    out += s;
  }
};

struct Reader {
  const std::string& in;
  size_t at = 0;
  void need(size_t n) const {
    if (n > in.size() - at) throw std::runtime_error("the reader's answer is truncated");
  }
  template <class T>
  T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  std::string str() {
    const uint32_t n = get<uint32_t>();
    need(n);
    std::string s = in.substr(at, n);
    at += n;
    return s;
  }
};

void encode(const OpenedVdb& vdb, const openvdb::GridPtrVec& read, std::string& out) {
  Writer w{out};
  w.put(char('K'));
  w.put(uint8_t(vdb.checksum_verified));
  w.put(uint32_t(vdb.metadata.size()));
  for (const auto& [key, value] : vdb.metadata) {
    w.str(key);
    w.put(uint8_t(value.index()));
    if (const auto* s = std::get_if<std::string>(&value)) w.str(*s);
    else if (const auto* d = std::get_if<double>(&value)) w.put(*d);
    else w.put(std::get<int64_t>(value));
  }
  w.put(uint32_t(vdb.grids.size()));
  for (const GridInfo& g : vdb.grids) {
    w.str(g.name);
    w.str(g.value_type);
  }
  std::ostringstream stream(std::ios::binary);
  openvdb::io::Stream vdb_stream(stream);
  vdb_stream.setCompression(openvdb::io::COMPRESS_ACTIVE_MASK);
  vdb_stream.setGridStatsMetadataEnabled(false);  // its voxel counts run on threads, which a forked child lacks
  vdb_stream.write(openvdb::GridCPtrVec(read.begin(), read.end()));
  out += stream.str();
}

GridsRead decode(const std::string& answer, const std::string& file) {
  if (answer.empty()) throw std::runtime_error(file + ": the reader's answer is empty");
  // The child's messages quote the file's own names and bytes: one line, bounded.
  if (answer[0] == 'G') throw GridNotFound(one_line(answer.substr(1, 4096)));
  if (answer[0] == 'R') throw std::runtime_error(one_line(answer.substr(1, 4096)));
  GridsRead out;
  Reader r{answer, 1};
  out.checksum_verified = r.get<uint8_t>() != 0;
  const uint32_t n_meta = r.get<uint32_t>();
  for (uint32_t i = 0; i < n_meta; ++i) {
    std::string key = r.str();
    const uint8_t type = r.get<uint8_t>();
    MetaValue value;
    if (type == 0) value = r.str();
    else if (type == 1) value = r.get<double>();
    else if (type == 2) value = r.get<int64_t>();
    else throw std::runtime_error("the reader's answer is malformed");
    out.metadata.emplace_back(std::move(key), std::move(value));
  }
  const uint32_t n_grids = r.get<uint32_t>();
  for (uint32_t i = 0; i < n_grids; ++i) {
    GridInfo g;
    g.name = r.str();
    g.value_type = r.str();
    out.grids.push_back(std::move(g));
  }
  std::istringstream stream(answer.substr(r.at), std::ios::binary);
  openvdb::io::Stream vdb_stream(stream);
  out.read = *vdb_stream.getGrids();
  out.read_in_child = true;
  return out;
}

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

}  // namespace

GridsRead read_grids(const std::filesystem::path& path, const GridChoice& choose, const VdbReadLimits& limits) {
  const std::string file = path.string();
  check_regular_file(path);
  init_openvdb();
  if (check_vdb_seal(path) == Seal::Verified) {  // nimbus's own file, intact: read here
    OpenedVdb vdb = open_vdb(path, /*seal_verified=*/true);
    GridsRead out;
    for (const std::string& name : choose(vdb.grids)) out.read.push_back(read_grid(vdb, path, name));
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
  std::string answer;
  try {
    answer = call_isolated(il, [&](std::string& out) {
      try {
        OpenedVdb vdb = open_vdb(path);
        openvdb::GridPtrVec read;
        for (const std::string& name : choose(vdb.grids)) read.push_back(read_grid(vdb, path, name));
        encode(vdb, read, out);
      } catch (const GridNotFound& e) {
        out = std::string("G") + e.what();
      } catch (const std::bad_alloc&) {
        throw;  // reported as the limit it is
      } catch (const std::exception& e) {
        out = std::string("R") + e.what();
      }
    });
  } catch (const IsolatedCallFailed& e) {
    using R = IsolatedCallFailed::Reason;
    const char* hint = e.reason == R::OutOfMemory ? "; if the file is sound, raise NIMBUS_READ_MEMORY_GB"
                       : e.reason == R::TimedOut  ? "; if the file is sound, raise NIMBUS_READ_SECONDS"
                                                  : "";
    throw std::runtime_error(file + ": " + one_line(e.what()) + hint);
  }
  try {
    return decode(answer, file);
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
