# Task panel of the VoroHex mesh object (the FemMeshGmsh task panel pattern): edit the
# options, Run (with progress and Stop), and see the quality summary and histogram.
import re

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

import VoroHex
import VoroHexGui
from VoroHexGui.histogram import HistogramWidget

# Widget per option name (VoroHex.OPTIONS is the one option table; options without a widget
# are edited in the property editor only).
WIDGETS = {
    "size": "sb_size",
    "max_hexes": "sb_max_hexes",
    "smooth_iterations": "sb_smooth_iterations",
    "smooth_passes": "sb_smooth_passes",
    "smooth_quality_target": "sb_smooth_quality_target",
    "volume_rel_tol": "le_volume_rel_tol",
    "distance_rel_tol": "le_distance_rel_tol",
}


def _get_property(obj, option):
    value = getattr(obj, option.prop)
    return value.Value if hasattr(value, "Value") else value


def summary_text(obj):
    """Plain-text quality summary of a mesh object's result properties."""
    if obj.Status == "error":
        return "Error: " + obj.Message
    if obj.Status != "ok":
        return "Not meshed yet: press Run or OK."
    return ("{} hexahedra, {} nodes\n"
            "Scheme: {}, {} sub-volume(s)\n"
            "Scaled Jacobian: min {:.3f}, mean {:.3f}\n"
            "Before smoothing: min {:.3f}, mean {:.3f}\n"
            "Volume error: {:.2e}").format(obj.HexCount, obj.NodeCount, obj.Scheme or "?",
                                           obj.SubVolumeCount, obj.MinScaledJacobian,
                                           obj.MeanScaledJacobian,
                                           obj.MinScaledJacobianBeforeSmoothing,
                                           obj.MeanScaledJacobianBeforeSmoothing,
                                           obj.VolumeError)


class TaskPanel:
    def __init__(self, obj):
        self.obj = obj
        self.form = FreeCADGui.PySideUic.loadUi(VoroHexGui.resource("ui", "HexMesh.ui"))
        self.form.setWindowIcon(QtGui.QIcon(VoroHexGui.resource("icons", "VoroHex.svg")))
        self.histogram = HistogramWidget(self.form.histogram_host)
        self.form.histogram_host.layout().addWidget(self.histogram)
        for name in ("le_volume_rel_tol", "le_distance_rel_tol"):
            v = QtGui.QDoubleValidator(0.0, 1.0, 15, self.form)
            v.setNotation(QtGui.QDoubleValidator.ScientificNotation)
            getattr(self.form, name).setValidator(v)
        # The stages before meshing, in pipeline order after the Mesh group: the Voronoi
        # graph, the decomposition (with a preview of both and the edge-type legend).
        layout = self.form.layout()
        graph_box = QtGui.QGroupBox("Voronoi graph (what the decomposition cuts along)",
                                    self.form)
        graph_box.setObjectName("gb_graph")
        graph_form = QtGui.QFormLayout(graph_box)
        self.eps = QtGui.QLineEdit(graph_box)
        self.eps.setObjectName("le_eps")
        graph_form.addRow("Eps (x diagonal):", self.eps)
        self.delta = QtGui.QLineEdit(graph_box)
        self.delta.setObjectName("le_delta")
        graph_form.addRow("Delta (x diagonal):", self.delta)
        for w in (self.eps, self.delta):
            v = QtGui.QDoubleValidator(0.0, 0.25, 15, w)
            v.setNotation(QtGui.QDoubleValidator.ScientificNotation)
            w.setValidator(v)
        self.max_depth = QtGui.QSpinBox(graph_box)
        self.max_depth.setObjectName("sb_max_depth")
        self.max_depth.setRange(1, 12)
        graph_form.addRow("Max. octree depth:", self.max_depth)
        dec_box = QtGui.QGroupBox("Decomposition (where no single scheme applies)", self.form)
        dec_box.setObjectName("gb_decomposition")
        dec_form = QtGui.QFormLayout(dec_box)
        self.decompose = QtGui.QCheckBox("Cut into sub-volumes before any fallback", dec_box)
        self.decompose.setObjectName("cb_decompose")
        dec_form.addRow(self.decompose)
        self.sharp_angle = QtGui.QDoubleSpinBox(dec_box)
        self.sharp_angle.setObjectName("sb_sharp_angle")
        self.sharp_angle.setRange(1, 180)
        self.sharp_angle.setSuffix(" \u00b0")
        dec_form.addRow("Sharp angle:", self.sharp_angle)
        self.decomposition_time = QtGui.QDoubleSpinBox(dec_box)
        self.decomposition_time.setObjectName("sb_decomposition_time_limit")
        self.decomposition_time.setRange(1, 3600)
        self.decomposition_time.setSuffix(" s")
        dec_form.addRow("Time limit:", self.decomposition_time)
        for w in (self.eps, self.delta, self.max_depth, self.decompose, self.sharp_angle,
                  self.decomposition_time):
            option = next(o for o in VoroHex.OPTIONS if self._widget(o) is w)
            w.setToolTip(option.doc)
        self.preview = QtGui.QPushButton("Preview graph and decomposition", dec_box)
        self.preview.setObjectName("pb_preview")
        self.preview.setToolTip("Computes the Voronoi graph and the decomposition of the solid "
                                "with these options, as document objects, to see where it "
                                "will be cut (Cancel in the busy dialog stops it)")
        dec_form.addRow(self.preview)
        self.preview_status = QtGui.QLabel("", dec_box)
        self.preview_status.setObjectName("lbl_preview")
        self.preview_status.setWordWrap(True)
        dec_form.addRow(self.preview_status)
        # The previewed graph's edge types: count per type, a check box shows or hides it.
        from VoroHexGui.graph_view import EdgeTypeTable

        self.edge_types = EdgeTypeTable(dec_box)
        self.edge_types.setObjectName("tbl_preview_edge_types")
        self.edge_types.setMinimumHeight(160)
        self.edge_types.setVisible(False)
        dec_form.addRow(self.edge_types)
        after_mesh = layout.indexOf(self.form.gb_params) + 1
        layout.insertWidget(after_mesh, graph_box)
        layout.insertWidget(after_mesh + 1, dec_box)
        self.preview.clicked.connect(self.run_preview)
        # Sub-volumes of the last run; selecting one highlights the nodes of its hexahedra.
        sv_box = QtGui.QGroupBox("Sub-volumes (select one to highlight it)", self.form)
        sv_box.setObjectName("gb_sub_volumes")
        self.sub_volumes = QtGui.QTableWidget(0, 5, sv_box)
        self.sub_volumes.setObjectName("tw_sub_volumes")
        self.sub_volumes.setHorizontalHeaderLabels(["id", "type", "scheme", "hexes", "min SJ"])
        self.sub_volumes.horizontalHeaderItem(1).setToolTip(
            "Vs: swept between two faces of the solid (around an f_s face); Ve: a block, or a "
            "sweep from or to a cut face; -: the tetrahedral fallback")
        self.sub_volumes.verticalHeader().setVisible(False)
        self.sub_volumes.setSelectionBehavior(QtGui.QAbstractItemView.SelectRows)
        self.sub_volumes.setSelectionMode(QtGui.QAbstractItemView.SingleSelection)
        self.sub_volumes.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        self.sub_volumes.horizontalHeader().setStretchLastSection(True)
        self.sub_volumes.setMinimumHeight(80)
        self.sub_volumes.setMaximumHeight(140)
        QtGui.QVBoxLayout(sv_box).addWidget(self.sub_volumes)
        self.form.layout().addWidget(sv_box)
        self.sub_volumes.itemSelectionChanged.connect(self.highlight_sub_volume)
        # Messages of the last run; selecting one selects the model entities it names.
        box = QtGui.QGroupBox("Messages (select one to highlight what it names)", self.form)
        box.setObjectName("gb_diagnostics")
        self.diagnostics = QtGui.QListWidget(box)
        self.diagnostics.setObjectName("lw_diagnostics")
        self.diagnostics.setWordWrap(True)
        self.diagnostics.setMinimumHeight(90)
        QtGui.QVBoxLayout(box).addWidget(self.diagnostics)
        self.form.layout().addWidget(box)
        self.diagnostics.currentRowChanged.connect(self.highlight)
        self.form.pb_run.clicked.connect(self.run)
        self.form.pb_stop.clicked.connect(self.stop)
        self.running = False
        self.stop_requested = False
        # Cancel puts the options back as they were when the panel opened (a stopped run
        # with a tiny size must not stay behind to be recomputed later).
        self.initial = {o.prop: getattr(obj, o.prop) for o in VoroHex.OPTIONS}
        self.initially_touched = "Touched" in obj.State
        self.load()
        self.show_result()
        if self.obj.Status:
            self.form.progress.setValue(100 if self.obj.Status == "ok" else 0)
            self.form.progress.setFormat("last run: " + self.obj.Status)
        else:
            self.form.progress.setFormat("not run yet")

    # Widgets <-> properties ------------------------------------------------------------
    def _widget(self, option):
        own = {"decompose": "decompose", "decomposition_time_limit": "decomposition_time",
               "sharp_angle": "sharp_angle", "eps": "eps", "delta": "delta",
               "max_depth": "max_depth"}
        if option.name in own:
            return getattr(self, own[option.name], None)
        name = WIDGETS.get(option.name)
        return getattr(self.form, name) if name else None

    def load(self):
        self.form.lbl_part.setText(self.obj.Part.Label if self.obj.Part else "(none)")
        for option in VoroHex.OPTIONS:
            w, value = self._widget(option), _get_property(self.obj, option)
            if isinstance(w, QtGui.QLineEdit):
                w.setText("{:g}".format(value))
            elif isinstance(w, QtGui.QCheckBox):
                w.setChecked(bool(value))
            elif w is not None:
                w.setValue(value)

    def store(self):
        """Writes the widgets into the properties; True if anything changed."""
        changed = False
        for option in VoroHex.OPTIONS:
            w = self._widget(option)
            if w is None:
                continue
            if isinstance(w, QtGui.QLineEdit):
                try:
                    value = float(w.text())
                except ValueError:
                    continue  # keep the property; the validator flags the text
            elif isinstance(w, QtGui.QCheckBox):
                value = w.isChecked()
            else:
                value = w.value()
            if value != _get_property(self.obj, option):
                setattr(self.obj, option.prop, value)
                changed = True
        return changed

    # Meshing ---------------------------------------------------------------------------
    def on_progress(self, stage, fraction):
        self.form.progress.setValue(int(round(100 * max(0.0, min(1.0, fraction)))))
        self.form.progress.setFormat("{}: %p%".format(stage))
        QtGui.QApplication.processEvents()  # meshing runs on this thread; keep Stop live
        return not self.stop_requested

    def run(self):
        if self.running:
            return
        self.store()
        self.running, self.stop_requested = True, False
        self.form.pb_run.setEnabled(False)
        self.form.pb_stop.setEnabled(True)
        self.form.progress.setValue(0)
        self.form.progress.setFormat("meshing: %p%")
        self.form.lbl_status.setText("Meshing...")
        QtGui.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
        proxy = self.obj.Proxy
        try:
            proxy.progress = self.on_progress
            self.obj.touch()
            self.obj.Document.recompute()
        finally:
            proxy.progress = None
            QtGui.QApplication.restoreOverrideCursor()
            self.running = False
            self.form.pb_run.setEnabled(True)
            self.form.pb_stop.setEnabled(False)
        if self.obj.Status == "ok":
            self.form.progress.setValue(100)
            self.form.progress.setFormat("done")
            if self.obj.Part and self.obj.Part.ViewObject:
                self.obj.Part.ViewObject.Visibility = False  # so the mesh is seen
        else:
            self.form.progress.setFormat("failed")
        self.show_result()

    def stop(self):
        self.stop_requested = True

    def run_preview(self):
        """Voronoi graph and decomposition of the solid as document objects (one undo step;
        a cancelled preview leaves the document as it was)."""
        part = self.obj.Part
        if part is None or self.running:
            return
        import VoroHexGraph
        import VoroHexObjects
        import VoroHexParts
        from VoroHexGui.commands import run_cancellable

        made = {}

        self.store()  # the preview uses the panel's graph and decomposition options
        options = VoroHexObjects.graph_options_of(self.obj)
        options["sharp_angle"] = self.obj.SharpAngle

        def work(busy):
            made["graph"] = VoroHexGraph.makeVoronoiGraph(self.obj.Document, part, progress=busy,
                                                          **options)
            if not busy.cancelled:
                made["parts"] = VoroHexParts.makeDecomposition(self.obj.Document, part,
                                                               progress=busy, **options)

        if run_cancellable(self.obj.Document, "VoroHex preview", work) is None:
            self.preview_status.setText("Preview cancelled.")
            return
        graph, parts = made["graph"], made["parts"]
        text = "Graph: {}.".format(graph.Message)
        if parts.Status in ("ok", "partial"):
            n = parts.SubVolumeCount
            text += " Decomposition: {} sub-volume{} ({}).".format(
                n, "" if n == 1 else "s", ", ".join(sorted(set(parts.Schemes))))
        else:
            text += " Decomposition failed: {}".format(parts.Message)
        self.preview_status.setText(text)
        self.edge_types.set_graph(graph)
        self.edge_types.setVisible(True)
        for o in (graph, parts):
            if o.ViewObject is not None:
                o.ViewObject.Visibility = True
        if part.ViewObject is not None:
            part.ViewObject.Transparency = 70

    def highlight_sub_volume(self):
        """Highlights the nodes of the selected sub-volume's hexahedra in the mesh view."""
        vobj = self.obj.ViewObject
        if vobj is None or not hasattr(vobj, "HighlightedNodes"):
            return
        rows = {i.row() for i in self.sub_volumes.selectedIndexes()}
        counts = list(self.obj.SubVolumeHexCounts)
        if not rows or min(rows) >= len(counts):
            vobj.HighlightedNodes = []
            return
        # The hexahedra of sub-volume k follow those of 1 .. k-1 (meshes are joined in that
        # order), so its elements are one range of ids.
        row = min(rows)
        first = sum(counts[:row]) + 1
        femmesh, nodes = self.obj.FemMesh, set()
        for e in range(first, first + counts[row]):
            nodes.update(femmesh.getElementNodes(e))
        vobj.HighlightedNodes = sorted(nodes)
        vobj.Visibility = True

    def highlight(self, row):
        """Selects, on the linked solid, the faces, edges and vertices message `row` names."""
        FreeCADGui.Selection.clearSelection()
        entities = list(self.obj.DiagnosticEntities)
        part = self.obj.Part
        if part is None or not 0 <= row < len(entities):
            return
        for name in entities[row].split(","):
            name = name.strip()
            if re.match(r"^(Face|Edge|Vertex)[0-9]+$", name):
                try:
                    FreeCADGui.Selection.addSelection(part, name)
                except Exception:  # an entity of a glued whole the part does not number
                    pass
        if part.ViewObject is not None and entities[row]:
            part.ViewObject.Visibility = True  # the named entities are on the solid

    def show_result(self):
        self.sub_volumes.setRowCount(0)
        if self.obj.Status == "ok":
            types = list(getattr(self.obj, "SubVolumeTypes", []))
            rows = list(zip(self.obj.SubVolumeSchemes, self.obj.SubVolumeHexCounts,
                            self.obj.SubVolumeMinScaledJacobian))
            self.sub_volumes.setRowCount(len(rows))
            for k, (scheme, hexes, min_sj) in enumerate(rows):
                kind = types[k] if k < len(types) else ""
                for c, text in enumerate((str(k + 1), kind, scheme, str(hexes),
                                          "{:.3f}".format(min_sj))):
                    self.sub_volumes.setItem(k, c, QtGui.QTableWidgetItem(text))
            self.sub_volumes.resizeColumnsToContents()
        self.diagnostics.clear()
        colours = {"error": "#b00000", "warning": "#a05a00"}
        entities = list(self.obj.DiagnosticEntities)
        for k, line in enumerate(self.obj.Diagnostics):
            item = QtGui.QListWidgetItem(line)
            names = entities[k] if k < len(entities) else ""
            item.setToolTip(line + ("\nNames: " + names if names else ""))
            severity = line.split(" ", 1)[0]
            if severity in colours:
                item.setForeground(QtGui.QBrush(QtGui.QColor(colours[severity])))
            self.diagnostics.addItem(item)
        self.form.lbl_status.setText(summary_text(self.obj))
        colour = "#b00000" if self.obj.Status == "error" else "palette(text)"
        self.form.lbl_status.setStyleSheet("color: {}".format(colour))
        self.histogram.set_counts(self.obj.ScaledJacobianHistogram
                                  if self.obj.Status == "ok" else [])

    # Task dialog protocol --------------------------------------------------------------
    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def accept(self):
        if self.running:
            return False
        if self.store() or self.obj.Status != "ok":
            self.run()
        self._close()
        return True

    def reject(self):
        if self.running:
            self.stop_requested = True
            return False
        for prop, value in self.initial.items():
            if getattr(self.obj, prop) != value:
                setattr(self.obj, prop, value)
        if not self.initially_touched and self.obj.Status == "ok":
            self.obj.purgeTouched()  # its mesh is the one of these options
        self._close()
        return True

    def _close(self):
        gui_doc = FreeCADGui.getDocument(self.obj.Document.Name)
        if gui_doc is not None:
            gui_doc.resetEdit()
        FreeCAD.Console.PrintLog("VoroHex: {}: {}\n".format(self.obj.Label, self.obj.Message))
