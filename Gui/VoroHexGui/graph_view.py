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


def swatch(rgb):
    pix = QtGui.QPixmap(18, 12)
    pix.fill(QtGui.QColor.fromRgbF(*rgb))
    return QtGui.QIcon(pix)


class GraphTaskPanel:
    """The legend: one row per edge type with its colour, meaning, count and a check box
    that shows or hides the type; and the graph's counts."""

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
        self.table = QtGui.QTableWidget(len(VoroHexGraph.EDGE_TYPES), 3)
        self.table.setObjectName("tbl_edge_types")
        self.table.setHorizontalHeaderLabels(["Type", "Edges", "Meaning"])
        self.table.verticalHeader().setVisible(False)
        self.table.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        for row, (name, rgb, meaning) in enumerate(VoroHexGraph.EDGE_TYPES):
            item = QtGui.QTableWidgetItem(swatch(rgb), name)
            item.setFlags(QtCore.Qt.ItemIsUserCheckable | QtCore.Qt.ItemIsEnabled)
            item.setCheckState(QtCore.Qt.Checked if name in obj.ShownTypes
                               else QtCore.Qt.Unchecked)
            self.table.setItem(row, 0, item)
            self.table.setItem(row, 1, QtGui.QTableWidgetItem(""))
            explained = QtGui.QTableWidgetItem(meaning)
            explained.setToolTip(meaning)
            self.table.setItem(row, 2, explained)
        self.table.horizontalHeader().setStretchLastSection(True)
        self.table.setWordWrap(True)
        self.table.resizeColumnsToContents()
        self.table.resizeRowsToContents()
        self.table.setMinimumHeight(420)
        layout.addWidget(self.table)
        self.table.itemChanged.connect(self.toggled)
        self.refresh()

    def counts(self):
        return {t: int(n) for t, n in self.obj.EdgeTypeCounts.items()}

    def refresh(self):
        counts = self.counts()
        self.table.blockSignals(True)
        for row, (name, _, _) in enumerate(VoroHexGraph.EDGE_TYPES):
            self.table.item(row, 1).setText(str(counts.get(name, 0)))
        self.table.blockSignals(False)
        self.summary.setText(self.obj.Message if self.obj.Status else "Not computed yet.")

    def toggled(self, item):
        if item.column() != 0:
            return
        shown = [self.table.item(r, 0).text() for r in range(self.table.rowCount())
                 if self.table.item(r, 0).checkState() == QtCore.Qt.Checked]
        self.obj.ShownTypes = shown
        self.obj.Document.recompute()
        self.refresh()

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self):
        FreeCADGui.ActiveDocument.resetEdit()
        return True

    def accept(self):
        return self.reject()
