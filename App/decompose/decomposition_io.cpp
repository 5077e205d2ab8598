#include "decompose/decomposition_io.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

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
  j["status"] = status_name(r.status);
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

bool write_decomposition(const DecompositionResult& r, const std::string& brep_path,
                         const std::string& json_path, std::string* error) {
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
  return true;
}

}  // namespace vorohex::decompose
