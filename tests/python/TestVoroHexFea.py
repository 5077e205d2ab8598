# FreeCAD unit tests of issue 21: second-order hexahedra, named groups, element types and
# CalculiX (run: freecadcmd -t TestVoroHexFea -M <Mod/VoroHex>). Registered through
# FreeCAD.__unit_test__ in Init.py.
import os
import re
import tempfile
import unittest

import FreeCAD
import Part

import VoroHex
import VoroHexObjects
from TestVoroHex import BoxDocument, hex_volume


class TestVoroHexFeaApi(unittest.TestCase):
    def setUp(self):
        self.box = Part.makeBox(10, 20, 30)

    def test_second_order_femmesh_has_20_node_hexes_freecad_writes_as_c3d20(self):
        r = VoroHex.mesh(self.box, size=10, order=2)
        self.assertTrue(r.ok, r.message)
        self.assertEqual(r.order, 2)
        # 1 x 2 x 3 hexes: 24 corners + 2*3*4 + 1*3*4 + 1*2*4 + 1*2*3*... mesh edges
        edges = 1 * 3 * 4 + 2 * 2 * 4 + 3 * 2 * 3
        self.assertEqual(r.node_count, 2 * 3 * 4 + edges)
        fm = r.to_femmesh()
        self.assertEqual(fm.VolumeCount, 6)
        self.assertTrue(all(len(fm.getElementNodes(v)) == 20 for v in fm.Volumes))
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "q.inp")
            fm.write(path)
            with open(path) as f:
                text = f.read()
        self.assertRegex(text, r"(?i)\*element,\s*type=C3D20")
        nodes, cells = {}, []
        body = text.split("type=C3D20", 1)[1] if "type=C3D20" in text else \
            re.split(r"(?i)type=C3D20", text, 1)[1]
        for line in text.split("\n"):
            v = [t.strip() for t in line.split(",")]
            if len(v) == 4 and v[0].isdigit():
                nodes[int(v[0])] = tuple(float(t) for t in v[1:])
        ids = [int(t) for t in re.split(r"[,\s]+", body.split("\n", 1)[1].split("*")[0])
               if t.strip().isdigit()]
        cells = [ids[k + 1:k + 21] for k in range(0, len(ids), 21)]
        self.assertEqual(len(cells), 6)
        c3d20_edges = ((0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
                       (0, 4), (1, 5), (2, 6), (3, 7))
        for c in cells:
            p = [nodes[n] for n in c]
            self.assertGreater(hex_volume(p[:8]), 0)  # a positive C3D20
            for k, (a, b) in enumerate(c3d20_edges):  # node 9 + k mid-way on edge a-b
                for i in range(3):
                    self.assertAlmostEqual(p[8 + k][i], (p[a][i] + p[b][i]) / 2, places=9)

    def test_named_groups_reach_the_femmesh(self):
        r = VoroHex.mesh(self.box, size=5)
        groups = r.groups
        self.assertEqual(len(groups), 26)
        self.assertEqual(sorted(n for n in groups if n.startswith("Face")),
                         sorted("Face{}".format(i) for i in range(1, 7)))
        nodes = r.nodes
        # Face5 of Part.makeBox is z = 0: all its nodes there, 3 x 5 of them.
        self.assertEqual(len(groups["Face5"]["nodes"]), 3 * 5)
        self.assertTrue(all(abs(nodes[n][2]) < 1e-12 for n in groups["Face5"]["nodes"]))
        self.assertEqual(len(groups["Face5"]["faces"]), 2 * 4)
        fm = r.to_femmesh()
        names = {fm.getGroupName(g): g for g in fm.Groups}
        self.assertIn("Face5", names)
        self.assertIn("Edge1", names)
        self.assertIn("Vertex1", names)
        self.assertEqual(fm.getGroupElementType(names["Face5"]), "Node")
        self.assertEqual(sorted(fm.getGroupElements(names["Face5"])),
                         sorted(n + 1 for n in groups["Face5"]["nodes"]))
        self.assertEqual(len(r.to_femmesh(groups=False).Groups), 0)

    def test_femmesh_groups_print_nothing(self):
        # FreeCAD's FemMesh prints two lines per group on the process's standard output
        # ("Added Group: ...", "AddGroupElements: ..."): 26 groups here, none printed; what is
        # written after still reaches the output.
        r = VoroHex.mesh(self.box, size=10)
        self.assertTrue(r.ok, r.message)
        with tempfile.TemporaryFile() as out:
            saved = os.dup(1)
            os.dup2(out.fileno(), 1)
            try:
                fm = r.to_femmesh()
                os.write(1, b"after the groups\n")
            finally:
                os.dup2(saved, 1)
                os.close(saved)
            out.seek(0)
            printed = out.read().decode(errors="replace")
        self.assertEqual(len(fm.Groups), 26)
        self.assertNotIn("Group", printed)
        self.assertIn("after the groups", printed)

    def test_order_and_element_errors(self):
        with self.assertRaises(ValueError):
            VoroHex.mesh(self.box, size=10, order=3)
        r = VoroHex.mesh(self.box, size=10)  # one element through x
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "m.inp")
            with self.assertRaisesRegex(ValueError, "unknown element type"):
                r.write(path, element="C3D99")
            with self.assertRaisesRegex(ValueError, "hourglasses"):
                r.write(path, element="C3D8R")
            with self.assertRaisesRegex(ValueError, "second-order"):
                r.write(path, element="C3D20")
            self.assertFalse(os.path.exists(path))
            self.assertEqual(r.write(path), [])
            with open(path) as f:
                text = f.read()
            self.assertIn("TYPE=C3D8I", text)
            self.assertIn("*NSET, NSET=Face1", text)


class TestVoroHexFeaObject(BoxDocument, unittest.TestCase):
    doc_name = "VoroHexFeaTest"

    def test_element_order_property_gives_20_node_hexes_to_calculix(self):
        import ObjectsFem

        mesh = self.make_mesh(size=10)
        self.assertEqual(mesh.ElementOrder, "2nd")  # new meshes are quadratic, as Gmsh's
        self.assertEqual(list(mesh.getEnumerationsOfProperty("ElementOrder")), ["1st", "2nd"])
        mesh.ElementOrder = "1st"
        self.doc.recompute()
        self.assertTrue(all(len(mesh.FemMesh.getElementNodes(v)) == 8
                            for v in mesh.FemMesh.Volumes))
        self.assertEqual(mesh.FemMesh.VolumeCount, 6)
        self.assertTrue(any(mesh.FemMesh.getGroupName(g) == "Face6"
                            for g in mesh.FemMesh.Groups))
        mesh.ElementOrder = "2nd"
        self.doc.recompute()
        self.assertTrue(mesh.isValid(), mesh.Message)
        fm = mesh.FemMesh
        self.assertTrue(all(len(fm.getElementNodes(v)) == 20 for v in fm.Volumes))
        self.assertEqual(mesh.NodeCount, fm.NodeCount)
        analysis, solver = self.steel_analysis()
        fixed = ObjectsFem.makeConstraintFixed(self.doc, "Fixed")
        fixed.References = [(self.box, "Face5")]
        analysis.addObject(fixed)
        analysis.addObject(mesh)
        self.doc.recompute()
        with tempfile.TemporaryDirectory() as d:
            with open(self.ccx_deck(analysis, solver, d)) as f:
                self.assertRegex(f.read(), r"(?i)\*element,\s*type=C3D20")


    def test_cantilever_through_freecad_and_calculix(self):
        """The issue's user path: analysis, CalculiX solver, material, fixed and force
        constraints and a VoroHex mesh, solved through FreeCAD's ccx tools. FreeCAD writes
        8-node hexes as C3D8 (it locks: -12 %); ElementOrder 2nd gives C3D20, within 1 % of
        Euler-Bernoulli (1.905 mm) at two elements through the thickness."""
        import shutil

        import ObjectsFem
        from femtools import ccxtools

        if shutil.which("ccx") is None:
            self.skipTest("CalculiX (ccx, Debian package calculix-ccx) is not installed")
        beam = self.doc.addObject("Part::Box", "Beam")
        beam.Length, beam.Width, beam.Height = 100, 10, 10
        self.doc.recompute()
        analysis, solver = self.steel_analysis()
        fixed = ObjectsFem.makeConstraintFixed(self.doc, "Fixed")
        fixed.References = [(beam, "Face1")]  # x = 0
        analysis.addObject(fixed)
        force = ObjectsFem.makeConstraintForce(self.doc, "Force")
        force.References = [(beam, "Face2")]  # x = 100
        force.Force = 1000.0
        force.Direction = (beam, ["Edge1"])  # along z
        analysis.addObject(force)
        mesh = VoroHexObjects.makeHexMesh(self.doc, beam, size=5)
        mesh.ElementOrder = "2nd"
        analysis.addObject(mesh)
        self.doc.recompute()
        self.assertTrue(mesh.isValid(), mesh.Message)
        with tempfile.TemporaryDirectory() as d:
            fea = ccxtools.FemToolsCcx(analysis, solver)
            fea.update_objects()
            fea.setup_working_dir(d)
            fea.setup_ccx()
            self.assertFalse(fea.check_prerequisites())
            fea.write_inp_file()
            with open(fea.inp_file_name) as f:
                self.assertRegex(f.read(), r"(?i)\*element,\s*type=C3D20")
            fea.ccx_run()
            fea.load_results()
        results = [o for o in analysis.Group if o.isDerivedFrom("Fem::FemResultObject")]
        self.assertTrue(results)
        r, nodes = results[-1], mesh.FemMesh.Nodes
        tip = [i for i, nid in enumerate(r.NodeNumbers) if abs(nodes[nid].x - 100) < 1e-6]
        self.assertEqual(len(tip), 21)  # 3 x 3 corners + 12 mid-edge nodes on the tip face
        uz = abs(sum(r.DisplacementVectors[i].z for i in tip) / len(tip))
        euler_bernoulli = 1000.0 * 100.0 ** 3 / (3 * 210000.0 * 10.0 ** 4 / 12.0)
        self.assertLess(abs(uz / euler_bernoulli - 1), 0.01, uz)
