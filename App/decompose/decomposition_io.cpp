#include "decompose/decomposition_io.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "mesh/mesh_sub_volumes.h"
#include "mesh/sweep.h"
#include "occ/shape_io.h"
#include "occ/split_solid.h"

namespace vorohex::decompose {

namespace {

const char* status_name(DecompositionStatus s) {
  switch (s) {
    case DecompositionStatus::ok:
      return "ok";
    case DecompositionStatus::partial:
      return "partial";
    case DecompositionStatus::failed:
      return "failed";
  }
  return "?";
}

std::string face_name(core::FaceId f) {
  return f.valid() ? core::entity_name(f) : std::string();
}

}  // namespace

std::string decomposition_json(const DecompositionResult& r) {
  using nlohmann::json;
  json j;
  j["method"] = "voronoi";
  j["status"] = status_name(r.status);
  if (r.status == DecompositionStatus::partial) j["partial_reason"] = partial_reason(r);
  j["counts"] = {{"sub_volumes_before_merge", r.stats.sub_volumes_before_merge},
                 {"sub_volumes", r.stats.sub_volumes},
                 {"decomposition_faces", r.stats.decomposition_faces},
                 {"quads", r.stats.quads},
                 {"edges_of_interest", r.stats.edges_of_interest},
                 {"projected_edges", r.stats.projected_edges}};
  j["sub_volumes"] = json::array();
  for (std::size_t i = 0; i < r.sub_volumes.size(); ++i) {
    const SubVolume& sv = r.sub_volumes[i];
    json s = {{"id", i},
              {"type", sub_volume_type_name(sv.type)},
              {"scheme", scheme_name(sv.scheme)},
              {"reason", sv.reason},
              {"volume", sv.volume},
              {"merged_from", sv.merged_from},
              {"f_s_face", sv.fs_face >= 0 ? json(sv.fs_face) : json(nullptr)}};
    if (sv.scheme == Scheme::sweep) {
      s["source"] = face_name(sv.source);
      s["target"] = face_name(sv.target);
    }
    // The virtual topology: where each of its faces and edges lies in the original solid.
    s["faces"] = json::array();
    for (const VirtualFace& vf : r.topology.faces)
      if (vf.sub_volume == int(i))
        s["faces"].push_back(
            {{"face", face_name(vf.face)},
             {"on", vf.original.valid() ? json(face_name(vf.original)) : json(nullptr)},
             {"decomposition_face",
              vf.decomposition_face >= 0 ? json(vf.decomposition_face) : json(nullptr)}});
    s["edges"] = json::array();
    for (const VirtualEdge& ve : r.topology.edges)
      if (ve.sub_volume == int(i))
        s["edges"].push_back(
            {{"edge", "Edge" + std::to_string(ve.edge.value())},
             {"on", ve.original.valid()        ? json("Edge" + std::to_string(ve.original.value()))
                    : ve.original_face.valid() ? json(face_name(ve.original_face))
                                               : json(nullptr)}});
    j["sub_volumes"].push_back(s);
  }
  j["decomposition_faces"] = json::array();
  for (std::size_t i = 0; i < r.faces.size(); ++i) {
    const DecompositionFace& f = r.faces[i];
    std::set<std::string> governors;
    for (int q : f.quads)
      for (const auto& g : r.quads[q].governors) governors.insert(g.name());
    j["decomposition_faces"].push_back({{"id", i},
                                        {"sub_volumes", {f.sub_volumes[0], f.sub_volumes[1]}},
                                        {"edges", f.num_edges},
                                        {"area", f.area},
                                        {"min_angle", f.min_angle},
                                        {"voronoi_elements", f.elements},
                                        {"governors", governors}});
  }
  j["edges"] = json::array();
  for (const ClassifiedEdge& e : r.edges) {
    if (!e.interest && e.type != EdgeType::tc && e.type != EdgeType::t3) continue;
    json targets = json::array();
    for (const auto& t : e.targets) targets.push_back(t.entity.name());
    j["edges"].push_back({{"voronoi_id", e.element},
                          {"type", detail::edge_type_name(e.type)},
                          {"targets", targets}});
  }
  j["vertices"] = json::array();
  for (const TreatedVertex& v : r.vertices) {
    json rects = json::array();
    for (const auto& rc : v.rectangles) rects.push_back({rc.a.name(), rc.b.name()});
    j["vertices"].push_back({{"voronoi_id", v.element}, {"row", v.row}, {"rectangles", rects}});
  }
  j["diagnostics"] = json::array();
  for (const auto& d : r.diagnostics)
    j["diagnostics"].push_back({{"severity", core::severity_name(d.severity)},
                                {"code", d.code},
                                {"message", d.message},
                                {"entities", d.entities}});
  j["stats"] = {{"seconds", r.stats.seconds}};
  return j.dump(2);
}

std::string decomposition_vtp(const DecompositionResult& r) {
  std::ostringstream pts, conn, offs, face, side_a, side_b, element, kind;
  pts.precision(12);
  int np = 0, cells = 0;
  for (std::size_t f = 0; f < r.faces.size(); ++f)
    for (int q : r.faces[f].quads) {
      if (q < 0 || q >= static_cast<int>(r.quads.size())) continue;
      const DecompositionQuad& quad = r.quads[q];
      if (quad.points.size() < 3) continue;
      for (const Vec3& p : quad.points) {
        pts << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
        conn << np++ << ' ';
      }
      offs << np << ' ';
      face << f << ' ';
      side_a << r.faces[f].sub_volumes[0] << ' ';
      side_b << r.faces[f].sub_volumes[1] << ' ';
      element << quad.element << ' ';
      kind << (quad.kind == "rectangle" ? 1 : 0) << ' ';
      ++cells;
    }
  auto array = [](const char* name, const std::ostringstream& values) {
    return std::string("<DataArray type=\"Int32\" Name=\"") + name + "\" format=\"ascii\">" +
           values.str() + "</DataArray>\n";
  };
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<PolyData>\n"
      << "<Piece NumberOfPoints=\"" << np << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
      << "NumberOfStrips=\"0\" NumberOfPolys=\"" << cells << "\">\n"
      << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n"
      << pts.str() << "</DataArray></Points>\n"
      << "<Polys>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" << conn.str()
      << "</DataArray>\n"
      << "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" << offs.str()
      << "</DataArray>\n</Polys>\n"
      << "<CellData Scalars=\"face\">\n"
      << array("face", face) << array("sub_volume_a", side_a) << array("sub_volume_b", side_b)
      << array("voronoi_element", element) << array("rectangle", kind)
      << "</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  return out.str();
}

bool write_decomposition(const DecompositionResult& r, const std::string& brep_path,
                         const std::string& json_path, std::string* error,
                         const std::string& vtp_path) {
  if (!brep_path.empty()) {
    std::vector<const occ::Solid*> solids;
    for (const SubVolume& sv : r.sub_volumes) solids.push_back(sv.solid.get());
    if (!occ::write_compound_brep(solids, brep_path, error)) return false;
  }
  if (!json_path.empty()) {
    std::ofstream out(json_path);
    out << decomposition_json(r) << "\n";
    if (!out) {
      if (error) *error = "cannot write " + json_path;
      return false;
    }
  }
  if (!vtp_path.empty()) {
    std::ofstream out(vtp_path);
    out << decomposition_vtp(r);
    if (!out) {
      if (error) *error = "cannot write " + vtp_path;
      return false;
    }
  }
  return true;
}

PlaneCutSchemes plane_cut_schemes(const PlaneCutResult& cut, bool multisweep) {
  PlaneCutSchemes out;
  out.schemes.assign(cut.pieces.size(), "");
  out.reasons.assign(cut.pieces.size(), "");
  if (cut.pieces.empty()) return out;
  std::vector<const occ::Solid*> pieces;
  for (const occ::Solid& s : cut.pieces) pieces.push_back(&s);
  const occ::ReadResult glued = occ::glue_solids(pieces, "The set of pieces");
  if (!glued.ok()) {
    for (const core::Diagnostic& d : glued.diagnostics)
      if (d.severity == core::Severity::error) {
        out.glue_error = d.message;
        break;
      }
    if (out.glue_error.empty()) out.glue_error = "the pieces could not be glued";
    return out;
  }
  // Solids of revolution too: a cut gives them only where it allowed them (the cylinders at
  // concave fillets' feet); sweeps whose linking sides carry their neighbours' imprints, as
  // the mesher takes them (a fillet's strip ended by mitres).
  const mesh::SubVolumePlan plan = mesh::plan_sub_volumes(*glued.solid, multisweep, true, true);
  out.ends.assign(cut.pieces.size(), {});
  for (std::size_t i = 0; i < plan.schemes.size() && i < out.schemes.size(); ++i) {
    out.schemes[i] = plan.schemes[i];
    out.reasons[i] = plan.reasons[i];
    if (out.schemes[i] != "sweep") continue;
    const mesh::SweepApplicability sweep = mesh::sweep_applicable(cut.pieces[i]);
    if (sweep.ok) out.ends[i] = {sweep.source, sweep.target};
  }
  return out;
}

std::string plane_cuts_json(const PlaneCutResult& cut, const PlaneCutSchemes& schemes) {
  using nlohmann::json;
  json j;
  j["method"] = "plane-cuts";
  j["status"] = cut.ok ? "ok" : "failed";
  j["counts"] = {{"planes", cut.planes},
                 {"cylinders", cut.cylinders},
                 {"sub_volumes_before_merge", cut.pieces_before_merge},
                 {"sub_volumes", cut.pieces.size()}};
  j["sub_volumes"] = json::array();
  for (std::size_t i = 0; i < cut.pieces.size(); ++i) {
    const std::string scheme = i < schemes.schemes.size() ? schemes.schemes[i] : "";
    std::string reason = i < schemes.reasons.size() ? schemes.reasons[i] : "";
    if (scheme.empty() && reason.empty()) reason = schemes.glue_error;
    const bool ends = i < schemes.ends.size() && schemes.ends[i].first.valid();
    // A sweep says which way it sweeps: its source and target among the piece's own faces
    // (the sub-volume's Face2, as FreeCAD numbers the piece).
    if (!scheme.empty() && reason.empty())
      reason = (scheme == "map"          ? std::string("a topological hexahedron")
                : scheme == "multisweep" ? std::string("prismatic: a multisweep along its axis")
                                         : "a " + scheme) +
               (ends ? " from its " + core::entity_name(schemes.ends[i].first) + " to its " +
                           core::entity_name(schemes.ends[i].second)
                     : std::string()) +
               " once glued to the other pieces";
    j["sub_volumes"].push_back({{"id", i},
                                {"scheme", scheme.empty() ? "none" : scheme},
                                {"reason", reason},
                                {"volume", cut.pieces[i].volume()}});
    if (ends) {
      j["sub_volumes"].back()["source"] = core::entity_name(schemes.ends[i].first);
      j["sub_volumes"].back()["target"] = core::entity_name(schemes.ends[i].second);
    }
  }
  j["knife_edges"] = cut.knife_edges;
  j["merges_checked_each"] = cut.merges_checked_each;
  j["cut_kind"] = cut_kind_text(cut);  // "the faces at its concave edges", ...
  j["cut_along"] = used_surfaces_text(cut, 4);
  j["cut_surfaces"] = json::array();
  for (std::size_t i = 0; i < cut.surfaces.size(); ++i) {
    const CutSurface& c = cut.surfaces[i];
    json edges = json::array();
    for (core::EdgeId e : c.edges) edges.push_back(core::entity_name(e));
    j["cut_surfaces"].push_back({{"id", i},
                                 {"kind", c.cylinder      ? "cylinder"
                                          : c.tangent     ? "tangent_plane"
                                          : c.around_hole ? "hole_plane"
                                          : c.at_foot     ? "foot_plane"
                                                          : "plane"},
                                 {"face", core::entity_name(c.face)},
                                 {"concave_edges", edges},
                                 {"used", c.used}});
  }
  j["decomposition_faces"] = json::array();
  j["diagnostics"] = json::array();
  if (!cut.ok)
    j["diagnostics"].push_back({{"severity", "error"},
                                {"code", "plane_cuts_failed"},
                                {"message", "The plane cuts failed: " + cut.why_not + "."},
                                {"entities", json::array()}});
  if (!left_out_text(cut).empty())
    j["diagnostics"].push_back({{"severity", "info"},
                                {"code", "cut_surfaces_left_out"},
                                {"message",
                                 "OCCT's cut along all surfaces of the concave edges at once "
                                 "failed, so they were added one at a time; left out, their "
                                 "concave edges not cut at: " +
                                     left_out_text(cut) + "."},
                                {"entities", json::array()}});
  if (!schemes.glue_error.empty())
    j["diagnostics"].push_back({{"severity", "warning"},
                                {"code", "pieces_not_glued"},
                                {"message", schemes.glue_error},
                                {"entities", json::array()}});
  return j.dump(2);
}

std::string whole_solid_json(Scheme scheme, const std::string& reason, double volume,
                             std::pair<core::FaceId, core::FaceId> ends) {
  using nlohmann::json;
  json j;
  j["method"] = "whole";
  j["status"] = "ok";
  j["counts"] = {{"sub_volumes_before_merge", 1}, {"sub_volumes", 1}, {"decomposition_faces", 0}};
  j["sub_volumes"] = json::array();
  j["sub_volumes"].push_back({{"id", 0},
                              {"scheme", scheme_name(scheme)},
                              {"reason", reason},
                              {"volume", volume},
                              {"merged_from", 1}});
  if (ends.first.valid() && ends.second.valid()) {
    j["sub_volumes"][0]["source"] = core::entity_name(ends.first);
    j["sub_volumes"][0]["target"] = core::entity_name(ends.second);
  }
  j["decomposition_faces"] = json::array();
  j["diagnostics"] = json::array();
  j["diagnostics"].push_back({{"severity", "info"},
                              {"code", "not_cut"},
                              {"message", std::string("Not cut: the mesher meshes it whole (") +
                                              scheme_name(scheme) + ": " + reason + ")."},
                              {"entities", json::array()}});
  return j.dump(2);
}

}  // namespace vorohex::decompose
