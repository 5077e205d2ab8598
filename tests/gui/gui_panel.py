# GUI test, run by ctest under Xvfb (like gui_hexmesh.py):
#   xvfb-run -a -s "-screen 0 1280x1024x24" freecad gui_panel.py -M <stage>/VoroHex
# The Hex mesh panel driven through its buttons, as a user does (issue 24):
#  - the panel: solid, size with the hex count to expect, element order, Run/Stop, the
#    result (scrolled into view), everything else collapsed;
#  - a size whose predicted count exceeds the limit (0.01 on a 90 mm part) is refused
#    before any work starts, with the count in the message;
#  - a part that takes more than 10 s to mesh: a QTimer ticking every 50 ms never sees a
#    gap over 0.3 s, and Stop ends the run within 1 s with no traceback in the Report view;
#    Stop also within 1 s in the decomposition (a cube with a steep pyramid pit, its steps
#    named in the bar as they run), the grid mesher and the smoothing stages;
#  - a fallback mesh gets a banner with a size that gives a structured mesh, found by trying;
#  - Run recomputes only the mesh being edited; Cancel on a never-run mesh removes it;
#    meshes are named after their part; commands are greyed out for a sketch, a face and a
#    tetrahedral mesh.
# Screenshots: VOROHEX_SCREENSHOT (default ./gui_panel.png) and siblings. Exit 0 = pass.
import os
import sys
import threading
import time
import traceback

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore, QtGui

TIMEOUT_S = 140
SHOT = os.environ.get("VOROHEX_SCREENSHOT", os.path.abspath("gui_panel.png"))
HEXME = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "hexme")


def log(msg):
    sys.stdout.write("gui_panel: {}\n".format(msg))
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


def screenshot(name):
    path = os.path.splitext(SHOT)[0] + name + ".png"
    pump(0.5)
    check(QtGui.QGuiApplication.primaryScreen().grabWindow(0).save(path), "screenshot " + path)


def report_text(mw):
    """What FreeCAD's Report view shows."""
    pump(0.5)  # it shows messages a moment later
    for w in mw.findChildren(QtGui.QTextEdit):
        if "report" in w.objectName().lower():
            return w.toPlainText()
    raise AssertionError("no Report view found")


def button(mw, which):
    """The visible button of the task panel. PySide2 may hand back a stale wrapper for a
    closed panel's button (its C++ object deleted, its address reused): skip those, and
    look again once Qt has processed its pending deletions."""
    # Up to 5 s: once (in a full ctest run, after a Stop in the decomposition) the panel's
    # button was not found within the 1 s this allowed before.
    for attempt in range(25):
        for box in mw.findChildren(QtGui.QDialogButtonBox):
            try:
                b = box.button(which)
                if b is not None and b.isVisible():
                    return b
            except RuntimeError:  # "Internal C++ object ... already deleted"
                continue
        QtCore.QCoreApplication.sendPostedEvents(None, QtCore.QEvent.DeferredDelete)
        pump(0.2)
    seen = []
    for box in mw.findChildren(QtGui.QDialogButtonBox):
        try:
            seen.append(", ".join("{} visible={}".format(b.text(), b.isVisible())
                                  for b in box.buttons()) or "no buttons")
        except RuntimeError:
            seen.append("deleted")
    modal = QtGui.QApplication.activeModalWidget()
    log("no visible {} button; button boxes: [{}]; modal widget: {}".format(
        which, " | ".join(seen), modal.windowTitle() if modal else None))
    return None


class Ticker:
    """A QTimer every 50 ms; the largest gap between two ticks is how long the GUI froze."""

    def __init__(self):
        self.timer = QtCore.QTimer()
        self.timer.setInterval(50)
        self.timer.timeout.connect(self.tick)
        self.last, self.worst, self.ticks = None, 0.0, 0

    def start(self):
        self.last, self.worst, self.ticks = time.time(), 0.0, 0
        self.timer.start()

    def tick(self):
        now = time.time()
        if now - self.last > self.worst:
            self.worst, self.worst_at = now - self.last, now
        self.last, self.ticks = now, self.ticks + 1

    def stop(self):
        self.timer.stop()


def wait_until(cond, seconds):
    end = time.time() + seconds
    while not cond() and time.time() < end:
        QtGui.QApplication.processEvents()
        time.sleep(0.01)
    return cond()


def open_panel(mw, part):
    from VoroHexGui import commands

    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(part)
    pump(0.2)
    check(commands.HexMeshCommand().IsActive(), "Hex mesh active for " + part.Label)
    Gui.runCommand("VoroHex_HexMesh")
    pump(0.5)
    check(bool(Gui.Control.activeDialog()), "panel open for " + part.Label)
    from VoroHexGui import task_panel  # noqa: F401

    return [o for o in part.Document.Objects if getattr(o, "Part", None) == part and
            o.isDerivedFrom("Fem::FemMeshObjectPython")][-1]


def widgets_of(mw):
    find = mw.findChild
    return {"size": find(QtGui.QDoubleSpinBox, "sb_size"),
            "run": find(QtGui.QPushButton, "pb_run"),
            "stop": find(QtGui.QPushButton, "pb_stop"),
            "progress": find(QtGui.QProgressBar, "progress"),
            "estimate": find(QtGui.QLabel, "lbl_estimate"),
            "banner": find(QtGui.QLabel, "lbl_banner"),
            "status": find(QtGui.QLabel, "lbl_status"),
            "result": find(QtGui.QGroupBox, "gb_quality"),
            "order": find(QtGui.QComboBox, "cb_element_order"),
            "suggestion": find(QtGui.QPushButton, "pb_suggestion")}


def stop_in_stage(mw, mesh, stage, after, ticker, size=None, smoothing=None, shot=None):
    """Run through the buttons, wait until the progress names `stage` (and `after` s more;
    a screenshot `shot` then, if named), press Stop; returns (seconds from Stop to the end of the run, when Stop was pressed)."""
    w = widgets_of(mw)
    if size is not None:
        w["size"].setValue(size)
    before = (mesh.Status, mesh.HexCount)
    ticker.start()
    t0 = time.time()
    w["run"].click()
    check(w["stop"].isEnabled(), "Run started ({}); Stop enabled".format(mesh.Part.Label))
    check(wait_until(lambda: stage in w["progress"].format(), 60),
          "progress reached the {} stage: {}".format(stage, w["progress"].format()))
    pump(after)
    if shot:
        screenshot(shot)
    running = time.time() - t0
    check(w["stop"].isEnabled(), "still running after {:.1f} s".format(running))
    t_stop = time.time()
    w["stop"].click()
    ended = wait_until(lambda: w["run"].isEnabled(), 5)
    latency = time.time() - t_stop
    ticker.stop()
    check(ended and latency < 1.0, "Stop in stage {} ended the run in {:.2f} s".format(
        stage, latency))
    check(ticker.worst <= 0.3, "50 ms timer: largest gap {:.3f} s ({:.2f} s after Run) over "
          "{} ticks".format(ticker.worst, ticker.worst_at - t0, ticker.ticks))
    check((mesh.Status, mesh.HexCount) == before, "the previous result is kept")
    check("stopped" in w["progress"].format() and "Stopped by the user" in w["status"].text(),
          "the panel says it was stopped: " + w["status"].text())
    return latency, running


def main():
    import Part

    # What is measured is whether VoroHex's work holds the GUI thread, not whether other
    # processes of a busy machine (builds, other tests) take the processor from it: the GUI
    # goes ahead of them when the test may (as root; ctest runs it alone, RUN_SERIAL). The
    # meshing child runs 10 steps below the GUI either way.
    try:
        os.nice(-5)
    except (PermissionError, OSError):
        log("running at normal priority (not allowed to raise it)")

    mw = Gui.getMainWindow()
    mw.setGeometry(0, 0, 1280, 1024)
    mw.showMaximized()
    Gui.activateWorkbench("VoroHexWorkbench")
    pump()
    combo = [d for d in mw.findChildren(QtGui.QDockWidget) if d.isVisible()
             and d.objectName() in ("Combo View", "ComboView")]
    if combo:
        mw.resizeDocks(combo, [430], QtCore.Qt.Horizontal)
    pump(1.0)
    doc = FreeCAD.newDocument("PanelDemo")
    from VoroHexGui import commands, task_panel

    # Commands greyed out for what they cannot take.
    sketch = doc.addObject("Sketcher::SketchObject", "Sketch")
    sketch.addGeometry(Part.LineSegment(FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(10, 0, 0)))
    face = doc.addObject("Part::Feature", "AFace")
    face.Shape = Part.makePlane(10, 10)
    import Fem

    tets = Fem.FemMesh()
    for i, p in enumerate(((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)), 1):
        tets.addNode(*p, i)
    tets.addVolume([1, 2, 3, 4], 1)
    tet_mesh = doc.addObject("Fem::FemMeshObject", "TetMesh")
    tet_mesh.FemMesh = tets
    doc.recompute()
    for obj in (sketch, face, tet_mesh):
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(obj)
        pump(0.1)
        check(not any(c.IsActive() for c in (commands.HexMeshCommand(),
                                               commands.VoronoiGraphCommand(),
                                               commands.DecompositionCommand(),
                                               commands.MeshQualityCommand())),
              "all four commands greyed out for " + obj.TypeId)
    Gui.Selection.clearSelection()

    # The panel on a box: what shows first, the estimate, Run through the button.
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = 40, 20, 10
    other = doc.addObject("Part::Box", "OtherBox")
    doc.recompute()
    import VoroHexObjects

    idle = VoroHexObjects.makeHexMesh(doc, other, size=5)  # touched, never computed
    check(idle.Label == "OtherBox_HexMesh" and "Touched" in idle.State,
          "a mesh named after its part, not computed: " + idle.Label)
    mesh = open_panel(mw, box)
    check(mesh.Label == "Box_HexMesh", "the new mesh is named after its part: " + mesh.Label)
    w = widgets_of(mw)
    from VoroHexGui.widgets import Section

    sections = [s for s in mw.findChildren(Section) if s.isVisible()]
    check(len(sections) >= 5 and not any(s.isExpanded() for s in sections),
          "{} sections below the result, all collapsed".format(len(sections)))
    order = w["order"]
    if hasattr(mesh, "ElementOrder"):
        check(order.isEnabled() and order.currentText() == str(mesh.ElementOrder),
              "element order bound to ElementOrder")
    else:
        check(not order.isEnabled() and order.toolTip() == "second order: coming",
              "element order shown, disabled until ElementOrder exists")
    w["size"].setValue(2.5)
    pump(0.1)
    check("512" in w["estimate"].text(), "live estimate: " + w["estimate"].text())
    # Schemes (Advanced: limits): an unknown name is flagged and never stored; a valid
    # list is stored in the Schemes property by Run.
    schemes = mw.findChild(QtGui.QLineEdit, "le_schemes")
    schemes.setText("map, bogus")
    pump(0.1)
    check("bogus" in schemes.toolTip() and schemes.styleSheet() != "",
          "an unknown scheme is flagged: " + schemes.toolTip())
    schemes.setText("map, sweep, midpoint")
    pump(0.1)
    check(schemes.styleSheet() == "", "a valid list is not flagged")
    w["run"].click()
    check(wait_until(lambda: w["run"].isEnabled(), 30), "the box run ended")
    check(mesh.Status == "ok" and mesh.HexCount == 512, "box meshed: " + mesh.Message)
    check(mesh.Scheme == "map" and not w["banner"].isVisible(), "structured: no banner")
    check(mesh.Schemes == "map,sweep,midpoint", "the schemes stored: " + mesh.Schemes)
    check("Touched" in idle.State and idle.Status == "" and idle.HexCount == 0,
          "Run recomputed only the mesh being edited (the other is still untouched)")
    check("Touched" not in mesh.State, "the edited mesh is up to date (no recompute pending)")
    check(bool(Gui.Control.activeDialog()), "the panel is still open after Run")
    w = widgets_of(mw)
    from VoroHexGui import widgets

    area = widgets.scroll_area_of(w["result"])
    top = w["result"].mapTo(area.widget(), QtCore.QPoint(0, 0)).y()
    bar = area.verticalScrollBar()
    check(bar.value() <= top <= bar.value() + area.viewport().height(),
          "the result is scrolled into view")
    # Run again in the same panel with another size (the panel's own form stays usable
    # after a run: scrolling the result into view once took it away).
    w["size"].setValue(5)
    pump(0.1)
    w["run"].click()
    check(wait_until(lambda: w["run"].isEnabled(), 30), "the second run ended")
    check(mesh.Status == "ok" and mesh.HexCount == 64,
          "meshed again at size 5: {} hexahedra ({})".format(mesh.HexCount, mesh.Message))
    check("64 hexahedra" in w["status"].text(),
          "the panel shows the new result: " + w["status"].text())
    from VoroHexGui import palette
    from VoroHexGui.histogram import HistogramWidget, bin_colour

    hist = mw.findChild(HistogramWidget)
    fm = hist.fontMetrics()
    check(hist.plot_rect().left() > max(fm.horizontalAdvance(t) for t in hist.y_labels()),
          "the histogram's y labels fit left of the plot ({})".format(hist.y_labels()))
    check(all(bin_colour(-1 + 0.1 * k).getRgbF()[:3] == tuple(
        QtGui.QColor.fromRgbF(*palette.band_colour(-0.95 + 0.1 * k)).getRgbF()[:3])
        for k in range(20)), "histogram bars use the quality view's colour scale")
    for o in (sketch, face, other, tet_mesh, idle):
        o.ViewObject.Visibility = False
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    screenshot("")

    # A size whose predicted count exceeds the limit: refused before any work starts.
    big = doc.addObject("Part::Box", "Part90")
    big.Length, big.Width, big.Height = 90, 60, 30
    doc.recompute()
    # OK after a refused Run (the run stored its size): not closed with a size beside the
    # mesh another size made - OK runs that size, which is refused again, and the panel
    # stays open saying why.
    w["size"].setValue(0.0001)
    pump(0.1)
    w["run"].click()
    pump(0.2)
    check("refused" in w["progress"].format(), "size 0.0001 refused: " + w["progress"].format())
    button(mw, QtGui.QDialogButtonBox.Ok).click()
    pump(0.3)
    check(bool(Gui.Control.activeDialog()) and w["banner"].isVisible() and
          mesh.HexCount == 64, "OK after a refused Run keeps the panel open: " +
          w["banner"].text())
    # Cancel keeps the mesh with the options that made it: the last run's size (5), not a
    # size typed after it, nor the one the panel opened with.
    w["size"].setValue(4)
    pump(0.1)
    button(mw, QtGui.QDialogButtonBox.Cancel).click()
    pump(0.3)
    check(abs(mesh.TargetSize.Value - 5) < 1e-9 and mesh.HexCount == 64 and
          "Touched" not in mesh.State,
          "Cancel after a run kept its mesh and its size ({}, {} hexahedra)".format(
              mesh.TargetSize, mesh.HexCount))
    big_mesh = open_panel(mw, big)
    w = widgets_of(mw)
    w["size"].setValue(0.01)
    pump(0.1)
    check("over the limit" in w["estimate"].text(), "estimate flags it: " + w["estimate"].text())
    t0 = time.time()
    w["run"].click()
    pump(0.2)
    check(time.time() - t0 < 1.0 and w["run"].isEnabled() and not w["stop"].isEnabled(),
          "nothing started")
    text = w["banner"].text()
    check(w["banner"].isVisible() and "1.6e+11 hexahedra" in text and "50,000,000" in text,
          "size 0.01 on a 90 mm part refused with the count: " + text)
    check(big_mesh.Status == "" and big_mesh.HexCount == 0, "the mesh object is untouched")
    screenshot("_refused")
    # Cancel on a mesh never run removes it.
    name = big_mesh.Name
    button(mw, QtGui.QDialogButtonBox.Cancel).click()
    pump(0.3)
    check(doc.getObject(name) is None, "Cancel on a never-run mesh removed it")
    # A run that fails on a new mesh, then Cancel: the mesh object goes too (two boxes that
    # overlap in a compound are refused by the meshing job, not before it).
    a = doc.addObject("Part::Box", "OverlapA")
    b = doc.addObject("Part::Box", "OverlapB")
    b.Placement.Base = FreeCAD.Vector(5, 5, 5)
    both = doc.addObject("Part::Compound", "Overlapping")
    both.Links = [a, b]
    doc.recompute()
    failing = open_panel(mw, both)
    w = widgets_of(mw)
    w["run"].click()
    check(wait_until(lambda: w["run"].isEnabled(), 30), "the failing run ended")
    check(failing.Status == "error", "the overlapping boxes fail: " + failing.Message)
    check(failing.Message.startswith("cannot read the solid: The shape holds 2 solids") and
          list(failing.Diagnostics) == ["error [shape_error] " + failing.Message],
          "the message as said, and in the Messages list: {}".format(list(failing.Diagnostics)))
    name = failing.Name
    button(mw, QtGui.QDialogButtonBox.Cancel).click()
    pump(0.3)
    check(doc.getObject(name) is None, "Cancel after a failed first run removed the mesh")
    for o in (a, b, both):
        o.ViewObject.Visibility = False

    # A part that takes more than 10 s to mesh: the GUI never freezes; Stop within 1 s. A
    # long cylinder at size 0.38 is a sweep of about 1.9 million hexahedra (under the 2
    # million that Run asks about first): seconds of smoothing and checking on any machine,
    # whatever the schemes (the ski jump's fallback took 36 s once, and is a multisweep now).
    report_before = report_text(mw)
    ticker = Ticker()
    long_part = doc.addObject("Part::Cylinder", "LongCylinder")
    long_part.Radius, long_part.Height = 22, 70
    ski = doc.addObject("Part::Feature", "SkiJump")
    ski.Shape = Part.read(os.path.join(HEXME, "n03o_skijump_box_cyl.step"))
    # A 2 x 2 x 2 cube with a steep pyramid pit (1 x 1, 1.6 deep; too steep for the
    # multisweep's sloped caps, which take HexMe n06's pentagonal one now): seconds of
    # decomposition (OCCT's split of the pit's wedges).
    V = FreeCAD.Vector
    corners = [V(0, 0, 0), V(2, 0, 0), V(2, 2, 0), V(0, 2, 0), V(0, 0, 2), V(2, 0, 2),
               V(2, 2, 2), V(0, 2, 2), V(.5, .5, 2), V(1.5, .5, 2), V(1.5, 1.5, 2),
               V(.5, 1.5, 2), V(1, 1, 0.4)]
    polygons = [[0, 3, 2, 1], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7],
                [4, 5, 9, 8], [5, 6, 10, 9], [6, 7, 11, 10], [7, 4, 8, 11], [8, 9, 12],
                [9, 10, 12], [10, 11, 12], [11, 8, 12]]
    notch = doc.addObject("Part::Feature", "SteepPit")
    notch.Shape = Part.Solid(Part.Shell([
        Part.Face(Part.makePolygon([corners[i] for i in f] + [corners[f[0]]]))
        for f in polygons]))
    sphere = doc.addObject("Part::Feature", "Sphere")
    sphere.Shape = Part.read(os.path.join(HEXME, "s17o_sphere.step"))
    doc.recompute()
    for o in (box, other, sketch, face, notch, sphere, ski):
        o.ViewObject.Visibility = False
    long_mesh = open_panel(mw, long_part)
    ticker.start()
    pump(2.0)
    ticker.stop()
    log("baseline, nothing running: {} ticks in 2 s, largest gap {:.3f} s".format(
        ticker.ticks, ticker.worst))
    latency, running = stop_in_stage(mw, long_mesh, "", 10.2, ticker, size=0.38)
    check(running > 10.0, "the long cylinder was still meshing after {:.1f} s".format(running))
    said = report_text(mw)[len(report_before):]
    check("Traceback" not in said and "Recompute failed" not in said and
          "stopped by the user" in said, "Report view: a message, no traceback: " +
          said.strip().replace("\n", " | "))
    # Stop in each long stage: the smoothing of the long cylinder, the decomposition, the
    # grid mesher (the fallback's) and the smoothing of the sphere.
    stop_in_stage(mw, long_mesh, "smooth", 0.5, ticker, size=0.38)
    button(mw, QtGui.QDialogButtonBox.Cancel).click()
    pump(0.3)
    notch_mesh = open_panel(mw, notch)
    # The Voronoi decomposition's own step, named as it runs (its steps cross from its child
    # process: the bar showed "decompose 0%" for all of the decomposition before). The
    # steep pit's graph takes a few tenths of a second, then OCCT's split of the solid by its
    # decomposition faces about 3.5 s (it fails; the fallback's grid mesh, ready beside it,
    # is used): the screenshot is taken 0.5 s into that step. (HexMe i09, used here before,
    # left its decomposition step after 10 ms once a solid's bounding box stopped being
    # recomputed on every call: it stops at an open vertex gap before any split.)
    stop_in_stage(mw, notch_mesh, "decompose", 0.5, ticker, shot="_decompose")
    button(mw, QtGui.QDialogButtonBox.Cancel).click()
    pump(0.3)
    sphere_mesh = open_panel(mw, sphere)
    stop_in_stage(mw, sphere_mesh, "grid", 0.3, ticker, size=0.15)
    stop_in_stage(mw, sphere_mesh, "smooth", 0.3, ticker, size=0.15)
    said = report_text(mw)[len(report_before):]
    check("Traceback" not in said and "Recompute failed" not in said,
          "no traceback after four stops")
    button(mw, QtGui.QDialogButtonBox.Cancel).click()
    pump(0.3)

    # A fallback mesh: the banner; coarser sizes are tried for a structured mesh (none
    # for a sphere: its shape, not the size, is what no scheme accepts).
    sphere_mesh = open_panel(mw, sphere)
    w = widgets_of(mw)
    sphere.ViewObject.Visibility = True
    w["size"].setValue(1.6)
    ticker.start()
    w["run"].click()
    check(wait_until(lambda: w["run"].isEnabled(), 60), "the sphere meshed by the fallback")
    check(sphere_mesh.Status == "ok" and sphere_mesh.Scheme == "grid",
          "scheme {}: {}".format(sphere_mesh.Scheme, sphere_mesh.Message))
    check(w["banner"].isVisible() and "Not a structured mesh" in w["banner"].text(),
          "banner: " + w["banner"].text())
    check(wait_until(lambda: "Trying" not in w["banner"].text(), 40),
          "the sizes tried: " + w["banner"].text())
    ticker.stop()
    check(ticker.worst <= 0.3, "no freeze while meshing and trying sizes: largest gap "
          "{:.3f} s".format(ticker.worst))
    check("No coarser size" in w["banner"].text() and not w["suggestion"].isVisible(),
          "no size suggested for the sphere: " + w["banner"].text())
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    screenshot("_banner")
    button(mw, QtGui.QDialogButtonBox.Ok).click()
    pump(0.3)
    check(not Gui.Control.activeDialog(), "OK closed the panel (mesh up to date)")
    # The sizes the banner tries on the ski jump (HexMe n03, whose one-to-one sweep folds
    # at HexMe's size 0.094) find one that gives a structured mesh: the multisweep at the
    # first, a plain sweep at coarser ones.
    job = task_panel.suggestion_job(ski.Shape, {}, task_panel.trial_sizes(0.0944))
    check(job.wait(30), "the sizes tried in {:.1f} s".format(job.elapsed))
    found = job.result()
    check(found and found[0][1] in ("sweep", "multisweep"),
          "a size that gives a structured mesh: {}".format(found))

    # Mesh quality opens in under 1 s for 100,000 hexahedra.
    for o in doc.Objects:
        if o.ViewObject is not None:
            o.ViewObject.Visibility = False
    block = doc.addObject("Part::Box", "Block")
    block.Length, block.Width, block.Height = 40, 20, 10
    doc.recompute()
    big = VoroHexObjects.makeHexMesh(doc, block, size=0.43)
    big.SmoothIterations, big.SmoothPasses = 0, 0
    doc.recompute()
    check(big.Status == "ok" and big.HexCount > 100000, "{:,} hexahedra".format(big.HexCount))
    pump(1.0)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(big)
    check(commands.MeshQualityCommand().IsActive(), "Mesh quality active for a hex mesh")
    from VoroHexGui import quality_view

    t0 = time.time()
    Gui.runCommand("VoroHex_MeshQuality")
    opened = time.time() - t0
    QtGui.QApplication.processEvents()
    painted = time.time() - t0
    panel = quality_view.current
    check(panel is not None and opened < 1.0, "Mesh quality opened in {:.2f} s for {:,} "
          "hexahedra (first frame drawn at {:.2f} s)".format(opened, big.HexCount, painted))
    check(sum(int(panel.legend.item(r, 1).text()) for r in range(panel.legend.rowCount()))
          == big.HexCount, "its legend counts them all")
    button(mw, QtGui.QDialogButtonBox.Close).click()
    pump(0.3)
    check(quality_view.current is None and not Gui.Control.activeDialog(), "closed")


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
