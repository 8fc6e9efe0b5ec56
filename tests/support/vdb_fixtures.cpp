// Test grids, per-test temporary directories and shell commands (vdb_fixtures.hpp).
#include "support/vdb_fixtures.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace nimbus::test {

openvdb::FloatGrid::Ptr make_ball(int radius, double voxel_size, const std::string& name) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  auto acc = grid->getAccessor();
  for (int i = -radius; i <= radius; ++i)
    for (int j = -radius; j <= radius; ++j)
      for (int k = -radius; k <= radius; ++k) {
        const double d = std::sqrt(double(i * i + j * j + k * k)) / radius;
        if (d >= 1.0) continue;
        const double ripple = 1.0 + 0.05 * std::sin(1.7 * i + 2.3 * j - 0.9 * k);
        acc.setValue(openvdb::Coord(i, j, k), float(5.7 * std::pow(1.0 - d, 3.0) * ripple));
      }
  grid->setName(name);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel_size));
  return grid;
}

TempDir::TempDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = "nimbus_io_" + std::to_string(::getpid());
  if (info) name += std::string("_") + info->test_suite_name() + "_" + info->name();
  for (char& c : name)
    if (c == '/') c = '_';
  path = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(path);
  std::filesystem::create_directories(path);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::permissions(path, std::filesystem::perms::owner_all, std::filesystem::perm_options::add, ec);
  std::filesystem::remove_all(path, ec);
}

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_bytes(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

int count_temp_files(const std::filesystem::path& dir) {
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    n += e.path().filename().string().find(".tmp") != std::string::npos;
  return n;
}


}  // namespace nimbus::test
