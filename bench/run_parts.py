#!/usr/bin/python3
"""Machined parts built the way FreeCAD users build them, through VoroHex.

Each part is made with FreeCAD's Part module (boxes, cylinders, fuse and cut, refine: what
the Part workbench's Fusion/Cut with "Refine" do; a fillet with makeFillet), written as
STEP and meshed with `vorohex mesh` at the default size (bounding-box diagonal / 20) and
at diagonal / 25. The shapes are the ones issues 20 and 22 name (a stepped block, the
paper's Figure 6 and 7 shapes, a block with two crossing holes, an L bracket with a hole
in each leg, a stepped plate with holes, a flanged pipe), a few more a user makes every
day, and two whose faces come to a point (a boss tangent to a plate's round outline from
inside; a lug whose round end is tangent to its tube, as HexMe i11), and the drilled and
countersunk holes and filleted edges of PartDesign, chamfered edges and a pyramidal
pocket, countersunk holes in a plate and a flange, a pocket with drafted walls, bosses and
pockets whose roots and floors are filleted (round and rectangular). Writes
bench/results/parts.md.

usage: run_parts.py [--build BUILD]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

from run_bench import HERE, REPO, measure


def build_parts(work):
    """STEP files of the parts; returns [(name, path, faces)]."""
    sys.path.append("/usr/lib/freecad-python3/lib")
    import FreeCAD  # noqa: F401  (FreeCAD must be imported before Part)
    import Part
    V = FreeCAD.Vector

    def box(x, y, z, p=(0, 0, 0)):
        return Part.makeBox(x, y, z, V(*p))

    def cyl(r, h, p, d=(0, 0, 1)):
        return Part.makeCylinder(r, h, V(*p), V(*d))

    def refined(s):
        s = s.removeSplitter()
        return s if s.ShapeType == "Solid" else s.Solids[0]

    parts = {}
    parts["stepped block"] = box(30, 20, 10).fuse(box(15, 20, 10, (0, 0, 10))).fuse(
        box(7, 20, 5, (0, 0, 20)))
    hexagon = Part.Face(Part.makePolygon(
        [V(10 * math.cos(k * math.pi / 3), 10 * math.sin(k * math.pi / 3), 0) for k in range(7)]))
    prism = hexagon.extrude(V(0, 0, 5))
    ring = prism.cut(cyl(5, 5, (0, 0, 0)))
    for k in range(6):
        a = k * math.pi / 3 + math.pi / 6
        fin = box(6, 2, 5, (0, -1, 0))
        fin.rotate(V(0, 0, 0), V(0, 0, 1), math.degrees(a))
        fin.translate(V(7 * math.cos(a), 7 * math.sin(a), 0))
        ring = ring.fuse(fin)
    parts["hexagonal ring with fins (Figure 6)"] = ring
    parts["hexagonal wheel with rod (Figure 7)"] = prism.fuse(cyl(3, 10, (0, 0, 5)))
    parts["block with two crossing holes"] = box(20, 20, 20).cut(
        cyl(4, 20, (10, 0, 10), (0, 1, 0))).cut(cyl(4, 20, (0, 10, 10), (1, 0, 0)))
    bracket = box(40, 30, 5).fuse(box(5, 30, 30))
    parts["L bracket with a hole in each leg"] = bracket.cut(cyl(4, 5, (22, 15, 0))).cut(
        cyl(4, 5, (0, 15, 18), (1, 0, 0)))
    edge = [e for e in bracket.Edges if abs(e.BoundBox.XMin - 5) < 1e-6
            and abs(e.BoundBox.ZMin - 5) < 1e-6 and e.BoundBox.YLength > 1]
    parts["L bracket, inner edge filleted"] = refined(bracket).makeFillet(4, edge)
    # A new user's PartDesign bracket (tests/data/l_bracket_fillet_holes.step): 60 x 50, legs 6
    # thick, 40 deep, its inner edge filleted 4, two holes off the middle of its foot and one in
    # its upright. Cut across each leg where the concave fillet meets it: a corner and two legs.
    angle = box(60, 40, 6, (0, -20, 0)).fuse(box(6, 40, 50, (0, -20, 0)))
    inner = [e for e in refined(angle).Edges if abs(e.BoundBox.XMin - 6) < 1e-6
             and abs(e.BoundBox.ZMin - 6) < 1e-6 and e.BoundBox.YLength > 1]
    parts["L bracket, inner edge filleted, holes in both legs"] = refined(angle).makeFillet(
        4, inner).cut(cyl(3.5, 6, (35, -10, 0))).cut(cyl(3.5, 6, (50, 10, 0))).cut(
            cyl(4, 6, (0, 0, 32), (1, 0, 0)))
    plate = box(40, 20, 4).fuse(box(20, 20, 4, (0, 0, 4)))
    for x in (8, 30):
        plate = plate.cut(cyl(2.5, 8, (x, 10, 0)))
    parts["stepped plate with holes"] = plate
    pipe = cyl(10, 40, (0, 0, 0)).fuse(cyl(20, 5, (0, 0, 0))).cut(cyl(7, 40, (0, 0, 0)))
    for k in range(4):
        a = k * math.pi / 2
        pipe = pipe.cut(cyl(2, 5, (15 * math.cos(a), 15 * math.sin(a), 0)))
    parts["flanged pipe with bolt holes"] = pipe
    parts["U channel with holes"] = box(60, 30, 20).cut(box(60, 20, 15, (0, 5, 5))).cut(
        cyl(3, 10, (15, 15, -2))).cut(cyl(3, 10, (45, 15, -2)))
    parts["plate with pocket and holes"] = box(60, 40, 10).cut(box(30, 20, 5, (15, 10, 5))).cut(
        cyl(3, 20, (7, 7, -2))).cut(cyl(3, 20, (53, 33, -2)))
    parts["shaft with collar and keyway"] = cyl(10, 60, (0, 0, 0)).fuse(
        cyl(14, 20, (0, 0, 20))).cut(box(4, 5, 15, (-2, 7, 40)))
    parts["flange with hub, bored"] = cyl(30, 8, (0, 0, 0)).fuse(cyl(15, 20, (0, 0, 8))).cut(
        cyl(8, 40, (0, 0, -5)))
    # A new user's PartDesign parts: a shaft with an end-milled keyway (round ends) and
    # chamfered ends (tests/data/keyed_shaft.step), whose blocks and sweeps spaced the nodes on
    # the keyway's end curves each by its own faces (at size 2.2: the grid's 88,431
    # hexahedra); a V-belt pulley (a revolved profile) with a keyway in its bore, where a sweep
    # bridges the keyway between two multisweeps' walls (its plane-cut pieces:
    # tests/data/vbelt_pulley_keyway_pieces.brep).
    shaft = cyl(12, 80, (0, 0, 0))
    shaft = shaft.makeChamfer(1, [e for e in shaft.Edges if hasattr(e.Curve, "Radius")])
    parts["shaft with an end-milled keyway, chamfered"] = shaft.cut(
        box(5, 8, 32, (8, -4, 24)).fuse(cyl(4, 5, (8, 0, 24), (1, 0, 0))).fuse(
            cyl(4, 5, (8, 0, 56), (1, 0, 0))))
    t = math.tan(math.radians(20))
    profile = [(8, -4), (15, -4), (15, 5), (32, 5), (32, 0), (40, 0), (40, 3), (30, 3 + 10 * t),
               (30, 13 - 10 * t), (40, 13), (40, 16), (32, 16), (32, 11), (15, 11), (15, 20),
               (8, 20)]
    wire = Part.makePolygon([V(r, 0, z) for r, z in profile + profile[:1]])
    pulley = Part.Face(wire).revolve(V(0, 0, 0), V(0, 0, 1), 360)
    parts["V-belt pulley with a keyway in its bore"] = pulley.cut(box(3.5, 5, 30, (7, -2.5, -5)))
    # A flange (a revolved profile: disc of radius 50, 10 thick, hub of radius 20 to height 30,
    # bore of radius 10), its hub's top edge chamfered 1.5, six bolt holes of radius 4 on a
    # circle of radius 35 (tests/data/chamfered_flange.step). At size 5 the chamfer's slab,
    # swept in one layer from the hub's cap as the multisweep meshed it, was refused as poor
    # (0.183 against a bar of 0.3 its source's quads, 0.259, cannot reach): the grid's.
    wire = Part.makePolygon([V(r, 0, z) for r, z in
                             [(10, 0), (50, 0), (50, 10), (20, 10), (20, 30), (10, 30), (10, 0)]])
    flange = Part.Face(wire).revolve(V(0, 0, 0), V(0, 0, 1), 360)
    flange = flange.makeChamfer(1.5, [e for e in flange.Edges if abs(e.BoundBox.ZMin - 30) < 1e-6
                                      and abs(e.BoundBox.XMax - 20) < 1e-6])
    for k in range(6):
        a = k * math.pi / 3
        flange = flange.cut(cyl(4, 10, (35 * math.cos(a), 35 * math.sin(a), 0)))
    parts["flange with a chamfered hub and six bolt holes"] = flange
    # A pillow-block housing as a new user built it in PartDesign (tests/data/pillow_block.step):
    # base 130 x 40 x 15 with two bolt slots, a pedestal 50 wide up to a boss of radius 25 along
    # Y (40 long), its root filleted 4, a bore of radius 15 chamfered 1 at both ends, a grease
    # hole of radius 2.5 from the top into the bore. The half ring over the bore, swept from
    # its outer cylinder, could not chart its source across the cylinder's period (the whole
    # part the grid's, 69,654 hexahedra), and the bore's chamfer slabs were mapped inside out.
    pillow = box(130, 40, 15, (-65, -20, 0)).fuse(box(50, 40, 25, (-25, -20, 15))).fuse(
        cyl(25, 40, (0, -20, 40), (0, 1, 0)))
    pillow = refined(pillow)
    pillow = pillow.makeFillet(4, [e for e in pillow.Edges if e.BoundBox.YLength > 39
                                   and abs(e.BoundBox.ZMin - 15) < 1e-6
                                   and abs(e.BoundBox.ZMax - 15) < 1e-6
                                   and abs(abs(e.BoundBox.XMin) - 25) < 1e-6])
    pillow = pillow.cut(cyl(15, 40, (0, -20, 40), (0, 1, 0)))
    pillow = pillow.makeChamfer(1, [e for e in pillow.Edges if hasattr(e.Curve, "Radius")
                                    and abs(e.Curve.Radius - 15) < 1e-6])
    for x in (-46, 46):
        pillow = pillow.cut(box(12, 11, 15, (x - 6, -5.5, 0)).fuse(
            cyl(5.5, 15, (x - 6, 0, 0))).fuse(cyl(5.5, 15, (x + 6, 0, 0))))
    parts["pillow-block housing with a grease hole"] = pillow.cut(cyl(2.5, 12, (0, 0, 53)))
    # A gear blank as a new user built it (tests/data/gear_blank.step): a revolved rim of radius
    # 60 (20 wide, inner radius 48), a web 8 thick, a hub of radius 25 (30 long) and a bore of
    # radius 12, the web's roots filleted 2, the rim's outer edges chamfered 1, six lightening
    # holes of radius 8 on a circle of radius 36.5. The web between the holes and the hub's
    # fillet is 1.5 wide: at the automatic size its sweep's source folds, so its sub-volumes
    # are meshed at half the size (the grid's 16,580 hexahedra at 0.127 before).
    wire = Part.makePolygon([V(r, 0, z) for r, z in
                             [(12, -15), (25, -15), (25, -4), (48, -4), (48, -10), (60, -10),
                              (60, 10), (48, 10), (48, 4), (25, 4), (25, 15), (12, 15),
                              (12, -15)]])
    gear = Part.Face(wire).revolve(V(0, 0, 0), V(0, 0, 1), 360)
    gear = gear.makeFillet(2, [e for e in gear.Edges if hasattr(e.Curve, "Radius")
                               and abs(abs(e.BoundBox.ZMin) - 4) < 1e-6
                               and min(abs(e.Curve.Radius - 25), abs(e.Curve.Radius - 48)) < 1e-6])
    gear = gear.makeChamfer(1, [e for e in gear.Edges if hasattr(e.Curve, "Radius")
                                and abs(e.Curve.Radius - 60) < 1e-6])
    for k in range(6):
        a = k * math.pi / 3
        gear = gear.cut(cyl(8, 20, (36.5 * math.cos(a), 36.5 * math.sin(a), -10)))
    parts["gear blank with six lightening holes"] = gear
    # A spacer ring as a new user built it (tests/data/spacer_ring.step): 50 outside, 38
    # inside, 15 high, its top edges chamfered 0.5, three radial holes of diameter 5 at half
    # its height. Planes around the holes make it blocks and sweeps in 3 s; their share of
    # the time was 4 s, and where the grid mesher beside and another job shared the cores it
    # ran out: the tet split's 78,452 hexahedra at 0.105 in 85 s, from run to run.
    ring = Part.Face(Part.makePolygon([V(r, 0, z) for r, z in
                                       [(19, 0), (25, 0), (25, 15), (19, 15), (19, 0)]])).revolve(
        V(0, 0, 0), V(0, 0, 1), 360)
    ring = ring.makeChamfer(0.5, [e for e in ring.Edges if e.BoundBox.ZMin > 14.9])
    for k in range(3):
        a = 2 * k * math.pi / 3
        ring = ring.cut(cyl(2.5, 14, (16 * math.cos(a), 16 * math.sin(a), 7.5),
                            (math.cos(a), math.sin(a), 0)))
    parts["spacer ring with three radial holes"] = ring
    # An eccentric cam as a new user built it (tests/data/eccentric_cam.step): a disc of
    # diameter 60 and 12 thick, 8 off the axis of its bore (diameter 20) with a keyway 6 wide
    # and 2.8 deep, its rim's edges chamfered 1. Its chamfer slabs are swept to and from the
    # multisweep's caps: the grid's 82,394 hexahedra before (a slab's target not the image of
    # its source, the rim's circle spaced from each side's own vertex).
    cam = cyl(30, 12, (8, 0, 0))
    cam = cam.makeChamfer(1, [e for e in cam.Edges if hasattr(e.Curve, "Radius")])
    parts["eccentric cam with a keyed bore, its rim chamfered"] = cam.cut(
        cyl(10, 12, (0, 0, 0)).fuse(box(6, 7.8, 12, (-3, 5, 0))))
    # A rib-stiffened angle (tests/data/ribbed_angle.step): legs 60 long and 6 thick, 80 deep,
    # three triangular gussets 5 thick (legs 34) and two holes of diameter 8 in each leg. The
    # gussets' sloped faces are one plane, which cut wedges out of both legs: the grid's
    # 517,734 hexahedra at this size as PartDesign built it.
    angle = box(60, 80, 6, (0, -40, 0)).fuse(box(6, 80, 60, (0, -40, 0)))
    for y in (-30, 0, 30):
        gusset = Part.Face(Part.makePolygon([V(6, y - 2.5, 6), V(40, y - 2.5, 6), V(6, y - 2.5, 40),
                                             V(6, y - 2.5, 6)])).extrude(V(0, 5, 0))
        angle = angle.fuse(gusset)
    for y in (-15, 15):
        angle = angle.cut(cyl(4, 6, (40, y, 0))).cut(cyl(4, 6, (0, y, 40), (1, 0, 0)))
    parts["angle with three gussets, two holes in each leg"] = angle
    parts["T-slot block"] = box(50, 30, 30).cut(box(10, 30, 10, (20, 0, 20))).cut(
        box(24, 30, 6, (13, 0, 14)))
    parts["tube with a cross hole"] = cyl(10, 50, (0, 0, 0)).cut(cyl(7, 50, (0, 0, 0))).cut(
        cyl(3, 30, (-15, 0, 25), (1, 0, 0)))
    # A thin-walled tube (wall 1 of radius 20: a seventieth of its diagonal) with a cross hole.
    parts["thin-walled tube with a cross hole"] = cyl(20, 40, (0, 0, 0)).cut(
        cyl(19, 40, (0, 0, 0))).cut(cyl(5, 50, (-25, 0, 20), (1, 0, 0)))
    # Round holes across the part's other direction (the plane cuts' planes around holes).
    parts["shaft with a cross hole"] = cyl(10, 50, (0, 0, 0)).cut(
        cyl(3, 30, (-15, 0, 25), (1, 0, 0)))
    parts["tube with two cross holes"] = cyl(10, 60, (0, 0, 0)).cut(cyl(7, 60, (0, 0, 0))).cut(
        cyl(3, 30, (-15, 0, 20), (1, 0, 0))).cut(cyl(3, 30, (0, -15, 40), (0, 1, 0)))
    parts["flanged pipe with a cross hole"] = cyl(20, 8, (0, 0, 0)).fuse(
        cyl(12, 50, (0, 0, 0))).cut(cyl(8, 60, (0, 0, -5))).cut(
        cyl(3, 40, (-20, 0, 35), (1, 0, 0)))
    parts["plate with a hole in its side and two through"] = box(60, 40, 10).cut(
        cyl(3, 20, (-1, 20, 5), (1, 0, 0))).cut(cyl(4, 10, (15, 10, 0))).cut(
        cyl(4, 10, (45, 30, 0)))
    # Parts prismatic along two axes (a feature across the main body's axis).
    plate = box(100, 60, 10)
    for x, y in [(10, 10), (10, 50), (70, 10), (70, 50)]:
        plate = plate.cut(cyl(4, 10, (x, y, 0)))
    parts["mounting plate with a lug, cross hole"] = plate.fuse(
        box(12, 30, 40, (85, 15, 10)).cut(cyl(6, 12, (85, 30, 35), (1, 0, 0))))
    base = box(100, 40, 10).cut(cyl(5, 10, (15, 20, 0))).cut(cyl(5, 10, (85, 20, 0)))
    parts["plate with a rib, hole along the rib"] = base.fuse(
        box(40, 16, 30, (30, 12, 10)).cut(cyl(5, 40, (30, 20, 25), (1, 0, 0))))
    angle = box(80, 50, 8).cut(cyl(5, 8, (20, 30, 0))).cut(cyl(5, 8, (60, 30, 0)))
    wall = box(80, 8, 50, (0, 0, 8)).cut(cyl(5, 8, (20, 0, 35), (0, 1, 0))).cut(
        cyl(5, 8, (60, 0, 35), (0, 1, 0)))
    parts["angle bracket, two holes in each leg"] = angle.fuse(wall)
    parts["block with a boss, cross hole"] = box(80, 40, 30).cut(
        cyl(6, 40, (40, 0, 15), (0, 1, 0))).fuse(cyl(10, 15, (20, 20, 30)))
    parts["block with a bored boss, cross hole"] = box(80, 40, 30).cut(
        cyl(6, 40, (40, 0, 15), (0, 1, 0))).fuse(cyl(10, 15, (20, 20, 30))).cut(
        cyl(5, 50, (20, 20, -1)))
    # Faces that come to a point: a boss whose circle is tangent to the plate's outline from
    # inside; a lug whose rounded end is tangent to the tube it is on (as HexMe i11).
    parts["plate with a boss tangent to its outline"] = cyl(20, 4, (0, 0, 0)).fuse(
        cyl(10, 12, (10, 0, 0)))
    lug = cyl(25, 10, (0, 10, 0), (1, 0, 0)).fuse(box(10, 40, 50, (0, 10, -25))).cut(
        cyl(6, 10, (0, 40, 0), (1, 0, 0)))
    parts["tube with a lug whose round end is tangent to it"] = cyl(15, 60, (0, 0, 0), (1, 0, 0)).fuse(
        lug).cut(cyl(9, 60, (0, 0, 0), (1, 0, 0)))
    # What PartDesign's Hole and Fillet make every day: a blind hole with a 118-degree drill
    # point, a countersunk hole, a block with its four top edges filleted (its Voronoi
    # graph's split did not return for 34 s; tests/data/block_top_fillets.step).
    tip = 4 / math.tan(math.radians(59))
    parts["block with a drilled blind hole"] = box(30, 30, 20).cut(
        cyl(4, 12, (15, 15, 8))).cut(
        Part.makeCone(4, 0, tip, V(15, 15, 8), V(0, 0, -1)))
    parts["block with a countersunk hole"] = box(30, 30, 20).cut(cyl(4, 20, (15, 15, 0))).cut(
        Part.makeCone(4, 8, 4, V(15, 15, 16)))
    top = box(30, 20, 10)
    parts["block with its top edges filleted"] = top.makeFillet(
        2, [e for e in top.Edges if e.BoundBox.ZMin > 10 - 1e-6])
    # Rounded edges cut across the fillets' feet: a block with a hole and its outer top edges
    # filleted, a plate with its hole's top edge filleted (a torus;
    # tests/data/plate_hole_edge_fillet.step), and a block with its top and vertical edges
    # filleted (a sphere's three-sided patch at each top corner;
    # tests/data/block_top_vertical_fillets.step).
    holed = box(40, 30, 10).cut(cyl(5, 10, (20, 15, 0)))
    parts["block with a hole, its top edges filleted"] = holed.makeFillet(
        2, [e for e in holed.Edges if e.BoundBox.ZMin > 10 - 1e-6 and
            max(e.BoundBox.XLength, e.BoundBox.YLength) > 20])
    plate = box(40, 30, 8).cut(cyl(5, 8, (20, 15, 0)))
    parts["plate with its hole's edge filleted"] = plate.makeFillet(
        1.5, [e for e in plate.Edges
              if e.BoundBox.ZMin > 8 - 1e-6 and 9 < e.BoundBox.XLength < 11])
    parts["block with its top and vertical edges filleted"] = top.makeFillet(
        2, [e for e in top.Edges if e.BoundBox.ZMin > 10 - 1e-6 or e.BoundBox.ZLength > 9])

    def at(e, z):
        return abs(e.BoundBox.ZMin - z) < 1e-6 and abs(e.BoundBox.ZMax - z) < 1e-6
    # More fillets as FreeCAD users put them: on four holes' edges, on a pocketed block's outer
    # top edges, on top and bottom edges, on a boss's top edge, and at a boss's root (concave:
    # no foot to cut at).
    plate4 = box(80, 50, 10)
    for x, y in [(10, 10), (70, 10), (10, 40), (70, 40)]:
        plate4 = plate4.cut(cyl(4, 10, (x, y, 0)))
    parts["plate with four holes, their edges filleted"] = plate4.makeFillet(
        1.5, [e for e in plate4.Edges if at(e, 10) and e.BoundBox.XLength < 9])
    pocketed = box(60, 40, 20).cut(box(30, 20, 10, (15, 10, 10)))
    parts["block with a pocket, its outer top edges filleted"] = pocketed.makeFillet(
        3, [e for e in pocketed.Edges
            if at(e, 20) and max(e.BoundBox.XLength, e.BoundBox.YLength) > 39])
    parts["block with its top and bottom edges filleted"] = top.makeFillet(
        2, [e for e in top.Edges if at(e, 10) or at(e, 0)])
    bossed = box(60, 40, 10).fuse(cyl(8, 15, (30, 20, 10))).removeSplitter()
    parts["plate with a boss, its top edge filleted"] = bossed.makeFillet(
        2, [e for e in bossed.Edges if at(e, 25)])
    parts["plate with a boss, its root filleted"] = bossed.makeFillet(
        2, [e for e in bossed.Edges if at(e, 10) and e.BoundBox.XLength < 17])
    # Bosses whose roots are rounded or chamfered (concave: cut through the foot on the plate
    # along the coaxial cylinder, the boss is revolved): the root alone, filleted or chamfered,
    # a bored boss, two bosses, a boss among bolt holes, a boss beside a pocket (the plate a
    # multisweep), a flange's hub; a round pocket and a counterbore whose floor is filleted (cut
    # at the floor's foot and beyond the wall: the ring between revolved).
    def circle(e):
        return e.Curve.TypeId == "Part::GeomCircle"
    parts["plate with a boss, only its root filleted"] = bossed.makeFillet(
        2, [e for e in bossed.Edges if at(e, 10) and circle(e)])
    parts["plate with a boss, its root chamfered"] = bossed.makeChamfer(
        2, [e for e in bossed.Edges if at(e, 10) and circle(e)])
    bored = bossed.cut(cyl(4, 25, (30, 20, 0)))
    parts["plate with a bored boss, its root filleted"] = bored.makeFillet(
        2, [e for e in bored.Edges if at(e, 10) and circle(e) and e.Curve.Radius > 7])
    two = box(80, 40, 10).fuse(cyl(7, 12, (20, 20, 10))).fuse(
        cyl(7, 12, (60, 20, 10))).removeSplitter()
    parts["plate with two bosses, their roots filleted"] = two.makeFillet(
        1.5, [e for e in two.Edges if at(e, 10) and circle(e)])
    bolted = box(80, 50, 8).fuse(cyl(10, 12, (40, 25, 8))).removeSplitter()
    for x, y in [(10, 10), (70, 10), (10, 40), (70, 40)]:
        bolted = bolted.cut(cyl(3, 8, (x, y, 0)))
    parts["plate with bolt holes and a boss, its root filleted"] = bolted.makeFillet(
        3, [e for e in bolted.Edges if at(e, 8) and circle(e) and e.Curve.Radius > 9])
    pocket = box(60, 40, 20).cut(cyl(10, 10, (30, 20, 10))).removeSplitter()
    parts["block with a round pocket, its floor filleted"] = pocket.makeFillet(
        2, [e for e in pocket.Edges if at(e, 10) and circle(e)])
    bored_pocket = pocket.cut(cyl(4, 10, (30, 20, 0))).removeSplitter()
    parts["counterbore, its floor filleted"] = bored_pocket.makeFillet(
        2, [e for e in bored_pocket.Edges if at(e, 10) and circle(e) and e.Curve.Radius > 9])
    beside = box(80, 40, 12).fuse(cyl(8, 10, (20, 20, 12))).removeSplitter().cut(
        box(20, 20, 6, (45, 10, 6)))
    parts["plate with a boss, its root filleted, and a pocket"] = beside.makeFillet(
        2, [e for e in beside.Edges if at(e, 12) and circle(e)])
    hub = cyl(40, 8, (0, 0, 0)).fuse(cyl(15, 30, (0, 0, 8))).removeSplitter()
    for i in range(4):
        a = math.pi / 2 * i + 0.3
        hub = hub.cut(cyl(4, 8, (28 * math.cos(a), 28 * math.sin(a), 0)))
    hub = hub.cut(cyl(8, 38, (0, 0, 0)))
    parts["flange with bolt holes, its hub's root filleted"] = hub.makeFillet(
        3, [e for e in hub.Edges if at(e, 8) and circle(e) and abs(e.Curve.Radius - 15) < 1e-6])
    # Chamfers and fillets on one part: the long top edges chamfered, the short ones and the
    # hole's filleted (tests/data/block_chamfered_and_filleted.step): feet at two heights.
    mixed = box(40, 20, 10).cut(cyl(4, 10, (20, 10, 0)))
    mixed = mixed.makeChamfer(1.5, [e for e in mixed.Edges
                                    if at(e, 10) and e.BoundBox.XLength > 39])
    parts["block with chamfered and filleted top edges, a hole"] = mixed.makeFillet(
        1, [e for e in mixed.Edges
            if at(e, 10) and (e.Curve.TypeId == "Part::GeomCircle" or
                              (e.BoundBox.XLength < 1e-6 and
                               min(abs(e.BoundBox.XMin), abs(e.BoundBox.XMin - 40)) < 1e-6))])
    # Part's Chamfer: a block with its four top edges chamfered (convex: the midpoint
    # subdivision's, 0.15, until cut across the chamfers' foot), and with its top and bottom
    # edges chamfered; a block with a pyramidal pocket (sloped caps of the multisweep).
    parts["block with its top edges chamfered"] = top.makeChamfer(
        2, [e for e in top.Edges if e.BoundBox.ZMin > 10 - 1e-6])
    parts["block with top and bottom edges chamfered"] = top.makeChamfer(
        2, [e for e in top.Edges
            if e.BoundBox.ZMin > 10 - 1e-6 or e.BoundBox.ZMax < 1e-6])
    pyramid = Part.makeLoft([Part.makePolygon([V(7, 5, -1), V(23, 5, -1), V(23, 15, -1),
                                               V(7, 15, -1), V(7, 5, -1)]),
                             Part.Vertex(V(15, 10, 5))], True)
    parts["block with a pyramidal pocket"] = top.cut(pyramid)
    # Holes and pockets that widen: a plate with two countersunk holes, a flange with four
    # countersunk bolt holes, a block with a pocket whose walls are drafted (a loft from its
    # floor's square to a larger one above the top, as PartDesign's SubtractiveLoft makes it).
    plate = box(60, 40, 10)
    for x in (15, 45):
        plate = plate.cut(cyl(3, 10, (x, 20, 0))).cut(Part.makeCone(3, 6, 3, V(x, 20, 7)))
    parts["plate with two countersunk holes"] = plate
    flange = cyl(40, 10, (0, 0, 0)).cut(cyl(10, 10, (0, 0, 0)))
    for i in range(4):
        x, y = 25 * math.cos(math.pi / 2 * i), 25 * math.sin(math.pi / 2 * i)
        flange = flange.cut(cyl(3, 10, (x, y, 0))).cut(Part.makeCone(3, 6, 3, V(x, y, 7)))
    parts["flange with countersunk bolt holes"] = flange

    def square(h, z):
        return Part.makePolygon([V(20 - h, 20 - h, z), V(20 + h, 20 - h, z), V(20 + h, 20 + h, z),
                                 V(20 - h, 20 + h, z), V(20 - h, 20 - h, z)])
    parts["block with a drafted pocket"] = box(40, 40, 20).cut(
        Part.makeLoft([square(5, 10), square(10.5, 21)], True))
    # Rectangular pockets whose floor edges are filleted (the fillets meet at mitres in the
    # corners), a rectangular boss whose root is, two pockets, a pocket near the plate's edge,
    # and a pocket whose vertical corners are rounded too (the fillets meet in tori there).
    def floor_edges(s, z, x0, x1, y0, y1):
        return [e for e in s.Edges if at(e, z) and e.BoundBox.XMin > x0 - 1e-6 and
                e.BoundBox.XMax < x1 + 1e-6 and e.BoundBox.YMin > y0 - 1e-6 and
                e.BoundBox.YMax < y1 + 1e-6]
    rect = refined(box(60, 40, 15).cut(box(30, 20, 8, (15, 10, 7))))
    parts["plate with a pocket, its floor edges filleted"] = rect.makeFillet(
        3, floor_edges(rect, 7, 15, 45, 10, 30))
    rboss = refined(box(60, 40, 10).fuse(box(24, 12, 8, (18, 14, 10))))
    parts["plate with a rectangular boss, its root filleted"] = rboss.makeFillet(
        2, floor_edges(rboss, 10, 18, 42, 14, 26))
    two = refined(box(80, 40, 12).cut(box(20, 20, 6, (8, 10, 6))).cut(box(24, 20, 6, (44, 10, 6))))
    parts["plate with two pockets, their floor edges filleted"] = two.makeFillet(
        2.5, floor_edges(two, 6, 8, 68, 10, 30))
    near = refined(box(50, 30, 12).cut(box(20, 14, 7, (3, 8, 5))))
    parts["plate with a pocket near its edge, its floor filleted"] = near.makeFillet(
        2, floor_edges(near, 5, 3, 23, 8, 22))
    corners = [e for e in rect.Edges if e.BoundBox.ZLength > 7.9 and e.BoundBox.ZMin > 6.9 and
               14 < e.BoundBox.XMin < 46 and 9 < e.BoundBox.YMin < 31]
    rounded = refined(rect.makeFillet(5, corners))
    parts["plate with a pocket, its corners and floor filleted"] = rounded.makeFillet(
        3, floor_edges(rounded, 7, 15, 45, 10, 30))
    rounded_boss = refined(rboss.makeFillet(3, [e for e in rboss.Edges
                                                if e.BoundBox.ZLength > 7.9 and e.BoundBox.ZMin > 9.9]))
    parts["plate with a rounded rectangular boss, its root filleted"] = rounded_boss.makeFillet(
        2, floor_edges(rounded_boss, 10, 18, 42, 14, 26))
    # The rectangular boss with its top edges filleted too (radius 1): the root's strips end
    # at the top fillets' feet.
    root = parts["plate with a rectangular boss, its root filleted"]
    parts["plate with a rectangular boss, its root and top edges filleted"] = root.makeFillet(
        1, floor_edges(root, 18, 18, 42, 14, 26))
    # An L-shaped pocket (two boxes fused, refined), its floor edges filleted: six strips, the
    # two at the L's inner corner meeting at a convex mitre.
    ell = refined(box(60, 50, 15).cut(refined(box(30, 10, 9, (10, 10, 7)).fuse(
        box(10, 30, 9, (10, 10, 7))))))
    parts["plate with an L-shaped pocket, its floor edges filleted"] = ell.makeFillet(
        2, floor_edges(ell, 7, 10, 40, 10, 40))
    # T- and U-shaped pockets (two and three boxes fused), their floor edges filleted: two
    # inner corners each.
    tee = refined(box(60, 50, 15).cut(refined(box(30, 10, 9, (15, 30, 7)).fuse(
        box(10, 30, 9, (25, 10, 7))))))
    parts["plate with a T-shaped pocket, its floor edges filleted"] = tee.makeFillet(
        2, floor_edges(tee, 7, 15, 45, 10, 40))
    you = refined(box(60, 50, 15).cut(refined(box(10, 30, 9, (10, 10, 7)).fuse(
        box(30, 10, 9, (10, 10, 7))).fuse(box(10, 30, 9, (30, 10, 7))))))
    parts["plate with a U-shaped pocket, its floor edges filleted"] = you.makeFillet(
        2, floor_edges(you, 7, 10, 40, 10, 40))
    out = []
    for k, (name, shape) in enumerate(parts.items()):
        solid = refined(shape)
        if not solid.isValid():
            raise RuntimeError(name + ": FreeCAD made an invalid solid")
        path = os.path.join(work, "part%02d.step" % k)
        solid.exportStep(path)
        out.append((name, path, len(solid.Faces)))
    return out


def mesh(vorohex, path, work, size=None, extra=()):
    report = os.path.join(work, "report.json")
    if os.path.exists(report):
        os.remove(report)
    cmd = [vorohex, "mesh", path, "-o", os.path.join(work, "out.msh"), "--report", report]
    if size:
        cmd += ["--size", "%.6g" % size]
    cmd += list(extra)
    code, seconds, mb, _ = measure(cmd, timeout=600)
    if not os.path.exists(report):
        return {"status": "no report (exit %d)" % code, "seconds": seconds}
    with open(report) as f:
        r = json.load(f)
    sj = r.get("check", {}).get("scaled_jacobian", {})
    status = ("valid " + r["scheme"]) if r.get("ok") else ", ".join(
        sorted({d["code"] for d in r.get("diagnostics", []) if d["severity"] == "error"}))
    return {"status": status, "hexes": r.get("check", {}).get("hexes"), "min": sj.get("min"),
            "mean": sj.get("mean"), "seconds": seconds, "size": r.get("size"),
            "sub_volumes": r.get("sub_volumes")}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    args = ap.parse_args()
    vorohex = os.path.join(os.path.abspath(args.build), "vorohex")
    commit = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for name, path, faces in build_parts(work):
            default = mesh(vorohex, path, work)
            finer = mesh(vorohex, path, work, default["size"] * 20 / 25) if default.get(
                "size") else {}
            rows.append((name, faces, default, finer))
            print(name, default, finer, flush=True)
        # Issue 23's engraved box: "ABC" 0.05 deep in a 10 x 5 x 2 box (bench/engraved_box.py),
        # at size 0.5 by the default schemes and by the grid mesher alone (engraving absorbed).
        box = os.path.join(REPO, "tests", "data", "engraved_box.step")
        default = mesh(vorohex, box, work, 0.5)
        grid = mesh(vorohex, box, work, 0.5, ["--schemes", "grid", "--no-decompose"])
        rows.append(("box with engraved text, size 0.5; right: the grid alone", 66, default, grid))
        print("engraved box", default, grid, flush=True)

    def f(v):
        return "%.3f" % v if isinstance(v, float) else ("" if v is None else str(v))

    structured = sum(1 for _, _, d, _ in rows if d["status"].startswith("valid")
                     and "grid" not in d["status"] and "tet-split" not in d["status"])
    lines = [
        "# Machined parts built in FreeCAD's Part module",
        "",
        "Generated by `bench/run_parts.py` at commit %s. Each part is built with FreeCAD's"
        " Part module (boxes and cylinders, fuse and cut, refined as the Part workbench's"
        " Refine option does; fillets and chamfers), written as STEP and meshed by `vorohex mesh` at the"
        " default size (diagonal / 20) and at diagonal / 25 (the engraved box: size 0.5, by"
        " the default schemes and by the grid mesher alone). SJ: scaled Jacobian after"
        " smoothing. Seconds: the whole command on the shared 2-core machine." % commit,
        "",
        "Meshed by a structured scheme at the default size: %d of %d." % (structured, len(rows)),
        "",
        "| part | faces | VoroHex (diagonal / 20) | sub-volumes | hexes | min SJ | mean SJ | s |"
        " diagonal / 25 | hexes | min SJ | mean SJ | s |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for name, faces, d, g in rows:
        lines.append("| %s | %d | %s | %s | %s | %s | %s | %.2f | %s | %s | %s | %s | %s |" % (
            name, faces, d["status"], f(d.get("sub_volumes")), f(d.get("hexes")), f(d.get("min")),
            f(d.get("mean")), d["seconds"], g.get("status", ""), f(g.get("hexes")),
            f(g.get("min")), f(g.get("mean")),
            "%.2f" % g["seconds"] if "seconds" in g else ""))
    with open(os.path.join(HERE, "results", "parts.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
