# VoroHex workbench GUI start-up. FreeCAD executes this file without __file__ and with
# separate globals, so everything the class needs is imported inside its methods.
import importlib.util
import os
import sys

# Gui/ holds the VoroHexGui package; on sys.path now, so documents restored before the
# workbench is activated find their view providers.
_vorohex_gui = os.path.join(os.path.dirname(importlib.util.find_spec("VoroHex").origin), "Gui")
if _vorohex_gui not in sys.path:
    sys.path.append(_vorohex_gui)


class VoroHexWorkbench(Workbench):  # noqa: F821 (Workbench is FreeCAD's builtin)
    import importlib.util as _util
    import os as _os

    MenuText = "VoroHex"
    ToolTip = "All-hexahedral FEM meshing (embedded Voronoi graph)"
    _mod_dir = _os.path.dirname(_util.find_spec("VoroHex").origin)
    Icon = _os.path.join(_mod_dir, "Resources", "icons", "VoroHex.svg")

    def Initialize(self):
        from VoroHexGui import commands

        commands.register()
        self.appendToolbar("VoroHex", commands.COMMANDS)
        self.appendMenu("&VoroHex", commands.COMMANDS)

    def Activated(self):
        # Few commands: show their names beside the icons so the toolbar explains itself.
        import FreeCADGui
        from PySide import QtCore, QtGui

        for bar in FreeCADGui.getMainWindow().findChildren(QtGui.QToolBar):
            if bar.objectName() == "VoroHex" or bar.windowTitle() == "VoroHex":
                bar.setToolButtonStyle(QtCore.Qt.ToolButtonTextBesideIcon)

    def Deactivated(self):
        return

    def GetClassName(self):
        return "Gui::PythonWorkbench"


Gui.addWorkbench(VoroHexWorkbench())  # noqa: F821
