# VoroHex: FreeCAD runs this at start-up (also in freecadcmd). Registers the unit tests;
# `import VoroHex` and `import VoroHexObjects` work because this folder is on sys.path.
import FreeCAD

FreeCAD.__unit_test__ += [
    "TestVoroHex", "TestVoroHexDocument", "TestVoroHexFea", "TestVoroHexSizes"]
