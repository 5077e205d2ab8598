# The "Hex mesh" command: one Part feature selected -> a VoroHex mesh object (added to the
# active FEM analysis if there is one, as FEM's own mesh commands do) and its task panel.
import time

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

import VoroHexGui
import VoroHexObjects


def is_solid(obj):
    """True for a document object whose shape holds a solid (cheap: IsActive asks often)."""
    if obj is None or not obj.isDerivedFrom("Part::Feature"):
        return False
    shape = obj.Shape
    return not shape.isNull() and shape.ShapeType in ("Solid", "CompSolid", "Compound") and \
        len(shape.Solids) > 0


def selected_part():
    """The single selected object holding a solid, or None (a sketch, a mesh, a face...)."""
    if FreeCADGui.ActiveDocument is None:
        return None
    sel = FreeCADGui.Selection.getSelection()
    if len(sel) == 1 and is_solid(sel[0]):
        return sel[0]
    return None


def active_analysis():
    try:
        import FemGui
    except ImportError:
        return None
    return FemGui.getActiveAnalysis()


class HexMeshCommand:
    def GetResources(self):
        return {
            "Pixmap": VoroHexGui.resource("icons", "VoroHex.svg"),
            "MenuText": "Hex mesh",
            "ToolTip": "All-hexahedral FEM mesh of the selected solid (VoroHex)",
        }

    def IsActive(self):
        return selected_part() is not None

    def Activated(self):
        part = selected_part()
        error = VoroHexObjects.source_error(part, True)
        if error is not None:
            FreeCAD.Console.PrintError("VoroHex: {}\n".format(error))
            QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), "VoroHex: cannot mesh", error)
            return
        doc = part.Document
        doc.openTransaction("Hex mesh")
        FreeCADGui.addModule("VoroHexObjects")
        FreeCADGui.doCommand(
            "_hexmesh = VoroHexObjects.makeHexMesh(FreeCAD.getDocument('{}'), "
            "FreeCAD.getDocument('{}').getObject('{}'))".format(doc.Name, doc.Name, part.Name))
        if active_analysis() is not None:
            FreeCADGui.addModule("FemGui")
            FreeCADGui.doCommand("FemGui.getActiveAnalysis().addObject(_hexmesh)")
        doc.commitTransaction()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.doCommand(
            "FreeCADGui.getDocument('{}').setEdit(_hexmesh.Name)".format(doc.Name))


class Progress:
    """A progress dialog for a job of the graph or decomposition commands (shown after half
    a second; its Cancel stops the job at once). The GUI stays live: the job runs in a
    child process and a timer polls it."""

    def __init__(self, text):
        self.text, self.dialog, self.started = text, None, time.time()

    def update(self, job):
        if self.dialog is None and time.time() - self.started > 0.5:
            self.dialog = QtGui.QProgressDialog(self.text, "Cancel", 0, 100,
                                                FreeCADGui.getMainWindow())
            self.dialog.setObjectName("vorohex_busy")
            self.dialog.setWindowTitle("VoroHex")
            self.dialog.setWindowModality(QtCore.Qt.WindowModal)
            self.dialog.setAutoClose(False)
            self.dialog.setAutoReset(False)
            self.dialog.canceled.connect(job.cancel)
            self.dialog.show()
        if self.dialog is not None:
            self.dialog.setLabelText("{}\n{} ({:.1f} s)".format(self.text, job.stage,
                                                                job.elapsed))
            self.dialog.setValue(int(100 * max(0.0, min(1.0, job.fraction))))

    def close(self):
        if self.dialog is not None:
            # Closing a QProgressDialog emits `canceled`: disconnect first.
            self.dialog.canceled.disconnect()
            self.dialog.close()
            self.dialog.deleteLater()
            self.dialog = None


# The jobs running now (tests and scripts wait for them: VoroHexGui.commands.wait()).
RUNNING = []


def start(label, work, args, on_done):
    """Runs work(report, *args) (a module-level function) in a child process with a
    Progress dialog; on_done(value, error) follows on the GUI thread: error is None,
    "cancelled", or why it failed."""
    import VoroHexJobs
    from VoroHexGui import widgets

    progress = Progress("{}...".format(label))

    def done(job):
        progress.close()
        if runner in RUNNING:
            RUNNING.remove(runner)
        try:
            value = job.result()
        except VoroHexJobs.Cancelled:
            FreeCAD.Console.PrintMessage("VoroHex: {} cancelled\n".format(label))
            on_done(None, "cancelled")
            return
        except RuntimeError as e:
            why = str(e).strip().splitlines()[-1] if str(e).strip() else "failed"
            FreeCAD.Console.PrintError("VoroHex: {}: {}\n".format(label, why))
            on_done(None, why)
            return
        on_done(value, None)

    runner = widgets.JobRunner(VoroHexJobs.Job(work, *args), progress.update, done,
                               parent=FreeCADGui.getMainWindow())
    RUNNING.append(runner)
    return runner


def wait(seconds=None):
    """Processes events until no job of these commands runs (scripts, tests)."""
    end = None if seconds is None else time.time() + seconds
    while RUNNING and (end is None or time.time() < end):
        QtGui.QApplication.processEvents()
        time.sleep(0.01)
    return not RUNNING


def make_object(doc, label, make):
    """make() in one transaction; an error leaves the document as it was."""
    doc.openTransaction(label)
    try:
        obj = make()
    except Exception as e:
        doc.abortTransaction()
        FreeCAD.Console.PrintError("VoroHex: {}: {}\n".format(label, e))
        return None
    doc.commitTransaction()
    return obj


def make_and_edit(part, label, module, factory, work, args):
    """Computes `work(report, brep, *args)` in a child process, then `module.factory(doc,
    part, data=...)` and the new object's task panel; a message if `part` is no solid."""
    error = VoroHexObjects.source_error(part)
    if error is not None:
        FreeCAD.Console.PrintError("VoroHex: {}\n".format(error))
        QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), "VoroHex: " + label, error)
        return None
    doc = part.Document
    import importlib

    factory = getattr(importlib.import_module(module), factory)

    def done(data, why):
        if data is None or doc.getObject(part.Name) is None:
            return
        obj = make_object(doc, label, lambda: factory(doc, part, data=data))
        if obj is None:
            return
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.getDocument(doc.Name).setEdit(obj.Name)

    return start(label, work, (part.Shape.exportBrepToString(),) + tuple(args), done)


def make_preview(mesh_obj, part, options, on_done):
    """The Voronoi graph and the decomposition of `part` with `options` (sharp_angle, eps,
    delta, max_depth; the decomposition's sub-volumes judged by the mesh's Schemes), computed
    in one child process, as document objects replacing the previous preview of `mesh_obj`;
    on_done((graph, decomposition) or None, error)."""
    import VoroHexGraph
    import VoroHexParts

    doc = part.Document
    graph_options = dict(options)
    angle = graph_options.pop("sharp_angle")
    schemes = getattr(mesh_obj, "Schemes", "")  # empty: every scheme

    def done(data, why):
        if data is None:
            on_done(None, "Preview cancelled." if why == "cancelled" else why)
            return

        def make():
            remove_preview(mesh_obj)
            g = VoroHexGraph.makeVoronoiGraph(doc, part, data=data[0], **options)
            p = VoroHexParts.makeDecomposition(doc, part, data=data[1], schemes=schemes,
                                               **options)
            mesh_obj.PreviewObjects = [g.Name, p.Name]
            return g, p

        made = make_object(doc, "VoroHex preview", make)
        if made is not None:
            for o in made:
                o.ViewObject.Visibility = True
            if part.ViewObject is not None:
                part.ViewObject.Transparency = 70
        on_done(made, None if made else "the preview failed (see the Report view)")

    return start("Preview", VoroHexObjects.preview_work,
                 (part.Shape.exportBrepToString(), angle, graph_options, schemes), done)


def remove_preview(mesh_obj):
    """Removes the graph and decomposition a previous Preview of `mesh_obj` made."""
    import VoroHexParts

    doc = mesh_obj.Document
    for name in list(getattr(mesh_obj, "PreviewObjects", [])):
        obj = doc.getObject(name)
        if obj is None:
            continue
        if hasattr(obj, "SubVolumeObjects"):
            VoroHexParts.remove(obj)
        else:
            doc.removeObject(name)
    mesh_obj.PreviewObjects = []


class VoronoiGraphCommand:
    def GetResources(self):
        return {
            "Pixmap": VoroHexGui.resource("icons", "VoroHexGraph.svg"),
            "MenuText": "Voronoi graph",
            "ToolTip": "The embedded Voronoi graph of the selected solid, its edges coloured "
                       "by type, with a legend (why the solid is cut where it is)",
        }

    def IsActive(self):
        return selected_part() is not None

    def Activated(self):
        import VoroHexGraph

        make_and_edit(selected_part(), "Voronoi graph", "VoroHexGraph", "makeVoronoiGraph",
                      VoroHexGraph.compute_work, (60.0, {}))


class DecompositionCommand:
    def GetResources(self):
        return {
            "Pixmap": VoroHexGui.resource("icons", "VoroHexParts.svg"),
            "MenuText": "Decomposition",
            "ToolTip": "Cut the selected solid into sweepable and mappable sub-volumes as the "
                       "hex mesher does (along the faces at its concave edges, else along its "
                       "Voronoi graph); faces coloured by scheme, decomposition faces marked",
        }

    def IsActive(self):
        return selected_part() is not None

    def Activated(self):
        import VoroHexParts

        make_and_edit(selected_part(), "Decomposition", "VoroHexParts", "makeDecomposition",
                      VoroHexParts.compute_work,
                      (60.0, True, {}, VoroHexParts.VoroHex.DECOMPOSITION_TIME_LIMIT, "auto"))


def is_hex_mesh(obj):
    """True for a FEM mesh object whose volumes are all hexahedra (not a tetrahedral mesh)."""
    if obj is None or not obj.isDerivedFrom("Fem::FemMeshObject"):
        return False
    fm = obj.FemMesh
    return fm.VolumeCount > 0 and fm.HexaCount == fm.VolumeCount


def selected_fem_mesh():
    """The single selected FEM mesh object holding hexahedra only, or None."""
    if FreeCADGui.ActiveDocument is None:
        return None
    sel = FreeCADGui.Selection.getSelection()
    if len(sel) == 1 and is_hex_mesh(sel[0]):
        return sel[0]
    return None


class MeshQualityCommand:
    def GetResources(self):
        return {
            "Pixmap": VoroHexGui.resource("icons", "VoroHexQuality.svg"),
            "MenuText": "Mesh quality",
            "ToolTip": "Colour the hexahedra of the selected FEM mesh by scaled Jacobian, "
                       "with a legend, and highlight the worst ones",
        }

    def IsActive(self):
        return selected_fem_mesh() is not None and not FreeCADGui.Control.activeDialog()

    def Activated(self):
        from VoroHexGui import quality_view

        mesh = selected_fem_mesh()
        try:
            panel = quality_view.QualityTaskPanel(mesh)
        except (TypeError, ValueError) as e:
            FreeCAD.Console.PrintError("VoroHex: {}\n".format(e))
            QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), "VoroHex: mesh quality",
                                      str(e))
            return
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Control.showDialog(panel)


def selected_vorohex_mesh():
    """The single selected VoroHex mesh object, or None."""
    if FreeCADGui.ActiveDocument is None:
        return None
    sel = FreeCADGui.Selection.getSelection()
    if len(sel) == 1 and getattr(getattr(sel[0], "Proxy", None), "Type", None) == \
            VoroHexObjects.TYPE:
        return sel[0]
    return None


class LocalSizeCommand:
    """Adds a FEM mesh region (FreeCAD's own object: a size and references) under the
    selected VoroHex mesh and opens FreeCAD's panel to pick its faces, edges or vertices."""

    def GetResources(self):
        return {
            "Pixmap": VoroHexGui.resource("icons", "VoroHexLocalSize.svg"),
            "MenuText": "Local size",
            "ToolTip": "Add a mesh region to the selected VoroHex mesh: a smaller size at the "
                       "faces, edges or vertices you pick, graded into the mesh size",
        }

    def IsActive(self):
        return selected_vorohex_mesh() is not None and not FreeCADGui.Control.activeDialog()

    def Activated(self):
        mesh = selected_vorohex_mesh()
        part = mesh.Part
        size = mesh.TargetSize.Value or (
            VoroHexObjects.automatic_size(part.Shape) if part is not None else 1.0)
        doc = mesh.Document
        doc.openTransaction("VoroHex local size")
        FreeCADGui.addModule("ObjectsFem")
        FreeCADGui.doCommand(
            "_region = ObjectsFem.makeMeshRegion(App.ActiveDocument, App.ActiveDocument.{}, "
            "{!r})".format(mesh.Name, round(size / 4.0, 6)))
        doc.commitTransaction()
        region = mesh.MeshRegionList[-1]
        # FreeCAD's region panel hides every FEM mesh; the part must show to be picked.
        shown = part.ViewObject.Visibility if part is not None else None
        if part is not None:
            part.ViewObject.Visibility = True
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.doCommand("Gui.ActiveDocument.setEdit(_region.Name)")
        RegionWatcher.start(mesh, region, part, shown)


class RegionWatcher:
    """Waits for FreeCAD's region panel to close, then shows the mesh again (the panel hid
    it) and puts the part's visibility back; a region left without faces, edges or vertices
    (the panel cancelled) is removed again, as it was only just added."""

    active = []  # keeps the watchers (and their timers) alive

    @classmethod
    def start(cls, mesh, region, part, part_shown):
        cls.active.append(cls(mesh, region, part, part_shown))

    def __init__(self, mesh, region, part, part_shown):
        self.doc, self.mesh_name, self.region_name = mesh.Document, mesh.Name, region.Name
        self.part_name = part.Name if part is not None else None
        self.part_shown = part_shown
        self.timer = QtCore.QTimer()
        self.timer.timeout.connect(self.check)
        self.timer.start(250)

    def check(self):
        if FreeCADGui.Control.activeDialog():
            return
        self.timer.stop()
        RegionWatcher.active.remove(self)
        mesh = self.doc.getObject(self.mesh_name)
        region = self.doc.getObject(self.region_name)
        if region is not None and not region.References:
            if mesh is not None:
                mesh.MeshRegionList = [r for r in mesh.MeshRegionList if r != region]
            self.doc.removeObject(self.region_name)
            FreeCAD.Console.PrintMessage(
                "VoroHex: the mesh region picked no face, edge or vertex and was removed.\n")
        part = self.doc.getObject(self.part_name) if self.part_name else None
        if part is not None and self.part_shown is not None:
            part.ViewObject.Visibility = self.part_shown
        if mesh is not None:
            mesh.ViewObject.Visibility = True
            if "Touched" in mesh.State:
                self.doc.recompute()


def register():
    FreeCADGui.addCommand("VoroHex_HexMesh", HexMeshCommand())
    FreeCADGui.addCommand("VoroHex_LocalSize", LocalSizeCommand())
    FreeCADGui.addCommand("VoroHex_VoronoiGraph", VoronoiGraphCommand())
    FreeCADGui.addCommand("VoroHex_Decomposition", DecompositionCommand())
    FreeCADGui.addCommand("VoroHex_MeshQuality", MeshQualityCommand())


COMMANDS = ["VoroHex_HexMesh", "VoroHex_LocalSize", "VoroHex_VoronoiGraph",
            "VoroHex_Decomposition", "VoroHex_MeshQuality"]
