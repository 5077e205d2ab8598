#!/usr/bin/python3
"""End-to-end tests of `vorohex mesh` for finite elements: .inp decks of first and second
order, their element types and named sets, and CalculiX on them (when ccx is installed).

Run by ctest: /usr/bin/python3 test_cli_fea.py <path to vorohex> <examples dir>
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import test_cli
from test_cli import run


def beam_step(directory):
    """STEP of the 100 x 10 x 10 cantilever of issue 21 (Face1: x = 0, Face2: x = 100)."""
    sys.path.append("/usr/lib/freecad-python3/lib")
    import FreeCAD  # noqa: F401  (FreeCAD must be imported before Part)
    import Part
    path = os.path.join(directory, "beam.step")
    Part.makeBox(100, 10, 10).exportStep(path)
    return path


def node_set(text, name):
    """The 1-based node ids of *NSET name in an INP text."""
    start = text.index("*NSET, NSET={}\n".format(name))
    body = text[start:].split("\n", 1)[1].split("*", 1)[0]
    return [int(v) for v in body.replace("\n", ",").split(",") if v.strip()]


def inp_nodes(text):
    """{id: (x, y, z)} of the *NODE block."""
    block = text.split("*NODE, NSET=NALL\n", 1)[1].split("*", 1)[0]
    out = {}
    for line in block.strip().split("\n"):
        v = line.split(",")
        out[int(v[0])] = tuple(float(t) for t in v[1:])
    return out


class FeaDecks(unittest.TestCase):
    """Issue 21: element types, named groups, second order, and an INP CalculiX solves."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        self.beam = beam_step(self.dir)

    def tearDown(self):
        self.tmp.cleanup()

    def mesh(self, *args, out="beam.inp"):
        path = os.path.join(self.dir, out)
        rep = os.path.join(self.dir, "report.json")
        code, stdout, stderr = run("mesh", self.beam, "-o", path, "--report", rep, *args)
        report = None
        if os.path.exists(rep):
            with open(rep) as f:
                report = json.load(f)
            os.remove(rep)
        return code, stdout, stderr, path, report

    def ccx_displacements(self, ccx, name, deck, component):
        """Runs CalculiX on `deck` as job `name`; the printed displacement `component` (1: x,
        3: z) of each node, in the order of the .dat file."""
        job = os.path.join(self.dir, name)
        with open(job + ".inp", "w") as f:
            f.write(deck)
        p = subprocess.run([ccx, os.path.basename(job)], cwd=self.dir, capture_output=True,
                           text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stdout[-2000:])
        self.assertNotIn("*ERROR", p.stdout)
        values = []
        with open(job + ".dat") as f:
            for line in f:
                v = line.split()
                if len(v) == 4 and v[0].isdigit():
                    values.append(float(v[component]))
        return values
    def test_groups_are_named_like_the_report_and_hold_the_right_nodes(self):
        code, stdout, stderr, path, report = self.mesh("--size", "5")
        self.assertEqual(code, 0, stdout + stderr)
        self.assertIn("groups               6 faces, 12 edges, 8 vertices", stdout)
        names = [g["name"] for g in report["groups"]]
        self.assertEqual(names[:6], ["Face{}".format(i) for i in range(1, 7)])
        self.assertIn("Edge12", names)
        self.assertIn("Vertex8", names)
        face2 = next(g for g in report["groups"] if g["name"] == "Face2")
        self.assertEqual((face2["nodes"], face2["element_faces"]), (9, 4))  # 2 x 2 quads
        self.assertEqual(report["element"], "C3D8I")
        self.assertEqual(report["order"], 1)
        with open(path) as f:
            text = f.read()
        nodes = inp_nodes(text)
        # Face1 is x = 0 and Face2 x = 100 (FreeCAD's and OCCT's numbering of a box).
        self.assertEqual({nodes[n][0] for n in node_set(text, "Face1")}, {0.0})
        self.assertEqual({nodes[n][0] for n in node_set(text, "Face2")}, {100.0})
        self.assertIn("*SURFACE, NAME=Face2, TYPE=ELEMENT", text)
        self.assertIn("*ELSET, ELSET=Face2_Elements", text)
        # The MSH file has the same groups as physical groups.
        code, stdout, stderr, msh, _ = self.mesh("--size", "5", out="beam.msh")
        self.assertEqual(code, 0, stderr)
        with open(msh) as f:
            self.assertIn('2 2 "Face2"', f.read())

    def test_second_order_files_are_read_and_judged_by_check(self):
        for ext in ("vtu", "msh"):
            code, stdout, stderr, path, report = self.mesh("--size", "5", "--order", "2",
                                                           out="beam2." + ext)
            self.assertEqual(code, 0, stdout + stderr)
            self.assertEqual(report["order"], 2)
            code, stdout, stderr = run("check", path, "--cad", self.beam)
            self.assertEqual(code, 0, stdout + stderr)
            self.assertIn("second order         20-node, 0 with det J <= 0", stdout)
        code, stdout, stderr, path, report = self.mesh("--size", "5", "--order", "2")
        self.assertEqual(code, 0, stdout + stderr)
        self.assertEqual(report["element"], "C3D20R")
        with open(path) as f:
            self.assertIn("*ELEMENT, TYPE=C3D20R, ELSET=SV0", f.read())
        # One element through the thickness: C3D20, said so.
        code, stdout, stderr, path, report = self.mesh("--size", "10", "--order", "2")
        self.assertEqual(code, 0, stdout + stderr)
        self.assertEqual(report["element"], "C3D20")
        self.assertIn("element_type_chosen", stderr)

    def test_bad_order_element_and_reduced_integration_exit_2(self):
        for args, phrase in ((["--order", "3"], "--order must be 1"),
                             (["--order", "two"], "--order must be 1"),
                             (["--element", "C3D27"], "unknown element type 'C3D27'"),
                             (["--element", "C3D20"], "needs --order 2"),
                             (["--order", "2", "--element", "C3D8I"], "needs --order 1")):
            code, stdout, stderr, path, _ = self.mesh("--size", "10", *args)
            self.assertEqual(code, 2, args)
            self.assertIn(phrase, stderr, args)
            self.assertFalse(os.path.exists(path), args)
        code, stdout, stderr, path, _ = self.mesh("--size", "10", "--element", "C3D8I",
                                                  out="beam.vtu")
        self.assertEqual(code, 2)
        self.assertIn("--element sets the element type of an .inp file", stderr)
        # Reduced integration asked for on a mesh one element thick: refused, nothing written.
        for args in (["--element", "C3D8R"], ["--order", "2", "--element", "C3D20R"]):
            code, stdout, stderr, path, _ = self.mesh("--size", "10", *args)
            self.assertEqual(code, 2, stdout + stderr)
            self.assertIn("reduced_integration_thin", stderr)
            self.assertFalse(os.path.exists(path))
        self.assertEqual([f for f in os.listdir(self.dir) if f.startswith(".vorohex-tmp")], [])

    def test_calculix_solves_the_deck_and_the_tip_deflection_is_within_1_percent(self):
        """Only *MATERIAL, *SOLID SECTION, *BOUNDARY on NSET Face1, *CLOAD on NSET Face2 and a
        *STEP are added to what `vorohex mesh` writes. Reference: Euler-Bernoulli,
        P L^3 / (3 E I) = 1.905 mm; two elements through the thickness (size 5)."""
        ccx = shutil.which("ccx")
        if ccx is None:
            self.skipTest("CalculiX (ccx, Debian package calculix-ccx) is not installed")
        euler_bernoulli = 1000.0 * 100.0 ** 3 / (3 * 210000.0 * 10.0 ** 4 / 12.0)
        for order, element in ((1, "C3D8I"), (2, "C3D20R")):
            code, stdout, stderr, path, report = self.mesh("--size", "5", "--order", str(order))
            self.assertEqual(code, 0, stdout + stderr)
            self.assertEqual(report["element"], element)
            with open(path) as f:
                text = f.read()
            tip = node_set(text, "Face2")
            deck = text + (
                "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000, 0.3\n"
                "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n"
                "*STEP\n*STATIC\n*BOUNDARY\nFace1, 1, 3, 0\n"
                "*CLOAD\nFace2, 3, {!r}\n*NODE PRINT, NSET=Face2\nU\n*END STEP\n").format(
                    1000.0 / len(tip))
            uz = self.ccx_displacements(ccx, "cantilever{}".format(order), deck, 3)
            self.assertEqual(len(uz), len(tip))
            deflection = sum(uz) / len(uz)
            error = deflection / euler_bernoulli - 1
            print("ccx cantilever order {} {}: tip {:.4f} mm, {:+.2f} % vs Euler-Bernoulli".format(
                order, element, deflection, 100 * error))
            self.assertLess(abs(error), 0.01)

    def test_calculix_pressure_on_a_named_surface_gives_the_exact_elongation(self):
        """*DSLOAD on the element-face SURFACE Face2 (tension 100 MPa), Face1 held in x and
        three of its vertices just enough against rigid motion: uniaxial stress, which 8-
        and 20-node hexes represent exactly, so every tip node moves s L / E = 0.047619 mm
        (a wrong face label would load other faces)."""
        ccx = shutil.which("ccx")
        if ccx is None:
            self.skipTest("CalculiX (ccx, Debian package calculix-ccx) is not installed")
        for order in (1, 2):
            code, stdout, stderr, path, _ = self.mesh("--size", "5", "--order", str(order))
            self.assertEqual(code, 0, stdout + stderr)
            with open(path) as f:
                text = f.read()
            nodes = inp_nodes(text)

            def vertex_at(p):
                for name in ("Vertex{}".format(i) for i in range(1, 9)):
                    n = node_set(text, name)[0]
                    if all(abs(nodes[n][k] - p[k]) < 1e-9 for k in range(3)):
                        return name

            deck = text + (
                "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000, 0.3\n"
                "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n*STEP\n*STATIC\n*BOUNDARY\n"
                "Face1, 1, 1, 0\n{}, 2, 3, 0\n{}, 3, 3, 0\n{}, 2, 2, 0\n"
                "*DSLOAD\nFace2, P, -100\n*NODE PRINT, NSET=Face2\nU\n*END STEP\n").format(
                    vertex_at((0, 0, 0)), vertex_at((0, 10, 0)), vertex_at((0, 0, 10)))
            ux = self.ccx_displacements(ccx, "tension{}".format(order), deck, 1)
            self.assertEqual(len(ux), len(node_set(text, "Face2")))
            for u in ux:
                self.assertAlmostEqual(u, 100.0 * 100.0 / 210000.0, delta=1e-6)


if __name__ == "__main__":
    test_cli.main()
