# Long computations (meshing, the Voronoi graph, the decomposition) run in a child process
# so that the caller (FreeCAD's GUI thread) never waits for them: it polls the job, which
# hands over progress messages and, at the end, the result. Stop kills the child and its
# own children (CGAL, the decomposition) at once, whatever stage they are in, and a crash
# in the computation ends the job with a message instead of ending FreeCAD.
"""Cancellable computations in a child process (VoroHex)."""

import os
import pickle
import signal
import tempfile
import threading
import time
import traceback

__all__ = ["Job", "Cancelled"]


class Cancelled(Exception):
    """The job was stopped (Job.result raises it after Job.cancel)."""


class Job:
    """Runs `work(report)` in a forked child process. `report(stage, fraction)` (in the
    child) sends progress to the parent, at most every `interval` seconds; work returns a
    picklable value. The parent calls poll() now and then (it never blocks): it reads the
    progress messages and returns True once the job is over; then result() returns the
    value or raises (Cancelled, or RuntimeError with the child's error or crash).

    Without os.fork (not on Debian) the work runs in a thread, and cancel() only sets
    `cancelled` for work that checks it."""

    def __init__(self, work, interval=0.05):
        self.stage, self.fraction = "starting", 0.0
        self.started = time.time()
        self.finished = None
        self.cancelled = False
        self._value = self._error = None
        self._buffer = b""
        self._result_path = None
        self._pid = None
        self._thread = None
        if hasattr(os, "fork"):
            self._start_child(work, interval)
        else:  # pragma: no cover - Windows; not packaged
            self._start_thread(work)

    # The child ------------------------------------------------------------------------
    def _start_child(self, work, interval):
        fd, self._result_path = tempfile.mkstemp(prefix="vorohex-job-", suffix=".pickle")
        os.close(fd)
        read_end, write_end = os.pipe()
        pid = os.fork()
        if pid == 0:  # the child: never returns
            code = 1
            try:
                os.close(read_end)
                os.setpgid(0, 0)  # its own group: cancel() kills its children with it
                os.nice(5)  # the GUI (the parent) goes first on a busy machine
                last = [0.0]

                def report(stage, fraction=0.0):
                    now = time.time()
                    if now - last[0] >= interval or fraction >= 1.0:
                        last[0] = now
                        _send(write_end, "p {:.4f} {}\n".format(float(fraction), stage))
                    return True

                value = work(report)
                with open(self._result_path, "wb") as f:
                    pickle.dump(value, f, protocol=pickle.HIGHEST_PROTOCOL)
                _send(write_end, "d\n")
                code = 0
            except BaseException:  # everything, so the parent learns why
                try:
                    text = traceback.format_exc().replace("\n", "\x1f")
                    _send(write_end, "e {}\n".format(text))
                except BaseException:
                    pass
            finally:
                os._exit(code)
        os.close(write_end)
        try:  # as the child does, so that a cancel right after the start finds the group
            os.setpgid(pid, pid)
        except OSError:
            pass
        self._pid = pid
        self._fd = read_end
        os.set_blocking(read_end, False)

    def _read_child(self):
        while True:
            try:
                chunk = os.read(self._fd, 1 << 16)
            except BlockingIOError:
                return False
            except InterruptedError:
                continue
            if not chunk:  # the child closed the pipe: it is done (or dead)
                return True
            self._buffer += chunk
            while b"\n" in self._buffer:
                line, self._buffer = self._buffer.split(b"\n", 1)
                self._message(line.decode("utf-8", "replace"))

    def _message(self, line):
        kind, _, rest = line.partition(" ")
        if kind == "p":
            fraction, _, stage = rest.partition(" ")
            self.stage, self.fraction = stage, float(fraction)
        elif kind == "d":
            self._done = True
        elif kind == "e":
            self._error = RuntimeError(rest.replace("\x1f", "\n").strip())

    def _reap(self):
        _, status = os.waitpid(self._pid, 0)
        os.close(self._fd)
        if self._error is None:
            if getattr(self, "_done", False):
                try:
                    with open(self._result_path, "rb") as f:
                        self._value = pickle.load(f)
                except Exception as e:  # pragma: no cover - a full disk, say
                    self._error = RuntimeError("the result could not be read back: {}".format(e))
            elif os.WIFSIGNALED(status):
                sig = os.WTERMSIG(status)
                self._error = RuntimeError("the computation crashed ({}{})".format(
                    signal.Signals(sig).name, ", perhaps for lack of memory"
                    if sig == signal.SIGKILL else ""))
            else:
                self._error = RuntimeError("the computation ended without a result")
        self._remove_result()

    def _remove_result(self):
        if self._result_path and os.path.exists(self._result_path):
            os.remove(self._result_path)

    # A thread, where there is no fork -----------------------------------------------
    def _start_thread(self, work):  # pragma: no cover
        def report(stage, fraction=0.0):
            self.stage, self.fraction = stage, fraction
            return not self.cancelled

        def run():
            try:
                self._value = work(report)
            except BaseException:
                self._error = RuntimeError(traceback.format_exc())

        self._thread = threading.Thread(target=run, daemon=True)
        self._thread.start()

    # The parent's side ----------------------------------------------------------------
    def poll(self):
        """Reads what the child sent; True once the job is over (done, failed or stopped)."""
        if self.finished is not None:
            return True
        if self._thread is not None:  # pragma: no cover
            over = not self._thread.is_alive()
        else:
            over = self._read_child()
            if over:
                self._reap()
        if over:
            self.finished = time.time()
        return over

    def wait(self, timeout=None, tick=0.02):
        """Polls until the job is over (or `timeout` seconds); True if it is over."""
        end = None if timeout is None else time.time() + timeout
        while not self.poll():
            if end is not None and time.time() > end:
                return False
            time.sleep(tick)
        return True

    def cancel(self):
        """Stops the job now: the child and everything it started are killed."""
        if self.finished is not None:
            return
        self.cancelled = True
        if self._pid is not None:
            try:
                os.killpg(self._pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            try:
                os.waitpid(self._pid, 0)
            except ChildProcessError:
                pass
            os.close(self._fd)
            self._remove_result()
            self.finished = time.time()

    @property
    def elapsed(self):
        return (self.finished or time.time()) - self.started

    def result(self):
        """The work's value; raises Cancelled, or RuntimeError saying why it failed."""
        if self.cancelled:
            raise Cancelled("VoroHex: stopped by the user")
        if self.finished is None:
            raise RuntimeError("VoroHex: the job is still running")
        if self._error is not None:
            raise self._error
        return self._value


def _send(fd, text):
    data = text.encode("utf-8")
    while data:
        n = os.write(fd, data)
        data = data[n:]
