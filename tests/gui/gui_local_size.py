# GUI test of the Local size command (issue 21), run by ctest under Xvfb:
#   QTWEBENGINE_DISABLE_SANDBOX=1 xvfb-run -a -s "-screen 0 1280x1024x24" \
#       freecad gui_local_size.py -M <stage>/VoroHex
# A plate with a hole made in the Part workbench (Box, Cylinder, Cut), a VoroHex mesh of it;
# Local size opens FreeCAD's region panel with the part shown; cancelled, the empty region
# is removed and the mesh shows again; with the hole picked, the mesh is refined there.
# Screenshot: VOROHEX_SCREENSHOT (default ./gui_local_size.png). Exit code 0 = pass.
import os
import sys
import threading
import time
import traceback

import FreeCAD
import FreeCADGui as Gui
import Part
from PySide import QtCore, QtGui

TIMEOUT_S = 100
SHOT = os.environ.get("VOROHEX_SCREENSHOT", os.path.abspath("gui_local_size.png"))


def log(msg):
    sys.stdout.write("gui_local_size: {}\n".format(msg))
    sys.stdout.flush()


def watchdog():
    log("timed out after {} s".format(TIMEOUT_S))
    os._exit(3)


def pump(seconds=0.2):
    end = time.time() + seconds
    while time.time() < end:
        QtGui.QApplication.processEvents()
        time.sleep(0.01)


def check(cond, what):
    if not cond:
        raise AssertionError(what)
    log("ok: " + what)


def main():
    import VoroHexObjects

    mw = Gui.getMainWindow()
    mw.setGeometry(0, 0, 1280, 1024)
    mw.showMaximized()
    Gui.activateWorkbench("VoroHexWorkbench")
    pump()
    doc = FreeCAD.newDocument("LocalSize")
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = 200, 100, 10
    cyl = doc.addObject("Part::Cylinder", "Cylinder")
    cyl.Radius, cyl.Height = 10, 10
    cyl.Placement.Base = FreeCAD.Vector(100, 50, 0)
    cut = doc.addObject("Part::Cut", "Cut")
    cut.Base, cut.Tool = box, cyl
    doc.recompute()
    mesh = VoroHexObjects.makeHexMesh(doc, cut, size=10)
    doc.recompute()
    coarse = mesh.HexCount
    check(mesh.Status == "ok" and coarse > 0, "plate meshed: {} hexes".format(coarse))
    cut.ViewObject.Visibility = False  # as the Hex mesh panel leaves it

    command = Gui.Command.get("VoroHex_LocalSize")
    Gui.Selection.clearSelection()
    check(not command.isActive(), "Local size needs a VoroHex mesh selected")
    Gui.Selection.addSelection(mesh)
    check(command.isActive(), "Local size active with the mesh selected")
    Gui.runCommand("VoroHex_LocalSize")
    pump(0.5)
    check(Gui.Control.activeDialog() and len(mesh.MeshRegionList) == 1,
          "a FEM mesh region added under the mesh, its panel open")
    check(cut.ViewObject.Visibility, "the part is shown to pick from")
    Gui.Control.closeDialog()
    pump(1.0)
    check(mesh.MeshRegionList == [] and doc.getObject("MeshRegion") is None,
          "cancelled without a pick: the empty region is removed")
    check(mesh.ViewObject.Visibility and not cut.ViewObject.Visibility,
          "the mesh shows again, the part is hidden again")

    Gui.Selection.addSelection(mesh)
    Gui.runCommand("VoroHex_LocalSize")
    pump(0.5)
    region = mesh.MeshRegionList[-1]
    hole = [i + 1 for i, f in enumerate(cut.Shape.Faces) if isinstance(f.Surface, Part.Cylinder)]
    region.References = [(cut, ("Face{}".format(hole[0]),))]
    region.CharacteristicLength = 2.0
    Gui.Control.closeDialog()
    pump(2.0)
    check(mesh.Status == "ok" and mesh.HexCount > 3 * coarse,
          "the hole picked at 2 mm: {} hexes (was {})".format(mesh.HexCount, coarse))
    check(mesh.ViewObject.Visibility, "the refined mesh is shown")
    check([c.Name for c in mesh.ViewObject.claimChildren()] == [region.Name],
          "the region sits under the mesh in the tree")
    view = Gui.ActiveDocument.ActiveView
    view.viewTop()
    view.fitAll()
    pump(0.5)
    check(QtGui.QGuiApplication.primaryScreen().grabWindow(0).save(SHOT),
          "screenshot saved to " + SHOT)


def run():
    code = 1
    try:
        main()
        code = 0
        log("PASS")
    except Exception:
        traceback.print_exc()
        log("FAIL")
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


timer = threading.Timer(TIMEOUT_S, watchdog)
timer.daemon = True
timer.start()
QtCore.QTimer.singleShot(0, run)
