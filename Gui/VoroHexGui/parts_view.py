# View provider and task panel of the decomposition object. The sub-volumes are child
# objects (shown, hidden, moved apart one by one), their faces coloured by role; the
# decomposition object itself draws nothing of its own (display mode "Sub-volumes"), so
# nothing is drawn twice. The panel is the legend, an Explode slider and the table of
# sub-volumes: a row selects its sub-volume in the 3D view, a pick in 3D selects its row.
# While it is open the solid shows as edges only (its faces would fight with the pieces').
import FreeCADGui
from PySide import QtCore, QtGui

import VoroHexGui
import VoroHexParts
from VoroHexGui.graph_view import FittedTable, WrappedTable, swatch
from VoroHexGui.view_provider import ViewProviderBase, fade_solid

MODE = "Sub-volumes"


class ViewProviderDecomposition(ViewProviderBase):
    ICON = "VoroHexParts.svg"

    def attach(self, vobj):
        super().attach(vobj)
        from pivy import coin

        vobj.addDisplayMode(coin.SoGroup(), MODE)

    def getDisplayModes(self, vobj):
        return [MODE]

    def getDefaultDisplayMode(self):
        return MODE

    def setDisplayMode(self, mode):
        return mode

    def claimChildren(self):
        return [c for c in getattr(self.Object, "SubVolumeObjects", []) if c is not None]

    def updateData(self, obj, prop):
        if prop in ("SubVolumeObjects", "FaceRoles"):
            colour_children(obj)
            if obj.ViewObject is not None and obj.ViewObject.DisplayMode != MODE:
                obj.ViewObject.DisplayMode = MODE

    def onChanged(self, vobj, prop):
        if prop == "Visibility":  # the sub-volumes show and hide with it
            for child in self.claimChildren():
                if child.ViewObject is not None:
                    child.ViewObject.Visibility = vobj.Visibility

    def onDelete(self, vobj, subelements):
        doc = vobj.Object.Document
        for child in self.claimChildren():
            if doc.getObject(child.Name) is not None:
                doc.removeObject(child.Name)
        return True

    def make_panel(self, obj):
        return PartsTaskPanel(obj)


def colour_children(obj):
    """Each sub-volume's faces in the colour of their role."""
    for child in getattr(obj, "SubVolumeObjects", []):
        if child is None or child.ViewObject is None:
            continue
        roles = list(child.FaceRoles)
        if len(roles) != len(child.Shape.Faces):
            continue
        child.ViewObject.LineWidth = 1.0
        child.ViewObject.DiffuseColor = [VoroHexParts.COLOURS.get(r, (0.5, 0.5, 0.5)) + (0.0,)
                                         for r in roles]


class PickObserver:
    """Selection in the 3D view or the tree -> the table's row."""

    def __init__(self, panel):
        self.panel = panel

    def addSelection(self, doc, obj, sub, pnt):
        self.panel.picked(obj)

    def setSelection(self, doc):
        return

    def removeSelection(self, doc, obj, sub):
        return

    def clearSelection(self, doc):
        return


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
        self.summary = summary
        # How to cut (the Method property), recomputed in a child process with a progress
        # dialog that can cancel it (an edit of the property recomputes in FreeCAD's own
        # thread, which the Voronoi graph's decomposition can hold for seconds).
        row = QtGui.QHBoxLayout()
        row.addWidget(QtGui.QLabel("Cut:"))
        self.method = QtGui.QComboBox()
        self.method.setObjectName("cb_method")
        self.method.addItems([label for label, _ in VoroHexParts.METHODS])
        # As narrow as the Combo View (its longest choice widened the panel past it).
        self.method.setSizeAdjustPolicy(QtGui.QComboBox.AdjustToMinimumContentsLengthWithIcon)
        self.method.setMinimumContentsLength(8)
        self.method.setCurrentIndex(self.method_index(obj.Method))
        self.method.setToolTip(obj.getDocumentationOfProperty("Method"))
        self.method.activated.connect(self.method_chosen)
        row.addWidget(self.method, 1)
        layout.addLayout(row)
        legend = FittedTable(len(VoroHexParts.ROLES), 2)
        legend.setObjectName("tbl_roles")
        legend.setHorizontalHeaderLabels(["Face role", "Meaning"])
        legend.verticalHeader().setVisible(False)
        legend.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        legend.setSelectionMode(QtGui.QAbstractItemView.NoSelection)
        legend.setWordWrap(True)
        legend.setTextElideMode(QtCore.Qt.ElideNone)
        legend.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        legend.setVerticalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        for row, (name, rgb, meaning) in enumerate(VoroHexParts.ROLES):
            legend.setItem(row, 0, QtGui.QTableWidgetItem(swatch(rgb), name))
            legend.setItem(row, 1, QtGui.QTableWidgetItem(meaning))
        header = legend.horizontalHeader()
        header.setSectionResizeMode(0, QtGui.QHeaderView.ResizeToContents)
        header.setSectionResizeMode(1, QtGui.QHeaderView.Stretch)
        self.legend = legend
        layout.addWidget(legend)
        row = QtGui.QHBoxLayout()
        row.addWidget(QtGui.QLabel("Explode:"))
        self.explode = QtGui.QSlider(QtCore.Qt.Horizontal)
        self.explode.setObjectName("sl_explode")
        self.explode.setRange(0, 100)
        self.explode.setValue(int(round(50 * obj.Explode)))
        self.explode.setToolTip("Moves the sub-volumes apart (property Explode, 0 to 2)")
        self.explode.valueChanged.connect(self.exploded)
        row.addWidget(self.explode)
        layout.addLayout(row)
        self.table = WrappedTable(0, 4)
        self.table.setObjectName("tbl_sub_volumes")
        self.table.setHorizontalHeaderLabels(["Id", "Type", "Scheme", "Why"])
        self.table.verticalHeader().setVisible(False)
        # The reasons are sentences: wrapped in their cells, never cut short (the narrow
        # Combo View showed "Not a block: the..." before).
        self.table.setWordWrap(True)
        self.table.setTextElideMode(QtCore.Qt.ElideNone)
        self.table.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        self.table.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        self.table.setSelectionBehavior(QtGui.QAbstractItemView.SelectRows)
        header = self.table.horizontalHeader()
        for col in range(3):
            header.setSectionResizeMode(col, QtGui.QHeaderView.ResizeToContents)
        header.setSectionResizeMode(3, QtGui.QHeaderView.Stretch)
        self.fill_table()
        self.table.setMinimumHeight(160)
        layout.addWidget(self.table)
        self.table.itemSelectionChanged.connect(self.selected)
        self.syncing = False
        self.faded = fade_solid(obj.Part, wireframe=True)
        FreeCADGui.Selection.clearSelection()
        self.observer = PickObserver(self)
        FreeCADGui.Selection.addObserver(self.observer)
        QtCore.QTimer.singleShot(0, self.legend.fit_rows)

    def fill_table(self):
        """The sub-volumes' rows: id, type, scheme and why."""
        obj = self.obj
        self.table.clearContents()
        self.table.setRowCount(len(obj.Schemes))
        for r, (t, s, why) in enumerate(zip(obj.Types, obj.Schemes, obj.Reasons)):
            for col, text in enumerate((str(r), t, s, why)):
                item = QtGui.QTableWidgetItem(text)
                item.setToolTip(text)
                self.table.setItem(r, col, item)
        # The exact cuts at concave edges type no sub-volume Vs or Ve.
        self.table.setColumnHidden(1, not any(obj.Types))
        self.table.fit_rows()

    @staticmethod
    def method_index(label):
        labels = [m[0] for m in VoroHexParts.METHODS]
        return labels.index(label) if label in labels else 0

    def method_chosen(self, index):
        """Another way to cut: computed in a child process (Cancel in its progress dialog
        leaves the object as it was), then stored as a recompute would."""
        label = VoroHexParts.METHODS[index][0]
        obj = self.obj
        if label == obj.Method or obj.Part is None:
            return
        import VoroHexObjects
        from VoroHexGui import commands

        def done(data, why):
            if data is None or obj.Document.getObject(obj.Name) is None:
                self.method.setCurrentIndex(self.method_index(obj.Method))
                if why and why != "cancelled":
                    self.summary.setText("Not recomputed: " + why)
                return
            doc = obj.Document
            doc.openTransaction("VoroHex decomposition method")
            obj.Method = label
            obj.Proxy.data, obj.Proxy.key = data, VoroHexParts.cache_key(obj)
            doc.recompute()
            doc.commitTransaction()
            self.summary.setText(obj.Message)
            self.fill_table()

        commands.start("Decomposition", VoroHexParts.compute_work,
                       (obj.Part.Shape.exportBrepToString(), obj.SharpAngle, obj.Merge,
                        VoroHexObjects.graph_options_of(obj), obj.TimeLimit,
                        VoroHexParts.METHOD_OF[label], obj.AllowedSchemes), done)

    def children(self):
        return [c for c in self.obj.SubVolumeObjects if c is not None]

    def exploded(self, value):
        self.obj.Explode = value / 50.0

    def selected(self):
        """Table rows -> the sub-volumes selected in the 3D view and the tree."""
        if self.syncing:
            return
        rows = sorted({i.row() for i in self.table.selectedItems()})
        children = self.children()
        self.syncing = True
        try:
            FreeCADGui.Selection.clearSelection()
            for r in rows:
                if r < len(children):
                    FreeCADGui.Selection.addSelection(children[r])
        finally:
            self.syncing = False

    def picked(self, obj_name):
        """A pick in 3D (or the tree) of a sub-volume -> its table row."""
        if self.syncing:
            return
        names = [c.Name for c in self.children()]
        if obj_name not in names:
            return
        self.syncing = True
        try:
            self.table.selectRow(names.index(obj_name))
        finally:
            self.syncing = False

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self):
        FreeCADGui.Selection.removeObserver(self.observer)
        FreeCADGui.Selection.clearSelection()
        self.faded.restore()
        FreeCADGui.ActiveDocument.resetEdit()
        return True

    def accept(self):
        return self.reject()


def sub_volume_faces(obj, index):
    """Names ("Face3", ...) of the compound's faces that bound sub-volume `index`."""
    solids = obj.Shape.Solids
    if index >= len(solids):
        return []
    return ["Face{}".format(k + 1) for k, f in enumerate(obj.Shape.Faces)
            if any(f.isSame(g) for g in solids[index].Faces)]

