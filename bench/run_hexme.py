#!/usr/bin/python3
"""Every HexMe model through VoroHex (mesh and decompose) beside Gmsh's automatic all-hex.

For each model of ../shared/models/hexme: `vorohex mesh` at the default size (bounding-box
diagonal / 20), Gmsh's subdivision all-hex at the same size (both judged by `vorohex check`
against the CAD), and `vorohex decompose` (sub-volumes before/after merging and schemes).
Writes bench/results/hexme.md.

usage: run_hexme.py [--build BUILD] [--no-gmsh] [--keep-decomposition] [--only PREFIX[,PREFIX...]]
       run_hexme.py --from-logs LOG [LOG...]

--no-gmsh keeps the Gmsh columns of the existing table (Gmsh's result does not change
with VoroHex; it takes most of the run's time). --keep-decomposition keeps the
`vorohex decompose` columns likewise (for a change that does not touch the decomposition). Every measured row is also printed (one
Python dict per line), so runs split over several processes (--only i, --only n, ...) can
be joined into one table with --from-logs (the last row of a model wins).
"""
import argparse
import ast
import json
import os
import re
import subprocess
import sys

from run_bench import HEXME, HERE, REPO, hexme_available, measure


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def errors(diagnostics):
    return ", ".join(sorted({d["code"] for d in diagnostics if d["severity"] == "error"})) or "?"


def failed_decomposition(report):
    """"failed: <error codes>" from the report a failed `vorohex decompose` writes, else None
    (its stderr's last line is often a warning printed after the error)."""
    if not report or report.get("status") != "failed":
        return None
    return "failed: " + errors(report.get("diagnostics", []))


def previous_columns(path, first, last):
    """Columns [first, last) per model from an existing table (for --no-gmsh: the Gmsh
    columns, for --keep-decomposition: the decomposition columns)."""
    out = {}
    try:
        with open(path) as fh:
            for line in fh:
                cells = [c.strip() for c in line.strip().strip("|").split("|")]
                if len(cells) == 14 and cells[0] not in ("model", "---"):
                    out[cells[0]] = cells[first:last]
    except OSError:
        pass
    return out


def previous_rows(path):
    """The rows of an existing table, read back (for --only: the models not measured again
    keep their row, so a partial run never drops the others)."""
    rows, across = {}, {}
    try:
        with open(path) as fh:
            lines = fh.read().split("\n")
    except OSError:
        return rows
    for line in lines:
        if line.startswith("Valid meshes with boundary quads"):
            for model, count in re.findall(r"(\w+) (\d+) \(", line.split("there):", 1)[-1]):
                across[model] = int(count)
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 14 or cells[0] in ("model", "---") or not line.startswith("|"):
            continue

        def num(text, kind=float):
            try:
                return kind(text)
            except ValueError:
                return None

        row = {"model": cells[0], "v": cells[1], "g_kept": cells[6:12], "d": cells[12],
               "d_sec": num(cells[13]), "v_sec": num(cells[5])}
        if num(cells[2], int) is not None:
            row["v_hexes"] = num(cells[2], int)
        if " -> " in cells[3]:
            row["v_min_before"], row["v_min"] = (float(x) for x in cells[3].split(" -> "))
        if " -> " in cells[4]:
            row["v_mean_before"], row["v_mean"] = (float(x) for x in cells[4].split(" -> "))
        elif num(cells[4]) is not None:
            row["v_mean"] = num(cells[4])
        if cells[0].split("_")[0] in across:
            row["v_across"] = across[cells[0].split("_")[0]]
        row = {k: v for k, v in row.items() if v is not None}
        rows[cells[0]] = row
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--no-gmsh", action="store_true")
    ap.add_argument("--keep-decomposition", action="store_true")
    ap.add_argument("--only", default="")
    ap.add_argument("--from-logs", nargs="+", default=None)
    ap.add_argument("--commit", default=None, help="the commit the measured binary was built from")
    args = ap.parse_args()
    global BUILT_FROM
    BUILT_FROM = args.commit or commit()
    if args.from_logs:
        by_model = {}
        for path in args.from_logs:
            with open(path) as fh:
                for line in fh:
                    if line.startswith("{'model'"):
                        row = ast.literal_eval(line)
                        # Killed: runs from before v_limit was recorded read a stale report.
                        if "v_limit" not in row and row.get("v_sec", 0) >= 299:
                            for k in ("v_hexes", "v_min_before", "v_min", "v_mean"):
                                row.pop(k, None)
                            row["v"] = "killed after %.0f s (300 s limit)" % row["v_sec"]
                        by_model[row["model"]] = row
        # Failed decompositions: the error codes from their report, when they wrote one (only
        # a run that ended on its own writes a failed report).
        for row in by_model.values():
            if row.get("d", "").startswith("failed:"):
                why = failed_decomposition(
                    load(os.path.join(HERE, "work", "hexme", row["model"] + ".decomposition.json")))
                row["d"] = why or row["d"].replace("(30 s or 3 GB limit)", "(30 s limit)")
        # Logs from before v_mean_before was recorded: the run's own report still has it.
        for row in by_model.values():
            rep = load(os.path.join(HERE, "work", "hexme", row["model"] + ".json"))
            if "v_mean" in row and "v_mean_before" not in row and rep and rep.get("ok"):
                row["v_mean_before"] = rep["smoothing"]["mean_scaled_jacobian_before"]
        write_table([by_model[m] for m in sorted(by_model)])
        return
    vorohex = os.path.join(args.build, "vorohex")
    work = os.path.join(HERE, "work", "hexme")
    os.makedirs(work, exist_ok=True)
    prefixes = tuple(args.only.split(","))
    if not hexme_available("every model is"):
        sys.exit(2)
    models = sorted(f for f in os.listdir(HEXME) if f.endswith(".step") and f.startswith(prefixes))
    rows = []
    table = os.path.join(HERE, "results", "hexme.md")
    kept = previous_columns(table, 6, 12) if args.no_gmsh else {}
    kept_d = previous_columns(table, 12, 14) if args.keep_decomposition else {}
    for model in models:
        step = os.path.join(HEXME, model)
        name = model[:-5]
        rep = os.path.join(work, name + ".json")
        if os.path.exists(rep):
            os.remove(rep)  # never read a previous run's report for a killed run
        code, sec, mb, err = measure([vorohex, "mesh", step, "-o", os.path.join(work, name + ".vtu"),
                                      "--report", rep, "--quiet"], timeout=MESH_TIMEOUT)
        r = load(rep)
        row = {"model": name, "v_sec": sec, "v_mb": mb, "v_limit": MESH_TIMEOUT}
        size = None
        if r is None:
            row["v"] = ("killed after %.0f s (%d s limit)" % (sec, MESH_TIMEOUT) if sec >= MESH_TIMEOUT - 1
                        else "crash (signal %d)" % -code if code < 0 else "crash (exit %d)" % code)
        elif r["ok"]:
            size = row["size"] = r["size"]
            c = r["check"]
            subs = r.get("sub_volumes", 1)
            row.update(v="valid " + r["scheme"] + (" (%d sub-volumes)" % subs if subs > 1 else ""),
                       v_hexes=c["hexes"],
                       v_min_before=r["smoothing"]["min_scaled_jacobian_before"],
                       v_mean_before=r["smoothing"]["mean_scaled_jacobian_before"],
                       v_min=c["scaled_jacobian"]["min"], v_mean=c["scaled_jacobian"]["mean"])
            for d in r["diagnostics"]:
                if d["code"] == "boundary_across_edges":
                    row["v_across"] = int(d["message"].split()[0])
        else:
            size = row["size"] = r["size"]
            row["v"] = errors(r["diagnostics"])
        if name in kept_d:
            row["d"], d_sec = kept_d[name]
            row["d_sec"] = float(d_sec) if d_sec else None
            row["d_kept"] = True
        else:
            drep = os.path.join(work, name + ".decomposition.json")
            if os.path.exists(drep):
                os.remove(drep)
            # The command bounds itself (--time-limit, stopped 10 % after it where OCCT does
            # not return); the kill is the bench's safety net.
            code, dsec, _, derr = measure([vorohex, "decompose", step, "-o",
                                           os.path.join(work, name + ".parts.brep"), "--report", drep,
                                           "--time-limit", str(DECOMPOSE_LIMIT), "--quiet"],
                                          timeout=DECOMPOSE_KILL, memory_gb=3)
            d = load(drep) if code == 0 else None
            if d is not None:
                subs = d.get("sub_volumes", [])
                schemes = {}
                for sv in subs:
                    schemes[sv.get("scheme", "?")] = schemes.get(sv.get("scheme", "?"), 0) + 1
                counts = d.get("counts", d.get("stats", {}))
                row["d"] = "%s -> %s (%s)" % (counts.get("sub_volumes_before_merge", "?"),
                                              counts.get("sub_volumes", len(subs)),
                                              ", ".join("%d %s" % (n, s) for s, n in sorted(schemes.items())))
            elif failed_decomposition(load(drep)):
                row["d"] = failed_decomposition(load(drep))
            else:
                last = [l for l in derr.strip().split("\n") if l][-1:] or ["exit %d" % code]
                if code == -9:  # killed by the bench (a run ending just before is not)
                    last = ["killed after %.0f s (%d s limit)" % (dsec, DECOMPOSE_KILL)]
                elif "bad_alloc" in derr:
                    last = ["out of memory (3 GB limit)"]
                elif code < 0:
                    last = ["crash (signal %d)" % -code]
                row["d"] = "failed: " + last[0].replace("vorohex: ", "")[:90].replace("|", "/")
            row["d_sec"] = dsec
        if name in kept:
            row["g_kept"] = kept[name]
        if not args.no_gmsh and size is not None:
            msh = os.path.join(work, name + ".gmsh.msh")
            code, gsec, gmb, gerr = measure([sys.executable, os.path.join(HERE, "gmsh_allhex.py"),
                                             step, msh, str(size)], timeout=900)
            row["g_sec"] = gsec
            if code != 0:
                row["g"] = "gmsh failed"
            else:
                crep = os.path.join(work, name + ".gmsh.json")
                subprocess.run([vorohex, "check", msh, "--cad", step, "--report", crep],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=900)
                g = load(crep)
                if g is None:
                    row["g"] = "check failed"
                else:
                    row.update(g="valid" if g["valid"] else "invalid: " + errors(g["diagnostics"]),
                               g_hexes=g["hexes"], g_min=g["scaled_jacobian"]["min"],
                               g_mean=g["scaled_jacobian"]["mean"],
                               g_inv=g["scaled_jacobian"]["inverted"])
                os.remove(msh)
        rows.append(row)
        print(row, flush=True)
    if args.only:
        # A partial run: the other models keep their rows (measured at an earlier commit,
        # which the header names with this one).
        measured = {r["model"] for r in rows}
        kept_rows = [r for m, r in previous_rows(table).items() if m not in measured]
        for r in kept_rows:
            r["kept"] = True
        rows = sorted(rows + kept_rows, key=lambda r: r["model"])
    write_table(rows)


BUILT_FROM = "unknown"
MESH_TIMEOUT = 600  # seconds for one `vorohex mesh` (HexMe i08 takes 324 s on this machine)
DECOMPOSE_LIMIT = 30  # `vorohex decompose --time-limit` (issue 22: every model under 30 s)
DECOMPOSE_KILL = 45  # the bench's kill, past the command's own stop (10 % after its limit)


def commit():
    try:
        return subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def decomposition_times(rows):
    """The decomposition's median and worst seconds, and how many ran over its limit."""
    secs = sorted((r["d_sec"], r["model"].split("_")[0]) for r in rows
                  if isinstance(r.get("d_sec"), (int, float)))
    if not secs:
        return ""
    n = len(secs)
    median = secs[n // 2][0] if n % 2 else 0.5 * (secs[n // 2 - 1][0] + secs[n // 2][0])
    over = [m for s, m in secs if s > DECOMPOSE_LIMIT]
    return ("Decomposition time: median %.1f s, worst %.1f s (%s); over %d s: %d of %d%s." % (
        median, secs[-1][0], secs[-1][1], DECOMPOSE_LIMIT, len(over), n,
        (" (" + ", ".join(over) + ")") if over else ""))


def across_edges(rows):
    """The valid meshes whose boundary quads cut across sharp edges (the check's warning)."""
    valid = [r for r in rows if r.get("v", "").startswith("valid")]
    across = [r for r in valid if r.get("v_across")]
    return ("Valid meshes with boundary quads that span two faces across a sharp edge with no"
            " node on it (warning `boundary_across_edges`: the mesh cuts a corner off there):"
            " %d of %d%s." % (len(across), len(valid), (": " + ", ".join(
                "%s %d (%s)" % (r["model"].split("_")[0], r["v_across"], r["v"].split()[1])
                for r in across)) if across else ""))


def write_table(rows):
    def f(v, fmt="%.3f"):
        return fmt % v if isinstance(v, (int, float)) else (v if v is not None else "")

    valid = sum(1 for r in rows if r.get("v", "").startswith("valid"))
    good = sum(1 for r in rows if r.get("v", "").startswith("valid") and r.get("v_min", -1) >= 0.2)
    structured = [r["model"].split("_")[0] for r in rows
                  if r.get("v", "").startswith("valid") and "tet-split" not in r["v"]
                  and "grid" not in r["v"]
                  and r["model"].startswith("i") and r.get("v_min", -1) >= 0.2]
    several = [m for m in structured
               if "sub-volumes)" in next(r["v"] for r in rows if r["model"].startswith(m + "_"))]
    # As the mesher decomposes (`vorohex decompose --auto`): the solid whole where one scheme
    # takes it, else the exact cuts at concave edges, else the Voronoi graph's; counted where
    # every sub-volume has a scheme and the mesh of them all is valid (the VoroHex column).
    as_mesher = [r for r in rows if r.get("v", "").startswith("valid")
                 and "tet-split" not in r["v"] and "grid" not in r["v"]]
    as_mesher_several = [r for r in as_mesher if "sub-volumes)" in r["v"]]
    decomposed = [r for r in rows if r.get("d", "") and not r["d"].startswith("failed")]
    schemed = [r for r in decomposed if " none" not in r["d"]]
    lines = [
        "# HexMe: VoroHex beside Gmsh's automatic all-hex, and VoroHex's decomposition",
        "",
        "Generated by `bench/run_hexme.py` on this machine (2 cores, shared with other work while",
        "measuring, so seconds are noisy). Size: bounding-box diagonal / 20 for both tools. SJ =",
        "Verdict scaled Jacobian computed by VoroHex's checker for both; VoroHex's min and mean SJ are",
        "shown before -> after smoothing. A VoroHex result is either `valid <scheme>` or the error codes",
        "of its diagnostics (never an invalid mesh reported as success). Gmsh:",
        "`Mesh.SubdivisionAlgorithm=2`, `Mesh.RecombineAll=1`. Decomposition: sub-volumes",
        "before -> after merging (schemes), or why it failed.",
        "",
        "VoroHex schemes: `map` (topological hexahedron), `sweep` (one-to-one), `multisweep`",
        "(prismatic parts: many-to-one, submapped walls), `revolve` (turned parts), `midpoint`",
        "(convex polyhedron), several sub-volumes of a decomposition meshed into one mesh",
        "(`map+sweep`, ...; tried before the fallback, in a child process stopped after 60 s)",
        "and the fallback for solids none accepts: `grid` (the grid mesher), or `tet-split`",
        "(tetrahedra split into hexahedra) where the grid's mesh is invalid and the tet split's",
        "is valid within its 60 s second chance (docs/meshing.md). The decomposition column is",
        "`vorohex decompose` on its own (`--time-limit 30`: it stops itself, 10 % later where",
        "OCCT's split does not return; 3 GB limit), with its median and worst time below.",
        "",
        "VoroHex meshes %d of %d models today, %d of them at min SJ >= 0.2 (VoroHex columns"
        " measured at commit %s%s)." % (
            valid, len(rows), good, BUILT_FROM + ("" if not any(r.get("kept") for r in rows) else
                                            " for %s, the other models' rows kept from the previous table" % ", ".join(
                                                r["model"].split("_")[0] for r in rows if not r.get("kept"))),
            ("; Gmsh columns kept from the previous table" if any("g_kept" in r for r in rows) else "")
            + ("; decomposition columns kept from the previous table"
               if any("d_kept" in r for r in rows) else "")),
        "Industrial models (i01-i25) valid by a structured scheme (not the fallback) with min SJ"
        " >= 0.2: %d%s; meshed as several structured sub-volumes (the exact cuts at concave"
        " edges, or the Voronoi decomposition) with min SJ >= 0.2: %d%s." % (
            len(structured), (" (" + ", ".join(structured) + ")") if structured else "",
            len(several), (" (" + ", ".join(several) + ")") if several else ""),
        "The Voronoi graph's decomposition alone (the decomposition column) completes on %d of"
        " them, and gives sub-volumes that all have a scheme on %d (the others fail: errors"
        " named, or stopped at the limit)." % (len(decomposed),
                                                                              len(schemed)),
        "As the mesher decomposes (the solid whole where one scheme takes it, else the exact cuts"
        " at concave edges, else the Voronoi graph's: `vorohex decompose --auto`), sub-volumes"
        " that all have a scheme and mesh valid together (the VoroHex column, not the fallback):"
        " %d of %d, %d of them several sub-volumes (%s)." % (
            len(as_mesher), len(rows), len(as_mesher_several),
            ", ".join(r["model"].split("_")[0] for r in as_mesher_several) or "none"),
        decomposition_times(rows),
        across_edges(rows),
        "",
        "| model | VoroHex | hexes | min SJ | mean SJ | s | Gmsh | hexes | min SJ | mean SJ | inverted | s | decomposition | s |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        vmin = ("%.3f -> %.3f" % (r["v_min_before"], r["v_min"])) if "v_min" in r else ""
        vmean = (("%.3f -> %.3f" % (r["v_mean_before"], r["v_mean"])) if "v_mean_before" in r
                 else f(r.get("v_mean")))
        gmsh = r.get("g_kept") or [r.get("g", ""), f(r.get("g_hexes"), "%d"), f(r.get("g_min")),
                                   f(r.get("g_mean")), f(r.get("g_inv"), "%d"),
                                   f(r.get("g_sec"), "%.2f")]
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % tuple(
            [r["model"], r.get("v", ""), f(r.get("v_hexes"), "%d"), vmin, vmean,
             f(r.get("v_sec"), "%.2f")] + gmsh + [r.get("d", ""), f(r.get("d_sec"), "%.2f")]))
    out = os.path.join(HERE, "results", "hexme.md")
    with open(out, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("wrote", out)


if __name__ == "__main__":
    main()
