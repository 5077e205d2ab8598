#!/usr/bin/python3
"""Boundary quads of a hex mesh that cross a sharp model edge with no node on it.

Such a quad has no face that all its nodes lie on, a node on one face of the edge (and not
on the other) and a node on the other face (and not on the first), and none on the edge or
its vertices: the mesh cuts the corner off there. `vorohex check` does not see it (it checks nodes, and its volume allowance
counts the quad's distance from the CAD as chord error): the measurement behind the known
gap in the README's "Validity and quality". Geometric, from FreeCAD's distances: a node is
on a face or an edge within 1e-6 x the bounding-box diagonal; an edge is sharp where its two
faces' normals differ by more than 30 degrees at its middle.

usage: sharp_edges.py MESH.inp CAD.step   (a mesh written by `vorohex mesh -o MESH.inp`)
"""
import re
import sys

sys.path.append("/usr/lib/freecad-python3/lib")
import FreeCAD  # noqa: E402
import Part  # noqa: E402

HEX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]


def read_inp(path):
    nodes, hexes, mode = {}, [], None
    for line in open(path):
        line = line.strip()
        if line.startswith("*"):
            upper = line.upper()
            mode = "node" if re.match(r"\*NODE\b(?!\s*OUTPUT)", upper) and "FILE" not in upper \
                else ("element" if upper.startswith("*ELEMENT") else None)
            continue
        if not line:
            continue
        if mode == "node":
            t = line.split(",")
            nodes[int(t[0])] = FreeCAD.Vector(*map(float, t[1:4]))
        elif mode == "element":
            hexes.append([int(x) for x in line.split(",") if x.strip()][1:9])
    return nodes, hexes


def sharp_edges(shape, degrees=30):
    out = []
    for i, e in enumerate(shape.Edges):
        faces = [j for j, f in enumerate(shape.Faces) if any(e.isSame(x) for x in f.Edges)]
        if len(faces) != 2:
            continue
        p = e.valueAt(0.5 * (e.FirstParameter + e.LastParameter))
        normals = []
        for j in faces:
            f = shape.Faces[j]
            u, v = f.Surface.parameter(p)
            normals.append(f.normalAt(u, v))
        if normals[0].getAngle(normals[1]) * 180 / 3.141592653589793 > degrees:
            out.append((i, faces[0], faces[1]))
    return out


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    nodes, hexes = read_inp(sys.argv[1])
    shape = Part.Shape()
    shape.read(sys.argv[2])
    tol = 1e-6 * shape.BoundBox.DiagonalLength
    sharp = sharp_edges(shape)
    count = {}
    for h in hexes:
        for f in HEX_FACES:
            key = tuple(sorted(h[i] for i in f))
            count[key] = count.get(key, 0) + 1
    boundary = [k for k, c in count.items() if c == 1]
    on_faces, on_edges = {}, {}
    for n in {n for k in boundary for n in k}:
        p = nodes[n]
        vertex = Part.Vertex(p)
        faces = set()
        for j, f in enumerate(shape.Faces):
            box = f.BoundBox
            box.enlarge(10 * tol)
            if box.isInside(p) and f.distToShape(vertex)[0] <= tol:
                faces.add(j)
        on_faces[n] = faces
        on_edges[n] = {i for i, a, b in sharp
                       if a in faces and b in faces and shape.Edges[i].distToShape(vertex)[0] <= tol}
    crossed = {}
    for k in boundary:
        if set.intersection(*[on_faces[n] for n in k]):
            continue  # the quad lies on one face (its sides may run along two of its edges)
        for i, a, b in sharp:
            only_a = any(a in on_faces[n] and b not in on_faces[n] for n in k)
            only_b = any(b in on_faces[n] and a not in on_faces[n] for n in k)
            if only_a and only_b and not any(i in on_edges[n] for n in k):
                name = "Edge%d" % (i + 1)
                crossed[name] = crossed.get(name, 0) + 1
    print("%d boundary quads; %d cross a sharp edge with no node on it: %s" % (
        len(boundary), sum(crossed.values()),
        ", ".join("%s %d" % (e, c) for e, c in sorted(crossed.items(), key=lambda t: -t[1]))))


if __name__ == "__main__":
    main()
