#include "mesh/map_block.h"

#include "core/option_checks.h"
#include "mesh/detail/sizing.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace vorohex::mesh {

using core::EdgeId;
using core::FaceId;
using core::NodeClass;
using core::Vec3;
using core::VertexId;

void MapBlockOptions::validate() const {
  core::require_positive("MapBlockOptions.size", size);
  core::require_at_least("MapBlockOptions.max_intervals", max_intervals, 1);
}

namespace {

// The block structure: corners labelled by (i, j, k) in {0,1}^3 as index i + 2j + 4k.
struct BlockEdge {
  EdgeId id;
  bool forward = true;  // the edge runs from the corner with bit d = 0 to bit d = 1
};

struct Block {
  std::array<VertexId, 8> corner;
  // edges[d][m]: the edge along direction d whose other two bits (lower direction first)
  // are m = b_lo + 2 b_hi.
  std::array<std::array<BlockEdge, 4>, 3> edges;
  std::array<FaceId, 6> faces;  // faces[2d + b]: the face where bit d equals b
};

using core::OrientedEdge;
using Solid = core::MeshDomain;

VertexId start_of(const Solid& s, const OrientedEdge& e) {
  return e.forward ? s.edge_first_vertex(e.edge) : s.edge_last_vertex(e.edge);
}

// The two directions other than d, lower first.
std::array<int, 2> others(int d) {
  return {d == 0 ? 1 : 0, d == 2 ? 1 : 2};
}

// Exact volume of the trilinear hexahedron through 8 lattice-ordered corners
// (c[i + 2j + 4k]) by 2x2x2 Gauss quadrature of det J (exact: degree <= 2 per variable).
double trilinear_volume(const std::array<Vec3, 8>& c) {
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  double vol = 0;
  for (double u : g)
    for (double v : g)
      for (double w : g) {
        const double U[2] = {1 - u, u}, V[2] = {1 - v, v}, W[2] = {1 - w, w};
        Vec3 du = Vec3::Zero(), dv = Vec3::Zero(), dw = Vec3::Zero();
        for (int n = 0; n < 8; ++n) {
          const int i = n & 1, j = (n >> 1) & 1, k = n >> 2;
          const double si = i ? 1 : -1, sj = j ? 1 : -1, sk = k ? 1 : -1;
          du += si * V[j] * W[k] * c[n];
          dv += sj * U[i] * W[k] * c[n];
          dw += sk * U[i] * V[j] * c[n];
        }
        vol += du.cross(dv).dot(dw) / 8;
      }
  return vol;
}

std::string count_of(int n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string find_block(const Solid& s, Block& block, std::vector<std::string>& entities) {
  auto fail = [&](std::string entity, std::string why) {
    if (!entity.empty()) entities.push_back(std::move(entity));
    return why;
  };
  if (s.num_faces() != 6)
    return fail("", "the solid has " + count_of(s.num_faces(), "face", "faces") + ", not 6");
  for (EdgeId e : s.edges()) {
    if (s.edge_is_degenerated(e))
      return fail(core::entity_name(e), core::entity_name(e) + " is degenerated");
    if (s.edge_first_vertex(e) == s.edge_last_vertex(e))
      return fail(core::entity_name(e), core::entity_name(e) + " is closed (one vertex)");
  }
  std::vector<std::array<VertexId, 4>> quads;
  for (FaceId f : s.faces()) {
    const auto wires = s.face_wires(f);
    const std::string name = core::entity_name(f);
    if (wires.size() != 1)
      return fail(name, name + " has " + std::to_string(wires.size()) + " wires (holes)");
    if (wires[0].size() != 4)
      return fail(name, name + " has " + std::to_string(wires[0].size()) + " edges");
    std::array<VertexId, 4> q;
    for (int i = 0; i < 4; ++i) q[i] = start_of(s, wires[0][i]);
    quads.push_back(q);
  }
  if (s.num_edges() != 12)
    return fail("", "the solid has " + count_of(s.num_edges(), "edge", "edges") + ", not 12");
  if (s.num_vertices() != 8)
    return fail("",
                "the solid has " + count_of(s.num_vertices(), "vertex", "vertices") + ", not 8");

  // Vertex adjacency (index 1..8).
  std::vector<std::vector<VertexId>> nbrs(9);
  for (EdgeId e : s.edges()) {
    const VertexId a = s.edge_first_vertex(e), b = s.edge_last_vertex(e);
    nbrs[a.value()].push_back(b);
    nbrs[b.value()].push_back(a);
  }
  for (VertexId v : s.vertices())
    if (nbrs[v.value()].size() != 3)
      return fail(core::entity_name(v), core::entity_name(v) + " is on " +
                                            std::to_string(nbrs[v.value()].size()) +
                                            " edges, not 3");

  // Label vertex 1 as (0,0,0), its neighbours as the unit steps, and the far corner of
  // each face through two of them as their sum; the last vertex is (1,1,1).
  std::array<int, 9> label;
  label.fill(-1);
  const VertexId v0(1);
  label[1] = 0;
  for (int n = 0; n < 3; ++n) label[nbrs[1][n].value()] = 1 << n;
  auto has = [](const std::array<VertexId, 4>& q, VertexId v) {
    return std::find(q.begin(), q.end(), v) != q.end();
  };
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b)
      for (const auto& q : quads)
        if (has(q, v0) && has(q, nbrs[1][a]) && has(q, nbrs[1][b]))
          for (VertexId v : q)
            if (label[v.value()] < 0) label[v.value()] = (1 << a) | (1 << b);
  for (int v = 1; v <= 8; ++v)
    if (label[v] < 0) label[v] = 7;
  std::array<int, 8> seen{};
  for (int v = 1; v <= 8; ++v) ++seen[label[v]];
  const std::string not_block = "the faces do not form a topological block";
  for (int n : seen)
    if (n != 1) return fail("", not_block);
  for (EdgeId e : s.edges()) {
    const int x = label[s.edge_first_vertex(e).value()] ^ label[s.edge_last_vertex(e).value()];
    if (x != 1 && x != 2 && x != 4) return fail(core::entity_name(e), not_block);
  }

  // Right-handed labelling: positive trilinear volume of the corner hex, else swap i and j.
  std::array<Vec3, 8> pts;
  for (int v = 1; v <= 8; ++v) pts[label[v]] = s.vertex_point(VertexId(v));
  if (trilinear_volume(pts) < 0) {
    for (int v = 1; v <= 8; ++v) {
      const int l = label[v];
      label[v] = (l & 4) | ((l & 1) << 1) | ((l & 2) >> 1);
    }
  }
  for (int v = 1; v <= 8; ++v) block.corner[label[v]] = VertexId(v);

  for (EdgeId e : s.edges()) {
    const int l0 = label[s.edge_first_vertex(e).value()], l1 = label[s.edge_last_vertex(e).value()];
    const int bit = l0 ^ l1;
    const int d = bit == 1 ? 0 : bit == 2 ? 1 : 2;
    const int low = std::min(l0, l1);
    const auto o = others(d);
    const int m = ((low >> o[0]) & 1) + 2 * ((low >> o[1]) & 1);
    block.edges[d][m] = {e, (l0 & bit) == 0};
  }
  for (std::size_t f = 0; f < quads.size(); ++f) {
    int all_and = 7, all_or = 0;
    for (VertexId v : quads[f]) all_and &= label[v.value()], all_or |= label[v.value()];
    const int fixed = all_and | (~all_or & 7);  // bits equal on all four corners
    if (fixed != 1 && fixed != 2 && fixed != 4)
      return fail(core::entity_name(FaceId(int(f) + 1)), not_block);
    const int d = fixed == 1 ? 0 : fixed == 2 ? 1 : 2;
    block.faces[2 * d + ((all_and >> d) & 1)] = FaceId(int(f) + 1);
  }
  return "";
}

struct Plan {
  bool ok = false;
  Block block;
  std::array<int, 3> intervals{};
  std::vector<core::Diagnostic> diagnostics;
};

Plan plan(const Solid& solid, const MapBlockOptions& options) {
  options.validate();
  Plan p;
  std::vector<std::string> entities;
  const std::string why = find_block(solid, p.block, entities);
  if (!why.empty()) {
    p.diagnostics.push_back(core::make_error(
        "not_applicable", "The solid is not a mapped block: " + why + ".", entities));
    return p;
  }
  for (int d = 0; d < 3; ++d) {
    double mean = 0, want = 0;
    for (const BlockEdge& e : p.block.edges[d]) mean += solid.edge_length(e.id) / 4;
    // With local sizes, the finest count any of the four parallel edges asks for.
    if (detail::graded(options.size_field)) {
      for (const BlockEdge& e : p.block.edges[d])
        want = std::max(want, detail::edge_segments(solid, e.id, options.size, options.size_field));
    } else {
      want = mean / options.size;
    }
    double n = std::max(1.0, std::round(want));
    if (!options.edge_intervals.empty()) {
      std::vector<int> given;
      std::vector<std::string> names;
      for (const BlockEdge& e : p.block.edges[d]) {
        const int i = e.id.value();
        given.push_back(i < int(options.edge_intervals.size()) ? options.edge_intervals[i] : 0);
        names.push_back(core::entity_name(e.id));
      }
      if (given[0] < 1 || std::count(given.begin(), given.end(), given[0]) != 4) {
        std::ostringstream s;
        s << "The given intervals of the four parallel edges of one block direction differ or "
             "are missing ("
          << names[0] << " " << given[0] << ", " << names[1] << " " << given[1] << ", " << names[2]
          << " " << given[2] << ", " << names[3] << " " << given[3] << ").";
        p.diagnostics.push_back(core::make_error("intervals_mismatch", s.str(), names));
        return p;
      }
      n = given[0];
    }
    if (n > options.max_intervals) {
      std::vector<std::string> names;
      for (const BlockEdge& e : p.block.edges[d]) names.push_back(core::entity_name(e.id));
      std::ostringstream s;
      s << "Edges of length " << mean << " at size " << options.size << " need " << n
        << " intervals, more than max_intervals = " << options.max_intervals << ".";
      p.diagnostics.push_back(core::make_error("too_many_intervals", s.str(), names));
      return p;
    }
    p.intervals[d] = static_cast<int>(n);
  }
  const auto& n = p.intervals;
  const double nodes = double(n[0] + 1) * (n[1] + 1) * (n[2] + 1);
  if (nodes > double(std::numeric_limits<std::int32_t>::max())) {
    p.diagnostics.push_back(core::make_error(
        "too_many_nodes", "The block would need " + std::to_string(nodes) +
                              " nodes, more than a mesh can index; use a larger size."));
    return p;
  }
  p.ok = true;
  return p;
}

}  // namespace

Applicability map_block_applicable(const core::MeshDomain& solid) {
  Block block;
  std::vector<std::string> entities;
  Applicability a;
  try {
    a.reason = find_block(solid, block, entities);
  } catch (const std::exception& e) {
    a.reason = std::string("its topology cannot be explored (") + e.what() + ")";
  }
  a.ok = a.reason.empty();
  return a;
}

std::array<std::vector<core::EdgeId>, 3> map_block_edge_groups(const core::MeshDomain& solid) {
  std::array<std::vector<core::EdgeId>, 3> groups;
  Block block;
  std::vector<std::string> entities;
  try {
    if (!find_block(solid, block, entities).empty()) return groups;
  } catch (const std::exception&) {
    return groups;
  }
  for (int d = 0; d < 3; ++d)
    for (const BlockEdge& e : block.edges[d]) groups[d].push_back(e.id);
  return groups;
}

MapBlockEstimate map_block_evaluate(const core::MeshDomain& solid, const MapBlockOptions& options) {
  const Plan p = plan(solid, options);
  MapBlockEstimate e;
  if (!p.ok) return e;  // map_block refuses: it produces nothing
  e.intervals = p.intervals;
  const auto& n = p.intervals;
  e.nodes = std::size_t(n[0] + 1) * (n[1] + 1) * (n[2] + 1);
  e.hexes = std::size_t(n[0]) * n[1] * n[2];
  return e;
}

MapBlockResult map_block(const core::MeshDomain& solid, const MapBlockOptions& options,
                         const core::Progress& progress) {
  MapBlockResult result;
  Plan p = plan(solid, options);  // throws std::invalid_argument on bad options
  result.diagnostics = std::move(p.diagnostics);
  if (!p.ok) return result;
  result.intervals = p.intervals;
  const Block& b = p.block;
  const std::array<int, 3> n = p.intervals;
  const std::int64_t sx = 1, sy = n[0] + 1, sz = std::int64_t(n[0] + 1) * (n[1] + 1);
  const std::array<std::int64_t, 3> stride = {sx, sy, sz};
  const std::size_t num_nodes = std::size_t(sz) * (n[2] + 1);
  std::vector<Vec3> P(num_nodes);
  std::vector<NodeClass> C(num_nodes, NodeClass::interior());
  auto at = [&](int i, int j, int k) { return i * sx + j * sy + k * sz; };
  const char* stage = "map_block";
  auto cancelled = [&] {
    if (!progress.cancelled()) return false;
    result.diagnostics.push_back(core::make_error("cancelled", "Mapped meshing was cancelled."));
    result.ok = false;
    return true;
  };

  try {
    // Corners.
    for (int c = 0; c < 8; ++c) {
      const std::int64_t id = at((c & 1) * n[0], ((c >> 1) & 1) * n[1], (c >> 2) * n[2]);
      P[id] = solid.vertex_point(b.corner[c]);
      C[id] = NodeClass::on(b.corner[c]);
    }
    // Edge rows by arc length.
    for (int d = 0; d < 3; ++d) {
      const auto o = others(d);
      for (int m = 0; m < 4; ++m) {
        const BlockEdge& e = b.edges[d][m];
        std::vector<Vec3> pts =
            detail::edge_points(solid, e.id, n[d], options.size_field, options.edge_nodes);
        if (!e.forward) std::reverse(pts.begin(), pts.end());
        const std::int64_t base =
            (m & 1) * n[o[0]] * stride[o[0]] + (m >> 1) * n[o[1]] * stride[o[1]];
        for (int t = 1; t < n[d]; ++t) {
          P[base + t * stride[d]] = pts[t];
          C[base + t * stride[d]] = NodeClass::on(e.id);
        }
      }
    }
    // Face grids: 2-D transfinite interpolation of the edge rows, projected when curved.
    for (int d = 0; d < 3; ++d) {
      const auto o = others(d);
      const int na = n[o[0]], nc = n[o[1]];
      const std::int64_t sa = stride[o[0]], sc = stride[o[1]];
      for (int side = 0; side < 2; ++side) {
        const FaceId f = b.faces[2 * d + side];
        const bool curved = !solid.face_is_planar(f);
        const std::int64_t base = side * n[d] * stride[d];
        const Vec3 p00 = P[base], p10 = P[base + na * sa], p01 = P[base + nc * sc],
                   p11 = P[base + na * sa + nc * sc];
        for (int t = 1; t < nc; ++t) {
          const double v = double(t) / nc;
          const Vec3 left = P[base + t * sc], right = P[base + na * sa + t * sc];
          for (int s = 1; s < na; ++s) {
            const double u = double(s) / na;
            const Vec3 q =
                (1 - u) * left + u * right + (1 - v) * P[base + s * sa] +
                v * P[base + s * sa + nc * sc] -
                ((1 - u) * (1 - v) * p00 + u * (1 - v) * p10 + (1 - u) * v * p01 + u * v * p11);
            const std::int64_t id = base + s * sa + t * sc;
            P[id] = curved ? solid.project_to_face(f, q) : q;
            C[id] = NodeClass::on(f);
          }
        }
      }
      if (cancelled()) return result;
    }
  } catch (const std::exception& e) {
    result.diagnostics.push_back(core::make_error(
        "geometry_error", std::string("Placing the block's boundary nodes failed: ") + e.what()));
    return result;
  }

  // Interior: 3-D transfinite interpolation (faces - edges + corners), no OCCT calls.
  const int n0 = n[0], n1 = n[1], n2 = n[2];
  Vec3 corner[8];
  for (int c = 0; c < 8; ++c) corner[c] = P[at((c & 1) * n0, ((c >> 1) & 1) * n1, (c >> 2) * n2)];
  for (int k = 1; k < n2; ++k) {
    const double w = double(k) / n2;
    for (int j = 1; j < n1; ++j) {
      const double v = double(j) / n1;
      for (int i = 1; i < n0; ++i) {
        const double u = double(i) / n0;
        const Vec3 faces = (1 - u) * P[at(0, j, k)] + u * P[at(n0, j, k)] +
                           (1 - v) * P[at(i, 0, k)] + v * P[at(i, n1, k)] +
                           (1 - w) * P[at(i, j, 0)] + w * P[at(i, j, n2)];
        const Vec3 edges = (1 - v) * (1 - w) * P[at(i, 0, 0)] + v * (1 - w) * P[at(i, n1, 0)] +
                           (1 - v) * w * P[at(i, 0, n2)] + v * w * P[at(i, n1, n2)] +
                           (1 - u) * (1 - w) * P[at(0, j, 0)] + u * (1 - w) * P[at(n0, j, 0)] +
                           (1 - u) * w * P[at(0, j, n2)] + u * w * P[at(n0, j, n2)] +
                           (1 - u) * (1 - v) * P[at(0, 0, k)] + u * (1 - v) * P[at(n0, 0, k)] +
                           (1 - u) * v * P[at(0, n1, k)] + u * v * P[at(n0, n1, k)];
        const double U[2] = {1 - u, u}, V[2] = {1 - v, v}, W[2] = {1 - w, w};
        Vec3 corners = Vec3::Zero();
        for (int c = 0; c < 8; ++c) corners += U[c & 1] * V[(c >> 1) & 1] * W[c >> 2] * corner[c];
        P[at(i, j, k)] = faces - edges + corners;
      }
    }
    progress.report(stage, 0.5 * k / n2);
    if (cancelled()) return result;
  }

  // The labelling made the corner hex right-handed, but where the block's eight corners
  // lie in one plane (a half annulus, its corners on the line across it) that hex is flat
  // and its sign says nothing: the lattice's own volume decides.
  double volume = 0;
  for (int k = 0; k < n2; ++k)
    for (int j = 0; j < n1; ++j)
      for (int i = 0; i < n0; ++i) {
        std::array<Vec3, 8> c;
        for (int n = 0; n < 8; ++n) c[n] = P[at(i + (n & 1), j + ((n >> 1) & 1), k + (n >> 2))];
        volume += trilinear_volume(c);
      }
  const bool mirrored = volume < 0;
  core::HexMesh& mesh = result.mesh;
  mesh.reserve(num_nodes, std::size_t(n0) * n1 * n2);
  for (std::size_t id = 0; id < num_nodes; ++id) mesh.add_node(P[id], C[id]);
  std::vector<Vec3>().swap(P);
  for (int k = 0; k < n2; ++k) {
    for (int j = 0; j < n1; ++j) {
      for (int i = 0; i < n0; ++i) {
        const auto a = static_cast<std::int32_t>(at(i, j, k));
        const auto y = static_cast<std::int32_t>(sy), z = static_cast<std::int32_t>(sz);
        if (mirrored)
          mesh.add_hex({a, a + y, a + 1 + y, a + 1, a + z, a + y + z, a + 1 + y + z, a + 1 + z}, 0);
        else
          mesh.add_hex({a, a + 1, a + 1 + y, a + y, a + z, a + 1 + z, a + 1 + y + z, a + y + z}, 0);
      }
    }
    progress.report(stage, 0.5 + 0.5 * (k + 1) / n2);
    if (cancelled()) {
      result.mesh = core::HexMesh();
      return result;
    }
  }
  result.ok = true;
  return result;
}

}  // namespace vorohex::mesh
