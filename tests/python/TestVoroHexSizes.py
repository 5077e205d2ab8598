# FreeCAD unit tests of issue 21's local sizes: VoroHex.mesh(..., sizes=...) and FreeCAD's
# own FEM mesh region objects under a VoroHex mesh (run: freecadcmd -t TestVoroHexSizes -M
# <Mod/VoroHex>). Registered through FreeCAD.__unit_test__ in Init.py.
import unittest

import FreeCAD
import ObjectsFem
import Part

import VoroHex
import VoroHexObjects

V = FreeCAD.Vector


def plate_with_hole():
    """200 x 100 x 10 with a round hole of radius 10 at its centre."""
    return Part.makeBox(200, 100, 10).cut(Part.makeCylinder(10, 10, V(100, 50, 0)))


def hole_face(shape):
    """The FreeCAD name of the shape's cylindrical face ("Face7")."""
    for i, f in enumerate(shape.Faces):
        if isinstance(f.Surface, Part.Cylinder):
            return "Face{}".format(i + 1)
    raise AssertionError("no cylindrical face")


class TestVoroHexSizesApi(unittest.TestCase):
    def setUp(self):
        self.plate = plate_with_hole()
        self.hole = hole_face(self.plate)

    def test_sizes_refine_at_the_entity_only(self):
        uniform = VoroHex.mesh(self.plate, size=10)
        local = VoroHex.mesh(self.plate, size=10, sizes={self.hole: 1.0})
        self.assertTrue(uniform.ok and local.ok, local.message)
        self.assertEqual(local.stats.local_sizes, {self.hole: 1.0})
        self.assertEqual(local.stats.scheme, "sweep")
        self.assertGreater(local.stats.hexes, 10 * uniform.stats.hexes)
        # The hole's mesh edges are about 1 long, the plate's far outline keeps about 10.
        groups = local.groups
        hole_nodes = set(groups[self.hole]["nodes"])
        self.assertGreaterEqual(len(hole_nodes), 2 * 63)  # 2 pi 10 / 1 around, top and bottom
        outline = [g for name, g in groups.items() if g["dim"] == 1 and len(g["nodes"]) == 21]
        self.assertTrue(outline)  # the 200-long edges: 20 segments of 10

    def test_grading_option(self):
        steep = VoroHex.mesh(self.plate, size=10, sizes={self.hole: 1.0}, size_grading=1.0)
        gentle = VoroHex.mesh(self.plate, size=10, sizes={self.hole: 1.0}, size_grading=0.2)
        self.assertTrue(steep.ok and gentle.ok)
        self.assertLess(steep.stats.hexes, gentle.stats.hexes)

    def test_bad_sizes_raise_naming_the_entry(self):
        with self.assertRaisesRegex(ValueError, "no Face99 \\(it has 7 faces\\)"):
            VoroHex.mesh(self.plate, size=10, sizes={"Face99": 1})
        with self.assertRaisesRegex(ValueError, "sizes\\['Face7'\\] must be > 0"):
            VoroHex.mesh(self.plate, size=10, sizes={"Face7": 0})
        with self.assertRaisesRegex(ValueError, "'Solid1' is not an entity name"):
            VoroHex.mesh(self.plate, size=10, sizes={"Solid1": 1})
        with self.assertRaisesRegex(TypeError, "sizes must be a dict"):
            VoroHex.mesh(self.plate, size=10, sizes=[("Face7", 1)])
        with self.assertRaisesRegex(ValueError, "size_grading' must be in \\(0, 10\\]"):
            VoroHex.mesh(self.plate, size=10, sizes={"Face7": 1}, size_grading=-1)

    def test_sizes_with_their_unit(self):
        # As FreeCAD writes lengths ("4 mm", "0.5 cm"): the same mesh as the number of mm.
        by_number = VoroHex.mesh(self.plate, size=10, sizes={self.hole: 2})
        by_text = VoroHex.mesh(self.plate, size="1 cm", sizes={self.hole: "2 mm"})
        self.assertTrue(by_number.ok and by_text.ok, by_text.message)
        self.assertEqual(by_text.stats.size_used, 10)
        self.assertEqual(by_text.stats.local_sizes, {self.hole: 2.0})
        self.assertEqual(by_text.stats.hexes, by_number.stats.hexes)
        with self.assertRaisesRegex(ValueError, "option 'size' must be a length, got '4 kg'"):
            VoroHex.mesh(self.plate, size="4 kg")
        with self.assertRaisesRegex(ValueError, "option 'size': 'large' is not a length"):
            VoroHex.mesh(self.plate, size="large")
        # Other options are numbers only.
        with self.assertRaisesRegex(TypeError, "option 'size_grading' must be a number"):
            VoroHex.mesh(self.plate, size=10, size_grading="0.3")


class TestVoroHexSizesObject(unittest.TestCase):
    def setUp(self):
        self.doc = FreeCAD.newDocument("VoroHexSizes")
        self.part = self.doc.addObject("Part::Feature", "Plate")
        self.part.Shape = plate_with_hole()
        self.doc.recompute()
        self.hole = hole_face(self.part.Shape)

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_a_fem_mesh_region_child_refines_the_mesh(self):
        obj = VoroHexObjects.makeHexMesh(self.doc, self.part, size=10)
        self.doc.recompute()
        coarse = obj.HexCount
        # FreeCAD's own mesh region object, made as the FEM workbench makes it.
        region = ObjectsFem.makeMeshRegion(self.doc, obj, 1.0, "HoleRegion")
        region.References = [(self.part, (self.hole,))]
        self.assertEqual(obj.MeshRegionList, [region])
        self.doc.recompute()
        self.assertEqual(obj.Status, "ok", obj.Message)
        self.assertGreater(obj.HexCount, 10 * coarse)
        # A region on an edge (the hole's top circle) through the helper, and the smaller
        # of two sizes on one entity wins.
        circle = [i + 1 for i, e in enumerate(self.part.Shape.Edges)
                  if isinstance(e.Curve, Part.Circle)][0]
        VoroHexObjects.addMeshRegion(obj, 0.5, ["Edge{}".format(circle), self.hole])
        sizes = VoroHexObjects.region_sizes(obj)
        self.assertEqual(sizes[self.hole], 0.5)
        self.assertEqual(sizes["Edge{}".format(circle)], 0.5)

    def test_the_hex_estimate_counts_the_graded_layers(self):
        shape = self.part.Shape
        plain, _ = VoroHexObjects.predicted_hexes(shape, 10)
        local, _ = VoroHexObjects.predicted_hexes(shape, 10, {self.hole: 1.0})
        # The layer around the hole: area 628 x the integral of 1/(1 + 0.3 d)^3 - 1/1000
        # up to d = 30, about 1,020 more than volume / size^3 = 197.
        self.assertAlmostEqual(plain, shape.Volume / 1000, places=6)
        self.assertAlmostEqual(local - plain, 628.3 * (0.99 / 0.6 - 0.03), delta=15)

    def test_bad_regions_are_errors_that_keep_the_previous_mesh(self):
        obj = VoroHexObjects.makeHexMesh(self.doc, self.part, size=10)
        self.doc.recompute()
        before = obj.HexCount
        other = self.doc.addObject("Part::Box", "Other")
        self.doc.recompute()
        region = ObjectsFem.makeMeshRegion(self.doc, obj, 1.0, "Wrong")
        region.References = [(other, ("Face1",))]
        self.doc.recompute()
        self.assertEqual(obj.Status, "error")
        self.assertIn("references 'Other', not the meshed part 'Plate'", obj.Message)
        self.assertEqual(obj.HexCount, before)
        region.References = [(self.part, ("Face99",))]
        self.doc.recompute()
        self.assertIn("no Face99", obj.Message)
        region.References = [(self.part, (self.hole,))]
        region.CharacteristicLength = 0
        self.doc.recompute()
        self.assertIn("has no size", obj.Message)
        self.assertEqual(obj.HexCount, before)

    def test_regions_survive_save_and_restore(self):
        import os
        import tempfile
        obj = VoroHexObjects.makeHexMesh(self.doc, self.part, size=10)
        region = ObjectsFem.makeMeshRegion(self.doc, obj, 1.0, "HoleRegion")
        region.References = [(self.part, (self.hole,))]
        self.doc.recompute()
        hexes = obj.HexCount
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "sizes.FCStd")
            self.doc.saveAs(path)
            name = obj.Name
            FreeCAD.closeDocument(self.doc.Name)
            self.doc = FreeCAD.openDocument(path)  # closed by tearDown
            mesh = self.doc.getObject(name)
            self.assertEqual([r.Name for r in mesh.MeshRegionList], ["HoleRegion"])
            mesh.touch()
            self.doc.recompute()
            self.assertEqual(mesh.Status, "ok", mesh.Message)
            self.assertEqual(mesh.HexCount, hexes)
