# View provider proxies of the VoroHex objects (FemMeshGmsh's VPMeshGmsh pattern).
import FreeCADGui

import VoroHexGui


class ViewProviderBase:
    """What every VoroHex object's view provider shares: double click opens the task panel
    made by make_panel(obj); icon from ICON; nothing saved with the document."""

    ICON = "VoroHex.svg"

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.ViewObject = vobj
        self.Object = vobj.Object

    def getIcon(self):
        return VoroHexGui.resource("icons", self.ICON)

    def updateData(self, obj, prop):
        return

    def onChanged(self, vobj, prop):
        return

    def make_panel(self, obj):
        raise NotImplementedError

    def setEdit(self, vobj, mode=0):
        vobj.show()
        FreeCADGui.Control.showDialog(self.make_panel(vobj.Object))
        return True

    def unsetEdit(self, vobj, mode=0):
        FreeCADGui.Control.closeDialog()
        return True

    def doubleClicked(self, vobj):
        if not FreeCADGui.Control.activeDialog():
            FreeCADGui.getDocument(vobj.Object.Document.Name).setEdit(vobj.Object.Name)
        return True

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


class ViewProviderHexMesh(ViewProviderBase):
    def make_panel(self, obj):
        from VoroHexGui import task_panel

        return task_panel.TaskPanel(obj)
