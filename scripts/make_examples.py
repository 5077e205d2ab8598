#!/usr/bin/python3
"""Writes the bundled example solids in examples/ with FreeCAD's Part module.

Run with FreeCAD's interpreter: /usr/bin/python3 scripts/make_examples.py
"""
import os
import sys

sys.path.append("/usr/lib/freecad-python3/lib")
import FreeCAD  # noqa: E402
import Part  # noqa: E402

V = FreeCAD.Vector
here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples")


def polyhedron(points, faces):
    shell = Part.Shell([Part.Face(Part.makePolygon([points[i] for i in f + [f[0]]])) for f in faces])
    solid = Part.Solid(shell)
    if solid.Volume < 0:
        solid.reverse()
    return solid


def tapered_brick(dx, dy, dz, taper):
    p = [V(0, 0, 0), V(dx, 0, 0), V(dx, dy, 0), V(0, dy, 0),
         V(taper, taper, dz), V(dx - taper, taper, dz), V(dx - taper, dy - taper, dz),
         V(taper, dy - taper, dz)]
    return polyhedron(p, [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5],
                          [2, 3, 7, 6], [3, 0, 4, 7]])


solids = {
    "box_3x2x1": Part.makeBox(3, 2, 1),
    "tapered_brick": tapered_brick(3, 2, 1, 0.5),
}
for name, solid in solids.items():
    assert solid.isValid() and solid.Volume > 0, name
    path = os.path.join(here, name + ".step")
    solid.exportStep(path)
    print(f"{path}: volume {solid.Volume:.6f}, {len(solid.Faces)} faces")
