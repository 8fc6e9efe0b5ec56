// OpenVDB start-up, metadata conversion and message clean-up for the VDB input/output.
#include "vdb_common.hpp"

#include <mutex>

namespace nimbus::volume::detail {

void init_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

openvdb::MetaMap to_meta_map(const Metadata& metadata) {
  openvdb::MetaMap meta;
  for (const auto& [key, value] : metadata) {
    if (meta[key]) meta.removeMeta(key);  // a key's type cannot change in place
    if (const auto* s = std::get_if<std::string>(&value)) meta.insertMeta(key, openvdb::StringMetadata(*s));
    else if (const auto* d = std::get_if<double>(&value)) meta.insertMeta(key, openvdb::DoubleMetadata(*d));
    else meta.insertMeta(key, openvdb::Int64Metadata(std::get<int64_t>(value)));
  }
  return meta;
}

Metadata from_meta_map(const openvdb::MetaMap& meta) {
  Metadata out;
  for (auto it = meta.beginMeta(); it != meta.endMeta(); ++it) {
    const openvdb::Metadata& m = *it->second;
    const std::string type = m.typeName();
    MetaValue value;
    if (type == openvdb::StringMetadata::staticTypeName())
      value = static_cast<const openvdb::StringMetadata&>(m).value();
    else if (type == openvdb::DoubleMetadata::staticTypeName())
      value = static_cast<const openvdb::DoubleMetadata&>(m).value();
    else if (type == openvdb::FloatMetadata::staticTypeName())
      value = double(static_cast<const openvdb::FloatMetadata&>(m).value());
    else if (type == openvdb::Int64Metadata::staticTypeName())
      value = int64_t(static_cast<const openvdb::Int64Metadata&>(m).value());
    else if (type == openvdb::Int32Metadata::staticTypeName())
      value = int64_t(static_cast<const openvdb::Int32Metadata&>(m).value());
    else if (type == openvdb::BoolMetadata::staticTypeName())
      value = int64_t(static_cast<const openvdb::BoolMetadata&>(m).value());
    else
      value = m.str();
    out.emplace_back(it->first, std::move(value));
  }
  return out;
}

std::string one_line(std::string text) {
  // A damaged file's bytes can come back inside OpenVDB's message (a 98-byte file once gave a
  // 1.9 GB line): keep the head, which says what went wrong.
  constexpr size_t kMax = 400;
  if (text.size() > kMax) text = text.substr(0, kMax) + "... (" + std::to_string(text.size() - kMax) + " more bytes)";
  for (char& c : text)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace nimbus::volume::detail
