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
    def claimChildren(self):
        # The FEM mesh regions (local sizes) sit under the mesh, as under a FemMeshGmsh.
        return list(getattr(self.Object, "MeshRegionList", []) or [])

    def make_panel(self, obj):
        from VoroHexGui import task_panel

        return task_panel.TaskPanel(obj)


class Faded:
    """A solid's look changed while a panel is open; restore() puts it back."""

    def __init__(self, vobj, saved):
        self.vobj, self.saved = vobj, saved

    def restore(self):
        if self.vobj is None:
            return
        try:
            for prop, value in self.saved.items():
                if getattr(self.vobj, prop) != value:
                    setattr(self.vobj, prop, value)
        except Exception:  # the solid was deleted meanwhile
            pass
        self.vobj = None


def fade_solid(part, transparency=80, wireframe=False):
    """Fades the solid `part` so what lies inside or on it is seen: translucent, or (with
    `wireframe`, for pieces that coincide with its faces and would fight with them) its
    edges only. Returns a Faded to restore it on close."""
    vobj = getattr(part, "ViewObject", None)
    if vobj is None:
        return Faded(None, {})
    saved = {"Visibility": vobj.Visibility, "Transparency": vobj.Transparency,
             "DisplayMode": vobj.DisplayMode}
    vobj.Visibility = True
    if wireframe and "Wireframe" in vobj.listDisplayModes():
        vobj.DisplayMode = "Wireframe"
    else:
        vobj.Transparency = transparency
    return Faded(vobj, saved)
