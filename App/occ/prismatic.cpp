#include "occ/prismatic.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_BuilderAlgo.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRep_Builder.hxx>
#include <ElCLib.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <GeomAbs_SurfaceType.hxx>
#include <ShapeFix_Face.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>
#include <gp_Pln.hxx>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "occ/solid_impl.h"

namespace vorohex::occ {
namespace {

Vec3 to_vec(const gp_XYZ& p) {
  return Vec3(p.X(), p.Y(), p.Z());
}
std::string face_name(int f) {
  return "Face" + std::to_string(f);
}
std::string edge_name(int e) {
  return "Edge" + std::to_string(e);
}

// A direction with the sign that makes its largest component positive: the same axis
// whichever way the faces that give it happen to face (a part built from a reversed wire).
Vec3 canonical(Vec3 d) {
  d.normalize();
  int big = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(d[k]) > std::abs(d[big]) + 1e-12) big = k;
  return d[big] < 0 ? Vec3(-d) : d;
}

// Directions of the solid's planes (normals), cylinders (axes) and extrusions, one per line.
std::vector<Vec3> candidate_axes(const core::MeshDomain& solid) {
  std::vector<Vec3> out;
  for (FaceId f : solid.faces()) {
    const core::SurfaceInfo info = solid.surface_info(f);
    if (info.kind != core::SurfaceKind::plane && info.kind != core::SurfaceKind::cylinder &&
        info.kind != core::SurfaceKind::extrusion)
      continue;
    Vec3 d = info.direction;
    if (d.norm() < 1e-12) continue;
    d = canonical(d);
    bool known = false;
    for (const Vec3& o : out) known = known || std::abs(std::abs(o.dot(d)) - 1) < 1e-12;
    if (!known) out.push_back(d);
  }
  return out;
}

const char* surface_kind(core::SurfaceKind t) {
  switch (t) {
    case core::SurfaceKind::cone:
      return "a cone";
    case core::SurfaceKind::sphere:
      return "a sphere";
    case core::SurfaceKind::torus:
      return "a torus";
    case core::SurfaceKind::revolution:
      return "a surface of revolution";
    default:
      return "a surface";
  }
}

const double kSlopeCos = 0.5;  // cos 60 degrees: the steepest a sloped cap may be

// Whether face f is a sloped cap for axis a (prismatic.h): its normal, sampled along its
// boundary and at a point inside, within 60 degrees of the axis and always on one side of
// it (`up`: the side of +a); no seam and no degenerated edge (a cone's apex, a sphere's pole).
bool sloped_cap(const core::MeshDomain& solid, FaceId f, const Vec3& a, bool& up) {
  std::vector<Vec3> q;
  std::vector<int> seen;
  for (const auto& wire : solid.face_wires(f))
    for (const OrientedEdge& oe : wire) {
      if (solid.edge_is_degenerated(oe.edge) ||
          std::find(seen.begin(), seen.end(), oe.edge.value()) != seen.end())
        return false;
      seen.push_back(oe.edge.value());
      for (const Vec3& p : solid.edge_points_by_length(oe.edge, 8)) q.push_back(p);
    }
  if (q.empty()) return false;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : q) mean += p;
  q.push_back(solid.project_to_face(f, mean / double(q.size())));
  int sign = 0;
  for (const Vec3& p : q) {
    const double c = solid.face_normal(f, p).dot(a);
    if (std::abs(c) < kSlopeCos || (sign != 0 && (c > 0) != (sign > 0))) return false;
    sign = c > 0 ? 1 : -1;
  }
  up = sign > 0;
  return true;
}

// Whether every face is a cap (flat or sloped) or a wall for `a`, and every edge vertical,
// horizontal or on a sloped cap; fills caps (with their heights, NaN for the sloped ones)
// or returns the reason.
std::string check_faces_and_edges(const core::MeshDomain& solid, const Vec3& a, const Vec3& origin,
                                  double tol, std::vector<FaceId>& caps,
                                  std::vector<double>& cap_height, std::vector<bool>& cap_up,
                                  std::vector<bool>& cap_sloped) {
  const double kParallel = 1e-9;  // |cos| of the angle between unit directions
  auto height = [&](const Vec3& p) { return (p - origin).dot(a); };
  std::vector<char> on_sloped(solid.num_faces() + 1, 0);
  auto add_sloped = [&](FaceId f, bool up) {
    caps.push_back(f);
    cap_height.push_back(std::nan(""));
    cap_up.push_back(up);
    cap_sloped.push_back(true);
    on_sloped[f.value()] = 1;
  };
  for (FaceId f : solid.faces()) {
    const core::SurfaceInfo info = solid.surface_info(f);
    // A face without a boundary (a broken piece of a split) is no cap or wall.
    const auto wires = solid.face_wires(f);
    if (wires.empty() || wires[0].empty()) return face_name(f.value()) + " has no boundary";
    bool up = false;
    if (info.kind == core::SurfaceKind::plane) {
      const Vec3 q = solid.vertex_point(solid.edge_first_vertex(wires[0][0].edge));
      const Vec3 n = solid.face_normal(f, q);
      const double cosine = n.dot(a);
      if (std::abs(std::abs(cosine) - 1) < kParallel) {
        caps.push_back(f);
        cap_height.push_back(height(q));
        cap_up.push_back(cosine > 0);
        cap_sloped.push_back(false);
      } else if (std::abs(cosine) > kParallel) {
        if (sloped_cap(solid, f, a, up)) {
          add_sloped(f, up);
          continue;
        }
        std::ostringstream why;
        why << face_name(f.value()) << " is a plane at "
            << std::acos(std::min(1.0, std::abs(cosine))) * 180 / 3.14159265358979323846
            << " degrees to the axis";
        return why.str();
      }
      continue;
    }
    if (info.kind == core::SurfaceKind::cylinder || info.kind == core::SurfaceKind::extrusion) {
      if (std::abs(std::abs(info.direction.normalized().dot(a)) - 1) > kParallel)
        return face_name(f.value()) + " is " +
               (info.kind == core::SurfaceKind::cylinder ? "a cylinder" : "an extrusion") +
               " across the axis";
      continue;
    }
    if (info.kind != core::SurfaceKind::other) {
      if (sloped_cap(solid, f, a, up)) {
        add_sloped(f, up);
        continue;
      }
      return face_name(f.value()) + " is " + surface_kind(info.kind);
    }
    // Another surface (B-spline, offset...): a wall when its normal is across the axis at
    // every sample of its boundary.
    bool wall = true;
    for (const auto& wire : wires)
      for (const OrientedEdge& oe : wire) {
        if (solid.edge_is_degenerated(oe.edge)) continue;
        for (const Vec3& q : solid.edge_points_by_length(oe.edge, 8))
          wall = wall && std::abs(solid.face_normal(f, q).dot(a)) <= 1e-7;
      }
    if (wall) continue;
    if (sloped_cap(solid, f, a, up)) {
      add_sloped(f, up);
      continue;
    }
    return face_name(f.value()) + " is a curved surface not parallel to the axis";
  }
  for (EdgeId e : solid.edges()) {
    if (solid.edge_is_degenerated(e)) return edge_name(e.value()) + " is degenerated";
    const core::CurveInfo info = solid.curve_info(e);
    if (info.kind == core::CurveKind::line &&
        std::abs(std::abs(info.direction.normalized().dot(a)) - 1) < kParallel)
      continue;
    // Other curves (a B-spline that is a straight line, as STEP files often carry): along
    // the axis when every sample lies on the axis line through the first, horizontal when
    // every sample lies at the first one's height.
    const std::vector<Vec3> p = solid.edge_points_by_length(e, 8);
    if (p.empty()) return edge_name(e.value()) + " has no points";
    bool vertical = true, horizontal = true;
    for (const Vec3& q : p) {
      const Vec3 d = q - p[0];
      vertical = vertical && (d - d.dot(a) * a).norm() <= tol;
      horizontal = horizontal && std::abs(d.dot(a)) <= tol;
    }
    bool climbs_a_sloped_cap = false;
    for (FaceId f : solid.edge_faces(e)) climbs_a_sloped_cap |= on_sloped[f.value()] != 0;
    if (!vertical && !horizontal && !climbs_a_sloped_cap)
      return edge_name(e.value()) + " neither runs along the axis nor lies at one height";
  }
  if (caps.empty()) return "no face is perpendicular to the axis";
  return "";
}

// The arrangement's building blocks: each model vertex and horizontal edge moved down
// along the axis onto the base plane (height 0), built once and shared by every cap that
// uses it, so that the caps' wires join.
class Projector {
 public:
  Projector(const core::MeshDomain& solid, const Vec3& a, const Vec3& origin)
      : solid_(solid),
        a_(a),
        origin_(origin),
        vertices_(solid.num_vertices() + 1),
        edges_(solid.num_edges() + 1) {}

  Vec3 down(const Vec3& p) const { return p - (p - origin_).dot(a_) * a_; }

  const TopoDS_Vertex& vertex(VertexId v) {
    TopoDS_Vertex& out = vertices_[v.value()];
    if (out.IsNull()) {
      const Vec3 p = down(solid_.vertex_point(v));
      out = BRepBuilderAPI_MakeVertex(gp_Pnt(p.x(), p.y(), p.z())).Vertex();
    }
    return out;
  }

  // The edge in its own direction (first to last vertex), on the base plane.
  const TopoDS_Edge& edge(EdgeId e) {
    TopoDS_Edge& out = edges_[e.value()];
    if (!out.IsNull()) return out;
    const TopoDS_Vertex &v0 = vertex(solid_.edge_first_vertex(e)),
                        &v1 = vertex(solid_.edge_last_vertex(e));
    const core::CurveInfo info = solid_.curve_info(e);
    std::vector<Vec3> p = solid_.edge_points_by_length(e, 32);
    auto pnt = [](const Vec3& q) { return gp_Pnt(q.x(), q.y(), q.z()); };
    // A circle's plane is across the axis when the edge lies at one height (else, climbing
    // a sloped cap, its shadow is an ellipse: interpolated below).
    bool level = true;
    for (const Vec3& q : p)
      level = level && std::abs((q - p[0]).dot(a_)) <= 1e-7 * (1 + info.radius);
    for (Vec3& q : p) q = down(q);
    if (info.kind == core::CurveKind::line) {
      out = BRepBuilderAPI_MakeEdge(v0, v1).Edge();
    } else if (info.kind == core::CurveKind::circle && level) {
      // The circle (its plane is across the axis) turned so that it runs as the edge does:
      // from the first sample through the middle one (or, closed, on to the second).
      gp_Dir n(a_.x(), a_.y(), a_.z());
      gp_Circ circ(gp_Ax2(pnt(down(info.origin)), n), info.radius);
      auto ahead = [&](const Vec3& from, const Vec3& to) {
        double d = ElCLib::Parameter(circ, pnt(to)) - ElCLib::Parameter(circ, pnt(from));
        while (d <= 0) d += 2 * M_PI;
        while (d > 2 * M_PI) d -= 2 * M_PI;
        return d;
      };
      const bool closed = (p.front() - p.back()).norm() <= 1e-9 * (1 + info.radius);
      const bool backwards = closed
                                 ? ahead(p[0], p[1]) > M_PI
                                 : ahead(p.front(), p[p.size() / 2]) > ahead(p.front(), p.back());
      if (backwards) circ.SetAxis(gp_Ax1(circ.Location(), n.Reversed()));
      out = BRepBuilderAPI_MakeEdge(circ, v0, v1).Edge();
    } else {
      const bool closed = (p.front() - p.back()).norm() <= 1e-12 * (1 + p.front().norm());
      Handle(TColgp_HArray1OfPnt) pts =
          new TColgp_HArray1OfPnt(1, int(p.size()) - (closed ? 1 : 0));
      for (int i = 1; i <= pts->Length(); ++i) pts->SetValue(i, pnt(p[i - 1]));
      GeomAPI_Interpolate interpolate(pts, closed, 1e-9);
      interpolate.Perform();
      if (!interpolate.IsDone()) throw std::runtime_error("cannot project " + edge_name(e.value()));
      out = BRepBuilderAPI_MakeEdge(interpolate.Curve(), v0, v1).Edge();
    }
    return out;
  }

  // A cap as a face on the base plane, its wires as the solid's (normal `n`).
  TopoDS_Face face(FaceId f, const Vec3& n) {
    const gp_Pln plane(gp_Pnt(origin_.x(), origin_.y(), origin_.z()), gp_Dir(n.x(), n.y(), n.z()));
    std::vector<TopoDS_Wire> wires;
    for (const auto& w : solid_.face_wires(f)) {
      BRepBuilderAPI_MakeWire mw;
      for (const OrientedEdge& oe : w) {
        const TopoDS_Edge& e = edge(oe.edge);
        mw.Add(oe.forward ? e : TopoDS::Edge(e.Reversed()));
      }
      if (!mw.IsDone())
        throw std::runtime_error("cannot rebuild the wires of " + face_name(f.value()));
      wires.push_back(mw.Wire());
    }
    BRepBuilderAPI_MakeFace mf(plane, wires.front(), true);
    for (std::size_t i = 1; i < wires.size(); ++i) mf.Add(wires[i]);
    if (!mf.IsDone()) throw std::runtime_error("cannot rebuild " + face_name(f.value()));
    ShapeFix_Face fix(mf.Face());
    fix.Perform();
    return fix.Face();
  }

 private:
  const core::MeshDomain& solid_;
  Vec3 a_, origin_;
  std::vector<TopoDS_Vertex> vertices_;
  std::vector<TopoDS_Edge> edges_;
};

// The structure for one axis, or the reason why not.
PrismaticStructure structure_for(const core::MeshDomain& solid, const Vec3& a) {
  PrismaticStructure r;
  r.axis = a;
  const BoundingBox box = solid.bounding_box();
  r.origin = box.min;
  const double diag = std::max(box.diagonal(), 1e-300);
  const double tol = std::max(1e-6 * diag, 2 * solid.tolerance());
  std::vector<double> cap_height;
  std::vector<bool> cap_up;
  r.reason =
      check_faces_and_edges(solid, a, r.origin, tol, r.caps, cap_height, cap_up, r.cap_sloped);
  if (!r.reason.empty()) return r;
  r.cap_up = cap_up;

  // Levels: the heights of the vertices on a wall or a flat cap (an apex among sloped caps
  // only is none), merged within the tolerance.
  std::vector<char> sloped_face(solid.num_faces() + 1, 0),
      level_vertex(solid.num_vertices() + 1, 0);
  for (std::size_t k = 0; k < r.caps.size(); ++k) sloped_face[r.caps[k].value()] = r.cap_sloped[k];
  for (FaceId f : solid.faces()) {
    if (sloped_face[f.value()]) continue;
    for (const auto& wire : solid.face_wires(f))
      for (const OrientedEdge& oe : wire)
        for (VertexId v : {solid.edge_first_vertex(oe.edge), solid.edge_last_vertex(oe.edge)})
          if (v.valid()) level_vertex[v.value()] = 1;
  }
  std::vector<double> h;
  for (VertexId v : solid.vertices())
    if (level_vertex[v.value()]) h.push_back(r.height(solid.vertex_point(v)));
  std::sort(h.begin(), h.end());
  for (double x : h)
    if (r.levels.empty() || x - r.levels.back() > tol) r.levels.push_back(x);
  auto level_of = [&](double x) {
    for (std::size_t i = 0; i < r.levels.size(); ++i)
      if (std::abs(r.levels[i] - x) <= tol) return int(i);
    return -1;
  };
  if (r.levels.size() < 2) {
    r.reason = "all vertices lie at one height";
    return r;
  }
  for (std::size_t k = 0; k < r.caps.size(); ++k) {
    const FaceId f = r.caps[k];
    if (!r.cap_sloped[k]) {
      const int l = level_of(cap_height[k]);
      if (l < 0) {
        r.reason = face_name(f.value()) + " lies between the vertices' heights";
        return r;
      }
      r.cap_level.push_back(l);
      continue;
    }
    // A sloped cap: the one level of its vertices on walls or flat caps; it stays clear of
    // the levels next to it (a twentieth of the slab), so that the slabs it bounds keep a
    // thickness everywhere.
    int l = -1;
    double lo = 1e300, hi = -1e300;
    for (const auto& wire : solid.face_wires(f))
      for (const OrientedEdge& oe : wire) {
        for (const Vec3& q : solid.edge_points_by_length(oe.edge, 8)) {
          lo = std::min(lo, r.height(q));
          hi = std::max(hi, r.height(q));
        }
        const VertexId v = solid.edge_first_vertex(oe.edge);
        if (!level_vertex[v.value()]) continue;
        const int lv = level_of(r.height(solid.vertex_point(v)));
        if (l >= 0 && lv != l) {
          r.reason =
              face_name(f.value()) +
              " slopes between two levels (its vertices on walls or flat caps lie at two heights)";
          return r;
        }
        l = lv;
      }
    if (l < 0) {
      r.reason = face_name(f.value()) + " slopes with no vertex on a wall or a flat cap";
      return r;
    }
    const bool too_high = l + 1 < int(r.levels.size()) &&
                          hi > r.levels[l + 1] - 0.05 * (r.levels[l + 1] - r.levels[l]);
    const bool too_low = l > 0 && lo < r.levels[l - 1] + 0.05 * (r.levels[l] - r.levels[l - 1]);
    if (too_high || too_low) {
      r.reason = face_name(f.value()) + " slopes to within a twentieth of the next level";
      return r;
    }
    r.cap_level.push_back(l);
  }

  // Arrangement: every cap and every horizontal edge, moved down to height 0, fused.
  TopTools_ListOfShape arguments;
  std::vector<TopoDS_Shape> moved_caps;
  std::vector<char> in_cap(solid.num_edges() + 1, 0);
  Projector projector(solid, a, r.origin);
  for (std::size_t k = 0; k < r.caps.size(); ++k) {
    const FaceId f = r.caps[k];
    moved_caps.push_back(projector.face(f, cap_up[k] ? a : Vec3(-a)));
    arguments.Append(moved_caps.back());
    for (const auto& wire : solid.face_wires(f))
      for (const OrientedEdge& oe : wire) in_cap[oe.edge.value()] = 1;
  }
  for (EdgeId e : solid.edges()) {
    if (in_cap[e.value()]) continue;
    const double h0 = r.height(solid.vertex_point(solid.edge_first_vertex(e)));
    const double h1 = r.height(solid.vertex_point(solid.edge_last_vertex(e)));
    if (std::abs(h0 - h1) > tol) continue;  // vertical: its projection is a vertex anyway
    arguments.Append(projector.edge(e));
  }
  BRepAlgoAPI_BuilderAlgo fuse;
  fuse.SetArguments(arguments);
  fuse.SetRunParallel(false);
  fuse.SetNonDestructive(true);
  fuse.SetFuzzyValue(tol);
  fuse.Build();
  if (fuse.HasErrors() || !fuse.IsDone()) {
    r.reason = "the caps' outlines could not be overlaid (OCCT's general fuse failed)";
    return r;
  }
  TopTools_IndexedMapOfShape regions;
  TopExp::MapShapes(fuse.Shape(), TopAbs_FACE, regions);
  r.covering_caps.assign(regions.Extent() + 1, {});
  for (std::size_t k = 0; k < moved_caps.size(); ++k) {
    TopTools_ListOfShape images = fuse.Modified(moved_caps[k]);
    if (images.IsEmpty() && !fuse.IsDeleted(moved_caps[k])) images.Append(moved_caps[k]);
    for (const TopoDS_Shape& im : images) {
      const int i = regions.FindIndex(im);
      if (i > 0) r.covering_caps[i].push_back(int(k));
    }
  }
  // Every region with normal +axis, in the map's order so that ids carry over.
  BRep_Builder builder;
  TopoDS_Compound oriented;
  builder.MakeCompound(oriented);
  for (int i = 1; i <= regions.Extent(); ++i) {
    TopoDS_Face face = TopoDS::Face(regions(i));
    BRepAdaptor_Surface s(face, false);
    if (s.GetType() != GeomAbs_Plane) {
      r.reason = "the overlay of the caps gave a face that is not planar";
      return r;
    }
    // The normal as du x dv (a plane's axis may be left-handed), then the face's sense.
    gp_Pnt q;
    gp_Vec du, dv;
    s.D1(0.5 * (s.FirstUParameter() + s.LastUParameter()),
         0.5 * (s.FirstVParameter() + s.LastVParameter()), q, du, dv);
    Vec3 n = to_vec(du.Crossed(dv).XYZ());
    if (face.Orientation() == TopAbs_REVERSED) n = -n;
    if (n.dot(a) < 0) face.Reverse();
    builder.Add(oriented, face);
  }
  r.arrangement = std::make_unique<Solid>(make_solid_impl(oriented));
  if (r.arrangement->num_faces() != regions.Extent()) {
    r.reason = "the overlay of the caps has faces that repeat";
    return r;
  }

  // Inside or outside per region and slab: the caps crossed from below, alternately
  // entering (a cap facing down) and leaving (facing up); above the top, outside.
  const std::size_t slabs = r.levels.size() - 1;
  r.inside.assign(regions.Extent() + 1, std::vector<bool>(slabs, false));
  for (int i = 1; i <= regions.Extent(); ++i) {
    std::vector<int> at(r.levels.size(), -1);
    for (int k : r.covering_caps[i]) {
      if (at[r.cap_level[k]] >= 0) {
        r.reason = face_name(r.caps[k].value()) + " and " +
                   face_name(r.caps[at[r.cap_level[k]]].value()) + " overlap";
        return r;
      }
      at[r.cap_level[k]] = k;
    }
    bool in = false;
    for (std::size_t l = 0; l < r.levels.size(); ++l) {
      if (at[l] >= 0) {
        if (r.cap_up[at[l]] != in) {
          r.reason = face_name(r.caps[at[l]].value()) +
                     " faces the wrong way for the material around it (not a valid solid)";
          return r;
        }
        in = !in;
      }
      if (l < slabs) r.inside[i][l] = in;
    }
    if (in) {
      r.reason = "the material over a region of the caps is never closed";
      return r;
    }
  }
  r.ok = true;
  return r;
}

}  // namespace

PrismaticStructure prismatic_structure(const core::MeshDomain& solid, const Vec3& axis) {
  PrismaticStructure best;
  best.reason = "no direction of its planes, cylinders or extrusions";
  try {
    std::vector<Vec3> axes =
        axis.norm() > 0 ? std::vector<Vec3>{canonical(axis)} : candidate_axes(solid);
    bool found = false;
    // Refused along every axis: the reason along the one whose caps (planar faces across
    // it) have the most area, the axis a user would sweep along (a block with a steep pit:
    // its top and bottom's, where the pit's faces are too steep, not the sides').
    std::string first_reason;
    double most_cap_area = -1;
    for (const Vec3& a : axes) {
      PrismaticStructure s = structure_for(solid, a);
      if (!s.ok) {
        const double cap_area = area_across(solid, a);
        if (cap_area > most_cap_area) first_reason = s.reason, most_cap_area = cap_area;
        continue;
      }
      const auto rank = [](const PrismaticStructure& p) {
        return std::make_pair(p.arrangement->num_faces(), p.levels.size());
      };
      if (!found || rank(s) < rank(best)) best = std::move(s);
      found = true;
    }
    if (!found && !first_reason.empty()) best.reason = first_reason;
  } catch (const Standard_Failure& e) {
    best = PrismaticStructure();
    best.reason = std::string("its geometry cannot be analysed (") + e.GetMessageString() + ")";
  } catch (const std::exception& e) {
    best = PrismaticStructure();
    best.reason = std::string("its geometry cannot be analysed (") + e.what() + ")";
  }
  return best;
}

double area_across(const core::MeshDomain& solid, const Vec3& axis) {
  double area = 0;
  for (FaceId f : solid.faces()) {
    if (!solid.face_is_planar(f)) continue;
    const auto wires = solid.face_wires(f);
    if (wires.empty() || wires[0].empty()) continue;
    const Vec3 n =
        solid.face_normal(f, solid.vertex_point(solid.edge_first_vertex(wires[0][0].edge)));
    if (std::abs(std::abs(n.normalized().dot(axis)) - 1) < 1e-9) area += solid.area(f);
  }
  return area;
}

EdgeInStructure edge_in_structure(const core::MeshDomain& solid, const PrismaticStructure& s,
                                  EdgeId e) {
  EdgeInStructure out;
  if (!s.ok || solid.edge_is_degenerated(e)) return out;
  const double tol = std::max(1e-6 * solid.diagonal(), 10 * solid.tolerance());
  double lo = 1e300, hi = -1e300;
  const std::vector<Vec3> samples = solid.edge_points_by_length(e, 8);
  bool vertical = true;
  for (const Vec3& q : samples) {
    lo = std::min(lo, s.height(q));
    hi = std::max(hi, s.height(q));
    const Vec3 d = q - samples.front();
    vertical = vertical && (d - d.dot(s.axis) * s.axis).norm() <= tol;
  }
  if (hi - lo <= tol) {
    // The arrangement edges whose middles, lifted to the edge's height, lie on it (the
    // overlay's edges never overlap an edge in part).
    for (EdgeId a : s.arrangement->edges()) {
      const Vec3 m = s.arrangement->edge_points_by_length(a, 2)[1];
      const Vec3 lifted = m + (lo - s.height(m)) * s.axis;
      if ((solid.project_to_edge(e, lifted) - lifted).norm() <= tol)
        out.arrangement_edges.push_back(a.value());
    }
    return out;
  }
  if (!vertical) {
    // An edge climbing a sloped cap: the arrangement edges whose middles lie under it. The
    // point of e over a middle m: from the nearest sample, alternately onto e and back onto
    // the axis line through m (it converges, the edge being less steep than 60 degrees).
    auto flat = [&](const Vec3& q) { return Vec3(q - s.height(q) * s.axis); };
    const std::vector<Vec3> fine = solid.edge_points_by_length(e, 64);
    double spacing = 0;
    for (std::size_t i = 1; i < fine.size(); ++i)
      spacing = std::max(spacing, (fine[i] - fine[i - 1]).norm());
    for (EdgeId a : s.arrangement->edges()) {
      const Vec3 m = s.arrangement->edge_points_by_length(a, 2)[1];
      std::size_t best = 0;
      for (std::size_t i = 1; i < fine.size(); ++i)
        if ((flat(fine[i]) - flat(m)).norm() < (flat(fine[best]) - flat(m)).norm()) best = i;
      if ((flat(fine[best]) - flat(m)).norm() > spacing + tol) continue;
      Vec3 q = m + (s.height(fine[best]) - s.height(m)) * s.axis;
      for (int k = 0; k < 100; ++k) {
        const Vec3 next = m + (s.height(solid.project_to_edge(e, q)) - s.height(m)) * s.axis;
        const bool still = (next - q).norm() <= 1e-3 * tol;
        q = next;
        if (still) break;
      }
      if ((solid.project_to_edge(e, q) - q).norm() <= tol)
        out.arrangement_edges.push_back(a.value());
    }
    return out;
  }
  for (std::size_t l = 0; l + 1 < s.levels.size(); ++l)
    if (s.levels[l] >= lo - tol && s.levels[l + 1] <= hi + tol) out.slabs.push_back(int(l));
  return out;
}

}  // namespace vorohex::occ
