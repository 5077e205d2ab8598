#!/usr/bin/python3
"""End-to-end tests of the commands that show what the mesher sees: `vorohex voronoi` and
`vorohex decompose` (the Voronoi graph, its decomposition, the plane cuts, --auto).

Run by ctest: /usr/bin/python3 test_cli_inspect.py <path to vorohex> <examples dir>
"""
import json
import os
import re
import sys
import tempfile
import unittest

import test_cli
from test_cli import HEXME, run


class InspectCommands(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_voronoi_graph_of_the_box(self):
        out, vtp = os.path.join(self.dir, "g.json"), os.path.join(self.dir, "g.vtp")
        code, stdout, stderr = run("voronoi", os.path.join(test_cli.EXAMPLES, "box_3x2x1.step"), "-o", out,
                                   "--vtp", vtp)
        self.assertEqual(code, 0, stdout + stderr)
        with open(out) as f:
            g = json.load(f)
        fs = [e for e in g["elements"] if e.get("f_s")]
        self.assertEqual(len(fs), 1)
        # The two 3x2 faces of FreeCAD's box are Face5 (z = 0) and Face6 (z = 1).
        self.assertEqual(sorted(fs[0]["governors"]), ["Face5", "Face6"])
        with open(vtp) as f:
            self.assertIn("PolyData", f.read())

    def test_decompose_l_shape(self):
        sys.path.append("/usr/lib/freecad-python3/lib")
        import FreeCAD
        import Part
        V = FreeCAD.Vector
        pts = [(0, 0), (4, 0), (4, 1), (1, 1), (1, 3), (0, 3), (0, 0)]
        solid = Part.Face(Part.makePolygon([V(x, y, 0) for x, y in pts])).extrude(V(0, 0, 3))
        step = os.path.join(self.dir, "l.step")
        solid.exportStep(step)
        parts, rep = os.path.join(self.dir, "parts.brep"), os.path.join(self.dir, "d.json")
        vtp = os.path.join(self.dir, "faces.vtp")
        code, stdout, stderr = run("decompose", step, "-o", parts, "--report", rep, "--no-merge",
                                   "--vtp", vtp)
        self.assertEqual(code, 0, stdout + stderr)
        with open(rep) as f:
            report = json.load(f)
        self.assertTrue(report["decomposition_faces"])
        with open(vtp) as f:
            text = f.read()
        self.assertIn("PolyData", text)
        self.assertIn('Name="sub_volume_a"', text)
        compound = Part.read(parts)
        self.assertEqual(len(compound.Solids), 3)
        self.assertAlmostEqual(sum(s.Volume for s in compound.Solids), solid.Volume, places=6)
        code, stdout, stderr = run("decompose", step, "-o", parts)
        self.assertEqual(code, 0, stdout + stderr)
        self.assertIn("1 after", stdout)  # the whole L is one sweep along its depth

    def test_decompose_plane_cuts_shows_the_pieces_the_mesher_uses(self):
        # A plate with bolt holes and a lug with a cross hole, built with Part booleans as a
        # FreeCAD user builds it: the mesher's exact cuts at its concave edges, written.
        sys.path.append("/usr/lib/freecad-python3/lib")
        import FreeCAD
        import Part
        V = FreeCAD.Vector
        plate = Part.makeBox(100, 60, 10)
        for x, y in [(10, 10), (10, 50), (70, 10), (70, 50)]:
            plate = plate.cut(Part.makeCylinder(4, 10, V(x, y, 0), V(0, 0, 1)))
        lug = Part.makeBox(12, 30, 40, V(85, 15, 10)).cut(
            Part.makeCylinder(6, 12, V(85, 30, 35), V(1, 0, 0)))
        solid = plate.fuse(lug).removeSplitter()
        step = os.path.join(self.dir, "plate_lug.step")
        solid.exportStep(step)
        parts = os.path.join(self.dir, "cuts.brep")
        code, stdout, stderr = run("decompose", step, "-o", parts, "--plane-cuts")
        self.assertEqual(code, 0, stdout + stderr)
        self.assertIn("2 after merging", stdout)
        self.assertEqual(stdout.count(": multisweep"), 2, stdout)
        # Why each cut is where it is: the surfaces, each with its face and concave edges.
        self.assertRegex(stdout, r"cut along: the plane of Face\d+ \(at Edge\d+")
        compound = Part.read(parts)
        self.assertEqual(len(compound.Solids), 2)
        self.assertAlmostEqual(sum(s.Volume for s in compound.Solids) / solid.Volume, 1, places=9)
        # The Voronoi decomposition's report and faces are not those of the cuts.
        code, _, stderr = run("decompose", step, "-o", parts, "--plane-cuts", "--report",
                              os.path.join(self.dir, "d.json"))
        self.assertEqual(code, 2)
        self.assertIn("--plane-cuts", stderr)
        for option in (["--sharp-angle", "30"], ["--eps", "0.02"]):
            code, _, stderr = run("decompose", step, "-o", parts, "--plane-cuts", *option)
            self.assertEqual(code, 2, option)
            self.assertIn(option[0] + " is an option of the Voronoi decomposition", stderr)
        # --no-merge: the pieces as cut, each with its scheme.
        code, stdout, _ = run("decompose", step, "-o", parts, "--plane-cuts", "--no-merge",
                              "--quiet")
        self.assertEqual(code, 0, stdout)
        cut = re.search(r"(\d+) pieces \(not merged\)", stdout)
        self.assertIsNotNone(cut, stdout)
        self.assertGreater(int(cut.group(1)), 2)
        self.assertEqual(len(Part.read(parts).Solids), int(cut.group(1)))

    def mesh_as_cut(self, step, cuts):
        """The report of `vorohex mesh` on step, checked to be made of the sub-volumes and
        schemes of the --auto report `cuts`."""
        mesh_rep = os.path.join(self.dir, "as_cut.json")
        code, _, stderr = run("mesh", step, "-o", os.path.join(self.dir, "as_cut.vtu"),
                              "--report", mesh_rep, "--quiet")
        self.assertEqual(code, 0, stderr)
        with open(mesh_rep) as f:
            meshed = json.load(f)
        self.assertEqual(sorted(sv["scheme"] for sv in cuts["sub_volumes"]),
                         sorted(meshed["sub_volume_schemes"]))
        return meshed

    def test_decompose_auto_shows_the_sub_volumes_the_mesher_meshes(self):
        # --auto: what `vorohex mesh` does with a solid. HexMe s07 (a notched block) one
        # multisweep takes whole: not cut. HexMe i10, which no single scheme takes: the
        # plane cuts at its concave edges, the blocks and sweeps its mesh is made of. A
        # sphere (no concave edge): the Voronoi decomposition, saying why.
        parts, rep = os.path.join(self.dir, "auto.brep"), os.path.join(self.dir, "auto.json")
        s07 = os.path.join(HEXME, "s07o_notch.step")
        code, stdout, stderr = run("decompose", s07, "-o", parts, "--auto", "--report", rep,
                                   "--quiet")
        self.assertEqual(code, 0, stdout + stderr)
        self.assertIn("not cut, the mesher meshes it whole", stdout)
        self.assertIn("sub-volume 0 (multisweep)", stdout)
        with open(rep) as f:
            report = json.load(f)
        self.assertEqual((report["method"], report["status"]), ("whole", "ok"))
        self.assertEqual([sv["scheme"] for sv in report["sub_volumes"]], ["multisweep"])
        sys.path.append("/usr/lib/freecad-python3/lib")
        import Part
        whole = Part.read(parts).Solids
        self.assertEqual(len(whole), 1)
        self.assertAlmostEqual(whole[0].Volume / Part.read(s07).Volume, 1, places=9)
        i10 = os.path.join(HEXME, "i10o_simp.step")
        code, stdout, stderr = run("decompose", i10, "-o", parts, "--auto", "--report", rep,
                                   "--quiet")
        self.assertEqual(code, 0, stdout + stderr)
        self.assertIn("plane cuts of", stdout)
        with open(rep) as f:
            cuts = json.load(f)
        self.assertEqual((cuts["method"], cuts["status"]), ("plane-cuts", "ok"))
        meshed = self.mesh_as_cut(i10, cuts)
        self.assertEqual(len(Part.read(parts).Solids), len(meshed["sub_volume_schemes"]))
        sphere = os.path.join(HEXME, "s17o_sphere.step")
        code, stdout, stderr = run("decompose", sphere, "-o", parts, "--auto", "--quiet")
        self.assertIn("not cut along the faces at its concave edges: it has no concave edge "
                      "to cut at; along its Voronoi graph instead", stdout)
        self.assertEqual(stdout.count("not cut along"), 1, stdout)  # printed once, not per process
        self.assertIn("decomposition of " + sphere + ": 1 sub-volume before merging", stdout)
        self.assertIn("as the mesher: not every sub-volume has a scheme, so vorohex mesh meshes "
                      "the solid with its fallback (the grid mesher) instead", stdout)
        for bad, why in ((["--plane-cuts"], "--auto and --plane-cuts: one or the other"),
                         (["--vtp", os.path.join(self.dir, "f.vtp")],
                          "--vtp is an option of the Voronoi decomposition alone")):
            code, _, stderr = run("decompose", s07, "-o", parts, "--auto", *bad)
            self.assertEqual(code, 2, bad)
            self.assertIn(why, stderr)

    def test_decompose_auto_cuts_around_a_cross_hole(self):
        # A tube with a cross hole through both walls, built with Part booleans: no concave
        # edge, so --auto (as the mesher) cuts with four planes around the hole, named once,
        # and vorohex mesh meshes the same structured sub-volumes.
        sys.path.append("/usr/lib/freecad-python3/lib")
        import FreeCAD
        import Part
        V = FreeCAD.Vector
        tube = (Part.makeCylinder(10, 50).cut(Part.makeCylinder(7, 50))
                .cut(Part.makeCylinder(3, 30, V(-15, 0, 25), V(1, 0, 0))).removeSplitter())
        step = os.path.join(self.dir, "tube.step")
        tube.exportStep(step)
        parts, rep = os.path.join(self.dir, "tube.brep"), os.path.join(self.dir, "tube.json")
        code, stdout, stderr = run("decompose", step, "-o", parts, "--auto", "--report", rep,
                                   "--quiet")
        self.assertEqual(code, 0, stdout + stderr)
        self.assertRegex(stdout, r"cut along: 4 planes around the hole of Face\d+\n")
        with open(rep) as f:
            cuts = json.load(f)
        self.assertEqual((cuts["method"], cuts["status"]), ("plane-cuts", "ok"))
        self.assertEqual([c["kind"] for c in cuts["cut_surfaces"]], ["hole_plane"] * 4)
        # A swept piece says which way it sweeps, by its own faces (as the report's ends).
        for v in cuts["sub_volumes"]:
            if v["scheme"] == "sweep":
                self.assertIn("a sweep from its {} to its {} once glued".format(
                    v["source"], v["target"]), v["reason"])
        self.assertIn("sweep", [v["scheme"] for v in cuts["sub_volumes"]])
        meshed = self.mesh_as_cut(step, cuts)
        self.assertGreaterEqual(meshed["check"]["scaled_jacobian"]["min"], 0.3)

    def test_a_lug_as_wide_as_its_tube_is_cut_across_the_tube(self):
        # A tube with a lug as wide as the tube standing on it, a hole across the lug, built
        # with Part booleans: the lug's sides are tangent to the tube. Cut along the tube's
        # cylinder, the lug comes off with knife edges (said so); the mesher then cuts along
        # the plane tangent to the tube across its top, and the pieces mesh structured.
        sys.path.append("/usr/lib/freecad-python3/lib")
        import FreeCAD
        import Part
        V = FreeCAD.Vector
        x = V(1, 0, 0)
        solid = (Part.makeCylinder(35, 80, V(-40, 0, 0), x)
                 .fuse(Part.makeBox(60, 70, 60, V(-30, -35, 0)))
                 .cut(Part.makeCylinder(17.5, 80, V(-40, 0, 0), x))
                 .cut(Part.makeCylinder(10, 70, V(0, -35, 47), V(0, 1, 0)))
                 .removeSplitter())
        step = os.path.join(self.dir, "lug_tube.step")
        solid.exportStep(step)
        parts = os.path.join(self.dir, "cuts.brep")
        code, stdout, stderr = run("decompose", step, "-o", parts, "--plane-cuts", "--quiet")
        self.assertIn("knife edges", stdout)
        self.assertRegex(stdout, r"the cylinder of Face\d+")
        code, stdout, stderr = run("decompose", step, "-o", parts, "--plane-cuts",
                                   "--tangent-planes", "--quiet")
        self.assertEqual(code, 0, stdout + stderr)
        self.assertRegex(stdout, r"the plane tangent to the cylinder of Face\d+")
        self.assertNotIn("knife edges", stdout)
        self.assertEqual(stdout.count(": multisweep"), 2, stdout)
        code, _, stderr = run("decompose", step, "-o", parts, "--tangent-planes")
        self.assertEqual(code, 2)
        self.assertIn("--tangent-planes is an option of --plane-cuts", stderr)
        # --auto takes the tangent planes where the cut's pieces have knife edges, as the
        # mesher does.
        code, stdout, stderr = run("decompose", step, "-o", parts, "--auto", "--quiet")
        self.assertEqual(code, 0, stdout + stderr)
        self.assertRegex(stdout, r"the plane tangent to the cylinder of Face\d+")
        out, rep = os.path.join(self.dir, "lug_tube.vtu"), os.path.join(self.dir, "r.json")
        code, _, stderr = run("mesh", step, "-o", out, "--report", rep, "--quiet")
        self.assertEqual(code, 0, stderr)
        with open(rep) as f:
            report = json.load(f)
        self.assertEqual(report["scheme"], "multisweep", report["diagnostics"])
        self.assertGreaterEqual(report["check"]["scaled_jacobian"]["min"], 0.25)
        self.assertTrue(report["check"]["valid"])

    def test_decompose_shows_progress_and_stops_at_its_time_limit(self):
        step = os.path.join(test_cli.EXAMPLES, "tapered_brick.step")
        parts, rep = os.path.join(self.dir, "parts.brep"), os.path.join(self.dir, "d.json")
        code, stdout, stderr = run("decompose", step, "-o", parts, "--report", rep)
        self.assertEqual(code, 0, stdout + stderr)
        lines = [l for l in stderr.splitlines() if l.startswith("[")]
        self.assertTrue(any(re.search(r"voronoi +0%", l) for l in lines), stderr)
        self.assertTrue(any(re.search(r"decompose +100%", l) for l in lines), stderr)
        self.assertIn("after", stdout)  # the summary comes back from the child process
        # Written beside and renamed: nothing partial is left.
        self.assertTrue(os.path.exists(parts) and os.path.exists(rep))
        self.assertFalse([f for f in os.listdir(self.dir) if f.endswith(".partial")])
        code, _, stderr = run("decompose", step, "-o", parts, "--quiet")
        self.assertEqual(code, 0, stderr)
        self.assertNotIn("%", stderr)
        # A limit too short for anything: a failure naming the step, in the report too; no
        # sub-volumes written.
        os.remove(parts)
        code, _, stderr = run("decompose", step, "-o", parts, "--report", rep,
                              "--time-limit", "0.001")
        self.assertEqual(code, 1, stderr)
        self.assertIn("error [time_limit] The decomposition stopped at its time limit while",
                      stderr)
        with open(rep) as f:
            report = json.load(f)
        self.assertEqual(report["status"], "failed")
        self.assertIn("time_limit", [d["code"] for d in report["diagnostics"]])
        self.assertFalse(os.path.exists(parts))
        for bad in ("0", "-1", "abc", "nan", "inf"):
            code, _, stderr = run("decompose", step, "-o", parts, "--time-limit", bad)
            self.assertEqual(code, 2, bad)
            self.assertIn("--time-limit", stderr)
        # The plane cuts take the limit too.
        code, _, stderr = run("decompose", step, "-o", parts, "--plane-cuts", "--time-limit",
                              "20", "--quiet")
        self.assertNotEqual(code, 2, stderr)

    def test_failed_decomposition_still_writes_its_report(self):
        # HexMe's notch: the split loses 1.3e-9 of the volume (over the 1e-9 allowed), so the
        # decomposition without merging fails; the report says why, and no sub-volumes are
        # written.
        step = os.path.join(HEXME, "s07o_notch.step")
        self.assertTrue(os.path.exists(step), step)
        parts, rep = os.path.join(self.dir, "parts.brep"), os.path.join(self.dir, "d.json")
        code, _, stderr = run("decompose", step, "-o", parts, "--report", rep, "--no-merge")
        self.assertEqual(code, 1, stderr)
        self.assertIn("volume_mismatch", stderr)
        with open(rep) as f:
            report = json.load(f)
        self.assertEqual(report["status"], "failed")
        self.assertIn("volume_mismatch", [d["code"] for d in report["diagnostics"]])
        self.assertFalse(os.path.exists(parts))
        # Merging, all pieces together are the notch itself, a multisweep: it is the one
        # sub-volume, and the report and the output say the split did not hold.
        code, out, stderr = run("decompose", step, "-o", parts, "--report", rep)
        self.assertEqual(code, 0, stderr)
        self.assertIn("sub-volume 0 (multisweep)", out)
        self.assertIn("partial: 1 split whose pieces failed the self-check", out)
        with open(rep) as f:
            report = json.load(f)
        self.assertEqual(report["status"], "partial")
        self.assertIn("split_check_failed", report["partial_reason"])
        self.assertEqual([sv["scheme"] for sv in report["sub_volumes"]], ["multisweep"])
        self.assertTrue(os.path.exists(parts))

    def test_inspect_bad_input(self):
        code, _, stderr = run("voronoi", os.path.join(self.dir, "missing.step"), "-o", "x.json")
        self.assertEqual(code, 2)
        code, _, stderr = run("voronoi", os.path.join(test_cli.EXAMPLES, "box_3x2x1.step"), "-o",
                              os.path.join(self.dir, "g.json"), "--eps", "-1")
        self.assertEqual(code, 2)
        code, _, stderr = run("decompose", os.path.join(test_cli.EXAMPLES, "box_3x2x1.step"))
        self.assertEqual(code, 2)
        self.assertIn("-o", stderr)


if __name__ == "__main__":
    test_cli.main()
