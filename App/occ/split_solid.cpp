#include "occ/split_solid.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepAlgoAPI_Splitter.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepFill.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Message_ProgressIndicator.hxx>
#include <Poly_Triangulation.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/isolated_call.h"
#include "occ/solid_impl.h"

namespace vorohex::occ {
namespace {

gp_Pnt pnt(const Vec3& p) {
  return gp_Pnt(p.x(), p.y(), p.z());
}

// The tool face of a polygon; null shape when degenerate.
TopoDS_Shape tool_face(const std::vector<Vec3>& pts, double tol) {
  std::vector<Vec3> p;
  for (const Vec3& q : pts)
    if (p.empty() || (q - p.back()).norm() > tol) p.push_back(q);
  if (p.size() > 1 && (p.front() - p.back()).norm() <= tol) p.pop_back();
  if (p.size() < 3) return {};
  Vec3 n(0, 0, 0);
  for (std::size_t i = 0; i < p.size(); ++i) n += p[i].cross(p[(i + 1) % p.size()]);
  if (0.5 * n.norm() < tol * tol) return {};
  n.normalize();
  bool planar = true;
  for (const Vec3& q : p) planar = planar && std::abs((q - p[0]).dot(n)) <= tol;
  if (planar) {
    BRepBuilderAPI_MakePolygon poly;
    for (const Vec3& q : p) poly.Add(pnt(q));
    poly.Close();
    gp_Pln plane(pnt(p[0]), gp_Dir(n.x(), n.y(), n.z()));
    BRepBuilderAPI_MakeFace mf(plane, poly.Wire(), true);
    if (!mf.IsDone()) return TopoDS_Shape();
    return mf.Face();
  }
  // A non-planar quadrilateral: the ruled surface between sides 0-1 and 3-2.
  const TopoDS_Edge e1 = BRepBuilderAPI_MakeEdge(pnt(p[0]), pnt(p[1]));
  const TopoDS_Edge e2 = BRepBuilderAPI_MakeEdge(pnt(p[3 % p.size()]), pnt(p[2]));
  return BRepFill::Face(e1, e2);
}

// Keeps only the faces of a solid that bound it (drops INTERNAL tool faces).
TopoDS_Solid without_internal_faces(const TopoDS_Solid& solid, int* dropped) {
  bool any = false;
  for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next())
    any = any || ex.Current().Orientation() == TopAbs_INTERNAL;
  if (!any) return solid;
  BRep_Builder b;
  TopoDS_Solid out;
  b.MakeSolid(out);
  for (TopExp_Explorer sh(solid, TopAbs_SHELL); sh.More(); sh.Next()) {
    TopoDS_Shell shell;
    b.MakeShell(shell);
    int kept = 0;
    for (TopExp_Explorer ex(sh.Current(), TopAbs_FACE); ex.More(); ex.Next()) {
      if (ex.Current().Orientation() == TopAbs_INTERNAL) {
        ++*dropped;
        continue;
      }
      b.Add(shell, ex.Current());
      ++kept;
    }
    // A shell made only of internal faces (OCCT puts a dangling tool face in a shell of
    // its own) leaves nothing: an empty shell would make the piece "not closed".
    if (kept == 0) continue;
    shell.Closed(true);
    b.Add(out, shell);
  }
  return out;
}

// Asks OCCT to stop once a deadline has passed (checked at its progress points).
class Deadline : public Message_ProgressIndicator {
 public:
  explicit Deadline(double seconds)
      : end_(std::chrono::steady_clock::now() +
             std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                 std::chrono::duration<double>(seconds))) {}
  Standard_Boolean UserBreak() override { return std::chrono::steady_clock::now() > end_; }
  void Show(const Message_ProgressScope&, const Standard_Boolean) override {}

 private:
  std::chrono::steady_clock::time_point end_;
};

// OCCT's splitter on `args` by `tools` (non-destructive, fuzzy to a hundredth of `tolerance`),
// stopped through its progress break at `time_limit` seconds (<= 0: none).
struct Split {
  TopoDS_Shape shape;
  bool done = false, timed_out = false;
};
Split split_by(const TopTools_ListOfShape& args, const TopTools_ListOfShape& tools,
               double tolerance, double time_limit) {
  Split out;
  BRepAlgoAPI_Splitter splitter;
  splitter.SetArguments(args);
  splitter.SetTools(tools);
  splitter.SetFuzzyValue(0.01 * tolerance);
  splitter.SetNonDestructive(true);
  Handle(Deadline) deadline = time_limit > 0 ? new Deadline(time_limit) : nullptr;
  splitter.Build(deadline.IsNull() ? Message_ProgressRange() : deadline->Start());
  out.timed_out = !deadline.IsNull() && deadline->UserBreak();
  out.done = !out.timed_out && splitter.IsDone();
  if (out.done) out.shape = splitter.Shape();
  return out;
}

// A split OCCT threw on: no pieces, the error named.
void failed_in_occt(SplitResult& out, const Standard_Failure& e) {
  out.pieces.clear();
  out.diagnostics.push_back(core::make_error(
      "split_failed", std::string("OCCT failed splitting the solid: ") +
                          (e.GetMessageString() ? e.GetMessageString() : "unknown")));
}

// Faces (and edges) on one surface merged. With `or_as_is`, where OCCT's unification throws
// (HexMe i14: a tube's end ring fused to its middle, where a plane tangent to the tube left a
// line on its cylinder) it is tried again without concatenating B-splines, then without
// merging edges, and else the shape is left as it is (a valid solid, its faces split where
// the pieces met); without, the exception is passed on (a failed cut or union).
TopoDS_Shape unified(const TopoDS_Shape& s, bool or_as_is = false) {
  const bool modes[][2] = {{true, true}, {true, false}, {false, false}};  // edges, B-splines
  for (int k = 0; k < 3; ++k) {
    try {
      ShapeUpgrade_UnifySameDomain unify(s, modes[k][0], true, modes[k][1]);
      unify.Build();
      return unify.Shape();
    } catch (...) {  // Standard_Failure and others
      if (!or_as_is) throw;
    }
  }
  return s;
}

// What unifying solids may take at most: where it ends at all it takes milliseconds
// (HexMe's plane cuts: at most 0.09 s, for i22's 80 pieces), so a hundred times that bound
// only the unification that loops, and no longer waits out the caller's whole limit (i02's
// cuts 30 s, a fuse among i15's merges 26 s).
double unification_bound(std::size_t solids) {
  return 2.0 + 0.1 * double(solids);
}

// Each solid unified, in order (a solid may become several), into one compound.
TopoDS_Compound unified_solids(const std::vector<TopoDS_Solid>& solids, bool or_as_is) {
  BRep_Builder b;
  TopoDS_Compound c;
  b.MakeCompound(c);
  for (const TopoDS_Solid& s : solids) {
    const TopoDS_Shape u = unified(s, or_as_is);
    for (TopExp_Explorer ex(u, TopAbs_SOLID); ex.More(); ex.Next()) b.Add(c, ex.Current());
  }
  return c;
}

// The solids of a shape, in order.
std::vector<TopoDS_Solid> solids_of(const TopoDS_Shape& c) {
  std::vector<TopoDS_Solid> out;
  for (TopExp_Explorer ex(c, TopAbs_SOLID); ex.More(); ex.Next())
    out.push_back(TopoDS::Solid(ex.Current()));
  return out;
}

// A unification as bytes for a server's child (core::IsolatedServer): with or_as_is ('1' or
// '0') first, then the solids as a BREP compound; its result the unified compound.
std::string unification_request(const std::vector<TopoDS_Solid>& solids, bool or_as_is) {
  BRep_Builder b;
  TopoDS_Compound c;
  b.MakeCompound(c);
  for (const TopoDS_Solid& s : solids) b.Add(c, s);
  std::ostringstream text;
  text << (or_as_is ? '1' : '0');
  BRepTools::Write(c, text);
  return text.str();
}

std::string serve_unification(const std::string& request) {
  if (request.empty()) throw std::runtime_error("an empty unification request");
  std::istringstream in(request.substr(1));
  TopoDS_Shape c;
  BRep_Builder b;
  BRepTools::Read(c, in, b);
  if (c.IsNull()) throw std::runtime_error("the unification's solids did not arrive");
  std::ostringstream text;
  BRepTools::Write(unified_solids(solids_of(c), request[0] == '1'), text);
  return text.str();
}

// Each solid unified, in order (a solid may become several). OCCT's unification takes no
// progress indicator and can loop without end: HexMe i02's plane cuts leave a piece (planes
// and cylinders crossing, B-spline intersection edges) on which ShapeUpgrade_UnifySameDomain
// still ran after 12 min, with every face kept or none. So with a time limit (`seconds` > 0,
// and at most unification_bound) it runs in a child process, stopped at the limit
// (`timed_out`): `server`'s when given (serve_unification), else one of its own. "" when
// done, else why not.
std::string unified_within(const std::vector<TopoDS_Solid>& solids, double seconds,
                           std::vector<TopoDS_Solid>& out, bool& timed_out, bool or_as_is = false,
                           core::IsolatedServer* server = nullptr) {
  if (seconds <= 0) {
    out = solids_of(unified_solids(solids, or_as_is));
    return "";
  }
  const bool bounded = seconds > unification_bound(solids.size());
  seconds = std::min(seconds, unification_bound(solids.size()));
  const core::Progress limit = core::Progress().with_time_limit(seconds);
  const core::IsolatedResult run =
      server ? server->call(unification_request(solids, or_as_is), limit)
             : core::isolated_call(
                   [&] {
                     std::ostringstream text;
                     BRepTools::Write(unified_solids(solids, or_as_is), text);
                     return text.str();
                   },
                   limit);
  // Stopped at the bound, the unification failed; at the caller's limit, time ran out.
  const bool stopped = run.status == core::IsolatedResult::Status::cancelled;
  timed_out = stopped && !bounded;
  if (stopped) {
    std::ostringstream why;
    why << "OCCT did not merge the faces of the split's pieces within "
        << (bounded ? "" : "the time limit (") << std::lround(seconds) << " s"
        << (bounded ? ", where it takes milliseconds when it ends" : ")");
    return why.str();
  }
  if (!run.ok())
    return "OCCT failed merging the faces of the split's pieces" +
           (run.message.empty() ? std::string() : " (" + run.message + ")");
  std::istringstream in(run.data);
  TopoDS_Shape c;
  BRep_Builder b;
  BRepTools::Read(c, in, b);
  if (c.IsNull()) return "the split's pieces did not come back from merging their faces";
  out = solids_of(c);
  return "";
}

}  // namespace

SplitResult split_solid(const Solid& solid, const std::vector<std::vector<Vec3>>& tools,
                        double tolerance, double time_limit) {
  return split_solid(solid, tools, {}, tolerance, time_limit);
}

bool face_cylinder(const Solid& solid, FaceId f, CutCylinder* cylinder) {
  const BRepAdaptor_Surface surface(TopoDS::Face(solid.impl().faces(f.value())));
  if (surface.GetType() != GeomAbs_Cylinder) return false;
  const gp_Cylinder c = surface.Cylinder();
  const gp_Pnt o = c.Location();
  const gp_Dir d = c.Axis().Direction();
  // The face's seam is where its u range starts (not always u = 0).
  double u0, u1, v0, v1;
  BRepTools::UVBounds(TopoDS::Face(solid.impl().faces(f.value())), u0, u1, v0, v1);
  const gp_Dir x = c.Position().XDirection().Rotated(c.Axis(), u0);
  cylinder->origin = Vec3(o.X(), o.Y(), o.Z());
  cylinder->axis = Vec3(d.X(), d.Y(), d.Z());
  cylinder->seam = Vec3(x.X(), x.Y(), x.Z());
  cylinder->radius = c.Radius();
  return true;
}

SplitResult split_solid(const Solid& solid, const std::vector<std::vector<Vec3>>& tools,
                        const std::vector<CutCylinder>& cylinders, double tolerance,
                        double time_limit) {
  const auto t0 = std::chrono::steady_clock::now();
  SplitResult out;
  try {
    TopTools_ListOfShape args, tool_list;
    args.Append(solid.impl().solid);
    for (const auto& t : tools) {
      const TopoDS_Shape f = tool_face(t, tolerance);
      if (!f.IsNull()) tool_list.Append(f);
    }
    for (const CutCylinder& c : cylinders) {
      const gp_Ax3 frame(pnt(c.origin), gp_Dir(c.axis.x(), c.axis.y(), c.axis.z()),
                         gp_Dir(c.seam.x(), c.seam.y(), c.seam.z()));
      BRepBuilderAPI_MakeFace mf(gp_Cylinder(frame, c.radius), 0, c.angle, c.from, c.to);
      if (mf.IsDone()) tool_list.Append(mf.Face());
    }
    TopoDS_Shape result = solid.impl().solid;
    if (!tool_list.IsEmpty()) {
      const Split split = split_by(args, tool_list, tolerance, time_limit);
      if (split.timed_out) {
        out.timed_out = true;
        out.diagnostics.push_back(core::make_error(
            "split_timeout", "OCCT did not split the solid by " + std::to_string(tools.size()) +
                                 " decomposition faces within " +
                                 std::to_string(int(std::lround(time_limit))) + " s"));
        return out;
      }
      if (!split.done) {
        out.diagnostics.push_back(core::make_error("split_failed",
                                                   "OCCT could not split the solid by the "
                                                   "decomposition faces"));
        return out;
      }
      result = split.shape;
    }
    std::vector<TopoDS_Solid> cut;
    for (TopExp_Explorer ex(result, TopAbs_SOLID); ex.More(); ex.Next())
      cut.push_back(
          without_internal_faces(TopoDS::Solid(ex.Current()), &out.dropped_internal_faces));
    const double left =
        time_limit - std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::vector<TopoDS_Solid> pieces;
    const std::string why =
        unified_within(cut, time_limit > 0 ? std::max(1.0, left) : 0, pieces, out.timed_out);
    if (!why.empty()) {
      out.diagnostics.push_back(
          core::make_error(out.timed_out ? "split_timeout" : "split_failed", why));
      return out;
    }
    for (const TopoDS_Solid& piece : pieces) out.pieces.push_back(make_solid(piece));
    out.ok = !out.pieces.empty();
    if (!out.ok)
      out.diagnostics.push_back(core::make_error("split_empty", "The split gave no solid"));
  } catch (const Standard_Failure& e) {
    failed_in_occt(out, e);
  }
  return out;
}

SplitResult split_at_interfaces(const Solid& solid, const Solid& glued, double tolerance,
                                double time_limit) {
  SplitResult out;
  try {
    TopTools_ListOfShape args, tools;
    args.Append(solid.impl().solid);
    const Solid::Impl& g = glued.impl();
    for (int f = 1; f <= g.faces.Extent(); ++f)
      if (g.interface_face[std::size_t(f)]) tools.Append(g.faces(f));
    if (tools.IsEmpty()) {
      out.diagnostics.push_back(core::make_error("split_failed", "the pieces share no face"));
      return out;
    }
    const Split split = split_by(args, tools, tolerance, time_limit);
    if (split.timed_out) {
      out.timed_out = true;
      out.diagnostics.push_back(core::make_error("split_timeout",
                                                 "OCCT did not split the solid at the pieces' "
                                                 "common faces in time"));
      return out;
    }
    if (!split.done) {
      out.diagnostics.push_back(core::make_error(
          "split_failed", "OCCT could not split the solid at the pieces' common faces"));
      return out;
    }
    for (TopExp_Explorer ex(split.shape, TopAbs_SOLID); ex.More(); ex.Next())
      out.pieces.push_back(make_solid(
          without_internal_faces(TopoDS::Solid(ex.Current()), &out.dropped_internal_faces)));
    out.ok = !out.pieces.empty();
  } catch (const Standard_Failure& e) {
    failed_in_occt(out, e);
  }
  return out;
}

bool is_closed(const Solid& solid) {
  try {
    int shells = 0;
    for (TopExp_Explorer ex(solid.impl().solid, TopAbs_SHELL); ex.More(); ex.Next(), ++shells)
      if (!BRep_Tool::IsClosed(ex.Current())) return false;
    return shells > 0;
  } catch (const Standard_Failure&) {
    return false;
  }
}

std::vector<FaceSample> sample_faces(const Solid& solid) {
  std::vector<FaceSample> out;
  const auto& impl = solid.impl();
  BRepMesh_IncrementalMesh mesher(impl.solid, 0.05 * solid.diagonal(), false, 0.5);
  for (int i = 1; i <= impl.faces.Extent(); ++i) {
    const TopoDS_Face& face = TopoDS::Face(impl.faces(i));
    FaceSample s;
    s.face = FaceId(i);
    GProp_GProps props;
    BRepGProp::SurfaceProperties(face, props);
    s.area = props.Mass();
    TopTools_IndexedMapOfShape edges, wires;
    TopExp::MapShapes(face, TopAbs_EDGE, edges);
    TopExp::MapShapes(face, TopAbs_WIRE, wires);
    s.num_edges = edges.Extent();
    s.num_wires = wires.Extent();
    TopLoc_Location loc;
    const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
    if (!tri.IsNull() && tri->NbTriangles() > 0) {
      // Centroid of the largest triangle: inside the face.
      double best = -1;
      for (int t = 1; t <= tri->NbTriangles(); ++t) {
        int a, b, c;
        tri->Triangle(t).Get(a, b, c);
        const gp_Pnt pa = tri->Node(a).Transformed(loc), pb = tri->Node(b).Transformed(loc),
                     pc = tri->Node(c).Transformed(loc);
        const double area = gp_Vec(pa, pb).Crossed(gp_Vec(pa, pc)).Magnitude();
        if (area > best) {
          best = area;
          s.point = Vec3((pa.X() + pb.X() + pc.X()) / 3, (pa.Y() + pb.Y() + pc.Y()) / 3,
                         (pa.Z() + pb.Z() + pc.Z()) / 3);
        }
      }
    } else {
      const gp_Pnt c = props.CentreOfMass();
      s.point = Vec3(c.X(), c.Y(), c.Z());
    }
    // The centroid of a triangle of a curved face lies off the surface by up to the
    // triangulation's deflection (5 % of the diagonal): on the face, it is where the face is
    // (a cone of a piece was taken for a decomposition face, at 1e-6 of the diagonal).
    s.point = solid.project_to_face(s.face, s.point);
    s.normal = solid.face_normal(s.face, s.point);
    out.push_back(s);
  }
  return out;
}

namespace {

// A Boolean operation of a and b, on copies of their sub-shapes (the geometry shared). The
// pieces of a split share their common edges and vertices with their neighbours, a result
// shares the sub-shapes the operation left as they were with its arguments, and OCCT's
// unification of the result changes sub-shapes in place: a fuse of two plane-cut pieces of
// HexMe i22 turned a third piece of volume 28.3 into one of -3244. (Unifying a copy of the
// result instead made the unification run without end on some unions of HexMe i01 and i15.)
template <class Operation>
bool run_boolean(Operation& op, const Solid& a, const Solid& b) {
  TopTools_ListOfShape arguments, tools;
  arguments.Append(BRepBuilderAPI_Copy(a.impl().solid, false, false).Shape());
  tools.Append(BRepBuilderAPI_Copy(b.impl().solid, false, false).Shape());
  op.SetArguments(arguments);
  op.SetTools(tools);
  op.SetNonDestructive(true);
  op.Build();
  return op.IsDone() && !op.HasErrors();
}

// fuse_solids, its unification in `server`'s child when given.
std::unique_ptr<Solid> fused_pair(const Solid& a, const Solid& b, double time_limit,
                                  bool split_faces_if_unification_fails,
                                  core::IsolatedServer* server) {
  try {
    BRepAlgoAPI_Fuse fuse;
    if (!run_boolean(fuse, a, b)) return nullptr;
    std::vector<TopoDS_Solid> fused, u;
    for (TopExp_Explorer ex(fuse.Shape(), TopAbs_SOLID); ex.More(); ex.Next())
      fused.push_back(TopoDS::Solid(ex.Current()));
    if (fused.size() != 1) return nullptr;  // apart, or touching along an edge
    bool timed_out = false;
    if (!unified_within(fused, time_limit, u, timed_out, split_faces_if_unification_fails, server)
             .empty() ||
        u.size() != 1)
      return nullptr;
    return std::make_unique<Solid>(make_solid(u[0]));
  } catch (const Standard_Failure&) {
    return nullptr;
  }
}

}  // namespace

std::unique_ptr<Solid> fuse_solids(const Solid& a, const Solid& b, double time_limit,
                                   bool split_faces_if_unification_fails) {
  return fused_pair(a, b, time_limit, split_faces_if_unification_fails, nullptr);
}

Fuser::Fuser() : server_(std::make_unique<core::IsolatedServer>(serve_unification)) {}

Fuser::~Fuser() = default;

std::unique_ptr<Solid> Fuser::fuse(const Solid& a, const Solid& b, double time_limit,
                                   bool split_faces_if_unification_fails) {
  return fused_pair(a, b, time_limit, split_faces_if_unification_fails, server_.get());
}

int Fuser::children() const {
  return server_->forks();
}

std::unique_ptr<Solid> cut_solids(const Solid& a, const Solid& b) {
  try {
    BRepAlgoAPI_Cut cut;
    if (!run_boolean(cut, a, b)) return nullptr;
    const TopoDS_Shape u = unified(cut.Shape());
    TopoDS_Solid only;
    int n = 0;
    for (TopExp_Explorer ex(u, TopAbs_SOLID); ex.More(); ex.Next(), ++n)
      only = TopoDS::Solid(ex.Current());
    if (n != 1) return nullptr;
    return std::make_unique<Solid>(make_solid(only));
  } catch (const Standard_Failure&) {
    return nullptr;
  }
}

double common_volume(const Solid& a, const Solid& b) {
  try {
    BRepAlgoAPI_Common common;
    if (!run_boolean(common, a, b)) return -1;
    GProp_GProps props;
    BRepGProp::VolumeProperties(common.Shape(), props, 1e-11);  // as Solid::volume
    return std::abs(props.Mass());
  } catch (const Standard_Failure&) {
    return -1;
  }
}

bool write_compound_brep(const std::vector<const Solid*>& solids, const std::string& path,
                         std::string* error) {
  try {
    BRep_Builder b;
    TopoDS_Compound c;
    b.MakeCompound(c);
    for (const Solid* s : solids) b.Add(c, s->impl().solid);
    if (!BRepTools::Write(c, path.c_str())) {
      if (error) *error = "cannot write " + path;
      return false;
    }
    return true;
  } catch (const Standard_Failure& e) {
    if (error) *error = e.GetMessageString() ? e.GetMessageString() : "OCCT failure";
    return false;
  }
}

std::string compound_brep_string(const std::vector<const Solid*>& solids) {
  try {
    BRep_Builder b;
    TopoDS_Compound c;
    b.MakeCompound(c);
    for (const Solid* s : solids) b.Add(c, s->impl().solid);
    std::ostringstream out;
    BRepTools::Write(c, out);
    return out.str();
  } catch (const Standard_Failure&) {
    return std::string();
  }
}

std::vector<Solid> solids_from_brep_string(const std::string& brep) {
  std::vector<Solid> out;
  try {
    TopoDS_Shape shape;
    BRep_Builder b;
    std::istringstream in(brep);
    BRepTools::Read(shape, in, b);
    if (shape.IsNull()) return out;
    for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next())
      out.push_back(make_solid(TopoDS::Solid(e.Current())));
  } catch (const Standard_Failure&) {
    out.clear();
  }
  return out;
}

}  // namespace vorohex::occ
