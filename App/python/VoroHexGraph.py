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
EDGE_TYPES = (
    ("[0]", (0.10, 0.35, 0.85), "between two faces that share nothing (f_s: a sweep)"),
    ("[1]", (0.10, 0.65, 0.20), "two faces sharing an edge (projected onto that edge)"),
    ("[1s]", (0.00, 0.40, 0.10), "the same at a sharp angle (projected onto both faces)"),
    ("[2]", (0.95, 0.55, 0.05), "two pairs of governors share edges"),
    ("[3]", (0.85, 0.10, 0.10), "three pairs share edges"),
    ("[1e]", (0.80, 0.10, 0.70), "two faces and an edge bounding one of them"),
    ("[0e]", (0.50, 0.20, 0.70), "two faces and an edge or vertex bounding neither"),
    ("[C]", (0.45, 0.45, 0.45), "the governors share a model vertex (no cut)"),
    ("degenerate", (0.00, 0.00, 0.00), "more than three governors"),
    ("none", (0.75, 0.75, 0.75), "of no interest (e.g. a face and its own edge)"),
)
TYPE_NAMES = [t[0] for t in EDGE_TYPES]
COLOURS = {t[0]: t[1] for t in EDGE_TYPES}
FS_COLOUR = (0.55, 0.75, 1.0)  # f_s faces (translucent) and their outlines
COLOURS["f_s"] = FS_COLOUR

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
     "Type of every edge of the Shape (one per Voronoi edge drawn; f_s for the outline "
     "edges of the f_s faces), in Shape.Edges order"),
    ("FsFacesDrawn", "App::PropertyInteger", "f_s faces drawn (their outline closes)"),
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
        """Recomputes the graph; on failure keeps the previous shape and raises."""
        error = VoroHexObjects.source_error(obj.Part)
        graph = None
        if error is None:
            graph = VoroHexObjects.compute_or_raise(obj, "Voronoi graph", lambda: (
                VoroHex.voronoi_graph(obj.Part, sharp_angle=obj.SharpAngle,
                                      progress=getattr(self, "progress", None),
                                      **VoroHexObjects.graph_options_of(obj))))
            if graph is None:  # cancelled (Status and Message say so)
                return
            if not graph.ok:
                error = "; ".join(d.get("message", "") for d in graph.diagnostics) or \
                    "the Voronoi graph could not be computed"
        if error is not None:
            obj.Status, obj.Message = "error", error
            raise RuntimeError("VoroHex: " + error)
        unknown = [t for t in obj.ShownTypes if t not in TYPE_NAMES]
        if unknown:
            obj.Status = "error"
            obj.Message = "unknown edge type(s) {} in ShownTypes; known: {}".format(
                ", ".join(unknown), ", ".join(TYPE_NAMES))
            raise RuntimeError("VoroHex: " + obj.Message)
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
        fs_drawn = 0
        if obj.ShowFsFaces:
            by_id = {e["id"]: e for e in graph.elements}
            for f in graph.fs_faces():
                face = fs_face([by_id[i].get("polyline", []) for i in f.get("incident", [])
                                if by_id.get(i, {}).get("kind") == "edge"])
                if face is not None:
                    shapes.append(face)
                    segment_types += ["f_s"] * len(face.Edges)
                    fs_drawn += 1
        if obj.ShowVertices:
            shapes += [Part.Vertex(FreeCAD.Vector(*v["point"])) for v in graph.of_kind("vertex")]
        obj.Shape = Part.makeCompound(shapes)
        obj.FsFacesDrawn = fs_drawn
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


def fs_face(polylines, tol=1e-9):
    """The face bounded by a Voronoi face's edges (their polylines chained into one loop):
    planar when its points are, else a filling surface; None when they do not close."""
    chains = [[FreeCAD.Vector(*p) for p in pl] for pl in polylines if len(pl) >= 2]
    if len(chains) < 2:
        return None
    scale = max((p - q).Length for c in chains for p in c for q in (chains[0][0],)) or 1.0
    close = 1e-6 * scale
    loop = list(chains.pop(0))
    while chains:
        end = loop[-1]
        for k, c in enumerate(chains):
            if (c[0] - end).Length <= close:
                loop += c[1:]
                break
            if (c[-1] - end).Length <= close:
                loop += list(reversed(c))[1:]
                break
        else:
            return None  # the edges do not chain: no face drawn
        chains.pop(k)
    if (loop[0] - loop[-1]).Length > close or len(loop) < 4:
        return None
    loop[-1] = loop[0]
    try:
        wire = Part.makePolygon(loop)
        plane = wire.findPlane(close)
        if plane is not None:
            return Part.Face(wire)
        return Part.makeFilledFace(wire.Edges)
    except Exception:  # OCCT could not make a face of it: the outline is drawn as edges
        return None


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


def makeVoronoiGraph(doc, part, name="VoronoiGraph", progress=None, **options):
    """Adds a Voronoi graph object for `part` to `doc` and computes it. Raises ValueError
    (and leaves the document as it was) when `part` holds no single solid. progress(stage,
    fraction) is called while it computes and may return False to cancel (the object is
    then taken out again and VoroHex.Cancelled raised). options: sharp_angle, eps, delta,
    max_depth (as for VoroHex.voronoi_graph), set as the object's properties before it
    computes."""
    error = VoroHexObjects.source_error(part)
    if error is not None:
        raise ValueError("VoroHex: " + error)
    obj = doc.addObject("Part::FeaturePython", name)
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
    VoroHexObjects.compute_new(obj, progress)
    return obj
