#!/usr/bin/python3
"""Gmsh's quadratic tetrahedra (FreeCAD's default FEM mesh) of a CAD file as a CalculiX deck
in the form bench/fea/run_plate_hole.py reads VoroHex's: *NODE, *ELEMENT TYPE=C3D10 ELSET=EALL,
and for every named planar or cylindrical boundary region given on the command line a node
set and an element-face surface of that name. The baseline the plate-with-hole rows are
compared with; never part of VoroHex's meshing.

usage: gmsh_tet10.py IN.step OUT.inp SIZE NAME=TEST [NAME=TEST ...]
  TEST: a Python expression in x, y, z true on the region's nodes, e.g. Face1='abs(x)<1e-6'
"""
import math  # noqa: F401  (for the TEST expressions)
import sys

import gmsh

# Abaqus C3D10 faces (0-based corners) and edge order of the mid-nodes 5..10.
FACES = ((0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0))
EDGES = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))


def main():
    src, out, size = sys.argv[1], sys.argv[2], float(sys.argv[3])
    regions = [a.split("=", 1) for a in sys.argv[4:]]
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    gmsh.model.occ.importShapes(src)
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMin", size)
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.ElementOrder", 2)
    gmsh.model.mesh.generate(3)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    xyz = {int(t): tuple(coords[3 * i:3 * i + 3]) for i, t in enumerate(tags)}
    # Where gmsh puts each tet10 mid-node: its local coordinates name the edge.
    local = gmsh.model.mesh.getElementProperties(11)[4]
    corner = [tuple(local[3 * k:3 * k + 3]) for k in range(4)]
    mid_of = {}
    for k in range(4, 10):
        p = tuple(local[3 * k:3 * k + 3])
        for a in range(4):
            for b in range(a + 1, 4):
                if all(abs(p[i] - 0.5 * (corner[a][i] + corner[b][i])) < 1e-9 for i in range(3)):
                    mid_of[frozenset((a, b))] = k
    _, elems, nodes = gmsh.model.mesh.getElements(3)
    tets = []
    for n in range(len(elems[0])):
        v = [int(t) for t in nodes[0][10 * n:10 * n + 10]]
        c = v[:4]
        p = [xyz[i] for i in c]
        e1 = [p[1][i] - p[0][i] for i in range(3)]
        e2 = [p[2][i] - p[0][i] for i in range(3)]
        e3 = [p[3][i] - p[0][i] for i in range(3)]
        det = (e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0])
               + e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]))
        order = [0, 1, 2, 3] if det > 0 else [0, 2, 1, 3]
        cs = [c[k] for k in order]
        mids = [v[mid_of[frozenset((order[a], order[b]))]] for a, b in EDGES]
        tets.append(cs + mids)
    lines = ["*NODE"] + ["%d, %r, %r, %r" % (t, *xyz[t]) for t in sorted(xyz)]
    lines.append("*ELEMENT, TYPE=C3D10, ELSET=EALL")
    lines += ["%d, %s" % (k + 1, ", ".join(str(i) for i in t)) for k, t in enumerate(tets)]
    for name, test in regions:
        inside = {t for t, (x, y, z) in xyz.items() if eval(test)}
        faces = [(k + 1, f + 1) for k, t in enumerate(tets) for f, tri in enumerate(FACES)
                 if all(t[i] in inside for i in tri)]
        members = sorted({t[i] for k, f in faces for t in [tets[k - 1]] for i in FACES[f - 1]}
                         | {tets[k - 1][4 + EDGES.index(e)] for k, f in faces
                            for e in EDGES if set(e) <= set(FACES[f - 1])})
        lines.append("*NSET, NSET=%s" % name)
        lines += [", ".join(str(i) for i in members[j:j + 16]) for j in range(0, len(members), 16)]
        lines.append("*SURFACE, NAME=%s, TYPE=ELEMENT" % name)
        lines += ["%d, S%d" % kf for kf in faces]
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    gmsh.finalize()


if __name__ == "__main__":
    main()
