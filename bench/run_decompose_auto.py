#!/usr/bin/python3
"""Every HexMe model through `vorohex decompose --auto`: the sub-volumes the mesher meshes.

For each model of ../shared/models/hexme: the solid whole where one scheme takes it, else the
exact cuts at its concave edges where every piece has a scheme, else the Voronoi graph's
decomposition (`--time-limit 30`, as the hexme bench's decomposition column). Beside it, the
scheme of the model's mesh in bench/results/hexme.md, to see that what the decomposition
shows is what the mesh is made of. Writes bench/results/decomposition_auto.md.

usage: run_decompose_auto.py [--build BUILD] [--commit SHA] [--only PREFIX[,PREFIX...]]
"""
import argparse
import json
import os
import re
import sys

from run_bench import HEXME, HERE, REPO, hexme_available, measure

LIMIT = 30  # --time-limit, as bench/run_hexme.py's decomposition column
KILL = 45
METHOD = {"whole": "whole", "plane-cuts": "plane cuts", "voronoi": "Voronoi graph"}


def mesh_schemes(table):
    """model -> the VoroHex column of bench/results/hexme.md ("valid map+sweep", ...)."""
    out = {}
    try:
        with open(table) as fh:
            for line in fh:
                cells = [c.strip() for c in line.strip().strip("|").split("|")]
                if len(cells) == 14 and cells[0] not in ("model", "---") and line.startswith("|"):
                    out[cells[0]] = cells[1]
    except OSError:
        pass
    return out


def outcome(report, stderr, code, seconds):
    """(method, status, "before -> after (schemes)" or why it failed)."""
    if report is None:
        last = [l for l in stderr.strip().split("\n") if l][-1:] or ["exit %d" % code]
        if code == -9:
            last = ["killed after %.0f s" % seconds]
        return "?", "failed", "failed: " + last[0].replace("vorohex: ", "")[:90].replace("|", "/")
    method = METHOD.get(report.get("method", "voronoi"), report.get("method", "?"))
    status = report.get("status", "failed")
    subs = report.get("sub_volumes", [])
    if status == "failed" or not subs:
        codes = sorted({d["code"] for d in report.get("diagnostics", []) if d["severity"] == "error"})
        return method, "failed", "failed: " + (", ".join(codes) or "?")
    schemes = {}
    for sv in subs:
        schemes[sv.get("scheme", "?")] = schemes.get(sv.get("scheme", "?"), 0) + 1
    counts = report.get("counts", {})
    return method, status, "%s -> %s (%s)" % (
        counts.get("sub_volumes_before_merge", "?"), counts.get("sub_volumes", len(subs)),
        ", ".join("%d %s" % (n, s) for s, n in sorted(schemes.items())))


def same_as_mesh(row):
    """"yes" where the sub-volumes' schemes are those of the mesh (hexme.md), "no" where the
    mesh is structured and they differ, "" where the mesh is the fallback's or invalid."""
    mesh = row["mesh"]
    if not mesh.startswith("valid ") or " grid" in mesh or "tet-split" in mesh:
        return ""
    count = re.search(r"\((\d+) sub-volumes\)", mesh)
    schemes = set(mesh.split()[1].split("+"))
    m = re.match(r"\d+ -> (\d+) \((.*)\)", row["what"])
    if not m:
        return "no"
    mine = {part.split()[1] for part in m.group(2).split(", ")}
    same = mine == schemes and int(m.group(1)) == (int(count.group(1)) if count else 1)
    return "yes" if same else "no"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--commit", default="unknown")
    ap.add_argument("--only", default="")
    args = ap.parse_args()
    if not hexme_available("every model is"):
        sys.exit(2)
    vorohex = os.path.join(args.build, "vorohex")
    work = os.path.join(HERE, "work", "auto")
    os.makedirs(work, exist_ok=True)
    meshes = mesh_schemes(os.path.join(HERE, "results", "hexme.md"))
    models = sorted(f for f in os.listdir(HEXME)
                    if f.endswith(".step") and f.startswith(tuple(args.only.split(","))))
    rows = []
    for model in models:
        name = model[:-5]
        rep = os.path.join(work, name + ".json")
        if os.path.exists(rep):
            os.remove(rep)
        code, sec, _, err = measure([vorohex, "decompose", os.path.join(HEXME, model), "-o",
                                     os.path.join(work, name + ".brep"), "--auto", "--report",
                                     rep, "--time-limit", str(LIMIT), "--quiet"],
                                    timeout=KILL, memory_gb=3)
        report = None
        if os.path.exists(rep):
            with open(rep) as fh:
                report = json.load(fh)
        method, status, what = outcome(report, err, code, sec)
        schemed = status != "failed" and " none" not in what
        row = dict(model=name, method=method, status=status, what=what, schemed=schemed,
                   seconds=sec, mesh=meshes.get(name, ""))
        rows.append(row)
        print(row, flush=True)
    write(rows, args.commit)


def write(rows, commit):
    schemed = [r for r in rows if r["schemed"]]
    by_method = {}
    for r in schemed:
        by_method[r["method"]] = by_method.get(r["method"], 0) + 1
    several = [r["model"].split("_")[0] for r in schemed
               if re.match(r"\d+ -> (\d+)", r["what"]) and
               int(re.match(r"\d+ -> (\d+)", r["what"]).group(1)) > 1]
    times = sorted(r["seconds"] for r in rows)
    lines = [
        "# HexMe: the sub-volumes the mesher meshes (`vorohex decompose --auto`)",
        "",
        "Generated by `bench/run_decompose_auto.py` at commit %s on this machine (2 cores)." % commit,
        "`--auto` shows what `vorohex mesh` does with a solid before any fallback: the solid",
        "whole where one scheme takes it; else the exact cuts along the faces at its concave",
        "edges where every piece has a scheme (within half the time limit); else the Voronoi",
        "graph's decomposition (`--time-limit 30` for the whole). The mesh column is the VoroHex",
        "column of bench/results/hexme.md (a mesh of several sub-volumes names their schemes",
        "joined by +; where the decomposition's sub-volumes did not mesh together, the mesh is",
        "the grid's).",
        "",
        "Sub-volumes that all have a scheme: %d of %d (%s); several sub-volumes, all with a"
        " scheme: %d (%s)." % (len(schemed), len(rows),
                               ", ".join("%s %d" % (m, n) for m, n in sorted(by_method.items())),
                               len(several), ", ".join(several)),
        "Seconds: median %.1f, worst %.1f." % (times[len(times) // 2] if times else 0,
                                               times[-1] if times else 0),
        "The same sub-volumes and schemes as the mesh, where that is structured: %d of %d%s." % (
            sum(1 for r in rows if same_as_mesh(r) == "yes"),
            sum(1 for r in rows if same_as_mesh(r)),
            "" if not any(same_as_mesh(r) == "no" for r in rows) else
            " (not on %s)" % ", ".join(r["model"].split("_")[0] for r in rows
                                       if same_as_mesh(r) == "no")),
        "",
        "| model | method | sub-volumes | s | mesh (hexme.md) | same |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append("| %s | %s | %s | %.2f | %s | %s |" % (
            r["model"], r["method"], r["what"], r["seconds"], r["mesh"], same_as_mesh(r)))
    out = os.path.join(HERE, "results", "decomposition_auto.md")
    with open(out, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("wrote", out)


if __name__ == "__main__":
    main()
