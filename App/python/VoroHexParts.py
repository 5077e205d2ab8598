# The parametric decomposition document object: the sub-volumes VoroHex cuts a linked solid
# into (vorohex decompose), as one compound whose faces the GUI colours by meshing scheme,
# with decomposition faces and sweep source/target faces marked. Usable headless.
"""VoroHex decomposition document object."""

import FreeCAD
import Part

import VoroHex
import VoroHexObjects

TYPE = "VoroHex::Decomposition"

# Face roles in legend order with their colours (RGB 0..1).
ROLES = (
    ("sweep", (0.30, 0.55, 0.90), "side face of a sub-volume meshed by sweeping"),
    ("map", (0.30, 0.75, 0.35), "face of a sub-volume meshed as a mapped block"),
    ("midpoint", (0.65, 0.45, 0.85), "face of a sub-volume meshed by midpoint subdivision"),
    ("none", (0.90, 0.25, 0.20), "face of a sub-volume no scheme accepts"),
    ("source/target", (0.10, 0.25, 0.60), "source or target face of a sweep"),
    ("decomposition", (0.98, 0.80, 0.15), "decomposition face (between two sub-volumes)"),
)
COLOURS = {r[0]: r[1] for r in ROLES}

RESULTS = (
    ("Status", "App::PropertyString", "ok, partial, or error when the last recompute failed"),
    ("Message", "App::PropertyString", "Summary of the last recompute, or why it failed"),
    ("SubVolumeCount", "App::PropertyInteger", "Sub-volumes (after merging)"),
    ("SubVolumesBeforeMerge", "App::PropertyInteger", "Sub-volumes of the first split"),
    ("DecompositionFaceCount", "App::PropertyInteger", "Faces between two sub-volumes"),
    ("Types", "App::PropertyStringList", "Vs or Ve per sub-volume"),
    ("Schemes", "App::PropertyStringList", "Meshing scheme per sub-volume (sweep, map, none)"),
    ("Reasons", "App::PropertyStringList", "Why that scheme, per sub-volume"),
    ("FaceRoles", "App::PropertyStringList",
     "Role of every face of the Shape, in Shape.Faces order (for colouring)"),
)


class Decomposition:
    """Proxy of the decomposition object (a Part::FeaturePython)."""

    Type = TYPE

    def __init__(self, obj):
        obj.Proxy = self
        self.add_properties(obj)

    def add_properties(self, obj):
        if not hasattr(obj, "Part"):
            obj.addProperty("App::PropertyLink", "Part", "Decomposition", "Solid to decompose")
        if not hasattr(obj, "SharpAngle"):
            obj.addProperty("App::PropertyFloatConstraint", "SharpAngle", "Decomposition",
                            "Dihedral angle (degrees) below which a [1] edge is [1s]")
            obj.SharpAngle = (60.0, 1.0, 180.0, 5.0)
        VoroHexObjects.add_option_properties(obj, VoroHexObjects.GRAPH_OPTIONS)
        if not hasattr(obj, "Merge"):
            obj.addProperty("App::PropertyBool", "Merge", "Decomposition",
                            "Unite neighbouring sub-volumes whose union is a sweep")
            obj.Merge = True
        for name, prop_type, doc in RESULTS:
            if not hasattr(obj, name):
                obj.addProperty(prop_type, name, "Result", doc)
                obj.setEditorMode(name, 1)

    def onDocumentRestored(self, obj):
        obj.SharpAngle = (obj.SharpAngle, 1.0, 180.0, 5.0)
        self.add_properties(obj)

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def execute(self, obj):
        """Re-decomposes; on failure keeps the previous shape and raises."""
        error = VoroHexObjects.source_error(obj.Part)
        d = None
        if error is None:
            d = VoroHexObjects.compute_or_raise(obj, "decomposition", lambda: (
                VoroHex.decompose(obj.Part, sharp_angle=obj.SharpAngle, merge=obj.Merge,
                                  progress=getattr(self, "progress", None),
                                  **VoroHexObjects.graph_options_of(obj))))
            if d is None:  # cancelled (Status and Message say so)
                return
            if not d.ok or not d.shapes:
                error = "; ".join(x.get("message", "") for x in d.diagnostics
                                  if x.get("severity") == "error") or "the decomposition failed"
        if error is not None:
            obj.Status, obj.Message = "error", error
            raise RuntimeError("VoroHex: " + error)
        compound = Part.makeCompound(d.shapes)
        obj.Shape = compound
        obj.FaceRoles = face_roles(compound, d)
        obj.SubVolumeCount = len(d.sub_volumes)
        obj.SubVolumesBeforeMerge = d.counts.get("sub_volumes_before_merge", 0)
        obj.DecompositionFaceCount = d.counts.get("decomposition_faces", 0)
        obj.Types = [sv.get("type", "?") for sv in d.sub_volumes]
        obj.Schemes = [sv.get("scheme", "none") for sv in d.sub_volumes]
        obj.Reasons = [sv.get("reason", "") for sv in d.sub_volumes]
        obj.Status = d.status
        schemes = {}
        for s in obj.Schemes:
            schemes[s] = schemes.get(s, 0) + 1
        obj.Message = "{} sub-volumes ({}), {} before merging, {} decomposition faces".format(
            obj.SubVolumeCount, ", ".join("{} {}".format(n, s) for s, n in sorted(
                schemes.items())), obj.SubVolumesBeforeMerge, obj.DecompositionFaceCount)


def face_roles(compound, d):
    """The role of every face of the compound (the sub-volumes' faces one after the other):
    a decomposition face where it coincides with a face of another sub-volume (same area
    and centre), a sweep's source or target, else its sub-volume's scheme."""
    tol = 1e-7 * max(compound.BoundBox.DiagonalLength, 1e-300)
    keys = [[(f.Area, f.CenterOfMass) for f in s.Faces] for s in d.shapes]

    def shared(i, area, centre):
        return any(abs(a - area) <= tol * max(1.0, area) and (c - centre).Length <= tol
                   for j, faces in enumerate(keys) if j != i for a, c in faces)

    roles = []
    for i, solid in enumerate(d.shapes):
        sv = d.sub_volumes[i] if i < len(d.sub_volumes) else {}
        scheme = sv.get("scheme", "none")
        ends = [sv.get("source"), sv.get("target")] if scheme == "sweep" else []
        for k, (area, centre) in enumerate(keys[i]):
            if shared(i, area, centre):
                roles.append("decomposition")
            elif "Face{}".format(k + 1) in ends:
                roles.append("source/target")
            else:
                roles.append(scheme if scheme in COLOURS else "none")
    if len(roles) != len(compound.Faces):  # sub-volumes sharing faces in the compound
        return ["none"] * len(compound.Faces)
    return roles


def makeDecomposition(doc, part, name="Decomposition", merge=True, progress=None, **options):
    """Adds a decomposition object for `part` to `doc` and computes it. Raises ValueError
    (and leaves the document as it was) when `part` holds no single solid. progress as for
    VoroHexGraph.makeVoronoiGraph; options: sharp_angle, eps, delta, max_depth, set as the
    object's properties before it computes."""
    error = VoroHexObjects.source_error(part)
    if error is not None:
        raise ValueError("VoroHex: " + error)
    obj = doc.addObject("Part::FeaturePython", name)
    Decomposition(obj)
    obj.Part = part
    try:
        VoroHexObjects.set_options(obj, options)
    except (TypeError, ValueError):
        doc.removeObject(obj.Name)  # the document as it was
        raise
    obj.Merge = merge
    if FreeCAD.GuiUp:
        from VoroHexGui import parts_view

        parts_view.ViewProviderDecomposition(obj.ViewObject)
    VoroHexObjects.compute_new(obj, progress)
    return obj
