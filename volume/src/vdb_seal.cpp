// Whole-file CRC-32 seal and content-derived UUID for VDB files (see vdb_seal.hpp).
#include "vdb_seal.hpp"

#include <zlib.h>

#include <algorithm>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <vector>

namespace nimbus::volume::detail {
namespace {

constexpr size_t kHeadBytes = size_t(1) << 20;   // the file metadata lies at the start
constexpr size_t kChunkBytes = size_t(4) << 20;
constexpr const char* kZeroUuid = "00000000-0000-0000-0000-000000000000";
constexpr size_t kUuidWithin = 64;  // the header UUID follows magic, versions and a flag

struct SealValue {
  uint32_t crc = 0;
  uint64_t bytes = 0;
  std::string uuid = kZeroUuid;
};

std::string format(const SealValue& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "crc32=%08" PRIx32 " bytes=%016" PRIu64 " uuid=%s", v.crc, v.bytes, v.uuid.c_str());
  return buf;
}

// Strict: only text that format() would produce.
std::optional<SealValue> parse(const std::string& text) {
  SealValue v;
  char uuid[37] = {};
  if (std::sscanf(text.c_str(), "crc32=%8" SCNx32 " bytes=%16" SCNu64 " uuid=%36s", &v.crc, &v.bytes, uuid) != 3)
    return std::nullopt;
  v.uuid = uuid;
  if (v.uuid.size() != std::strlen(kZeroUuid) || format(v) != text) return std::nullopt;
  return v;
}

// MetaMap::writeMeta stores an entry as u32 length + key, u32 length + type name, u32 size +
// value (little-endian on every platform OpenVDB supports).
std::string entry_prefix() {
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const std::string key = kChecksumKey, type = "string";
  return u32(uint32_t(key.size())) + key + u32(uint32_t(type.size())) + type +
         u32(uint32_t(checksum_placeholder().size()));
}

struct Window {
  uint64_t offset;
  std::string bytes;  // read in place of the file's bytes at offset
};

struct Digest {
  uint32_t crc = 0;
  uint64_t mix = 0;  // a second, independent 64-bit hash (for the UUID)
};

// One pass over the file with the windows' bytes substituted. `mix` also computes Digest::mix.
Digest digest(std::ifstream& in, uint64_t size, const std::vector<Window>& windows, bool mix,
              const std::string& who) {
  in.clear();
  in.seekg(0);
  Digest d;
  d.crc = uint32_t(crc32_z(0L, Z_NULL, 0));
  uint64_t h = 0xcbf29ce484222325ull;
  std::vector<char> buf(kChunkBytes);
  for (uint64_t pos = 0; pos < size;) {
    const size_t n = size_t(std::min<uint64_t>(kChunkBytes, size - pos));
    if (!in.read(buf.data(), std::streamsize(n))) throw std::runtime_error(who + ": read error");
    for (const Window& w : windows) {
      const uint64_t lo = std::max(pos, w.offset), hi = std::min(pos + n, w.offset + w.bytes.size());
      if (lo < hi) std::memcpy(buf.data() + (lo - pos), w.bytes.data() + (lo - w.offset), size_t(hi - lo));
    }
    d.crc = uint32_t(crc32_z(d.crc, reinterpret_cast<const Bytef*>(buf.data()), n));
    if (mix) {  // FNV-1a over 8-byte words, with a shift to fold the high bits down
      size_t i = 0;
      for (uint64_t w; i + 8 <= n; i += 8) {
        std::memcpy(&w, buf.data() + i, 8);
        h = (h ^ w) * 0x100000001b3ull;
        h ^= h >> 29;
      }
      for (; i < n; ++i) h = (h ^ uint8_t(buf[i])) * 0x100000001b3ull;
    }
    pos += n;
  }
  d.mix = h;
  return d;
}

std::string read_head(std::ifstream& in, uint64_t size, const std::string& who) {
  std::string head(size_t(std::min<uint64_t>(size, kHeadBytes)), '\0');
  in.seekg(0);
  if (!in.read(head.data(), std::streamsize(head.size()))) throw std::runtime_error(who + ": read error");
  return head;
}

// Offset of the seal's value, if the file carries one.
std::optional<uint64_t> find_seal(const std::string& head) {
  const std::string prefix = entry_prefix();
  const size_t at = head.find(prefix);
  if (at == std::string::npos) return std::nullopt;
  return uint64_t(at + prefix.size());
}

}  // namespace

std::string checksum_placeholder() { return format(SealValue{}); }

std::optional<std::string> seal_uuid(const std::string& value) {
  const auto v = parse(value);
  return v ? std::optional<std::string>(v->uuid) : std::nullopt;
}

void seal_vdb_file(const std::filesystem::path& file, const std::string& uuid,
                   const std::filesystem::path& display) {
  const std::string who = "cannot write " + display.string();
  const auto fail = [&](const std::string& what) { return std::runtime_error(who + ": " + what); };
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(file, ec);
  if (ec) throw fail(ec.message());
  std::ifstream in(file, std::ios::binary);
  if (!in) throw fail("cannot reopen the file to seal it");
  const std::string head = read_head(in, size, who);
  const auto value_at = find_seal(head);
  const size_t uuid_at = head.find(uuid);
  if (!value_at || uuid.size() != std::strlen(kZeroUuid) || uuid_at == std::string::npos || uuid_at > kUuidWithin)
    throw fail("unexpected OpenVDB file layout (no checksum field or header UUID)");

  // The UUID comes from the content with the UUID and checksum fields blanked ...
  const Window blank_seal{*value_at, checksum_placeholder()};
  const Digest content = digest(in, size, {Window{uuid_at, kZeroUuid}, blank_seal}, true, who);
  char id[40];
  const uint64_t m = content.mix;
  std::snprintf(id, sizeof id, "%08" PRIx32 "-%04x-%04x-%04x-%012" PRIx64, uint32_t(m >> 32),
                unsigned(m >> 16) & 0xffffu, unsigned(m) & 0xffffu, unsigned(content.crc >> 16),
                ((uint64_t(content.crc) & 0xffffu) << 32) | (size & 0xffffffffu));
  // ... and the CRC covers the final UUID with the checksum field blanked.
  const Digest final_digest = digest(in, size, {Window{uuid_at, id}, blank_seal}, false, who);
  in.close();

  std::fstream out(file, std::ios::binary | std::ios::in | std::ios::out);
  const std::string value = format(SealValue{final_digest.crc, size, id});
  out.seekp(std::streamoff(uuid_at));
  out.write(id, std::streamsize(std::strlen(id)));
  out.seekp(std::streamoff(*value_at));
  out.write(value.data(), std::streamsize(value.size()));
  out.flush();
  if (!out) throw fail("cannot write the checksum");
}

Seal check_vdb_seal(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(file, ec);
  if (ec) throw std::runtime_error(name + ": " + ec.message());
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(name + ": cannot open for reading");
  const std::string head = read_head(in, size, name);
  const auto value_at = find_seal(head);
  if (!value_at) {
    // The key without the type and size that follow it in a seal: those bytes are damaged.
    if (head.find(entry_prefix().substr(0, 4 + std::strlen(kChecksumKey))) != std::string::npos)
      throw std::runtime_error(name + ": corrupt VDB file (its checksum field is damaged)");
    return Seal::Absent;
  }
  const size_t len = checksum_placeholder().size();
  if (*value_at + len > head.size()) throw std::runtime_error(name + ": truncated VDB file (it ends inside its metadata)");
  const auto seal = parse(head.substr(size_t(*value_at), len));
  if (!seal) throw std::runtime_error(name + ": corrupt VDB file (its checksum field is damaged)");
  // Another writer that copied nimbus's file metadata (pyopenvdb's readAll + write, say) gives
  // the file a new header UUID: the seal then describes some earlier file, not this one.
  const size_t uuid_at = head.find(seal->uuid);
  if (uuid_at == std::string::npos || uuid_at > kUuidWithin) return Seal::Absent;
  if (seal->bytes != size)
    throw std::runtime_error(name + (size < seal->bytes ? ": truncated VDB file (" : ": corrupt VDB file (") +
                             std::to_string(size) + " bytes, written as " + std::to_string(seal->bytes) + ")");
  const Digest d = digest(in, size, {Window{*value_at, checksum_placeholder()}}, false, name);
  if (d.crc != seal->crc)
    throw std::runtime_error(name + ": corrupt VDB file (CRC-32 mismatch: its bytes changed after writing)");
  return Seal::Verified;
}

}  // namespace nimbus::volume::detail
