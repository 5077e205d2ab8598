# "Mesh quality": hexahedra of a FEM mesh coloured by scaled Jacobian (the visible faces of
# each element take its colour), a legend with the count per band, and the worst elements'
# nodes highlighted. Colours are reset when the panel closes.
import FreeCADGui
from PySide import QtGui

import VoroHex
import VoroHexGui
from VoroHexGui.graph_view import swatch

# Bands of the scaled Jacobian, worst first: (upper bound, colour, label).
BANDS = (
    (0.0, (0.55, 0.0, 0.55), "inverted (<= 0)"),
    (0.2, (0.90, 0.10, 0.10), "0 - 0.2 (poor)"),
    (0.4, (0.98, 0.55, 0.10), "0.2 - 0.4"),
    (0.6, (0.98, 0.85, 0.15), "0.4 - 0.6"),
    (0.8, (0.60, 0.85, 0.25), "0.6 - 0.8"),
    (1.01, (0.15, 0.65, 0.25), "0.8 - 1 (good)"),
)


def band(value):
    for i, (upper, _, _) in enumerate(BANDS):
        if value <= upper:
            return i
    return len(BANDS) - 1


# The open panel (None when closed): FreeCAD's ElementColor cannot be read back, so tests
# and scripts look at what the panel applied.
current = None


def colour_by_quality(mesh_obj):
    """Colours the elements; returns ({element: sj}, counts per band, {element: colour})."""
    sj = VoroHex.element_quality(mesh_obj)
    counts = [0] * len(BANDS)
    colours = {}
    for eid, v in sj.items():
        b = band(v)
        counts[b] += 1
        colours[eid] = BANDS[b][1]
    mesh_obj.ViewObject.ElementColor = colours
    return sj, counts, colours


def worst_nodes(mesh_obj, sj, threshold):
    """Node ids of the elements whose scaled Jacobian is below threshold."""
    nodes = set()
    for eid, v in sj.items():
        if v < threshold:
            nodes.update(mesh_obj.FemMesh.getElementNodes(eid))
    return sorted(nodes)


class QualityTaskPanel:
    def __init__(self, mesh_obj):
        self.obj = mesh_obj
        global current
        self.sj, counts, self.colours = colour_by_quality(mesh_obj)
        current = self
        # Nodes drawn as points would hide the colours; restored on close.
        self.display_mode = mesh_obj.ViewObject.DisplayMode
        if "Faces & Wireframe" in mesh_obj.ViewObject.listDisplayModes():
            mesh_obj.ViewObject.DisplayMode = "Faces & Wireframe"
        self.form = QtGui.QWidget()
        self.form.setWindowTitle("Mesh quality")
        self.form.setWindowIcon(QtGui.QIcon(VoroHexGui.resource("icons", "VoroHexQuality.svg")))
        layout = QtGui.QVBoxLayout(self.form)
        values = list(self.sj.values())
        summary = QtGui.QLabel("{} hexahedra, scaled Jacobian min {:.3f}, mean {:.3f}".format(
            len(values), min(values) if values else 0,
            sum(values) / len(values) if values else 0))
        summary.setObjectName("lbl_quality_summary")
        summary.setWordWrap(True)
        layout.addWidget(summary)
        self.legend = QtGui.QTableWidget(len(BANDS), 2)
        self.legend.setObjectName("tbl_quality_bands")
        self.legend.setHorizontalHeaderLabels(["Scaled Jacobian", "Hexahedra"])
        self.legend.verticalHeader().setVisible(False)
        self.legend.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        for row, ((_, rgb, label), n) in enumerate(zip(BANDS, counts)):
            self.legend.setItem(row, 0, QtGui.QTableWidgetItem(swatch(rgb), label))
            self.legend.setItem(row, 1, QtGui.QTableWidgetItem(str(n)))
        self.legend.horizontalHeader().setStretchLastSection(True)
        self.legend.resizeColumnsToContents()
        self.legend.setMinimumHeight(220)
        layout.addWidget(self.legend)
        row = QtGui.QHBoxLayout()
        row.addWidget(QtGui.QLabel("Select below"))
        self.threshold = QtGui.QDoubleSpinBox()
        self.threshold.setObjectName("sb_worst_threshold")
        self.threshold.setRange(-1.0, 1.0)
        self.threshold.setSingleStep(0.05)
        self.threshold.setValue(0.2)
        row.addWidget(self.threshold)
        self.select = QtGui.QPushButton("Highlight worst")
        self.select.setObjectName("pb_highlight_worst")
        self.select.clicked.connect(self.highlight)
        row.addWidget(self.select)
        layout.addLayout(row)
        self.found = QtGui.QLabel("")
        self.found.setObjectName("lbl_worst")
        self.found.setWordWrap(True)
        layout.addWidget(self.found)

    def highlight(self):
        t = self.threshold.value()
        elements = [e for e, v in self.sj.items() if v < t]
        nodes = worst_nodes(self.obj, self.sj, t)
        self.obj.ViewObject.HighlightedNodes = nodes
        worst = sorted(elements, key=lambda e: self.sj[e])[:5]
        self.found.setText("{} hexahedra below {:.2f} ({} nodes highlighted){}".format(
            len(elements), t, len(nodes), "; worst: " + ", ".join(
                "{} ({:.3f})".format(e, self.sj[e]) for e in worst) if worst else ""))

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self):
        global current
        current = None
        self.colours = {}
        self.obj.ViewObject.ElementColor = {}
        self.obj.ViewObject.HighlightedNodes = []
        self.obj.ViewObject.DisplayMode = self.display_mode
        FreeCADGui.Control.closeDialog()
        return True

    def accept(self):
        return self.reject()
