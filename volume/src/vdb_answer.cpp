// The isolated reader's answer, written and read (vdb_answer.hpp).
#include "vdb_answer.hpp"

#include <openvdb/io/Stream.h>

#include <cstring>
#include <sstream>
#include <stdexcept>

#include "vdb_common.hpp"

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

}  // namespace

void encode_answer(const OpenedVdb& vdb, const openvdb::GridPtrVec& read, std::string& out) {
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
  vdb_stream.setGridStatsMetadataEnabled(false);  // the caller computes what it needs
  vdb_stream.write(openvdb::GridCPtrVec(read.begin(), read.end()));
  out += stream.str();
}

GridsRead decode_answer(const std::string& answer) {
  if (answer.empty()) throw std::runtime_error("the reader's answer is empty");
  // The reader's messages quote the file's own names and bytes: one line, bounded.
  if (answer[0] == 'G') throw GridNotFound(one_line(answer.substr(1, 4096)));
  if (answer[0] == 'R') throw std::runtime_error(one_line(answer.substr(1, 4096)));
  if (answer[0] != 'K') throw std::runtime_error("the reader's answer is malformed");
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

}  // namespace nimbus::volume::detail
