# Long computations (meshing, the Voronoi graph, the decomposition) run in a child process
# so that the caller (FreeCAD's GUI thread) never waits for them: it polls the job, which
# hands over progress messages and, at the end, the result. Stop kills the child and its
# own children (CGAL, the decomposition) at once, whatever stage they are in, and a crash
# in the computation ends the job with a message instead of ending FreeCAD.
#
# The child is a new Python interpreter (the one FreeCAD runs on), not a fork of FreeCAD:
# a fork shares FreeCAD's memory copy-on-write, and the page copies it costs the GUI after
# the fork froze it for up to 0.6 s on a busy machine. Starting the child costs about 0.6 s
# (importing FreeCAD and Part); the work is a module-level function and plain arguments.
"""Cancellable computations in a child process (VoroHex)."""

import os
import pickle
import signal
import subprocess
import sys
import tempfile
import time

__all__ = ["Job", "Cancelled"]

MOD_DIR = os.path.dirname(os.path.abspath(__file__))


# Children killed by cancel() and not yet reaped: the kernel frees a killed child's memory
# in its own time (0.1 to 0.3 s for one that loaded FreeCAD, on a busy machine); the GUI
# does not wait for it, they are reaped later.
_killed = []


def _reap_killed():
    _killed[:] = [p for p in _killed if p.poll() is None]


class Cancelled(Exception):
    """The job was stopped (Job.result raises it after Job.cancel)."""


def _interpreter():
    """The Python executable FreeCAD's own Python is (inside FreeCAD, sys.executable is
    FreeCAD itself)."""
    name = os.path.basename(sys.executable)
    if name.startswith("python"):
        return sys.executable
    v = sys.version_info
    for candidate in (os.path.join(sys.base_prefix, "bin", "python{}.{}".format(v[0], v[1])),
                      os.path.join(sys.base_prefix, "bin", "python3")):
        if os.path.exists(candidate):
            return candidate
    return "python3"


def _freecad_lib():
    """The folder holding FreeCAD.so, for the child's sys.path."""
    try:
        import FreeCAD

        return os.path.join(FreeCAD.getHomePath(), "lib")
    except ImportError:  # pragma: no cover - always inside FreeCAD here
        return ""


# The child's first lines: its sys.path (VoroHex's folder, FreeCAD's library), then the job.
_BOOTSTRAP = ("import sys; sys.path[:0] = [sys.argv[1], sys.argv[2]]; "
              "import VoroHexJobs; VoroHexJobs._child(int(sys.argv[3]), sys.argv[4])")


class Job:
    """Runs `function(report, *args)` in a child process: `function` is a module-level
    function (it is named to the child, not copied), args are picklable; `report(stage,
    fraction)` (in the child) sends progress to the parent, at most every `interval`
    seconds. The parent calls poll() now and then (it never blocks): it reads the progress
    messages and returns True once the job is over; then result() returns the function's
    value or raises (Cancelled, or RuntimeError with the child's error or crash)."""

    def __init__(self, function, *args, interval=0.05):
        _reap_killed()
        self.stage, self.fraction = "starting", 0.0
        self.started = time.time()
        self.finished = None
        self.cancelled = False
        self._value = self._error = None
        self._done = False
        self._buffer = b""
        fd, self._path = tempfile.mkstemp(prefix="vorohex-job-", suffix=".pickle")
        with os.fdopen(fd, "wb") as f:  # the task in, the result out, through one file
            pickle.dump((function.__module__, function.__qualname__, args, interval), f,
                        protocol=pickle.HIGHEST_PROTOCOL)
        read_end, write_end = os.pipe()
        env = dict(os.environ)
        env.pop("PYTHONPATH", None)
        self._proc = subprocess.Popen(
            [_interpreter(), "-I", "-c", _BOOTSTRAP, MOD_DIR, _freecad_lib(), str(write_end),
             self._path], pass_fds=(write_end,), stdin=subprocess.DEVNULL,
            cwd=tempfile.gettempdir(), env=env, start_new_session=True, close_fds=True)
        os.close(write_end)
        self._fd = read_end
        os.set_blocking(read_end, False)

    def _read(self):
        """Reads what the child sent; True when the child has closed its end."""
        while True:
            try:
                chunk = os.read(self._fd, 1 << 16)
            except BlockingIOError:
                return False
            except InterruptedError:
                continue
            if not chunk:
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
        status = self._proc.wait()
        os.close(self._fd)
        if self._error is None:
            if self._done:
                try:
                    with open(self._path, "rb") as f:
                        self._value = pickle.load(f)
                except Exception as e:  # pragma: no cover - a full disk, say
                    self._error = RuntimeError("the result could not be read back: {}".format(e))
            elif status < 0:
                sig = -status
                self._error = RuntimeError("the computation crashed ({}{})".format(
                    signal.Signals(sig).name, ", perhaps for lack of memory"
                    if sig == signal.SIGKILL else ""))
            else:
                self._error = RuntimeError("the computation ended without a result (exit "
                                           "code {})".format(status))
        self._remove()

    def _remove(self):
        if os.path.exists(self._path):
            os.remove(self._path)

    def poll(self):
        """Reads what the child sent; True once the job is over (done, failed or stopped)."""
        if self.finished is not None:
            return True
        _reap_killed()
        if not self._read():
            return False
        self._reap()
        self.finished = time.time()
        return True

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
        try:
            if hasattr(os, "killpg"):
                os.killpg(self._proc.pid, signal.SIGKILL)  # its group: its children too
            else:  # pragma: no cover
                self._proc.kill()
        except ProcessLookupError:
            pass
        if self._proc.poll() is None:
            _killed.append(self._proc)  # dead, not yet reaped: later, not now
        os.close(self._fd)
        self._remove()
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
        data = data[os.write(fd, data):]


def _child(fd, path):
    """The child's side: runs the job stored in `path`, writes its value back there."""
    import importlib
    import traceback

    code = 1
    try:
        if hasattr(os, "nice"):
            os.nice(10)  # the GUI (the parent) goes first on a busy machine
        with open(path, "rb") as f:
            module, name, args, interval = pickle.load(f)
        function = importlib.import_module(module)
        for part in name.split("."):
            function = getattr(function, part)
        last = [0.0]

        def report(stage, fraction=0.0):
            now = time.time()
            if now - last[0] >= interval or fraction >= 1.0:
                last[0] = now
                _send(fd, "p {:.4f} {}\n".format(float(fraction), stage))
            return True

        value = function(report, *args)
        with open(path, "wb") as f:
            pickle.dump(value, f, protocol=pickle.HIGHEST_PROTOCOL)
        _send(fd, "d\n")
        code = 0
    except BaseException:  # everything, so that the parent learns why
        try:
            _send(fd, "e {}\n".format(traceback.format_exc().replace("\n", "\x1f")))
        except BaseException:
            pass
    finally:
        os._exit(code)
