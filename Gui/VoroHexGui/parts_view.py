# View provider and task panel of the decomposition object: faces coloured by the scheme
# of their sub-volume, decomposition faces and sweep ends marked; the panel is the legend
# and a table of sub-volumes (selecting a row selects that sub-volume's faces).
import FreeCADGui
from PySide import QtCore, QtGui

import VoroHexGui
from VoroHexGui.view_provider import ViewProviderBase
import VoroHexParts
from VoroHexGui.graph_view import swatch


class ViewProviderDecomposition(ViewProviderBase):
    ICON = "VoroHexParts.svg"

    def updateData(self, obj, prop):
        if prop in ("FaceRoles", "Shape"):
            colour_faces(obj)

    def make_panel(self, obj):
        return PartsTaskPanel(obj)


def colour_faces(obj):
    vobj = obj.ViewObject
    if vobj is None:
        return
    roles = list(obj.FaceRoles)
    if not roles or len(roles) != len(obj.Shape.Faces):
        return
    vobj.LineWidth = 2.0
    vobj.DiffuseColor = [VoroHexParts.COLOURS.get(r, (0.5, 0.5, 0.5)) + (0.0,) for r in roles]


def sub_volume_faces(obj, index):
    """Names ("Face3", ...) of the compound's faces that bound sub-volume `index`."""
    solids = obj.Shape.Solids
    if index >= len(solids):
        return []
    return ["Face{}".format(k + 1) for k, f in enumerate(obj.Shape.Faces)
            if any(f.isSame(g) for g in solids[index].Faces)]


class PartsTaskPanel:
    def __init__(self, obj):
        self.obj = obj
        self.form = QtGui.QWidget()
        self.form.setWindowTitle("Decomposition")
        self.form.setWindowIcon(QtGui.QIcon(VoroHexGui.resource("icons", "VoroHexParts.svg")))
        layout = QtGui.QVBoxLayout(self.form)
        summary = QtGui.QLabel(obj.Message or "Not computed yet.")
        summary.setObjectName("lbl_parts_summary")
        summary.setWordWrap(True)
        layout.addWidget(summary)
        legend = QtGui.QListWidget()
        legend.setObjectName("lst_roles")
        for name, rgb, meaning in VoroHexParts.ROLES:
            legend.addItem(QtGui.QListWidgetItem(swatch(rgb), "{}: {}".format(name, meaning)))
        legend.setMaximumHeight(140)
        layout.addWidget(legend)
        self.table = QtGui.QTableWidget(len(obj.Schemes), 4)
        self.table.setObjectName("tbl_sub_volumes")
        self.table.setHorizontalHeaderLabels(["Id", "Type", "Scheme", "Why"])
        self.table.verticalHeader().setVisible(False)
        self.table.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        self.table.setSelectionBehavior(QtGui.QAbstractItemView.SelectRows)
        for row, (t, s, why) in enumerate(zip(obj.Types, obj.Schemes, obj.Reasons)):
            for col, text in enumerate((str(row), t, s, why)):
                item = QtGui.QTableWidgetItem(text)
                item.setToolTip(text)
                self.table.setItem(row, col, item)
        self.table.horizontalHeader().setStretchLastSection(True)
        self.table.resizeColumnsToContents()
        layout.addWidget(self.table)
        self.table.itemSelectionChanged.connect(self.selected)

    def selected(self):
        rows = sorted({i.row() for i in self.table.selectedItems()})
        FreeCADGui.Selection.clearSelection()
        for r in rows:
            FreeCADGui.Selection.addSelection(self.obj, sub_volume_faces(self.obj, r))

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self):
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.ActiveDocument.resetEdit()
        return True

    def accept(self):
        return self.reject()
