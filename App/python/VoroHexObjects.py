# The parametric hex mesh document object, on FreeCAD's FemMeshGmsh pattern: a
# Fem::FemMeshObjectPython whose proxy re-meshes its linked Part on recompute.
"""VoroHex document objects (usable headless, in freecadcmd)."""

import math
import os
import sys
from array import array

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
    ("Scheme", "App::PropertyString",
     "How the solid was meshed: map (block), sweep, multisweep, revolve, midpoint, or grid "
     "(the fallback); sub-volumes joined by +"),
    ("VolumeError", "App::PropertyFloat", "Relative volume error of the mesh vs the solid"),
    ("ScaledJacobianHistogram", "App::PropertyIntegerList",
     "Hexes per scaled Jacobian bin of 0.1 from -1 to 1"),
    ("SubVolumeSchemes", "App::PropertyStringList", "Per sub-volume (1, 2, ...): its scheme"),
    ("SubVolumeTypes", "App::PropertyStringList",
     "Per sub-volume: Vs (swept between two faces of the solid), Ve (a block, or a sweep "
     "from or to a cut face), - (the fallback: the grid mesher)"),
    ("SubVolumeHexCounts", "App::PropertyIntegerList", "Per sub-volume: its hexahedra"),
    ("SubVolumeMinScaledJacobian", "App::PropertyFloatList",
     "Per sub-volume: the smallest scaled Jacobian of its hexahedra"),
    ("SizeUsed", "App::PropertyFloat", "The target size the last mesh was made with (mm)"),
    ("ScaledJacobians", "App::PropertyFloatList",
     "Scaled Jacobian of every hexahedron, element 1, 2, ... (the Mesh quality view reads "
     "it instead of computing it again)"),
    ("Diagnostics", "App::PropertyStringList",
     "Messages of the last recompute, one per line: severity [code] message"),
    ("DiagnosticEntities", "App::PropertyStringList",
     "Per message, the model entities it names (Face7, Edge3, ...; comma-separated)"),
)


def record_diagnostics(obj, diagnostics):
    """Stores the messages and the entities each names (the task panel highlights them)."""
    obj.Diagnostics = ["{} [{}] {}".format(d.severity, d.code, d.message) for d in diagnostics]
    obj.DiagnosticEntities = [",".join(d.entities) for d in diagnostics]


def merged_split_faces(shape):
    """(solid, n): `shape` with the faces that lie on one surface with a neighbour merged
    (OCCT's unification, as Part > Refine shape), and how many faces that took away; (shape,
    0) when none do or the unification fails. A Part boolean without Refine (FreeCAD 0.20's
    default) keeps faces split where its operands met; the Voronoi graph takes each as a face
    of its own, equally near as its neighbour along a whole region, drawn as a degenerate
    edge, and the decomposition follows it (an L bracket fused and cut without Refine: no
    [1e] edge and one sub-volume without a scheme; refined: two [1e] edges, a block and two
    sweeps). So the graph and decomposition objects work on the merged solid. (The hex mesh's
    schemes take such faces as they are.)"""
    try:
        merged = shape.removeSplitter()
        if merged.ShapeType != "Solid":
            solids = merged.Solids
            if len(solids) != 1:
                return shape, 0
            merged = solids[0]
        n = len(shape.Faces) - len(merged.Faces)
        if n <= 0 or not merged.isValid() or abs(merged.Volume - shape.Volume) > \
                1e-9 * max(abs(shape.Volume), 1e-300):
            return shape, 0
        return merged, n
    except Exception:  # OCCT's unification failed: the faces as they are
        return shape, 0


def merged_faces_note(n):
    """What a graph or decomposition computed on merged_split_faces() says of it."""
    return ("Computed with {} face{} merged into a neighbour on the same surface (a Part "
            "boolean without Refine): face names refer to the refined solid.").format(
                n, "s" if n > 1 else "")


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
    # A feature whose last recompute failed still holds the shape of the one before: meshing
    # it would mesh what the user no longer sees in the tree (a Body: its Tip feature).
    for feature in (part, getattr(part, "Tip", None)):
        if feature is not None and "Invalid" in getattr(feature, "State", []):
            return ("'{}' failed to recompute, so its shape is the last one that did: fix it "
                    "(the Report view says why) and recompute first".format(feature.Label))
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


def object_name(part, kind):
    """An internal name for a new object made from `part` ("Box_HexMesh"): FreeCAD keeps
    names to ASCII letters, digits and underscores and makes them unique itself."""
    import re

    base = re.sub(r"[^A-Za-z0-9_]", "_", part.Name)
    return "{}_{}".format(base, kind)


def graph_options_of(obj):
    """Keyword options eps, delta, max_depth for VoroHex.voronoi_graph / decompose."""
    return {o.name: getattr(obj, o.prop) for o in GRAPH_OPTIONS if hasattr(obj, o.prop)}


def options_of(obj):
    """Keyword options for VoroHex.mesh from the object's properties (via VoroHex.OPTIONS,
    and order from ElementOrder)."""
    opts = {}
    for o in VoroHex.OPTIONS:
        value = getattr(obj, o.prop)
        if o.prop_type == "App::PropertyLength":
            value = value.Value
        opts[o.name] = None if (o.auto_zero and value == 0) else value
    if hasattr(obj, "ElementOrder"):
        opts["order"] = str(obj.ElementOrder)
    sizes = region_sizes(obj)
    if sizes:
        opts["sizes"] = sizes
    return opts


def region_sizes(obj):
    """Local sizes {"Face7": 0.5, ...} from the FEM mesh region objects in the object's
    MeshRegionList (FreeCAD's Fem::MeshRegion: CharacteristicLength and References). A
    region must reference faces, edges or vertices of the meshed part itself and have a
    size; ValueError naming the region otherwise. An entity in two regions keeps the
    smaller size."""
    sizes = {}
    part = getattr(obj, "Part", None)
    for region in getattr(obj, "MeshRegionList", []) or []:
        if region is None or not hasattr(region, "CharacteristicLength"):
            continue
        if getattr(region, "Suppressed", False):
            continue
        size = region.CharacteristicLength.Value
        if size <= 0:
            raise ValueError("VoroHex: mesh region '{}' has no size (CharacteristicLength is "
                             "0)".format(region.Label))
        refs = getattr(region, "References", []) or []
        if not refs:
            raise ValueError("VoroHex: mesh region '{}' references no face, edge or vertex"
                             .format(region.Label))
        for ref_obj, subs in refs:
            # The part itself, the same shape, or the tip of a PartDesign Body (a pick in the
            # 3D view names the tip feature; the Body's faces are numbered as the tip's).
            same = part is not None and (
                ref_obj == part or getattr(part, "Tip", None) == ref_obj or (
                    hasattr(ref_obj, "Shape") and ref_obj.Shape.isSame(part.Shape)))
            if not same:
                raise ValueError("VoroHex: mesh region '{}' references '{}', not the meshed part "
                                 "'{}': pick faces, edges or vertices of '{}'".format(
                                     region.Label, ref_obj.Label,
                                     part.Label if part is not None else "(none)",
                                     part.Label if part is not None else "the part"))
            for sub in (subs if isinstance(subs, (list, tuple)) else [subs]):
                if not sub or not sub.startswith(("Face", "Edge", "Vertex")):
                    raise ValueError("VoroHex: mesh region '{}' references '{}' of '{}'; only "
                                     "faces, edges and vertices can take a local size".format(
                                         region.Label, sub or "the whole object", ref_obj.Label))
                sizes[sub] = min(size, sizes.get(sub, size))
    return sizes


def addMeshRegion(mesh_obj, size, references):
    """Adds a FreeCAD FEM mesh region (a local size) to a VoroHex mesh object: `size` in
    mm at `references`, a list of sub-element names of its part ("Face7", "Edge3"). Returns
    the region; the mesh follows it on the next recompute."""
    try:
        import ObjectsFem
    except ImportError:  # plain python3 with FreeCAD's lib: the FEM module is not on the path
        sys.path.append(os.path.join(FreeCAD.getHomePath(), "Mod", "Fem"))
        import ObjectsFem

    if getattr(getattr(mesh_obj, "Proxy", None), "Type", None) != TYPE:
        raise TypeError("VoroHex: {} is not a VoroHex mesh object".format(
            getattr(mesh_obj, "Label", mesh_obj)))
    if isinstance(references, str):
        references = [references]
    size = VoroHex._number("size", size)
    if size <= 0:
        raise ValueError("VoroHex: a local size must be > 0, got {}".format(size))
    for name in references:
        if not isinstance(name, str) or not VoroHex._ENTITY_NAME.match(name):
            raise ValueError("VoroHex: {!r} is not a face, edge or vertex name (FaceN, EdgeN, "
                             "VertexN)".format(name))
        try:
            mesh_obj.Part.Shape.getElement(name)
        except Exception:
            raise ValueError("VoroHex: '{}' has no {}".format(mesh_obj.Part.Label, name))
    region = ObjectsFem.makeMeshRegion(mesh_obj.Document, mesh_obj, size,
                                       object_name(mesh_obj, "MeshRegion"))
    region.References = [(mesh_obj.Part, tuple(references))]
    return region


class HexMesh:
    """Proxy of the VoroHex mesh object."""

    Type = TYPE

    def __init__(self, obj):
        obj.Proxy = self
        self.add_properties(obj, new=True)

    def add_properties(self, obj, new=False):
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
        if not hasattr(obj, "ElementOrder"):  # as FreeCAD's FemMeshGmsh names it
            obj.addProperty("App::PropertyEnumeration", "ElementOrder", "FEM Mesh",
                            "1st: 8-node hexahedra; 2nd: 20-node, mid-edge nodes on the CAD")
            obj.ElementOrder = list(VoroHex.ELEMENT_ORDERS)
            # New meshes are quadratic, as FemMeshGmsh's: FreeCAD's CalculiX writer makes
            # 8-node hexahedra C3D8, which lock in bending (-12 % on a cantilever two
            # elements thick), 20-node ones C3D20 (-0.3 %). A file saved before the
            # property existed had linear hexahedra and keeps them.
            obj.ElementOrder = "2nd" if new else "1st"
        if not hasattr(obj, "MeshRegionList"):  # as FemMeshGmsh names it: local sizes
            obj.addProperty("App::PropertyLinkList", "MeshRegionList", "FEM Mesh",
                            "FEM mesh regions: a smaller size at the faces, edges and vertices "
                            "they reference, graded into TargetSize at SizeGrading")
        if not hasattr(obj, "PreviewObjects"):  # names, not links: no dependency on them
            obj.addProperty("App::PropertyStringList", "PreviewObjects", "Result",
                            "The graph and decomposition the panel's last Preview made")
            obj.setEditorMode("PreviewObjects", 2)

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
        FreeCAD marks the object invalid with that message. (The task panel meshes in a
        child process instead, VoroHexJobs, and hands the result to apply().)"""
        error = source_error(obj.Part, True)
        payload = None
        if error is None:
            error = refusal(obj)
        if error is None:
            try:
                payload = mesh_payload(VoroHex.mesh(
                    obj.Part.Shape, progress=getattr(self, "progress", None), **options_of(obj)))
            except (TypeError, ValueError) as e:
                error = str(e).replace("VoroHex: ", "")
        if error is not None:
            record_diagnostics(obj, [])
            obj.Status, obj.Message = "error", error
            raise RuntimeError("VoroHex: " + error)
        error = self.apply(obj, payload)
        if error is not None:
            raise RuntimeError("VoroHex: " + error)

    def apply(self, obj, payload, femmesh=None):
        """Stores a mesh_payload() on the object (femmesh: its FemMesh when already built).
        Returns None, or the error (the previous mesh is kept, Status "error")."""
        record_diagnostics(obj, payload["diagnostics"])
        if not payload["ok"]:
            obj.Status, obj.Message = "error", payload["message"]
            return payload["message"]
        s = payload["stats"]
        obj.FemMesh = femmesh if femmesh is not None else femmesh_of(payload)
        obj.HexCount, obj.NodeCount, obj.SubVolumeCount = s["hexes"], s["nodes"], \
            s["sub_volumes"]
        obj.MinScaledJacobian, obj.MeanScaledJacobian = s["min_scaled_jacobian"], \
            s["mean_scaled_jacobian"]
        obj.MinScaledJacobianBeforeSmoothing = s["min_scaled_jacobian_before_smoothing"]
        obj.MeanScaledJacobianBeforeSmoothing = s["mean_scaled_jacobian_before_smoothing"]
        obj.Scheme = s["scheme"]
        obj.VolumeError = s["volume_rel_error"]
        obj.ScaledJacobianHistogram = [int(c) for c in s["histogram"]]
        obj.ScaledJacobians = array("d", payload.get("scaled_jacobian", b"")).tolist()
        if hasattr(obj, "SizeUsed"):
            obj.SizeUsed = s["size_used"]
        table = payload["sub_volumes"]
        obj.SubVolumeSchemes = [r["scheme"] for r in table]
        obj.SubVolumeTypes = [r["type"] for r in table]
        obj.SubVolumeHexCounts = [r["hexes"] for r in table]
        obj.SubVolumeMinScaledJacobian = [float(r["min_scaled_jacobian"]) for r in table]
        obj.Status, obj.Message = "ok", payload["message"]
        self.arrays = (payload["nodes"], payload["hexes"])  # the Mesh quality view's (not saved)
        return None


class Diagnostic:
    """A message of a run as plain values (what a child process hands back)."""

    def __init__(self, severity, code, message, entities):
        self.severity, self.code, self.message = severity, code, message
        self.entities = list(entities)


def mesh_payload(result):
    """A VoroHex.MeshResult as plain, picklable values: what apply() stores."""
    stats = result.stats.as_dict()
    mesh = result.core_mesh
    return {
        "ok": bool(result.ok),
        "message": result.message,
        "stats": stats,
        "diagnostics": [Diagnostic(d.severity, d.code, d.message, d.entities)
                        for d in result.diagnostics],
        "sub_volumes": result.sub_volume_table() if result.ok else [],
        "nodes": mesh.node_bytes() if result.ok else b"",
        "hexes": mesh.hex_bytes() if result.ok else b"",
        "mid_edges": mesh.mid_edge_bytes() if result.ok else b"",
        "groups": [(name, g["nodes"]) for name, g in result.groups.items()] if result.ok else [],
        "scaled_jacobian": array("d", result.scaled_jacobian).tobytes() if result.ok else b"",
    }


class FemMeshBuilder:
    """Builds the Fem.FemMesh of a payload a slice at a time (step() with a time budget),
    so that a large mesh does not hold the GUI still while its elements are added."""

    def __init__(self, payload):
        import Fem
        from array import array

        self.femmesh = Fem.FemMesh()
        self.nodes = array("d", payload["nodes"])
        self.hexes = array("i", payload["hexes"])
        self.mid = array("i", payload.get("mid_edges", b""))
        self.groups = payload.get("groups", [])
        self.n_nodes, self.n_hexes = len(self.nodes) // 3, len(self.hexes) // 8
        self.node, self.hex = 0, 0

    def step(self, seconds=None):
        """Adds nodes, then hexahedra, for about `seconds` (None: all); True when done."""
        import time

        end = None if seconds is None else time.time() + seconds
        fm, nodes, hexes, mid = self.femmesh, self.nodes, self.hexes, self.mid
        while self.node < self.n_nodes:
            stop = min(self.n_nodes, self.node + 2000)
            for i in range(self.node, stop):
                fm.addNode(nodes[3 * i], nodes[3 * i + 1], nodes[3 * i + 2], i + 1)
            self.node = stop
            if end is not None and time.time() > end:
                return False
        while self.hex < self.n_hexes:
            stop = min(self.n_hexes, self.hex + 1000)
            for e in range(self.hex, stop):
                cell = list(hexes[8 * e:8 * e + 8])
                if mid:
                    cell += mid[12 * e:12 * e + 12]
                fm.addVolume(VoroHex.smesh_nodes(cell), e + 1)
            self.hex = stop
            if end is not None and time.time() > end:
                return False
        if self.groups:
            VoroHex.add_groups(fm, self.groups)
            self.groups = []
        return True

    @property
    def fraction(self):
        total = self.n_nodes + self.n_hexes
        return (self.node + self.hex) / total if total else 1.0


def femmesh_of(payload):
    builder = FemMeshBuilder(payload)
    builder.step()
    return builder.femmesh


def shape_from_brep(brep):
    """A Part.Shape from exportBrepToString()'s text (how shapes reach a child process)."""
    import Part

    shape = Part.Shape()
    shape.importBrepFromString(brep, False)
    return shape


def mesh_work(report, brep, options):
    """Meshes the shape `brep` with keyword `options`: what a VoroHexJobs.Job runs in its
    child process for the task panel; returns mesh_payload()."""
    return mesh_payload(VoroHex.mesh(shape_from_brep(brep), progress=report, **options))


def is_structured(scheme):
    """False for a scheme (or "map+grid") that has the tetrahedral fallback or the grid
    mesher in it: not a structured mesh."""
    return not any(s in ("tet-split", "grid") for s in (scheme or "").split("+"))


def trials_work(report, brep, options, sizes):
    """Meshes the shape at each size without the fallback and without smoothing (cheap),
    each stopped after 10 s: [(size, scheme, hexes)] for the sizes that gave a structured
    mesh. Run in a child process when a mesh was not structured."""
    shape = shape_from_brep(brep)
    trial = dict(options, fallback=False, smooth_iterations=0, smooth_passes=0,
                 time_limit=10.0,
                 decomposition_time_limit=min(10.0, options.get("decomposition_time_limit")
                                              or 10.0))
    found = []
    for k, size in enumerate(sizes):
        report("trying size {:.3g}".format(size), k / len(sizes))
        r = VoroHex.mesh(shape, **dict(trial, size=size))
        if r.ok and is_structured(r.stats.scheme):
            found.append((size, r.stats.scheme, r.stats.hexes))
    return found


def preview_work(report, brep, sharp_angle, options, schemes=""):
    """The Voronoi graph and the decomposition (merged, as the mesher cuts: method "auto",
    its sub-volumes judged by the mesh's `schemes`) of the shape, as their compute() values:
    the hex mesh panel's Preview, in one child process."""
    import VoroHexGraph
    import VoroHexParts

    shape = shape_from_brep(brep)
    return (VoroHexGraph.compute(shape, sharp_angle, options, report),
            VoroHexParts.compute(shape, sharp_angle, True, options, report, method="auto",
                                 schemes=schemes))


def automatic_size(shape):
    """The size VoroHex uses for TargetSize 0: the bounding-box diagonal / 20."""
    return shape.BoundBox.DiagonalLength / 20.0


def predicted_hexes(shape, size, sizes=None, grading=0.3):
    """(low, high): the hexahedra to expect at `size` (0 or None: automatic). low = volume /
    size^3, what a structured mesh (map, sweep) has; high = 4 x that, a bound for the
    fallback (the grid mesher's core plus its pillow layer, refined up to twice where walls
    are thin, stays below it on HexMe's curved models). Local sizes ({"Face7": 0.5}) add
    the hexahedra of the graded layer around each entity: the integral of 1 / h^3 - 1 /
    size^3 over the distance d from it (h = local + grading d, up to size), on the solid's
    side of a face, around an edge (a half cylinder) and a vertex (an eighth of a ball)."""
    size = size or automatic_size(shape)
    low = shape.Volume / size ** 3 if size > 0 else float("inf")
    g = grading
    for name, s in (sizes or {}).items():
        if not 0 < s < size:
            continue
        try:
            sub = shape.getElement(name)
        except Exception:  # an unknown entity: the meshing says so
            continue
        H, reach = size, (size - s) / g  # closed forms, as SizeField::graded_cells
        if name.startswith("Face"):
            low += sub.Area * ((1 / s ** 2 - 1 / H ** 2) / (2 * g) - reach / H ** 3)
        elif name.startswith("Edge"):
            low += sub.Length * math.pi * ((1 / (2 * s) - 1 / H + s / (2 * H ** 2)) / g ** 2
                                           - reach ** 2 / (2 * H ** 3))
        else:
            low += 0.5 * math.pi * ((math.log(H / s) - 1.5 + 2 * s / H - s ** 2 / (2 * H ** 2))
                                    / g ** 3 - reach ** 3 / (3 * H ** 3))
    return low, 4.0 * low


def refusal(obj, size=None):
    """Why meshing `obj` at `size` (default its TargetSize) must not start, or None: even a
    structured mesh would have more hexahedra than MaxHexes. Checked before any work."""
    if obj.Part is None:
        return None
    if size is None:
        size = obj.TargetSize.Value
    try:
        sizes = region_sizes(obj)
    except ValueError:  # a bad region: meshing reports it
        sizes = {}
    low, _ = predicted_hexes(obj.Part.Shape, size, sizes, getattr(obj, "SizeGrading", 0.3))
    if low <= obj.MaxHexes:
        return None
    return ("size {:g} mm would give about {} hexahedra (volume / size\u00b3), more than the "
            "limit of {:,} (MaxHexes); nothing was meshed. Increase the size{}.").format(
                size or automatic_size(obj.Part.Shape), format_count(low), obj.MaxHexes,
                " to at least {:.3g} mm".format((obj.Part.Shape.Volume / obj.MaxHexes) ** (1 / 3))
                if obj.Part.Shape.Volume > 0 else "")


def format_count(n):
    """12,300 or 3.0e+10: a hex count for a message."""
    return "{:,}".format(int(round(n))) if n < 1e9 else "{:.1e}".format(n)


def makeHexMesh(doc, part, name=None, size=None):
    """Adds a VoroHex mesh object for `part` to `doc`, named after it ("Box_HexMesh").
    Raises ValueError, leaving the document untouched, when `part` holds no single closed
    solid."""
    error = source_error(part, True)
    if error is not None:
        raise ValueError("VoroHex: " + error)
    obj = doc.addObject("Fem::FemMeshObjectPython", name or object_name(part, "HexMesh"))
    if name is None:
        obj.Label = "{}_HexMesh".format(part.Label)
    HexMesh(obj)
    obj.Part = part
    if size is not None:
        obj.TargetSize = size
    if FreeCAD.GuiUp:
        from VoroHexGui import view_provider

        view_provider.ViewProviderHexMesh(obj.ViewObject)
    return obj
