// `nimbus bench volume`, reading: what reading a file costs nimbus against OpenVDB reading it
// alone (the anchor), for its own sealed files (CRC-32, then in-process) and for the same grids
// as a foreign file (no seal: read by the isolated reader program, vdb_read.hpp), with the values checked
// identical to the anchor's.
#include "bench_volume_read.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::cli {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Least time of `repeats` runs of f().
template <class F>
double best_of(int repeats, F&& f) {
  double best = 1e300;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, seconds_since(t0));
  }
  return best;
}

// Largest |a - b| over a's active voxels and b's (inactive = background); -1 when the active
// voxel counts differ.
double max_difference(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b) {
  if (a.activeVoxelCount() != b.activeVoxelCount()) return -1.0;
  double d = 0.0;
  const auto acc = b.getConstAccessor();
  for (auto it = a.cbeginValueOn(); it; ++it) d = std::max(d, std::fabs(double(*it) - double(acc.getValue(it.getCoord()))));
  return d;
}

}  // namespace

void bench_reading(const std::vector<std::filesystem::path>& files, const std::filesystem::path& tmp, int repeats) {
  std::printf("\n### Reading (best of %d; the anchor is OpenVDB reading the grid alone, in process)\n\n", repeats);
  std::printf("| file | active voxels | MB | OpenVDB alone ms (anchor) | sealed, in process ms | foreign, by the reader program ms | "
              "foreign / anchor | max diff vs anchor (sealed / foreign) |\n|---|---:|---:|---:|---:|---:|---:|---|\n");
  for (const std::filesystem::path& path : files) {
    openvdb::FloatGrid::Ptr anchor;
    openvdb::MetaMap::Ptr meta;
    const double t_anchor = best_of(repeats, [&] {
      openvdb::io::File f(path.string());
      f.open(false);
      anchor = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid("density"));
      meta = f.getMetadata();
      f.close();
    });
    // The same grid and metadata without nimbus's seal, as another tool would write them.
    const std::filesystem::path foreign = tmp / ("foreign-" + path.filename().string());
    meta->removeMeta("nimbus_checksum");
    {
      openvdb::io::File out(foreign.string());
      out.write({anchor}, *meta);
      out.close();
    }
    volume::VolumeFile sealed, other;
    const double t_sealed = best_of(repeats, [&] { sealed = volume::read_volume_vdb(path); });
    const double t_foreign = best_of(repeats, [&] { other = volume::read_volume_vdb(foreign); });
    const double d_sealed = max_difference(*anchor, *sealed.grid), d_foreign = max_difference(*anchor, *other.grid);
    std::printf("| %s | %llu | %.2f | %.1f | %.1f%s | %.1f%s | %.2f | %g / %g%s |\n", path.filename().c_str(),
                static_cast<unsigned long long>(anchor->activeVoxelCount()),
                double(std::filesystem::file_size(path)) / 1e6, t_anchor * 1e3, t_sealed * 1e3,
                sealed.checksum_verified && !sealed.read_in_child ? "" : " (NOT sealed in process)", t_foreign * 1e3,
                other.read_in_child ? "" : " (NOT by the reader)", t_foreign / t_anchor, d_sealed, d_foreign,
                d_sealed == 0.0 && d_foreign == 0.0 ? " (identical)" : " (NOT identical)");
    std::filesystem::remove(foreign);
  }
  // The reader program's fixed cost: starting it (fork, exec, loading OpenVDB) for a file with
  // one empty grid, against OpenVDB opening the same file in process.
  const std::filesystem::path empty = tmp / "foreign-empty.vdb";
  {
    openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create(0.0f);
    g->setName("density");
    openvdb::io::File out(empty.string());
    out.write({g});
    out.close();
  }
  const double t_open = best_of(repeats, [&] {
    openvdb::io::File f(empty.string());
    f.open(false);
    f.readGrid("density");
    f.close();
  });
  const double t_start = best_of(repeats, [&] { volume::read_volume_vdb(empty); });
  std::printf("\nThe reader program's start (a file with one empty grid): %.1f ms, against %.2f ms for OpenVDB "
              "alone in process\n", t_start * 1e3, t_open * 1e3);
  std::filesystem::remove(empty);
}

}  // namespace nimbus::cli
