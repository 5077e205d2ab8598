# Task panel of the VoroHex mesh object, laid out like FreeCAD's own mesh panels: the
# solid, the size (with the hex count to expect), the element order, Run/Stop, and the
# result (scheme, counts, quality, histogram, a banner when the mesh is not structured).
# Everything else sits in collapsed sections below. Meshing runs in a child process
# (VoroHexJobs), so the GUI never waits for it and Stop ends it at once.
import re

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

import VoroHex
import VoroHexGui
import VoroHexJobs
import VoroHexObjects
from VoroHexGui import widgets
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

# Schemes that are not a structured (block, sweep, midpoint) mesh: the grid mesher (the
# fallback, issue 23) and the tetrahedral split it replaced (still an option for comparison).
UNSTRUCTURED = ("tet-split", "grid")

# The hex count above which Run asks before it starts (a long run and much memory).
CONFIRM_ABOVE = 2_000_000


def _get_property(obj, option):
    value = getattr(obj, option.prop)
    return value.Value if hasattr(value, "Value") else value


# The single-solid schemes, in the order the pipeline tries them by default, then grid.
KNOWN_SCHEMES = tuple(VoroHex._core.scheme_names())


def scheme_list(text):
    """ "map, sweep" -> ["map", "sweep"] (empty names dropped)."""
    return [t.strip() for t in (text or "").split(",") if t.strip()]


def unknown_schemes(names):
    return [n for n in names if n not in KNOWN_SCHEMES]


def unstructured_parts(scheme):
    """The schemes of "sweep+tet-split" that are not structured (empty: all structured)."""
    return [s for s in (scheme or "").split("+") if s in UNSTRUCTURED]


# The properties a run sets besides the mesh and its figures: its outcome and messages
# (a failed run keeps the previous mesh and sets only these).
RUN_STATUS = ("Status", "Message", "Diagnostics", "DiagnosticEntities")


def run_status(obj):
    """The RUN_STATUS properties' values (those an object of an older version has)."""
    return {p: getattr(obj, p) for p in RUN_STATUS if hasattr(obj, p)}


def summary_text(obj):
    """Plain-text quality summary of a mesh object's result properties."""
    if obj.Status == "error":
        return "Error: " + obj.Message
    if obj.Status != "ok":
        return "Not meshed yet: press Run."
    return ("Scheme: {}, {} sub-volume(s)\n"
            "{:,} hexahedra, {:,} nodes\n"
            "Scaled Jacobian: min {:.3f}, mean {:.3f}\n"
            "Before smoothing: min {:.3f}, mean {:.3f}\n"
            "Volume error: {:.2e}").format(obj.Scheme or "?", obj.SubVolumeCount, obj.HexCount,
                                           obj.NodeCount, obj.MinScaledJacobian,
                                           obj.MeanScaledJacobian,
                                           obj.MinScaledJacobianBeforeSmoothing,
                                           obj.MeanScaledJacobianBeforeSmoothing,
                                           obj.VolumeError)


def mesh_job(shape, options):
    """A VoroHexJobs.Job meshing `shape` with keyword `options` in a child process; its
    result is VoroHexObjects.mesh_payload()."""
    return VoroHexJobs.Job(VoroHexObjects.mesh_work, shape.exportBrepToString(), options)


def trial_sizes(size):
    """Coarser sizes to try when the mesh was not structured (a sweep whose layers fold at
    one size can work at another)."""
    return [size * f for f in (1.5, 2.0, 3.0)]


def suggestion_job(shape, options, sizes):
    """VoroHexObjects.trials_work in a child process: the sizes that give a structured
    mesh."""
    return VoroHexJobs.Job(VoroHexObjects.trials_work, shape.exportBrepToString(), options,
                           sizes)


class TaskPanel:
    def __init__(self, obj):
        self.obj = obj
        self.form = FreeCADGui.PySideUic.loadUi(VoroHexGui.resource("ui", "HexMesh.ui"))
        self.form.setWindowIcon(QtGui.QIcon(VoroHexGui.resource("icons", "VoroHex.svg")))
        self.histogram = HistogramWidget(self.form.histogram_host)
        widgets.layout_of(self.form.histogram_host).addWidget(self.histogram)
        for name in ("le_volume_rel_tol", "le_distance_rel_tol"):
            v = QtGui.QDoubleValidator(0.0, 1.0, 15, self.form)
            v.setNotation(QtGui.QDoubleValidator.ScientificNotation)
            getattr(self.form, name).setValidator(v)
        self.runner = None  # the meshing job's poller while it runs
        self.builder = None  # the FemMesh being built from a finished job
        self.trials = None  # the suggestion job
        self.close_when_done = False
        self.payload = None
        self.suggested_size = None
        self._build_advanced()
        # Labels above their fields where the panel is narrower than label and field side by
        # side: FreeCAD's Combo View opens about 250 px wide, and the panel's minimum was 339
        # px with no horizontal scroll bar (the size field, Stop, the histogram cut off).
        for form in self.form.findChildren(QtGui.QFormLayout):
            form.setRowWrapPolicy(QtGui.QFormLayout.WrapLongRows)
        self._bind_element_order()
        self.form.pb_run.clicked.connect(self.run)
        self.form.pb_stop.clicked.connect(self.stop)
        self.form.pb_suggestion.clicked.connect(self.use_suggestion)
        self.form.sb_size.valueChanged.connect(self.update_estimate)
        self.form.sb_max_hexes.valueChanged.connect(self.update_estimate)
        # Cancel puts the options back as they were when the panel opened, or as the last
        # run that made the mesh had them: the mesh and its options stay together (a
        # stopped run with a tiny size must not stay behind to be recomputed later, nor a
        # size beside the mesh another size made). A run that failed is undone too (its
        # error status and messages), and a mesh object never meshed goes again.
        self.initial = {o.prop: getattr(obj, o.prop) for o in VoroHex.OPTIONS}
        self.initially_touched = "Touched" in obj.State
        self.initial_result = run_status(obj)
        self.meshed = bool(obj.Status)  # a mesh (or an error) was made before or here
        self.load()
        self.show_result()
        previews = [obj.Document.getObject(n) for n in getattr(obj, "PreviewObjects", [])]
        if len(previews) == 2 and None not in previews:
            self.show_preview(*previews)
        if self.obj.Status:
            self.form.progress.setValue(100 if self.obj.Status == "ok" else 0)
            self.form.progress.setFormat("last run: " + self.obj.Status)
        else:
            self.form.progress.setFormat("not run yet")

    # Layout ---------------------------------------------------------------------------
    def _build_advanced(self):
        """Everything but the size and the order, in collapsed sections after the result."""
        layout = widgets.layout_of(self.form)
        # The stages before meshing: the Voronoi graph, the decomposition (with a preview
        # of both and the edge-type legend).
        graph_box = QtGui.QWidget()
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
        dec_box = QtGui.QWidget()
        dec_form = QtGui.QFormLayout(dec_box)
        self.decompose = QtGui.QCheckBox("Cut into sub-volumes first", dec_box)
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
        limits = widgets.layout_of(self.form.gb_limits)
        self.fallback = QtGui.QCheckBox("Fallback (grid mesher)")
        self.fallback.setObjectName("cb_fallback")
        limits.addRow(self.fallback)
        self.schemes = QtGui.QLineEdit()
        self.schemes.setObjectName("le_schemes")
        self.schemes.setPlaceholderText(", ".join(VoroHex._core.MeshOptions().schemes))
        self.schemes.textChanged.connect(self._check_schemes)
        limits.addRow("Schemes:", self.schemes)
        self.time_limit = QtGui.QDoubleSpinBox()
        self.time_limit.setObjectName("sb_time_limit")
        self.time_limit.setRange(0, 1e6)
        self.time_limit.setSuffix(" s")
        self.time_limit.setSpecialValueText("none")
        limits.addRow("Time limit:", self.time_limit)
        for w in (self.eps, self.delta, self.max_depth, self.decompose, self.sharp_angle,
                  self.decomposition_time, self.fallback, self.time_limit, self.schemes):
            option = next(o for o in VoroHex.OPTIONS if self._widget(o) is w)
            w.setToolTip(option.doc)
        self.preview = QtGui.QPushButton("Preview graph and cuts", dec_box)
        self.preview.setObjectName("pb_preview")
        self.preview.setToolTip("Computes the Voronoi graph and the decomposition of the solid "
                                "with these options, as document objects (replacing the "
                                "previous preview), to see where it will be cut")
        dec_form.addRow(self.preview)
        self.preview_status = QtGui.QLabel("", dec_box)
        self.preview_status.setObjectName("lbl_preview")
        self.preview_status.setWordWrap(True)
        dec_form.addRow(self.preview_status)
        from VoroHexGui.graph_view import EdgeTypeTable

        self.edge_types = EdgeTypeTable(dec_box)
        self.edge_types.setObjectName("tbl_preview_edge_types")
        self.edge_types.setVisible(False)
        dec_form.addRow(self.edge_types)
        self.preview.clicked.connect(self.run_preview)
        # Sub-volumes of the last run; selecting one highlights the nodes of its hexahedra.
        self.sub_volumes = QtGui.QTableWidget(0, 5)
        self.sub_volumes.setObjectName("tw_sub_volumes")
        self.sub_volumes.setHorizontalHeaderLabels(["id", "type", "scheme", "hexes", "min SJ"])
        self.sub_volumes.horizontalHeaderItem(1).setToolTip(
            "Vs: swept between two faces of the solid (around an f_s face); Ve: a block, or a "
            "sweep from or to a cut face; -: the fallback (grid mesher)")
        self.sub_volumes.verticalHeader().setVisible(False)
        self.sub_volumes.setSelectionBehavior(QtGui.QAbstractItemView.SelectRows)
        self.sub_volumes.setSelectionMode(QtGui.QAbstractItemView.SingleSelection)
        self.sub_volumes.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        self.sub_volumes.horizontalHeader().setStretchLastSection(True)
        self.sub_volumes.setMinimumHeight(80)
        self.sub_volumes.setMaximumHeight(160)
        self.sub_volumes.itemSelectionChanged.connect(self.highlight_sub_volume)
        # Messages of the last run; selecting one selects the model entities it names.
        self.diagnostics = QtGui.QListWidget()
        self.diagnostics.setObjectName("lw_diagnostics")
        self.diagnostics.setWordWrap(True)
        self.diagnostics.setMinimumHeight(90)
        self.diagnostics.currentRowChanged.connect(self.highlight)
        self.sections = {}
        spacer = layout.indexOf(self.form.gb_quality) + 1
        for key, title, content in (
                ("sub_volumes", "Sub-volumes", self.sub_volumes),
                ("messages", "Messages", self.diagnostics),
                ("limits", "Advanced: limits, fallback", self.form.gb_limits),
                ("graph", "Advanced: Voronoi graph", graph_box),
                ("decomposition", "Advanced: decomposition", dec_box),
                ("smoothing", "Advanced: smoothing", self.form.gb_smoothing),
                ("check", "Advanced: tolerances", self.form.gb_check)):
            layout.removeWidget(content)
            if isinstance(content, QtGui.QGroupBox):
                content.setTitle("")
            section = widgets.Section(title, content, self.form, name="sec_" + key)
            layout.insertWidget(spacer, section)
            spacer += 1
            self.sections[key] = section

    def _bind_element_order(self):
        """Element order: the ElementOrder property ("1st"/"2nd", issue 21); an object
        without it (made by an older version, not yet restored) shows 1st, disabled."""
        combo = self.form.cb_element_order
        if hasattr(self.obj, "ElementOrder"):
            try:
                values = list(self.obj.getEnumerationsOfProperty("ElementOrder"))
            except Exception:  # not an enumeration: a string property
                values = ["1st", "2nd"]
            combo.clear()
            combo.addItems(values)
            combo.setToolTip("Linear (8-node) or quadratic hexahedra (property ElementOrder)")
            combo.setEnabled(True)
        else:
            combo.setCurrentIndex(0)
            combo.setEnabled(False)
            combo.setToolTip("second order: coming")

    # Widgets <-> properties ------------------------------------------------------------
    def _widget(self, option):
        own = {"decompose": "decompose", "decomposition_time_limit": "decomposition_time",
               "sharp_angle": "sharp_angle", "eps": "eps", "delta": "delta",
               "max_depth": "max_depth", "fallback": "fallback", "time_limit": "time_limit",
               "schemes": "schemes"}
        if option.name in own:
            return getattr(self, own[option.name], None)
        name = WIDGETS.get(option.name)
        return getattr(self.form, name) if name else None

    def load(self):
        self.form.lbl_part.setText(self.obj.Part.Label if self.obj.Part else "(none)")
        for option in VoroHex.OPTIONS:
            w, value = self._widget(option), _get_property(self.obj, option)
            if option.kind == "schemes":
                w.setText(", ".join(scheme_list(value)))
            elif isinstance(w, QtGui.QLineEdit):
                w.setText("{:g}".format(value))
            elif isinstance(w, QtGui.QCheckBox):
                w.setChecked(bool(value))
            elif w is not None:
                w.setValue(value)
        if self.form.cb_element_order.isEnabled():
            k = self.form.cb_element_order.findText(str(self.obj.ElementOrder))
            self.form.cb_element_order.setCurrentIndex(max(k, 0))
        self.update_estimate()

    def store(self):
        """Writes the widgets into the properties; True if anything changed."""
        changed = False
        for option in VoroHex.OPTIONS:
            w = self._widget(option)
            if w is None:
                continue
            if option.kind == "schemes":
                names = scheme_list(w.text()) or list(VoroHex._core.MeshOptions().schemes)
                if unknown_schemes(names):
                    continue  # keep the property; _check_schemes flags the text
                value = ",".join(names)
                if names == scheme_list(_get_property(self.obj, option)):
                    continue
            elif isinstance(w, QtGui.QLineEdit):
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
        combo = self.form.cb_element_order
        if combo.isEnabled() and combo.currentText() != str(self.obj.ElementOrder):
            self.obj.ElementOrder = combo.currentText()
            changed = True
        return changed

    def _check_schemes(self, text):
        """Flags scheme names that do not exist (the property keeps its value)."""
        unknown = unknown_schemes(scheme_list(text))
        self.schemes.setStyleSheet("background-color: #f4cccc;" if unknown else "")
        self.schemes.setToolTip(
            "Unknown scheme{}: {}; the schemes are {}".format(
                "s" if len(unknown) > 1 else "", ", ".join(unknown), ", ".join(KNOWN_SCHEMES))
            if unknown else next(o.doc for o in VoroHex.OPTIONS if o.name == "schemes")
            + " (empty: " + ", ".join(VoroHex._core.MeshOptions().schemes) + ")")

    # The hex count to expect -----------------------------------------------------------
    def estimate(self, size=None):
        """(count, how): the hexahedra to expect at `size` (default: the size field)."""
        part = self.obj.Part
        if part is None:
            return None, ""
        size = self.form.sb_size.value() if size is None else size
        shape = part.Shape
        size = size or VoroHexObjects.automatic_size(shape)
        last = self.obj.SizeUsed if self.obj.Status == "ok" else 0
        if last > 0 and self.obj.HexCount > 0:  # scaled from the last run: knows its scheme
            return self.obj.HexCount * (last / size) ** 3, "scaled from the last run"
        try:
            sizes = VoroHexObjects.region_sizes(self.obj)
        except ValueError:  # a bad region: Run says so
            sizes = {}
        low, high = VoroHexObjects.predicted_hexes(shape, size, sizes,
                                                   getattr(self.obj, "SizeGrading", 0.3))
        return low, "volume / size\u00b3{}; up to {} if the fallback meshes it".format(
            ", plus the layers graded around {} local sizes".format(len(sizes)) if sizes else "",
            VoroHexObjects.format_count(high))

    def update_estimate(self, *args):
        count, how = self.estimate()
        label = self.form.lbl_estimate
        if count is None:
            label.setText("")
            return
        over = count > self.form.sb_max_hexes.value()
        label.setText("\u2248 {} hexahedra{}".format(
            VoroHexObjects.format_count(count), " (over the limit)" if over else ""))
        label.setToolTip("Hexahedra to expect ({}); the limit is {:,} (Advanced: limits)"
                         .format(how, self.form.sb_max_hexes.value()))
        label.setStyleSheet("color: #b00000" if over else "")

    # Meshing ---------------------------------------------------------------------------
    @property
    def running(self):
        return self.runner is not None or self.builder is not None

    def _set_running(self, on):
        self.form.pb_run.setEnabled(not on)
        self.form.pb_stop.setEnabled(on)
        self.preview.setEnabled(not on)

    def run(self):
        if self.running:
            return
        self.stop_trials()
        self.store()
        part = self.obj.Part
        error = VoroHexObjects.source_error(part, True) or VoroHexObjects.refusal(self.obj)
        if error is not None:  # refused before any work starts
            self.refuse(error)
            return
        count, _ = self.estimate(self.obj.TargetSize.Value)
        if count > CONFIRM_ABOVE and not self.confirm(count):
            return
        try:
            options = VoroHexObjects.options_of(self.obj)
            VoroHex.validate_options(**options)
        except (TypeError, ValueError) as e:
            self.refuse(str(e).replace("VoroHex: ", ""))
            return
        self._set_running(True)
        self.form.progress.setValue(0)
        self.form.progress.setFormat("starting")
        self.form.lbl_status.setText("Meshing...")
        self.form.lbl_banner.setVisible(False)
        self.form.pb_suggestion.setVisible(False)
        self.runner = widgets.JobRunner(mesh_job(part.Shape, options), self.on_progress,
                                        self.on_done, parent=self.form)

    def confirm(self, count):
        answer = QtGui.QMessageBox.question(
            FreeCADGui.getMainWindow(), "VoroHex: a large mesh",
            "About {} hexahedra are expected: meshing may take long and use much memory. "
            "Mesh anyway?".format(VoroHexObjects.format_count(count)),
            QtGui.QMessageBox.Yes | QtGui.QMessageBox.No, QtGui.QMessageBox.No)
        return answer == QtGui.QMessageBox.Yes

    def refuse(self, error):
        """A run that does not start: said in the panel and the Report view; the mesh and
        the document stay as they were."""
        FreeCAD.Console.PrintWarning("VoroHex: {}: not meshed: {}\n".format(self.obj.Label,
                                                                            error))
        self.show_banner("Not meshed: " + error, "#b00000")
        self.form.progress.setValue(0)
        self.form.progress.setFormat("refused")
        widgets.scroll_to(self.form.gb_quality)

    def on_progress(self, job):
        self.form.progress.setValue(int(round(100 * max(0.0, min(1.0, job.fraction)))))
        self.form.progress.setFormat("{}: %p%  ({:.1f} s)".format(job.stage, job.elapsed))

    def on_done(self, job):
        self.runner = None
        try:
            payload = job.result()
        except VoroHexJobs.Cancelled:
            self.finished("Stopped by the user after {:.1f} s; {}.".format(
                job.elapsed, self.kept_text()), "stopped")
            FreeCAD.Console.PrintMessage("VoroHex: meshing {} stopped by the user\n".format(
                self.obj.Label))
            return
        except RuntimeError as e:
            why = str(e).strip().splitlines()[-1] if str(e).strip() else "failed"
            # The child's exception as its last line says it ("VoroHex.ShapeError: VoroHex:
            # cannot read the solid: ..."): the message only.
            kind = re.match(r"^(?:VoroHex: )?(?:VoroHex\.)?(\w*Error): ", why)
            why = re.sub(r"^(VoroHex: )?(VoroHex\.)?\w*Error: (VoroHex: )?", "", why)
            self.obj.Status, self.obj.Message = "error", why
            # In the Messages list too (it showed none for such a failure): its code from the
            # exception's name (ShapeError: shape_error).
            code = re.sub(r"(?<!^)([A-Z])", r"_\1", kind.group(1)).lower() if kind else "failed"
            VoroHexObjects.record_diagnostics(
                self.obj, [VoroHexObjects.Diagnostic("error", code, why, [])])
            self.obj.purgeTouched()
            FreeCAD.Console.PrintError("VoroHex: {}: {}\n".format(self.obj.Label, why))
            self.finished(None, "failed")
            return
        if not payload["ok"]:
            self.obj.Proxy.apply(self.obj, payload)
            self.obj.purgeTouched()
            FreeCAD.Console.PrintWarning("VoroHex: {}: {}\n".format(self.obj.Label,
                                                                    payload["message"]))
            self.finished(None, "failed")
            return
        self.payload = payload
        self.builder = VoroHexObjects.FemMeshBuilder(payload)
        self.form.progress.setFormat("FemMesh: %p%")
        QtCore.QTimer.singleShot(0, self._build_step)

    def _build_step(self):
        """Adds the FemMesh's elements a slice at a time (the GUI stays live)."""
        if self.builder is None:  # stopped
            return
        if not self.builder.step(0.04):
            self.form.progress.setValue(int(100 * self.builder.fraction))
            QtCore.QTimer.singleShot(0, self._build_step)
            return
        femmesh, self.builder = self.builder.femmesh, None
        self.obj.Proxy.apply(self.obj, self.payload, femmesh)
        self.obj.purgeTouched()  # this mesh is the one of these options: no recompute
        # What Cancel keeps from now on: this mesh with the options that made it.
        self.initial = {o.prop: getattr(self.obj, o.prop) for o in VoroHex.OPTIONS}
        self.initially_touched = False
        self.initial_result = run_status(self.obj)
        self.meshed = True
        if self.obj.Part and self.obj.Part.ViewObject:
            self.obj.Part.ViewObject.Visibility = False  # so the mesh is seen
        if self.obj.ViewObject is not None:
            self.obj.ViewObject.Visibility = True
        closing = self.close_when_done  # OK pressed: the panel closes, no trials for it
        self.finished(None, "done")
        if unstructured_parts(self.obj.Scheme) and not closing:
            self.start_trials()

    def finished(self, status_text, progress_text):
        self._set_running(False)
        self.form.progress.setValue(100 if progress_text == "done" else 0)
        self.form.progress.setFormat(progress_text)
        self.show_result()
        if status_text:
            self.form.lbl_status.setText(status_text)
        widgets.scroll_to(self.form.gb_quality)
        if self.close_when_done:
            self.close_when_done = False
            if progress_text == "done":
                self._close()

    def kept_text(self):
        """What a stopped run leaves: the mesh before, or none."""
        return "the previous mesh is kept" if self.obj.Status == "ok" else "nothing was meshed"

    def stop(self):
        """Stop: the child process is killed at once, whatever stage it is in."""
        if self.runner is not None:
            self.runner.stop()
        elif self.builder is not None:  # meshed, the FemMesh still being built
            self.builder = None
            self.finished("Stopped by the user; {}.".format(self.kept_text()), "stopped")
            FreeCAD.Console.PrintMessage("VoroHex: meshing {} stopped by the user\n".format(
                self.obj.Label))
        self.stop_trials()

    # Not structured: a banner, and sizes that give a structured mesh -------------------
    def show_banner(self, text, colour="#8a5a00"):
        if self.form is None:  # the panel has closed
            return
        banner = self.form.lbl_banner
        banner.setText(text)
        banner.setStyleSheet("QLabel {{ background: {}; color: white; padding: 6px; "
                             "border-radius: 3px; }}".format(colour))
        banner.setVisible(True)

    def structured_banner(self):
        """The banner's text for the current result, or None when it is structured."""
        parts = unstructured_parts(self.obj.Scheme)
        if self.obj.Status != "ok" or not parts:
            return None
        what = {"tet-split": "the tetrahedral fallback (tetrahedra split into hexahedra)",
                "grid": "the grid mesher"}
        return ("Not a structured mesh: {} meshed {}, so expect poorer elements."
                .format(" and ".join(what[p] for p in parts),
                        "this solid" if self.obj.SubVolumeCount <= 1 else "some solids"))

    def start_trials(self):
        part = self.obj.Part
        size = self.obj.SizeUsed
        if part is None or size <= 0:
            return
        self.trials = widgets.JobRunner(
            suggestion_job(part.Shape, VoroHexObjects.options_of(self.obj), trial_sizes(size)),
            lambda job: None, self.on_trials, parent=self.form)
        self.show_banner(self.structured_banner() + " Trying coarser sizes for a structured "
                         "mesh...")

    def stop_trials(self):
        if self.trials is not None:
            self.trials.stop()
            self.trials = None

    def on_trials(self, job):
        self.trials = None
        if self.form is None:  # the panel closed while the sizes were tried
            return
        try:
            found = job.result()
        except (VoroHexJobs.Cancelled, RuntimeError):
            found = None
        text = self.structured_banner()
        if text is None:
            return
        tried = ", ".join("{:.3g}".format(s) for s in trial_sizes(self.obj.SizeUsed))
        if found:
            size, scheme, hexes = found[0]
            self.suggested_size = size
            self.show_banner("{} Size {:.3g} gives a {} ({:,} hexahedra).".format(
                text, size, scheme, hexes))
            self.form.pb_suggestion.setText("Use size {:.3g}".format(size))
            self.form.pb_suggestion.setVisible(True)
        elif found is not None:
            self.show_banner("{} No coarser size ({} mm) gives a structured mesh either: the "
                             "solid's shape, not the size, is what no scheme accepts."
                             .format(text, tried))
        else:
            self.show_banner(text)

    def use_suggestion(self):
        if self.suggested_size:
            self.form.sb_size.setValue(self.suggested_size)
            self.form.pb_suggestion.setVisible(False)
            self.run()

    # Preview ---------------------------------------------------------------------------
    def run_preview(self):
        """Voronoi graph and decomposition of the solid as document objects, replacing the
        previous preview of this mesh."""
        part = self.obj.Part
        if part is None or self.running:
            return
        from VoroHexGui import commands

        self.store()  # the preview uses the panel's graph and decomposition options
        options = VoroHexObjects.graph_options_of(self.obj)
        options["sharp_angle"] = self.obj.SharpAngle
        self.preview.setEnabled(False)
        self.preview_status.setText("Computing the Voronoi graph and the decomposition...")
        commands.make_preview(self.obj, part, options, self.preview_done)

    def preview_done(self, made, error):
        self.preview.setEnabled(not self.running)
        if made is None:
            self.preview_status.setText(error or "Preview stopped.")
            return
        self.show_preview(*made)

    def show_preview(self, graph, parts):
        """The preview's summary and the graph's edge types, as after Preview (also when the
        panel reopens on a mesh whose preview objects are still in the document)."""
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
        self.edge_types.fit_rows()

    # Highlights ------------------------------------------------------------------------
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

    def clear_highlights(self):
        vobj = self.obj.ViewObject
        if vobj is not None and hasattr(vobj, "HighlightedNodes") and vobj.HighlightedNodes:
            vobj.HighlightedNodes = []
        FreeCADGui.Selection.clearSelection()

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
        self.sections["sub_volumes"].setTitle("Sub-volumes ({})".format(
            self.sub_volumes.rowCount()))
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
        self.sections["messages"].setTitle("Messages ({})".format(self.diagnostics.count()))
        self.form.lbl_status.setText(summary_text(self.obj))
        colour = "#b00000" if self.obj.Status == "error" else "palette(text)"
        self.form.lbl_status.setStyleSheet("color: {}".format(colour))
        self.histogram.set_counts(self.obj.ScaledJacobianHistogram
                                  if self.obj.Status == "ok" else [])
        banner = self.structured_banner()
        if banner:
            self.show_banner(banner)
        else:
            self.form.lbl_banner.setVisible(False)
        self.form.pb_suggestion.setVisible(False)
        self.update_estimate()

    # Task dialog protocol --------------------------------------------------------------
    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def accept(self):
        """OK: the mesh of the options shown. Runs (and closes when done) unless the mesh is
        already theirs: the options differ from those of the mesh (a Run stopped or refused
        has stored its options already, so what store() changes now is not enough to tell),
        or the last run failed. A run refused keeps the panel open: it says why."""
        if self.running:
            return False
        self.store()
        if self.options_differ() or self.obj.Status != "ok":
            self.close_when_done = True  # closes when the run is done
            self.run()
            if self.running:
                return False
            self.close_when_done = False
            if self.obj.Status != "ok" or self.options_differ():
                return False  # refused or failed: the panel says why
        self._close()
        return True

    def options_differ(self):
        """Whether the object's options differ from those of its mesh (self.initial)."""
        return any(getattr(self.obj, prop) != value for prop, value in self.initial.items())

    def reject(self):
        if self.running:
            self.stop()
        self.stop_trials()
        never_run = not self.meshed
        for prop, value in list(self.initial.items()) + list(self.initial_result.items()):
            if getattr(self.obj, prop) != value:
                setattr(self.obj, prop, value)
        if not self.initially_touched and self.obj.Status == "ok":
            self.obj.purgeTouched()  # its mesh is the one of these options
        doc = self.obj.Document
        self._close()
        if never_run:  # Cancel on a mesh that was never made: it goes again
            name = self.obj.Name
            if doc.getObject(name) is not None:
                for parent in self.obj.InList:  # an analysis holding it
                    if hasattr(parent, "removeObject"):
                        parent.removeObject(self.obj)
                doc.removeObject(name)
                FreeCAD.Console.PrintMessage("VoroHex: {} removed (never meshed)\n".format(
                    name))
        return True

    def _close(self):
        self.stop_trials()  # its banner and button belong to this panel
        self.clear_highlights()
        gui_doc = FreeCADGui.getDocument(self.obj.Document.Name)
        if gui_doc is not None:
            gui_doc.resetEdit()
        FreeCAD.Console.PrintLog("VoroHex: {}: {}\n".format(self.obj.Label, self.obj.Message))
