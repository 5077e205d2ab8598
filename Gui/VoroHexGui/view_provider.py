# View provider proxy of the VoroHex mesh object (FemMeshGmsh's VPMeshGmsh pattern).
import FreeCADGui

import VoroHexGui


class ViewProviderHexMesh:
    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.ViewObject = vobj
        self.Object = vobj.Object

    def getIcon(self):
        return VoroHexGui.resource("icons", "VoroHex.svg")

    def updateData(self, obj, prop):
        return

    def onChanged(self, vobj, prop):
        return

    def setEdit(self, vobj, mode=0):
        from VoroHexGui import task_panel

        vobj.show()
        FreeCADGui.Control.showDialog(task_panel.TaskPanel(vobj.Object))
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
