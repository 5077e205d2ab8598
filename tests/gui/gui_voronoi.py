# GUI test, run by ctest under Xvfb (like gui_hexmesh.py):
#   xvfb-run -a -s "-screen 0 1280x1024x24" freecad gui_voronoi.py -M <stage>/VoroHex
# On an L-shaped extrusion: runs VoroHex_VoronoiGraph, checks that the legend and the
# object show as many edges per type as the Voronoi graph has, that every drawn segment is
# coloured by its type, that unchecking a type in the legend hides it, and saves a
# screenshot (VOROHEX_SCREENSHOT, default ./gui_voronoi_l.png). Exit code 0 = pass.
import os
import sys
import threading
import time
import traceback

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore, QtGui

TIMEOUT_S = 170  # CI budget; under a heavy load (other builds) this test took 120 s
SHOT = os.environ.get("VOROHEX_SCREENSHOT", os.path.abspath("gui_voronoi_l.png"))


def log(msg):
    sys.stdout.write("gui_voronoi: {}\n".format(msg))
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
    import Part

    mw = Gui.getMainWindow()
    mw.setGeometry(0, 0, 1280, 1024)
    mw.showMaximized()
    Gui.activateWorkbench("VoroHexWorkbench")
    pump()
    combo = [d for d in mw.findChildren(QtGui.QDockWidget) if d.isVisible()
             and d.objectName() in ("Combo View", "ComboView")]
    if combo:
        mw.resizeDocks(combo, [470], QtCore.Qt.Horizontal)
    pump(1.0)
    doc = FreeCAD.newDocument("VoronoiDemo")
    V = FreeCAD.Vector
    pts = [(0, 0), (40, 0), (40, 10), (10, 10), (10, 30), (0, 30), (0, 0)]
    l_shape = doc.addObject("Part::Feature", "L")
    l_shape.Shape = Part.Face(Part.makePolygon([V(x, y, 0) for x, y in pts])).extrude(
        V(0, 0, 30))
    doc.recompute()
    Gui.Selection.clearSelection()
    from VoroHexGui import commands

    check(not commands.VoronoiGraphCommand().IsActive(), "command inactive without selection")
    Gui.Selection.addSelection(l_shape)
    pump()
    check(commands.VoronoiGraphCommand().IsActive(), "command active with the L selected")
    Gui.runCommand("VoroHex_VoronoiGraph")
    check(commands.wait(60), "the graph was computed (in a child process)")
    pump(0.5)
    graphs = [o for o in doc.Objects if hasattr(o, "SegmentTypes")]
    check(len(graphs) == 1, "one Voronoi graph object created")
    g = graphs[0]
    check(g.isValid() and g.Status == "ok", "graph computed: " + g.Message)
    check(bool(Gui.Control.activeDialog()), "legend task panel open")

    import VoroHex
    import VoroHexGraph

    graph = VoroHex.voronoi_graph(l_shape)
    expected = graph.type_counts()
    table = mw.findChild(QtGui.QTableWidget, "tbl_edge_types")
    check(table is not None and table.rowCount() == len(VoroHexGraph.EDGE_TYPES),
          "legend lists every edge type")
    shown = {table.item(r, 0).text(): int(table.item(r, 1).text())
             for r in range(table.rowCount())}
    check(all(shown[t] == n for t, n in expected.items()) and sum(shown.values()) ==
          graph.counts["edges"], "legend counts per type equal the graph's {}".format(expected))
    drawn = {t: int(n) for t, n in g.ShownEdgeCounts.items()}
    with_lines = {}
    for e in graph.of_kind("edge"):
        if len(set(e["polyline"])) >= 2:
            with_lines[e["type"]] = with_lines.get(e["type"], 0) + 1
    check(drawn == with_lines, "edges drawn per type equal the graph's {}".format(drawn))
    colours = list(g.ViewObject.LineColorArray)
    check(len(colours) == len(g.Shape.Edges), "one colour per drawn segment")
    for c, t in zip(colours, g.SegmentTypes):
        want = VoroHexGraph.COLOURS[t]
        if max(abs(c[i] - want[i]) for i in range(3)) > 0.01:
            raise AssertionError("segment of type {} coloured {}".format(t, c))
    log("ok: every segment coloured by its type")

    l_shape.ViewObject.Transparency = 80
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    pump(0.5)
    view.fitAll()
    pump(0.5)
    os.makedirs(os.path.dirname(SHOT) or ".", exist_ok=True)
    check(QtGui.QGuiApplication.primaryScreen().grabWindow(0).save(SHOT),
          "screenshot saved to " + SHOT)

    fs = mw.findChild(QtGui.QCheckBox, "cb_fs_faces")
    check(fs is not None and fs.isChecked() and g.FsFacesDrawn == g.FsFaceCount > 0
          and not g.FsFacesNotDrawn
          and "{} of {}".format(g.FsFaceCount, g.FsFaceCount) in fs.text(),
          "all f_s faces drawn ({})".format(fs.text() if fs else None))
    check(len(g.FsFaceTriangles) > 0 and len(g.FsFaceTriangles) % 3 == 0 and
          max(g.FsFaceTriangles) < len(g.FsFacePoints),
          "as {} triangles".format(len(g.FsFaceTriangles) // 3))
    # Faces, not outlines: nothing of them is in the Shape (whose edges and vertices the view
    # draws as lines and points); a Coin node of their own draws the triangles translucent.
    check(not g.Shape.Faces and "f_s" not in g.SegmentTypes,
          "no f_s outlines or point markers in the shape")
    vp = g.ViewObject.Proxy
    check(vp.fs_faces.coordIndex.getNum() == 4 * len(g.FsFaceTriangles) // 3 and
          vp.fs_material.transparency[0] > 0.3 and vp.fs_switch.whichChild.getValue() == 0,
          "the view draws them translucent")
    check(l_shape.ViewObject.Transparency >= 70 and l_shape.ViewObject.Visibility,
          "the solid fades under the graph")
    # Unchecking [C] in the legend hides its edges.
    row = [r for r in range(table.rowCount()) if table.item(r, 0).text() == "[C]"][0]
    table.item(row, 0).setCheckState(QtCore.Qt.Unchecked)
    pump(0.5)
    check("[C]" not in g.ShownTypes and "[C]" not in g.SegmentTypes, "[C] edges hidden")
    check(len(g.ViewObject.LineColorArray) == len(g.Shape.Edges), "colours follow the shape")
    close = None
    for box in mw.findChildren(QtGui.QDialogButtonBox):
        b = box.button(QtGui.QDialogButtonBox.Close)
        if b is not None and b.isVisible():
            close = b
    check(close is not None, "legend has a Close button")
    close.click()
    pump(0.3)
    check(not Gui.Control.activeDialog(), "legend closed")
    check(l_shape.ViewObject.Transparency == 0, "the solid is back (opaque) after close")
    g.ViewObject.Visibility = False

    # The decomposition of the same L: three sub-volumes when not merged, coloured by scheme.
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(l_shape)
    pump()
    check(commands.DecompositionCommand().IsActive(), "decomposition command active")
    Gui.runCommand("VoroHex_Decomposition")
    check(commands.wait(60), "the decomposition was computed (in a child process)")
    pump(0.5)
    parts = [o for o in doc.Objects if hasattr(o, "SubVolumeObjects")]
    check(len(parts) == 1 and parts[0].Status in ("ok", "partial"), "decomposition computed")
    d = parts[0]
    # As the mesher (the command's method): the L is a sweep whole, not cut.
    check(d.Method == "As the mesher" and d.MethodUsed.startswith("Not cut") and
          d.SubVolumeCount == 1 and list(d.Schemes) == ["sweep"],
          "as the mesher: the L is one sweep, not cut: " + d.Message)
    close_panel(mw)
    d.Method = "Voronoi graph"
    doc.recompute()
    pump(0.5)
    check(d.MethodUsed == "Cut along its Voronoi graph" and d.SubVolumeCount == 1 and
          d.SubVolumesBeforeMerge == 3 and list(d.Schemes) == ["sweep"],
          "along its Voronoi graph, merged: the L is one sweep: " + d.Message)
    d.Merge = False
    doc.recompute()
    pump(0.5)
    check(d.SubVolumeCount == 3 and d.DecompositionFaceCount == 2,
          "not merged: 3 sub-volumes, 2 decomposition faces")
    import VoroHexParts

    children = list(d.SubVolumeObjects)
    check(len(children) == 3 and all(c.Shape.Solids for c in children) and
          sorted(d.ViewObject.Proxy.claimChildren(), key=lambda c: c.Name) ==
          sorted(children, key=lambda c: c.Name), "each sub-volume its own child object")
    roles_seen = set()
    for child in children:
        colours = list(child.ViewObject.DiffuseColor)
        check(len(colours) == len(child.Shape.Faces) == len(child.FaceRoles),
              "{}: one colour per face".format(child.Label))
        for c, role in zip(colours, child.FaceRoles):
            want = VoroHexParts.COLOURS[role]
            roles_seen.add(role)
            if max(abs(c[i] - want[i]) for i in range(3)) > 0.01:
                raise AssertionError("face of role {} coloured {}".format(role, c))
    check({"decomposition", "map", "sweep", "source/target"} <= roles_seen,
          "every face coloured by its role: " + ", ".join(sorted(roles_seen)))
    check(d.ViewObject.DisplayMode == "Sub-volumes", "the compound itself draws nothing twice")
    children[0].ViewObject.Visibility = False
    pump(0.2)
    check(not children[0].ViewObject.Visibility and children[1].ViewObject.Visibility,
          "a sub-volume hides on its own")
    children[0].ViewObject.Visibility = True
    Gui.ActiveDocument.setEdit(d.Name)
    pump(0.5)
    check(l_shape.ViewObject.DisplayMode == "Wireframe", "the solid fades to its edges")
    table = mw.findChild(QtGui.QTableWidget, "tbl_sub_volumes")
    check(table is not None and table.rowCount() == 3, "sub-volume table has 3 rows")
    pump(0.3)
    check(table.cut_cells() == [], "every reason whole in its cell (wrapped): {}".format(
        table.cut_cells()))
    table.selectRow(1)
    pump(0.3)
    sel = Gui.Selection.getSelection()
    check(len(sel) == 1 and sel[0] == children[1], "selecting a row selects that sub-volume")
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(children[2], "Face1")  # as a pick in the 3D view does
    pump(0.3)
    rows = sorted({i.row() for i in table.selectedItems()})
    check(rows == [2], "a pick of a sub-volume selects its row: {}".format(rows))
    explode = mw.findChild(QtGui.QSlider, "sl_explode")
    centre = children[0].Shape.BoundBox.Center
    explode.setValue(50)
    pump(0.3)
    moved = children[0].Placement.Base.Length
    check(d.Explode == 1.0 and moved > 1.0, "Explode moves the sub-volumes apart ({:.1f} mm)"
          .format(moved))
    legend = mw.findChild(QtGui.QTableWidget, "tbl_roles")
    check(legend is not None and legend.verticalScrollBar().maximum() == 0,
          "the role legend shows all its rows")
    # (The role names' column is sized to its contents; the meanings' column wraps.)
    cut = [cell for cell in legend.cut_cells() if cell[1] == 1]
    check(not cut, "no meaning in the role legend is cut: rows {}".format(cut))
    del centre
    Gui.Selection.clearSelection()
    table.clearSelection()
    l_shape.ViewObject.Visibility = False
    screenshot(view, "gui_decomposition_l")
    # How to cut, chosen in the panel: computed in a child process (its progress dialog),
    # then shown in the panel and the object; back to the Voronoi graph's.
    method = mw.findChild(QtGui.QComboBox, "cb_method")
    check(method is not None and method.currentText() == "Voronoi graph",
          "the panel's Cut chooser shows the object's Method")
    for index, label, rows in ((0, "As the mesher", 1), (1, "Voronoi graph", 3)):
        method.setCurrentIndex(index)
        method.activated.emit(index)
        check(commands.wait(60), "the decomposition was computed again (in a child process)")
        pump(0.5)
        check(d.Method == label and table.rowCount() == rows == d.SubVolumeCount and
              summary_text(mw) == d.Message,
              "Cut: {}: {} row(s), the panel's summary is the object's: {}".format(
                  label, table.rowCount(), d.Message))
    check(d.MethodUsed == "Cut along its Voronoi graph", "back to the Voronoi graph's cut")
    children = list(d.SubVolumeObjects)
    close_panel(mw)
    check(not Gui.Control.activeDialog(), "decomposition panel closed")
    check(l_shape.ViewObject.DisplayMode != "Wireframe" and not Gui.Selection.getSelection(),
          "the solid is back and the selection cleared after close")
    explode_back = d.Explode
    d.Explode = 0.0
    check(explode_back == 1.0 and children[0].Placement.Base.Length < 1e-9,
          "Explode 0 puts them back")
    d.ViewObject.Visibility = False

    # The hex mesh panel holds the whole pipeline: its graph and decomposition options go
    # to the preview, whose edge-type legend counts and toggles types; then Run meshes.
    import VoroHexObjects

    lmesh = VoroHexObjects.makeHexMesh(doc, l_shape, "LMesh", size=2.5)
    Gui.ActiveDocument.setEdit(lmesh.Name)
    pump(1.0)
    from VoroHexGui.widgets import Section

    for name in ("sec_graph", "sec_decomposition", "sec_smoothing", "sec_check"):
        section = mw.findChild(Section, name)
        check(section is not None and not section.isExpanded(), "collapsed section " + name)
        section.setExpanded(True)
    mw.findChild(QtGui.QLineEdit, "le_eps").setText("0.02")
    mw.findChild(QtGui.QDoubleSpinBox, "sb_sharp_angle").setValue(50)
    before = set(o.Name for o in doc.Objects)
    mw.findChild(QtGui.QPushButton, "pb_preview").click()
    check(commands.wait(60), "the preview was computed")
    pump(0.3)
    made = [o for o in doc.Objects if o.Name not in before and hasattr(o, "Proxy")]
    pg = [o for o in made if hasattr(o, "SegmentTypes")]
    check(len(pg) == 1 and len(made) == 2, "Preview made a graph and a decomposition")
    pg = pg[0]
    check((pg.Eps, pg.SharpAngle, lmesh.Eps, lmesh.SharpAngle) == (0.02, 50, 0.02, 50),
          "the panel's eps and sharp angle went to the mesh object and the preview")
    expected = VoroHex.voronoi_graph(l_shape, eps=0.02, sharp_angle=50).type_counts()
    legend = mw.findChild(QtGui.QTableWidget, "tbl_preview_edge_types")
    check(legend is not None and legend.isVisible(), "the panel shows the preview's legend")
    counts = {legend.item(r, 0).text(): int(legend.item(r, 1).text())
              for r in range(legend.rowCount())}
    check(all(counts[t] == n for t, n in expected.items())
          and sum(counts.values()) == sum(expected.values()),
          "its counts per type equal the graph's {}".format(expected))
    row = [r for r in range(legend.rowCount()) if legend.item(r, 0).text() == "[C]"][0]
    legend.item(row, 0).setCheckState(QtCore.Qt.Unchecked)
    pump(0.5)
    check("[C]" not in pg.ShownTypes and "[C]" not in pg.SegmentTypes,
          "unchecking [C] in the panel hides the preview's [C] edges")
    run_button = mw.findChild(QtGui.QPushButton, "pb_run")
    run_button.click()
    end = time.time() + 60
    while not run_button.isEnabled() and time.time() < end:
        pump(0.05)
    check(lmesh.Status == "ok", "Run meshed the L: " + lmesh.Message)
    sv = mw.findChild(QtGui.QTableWidget, "tw_sub_volumes")
    check(sv.rowCount() == 1 and sv.item(0, 1).text() == "Vs" and sv.item(0, 2).text() == "sweep",
          "sub-volume table: one Vs swept")
    for o in made:
        o.ViewObject.Visibility = o in (pg,)
    lmesh.ViewObject.Visibility = False
    l_shape.ViewObject.Visibility = True
    l_shape.ViewObject.Transparency = 80
    view.viewIsometric()
    view.fitAll()
    for area in mw.findChildren(QtGui.QScrollArea):
        if area.isVisible() and area.widget() and area.widget().findChild(
                QtGui.QTableWidget, "tbl_preview_edge_types"):
            area.ensureWidgetVisible(legend)
    pump(1.0)
    pipeline_shot = SHOT.replace("gui_voronoi_l", "gui_pipeline_l")
    check(QtGui.QGuiApplication.primaryScreen().grabWindow(0).save(pipeline_shot),
          "screenshot saved to " + pipeline_shot)
    for box in mw.findChildren(QtGui.QDialogButtonBox):
        b = box.button(QtGui.QDialogButtonBox.Ok)
        if b is not None and b.isVisible():
            b.click()
    pump(0.3)
    check(not Gui.Control.activeDialog(), "mesh panel closed with OK")
    for o in made + [l_shape]:
        o.ViewObject.Visibility = False

    # Mesh quality of a sphere meshed by the fallback (a varied quality to look at).

    sphere = doc.addObject("Part::Sphere", "Sphere")
    sphere.Radius = 10
    sphere.Placement.Base = V(70, 0, 0)
    doc.recompute()
    mesh = VoroHexObjects.makeHexMesh(doc, sphere, size=2.5)
    doc.recompute()
    check(mesh.Status == "ok" and mesh.Scheme == "grid", "sphere meshed: " + mesh.Message)
    sphere.ViewObject.Visibility = False
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(mesh)
    pump()
    check(commands.MeshQualityCommand().IsActive(), "mesh quality command active")
    Gui.runCommand("VoroHex_MeshQuality")
    pump(0.5)
    check(bool(Gui.Control.activeDialog()), "quality panel open")
    from VoroHexGui import quality_view

    panel = quality_view.current
    check(panel is not None and len(panel.colours) == mesh.HexCount
          and set(panel.colours) == set(mesh.FemMesh.Volumes), "every hexahedron coloured")
    bands = mw.findChild(QtGui.QTableWidget, "tbl_quality_bands")
    total = sum(int(bands.item(r, 1).text()) for r in range(bands.rowCount()))
    check(total == mesh.HexCount, "legend counts all {} hexahedra".format(total))
    threshold = mw.findChild(QtGui.QDoubleSpinBox, "sb_worst_threshold")
    # (The grid mesher's sphere has no hex below 0.5, the smoothing's target: the pillow
    # layer's hexes, 0.5 to 0.7, are the ones to highlight.)
    threshold.setValue(0.7)
    mw.findChild(QtGui.QPushButton, "pb_highlight_worst").click()
    pump(0.3)
    import VoroHex

    sj = VoroHex.element_quality(mesh)
    below = [e for e, v in sj.items() if v < 0.7]
    check(len(below) > 0 and len(mesh.ViewObject.HighlightedNodes) > 0,
          "{} hexahedra below 0.7 highlighted".format(len(below)))
    check(abs(min(sj.values()) - mesh.MinScaledJacobian) < 1e-6,
          "colours from the same values as the object's minimum")
    Gui.Selection.clearSelection()
    screenshot(view, "gui_quality_sphere")
    close_panel(mw)
    check(not Gui.Control.activeDialog() and quality_view.current is None
          and not panel.colours, "quality panel closed, colours reset")
    mesh.ViewObject.Visibility = False

    # The paper's Figure 6 part as its caption describes it: a hexagonal ring whose six
    # walls (the "main faces") meet in six corners, with six triangular protrusions, each
    # a thin region holding an f_s face. Its graph, with the counts per type; its mesh.
    figure6 = doc.addObject("Part::Feature", "Figure6Part")
    from TestVoroHex import figure6_shape  # the same part as the Python tests (staged)

    figure6.Shape = figure6_shape()
    doc.recompute()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(figure6)
    pump()
    Gui.runCommand("VoroHex_VoronoiGraph")
    check(commands.wait(60), "the graph was computed (in a child process)")
    pump(0.5)
    g6 = [o for o in doc.Objects if hasattr(o, "SegmentTypes") and o.Part == figure6]
    check(len(g6) == 1 and g6[0].Status == "ok", "Figure 6 part: graph computed")
    graph6 = VoroHex.voronoi_graph(figure6)
    table = mw.findChild(QtGui.QTableWidget, "tbl_edge_types")
    shown = {table.item(r, 0).text(): int(table.item(r, 1).text())
             for r in range(table.rowCount())}
    expected6 = graph6.type_counts()
    check(all(shown[t] == n for t, n in expected6.items()) and sum(shown.values()) ==
          graph6.counts["edges"], "Figure 6 part: legend counts equal the graph's {}".format(
              expected6))
    check(graph6.counts["f_s"] >= 6 + 6,
          "f_s faces in the six walls and six protrusions ({})".format(
              graph6.counts["f_s"]))
    figure6.ViewObject.Transparency = 80
    screenshot(view, "gui_voronoi_figure6")
    close_panel(mw)
    g6[0].ViewObject.Visibility = False
    # Cancel during a long command: the busy dialog's Cancel stops it, the GUI stays
    # responsive (the timer that presses Cancel fires meanwhile) and the document is as it
    # was. The part: Figure 6's with a cross hole through two corners, which no scheme takes
    # whole and the plane cuts do not cut (24 surfaces), so the decomposition as the mesher
    # does it is the Voronoi graph's (about 20 s; Figure 6's own is one sweep at once).
    holed = doc.addObject("Part::Feature", "Figure6Holed")
    holed.Shape = figure6_shape().cut(Part.makeCylinder(0.3, 14, FreeCAD.Vector(-7, 0, 1.5),
                                                        FreeCAD.Vector(1, 0, 0)))
    holed.ViewObject.Visibility = False
    doc.recompute()
    names_before = sorted(o.Name for o in doc.Objects)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(holed)
    pump()
    pressed = []

    def press_cancel():
        for dialog in mw.findChildren(QtGui.QProgressDialog, "vorohex_busy"):
            if dialog.isVisible():
                for button in dialog.findChildren(QtGui.QPushButton):
                    pressed.append(time.time())
                    button.click()

    QtCore.QTimer.singleShot(1200, press_cancel)
    report_before = report_text(mw)
    t0 = time.time()
    Gui.runCommand("VoroHex_Decomposition")
    check(commands.wait(60), "the decomposition was computed (in a child process)")
    commands.wait(60)
    done = time.time()
    pump(0.5)
    said = report_text(mw)[len(report_before):]
    check("cancelled" in said and "Traceback" not in said and "Exception" not in said,
          "the Report view says it was cancelled, with no traceback: " + repr(said.strip()))
    check(bool(pressed) and done - pressed[0] < 1.0,
          "Cancel pressed in the busy dialog {:.1f} s into the run, which ended {:.2f} s "
          "later".format(pressed[0] - t0 if pressed else -1, done - pressed[0] if pressed else -1))
    check(sorted(o.Name for o in doc.Objects) == names_before and not Gui.Control.activeDialog(),
          "cancelled: the document is as it was, no panel open")
    mesh6 = VoroHexObjects.makeHexMesh(doc, figure6, "Figure6Mesh", size=0.5)
    doc.recompute()
    check(mesh6.Status == "ok" and mesh6.MinScaledJacobianBeforeSmoothing >= 0.3,
          "Figure 6 part meshed ({}, min scaled Jacobian {:.3f})".format(
              mesh6.Scheme, mesh6.MinScaledJacobianBeforeSmoothing))
    figure6.ViewObject.Visibility = False
    screenshot(view, "gui_hexmesh_figure6")
    # Its mesh quality: every hexahedron coloured, the legend counts them all.
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(mesh6)
    pump()
    Gui.runCommand("VoroHex_MeshQuality")
    pump(0.5)
    bands = mw.findChild(QtGui.QTableWidget, "tbl_quality_bands")
    total = sum(int(bands.item(r, 1).text()) for r in range(bands.rowCount()))
    check(total == mesh6.HexCount, "Figure 6 part: the quality legend counts all {} "
          "hexahedra".format(total))
    screenshot(view, "gui_quality_figure6")
    close_panel(mw)
    mesh6.ViewObject.Visibility = False
    # The Decomposition command run to the end on this part (long enough for its busy
    # dialog: closing that dialog once took the finished run for a cancelled one and threw
    # the object away): what it gives, in its panel. Merged, the prism is one sweep; not
    # merged, the walls, corners and protrusions the Voronoi graph cut apart.
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(figure6)
    pump()
    Gui.runCommand("VoroHex_Decomposition")  # about 2.5 s: its busy dialog appears
    check(commands.wait(60), "the decomposition was computed (in a child process)")
    pump(0.5)
    d6 = [o for o in doc.Objects if hasattr(o, "SubVolumeObjects") and o.Part == figure6]
    check(len(d6) == 1 and d6[0].Status == "ok" and list(d6[0].Schemes) == ["sweep"],
          "Figure 6 part: as the mesher, one sweep: " + (d6[0].Message if d6 else "?"))
    summary = mw.findChild(QtGui.QLabel, "lbl_parts_summary")
    check(summary is not None and summary.text() == d6[0].Message, "and its panel shows it")
    close_panel(mw)
    d6[0].Method = "Voronoi graph"
    doc.recompute()
    pump(0.5)
    check(d6[0].Status == "ok" and list(d6[0].Schemes) == ["sweep"] and
          d6[0].SubVolumesBeforeMerge >= 12,
          "Figure 6 part: along its Voronoi graph, cut, then merged into one sweep: " +
          d6[0].Message)
    d6[0].Merge = False
    doc.recompute()
    pump(0.5)
    check(d6[0].SubVolumeCount == d6[0].SubVolumesBeforeMerge and
          len(d6[0].Shape.Solids) == d6[0].SubVolumeCount,
          "not merged: the cut's {} sub-volumes ({})".format(d6[0].SubVolumeCount,
                                                             d6[0].Message))
    Gui.ActiveDocument.setEdit(d6[0].Name)
    pump(0.5)
    figure6.ViewObject.Visibility = False  # the decomposition's faces, not the solid's
    screenshot(view, "gui_decomposition_figure6")
    close_panel(mw)


def summary_text(mw):
    """The decomposition panel's summary line."""
    label = mw.findChild(QtGui.QLabel, "lbl_parts_summary")
    return label.text() if label is not None else None


def report_text(mw):
    """What FreeCAD's Report view shows."""
    for w in mw.findChildren(QtGui.QTextEdit):
        if "report" in w.objectName().lower():
            return w.toPlainText()
    raise AssertionError("no Report view found")


def screenshot(view, name):
    """The whole window, isometric and fitted, as SHOT's folder/<name>.png."""
    view.viewIsometric()
    view.fitAll()
    pump(0.5)
    path = SHOT.replace("gui_voronoi_l", name)
    check(QtGui.QGuiApplication.primaryScreen().grabWindow(0).save(path),
          "screenshot saved to " + path)


def close_panel(mw):
    for box in mw.findChildren(QtGui.QDialogButtonBox):
        b = box.button(QtGui.QDialogButtonBox.Close)
        if b is not None and b.isVisible():
            b.click()
            pump(0.3)
            return


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
