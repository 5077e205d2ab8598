# FreeCAD unit tests of VoroHex (run: freecadcmd -t TestVoroHex -M <Mod/VoroHex>).
# Registered through FreeCAD.__unit_test__ in Init.py.
import array
import math
import os
import re
import tempfile
import time
import unittest

import FreeCAD
import Part

import VoroHex
import VoroHexObjects

# VTK hex faces, outward (the mesh order VoroHex uses, and Abaqus/CalculiX C3D8 order).
HEX_FACES = ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))


def hex_volume(p):
    """Signed volume of a hexahedron (8 points, VTK/C3D8 order), by the divergence theorem
    over its faces split into triangles around each face centroid."""
    vol = 0.0
    for f in HEX_FACES:
        q = [p[i] for i in f]
        c = [sum(v[k] for v in q) / 4.0 for k in range(3)]
        for i in range(4):
            a, b = q[i], q[(i + 1) % 4]
            vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                    a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0
    return vol


def femmesh_hex_volumes(fm):
    """Volumes of a Fem.FemMesh's hexahedra, read in SMESH order and converted to VTK."""
    out = []
    for vid in fm.Volumes:
        ids = fm.getElementNodes(vid)
        pts = [fm.Nodes[ids[k]] for k in VoroHex.SMESH_FROM_VTK]
        out.append(hex_volume([(v.x, v.y, v.z) for v in pts]))
    return out


def inp_c3d8_volumes(path):
    """Volumes of the C3D8 elements of an Abaqus/CalculiX .inp, computed from its text."""
    nodes, elements, section = {}, [], None
    pending = []
    with open(path) as f:
        for raw in f:
            line = raw.strip()
            if not line or line.startswith("**"):
                continue
            if line.startswith("*"):
                key = line.upper().replace(" ", "")
                if key.startswith("*NODE") and not key.startswith("*NODEPRINT") and \
                        not key.startswith("*NODEFILE"):
                    section = "node"
                elif re.match(r"\*ELEMENT,(.*,)?TYPE=C3D8[RI]?(,|$)", key):
                    section = "hex"
                else:
                    section = None
                continue
            vals = [v for v in line.split(",") if v.strip()]
            if section == "node":
                nodes[int(vals[0])] = tuple(float(v) for v in vals[1:4])
            elif section == "hex":
                pending.extend(int(v) for v in vals)
                if len(pending) >= 9:  # element id + 8 nodes (may span lines)
                    elements.append(pending[1:9])
                    pending = pending[9:]
    return [hex_volume([nodes[n] for n in e]) for e in elements]


class TestVoroHexApi(unittest.TestCase):
    def setUp(self):
        self.box = Part.makeBox(10, 20, 30)

    def test_module_comes_from_expected_folder(self):
        stage = os.environ.get("VOROHEX_STAGE_DIR")
        if stage:  # under ctest: never a stale install elsewhere
            self.assertEqual(os.path.realpath(os.path.dirname(VoroHex.__file__)),
                             os.path.realpath(stage))

    def test_box_meshes(self):
        r = VoroHex.mesh(self.box, size=5)
        self.assertTrue(r.ok, r.message)
        s = r.stats
        self.assertEqual((s.hexes, s.nodes), (2 * 4 * 6, 3 * 5 * 7))
        self.assertEqual((r.hex_count, r.node_count), (48, 105))
        self.assertEqual(len(r.nodes), 105)
        self.assertEqual(len(r.hexes[0]), 8)
        self.assertEqual(len(r.scaled_jacobian), 48)
        self.assertAlmostEqual(s.min_scaled_jacobian, 1.0, places=9)
        self.assertAlmostEqual(s.mean_scaled_jacobian, 1.0, places=9)
        self.assertEqual(sum(s.histogram), 48)
        self.assertLess(s.volume_rel_error, 1e-9)
        self.assertEqual(s.sub_volumes, 1)
        self.assertFalse(r.errors)
        nodes = r.nodes
        vols = [hex_volume([tuple(nodes[i]) for i in h]) for h in r.hexes]
        self.assertTrue(all(v > 0 for v in vols))
        self.assertAlmostEqual(sum(vols), 6000.0, places=6)
        self.assertTrue(VoroHex.check(r, self.box).valid)

    def test_femmesh_smesh_order_positive(self):
        r = VoroHex.mesh(self.box, size=10)
        fm = r.to_femmesh()
        self.assertEqual((fm.NodeCount, fm.VolumeCount), (r.node_count, r.hex_count))
        self.assertEqual(fm.HexaCount, r.hex_count)
        vols = femmesh_hex_volumes(fm)
        self.assertTrue(all(v > 0 for v in vols))
        self.assertAlmostEqual(sum(vols), 6000.0, places=6)
        report = VoroHex.check(fm, self.box)
        self.assertTrue(report.valid, [str(d) for d in report.diagnostics])
        # The worst hexahedra, located (here all alike: the first three of them).
        self.assertEqual(len(report.worst), 3)
        self.assertAlmostEqual(report.worst[0]["scaled_jacobian"],
                               report.scaled_jacobian.min, places=12)
        self.assertEqual(len(report.worst[0]["centre"]), 3)

    def test_cylinder_is_swept(self):
        cyl = Part.makeCylinder(5, 10)
        r = VoroHex.mesh(cyl, size=1.5)
        self.assertTrue(r.ok, r.message)
        self.assertEqual(r.stats.scheme, "sweep")
        self.assertTrue(VoroHex.check(r, cyl).valid)

    def test_sphere_is_diagnosed_without_the_fallback(self):
        r = VoroHex.mesh(Part.makeSphere(5), fallback=False)
        self.assertFalse(r.ok)
        self.assertTrue(r.errors)
        self.assertIn("not_supported_yet", [d.code for d in r.errors])
        self.assertTrue(r.message)
        self.assertEqual(r.hex_count, 0)

    def test_time_limit(self):
        r = VoroHex.mesh(Part.makeBox(30, 20, 10), size=0.1, time_limit=0.05)
        self.assertFalse(r.ok)
        self.assertIn("time_limit", [d.code for d in r.errors])
        self.assertEqual(r.hex_count, 0)
        with self.assertRaisesRegex(ValueError, "time_limit"):
            VoroHex.mesh(Part.makeBox(1, 1, 1), time_limit=-1)

    def test_sphere_is_meshed_by_the_fallback_with_a_warning(self):
        sphere = Part.makeSphere(5)
        r = VoroHex.mesh(sphere, size=1.5, smooth_passes=2)
        self.assertTrue(r.ok, r.message)
        self.assertEqual(r.stats.scheme, "grid")
        self.assertIn("fallback", [d.code for d in r.diagnostics])
        self.assertIn("grid", [d.code for d in r.diagnostics])
        # On two cores the fallback ran beside the (failed) decomposition.
        self.assertEqual(r.stats.fallback_beside, (os.cpu_count() or 1) >= 2)
        self.assertGreater(r.stats.min_scaled_jacobian, 0)
        self.assertTrue(VoroHex.check(r, sphere).valid)
        with self.assertRaisesRegex(TypeError, "fallback"):
            VoroHex.mesh(sphere, fallback="no")
        # The tetrahedral fallback stays for comparison; an unknown one is refused.
        with self.assertRaisesRegex(TypeError, "fallback_scheme"):
            VoroHex.mesh(sphere, fallback_scheme=1)
        with self.assertRaisesRegex(ValueError, "fallback_scheme"):
            VoroHex.mesh(sphere, fallback_scheme="octree")

    def test_stop_inside_the_fallbacks_tetrahedra(self):
        # (The tetrahedral fallback, kept for comparison behind fallback_scheme.)
        # CGAL meshes the tetrahedra in a child process that checks no flag: while it works,
        # the progress callback still hears from the waiting side (heartbeats) and a False
        # from it stops the run there (the child is killed).
        beats = []

        def stop_in_tetrahedra(stage, fraction):
            if stage == "tetrahedra":
                beats.append(fraction)
            return len(beats) < 3

        r = VoroHex.mesh(Part.makeSphere(5), size=0.15, progress=stop_in_tetrahedra,
                         fallback_scheme="tet-split")
        self.assertFalse(r.ok)
        self.assertIn("cancelled", [d.code for d in r.errors])
        self.assertEqual(r.hex_count, 0)
        self.assertGreaterEqual(len(beats), 3)

    def test_decompose_l_shape(self):
        pts = [(0, 0, 0), (4, 0, 0), (4, 1, 0), (1, 1, 0), (1, 3, 0), (0, 3, 0), (0, 0, 0)]
        face = Part.Face(Part.makePolygon([FreeCAD.Vector(*p) for p in pts]))
        solid = face.extrude(FreeCAD.Vector(0, 0, 3))
        with tempfile.TemporaryDirectory() as tmp:
            vtp = os.path.join(tmp, "faces.vtp")
            d = VoroHex.decompose(solid, merge=False, vtp=vtp)
            self.assertTrue(os.path.exists(vtp))
        self.assertTrue(d.ok, d.diagnostics)
        self.assertEqual(d.counts["sub_volumes"], 3)
        self.assertEqual(len(d.shapes), 3)
        self.assertEqual(sorted(sv["type"] for sv in d.sub_volumes), ["Ve", "Vs", "Vs"])
        self.assertAlmostEqual(sum(s.Volume for s in d.shapes), solid.Volume, places=6)
        self.assertTrue(d.faces)
        # The cuts meet the walls square: 90 degrees, above the default sharp angle (60).
        self.assertEqual([round(f["min_angle"], 6) for f in d.faces], [90.0] * len(d.faces))
        merged = VoroHex.decompose(solid)
        self.assertEqual(len(merged.shapes), 1)
        self.assertEqual(merged.sub_volumes[0]["scheme"], "sweep")
        with self.assertRaisesRegex(ValueError, "sharp_angle"):
            VoroHex.decompose(solid, sharp_angle=0)
        with self.assertRaisesRegex(TypeError, "merge"):
            VoroHex.decompose(solid, merge="yes")
        # A time limit too short for anything: a failed decomposition naming the step.
        late = VoroHex.decompose(solid, time_limit=0.001)
        self.assertFalse(late.ok)
        self.assertEqual(late.shapes, [])
        errors = [d for d in late.diagnostics if d["severity"] == "error"]
        self.assertIn("time_limit", [d["code"] for d in errors])
        self.assertIn("stopped at its time limit while",
                      [d for d in errors if d["code"] == "time_limit"][0]["message"])
        for bad in (0, -1, float("nan")):
            with self.assertRaisesRegex(ValueError, "time_limit"):
                VoroHex.decompose(solid, time_limit=bad)
        with self.assertRaisesRegex(TypeError, "time_limit"):
            VoroHex.decompose(solid, time_limit="10")
        self.assertTrue(VoroHex.decompose(solid, method="plane-cuts", time_limit=20).ok)

    def test_plane_cuts_decomposition(self):
        # The mesher's other decomposition, from Python: a round post on a plate is cut
        # around and under the post (one cylinder, one plane: three pieces), and the pieces
        # under and beside the post merge again into the plate's multisweep.
        plate = Part.makeBox(60, 40, 10)
        post = Part.makeCylinder(8, 20, FreeCAD.Vector(30, 20, 10))
        solid = plate.fuse(post).removeSplitter()
        d = VoroHex.decompose(solid, method="plane-cuts")
        self.assertTrue(d.ok, d.diagnostics)
        self.assertEqual(d.method, "plane-cuts")
        self.assertEqual(d.counts["planes"], 1)
        self.assertEqual(d.counts["cylinders"], 1)
        self.assertEqual(d.counts["sub_volumes_before_merge"], 3)
        self.assertEqual(sorted(sv["scheme"] for sv in d.sub_volumes), ["multisweep", "sweep"])
        # Merged without checking each merge's neighbours, the post and the piece under it
        # become one cylinder, which the plate's top circle splits once glued (no sweep): the
        # merging ran again checking each merge.
        self.assertTrue(d.merges_checked_each)
        # Why the cuts are where they are: the plate's top plane and the post's cylinder,
        # both taken at the circle where the post stands on the plate.
        self.assertEqual([c["kind"] for c in d.cut_surfaces], ["plane", "cylinder"])
        top = [f for f in solid.Faces if abs(f.CenterOfMass.z - 10) < 1e-9
               and f.Surface.__class__.__name__ == "Plane"][0]
        index = [k for k, f in enumerate(solid.Faces) if f.isSame(top)][0]
        self.assertEqual(d.cut_surfaces[0]["face"], "Face%d" % (index + 1))
        circle = d.cut_surfaces[0]["concave_edges"]
        self.assertEqual(circle, d.cut_surfaces[1]["concave_edges"])
        self.assertTrue(all(c["used"] for c in d.cut_surfaces))
        self.assertEqual(len(d.shapes), 2)
        self.assertAlmostEqual(sum(s.Volume for s in d.shapes), solid.Volume, places=6)
        # merge=False: the three pieces as cut, each with its scheme.
        cut = VoroHex.decompose(solid, method="plane-cuts", merge=False)
        self.assertTrue(cut.ok, cut.diagnostics)
        self.assertEqual(len(cut.shapes), 3)
        self.assertEqual(cut.counts["sub_volumes"], 3)
        self.assertTrue(all(sv["scheme"] != "none" for sv in cut.sub_volumes))
        self.assertAlmostEqual(sum(s.Volume for s in cut.shapes), solid.Volume, places=6)
        for sv, shape in zip(d.sub_volumes, d.shapes):
            self.assertAlmostEqual(sv["volume"], shape.Volume, places=6)
        # No concave edge: a clear failure, nothing to show.
        sphere = VoroHex.decompose(Part.makeSphere(5), method="plane-cuts")
        self.assertFalse(sphere.ok)
        self.assertEqual(sphere.shapes, [])
        self.assertIn("no concave edge", sphere.diagnostics[0]["message"])
        with self.assertRaisesRegex(ValueError, "'sharp_angle' is an option of the Voronoi"):
            VoroHex.decompose(solid, method="plane-cuts", sharp_angle=30)
        with self.assertRaisesRegex(ValueError, "'method' must be"):
            VoroHex.decompose(solid, method="planes")
        with self.assertRaisesRegex(ValueError, "'tangent_planes' is an option of"):
            VoroHex.decompose(solid, tangent_planes=True)
        with self.assertRaisesRegex(TypeError, "'tangent_planes' must be True or False"):
            VoroHex.decompose(solid, method="plane-cuts", tangent_planes="yes")

    def test_auto_decomposition_is_what_the_mesher_meshes(self):
        # method="auto" gives the sub-volumes the mesher meshes: a solid one scheme takes
        # whole is not cut; HexMe i10 (no single scheme) is cut along the planes of the faces
        # at its concave edges into the blocks and sweeps its mesh is made of; a sphere (no
        # concave edge) goes to the Voronoi decomposition, which says why.
        box = Part.makeBox(2, 3, 4)
        whole = VoroHex.decompose(box, method="auto")
        self.assertEqual((whole.method, whole.status), ("whole", "ok"))
        self.assertEqual([sv["scheme"] for sv in whole.sub_volumes], ["map"])
        self.assertEqual(len(whole.shapes), 1)
        self.assertAlmostEqual(whole.shapes[0].Volume, 24.0, places=9)
        self.assertEqual([d["code"] for d in whole.diagnostics], ["not_cut"])
        # A sweep whole names its source and target (the decomposition view's dark faces).
        V = FreeCAD.Vector
        pentagon = Part.Face(Part.makePolygon(
            [V(math.cos(a), math.sin(a), 0) for a in
             [2 * math.pi * k / 5 for k in range(5)] + [0]])).extrude(V(0, 0, 3))
        swept = VoroHex.decompose(pentagon, method="auto")
        self.assertEqual([sv["scheme"] for sv in swept.sub_volumes], ["sweep"])
        ends = {swept.sub_volumes[0]["source"], swept.sub_volumes[0]["target"]}
        caps = {"Face%d" % (k + 1) for k, f in enumerate(pentagon.Faces)
                if len(f.Edges) == 5}
        self.assertEqual(ends, caps)
        hexme = os.environ.get("VOROHEX_HEXME")
        self.assertTrue(hexme, "VOROHEX_HEXME: the repository's tests/data/hexme (ctest sets it)")
        i10 = Part.read(os.path.join(hexme, "i10o_simp.step"))
        d = VoroHex.decompose(i10, method="auto")
        self.assertEqual((d.method, d.status), ("plane-cuts", "ok"), d.diagnostics)
        for sv, piece in zip(d.sub_volumes, d.shapes):  # each sweep's ends: two of its faces
            if sv["scheme"] == "sweep":
                self.assertLessEqual(int(sv["source"][4:]), len(piece.Faces))
                self.assertLessEqual(int(sv["target"][4:]), len(piece.Faces))
        self.assertAlmostEqual(sum(s.Volume for s in d.shapes) / i10.Volume, 1, places=6)
        m = VoroHex.mesh(i10)
        self.assertTrue(m.ok, m.message)
        self.assertEqual(sorted(sv["scheme"] for sv in d.sub_volumes),
                         sorted(m.stats.sub_volume_schemes))
        sphere = VoroHex.decompose(Part.makeSphere(5), method="auto")
        self.assertEqual(sphere.method, "voronoi")
        why = [x for x in sphere.diagnostics if x["code"] == "plane_cuts_not_used"]
        self.assertEqual(len(why), 1)
        self.assertIn("no concave edge", why[0]["message"])
        # The meshers that judge: without the multisweep, a round post on a plate is not
        # taken whole, and its pieces are blocks and sweeps only.
        post = Part.makeBox(60, 40, 10).fuse(
            Part.makeCylinder(8, 20, FreeCAD.Vector(30, 20, 10))).removeSplitter()
        self.assertEqual(VoroHex.decompose(post, method="auto").method, "whole")
        no_multi = VoroHex.decompose(post, method="auto", multisweep=False)
        self.assertNotEqual(no_multi.method, "whole")
        self.assertNotIn("multisweep", [sv["scheme"] for sv in no_multi.sub_volumes])
        with self.assertRaisesRegex(TypeError, "'multisweep' must be True or False"):
            VoroHex.decompose(post, method="auto", multisweep=1)
        with self.assertRaisesRegex(ValueError, "'method' must be"):
            VoroHex.decompose(post, method="mesher")

    def test_auto_cuts_around_a_cross_hole(self):
        # A thin-walled tube with a cross hole, made as a FreeCAD user makes it: no concave
        # edge to cut at, so method "auto" (as the mesher) cuts with four planes around the
        # hole, each named as such, and the mesh is made of the same structured sub-volumes.
        import VoroHexParts
        V = FreeCAD.Vector
        tube = (Part.makeCylinder(20, 40).cut(Part.makeCylinder(19, 40))
                .cut(Part.makeCylinder(5, 50, V(-25, 0, 20), V(1, 0, 0))).removeSplitter())
        d = VoroHex.decompose(tube, method="auto")
        self.assertEqual((d.method, d.status), ("plane-cuts", "ok"), d.diagnostics)
        self.assertEqual([c["kind"] for c in d.cut_surfaces], ["hole_plane"] * 4)
        hole = d.cut_surfaces[0]["face"]
        self.assertIsInstance(tube.Faces[int(hole[4:]) - 1].Surface, Part.Cylinder)
        self.assertEqual(tube.Faces[int(hole[4:]) - 1].Surface.Radius, 5)
        self.assertEqual(VoroHexParts.method_text(d),
                         "Cut along planes around its holes (4 planes around the hole of "
                         + hole + ")")
        # FreeCAD's Volume of the tube itself is off by 4e-6 (4742.497: its default integration
        # over the hole's intersection faces; 4742.480 accurately, the pieces' sum 4742.479).
        self.assertAlmostEqual(sum(s.Volume for s in d.shapes) / tube.Volume, 1, places=5)
        m = VoroHex.mesh(tube)
        self.assertTrue(m.ok, m.message)
        self.assertEqual(sorted(sv["scheme"] for sv in d.sub_volumes),
                         sorted(m.stats.sub_volume_schemes))
        self.assertGreaterEqual(m.stats.min_scaled_jacobian, 0.3)

    def test_partdesign_drilled_blind_hole_is_cut_and_swept(self):
        # A block with a blind hole made by PartDesign's Hole (its default drill point, a
        # 118-degree cone): cut along the hole's cylinder, the column under the hole is swept
        # up to the cone (its apex on a node), the rest is one multisweep. It was the grid
        # mesher's before.
        import Sketcher  # noqa: F401  (the sketches' type)
        V = FreeCAD.Vector
        doc = FreeCAD.newDocument("DrilledHole")
        try:
            body = doc.addObject("PartDesign::Body", "Body")
            base = body.newObject("Sketcher::SketchObject", "Base")
            base.Support, base.MapMode = (doc.getObject("XY_Plane"), [""]), "FlatFace"
            corners = [V(0, 0, 0), V(30, 0, 0), V(30, 30, 0), V(0, 30, 0)]
            for i in range(4):
                base.addGeometry(Part.LineSegment(corners[i], corners[(i + 1) % 4]))
            doc.recompute()
            pad = body.newObject("PartDesign::Pad", "Pad")
            pad.Profile, pad.Length = base, 20
            doc.recompute()
            top = next(i for i, f in enumerate(pad.Shape.Faces)
                       if abs(f.CenterOfMass.z - 20) < 1e-6)
            circle = body.newObject("Sketcher::SketchObject", "HoleSketch")
            circle.Support, circle.MapMode = (pad, ["Face%d" % (top + 1)]), "FlatFace"
            doc.recompute()
            circle.addGeometry(Part.Circle(V(15, 15, 0), V(0, 0, 1), 4))
            doc.recompute()
            hole = body.newObject("PartDesign::Hole", "Hole")
            hole.Profile, hole.Diameter, hole.Depth = circle, 8, 12
            hole.DepthType, hole.DrillPoint, hole.Threaded = "Dimension", "Angled", False
            doc.recompute()
            self.assertTrue(hole.isValid())
            shape = body.Shape
            self.assertIn("Cone", [type(f.Surface).__name__ for f in shape.Faces])
            m = VoroHex.mesh(shape)
            self.assertTrue(m.ok, m.message)
            self.assertEqual((m.stats.scheme, m.stats.sub_volumes), ("sweep+multisweep", 2))
            self.assertGreaterEqual(m.stats.min_scaled_jacobian, 0.4)
            self.assertLess(m.stats.volume_rel_error, 0.005)
        finally:
            FreeCAD.closeDocument(doc.Name)

    def test_plane_cuts_tangent_to_a_tube_where_a_lug_is_as_wide(self):
        # A lug as wide as the tube it stands on (its sides tangent to the tube): cut along
        # the tube's cylinder, its pieces have knife edges; with tangent_planes the cut is the
        # plane across the tube's top, and both pieces have a scheme.
        V = FreeCAD.Vector
        x = V(1, 0, 0)
        solid = (Part.makeCylinder(35, 80, V(-40, 0, 0), x)
                 .fuse(Part.makeBox(60, 70, 60, V(-30, -35, 0)))
                 .cut(Part.makeCylinder(17.5, 80, V(-40, 0, 0), x))
                 .cut(Part.makeCylinder(10, 70, V(0, -35, 47), V(0, 1, 0)))
                 .removeSplitter())
        d = VoroHex.decompose(solid, method="plane-cuts")
        self.assertTrue(d.knife_edges)
        self.assertIn("cylinder", [c["kind"] for c in d.cut_surfaces])
        t = VoroHex.decompose(solid, method="plane-cuts", tangent_planes=True)
        self.assertTrue(t.ok, t.diagnostics)
        self.assertFalse(t.knife_edges)
        kinds = [c["kind"] for c in t.cut_surfaces]
        self.assertEqual(kinds.count("tangent_plane"), 1, kinds)
        self.assertNotIn("cylinder", kinds)
        self.assertEqual([sv["scheme"] for sv in t.sub_volumes], ["multisweep", "multisweep"])
        self.assertAlmostEqual(sum(s.Volume for s in t.shapes) / solid.Volume, 1, places=6)

    def test_graph_and_decomposition_report_progress_and_can_be_cancelled(self):
        # Both run in a child process: heartbeats reach the callback, False stops it.
        fig6 = figure6_shape()
        beats = []
        d = VoroHex.decompose(fig6,
                              progress=lambda stage, f: beats.append((stage, f)) or True)
        # It ran to the end: walls, corners and protrusions cut apart, then merged into the
        # one sweep the prism is.
        self.assertGreaterEqual(d.counts["sub_volumes_before_merge"], 12)
        self.assertEqual([sv["scheme"] for sv in d.sub_volumes], ["sweep"])
        # The decomposition's own fractions cross from the child process, in order, to the
        # end; between them heartbeats repeat the latest (the run takes about 2.4 s).
        self.assertGreaterEqual(len(beats), 5)
        fractions = [f for s, f in beats if s == "decompose"]
        self.assertEqual(fractions, sorted(fractions))
        self.assertEqual((fractions[0], fractions[-1]), (0.0, 1.0))
        self.assertIn(0.5, fractions)
        t0 = time.time()
        with self.assertRaisesRegex(VoroHex.Cancelled, "cancelled"):
            VoroHex.decompose(fig6, progress=lambda stage, f: False)
        self.assertLess(time.time() - t0, 2.0)  # the whole run takes about 2.4 s here
        graph = VoroHex.voronoi_graph(fig6, progress=lambda stage, f: True)
        self.assertEqual(graph.counts["edges"], 240)

    def test_tapered_brick_meshes(self):
        bottom = Part.makePolygon([FreeCAD.Vector(*p) for p in
                                   [(0, 0, 0), (20, 0, 0), (20, 10, 0), (0, 10, 0), (0, 0, 0)]])
        top = Part.makePolygon([FreeCAD.Vector(*p) for p in
                                [(4, 2, 8), (16, 2, 8), (16, 8, 8), (4, 8, 8), (4, 2, 8)]])
        solid = Part.makeLoft([bottom, top], True)
        r = VoroHex.mesh(solid, size=2)
        self.assertTrue(r.ok, r.message)
        self.assertGreater(r.stats.min_scaled_jacobian, 0)
        self.assertTrue(VoroHex.check(r, solid).valid)

    def test_argument_errors(self):
        with self.assertRaisesRegex(TypeError, "Part.Shape"):
            VoroHex.mesh(42)
        with self.assertRaisesRegex(TypeError, "bogus"):
            VoroHex.mesh(self.box, bogus=1)
        for bad in (0, -1.0, float("nan"), float("inf")):
            with self.assertRaisesRegex(ValueError, "size"):
                VoroHex.mesh(self.box, size=bad)
        with self.assertRaisesRegex(ValueError, "'size': 'big' is not a length"):
            VoroHex.mesh(self.box, size="big")  # a string is a length with its unit ("4 mm")
        with self.assertRaisesRegex(ValueError, "max_hexes"):
            VoroHex.mesh(self.box, max_hexes=0)
        with self.assertRaisesRegex(ValueError, "no solid"):
            VoroHex.mesh(Part.makePolygon([FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(1, 0, 0),
                                           FreeCAD.Vector(1, 1, 0)]))
        with self.assertRaisesRegex(ValueError, "open shell.*Edge"):
            VoroHex.mesh(Part.makeShell(self.box.Faces[:5]))
        with self.assertRaisesRegex(ValueError, "overlap"):
            VoroHex.mesh(Part.makeCompound([self.box, Part.makeSphere(1)]))
        with self.assertRaises(ValueError):
            VoroHex.mesh(Part.Shape())
        with self.assertRaisesRegex(TypeError, "progress"):
            VoroHex.mesh(self.box, progress=3)

    def test_several_solids_are_meshed_as_one_conforming_mesh(self):
        # Two boxes touching at x = 10 (separate shapes, as two Part features would give):
        # glued at the common face, each mapped, one mesh with the face's nodes shared.
        other = Part.makeBox(10, 20, 30, FreeCAD.Vector(10, 0, 0))
        r = VoroHex.mesh(Part.makeCompound([self.box, other]), size=5)
        self.assertTrue(r.ok, [d.message for d in r.errors])
        self.assertEqual(r.stats.sub_volumes, 2)
        self.assertEqual(r.stats.hexes, 2 * 2 * 4 * 6)
        self.assertEqual(r.stats.nodes, 2 * 3 * 5 * 7 - 5 * 7)
        self.assertAlmostEqual(r.stats.cad_volume, 12000, places=6)
        self.assertIn("solids_joined", [d.code for d in r.diagnostics])
        # Per sub-volume: its scheme, hexes and quality; the hexes of each are one range.
        self.assertEqual(r.stats.sub_volume_schemes, ["map", "map"])
        table = r.sub_volume_table()
        self.assertEqual([t["id"] for t in table], [1, 2])
        self.assertEqual([t["hexes"] for t in table], [48, 48])
        self.assertEqual([t["scheme"] for t in table], ["map", "map"])
        self.assertEqual([t["type"] for t in table], ["Ve", "Ve"])  # blocks
        self.assertAlmostEqual(table[0]["min_scaled_jacobian"], 1.0, places=9)
        ids = array.array("i")
        ids.frombytes(r.core_mesh.sub_volume_bytes())
        self.assertEqual(list(ids), [1] * 48 + [2] * 48)
        # The graph and the decomposition take one solid and say so.
        with self.assertRaisesRegex(ValueError, "2 solids"):
            VoroHex.voronoi_graph(Part.makeCompound([self.box, other]))

    def test_graph_and_decomposition_options(self):
        # The Voronoi graph's eps, delta, max_depth and the decomposition's sharp_angle are
        # mesh options too (they shape the cut of a solid no single scheme meshes).
        for bad, word in ((dict(eps=0.5), "eps"), (dict(delta=0.02), "delta"),
                          (dict(max_depth=13), "max_depth"), (dict(sharp_angle=0), "sharp_angle"),
                          (dict(sharp_angle=200), "sharp_angle")):
            with self.assertRaisesRegex(ValueError, word):
                VoroHex.mesh(self.box, **bad)
            with self.assertRaisesRegex(ValueError, word):
                VoroHex.validate_options(**bad)
        with self.assertRaisesRegex(TypeError, "max_depth"):
            VoroHex.mesh(self.box, max_depth="9")
        # Without the multisweep, which meshes the post on its plate as one prismatic solid.
        r = VoroHex.mesh(post_on_plate(), size=0.5, eps=0.02, delta=0.002, max_depth=8,
                         sharp_angle=45, schemes="map,sweep,midpoint")
        self.assertTrue(r.ok, r.message)
        self.assertGreater(r.stats.sub_volumes, 1)
        table = r.sub_volume_table()
        self.assertEqual({t["type"] for t in table} <= {"Vs", "Ve"}, True)
        self.assertEqual(len(table), r.stats.sub_volumes)
        # A sweep of one solid runs between two of its faces: Vs.
        self.assertEqual([t["type"] for t in VoroHex.mesh(Part.makeCylinder(5, 10), size=2)
                          .sub_volume_table()], ["Vs"])

    def test_curved_solids_are_valid_on_the_cad(self):
        # Issue 7's curved solids without HexMe: a cylinder and a plate with two round
        # holes (both swept), at the default size and at a finer one.
        V = FreeCAD.Vector
        plate = Part.makeBox(8, 4, 0.5).cut(Part.makeCylinder(0.8, 1, V(2, 2, -0.2))).cut(
            Part.makeCylinder(0.8, 1, V(6, 2, -0.2))).removeSplitter()
        for shape in (Part.makeCylinder(5, 10), plate):
            for size in (None, shape.BoundBox.DiagonalLength / 40):
                r = VoroHex.mesh(shape, size=size)
                self.assertTrue(r.ok, r.message)
                self.assertEqual(r.stats.scheme, "sweep")
                self.assertGreaterEqual(r.stats.min_scaled_jacobian, 0.2)
                self.assertLessEqual(r.stats.max_boundary_distance,
                                     1e-6 * shape.BoundBox.DiagonalLength)
                self.assertLess(r.stats.volume_rel_error, 1e-2)  # chords of the circles

    def test_too_many_hexes_is_a_diagnostic(self):
        r = VoroHex.mesh(self.box, size=1, max_hexes=100)
        self.assertFalse(r.ok)
        self.assertIn("too_many_hexes", [d.code for d in r.errors])

    def test_progress_callback(self):
        calls = []
        r = VoroHex.mesh(self.box, size=5, progress=lambda s, f: calls.append((s, f)))
        self.assertTrue(r.ok)
        self.assertTrue(calls)
        self.assertTrue(all(0.0 <= f <= 1.0 and isinstance(s, str) for s, f in calls))

        def boom(stage, fraction):
            raise RuntimeError("stop here")

        with self.assertRaisesRegex(RuntimeError, "stop here"):
            VoroHex.mesh(self.box, size=5, progress=boom)

    def test_write_and_check_files(self):
        r = VoroHex.mesh(self.box, size=5)
        with tempfile.TemporaryDirectory() as d:
            for ext in ("vtu", "msh", "inp"):
                path = os.path.join(d, "box." + ext)
                r.write(path)
                self.assertGreater(os.path.getsize(path), 0)
            report = VoroHex.check(os.path.join(d, "box.vtu"), self.box)
            self.assertTrue(report.valid)
            self.assertEqual(report.hexes, 48)
            vols = inp_c3d8_volumes(os.path.join(d, "box.inp"))
            self.assertEqual(len(vols), 48)
            self.assertTrue(all(v > 0 for v in vols))
            with self.assertRaises(FileNotFoundError):
                VoroHex.check(os.path.join(d, "missing.vtu"))
            with self.assertRaises(RuntimeError):
                r.write(os.path.join(d, "box.unknown"))

    def test_smoothing_off_keeps_quality(self):
        cyl = Part.makeCylinder(5, 10)
        r = VoroHex.mesh(cyl, size=1.5, smooth_iterations=0, smooth_passes=0)
        self.assertTrue(r.ok, r.message)
        s = r.stats
        self.assertEqual(s.scheme, "sweep")
        self.assertEqual(s.min_scaled_jacobian_before_smoothing, s.min_scaled_jacobian)
        self.assertEqual(s.mean_scaled_jacobian_before_smoothing, s.mean_scaled_jacobian)
        self.assertGreaterEqual(s.seconds_smoothing, 0.0)
        self.assertAlmostEqual(s.seconds, s.seconds_meshing + s.seconds_smoothing +
                               s.seconds_checking)

    def test_smoothing_never_lowers_minimum(self):
        cyl = Part.makeCylinder(5, 10)
        off = VoroHex.mesh(cyl, size=1.5, smooth_iterations=0, smooth_passes=0)
        on = VoroHex.mesh(cyl, size=1.5)
        self.assertTrue(on.ok, on.message)
        s = on.stats
        self.assertEqual((on.hex_count, on.node_count), (off.hex_count, off.node_count))
        # The mesh before smoothing is the unsmoothed mesh of the run with smoothing off.
        self.assertAlmostEqual(s.min_scaled_jacobian_before_smoothing,
                               off.stats.min_scaled_jacobian, places=12)
        self.assertAlmostEqual(s.mean_scaled_jacobian_before_smoothing,
                               off.stats.mean_scaled_jacobian, places=12)
        self.assertGreaterEqual(s.min_scaled_jacobian,
                                s.min_scaled_jacobian_before_smoothing - 1e-12)
        self.assertGreater(s.seconds_smoothing, 0.0)
        self.assertTrue(VoroHex.check(on, cyl).valid)
        # The options reach the core: smoothing moved nodes, Laplacian-only too.
        moved = max(abs(a - b) for p, q in zip(on.nodes, off.nodes) for a, b in zip(p, q))
        self.assertGreater(moved, 1e-6)
        lap = VoroHex.mesh(cyl, size=1.5, smooth_iterations=3, smooth_passes=0,
                           smooth_quality_target=0.9)
        self.assertTrue(lap.ok, lap.message)
        self.assertGreaterEqual(lap.stats.min_scaled_jacobian,
                                lap.stats.min_scaled_jacobian_before_smoothing - 1e-12)

    def test_smoothing_option_errors(self):
        for name, bad in (("smooth_iterations", -1), ("smooth_passes", -2),
                          ("smooth_iterations", 1.5), ("smooth_passes", float("nan")),
                          ("smooth_quality_target", 0), ("smooth_quality_target", -0.5),
                          ("smooth_quality_target", 1.5),
                          ("smooth_quality_target", float("nan"))):
            with self.assertRaisesRegex(ValueError, name, msg="{}={}".format(name, bad)):
                VoroHex.mesh(self.box, size=5, **{name: bad})
        with self.assertRaisesRegex(TypeError, "smooth_iterations"):
            VoroHex.mesh(self.box, size=5, smooth_iterations="many")
        names = [o.name for o in VoroHex.OPTIONS]
        for name in ("smooth_iterations", "smooth_passes", "smooth_quality_target"):
            self.assertIn(name, names)
        defaults = {o.name: o.default for o in VoroHex.OPTIONS}
        self.assertEqual((defaults["smooth_iterations"], defaults["smooth_passes"]), (20, 10))
        self.assertEqual(defaults["smooth_quality_target"], 0.5)

    def test_l_shape_is_swept(self):
        pts = [(0, 0, 0), (20, 0, 0), (20, 6, 0), (6, 6, 0), (6, 16, 0), (0, 16, 0), (0, 0, 0)]
        face = Part.Face(Part.makePolygon([FreeCAD.Vector(*p) for p in pts]))
        solid = face.extrude(FreeCAD.Vector(0, 0, 5))
        r = VoroHex.mesh(solid, size=1.5)
        self.assertTrue(r.ok, r.message)
        self.assertEqual(r.stats.scheme, "sweep")
        report = VoroHex.check(r, solid)
        self.assertTrue(report.valid, [str(d) for d in report.diagnostics])
        self.assertEqual(report.non_positive, 0)
        nodes = r.nodes
        vols = [hex_volume([tuple(nodes[i]) for i in h]) for h in r.hexes]
        self.assertTrue(all(v > 0 for v in vols), min(vols))
        self.assertTrue(all(v > 0 for v in r.core_mesh.hex_volumes()))
        self.assertTrue(math.isclose(sum(vols), solid.Volume, rel_tol=1e-6))
        self.assertTrue(all(v > 0 for v in femmesh_hex_volumes(r.to_femmesh())))

    def test_machined_parts_use_multisweep_and_revolve(self):
        V = FreeCAD.Vector
        # A flanged pipe with bolt holes: prismatic along its axis (multisweep).
        pipe = Part.makeCylinder(40, 8).fuse(Part.makeCylinder(22, 60))
        pipe = pipe.cut(Part.makeCylinder(16, 80, V(0, 0, -10)))
        for k in range(6):
            a = 2 * math.pi * k / 6
            pipe = pipe.cut(Part.makeCylinder(3.5, 30, V(31 * math.cos(a), 31 * math.sin(a), -5)))
        pipe = pipe.removeSplitter()
        # A pulley with a V-groove (cones) and a bore: of revolution (revolve).
        rz = [(8, 0), (20, 0), (20, 6), (32, 6), (32, 0), (40, 0), (40, 4), (32, 10), (40, 16),
              (40, 20), (32, 20), (32, 14), (20, 14), (20, 20), (8, 20)]
        profile = Part.Face(Part.makePolygon([V(r, 0, z) for r, z in rz + rz[:1]]))
        pulley = Part.Solid(profile.revolve(V(0, 0, 0), V(0, 0, 1), 360))
        for solid, scheme in ((pipe, "multisweep"), (pulley, "revolve")):
            r = VoroHex.mesh(solid, fallback=False, decompose=False)
            self.assertTrue(r.ok, r.message)
            self.assertEqual(r.stats.scheme, scheme)
            self.assertGreaterEqual(r.stats.min_scaled_jacobian, 0.3)
            self.assertTrue(VoroHex.check(r, solid).valid)
        # The schemes option: without the revolve the pulley is refused (no fallback).
        r = VoroHex.mesh(pulley, schemes="map,sweep,multisweep", fallback=False, decompose=False)
        self.assertFalse(r.ok)
        self.assertIn("Not prismatic", r.message)
        r = VoroHex.mesh(pulley, schemes=["revolve"], fallback=False, decompose=False)
        self.assertEqual(r.stats.scheme, "revolve")
        with self.assertRaises(ValueError):
            VoroHex.mesh(pulley, schemes="map,loft")
        with self.assertRaises(TypeError):
            VoroHex.mesh(pulley, schemes=5)

    def test_the_same_part_built_five_ways_gets_the_same_scheme(self):
        # A plate with a boss and two holes: Part API booleans, Part workbench objects (Cut
        # of a MultiFuse, with Refine), a STEP round trip, the plate from a reversed wire,
        # and PartDesign (a Pad of a sketch with two circles, a Pad of a circle sketched on
        # its top face).
        V = FreeCAD.Vector
        doc = FreeCAD.newDocument("VoroHexFourWays")
        try:
            plate = Part.makeBox(60, 40, 8)
            boss = Part.makeCylinder(8, 12, V(30, 20, 8))
            holes = [Part.makeCylinder(3, 40, V(10, 10, -5)), Part.makeCylinder(3, 40, V(50, 30, -5))]
            api = plate.fuse(boss).cut(holes[0]).cut(holes[1]).removeSplitter()
            objs = []
            for name, shape in (("Plate", plate), ("Boss", boss), ("H1", holes[0]), ("H2", holes[1])):
                o = doc.addObject("Part::Feature", name)
                o.Shape = shape
                objs.append(o)
            fused = doc.addObject("Part::MultiFuse", "Fusion")
            fused.Shapes = objs[:2]
            fused.Refine = True
            tools = doc.addObject("Part::MultiFuse", "Holes")
            tools.Shapes = objs[2:]
            cut = doc.addObject("Part::Cut", "Cut")
            cut.Base, cut.Tool = fused, tools
            cut.Refine = True
            doc.recompute()
            workbench = cut.Shape
            path = os.path.join(tempfile.mkdtemp(), "plate.step")
            api.exportStep(path)
            step = Part.read(path)
            pts = [V(0, 0, 0), V(0, 40, 0), V(60, 40, 0), V(60, 0, 0), V(0, 0, 0)]  # clockwise
            reversed_plate = Part.Face(Part.makePolygon(pts)).extrude(V(0, 0, 8))
            reversed_part = reversed_plate.fuse(boss).cut(holes[0]).cut(holes[1]).removeSplitter()
            part_design = self._part_design_plate_with_boss(doc)
            results = []
            for name, solid in (("API", api), ("workbench", workbench), ("STEP", step),
                                ("reversed wire", reversed_part), ("PartDesign", part_design)):
                self.assertAlmostEqual(solid.Volume, api.Volume, delta=1e-6 * api.Volume)
                r = VoroHex.mesh(solid, size=4, fallback=False, decompose=False)
                self.assertTrue(r.ok, name + ": " + r.message)
                results.append((name, r.stats.scheme, r.stats.hexes))
            self.assertEqual({s for _, s, _ in results}, {"multisweep"}, results)
            self.assertEqual(len({h for _, _, h in results}), 1, results)
        finally:
            FreeCAD.closeDocument(doc.Name)

    @staticmethod
    def _part_design_plate_with_boss(doc):
        import Sketcher
        V = FreeCAD.Vector
        body = doc.addObject("PartDesign::Body", "Body")
        base = body.newObject("Sketcher::SketchObject", "PlateSketch")
        base.Support = (doc.getObject("XY_Plane"), [""])
        base.MapMode = "FlatFace"
        corners = [V(0, 0, 0), V(60, 0, 0), V(60, 40, 0), V(0, 40, 0)]
        for i in range(4):
            base.addGeometry(Part.LineSegment(corners[i], corners[(i + 1) % 4]))
        for i in range(4):
            base.addConstraint(Sketcher.Constraint("Coincident", i, 2, (i + 1) % 4, 1))
        base.addGeometry(Part.Circle(V(10, 10, 0), V(0, 0, 1), 3))
        base.addGeometry(Part.Circle(V(50, 30, 0), V(0, 0, 1), 3))
        pad = body.newObject("PartDesign::Pad", "Pad")
        pad.Profile, pad.Length = base, 8
        doc.recompute()
        top = next(i + 1 for i, f in enumerate(pad.Shape.Faces)
                   if abs(f.CenterOfMass.z - 8) < 1e-9 and f.normalAt(0, 0).z > 0.5)
        sketch = body.newObject("Sketcher::SketchObject", "BossSketch")
        sketch.Support = (pad, ["Face{}".format(top)])
        sketch.MapMode = "FlatFace"
        sketch.addGeometry(Part.Circle(V(30, 20, 0), V(0, 0, 1), 8))
        boss = body.newObject("PartDesign::Pad", "BossPad")
        boss.Profile, boss.Length = sketch, 12
        doc.recompute()
        return body.Shape

    def test_voronoi_graph_box(self):
        box = Part.makeBox(3, 2, 1)
        by_area = sorted(range(len(box.Faces)), key=lambda i: box.Faces[i].Area)
        largest = sorted("Face{}".format(i + 1) for i in by_area[-2:])
        self.assertGreater(box.Faces[by_area[-2]].Area, box.Faces[by_area[-3]].Area)
        g = VoroHex.voronoi_graph(box)
        self.assertTrue(g.ok, g.diagnostics)
        self.assertEqual(g.counts["f_s"], 1)
        fs = g.fs_faces()
        self.assertEqual(len(fs), 1)
        self.assertEqual(sorted(fs[0]["governors"]), largest)
        self.assertEqual(fs[0]["kind"], "face")
        self.assertEqual(len(g.find(largest)), 1)
        # f_s lies midway between the two largest faces (z = 0 and z = 1).
        self.assertAlmostEqual(fs[0]["point"][2], 0.5, places=3)
        self.assertEqual(g.counts["faces"], len(g.of_kind("face")))
        self.assertEqual(g.counts["edges"], len(g.of_kind("edge")))
        self.assertEqual(g.counts["vertices"], len(g.of_kind("vertex")))
        for e in g.of_kind("edge"):
            self.assertGreaterEqual(len(e["polyline"]), 2)
            self.assertEqual(len(e["polyline"][0]), 3)
        for e in g.elements:
            self.assertTrue(all(re.match(r"(Face|Edge|Vertex)\d+$", n) for n in e["governors"]))
            self.assertTrue(all(0 <= i < len(g.elements) for i in e["incident"]))

    def test_voronoi_graph_cube_centre(self):
        g = VoroHex.voronoi_graph(Part.makeBox(2, 2, 2), eps=0.01)
        centre = [e for e in g.of_kind("vertex") if len(e["governors"]) == 6]
        self.assertEqual(len(centre), 1, g.of_kind("vertex"))
        self.assertEqual(sorted(centre[0]["governors"]),
                         sorted("Face{}".format(i) for i in range(1, 7)))
        for c in centre[0]["point"]:
            self.assertAlmostEqual(c, 1.0, places=2)
        # Opposite faces of a cube meet only at its centre: no f_s face.
        self.assertEqual(g.counts["f_s"], 0)

    def test_voronoi_graph_errors(self):
        for kwargs, name in (({"eps": -1}, "eps"), ({"eps": float("nan")}, "eps"),
                             ({"delta": 0}, "delta"), ({"eps": 0.01, "delta": 0.1}, "delta"),
                             ({"max_depth": 13}, "max_depth"), ({"max_depth": 2.5}, "max_depth"),
                             ({"linear_tolerance": 0.7}, "linear_tolerance")):
            with self.assertRaisesRegex(ValueError, name, msg=repr(kwargs)):
                VoroHex.voronoi_graph(self.box, **kwargs)
        with self.assertRaises(VoroHex.ShapeError):
            VoroHex.voronoi_graph(Part.makeShell(self.box.Faces[:5]))

    def test_check_detects_inverted_hex(self):
        pts = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
        good = VoroHex.check((pts, [list(range(8))]))
        self.assertTrue(good.valid)
        bad = VoroHex.check((pts, [[4, 5, 6, 7, 0, 1, 2, 3]]))
        self.assertFalse(bad.valid)
        self.assertEqual(bad.non_positive, 1)


class BoxDocument:
    """A mixin for document-object tests: a new document with a 10 x 20 x 30 Part::Box
    (`doc_name` names the document), closed afterwards; make_mesh() adds its hex mesh."""

    doc_name = "VoroHexTest"

    def setUp(self):
        self.doc = FreeCAD.newDocument(self.doc_name)
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 10, 20, 30
        self.doc.recompute()

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def make_mesh(self, size=5):
        obj = VoroHexObjects.makeHexMesh(self.doc, self.box, size=size)
        self.doc.recompute()
        return obj

    def steel_analysis(self):
        """A static FEM analysis with FreeCAD's CalculiX solver and a steel material:
        (analysis, solver); the constraints and the mesh are the caller's."""
        import ObjectsFem

        analysis = ObjectsFem.makeAnalysis(self.doc, "Analysis")
        solver = ObjectsFem.makeSolverCalculixCcxTools(self.doc, "CalculiXccxTools")
        solver.AnalysisType = "static"
        analysis.addObject(solver)
        material = ObjectsFem.makeMaterialSolid(self.doc, "Steel")
        mat = material.Material
        mat.update({"Name": "Steel", "YoungsModulus": "210000 MPa",
                    "PoissonRatio": "0.30", "Density": "7900 kg/m^3"})
        material.Material = mat
        analysis.addObject(material)
        return analysis, solver

    def ccx_deck(self, analysis, solver, folder):
        """The .inp FreeCAD's CalculiX tools write for `analysis` into `folder` (test mode:
        not solved), after their prerequisites check passed: its path."""
        from femtools import ccxtools

        fea = ccxtools.FemToolsCcx(analysis, solver, test_mode=True)
        fea.update_objects()
        fea.setup_working_dir(folder)
        self.assertFalse(fea.check_prerequisites())
        self.assertFalse(fea.write_inp_file())
        return fea.inp_file_name


def snapshot(doc):
    """Objects and their (non-geometry) property values, to prove a document unchanged."""
    out = []
    for o in doc.Objects:
        props = {}
        for p in o.PropertiesList:
            if p in ("Shape", "Mesh", "FemMesh", "Proxy"):
                continue
            props[p] = repr(o.getPropertyByName(p))
        out.append((o.Name, o.TypeId, props))
    return out


def post_on_plate():
    """A 4 x 4 x 1 plate with a 1 x 1 x 3 post standing on its middle (no single scheme
    meshes it; it is cut into sub-volumes)."""
    return Part.makeBox(4, 4, 1).fuse(
        Part.makeBox(1, 1, 3, FreeCAD.Vector(1.5, 1.5, 1))).removeSplitter()


def figure6_shape():
    """The Figure 6 part of tests/cpp/fixtures/solids.h (a hexagonal ring, six triangular
    protrusions)."""
    V = FreeCAD.Vector
    outer, inner = [], []
    apothem = 5 * math.cos(math.pi / 6)
    for k in range(6):
        a0, am = math.pi / 3 * k, math.pi / 3 * (k + 0.5)
        cx, cy = apothem * math.cos(am), apothem * math.sin(am)
        tx, ty = -math.sin(am), math.cos(am)
        outer += [V(5 * math.cos(a0), 5 * math.sin(a0), 0), V(cx - 0.75 * tx, cy - 0.75 * ty, 0),
                  V((apothem + 1.5) * math.cos(am), (apothem + 1.5) * math.sin(am), 0),
                  V(cx + 0.75 * tx, cy + 0.75 * ty, 0)]
        inner.append(V(4 * math.cos(a0), 4 * math.sin(a0), 0))
    # The hole is cut out (Part.Face of both wires leaves the inner one wrongly oriented: an
    # invalid solid of the wrong volume, which VoroHex had to repair before meshing).
    ring = Part.Face(Part.makePolygon(outer + outer[:1])).cut(
        Part.Face(Part.makePolygon(inner + inner[:1])))
    return ring.Faces[0].extrude(V(0, 0, 3))
