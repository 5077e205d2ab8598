#!/usr/bin/python3
"""Plate 200 x 100 x 10 mm with a central hole of diameter 20 (steel, E 210000 MPa,
nu 0.3) pulled by 100 MPa on its end faces, solved by CalculiX (ccx) from the INP that
`vorohex mesh` writes alone: this script appends only *MATERIAL, *SOLID SECTION,
*BOUNDARY on the named NSET of the face at x = 0 (plus two of its nodes against rigid
motion), a *DSLOAD (pressure -100) on the named SURFACE of the face at x = 200, and a
*STEP. The peak hoop stress: the largest SXX over the hole's nodes (ccx's nodal stresses),
and where it sits (angle from the load axis; the theory's peak is at 90 degrees).
Reference: Heywood's finite-width factor Kt = 2 + (1 - d/W)^3 on the net section,
100 x 100 / 80 x 2.512 = 314 MPa (plane stress; the 3-D plate's C3D20R values converge to
about 322, and the issue measured Gmsh's tet10 at 321).

Before the quad rings around holes and whole circles in multiples of 4 segments (the
lattice cut by the hole, same script): C3D8I 289.1 MPa (-7.9 %) at 102.9 degrees at size 5
(2,562 nodes), 327.5 (+4.3 %) at 96.9 degrees at size 2.5; C3D20R 297.0 (-5.4 %) at 90 at
size 5, 314.2 at 96.9 at size 2.5: the peak sat on the hole's node nearest 90 degrees.

Gmsh tet10 rows: Gmsh's quadratic tetrahedra (FreeCAD's default FEM mesh) of the same STEP
at that size, solved the same way (bench/fea/gmsh_tet10.py writes the deck with the same
named node sets and surfaces): the accuracy a FreeCAD user gets today, against node count.

Rows with a size at the hole: `--size-at` on the hole's face (local size), graded into the
global size at 0.3 per mm (the default): the refinement where the stress peaks, without the
node count of a uniformly fine mesh.

Writes bench/results/fea_plate.md.  usage: run_plate_hole.py [--build BUILD] [--sizes LIST]
[--local ORDER:SIZE:HOLE,...]
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
W, L, T, D = 100.0, 200.0, 10.0, 20.0
REFERENCE = 100.0 * W / (W - D) * (2 + (1 - D / W) ** 3)  # 314 MPa


def plate_step(path):
    sys.path.append("/usr/lib/freecad-python3/lib")
    import FreeCAD
    import Part
    V = FreeCAD.Vector
    shape = Part.makeBox(L, W, T).cut(Part.makeCylinder(D / 2, T, V(L / 2, W / 2, 0)))
    shape.exportStep(path)
    read = Part.Shape()
    read.read(path)  # the face names as the STEP file numbers them
    return next("Face%d" % (i + 1) for i, f in enumerate(read.Faces)
                if isinstance(f.Surface, Part.Cylinder))


def nodes_of(text):
    out = {}
    for m in re.finditer(r"^(\d+), (\S+), (\S+), (\S+)$", text.split("*ELEMENT")[0], re.M):
        out[int(m.group(1))] = tuple(float(m.group(k)) for k in (2, 3, 4))
    return out


def node_sets(text):
    sets = {}
    for m in re.finditer(r"\*NSET, NSET=(\w+)\n(.*?)(?=\n\*|\Z)", text, re.S):
        sets[m.group(1)] = [int(v) for v in m.group(2).replace("\n", ",").split(",") if v.strip()]
    return sets


def face_where(sets, xyz, test):
    for name, ids in sets.items():
        if name.startswith("Face") and all(test(*xyz[i]) for i in ids):
            return name
    raise RuntimeError("no face set found")


def frd_stresses(path):
    """Nodal stresses (SXX, SYY, SZZ, SXY, SYZ, SZX) from ccx's .frd."""
    out, block = {}, False
    with open(path) as f:
        for line in f:
            if line.startswith(" -4  STRESS"):
                block = True
            elif block and line.startswith(" -3"):
                break
            elif block and line.startswith(" -1"):
                nid = int(line[3:13])
                vals = [float(line[13 + 12 * k:25 + 12 * k]) for k in range(6)]
                out[nid] = vals
    return out


def solve(text, work, tag):
    xyz = nodes_of(text)
    sets = node_sets(text)
    fixed = face_where(sets, xyz, lambda x, y, z: abs(x) < 1e-9)
    pulled = face_where(sets, xyz, lambda x, y, z: abs(x - L) < 1e-9)
    hole = face_where(sets, xyz, lambda x, y, z: abs(math.hypot(x - L / 2, y - W / 2) - D / 2) < 1e-6)
    corner = min(sets[fixed], key=lambda n: math.dist(xyz[n], (0, 0, 0)))
    other = min(sets[fixed], key=lambda n: math.dist(xyz[n], (0, W, 0)))
    deck = text + (
        "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000, 0.3\n"
        "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n"
        "*STEP\n*STATIC\n*BOUNDARY\n{f}, 1, 1, 0\n{c}, 2, 3, 0\n{o}, 3, 3, 0\n"
        "*DSLOAD\n{p}, P, -100\n*NODE FILE\nS\n*END STEP\n").format(
            f=fixed, c=corner, o=other, p=pulled)
    with open(os.path.join(work, tag + ".inp"), "w") as f:
        f.write(deck)
    t0 = time.time()
    p = subprocess.run(["ccx", tag], cwd=work, capture_output=True, text=True, timeout=1800)
    seconds = time.time() - t0
    if p.returncode != 0 or "ERROR" in p.stdout:
        raise RuntimeError("ccx failed on {}: {}".format(tag, p.stdout[-2000:]))
    s = frd_stresses(os.path.join(work, tag + ".frd"))
    peak = max(sets[hole], key=lambda n: s[n][0])
    x, y, _ = xyz[peak]
    angle = abs(math.degrees(math.atan2(y - W / 2, x - L / 2)))
    return s[peak][0], angle, len(xyz), seconds


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--sizes", default="10,5,2.5")
    ap.add_argument("--local", default="1:10:1.25,1:5:1.25,2:10:2.5,2:5:2.5",
                    help="order:global size:hole size runs with --size-at on the hole's face")
    ap.add_argument("--gmsh", default="10,5,3.5,2.5",
                    help="sizes of the Gmsh quadratic-tetrahedra rows (C3D10), empty: none")
    ap.add_argument("--out", default=os.path.join(REPO, "bench", "results", "fea_plate.md"))
    args = ap.parse_args()
    vorohex = os.path.join(args.build, "vorohex")
    work = tempfile.mkdtemp(prefix="vorohex_plate_")
    step = os.path.join(work, "plate.step")
    hole_face = plate_step(step)
    runs = [(order, float(size), None) for order in (1, 2) for size in args.sizes.split(",")]
    for spec in filter(None, args.local.split(",")):
        order, size, local = spec.split(":")
        runs.append((int(order), float(size), float(local)))
    rows = []
    for order, size, local in runs:
        out = os.path.join(work, "plate.inp")
        cmd = [vorohex, "mesh", step, "-o", out, "--size", str(size), "--order", str(order),
               "--quiet"]
        if local:
            cmd += ["--size-at", "%s=%g" % (hole_face, local)]
        p = subprocess.run(cmd, capture_output=True, text=True)
        hole = "-" if local is None else "%g" % local
        if p.returncode != 0:
            rows.append((order, size, hole, "-", "failed: " + p.stderr.strip()[-200:], "", "", "",
                         ""))
            continue
        text = open(out).read()
        element = re.search(r"TYPE=(\w+)", text).group(1)
        peak, angle, nodes, sec = solve(text, work, "plate_%d_%g_%s" % (order, size, hole))
        rows.append((order, size, hole, element, nodes, "%.1f" % peak,
                     "%+.1f %%" % (100 * (peak / REFERENCE - 1)), "%.1f" % angle, "%.2f" % sec))
        print(rows[-1], flush=True)
    for size in [float(v) for v in filter(None, args.gmsh.split(","))]:
        out = os.path.join(work, "gmsh.inp")
        p = subprocess.run([sys.executable, os.path.join(HERE, "gmsh_tet10.py"), step, out,
                            str(size), "Face1=abs(x)<1e-6", "Face2=abs(x-%r)<1e-6" % L,
                            "Face3=abs(math.hypot(x-%r,y-%r)-%r)<1e-6" % (L / 2, W / 2, D / 2)],
                           capture_output=True, text=True)
        if p.returncode != 0:
            rows.append(("Gmsh tet10", size, "-", "-", "failed: " + p.stderr.strip()[-200:], "",
                         "", "", ""))
            continue
        text = open(out).read()
        peak, angle, nodes, sec = solve(text, work, "gmsh_%g" % size)
        rows.append(("Gmsh tet10", size, "-", "C3D10", nodes, "%.1f" % peak,
                     "%+.1f %%" % (100 * (peak / REFERENCE - 1)), "%.1f" % angle, "%.2f" % sec))
        print(rows[-1], flush=True)
    lines = ["# Plate with a hole through CalculiX (bench/fea/run_plate_hole.py)", "",
             __doc__.split("Writes")[0].strip(), "",
             "| order | size | size at the hole | element | nodes | peak SXX (MPa) | error vs %.0f MPa | angle of the peak (deg) | ccx s |" % REFERENCE,
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| " + " | ".join(str(c) for c in r) + " |")
    with open(args.out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", args.out)


if __name__ == "__main__":
    main()
