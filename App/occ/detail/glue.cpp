#include "occ/detail/glue.h"

#include <BOPAlgo_GlueEnum.hxx>
#include <BRepAlgoAPI_BuilderAlgo.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepGProp.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "occ/detail/names.h"
#include "occ/solid_impl.h"

namespace vorohex::occ::detail {

using core::make_error;
using core::make_info;

namespace {

// The volume by adaptive integration to a relative error of about 1e-10, and in `error`
// the absolute error OCCT estimates it reached. The plain Gauss integration is off
// by up to about 1e-8 on curved faces: two ways of cutting a cylinder into pieces then
// differ by more than the 1e-9 a volume comparison allows (HexMe i20's plane cuts).
double accurate_volume(const TopoDS_Shape& s, double& error) {
  GProp_GProps props;
  const double relative = BRepGProp::VolumeProperties(s, props, 1e-10);
  error = std::abs(relative * props.Mass());
  return props.Mass();
}

// Where glued solids touch without a common face: an edge (vertex) whose solids are not
// all connected through faces through it that two of them share. Meshed one by one, such
// solids would give a mesh that is not a manifold there (hexes meeting along an edge or at
// a node only). Three solids around an edge, each sharing a face with the next (the
// corner of a decomposed L), are connected and fine. Named as in the whole shape.
std::vector<std::string> touching_without_face(const std::vector<TopoDS_Solid>& parts,
                                               const TopoDS_Shape& whole) {
  const int n = static_cast<int>(parts.size());
  std::vector<TopTools_IndexedMapOfShape> faces(n);
  for (int i = 0; i < n; ++i) TopExp::MapShapes(parts[i], TopAbs_FACE, faces[i]);
  std::vector<std::string> names;
  auto check = [&](TopAbs_ShapeEnum kind, const char* prefix) {
    TopTools_IndexedDataMapOfShapeListOfShape entity_faces;
    TopExp::MapShapesAndAncestors(whole, kind, TopAbs_FACE, entity_faces);
    for (int k = 1; k <= entity_faces.Extent(); ++k) {
      const TopoDS_Shape& entity = entity_faces.FindKey(k);
      if (kind == TopAbs_EDGE && BRep_Tool::Degenerated(TopoDS::Edge(entity))) continue;
      // Solids through the entity, joined when a face through it belongs to both.
      std::vector<int> comp(n, -1);
      std::vector<int> solids;
      for (const TopoDS_Shape& f : entity_faces(k)) {
        std::vector<int> owners;
        for (int i = 0; i < n; ++i)
          if (faces[i].Contains(f)) owners.push_back(i);
        for (int i : owners)
          if (comp[i] < 0) comp[i] = i, solids.push_back(i);
        for (std::size_t a = 1; a < owners.size(); ++a) {
          const int from = comp[owners[a]], to = comp[owners[0]];
          if (from != to)
            for (int& c : comp)
              if (c == from) c = to;
        }
      }
      for (int i : solids)
        if (comp[i] != comp[solids[0]]) {
          names.push_back(prefix + std::to_string(k));
          break;
        }
    }
  };
  check(TopAbs_EDGE, "Edge");
  const std::size_t flagged_edges = names.size();
  check(TopAbs_VERTEX, "Vertex");
  // Entity numbers: as MapShapes of the whole numbers them (the names users see).
  TopTools_IndexedMapOfShape all_edges, all_vertices;
  TopExp::MapShapes(whole, TopAbs_EDGE, all_edges);
  TopExp::MapShapes(whole, TopAbs_VERTEX, all_vertices);
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces, vertex_faces;
  TopExp::MapShapesAndAncestors(whole, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  TopExp::MapShapesAndAncestors(whole, TopAbs_VERTEX, TopAbs_FACE, vertex_faces);
  // A vertex at the end of a flagged edge says nothing more: only the edge is named.
  TopTools_IndexedMapOfShape edge_ends;
  for (std::size_t i = 0; i < flagged_edges; ++i)
    TopExp::MapShapes(edge_faces.FindKey(std::stoi(names[i].substr(4))), TopAbs_VERTEX, edge_ends);
  names.erase(
      std::remove_if(names.begin() + flagged_edges, names.end(),
                     [&](const std::string& name) {
                       return edge_ends.Contains(vertex_faces.FindKey(std::stoi(name.substr(6))));
                     }),
      names.end());
  for (std::string& name : names) {
    const bool edge = name.rfind("Edge", 0) == 0;
    const int k = std::stoi(name.substr(edge ? 4 : 6));
    name = edge ? "Edge" + std::to_string(all_edges.FindIndex(edge_faces.FindKey(k)))
                : "Vertex" + std::to_string(all_vertices.FindIndex(vertex_faces.FindKey(k)));
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

// The volume a solid's modelling tolerances leave open: a skin of each face's tolerance
// over the face, and a tube of each edge's tolerance along the edge (an edge of tolerance t
// lies anywhere within t of its curve, and the faces meeting there with it). STEP files
// carry edges far more tolerant than their faces: HexMe i05's B-spline edges up to 1.3e-3
// where its faces have 1e-7, a tube of 3.2e-4 in all where the faces' skin is 2.5e-4.
double tolerance_skin(const TopoDS_Shape& s) {
  double skin = 0;
  for (TopExp_Explorer ex(s, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& f = TopoDS::Face(ex.Current());
    GProp_GProps area;
    BRepGProp::SurfaceProperties(f, area);
    skin += area.Mass() * std::max(BRep_Tool::Tolerance(f), Precision::Confusion());
  }
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(s, TopAbs_EDGE, edges);
  for (int i = 1; i <= edges.Extent(); ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(edges(i));
    // Edges no more tolerant than 1e-5 are left out (their tubes are below the faces' skin by
    // orders of magnitude), and their lengths not integrated: most edges of split pieces.
    const double t = BRep_Tool::Tolerance(edge);
    if (t <= 100 * Precision::Confusion() || BRep_Tool::Degenerated(edge)) continue;
    GProp_GProps length;
    BRepGProp::LinearProperties(edge, length);
    skin += M_PI * t * t * length.Mass();
  }
  return skin;
}

}  // namespace

ReadResult glue(const std::vector<TopoDS_Solid>& solids, const std::string& where, ReadResult r,
                const GlueOptions& options) {
  // Overlap shows as a glued volume below the sum of the solids' volumes. What the volumes
  // may differ by without any: the integration's estimated error, and what the modelling
  // tolerances leave open (the fuse moves faces by up to that: HexMe i20's 45 plane-cut
  // pieces, 2.6e-9 of the volume, 1e-3 in a skin allowance of 0.04).
  double volume = 0, error = 0;
  for (const TopoDS_Solid& s : solids) {
    if (!options.check_overlap) break;
    double e = 0;
    volume += accurate_volume(s, e);
    error += e + tolerance_skin(s);
  }
  // The general fuse of the solids as given; where that fails (no result, parts turned inside
  // out or volume lost), again on copies that share no sub-shapes. Split pieces share their
  // common faces, and OCCT's fuse mistakes some of those: HexMe i19's plane-cut pieces meet on
  // a cylinder of radius 30 in sliver faces 0.6 wide, and two of them came out inside out
  // (volumes -11,713 and -22,158 for 1,042 and 2,786); fused as copies, the common faces are
  // found by intersection and all 44 glue. (FreeCAD's generalFuse copies its tools too.)
  TopoDS_Shape glued;
  std::vector<TopoDS_Solid> parts;
  double glued_volume = 0, glued_error = 0;
  int inside_out = 0;  // parts the fuse turned inside out (negative volume)
  auto lost_volume = [&] {
    return options.check_overlap &&
           std::abs(glued_volume - volume) > 1e-9 * std::abs(volume) + error + glued_error;
  };
  auto fuse_with = [&](bool copies) {
    glued.Nullify();
    parts.clear();
    glued_volume = glued_error = 0;
    inside_out = 0;
    try {
      BRepAlgoAPI_BuilderAlgo fuse;
      TopTools_ListOfShape args;
      for (const TopoDS_Solid& s : solids)
        args.Append(copies ? BRepBuilderAPI_Copy(s).Shape() : TopoDS_Shape(s));
      fuse.SetArguments(args);
      fuse.SetRunParallel(false);
      fuse.SetNonDestructive(true);  // the solids may share sub-shapes with others (split pieces)
      if (options.only_touching) fuse.SetGlue(BOPAlgo_GlueShift);
      fuse.Build();
      if (fuse.IsDone() && !fuse.HasErrors()) glued = fuse.Shape();
    } catch (const Standard_Failure&) {
      glued.Nullify();
    }
    if (glued.IsNull()) return false;
    for (TopExp_Explorer ex(glued, TopAbs_SOLID); ex.More(); ex.Next()) {
      parts.push_back(TopoDS::Solid(ex.Current()));
      if (!options.check_overlap) continue;
      double e = 0;
      const double v = accurate_volume(parts.back(), e);
      glued_volume += v;
      glued_error += e;
      if (v < 0) ++inside_out;
    }
    return parts.size() == solids.size() && !lost_volume();
  };
  if (!fuse_with(false)) fuse_with(true);
  if (glued.IsNull()) {
    r.diagnostics.push_back(make_error("invalid_shape", where + " holds " +
                                                            plural(int(solids.size()), "solid") +
                                                            " that OCCT's general fuse could not "
                                                            "glue at their common faces."));
    return r;
  }
  if (parts.size() != solids.size() || lost_volume()) {
    std::ostringstream why;
    why.precision(10);
    why << where << " holds " << plural(int(solids.size()), "solid");
    if (parts.size() != solids.size())
      why << " that overlap (their general fuse has " << plural(int(parts.size()), "solid")
          << "); solids may touch at common faces but not share volume.";
    else if (inside_out > 0)
      why << " that OCCT's general fuse could not glue: it turned " << inside_out << " of them "
          << "inside out (glued, their volume is " << glued_volume << " instead of " << volume
          << ").";
    else
      why << " that overlap (glued, their volume is " << glued_volume << " instead of " << volume
          << "); solids may touch at common faces but not share volume.";
    r.diagnostics.push_back(make_error("overlapping_solids", why.str()));
    return r;
  }
  BRep_Builder b;
  TopoDS_Compound compound;
  b.MakeCompound(compound);
  for (const TopoDS_Solid& s : parts) b.Add(compound, s);
  const std::vector<std::string> pinched =
      options.check_manifold ? touching_without_face(parts, compound) : std::vector<std::string>();
  if (!pinched.empty()) {
    r.diagnostics.push_back(make_error(
        "non_manifold",
        where + " holds solids that touch along an edge or at a vertex without a common face (" +
            join_names(pinched, 8) +
            "): one mesh of them would not be a manifold there. Join them by a face, or mesh "
            "them apart.",
        pinched));
    return r;
  }
  r.solid = std::make_unique<Solid>(make_solid_impl(compound));
  std::ostringstream s;
  s << where << " holds " << solids.size() << " solids; each is meshed, ";
  const int shared = r.solid->num_interface_faces();
  if (shared == 0)
    s << "none touches another.";
  else
    s << "with one mesh across the " << plural(shared, "face") << " they share.";
  r.diagnostics.push_back(make_info("several_solids", s.str()));
  return r;
}

}  // namespace vorohex::occ::detail
