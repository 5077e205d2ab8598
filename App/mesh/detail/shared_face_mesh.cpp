#include "mesh/detail/shared_face_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <unordered_map>
#include <utility>

namespace vorohex::mesh::detail {

using core::Vec3;

namespace {

// Points within `tol` of each other found by hashing them into cells of that size.
class PointIndex {
 public:
  explicit PointIndex(double tol) : tol_(tol) {}
  // The id of a point within tol of p, or -1.
  int find(const Vec3& p) const {
    const auto c = cell(p);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(hash({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (it == cells_.end()) continue;
          for (int i : it->second)
            if ((points_[i] - p).norm() <= tol_) return i;
        }
    return -1;
  }
  // p's id, a new one where no point lies within tol.
  int insert(const Vec3& p) {
    const int known = find(p);
    if (known >= 0) return known;
    points_.push_back(p);
    cells_[hash(cell(p))].push_back(int(points_.size() - 1));
    return int(points_.size() - 1);
  }
  const std::vector<Vec3>& points() const { return points_; }

 private:
  std::array<long long, 3> cell(const Vec3& p) const {
    return {static_cast<long long>(std::floor(p.x() / tol_)),
            static_cast<long long>(std::floor(p.y() / tol_)),
            static_cast<long long>(std::floor(p.z() / tol_))};
  }
  static std::size_t hash(const std::array<long long, 3>& c) {
    return std::size_t(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
  }
  double tol_;
  std::vector<Vec3> points_;
  std::unordered_map<std::size_t, std::vector<int>> cells_;
};

}  // namespace

std::vector<std::array<Vec3, 4>> quads_on_face(const core::HexMesh& mesh, const occ::Solid& solid,
                                               core::FaceId f) {
  std::set<int> edges, vertices;
  for (const auto& wire : solid.face_wires(f))
    for (const core::OrientedEdge& oe : wire) {
      edges.insert(oe.edge.value());
      vertices.insert(solid.edge_first_vertex(oe.edge).value());
      vertices.insert(solid.edge_last_vertex(oe.edge).value());
    }
  auto on = [&](std::int32_t n) {
    const core::NodeClass c = mesh.node_classes()[n];
    return (c.dim == 2 && c.id == f.value()) || (c.dim == 1 && edges.count(c.id)) ||
           (c.dim == 0 && vertices.count(c.id));
  };
  std::vector<std::array<Vec3, 4>> out;
  const double tol = 1e-6 * solid.diagonal();
  for (const core::BoundaryFace& b : core::boundary_faces(mesh)) {
    const core::HexNodes& h = mesh.hexes()[b.hex];
    const auto& c = core::kHexFaces[b.face];
    std::array<Vec3, 4> q;
    bool all = true;
    for (int i = 0; i < 4 && all; ++i) all = on(h[c[i]]), q[i] = mesh.points()[h[c[i]]];
    if (!all) continue;
    const Vec3 centre = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    // Off a curved face by its sagitta (a side of 2.2 on a cylinder of radius 4: 0.15), off
    // a face it does not lie on (its corners all on the face's edges) by about its side.
    if ((solid.project_to_face(f, centre) - centre).norm() > tol + 0.2 * (q[2] - q[0]).norm())
      continue;
    out.push_back(q);
  }
  return out;
}

bool onto_quads_by_connectivity(std::vector<core::Vec3>& P, std::size_t base, std::size_t m,
                                std::size_t nb, const std::vector<std::array<int, 4>>& own,
                                const std::vector<std::array<core::Vec3, 4>>& quads, double size) {
  const double tol = 1e-6 * size;
  if (own.size() != quads.size() || m < nb) return false;
  // The neighbour's corners as distinct points, its quads by their ids.
  PointIndex index(tol);
  std::vector<std::array<int, 4>> theirs;
  for (const auto& q : quads)
    theirs.push_back(
        {index.insert(q[0]), index.insert(q[1]), index.insert(q[2]), index.insert(q[3])});
  const std::vector<Vec3>& points = index.points();
  if (points.size() != m) return false;
  std::map<std::pair<int, int>, std::vector<int>> their_edge;  // (low, high) -> quads
  std::map<std::pair<int, int>, std::vector<int>> own_edge;
  auto key = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  for (std::size_t q = 0; q < theirs.size(); ++q)
    for (int c = 0; c < 4; ++c) {
      their_edge[key(theirs[q][c], theirs[q][(c + 1) % 4])].push_back(int(q));
      own_edge[key(own[q][c], own[q][(c + 1) % 4])].push_back(int(q));
    }
  std::vector<int> match(m, -1), matched_by(m, -1);  // own node -> their point, and back
  for (std::size_t j = 0; j < nb; ++j) {
    const int found = index.find(P[base + j]);
    if (found < 0 || matched_by[found] >= 0) return false;
    match[j] = found, matched_by[found] = int(j);
  }
  std::vector<int> image(own.size(), -1), imaged_by(theirs.size(), -1);  // quad pairing
  // Pairs own quad q with their quad t along the edge a-b of q (both paired nodes); false
  // where the corners do not agree.
  auto pair_quads = [&](int q, int t, int c) {
    const int a = own[q][c], b = own[q][(c + 1) % 4];
    const auto& T = theirs[t];
    int ta = -1;
    for (int i = 0; i < 4; ++i)
      if (T[i] == match[a]) ta = i;
    if (ta < 0) return false;
    const int dir = T[(ta + 1) % 4] == match[b] ? 1 : T[(ta + 3) % 4] == match[b] ? 3 : 0;
    if (dir == 0) return false;
    for (int i = 2; i < 4; ++i) {
      const int node = own[q][(c + i) % 4], point = T[(ta + dir * i) % 4];
      if (match[node] < 0 && matched_by[point] < 0)
        match[node] = point, matched_by[point] = node;
      else if (match[node] != point)
        return false;
    }
    image[q] = t, imaged_by[t] = q;
    return true;
  };
  std::vector<int> queue;
  // A quad along the boundary to start from: a boundary edge has one quad on either side.
  for (std::size_t q = 0; q < own.size() && queue.empty(); ++q)
    for (int c = 0; c < 4 && queue.empty(); ++c) {
      const int a = own[q][c], b = own[q][(c + 1) % 4];
      if (match[a] < 0 || match[b] < 0 || own_edge[key(a, b)].size() != 1) continue;
      const auto& ts = their_edge[key(match[a], match[b])];
      if (ts.size() != 1 || !pair_quads(int(q), ts[0], c)) return false;
      queue.push_back(int(q));
    }
  // Then across the edges of paired quads: the other quad on each side.
  for (std::size_t next = 0; next < queue.size(); ++next) {
    const int q = queue[next];
    for (int c = 0; c < 4; ++c) {
      const int a = own[q][c], b = own[q][(c + 1) % 4];
      const auto& os = own_edge[key(a, b)];
      const auto& ts = their_edge[key(match[a], match[b])];
      if (os.size() != ts.size()) return false;
      if (os.size() != 2) continue;
      const int q2 = os[0] == q ? os[1] : os[0], t2 = ts[0] == image[q] ? ts[1] : ts[0];
      if (image[q2] >= 0) {
        if (image[q2] != t2) return false;
        continue;
      }
      if (imaged_by[t2] >= 0) return false;
      int c2 = -1;
      for (int i = 0; i < 4; ++i)
        if (key(own[q2][i], own[q2][(i + 1) % 4]) == key(a, b)) c2 = i;
      if (c2 < 0 || !pair_quads(q2, t2, c2)) return false;
      queue.push_back(q2);
    }
  }
  if (queue.size() != own.size()) return false;
  for (std::size_t j = nb; j < m; ++j)
    if (match[j] < 0) return false;
  for (std::size_t j = nb; j < m; ++j) P[base + j] = points[match[j]];
  return true;
}

}  // namespace vorohex::mesh::detail
