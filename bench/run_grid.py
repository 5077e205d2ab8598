#!/usr/bin/python3
"""The grid mesher on every HexMe model (forced: `--schemes grid --no-decompose`), and on a
box with engraved letters (10 x 5 x 2, letters cut 0.05 deep, size 0.5).

For each model of ../shared/models/hexme: `vorohex mesh` at the default size (bounding-box
diagonal / 20) with the grid scheme only; the mesh is judged by the pipeline's validity check
(positive scaled Jacobian, conforming, closed, volume, boundary nodes on the CAD). Writes
bench/results/grid.md.

usage: run_grid.py [--build BUILD] [--only PREFIX[,PREFIX...]] [--timeout S]
"""
import argparse
import json
import os
import sys
import tempfile

from run_bench import HEXME, HERE, REPO, hexme_available, measure


def engraved_box(path):
    """A 10 x 5 x 2 box with the letters "VHX" cut 0.05 deep into its top (FreeCAD's Part)."""
    sys.path.append("/usr/lib/freecad-python3/lib")
    import FreeCAD  # noqa: F401
    import Part
    V = FreeCAD.Vector
    box = Part.makeBox(10, 5, 2)
    strokes = [  # polygons in the top face (x, y), 0.3 wide strokes
        [(1, 3.8), (1.3, 3.8), (2, 1.6), (2.7, 3.8), (3, 3.8), (2.15, 1.2), (1.85, 1.2)],  # V
        [(4, 1.2), (4.3, 1.2), (4.3, 2.35), (5.2, 2.35), (5.2, 1.2), (5.5, 1.2), (5.5, 3.8),
         (5.2, 3.8), (5.2, 2.65), (4.3, 2.65), (4.3, 3.8), (4, 3.8)],  # H
        [(6.5, 1.2), (6.85, 1.2), (7.35, 2.2), (7.85, 1.2), (8.2, 1.2), (7.55, 2.5), (8.2, 3.8),
         (7.85, 3.8), (7.35, 2.8), (6.85, 3.8), (6.5, 3.8), (7.15, 2.5)],  # X
    ]
    for s in strokes:
        face = Part.Face(Part.makePolygon([V(x, y, 2) for x, y in s + s[:1]]))
        box = box.cut(face.extrude(V(0, 0, -0.05)))
    box = box.removeSplitter()
    box.exportStep(path)
    return len(box.Faces)


def run(vorohex, model, work, timeout, size=None):
    name = os.path.splitext(os.path.basename(model))[0]
    out = os.path.join(work, name + ".vtu")
    rep = os.path.join(work, name + ".json")
    cmd = [vorohex, "mesh", model, "-o", out, "--schemes", "grid", "--no-decompose",
           "--report", rep, "--quiet", "--time-limit", str(timeout)]
    if size:
        cmd += ["--size", str(size)]
    code, seconds, rss, err = measure(cmd, timeout=timeout + 30)
    row = {"model": name, "exit": code, "seconds": seconds, "rss_mb": rss}
    try:
        with open(rep) as f:
            j = json.load(f)
    except (OSError, ValueError):
        row["status"] = "crashed (exit %d)" % code
        return row
    chk = j.get("check", {})
    row["hexes"] = chk.get("hexes", 0)
    sj = chk.get("scaled_jacobian", {})
    row["min_sj"] = sj.get("min")
    row["mean_sj"] = sj.get("mean")
    row["below_0_2"] = sj.get("fraction_below_0_2")
    row["volume_rel_error"] = chk.get("cad", {}).get("volume_rel_error")
    errors = sorted({d["code"] for d in j.get("diagnostics", []) if d["severity"] == "error"})
    notes = sorted({d["code"] for d in j.get("diagnostics", [])
                    if d["severity"] == "warning" and d["code"] in
                    ("features_not_captured", "features_absorbed", "grid_core_split",
                     "size_reduced")})
    row["status"] = "valid" if j.get("ok") else "invalid: " + ", ".join(errors)
    row["notes"] = ", ".join(notes)
    row["grid"] = next((d["message"] for d in j.get("diagnostics", []) if d["code"] == "grid"), "")
    return row


def fmt(v, f="%.3f"):
    return "-" if v is None else f % v


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--only", default="")
    ap.add_argument("--timeout", type=float, default=120)
    ap.add_argument("--out", default=os.path.join(HERE, "results", "grid.md"))
    a = ap.parse_args()
    vorohex = os.path.join(a.build, "vorohex")
    if not hexme_available("the grid table"):
        sys.exit(1)
    prefixes = [p for p in a.only.split(",") if p]
    models = sorted(m for m in os.listdir(HEXME) if m.endswith(".step")
                    and (not prefixes or any(m.startswith(p) for p in prefixes)))
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for m in models:
            row = run(vorohex, os.path.join(HEXME, m), work, a.timeout)
            print(row, flush=True)
            rows.append(row)
        engraved = os.path.join(work, "engraved_box.step")
        faces = engraved_box(engraved)
        erow = run(vorohex, engraved, work, a.timeout, size=0.5)
        erow["model"] = "engraved box (%d faces), size 0.5" % faces
        print(erow, flush=True)
    valid = [r for r in rows if r["status"] == "valid"]
    lines = ["# Grid mesher on HexMe", "",
             "`bench/run_grid.py`: every HexMe model meshed by the grid scheme alone "
             "(`vorohex mesh --schemes grid --no-decompose`, default size = diagonal / 20, "
             "global smoothing on), judged by the pipeline's validity check. Times are wall "
             "clock on the shared 2-core machine, whole command (read, mesh, smooth, check, "
             "write).", "",
             "Valid: %d of %d; min scaled Jacobian >= 0.2 on %d of the valid ones; time per "
             "model: median %.1f s, max %.1f s (%s); the command stops at %g s." % (
                 len(valid), len(rows), sum(1 for r in valid if (r.get("min_sj") or 0) >= 0.2),
                 sorted(r["seconds"] for r in rows)[len(rows) // 2],
                 max(r["seconds"] for r in rows),
                 max(rows, key=lambda r: r["seconds"])["model"], a.timeout),
             "",
             "By series: " + ", ".join(
                 "%s %d/%d valid" % (p, sum(1 for r in valid if r["model"].startswith(p)),
                                     sum(1 for r in rows if r["model"].startswith(p)))
                 for p in ("s", "n", "i")) + ".",
             "", "| model | status | hexes | min SJ | mean SJ | < 0.2 | volume err | s | notes |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows + [erow]:
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %.1f | %s |" % (
            r["model"], r["status"], r.get("hexes", "-"), fmt(r.get("min_sj"), "%.3g"),
            fmt(r.get("mean_sj")), fmt(r.get("below_0_2"), "%.3f"),
            fmt(r.get("volume_rel_error"), "%.1e"), r["seconds"], r.get("notes", "")))
    with open(a.out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", a.out)


if __name__ == "__main__":
    main()
