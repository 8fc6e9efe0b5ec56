// Cutting a field into 128-voxel-aligned bricks, tagging brick files, and joining them.
#include "nimbus/volume/brick.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <map>
#include <optional>
#include <regex>
#include <stdexcept>

#include "nimbus/volume/preset.hpp"
#include "nimbus/volume/up_axis.hpp"
#include "nimbus/volume/vdb_read.hpp"
#include "vdb_seal.hpp"

namespace nimbus::volume {
namespace {

constexpr const char* kIndexKey = "brick_index";
constexpr const char* kLayoutKey = "brick_layout";
constexpr const char* kBoxKey = "brick_box";
constexpr const char* kFieldBoxKey = "field_box";
constexpr const char* kFieldIdKey = "field_id";
constexpr const char* kStorageKey = "brick_half_float";

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// 128-voxel blocks the field spans along axis a: first block and count.
std::pair<int, int> blocks(const openvdb::CoordBBox& field, int a) {
  const int b0 = floor_div(field.min()[a], kBrickAlign), b1 = floor_div(field.max()[a], kBrickAlign);
  return {b0, b1 - b0 + 1};
}

std::string box_text(const openvdb::CoordBBox& b) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%d %d %d %d %d %d", b.min().x(), b.min().y(), b.min().z(), b.max().x(),
                b.max().y(), b.max().z());
  return buf;
}

std::optional<openvdb::CoordBBox> parse_box(const std::string& text) {
  int v[6];
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d %d %d %d %d %d%c", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &tail) != 6)
    return std::nullopt;
  return openvdb::CoordBBox(openvdb::Coord(v[0], v[1], v[2]), openvdb::Coord(v[3], v[4], v[5]));
}

const MetaValue* find(const Metadata& m, const std::string& key) {
  for (const auto& [k, v] : m)
    if (k == key) return &v;
  return nullptr;
}
std::optional<std::string> get_string(const Metadata& m, const std::string& key) {
  const MetaValue* v = find(m, key);
  if (v && std::holds_alternative<std::string>(*v)) return std::get<std::string>(*v);
  return std::nullopt;
}
std::optional<int64_t> get_int(const Metadata& m, const std::string& key) {
  const MetaValue* v = find(m, key);
  if (v && std::holds_alternative<int64_t>(*v)) return std::get<int64_t>(*v);
  return std::nullopt;
}
std::optional<double> get_double(const Metadata& m, const std::string& key) {
  const MetaValue* v = find(m, key);
  if (v && std::holds_alternative<double>(*v)) return std::get<double>(*v);
  if (v && std::holds_alternative<int64_t>(*v)) return double(std::get<int64_t>(*v));
  return std::nullopt;
}
std::string value_text(const Metadata& m, const std::string& key) {
  const MetaValue* v = find(m, key);
  if (!v) return "(none)";
  if (const auto* s = std::get_if<std::string>(v)) return "'" + *s + "'";
  if (const auto* i = std::get_if<int64_t>(v)) return std::to_string(*i);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", std::get<double>(*v));
  return buf;
}

// One brick file as read: its tag and grids.
struct BrickFile {
  std::filesystem::path path;
  BrickTag tag;
  Metadata metadata;
  openvdb::CoordBBox box;
  std::vector<openvdb::FloatGrid::Ptr> grids;  // z-up, density first
};

std::runtime_error brick_error(const std::filesystem::path& path, const std::string& what) {
  return std::runtime_error(path.string() + ": " + what);
}

BrickFile read_brick(const std::filesystem::path& path) {
  VdbReadOptions ro;
  ro.grid = "density";
  VolumeFile density;
  try {
    density = read_volume_vdb(path, ro);
  } catch (const GridNotFound&) {
    throw brick_error(path, "not a nimbus brick (no density grid)");
  }
  BrickFile b;
  b.path = path;
  b.metadata = density.metadata;
  const Metadata& m = b.metadata;
  const auto index = get_int(m, kIndexKey);
  if (!index || !density.checksum_verified)
    throw brick_error(path, "not a nimbus brick (no sealed brick_index metadata; bricks come from nimbus generate --brick I/N)");
  const auto layout = get_string(m, kLayoutKey);
  const auto box = parse_box(get_string(m, kBoxKey).value_or(""));
  const auto field = parse_box(get_string(m, kFieldBoxKey).value_or(""));
  const auto id = get_string(m, kFieldIdKey);
  const auto half = get_int(m, kStorageKey);
  if (!layout || !box || !field || !id || !half) throw brick_error(path, "a brick's metadata is incomplete or malformed");
  try {
    b.tag.layout = make_brick_layout(*field, *layout);
  } catch (const std::invalid_argument& e) {
    throw brick_error(path, std::string("brick layout: ") + e.what());
  }
  if (*index < 0 || *index >= b.tag.layout.size())
    throw brick_error(path, "brick index " + std::to_string(*index) + " is outside layout " + *layout);
  b.tag.index = int(*index);
  b.tag.field_id = *id;
  b.tag.half_float = *half != 0;
  b.box = brick_box(b.tag.layout, b.tag.index);
  if (b.box != *box) throw brick_error(path, "its brick_box does not match brick " + std::to_string(b.tag.index) + " of its layout");

  const bool y_up = get_string(m, "up_axis").value_or("z") == "y";
  auto to_z_up = [&](openvdb::FloatGrid::Ptr g) { return y_up ? rotate_y_up_to_z_up(*g) : g; };
  b.grids.push_back(to_z_up(density.grid));
  for (const GridInfo& g : density.grids) {
    if (g.name == "density") continue;
    if (g.name != "temperature" || g.value_type != "float")
      throw brick_error(path, "holds grid '" + g.name + "', which nimbus bricks do not have");
    ro.grid = g.name;
    b.grids.push_back(to_z_up(read_volume_vdb(path, ro).grid));
  }
  for (const auto& g : b.grids) {
    const openvdb::CoordBBox active = g->evalActiveVoxelBoundingBox();
    if (!active.empty() && !b.box.isInside(active))
      throw brick_error(path, "grid " + g->getName() + " has voxels outside its brick box [" + box_text(b.box) +
                                  "] (damaged, or not the brick it says it is)");
  }
  return b;
}

// "seed 3 vs 7": the first export key in which two bricks' fields differ.
std::string field_difference(const Metadata& a, const Metadata& b) {
  for (const char* key : {"preset", "seed", "time", "frame", "up_axis", kLayoutKey, kFieldBoxKey, kStorageKey})
    if (value_text(a, key) != value_text(b, key)) return std::string(key) + " " + value_text(b, key) + " vs " + value_text(a, key);
  return "parameters or voxel size differ (field_id " + get_string(b, kFieldIdKey).value_or("") + " vs " +
         get_string(a, kFieldIdKey).value_or("") + ")";
}

}  // namespace

std::string BrickLayout::text() const {
  return std::to_string(counts[0]) + "x" + std::to_string(counts[1]) + "x" + std::to_string(counts[2]);
}

BrickLayout make_brick_layout(const openvdb::CoordBBox& field, const std::string& counts_text) {
  if (field.empty()) throw std::invalid_argument("the field is empty");
  std::smatch m;
  std::array<int, 3> counts{};
  int blocks_along[3];
  for (int a = 0; a < 3; ++a) blocks_along[a] = blocks(field, a).second;
  if (std::regex_match(counts_text, m, std::regex(R"((\d{1,4})x(\d{1,4})x(\d{1,4}))"))) {
    for (int a = 0; a < 3; ++a) counts[a] = std::stoi(m[a + 1]);
  } else if (std::regex_match(counts_text, std::regex(R"(\d{1,4})"))) {
    const int n = std::stoi(counts_text);
    if (n < 1) throw std::invalid_argument("brick count '" + counts_text + "' must be at least 1");
    // Every factorisation n = a b c that the blocks allow; the one with the smallest largest brick
    // side (in blocks), then the smallest sum of sides.
    std::pair<int, int> best{1 << 30, 1 << 30};
    for (int a = 1; a <= n; ++a)
      for (int b = 1; a * b <= n; ++b) {
        if (n % (a * b)) continue;
        const int c = n / (a * b);
        const int k[3] = {a, b, c};
        int worst = 0, sum = 0;
        bool fits = true;
        for (int ax = 0; ax < 3; ++ax) {
          if (k[ax] > blocks_along[ax]) fits = false;
          const int side = (blocks_along[ax] + k[ax] - 1) / k[ax];
          worst = std::max(worst, side);
          sum += side;
        }
        if (fits && std::make_pair(worst, sum) < best) {
          best = {worst, sum};
          counts = {a, b, c};
        }
      }
    if (counts[0] == 0)
      throw std::invalid_argument(counts_text + " bricks cannot be cut from a field of " + std::to_string(blocks_along[0]) +
                                  "x" + std::to_string(blocks_along[1]) + "x" + std::to_string(blocks_along[2]) +
                                  " blocks of 128 voxels (every brick needs at least one block along each axis)");
  } else {
    throw std::invalid_argument("brick count '" + counts_text + "' must be N or AxBxC (e.g. 4 or 2x2x1)");
  }
  const long total = long(counts[0]) * counts[1] * counts[2];
  if (total < 1 || total > 4096)
    throw std::invalid_argument("brick count " + counts_text + " must give 1 to 4096 bricks");
  static const char* axes = "xyz";
  for (int a = 0; a < 3; ++a)
    if (counts[a] > blocks_along[a])
      throw std::invalid_argument(std::to_string(counts[a]) + " bricks along " + axes[a] + " but the field spans only " +
                                  std::to_string(blocks_along[a]) + " block(s) of 128 voxels there");
  BrickLayout layout;
  layout.counts = counts;
  layout.field = field;
  return layout;
}

openvdb::CoordBBox brick_box(const BrickLayout& layout, int index) {
  if (index < 0 || index >= layout.size())
    throw std::out_of_range("brick " + std::to_string(index) + " of " + layout.text() + " does not exist");
  const int at[3] = {index % layout.counts[0], index / layout.counts[0] % layout.counts[1],
                     index / (layout.counts[0] * layout.counts[1])};
  openvdb::Coord lo, hi;
  for (int a = 0; a < 3; ++a) {
    const auto [b0, n] = blocks(layout.field, a);
    const int c = layout.counts[a];
    const int first = b0 + int(int64_t(at[a]) * n / c), end = b0 + int(int64_t(at[a] + 1) * n / c);
    lo[a] = std::max(layout.field.min()[a], first * kBrickAlign);
    hi[a] = std::min(layout.field.max()[a], end * kBrickAlign - 1);
  }
  return {lo, hi};
}

std::string field_identity(const CloudParams& params, const GenerateOptions& options, char up_axis, bool half_float) {
  char extra[128];
  std::snprintf(extra, sizeof extra, "|voxel %.17g|time %.17g|up %c|half %d|octave_limit %d", options.voxel_size,
                options.time, up_axis, int(half_float), int(options.octave_limit));
  const std::string text = cloud_to_json(params).dump() + extra;
  uint64_t h = 14695981039346656037ull;  // FNV-1a, 64 bits
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016" PRIx64, h);
  return hex;
}

Metadata brick_metadata(const BrickTag& tag) {
  return {{kIndexKey, int64_t(tag.index)},
          {kLayoutKey, tag.layout.text()},
          {kBoxKey, box_text(brick_box(tag.layout, tag.index))},
          {kFieldBoxKey, box_text(tag.layout.field)},
          {kFieldIdKey, tag.field_id},
          {kStorageKey, int64_t(tag.half_float)}};
}

JoinedField join_bricks(const std::vector<std::filesystem::path>& files) {
  if (files.empty()) throw std::runtime_error("no brick files given");
  std::map<int, BrickFile> bricks;
  std::optional<BrickFile> first;
  for (const auto& path : files) {
    BrickFile b = read_brick(path);
    if (!first) {
      first = b;
    } else {
      if (b.tag.field_id != first->tag.field_id || b.tag.layout.text() != first->tag.layout.text() ||
          b.tag.layout.field != first->tag.layout.field)
        throw brick_error(path, "a brick of another field than " + first->path.string() + ": " +
                                    field_difference(first->metadata, b.metadata));
      if (b.grids.size() != first->grids.size())
        throw brick_error(path, "has " + std::to_string(b.grids.size()) + " grid(s), " + first->path.string() + " " +
                                    std::to_string(first->grids.size()));
    }
    const int index = b.tag.index;
    if (auto it = bricks.find(index); it != bricks.end())
      throw brick_error(path, "brick " + std::to_string(index) + " of " + b.tag.layout.text() + " is given twice (also " +
                                  it->second.path.string() + ")");
    bricks.emplace(index, std::move(b));
  }
  const BrickLayout layout = first->tag.layout;
  std::string missing;
  int n_missing = 0;
  for (int i = 0; i < layout.size(); ++i)
    if (!bricks.count(i)) {
      if (n_missing++ < 16) missing += (missing.empty() ? "" : ", ") + std::to_string(i) + " [" + box_text(brick_box(layout, i)) + "]";
    }
  if (n_missing)
    throw std::runtime_error("missing " + std::to_string(n_missing) + " of the " + std::to_string(layout.size()) + " bricks of " +
                             layout.text() + " (field " + first->tag.field_id + "): " + missing +
                             (n_missing > 16 ? ", ..." : ""));

  JoinedField out;
  out.layout = layout;
  out.options.half_float = first->tag.half_float;
  for (size_t g = 0; g < first->grids.size(); ++g) {
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName(first->grids[g]->getName());
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(first->grids[g]->transform().copy());
    for (auto& [index, b] : bricks) {
      if (b.grids[g]->transform() != grid->transform())
        throw brick_error(b.path, "its transform differs from " + first->path.string() + "'s");
      grid->tree().merge(b.grids[g]->tree(), openvdb::MERGE_ACTIVE_STATES);
    }
    out.grids.push_back(grid);
  }
  out.active_voxels = int64_t(out.grids[0]->activeVoxelCount());

  // The one-process file's metadata: the export keys, the brick keys removed.
  const Metadata& m = first->metadata;
  ExportInfo& info = out.info;
  info.creator = get_string(m, "creator").value_or("");
  info.preset = get_string(m, "preset").value_or("");
  info.seed = get_int(m, "seed").value_or(0);
  info.time = get_double(m, "time").value_or(0.0);
  info.frame = get_int(m, "frame").value_or(0);
  info.fps = get_double(m, "fps");
  info.up_axis = get_string(m, "up_axis").value_or("z") == "y" ? 'y' : 'z';
  info.units = get_string(m, "units").value_or("metres");
  info.nimbus_version = get_string(m, "nimbus_version").value_or("");
  static const std::vector<std::string> dropped = {"creator", "preset", "seed", "time", "frame", "fps", "up_axis", "units",
                                                   "nimbus_version", detail::kChecksumKey, kIndexKey, kLayoutKey, kBoxKey,
                                                   kFieldBoxKey, kFieldIdKey, kStorageKey};
  for (const auto& kv : m)
    if (std::find(dropped.begin(), dropped.end(), kv.first) == dropped.end()) info.extra.push_back(kv);
  return out;
}

}  // namespace nimbus::volume
