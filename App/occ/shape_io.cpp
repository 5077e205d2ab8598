#include "occ/shape_io.h"

#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <Interface_Check.hxx>
#include <Interface_CheckIterator.hxx>
#include <Interface_EntityIterator.hxx>
#include <Interface_Graph.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <ShapeFix_Shape.hxx>
#include <Standard_Failure.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <XSControl_Reader.hxx>
#include <XSControl_WorkSession.hxx>

#include <sys/stat.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <unordered_set>

#include "core/isolated_call.h"
#include "occ/detail/canonical_surfaces.h"
#include "occ/detail/elementary_surfaces.h"
#include "occ/detail/glue.h"
#include "occ/detail/names.h"
#include "occ/solid_impl.h"

namespace vorohex::occ {
namespace {

using core::make_error;
using core::make_info;
using core::make_warning;
using detail::join_names;
using detail::plural;

enum class Format { step, brep, iges, unknown };

std::string lower_extension(const std::string& path) {
  const auto slash = path.find_last_of("/\\");
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext;
}

Format format_of(const std::string& ext) {
  if (ext == ".step" || ext == ".stp") return Format::step;
  if (ext == ".brep" || ext == ".brp") return Format::brep;
  if (ext == ".iges" || ext == ".igs") return Format::iges;
  return Format::unknown;
}

int count(const TopoDS_Shape& shape, TopAbs_ShapeEnum type) {
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(shape, type, map);
  return map.Extent();
}

double signed_volume(const TopoDS_Shape& s) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(s, props);
  return props.Mass();
}

// Edges bounding exactly one face of the shell (a seam counts twice, degenerated edges are
// skipped), named by their index in the edge map of the whole read shape.
std::vector<std::string> free_edges(const TopoDS_Shape& shell, const TopoDS_Shape& whole) {
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(whole, TopAbs_EDGE, edges);
  std::vector<int> uses(edges.Extent() + 1, 0);
  for (TopExp_Explorer f(shell, TopAbs_FACE); f.More(); f.Next())
    for (TopExp_Explorer e(f.Current(), TopAbs_EDGE); e.More(); e.Next())
      ++uses[edges.FindIndex(e.Current())];
  std::vector<std::string> names;
  for (int i = 1; i <= edges.Extent(); ++i)
    if (uses[i] == 1 && !BRep_Tool::Degenerated(TopoDS::Edge(edges(i))))
      names.push_back("Edge" + std::to_string(i));
  return names;
}

// Faces without a surface and edges (not degenerated) without a 3D curve, named by their
// index in the whole shape. Damaged BREP text makes them, and OCCT's validity check
// dereferences the missing geometry (BRepCheck_Edge::InContext; found by fuzzing).
std::vector<std::string> missing_geometry(const TopoDS_Shape& shape) {
  TopTools_IndexedMapOfShape faces, edges;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  TopExp::MapShapes(shape, TopAbs_EDGE, edges);
  std::vector<std::string> names;
  for (int i = 1; i <= faces.Extent(); ++i)
    if (BRep_Tool::Surface(TopoDS::Face(faces(i))).IsNull())
      names.push_back("Face" + std::to_string(i));
  for (int i = 1; i <= edges.Extent(); ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(edges(i));
    double first = 0, last = 0;
    if (!BRep_Tool::Degenerated(edge) && BRep_Tool::Curve(edge, first, last).IsNull())
      names.push_back("Edge" + std::to_string(i));
  }
  return names;
}

// OCCT's BREP reader does not look at the stream state: on text that ends early or holds a
// word where a number belongs, its loops go on reading the failed stream (an edge's list of
// representations ends at a 0 that never comes: it hangs). With exceptions on, the first
// failed read ends the reading (std::ios_base::failure, reported as kBrepMalformed).
TopoDS_Shape read_brep(std::istream& in) {
  in.exceptions(std::ios::failbit | std::ios::badbit);
  TopoDS_Shape shape;
  BRep_Builder builder;
  BRepTools::Read(shape, in, builder);
  return shape;
}

// OCCT's shape healing of a solid that fails its check, in a child process
// (core/isolated_call.h): on a damaged solid found by fuzz_shape_reader it classified points
// without end (BRepTopAdaptor_FClass2d::Perform < ShapeFix_Solid::SolidFromShell), and its
// loops look at no progress indicator. The child sends the repaired solid back as BREP
// text; null when it could not repair it, crashed, or passed the time limit (`why` says).
TopoDS_Solid repaired(const TopoDS_Solid& solid, double time_limit, std::string& why) {
  const core::IsolatedResult run = core::isolated_call(
      [&solid] {
        ShapeFix_Shape fix(solid);
        fix.Perform();
        const TopoDS_Shape result = fix.Shape();
        if (count(result, TopAbs_SOLID) != 1) return std::string();
        TopExp_Explorer ex(result, TopAbs_SOLID);
        if (!BRepCheck_Analyzer(ex.Current()).IsValid()) return std::string();
        std::ostringstream out;
        BRepTools::Write(ex.Current(), out);
        return out.str();
      },
      time_limit > 0 ? core::Progress().with_time_limit(time_limit) : core::Progress());
  if (run.status == core::IsolatedResult::Status::cancelled) {
    std::ostringstream s;
    s << "OCCT's shape healing (ShapeFix) did not finish within " << time_limit << " s";
    why = s.str();
    return TopoDS_Solid();
  }
  if (run.status == core::IsolatedResult::Status::crashed) {
    why = "OCCT's shape healing (ShapeFix) crashed on it (" + run.message + ")";
    return TopoDS_Solid();
  }
  why = "OCCT's shape healing (ShapeFix) could not repair it";
  if (!run.ok() || run.data.empty()) return TopoDS_Solid();
  try {
    std::istringstream in(run.data);
    const TopoDS_Shape shape = read_brep(in);
    if (shape.IsNull() || shape.ShapeType() != TopAbs_SOLID) return TopoDS_Solid();
    return TopoDS::Solid(shape);
  } catch (const std::exception&) {
  } catch (const Standard_Failure&) {
  }
  return TopoDS_Solid();
}

// Whether `converted` is `solid` with other surfaces only: valid, with the same numbers of
// faces, edges and vertices, and its volume within `absolute` + `relative` x the solid's of
// it. Integrated to 1e-9 where `precise` (a B-spline and the surface it is: OCCT's fixed
// order errs on B-splines), else with OCCT's fixed order (the same surfaces, reparametrised:
// the same error on both).
bool same_solid(const TopoDS_Solid& solid, const TopoDS_Solid& converted, double relative,
                double absolute, bool precise) {
  try {
    for (TopAbs_ShapeEnum kind : {TopAbs_FACE, TopAbs_EDGE, TopAbs_VERTEX}) {
      TopTools_IndexedMapOfShape a, b;
      TopExp::MapShapes(solid, kind, a);
      TopExp::MapShapes(converted, kind, b);
      if (a.Extent() != b.Extent()) return false;
    }
    auto volume = [&](const TopoDS_Solid& s) {
      GProp_GProps props;
      if (precise)
        BRepGProp::VolumeProperties(s, props, 1e-9);
      else
        BRepGProp::VolumeProperties(s, props);
      return props.Mass();
    };
    const double v0 = volume(solid), v1 = volume(converted);
    return std::abs(v1 - v0) <= absolute + relative * std::abs(v0) &&
           BRepCheck_Analyzer(converted).IsValid();
  } catch (const Standard_Failure&) {
    return false;
  }
}

// Turned faces stored as surfaces of revolution of a line get the cylinder or cone they
// are (occ/detail/elementary_surfaces.h: the same points, the volume to 1e-7), and B-spline
// faces within 2e-6 of the solid's size of a plane or cylinder that surface
// (occ/detail/canonical_surfaces.h: the volume within their deviation times their area,
// and 1e-6 more, what OCCT's integration of a rational B-spline may miss by: a NURBS
// flanged pipe's 1.4e-7, 160 times the error it reports). Each result is kept only when it
// is the same solid (same_solid); else the solid stays as it was.
TopoDS_Solid with_elementary_surfaces(const TopoDS_Solid& solid, const std::string& where,
                                      ReadResult& r) {
  TopoDS_Solid out = solid;
  const detail::ElementaryResult e = detail::elementary_surfaces(out);
  if (e.converted > 0 && same_solid(out, e.solid, 1e-7, 0, false)) {
    r.diagnostics.push_back(make_info(
        "elementary_surfaces",
        where + " stores " + plural(e.converted, "face") +
            " as surfaces of revolution of a line; they were given the cylinders and cones they "
            "are (same points, same parametrisation) and are meshed as such."));
    out = e.solid;
  }
  const detail::CanonicalResult c = detail::canonical_surfaces(out, 2e-6);
  if (c.converted + c.planes > 0 && same_solid(out, c.solid, 1e-6, c.volume_bound, true)) {
    std::ostringstream m;
    m.precision(2);
    const int n = c.converted + c.planes;
    m << where << " stores " << plural(n, "face")
      << (n == 1 ? " as a B-spline surface" : " as B-spline surfaces") << " within " << c.deviation
      << " of ";
    if (c.converted > 0) m << plural(c.converted, "cylinder");
    if (c.converted > 0 && c.planes > 0) m << " and ";
    if (c.planes > 0) m << plural(c.planes, "plane");
    if (n == 1 && c.snapped > 0)
      m << " (on the cylinder of another of its faces)";
    else if (c.snapped > 0)
      m << " (" << (c.snapped == 1 ? "one" : std::to_string(c.snapped))
        << " of them on the cylinder of another of its faces)";
    m << "; " << (n == 1 ? "it was" : "they were") << " given "
      << (n == 1 ? "that surface" : "those surfaces") << " and meshed as such.";
    r.diagnostics.push_back(make_info("canonical_surfaces", m.str()));
    out = c.solid;
  }
  return out;
}

// Validity of one solid: OCCT's check (with ShapeFix healing when it fails), outward
// orientation, faces. Null (with an error in r) when it cannot be used.
TopoDS_Solid checked_solid(TopoDS_Solid solid, const std::string& where, const ReadOptions& options,
                           ReadResult& r) {
  if (!BRepCheck_Analyzer(solid).IsValid()) {
    // Bad tolerances and similar defects: try OCCT's shape healing before giving up.
    std::string why;
    const TopoDS_Solid fixed = repaired(solid, options.repair_time_limit, why);
    if (fixed.IsNull()) {
      r.diagnostics.push_back(
          make_error("invalid_shape", where +
                                          " holds a solid that fails OCCT's validity check "
                                          "(self-intersecting or broken geometry) and " +
                                          why + "."));
      return TopoDS_Solid();
    }
    solid = fixed;
    r.diagnostics.push_back(make_warning(
        "shape_repaired", where + " holds a solid that failed OCCT's validity check (e.g. "
                                  "tolerances too small for its geometry); it was repaired "
                                  "with OCCT's shape healing (ShapeFix) before meshing."));
  }
  // An inside-out solid has negative volume: turn it, so normals point outwards.
  if (signed_volume(solid) < 0) {
    BRepLib::OrientClosedSolid(solid);
    r.diagnostics.push_back(
        make_info("solid_reoriented", where + " holds an inside-out solid; it was turned."));
  }
  // A shell whose free edges are not detected by incidence (e.g. non-manifold) still fails.
  if (count(solid, TopAbs_FACE) == 0) {
    r.diagnostics.push_back(make_error("no_solid", where + " holds an empty solid."));
    return TopoDS_Solid();
  }
  return with_elementary_surfaces(solid, where, r);
}

// The checks shared by files and strings: one valid, closed solid (or several, when the
// options allow it).
ReadResult analyse(const TopoDS_Shape& shape, const std::string& where,
                   const ReadOptions& options) {
  ReadResult r;
  if (shape.IsNull()) {
    r.diagnostics.push_back(make_error("unreadable_file", where + " contains no shape."));
    return r;
  }
  const std::vector<std::string> broken = missing_geometry(shape);
  if (!broken.empty()) {
    r.diagnostics.push_back(
        make_error("invalid_shape",
                   where + " holds faces without surface or edges without curve (" +
                       join_names(broken, 8) + "); OCCT can neither check nor repair such a shape.",
                   broken));
    return r;
  }
  const int solids = count(shape, TopAbs_SOLID);
  const int shells = count(shape, TopAbs_SHELL);
  const int faces = count(shape, TopAbs_FACE);
  if (solids > 1 && !options.several_solids) {
    r.diagnostics.push_back(make_error(
        "several_solids",
        where + " contains " + plural(solids, "solid") + "; this command takes one solid."));
    return r;
  }
  if (solids > 1) {
    std::vector<TopoDS_Solid> checked;
    int k = 0;
    for (TopExp_Explorer ex(shape, TopAbs_SOLID); ex.More(); ex.Next()) {
      const TopoDS_Solid s = checked_solid(
          TopoDS::Solid(ex.Current()), where + " (solid " + std::to_string(++k) + ")", options, r);
      if (s.IsNull()) return r;
      checked.push_back(s);
    }
    return detail::glue(checked, where, std::move(r));
  }
  TopoDS_Solid solid;
  if (solids == 1) {
    TopExp_Explorer ex(shape, TopAbs_SOLID);
    solid = TopoDS::Solid(ex.Current());
  } else if (shells == 1) {
    TopExp_Explorer ex(shape, TopAbs_SHELL);
    const TopoDS_Shell shell = TopoDS::Shell(ex.Current());
    const std::vector<std::string> open = free_edges(shell, shape);
    if (!open.empty() && faces == 1) {  // a lone face (a surface): no volume at all
      r.diagnostics.push_back(
          make_error("no_solid", where + " contains 1 face and no solid (a surface bounded by " +
                                     plural(int(open.size()), "edge") + ", " + join_names(open, 8) +
                                     ": it encloses no volume)."));
      return r;
    }
    if (!open.empty()) {
      r.diagnostics.push_back(make_error(
          "open_shell",
          where + " holds a shell that is not closed: " + plural(int(open.size()), "edge") +
              " bound only one face (" + join_names(open, 8) + ").",
          open));
      return r;
    }
    BRepBuilderAPI_MakeSolid make(shell);
    if (!make.IsDone()) {
      r.diagnostics.push_back(make_error(
          "invalid_shape", where + " holds a closed shell that cannot be made a solid."));
      return r;
    }
    solid = make.Solid();
    BRepLib::OrientClosedSolid(solid);
    r.diagnostics.push_back(make_info("closed_shell_made_solid",
                                      where + " holds a closed shell; it was made a solid."));
  } else {
    std::string what;
    if (shells > 1)
      what = plural(shells, "shell");
    else if (faces > 0)
      what = plural(faces, "face");
    else if (count(shape, TopAbs_EDGE) > 0)
      what = plural(count(shape, TopAbs_EDGE), "edge");
    else
      what = "no faces";
    r.diagnostics.push_back(make_error("no_solid", where + " contains " + what + " and no solid."));
    return r;
  }
  solid = checked_solid(solid, where, options, r);
  if (solid.IsNull()) return r;
  r.solid = std::make_unique<Solid>(make_solid_impl(solid));
  return r;
}

// Entities that OCCT failed to load (an unresolved reference, an entity of the wrong type, a
// number that is not one) keep null references, which OCCT's translators (StepToGeom,
// StepToTopoDS, IGESToBRep) dereference: they crash. A file in which an entity of geometry
// or topology failed, or an entity that one of them refers to, is refused before the
// transfer. Failures of entities the shape does not need (presentation: styles, colours,
// point markers, layers; metadata: units, products, names, validation properties; unknown
// entity types) are a warning naming them: the transfer of the shape never reads them, and
// every CAD tool opens such files (Gmsh's benchmark universal joint has 182 point styles with
// an illegal marker).
bool is_step_shape_entity(const std::string& type) {
  if (type.rfind("StepGeom_", 0) == 0 || type.rfind("StepShape_", 0) == 0) return true;
  if (type.rfind("StepRepr_", 0) != 0) return false;
  // Representations and their relations carry the shape and the placements of an
  // assembly's parts; their properties and descriptive items do not.
  for (const char* metadata : {"Property", "Descriptive", "Measure", "Value", "Integer", "Real",
                               "ShapeAspect", "Characterized", "ProductDefinitionShape"})
    if (type.find(metadata) != std::string::npos) return false;
  return true;
}
bool is_iges_shape_entity(const std::string& type) {
  return type.rfind("IGESGeom_", 0) == 0 || type.rfind("IGESSolid_", 0) == 0;
}

// Sorts the entities that failed to load into those the shape needs (an error in r, true:
// the file is refused) and the others (a warning, ignored_entities, in warnings).
bool refuse_damaged(const XSControl_Reader& reader, bool (*is_shape_entity)(const std::string&),
                    const std::string& where, const char* kind, ReadResult& r,
                    std::vector<core::Diagnostic>& warnings) {
  const Handle(Interface_InterfaceModel) model = reader.Model();
  Interface_CheckIterator checks = reader.WS()->ModelCheckList(false);  // load checks only
  std::vector<std::string> failures, ignored;
  std::map<std::string, int> ignored_types;
  for (checks.Start(); checks.More(); checks.Next()) {
    const Handle(Interface_Check)& check = checks.Value();
    if (!check->HasFailed() || checks.Number() < 1 || checks.Number() > model->NbEntities())
      continue;
    const Handle(Standard_Transient) entity = model->Value(checks.Number());
    const std::string type = entity->DynamicType()->Name();
    // Needed: an entity of the shape, or one that an entity of the shape refers to, other
    // than a representation context (its units and uncertainty are metadata: HexMe's i12 has
    // an SI unit with a wrong parameter count, which the translator copes with).
    bool needed = is_shape_entity(type);
    for (Interface_EntityIterator users = reader.WS()->Graph().Sharings(entity);
         !needed && users.More(); users.Next()) {
      const std::string user = users.Value()->DynamicType()->Name();
      needed = is_shape_entity(user) && user.find("Context") == std::string::npos;
    }
    const std::string what =
        std::string(model->StringLabel(entity)->ToCString()) + " " + type + ": " + check->CFail(1);
    if (needed) {
      failures.push_back(what);
    } else {
      ignored.push_back(what);
      ++ignored_types[type];
    }
  }
  if (!failures.empty()) {
    r.diagnostics.push_back(make_error(
        "unreadable_file", where + " is a damaged " + kind +
                               " file: " + std::to_string(failures.size()) +
                               (failures.size() == 1 ? " entity" : " entities") +
                               " of its shape fail to load (" + join_names(failures, 3) + ")."));
    return true;
  }
  if (!ignored.empty()) {
    std::vector<std::string> types;
    for (const auto& [type, n] : ignored_types) types.push_back(std::to_string(n) + " " + type);
    warnings.push_back(make_warning(
        "ignored_entities",
        where + ": " + std::to_string(ignored.size()) +
            (ignored.size() == 1 ? " entity" : " entities") + " that the shape does not need " +
            (ignored.size() == 1 ? "fails" : "fail") + " to load and " +
            (ignored.size() == 1 ? "is" : "are") + " ignored (" + join_names(types, 5) +
            "; first: " + join_names(ignored, 2) + ")."));
  }
  return false;
}

// Instance names (#n) of a STEP file given twice, referred to but never given, or referred
// to by their own entity. OCCT's reader resolves the references of a file with a name given
// twice in a second pass over arrays it does not initialise (StepData_StepReaderData::
// SetEntityNumbers), which, depending on what the heap held, never ends; with a dangling
// reference, or an oriented edge that is its own edge, its own check of the file recurses
// without end (StepShape_OrientedEdge::EdgeStart). All found by fuzzing; names are unique
// and resolved in ISO 10303-21 files (SCOPE blocks aside: then this says nothing).
// Returns "" or what is wrong.
std::string step_name_problem(std::istream& in) {
  std::unordered_set<long long> names, references;
  enum { statement_start, name, before_equals, body } phase = statement_start;
  bool quoted = false, comment = false, reference = false, named = false;
  long long id = 0, ref = 0;
  char previous = 0;
  int scope = 0;  // characters of "&SCOPE" just seen outside strings and comments
  for (char c; in.get(c); previous = c) {
    if (quoted) {
      quoted = c != '\'';  // a doubled quote reopens at once
      continue;
    }
    if (comment) {
      comment = !(previous == '*' && c == '/');
      continue;
    }
    if (c == '/' && in.peek() == '*') {
      comment = true;
      in.get(c);
      c = 0;  // so that "/*/" does not close it
      continue;
    }
    scope = c == "&SCOPE"[scope] ? scope + 1 : c == '&' ? 1 : 0;
    if (scope == 6) return "";
    const bool digit = c >= '0' && c <= '9';
    if (reference && (!digit || ref >= (1LL << 50))) {
      if (named && ref == id) return "#" + std::to_string(id) + " refers to itself";
      references.insert(ref);
      reference = false;
    } else if (reference) {
      ref = 10 * ref + (c - '0');
    }
    const bool space = std::isspace(static_cast<unsigned char>(c)) != 0;
    if (c == ';') {
      phase = statement_start;
    } else if (c == '\'') {
      quoted = true;
      phase = body;
    } else if (phase == statement_start && !space) {
      phase = c == '#' ? name : body;
      id = 0;
      named = false;
    } else if (phase == name && digit && id < (1LL << 50)) {
      id = 10 * id + (c - '0');
    } else if ((phase == name || phase == before_equals) && c == '=') {
      if (!names.insert(id).second) return "the name #" + std::to_string(id) + " is given twice";
      named = true;
      phase = body;
    } else if (phase == name || phase == before_equals) {
      phase = space ? before_equals : body;
    } else if (phase == body && c == '#') {
      reference = true;
      ref = 0;
    }
  }
  // Unclosed, the rest would be hidden from this scan (OCCT's parser goes on after it).
  if (quoted || comment) return "a string or a comment is never closed";
  for (long long r : references)
    if (!names.count(r)) return "it refers to #" + std::to_string(r) + ", which it never gives";
  return "";
}

// OCCT's IGES parser keeps static state from the previous file (IGESFile): parameter lines
// it reads before any directory entry are filed under the previous file's entries, freed by
// then, and it crashes (iges_newparam; found by fuzzing). It cuts the text into records of
// 80 columns whatever the line ends, so only files made of such records, column 73 holding
// the sections S, G, D, P, T in this order, are given to it.
bool iges_records_in_order(std::istream& in) {
  const std::string order = "SGDPT";
  std::size_t last = 0;
  bool directory = false;
  std::string line;
  while (std::getline(in, line, '\n')) {
    std::istringstream records(line);  // lone \r ends records too
    for (std::string record; std::getline(records, record, '\r');) {
      if (record.find_first_not_of(" \t") == std::string::npos) continue;
      const std::size_t section = record.size() == 80 ? order.find(record[72]) : std::string::npos;
      if (section == std::string::npos || section < last || (record[72] == 'P' && !directory))
        return false;
      last = section;
      directory = directory || record[72] == 'D';
    }
  }
  return true;
}

const char* const kBrepMalformed = "the text ends early or holds a word where a number belongs";

// OCCT's BREP reader dereferences the basis of a trimmed, offset, extrusion or revolution
// curve or surface without looking (null when the basis has an unknown type: found by
// fuzz_shape_reader, bench/fuzz/README.md). Short of parsing the geometry sections
// ourselves, the text is read once in a child process (core/isolated_call.h): a crash
// there is this message ("" when the reader came back, with or without an exception),
// and the caller's process reads it only then.
std::string brep_reader_crash(const std::string& text) {
  const core::IsolatedResult probe = core::isolated_call([&text] {
    try {
      std::istringstream in(text);
      read_brep(in);
    } catch (...) {  // the caller's own read reports it
    }
    return std::string();
  });
  if (probe.status != core::IsolatedResult::Status::crashed) return "";
  return "OCCT's BREP reader crashed on it (" + probe.message +
         "); most often a trimmed, offset, extrusion or revolution curve or surface whose "
         "basis is missing or of an unknown type";
}

bool only_whitespace(std::ifstream& in) {
  char buf[4096];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i)
      if (!std::isspace(static_cast<unsigned char>(buf[i]))) return false;
  }
  return true;
}

// OCCT's readers print their own notes on stdout through the default messenger (a STEP
// file with a header and no data: "Interruption ReadFile par Exception ... Abandon", in
// French, in colour; a syntax error: "**** ERR StepFile : Undefined Parsing: Line 3: ...",
// in red, before our error). While one of these is alive the messenger's printers are set
// aside and a collector takes their place: what is wrong with the file is said by our
// diagnostics, with the reader's failures (`failures()`) where no shape could be read.
class FailureCollector : public Message_Printer {
 public:
  mutable std::vector<std::string> failures;  // send() is const in OCCT

 protected:
  void send(const TCollection_AsciiString& text, const Message_Gravity gravity) const override {
    if (gravity < Message_Fail || failures.size() >= 3) return;
    std::string t = text.ToCString();
    // "**** ERR StepFile : Undefined Parsing: Line 3: ...    ****" -> its words.
    const auto trim = [](std::string& x) {
      const std::size_t a = x.find_first_not_of(" *\t\n\r");
      const std::size_t b = x.find_last_not_of(" *\t\n\r");
      x = a == std::string::npos ? std::string() : x.substr(a, b - a + 1);
    };
    trim(t);
    if (t.rfind("ERR ", 0) == 0) t = t.substr(4);
    if (!t.empty()) failures.push_back(t);
  }
};

class QuietReaders {
 public:
  QuietReaders() : collector_(new FailureCollector) {
    const Handle(Message_Messenger)& m = Message::DefaultMessenger();
    for (Message_SequenceOfPrinters::Iterator it(m->Printers()); it.More(); it.Next())
      set_aside_.push_back(it.Value());
    for (const Handle(Message_Printer) & p : set_aside_) m->RemovePrinter(p);
    m->AddPrinter(collector_);
  }
  ~QuietReaders() {
    const Handle(Message_Messenger)& m = Message::DefaultMessenger();
    m->RemovePrinter(collector_);
    for (const Handle(Message_Printer) & p : set_aside_) m->AddPrinter(p);
  }
  QuietReaders(const QuietReaders&) = delete;
  QuietReaders& operator=(const QuietReaders&) = delete;
  // What the reader reported as failures, "; "-joined (at most three), or empty.
  std::string failures() const {
    std::string out;
    for (const std::string& f : collector_->failures) out += (out.empty() ? "" : "; ") + f;
    return out;
  }

 private:
  Handle(FailureCollector) collector_;
  std::vector<Handle(Message_Printer)> set_aside_;
};

}  // namespace

ReadResult read_solid(const std::string& path, const ReadOptions& options) {
  ReadResult r;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
    r.diagnostics.push_back(make_error(
        "file_not_found",
        "The file " + path +
            (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode) ? " is a folder, not a file."
                                                                   : " does not exist.")));
    return r;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    r.diagnostics.push_back(
        make_error("unreadable_file", "The file " + path + " cannot be opened."));
    return r;
  }
  if (only_whitespace(in)) {
    r.diagnostics.push_back(make_error("empty_file", "The file " + path + " is empty."));
    return r;
  }
  const std::string ext = lower_extension(path);
  const Format format = format_of(ext);
  if (format == Format::unknown) {
    r.diagnostics.push_back(
        make_error("unsupported_format", "The file " + path + " has the unsupported extension '" +
                                             (ext.empty() ? "(none)" : ext) +
                                             "'; use .step/.stp, .brep/.brp or .iges/.igs."));
    return r;
  }
  const std::string where = "The file " + path;
  const char* kind = format == Format::step ? "STEP" : format == Format::iges ? "IGES" : "BREP";
  TopoDS_Shape shape;
  std::vector<core::Diagnostic> warnings;  // entities of the file the shape does not need
  try {
    bool read = false;
    std::string reader_failures;  // what OCCT's STEP or IGES reader reported as failures
    if (format == Format::step) {
      std::ifstream file(path, std::ios::binary);
      const std::string names = step_name_problem(file);
      if (!names.empty()) {
        r.diagnostics.push_back(
            make_error("unreadable_file", where + " is a damaged STEP file: " + names + "."));
        return r;
      }
      const QuietReaders quiet;
      STEPControl_Reader reader;
      if (reader.ReadFile(path.c_str()) == IFSelect_RetDone) {
        if (refuse_damaged(reader, is_step_shape_entity, where, kind, r, warnings)) return r;
        if (reader.TransferRoots() > 0) {
          shape = reader.OneShape();
          read = !shape.IsNull();
        }
      }
      reader_failures = quiet.failures();
    } else if (format == Format::iges) {
      std::ifstream file(path, std::ios::binary);
      if (!iges_records_in_order(file)) {
        r.diagnostics.push_back(make_error(
            "unreadable_file", where + " is a damaged IGES file: not all lines are records of "
                                       "80 columns with the sections S, G, D, P, T in order "
                                       "(column 73)."));
        return r;
      }
      const QuietReaders quiet;
      IGESControl_Reader reader;
      if (reader.ReadFile(path.c_str()) == IFSelect_RetDone) {
        if (refuse_damaged(reader, is_iges_shape_entity, where, kind, r, warnings)) return r;
        if (reader.TransferRoots() > 0) {
          shape = reader.OneShape();
          read = !shape.IsNull();
        }
      }
      reader_failures = quiet.failures();
    } else {
      // Read once: the child probes the same text the caller then parses (a file that
      // changed in between could crash the caller).
      std::ifstream file(path, std::ios::binary);
      const std::string text((std::istreambuf_iterator<char>(file)),
                             std::istreambuf_iterator<char>());
      const std::string crash = brep_reader_crash(text);
      if (!crash.empty()) {
        r.diagnostics.push_back(
            make_error("unreadable_file", where + " is a damaged BREP file: " + crash + "."));
        return r;
      }
      std::istringstream in(text);
      shape = read_brep(in);
      read = !shape.IsNull();
    }
    if (!read) {
      r.diagnostics.push_back(make_error(
          "unreadable_file",
          where + " is not a readable " + kind + " file (no shape could be read" +
              (reader_failures.empty() ? std::string() : "; the reader: " + reader_failures) +
              ")."));
      return r;
    }
    ReadResult analysed = analyse(shape, where, options);
    analysed.diagnostics.insert(analysed.diagnostics.begin(), warnings.begin(), warnings.end());
    return analysed;
  } catch (const std::ios_base::failure&) {
    r.diagnostics.push_back(make_error("unreadable_file", where + " is not a readable " + kind +
                                                              " file: " + kBrepMalformed + "."));
  } catch (const Standard_Failure& e) {
    r.diagnostics.push_back(make_error(
        "unreadable_file", where + " could not be read as " + kind + ": " + e.GetMessageString()));
  } catch (const std::exception& e) {
    r.diagnostics.push_back(
        make_error("unreadable_file", where + " could not be read as " + kind + ": " + e.what()));
  }
  r.solid.reset();
  return r;
}

ReadResult read_solid_from_brep_string(const std::string& brep, const ReadOptions& options) {
  ReadResult r;
  const std::string where = "The BREP string";
  if (std::all_of(brep.begin(), brep.end(),
                  [](unsigned char ch) { return std::isspace(ch) != 0; })) {
    r.diagnostics.push_back(make_error("empty_file", where + " is empty."));
    return r;
  }
  const std::string crash = brep_reader_crash(brep);
  if (!crash.empty()) {
    r.diagnostics.push_back(
        make_error("unreadable_file", where + " is not valid BREP text: " + crash + "."));
    return r;
  }
  try {
    std::istringstream in(brep);
    const TopoDS_Shape shape = read_brep(in);
    if (shape.IsNull()) {
      r.diagnostics.push_back(make_error(
          "unreadable_file", where + " is not valid BREP text (no shape could be read)."));
      return r;
    }
    return analyse(shape, where, options);
  } catch (const std::ios_base::failure&) {
    r.diagnostics.push_back(
        make_error("unreadable_file", where + " is not valid BREP text: " + kBrepMalformed + "."));
  } catch (const Standard_Failure& e) {
    r.diagnostics.push_back(make_error(
        "unreadable_file", where + " could not be read as BREP: " + e.GetMessageString()));
  } catch (const std::exception& e) {
    r.diagnostics.push_back(
        make_error("unreadable_file", where + " could not be read as BREP: " + e.what()));
  }
  r.solid.reset();
  return r;
}

ReadResult glue_solids(const std::vector<const Solid*>& solids, const std::string& where,
                       const GlueOptions& options) {
  std::vector<TopoDS_Solid> shapes;
  for (const Solid* s : solids)
    for (const TopoDS_Solid& part : s->impl().parts) shapes.push_back(part);
  try {
    return detail::glue(shapes, where, ReadResult(), options);
  } catch (const Standard_Failure& e) {
    ReadResult r;
    r.diagnostics.push_back(make_error(
        "invalid_shape", where + ": OCCT failed gluing the solids (" +
                             std::string(e.GetMessageString() ? e.GetMessageString() : "") + ")."));
    return r;
  }
}

bool write_solid(const Solid& solid, const std::string& path, std::string* error) {
  const std::string ext = lower_extension(path);
  const Format format = format_of(ext);
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  try {
    if (format == Format::step) {
      STEPControl_Writer writer;
      if (writer.Transfer(solid.impl().solid, STEPControl_AsIs) != IFSelect_RetDone)
        return fail("cannot convert the solid to STEP for " + path);
      if (writer.Write(path.c_str()) != IFSelect_RetDone)
        return fail("cannot write the STEP file " + path);
      return true;
    }
    if (format == Format::brep) {
      if (!BRepTools::Write(solid.impl().solid, path.c_str()))
        return fail("cannot write the BREP file " + path);
      return true;
    }
    return fail("cannot write " + path + ": use the extension .step, .stp or .brep");
  } catch (const Standard_Failure& e) {
    return fail("cannot write " + path + ": " + e.GetMessageString());
  }
}

}  // namespace vorohex::occ
