# The parametric decomposition document object: the sub-volumes VoroHex cuts a linked solid
# into (vorohex decompose), as one compound (its Shape) and as one child object per
# sub-volume (shown, hidden and moved apart one by one: Explode), whose faces the GUI
# colours by their role: the sub-volume's scheme, a sweep's source and target, and the
# decomposition faces between sub-volumes. Usable headless.
"""VoroHex decomposition document object."""

import FreeCAD
import Part

import VoroHex
import VoroHexObjects

TYPE = "VoroHex::Decomposition"

# Face roles in legend order with their colours (RGB 0..1): Okabe & Ito's colour-blind safe
# colours; VoroHexGui/colour_check.py measures every pair at least 12 CIEDE2000 units apart
# for normal vision and each dichromacy (a test checks it).
ROLES = (
    ("sweep", (0x56 / 255, 0xB4 / 255, 0xE9 / 255),
     "side face of a swept sub-volume (sweep, multisweep, revolve)"),
    ("map", (0x00 / 255, 0x9E / 255, 0x73 / 255), "face of a sub-volume meshed as a mapped block"),
    ("midpoint", (0xCC / 255, 0x79 / 255, 0xA7 / 255),
     "face of a sub-volume meshed by midpoint subdivision"),
    ("none", (0xD5 / 255, 0x5E / 255, 0x00 / 255), "face of a sub-volume no scheme accepts"),
    ("source/target", (0x00 / 255, 0x72 / 255, 0xB2 / 255), "source or target face of a sweep"),
    ("decomposition", (0xF0 / 255, 0xE4 / 255, 0x42 / 255), "a cut: face between two sub-volumes"),
)
COLOURS = {r[0]: r[1] for r in ROLES}
# Sweeps along the sub-volume's axis (many-to-one) or about it take the sweep's colour.
SWEPT = {"multisweep": "sweep", "revolve": "sweep"}

# The Method property's choices and the VoroHex.decompose method each stands for.
METHODS = (
    ("As the mesher", "auto"),
    ("Voronoi graph", "voronoi"),
    ("Exact cuts at concave edges", "plane-cuts"),
)
METHOD_OF = dict(METHODS)

RESULTS = (
    ("Status", "App::PropertyString", "ok, partial, or error when the last recompute failed"),
    ("MethodUsed", "App::PropertyString",
     "How the solid was cut: along its Voronoi graph, or along the faces at its concave edges"),
    ("Message", "App::PropertyString", "Summary of the last recompute, or why it failed"),
    ("SubVolumeCount", "App::PropertyInteger", "Sub-volumes (after merging)"),
    ("SubVolumesBeforeMerge", "App::PropertyInteger", "Sub-volumes of the first split"),
    ("DecompositionFaceCount", "App::PropertyInteger", "Faces between two sub-volumes"),
    ("Types", "App::PropertyStringList", "Vs or Ve per sub-volume"),
    ("Schemes", "App::PropertyStringList",
     "Meshing scheme per sub-volume (sweep, map, multisweep, revolve, midpoint, none)"),
    ("Reasons", "App::PropertyStringList", "Why that scheme, per sub-volume"),
    ("FaceRoles", "App::PropertyStringList",
     "Role of every face of the sub-volumes, one sub-volume after the other (each child "
     "object has its own FaceRoles, in its Shape.Faces order)"),
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
        if not hasattr(obj, "SubVolumeObjects"):
            obj.addProperty("App::PropertyLinkList", "SubVolumeObjects", "Decomposition",
                            "One object per sub-volume (its children in the tree)")
            obj.setEditorMode("SubVolumeObjects", 1)
        if not hasattr(obj, "Explode"):
            obj.addProperty("App::PropertyFloat", "Explode", "Decomposition",
                            "Moves the sub-volumes apart: 0 in place, 1 each by its distance "
                            "from the centre")
            obj.Explode = 0.0
        if not hasattr(obj, "Merge"):
            obj.addProperty("App::PropertyBool", "Merge", "Decomposition",
                            "Unite neighbouring sub-volumes whose union is a sweep")
            obj.Merge = True
        if not hasattr(obj, "Method"):
            obj.addProperty("App::PropertyEnumeration", "Method", "Decomposition",
                            "As the mesher: the exact cuts along the faces at its concave edges "
                            "where they give sub-volumes that all have a scheme, else the "
                            "Voronoi graph's decomposition (what Hex mesh does with a solid no "
                            "single scheme meshes); or only one of the two")
            obj.Method = [m[0] for m in METHODS]
            # A document saved before the property existed showed the Voronoi graph's.
            obj.Method = "Voronoi graph" if getattr(self, "restoring", False) else METHODS[0][0]
        if not hasattr(obj, "AllowedSchemes"):
            obj.addProperty("App::PropertyString", "AllowedSchemes", "Decomposition",
                            "The schemes that may mesh a sub-volume, comma-separated, as the "
                            "hex mesh's Schemes: a mapped block, a sweep and midpoint "
                            "subdivision always; multisweep (prismatic) and revolve only when "
                            "named")
            obj.AllowedSchemes = ALL_SCHEMES
        if not hasattr(obj, "TimeLimit"):
            obj.addProperty("App::PropertyFloat", "TimeLimit", "Decomposition",
                            "Seconds the decomposition may take (> 0): stopped before its "
                            "split ends it fails, later its merging stops")
            obj.TimeLimit = VoroHex.DECOMPOSITION_TIME_LIMIT
        for name, prop_type, doc in RESULTS:
            if not hasattr(obj, name):
                obj.addProperty(prop_type, name, "Result", doc)
                obj.setEditorMode(name, 1)

    def onDocumentRestored(self, obj):
        obj.SharpAngle = (obj.SharpAngle, 1.0, 180.0, 5.0)
        self.restoring = True
        try:
            self.add_properties(obj)
        finally:
            self.restoring = False

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def onChanged(self, obj, prop):
        if prop == "Explode":
            explode(obj)

    def execute(self, obj):
        """Re-decomposes; on failure keeps the previous shape and raises."""
        error = VoroHexObjects.source_error(obj.Part)
        if error is None:
            key = cache_key(obj)
            data = getattr(self, "data", None)
            if data is None or getattr(self, "key", None) != key:
                data = VoroHexObjects.compute_or_raise(obj, "decomposition", lambda: compute(
                    obj.Part.Shape, obj.SharpAngle, obj.Merge,
                    VoroHexObjects.graph_options_of(obj), getattr(self, "progress", None),
                    obj.TimeLimit, METHOD_OF[obj.Method], obj.AllowedSchemes))
                if data is None:  # cancelled (Status and Message say so)
                    return
            error = self.apply(obj, data)
        if error is not None:
            obj.Status, obj.Message = "error", error
            raise RuntimeError("VoroHex: " + error)

    def apply(self, obj, data):
        """Stores what compute() returned: the compound, one child object per sub-volume
        with its face roles; the error, or None."""
        d = data["decomposition"]
        merged = data.get("merged_faces", 0)
        note = VoroHexObjects.merged_faces_note(merged) if merged else None
        fallback = [x["message"] for x in d.diagnostics if x.get("code") == "mesher_fallback"]
        if not d.ok or not data["solids"]:
            why = "; ".join(x.get("message", "") for x in d.diagnostics
                            if x.get("severity") == "error") or "the decomposition failed"
            return " ".join([why.rstrip(".") + "."] + ([note] if note else []) + fallback)
        self.data, self.key = data, cache_key(obj)
        solids = [Part.Shape() for _ in data["solids"]]
        for shape, text in zip(solids, data["solids"]):
            shape.importBrepFromString(text, False)
        obj.Shape = Part.makeCompound(solids)
        obj.FaceRoles = [r for roles in data["roles"] for r in roles]
        obj.SubVolumeCount = len(d.sub_volumes)
        obj.SubVolumesBeforeMerge = d.counts.get("sub_volumes_before_merge", 0)
        # The plane cuts count no decomposition faces: the sub-volumes' faces against
        # another, the same face on both sides counted once.
        obj.DecompositionFaceCount = d.counts.get(
            "decomposition_faces", data.get("decomposition_faces", 0))
        obj.Types = [sv.get("type", "") for sv in d.sub_volumes]
        obj.Schemes = [sv.get("scheme", "none") for sv in d.sub_volumes]
        obj.Reasons = [sv.get("reason", "") for sv in d.sub_volumes]
        obj.Status = d.status
        obj.MethodUsed = method_text(d)
        schemes = {}
        for s in obj.Schemes:
            schemes[s] = schemes.get(s, 0) + 1
        obj.Message = "{}: {} ({}), {} before merging, {}".format(
            obj.MethodUsed,
            plural(obj.SubVolumeCount, "sub-volume"), ", ".join("{} {}".format(n, s) for s, n in
                                                               sorted(schemes.items())),
            obj.SubVolumesBeforeMerge, plural(obj.DecompositionFaceCount, "decomposition face"))
        if d.status == "partial":
            obj.Message += ". Partial: " + (d.partial_reason or "see the report's warnings")
        if fallback:
            obj.Message += ". " + fallback[0].rstrip(".")
        if note:
            obj.Message += ". " + note
        set_children(obj, solids, data["roles"])
        return None


def method_text(d):
    """How a VoroHex.Decomposition cut its solid, for the Message and MethodUsed."""
    if d.method == "whole":
        return "Not cut (the mesher meshes it whole)"
    if d.method != "plane-cuts":
        if len(d.sub_volumes) == 1 and d.counts.get("sub_volumes_before_merge", 1) == 1:
            return "Not cut (its Voronoi graph gives one sub-volume)"
        return "Cut along its Voronoi graph"
    # The cut's own words (decompose::cut_kind_text, used_surfaces_text).
    return "Cut along {} ({})".format(d.data.get("cut_kind", "the faces at its concave edges"),
                                      d.data.get("cut_along", ""))


def plural(n, noun):
    """"1 sub-volume", "2 sub-volumes"."""
    return "{} {}{}".format(n, noun, "" if n == 1 else "s")


def cache_key(obj):
    return (obj.Part.Name if obj.Part else None, obj.SharpAngle, obj.Merge, obj.TimeLimit,
            obj.Method, obj.AllowedSchemes,
            tuple(sorted(VoroHexObjects.graph_options_of(obj).items())))


# The decomposition's default AllowedSchemes: the mesher's default schemes.
ALL_SCHEMES = ",".join(VoroHex._core.MeshOptions().schemes)


def judging_schemes(schemes):
    """(multisweep, revolve) from a Schemes text as the hex mesh takes it (parsed and checked
    as VoroHex.mesh's `schemes`: an unknown name raises ValueError naming it; empty: every
    scheme): whether prismatic and revolved sub-volumes count as meshable."""
    names = list(VoroHex._make_options({"schemes": schemes}).schemes) or ALL_SCHEMES.split(",")
    return "multisweep" in names, "revolve" in names


def compute(shape, sharp_angle, merge, options, progress=None,
            time_limit=VoroHex.DECOMPOSITION_TIME_LIMIT, method="voronoi", schemes=ALL_SCHEMES):
    """The decomposition of `shape` as plain values (no document access: it runs in a child
    process for the GUI): the VoroHex.Decomposition without its shapes, each sub-volume as
    a BREP string, and the role of each of its faces. apply() stores them. For the Voronoi
    graph's alone, faces split on one surface are merged first
    (VoroHexObjects.merged_split_faces); as the mesher, they are taken as the mesher takes
    them. schemes: the Schemes text that judges the sub-volumes (judging_schemes)."""
    # The mesher takes split faces as they are: as the mesher (and for its exact cuts) so
    # does the decomposition.
    multisweep, revolve = judging_schemes(schemes)
    merged = 0
    if method == "voronoi":
        shape, merged = VoroHexObjects.merged_split_faces(shape)
    if method == "plane-cuts":  # it takes none of the Voronoi graph's options
        d = VoroHex.decompose(shape, merge=merge, progress=progress, time_limit=time_limit,
                              method=method, multisweep=multisweep, revolve=revolve)
    else:
        d = VoroHex.decompose(shape, sharp_angle=sharp_angle, merge=merge, progress=progress,
                              time_limit=time_limit, method=method, multisweep=multisweep,
                              revolve=revolve, **options)
    roles = face_roles(d) if d.ok and d.shapes else []
    between = distinct_faces(d.shapes, roles) if roles else 0
    solids = [s.exportBrepToString() for s in d.shapes]
    d.shapes = []
    return {"decomposition": d, "solids": solids, "roles": roles, "merged_faces": merged,
            "decomposition_faces": between}


def compute_work(report, brep, sharp_angle, merge, options,
                 time_limit=VoroHex.DECOMPOSITION_TIME_LIMIT, method="voronoi",
                 schemes=ALL_SCHEMES):
    """compute() of the shape `brep` (exportBrepToString()), in a VoroHexJobs child."""
    return compute(VoroHexObjects.shape_from_brep(brep), sharp_angle, merge, options, report,
                   time_limit, method, schemes)


def set_children(obj, solids, roles):
    """One Part::Feature per sub-volume under the decomposition object (made, reused or
    removed so that there are as many as sub-volumes)."""
    doc = obj.Document
    children = [c for c in obj.SubVolumeObjects if c is not None]
    while len(children) > len(solids):
        doc.removeObject(children.pop().Name)
    for k, solid in enumerate(solids):
        if k < len(children):
            child = children[k]
        else:
            child = doc.addObject("Part::Feature", "{}_SubVolume".format(obj.Name))
            for prop, kind, doc_text in (
                    ("SubVolume", "App::PropertyInteger", "Index in the decomposition (0, 1, ...)"),
                    ("Scheme", "App::PropertyString", "Meshing scheme of this sub-volume"),
                    ("SubVolumeType", "App::PropertyString", "Vs or Ve"),
                    ("FaceRoles", "App::PropertyStringList",
                     "Role of each face, in Shape.Faces order")):
                child.addProperty(kind, prop, "Sub-volume", doc_text)
                child.setEditorMode(prop, 1)
            children.append(child)
        child.Shape = solid
        child.SubVolume = k
        child.Scheme = obj.Schemes[k] if k < len(obj.Schemes) else "none"
        child.SubVolumeType = obj.Types[k] if k < len(obj.Types) else ""
        child.FaceRoles = roles[k] if k < len(roles) else []
        # Named after their decomposition: a second decomposition of the same part has its
        # own (FreeCAD would otherwise number the repeated labels "...001").
        child.Label = "{} sub-volume {} ({})".format(
            obj.Label, k,
            " ".join(t for t in (child.SubVolumeType, child.Scheme) if t))
        child.purgeTouched()
    obj.SubVolumeObjects = children
    explode(obj)


def explode(obj):
    """Moves each sub-volume from the whole's centre by Explode x its own offset."""
    children = [c for c in getattr(obj, "SubVolumeObjects", []) if c is not None]
    if not children:
        return
    centres = [c.Shape.BoundBox.Center for c in children]
    whole = FreeCAD.Vector()
    for c in centres:
        whole += c
    whole = whole * (1.0 / len(centres))
    for child, centre in zip(children, centres):
        child.Placement = FreeCAD.Placement((centre - whole) * obj.Explode, FreeCAD.Rotation())
        child.purgeTouched()  # moved only: nothing to recompute


def face_roles(d):
    """The role of every face of every sub-volume (a list per sub-volume, in its Faces
    order): a decomposition face where most of it lies against another sub-volume (on the
    same face, or on part of a larger one, as the plane cuts' merged pieces meet), a sweep's
    source or target, else its sub-volume's scheme."""
    tol = coincidence(d.shapes)
    roles = []
    for i, solid in enumerate(d.shapes):
        sv = d.sub_volumes[i] if i < len(d.sub_volumes) else {}
        scheme = sv.get("scheme", "none")
        ends = [sv.get("source"), sv.get("target")] if scheme == "sweep" else []
        mine = []
        for k, face in enumerate(solid.Faces):
            if against_another(face, i, d.shapes, tol):
                mine.append("decomposition")
            elif "Face{}".format(k + 1) in ends:
                mine.append("source/target")
            else:
                mine.append(SWEPT.get(scheme, scheme) if SWEPT.get(scheme, scheme) in COLOURS
                            else "none")
        roles.append(mine)
    return roles


def distinct_faces(shapes, roles):
    """How many faces lie between sub-volumes: the decomposition faces, one that two
    sub-volumes both have (same area and centre) counted once."""
    tol = coincidence(shapes)
    seen = []
    for solid, mine in zip(shapes, roles):
        for face, role in zip(solid.Faces, mine):
            if role != "decomposition":
                continue
            key = (face.Area, face.CenterOfMass)
            if not any(abs(a - key[0]) <= tol * max(1.0, a) and (c - key[1]).Length <= tol
                       for a, c in seen):
                seen.append(key)
    return len(seen)


def coincidence(shapes):
    """The distance below which the sub-volumes' geometry coincides: 1e-7 of their extent."""
    diagonal = max((s.BoundBox.DiagonalLength for s in shapes), default=1.0)
    return 1e-7 * max(diagonal, 1e-300)


def inner_points(face, at_most=12):
    """Up to `at_most` points inside `face`, each with the area it stands for: the centres
    of its largest triangles, projected onto it (its centre of mass can lie in a hole, or
    off a curved face)."""
    points, triangles = face.tessellate(0.01 * max(face.BoundBox.DiagonalLength, 1e-300))

    def area(t):
        a, b, c = (points[j] for j in t)
        return 0.5 * (b - a).cross(c - a).Length

    out = []
    for t in sorted(triangles, key=area, reverse=True)[:at_most]:
        a, b, c = (points[j] for j in t)
        u, v = face.Surface.parameter((a + b + c) * (1.0 / 3.0))
        out.append((face.Surface.value(u, v), area(t)))
    return out or [(face.CenterOfMass, 1.0)]


def against_another(face, i, shapes, tol):
    """Whether most of `face` (of shapes[i]; by the area its sample points stand for) lies
    on faces of other shapes: a face between two sub-volumes, all of it or most, not an
    outer face that touches another sub-volume along a strip."""
    on = total = 0.0
    for p, weight in inner_points(face):
        total += weight
        vertex = Part.Vertex(p)
        if any(j != i and near_box(other, p, 10 * tol) and
               any(near_box(f, p, 10 * tol) and f.distToShape(vertex)[0] <= 10 * tol
                   for f in other.Faces)
               for j, other in enumerate(shapes)):
            on += weight
    return on >= 0.5 * total


def near_box(shape, p, tol):
    """Whether p lies in `shape`'s bounding box grown by tol (before a distance query)."""
    box = FreeCAD.BoundBox(shape.BoundBox)
    box.enlarge(tol)
    return box.isInside(p)


def makeDecomposition(doc, part, name=None, merge=True, progress=None, data=None,
                      time_limit=None, method="auto", schemes=None, **options):
    """Adds a decomposition object for `part` to `doc` and computes it. Raises ValueError
    (and leaves the document as it was) when `part` holds no single solid. progress as for
    VoroHexGraph.makeVoronoiGraph; options: sharp_angle, eps, delta, max_depth, set as the
    object's properties before it computes; time_limit: seconds (TimeLimit, default 30);
    method: "auto" (as the mesher, the default), "voronoi" or "plane-cuts", as for
    VoroHex.decompose (the Method property); schemes: the Schemes text judging the
    sub-volumes (AllowedSchemes; default every scheme; a hex mesh's Preview passes the
    mesh's Schemes)."""
    error = VoroHexObjects.source_error(part)
    if error is not None:
        raise ValueError("VoroHex: " + error)
    labels = {m: label for label, m in METHODS}
    if method not in labels:
        raise ValueError("VoroHex: option 'method' must be 'auto', 'voronoi' or 'plane-cuts', "
                         "got {!r}".format(method))
    if time_limit is not None:
        time_limit = VoroHex._seconds("time_limit", time_limit)
    if schemes is not None:
        judging_schemes(schemes)  # a bad text is refused before the document changes
    obj = doc.addObject("Part::FeaturePython",
                        name or VoroHexObjects.object_name(part, "Decomposition"))
    if name is None:
        obj.Label = "{}_Decomposition".format(part.Label)
    Decomposition(obj)
    obj.Part = part
    try:
        VoroHexObjects.set_options(obj, options)
    except (TypeError, ValueError):
        doc.removeObject(obj.Name)  # the document as it was
        raise
    obj.Merge = merge
    obj.Method = labels[method]
    if time_limit is not None:
        obj.TimeLimit = time_limit
    if schemes is not None:
        obj.AllowedSchemes = schemes
    if FreeCAD.GuiUp:
        from VoroHexGui import parts_view

        parts_view.ViewProviderDecomposition(obj.ViewObject)
    if data is not None:
        obj.Proxy.data, obj.Proxy.key = data, cache_key(obj)
    VoroHexObjects.compute_new(obj, progress)
    return obj


def remove(obj):
    """Removes a decomposition object with its sub-volume children."""
    doc = obj.Document
    names = [c.Name for c in getattr(obj, "SubVolumeObjects", []) if c is not None]
    doc.removeObject(obj.Name)
    for name in names:
        if doc.getObject(name) is not None:
            doc.removeObject(name)
