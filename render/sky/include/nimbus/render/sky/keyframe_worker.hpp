// A background thread that makes values for keyframe numbers in the order a render loop wants
// them, holds the ones made near the frame drawn, and never blocks the asker: the one worker
// behind SkyKeyframes (the clouds' keyframes) and KeyframeLightVolumes (their light volumes).
//
// Every value is made under a context (a light, say; Context{} when there is none): setting a new
// context drops the values made under the old one, and the value being made under the old one
// is stopped: make() runs under a stop token of its own (nimbus/base/cancel.hpp), which a new
// context or the destructor stops, so a long make() that polls it ends at once (throwing
// Cancelled, which is no failure) and the worker turns to the new context's keys. A failure stops
// the worker; its message is kept and rethrown by wait().
#pragma once
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <stop_token>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "nimbus/base/cancel.hpp"

namespace nimbus::render {

struct KeyframeWorkerStats {
  int64_t made = 0;          // values made (all contexts)
  int64_t stopped = 0;       // makings stopped by a new context before they were done
  double seconds_total = 0;  // making them, all
  double seconds_last = 0;   // the last one
  bool busy = false;         // making one now
};

struct KeyframeWorkerNoContext {
  bool operator==(const KeyframeWorkerNoContext&) const { return true; }
};

template <class T, class Context = KeyframeWorkerNoContext>
class KeyframeWorker {
 public:
  using Value = std::shared_ptr<const T>;
  // Runs on the worker thread without the lock: the value of keyframe `key` under `context`.
  using Make = std::function<T(int64_t key, const Context& context)>;
  // Runs under the lock: whether a wanted key can be made now (default: always).
  using Makeable = std::function<bool(int64_t key)>;

  // `what` names a value in error messages ("sky keyframe": "sky keyframe 3: ..."). The thread
  // starts here and idles until a key is wanted.
  KeyframeWorker(std::string what, Make make, Makeable makeable = {})
      : what_(std::move(what)), make_(std::move(make)), makeable_(std::move(makeable)) {
    worker_ = std::thread([this] { run(); });
  }
  // Stops the worker: the value being made is stopped (a make() that polls its stop token ends
  // at once; one that does not is waited for).
  ~KeyframeWorker() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
      making_.request_stop();
    }
    stopping_ = true;
    wake_.notify_all();
    worker_.join();
  }
  KeyframeWorker(const KeyframeWorker&) = delete;
  KeyframeWorker& operator=(const KeyframeWorker&) = delete;

  // Wants `keys` (made in that order) under `context`; of the values held, the `keep` nearest to
  // centre_x2 / 2 stay (ties: the lower key goes first). Never blocks.
  void want(const Context& context, std::vector<int64_t> keys, int64_t centre_x2, std::size_t keep) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      use(context);
      wanted_ = std::move(keys);
      while (values_.size() > keep) {
        auto far = std::max_element(values_.begin(), values_.end(), [&](const auto& a, const auto& b) {
          return std::abs(2 * a.first - centre_x2) < std::abs(2 * b.first - centre_x2);
        });
        values_.erase(far);
      }
    }
    wake_.notify_all();
  }

  // Keyframe `key`'s value under `context`, or null while it is not made.
  Value get(const Context& context, int64_t key) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!(context_ == context)) return nullptr;
    auto it = values_.find(key);
    return it == values_.end() ? nullptr : it->second;
  }

  // Blocks until it is made (wanting it first); rethrows the worker's failure (std::runtime_error).
  Value wait(const Context& context, int64_t key) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (context_ == context && values_.count(key) > 0) return values_.at(key);
    if (use(context)) wanted_.clear();
    if (std::find(wanted_.begin(), wanted_.end(), key) == wanted_.end()) wanted_.insert(wanted_.begin(), key);
    wake_.notify_all();
    made_.wait(lock, [&] { return !error_.empty() || (context_ == context && values_.count(key) > 0); });
    if (!error_.empty()) throw std::runtime_error(error_);
    return values_.at(key);
  }

  // The failure that stopped the worker, if any; empty otherwise.
  std::string error() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return error_;
  }
  KeyframeWorkerStats stats() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return stats_;
  }
  // True once the destructor has begun.
  bool stopping() const { return stopping_; }

 private:
  // Under the lock: a new context drops the old one's values (true).
  bool use(const Context& context) {
    if (context_ == context) return false;
    context_ = context;
    values_.clear();
    ++generation_;
    making_.request_stop();  // what is being made under the old context is wasted: stop it
    return true;
  }

  // Under the lock: the first wanted key that is not made and can be.
  bool next_key(int64_t& key) const {
    for (int64_t w : wanted_)
      if (!values_.count(w) && (!makeable_ || makeable_(w))) {
        key = w;
        return true;
      }
    return false;
  }

  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      int64_t key = 0;
      wake_.wait(lock, [&] { return stop_ || !error_.empty() || next_key(key); });
      if (stop_ || !error_.empty()) return;
      const Context context = context_;
      const uint64_t generation = generation_;
      making_ = std::stop_source();
      const std::stop_token stop = making_.get_token();
      stats_.busy = true;
      lock.unlock();
      const auto start = std::chrono::steady_clock::now();
      Value made;
      std::string failure;
      bool stopped = false;
      try {
        const StopScope scope(stop);
        made = std::make_shared<const T>(make_(key, context));
      } catch (const Cancelled& e) {
        stopped = true;
        failure = what_ + " " + std::to_string(key) + ": " + e.what();
      } catch (const std::exception& e) {
        failure = what_ + " " + std::to_string(key) + ": " + e.what();
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      lock.lock();
      stats_.busy = false;
      if (made) {
        ++stats_.made;
        stats_.seconds_total += seconds;
        stats_.seconds_last = seconds;
        if (generation == generation_) values_[key] = made;  // else the context moved on while it was made
      } else if (stopped && stop.stop_requested()) {
        ++stats_.stopped;  // by a new context (or the destructor): not a failure
      } else if (!stop_) {
        error_ = failure;
      }
      made_.notify_all();
    }
  }

  const std::string what_;
  const Make make_;
  const Makeable makeable_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, made_;
  Context context_{};
  uint64_t generation_ = 0;
  std::map<int64_t, Value> values_;  // under context_
  std::vector<int64_t> wanted_;
  std::stop_source making_;  // the stop of the value being made (under the lock)
  std::string error_;
  KeyframeWorkerStats stats_;
  bool stop_ = false;
  std::atomic<bool> stopping_{false};
  std::thread worker_;  // last: started once everything above is built
};

}  // namespace nimbus::render
