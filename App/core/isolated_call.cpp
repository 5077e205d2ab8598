#include "core/isolated_call.h"

#include <csignal>
#include <cstring>
#include <exception>
#include <string>

#if defined(__unix__) || defined(__APPLE__)
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#define VOROHEX_HAVE_FORK 1
#endif
#ifdef __linux__
#include <sys/prctl.h>
#endif

namespace vorohex::core {

namespace {

constexpr char kResult = 'R';
constexpr char kException = 'E';

IsolatedResult run_here(const std::function<std::string()>& work) {
  IsolatedResult r;
  try {
    r.data = work();
    r.status = IsolatedResult::Status::ok;
  } catch (const std::exception& ex) {
    r.message = ex.what();
  }
  return r;
}

#ifdef VOROHEX_HAVE_FORK
bool write_all(int fd, const char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

// In the child: no return, no destructors of the parent's objects, no atexit handlers.
// A child that calls isolated_call itself (the decomposition's split stops OCCT's face
// merging that way) dies with its parent: a parent killed at its time limit or on cancel
// leaves no grandchild running on.
[[noreturn]] void child(int fd, const std::function<std::string()>& work, pid_t parent) {
#ifdef __linux__
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(4);  // the parent died before prctl took effect
#else
  (void)parent;
#endif
  std::string out;
  try {
    out = kResult + work();
  } catch (const std::exception& ex) {
    out = kException + std::string(ex.what());
  } catch (...) {
    out = kException + std::string("unknown exception");
  }
  const bool written = write_all(fd, out.data(), out.size());
  ::close(fd);
  ::_exit(written ? 0 : 3);
}
#endif

}  // namespace

std::string signal_name(int signal) {
  switch (signal) {
    case SIGSEGV:
      return "SIGSEGV (segmentation fault)";
    case SIGFPE:
      return "SIGFPE (arithmetic exception)";
    case SIGABRT:
      return "SIGABRT (aborted)";
    case SIGBUS:
      return "SIGBUS (bus error)";
    case SIGILL:
      return "SIGILL (illegal instruction)";
    case SIGKILL:
      return "SIGKILL (killed, perhaps for lack of memory)";
    default:
      return "signal " + std::to_string(signal);
  }
}

IsolatedResult isolated_call(const std::function<std::string()>& work, const Progress& progress,
                             const IsolatedCallOptions& options) {
#ifndef VOROHEX_HAVE_FORK
  (void)progress;
  return run_here(work);
#else
  if (!options.isolate) return run_here(work);
  int fds[2];
  if (::pipe(fds) != 0) return run_here(work);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return run_here(work);
  }
  if (pid == 0) {
    ::close(fds[0]);
    child(fds[1], work, parent);
  }
  ::close(fds[1]);

  IsolatedResult r;
  std::string bytes;
  bool cancelled = false;
  char buffer[1 << 16];
  for (int tick = 0;; ++tick) {
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, 100);
    if (ready > 0) {
      const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
      if (n > 0) {
        bytes.append(buffer, static_cast<std::size_t>(n));
        continue;
      }
      if (n == 0 || errno != EINTR) break;  // end of the pipe: the child is done
    }
    if (progress.cancelled()) {
      ::kill(pid, SIGKILL);
      cancelled = true;
      break;
    }
    // A heartbeat, so that a GUI that processes events in the callback stays responsive.
    if (!options.stage.empty() && tick % 2 == 0) progress.report(options.stage, 0.0);
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (cancelled) {
    r.status = IsolatedResult::Status::cancelled;
    r.message = progress.timed_out() ? "the time limit was reached" : "cancelled";
    return r;
  }
  if (WIFSIGNALED(status)) {
    r.status = IsolatedResult::Status::crashed;
    r.signal = WTERMSIG(status);
    r.message = "the computation crashed with " + signal_name(r.signal);
    return r;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || bytes.empty()) {
    r.status = IsolatedResult::Status::crashed;
    r.message = "the computation ended without a result (exit code " +
                std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
    return r;
  }
  if (bytes[0] == kException) {
    r.status = IsolatedResult::Status::failed;
    r.message = bytes.substr(1);
    return r;
  }
  r.status = IsolatedResult::Status::ok;
  r.data = bytes.substr(1);
  return r;
#endif
}

}  // namespace vorohex::core
