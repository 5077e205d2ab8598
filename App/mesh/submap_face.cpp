#include "mesh/submap_face.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include "mesh/detail/quad_quality.h"

namespace vorohex::mesh {

using core::OrientedEdge;
using core::Vec3;
using Vec2 = Eigen::Vector2d;

const char* vertex_type_name(VertexType t) {
  switch (t) {
    case VertexType::end:
      return "End";
    case VertexType::side:
      return "Side";
    case VertexType::corner:
      return "Corner";
    default:
      return "Reversal";
  }
}

namespace {

const double kPi = 3.14159265358979323846;

// An edge as its wire runs it: sample points from its start to its end.
std::vector<Vec3> run(const core::MeshDomain& s, const OrientedEdge& oe) {
  std::vector<Vec3> p = s.edge_points_by_length(oe.edge, 16);
  if (!oe.forward) std::reverse(p.begin(), p.end());
  return p;
}

core::VertexId start_vertex(const core::MeshDomain& s, const OrientedEdge& oe) {
  return oe.forward ? s.edge_first_vertex(oe.edge) : s.edge_last_vertex(oe.edge);
}

double chart_angle(const core::SurfaceChart& chart, const std::vector<Vec3>& p) {
  const Vec2 d = chart.to_chart(p[1]) - chart.to_chart(p[0]);
  return std::atan2(d.y(), d.x());
}

}  // namespace

SubmapStructure submap_structure(const core::MeshDomain& solid, core::FaceId face, bool mapped_too,
                                 double slack) {
  SubmapStructure out;
  const std::string fname = core::entity_name(face);
  try {
    const auto wires = solid.face_wires(face);
    if (wires.empty()) {
      out.reason = fname + " has no boundary";
      return out;
    }
    std::vector<std::vector<std::vector<Vec3>>> runs(wires.size());
    for (std::size_t w = 0; w < wires.size(); ++w)
      for (const OrientedEdge& oe : wires[w]) {
        if (solid.edge_is_degenerated(oe.edge)) {
          out.reason = core::entity_name(oe.edge) + " of " + fname + " is degenerated";
          return out;
        }
        runs[w].push_back(run(solid, oe));
      }
    out.directions.resize(wires.size());
    out.types.resize(wires.size());
    out.angles.resize(wires.size());
    std::vector<std::vector<int>> units(wires.size());
    for (std::size_t w = 0; w < wires.size(); ++w) {
      const std::size_t n = wires[w].size();
      int total = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const std::vector<Vec3>& in = runs[w][(k + n - 1) % n];
        const std::vector<Vec3>& o = runs[w][k];
        const Vec3 vertex = o.front();
        const Vec3 t_in = (in[in.size() - 1] - in[in.size() - 2]).normalized();
        const Vec3 t_out = (o[1] - o[0]).normalized();
        const Vec3 normal = solid.face_normal(face, vertex);
        double turn = std::atan2(t_in.cross(t_out).dot(normal), t_in.dot(t_out));
        if (std::abs(std::abs(turn) - kPi) < 1e-3) {
          // The edges go back along each other: into the face between them (a cusp, turn
          // +180) or around a slit (a reversal, -180), told apart by their chords further on.
          const Vec3 c_in = vertex - in[in.size() - 3], c_out = o[2] - vertex;
          turn = c_in.cross(c_out).dot(normal) > 1e-12 * c_in.norm() * c_out.norm() ? kPi : -kPi;
        }
        const double alpha = (kPi - turn) * 180 / kPi;
        const int k90 = int(std::lround(alpha / 90));
        out.angles[w].push_back(alpha);
        if (k90 < 1 || k90 > 4 || std::abs(alpha - 90 * k90) > slack) {
          std::ostringstream why;
          why << core::entity_name(start_vertex(solid, wires[w][k])) << " of " << fname
              << " has an interior angle of " << std::lround(alpha)
              << " degrees, not near 90, 180, 270 or 360";
          out.reason = why.str();
          return out;
        }
        out.types[w].push_back(VertexType(k90 - 1));
        units[w].push_back(2 - k90);
        total += 2 - k90;
      }
      const int expected = w == 0 ? 4 : -4;
      if (total != expected) {
        std::ostringstream why;
        why << (w == 0 ? "the outer loop" : "a hole") << " of " << fname << " turns by "
            << total * 90 << " degrees, not " << expected * 90;
        out.reason = why.str();
        return out;
      }
    }
    if (wires.size() == 1 && wires[0].size() == 4 && !mapped_too) {
      out.reason = fname + " has four End vertices: a mapped face";
      return out;
    }
    // Directions: the outer loop from +i; each hole from its first edge's angle to the
    // outer loop's first edge in the face's chart (mirrored charts turn the other way).
    const std::unique_ptr<core::SurfaceChart> chart_ptr = solid.face_chart(face);
    const core::SurfaceChart& chart = *chart_ptr;
    double area = 0;
    for (const auto& r : runs[0])
      for (std::size_t i = 0; i + 1 < r.size(); ++i) {
        const Vec2 a = chart.to_chart(r[i]), b = chart.to_chart(r[i + 1]);
        area += a.x() * b.y() - a.y() * b.x();
      }
    const double sense = area < 0 ? -1 : 1;
    const double reference = chart_angle(chart, runs[0][0]);
    for (std::size_t w = 0; w < wires.size(); ++w) {
      int d = 0;
      if (w > 0) {
        double delta = sense * (chart_angle(chart, runs[w][0]) - reference) / (kPi / 2);
        const double rounded = std::round(delta);
        if (std::abs(delta - rounded) * 90 > slack) {
          out.reason = "a hole of " + fname + " is not aligned with its outer loop";
          return out;
        }
        d = ((int(rounded) % 4) + 4) % 4;
      }
      for (std::size_t k = 0; k < wires[w].size(); ++k) {
        if (k > 0) d = ((d + units[w][k]) % 4 + 4) % 4;
        out.directions[w].push_back(d);
      }
    }
  } catch (const std::exception& e) {
    out = SubmapStructure();
    out.reason = "the geometry of " + fname + " cannot be evaluated (" + e.what() + ")";
    return out;
  }
  out.ok = true;
  return out;
}

QuadFaceMesh submap_face(const core::MeshDomain& solid, core::FaceId face,
                         const std::vector<std::vector<Vec3>>& loops,
                         const std::vector<std::vector<int>>& counts,
                         const SubmapStructure& structure) {
  QuadFaceMesh m;
  auto fail = [&](const std::string& why) {
    m = QuadFaceMesh();
    m.diagnostics.push_back(core::make_error(
        "submap_failed", "Submapping " + core::entity_name(face) + " failed: " + why + ".",
        {core::entity_name(face)}));
    return m;
  };
  const std::size_t nw = structure.directions.size();
  if (!structure.ok || loops.size() != nw || counts.size() != nw)
    return fail("one loop of nodes and counts per wire is needed");
  static const int step[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  // Lattice coordinates of each loop's nodes, each loop from (0, 0).
  std::vector<std::vector<std::array<int, 2>>> ij(nw);
  for (std::size_t w = 0; w < nw; ++w) {
    if (counts[w].size() != structure.directions[w].size())
      return fail("one count per edge is needed");
    std::array<int, 2> at{0, 0};
    for (std::size_t e = 0; e < counts[w].size(); ++e)
      for (int s = 0; s < counts[w][e]; ++s) {
        ij[w].push_back(at);
        at = {at[0] + step[structure.directions[w][e]][0],
              at[1] + step[structure.directions[w][e]][1]};
      }
    if (at != std::array<int, 2>{0, 0})
      return fail("the intervals along opposite sides of a loop differ");
    if (ij[w].size() != loops[w].size()) return fail("the boundary node count does not match");
  }
  const std::unique_ptr<core::SurfaceChart> chart_ptr = solid.face_chart(face);
  const core::SurfaceChart& chart = *chart_ptr;
  std::vector<std::vector<Vec2>> uv(nw);
  for (std::size_t w = 0; w < nw; ++w)
    for (const Vec3& p : loops[w]) uv[w].push_back(chart.to_chart(p));
  // Holes: placed where the least-squares affine map from the chart to the lattice, fitted
  // on the outer loop, puts them.
  if (nw > 1) {
    Eigen::MatrixXd a(ij[0].size(), 3);
    Eigen::MatrixXd b(ij[0].size(), 2);
    for (std::size_t k = 0; k < ij[0].size(); ++k) {
      a.row(k) << uv[0][k].x(), uv[0][k].y(), 1.0;
      b.row(k) << ij[0][k][0], ij[0][k][1];
    }
    const Eigen::MatrixXd fit = a.colPivHouseholderQr().solve(b);  // 3 x 2
    for (std::size_t w = 1; w < nw; ++w) {
      Vec2 shift = Vec2::Zero();
      for (std::size_t k = 0; k < ij[w].size(); ++k) {
        const Eigen::RowVector3d c(uv[w][k].x(), uv[w][k].y(), 1.0);
        const Eigen::RowVector2d predicted = c * fit;
        shift += Vec2(predicted(0) - ij[w][k][0], predicted(1) - ij[w][k][1]);
      }
      shift /= double(ij[w].size());
      const int si = int(std::lround(shift.x())), sj = int(std::lround(shift.y()));
      for (auto& p : ij[w]) p = {p[0] + si, p[1] + sj};
    }
  }
  // Boundary lattice points; a point the loop passes twice is allowed only on a slit: the
  // two sides of the edges into and out of a Reversal vertex (the loop goes out and back on
  // one lattice line, the material on both sides).
  std::map<std::array<int, 2>, std::vector<int>> boundary_at;
  std::vector<std::array<double, 2>> side_in, side_out;  // left normals of a node's edges
  {
    int next = 0;
    for (std::size_t w = 0; w < nw; ++w) {
      const std::size_t n = ij[w].size();
      for (std::size_t k = 0; k < n; ++k, ++next) {
        boundary_at[ij[w][k]].push_back(next);
        const auto& a = ij[w][(k + n - 1) % n];
        const auto& b = ij[w][k];
        const auto& c = ij[w][(k + 1) % n];
        side_in.push_back({-double(b[1] - a[1]), double(b[0] - a[0])});
        side_out.push_back({-double(c[1] - b[1]), double(c[0] - b[0])});
      }
    }
  }
  {
    // Positions of each boundary node in its loop, to recognise slits.
    std::vector<std::pair<std::size_t, std::size_t>> where;  // (wire, index)
    for (std::size_t w = 0; w < nw; ++w)
      for (std::size_t k = 0; k < ij[w].size(); ++k) where.emplace_back(w, k);
    for (const auto& [p, ids] : boundary_at) {
      if (ids.size() == 1) continue;
      bool slit = ids.size() == 2 && where[ids[0]].first == where[ids[1]].first;
      if (slit) {
        // The loop between the two passes must be a path out and back: symmetric about its
        // middle node.
        const auto& l = ij[where[ids[0]].first];
        const std::size_t n = l.size(), a = where[ids[0]].second, b = where[ids[1]].second;
        bool found = false;
        for (const auto& [from, gap] :
             {std::pair{a, (b + n - a) % n}, std::pair{b, (a + n - b) % n}}) {
          if (gap % 2 != 0 || gap < 2) continue;
          bool symmetric = true;
          for (std::size_t t = 1; t < gap / 2 && symmetric; ++t)
            symmetric = l[(from + t) % n] == l[(from + gap - t) % n];
          found = found || symmetric;
        }
        slit = found;
      }
      if (!slit)
        return fail(nw > 1 ? "its lattice loops touch (a hole does not fit its lattice)"
                           : "its lattice outline touches itself");
    }
  }
  std::map<std::array<int, 2>, int> node_at;  // lattice points with one node
  for (const auto& [p, ids] : boundary_at)
    if (ids.size() == 1) node_at.emplace(p, ids[0]);
  // The node at boundary point p seen from offset (dx, dy): on a slit, the side facing it.
  auto pick = [&](const std::array<int, 2>& p, double dx, double dy) -> int {
    const auto it = boundary_at.find(p);
    if (it == boundary_at.end()) return -1;
    for (int id : it->second)
      if (side_in[id][0] * dx + side_in[id][1] * dy > 0 ||
          side_out[id][0] * dx + side_out[id][1] * dy > 0)
        return id;
    return it->second.front();
  };
  auto inside = [&](double x, double y) {
    bool in = false;
    for (const auto& l : ij)
      for (std::size_t k = 0, j = l.size() - 1; k < l.size(); j = k++) {
        const double xk = l[k][0], yk = l[k][1], xj = l[j][0], yj = l[j][1];
        if ((yk > y) != (yj > y) && x < (xj - xk) * (y - yk) / (yj - yk) + xk) in = !in;
      }
    return in;
  };
  // Every hole must lie inside the outer loop.
  for (std::size_t w = 1; w < nw; ++w) {
    bool in = false;
    const auto& outer = ij[0];
    const double x = ij[w][0][0] + 0.25, y = ij[w][0][1] + 0.25;
    for (std::size_t k = 0, j = outer.size() - 1; k < outer.size(); j = k++) {
      const double xk = outer[k][0], yk = outer[k][1], xj = outer[j][0], yj = outer[j][1];
      if ((yk > y) != (yj > y) && x < (xj - xk) * (y - yk) / (yj - yk) + xk) in = !in;
    }
    if (!in) return fail("a hole falls outside its lattice");
  }
  int imin = 0, imax = 0, jmin = 0, jmax = 0;
  for (const auto& p : ij[0])
    imin = std::min(imin, p[0]), imax = std::max(imax, p[0]), jmin = std::min(jmin, p[1]),
    jmax = std::max(jmax, p[1]);
  std::vector<Vec2> q;  // chart positions: boundary loops, then inner nodes
  for (const auto& l : uv) q.insert(q.end(), l.begin(), l.end());
  const std::size_t nb = q.size();
  // A cell corner: a boundary node (the side facing the cell centre), else an inner node.
  auto node = [&](int i, int j, double cx, double cy) {
    const int b = pick({i, j}, cx - i, cy - j);
    if (b >= 0) return b;
    const auto it = node_at.find({i, j});
    if (it != node_at.end()) return it->second;
    const int id = int(q.size());
    node_at.emplace(std::array<int, 2>{i, j}, id);
    q.push_back(Vec2::Zero());
    return id;
  };
  for (int j = jmin; j < jmax; ++j)
    for (int i = imin; i < imax; ++i) {
      const double cx = i + 0.5, cy = j + 0.5;
      if (inside(cx, cy))
        m.quads.push_back({node(i, j, cx, cy), node(i + 1, j, cx, cy), node(i + 1, j + 1, cx, cy),
                           node(i, j + 1, cx, cy)});
    }
  if (m.quads.empty()) return fail("its lattice holds no cell");
  // Inner nodes: discrete harmonic map in the chart (over-relaxed Gauss-Seidel on the four
  // lattice neighbours), started at the mean of the boundary.
  std::vector<std::array<int, 2>> coords(q.size());
  for (const auto& [p, id] : node_at) coords[id] = p;
  for (const auto& [p, ids] : boundary_at)
    for (int id : ids) coords[id] = p;
  Vec2 mean = Vec2::Zero();
  for (std::size_t k = 0; k < nb; ++k) mean += q[k] / double(nb);
  std::vector<std::array<int, 4>> nbr(q.size(), {-1, -1, -1, -1});
  for (std::size_t k = nb; k < q.size(); ++k) {
    q[k] = mean;
    for (int d = 0; d < 4; ++d) {
      const std::array<int, 2> p{coords[k][0] + step[d][0], coords[k][1] + step[d][1]};
      int id = pick(p, -step[d][0], -step[d][1]);
      if (id < 0) {
        const auto it = node_at.find(p);
        if (it == node_at.end()) return fail("an inner lattice node lacks a neighbour");
        id = it->second;
      }
      nbr[k][d] = id;
    }
  }
  double extent = 0;
  for (std::size_t k = 0; k < nb; ++k) extent = std::max(extent, (q[k] - mean).norm());
  const double tol = 1e-12 * std::max(extent, 1e-300);
  const double omega = 2 / (1 + std::sin(kPi / std::max(2, std::max(imax - imin, jmax - jmin))));
  for (int it = 0; it < 20000 && q.size() > nb; ++it) {
    double moved = 0;
    for (std::size_t k = nb; k < q.size(); ++k) {
      const Vec2 avg = 0.25 * (q[nbr[k][0]] + q[nbr[k][1]] + q[nbr[k][2]] + q[nbr[k][3]]);
      const Vec2 next_q = q[k] + omega * (avg - q[k]);
      moved = std::max(moved, (next_q - q[k]).norm());
      q[k] = next_q;
    }
    if (moved <= tol) break;
  }
  for (const auto& l : loops) m.points.insert(m.points.end(), l.begin(), l.end());
  m.num_boundary = nb;
  for (std::size_t k = nb; k < q.size(); ++k) m.points.push_back(chart.to_surface(q[k]));
  detail::measure_quads(solid, face, m);
  if (m.min_quality <= 0) return fail("its lattice folds on the face");
  m.ok = true;
  return m;
}

void add_submap_balance(IntervalProblem& problem, const SubmapStructure& structure,
                        const std::vector<std::vector<int>>& curves, const std::string& why) {
  for (std::size_t w = 0; w < structure.directions.size() && w < curves.size(); ++w) {
    const std::string loop =
        structure.directions.size() > 1 ? " (loop " + std::to_string(w + 1) + ")" : "";
    IntervalProblem::Equal u{{}, {}, why + loop + ": +i and -i sides"};
    IntervalProblem::Equal v{{}, {}, why + loop + ": +j and -j sides"};
    const auto& dirs = structure.directions[w];
    for (std::size_t e = 0; e < dirs.size() && e < curves[w].size(); ++e)
      (dirs[e] == 0   ? u.lhs
       : dirs[e] == 2 ? u.rhs
       : dirs[e] == 1 ? v.lhs
                      : v.rhs)
          .push_back(curves[w][e]);
    if (!u.lhs.empty() || !u.rhs.empty()) problem.equal.push_back(std::move(u));
    if (!v.lhs.empty() || !v.rhs.empty()) problem.equal.push_back(std::move(v));
  }
}

std::vector<int> submap_directions(const core::MeshDomain& solid, core::FaceId face) {
  const SubmapStructure s = submap_structure(solid, face);
  if (!s.ok || s.directions.size() != 1) return {};
  return s.directions[0];
}

QuadFaceMesh submap_face(const core::MeshDomain& solid, core::FaceId face,
                         const std::vector<Vec3>& loop, const std::vector<int>& counts,
                         const std::vector<int>& directions) {
  SubmapStructure s;
  s.ok = true;
  s.directions = {directions};
  return submap_face(solid, face, {loop}, {counts}, s);
}

void add_submap_balance(IntervalProblem& problem, const std::vector<int>& directions,
                        const std::vector<int>& curves, const std::string& why) {
  SubmapStructure s;
  s.ok = true;
  s.directions = {directions};
  add_submap_balance(problem, s, {curves}, why);
}

}  // namespace vorohex::mesh
