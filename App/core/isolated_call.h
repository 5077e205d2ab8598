// Runs a computation in a child process, so that a crash inside a third-party library
// (a segmentation fault or floating-point trap in CGAL, say) ends that computation with a
// status instead of ending the caller (the CLI, or FreeCAD with the user's document).
// The child gets a copy of the caller's memory (fork), runs `work` and sends the bytes it
// returns back through a pipe; the caller waits, reporting progress and watching the
// cancel flag and the time limit, and kills the child when the run is cancelled (so a
// computation that cannot check a cancel flag itself can still be stopped).
// On systems without fork, `work` runs in the calling process.
// IsolatedJob starts such a child and lets the caller go on with its own work meanwhile
// (the pipeline computes the fallback beside the decomposition); its result is taken later,
// or the child is killed when the job is dropped untaken.
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "core/progress.h"

namespace vorohex::core {

struct IsolatedResult {
  enum class Status {
    ok,         // `work` returned; `data` holds what it returned
    failed,     // `work` threw; `message` holds the exception's text
    crashed,    // the child died of a signal (`signal`) or exited without a result
    cancelled,  // the cancel flag or the time limit stopped it
  };
  Status status = Status::failed;
  std::string data;
  std::string message;
  int signal = 0;
  bool ok() const { return status == Status::ok; }
};

struct IsolatedCallOptions {
  std::string_view stage = "";  // progress stage reported while waiting ("" = none)
  bool isolate = true;          // false: run `work` in this process (for debugging)
};

// `work` returns its result as bytes (an exception becomes Status::failed).
IsolatedResult isolated_call(const std::function<std::string()>& work,
                             const Progress& progress = {},
                             const IsolatedCallOptions& options = {});

// A computation started in a child process now, taken later. Move-only; the child is
// killed when the job is destroyed or cancelled untaken. `work` gets a Progress with
// `limits`' deadline (not its cancel flag: the caller kills the child on cancel) whose
// reports cross to the caller through a second pipe: take() passes the latest on to its
// own progress, and the first report of each stage (a stage's start is never lost).
// Without fork (or when the fork fails), `work` runs in take() instead, with take()'s
// progress. `nice` (0-19) lowers the child's scheduling priority: work that may be thrown
// away then takes only what the caller's other processes leave of the cores.
class IsolatedJob {
 public:
  using Work = std::function<std::string(const Progress&)>;
  IsolatedJob() = default;
  explicit IsolatedJob(Work work, const Progress& limits = {}, int nice = 0);
  IsolatedJob(IsolatedJob&& other) noexcept;
  IsolatedJob& operator=(IsolatedJob&& other) noexcept;
  IsolatedJob(const IsolatedJob&) = delete;
  IsolatedJob& operator=(const IsolatedJob&) = delete;
  ~IsolatedJob();
  bool started() const { return pid_ > 0 || static_cast<bool>(work_); }
  // Waits for the result, as isolated_call does (killed on cancel), reporting the child's
  // latest progress (or, before any, heartbeats of options.stage).
  IsolatedResult take(const Progress& progress = {}, const IsolatedCallOptions& options = {});
  void cancel();  // kills the child (nothing to take afterwards)

 private:
  int pid_ = -1, fd_ = -1, progress_fd_ = -1;
  Work work_;  // set when no child runs it
};

// A child process that serves calls one after another: each call's bytes go to `handler` in
// the child, whose result comes back. For many short computations (a decomposition's unions,
// each unified by OCCT, which can loop without end), where a fork per call (isolated_call)
// costs more than the computation: a fork copies the caller's page tables, and the caller's
// next write to each of its pages faults (HexMe i22's 80 merges, 2 s of unification in
// children forked one per union, 0.1 s in the caller itself). The child is forked at the
// first call, and again at the next call after one was stopped (cancelled or at its time
// limit: the child is killed) or crashed. It ends with the server. The handler must take
// all it needs from its bytes: the child sees the caller's memory as it was at the fork.
// Without fork, calls run in the calling process.
class IsolatedServer {
 public:
  using Handler = std::function<std::string(const std::string& request)>;
  explicit IsolatedServer(Handler handler) : handler_(std::move(handler)) {}
  IsolatedServer(const IsolatedServer&) = delete;
  IsolatedServer& operator=(const IsolatedServer&) = delete;
  ~IsolatedServer() { stop(); }
  // The handler's result for `request` (Status as isolated_call's; `progress`: its cancel flag
  // and time limit).
  IsolatedResult call(const std::string& request, const Progress& progress = {});
  int forks() const { return forks_; }  // children started so far

 private:
  bool start();
  int stop();  // the child killed (if still running) and reaped: its wait status
  Handler handler_;
  int pid_ = -1, fd_ = -1, forks_ = 0;
};

// The name of a signal for messages ("SIGSEGV (segmentation fault)").
std::string signal_name(int signal);

}  // namespace vorohex::core
