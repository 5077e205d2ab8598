# GUI test, run by ctest under Xvfb:
#   QTWEBENGINE_DISABLE_SANDBOX=1 xvfb-run -a -s "-screen 0 1280x1024x24" \
#       freecad gui_hexmesh.py -M <stage>/VoroHex
# Activates the workbench, selects a box, runs VoroHex_HexMesh, accepts the task panel,
# checks the mesh object, and saves a screenshot of the whole window
# (VOROHEX_SCREENSHOT, default ./gui_hexmesh_box.png). Exit code 0 = pass.
import os
import sys
import threading
import time
import traceback

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore, QtGui

TIMEOUT_S = 100  # CI budget: a modal dialog or a hang must not block the pipeline
SHOT = os.environ.get("VOROHEX_SCREENSHOT", os.path.abspath("gui_hexmesh_box.png"))


def log(msg):
    sys.stdout.write("gui_hexmesh: {}\n".format(msg))
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


def task_ok_button(mw, which=QtGui.QDialogButtonBox.Ok):
    for box in mw.findChildren(QtGui.QDialogButtonBox):
        b = box.button(which)
        if b is not None and b.isVisible():
            return b
    return None


def main():
    mw = Gui.getMainWindow()
    mw.setGeometry(0, 0, 1280, 1024)
    mw.showMaximized()
    Gui.activateWorkbench("VoroHexWorkbench")
    pump()
    check(Gui.activeWorkbench().name() == "VoroHexWorkbench", "workbench active")
    toolbars = [t.windowTitle() for t in mw.findChildren(QtGui.QToolBar) if t.isVisible()]
    check("VoroHex" in toolbars, "VoroHex toolbar visible")

    combo = [d for d in mw.findChildren(QtGui.QDockWidget) if d.isVisible()
             and d.objectName() in ("Combo View", "ComboView")]
    # Before the 3-D view exists: under Xvfb a GL view resized later is not re-rendered.
    if combo:  # wide enough for the task panel and the property names
        mw.resizeDocks(combo, [400], QtCore.Qt.Horizontal)
    pump(1.0)
    doc = FreeCAD.newDocument("HexMeshDemo")
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = 40, 20, 10
    doc.recompute()
    Gui.SendMsgToActiveView("ViewFit")
    pump()
    Gui.Selection.clearSelection()
    from VoroHexGui import commands

    check(not commands.HexMeshCommand().IsActive(), "command inactive without selection")
    Gui.Selection.addSelection(box)
    pump()
    check(commands.HexMeshCommand().IsActive(), "command active with the box selected")
    Gui.runCommand("VoroHex_HexMesh")
    pump(0.5)
    meshes = [o for o in doc.Objects if o.isDerivedFrom("Fem::FemMeshObjectPython")]
    check(len(meshes) == 1, "one mesh object created")
    mesh = meshes[0]
    check(bool(Gui.Control.activeDialog()), "task panel open")
    size_box = mw.findChild(QtGui.QDoubleSpinBox, "sb_size")
    check(size_box is not None, "size field in the task panel")
    size_box.setValue(2.5)
    for name, value in (("sb_smooth_iterations", 5), ("sb_smooth_passes", 4)):
        spin = mw.findChild(QtGui.QSpinBox, name)
        check(spin is not None and spin.minimum() == 0, name + " in the task panel, min 0")
        spin.setValue(value)
    target = mw.findChild(QtGui.QDoubleSpinBox, "sb_smooth_quality_target")
    check(target is not None and target.value() == 0.5, "quality target shows the default")
    ok = task_ok_button(mw)
    check(ok is not None, "task panel OK button")
    ok.click()  # meshes (in a child process), then closes
    end = time.time() + 30
    while Gui.Control.activeDialog() and time.time() < end:
        pump(0.1)
    check(not Gui.Control.activeDialog(), "task panel closed")
    check(mesh.isValid() and mesh.Status == "ok", "mesh valid: " + mesh.Message)
    check(mesh.HexCount == 16 * 8 * 4, "hex count {} == 512".format(mesh.HexCount))
    check(mesh.FemMesh.VolumeCount == mesh.HexCount, "FemMesh filled")
    check((mesh.SmoothIterations, mesh.SmoothPasses) == (5, 4), "smoothing options stored")
    check(mesh.Scheme == "map", "scheme recorded")
    import VoroHex

    check(VoroHex.check(mesh.FemMesh, box.Shape).valid, "VoroHex.check valid")
    check(not box.ViewObject.Visibility, "solid hidden, mesh shown")

    pump(1.0)  # let the 3-D view take its final size before fitting
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    pump(0.5)
    view.fitAll()
    cam = view.getCameraNode()
    if hasattr(cam, "height"):  # orthographic: fitAll fits the height; leave room at the sides
        cam.height.setValue(cam.height.getValue() * 1.3)
    view.redraw()
    Gui.Selection.clearSelection()
    # Select the mesh so the tree and property view show it, without the 3-D selection
    # colour hiding the mesh's own look.
    mesh.ViewObject.Selectable = False
    Gui.Selection.addSelection(mesh)
    pump(1.0)
    os.makedirs(os.path.dirname(SHOT) or ".", exist_ok=True)
    pixmap = QtGui.QGuiApplication.primaryScreen().grabWindow(0)
    check(pixmap.save(SHOT), "screenshot saved to " + SHOT)

    # Re-open the task panel: it shows the quality summary and the histogram.
    mesh.ViewObject.Selectable = True
    Gui.Selection.clearSelection()
    Gui.ActiveDocument.setEdit(mesh.Name)
    pump(1.0)
    from VoroHexGui.histogram import HistogramWidget

    hist = mw.findChild(HistogramWidget)
    check(hist is not None and sum(hist.counts) == mesh.HexCount, "histogram shows all hexes")
    status = mw.findChild(QtGui.QLabel, "lbl_status")
    check(status is not None and "512 hexahedra" in status.text(), "quality summary shown")
    check("Before smoothing: min 1.000" in status.text(), "before/after quality shown")
    panel_shot = os.path.splitext(SHOT)[0] + "_panel.png"
    check(QtGui.QGuiApplication.primaryScreen().grabWindow(0).save(panel_shot),
          "panel screenshot saved to " + panel_shot)
    # Stop during a long run: the GUI stays responsive (the timer that presses Stop fires
    # while meshing runs) and the previous mesh is kept.
    size_box = mw.findChild(QtGui.QDoubleSpinBox, "sb_size")
    size_box.setValue(0.25)  # about 512,000 hexes: seconds of work
    stop = mw.findChild(QtGui.QPushButton, "pb_stop")
    run = mw.findChild(QtGui.QPushButton, "pb_run")
    t0 = time.time()
    run.click()
    pump(0.7)
    check(stop.isEnabled(), "still meshing after 0.7 s")
    stop.click()
    pump(0.3)
    elapsed = time.time() - t0
    status = mw.findChild(QtGui.QLabel, "lbl_status")
    check("Stopped by the user" in status.text(), "run stopped ({:.1f} s): {}".format(
        elapsed, status.text()))
    check(mesh.Status == "ok", "a stop is no error: " + mesh.Message)
    check(mesh.FemMesh.VolumeCount == 512 and mesh.HexCount == 512,
          "previous mesh kept after Stop")
    check(run.isEnabled() and not stop.isEnabled(), "Run enabled again, Stop disabled")
    size_box.setValue(2.5)
    task_ok_button(mw, QtGui.QDialogButtonBox.Cancel).click()
    pump(0.3)
    check(not Gui.Control.activeDialog(), "task panel closed again")

    # Messages name model entities; selecting one in the panel selects them on the solid.
    # A prism with a corner chamfer 0.014 long: its tiny edges are named before meshing.
    import Part

    pts = [FreeCAD.Vector(*p) for p in ((0, 0, 0), (40, 0, 0), (40, 10, 0), (0.1, 10, 0),
                                        (0, 9.9, 0), (0, 0, 0))]
    prism = doc.addObject("Part::Feature", "ChamferedPrism")
    prism.Shape = Part.Face(Part.makePolygon(pts)).extrude(FreeCAD.Vector(0, 0, 10))
    doc.recompute()
    box.ViewObject.Visibility = False
    import VoroHexObjects

    chamfered = VoroHexObjects.makeHexMesh(doc, prism, "ChamferedMesh", size=5)
    doc.recompute()
    check(chamfered.Status == "ok", "chamfered prism meshed: " + chamfered.Message)
    tiny = [k for k, line in enumerate(chamfered.Diagnostics) if "[tiny_edges]" in line]
    check(len(tiny) == 1, "tiny_edges among the recorded messages")
    named = chamfered.DiagnosticEntities[tiny[0]].split(",")
    check(named and all(n.startswith("Edge") for n in named), "it names edges: " + str(named))
    Gui.Selection.clearSelection()
    Gui.ActiveDocument.setEdit(chamfered.Name)
    pump(1.0)
    listing = mw.findChild(QtGui.QListWidget, "lw_diagnostics")
    check(listing is not None and listing.count() == len(chamfered.Diagnostics),
          "the panel lists every message")
    listing.setCurrentRow(tiny[0])
    pump(0.5)
    selected = [n for s in Gui.Selection.getSelectionEx() for n in s.SubElementNames]
    check(sorted(selected) == sorted(named), "selecting it selects {} on the solid".format(named))
    # Preview: graph and decomposition of the solid as document objects, before meshing.
    check(mw.findChild(QtGui.QCheckBox, "cb_decompose").isChecked() == chamfered.Decompose,
          "decomposition options in the panel")
    names_before = set(o.Name for o in doc.Objects)
    mw.findChild(QtGui.QPushButton, "pb_preview").click()
    check(commands.wait(60), "the preview was computed")
    pump(0.3)
    made = [o for o in doc.Objects if o.Name not in names_before and hasattr(o, "Proxy")]
    check(sorted(o.Proxy.__class__.__name__ for o in made) == ["Decomposition", "VoronoiGraph"]
          and all(o.Part == prism for o in made), "Preview made the graph and decomposition")
    preview = mw.findChild(QtGui.QLabel, "lbl_preview").text()
    check(preview.startswith("Graph: ") and "Decomposition" in preview, "preview: " + preview)
    # Reopened, the panel shows the preview it made (its objects are still in the document).
    Gui.ActiveDocument.resetEdit()
    pump(0.5)
    Gui.ActiveDocument.setEdit(chamfered.Name)
    pump(1.0)
    again = mw.findChild(QtGui.QLabel, "lbl_preview").text()
    check(again == preview, "reopened, the panel shows the preview: " + again)
    legend = mw.findChild(QtGui.QTableWidget, "tbl_preview_edge_types")
    check(legend is not None and not legend.isHidden() and legend.rowCount() > 0,
          "and the graph's edge-type legend (in its section, collapsed on opening)")
    listing = mw.findChild(QtGui.QListWidget, "lw_diagnostics")
    for o in made:
        o.ViewObject.Visibility = False
    Gui.Selection.clearSelection()
    listing.setCurrentRow(-1)
    listing.setCurrentRow(tiny[0])
    pump(0.3)
    # For the screenshot: only the solid, looking at the chamfer with the named edges
    # selected, and the panel scrolled down to the messages.
    for o in (chamfered, mesh, box):
        o.ViewObject.Visibility = False
    prism.ViewObject.Visibility = True
    from pivy import coin

    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    top = max(named, key=lambda n: prism.Shape.getElement(n).BoundBox.ZMax)
    target = prism.Shape.getElement(top).BoundBox.Center  # the chamfer's top edge
    look = FreeCAD.Vector(1, -1, -0.8).normalize()  # towards the chamfered corner
    cam = view.getCameraNode()
    eye = target - look * 60
    cam.position.setValue(eye.x, eye.y, eye.z)
    cam.pointAt(coin.SbVec3f(target.x, target.y, target.z), coin.SbVec3f(0, 0, 1))
    if hasattr(cam, "height"):
        cam.height.setValue(3.0)  # about 20 chamfer widths across
    view.redraw()
    for area in mw.findChildren(QtGui.QScrollArea):
        if area.isVisible() and area.widget() and area.widget().findChild(
                QtGui.QListWidget, "lw_diagnostics"):
            area.verticalScrollBar().setValue(area.verticalScrollBar().maximum())
    pump(1.0)
    diag_shot = os.path.splitext(SHOT)[0] + "_diagnostics.png"
    check(QtGui.QGuiApplication.primaryScreen().grabWindow(0).save(diag_shot),
          "diagnostics screenshot saved to " + diag_shot)
    task_ok_button(mw, QtGui.QDialogButtonBox.Cancel).click()
    pump(0.3)
    Gui.Selection.clearSelection()

    # Sub-volumes: two blocks glued at a face (a block standing on a larger one), meshed
    # with one interval assignment; the table lists both, selecting one highlights it.
    two = doc.addObject("Part::Feature", "TwoBlocks")
    two.Shape = Part.makeCompound([Part.makeBox(40, 20, 10),
                                   Part.makeBox(20, 20, 15, FreeCAD.Vector(10, 0, 10))])
    doc.recompute()
    prism.ViewObject.Visibility = False
    joined = VoroHexObjects.makeHexMesh(doc, two, "TwoBlocksMesh", size=2.5)
    doc.recompute()
    check(joined.Status == "ok" and joined.SubVolumeCount == 2,
          "two glued blocks meshed as one: " + joined.Message)
    check(list(joined.SubVolumeHexCounts) == [16 * 8 * 4, 8 * 8 * 6],
          "hexes per sub-volume " + str(list(joined.SubVolumeHexCounts)))
    two.ViewObject.Visibility = False
    Gui.ActiveDocument.setEdit(joined.Name)
    pump(1.0)
    table = mw.findChild(QtGui.QTableWidget, "tw_sub_volumes")
    check(table is not None and table.rowCount() == 2, "the panel's table lists 2 sub-volumes")
    check([table.item(r, 2).text() for r in range(2)] == list(joined.SubVolumeSchemes),
          "with their schemes " + str(list(joined.SubVolumeSchemes)))
    check([table.item(r, 1).text() for r in range(2)] == list(joined.SubVolumeTypes)
          and len(joined.SubVolumeTypes) == 2,
          "and types " + str(list(joined.SubVolumeTypes)))
    table.selectRow(1)
    pump(0.5)
    # Its 8 x 8 x 6 hexahedra: 9 x 9 x 7 corners, and for a quadratic mesh (new meshes are
    # "2nd") one node on each of its 8*9*7 + 9*8*7 + 9*9*6 mesh edges.
    upper = 9 * 9 * 7 + (8 * 9 * 7 * 2 + 9 * 9 * 6 if joined.ElementOrder == "2nd" else 0)
    check(len(joined.ViewObject.HighlightedNodes) == upper,
          "selecting the upper block highlights its {} nodes".format(upper))
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    cam = view.getCameraNode()
    if hasattr(cam, "height"):
        cam.height.setValue(cam.height.getValue() * 1.2)
    for area in mw.findChildren(QtGui.QScrollArea):
        if area.isVisible() and area.widget() and area.widget().findChild(
                QtGui.QTableWidget, "tw_sub_volumes"):
            bar = area.verticalScrollBar()
            bar.setValue(bar.maximum() - 160)
    pump(1.0)
    sv_shot = os.path.splitext(SHOT)[0] + "_sub_volumes.png"
    check(QtGui.QGuiApplication.primaryScreen().grabWindow(0).save(sv_shot),
          "sub-volume screenshot saved to " + sv_shot)
    task_ok_button(mw, QtGui.QDialogButtonBox.Cancel).click()
    pump(0.3)
    joined.ViewObject.HighlightedNodes = []

    # Inside an active FEM analysis the new mesh object joins it (as FEM's mesh commands do).
    import FemGui
    import ObjectsFem

    analysis = ObjectsFem.makeAnalysis(doc, "Analysis")
    FemGui.setActiveAnalysis(analysis)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(box)
    pump()
    Gui.runCommand("VoroHex_HexMesh")
    pump(0.5)
    new = [o for o in doc.Objects
           if o.isDerivedFrom("Fem::FemMeshObjectPython") and o not in (mesh, chamfered, joined)]
    check(len(new) == 1 and new[0] in analysis.Group, "mesh object added to the analysis")
    task_ok_button(mw, QtGui.QDialogButtonBox.Cancel).click()
    pump(0.3)
    check(not Gui.Control.activeDialog(), "task panel cancelled")


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
