#pragma once
// A process-wide memo for the expensive inputs that many points of one `reproduce` share (a
// MuJoCo trial, a synthetic robot and its calibration): the first request for a key computes
// the value, concurrent requests for the same key wait on its shared_future, later ones get the
// stored object — or the stored error, so every point that needs a failed value fails with the
// same message. Entries are never evicted (callers keep keys few).
//
// Errors. A std::logic_error (a bug) is kept as it is. Anything else becomes a
// core::ComputationError whose message names the key by `label(key)` (once: a message that
// already names it is kept), so a point that fails on a shared value says which one.
#include <cstddef>
#include <exception>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace slipwalk::sweeps::engine {

template <class Key, class Value>
class OnceCache {
 public:
  using Pointer = std::shared_ptr<const Value>;

  /// The value of `key`, from `make()` on first request. `label(key)` names the key in errors.
  template <class Make, class Label>
  Pointer get(const Key& key, Make&& make, Label&& label) {
    std::promise<Pointer> promise;
    std::shared_future<Pointer> future;
    bool mine = false;
    {
      const std::lock_guard lock(mutex_);
      const auto it = entries_.find(key);
      if (it != entries_.end()) {
        future = it->second;
      } else {
        future = promise.get_future().share();
        entries_.emplace(key, future);
        ++computations_;
        mine = true;
      }
    }
    if (mine) {
      try {
        promise.set_value(std::make_shared<const Value>(std::forward<Make>(make)()));
      } catch (const std::logic_error&) {
        promise.set_exception(std::current_exception());
      } catch (const std::exception& e) {
        const std::string what = e.what();
        const std::string name = label(key);
        promise.set_exception(std::make_exception_ptr(core::ComputationError(
            what.find(name) == std::string::npos ? name + ": " + what : what)));
      }
    }
    return future.get();
  }

  /// How many values were computed (a test that the memo holds).
  [[nodiscard]] std::size_t computations() {
    const std::lock_guard lock(mutex_);
    return computations_;
  }

  void clear() {
    const std::lock_guard lock(mutex_);
    entries_.clear();
    computations_ = 0;
  }

 private:
  std::mutex mutex_;
  std::map<Key, std::shared_future<Pointer>> entries_;
  std::size_t computations_ = 0;
};

}  // namespace slipwalk::sweeps::engine
