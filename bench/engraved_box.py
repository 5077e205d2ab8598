#!/usr/bin/python3
"""A 10 x 5 x 2 box with text engraved 0.05 deep into its top face (issue 23's target).

The letters come from a TrueType font through FreeCAD's Part.makeWireString (curved
outlines, B-spline edges), cut from the box and refined (removeSplitter). Writes a STEP.

usage: engraved_box.py OUT.step [--text ABC] [--font PATH] [--depth 0.05] [--height 2.6]
"""
import argparse
import sys

sys.path.append("/usr/lib/freecad-python3/lib")
import FreeCAD  # noqa: E402
import Part  # noqa: E402

FONTS = ["/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf",
         "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"]


def engraved_box(text="ABC", font=None, depth=0.05, height=2.6):
    V = FreeCAD.Vector
    font = font or next(f for f in FONTS if __import__("os").path.exists(f))
    box = Part.makeBox(10, 5, 2)
    faces = []
    for char in Part.makeWireString(text, font, height, 0):
        # One letter: its outer wire and holes (the largest wire is the outline).
        wires = sorted(char, key=lambda w: -Part.Face(w).Area)
        face = Part.Face(wires[0])
        for hole in wires[1:]:
            face = face.cut(Part.Face(hole))
        faces.append(face)
    letters = faces[0].fuse(faces[1:]) if len(faces) > 1 else faces[0]
    bb = letters.BoundBox  # centred on the top face
    letters.translate(V(5 - (bb.XMin + bb.XMax) / 2, 2.5 - (bb.YMin + bb.YMax) / 2, 2))
    cut = letters.extrude(V(0, 0, -depth))
    part = box.cut(cut).removeSplitter()
    return part


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out")
    p.add_argument("--text", default="ABC")
    p.add_argument("--font")
    p.add_argument("--depth", type=float, default=0.05)
    p.add_argument("--height", type=float, default=2.6)
    a = p.parse_args()
    part = engraved_box(a.text, a.font, a.depth, a.height)
    if not part.isValid() or len(part.Solids) != 1:
        sys.exit("engraved_box: the cut gave no single valid solid")
    part.exportStep(a.out)
    print("%s: %d faces, %d edges, volume %.4f" % (a.out, len(part.Faces), len(part.Edges),
                                                   part.Volume))


if __name__ == "__main__":
    main()
