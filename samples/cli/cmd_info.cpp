// `nimbus info FILE.vdb [--grid NAME]`: what a VDB file holds, grid by grid (name, type, class,
// active voxels, index and world boxes, voxel size, value range, background, half float) and
// its file metadata. A missing or damaged file is a runtime error (exit 1), an unknown grid
// name a usage error (exit 2).
#include <array>
#include <charconv>
#include <cstdio>
#include <optional>
#include <string>
#include <variant>

#include "cli.hpp"
#include "nimbus/base/input_limits.hpp"
#include "nimbus/volume/vdb_info.hpp"

namespace nimbus::cli {
namespace {

struct InfoOptions {
  std::string file;
  std::string grid;
};

// Metadata: the shortest text that reads back as the same double. Geometry and values: 7
// significant digits, a float's precision.
std::string num(double v, bool exact = false) {
  char buf[64];
  const auto r = exact ? std::to_chars(buf, buf + sizeof buf, v)
                       : std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 7);
  return std::string(buf, r.ptr);
}

std::string meta_text(const volume::MetaValue& v) {
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  if (const auto* d = std::get_if<double>(&v)) return num(*d, true);
  return std::to_string(std::get<int64_t>(v));
}

template <class T>
std::string triple(const std::array<T, 3>& a) {
  return "(" + num(double(a[0])) + ", " + num(double(a[1])) + ", " + num(double(a[2])) + ")";
}

void print_grid(const volume::GridSummary& g) {
  std::printf("grid %s\n", g.name.c_str());
  std::printf("  value type:     %s\n", g.value_type.c_str());
  std::printf("  class:          %s\n", g.grid_class.c_str());
  std::printf("  active voxels:  %llu\n", static_cast<unsigned long long>(g.active_voxels));
  if (g.empty) {
    std::printf("  index bbox:     empty\n  world bbox:     empty\n");
  } else {
    std::printf("  index bbox:     %s to %s, %lld x %lld x %lld voxels\n", triple(g.index_min).c_str(),
                triple(g.index_max).c_str(), static_cast<long long>(g.index_max[0]) - g.index_min[0] + 1,
                static_cast<long long>(g.index_max[1]) - g.index_min[1] + 1,
                static_cast<long long>(g.index_max[2]) - g.index_min[2] + 1);
    std::printf("  world bbox:     %s to %s (voxel corners)\n", triple(g.world_min).c_str(), triple(g.world_max).c_str());
  }
  const bool uniform = g.voxel_size[0] == g.voxel_size[1] && g.voxel_size[1] == g.voxel_size[2];
  std::printf("  voxel size:     %s%s\n", uniform ? num(g.voxel_size[0]).c_str() : triple(g.voxel_size).c_str(),
              g.linear_transform ? "" : " (at the origin; frustum transform)");
  if (g.value_range)
    std::printf("  value range:    %s to %s\n", num(g.value_range->first).c_str(), num(g.value_range->second).c_str());
  else
    std::printf("  value range:    %s\n", g.active_voxels ? "n/a (not a scalar grid)" : "n/a (no active values)");
  std::printf("  background:     %s\n", g.background.c_str());
  std::printf("  half float:     %s\n", g.half_float ? "yes" : "no");
  bool header = false;
  for (const auto& [key, value] : g.metadata) {
    if (key == "name" || key == "class" || key == "is_saved_as_half_float") continue;  // printed above
    if (!header) std::printf("  grid metadata:\n");
    header = true;
    std::printf("    %s: %s\n", key.c_str(), meta_text(value).c_str());
  }
}

int run_info(const InfoOptions& o) {
  std::optional<std::string> grid;
  if (!o.grid.empty()) grid = o.grid;
  refuse_special_file(o.file, "FILE");
  volume::FileSummary s;
  try {
    s = volume::summarize_vdb(o.file, grid);
  } catch (const volume::GridNotFound& e) {
    throw UsageError(std::string("--grid: ") + e.what());
  }
  std::printf("%s: %zu grid%s, %s\n", o.file.c_str(), s.grids.size(), s.grids.size() == 1 ? "" : "s",
              s.checksum_verified ? "nimbus checksum verified" : "no nimbus checksum");
  std::printf("file metadata:\n");
  if (s.metadata.empty()) std::printf("  (none)\n");
  for (const auto& [key, value] : s.metadata) std::printf("  %s: %s\n", key.c_str(), meta_text(value).c_str());
  for (const auto& g : s.grids) print_grid(g);
  return 0;
}

}  // namespace

void add_info_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand("info", "Print the grids, boxes, voxel size, value range and metadata of a VDB file");
  cmd->add_option("file", o->file, "the .vdb file")->required();
  cmd->add_option("--grid", o->grid, "only this grid");
  cmd->callback([&action, o] { action = [o] { return run_info(*o); }; });
}

}  // namespace nimbus::cli
