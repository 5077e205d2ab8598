# View provider and task panel of the Voronoi graph object: edges coloured by type, the
# f_s faces as translucent triangles (a Coin node of their own: no outline, no point
# markers), and a legend (colour, type, count, meaning) that toggles types. While the
# panel is open the solid fades, so the graph inside it is seen.
import FreeCADGui
from PySide import QtCore, QtGui

import VoroHexGraph
import VoroHexGui
from VoroHexGui.view_provider import ViewProviderBase, fade_solid


class ViewProviderVoronoiGraph(ViewProviderBase):
    ICON = "VoroHexGraph.svg"

    def attach(self, vobj):
        super().attach(vobj)
        from pivy import coin

        self.fs_switch = coin.SoSwitch()
        sep = coin.SoSeparator()
        hints = coin.SoShapeHints()
        hints.vertexOrdering = coin.SoShapeHints.COUNTERCLOCKWISE
        hints.shapeType = coin.SoShapeHints.UNKNOWN_SHAPE_TYPE  # lit from both sides
        self.fs_material = coin.SoMaterial()
        self.fs_material.diffuseColor.setValue(*VoroHexGraph.FS_COLOUR)
        self.fs_material.transparency.setValue(0.55)
        self.fs_coords = coin.SoCoordinate3()
        self.fs_faces = coin.SoIndexedFaceSet()
        for node in (hints, self.fs_material, self.fs_coords, self.fs_faces):
            sep.addChild(node)
        self.fs_switch.addChild(sep)
        self.fs_switch.whichChild = 0
        vobj.RootNode.addChild(self.fs_switch)
        self.draw_fs_faces(vobj.Object)

    def draw_fs_faces(self, obj):
        """The f_s faces' triangles (FsFacePoints, FsFaceTriangles) into the Coin node."""
        if not hasattr(self, "fs_coords") or not hasattr(obj, "FsFaceTriangles"):
            return
        points = [(p.x, p.y, p.z) for p in obj.FsFacePoints]
        tris = list(obj.FsFaceTriangles)
        index = []
        for k in range(0, len(tris) - 2, 3):
            index += [tris[k], tris[k + 1], tris[k + 2], -1]
        self.fs_coords.point.setValues(0, len(points), points)
        self.fs_coords.point.setNum(len(points))
        self.fs_faces.coordIndex.setValues(0, len(index), index)
        self.fs_faces.coordIndex.setNum(len(index))

    def updateData(self, obj, prop):
        if prop in ("SegmentTypes", "Shape"):
            colour_edges(obj)
        if prop in ("FsFacePoints", "FsFaceTriangles"):
            self.draw_fs_faces(obj)

    def onChanged(self, vobj, prop):
        if prop == "Visibility" and hasattr(self, "fs_switch"):
            self.fs_switch.whichChild = 0 if vobj.Visibility else -1

    def make_panel(self, obj):
        return GraphTaskPanel(obj)


def colour_edges(obj):
    """One colour per line segment from its type; thick lines, small vertices."""
    vobj = obj.ViewObject
    if vobj is None:
        return
    types = list(obj.SegmentTypes)
    if len(types) != len(obj.Shape.Edges):
        return  # mid-recompute: the shape and the list are set one after the other
    vobj.LineWidth = 3.0
    vobj.PointSize = 4.0
    vobj.PointColor = (0.25, 0.25, 0.25)
    if types:
        vobj.LineColorArray = [VoroHexGraph.COLOURS.get(t, (0, 0, 0)) for t in types]


def swatch(rgb):
    pix = QtGui.QPixmap(18, 12)
    pix.fill(QtGui.QColor.fromRgbF(*rgb))
    return QtGui.QIcon(pix)


class FittedTable(QtGui.QTableWidget):
    """A legend table whose rows are as tall as their wrapped text, refitted whenever the
    panel's width changes: nothing cut, nothing to scroll."""

    def fit_rows(self):
        """Rows as tall as their wrapped text, the table as tall as its rows (no scrolling,
        no cut text)."""
        self.resizeRowsToContents()
        height = self.horizontalHeader().height() + 2 * self.frameWidth()
        height += sum(self.rowHeight(r) for r in range(self.rowCount()))
        self.setMinimumHeight(height)
        self.setMaximumHeight(height)

    def resizeEvent(self, event):
        super().resizeEvent(event)
        QtCore.QTimer.singleShot(0, self.fit_rows)  # after the columns took their widths

    def cut_cells(self):
        """(row, column) of every cell whose text does not fit in it (tests: none)."""
        return cut_cells(self)


class WrappedTable(QtGui.QTableWidget):
    """A table of long texts (the sub-volumes' reasons) wrapped in their cells, its rows
    refitted whenever its width changes, each at most `max_lines` lines tall (the whole text
    in the cell's tooltip: a reason of 300 characters in a narrow column pushed its row's id
    and scheme out of sight); it scrolls when they are many."""

    max_lines = 5

    def fit_rows(self):
        self.resizeRowsToContents()
        tallest = self.max_lines * QtGui.QFontMetrics(self.font()).lineSpacing() + 8
        for r in range(self.rowCount()):
            if self.rowHeight(r) > tallest:
                self.setRowHeight(r, tallest)

    def resizeEvent(self, event):
        super().resizeEvent(event)
        QtCore.QTimer.singleShot(0, self.fit_rows)

    def cut_cells(self):
        """(row, column) of every cell whose text does not fit in it (tests: none)."""
        return cut_cells(self, icon_columns=())


def cut_cells(table, icon_columns=(0,)):
    """(row, column) of every cell of `table` whose text does not fit in it (cells of
    `icon_columns` hold an icon or a check box beside their text)."""
    cut = []
    for r in range(table.rowCount()):
        for c in range(table.columnCount()):
            item = table.item(r, c)
            fm = QtGui.QFontMetrics(item.font() if item.font() else table.font())
            width = table.columnWidth(c) - 8 - (26 if c in icon_columns else 0)
            need = fm.boundingRect(QtCore.QRect(0, 0, max(width, 1), 10000),
                                   int(QtCore.Qt.TextWordWrap), item.text())
            if need.width() > width + 1 or need.height() > table.rowHeight(r):
                cut.append((r, c))
    return cut


class EdgeTypeTable(FittedTable):
    """The edge-type legend of a Voronoi graph object: per type its colour, name (a check
    box that shows or hides the type), number of edges and meaning (wrapped, never cut)."""

    def __init__(self, parent=None):
        super().__init__(len(VoroHexGraph.EDGE_TYPES), 3, parent)
        self.obj = None
        self.setObjectName("tbl_edge_types")
        self.setHorizontalHeaderLabels(["Type", "Edges", "Meaning"])
        self.verticalHeader().setVisible(False)
        self.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        self.setSelectionMode(QtGui.QAbstractItemView.NoSelection)
        self.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        self.setVerticalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        for row, (name, rgb, meaning) in enumerate(VoroHexGraph.EDGE_TYPES):
            item = QtGui.QTableWidgetItem(swatch(rgb), name)
            item.setFlags(QtCore.Qt.ItemIsUserCheckable | QtCore.Qt.ItemIsEnabled)
            item.setCheckState(QtCore.Qt.Checked)
            self.setItem(row, 0, item)
            self.setItem(row, 1, QtGui.QTableWidgetItem(""))
            explained = QtGui.QTableWidgetItem(meaning)
            explained.setToolTip(meaning)
            self.setItem(row, 2, explained)
        header = self.horizontalHeader()
        header.setSectionResizeMode(0, QtGui.QHeaderView.ResizeToContents)
        header.setSectionResizeMode(1, QtGui.QHeaderView.ResizeToContents)
        header.setSectionResizeMode(2, QtGui.QHeaderView.Stretch)
        self.setWordWrap(True)
        self.setTextElideMode(QtCore.Qt.ElideNone)
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
        self.obj.recompute()  # redraws from the graph kept by the object: no new graph
        self.refresh()


class GraphTaskPanel:
    """The legend (EdgeTypeTable) and the graph's counts; the solid fades meanwhile."""

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
        layout.addWidget(self.table)
        self.table.itemChanged.connect(lambda item: self.refresh())
        self.table.set_graph(obj)
        self.fs_faces = QtGui.QCheckBox(self.form)
        self.fs_faces.setObjectName("cb_fs_faces")
        self.fs_faces.setIcon(swatch(VoroHexGraph.FS_COLOUR))
        self.fs_faces.setToolTip("Voronoi faces between two model faces that share nothing: "
                                 "where the solid is swept between them (drawn translucent)")
        layout.addWidget(self.fs_faces)
        self.not_drawn = QtGui.QLabel()
        self.not_drawn.setObjectName("lbl_fs_not_drawn")
        self.not_drawn.setWordWrap(True)
        layout.addWidget(self.not_drawn)
        layout.addStretch(1)
        self.fs_faces.toggled.connect(self.fs_toggled)
        self.faded = fade_solid(obj.Part, transparency=80)
        self.refresh()

    def fs_toggled(self, on):
        if bool(self.obj.ShowFsFaces) != on:
            self.obj.ShowFsFaces = on
            self.obj.recompute()
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
        missing = list(getattr(self.obj, "FsFacesNotDrawn", []))
        self.not_drawn.setText("Not drawn: " + "; ".join(missing) if missing else "")
        self.not_drawn.setVisible(bool(missing))

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self):
        self.faded.restore()
        FreeCADGui.ActiveDocument.resetEdit()
        return True

    def accept(self):
        return self.reject()
