# FreeCAD unit tests of VoroHex's document objects and what the views draw (run:
# freecadcmd -t TestVoroHexDocument -M <Mod/VoroHex>). Registered through
# FreeCAD.__unit_test__ in Init.py; the API's tests are in TestVoroHex.py.
import math
import os
import tempfile
import unittest

import FreeCAD
import Part

import VoroHex
import VoroHexGraph
import VoroHexObjects
import VoroHexParts
from TestVoroHex import BoxDocument, femmesh_hex_volumes, figure6_shape, inp_c3d8_volumes, snapshot


def edges_at_height(shape, z):
    """The numbers (1-based, as Part's Fillet and Chamfer take them) of the shape's edges
    lying at height z: a box's top edges."""
    return [i + 1 for i, e in enumerate(shape.Edges)
            if abs(e.BoundBox.ZMin - z) < 1e-9 and abs(e.BoundBox.ZMax - z) < 1e-9]


class TestVoroHexObject(BoxDocument, unittest.TestCase):

    def make_l(self):
        """An L-shaped extrusion (4 x 3, legs 1 thick, 3 deep) as a document object."""
        pts = [(0, 0, 0), (4, 0, 0), (4, 1, 0), (1, 1, 0), (1, 3, 0), (0, 3, 0), (0, 0, 0)]
        l_shape = self.doc.addObject("Part::Feature", "L")
        l_shape.Shape = Part.Face(Part.makePolygon([FreeCAD.Vector(*p) for p in pts])).extrude(
            FreeCAD.Vector(0, 0, 3))
        self.doc.recompute()
        return l_shape

    def reopened(self, path, name):
        """The document saved to `path`, closed and opened again; its object `name`."""
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        return self.doc.getObject(name)

    def test_cancelled_graph_or_decomposition_leaves_the_document_as_it_was(self):
        part = self.doc.addObject("Part::Feature", "Figure6")
        part.Shape = figure6_shape()
        self.doc.recompute()
        names = sorted(o.Name for o in self.doc.Objects)
        with self.assertRaisesRegex(VoroHex.Cancelled, "decomposition was cancelled"):
            VoroHexParts.makeDecomposition(self.doc, part, progress=lambda stage, f: False,
                                           method="voronoi")
        self.assertEqual(sorted(o.Name for o in self.doc.Objects), names)
        # Not cancelled, the same call makes the object. (The graph of this part takes 0.1 s,
        # less than the first progress call: it cannot be cancelled in time to test it.)
        obj = VoroHexParts.makeDecomposition(self.doc, part, progress=lambda stage, f: True,
                                             method="voronoi")
        self.assertEqual((obj.Status, obj.SubVolumeCount), ("ok", 1))

    def test_graph_and_decomposition_merge_faces_split_on_one_surface(self):
        # An L fused from two boxes without Refine (FreeCAD 0.20's default for Part
        # booleans) keeps faces split where the boxes met. The graph and the Voronoi graph's
        # decomposition merge them first, as Part > Refine shape does: the same graph and
        # sub-volumes as the refined L's, and their message says so. (On the split faces the
        # API's graph has a degenerate edge where the boxes met.) As the mesher, the
        # decomposition takes them as they are, as the mesher does.
        fused = Part.makeBox(40, 10, 10).fuse(Part.makeBox(10, 10, 40))
        refined = fused.removeSplitter()
        extra = len(fused.Faces) - len(refined.Faces)
        self.assertEqual(extra, 6)
        self.assertIn("degenerate", VoroHex.voronoi_graph(fused).type_counts())
        self.assertNotIn("degenerate", VoroHex.voronoi_graph(refined).type_counts())
        objects = {}
        for name, shape in (("Unrefined", fused), ("Refined", refined)):
            part = self.doc.addObject("Part::Feature", name)
            part.Shape = shape
            self.doc.recompute()
            objects[name] = (VoroHexGraph.makeVoronoiGraph(self.doc, part),
                             VoroHexParts.makeDecomposition(self.doc, part, method="voronoi"))
        (g, d), (g_ref, d_ref) = objects["Unrefined"], objects["Refined"]
        self.assertEqual(dict(g.EdgeTypeCounts), dict(g_ref.EdgeTypeCounts))
        self.assertNotIn("degenerate", dict(g.EdgeTypeCounts))
        self.assertEqual((list(d.Schemes), d.SubVolumeCount),
                         (list(d_ref.Schemes), d_ref.SubVolumeCount))
        note = "Computed with {} faces merged into a neighbour on the same surface".format(extra)
        for obj in (g, d):
            self.assertEqual(obj.Status, "ok", obj.Message)
            self.assertIn(note, obj.Message)
        for obj in (g_ref, d_ref):
            self.assertNotIn("merged", obj.Message)
        mesher = VoroHexParts.makeDecomposition(self.doc, self.doc.getObject("Unrefined"))
        self.assertNotIn("merged", mesher.Message)
        self.assertEqual((mesher.MethodUsed, mesher.SubVolumeCount),
                         ("Not cut (the mesher meshes it whole)", 1), mesher.Message)
        self.assertEqual(len(mesher.SubVolumeObjects[0].Shape.Faces), len(fused.Faces))

    def test_voronoi_graph_object(self):
        l_shape = self.make_l()
        g = VoroHexGraph.makeVoronoiGraph(self.doc, l_shape)
        self.assertTrue(g.isValid(), g.getStatusString())
        self.assertEqual(g.Status, "ok")
        graph = VoroHex.voronoi_graph(l_shape)
        expected = graph.type_counts()
        self.assertEqual({t: int(n) for t, n in g.EdgeTypeCounts.items()}, expected)
        # Every edge with a polyline is drawn, grouped by type; the segments carry their type.
        drawn = {}
        for e in graph.of_kind("edge"):
            if len(set(e["polyline"])) >= 2:
                drawn[e["type"]] = drawn.get(e["type"], 0) + 1
        self.assertEqual({t: int(n) for t, n in g.ShownEdgeCounts.items()}, drawn)
        self.assertEqual(len(g.SegmentTypes), len(g.Shape.Edges))
        self.assertEqual(len(g.Shape.Vertexes) >= g.VertexCount, True)
        self.assertEqual(g.EdgeCount, graph.counts["edges"])
        # Hiding a type removes exactly its segments.
        hidden = "[C]"
        self.assertIn(hidden, expected)
        g.ShownTypes = [t for t in VoroHexGraph.TYPE_NAMES if t != hidden]
        self.doc.recompute()
        self.assertNotIn(hidden, g.SegmentTypes)
        self.assertNotIn(hidden, g.ShownEdgeCounts)
        self.assertEqual(len(g.SegmentTypes), len(g.Shape.Edges))
        # The f_s faces are drawn as triangles (FsFacePoints, FsFaceTriangles: the view draws
        # them translucent), not as faces of the Shape (whose edges and vertices would be
        # outlines and point markers); ShowFsFaces off leaves the lines only.
        self.assertGreater(g.FsFaceCount, 0)
        self.assertEqual((g.FsFacesDrawn, list(g.FsFacesNotDrawn), len(g.Shape.Faces)),
                         (g.FsFaceCount, [], 0))
        tris = list(g.FsFaceTriangles)
        self.assertTrue(tris and len(tris) % 3 == 0 and max(tris) < len(g.FsFacePoints))
        self.assertNotIn("f_s", g.SegmentTypes)
        g.ShowFsFaces = False
        self.doc.recompute()
        self.assertEqual((g.FsFacesDrawn, len(g.FsFaceTriangles)), (0, 0))
        self.assertEqual(len(g.SegmentTypes), len(g.Shape.Edges))
        # The graph's own options, set at creation; a bad one is refused before anything is
        # added to the document.
        fine = VoroHexGraph.makeVoronoiGraph(self.doc, l_shape, eps=0.02, delta=0.002,
                                             sharp_angle=45)
        self.assertEqual((fine.Eps, fine.Delta, fine.MaxDepth, fine.SharpAngle),
                         (0.02, 0.002, 9, 45))
        self.assertEqual(fine.EdgeCount, VoroHex.voronoi_graph(l_shape, eps=0.02, delta=0.002)
                         .counts["edges"])
        names = [o.Name for o in self.doc.Objects]
        with self.assertRaisesRegex(ValueError, "eps"):
            VoroHexGraph.makeVoronoiGraph(self.doc, l_shape, eps=0.5)
        with self.assertRaisesRegex(ValueError, "max_depth"):
            VoroHexParts.makeDecomposition(self.doc, l_shape, max_depth=20)
        self.assertEqual([o.Name for o in self.doc.Objects], names)
        fine.Eps = 0.3  # edited later: the recompute fails with the reason
        self.doc.recompute()
        self.assertEqual(fine.Status, "error")
        self.assertIn("eps", fine.Message)
        # Saved and reopened, the object keeps its properties.
        with tempfile.TemporaryDirectory() as tmp:
            g2 = self.reopened(os.path.join(tmp, "graph.FCStd"), g.Name)
            self.assertEqual(list(g2.ShownTypes), [t for t in VoroHexGraph.TYPE_NAMES
                                                   if t != hidden])
            self.assertEqual(dict(g2.EdgeTypeCounts), {t: str(n) for t, n in expected.items()})
        with self.assertRaisesRegex(ValueError, "FEM mesh|not a solid|No geometry"):
            VoroHexGraph.makeVoronoiGraph(self.doc, None)

    def test_decomposition_object(self):
        l_shape = self.make_l()
        d = VoroHexParts.makeDecomposition(self.doc, l_shape, merge=False, method="voronoi")
        self.assertTrue(d.isValid(), d.getStatusString())
        self.assertEqual((d.Method, d.MethodUsed), ("Voronoi graph", "Cut along its Voronoi graph"))
        self.assertEqual(d.SubVolumeCount, 3)
        self.assertEqual(len(d.Shape.Solids), 3)
        self.assertAlmostEqual(sum(s.Volume for s in d.Shape.Solids), 18.0, places=6)
        self.assertEqual(sorted(d.Types), ["Ve", "Vs", "Vs"])
        self.assertEqual(len(d.FaceRoles), len(d.Shape.Faces))
        # A second decomposition of the part: its sub-volumes are named after it, so no
        # label repeats (FreeCAD would number them "...001").
        d2 = VoroHexParts.makeDecomposition(self.doc, l_shape, merge=False, method="voronoi")
        labels = [c.Label for c in list(d.SubVolumeObjects) + list(d2.SubVolumeObjects)]
        self.assertEqual(len(set(labels)), 6, labels)
        for parent in (d, d2):
            for c in parent.SubVolumeObjects:
                self.assertTrue(c.Label.startswith(parent.Label + " sub-volume "), c.Label)
        VoroHexParts.remove(d2)
        # The two cuts are faces of two sub-volumes each.
        self.assertEqual(d.DecompositionFaceCount, 2)
        self.assertEqual(list(d.FaceRoles).count("decomposition"), 4)
        d.Merge = True
        self.doc.recompute()
        self.assertEqual((d.SubVolumeCount, d.SubVolumesBeforeMerge), (1, 3))
        self.assertEqual(list(d.Schemes), ["sweep"])
        self.assertEqual(list(d.FaceRoles).count("source/target"), 2)
        self.assertNotIn("decomposition", d.FaceRoles)
        # Its time limit: too short, the recompute fails saying so and keeps the last result.
        self.assertEqual(d.TimeLimit, 30.0)
        d.TimeLimit = 0.001
        self.doc.recompute()
        self.assertEqual(d.Status, "error")
        self.assertIn("time limit", d.Message)
        self.assertEqual((d.SubVolumeCount, len(d.Shape.Solids)), (1, 1))
        d.TimeLimit = 30
        self.doc.recompute()
        self.assertEqual((d.Status, d.SubVolumeCount), ("ok", 1))
        names = [o.Name for o in self.doc.Objects]
        for bad in (0, -5):
            with self.assertRaisesRegex(ValueError, "time_limit"):
                VoroHexParts.makeDecomposition(self.doc, l_shape, time_limit=bad)
        self.assertEqual([o.Name for o in self.doc.Objects], names)

    def test_decomposition_object_with_multisweeps_and_revolves(self):
        # The meshers judge the sub-volumes: a stepped plate with two holes is one multisweep,
        # a ring of triangular section one revolve, both drawn in the sweep's colour; the
        # ring's cones are its own faces (no decomposition face). Why a decomposition is
        # partial is in its message.
        V = FreeCAD.Vector
        plate = Part.makeBox(80, 50, 6).fuse(Part.makeBox(40, 50, 6, V(40, 0, 6)))
        for x in (20, 60):
            plate = plate.cut(Part.makeCylinder(5, 30, V(x, 25, -5)))
        ring = Part.Face(Part.makePolygon([V(6, 0, 0), V(10, 0, 0), V(8, 0, 3), V(6, 0, 0)]))
        ring = Part.makeSolid(Part.makeShell(ring.revolve(V(0, 0, 0), V(0, 0, 1), 360).Faces))
        for shape, scheme in ((plate.removeSplitter(), "multisweep"), (ring, "revolve")):
            part = self.doc.addObject("Part::Feature", scheme)
            part.Shape = shape
            # As the mesher (the default): one scheme takes the solid whole, it is not cut.
            whole = VoroHexParts.makeDecomposition(self.doc, part)
            self.assertEqual((whole.Method, whole.Status), ("As the mesher", "ok"))
            self.assertEqual(list(whole.Schemes), [scheme], whole.Message)
            self.assertEqual(set(whole.FaceRoles), {"sweep"}, whole.Message)
            self.assertTrue(whole.Message.startswith(
                "Not cut (the mesher meshes it whole): 1 sub-volume (1 " + scheme + ")"),
                whole.Message)
            self.assertAlmostEqual(whole.Shape.Volume, shape.Volume, places=6)
            d = VoroHexParts.makeDecomposition(self.doc, part, method="voronoi")
            self.assertTrue(d.isValid(), d.getStatusString())
            self.assertEqual(list(d.Schemes), [scheme], d.Message)
            self.assertEqual(set(d.FaceRoles), {"sweep"}, d.Message)
            how = ("Not cut (its Voronoi graph gives one sub-volume)"
                   if d.SubVolumesBeforeMerge == 1 else "Cut along its Voronoi graph")
            self.assertTrue(d.Message.startswith(how + ": 1 sub-volume (1 " + scheme + ")"),
                            d.Message)
            self.assertIn(d.Status, ("ok", "partial"))
            self.assertEqual("Partial: " in d.Message, d.Status == "partial", d.Message)
            if scheme == "revolve":
                self.assertEqual((d.Status, d.DecompositionFaceCount), ("ok", 0), d.Message)

    def test_decomposition_judged_by_the_mesh_schemes(self):
        # A stepped plate with two holes is one multisweep; with the schemes a hex mesh may
        # use without multisweep (its Schemes, which the Preview passes), the decomposition
        # shows what that mesh does instead: cut at its step into two sweeps.
        V = FreeCAD.Vector
        plate = Part.makeBox(80, 50, 6).fuse(Part.makeBox(40, 50, 6, V(40, 0, 6)))
        for x in (20, 60):
            plate = plate.cut(Part.makeCylinder(5, 30, V(x, 25, -5)))
        part = self.doc.addObject("Part::Feature", "Plate")
        part.Shape = plate.removeSplitter()
        self.doc.recompute()
        whole = VoroHexParts.makeDecomposition(self.doc, part)
        self.assertEqual(whole.AllowedSchemes, VoroHexParts.ALL_SCHEMES)
        self.assertEqual(list(whole.Schemes), ["multisweep"], whole.Message)
        no_multisweep = "map,sweep,revolve,midpoint"
        d = VoroHexParts.makeDecomposition(self.doc, part, schemes=no_multisweep)
        self.assertEqual((d.Status, d.AllowedSchemes), ("ok", no_multisweep), d.Message)
        self.assertNotIn("multisweep", list(d.Schemes), d.Message)
        mesh = VoroHex.mesh(part.Shape, schemes=no_multisweep, size=4)
        self.assertTrue(mesh.ok, mesh.message)
        self.assertEqual(sorted(d.Schemes), sorted(mesh.stats.sub_volume_schemes), d.Message)
        # Edited back to every scheme, the recompute takes the plate whole again.
        d.AllowedSchemes = ""
        self.doc.recompute()
        self.assertEqual(list(d.Schemes), ["multisweep"], d.Message)
        # The Preview's work, in its child: the same with the mesh's schemes.
        _, data = VoroHexObjects.preview_work(None, part.Shape.exportBrepToString(), 60.0, {},
                                              no_multisweep)
        self.assertEqual(sorted(v["scheme"] for v in data["decomposition"].sub_volumes),
                         sorted(mesh.stats.sub_volume_schemes))
        names = [o.Name for o in self.doc.Objects]
        with self.assertRaisesRegex(ValueError, "unknown scheme 'swep'"):
            VoroHexParts.makeDecomposition(self.doc, part, schemes="map,swep")
        self.assertEqual([o.Name for o in self.doc.Objects], names)

    def test_recompute_counts_validity(self):
        obj = self.make_mesh()
        self.assertEqual(obj.Proxy.Type, "Fem::VoroHexMesh")
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.Status, "ok")
        # New meshes are quadratic (ElementOrder "2nd"): the 3 x 5 x 7 corners and one node
        # on each mesh edge (2 x 5 x 7 along x, 3 x 4 x 7 along y, 3 x 5 x 6 along z).
        self.assertEqual(obj.ElementOrder, "2nd")
        self.assertEqual((obj.HexCount, obj.NodeCount), (48, 105 + 70 + 84 + 90))
        self.assertEqual((obj.FemMesh.VolumeCount, obj.FemMesh.NodeCount), (48, 349))
        self.assertEqual(obj.SubVolumeCount, 1)
        self.assertEqual((list(obj.SubVolumeSchemes), list(obj.SubVolumeHexCounts)), (["map"], [48]))
        self.assertAlmostEqual(obj.SubVolumeMinScaledJacobian[0], 1.0, places=9)
        self.assertEqual(len(obj.Diagnostics), len(obj.DiagnosticEntities))
        self.assertAlmostEqual(obj.MinScaledJacobian, 1.0, places=9)
        self.assertEqual(sum(obj.ScaledJacobianHistogram), 48)
        self.assertTrue(VoroHex.check(obj.FemMesh, self.box.Shape).valid)
        self.assertTrue(all(v > 0 for v in femmesh_hex_volumes(obj.FemMesh)))
        self.assertEqual(obj.TargetSize.Value, 5)

    def test_smaller_size_more_hexes(self):
        obj = self.make_mesh(size=10)
        coarse = obj.HexCount
        obj.TargetSize = 2.5
        self.doc.recompute()
        self.assertTrue(obj.isValid())
        self.assertGreater(obj.HexCount, coarse)
        self.assertEqual(obj.HexCount, 4 * 8 * 12)

    def test_part_change_triggers_remesh(self):
        obj = self.make_mesh(size=10)
        self.box.Length = 20
        self.doc.recompute()
        self.assertTrue(obj.isValid())
        self.assertEqual(obj.HexCount, 2 * 2 * 3)

    def test_error_keeps_previous_mesh(self):
        obj = self.make_mesh(size=10)
        before = obj.FemMesh.VolumeCount
        sphere = self.doc.addObject("Part::Sphere", "Sphere")
        obj.Part = sphere
        obj.Fallback = False  # the sphere is refused instead of meshed by the fallback
        self.doc.recompute()
        self.assertFalse(obj.isValid())
        self.assertEqual(obj.Status, "error")
        self.assertIn("not supported yet", obj.Message)
        self.assertIn("not supported yet", obj.getStatusString())
        self.assertEqual(obj.FemMesh.VolumeCount, before)
        self.assertEqual(obj.HexCount, before)
        obj.Part = self.box  # recovers
        self.doc.recompute()
        self.assertTrue(obj.isValid())
        self.assertEqual(obj.Status, "ok")

    def check_rejected(self, source, pattern):
        before = snapshot(self.doc)
        with self.assertRaisesRegex(ValueError, pattern):
            VoroHexObjects.makeHexMesh(self.doc, source)
        self.assertEqual(snapshot(self.doc), before)

    def test_wire_rejected(self):
        wire = self.doc.addObject("Part::Feature", "Wire")
        wire.Shape = Part.makePolygon([FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(5, 0, 0),
                                       FreeCAD.Vector(5, 5, 0)])
        self.doc.recompute()
        self.check_rejected(wire, "no solid")

    def test_open_shell_rejected(self):
        shell = self.doc.addObject("Part::Feature", "Shell")
        shell.Shape = Part.makeShell(self.box.Shape.Faces[:5])
        self.doc.recompute()
        self.check_rejected(shell, "open shell")

    def test_meshes_rejected(self):
        import Mesh

        tri = self.doc.addObject("Mesh::Feature", "Tri")
        tri.Mesh = Mesh.createBox(1, 1, 1)
        self.doc.recompute()
        self.check_rejected(tri, "triangle mesh")
        fem = self.make_mesh(size=10)
        self.check_rejected(fem, "FEM mesh")
        self.check_rejected(None, "No geometry")

    def test_save_and_restore(self):
        obj = self.make_mesh(size=10)
        name, hexes = obj.Name, obj.HexCount
        with tempfile.TemporaryDirectory() as d:
            o2 = self.reopened(os.path.join(d, "hex.FCStd"), name)
            self.assertEqual(o2.Proxy.Type, "Fem::VoroHexMesh")
            self.assertEqual(o2.HexCount, hexes)
            self.assertEqual(o2.FemMesh.VolumeCount, hexes)
            o2.TargetSize = 5
            self.doc.recompute()
            self.assertTrue(o2.isValid(), o2.getStatusString())
            self.assertEqual(o2.HexCount, 48)

    def test_smoothing_properties(self):
        obj = self.make_mesh(size=10)
        for o in VoroHex.OPTIONS:  # every option has its property, in its group
            self.assertIn(o.prop, obj.PropertiesList)
            self.assertEqual(obj.getGroupOfProperty(o.prop), o.group)
        self.assertEqual(obj.getGroupOfProperty("SmoothIterations"), "Smoothing")
        self.assertEqual((obj.SmoothIterations, obj.SmoothPasses), (20, 10))
        self.assertAlmostEqual(obj.SmoothQualityTarget, 0.5)
        self.assertEqual(obj.Scheme, "map")
        for name in ("MinScaledJacobianBeforeSmoothing", "MeanScaledJacobianBeforeSmoothing",
                     "Scheme"):
            self.assertEqual(obj.getGroupOfProperty(name), "Result")
            self.assertIn("ReadOnly", obj.getEditorMode(name))
        obj.SmoothIterations, obj.SmoothPasses, obj.SmoothQualityTarget = 7, 0, 0.8
        opts = VoroHexObjects.options_of(obj)
        self.assertEqual((opts["smooth_iterations"], opts["smooth_passes"]), (7, 0))
        self.assertAlmostEqual(opts["smooth_quality_target"], 0.8)
        obj.SmoothIterations = -5  # the constraint keeps it >= 0
        self.assertEqual(obj.SmoothIterations, 0)

    def test_part_chamfer_is_a_block_and_a_tapered_slab(self):
        # A box with its four top edges chamfered by Part's Chamfer feature: convex, so the
        # midpoint subdivision takes it (min 0.15), poorly; cut across the chamfers' foot it
        # is a block and a tapered slab, both mapped, and the mesh object says why.
        box = self.doc.addObject("Part::Box", "Block")
        box.Length, box.Width, box.Height = 40, 30, 20
        self.doc.recompute()
        chamfer = self.doc.addObject("Part::Chamfer", "Chamfer")
        chamfer.Base = box
        top = edges_at_height(box.Shape, 20)
        chamfer.Edges = [(i, 3.0, 3.0) for i in top]
        self.doc.recompute()
        self.assertEqual(len(chamfer.Shape.Faces), 10)
        obj = VoroHexObjects.makeHexMesh(self.doc, chamfer)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual((obj.Scheme, obj.SubVolumeCount), ("map", 2))
        self.assertGreaterEqual(obj.MinScaledJacobian, 0.55)
        self.assertTrue(any("[midpoint_replaced]" in line for line in obj.Diagnostics),
                        list(obj.Diagnostics))

    def test_part_fillet_on_a_plate_with_a_hole_is_cut_at_the_fillets_foot(self):
        # A plate with a hole (Part's Cut), its top edges and the hole's top edge rounded
        # by Part's Fillet feature: convex rounded edges, no concave edge to cut at; cut
        # across the fillets' foot it is a plate and a slab whose fillets are its sides, both
        # swept (the grid mesher's before).
        box = self.doc.addObject("Part::Box", "Plate")
        box.Length, box.Width, box.Height = 40, 30, 10
        hole = self.doc.addObject("Part::Cylinder", "Hole")
        hole.Radius, hole.Height = 5, 10
        hole.Placement.Base = FreeCAD.Vector(20, 15, 0)
        cut = self.doc.addObject("Part::Cut", "Cut")
        cut.Base, cut.Tool = box, hole
        self.doc.recompute()
        fillet = self.doc.addObject("Part::Fillet", "Fillet")
        fillet.Base = cut
        top = edges_at_height(cut.Shape, 10)
        fillet.Edges = [(i, 2.0, 2.0) for i in top]
        self.doc.recompute()
        self.assertTrue(fillet.Shape.isValid())
        obj = VoroHexObjects.makeHexMesh(self.doc, fillet)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual((obj.Scheme, obj.SubVolumeCount), ("sweep", 2))
        self.assertGreaterEqual(obj.MinScaledJacobian, 0.3)
        self.assertTrue(any("the plane across the foot of Face" in line
                            for line in obj.Diagnostics), list(obj.Diagnostics))

    def test_part_fillet_on_a_boss_root_is_cut_at_its_foot_and_revolved(self):
        # A plate and a round boss fused (Part's Fusion, refined), the boss's root rounded by
        # Part's Fillet: a concave fillet, no concave edge left; cut along the cylinder
        # through the fillet's foot on the plate, the plate is a sweep with a round hole and
        # the boss with its fillet a solid of revolution (the grid mesher's before).
        box = self.doc.addObject("Part::Box", "Plate")
        box.Length, box.Width, box.Height = 60, 40, 10
        boss = self.doc.addObject("Part::Cylinder", "Boss")
        boss.Radius, boss.Height = 8, 15
        boss.Placement.Base = FreeCAD.Vector(30, 20, 10)
        fusion = self.doc.addObject("Part::MultiFuse", "Fusion")
        fusion.Shapes = [box, boss]
        fusion.Refine = True
        self.doc.recompute()
        root = [i + 1 for i, e in enumerate(fusion.Shape.Edges)
                if e.Curve.TypeId == "Part::GeomCircle"
                and abs(e.BoundBox.ZMin - 10) < 1e-6 and abs(e.BoundBox.ZMax - 10) < 1e-6]
        self.assertEqual(len(root), 1)
        fillet = self.doc.addObject("Part::Fillet", "Fillet")
        fillet.Base = fusion
        fillet.Edges = [(root[0], 2.0, 2.0)]
        self.doc.recompute()
        self.assertTrue(fillet.Shape.isValid())
        obj = VoroHexObjects.makeHexMesh(self.doc, fillet)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.Scheme, "sweep+revolve")
        self.assertGreaterEqual(obj.MinScaledJacobian, 0.5)
        self.assertTrue(any("the cylinder through the foot of Face" in line
                            for line in obj.Diagnostics), list(obj.Diagnostics))

    def test_part_design_pocket_with_its_floor_filleted_is_swept_along_the_fillets(self):
        # PartDesign as a user builds it: a Pad of a sketched rectangle, a Pocket sketched on
        # its top face, a Fillet on the pocket's four floor edges (they meet at mitres in the
        # corners). Cut across the fillets' feet, beyond the walls and along the mitres, each
        # fillet lies on a strip swept from mitre to mitre, the rest blocks (the grid
        # mesher's before).
        import Sketcher  # noqa: F401  (the sketches' type)
        V = FreeCAD.Vector

        def rectangle(sketch, x0, y0, x1, y1):
            corners = [V(x0, y0, 0), V(x1, y0, 0), V(x1, y1, 0), V(x0, y1, 0)]
            for i in range(4):
                sketch.addGeometry(Part.LineSegment(corners[i], corners[(i + 1) % 4]))

        body = self.doc.addObject("PartDesign::Body", "Body")
        base = body.newObject("Sketcher::SketchObject", "PlateSketch")
        base.Support, base.MapMode = (self.doc.getObject("XY_Plane"), [""]), "FlatFace"
        rectangle(base, 0, 0, 60, 40)
        pad = body.newObject("PartDesign::Pad", "Pad")
        pad.Profile, pad.Length = base, 15
        self.doc.recompute()
        top = next(i + 1 for i, f in enumerate(pad.Shape.Faces)
                   if abs(f.CenterOfMass.z - 15) < 1e-9)
        sketch = body.newObject("Sketcher::SketchObject", "PocketSketch")
        sketch.Support, sketch.MapMode = (pad, ["Face{}".format(top)]), "FlatFace"
        rectangle(sketch, 15, 10, 45, 30)
        pocket = body.newObject("PartDesign::Pocket", "Pocket")
        pocket.Profile, pocket.Length = sketch, 8
        self.doc.recompute()
        floor = ["Edge{}".format(i) for i in edges_at_height(pocket.Shape, 7)]
        self.assertEqual(len(floor), 4)
        fillet = body.newObject("PartDesign::Fillet", "Fillet")
        fillet.Base, fillet.Radius = (pocket, floor), 3
        self.doc.recompute()
        self.assertTrue(fillet.isValid() and fillet.Shape.isValid())
        obj = VoroHexObjects.makeHexMesh(self.doc, body)
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.Scheme, "map+sweep")
        self.assertEqual(obj.SubVolumeCount, 21)
        self.assertGreaterEqual(obj.MinScaledJacobian, 0.4)
        self.assertTrue(any("ended at 4 mitre planes" in line for line in obj.Diagnostics),
                        list(obj.Diagnostics))

    def test_a_failed_mesh_says_each_error_once(self):
        # A round pocket whose floor is filleted (tests/data), second order as the panel's
        # default, with too few hexahedra allowed to make it again at half the size: the
        # mid-edge nodes on the fillet leave nodes off the CAD, an error both in the mesh's
        # diagnostics and in its check's. The object's message said it twice.
        hexme = os.environ.get("VOROHEX_HEXME")
        self.assertTrue(hexme, "VOROHEX_HEXME: the repository's tests/data/hexme (ctest sets it)")
        data = os.path.dirname(hexme)
        part = self.doc.addObject("Part::Feature", "Pocket")
        part.Shape = Part.read(os.path.join(data, "round_pocket_floor_fillet.step"))
        self.doc.recompute()
        obj = VoroHexObjects.makeHexMesh(self.doc, part)
        obj.ElementOrder, obj.MaxHexes = "2nd", 2000
        self.doc.recompute()
        self.assertEqual(obj.Status, "error")
        self.assertEqual(obj.Message.count("lie off the CAD boundary"), 1, obj.Message)
        self.assertIn("Give a smaller size", obj.Message)

    def test_a_feature_whose_recompute_failed_is_refused_not_meshed_stale(self):
        # A fillet too large for its box fails to recompute and keeps its last good shape:
        # the mesh refuses it by name instead of meshing the shape the tree no longer shows.
        box = self.doc.addObject("Part::Box", "Block")
        box.Length, box.Width, box.Height = 40, 20, 10
        self.doc.recompute()
        fillet = self.doc.addObject("Part::Fillet", "Fillet")
        fillet.Base = box
        top = edges_at_height(box.Shape, 10)
        fillet.Edges = [(i, 1.0, 1.0) for i in top]
        self.doc.recompute()
        self.assertTrue(fillet.Shape.isValid())
        fillet.Edges = [(i, 12.0, 12.0) for i in top]
        self.doc.recompute()
        self.assertIn("Invalid", fillet.State)
        error = VoroHexObjects.source_error(fillet, True)
        self.assertIsNotNone(error)
        self.assertIn("failed to recompute", error)
        self.assertIn("Fillet", error)

    def test_recompute_with_smoothing_off_and_on(self):
        cyl = self.doc.addObject("Part::Cylinder", "Cylinder")
        cyl.Radius, cyl.Height = 5, 10
        self.doc.recompute()
        obj = VoroHexObjects.makeHexMesh(self.doc, cyl, size=1.5)
        obj.SmoothIterations, obj.SmoothPasses = 0, 0
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertEqual(obj.Scheme, "sweep")
        self.assertEqual(obj.MinScaledJacobianBeforeSmoothing, obj.MinScaledJacobian)
        self.assertEqual(obj.MeanScaledJacobianBeforeSmoothing, obj.MeanScaledJacobian)
        unsmoothed = obj.MinScaledJacobian
        obj.SmoothIterations, obj.SmoothPasses = 20, 10
        self.doc.recompute()
        self.assertTrue(obj.isValid(), obj.getStatusString())
        self.assertAlmostEqual(obj.MinScaledJacobianBeforeSmoothing, unsmoothed, places=12)
        self.assertGreaterEqual(obj.MinScaledJacobian, unsmoothed - 1e-12)
        self.assertTrue(VoroHex.check(obj.FemMesh, cyl.Shape).valid)
        self.assertTrue(all(v > 0 for v in femmesh_hex_volumes(obj.FemMesh)))

    def test_old_document_gains_new_properties(self):
        obj = self.make_mesh(size=10)
        obj.SmoothIterations = 3
        name = obj.Name
        new = ("SmoothPasses", "SmoothQualityTarget", "MinScaledJacobianBeforeSmoothing",
               "MeanScaledJacobianBeforeSmoothing", "Scheme")
        for prop in new:  # as written before these existed
            obj.removeProperty(prop)
        self.assertNotIn("SmoothPasses", obj.PropertiesList)
        with tempfile.TemporaryDirectory() as d:
            o2 = self.reopened(os.path.join(d, "old.FCStd"), name)
            for prop in new:
                self.assertIn(prop, o2.PropertiesList)
            self.assertEqual(o2.SmoothIterations, 3)  # kept from the file
            self.assertEqual(o2.SmoothPasses, 10)  # the default
            self.assertAlmostEqual(o2.SmoothQualityTarget, 0.5)
            o2.SmoothIterations = -1  # limits are set again after restore
            self.assertEqual(o2.SmoothIterations, 0)
            o2.SmoothQualityTarget = 2.0
            self.assertAlmostEqual(o2.SmoothQualityTarget, 1.0)
            o2.TargetSize = 5
            self.doc.recompute()
            self.assertTrue(o2.isValid(), o2.getStatusString())
            self.assertEqual((o2.HexCount, o2.Scheme), (48, "map"))

    def test_femmesh_export_inp(self):
        import Fem

        obj = self.make_mesh(size=5)
        obj.ElementOrder = "1st"  # linear hexahedra: FreeCAD exports them as C3D8
        self.doc.recompute()
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "mesh.inp")
            Fem.export([obj], path)
            vols = inp_c3d8_volumes(path)
            self.assertEqual(len(vols), 48)
            self.assertTrue(all(v > 0 for v in vols))
            self.assertAlmostEqual(sum(vols), 6000.0, places=6)

    def test_calculix_analysis_inp(self):
        import ObjectsFem

        analysis, solver = self.steel_analysis()
        fixed = ObjectsFem.makeConstraintFixed(self.doc, "Fixed")
        fixed.References = [(self.box, "Face5")]  # z = 0
        analysis.addObject(fixed)
        force = ObjectsFem.makeConstraintForce(self.doc, "Force")
        force.References = [(self.box, "Face6")]  # z = 30
        force.Force = 1000.0
        analysis.addObject(force)
        mesh = VoroHexObjects.makeHexMesh(self.doc, self.box, size=5)
        mesh.ElementOrder = "1st"  # FreeCAD's writer on linear hexahedra (new meshes: 2nd)
        analysis.addObject(mesh)
        self.doc.recompute()
        self.assertTrue(mesh.isValid())

        with tempfile.TemporaryDirectory() as d:
            path = self.ccx_deck(analysis, solver, d)
            with open(path) as f:
                text = f.read()
            self.assertRegex(text, r"(?i)\*element,\s*type=C3D8")
            self.assertRegex(text, r"(?i)\*boundary")
            self.assertRegex(text, r"(?i)\*cload")
            vols = inp_c3d8_volumes(path)
            self.assertEqual(len(vols), 48)
            self.assertTrue(all(v > 0 for v in vols), min(vols))
            self.assertTrue(math.isclose(sum(vols), 6000.0, rel_tol=1e-9))


class TestVoroHexDrawing(unittest.TestCase):
    """Issue 24: what the views draw, headless."""

    def test_palettes_are_colour_blind_safe(self):
        # Every pair of edge types, face roles and quality bands stays at least 10 CIEDE2000
        # units apart for normal vision and simulated protanopia, deuteranopia and
        # tritanopia (Machado et al. 2009). The former palette failed: [1] and [2] 2.1 apart
        # for protanopia.
        import sys

        sys.path.append(os.path.join(os.path.dirname(VoroHex.__file__), "Gui"))
        from VoroHexGui import colour_check, palette

        palettes = {"edge types": dict(VoroHexGraph.COLOURS),
                    "face roles": dict(VoroHexParts.COLOURS),
                    "quality bands": {b[2]: b[1] for b in palette.BANDS}}
        for name, colours in palettes.items():
            for vision in colour_check.VISIONS:
                d, a, b = colour_check.closest_pair(colours, vision)
                self.assertGreaterEqual(d, 10.0, "{}, {}: {} and {} only {:.1f} apart".format(
                    name, vision, a, b, d))
        # The check itself: a known CIEDE2000 pair (Sharma, Wu & Dalal 2005, pair 1).
        self.assertAlmostEqual(colour_check.delta_e_2000((50, 2.6772, -79.7751),
                                                         (50, 0, -82.7485)), 2.0425, places=4)

    def test_plate_f_s_faces_all_drawn(self):
        # A plate with two holes: its mid-plane f_s face has three boundary loops (the outer
        # one and one per hole); it was not drawn before. A tube's f_s face (a cylinder
        # between two circles) is drawn as the band between them.
        import VoroHexFaces

        plate = Part.makeBox(60, 40, 4)
        for x in (15, 45):
            plate = plate.cut(Part.makeCylinder(5, 4, FreeCAD.Vector(x, 20, 0)))
        tube = Part.makeCylinder(10, 30).cut(Part.makeCylinder(7, 30))
        for shape in (plate, tube):
            data = VoroHexGraph.compute(shape, 60.0, {})
            fs = data["fs"]
            self.assertTrue(fs)
            for pts, tris, why in fs:
                self.assertIsNone(why)
                # The triangles cover the face: their area is the Voronoi face's (plate: the
                # mid-plane, inset by the half-thickness 2 from the sides and the holes).
                area = sum(((FreeCAD.Vector(*pts[b]) - FreeCAD.Vector(*pts[a])).cross(
                    FreeCAD.Vector(*pts[c]) - FreeCAD.Vector(*pts[a]))).Length / 2
                    for a, b, c in tris)
                if shape is plate:
                    self.assertAlmostEqual(area, 56 * 36 - 2 * math.pi * 7 ** 2, delta=20)
                else:
                    # between the walls (radius 8.5), 1.5 in from each end
                    self.assertAlmostEqual(area, 2 * math.pi * 8.5 * 27, delta=20)
        self.assertEqual(VoroHexFaces.triangulate_face([[(0, 0, 0), (1, 0, 0)]], 1.0)[2],
                         "its 1 boundary edge(s) do not close into a loop")


if __name__ == "__main__":
    unittest.main()
