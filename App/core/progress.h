// Progress reporting and cancellation, passed down explicitly (no globals).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <limits>
#include <string>
#include <string_view>

namespace vorohex::core {

// Seconds of the steady clock since t0 (the stages' timings in results and reports).
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

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
  // Cancelled by the flag, or past the deadline (a time limit works like a cancel).
  bool cancelled() const {
    return (cancel_ && cancel_->load(std::memory_order_relaxed)) || timed_out();
  }
  bool timed_out() const { return has_deadline_ && std::chrono::steady_clock::now() > deadline_; }
  // Seconds until the deadline (negative past it; infinity without one).
  double seconds_left() const {
    if (!has_deadline_) return std::numeric_limits<double>::infinity();
    return std::chrono::duration<double>(deadline_ - std::chrono::steady_clock::now()).count();
  }

  // A copy that also counts as cancelled once `seconds` have passed from now (or at this
  // one's deadline, if that comes first: a limit never extends another).
  Progress with_time_limit(double seconds) const {
    Progress p = *this;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(seconds));
    p.deadline_ = has_deadline_ ? std::min(deadline_, deadline) : deadline;
    p.has_deadline_ = true;
    return p;
  }

  // A copy with the same deadline but no callback and no cancel flag: for work in a child
  // process (core/isolated_call.h), which must not call back into the caller (FreeCAD's
  // Python) and is killed by the caller on cancel.
  Progress detached() const {
    Progress p;
    p.has_deadline_ = has_deadline_;
    p.deadline_ = deadline_;
    return p;
  }
  // A copy whose stages are named after `label` ("finer grid: smooth"): a retry's stages
  // read as its own, not as the first run's going back to 0 % (or staying at 100 %).
  Progress labelled(const std::string& label) const {
    Progress p = *this;
    if (callback_)
      p.callback_ = [inner = callback_, label](std::string_view stage, double fraction) {
        inner(label + ": " + std::string(stage), fraction);
      };
    return p;
  }
  // A copy whose reports go to `callback` instead.
  Progress reporting_to(Callback callback) const {
    Progress p = *this;
    p.callback_ = std::move(callback);
    return p;
  }

 private:
  Callback callback_;
  const std::atomic<bool>* cancel_ = nullptr;
  bool has_deadline_ = false;
  std::chrono::steady_clock::time_point deadline_{};
};

}  // namespace vorohex::core
