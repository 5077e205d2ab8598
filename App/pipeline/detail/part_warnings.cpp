#include "pipeline/detail/part_warnings.h"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <string>
#include <utility>

#include "quality/sharp_edges.h"

namespace vorohex::pipeline::detail {

// Model edges shorter than, and faces narrower than, a quarter of the size: no scheme
// absorbs them yet (that needs the virtual topology's composite entities), so the mesh
// keeps them as entities of their own and its elements there are small and poor. Said
// before meshing, naming them, with what the user can do.
// With local sizes, each entity is compared with the size where it is.
std::vector<core::Diagnostic> small_features(const occ::Solid& solid,
                                             const core::SizeField& sizes) {
  const double size = sizes.global();
  std::vector<std::pair<double, std::string>> edges, faces;
  std::vector<double> length(solid.num_edges() + 1, 0.0);  // by edge id; 0 when degenerated
  std::vector<double> local(solid.num_edges() + 1, size);  // by edge id: the size at its middle
  for (core::EdgeId e : solid.edges()) {
    if (solid.edge_is_degenerated(e)) continue;
    length[e.value()] = solid.edge_length(e);
    if (!sizes.uniform()) local[e.value()] = sizes.at(solid.edge_points_by_length(e, 2)[1]);
    if (length[e.value()] < 0.25 * local[e.value()])
      edges.emplace_back(length[e.value()], core::entity_name(e));
  }
  for (core::FaceId f : solid.faces()) {
    double perimeter = 0, at = size;
    for (const auto& wire : solid.face_wires(f))
      for (const occ::OrientedEdge& oe : wire) {
        perimeter += length[oe.edge.value()];
        at = std::min(at, local[oe.edge.value()]);
      }
    // Width of a strip of that area and perimeter (a rectangle a x b: ab / (a + b), about b
    // for b << a; a disc: its radius).
    const double width = perimeter > 0 ? 2 * solid.area(f) / perimeter : 0;
    if (width < 0.25 * at) faces.emplace_back(width, core::entity_name(f));
  }
  std::vector<core::Diagnostic> out;
  auto say = [&](std::vector<std::pair<double, std::string>>& list, const char* code,
                 const char* what, const char* measure) {
    if (list.empty()) return;
    std::sort(list.begin(), list.end());
    std::ostringstream s;
    s << list.size() << " " << what << " " << measure << " a quarter of the size "
      << (sizes.uniform() ? "" : "where they are (global size ") << size
      << (sizes.uniform() ? "" : ")") << " (";
    std::vector<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (i < 5) s << (i ? ", " : "") << list[i].second << " " << list[i].first;
      names.push_back(list[i].second);
    }
    const bool one = list.size() == 1;
    s << (list.size() > 5 ? ", ..." : "") << "): " << (one ? "it is" : "they are") << " meshed as "
      << (one ? "it is" : "they are") << ", with small elements of poor "
      << "quality around " << (one ? "it" : "them") << ". Remove " << (one ? "it" : "them")
      << " in the CAD (defeaturing) or give a smaller size.";
    out.push_back(core::make_warning(code, s.str(), names));
  };
  say(edges, "tiny_edges", edges.size() == 1 ? "model edge is" : "model edges are", "shorter than");
  say(faces, "sliver_faces", faces.size() == 1 ? "model face is" : "model faces are",
      "narrower than");
  return out;
}

// The part's sharp edges and the best scaled Jacobian they allow any hex mesh that follows
// them (quality/sharp_edges.h), said before meshing so that a low minimum there is not put
// down to the mesher: one warning naming the sharpest (none when every bound is 0.5 or more).
std::vector<core::Diagnostic> sharp_edge_info(const occ::Solid& solid) {
  const quality::SharpEdges sharp = quality::sharp_edges(solid);
  if (sharp.edges.empty()) return {};
  std::vector<std::string> names;
  std::ostringstream s;
  s << std::setprecision(3);
  const quality::SharpEdge& worst = sharp.edges.front();
  s << "The part's geometry bounds the quality of any hex mesh that follows its edges: a "
    << "scaled Jacobian of at most " << worst.bound << " along " << core::entity_name(worst.edge)
    << ", whatever the mesher (";
  for (std::size_t i = 0; i < sharp.edges.size(); ++i) {
    const quality::SharpEdge& e = sharp.edges[i];
    names.push_back(core::entity_name(e.edge));
    if (i < 5)
      s << (i ? "; " : "") << core::entity_name(e.edge) << ": its faces meet at " << e.angle
        << " degrees inside the part, " << e.bound;
  }
  s << (sharp.edges.size() > 5 ? "; ..." : "")
    << "). A chamfer or a round there in the CAD lifts the bound.";
  return {core::make_warning("geometry_bounds_quality", s.str(), names)};
}

}  // namespace vorohex::pipeline::detail
