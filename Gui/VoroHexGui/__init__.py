# VoroHexGui: FreeCAD GUI side of VoroHex (commands, task panel, view provider).
"""VoroHex workbench GUI."""
import os

# Gui/VoroHexGui/ -> the Mod folder (installed) or the source root: both hold Resources/.
MOD_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def resource(*parts):
    """Absolute path of a file under Resources/ (icons, ui)."""
    return os.path.join(MOD_DIR, "Resources", *parts)
