#include "grid/composites.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

namespace vorohex::grid {
namespace {

using core::FaceId;
using core::Vec3;

double box_distance(const core::BoundingBox& b, const Vec3& p) {
  Vec3 d = Vec3::Zero();
  for (int i = 0; i < 3; ++i) d[i] = std::max({b.min[i] - p[i], 0.0, p[i] - b.max[i]});
  return d.norm();
}

// A model edge between two distinct faces (not a seam, not degenerated).
bool feature_edge(const core::MeshDomain& solid, core::EdgeId e) {
  if (solid.edge_is_degenerated(e)) return false;
  const std::vector<FaceId> f = solid.edge_faces(e);
  return f.size() >= 2 && f[0] != f[1];
}

int find(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Points of face f's triangulation no farther apart than `spacing` (a barycentric grid on
// each triangle: a planar face's triangulation may have no node inside it), one per cube of
// half that edge (a fine triangulation along a curved outline gives many), at most `cap`.
std::vector<Vec3> face_samples(const occ::Tessellation& tess, FaceId f, double spacing,
                               std::size_t cap) {
  std::vector<Vec3> out;
  if (f.value() >= int(tess.faces.size())) return out;
  const occ::FaceTriangulation& t = tess.faces[f.value()];
  std::unordered_set<std::int64_t> taken;
  auto add = [&](const Vec3& x) {
    const double h = spacing / 2;
    const std::int64_t i = std::int64_t(std::floor(x.x() / h)),
                       j = std::int64_t(std::floor(x.y() / h)),
                       k = std::int64_t(std::floor(x.z() / h));
    if (taken.insert((i * 73856093) ^ (j * 19349663) ^ (k * 83492791)).second) out.push_back(x);
  };
  for (const auto& tri : t.triangles) {
    const Vec3 &a = t.nodes[tri[0]], &b = t.nodes[tri[1]], &c = t.nodes[tri[2]];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    add((a + b + c) / 3);
    const int n = std::clamp(int(std::ceil(longest / spacing)), 1, 64);
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
        add(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n));
  }
  if (out.size() > cap) {  // evenly thinned
    std::vector<Vec3> thin;
    for (std::size_t i = 0; i < cap; ++i) thin.push_back(out[i * out.size() / cap]);
    out.swap(thin);
  }
  return out;
}

}  // namespace

std::string Composite::name() const {
  std::string s;
  for (FaceId f : faces) s += (s.empty() ? "" : "+") + core::entity_name(f);
  return s;
}

std::string Composite::summary() const {
  if (faces.size() <= 4) return name();
  return core::entity_name(host) + " with " + std::to_string(faces.size() - 1) + " absorbed faces";
}

bool SmallFeatures::same_composite(int a, int b) const {
  if (a == b) return true;
  if (a <= 0 || b <= 0 || a >= int(composite_of_face.size()) || b >= int(composite_of_face.size()))
    return false;
  return composite_of_face[a] >= 0 && composite_of_face[a] == composite_of_face[b];
}

Vec3 SmallFeatures::project(const core::MeshDomain& solid, FaceId f, const Vec3& p,
                            FaceId& face) const {
  face = f;
  Vec3 best = solid.project_to_face(f, p);
  const int c = f.value() < int(composite_of_face.size()) ? composite_of_face[f.value()] : -1;
  if (c < 0) return best;
  double d = best.allFinite() ? (best - p).norm() : std::numeric_limits<double>::infinity();
  for (FaceId g : composites[c].faces) {
    if (g == f || box_distance(face_boxes[g.value()], p) >= d) continue;
    const Vec3 q = solid.project_to_face(g, p);
    if (q.allFinite() && (q - p).norm() < d) d = (q - p).norm(), best = q, face = g;
  }
  return best;
}

SmallFeatures find_small_features(const core::MeshDomain& solid, const occ::Tessellation& tess,
                                  double size) {
  SmallFeatures r;
  r.small = 0.25 * size;
  const int nf = solid.num_faces(), ne = solid.num_edges();
  r.absorbed_face.assign(nf + 1, 0);
  r.absorbed_edge.assign(ne + 1, 0);
  r.composite_of_face.assign(nf + 1, -1);
  std::vector<double> length(ne + 1, 0.0), area(nf + 1, 0.0);
  for (core::EdgeId e : solid.edges())
    if (!solid.edge_is_degenerated(e)) length[e.value()] = solid.edge_length(e);
  // Slivers: narrower than `small` (twice the area over the perimeter).
  std::vector<std::vector<core::EdgeId>> face_edges(nf + 1);
  for (FaceId f : solid.faces()) {
    area[f.value()] = std::abs(solid.area(f));
    double perimeter = 0;
    for (const auto& wire : solid.face_wires(f))
      for (const core::OrientedEdge& oe : wire) {
        perimeter += length[oe.edge.value()];
        face_edges[f.value()].push_back(oe.edge);
      }
    r.absorbed_face[f.value()] = perimeter > 0 && 2 * area[f.value()] / perimeter < r.small;
  }
  auto mark_edges = [&] {
    for (core::EdgeId e : solid.edges()) {
      if (solid.edge_is_degenerated(e)) continue;
      bool a = length[e.value()] < r.small;
      for (FaceId f : solid.edge_faces(e)) a = a || r.absorbed_face[f.value()];
      r.absorbed_edge[e.value()] = a;
    }
  };
  mark_edges();
  // Enclosed faces: every feature edge absorbed, every neighbour across them a sliver, and
  // every point within the size of those neighbours (an engraving's floor: its walls are
  // slivers; a floor wider than two cells is a feature the mesh can resolve, and stays).
  std::vector<char> enclosed(nf + 1, 0);
  for (FaceId f : solid.faces()) {
    if (r.absorbed_face[f.value()]) continue;
    std::vector<FaceId> neighbours;
    bool all = true;
    for (core::EdgeId e : face_edges[f.value()]) {
      if (!feature_edge(solid, e)) continue;
      all = all && r.absorbed_edge[e.value()];
      for (FaceId g : solid.edge_faces(e))
        if (g != f && std::find(neighbours.begin(), neighbours.end(), g) == neighbours.end())
          neighbours.push_back(g);
    }
    if (!all || neighbours.empty()) continue;
    for (FaceId g : neighbours) all = all && r.absorbed_face[g.value()];
    if (!all) continue;
    const std::vector<Vec3> nodes = face_samples(tess, f, 0.5 * size, 4000);
    if (nodes.empty()) continue;
    std::vector<core::BoundingBox> boxes;
    for (FaceId g : neighbours) boxes.push_back(solid.face_bounding_box(g));
    bool near = true;
    std::size_t last = 0;  // the neighbour the previous point was near: likely this one's
    for (std::size_t i = 0; i < nodes.size() && near; ++i) {
      double d = solid.distance_to_face(neighbours[last], nodes[i]);
      for (std::size_t k = 0; k < neighbours.size() && d > size; ++k)
        if (box_distance(boxes[k], nodes[i]) < d) {
          const double dk = solid.distance_to_face(neighbours[k], nodes[i]);
          if (dk < d) d = dk, last = k;
        }
      near = d <= size;
    }
    enclosed[f.value()] = near;
  }
  for (FaceId f : solid.faces())
    if (enclosed[f.value()]) r.absorbed_face[f.value()] = 1;
  mark_edges();

  // Clusters of absorbed faces joined across feature edges, each attached to the resolved
  // face it shares the most edge length with (the largest of its own faces when none).
  std::vector<int> parent(nf + 1);
  std::iota(parent.begin(), parent.end(), 0);
  for (core::EdgeId e : solid.edges()) {
    if (!feature_edge(solid, e)) continue;
    const std::vector<FaceId> f = solid.edge_faces(e);
    if (r.absorbed_face[f[0].value()] && r.absorbed_face[f[1].value()])
      parent[find(parent, f[0].value())] = find(parent, f[1].value());
  }
  std::map<int, std::map<int, double>> shared;  // cluster -> resolved face -> edge length
  for (core::EdgeId e : solid.edges()) {
    if (!feature_edge(solid, e)) continue;
    const std::vector<FaceId> f = solid.edge_faces(e);
    for (int s = 0; s < 2; ++s) {
      const int a = f[s].value(), b = f[1 - s].value();
      if (r.absorbed_face[a] && !r.absorbed_face[b])
        shared[find(parent, a)][b] += length[e.value()];
    }
  }
  std::map<int, std::vector<FaceId>> members;  // cluster -> its faces
  for (FaceId f : solid.faces())
    if (r.absorbed_face[f.value()]) members[find(parent, f.value())].push_back(f);
  std::map<int, int> composite_of_host;
  for (const auto& [cluster, faces] : members) {
    int host = 0;
    double best = -1;
    for (const auto& [g, l] : shared[cluster])
      if (l > best || (l == best && area[g] > area[host])) best = l, host = g;
    bool own = host == 0;  // no resolved neighbour: the cluster's largest face hosts it
    if (own)
      for (FaceId f : faces)
        if (host == 0 || area[f.value()] > area[host]) host = f.value();
    auto [it, fresh] = composite_of_host.try_emplace(host, int(r.composites.size()));
    if (fresh) r.composites.push_back({FaceId(host), {FaceId(host)}});
    for (FaceId f : faces)
      if (f.value() != host) r.composites[it->second].faces.push_back(f);
  }
  r.face_boxes.resize(nf + 1);
  for (std::size_t c = 0; c < r.composites.size(); ++c) {
    Composite& comp = r.composites[c];
    std::sort(comp.faces.begin() + 1, comp.faces.end());
    for (FaceId f : comp.faces) {
      r.composite_of_face[f.value()] = int(c);
      r.face_boxes[f.value()] = solid.face_bounding_box(f);
      if (f == comp.host) continue;
      for (const Vec3& x : face_samples(tess, f, 0.25 * size, 400)) r.samples.push_back(x);
    }
  }
  constexpr std::size_t kMaxSamples = 50'000;  // the deviation's cost stays bounded
  if (r.samples.size() > kMaxSamples) {
    std::vector<Vec3> thin;
    for (std::size_t i = 0; i < kMaxSamples; ++i)
      thin.push_back(r.samples[i * r.samples.size() / kMaxSamples]);
    r.samples.swap(thin);
  }
  return r;
}

CompositeDeviation composite_deviation(const core::HexMesh& mesh, const core::MeshDomain& solid,
                                       const SmallFeatures& features) {
  CompositeDeviation r;
  if (features.empty()) return r;
  // Boundary quads: hex faces no other hex shares.
  struct Quad {
    std::array<std::int32_t, 4> n;
    int count;
  };
  std::unordered_map<std::string, Quad> faces;
  for (const core::HexNodes& h : mesh.hexes())
    for (const auto& f : core::kHexFaces) {
      std::array<std::int32_t, 4> n{h[f[0]], h[f[1]], h[f[2]], h[f[3]]}, k = n;
      std::sort(k.begin(), k.end());
      const std::string key(reinterpret_cast<const char*>(k.data()), sizeof(k));
      auto [it, fresh] = faces.try_emplace(key, Quad{n, 0});
      ++it->second.count;
    }
  // Quads on a composite: a node on one of its faces and none on a face outside it.
  std::vector<std::pair<std::array<std::int32_t, 4>, int>> on;
  std::vector<std::array<std::int32_t, 4>> boundary;
  for (const auto& [key, q] : faces) {
    if (q.count != 1) continue;
    boundary.push_back(q.n);
    int c = -1;
    bool outside = false;
    for (std::int32_t n : q.n) {
      const core::NodeClass nc = mesh.node_class(core::NodeId(n));
      if (nc.dim != 2) continue;
      const int k =
          nc.id < int(features.composite_of_face.size()) ? features.composite_of_face[nc.id] : -1;
      if (k < 0 || (c >= 0 && k != c)) outside = true;
      c = k;
    }
    if (!outside && c >= 0) on.push_back({q.n, c});
  }
  std::sort(on.begin(), on.end());  // deterministic order
  r.quads = on.size();
  if (on.empty()) return r;
  // Mesh side: the quad (bilinear) at its centre and edge midpoints, against the composite.
  std::unordered_set<std::int64_t> edges_done;
  double cell = 0;
  for (const auto& [n, c] : on) {
    std::array<Vec3, 4> p;
    for (int i = 0; i < 4; ++i) p[i] = mesh.point(core::NodeId(n[i]));
    std::vector<Vec3> points{(p[0] + p[1] + p[2] + p[3]) / 4};
    for (int i = 0; i < 4; ++i) {
      const std::int32_t a = std::min(n[i], n[(i + 1) % 4]), b = std::max(n[i], n[(i + 1) % 4]);
      cell += (p[i] - p[(i + 1) % 4]).norm();
      if (edges_done.insert((std::int64_t(a) << 32) | std::uint32_t(b)).second)
        points.push_back((p[i] + p[(i + 1) % 4]) / 2);
    }
    const FaceId host = features.composites[c].host;
    for (const Vec3& x : points) {
      FaceId f;
      const Vec3 q = features.project(solid, host, x, f);
      const double d = q.allFinite() ? (q - x).norm() : 0;
      if (d > r.mesh_side) r.mesh_side = d;
      if (d > r.max) r.max = d, r.where = x;
    }
  }
  cell = std::max(cell / double(4 * on.size()), 1e-12);
  std::sort(boundary.begin(), boundary.end());
  // CAD side: each sample of an absorbed face against every boundary quad (the real surface
  // may be followed by quads on a neighbouring face: the distance is to the mesh's boundary),
  // four triangles each about the centre, found through a hash of cells of the mean composite
  // quad edge length.
  auto cell_of = [&](const Vec3& x, int i) { return std::int64_t(std::floor(x[i] / cell)); };
  auto key_of = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return (i * 73856093) ^ (j * 19349663) ^ (k * 83492791);
  };
  std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;
  for (std::size_t q = 0; q < boundary.size(); ++q) {
    Vec3 lo = mesh.point(core::NodeId(boundary[q][0])), hi = lo;
    for (std::int32_t n : boundary[q])
      lo = lo.cwiseMin(mesh.point(core::NodeId(n))), hi = hi.cwiseMax(mesh.point(core::NodeId(n)));
    for (std::int64_t i = cell_of(lo, 0); i <= cell_of(hi, 0); ++i)
      for (std::int64_t j = cell_of(lo, 1); j <= cell_of(hi, 1); ++j)
        for (std::int64_t k = cell_of(lo, 2); k <= cell_of(hi, 2); ++k)
          grid[key_of(i, j, k)].push_back(q);
  }
  auto distance_to_quad = [&](std::size_t q, const Vec3& x) {
    std::array<Vec3, 4> p;
    for (int i = 0; i < 4; ++i) p[i] = mesh.point(core::NodeId(boundary[q][i]));
    const Vec3 m = (p[0] + p[1] + p[2] + p[3]) / 4;
    double d = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 4; ++i)
      d = std::min(d, (closest_on_triangle(x, p[i], p[(i + 1) % 4], m) - x).norm());
    return d;
  };
  for (const Vec3& x : features.samples) {
    double d = std::numeric_limits<double>::infinity();
    const std::int64_t ci = cell_of(x, 0), cj = cell_of(x, 1), ck = cell_of(x, 2);
    // Shells of cells around x, nearest first: after shell s every quad within s cells of x
    // has been seen, so a distance below that is final.
    constexpr int kShells = 4;
    int shell = 1;
    for (; shell <= kShells && d > (shell - 1) * cell; ++shell)
      for (std::int64_t i = ci - shell; i <= ci + shell; ++i)
        for (std::int64_t j = cj - shell; j <= cj + shell; ++j)
          for (std::int64_t k = ck - shell; k <= ck + shell; ++k) {
            if (std::max({std::abs(i - ci), std::abs(j - cj), std::abs(k - ck)}) != shell &&
                shell > 1)
              continue;  // seen in an inner shell
            auto it = grid.find(key_of(i, j, k));
            if (it != grid.end())
              for (std::size_t q : it->second) d = std::min(d, distance_to_quad(q, x));
          }
    if (d > (shell - 1) * cell)  // a nearer quad may lie outside the cells searched
      for (std::size_t q = 0; q < boundary.size(); ++q) d = std::min(d, distance_to_quad(q, x));
    if (d > r.cad_side) r.cad_side = d;
    if (d > r.max) r.max = d, r.where = x;
  }
  return r;
}

core::Diagnostic deviation_diagnostic(const SmallFeatures& features, const CompositeDeviation& d) {
  std::ostringstream s;
  std::vector<std::string> faces;
  s << "The mesh follows " << features.composites.size()
    << (features.composites.size() == 1 ? " composite face" : " composite faces") << " (";
  for (std::size_t c = 0; c < features.composites.size(); ++c) {
    if (c < 4) s << (c ? "; " : "") << features.composites[c].summary();
    for (FaceId f : features.composites[c].faces) faces.push_back(core::entity_name(f));
  }
  s << (features.composites.size() > 4 ? "; ..." : "") << ") with each node on the nearest of "
    << "their real faces; the largest deviation of its boundary from the real surface is " << d.max
    << " (mesh to surface " << d.mesh_side << ", absorbed faces to mesh " << d.cad_side << "; at "
    << d.where.x() << ", " << d.where.y() << ", " << d.where.z() << ", over " << d.quads
    << " boundary quads).";
  return core::make_info("absorbed_deviation", s.str(), faces);
}

}  // namespace vorohex::grid
