#include "mesh/detail/revolved_part.h"

#include <algorithm>
#include <cmath>

namespace vorohex::mesh::detail {

using core::EdgeId;
using core::Vec3;

namespace {

const double kPi = 3.14159265358979323846;

// A share t of a turn as p / q with q 1, 2 or 4 (an arc between vertices a quarter of a turn
// apart); q = 0 for another share.
struct Share {
  int p = 0, q = 0;
};
Share quarter_share(double t) {
  for (int q : {1, 2, 4}) {
    const int p = int(std::lround(t * q));
    if (p >= 1 && std::abs(t * q - p) <= 1e-6) return {p, q};
  }
  return {};
}

bool shared(const RevolvedPart& part, EdgeId e) {
  return std::size_t(e.value()) < part.shared_edge.size() && part.shared_edge[e.value()];
}

}  // namespace

std::vector<double> turns_about_axis(const occ::Solid& s, const Vec3& origin, const Vec3& axis) {
  std::vector<double> turns(std::size_t(s.num_edges()) + 1, 0);
  auto across = [&](const Vec3& q) {
    const Vec3 d = q - origin;
    return Vec3(d - d.dot(axis) * axis);
  };
  for (EdgeId e : s.edges()) {
    if (s.edge_is_degenerated(e) || s.curve_info(e).kind != core::CurveKind::circle) continue;
    const std::vector<Vec3> p = s.edge_points_by_length(e, 32);
    double angle = 0;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
      const Vec3 a = across(p[i]), b = across(p[i + 1]);
      angle += std::atan2(a.cross(b).dot(axis), a.dot(b));
    }
    const double t = std::abs(angle) / (2 * kPi);
    turns[e.value()] = t > 1e-6 ? t : 0;
  }
  return turns;
}

void add_revolved_constraints(IntervalProblem& problem, const RevolvedPart& part,
                              const std::function<int(EdgeId)>& curve, const std::string& who) {
  const std::vector<double>& turns = part.turns;
  double radius = 0;
  for (EdgeId e : part.solid.edges())
    if (turns[e.value()] > 0) radius = std::max(radius, part.solid.curve_info(e).radius);
  int sectors = -1;
  for (EdgeId e : part.solid.edges()) {
    if (part.solid.edge_is_degenerated(e)) continue;
    const int k = curve(e);
    const double t = turns[e.value()];
    if (t <= 0) {
      if (shared(part, e))
        problem.even.push_back(
            {{k}, who + " (revolve): " + core::entity_name(e) + ", an edge of its section"});
      continue;
    }
    if (sectors < 0) {
      sectors = problem.add_curve(2 * kPi * radius, who + " sectors");
      const std::string why = who + " (revolve): its sectors";
      problem.even.push_back({{sectors}, why + ", a multiple of 4", 4});
      problem.at_least.push_back({{sectors}, 8, why + ", at least 8"});
    }
    // q times its count is p sectors (its share of a turn p / q).
    if (const Share sh = quarter_share(t); sh.q > 0)
      problem.equal.push_back(
          {std::vector<int>(sh.q, k), std::vector<int>(sh.p, sectors),
           who + " (revolve): " + core::entity_name(e) + ", its share of the sectors"});
  }
}

RevolveOptions revolved_options(const RevolvedPart& part, RevolveOptions o,
                                const std::vector<int>& counts) {
  o.sectors = 0;
  o.has_start = false;
  o.edge_intervals.assign(counts.size(), 0);
  for (EdgeId e : part.solid.edges()) {
    if (part.solid.edge_is_degenerated(e) || std::size_t(e.value()) >= counts.size()) continue;
    const double t = part.turns[e.value()];
    const bool circle = t > 0;
    if (const Share sh = quarter_share(t); sh.q > 0 && o.sectors == 0 && counts[e.value()] > 0)
      o.sectors = counts[e.value()] * sh.q / sh.p;
    if (shared(part, e)) {
      if (!circle) o.edge_intervals[e.value()] = counts[e.value()];
      if (circle && !o.has_start)
        o.has_start = true, o.start = part.solid.vertex_point(part.solid.edge_first_vertex(e));
    }
  }
  if (o.sectors < 8 || o.sectors % 4 != 0) o.sectors = 0;  // from the size instead
  return o;
}

RevolveResult mesh_revolved(const RevolvedPart& part, const RevolveOptions& base,
                            const std::vector<int>& counts,
                            const std::vector<std::vector<Vec3>>& edge_nodes,
                            const core::Progress& progress) {
  RevolveOptions o = revolved_options(part, base, counts);
  o.edge_nodes = edge_nodes;
  // Every circle or arc it shares must end at sectors' angles (its neighbour meshes it from
  // its vertices).
  if (o.has_start && o.sectors > 0) {
    const Vec3 d0 = o.start - part.origin;
    const Vec3 u = (d0 - d0.dot(part.axis) * part.axis).normalized();
    const Vec3 v = part.axis.cross(u);
    for (EdgeId e : part.solid.edges()) {
      if (!shared(part, e) || part.turns[e.value()] <= 0) continue;
      for (const core::VertexId x :
           {part.solid.edge_first_vertex(e), part.solid.edge_last_vertex(e)}) {
        const Vec3 d = part.solid.vertex_point(x) - part.origin;
        const double turns = std::atan2(d.dot(v), d.dot(u)) / (2 * kPi) * o.sectors;
        if (std::abs(turns - std::round(turns)) > 1e-6) {
          RevolveResult r;
          r.diagnostics.push_back(core::make_error(
              "revolve_misaligned",
              "the circles it shares with its neighbours (" + core::entity_name(e) +
                  " among them) end at angles no common count of sectors meets"));
          return r;
        }
      }
    }
  }
  return revolve(part.solid, o, progress);
}

}  // namespace vorohex::mesh::detail
