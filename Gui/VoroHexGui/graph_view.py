# View provider and task panel of the Voronoi graph object: edges coloured by type, and a
# legend (colour, type, meaning, count, shown or not) that toggles types.
import FreeCADGui
from PySide import QtCore, QtGui

import VoroHexGraph
import VoroHexGui
from VoroHexGui.view_provider import ViewProviderBase


class ViewProviderVoronoiGraph(ViewProviderBase):
    ICON = "VoroHexGraph.svg"

    def updateData(self, obj, prop):
        if prop in ("SegmentTypes", "Shape"):
            colour_edges(obj)

    def make_panel(self, obj):
        return GraphTaskPanel(obj)


def colour_edges(obj):
    """One colour per line segment from its type; thick lines, visible vertices."""
    vobj = obj.ViewObject
    if vobj is None:
        return
    types = list(obj.SegmentTypes)
    if len(types) != len(obj.Shape.Edges):
        return  # mid-recompute: the shape and the list are set one after the other
    vobj.LineWidth = 3.0
    vobj.PointSize = 6.0
    vobj.PointColor = (0.1, 0.1, 0.1)
    if types:
        vobj.LineColorArray = [VoroHexGraph.COLOURS.get(t, (0, 0, 0)) for t in types]
    if obj.Shape.Faces:  # the f_s faces: translucent, so the graph stays visible through them
        vobj.ShapeColor = VoroHexGraph.FS_COLOUR
        vobj.Transparency = 65


def swatch(rgb):
    pix = QtGui.QPixmap(18, 12)
    pix.fill(QtGui.QColor.fromRgbF(*rgb))
    return QtGui.QIcon(pix)


class EdgeTypeTable(QtGui.QTableWidget):
    """The edge-type legend of a Voronoi graph object: per type its colour, name (a check
    box that shows or hides the type), number of edges and meaning."""

    def __init__(self, parent=None):
        super().__init__(len(VoroHexGraph.EDGE_TYPES), 3, parent)
        self.obj = None
        self.setObjectName("tbl_edge_types")
        self.setHorizontalHeaderLabels(["Type", "Edges", "Meaning"])
        self.verticalHeader().setVisible(False)
        self.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        for row, (name, rgb, meaning) in enumerate(VoroHexGraph.EDGE_TYPES):
            item = QtGui.QTableWidgetItem(swatch(rgb), name)
            item.setFlags(QtCore.Qt.ItemIsUserCheckable | QtCore.Qt.ItemIsEnabled)
            item.setCheckState(QtCore.Qt.Checked)
            self.setItem(row, 0, item)
            self.setItem(row, 1, QtGui.QTableWidgetItem(""))
            explained = QtGui.QTableWidgetItem(meaning)
            explained.setToolTip(meaning)
            self.setItem(row, 2, explained)
        self.horizontalHeader().setStretchLastSection(True)
        self.setWordWrap(True)
        self.resizeColumnsToContents()
        self.resizeRowsToContents()
        self.itemChanged.connect(self.toggled)

    def set_graph(self, obj):
        """Shows the counts and shown types of a graph object (None: empty)."""
        self.obj = obj
        self.refresh()

    def counts(self):
        if self.obj is None:
            return {}
        return {t: int(n) for t, n in self.obj.EdgeTypeCounts.items()}

    def refresh(self):
        counts = self.counts()
        shown = list(self.obj.ShownTypes) if self.obj is not None else []
        self.blockSignals(True)
        for row, (name, _, _) in enumerate(VoroHexGraph.EDGE_TYPES):
            self.item(row, 1).setText(str(counts.get(name, 0)) if self.obj is not None else "")
            self.item(row, 0).setCheckState(QtCore.Qt.Checked if name in shown
                                            else QtCore.Qt.Unchecked)
        self.blockSignals(False)

    def toggled(self, item):
        if item.column() != 0 or self.obj is None:
            return
        self.obj.ShownTypes = [self.item(r, 0).text() for r in range(self.rowCount())
                               if self.item(r, 0).checkState() == QtCore.Qt.Checked]
        self.obj.Document.recompute()
        self.refresh()


class GraphTaskPanel:
    """The legend (EdgeTypeTable) and the graph's counts."""

    def __init__(self, obj):
        self.obj = obj
        self.form = QtGui.QWidget()
        self.form.setWindowTitle("Voronoi graph")
        self.form.setWindowIcon(QtGui.QIcon(VoroHexGui.resource("icons", "VoroHexGraph.svg")))
        layout = QtGui.QVBoxLayout(self.form)
        self.summary = QtGui.QLabel()
        self.summary.setObjectName("lbl_graph_summary")
        self.summary.setWordWrap(True)
        layout.addWidget(self.summary)
        self.table = EdgeTypeTable(self.form)
        self.table.setMinimumHeight(420)
        layout.addWidget(self.table)
        self.table.itemChanged.connect(lambda item: self.refresh())
        self.table.set_graph(obj)
        self.fs_faces = QtGui.QCheckBox(self.form)
        self.fs_faces.setObjectName("cb_fs_faces")
        self.fs_faces.setIcon(swatch(VoroHexGraph.FS_COLOUR))
        self.fs_faces.setToolTip("Voronoi faces between two model faces that share nothing: "
                                 "where the solid is swept between them (drawn translucent)")
        layout.addWidget(self.fs_faces)
        self.fs_faces.toggled.connect(self.fs_toggled)
        self.refresh()

    def fs_toggled(self, on):
        if bool(self.obj.ShowFsFaces) != on:
            self.obj.ShowFsFaces = on
            self.obj.Document.recompute()
        self.refresh()

    def counts(self):
        return self.table.counts()

    def refresh(self):
        self.table.refresh()
        self.summary.setText(self.obj.Message if self.obj.Status else "Not computed yet.")
        self.fs_faces.blockSignals(True)
        self.fs_faces.setChecked(bool(self.obj.ShowFsFaces))
        self.fs_faces.setText("f_s faces ({} of {} drawn)".format(self.obj.FsFacesDrawn,
                                                                  self.obj.FsFaceCount))
        self.fs_faces.blockSignals(False)

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self):
        FreeCADGui.ActiveDocument.resetEdit()
        return True

    def accept(self):
        return self.reject()
