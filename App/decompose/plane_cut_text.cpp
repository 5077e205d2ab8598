// The words that say why a plane cut is where it is (PlaneCutResult's surfaces): the
// surfaces used, the kinds of cut, the ones left out.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "decompose/plane_cuts.h"

namespace vorohex::decompose {

std::string surface_text(const CutSurface& s, bool with_edges) {
  std::string t = std::string(s.cylinder && s.ring      ? "a cylinder around the pocket rounded by "
                              : s.cylinder && s.at_foot ? "the cylinder through the foot of "
                              : s.cylinder              ? "the cylinder of "
                              : s.tangent               ? "the plane tangent to the cylinder of "
                              : s.around_hole           ? "a plane around the hole of "
                              : s.beyond  ? "a plane as far beyond the wall as the foot of "
                              : s.mitre   ? "the mitre plane of "
                              : s.corner  ? "the plane where a strip turns round "
                              : s.at_foot ? "the plane across the foot of "
                                          : "the plane of ") +
                  core::entity_name(s.face);
  if (!with_edges || s.edges.empty()) return t;
  t += " (at ";
  for (std::size_t k = 0; k < s.edges.size(); ++k)
    t += (k ? ", " : "") + core::entity_name(s.edges[k]);
  return t + ")";
}

std::string used_surfaces_text(const PlaneCutResult& cut, std::size_t at_most, bool with_edges) {
  // The planes of fillets' strips are named once per fillet, with their mitres counted ("the
  // strips of Face3 and Face7 (across their feet and as far beyond their walls), ended at 4
  // mitre planes").
  std::vector<core::FaceId> strips, corners;
  int mitres = 0;
  auto in = [](const std::vector<core::FaceId>& v, core::FaceId f) {
    return std::find(v.begin(), v.end(), f) != v.end();
  };
  for (const CutSurface& s : cut.surfaces) {
    if (s.used && s.beyond) strips.push_back(s.face);
    if (s.used && s.mitre) ++mitres;
    if (s.used && s.corner && !in(corners, s.face)) corners.push_back(s.face);
  }
  auto on_a_strip = [&](const CutSurface& s) {
    return s.beyond || s.mitre || s.corner || (s.at_foot && !s.cylinder && in(strips, s.face)) ||
           (s.cylinder && (s.at_foot || s.ring) && in(corners, s.face));
  };
  // The planes around one hole are named once, with their number ("4 planes around the hole
  // of Face5").
  std::vector<std::pair<std::string, int>> named;
  if (!strips.empty()) {
    std::string t = "the strips of ";
    for (std::size_t k = 0; k < strips.size(); ++k)
      t += (k == 0 ? "" : k + 1 == strips.size() ? " and " : ", ") + core::entity_name(strips[k]);
    t += std::string(strips.size() > 1 ? " (across their feet and as far beyond their walls)"
                                       : " (across its foot and as far beyond its wall)");
    if (mitres > 0)
      t += ", ended at " + std::to_string(mitres) + (mitres > 1 ? " mitre planes" : " mitre plane");
    if (!corners.empty()) {
      t += std::string(mitres > 0 ? " and" : ",") + " turning round " +
           std::to_string(corners.size()) +
           (corners.size() > 1 ? " rounded corners (" : " rounded corner (");
      for (std::size_t k = 0; k < corners.size(); ++k)
        t += (k ? ", " : "") + core::entity_name(corners[k]);
      t += ") on sectors of cylinders";
    }
    named.push_back({t, 1});
  }
  for (const CutSurface& s : cut.surfaces) {
    if (!s.used || on_a_strip(s)) continue;
    const std::string t = surface_text(s, with_edges);
    if (s.around_hole && !named.empty() && named.back().first == t)
      ++named.back().second;
    else
      named.push_back({t, 1});
  }
  std::string t;
  std::size_t shown = 0;
  for (const auto& [text, n] : named) {
    if (shown == at_most) break;
    t += (shown++ ? ", " : "") +
         (n > 1 ? std::to_string(n) + " planes" + text.substr(text.find(" around")) : text);
  }
  if (named.size() > shown) t += " and " + std::to_string(named.size() - shown) + " more";
  return t;
}

std::string cut_kind_text(const PlaneCutResult& cut) {
  bool holes = false, concave = false, feet = false, fillets = false, strips = false;
  for (const CutSurface& s : cut.surfaces)
    if (s.used)
      (s.around_hole                     ? holes
       : s.beyond || s.mitre || s.corner ? strips
       : s.at_foot && s.cylinder         ? fillets
       : s.at_foot                       ? feet
                                         : concave) = true;
  std::vector<std::string> kinds;
  if (concave) kinds.push_back("the faces at its concave edges");
  if (holes) kinds.push_back("planes around its holes");
  if (feet && !strips) kinds.push_back("planes across the feet of its tapered or rounded faces");
  if (strips) kinds.push_back("planes along the strips of its fillets on floors");
  if (fillets) kinds.push_back("cylinders through the feet of its concave round fillets");
  if (kinds.empty()) kinds.push_back("the faces at its concave edges");
  std::string t = kinds[0];
  for (std::size_t k = 1; k < kinds.size(); ++k)
    t += (k + 1 == kinds.size() ? " and " : ", ") + kinds[k];
  if (cut.octants > 0)
    t += " (" + std::to_string(cut.octants) + (cut.octants == 1 ? " octant" : " octants") +
         " of a ball, as at a corner where three fillets meet, each parted like a cube's corner "
         "into four blocks, and the fillets' strips beside them into three)";
  return t;
}

std::string left_out_text(const PlaneCutResult& cut) {
  std::string t;
  for (const CutSurface& s : cut.surfaces)
    if (!s.used) t += (t.empty() ? "" : ", ") + surface_text(s, false);
  return t;
}

}  // namespace vorohex::decompose
