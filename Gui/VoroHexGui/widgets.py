# Small widgets and helpers the task panels share: a collapsible section, the scroll area
# around a task panel, and a poll timer that drives a VoroHexJobs.Job from the GUI thread.
import time

import FreeCADGui
from PySide import QtCore, QtGui
import shiboken2


def layout_of(widget):
    """widget.layout(), never a stale wrapper. PySide2 5.15 can hand back the Python wrapper
    of a layout deleted with a closed panel whose address Qt reused for this one: its every
    call raises "Internal C++ object (QFormLayout) already deleted" (tests/gui/gui_panel.py,
    about once in five runs, opening the panel again after Cancel). Such a wrapper is dropped
    from PySide's table and the layout wrapped anew."""
    layout = widget.layout()
    if layout is not None and not shiboken2.isValid(layout):
        shiboken2.invalidate(layout)
        layout = widget.layout()
    return layout


class Section(QtGui.QWidget):
    """A titled section whose content shows or hides with a click on its title (collapsed
    at first), like the "Advanced" parts of FreeCAD's own panels."""

    def __init__(self, title, content, parent=None, expanded=False, name=None):
        super().__init__(parent)
        if name:
            self.setObjectName(name)
        layout = QtGui.QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(2)
        self.toggle = QtGui.QToolButton(self)
        self.toggle.setObjectName((name or "section") + "_toggle")
        self.toggle.setToolButtonStyle(QtCore.Qt.ToolButtonTextBesideIcon)
        self.toggle.setCheckable(True)
        self.toggle.setAutoRaise(True)
        self.toggle.setSizePolicy(QtGui.QSizePolicy.Expanding, QtGui.QSizePolicy.Fixed)
        self.toggle.toggled.connect(self.setExpanded)
        layout.addWidget(self.toggle)
        self.content = content
        content.setParent(self)
        layout.addWidget(content)
        self.setTitle(title)
        self.setExpanded(expanded)

    def setTitle(self, title):
        self.toggle.setText(title)

    def isExpanded(self):
        return self.toggle.isChecked()

    def setExpanded(self, on):
        self.toggle.blockSignals(True)
        self.toggle.setChecked(on)
        self.toggle.blockSignals(False)
        self.toggle.setArrowType(QtCore.Qt.DownArrow if on else QtCore.Qt.RightArrow)
        self.content.setVisible(on)


def scroll_area_of(widget):
    """The QScrollArea a task panel sits in (FreeCAD's task view), or None: the innermost
    of the main window's scroll areas that hold `widget`. Not by walking up parentWidget():
    the Python wrappers that walk made for FreeCAD's own widgets took the panel's form with
    them when they were dropped (PySide2 5.15: `self.form` "already deleted" while the panel
    was still shown), so a second Run in the same panel failed."""
    areas = [a for a in FreeCADGui.getMainWindow().findChildren(QtGui.QScrollArea)
             if a.isAncestorOf(widget)]
    inner = [a for a in areas if not any(b is not a and a.isAncestorOf(b) for b in areas)]
    return inner[0] if inner else None


def scroll_to(widget):
    """Scrolls the task view so that `widget` is in sight."""
    area = scroll_area_of(widget)
    if area is not None:
        area.ensureWidgetVisible(widget, 0, 0)


class JobRunner(QtCore.QObject):
    """Polls a VoroHexJobs.Job every `tick` ms on the GUI thread: on_progress(job) while it
    runs, on_done(job) once (whether it finished, failed or was stopped)."""

    def __init__(self, job, on_progress, on_done, tick=50, parent=None):
        super().__init__(parent)
        self.job, self.on_progress, self.on_done = job, on_progress, on_done
        self.timer = QtCore.QTimer(self)
        self.timer.setInterval(tick)
        self.timer.timeout.connect(self._poll)
        self.timer.start()

    def _poll(self):
        over = self.job.poll()
        if not over:
            self.on_progress(self.job)
            return
        self.timer.stop()
        self.on_done(self.job)

    def stop(self):
        """Cancels the job; on_done follows at once."""
        self.job.cancel()
        self._poll()

    @property
    def running(self):
        return self.timer.isActive()


def wait_for(runner, seconds=None):
    """Processes events until the runner is over (scripts and tests)."""
    end = None if seconds is None else time.time() + seconds
    while runner.running and (end is None or time.time() < end):
        QtGui.QApplication.processEvents()
        time.sleep(0.01)
    return not runner.running
