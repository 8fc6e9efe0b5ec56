// `nimbus bench volume`'s reading table: sealed files in process and foreign files in the
// isolated child, against OpenVDB reading them alone.
#pragma once
#include <filesystem>
#include <vector>

namespace nimbus::cli {

// One row per file (each holds a float grid "density", written by nimbus); copies without the
// seal are written to `tmp` and removed.
void bench_reading(const std::vector<std::filesystem::path>& files, const std::filesystem::path& tmp, int repeats);

}  // namespace nimbus::cli
