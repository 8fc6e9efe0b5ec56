// KeyframeWorker (render/sky/keyframe_worker.hpp), the background thread behind SkyKeyframes and
// KeyframeLightVolumes: values are made for the keys wanted under the current context, a new
// context drops the old values and discards one still being made (stopping it when it polls its
// stop token), failures reach wait(), and
// the values held are pruned to those nearest the frame. Synchronised with gates, never sleeps.
#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <memory>
#include <mutex>
#include <stop_token>
#include <thread>
#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/base/cancel.hpp"
#include "nimbus/render/sky/keyframe_worker.hpp"

namespace nimbus::render {
namespace {

// A value that says which key and context it was made for.
struct Made {
  int64_t key = 0;
  int context = 0;
};

using Worker = KeyframeWorker<Made, int>;

// Records the keys made, in order.
struct Log {
  std::mutex mutex;
  std::vector<int64_t> keys;
  void add(int64_t k) {
    std::lock_guard<std::mutex> lock(mutex);
    keys.push_back(k);
  }
  std::vector<int64_t> all() {
    std::lock_guard<std::mutex> lock(mutex);
    return keys;
  }
};

TEST(KeyframeWorker, WaitMakesTheKeyUnderItsContextAndGetReturnsIt) {
  Log log;
  Worker w("thing", [&](int64_t k, const int& c) {
    log.add(k);
    return Made{k, c};
  });
  EXPECT_EQ(w.get(7, 3), nullptr);  // nothing wanted yet
  const auto v = w.wait(7, 3);
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v->key, 3);
  EXPECT_EQ(v->context, 7);
  EXPECT_EQ(w.get(7, 3), v);
  EXPECT_EQ(w.get(8, 3), nullptr);  // another context holds nothing
  EXPECT_EQ(w.wait(7, 3), v);       // made once
  EXPECT_EQ(log.all(), std::vector<int64_t>{3});
  EXPECT_EQ(w.stats().made, 1);
  EXPECT_FALSE(w.stats().busy);
  EXPECT_GE(w.stats().seconds_total, w.stats().seconds_last);
}

TEST(KeyframeWorker, WantedKeysAreMadeInTheirOrder) {
  Log log;
  std::promise<void> gate;
  std::shared_future<void> open = gate.get_future().share();
  Worker w("thing", [&](int64_t k, const int& c) {
    open.wait();  // all keys are wanted before the first is made
    log.add(k);
    return Made{k, c};
  });
  w.want(1, {5, 6, 4, 7}, 2 * 5 + 1, 8);
  gate.set_value();
  w.wait(1, 7);
  const std::vector<int64_t> made = log.all();
  ASSERT_EQ(made.size(), 4u);
  EXPECT_EQ(made, (std::vector<int64_t>{5, 6, 4, 7}));
}

TEST(KeyframeWorker, ANewContextDropsTheOldValuesAndDiscardsOneInTheMaking) {
  std::promise<void> started_promise, gate;
  std::future<void> started = started_promise.get_future();
  std::shared_future<void> open = gate.get_future().share();
  std::once_flag first;
  Worker w("thing", [&](int64_t k, const int& c) {
    std::call_once(first, [&] {
      started_promise.set_value();
      open.wait();  // the context changes while this value is made
    });
    return Made{k, c};
  });
  w.want(1, {2}, 4, 4);
  started.wait();
  w.want(2, {2}, 4, 4);  // new context: the value under 1 being made must not be kept
  gate.set_value();
  const auto v = w.wait(2, 2);
  EXPECT_EQ(v->context, 2);
  EXPECT_EQ(w.get(1, 2), nullptr);
  // And back: context 1's values were dropped, so key 2 is made again under 1.
  EXPECT_EQ(w.wait(1, 2)->context, 1);
  EXPECT_EQ(w.get(2, 2), nullptr);
}

// A make() that polls its stop token (cancel.hpp) is stopped by a new context at once: it never
// finishes on its own here, so the test ends only if the stop reaches it; the stop is no failure.
TEST(KeyframeWorker, ANewContextStopsTheMakingThatPollsItsToken) {
  std::promise<void> started_promise;
  std::future<void> started = started_promise.get_future();
  std::once_flag first;
  std::atomic<bool> saw_stop{false};
  Worker w("thing", [&](int64_t k, const int& c) {
    if (c == 1) {
      const std::stop_token stop = current_stop_token();
      std::call_once(first, [&] { started_promise.set_value(); });
      while (!stop.stop_requested()) std::this_thread::yield();
      saw_stop = true;
      throw_if_stopped(stop);
    }
    return Made{k, c};
  });
  w.want(1, {5}, 10, 4);
  started.wait();
  EXPECT_TRUE(w.stats().busy);
  const auto v = w.wait(2, 5);  // a new context: context 1's making stops, then 2's is made
  EXPECT_EQ(v->context, 2);
  EXPECT_TRUE(saw_stop);
  EXPECT_EQ(w.stats().stopped, 1);
  EXPECT_EQ(w.stats().made, 1);
  EXPECT_EQ(w.error(), "");
}

// The destructor stops a making that polls its token: this test would hang otherwise.
TEST(KeyframeWorker, TheDestructorStopsTheMaking) {
  std::promise<void> started_promise;
  std::future<void> started = started_promise.get_future();
  {
    Worker w("thing", [&](int64_t k, const int& c) {
      const std::stop_token stop = current_stop_token();
      started_promise.set_value();
      while (!stop.stop_requested()) std::this_thread::yield();
      throw_if_stopped(stop);
      return Made{k, c};
    });
    w.want(1, {5}, 10, 4);
    started.wait();
  }
  SUCCEED();
}

TEST(KeyframeWorker, OnlyMakeableKeysAreMade) {
  std::mutex m;
  bool allow_9 = false;
  Log log;
  Worker w(
      "thing",
      [&](int64_t k, const int& c) {
        log.add(k);
        return Made{k, c};
      },
      [&](int64_t k) {
        std::lock_guard<std::mutex> lock(m);
        return k != 9 || allow_9;
      });
  w.want(0, {9, 10}, 19, 4);
  w.wait(0, 10);
  EXPECT_EQ(w.get(0, 9), nullptr);
  EXPECT_EQ(log.all(), std::vector<int64_t>{10});
  {
    std::lock_guard<std::mutex> lock(m);
    allow_9 = true;
  }
  EXPECT_EQ(w.wait(0, 9)->key, 9);
}

TEST(KeyframeWorker, AFailureStopsTheWorkerAndReachesWaitNamingTheKey) {
  Worker w("sky keyframe", [](int64_t k, const int& c) -> Made {
    if (k == 4) throw std::runtime_error("the file is damaged");
    return Made{k, c};
  });
  EXPECT_EQ(w.wait(0, 3)->key, 3);
  try {
    w.wait(0, 4);
    FAIL() << "wait returned for a key whose making failed";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "sky keyframe 4: the file is damaged");
  }
  EXPECT_EQ(w.error(), "sky keyframe 4: the file is damaged");
  EXPECT_THROW(w.wait(0, 5), std::runtime_error);  // stopped: nothing more is made
}

TEST(KeyframeWorker, ValuesFarFromTheFrameArePrunedToKeep) {
  Worker w("thing", [](int64_t k, const int& c) { return Made{k, c}; });
  for (int64_t k = 0; k < 6; ++k) w.wait(0, k);
  // The frame is the pair (3, 4): centre 3.5; keep the 4 nearest, 2..5.
  w.want(0, {3, 4}, 7, 4);
  EXPECT_EQ(w.get(0, 0), nullptr);
  EXPECT_EQ(w.get(0, 1), nullptr);
  for (int64_t k = 2; k < 6; ++k) EXPECT_NE(w.get(0, k), nullptr) << k;
}

TEST(KeyframeWorker, DestructionEndsALongMakeThatPollsStopping) {
  std::promise<void> started_promise;
  std::future<void> started = started_promise.get_future();
  std::atomic<bool> saw_stop{false};
  {
    const Worker* self = nullptr;  // set before any key is wanted
    Worker w("thing", [&](int64_t, const int&) -> Made {
      started_promise.set_value();
      while (!self->stopping()) std::this_thread::yield();
      saw_stop = true;
      throw std::runtime_error("stopped");
    });
    self = &w;
    w.want(0, {1}, 2, 4);
    started.wait();
  }  // the destructor returns: the make saw stopping() and ended
  EXPECT_TRUE(saw_stop);
}

}  // namespace
}  // namespace nimbus::render
