# "Mesh quality": hexahedra of a FEM mesh coloured by scaled Jacobian (the visible faces of
# each element take its colour), a legend with the count per band, and the worst elements'
# nodes highlighted. Colours are reset when the panel closes.
import FreeCADGui
from PySide import QtGui

import VoroHex
import VoroHexGui
from VoroHexGui import palette
from VoroHexGui.graph_view import swatch

# The bands and their colours: one scale with the task panel's histogram (palette.py).
BANDS = palette.BANDS
band = palette.band


# The open panel (None when closed): FreeCAD's ElementColor cannot be read back, so tests
# and scripts look at what the panel applied.
current = None


# The six faces of a hexahedron in VTK node order, each seen from outside.
HEX_FACES = ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))


def mesh_arrays(mesh_obj):
    """(node coordinates N x 3, hexahedra M x 8 as row indices in VTK order, element ids M)
    of a FEM mesh of hexahedra. A VoroHex mesh made in this session keeps them (its last
    run's payload); any other is read from the FemMesh (about 1 s per 100,000 hexahedra)."""
    import numpy as np

    fm = mesh_obj.FemMesh
    kept = getattr(getattr(mesh_obj, "Proxy", None), "arrays", None)
    if kept is not None and len(kept[1]) // 32 == fm.VolumeCount:
        points = np.frombuffer(kept[0], dtype=np.float64).reshape(-1, 3)
        hexes = np.frombuffer(kept[1], dtype=np.int32).reshape(-1, 8)
        return points, hexes, np.arange(1, len(hexes) + 1)
    by_id = fm.Nodes
    ids = sorted(by_id)
    row = {nid: i for i, nid in enumerate(ids)}
    points = np.array([tuple(by_id[i]) for i in ids], dtype=np.float64).reshape(-1, 3)
    elements = list(fm.Volumes)
    order = VoroHex.SMESH_FROM_VTK
    hexes = np.empty((len(elements), 8), dtype=np.int32)
    for k, e in enumerate(elements):
        nodes = fm.getElementNodes(e)
        hexes[k] = [row[nodes[j]] for j in order]
    return points, hexes, np.array(elements)


def element_quality(mesh_obj, arrays=None):
    """The scaled Jacobian of every hexahedron, in the order of mesh_arrays(): a VoroHex
    mesh stores it (ScaledJacobians, element 1, 2, ...); any other is measured."""
    import numpy as np

    fm = mesh_obj.FemMesh
    stored = getattr(mesh_obj, "ScaledJacobians", [])
    if len(stored) and len(stored) == fm.VolumeCount == getattr(mesh_obj, "HexCount", -1):
        return np.asarray(stored, dtype=np.float64)
    points, hexes, _ = arrays or mesh_arrays(mesh_obj)
    core = VoroHex._core.HexMesh.from_bytes(points.tobytes(), hexes.astype(np.int32).tobytes())
    return np.asarray(core.scaled_jacobians(), dtype=np.float64)


def boundary_faces(hexes):
    """(faces K x 4 node rows, the element row of each): the hexahedra's faces that no other
    hexahedron shares, seen from outside."""
    import numpy as np

    faces = hexes[:, HEX_FACES].reshape(-1, 4)
    low3 = np.sort(faces, axis=1)[:, :3].astype(np.int64)
    if len(hexes) and low3.max() < (1 << 21):
        # Three corners name a quad of a conforming mesh: one 63-bit key per face.
        key = (low3[:, 0] << 42) | (low3[:, 1] << 21) | low3[:, 2]
    else:  # more than two million nodes: the four corners as one 16-byte key
        key = np.ascontiguousarray(np.sort(faces, axis=1)).view(
            np.dtype((np.void, faces.dtype.itemsize * 4))).ravel()
    _, first, counts = np.unique(key, return_index=True, return_counts=True)
    once = first[counts == 1]
    return faces[once], once // 6


class Overlay:
    """The mesh's boundary faces, each in the colour of its hexahedron's band, as a Coin
    node in the 3D view (FreeCAD's ElementColor takes minutes for 100,000 elements: its
    cost grows with the square of their number)."""

    def __init__(self, points, faces, colours):
        from pivy import coin

        self.root = coin.SoSeparator()
        material = coin.SoMaterial()
        material.diffuseColor.setValues(0, len(colours), colours.tolist())
        binding = coin.SoMaterialBinding()
        binding.value = coin.SoMaterialBinding.PER_FACE
        coords = coin.SoCoordinate3()
        coords.point.setValues(0, len(points), points.tolist())
        offset = coin.SoPolygonOffset()  # behind the mesh's own element edges
        index = coin.SoIndexedFaceSet()
        import numpy as np

        flat = np.hstack([faces, -np.ones((len(faces), 1), dtype=faces.dtype)]).ravel().tolist()
        index.coordIndex.setValues(0, len(flat), flat)
        for node in (material, binding, coords, offset, index):
            self.root.addChild(node)
        self.scene = None
        view = getattr(FreeCADGui.ActiveDocument, "ActiveView", None)
        if view is not None and hasattr(view, "getSceneGraph"):
            self.scene = view.getSceneGraph()
            self.scene.addChild(self.root)

    def remove(self):
        if self.scene is not None:
            self.scene.removeChild(self.root)
            self.scene = None


def colour_by_quality(mesh_obj):
    """Colours the elements (the Overlay of the mesh's surface); returns (Quality, counts
    per band, the Overlay)."""
    import numpy as np

    arrays = mesh_arrays(mesh_obj)
    points, hexes, ids = arrays
    values = element_quality(mesh_obj, arrays)
    uppers = np.array([b[0] for b in BANDS[:-1]])
    bands = np.searchsorted(uppers, values, side="left")  # value <= upper: that band
    counts = np.bincount(bands, minlength=len(BANDS)).tolist()
    palette_rgb = np.array([b[1] for b in BANDS])
    faces, owner = boundary_faces(hexes)
    used, local = np.unique(faces, return_inverse=True)  # only the surface's nodes
    overlay = Overlay(points[used], local.reshape(faces.shape), palette_rgb[bands[owner]])
    return Quality(ids, values, bands), counts, overlay


class Quality:
    """The scaled Jacobian per element (arrays; sj and colours as dicts when asked)."""

    def __init__(self, ids, values, bands):
        self.ids, self.values, self.bands = ids, values, bands

    @property
    def sj(self):
        return dict(zip(self.ids.tolist(), self.values.tolist()))

    @property
    def colours(self):
        return dict(zip(self.ids.tolist(), (BANDS[b][1] for b in self.bands.tolist())))

    def below(self, threshold):
        """Element ids below the threshold, worst first."""
        rows = [int(r) for r in self.values.argsort() if self.values[r] < threshold]
        return [int(self.ids[r]) for r in rows], [float(self.values[r]) for r in rows]


def worst_nodes(mesh_obj, elements):
    """Node ids of the elements."""
    nodes = set()
    for eid in elements:
        nodes.update(mesh_obj.FemMesh.getElementNodes(eid))
    return sorted(nodes)


class QualityTaskPanel:
    def __init__(self, mesh_obj):
        self.obj = mesh_obj
        global current
        self.quality, counts, self.overlay = colour_by_quality(mesh_obj)
        current = self
        # The mesh shows its element edges over the coloured surface (its own faces and
        # nodes would hide the colours); restored on close.
        self.display_mode = mesh_obj.ViewObject.DisplayMode
        if "Wireframe" in mesh_obj.ViewObject.listDisplayModes():
            mesh_obj.ViewObject.DisplayMode = "Wireframe"
        # The solid the mesh was made from would fight with the coloured surface.
        from VoroHexGui.view_provider import Faded

        part = getattr(mesh_obj, "Part", None)
        vpart = getattr(part, "ViewObject", None)
        self.part_shown = Faded(vpart, {"Visibility": vpart.Visibility} if vpart else {})
        if vpart is not None:
            vpart.Visibility = False
        self.form = QtGui.QWidget()
        self.form.setWindowTitle("Mesh quality")
        self.form.setWindowIcon(QtGui.QIcon(VoroHexGui.resource("icons", "VoroHexQuality.svg")))
        layout = QtGui.QVBoxLayout(self.form)
        values = self.quality.values
        summary = QtGui.QLabel("{} hexahedra, scaled Jacobian min {:.3f}, mean {:.3f}".format(
            len(values), float(values.min()) if len(values) else 0,
            float(values.mean()) if len(values) else 0))
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
        elements, values = self.quality.below(t)
        nodes = worst_nodes(self.obj, elements)
        self.obj.ViewObject.HighlightedNodes = nodes
        self.found.setText("{} hexahedra below {:.2f} ({} nodes highlighted){}".format(
            len(elements), t, len(nodes), "; worst: " + ", ".join(
                "{} ({:.3f})".format(e, v) for e, v in zip(elements[:5], values[:5]))
            if elements else ""))

    @property
    def sj(self):
        return self.quality.sj

    @property
    def colours(self):
        return self.quality.colours if self.quality is not None else {}

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self):
        global current
        current = None
        self.quality = None
        self.overlay.remove()
        self.part_shown.restore()
        self.obj.ViewObject.HighlightedNodes = []
        self.obj.ViewObject.DisplayMode = self.display_mode
        FreeCADGui.Control.closeDialog()
        return True

    def accept(self):
        return self.reject()
