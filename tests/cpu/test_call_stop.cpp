// A stop belongs to its call (nimbus/base/cancel.hpp): a call whose stop is requested ends with
// Cancelled, and a call running at the same time on another thread, whose own stop was not
// requested, ends with exactly the result it has alone, whichever threads ran whose tasks.
#include <gtest/gtest.h>

#include <atomic>
#include <barrier>
#include <exception>
#include <thread>
#include <vector>

#include "nimbus/base/cancel.hpp"
#include "nimbus/noise/batch.hpp"
#include "nimbus/volume/generate.hpp"
#include "nimbus/volume/preset.hpp"

namespace nimbus {
namespace {

volume::CloudParams humilis() {
  return volume::cloud_from_json(volume::load_preset("cumulus-humilis")["cloud"], "cumulus-humilis");
}

volume::GenerateOptions at_voxel(double voxel_size_m) {
  volume::GenerateOptions o;
  o.voxel_size = voxel_size_m;
  return o;
}

void expect_same_grid(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b) {
  ASSERT_EQ(a.activeVoxelCount(), b.activeVoxelCount());
  auto acc = b.getConstAccessor();
  for (auto it = a.cbeginValueOn(); it; ++it) {
    float v = 0.0f;
    ASSERT_TRUE(acc.probeValue(it.getCoord(), v)) << it.getCoord();
    ASSERT_EQ(v, *it) << it.getCoord();
  }
}

TEST(CallStop, AThreadWithoutAScopeHasATokenThatNeverStops) {
  EXPECT_FALSE(current_stop_token().stop_possible());
  std::stop_source source;
  {
    const StopScope scope(source.get_token());
    EXPECT_TRUE(current_stop_token().stop_possible());
    {
      const StopScope inner{std::stop_token{}};  // nested: the inner scope's token, then the outer's again
      EXPECT_FALSE(current_stop_token().stop_possible());
    }
    source.request_stop();
    EXPECT_TRUE(current_stop_token().stop_requested());
    EXPECT_THROW(throw_if_stopped(current_stop_token()), Cancelled);
  }
  EXPECT_FALSE(current_stop_token().stop_possible());
  // Another thread never sees this thread's scope.
  const StopScope scope(source.get_token());
  bool seen = true;
  std::thread([&] { seen = current_stop_token().stop_possible(); }).join();
  EXPECT_FALSE(seen);
}

// Two generations at once, each with a stop of its own: the first stops itself part-way (from its
// progress, as the Python module's progress callable does); the second runs to the end and makes
// the very voxels it makes alone. With one process-wide flag it raised Cancelled too.
TEST(CallStop, AStopReachesItsOwnGenerationAndNoOther) {
  const volume::CloudParams p = humilis();
  const openvdb::FloatGrid::Ptr alone = volume::generate_density(p, at_voxel(8.0));
  ASSERT_GT(alone->activeVoxelCount(), 0);

  for (int round = 0; round < 3; ++round) {
    std::barrier start(2);
    std::exception_ptr first_error, second_error;
    openvdb::FloatGrid::Ptr second;
    std::atomic<double> first_reached{0.0};
    std::thread first([&] {
      std::stop_source source;
      const StopScope scope(source.get_token());
      volume::GenerateOptions o = at_voxel(8.0);
      o.progress = [&](double f) {
        first_reached.store(f);
        if (f > 0.2) source.request_stop();
      };
      start.arrive_and_wait();
      try {
        (void)volume::generate_density(p, o);
      } catch (...) {
        first_error = std::current_exception();
      }
    });
    std::thread other([&] {
      std::stop_source source;  // never requested
      const StopScope scope(source.get_token());
      start.arrive_and_wait();
      try {
        second = volume::generate_density(p, at_voxel(8.0));
      } catch (...) {
        second_error = std::current_exception();
      }
    });
    first.join();
    other.join();
    ASSERT_TRUE(first_error) << "round " << round << ": the stopped generation ran to the end";
    EXPECT_THROW(std::rethrow_exception(first_error), Cancelled);
    EXPECT_LT(first_reached.load(), 0.9) << "stopped part-way";
    ASSERT_FALSE(second_error) << "round " << round << ": the other generation was stopped too";
    ASSERT_TRUE(second);
    expect_same_grid(*alone, *second);
  }
}

TEST(CallStop, ANoiseGridPollsItsCallsStop) {
  noise::NoiseParams np;
  np.kind = noise::Kind::Worley;
  np.fractal = noise::Fractal::Fbm;
  np.octaves = 2;
  const noise::NoiseField field(np);
  noise::GridSpec grid;
  grid.spacing = 1.0 / 64.0;
  grid.res = {64, 64, 64};
  std::vector<float> free_run(grid.count()), stopped_run(grid.count());
  noise::evaluate_grid(field, grid, free_run);
  for (const bool parallel : {true, false}) {
    std::stop_source source;
    source.request_stop();
    const StopScope scope(source.get_token());
    noise::BatchOptions o;
    o.parallel = parallel;
    EXPECT_THROW(noise::evaluate_grid(field, grid, stopped_run, o), Cancelled) << "parallel " << parallel;
  }
  // Under a scope whose stop is not requested: the same bits as without one.
  std::stop_source quiet;
  const StopScope scope(quiet.get_token());
  for (const bool parallel : {true, false}) {
    noise::BatchOptions o;
    o.parallel = parallel;
    std::vector<float> again(grid.count());
    noise::evaluate_grid(field, grid, again, o);
    EXPECT_EQ(again, free_run) << "parallel " << parallel;
  }
}

}  // namespace
}  // namespace nimbus
