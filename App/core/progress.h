// Progress reporting and cancellation, passed down explicitly (no globals).
#pragma once

#include <atomic>
#include <functional>
#include <string_view>

namespace vorohex::core {

class Progress {
 public:
  using Callback = std::function<void(std::string_view stage, double fraction)>;

  Progress() = default;
  Progress(Callback callback, const std::atomic<bool>* cancel = nullptr)
      : callback_(std::move(callback)), cancel_(cancel) {}

  // fraction in [0, 1] of the named stage.
  void report(std::string_view stage, double fraction) const {
    if (callback_) callback_(stage, fraction);
  }
  bool cancelled() const { return cancel_ && cancel_->load(std::memory_order_relaxed); }

 private:
  Callback callback_;
  const std::atomic<bool>* cancel_ = nullptr;
};

}  // namespace vorohex::core
