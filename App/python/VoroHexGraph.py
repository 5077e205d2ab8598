# The parametric Voronoi graph document object: the embedded Voronoi graph of a linked
# solid as lines (edges, grouped and coloured by their decomposition type) and points
# (vertices). Usable headless; the GUI adds colours and a legend (VoroHexGui.graph_view).
"""VoroHex Voronoi graph document object."""

import FreeCAD
import Part

import VoroHex
import VoroHexObjects

TYPE = "VoroHex::VoronoiGraph"

# Every edge type the decomposition knows, in legend order, with its colour (RGB 0..1)
# and what it means (docs/decomposition.md has the rules).
# Colour-blind safe: Paul Tol's "muted" colours with Okabe & Ito's sky blue and pink, black
# and two greys; VoroHexGui/colour_check.py measures every pair at least 13 CIEDE2000 units
# apart for normal vision and for protanopia, deuteranopia and tritanopia (a test checks it).
EDGE_TYPES = (
    ("[0]", (0x33 / 255, 0x22 / 255, 0x88 / 255),
     "between two faces that share nothing (f_s: a sweep)"),
    ("[1]", (0x11 / 255, 0x77 / 255, 0x33 / 255),
     "two faces sharing an edge (projected onto that edge)"),
    ("[1s]", (0xDD / 255, 0xCC / 255, 0x77 / 255),
     "the same at a sharp angle (projected onto both faces)"),
    ("[2]", (0xCC / 255, 0x79 / 255, 0xA7 / 255), "two pairs of governors share edges"),
    ("[3]", (0xAA / 255, 0x44 / 255, 0x99 / 255), "three pairs share edges"),
    ("[1e]", (0x56 / 255, 0xB4 / 255, 0xE9 / 255), "two faces and an edge bounding one of them"),
    ("[0e]", (0x99 / 255, 0x99 / 255, 0x33 / 255),
     "two faces and an edge or vertex bounding neither"),
    ("[C]", (0x77 / 255, 0x77 / 255, 0x77 / 255), "the governors share a model vertex (no cut)"),
    ("degenerate", (0.0, 0.0, 0.0), "more than three governors"),
    ("none", (0xCC / 255, 0xCC / 255, 0xCC / 255),
     "of no interest (e.g. a face and its own edge)"),
)
TYPE_NAMES = [t[0] for t in EDGE_TYPES]
COLOURS = {t[0]: t[1] for t in EDGE_TYPES}
FS_COLOUR = (0.53, 0.80, 0.93)  # f_s faces (translucent)

RESULTS = (
    ("Status", "App::PropertyString", "ok, or error when the last recompute failed"),
    ("Message", "App::PropertyString", "Summary of the last recompute, or why it failed"),
    ("VertexCount", "App::PropertyInteger", "Voronoi vertices"),
    ("EdgeCount", "App::PropertyInteger", "Voronoi edges"),
    ("FaceCount", "App::PropertyInteger", "Voronoi faces"),
    ("FsFaceCount", "App::PropertyInteger", "Voronoi faces between two unconnected faces"),
    ("EdgeTypeCounts", "App::PropertyMap", "Voronoi edges per type (the whole graph)"),
    ("ShownEdgeCounts", "App::PropertyMap", "Voronoi edges drawn per type"),
    ("SegmentTypes", "App::PropertyStringList",
     "Type of every edge of the Shape (one per Voronoi edge drawn), in Shape.Edges order"),
    ("FsFacesDrawn", "App::PropertyInteger", "f_s faces drawn"),
    ("FsFacesNotDrawn", "App::PropertyStringList",
     "f_s faces that could not be drawn: the face, its governors and why"),
    ("FsFacePoints", "App::PropertyVectorList", "Corners of the triangles that draw the f_s "
     "faces (the view draws them translucent; they are not part of the Shape)"),
    ("FsFaceTriangles", "App::PropertyIntegerList",
     "Three indices into FsFacePoints per triangle of the f_s faces"),
)


class VoronoiGraph:
    """Proxy of the Voronoi graph object (a Part::FeaturePython)."""

    Type = TYPE

    def __init__(self, obj):
        obj.Proxy = self
        self.add_properties(obj)

    def add_properties(self, obj):
        if not hasattr(obj, "Part"):
            obj.addProperty("App::PropertyLink", "Part", "Voronoi graph",
                            "Solid whose embedded Voronoi graph is shown")
        if not hasattr(obj, "SharpAngle"):
            obj.addProperty("App::PropertyFloatConstraint", "SharpAngle", "Voronoi graph",
                            "Dihedral angle (degrees) below which a [1] edge is [1s]")
            obj.SharpAngle = (60.0, 1.0, 180.0, 5.0)
        VoroHexObjects.add_option_properties(obj, VoroHexObjects.GRAPH_OPTIONS)
        if not hasattr(obj, "ShownTypes"):
            obj.addProperty("App::PropertyStringList", "ShownTypes", "Voronoi graph",
                            "Edge types drawn (" + ", ".join(TYPE_NAMES) + ")")
            obj.ShownTypes = TYPE_NAMES
        if not hasattr(obj, "ShowFsFaces"):
            obj.addProperty("App::PropertyBool", "ShowFsFaces", "Voronoi graph",
                            "Draw the f_s faces (between two unconnected model faces: where "
                            "the solid is swept) as translucent faces")
            obj.ShowFsFaces = True
        if not hasattr(obj, "ShowVertices"):
            obj.addProperty("App::PropertyBool", "ShowVertices", "Voronoi graph",
                            "Draw the Voronoi vertices as points")
            obj.ShowVertices = True
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
        """Recomputes the graph (only when its options changed: showing or hiding a type
        redraws the graph kept from last time); on failure keeps the previous shape and
        raises."""
        error = VoroHexObjects.source_error(obj.Part)
        if error is None:
            key = cache_key(obj)
            data = getattr(self, "data", None)
            if data is None or getattr(self, "key", None) != key:
                data = VoroHexObjects.compute_or_raise(obj, "Voronoi graph", lambda: compute(
                    obj.Part.Shape, obj.SharpAngle, VoroHexObjects.graph_options_of(obj),
                    getattr(self, "progress", None)))
                if data is None:  # cancelled (Status and Message say so)
                    return
            error = self.apply(obj, data)
        if error is not None:
            obj.Status, obj.Message = "error", error
            raise RuntimeError("VoroHex: " + error)

    def apply(self, obj, data):
        """Draws what compute() returned (the edges of the shown types as lines, vertices
        as points; the f_s faces' triangles as properties the view draws); the error, or
        None."""
        graph = data["graph"]
        merged = data.get("merged_faces", 0)
        note = VoroHexObjects.merged_faces_note(merged) if merged else None
        if not graph.ok:
            return ("; ".join(d.get("message", "") for d in graph.diagnostics) or
                    "the Voronoi graph could not be computed") + (" " + note if note else "")
        unknown = [t for t in obj.ShownTypes if t not in TYPE_NAMES]
        if unknown:
            return "unknown edge type(s) {} in ShownTypes; known: {}".format(
                ", ".join(unknown), ", ".join(TYPE_NAMES))
        self.data, self.key = data, cache_key(obj)
        shapes, segment_types, shown = [], [], {}
        for t in TYPE_NAMES:  # grouped by type, in legend order
            if t not in obj.ShownTypes:
                continue
            for e in graph.of_kind("edge"):
                if e.get("type", "none") != t:
                    continue
                wire = polyline(e.get("polyline", []))
                if wire is None:
                    continue
                shapes.append(wire)
                segment_types += [t] * len(wire.Edges)
                shown[t] = shown.get(t, 0) + 1
        points, triangles, missing = [], [], []
        for face, (pts, tris, why) in zip(graph.fs_faces(), data["fs"]):
            if pts is None:
                missing.append("Voronoi face {} ({}): {}".format(
                    face["id"], ", ".join(face["governors"]), why))
                continue
            if obj.ShowFsFaces:
                base = len(points)
                points += [FreeCAD.Vector(*p) for p in pts]
                triangles += [base + i for t in tris for i in t]
        if obj.ShowVertices:
            shapes += [Part.Vertex(FreeCAD.Vector(*v["point"])) for v in graph.of_kind("vertex")]
        obj.Shape = Part.makeCompound(shapes)
        obj.FsFacesDrawn = len(graph.fs_faces()) - len(missing) if obj.ShowFsFaces else 0
        obj.FsFacesNotDrawn = missing
        obj.FsFacePoints = points
        obj.FsFaceTriangles = triangles
        obj.SegmentTypes = segment_types
        obj.EdgeTypeCounts = {t: str(n) for t, n in graph.type_counts().items()}
        obj.ShownEdgeCounts = {t: str(n) for t, n in shown.items()}
        c = graph.counts
        obj.VertexCount, obj.EdgeCount = c.get("vertices", 0), c.get("edges", 0)
        obj.FaceCount, obj.FsFaceCount = c.get("faces", 0), c.get("f_s", 0)
        obj.Status = "ok"
        obj.Message = "{} vertices, {} edges ({}), {} faces ({} f_s)".format(
            obj.VertexCount, obj.EdgeCount,
            ", ".join("{} {}".format(n, t) for t, n in sorted(graph.type_counts().items())),
            obj.FaceCount, obj.FsFaceCount)
        if note:
            obj.Message += ". " + note
        return None


def cache_key(obj):
    """What the graph itself depends on (not what is shown of it)."""
    return (obj.Part.Name if obj.Part else None, obj.SharpAngle,
            tuple(sorted(VoroHexObjects.graph_options_of(obj).items())))


def compute(shape, sharp_angle, options, progress=None):
    """The graph of `shape` and the triangles of its f_s faces, as plain values (no
    document access: it runs in a child process for the GUI); apply() draws them. Faces
    split on one surface are merged first (VoroHexObjects.merged_split_faces)."""
    shape, merged = VoroHexObjects.merged_split_faces(shape)
    graph = VoroHex.voronoi_graph(shape, sharp_angle=sharp_angle, progress=progress, **options)
    fs = []
    if graph.ok:
        import VoroHexFaces

        scale = shape.BoundBox.DiagonalLength
        by_id = {e["id"]: e for e in graph.elements}
        for f in graph.fs_faces():
            fs.append(VoroHexFaces.triangulate_face(
                [by_id[i].get("polyline", []) for i in f.get("incident", [])
                 if by_id.get(i, {}).get("kind") == "edge"], scale, f.get("point")))
    return {"graph": graph, "fs": fs, "merged_faces": merged}


def compute_work(report, brep, sharp_angle, options):
    """compute() of the shape `brep` (exportBrepToString()), in a VoroHexJobs child."""
    return compute(VoroHexObjects.shape_from_brep(brep), sharp_angle, options, report)


def polyline(points):
    """One edge through the points (a degree-1 B-spline, so the view shows no vertex at
    every sample), consecutive duplicates dropped; None if degenerate."""
    pts = []
    for p in points:
        v = FreeCAD.Vector(*p)
        if not pts or (v - pts[-1]).Length > 1e-12:
            pts.append(v)
    if len(pts) < 2:
        return None
    if len(pts) == 2:
        return Part.LineSegment(pts[0], pts[1]).toShape()
    curve = Part.BSplineCurve()
    curve.buildFromPoles(pts, False, 1)
    return curve.toShape()


def makeVoronoiGraph(doc, part, name=None, progress=None, data=None, **options):
    """Adds a Voronoi graph object for `part` to `doc` and computes it. Raises ValueError
    (and leaves the document as it was) when `part` holds no single solid. progress(stage,
    fraction) is called while it computes and may return False to cancel (the object is
    then taken out again and VoroHex.Cancelled raised). options: sharp_angle, eps, delta,
    max_depth (as for VoroHex.voronoi_graph), set as the object's properties before it
    computes. data: what compute() returned for these options (computed elsewhere, in a
    child process): drawn without computing again. The object is named after the part."""
    error = VoroHexObjects.source_error(part)
    if error is not None:
        raise ValueError("VoroHex: " + error)
    obj = doc.addObject("Part::FeaturePython",
                        name or VoroHexObjects.object_name(part, "VoronoiGraph"))
    if name is None:
        obj.Label = "{}_VoronoiGraph".format(part.Label)
    VoronoiGraph(obj)
    obj.Part = part
    try:
        VoroHexObjects.set_options(obj, options)
    except (TypeError, ValueError):
        doc.removeObject(obj.Name)  # the document as it was
        raise
    if FreeCAD.GuiUp:
        from VoroHexGui import graph_view

        graph_view.ViewProviderVoronoiGraph(obj.ViewObject)
    if data is not None:
        obj.Proxy.data, obj.Proxy.key = data, cache_key(obj)
    VoroHexObjects.compute_new(obj, progress)
    return obj
