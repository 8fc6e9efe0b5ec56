// Fuzz target: reading VDB files (volume/src/vdb_*.cpp) as `nimbus info` and `nimbus render`
// do: the input bytes are written to a file, then read_volume_vdb (and, for a grid whose active
// box is small, dense_active_box, the renderer's dense copy) and summarize_vdb are called.
//
// The contract checked (vdb_read.hpp, vdb_info.hpp): every failure is a std::runtime_error
// whose message is one line (at most 64 KB) starting with the file name (dense_active_box may also refuse a
// box with nimbus::OutOfMemoryRequest); a grid that was read holds no NaN or Inf among its
// active values; both readers agree on whether the nimbus seal was verified. Anything else,
// and any crash, hang or runaway allocation, is a finding.
//
// Boxes over kDenseLimit voxels are not copied here: whether such a copy fits depends on the
// machine's memory (nimbus::ensure_fits_in_memory reads MemAvailable), so the command-line
// driver (run_hostile_vdbs.py, with an address-space limit) covers them instead.
#include <cmath>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <string_view>

#include "fuzz_common.hpp"
#include "nimbus/base/memory.hpp"
#include "nimbus/volume/vdb_info.hpp"
#include "nimbus/volume/vdb_read.hpp"

namespace {

using nimbus::fuzz::contract_failure;
using nimbus::fuzz::one_line;

constexpr int64_t kDenseLimit = int64_t(1) << 24;  // 16 M voxels, 64 MB of floats
constexpr size_t kMessageLimit = 64 << 10;          // a one-line message a person can read

void expect_named(const std::exception& e, const std::string& step, const std::string& path) {
  const std::string_view what = e.what();
  if (what.size() > kMessageLimit)  // e.g. a corrupt type name of gigabytes echoed in the error
    contract_failure(step + ": a message of " + std::to_string(what.size()) + " bytes: " +
                     std::string(what.substr(0, 200)) + "...");
  if (!one_line(what)) contract_failure(step + ": the message is not one line: " + std::string(what));
  if (what.substr(0, path.size()) != path)
    contract_failure(step + ": the message does not start with the file name: " + std::string(what));
}

[[noreturn]] void wrong_type(const std::string& step, const std::exception& e) {
  contract_failure(step + " threw " + nimbus::fuzz::type_name(e) + ", not std::runtime_error: " + e.what());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace volume = nimbus::volume;
  static const nimbus::fuzz::ScratchFile file(".vdb");
  file.write(std::string_view(reinterpret_cast<const char*>(data), size));
  const std::string& path = file.path();

  std::optional<bool> verified_by_read;
  try {
    const volume::VolumeFile v = volume::read_volume_vdb(path);
    verified_by_read = v.checksum_verified;
    if (!v.grid) contract_failure("read_volume_vdb returned no grid and threw nothing");
    int64_t active = 0;
    for (auto it = v.grid->cbeginValueOn(); it && active < kDenseLimit; ++it, ++active)
      if (!std::isfinite(*it)) contract_failure("read_volume_vdb accepted a grid with a non-finite active value");
    // The box in 64 bits: its extent can pass 2^31 (voxels near both ends of the int32 range),
    // and a grid with nodes but no active voxel has an inverted (empty) box.
    const openvdb::CoordBBox box = v.grid->evalActiveVoxelBoundingBox();
    {
      int64_t voxels = 1;
      for (int a = 0; a < 3; ++a) {
        const int64_t n = int64_t(box.max()[a]) - int64_t(box.min()[a]) + 1;
        if (n <= 0) voxels = 0;
        else if (voxels > 0) voxels = (n > kDenseLimit || voxels > kDenseLimit) ? kDenseLimit + 1 : voxels * n;
      }
      if (voxels <= kDenseLimit) {
        try {
          const volume::DenseBox dense = volume::dense_active_box(*v.grid);
          if (int64_t(dense.values.size()) != dense.size[0] * dense.size[1] * dense.size[2])
            contract_failure("dense_active_box: values.size() does not match size");
        } catch (const nimbus::OutOfMemoryRequest&) {
        } catch (const std::runtime_error& e) {  // an index box no dense copy can hold; names the grid
          if (std::string_view(e.what()).find("grid '") == std::string_view::npos)
            contract_failure(std::string("dense_active_box: the message does not name the grid: ") + e.what());
        } catch (const std::exception& e) {
          wrong_type("dense_active_box", e);
        }
      }
    }
  } catch (const std::runtime_error& e) {
    expect_named(e, "read_volume_vdb", path);
  } catch (const std::exception& e) {
    wrong_type("read_volume_vdb", e);
  }

  try {
    const volume::FileSummary s = volume::summarize_vdb(path);
    if (verified_by_read && *verified_by_read != s.checksum_verified)
      contract_failure("read_volume_vdb and summarize_vdb disagree on the seal");
  } catch (const std::runtime_error& e) {
    expect_named(e, "summarize_vdb", path);
  } catch (const std::exception& e) {
    wrong_type("summarize_vdb", e);
  }
  return 0;
}
