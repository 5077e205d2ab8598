#!/usr/bin/env python3
"""Summarises the libFuzzer logs of run_fuzz.sh into bench/results/fuzz.md.

run_fuzz.sh runs each target in segments: a segment ends when the time is used up or when
libFuzzer stops at a finding (crash, leak, timeout, out-of-memory); the next segment goes
on with the same working corpus. Each finding is attributed by its stack top: the first
frame in VoroHex's sources (App/, bench/fuzz/) or in an OCCT library (libTK*), skipping
sanitizer, libFuzzer and C/C++ runtime frames. Findings in VoroHex code are open crashes;
those in OCCT are third-party and listed with their stack top.

usage: fuzz_report.py --root REPO --build BUILD --work WORKDIR --out FUZZ.md --budget S
                      --replayed N --flags FLAGS TARGET...
"""
import argparse
import datetime
import os
import re
import subprocess

STATUS = re.compile(r"^#(\d+)\s+(\w+)\s+cov: (\d+) ft: (\d+) corp: (\d+)/(\S+)")
FRAME = re.compile(r"^\s+#(\d+) 0x[0-9a-f]+\s+(?:in (.*?) )?((?:/|\(|<).*)$")
TITLE = re.compile(r"(ERROR: (?:AddressSanitizer|LeakSanitizer|libFuzzer|UndefinedBehaviorSanitizer)"
                   r": .*|runtime error: .*|ALARM: working on the last Unit for \d+ seconds)")


def frame_owner(location, root):
    if "/libTK" in location:
        return "OCCT"
    if os.path.join(root, "App") + "/" in location or os.path.join(root, "bench/fuzz") in location:
        return "VoroHex"
    return None


def short_name(function):
    name = function.replace("(anonymous namespace)::", "")
    name = re.sub(r"\(.*", "", name)  # drop the parameter list
    return name.replace("vorohex::", "")


def parse_finding(text, root):
    """Kind, title, owner and stack top of the finding a segment log ends with."""
    artifact = re.search(r"Test unit written to (\S+)", text)
    title = TITLE.search(text)
    frames = []
    started = False
    for line in text.splitlines():
        m = FRAME.match(line)
        if m:
            started = True
            frames.append((m.group(2) or "?", m.group(3)))
        elif started and not re.match(r"^\s+#\d+ ", line):
            break  # the first stack only (the error location or the allocation)
    owner, top = None, []
    for i, (function, location) in enumerate(frames):
        owner = frame_owner(location, root)
        if owner:
            for f, loc in frames[i:]:
                if frame_owner(loc, root) and short_name(f) not in top:
                    top.append(short_name(f))
                if len(top) == 3:
                    break
            break
    path = artifact.group(1) if artifact else ""
    kind = os.path.basename(path).split("-")[0] if path else "unknown"
    return {
        "kind": kind,
        "artifact": path,
        "title": title.group(1).strip() if title else "(no sanitizer report)",
        "owner": owner or "unknown",
        "top": " < ".join(top) if top else "(no stack)",
    }


def summarise(target, work, root):
    tdir = os.path.join(work, target)
    segments = []
    with open(os.path.join(tdir, "segments")) as f:
        for line in f:
            n, rc, seconds = line.split()
            segments.append((int(n), int(rc), int(seconds)))
    s = {"target": target, "seconds": 0, "executions": 0, "cov": 0, "ft": 0, "findings": [],
         "segments": len(segments)}
    for n, rc, seconds in segments:
        with open(os.path.join(tdir, "logs", "seg%03d.log" % n), errors="replace") as f:
            text = f.read()
        s["seconds"] += seconds
        runs = re.search(r"stat::number_of_executed_units: (\d+)", text)
        if runs:
            s["executions"] += int(runs.group(1))
        for line in text.splitlines():
            m = STATUS.match(line)
            if m:
                s["cov"], s["ft"] = max(s["cov"], int(m.group(3))), max(s["ft"], int(m.group(4)))
        if rc != 0:
            s["findings"].append(parse_finding(text, root))
    corpus = os.path.join(tdir, "corpus")
    files = [os.path.join(corpus, f) for f in os.listdir(corpus)]
    s["corpus_files"] = len(files)
    s["corpus_kb"] = sum(os.path.getsize(f) for f in files) / 1024.0
    return s


def replays(build, target, artifact):
    """Runs one input again: "yes" if it fails again, "no" if it passes."""
    if not artifact or not os.path.exists(artifact):
        return "?"
    try:
        rc = subprocess.run([os.path.join(build, "fuzz", target), "-close_fd_mask=1",
                             "-timeout=60", "-rss_limit_mb=4096", artifact],
                            capture_output=True, timeout=180, check=False).returncode
    except subprocess.TimeoutExpired:
        return "yes"
    return "yes" if rc != 0 else "no"


def git(root, *args):
    return subprocess.run(["git", "-C", root] + list(args), capture_output=True, text=True,
                          check=False).stdout.strip()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--budget", type=int, required=True)
    ap.add_argument("--replayed", type=int, required=True)
    ap.add_argument("--flags", required=True)
    ap.add_argument("targets", nargs="+")
    a = ap.parse_args()
    results = [summarise(t, a.work, a.root) for t in a.targets]

    commit = git(a.root, "rev-parse", "--short", "HEAD")
    # Only the sources the targets are built from.
    dirty = git(a.root, "diff", "--name-only", "HEAD", "--", "App/core", "App/io", "App/occ",
                "App/quality", "bench/fuzz")
    clang = subprocess.run(["clang++", "--version"], capture_output=True, text=True,
                           check=False).stdout.splitlines()[0]
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    out = ["# Fuzzing the readers (libFuzzer)", ""]
    out.append("Written by `bench/fuzz/run_fuzz.sh` (targets and method: `bench/fuzz/README.md`). "
               "Date: %s. Commit: %s%s. %s; machine: %d cores, shared with other jobs." %
               (date, commit, " (plus uncommitted changes in " +
                ", ".join(dirty.splitlines()) + ")" if dirty else "", clang,
                os.cpu_count()))
    out.append("")
    out.append("Flags: `%s`. Budget %d s per target, the targets one after the other. "
               "Before fuzzing, the %d inputs in `bench/fuzz/regressions/` were replayed: no "
               "crash." % (a.flags, a.budget, a.replayed))
    out.append("")
    out.append("| target | seconds | executions | exec/s | cov (edges) | ft (features) | corpus "
               "(files / KB) | crashes in VoroHex | third-party (OCCT) findings |")
    out.append("|---|---|---|---|---|---|---|---|---|")
    for s in results:
        ours = [f for f in s["findings"] if f["owner"] != "OCCT"]
        theirs = [f for f in s["findings"] if f["owner"] == "OCCT"]
        out.append("| %s | %d | %d | %.0f | %d | %d | %d / %.0f | %s | %d |" % (
            s["target"], s["seconds"], s["executions"], s["executions"] / max(1, s["seconds"]),
            s["cov"], s["ft"], s["corpus_files"], s["corpus_kb"],
            "0" if not ours else ", ".join(os.path.basename(f["artifact"]) for f in ours),
            len(theirs)))
    out.append("")
    out.append("Coverage counts VoroHex code only (OCCT is not instrumented). A run stops at a "
               "finding and goes on in a new segment with the same corpus.")
    for s in results:
        if not s["findings"]:
            continue
        groups = {}
        for f in s["findings"]:
            groups.setdefault((f["owner"], f["kind"], f["top"]), []).append(f)
        out.append("")
        out.append("## %s: %d findings in %d segments, %d distinct" % (
            s["target"], len(s["findings"]), s["segments"], len(groups)))
        out.append("")
        out.append("Alone: whether the example input still fails when run by itself (no: the "
                   "failure depends on state left by earlier inputs).")
        out.append("")
        out.append("| where | kind | count | stack top (innermost first) | report | example "
                   "input | alone |")
        out.append("|---|---|---|---|---|---|---|")
        for (owner, kind, top), fs in sorted(groups.items(), key=lambda g: -len(g[1])):
            example = fs[0]["artifact"]
            out.append("| %s | %s | %d | `%s` | %s | %s | %s |" % (
                owner, kind, len(fs), top, re.sub(r" \(pc .*", "", fs[0]["title"])[:90],
                os.path.basename(example), replays(a.build, s["target"], example)))
    out.append("")
    with open(a.out, "w") as f:
        f.write("\n".join(out))


if __name__ == "__main__":
    main()
