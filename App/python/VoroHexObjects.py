# The parametric hex mesh document object, on FreeCAD's FemMeshGmsh pattern: a
# Fem::FemMeshObjectPython whose proxy re-meshes its linked Part on recompute.
"""VoroHex document objects (usable headless, in freecadcmd)."""

import FreeCAD

import VoroHex

TYPE = "Fem::VoroHexMesh"

# Read-only result properties: (name, type, doc).
RESULTS = (
    ("Status", "App::PropertyString", "ok, or error when the last recompute failed"),
    ("Message", "App::PropertyString", "Summary of the last recompute, or why it failed"),
    ("HexCount", "App::PropertyInteger", "Number of hexahedra"),
    ("NodeCount", "App::PropertyInteger", "Number of nodes"),
    ("SubVolumeCount", "App::PropertyInteger", "Number of sub-volumes of the decomposition"),
    ("MinScaledJacobian", "App::PropertyFloat", "Smallest scaled Jacobian (1 = cube)"),
    ("MeanScaledJacobian", "App::PropertyFloat", "Mean scaled Jacobian"),
    ("MinScaledJacobianBeforeSmoothing", "App::PropertyFloat",
     "Smallest scaled Jacobian before global smoothing"),
    ("MeanScaledJacobianBeforeSmoothing", "App::PropertyFloat",
     "Mean scaled Jacobian before global smoothing"),
    ("Scheme", "App::PropertyString", "How the solid was meshed: map (block) or sweep"),
    ("VolumeError", "App::PropertyFloat", "Relative volume error of the mesh vs the solid"),
    ("ScaledJacobianHistogram", "App::PropertyIntegerList",
     "Hexes per scaled Jacobian bin of 0.1 from -1 to 1"),
    ("SubVolumeSchemes", "App::PropertyStringList", "Per sub-volume (1, 2, ...): its scheme"),
    ("SubVolumeTypes", "App::PropertyStringList",
     "Per sub-volume: Vs (swept between two faces of the solid), Ve (a block, or a sweep "
     "from or to a cut face), - (the tetrahedral fallback)"),
    ("SubVolumeHexCounts", "App::PropertyIntegerList", "Per sub-volume: its hexahedra"),
    ("SubVolumeMinScaledJacobian", "App::PropertyFloatList",
     "Per sub-volume: the smallest scaled Jacobian of its hexahedra"),
    ("Diagnostics", "App::PropertyStringList",
     "Messages of the last recompute, one per line: severity [code] message"),
    ("DiagnosticEntities", "App::PropertyStringList",
     "Per message, the model entities it names (Face7, Edge3, ...; comma-separated)"),
)


def record_diagnostics(obj, diagnostics):
    """Stores the messages and the entities each names (the task panel highlights them)."""
    obj.Diagnostics = ["{} [{}] {}".format(d.severity, d.code, d.message) for d in diagnostics]
    obj.DiagnosticEntities = [",".join(d.entities) for d in diagnostics]


def source_error(part, several=False):
    """Why `part` cannot be used (a sentence), or None if it holds one solid (or, with
    `several`, one or more: the hex mesh takes several)."""
    if part is None:
        return "No geometry linked: set the Part property to a solid"
    if part.isDerivedFrom("Fem::FemMeshObject"):
        return "'{}' is a FEM mesh, not a solid; select the solid it was made from".format(
            part.Label)
    if part.isDerivedFrom("Mesh::Feature"):
        return ("'{}' is a triangle mesh, not a solid; convert it first (Part > Create shape "
                "from mesh, then Part > Convert to solid)".format(part.Label))
    try:
        VoroHex.check_shape(part, several)
    except (TypeError, ValueError) as e:
        return "'{}': {}".format(part.Label, str(e).replace("VoroHex: ", ""))
    return None


# The Voronoi graph's options (eps, delta, max_depth), shared by the mesh, graph and
# decomposition objects under the same property names.
GRAPH_OPTIONS = tuple(o for o in VoroHex.OPTIONS if o.group == "Voronoi graph")


def add_option_properties(obj, options, group=None):
    """Adds the properties of `options` (VoroHex.OPTIONS entries) the object lacks, with
    their defaults; sets the limits of constraint properties again (FreeCAD does not save
    them), so it also serves on restore."""
    for o in options:
        if not hasattr(obj, o.prop):
            obj.addProperty(o.prop_type, o.prop, group or o.group, o.doc)
            value = 0 if o.auto_zero else o.default
            setattr(obj, o.prop, (value,) + o.limits if o.limits else value)
        elif o.limits:
            setattr(obj, o.prop, (getattr(obj, o.prop),) + o.limits)


def set_options(obj, options):
    """Sets the properties of keyword options (eps=..., sharp_angle=...; None keeps the
    default) through VoroHex.OPTIONS; TypeError or ValueError naming a bad option or one
    the object does not have."""
    by_name = {o.name: o for o in VoroHex.OPTIONS}
    VoroHex.validate_options(**options)
    for name, value in options.items():
        o = by_name.get(name)
        if o is None or not hasattr(obj, o.prop):
            raise TypeError("VoroHex: {} has no option '{}'".format(obj.Label, name))
        if value is not None:
            setattr(obj, o.prop, value)


def compute_or_raise(obj, what, compute):
    """compute() for an object's execute: a bad option (ValueError, named) sets Status
    "error" and Message, and raises RuntimeError so FreeCAD marks the object. A cancel sets
    Status "error", Message "cancelled" and returns None without raising (FreeCAD would
    print a traceback for it): compute_new, which passed the progress callback, then takes
    the object out again and raises VoroHex.Cancelled."""
    try:
        return compute()
    except VoroHex.Cancelled:
        obj.Status, obj.Message = "error", "cancelled"
        obj.Proxy.cancelled = "the {} was cancelled".format(what)
        return None
    except ValueError as e:  # a bad Eps, Delta, MaxDepth or SharpAngle
        obj.Status, obj.Message = "error", str(e).replace("VoroHex: ", "")
        raise RuntimeError("VoroHex: " + obj.Message)


def compute_new(obj, progress):
    """Computes an object just added by a make* function, calling progress(stage, fraction)
    (False cancels). A cancelled run removes the object, leaving the document as it was,
    and raises VoroHex.Cancelled."""
    obj.Proxy.progress, obj.Proxy.cancelled = progress, None
    try:
        obj.recompute()
    finally:
        obj.Proxy.progress = None
    why = getattr(obj.Proxy, "cancelled", None)
    if why:
        obj.Document.removeObject(obj.Name)
        raise VoroHex.Cancelled("VoroHex: " + why)


def graph_options_of(obj):
    """Keyword options eps, delta, max_depth for VoroHex.voronoi_graph / decompose."""
    return {o.name: getattr(obj, o.prop) for o in GRAPH_OPTIONS if hasattr(obj, o.prop)}


def options_of(obj):
    """Keyword options for VoroHex.mesh from the object's properties (via VoroHex.OPTIONS)."""
    opts = {}
    for o in VoroHex.OPTIONS:
        value = getattr(obj, o.prop)
        if o.prop_type == "App::PropertyLength":
            value = value.Value
        opts[o.name] = None if (o.auto_zero and value == 0) else value
    return opts


class HexMesh:
    """Proxy of the VoroHex mesh object."""

    Type = TYPE

    def __init__(self, obj):
        obj.Proxy = self
        self.add_properties(obj)

    def add_properties(self, obj):
        # Only adds what is missing, so it can run again on restore of older files.
        if not hasattr(obj, "Part"):
            obj.addProperty("App::PropertyLink", "Part", "FEM Mesh",
                            "Solid the hex mesh is made from")
        for o in VoroHex.OPTIONS:
            if not hasattr(obj, o.prop):
                obj.addProperty(o.prop_type, o.prop, o.group, o.doc)
                value = 0 if o.auto_zero else o.default
                setattr(obj, o.prop, (value,) + o.limits if o.limits else value)
        for name, prop_type, doc in RESULTS:
            if not hasattr(obj, name):
                obj.addProperty(prop_type, name, "Result", doc)
                obj.setEditorMode(name, 1)  # read-only in the property editor

    def onDocumentRestored(self, obj):
        # Files older than an option lack its property; add it with the default. FreeCAD
        # does not save the limits of constraint properties, so set them again.
        for o in VoroHex.OPTIONS:
            if o.limits and hasattr(obj, o.prop):
                setattr(obj, o.prop, (getattr(obj, o.prop),) + o.limits)
        self.add_properties(obj)

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def execute(self, obj):
        """Re-meshes; on failure keeps the previous FemMesh, records why and raises so
        FreeCAD marks the object invalid with that message."""
        error = source_error(obj.Part, True)
        result = None
        if error is None:
            try:
                result = VoroHex.mesh(obj.Part.Shape, progress=getattr(self, "progress", None),
                                      **options_of(obj))
            except (TypeError, ValueError) as e:
                error = str(e).replace("VoroHex: ", "")
        if result is not None and not result.ok:
            error = result.message
        record_diagnostics(obj, [] if result is None else list(result.diagnostics))
        if error is not None:
            obj.Status, obj.Message = "error", error
            raise RuntimeError("VoroHex: " + error)
        femmesh = result.to_femmesh()
        s = result.stats
        obj.FemMesh = femmesh
        obj.HexCount, obj.NodeCount, obj.SubVolumeCount = s.hexes, s.nodes, s.sub_volumes
        obj.MinScaledJacobian, obj.MeanScaledJacobian = s.min_scaled_jacobian, \
            s.mean_scaled_jacobian
        obj.MinScaledJacobianBeforeSmoothing = s.min_scaled_jacobian_before_smoothing
        obj.MeanScaledJacobianBeforeSmoothing = s.mean_scaled_jacobian_before_smoothing
        obj.Scheme = s.scheme
        obj.VolumeError = s.volume_rel_error
        obj.ScaledJacobianHistogram = [int(c) for c in s.histogram]
        table = result.sub_volume_table()
        obj.SubVolumeSchemes = [r["scheme"] for r in table]
        obj.SubVolumeTypes = [r["type"] for r in table]
        obj.SubVolumeHexCounts = [r["hexes"] for r in table]
        obj.SubVolumeMinScaledJacobian = [float(r["min_scaled_jacobian"]) for r in table]
        obj.Status, obj.Message = "ok", result.message
        self.last_result = result  # for the task panel (not saved)


def makeHexMesh(doc, part, name="HexMesh", size=None):
    """Adds a VoroHex mesh object for `part` to `doc`. Raises ValueError, leaving the
    document untouched, when `part` holds no single closed solid."""
    error = source_error(part, True)
    if error is not None:
        raise ValueError("VoroHex: " + error)
    obj = doc.addObject("Fem::FemMeshObjectPython", name)
    HexMesh(obj)
    obj.Part = part
    if size is not None:
        obj.TargetSize = size
    if FreeCAD.GuiUp:
        from VoroHexGui import view_provider

        view_provider.ViewProviderHexMesh(obj.ViewObject)
    return obj
