#include "mesh/submap_face.h"

#include "mesh/detail/quad_quality.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>

namespace vorohex::mesh {

using core::Vec3;

std::vector<int> submap_directions(const occ::Solid& solid, core::FaceId face) {
  if (!solid.face_is_planar(face)) return {};
  const auto wires = solid.face_wires(face);
  if (wires.size() != 1 || wires[0].size() <= 4) return {};
  const auto& wire = wires[0];
  const std::size_t n = wire.size();
  // Tangents at the start and end of each edge as the wire runs.
  std::vector<Vec3> start(n), end(n);
  for (std::size_t k = 0; k < n; ++k) {
    std::vector<Vec3> p = solid.edge_points_by_length(wire[k].edge, 16);
    if (!wire[k].forward) std::reverse(p.begin(), p.end());
    start[k] = (p[1] - p[0]).normalized();
    end[k] = (p[p.size() - 1] - p[p.size() - 2]).normalized();
  }
  const double kPi = 3.14159265358979323846, slack = 15 * kPi / 180;
  std::vector<int> dir(n, 0);
  int total = 0;
  for (std::size_t k = 0; k + 1 <= n; ++k) {
    const std::size_t next = (k + 1) % n;
    std::vector<Vec3> p = solid.edge_points_by_length(wire[next].edge, 1);
    const Vec3 corner = wire[next].forward ? p[0] : p[1];
    const Vec3 normal = solid.face_normal(face, corner);
    const double angle = std::atan2(end[k].cross(start[next]).dot(normal), end[k].dot(start[next]));
    int turn;
    if (std::abs(angle - kPi / 2) < slack)
      turn = 1;
    else if (std::abs(angle + kPi / 2) < slack)
      turn = -1;
    else if (std::abs(angle) < slack)
      turn = 0;
    else
      return {};
    total += turn;
    if (next != 0) dir[next] = ((dir[k] + turn) % 4 + 4) % 4;
  }
  if (total != 4) return {};  // not a simple outline turning once around the face
  return dir;
}

QuadFaceMesh submap_face(const occ::Solid& solid, core::FaceId face, const std::vector<Vec3>& loop,
                         const std::vector<int>& counts, const std::vector<int>& directions) {
  QuadFaceMesh m;
  auto fail = [&](const std::string& why) {
    m.diagnostics.push_back(core::make_error(
        "submap_failed", "Submapping " + core::entity_name(face) + " failed: " + why + ".",
        {core::entity_name(face)}));
    return m;
  };
  if (counts.size() != directions.size()) return fail("one count per edge is needed");
  static const int step[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  // Integer coordinates of the boundary nodes along the wire.
  std::vector<std::array<int, 2>> ij;
  std::map<std::array<int, 2>, int> node_at;
  std::array<int, 2> at{0, 0};
  for (std::size_t e = 0; e < counts.size(); ++e)
    for (int s = 0; s < counts[e]; ++s) {
      if (!node_at.emplace(at, int(ij.size())).second)
        return fail("its lattice outline touches itself");
      ij.push_back(at);
      at = {at[0] + step[directions[e]][0], at[1] + step[directions[e]][1]};
    }
  if (at != std::array<int, 2>{0, 0}) return fail("the intervals along opposite sides differ");
  if (ij.size() != loop.size()) return fail("the boundary node count does not match");
  // Cells inside the outline (even-odd test of each cell centre against the lattice polygon).
  int imin = 0, imax = 0, jmin = 0, jmax = 0;
  for (const auto& p : ij)
    imin = std::min(imin, p[0]), imax = std::max(imax, p[0]), jmin = std::min(jmin, p[1]),
    jmax = std::max(jmax, p[1]);
  auto inside = [&](double x, double y) {
    bool in = false;
    for (std::size_t k = 0, l = ij.size() - 1; k < ij.size(); l = k++) {
      const double xk = ij[k][0], yk = ij[k][1], xl = ij[l][0], yl = ij[l][1];
      if ((yk > y) != (yl > y) && x < (xl - xk) * (y - yk) / (yl - yk) + xk) in = !in;
    }
    return in;
  };
  m.points = loop;
  m.num_boundary = loop.size();
  auto node = [&](int i, int j) {
    const auto it = node_at.find({i, j});
    if (it != node_at.end()) return it->second;
    const int id = int(m.points.size());
    node_at.emplace(std::array<int, 2>{i, j}, id);
    m.points.push_back(Vec3::Zero());
    return id;
  };
  for (int j = jmin; j < jmax; ++j)
    for (int i = imin; i < imax; ++i) {
      if (!inside(i + 0.5, j + 0.5)) continue;
      m.quads.push_back({node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
    }
  // Inner nodes: discrete harmonic map of the lattice (Gauss-Seidel on the four lattice
  // neighbours), started at the mean of the boundary.
  std::vector<std::array<int, 2>> coords(m.points.size());
  for (const auto& [p, id] : node_at) coords[id] = p;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : loop) mean += p / double(loop.size());
  for (std::size_t k = loop.size(); k < m.points.size(); ++k) m.points[k] = mean;
  std::vector<std::array<int, 4>> nbr(m.points.size(), {-1, -1, -1, -1});
  for (std::size_t k = loop.size(); k < m.points.size(); ++k)
    for (int d = 0; d < 4; ++d) {
      const auto it = node_at.find({coords[k][0] + step[d][0], coords[k][1] + step[d][1]});
      if (it == node_at.end()) return fail("an inner lattice node lacks a neighbour");
      nbr[k][d] = it->second;
    }
  const double tol = 1e-12 * solid.diagonal();
  for (int it = 0; it < 20000 && m.points.size() > loop.size(); ++it) {
    double moved = 0;
    for (std::size_t k = loop.size(); k < m.points.size(); ++k) {
      const Vec3 p = 0.25 * (m.points[nbr[k][0]] + m.points[nbr[k][1]] + m.points[nbr[k][2]] +
                             m.points[nbr[k][3]]);
      moved = std::max(moved, (p - m.points[k]).norm());
      m.points[k] = p;
    }
    if (moved <= tol) break;
  }
  detail::measure_quads(solid, face, m);
  if (m.quads.empty() || m.min_quality <= 0) return fail("its lattice folds");
  m.ok = true;
  return m;
}

void add_submap_balance(IntervalProblem& problem, const std::vector<int>& directions,
                        const std::vector<int>& curves, const std::string& why) {
  IntervalProblem::Equal u{{}, {}, why + ": +u and -u sides"};
  IntervalProblem::Equal v{{}, {}, why + ": +v and -v sides"};
  for (std::size_t e = 0; e < directions.size() && e < curves.size(); ++e)
    (directions[e] == 0   ? u.lhs
     : directions[e] == 2 ? u.rhs
     : directions[e] == 1 ? v.lhs
                          : v.rhs)
        .push_back(curves[e]);
  problem.equal.push_back(std::move(u));
  problem.equal.push_back(std::move(v));
}

}  // namespace vorohex::mesh
