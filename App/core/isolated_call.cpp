#include "core/isolated_call.h"

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#define VOROHEX_HAVE_FORK 1
#endif
#ifdef __linux__
#include <sys/prctl.h>
#endif
#ifdef VOROHEX_HAVE_FORK
#include <sys/socket.h>
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

bool read_all(int fd, char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t r = ::read(fd, p, n);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    p += r;
    n -= static_cast<std::size_t>(r);
  }
  return true;
}

// Writes to a socket without SIGPIPE when the other end is gone (false instead).
bool send_all(int fd, const char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::send(fd, p, n, MSG_NOSIGNAL);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

// A message: its length (8 bytes, this machine's order: both ends are one program), then it.
bool send_message(int fd, const std::string& m) {
  const std::uint64_t n = m.size();
  return send_all(fd, reinterpret_cast<const char*>(&n), sizeof n) && send_all(fd, m.data(), n);
}

// What a child sent (kResult or kException first, then the bytes or the message).
IsolatedResult decoded(const std::string& bytes) {
  IsolatedResult r;
  r.status = bytes[0] == kException ? IsolatedResult::Status::failed : IsolatedResult::Status::ok;
  (r.ok() ? r.data : r.message) = bytes.substr(1);
  return r;
}

// The server's child: requests in, results out (kResult or kException first), until the
// caller closes its end.
[[noreturn]] void serve(int fd, const IsolatedServer::Handler& handler, pid_t parent) {
#ifdef __linux__
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(4);
#else
  (void)parent;
#endif
  for (;;) {
    std::uint64_t n = 0;
    if (!read_all(fd, reinterpret_cast<char*>(&n), sizeof n)) ::_exit(0);
    std::string request(n, '\0');
    if (!read_all(fd, request.data(), n)) ::_exit(0);
    std::string out;
    try {
      out = kResult + handler(request);
    } catch (const std::exception& ex) {
      out = kException + std::string(ex.what());
    } catch (...) {
      out = kException + std::string("unknown exception");
    }
    if (!send_message(fd, out)) ::_exit(3);
  }
}
#endif

}  // namespace

bool IsolatedServer::start() {
#ifdef VOROHEX_HAVE_FORK
  int fds[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM, 0, fds) != 0) return false;
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    serve(fds[1], handler_, parent);
  }
  ::close(fds[1]);
  if (pid < 0) {
    ::close(fds[0]);
    return false;
  }
  pid_ = pid, fd_ = fds[0];
  ++forks_;
  return true;
#else
  return false;
#endif
}

int IsolatedServer::stop() {
  int status = 0;
#ifdef VOROHEX_HAVE_FORK
  if (pid_ > 0) {
    ::close(fd_);
    ::kill(pid_, SIGKILL);  // a child that died already keeps the status it died with
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
#endif
  pid_ = fd_ = -1;
  return status;
}

IsolatedResult IsolatedServer::call(const std::string& request, const Progress& progress) {
#ifdef VOROHEX_HAVE_FORK
  IsolatedResult r;
  // A child that died since the last call (its end closed) fails the send: started anew once.
  bool sent = (pid_ > 0 || start()) && send_message(fd_, request);
  if (!sent && pid_ > 0) {
    stop();
    sent = start() && send_message(fd_, request);
  }
  if (!sent) {
    stop();
    return run_here([&] { return handler_(request); });
  }
  std::string bytes;
  std::uint64_t length = 0;
  bool have_length = false;
  char buffer[1 << 16];
  for (;;) {
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, 50);
    if (ready > 0) {
      const ssize_t n = ::read(fd_, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;  // the child died
      bytes.append(buffer, static_cast<std::size_t>(n));
      if (!have_length && bytes.size() >= sizeof length) {
        std::memcpy(&length, bytes.data(), sizeof length);
        bytes.erase(0, sizeof length);
        have_length = true;
      }
      if (have_length && bytes.size() >= length) break;
      continue;
    }
    if (progress.cancelled()) {
      stop();
      r.status = IsolatedResult::Status::cancelled;
      r.message = progress.timed_out() ? "the time limit was reached" : "cancelled";
      return r;
    }
  }
  if (!have_length || bytes.size() < length || bytes.empty()) {
    // Ended without a whole result: a crash (its signal, once reaped).
    const int status = stop();
    r.status = IsolatedResult::Status::crashed;
    if (WIFSIGNALED(status)) {
      r.signal = WTERMSIG(status);
      r.message = "the computation crashed with " + signal_name(r.signal);
    } else {
      r.message = "the computation ended without a result";
    }
    return r;
  }
  return decoded(bytes);
#else
  (void)progress;
  return run_here([&] { return handler_(request); });
#endif
}

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

IsolatedJob::IsolatedJob(Work work, const Progress& limits, int nice) {
#ifdef VOROHEX_HAVE_FORK
  int fds[2], reports[2];
  if (::pipe(fds) == 0) {
    if (::pipe(reports) != 0) reports[0] = reports[1] = -1;
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::close(fds[0]);
      if (reports[0] >= 0) ::close(reports[0]);
      if (nice > 0) (void)::nice(std::min(nice, 19));  // a failure leaves the priority as is
      const int out = reports[1];
      // Reports never block the work: when the caller is not reading (busy with its own
      // work), they are dropped.
      if (out >= 0) ::fcntl(out, F_SETFL, ::fcntl(out, F_GETFL) | O_NONBLOCK);
      const Progress progress =
          limits.detached().reporting_to([out](std::string_view stage, double fraction) {
            if (out < 0) return;
            char line[160];
            const int n = std::snprintf(line, sizeof line, "%.*s\t%.4f\n",
                                        int(std::min<std::size_t>(stage.size(), 100)), stage.data(),
                                        fraction);
            if (n > 0) [[maybe_unused]]
              const ssize_t w = ::write(out, line, std::size_t(n));
          });
      child(
          fds[1], [&] { return work(progress); }, parent);
    }
    ::close(fds[1]);
    if (reports[1] >= 0) ::close(reports[1]);
    if (pid > 0) {
      pid_ = pid;
      fd_ = fds[0];
      progress_fd_ = reports[0];
      return;
    }
    ::close(fds[0]);
    if (reports[0] >= 0) ::close(reports[0]);
  }
#else
  (void)limits;
#endif
  work_ = std::move(work);
}

IsolatedJob::IsolatedJob(IsolatedJob&& other) noexcept
    : pid_(other.pid_),
      fd_(other.fd_),
      progress_fd_(other.progress_fd_),
      work_(std::move(other.work_)) {
  other.pid_ = other.fd_ = other.progress_fd_ = -1;
  other.work_ = nullptr;
}

IsolatedJob& IsolatedJob::operator=(IsolatedJob&& other) noexcept {
  if (this != &other) {
    cancel();
    pid_ = other.pid_, fd_ = other.fd_, progress_fd_ = other.progress_fd_;
    work_ = std::move(other.work_);
    other.pid_ = other.fd_ = other.progress_fd_ = -1;
    other.work_ = nullptr;
  }
  return *this;
}

IsolatedJob::~IsolatedJob() {
  cancel();
}

void IsolatedJob::cancel() {
  work_ = nullptr;
#ifdef VOROHEX_HAVE_FORK
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::close(fd_);
    if (progress_fd_ >= 0) ::close(progress_fd_);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
#endif
  pid_ = fd_ = progress_fd_ = -1;
}

IsolatedResult IsolatedJob::take(const Progress& progress, const IsolatedCallOptions& options) {
  if (work_) {
    const Work work = std::move(work_);
    work_ = nullptr;
    return run_here([&] { return work(progress); });
  }
  IsolatedResult r;
#ifdef VOROHEX_HAVE_FORK
  if (pid_ <= 0) {
    r.message = "nothing was started";
    return r;
  }
  const pid_t pid = pid_;
  const int fd = fd_;
  int reports = progress_fd_;
  pid_ = fd_ = progress_fd_ = -1;
  std::string bytes, lines;
  std::string stage(options.stage);  // the latest report: stage and fraction
  double fraction = 0;
  bool heard = false;  // whether the child has reported yet
  bool cancelled = false;
  char buffer[1 << 16];
  for (int tick = 0;; ++tick) {
    pollfd p[2] = {{fd, POLLIN, 0}, {reports, POLLIN, 0}};
    const int ready = ::poll(p, reports >= 0 ? 2 : 1, 100);
    if (ready > 0 && reports >= 0 && (p[1].revents & (POLLIN | POLLHUP))) {
      const ssize_t n = ::read(reports, buffer, sizeof buffer);
      if (n > 0) {
        lines.append(buffer, static_cast<std::size_t>(n));
        // Of the complete lines read at once, the latest counts, and the first of each new
        // stage too: a stage's start is not lost behind its next reports (the Voronoi
        // decomposition's 0 %, followed within milliseconds by a report per edge, was at
        // times; a caller saw the stage begin at 15 %).
        bool last_passed_on = true;
        std::size_t begin = 0;
        for (std::size_t end; (end = lines.find('\n', begin)) != std::string::npos;
             begin = end + 1) {
          const std::string line = lines.substr(begin, end - begin);
          const std::size_t tab = line.find('\t');
          if (tab == std::string::npos) continue;
          const bool new_stage = !heard || line.compare(0, tab, stage) != 0;
          stage = line.substr(0, tab), fraction = std::strtod(line.c_str() + tab + 1, nullptr);
          heard = true;
          last_passed_on = new_stage;
          if (new_stage) progress.report(stage, fraction);
        }
        lines.erase(0, begin);
        if (!last_passed_on) progress.report(stage, fraction);
      } else if (n == 0 || errno != EINTR) {
        ::close(reports);
        reports = -1;
      }
    }
    if (ready > 0 && (p[0].revents & (POLLIN | POLLHUP))) {
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
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
    if (!stage.empty() && tick % 2 == 0) progress.report(stage, fraction);
  }
  ::close(fd);
  if (reports >= 0) ::close(reports);
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
  r = decoded(bytes);
#else
  (void)progress;
  (void)options;
  r.message = "nothing was started";
#endif
  return r;
}

IsolatedResult isolated_call(const std::function<std::string()>& work, const Progress& progress,
                             const IsolatedCallOptions& options) {
  if (!options.isolate) return run_here(work);
  return IsolatedJob([&](const Progress&) { return work(); }).take(progress, options);
}

}  // namespace vorohex::core
