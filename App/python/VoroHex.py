# VoroHex: all-hexahedral meshing of a CAD solid, for FreeCAD's Python.
#
#   import VoroHex
#   r = VoroHex.mesh(shape, size=2.0)       # shape: a Part.Shape holding one closed solid
#   r.ok, r.diagnostics, r.stats, r.nodes, r.hexes, r.scaled_jacobian
#   r.to_femmesh()                          # Fem.FemMesh, SMESH node order
#   r.write("part.vtu")                     # .vtu / .msh / .inp
#   VoroHex.check(r, shape)                 # validity and quality of any hex mesh
#   g = VoroHex.voronoi_graph(shape)        # embedded Voronoi graph: g.elements, g.counts
#
# Why two modules: the compiled _VoroHexCore knows only plain values (BREP strings, byte
# buffers) and no FreeCAD type, so it can be built and tested without FreeCAD; this file is
# the thin FreeCAD side (Part.Shape checks, Fem.FemMesh, numpy when present).
"""VoroHex all-hexahedral mesher (Sheffer et al., embedded Voronoi graph)."""

import json
import math
import numbers
import os
import re
from array import array

import _VoroHexCore as _core
from VoroHexFemMesh import (SMESH_FROM_VTK, SMESH_FROM_VTK20, add_groups, femmesh_of as _femmesh_of,
                            smesh_nodes, vtk_cells)

try:  # numpy is optional: without it node and hex arrays are lists of tuples
    import numpy as _np
except ImportError:  # pragma: no cover - numpy is installed with FreeCAD on Debian
    _np = None

__all__ = ["mesh", "check", "voronoi_graph", "MeshResult", "MeshStats", "VoronoiGraph",
           "CancelToken", "OPTIONS", "ShapeError", "from_femmesh", "SMESH_FROM_VTK", "SMESH_FROM_VTK20",
           "decompose", "Decomposition", "element_quality", "validate_options"]

MOD_DIR = os.path.dirname(os.path.abspath(__file__))
CancelToken = _core.CancelToken
Diagnostic = _core.Diagnostic
CheckReport = _core.CheckReport

ELEMENT_ORDERS = ("1st", "2nd")  # the ElementOrder property's values, as FemMeshGmsh names them


class ShapeError(ValueError):
    """The shape given cannot be meshed as one solid (no solid, several, open shell...)."""


class _Option:
    """One pipeline option: its keyword, the FreeCAD property that carries it, and how.

    kind decides the check: "length" > 0, "count" whole >= 1, "iterations" whole >= 0,
    "fraction" in (0, 1], "angle" in (0, 180] degrees, "tolerance" >= 0, "flag" True or
    False, "schemes" scheme names (a list, or one comma-separated string), "choice" a string
    the C++ options' validate() checks. limits = (min, max, step) of a constraint
    property (App::PropertyIntegerConstraint / PropertyFloatConstraint), else None."""

    def __init__(self, name, prop, prop_type, group, doc, kind, auto_zero=False, limits=None):
        self.name, self.prop, self.prop_type = name, prop, prop_type
        self.group, self.doc, self.kind, self.auto_zero = group, doc, kind, auto_zero
        self.limits = limits

    @property
    def default(self):
        value = getattr(_core.MeshOptions(), self.name)
        return ",".join(value) if self.kind == "schemes" else value

    @property
    def integer(self):
        return self.kind in ("count", "iterations")


# The single table mapping keyword options <-> MeshOptions fields <-> document properties.
# A new pipeline option is one line here (and one field in the C++ binding).
OPTIONS = (
    _Option("size", "TargetSize", "App::PropertyLength", "Mesh",
            "Target hex edge length; 0 = automatic (bounding-box diagonal / 20)", "length",
            auto_zero=True),
    _Option("size_grading", "SizeGrading", "App::PropertyFloat", "Mesh",
            "How fast the size grows away from a local size (a FEM mesh region child): "
            "0.3 = 0.3 mm larger per mm of distance, in (0, 10]", "grading"),
    _Option("max_hexes", "MaxHexes", "App::PropertyInteger", "Mesh",
            "Refuse to mesh when more hexahedra than this are predicted", "count"),
    _Option("time_limit", "TimeLimit", "App::PropertyFloat", "Mesh",
            "Seconds after which meshing stops like a cancel (0 = no limit)", "tolerance"),
    _Option("schemes", "Schemes", "App::PropertyString", "Mesh",
            "Single-solid schemes tried in this order, comma-separated: map, sweep, "
            "multisweep, revolve, midpoint, grid (one left out is never used; grid only when "
            "named)", "schemes"),
    _Option("fallback", "Fallback", "App::PropertyBool", "Mesh",
            "Where no structured scheme (map, sweep, multisweep, revolve, midpoint) applies, "
            "mesh the solid with the grid mesher (poorer elements at the boundary, reported as "
            "a warning); false refuses instead", "flag"),
    _Option("fallback_scheme", "FallbackScheme", "App::PropertyString", "Mesh",
            "The fallback: grid (core grid, pillow layer to the CAD, features captured) or "
            "tet-split (tetrahedra split into hexahedra, kept for comparison)", "choice"),
    _Option("eps", "Eps", "App::PropertyFloat", "Voronoi graph",
            "Merge tolerance and finest octree cell of the Voronoi graph, relative to the "
            "bounding-box diagonal, in (0, 0.25]", "fraction"),
    _Option("delta", "Delta", "App::PropertyFloat", "Voronoi graph",
            "Accuracy the Voronoi graph is embedded to, relative to the diagonal, in (0, Eps]",
            "fraction"),
    _Option("max_depth", "MaxDepth", "App::PropertyIntegerConstraint", "Voronoi graph",
            "Maximum octree depth of the Voronoi graph, 1..12", "count", limits=(1, 12, 1)),
    _Option("decompose", "Decompose", "App::PropertyBool", "Decomposition",
            "Where no single scheme applies, cut the solid into sub-volumes along its Voronoi "
            "graph and mesh them into one conforming mesh (before any fallback)", "flag"),
    _Option("sharp_angle", "SharpAngle", "App::PropertyFloatConstraint", "Decomposition",
            "Dihedral angle (degrees) below which the cut follows both faces of a model edge "
            "([1s] edges), in (0, 180]", "angle", limits=(1.0, 180.0, 5.0)),
    _Option("decomposition_time_limit", "DecompositionTimeLimit", "App::PropertyFloat",
            "Decomposition",
            "Seconds the Voronoi graph and the cut may take before the fallback takes over (> 0)",
            "tolerance"),
    _Option("smooth_iterations", "SmoothIterations", "App::PropertyIntegerConstraint",
            "Smoothing", "Laplacian smoothing sweeps (0 and SmoothPasses 0 = no smoothing)",
            "iterations", limits=(0, 100000, 1)),
    _Option("smooth_passes", "SmoothPasses", "App::PropertyIntegerConstraint", "Smoothing",
            "Untangling and worst-element optimisation passes (0 = none)", "iterations",
            limits=(0, 100000, 1)),
    _Option("smooth_quality_target", "SmoothQualityTarget", "App::PropertyFloatConstraint",
            "Smoothing", "Scaled Jacobian in (0, 1]: hexes below it are optimised, and no "
            "smoothing move may push a hex below it", "fraction", limits=(0.01, 1.0, 0.05)),
    _Option("volume_rel_tol", "VolumeTolerance", "App::PropertyPrecision", "Check",
            "Allowed relative volume error of the mesh against the solid", "tolerance"),
    _Option("distance_rel_tol", "DistanceTolerance", "App::PropertyPrecision", "Check",
            "Allowed distance of boundary nodes from the solid, relative to its diagonal",
            "tolerance"),
)
_OPTION_BY_NAME = {o.name: o for o in OPTIONS}


def _length_text(name, text):
    """A length written as FreeCAD writes one ("4 mm", "0.5 cm", "2"), in mm: what the
    Quantity FreeCAD parses it to gives, else ValueError naming the option."""
    try:
        import FreeCAD
        q = FreeCAD.Units.Quantity(text)
    except ImportError:
        raise TypeError("VoroHex: option '{}' must be a number (mm), got {!r} (a length with its "
                        "unit needs FreeCAD)".format(name, text))
    except Exception:
        raise ValueError("VoroHex: option '{}': {!r} is not a length (a number of mm, or one with "
                         "its unit such as '4 mm')".format(name, text))
    if q.Unit != FreeCAD.Units.Length and q.Unit != FreeCAD.Units.Unit():
        raise ValueError("VoroHex: option '{}' must be a length, got {!r} ({})".format(
            name, text, q.Unit.Type or q.Unit))
    return q.Value


def _number(name, value, integer=False, length=False):
    """value as a float (int where `integer`), else TypeError / ValueError naming the option.
    A FreeCAD Quantity gives its value (mm for a length); a string is taken only for a
    `length`, as FreeCAD parses it ("4 mm", "0.5 cm")."""
    if length and isinstance(value, str):
        value = _length_text(name, value)
    if hasattr(value, "Value") and hasattr(value, "Unit"):  # FreeCAD.Units.Quantity (mm)
        value = value.Value
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError("VoroHex: option '{}' must be a number, got {!r}".format(name, value))
    value = float(value)
    if math.isnan(value) or math.isinf(value):
        raise ValueError("VoroHex: option '{}' must be finite, got {}".format(name, value))
    if integer:
        if value != int(value):
            raise ValueError("VoroHex: option '{}' must be a whole number, got {}".format(
                name, value))
        return int(value)
    return value


def _seconds(name, value):
    """A time limit: a number of seconds > 0, else TypeError / ValueError naming it."""
    value = _number(name, value)
    if value <= 0:
        raise ValueError("VoroHex: option '{}' must be a number of seconds > 0, got "
                         "{!r}".format(name, value))
    return value


def _check_range(option, value):
    """Raises ValueError naming the option unless value suits option.kind."""
    kind, name = option.kind, option.name
    if kind in ("length", "count") and value <= 0:
        raise ValueError("VoroHex: option '{}' must be > 0, got {}{}".format(
            name, value, " (leave it out or pass None for automatic)"
            if option.auto_zero else ""))
    if kind == "fraction" and not 0 < value <= 1:
        raise ValueError("VoroHex: option '{}' must be in (0, 1], got {}".format(name, value))
    if kind == "grading" and not 0 < value <= 10:
        raise ValueError("VoroHex: option '{}' must be in (0, 10], got {}".format(name, value))
    if kind == "angle" and not 0 < value <= 180:
        raise ValueError("VoroHex: option '{}' must be in (0, 180] degrees, got {}".format(
            name, value))
    if value < 0:
        raise ValueError("VoroHex: option '{}' must be >= 0, got {}".format(name, value))
    if option.integer and value > 2**31 - 1 and kind != "count":
        raise ValueError("VoroHex: option '{}' is too large: {}".format(name, value))


def _make_options(kwargs):
    unknown = sorted(set(kwargs) - set(_OPTION_BY_NAME))
    if unknown:
        raise TypeError("VoroHex: unknown option(s) {}; known options: {}".format(
            ", ".join(unknown), ", ".join([o.name for o in OPTIONS] + ["order", "sizes"])))
    opts = _core.MeshOptions()
    for name, value in kwargs.items():
        if value is None:
            continue  # None = keep the default (for size: automatic)
        option = _OPTION_BY_NAME[name]
        if option.kind == "schemes":
            if isinstance(value, str):
                value = [v.strip() for v in value.split(",")] if value.strip() else []
            if not isinstance(value, (list, tuple)) or not all(isinstance(v, str) for v in value):
                raise TypeError("VoroHex: option 'schemes' must be a list of scheme names or "
                                "one comma-separated string, got {!r}".format(value))
            setattr(opts, name, list(value))
            continue
        if option.kind == "choice":
            if not isinstance(value, str):
                raise TypeError("VoroHex: option '{}' must be a string, got {!r}".format(
                    name, value))
            setattr(opts, name, value)
            continue
        if option.kind == "flag":
            if not isinstance(value, bool):
                raise TypeError("VoroHex: option '{}' must be True or False, got {!r}".format(
                    name, value))
            setattr(opts, name, value)
            continue
        value = _number(name, value, integer=option.integer, length=option.kind == "length")
        _check_range(option, value)
        setattr(opts, name, value)
    opts.validate()
    return opts


def validate_options(**options):
    """Raises TypeError (unknown option, wrong type) or ValueError (bad value) naming the
    option, for keyword options of VoroHex.OPTIONS and order; returns None when they are
    fine."""
    options = dict(options)
    if "order" in options:
        _order(options.pop("order"))
    if "sizes" in options:
        _local_sizes(options.pop("sizes"))
    _make_options(options)


_ENTITY_NAME = re.compile(r"^(Face|Edge|Vertex)[1-9][0-9]{0,8}$")


def _local_sizes(sizes):
    """[(name, size)] from {"Face7": 0.5, ...} (sizes may be Quantities); TypeError or
    ValueError naming the entry."""
    if sizes is None:
        return []
    if not isinstance(sizes, dict):
        raise TypeError("VoroHex: sizes must be a dict such as {{'Face7': 0.5}}, got {!r}".format(
            sizes))
    out = []
    for name, value in sizes.items():
        if not isinstance(name, str) or not _ENTITY_NAME.match(name):
            raise ValueError("VoroHex: sizes: {!r} is not an entity name (FaceN, EdgeN or "
                             "VertexN, as FreeCAD names sub-elements)".format(name))
        value = _number("sizes[{!r}]".format(name), value, length=True)
        if value <= 0:
            raise ValueError("VoroHex: sizes[{!r}] must be > 0, got {}".format(name, value))
        out.append((name, value))
    return out


def _shape_of(shape):
    """The Part.Shape of a Part.Shape or of a document object; TypeError otherwise."""
    import Part

    if isinstance(shape, Part.Shape):
        return shape
    type_id = getattr(shape, "TypeId", None)
    if type_id is not None:  # a document object: give its Shape, or say what it is
        inner = getattr(shape, "Shape", None)
        if isinstance(inner, Part.Shape):
            return inner
        raise TypeError("VoroHex: '{}' is a {}, which has no Part shape; select a solid "
                        "(for a mesh: Part > Create shape from mesh, then Convert to solid)"
                        .format(getattr(shape, "Label", "?"), type_id))
    raise TypeError("VoroHex: expected a Part.Shape holding one solid, got {}".format(
        type(shape).__name__))


def _free_edges(shape):
    """Names of edges bounding only one face (why a shell is open)."""
    import Part

    names = []
    for i, e in enumerate(shape.Edges, 1):
        if len(shape.ancestorsOfType(e, Part.Face)) == 1:
            names.append("Edge{}".format(i))
    return names


def check_shape(shape, several=False):
    """Raises ShapeError (a ValueError) unless shape is one closed solid (or, with `several`,
    one or more solids); returns it."""
    shape = _shape_of(shape)
    if shape.isNull():
        raise ShapeError("VoroHex: the shape is empty (null)")
    solids = shape.Solids
    if len(solids) > 1 and not several:
        raise ShapeError("VoroHex: the shape holds {} solids; this takes one solid (fuse them or "
                         "select one; the mesh accepts several)".format(len(solids)))
    if not solids:
        shells = shape.Shells
        if shells and not all(s.isClosed() for s in shells):
            free = _free_edges(shape)
            raise ShapeError("VoroHex: the shape is an open shell, not a solid; free edges: {}"
                             .format(", ".join(free[:12]) + (" ..." if len(free) > 12 else "")))
        if shells:
            raise ShapeError("VoroHex: the shape is a closed shell but not a solid; make a "
                             "solid first (Part > Convert to solid)")
        kind = "faces" if shape.Faces else ("a wire/edges" if shape.Edges else "vertices")
        raise ShapeError("VoroHex: the shape contains no solid (it has {}); only solids can "
                         "be hex-meshed".format(kind))
    return shape


def _read_solid(shape, several=False):
    solid, diags = _core.read_brep(shape.exportBrepToString(), several)
    if solid is None:
        msg = "; ".join(d.message for d in diags if d.severity == "error") or "unknown error"
        # The core names its input "The BREP string": here it is the user's shape.
        msg = msg.replace("The BREP string", "The shape")
        raise ShapeError("VoroHex: cannot read the solid: " + msg)
    return solid


class MeshStats:
    """Counts and quality figures of a mesh result (plain attributes)."""

    def __init__(self, core_result):
        c, s = core_result.check, core_result.stats
        sj = c.scaled_jacobian
        self.hexes, self.nodes = c.hexes, c.nodes
        self.min_scaled_jacobian, self.mean_scaled_jacobian = sj.min, sj.mean
        self.max_scaled_jacobian = sj.max
        self.histogram = list(sj.histogram)  # bin i: [-1 + 0.1 i, -1 + 0.1 (i + 1))
        self.inverted = sj.inverted
        self.fraction_below_0_2 = sj.fraction_below_0_2
        self.volume_rel_error = c.volume_rel_error
        self.mesh_volume, self.cad_volume = c.mesh_volume, c.cad_volume
        self.max_boundary_distance = c.max_boundary_distance
        self.sub_volumes = s.sub_volumes
        self.sub_volume_schemes = list(s.sub_volume_schemes)  # per sub-volume 1, 2, ...
        self.size_used = s.size_used
        self.local_sizes = dict(s.local_sizes)  # {"Face7": 0.5}: the local sizes applied
        self.intervals = tuple(s.intervals)
        self.scheme = s.scheme  # "map" (mapped block), "sweep" (one-to-one) or "midpoint"
        # Quality before global smoothing (equal to the final one when smoothing is off).
        self.min_scaled_jacobian_before_smoothing = s.min_sj_before_smoothing
        self.mean_scaled_jacobian_before_smoothing = s.mean_sj_before_smoothing
        self.seconds_meshing = s.seconds_meshing
        self.seconds_smoothing = s.seconds_smoothing
        self.seconds_checking = s.seconds_checking
        # The fallback's mesh was computed beside the decomposition (two cores or more).
        self.fallback_beside = s.fallback_beside
        self.seconds = s.seconds_meshing + s.seconds_smoothing + s.seconds_checking

    def as_dict(self):
        return dict(vars(self))

    def __repr__(self):
        return "MeshStats({})".format(", ".join("{}={!r}".format(k, v)
                                                for k, v in vars(self).items()))


def _nodes_of(core_mesh):
    buf = core_mesh.node_bytes()
    if _np is not None:
        return _np.frombuffer(buf, dtype=_np.float64).reshape(-1, 3).copy()
    flat = array("d", buf)
    return [tuple(flat[i:i + 3]) for i in range(0, len(flat), 3)]


def _hexes_of(core_mesh):
    buf = core_mesh.hex_bytes()
    if _np is not None:
        return _np.frombuffer(buf, dtype=_np.int32).reshape(-1, 8).copy()
    flat = array("i", buf)
    return [tuple(flat[i:i + 8]) for i in range(0, len(flat), 8)]


class MeshResult:
    """What VoroHex.mesh returns: status, diagnostics, statistics and the mesh."""

    def __init__(self, core_result, solid):
        self._core = core_result
        self._solid = solid
        self._mesh = core_result.mesh

    ok = property(lambda self: self._core.ok, doc="True if a valid mesh was produced")
    diagnostics = property(lambda self: self._core.diagnostics)
    check_report = property(lambda self: self._core.check, doc="the validity check")
    stats = property(lambda self: MeshStats(self._core))
    scaled_jacobian = property(lambda self: list(self._core.scaled_jacobian))
    hex_count = property(lambda self: self._mesh.num_hexes)
    node_count = property(lambda self: self._mesh.num_nodes)
    core_mesh = property(lambda self: self._mesh, doc="the _VoroHexCore.HexMesh")

    @property
    def errors(self):
        return [d for d in self.diagnostics if d.severity == "error"]

    @property
    def message(self):
        """One line for the user: the errors, else 'ok' with the counts."""
        # The check's errors are among the result's too: each said once.
        errs = list({(d.code, d.message): d for d in self.errors + ([] if self.ok else [
            d for d in self.check_report.diagnostics if d.severity == "error"])}.values())
        if errs or not self.ok:
            return "; ".join(_describe(d) for d in errs) or "meshing failed"
        s = self.stats
        return "{} hexes, {} nodes, min scaled Jacobian {:.3f}".format(
            s.hexes, s.nodes, s.min_scaled_jacobian)

    @property
    def nodes(self):
        """N x 3 coordinates (numpy array if numpy is installed, else list of tuples)."""
        return _nodes_of(self._mesh)

    @property
    def hexes(self):
        """M x 8 zero-based node indices, VTK order."""
        return _hexes_of(self._mesh)

    def sub_volume_table(self):
        """Per sub-volume (SubVolume cell data 1, 2, ...; 0 for a solid meshed whole): a dict
        with id, type ("Vs": swept between two faces of the solid, "Ve": a block or a sweep
        from or to a cut face, "-": the fallback, the grid mesher), scheme, hexes and the min and
        mean scaled Jacobian of its hexes."""
        ids = array("i", self._mesh.sub_volume_bytes())
        sj = self._core.scaled_jacobian
        schemes = list(self._core.stats.sub_volume_schemes)
        types = list(self._core.stats.sub_volume_types)
        rows = {}
        for k, sv in enumerate(ids):
            r = rows.setdefault(sv, {"id": sv, "hexes": 0, "min_scaled_jacobian": float("inf"),
                                     "sum": 0.0})
            r["hexes"] += 1
            if k < len(sj):
                r["min_scaled_jacobian"] = min(r["min_scaled_jacobian"], sj[k])
                r["sum"] += sj[k]
        table = []
        for sv in sorted(rows):
            r = rows[sv]
            r["mean_scaled_jacobian"] = r.pop("sum") / r["hexes"]
            # A solid meshed whole carries sub-volume 0 on its hexes: it is the one scheme.
            k = max(sv, 1) - 1
            r["scheme"] = schemes[k] if k < len(schemes) else ""
            r["type"] = types[k] if k < len(types) else ""
            table.append(r)
        return table

    @property
    def order(self):
        """1 (8-node hexahedra) or 2 (20-node)."""
        return self._mesh.order

    @property
    def groups(self):
        """Named groups per CAD entity, faces first: {name: {"dim", "id", "nodes" (0-based
        node indices), "faces" ([(hex, local face)], faces only)}}; names as in FreeCAD
        ("Face7", "Edge3", "Vertex1")."""
        out = {}
        for g in self._core.groups:
            faces = array("i", g["faces"])
            out[g["name"]] = {"dim": g["dim"], "id": g["id"],
                              "nodes": array("i", g["nodes"]).tolist(),
                              "faces": [(faces[i], faces[i + 1]) for i in range(0, len(faces), 2)]}
        return out

    def to_femmesh(self, groups=True):
        """A Fem.FemMesh with the hexahedra in SMESH node order (1-based ids; 20-node
        hexahedra for order 2), with a node group per CAD face, edge and vertex ("Face7",
        ...) unless groups is False."""
        named = [(name, g["nodes"]) for name, g in self.groups.items()] if groups else ()
        return _femmesh_of(self._mesh, named)

    def write(self, path, element=None):
        """Writes .vtu, .msh or .inp (format from the extension), with the named groups.
        element: the .inp element type (C3D8, C3D8I, C3D8R for order 1; C3D20, C3D20R for
        order 2); None = C3D8I / C3D20R, replaced where known to fail. Returns the element
        choice's diagnostics; raises ValueError for an unknown or refused element."""
        if element is not None and not isinstance(element, str):
            raise TypeError("VoroHex: element must be a name such as 'C3D8I', got {!r}".format(
                element))
        return _core.write_result(self._core, os.fspath(path), element or "")

    def __repr__(self):
        return "<VoroHex.MeshResult ok={} {}>".format(self.ok, self.message)


def _describe(d):
    ents = " ({})".format(", ".join(d.entities)) if d.entities else ""
    return "{}{}".format(d.message, ents)


def _order(order):
    """1 or 2 from 1, 2, "1st" or "2nd" (the ElementOrder property's values)."""
    if order in ELEMENT_ORDERS:
        return ELEMENT_ORDERS.index(order) + 1
    if isinstance(order, bool) or order not in (1, 2):
        raise ValueError("VoroHex: order must be 1 (8-node hexahedra) or 2 (20-node), got "
                         "{!r}".format(order))
    return int(order)


def mesh(shape, size=None, progress=None, cancel=None, order=1, sizes=None, **options):
    """Hex-meshes the one solid in `shape` (a Part.Shape or a Part feature).

    size: target edge length (a number of mm, a Quantity, or a string with its unit such as
    "4 mm"); None = automatic.
    order: 1 (8-node hexahedra) or 2 (20-node: mid-edge nodes on the CAD edge or face they
    belong to, straight inside); "1st"/"2nd" also work.
    sizes: smaller sizes at CAD entities, {"Face7": 0.5, "Edge3": 1}, graded into size at
    size_grading (0.3: 0.3 mm larger per mm of distance); an entity the solid does not
    have raises ValueError.
    progress: optional callable(stage, fraction); returning False cancels.
    cancel: optional VoroHex.CancelToken, .cancel() from another thread stops meshing.
    Other keyword options: see VoroHex.OPTIONS. Unknown keywords raise TypeError; bad
    values or shapes raise ValueError (ShapeError for shapes). Meshing failures are not
    exceptions: the result has ok=False and diagnostics saying why.
    """
    if progress is not None and not callable(progress):
        raise TypeError("VoroHex: progress must be callable(stage, fraction)")
    if cancel is not None and not isinstance(cancel, CancelToken):
        raise TypeError("VoroHex: cancel must be a VoroHex.CancelToken")
    opts = _make_options(dict(options, size=size))
    opts.order = _order(order)
    opts.local_sizes = _local_sizes(sizes)
    solid = _read_solid(check_shape(shape, True), True)
    core_result = _core.generate_mesh(solid, opts, progress, cancel)
    return MeshResult(core_result, solid)


def from_femmesh(femmesh):
    """A _VoroHexCore.HexMesh from a Fem.FemMesh's hexahedra (VTK order): 8-node ones, and
    the corners of 20-node ones (their mid-edge nodes are not read)."""
    by_id = femmesh.Nodes  # a new dict at every access: read it once
    ids = sorted(by_id)
    index = {nid: i for i, nid in enumerate(ids)}
    nodes = array("d")
    for nid in ids:
        p = by_id[nid]
        nodes.extend((p.x, p.y, p.z))
    hexes = array("i")
    for vid in femmesh.Volumes:
        en = femmesh.getElementNodes(vid)
        if len(en) not in (8, 20):
            raise ValueError("VoroHex: element {} has {} nodes; only 8- and 20-node hexahedra "
                             "can be checked".format(vid, len(en)))
        hexes.extend(index[en[k]] for k in SMESH_FROM_VTK)
    return _core.HexMesh.from_bytes(nodes.tobytes(), hexes.tobytes())


def element_quality(mesh):
    """Scaled Jacobian of every hexahedron of a Fem.FemMesh (or a mesh object holding one)
    as {element id: value}: 1 for a cube, <= 0 when inverted."""
    femmesh = getattr(mesh, "FemMesh", mesh)
    if not (hasattr(femmesh, "Volumes") and hasattr(femmesh, "getElementNodes")):
        raise TypeError("VoroHex.element_quality: expected a Fem.FemMesh or a mesh object, "
                        "got {}".format(type(mesh).__name__))
    values = from_femmesh(femmesh).scaled_jacobians()
    return dict(zip(femmesh.Volumes, values))


def _as_core_mesh(mesh_or_path):
    if isinstance(mesh_or_path, MeshResult):
        return mesh_or_path.core_mesh
    if isinstance(mesh_or_path, _core.HexMesh):
        return mesh_or_path
    if isinstance(mesh_or_path, (str, os.PathLike)):
        path = os.fspath(mesh_or_path)
        if not os.path.exists(path):
            raise FileNotFoundError("VoroHex.check: no such file: " + path)
        m, diags = _core.read_mesh(path)
        if m is None:
            raise ValueError("VoroHex.check: cannot read {}: {}".format(
                path, "; ".join(d.message for d in diags)))
        return m
    femmesh = getattr(mesh_or_path, "FemMesh", mesh_or_path)  # a mesh object or a FemMesh
    if hasattr(femmesh, "Volumes") and hasattr(femmesh, "getElementNodes"):
        return from_femmesh(femmesh)
    if isinstance(mesh_or_path, tuple) and len(mesh_or_path) == 2:  # (nodes, hexes)
        nodes, hexes = mesh_or_path
        n = array("d", [float(c) for p in nodes for c in p])
        h = array("i", [int(v) for e in hexes for v in e])
        return _core.HexMesh.from_bytes(n.tobytes(), h.tobytes())
    raise TypeError("VoroHex.check: expected a MeshResult, a file path, a Fem.FemMesh or "
                    "(nodes, hexes), got {}".format(type(mesh_or_path).__name__))


def check(mesh_or_path, shape=None, volume_rel_tol=None, distance_rel_tol=None):
    """Validity and quality of a hex mesh (VoroHex's or any tool's), optionally against
    the solid it should fill. Returns a CheckReport (.valid, .diagnostics, ...)."""
    m = _as_core_mesh(mesh_or_path)
    solid = _read_solid(check_shape(shape, True), True) if shape is not None else None
    defaults = _core.MeshOptions()
    vt = defaults.volume_rel_tol if volume_rel_tol is None else _number(
        "volume_rel_tol", volume_rel_tol)
    dt = defaults.distance_rel_tol if distance_rel_tol is None else _number(
        "distance_rel_tol", distance_rel_tol)
    return _core.check_mesh(m, solid, vt, dt)


class VoronoiGraph:
    """The embedded Voronoi graph of a solid (what VoroHex.voronoi_graph returns).

    elements: list of dicts, one per Voronoi vertex, edge and face, with
      "id" (its index), "kind" ("vertex", "edge" or "face"), "governors" (FreeCAD names of
      the nearest model entities, e.g. ["Face1", "Face3"]), "point" (x, y, z; a face's is
      one point of it, an edge's its middle), "radius" (distance to the governors),
      "verified", "incident" (ids of incident elements), "f_s" (faces: governed by two
      unconnected model faces) and "polyline" (edges: list of (x, y, z)).
    counts: {"vertices", "edges", "faces", "f_s"}; status: "ok", "partial" or "failed";
    diagnostics: list of dicts (severity, code, message, entities); stats: octree figures.
    """

    def __init__(self, data):
        self.data = data
        self.elements = data.get("elements", [])
        for e in self.elements:
            e["point"] = tuple(e["point"])
            e.setdefault("f_s", False)
            if "polyline" in e:
                e["polyline"] = [tuple(p) for p in e["polyline"]]
        self.counts = data.get("counts", {})
        self.stats = data.get("stats", {})
        self.status = data.get("status", "failed")
        self.diagnostics = data.get("diagnostics", [])

    ok = property(lambda self: self.status != "failed",
                  doc="False when no graph could be computed (see diagnostics)")

    def of_kind(self, kind):
        """Elements of one kind: "vertex", "edge" or "face"."""
        return [e for e in self.elements if e["kind"] == kind]

    def fs_faces(self):
        """Voronoi faces governed by two unconnected model faces (the paper's f_s)."""
        return [e for e in self.elements if e["kind"] == "face" and e["f_s"]]

    def find(self, governors):
        """Elements governed by exactly these entities (names, any order)."""
        want = sorted(governors)
        return [e for e in self.elements if sorted(e["governors"]) == want]

    def type_counts(self):
        """Number of Voronoi edges per type, e.g. {"[1]": 8, "[2]": 4}."""
        counts = {}
        for e in self.of_kind("edge"):
            counts[e.get("type", "none")] = counts.get(e.get("type", "none"), 0) + 1
        return counts

    def as_dict(self):
        return self.data

    def __repr__(self):
        return "<VoroHex.VoronoiGraph {} {}>".format(self.status, self.counts)


def _voronoi_options(eps, delta, max_depth, linear_tolerance):
    opts = _core.VoronoiOptions()
    given = dict(eps=eps, delta=delta, max_depth=max_depth, linear_tolerance=linear_tolerance)
    for name, value in given.items():
        if value is None:
            continue
        value = _number(name, value, integer=name == "max_depth")
        if name == "max_depth" and not 1 <= value <= 12:
            raise ValueError("VoroHex: option 'max_depth' must be in 1..12, got {}".format(
                value))
        if value <= 0:
            raise ValueError("VoroHex: option '{}' must be > 0, got {}".format(name, value))
        setattr(opts, name, value)
    try:
        opts.validate()
    except ValueError as e:
        raise ValueError("VoroHex: " + str(e)) from None
    return opts


Cancelled = _core.Cancelled  # raised when a progress callback returns False


def voronoi_graph(shape, eps=None, delta=None, max_depth=None, linear_tolerance=None,
                  sharp_angle=None, progress=None):
    """The embedded Voronoi graph of the one solid in `shape` (a Part.Shape or feature).

    eps: merge tolerance / finest cell, delta: embedding accuracy, linear_tolerance: chord
    tolerance of curved entities, all relative to the bounding-box diagonal; max_depth:
    octree depth 1..12. None keeps the default (VoroHex's C++ VoronoiOptions). Returns a
    VoronoiGraph; bad values raise ValueError naming the option, bad shapes ShapeError.
    Every edge element gets "type", its class for the decomposition ("[0]", "[1]", "[1s]",
    "[2]", "[3]", "[1e]", "[0e]", "[C]", "degenerate" or "none"); sharp_angle (degrees,
    default 60) is the dihedral below which a [1] edge is [1s]. It is computed in a child
    process: progress(stage, fraction) is called about every 0.2 s and may return False to
    stop it (VoroHex.Cancelled is raised).
    """
    opts = _voronoi_options(eps, delta, max_depth, linear_tolerance)
    angle = 60.0 if sharp_angle is None else _number("sharp_angle", sharp_angle)
    if not 0 < angle <= 180:
        raise ValueError("VoroHex: option 'sharp_angle' must be in (0, 180], got {}".format(
            angle))
    solid = _read_solid(check_shape(shape))
    text, types = _core.typed_voronoi_graph(solid, opts, angle, progress)
    graph = VoronoiGraph(json.loads(text))
    by_id = dict(types)
    for e in graph.elements:
        if e["kind"] == "edge":
            e["type"] = by_id.get(e["id"], "none")
    return graph


class Decomposition:
    """The decomposition of a solid into sub-volumes (what VoroHex.decompose returns).

    status: "ok", "partial" or "failed" (partial_reason: why partial); counts:
    {"sub_volumes_before_merge", "sub_volumes", "decomposition_faces", "quads", ...};
    sub_volumes: list of dicts with "id", "type" ("Vs"/"Ve"), "scheme" ("sweep"/"map"/
    "multisweep"/"revolve"/"midpoint"/"none"), "reason", "volume", "merged_from",
    "source"/"target" (sweeps); faces: the decomposition faces ("id",
    "sub_volumes", "edges", "area", "min_angle" (degrees, its smallest angle with a
    neighbouring face), "voronoi_elements", "governors"); diagnostics: list of dicts;
    shapes: the sub-volumes as Part.Solid, in the order of sub_volumes (empty when the
    decomposition failed). method: "voronoi", "plane-cuts" or "whole" (method="auto" on
    a solid one scheme meshes whole; see decompose).
    cut_surfaces (plane cuts only): why each cut is where it is, a dict per surface with
    "kind" ("plane"/"cylinder"/"tangent_plane": tangent to the cylinder of "face"/
    "hole_plane": parallel to the axis of the hole "face" is on, about 1.5 radii from it,
    where the cut at concave edges alone fails; "foot_plane": across an axis where the
    tapered "face" (a chamfer, a cone) meets a wall, where the others fail; method "auto"
    only),
    "face" (the model face it extends, "Face7"), "concave_edges" (where it is taken,
    ["Edge12", ...]) and "used" (False: left out); knife_edges: pieces meet at an angle near
    zero where a planar face touches a cylinder cut along (the mesher then tries
    tangent_planes=True where they do not mesh); merges_checked_each: the merging, run first
    without checking each merge's neighbours, left a piece without a scheme and was run
    again checking them.
    """

    def __init__(self, data, shapes):
        self.data = data
        self.status = data.get("status", "failed")
        self.partial_reason = data.get("partial_reason", "")  # why "partial" (else empty)
        self.counts = data.get("counts", {})
        self.sub_volumes = data.get("sub_volumes", [])
        self.faces = data.get("decomposition_faces", [])
        self.diagnostics = data.get("diagnostics", [])
        self.shapes = shapes
        self.method = data.get("method", "voronoi")
        self.cut_surfaces = data.get("cut_surfaces", [])
        self.knife_edges = data.get("knife_edges", False)
        self.merges_checked_each = data.get("merges_checked_each", False)

    ok = property(lambda self: self.status != "failed",
                  doc="False when the solid could not be cut (see diagnostics)")

    def as_dict(self):
        return self.data

    def __repr__(self):
        return "<VoroHex.Decomposition {} {}>".format(self.status, self.counts)


# Seconds decompose() may take unless told otherwise (as `vorohex decompose --time-limit`).
DECOMPOSITION_TIME_LIMIT = 30.0


def decompose(shape, sharp_angle=None, merge=True, vtp=None, eps=None, delta=None,
              max_depth=None, linear_tolerance=None, progress=None, method="voronoi",
              time_limit=DECOMPOSITION_TIME_LIMIT, tangent_planes=False, multisweep=True,
              revolve=True):
    """Cuts the one solid in `shape` into sweepable and mappable sub-volumes along its
    embedded Voronoi graph (vorohex decompose). sharp_angle: degrees in (0, 180] below
    which a dihedral counts as sharp (default 60); merge: unite neighbours whose union is
    a sweep; vtp: a path to write the decomposition faces to (VTK PolyData); the graph
    options are those of voronoi_graph; progress as for voronoi_graph; time_limit: seconds
    the whole may take (default 30, as `vorohex decompose --time-limit`): the split and the
    merging get what is left; stopped before the split ends it fails (status "failed", a
    "time_limit" error naming the step), stopped later the merging ends and the
    sub-volumes it has are returned. Returns a Decomposition.

    method="plane-cuts": the mesher's other way (vorohex decompose --plane-cuts): exact
    cuts along the planes and cylinders of the faces at concave edges, through the whole
    solid, then pieces merged while their union keeps a scheme. Each sub-volume has "id",
    "scheme" (the scheme it gets once glued to the others, "none" with a "reason") and
    "volume"; counts has "planes", "cylinders", "sub_volumes_before_merge" and
    "sub_volumes"; shapes holds the pieces, also the pieces as cut when the cuts failed
    (status "failed", the reason in diagnostics). It takes none of the Voronoi options
    (time_limit and progress it takes). tangent_planes=True (plane cuts only): each
    cylinder that a planar face touches tangently is replaced by the plane tangent to it
    across its concave edges (vorohex decompose --plane-cuts --tangent-planes; what the
    mesher tries where the cut's pieces have knife edges and do not mesh). merge=False
    with it: the pieces as cut, each with its scheme (--plane-cuts --no-merge).

    method="auto": the sub-volumes the mesher meshes (vorohex decompose --auto): the solid
    whole where one scheme takes it (method "whole", info "not_cut"; judged as the meshers
    judge, without meshing); else the plane cuts where they give sub-volumes that all have
    a scheme (with tangent_planes=True where the first cut's pieces have knife edges),
    within half of time_limit; else the Voronoi decomposition, within a fifth of it (the 6 s
    the mesher gives it by default). Its method says which; a Voronoi result also carries
    the info "plane_cuts_not_used" saying why not, and "mesher_fallback" where not every
    sub-volume has a scheme (the mesher then meshes the solid with the grid mesher). vtp is
    written by the Voronoi decomposition only.

    multisweep, revolve (default True): whether the many-to-one sweep of prismatic parts
    and the revolution judge the sub-volumes besides the mapped block, the sweep and
    midpoint subdivision (as the mesh's schemes; the plane cuts take no revolve)."""
    import time
    if method not in ("voronoi", "plane-cuts", "auto"):
        raise ValueError("VoroHex: option 'method' must be 'voronoi', 'plane-cuts' or 'auto', "
                         "got {!r}".format(method))
    for name, value in (("multisweep", multisweep), ("revolve", revolve)):
        if not isinstance(value, bool):
            raise TypeError("VoroHex: option '{}' must be True or False, got {!r}".format(
                name, value))
    limit = _seconds("time_limit", time_limit)
    if not isinstance(tangent_planes, bool):
        raise TypeError("VoroHex: option 'tangent_planes' must be True or False, got "
                        "{!r}".format(tangent_planes))
    if not isinstance(merge, bool):
        raise TypeError("VoroHex: option 'merge' must be True or False, got {!r}".format(merge))
    if tangent_planes and method != "plane-cuts":
        raise ValueError("VoroHex: option 'tangent_planes' is an option of "
                         "method='plane-cuts'")
    if method == "plane-cuts":
        given = dict(sharp_angle=sharp_angle, vtp=vtp, eps=eps, delta=delta,
                     max_depth=max_depth, linear_tolerance=linear_tolerance)
        named = sorted(k for k, v in given.items() if v is not None)
        if named:
            raise ValueError("VoroHex: option '{}' is an option of the Voronoi decomposition; "
                             "method='plane-cuts' takes none".format(named[0]))
        solid = _read_solid(check_shape(shape))
        return _writing_parts(lambda brep: _core.plane_cuts_json(
            solid, brep, progress, limit, tangent_planes, merge, multisweep))
    angle = 60.0 if sharp_angle is None else _number("sharp_angle", sharp_angle)
    if not 0 < angle <= 180:
        raise ValueError("VoroHex: option 'sharp_angle' must be in (0, 180], got {}".format(
            angle))
    opts = _voronoi_options(eps, delta, max_depth, linear_tolerance)
    checked = check_shape(shape)
    solid = _read_solid(checked)

    def voronoi(seconds):
        return _writing_parts(lambda brep: _core.decomposition_json(
            solid, opts, angle, merge, brep, vtp or "", progress, seconds, multisweep, revolve))

    if method == "voronoi":
        return voronoi(limit)
    start = time.monotonic()
    text = _core.whole_solid_json(solid, multisweep, revolve)
    if text:
        return Decomposition(json.loads(text), [checked.Solids[0]])
    cut = _writing_parts(lambda brep: _core.plane_cuts_json(
        solid, brep, progress, 0.5 * limit, False, merge, multisweep, as_the_mesher=True))
    if cut.ok:
        return cut
    why = "; ".join(x.get("message", "") for x in cut.diagnostics
                    if x.get("severity") == "error") or "no sub-volumes"
    # At most a fifth of the limit: the 6 s the mesher gives it by default (a tenth of its
    # decomposition time limit of 60 s).
    d = voronoi(max(1.0, min(0.2 * limit, limit - (time.monotonic() - start))))
    d.diagnostics.append({"severity": "info", "code": "plane_cuts_not_used", "entities": [],
                          "message": "Not cut along the faces at its concave edges: " +
                          why[0].lower() + why[1:]})
    if not d.ok or any(sv.get("scheme") == "none" for sv in d.sub_volumes):
        d.diagnostics.append({
            "severity": "info", "code": "mesher_fallback", "entities": [],
            "message": "Not every sub-volume has a scheme, so the mesher meshes the solid "
                       "with its fallback (the grid mesher) instead."})
    return d


def _writing_parts(compute):
    """The Decomposition of compute(brep_path) (its JSON text), with the solids it wrote to
    brep_path (a temporary file)."""
    import tempfile
    with tempfile.TemporaryDirectory(prefix="vorohex-") as tmp:
        brep = os.path.join(tmp, "parts.brep")
        text = compute(brep)
        shapes = []
        if os.path.exists(brep):
            import Part
            shapes = list(Part.read(brep).Solids)
    return Decomposition(json.loads(text), shapes)
