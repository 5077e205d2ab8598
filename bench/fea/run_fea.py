#!/usr/bin/python3
"""Cantilever 100 x 10 x 10 mm (steel, E = 210000 MPa, nu = 0.3), clamped at x = 0 (Face1),
1000 N in +z on the tip face (Face2), solved by CalculiX (ccx) from an INP that
`vorohex mesh` writes alone: this script appends only *MATERIAL, *SOLID SECTION, *BOUNDARY
on the named NSET Face1, *CLOAD on the named NSET Face2 (1000 N shared equally by its
nodes) and a *STEP. The tip deflection (mean z displacement of Face2's nodes) is compared
with Euler-Bernoulli, P L^3 / (3 E I) = 1.905 mm (Timoshenko adds the shear term
P L / (k G A) = 0.0149 mm, +0.78 %).

Part 2 measures where C3D8I stops being trustworthy: the size-5 mesh (two elements through
the thickness) with its inner cross-sections tilted alternately (trapezoidal elements, the
classic distortion test), C3D8I's deflection against the converged C3D20R value of the
same beam, per minimum scaled Jacobian.

Part 3: Gmsh's quadratic tetrahedra (FreeCAD's default FEM mesh) of the same beam, for
comparison at similar node counts.

Writes bench/results/fea.md.  usage: run_fea.py [--build BUILD]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
EULER_BERNOULLI = 1000.0 * 100.0 ** 3 / (3 * 210000.0 * 10.0 ** 4 / 12.0)  # 1.9048 mm


def beam_step(path):
    sys.path.append("/usr/lib/freecad-python3/lib")
    import FreeCAD  # noqa: F401
    import Part
    Part.makeBox(100, 10, 10).exportStep(path)


def node_set(text, name):
    m = re.search(r"\*NSET, NSET=%s\n(.*?)\n\*" % name, text + "\n*", re.S)
    return [int(v) for v in m.group(1).replace("\n", ",").split(",") if v.strip()]


def solve(inp_text, work, tag):
    """Appends the load case to a VoroHex INP, runs ccx; (mean tip uz, seconds, nodes)."""
    tip = node_set(inp_text, "Face2")
    deck = inp_text + (
        "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000, 0.3\n"
        "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n"
        "*STEP\n*STATIC\n*BOUNDARY\nFace1, 1, 3, 0\n"
        "*CLOAD\nFace2, 3, {!r}\n*NODE PRINT, NSET=Face2\nU\n*END STEP\n").format(
            1000.0 / len(tip))
    with open(os.path.join(work, tag + ".inp"), "w") as f:
        f.write(deck)
    t0 = time.time()
    p = subprocess.run(["ccx", tag], cwd=work, capture_output=True, text=True, timeout=600)
    seconds = time.time() - t0
    if p.returncode != 0 or "ERROR" in p.stdout:
        raise RuntimeError("ccx failed on {}: {}".format(tag, p.stdout[-2000:]))
    uz = []
    with open(os.path.join(work, tag + ".dat")) as f:
        for line in f:
            v = line.split()
            if len(v) == 4 and v[0].isdigit():
                uz.append(float(v[3]))
    nodes = len(re.findall(r"^\d+, ", inp_text.split("*ELEMENT")[0], re.M))
    return sum(uz) / len(uz), seconds, nodes


def mesh(vorohex, step, work, size, order, element=None):
    out = os.path.join(work, "beam.inp")
    args = [vorohex, "mesh", step, "-o", out, "--size", str(size), "--order", str(order),
            "--quiet"]
    if element:
        args += ["--element", element]
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != 0:
        return None, (p.stderr.strip().splitlines() or ["exit {}".format(p.returncode)])[-1]
    with open(out) as f:
        return f.read(), None


def scaled_jacobian(c):
    nbrs = [(1, 3, 4), (2, 0, 5), (3, 1, 6), (0, 2, 7), (7, 5, 0), (4, 6, 1), (5, 7, 2), (6, 4, 3)]
    vals = []
    for i, (a, b, d) in enumerate(nbrs):
        m = np.stack([c[a] - c[i], c[b] - c[i], c[d] - c[i]], axis=1)
        vals.append(np.linalg.det(m / np.linalg.norm(m, axis=0)))
    return min(vals)


def distort(inp_text, amplitude):
    """Tilts every inner cross-section x = const (0 < x < 100) by +-amplitude * (z - 5) / 5,
    alternating sign from one section to the next; returns (text, min scaled Jacobian)."""
    head, rest = inp_text.split("*ELEMENT", 1)
    lines = head.split("\n")
    coords = {}
    for k, line in enumerate(lines):
        m = re.match(r"^(\d+), (\S+), (\S+), (\S+)$", line)
        if not m:
            continue
        nid, x, y, z = int(m.group(1)), float(m.group(2)), float(m.group(3)), float(m.group(4))
        if 1e-9 < x < 100 - 1e-9:
            sign = 1 if int(round(x / 5.0)) % 2 else -1
            x += sign * amplitude * (z - 5.0) / 5.0
        coords[nid] = np.array([x, y, z])
        lines[k] = "{}, {!r}, {!r}, {!r}".format(nid, x, y, z)
    sj = 1.0
    for line in rest.split("*ELSET")[0].split("\n"):
        v = line.replace(",", " ").split()
        if len(v) == 9 and all(t.isdigit() for t in v):
            v = [int(t) for t in v]
            sj = min(sj, scaled_jacobian(np.array([coords[n] for n in v[1:]])))
    return "\n".join(lines) + "*ELEMENT" + rest, sj


def element_type(text, name):
    return re.sub(r"TYPE=C3D8I?,", "TYPE={},".format(name), text)


def perturb(inp_text, amplitude, seed=1):
    """Moves every node off the boundary (0 < x < 100, 0 < y, z < 10) by a random vector of
    up to amplitude in each coordinate (a fixed seed); returns (text, min, mean scaled
    Jacobian)."""
    rng = np.random.default_rng(seed)
    head, rest = inp_text.split("*ELEMENT", 1)
    lines = head.split("\n")
    coords = {}
    for k, line in enumerate(lines):
        m = re.match(r"^(\d+), (\S+), (\S+), (\S+)$", line)
        if not m:
            continue
        nid = int(m.group(1))
        p = np.array([float(m.group(2)), float(m.group(3)), float(m.group(4))])
        inside = 1e-9 < p[0] < 100 - 1e-9 and all(1e-9 < p[i] < 10 - 1e-9 for i in (1, 2))
        if inside:
            p = p + rng.uniform(-amplitude, amplitude, 3)
        coords[nid] = p
        lines[k] = "{}, {!r}, {!r}, {!r}".format(nid, *p)
    sjs = []
    for line in rest.split("*ELSET")[0].split("\n"):
        v = line.replace(",", " ").split()
        if len(v) == 9 and all(t.isdigit() for t in v):
            sjs.append(scaled_jacobian(np.array([coords[int(n)] for n in v[1:]])))
    return "\n".join(lines) + "*ELEMENT" + rest, min(sjs), sum(sjs) / len(sjs)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    args = ap.parse_args()
    vorohex = os.path.join(args.build, "vorohex")
    work = tempfile.mkdtemp(prefix="vorohex_fea_")
    step = os.path.join(work, "beam.step")
    beam_step(step)
    rows = []
    for order, elements in ((1, ["C3D8", "C3D8I", "C3D8R", None]), (2, ["C3D20", "C3D20R", None])):
        for size in (10, 5, 2.5):
            for element in elements:
                text, why = mesh(vorohex, step, work, size, order, element)
                label = element or "default"
                if text is None:
                    rows.append((order, size, label, "-", "refused: " + why, "", ""))
                    continue
                used = re.search(r"TYPE=(\w+)", text).group(1)
                uz, seconds, nodes = solve(text, work, "b")
                rows.append((order, size, label if element else "default ({})".format(used),
                             nodes, "{:.4f}".format(uz),
                             "{:+.2f} %".format(100 * (uz / EULER_BERNOULLI - 1)),
                             "{:.2f}".format(seconds)))
    # FreeCAD's default FEM mesh beside them: Gmsh's quadratic tetrahedra (C3D10).
    for size in (10, 5, 2.5):
        out_inp = os.path.join(work, "gmsh.inp")
        p = subprocess.run([sys.executable, os.path.join(HERE, "gmsh_tet10.py"), step, out_inp,
                            str(size), "Face1=abs(x)<1e-6", "Face2=abs(x-100)<1e-6"],
                           capture_output=True, text=True)
        if p.returncode != 0:
            rows.append(("Gmsh tet10", size, "C3D10", "-", "failed: " + p.stderr[-200:], "", ""))
            continue
        with open(out_inp) as f:
            text = f.read()
        uz, seconds, nodes = solve(text, work, "g")
        rows.append(("Gmsh tet10", size, "C3D10", nodes, "{:.4f}".format(uz),
                     "{:+.2f} %".format(100 * (uz / EULER_BERNOULLI - 1)),
                     "{:.2f}".format(seconds)))
    # C3D8I on distorted (trapezoidal) elements against the converged C3D20R value.
    ref_text, _ = mesh(vorohex, step, work, 2.5, 2, "C3D20R")
    reference = solve(ref_text, work, "ref")[0]
    base, _ = mesh(vorohex, step, work, 5, 1, "C3D8I")
    distortion = []
    for amplitude in (0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0):
        text, sj = distort(base, amplitude)
        uz = solve(text, work, "d")[0]
        uz8 = solve(element_type(text, "C3D8"), work, "d8")[0]
        distortion.append((amplitude, sj, uz, 100 * (uz / reference - 1), uz8,
                           100 * (uz8 / reference - 1)))
    fine, _ = mesh(vorohex, step, work, 2.5, 1, "C3D8I")
    random = []
    for amplitude in (0.0, 0.2, 0.4, 0.6, 0.8, 0.9, 1.0):
        text, sj_min, sj_mean = perturb(fine, amplitude)
        if sj_min <= 0:
            continue
        uz = solve(text, work, "r")[0]
        uz8 = solve(element_type(text, "C3D8"), work, "r8")[0]
        random.append((amplitude, sj_min, sj_mean, uz, 100 * (uz / reference - 1), uz8,
                       100 * (uz8 / reference - 1)))

    out = [
        "# Cantilever through CalculiX (bench/fea/run_fea.py)", "",
        "Beam 100 x 10 x 10 mm, steel (E 210000 MPa, nu 0.3), clamped at Face1 (x = 0), 1000 N "
        "on Face2's nodes (equal shares), solved by ccx from the INP `vorohex mesh` writes plus "
        "material, *BOUNDARY on NSET Face1, *CLOAD on NSET Face2 and a *STEP. Tip deflection: "
        "mean z displacement of Face2's nodes. Reference: Euler-Bernoulli "
        "{:.4f} mm (Timoshenko: +0.78 %). Size 10 is one element through the thickness, 5 two, "
        "2.5 four. Gmsh tet10 rows: Gmsh's quadratic tetrahedra (FreeCAD's default FEM mesh) "
        "of the same STEP at that size, loaded the same way (bench/fea/gmsh_tet10.py writes "
        "the same named node sets).".format(EULER_BERNOULLI), "",
        "| order | size | element | nodes | tip uz (mm) | error vs E-B | ccx s |",
        "|---|---|---|---|---|---|---|"]
    out += ["| {} | {} | {} | {} | {} | {} | {} |".format(*r) for r in rows]
    out += ["", "## C3D8I on distorted hexahedra", "",
            "The size-5 mesh (two elements through the thickness) with inner cross-sections "
            "tilted alternately by +-a at the top and bottom faces (trapezoids), C3D8I, against "
            "the converged C3D20R value of the same beam at size 2.5 ({:.4f} mm).".format(
                reference), "",
            "| tilt a (mm) | min scaled Jacobian | C3D8I tip uz (mm) | C3D8I error | C3D8 tip uz "
            "(mm) | C3D8 error |",
            "|---|---|---|---|---|---|"]
    out += ["| {} | {:.3f} | {:.4f} | {:+.2f} % | {:.4f} | {:+.2f} % |".format(*d)
            for d in distortion]
    out += ["", "The size-2.5 mesh (four elements through the thickness) with every inner node "
            "moved by a random vector (each coordinate uniform in [-a, a], seed 1), the "
            "distortion a tetrahedral fallback leaves behind:", "",
            "| a (mm) | min scaled Jacobian | mean | C3D8I tip uz (mm) | C3D8I error | C3D8 tip uz "
            "(mm) | C3D8 error |",
            "|---|---|---|---|---|---|---|"]
    out += ["| {} | {:.3f} | {:.3f} | {:.4f} | {:+.2f} % | {:.4f} | {:+.2f} % |".format(*d)
            for d in random]
    out += ["", "## What the element choice does with this", "",
            "- Reduced integration one element through the thickness (size 10) hourglasses "
            "(the issue measured 23-28 x the deflection): `vorohex mesh` refuses C3D8R/C3D20R "
            "asked for on such a mesh, and the second-order default becomes C3D20 there. C3D8R "
            "is still far off with two and four elements (+32 %, +6 %): a warning when asked "
            "for; C3D20R is fine from two.",
            "- C3D8 locks (-35 %, -12 %, -3.5 %); C3D8I is within 1 % from one element "
            "through the thickness: it is the first-order default.",
            "- No per-element scaled Jacobian predicts C3D8I's error: with inner nodes moved "
            "at random it stays within 0.3 % down to a minimum of 0.19, and on trapezoids it "
            "drifts while the scaled Jacobian stays above 0.93, always closer than C3D8. The "
            "issue measured C3D8I +12 % too soft on a tetrahedral-fallback mesh of mean scaled "
            "Jacobian 0.42, so the rule is on the mesh's mean: below 0.6 (between the 0.83 "
            "measured fine and the 0.42 measured wrong) the default is C3D8 with a warning, "
            "and C3D8I asked for gets a warning. A conservative value, not a measured edge: "
            "no mesh between the two was measured."]
    path = os.path.join(REPO, "bench", "results", "fea.md")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    print("\n".join(out))


if __name__ == "__main__":
    main()
