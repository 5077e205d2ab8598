# The "Hex mesh" command: one Part feature selected -> a VoroHex mesh object (added to the
# active FEM analysis if there is one, as FEM's own mesh commands do) and its task panel.
import time

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

import VoroHexGui
import VoroHexObjects


def selected_part():
    """The single selected Part feature, or None."""
    if FreeCADGui.ActiveDocument is None:
        return None
    sel = FreeCADGui.Selection.getSelection()
    if len(sel) == 1 and sel[0].isDerivedFrom("Part::Feature"):
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


class Busy:
    """Progress for a long recompute: a busy dialog (shown after half a second) whose Cancel
    stops it; the callback keeps the GUI responsive."""

    current = None

    def __init__(self, text):
        self.text, self.dialog, self.cancelled = text, None, False
        self.start = time.time()
        Busy.current = self

    def __call__(self, stage, fraction):
        if self.dialog is None and time.time() - self.start > 0.5:
            self.dialog = QtGui.QProgressDialog(self.text, "Cancel", 0, 0,
                                                FreeCADGui.getMainWindow())
            self.dialog.setObjectName("vorohex_busy")
            self.dialog.setWindowTitle("VoroHex")
            self.dialog.setWindowModality(QtCore.Qt.WindowModal)
            self.dialog.canceled.connect(self.cancel)
            self.dialog.show()
        QtGui.QApplication.processEvents()
        if self.dialog is not None and self.dialog.wasCanceled():
            self.cancelled = True
        return not self.cancelled

    def cancel(self):
        self.cancelled = True

    def close(self):
        if self.dialog is not None:
            # Closing a QProgressDialog emits `canceled`: a run that finished after its
            # dialog had appeared was then taken as cancelled and its result thrown away.
            self.dialog.canceled.disconnect(self.cancel)
            self.dialog.close()
            self.dialog.deleteLater()
        Busy.current = None


def run_cancellable(doc, label, work):
    """Runs work(busy) (which makes document objects, passing `busy` as their progress) in
    one transaction with a Busy dialog; a cancelled run removes what it made, leaving the
    document as it was. Returns the objects made, or None when cancelled."""
    before = set(o.Name for o in doc.Objects)
    doc.openTransaction(label)
    busy = Busy("{}...".format(label))
    try:
        work(busy)
    except Exception:  # VoroHex.Cancelled from a make* function, also through doCommand
        if not busy.cancelled:
            doc.abortTransaction()
            raise
    finally:
        busy.close()
    made = [o for o in doc.Objects if o.Name not in before]
    if busy.cancelled:
        names = [o.Name for o in made]
        doc.abortTransaction()
        for name in names:  # in case the transaction did not hold them
            if doc.getObject(name) is not None:
                doc.removeObject(name)
        FreeCAD.Console.PrintMessage("VoroHex: {} cancelled\n".format(label))
        return None
    doc.commitTransaction()
    return made


def make_and_edit(part, label, module, factory):
    """`module.factory(doc, part, progress=...)` as a recorded, cancellable command (the
    busy dialog), then the new object's task panel; a message if `part` is no solid."""
    error = VoroHexObjects.source_error(part)
    if error is not None:
        FreeCAD.Console.PrintError("VoroHex: {}\n".format(error))
        QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), "VoroHex: " + label, error)
        return
    doc = part.Document
    FreeCADGui.addModule(module)
    FreeCADGui.addModule("VoroHexGui.commands")
    made = run_cancellable(doc, label, lambda busy: FreeCADGui.doCommand(
        "_made = {}.{}(FreeCAD.getDocument('{}'), FreeCAD.getDocument('{}').getObject('{}'), "
        "progress=VoroHexGui.commands.Busy.current)".format(module, factory, doc.Name,
                                                            doc.Name, part.Name)))
    if not made:  # cancelled, or nothing was made
        return
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.doCommand("FreeCADGui.getDocument('{}').setEdit('{}')".format(doc.Name,
                                                                             made[0].Name))


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
        make_and_edit(selected_part(), "Voronoi graph", "VoroHexGraph", "makeVoronoiGraph")


class DecompositionCommand:
    def GetResources(self):
        return {
            "Pixmap": VoroHexGui.resource("icons", "VoroHexParts.svg"),
            "MenuText": "Decomposition",
            "ToolTip": "Cut the selected solid into sweepable and mappable sub-volumes along "
                       "its Voronoi graph; faces coloured by scheme, decomposition faces marked",
        }

    def IsActive(self):
        return selected_part() is not None

    def Activated(self):
        make_and_edit(selected_part(), "Decomposition", "VoroHexParts", "makeDecomposition")


def selected_fem_mesh():
    """The single selected FEM mesh object holding hexahedra, or None."""
    if FreeCADGui.ActiveDocument is None:
        return None
    sel = FreeCADGui.Selection.getSelection()
    if len(sel) == 1 and sel[0].isDerivedFrom("Fem::FemMeshObject") and \
            sel[0].FemMesh.VolumeCount > 0:
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


def register():
    FreeCADGui.addCommand("VoroHex_HexMesh", HexMeshCommand())
    FreeCADGui.addCommand("VoroHex_VoronoiGraph", VoronoiGraphCommand())
    FreeCADGui.addCommand("VoroHex_Decomposition", DecompositionCommand())
    FreeCADGui.addCommand("VoroHex_MeshQuality", MeshQualityCommand())


COMMANDS = ["VoroHex_HexMesh", "VoroHex_VoronoiGraph", "VoroHex_Decomposition",
            "VoroHex_MeshQuality"]
