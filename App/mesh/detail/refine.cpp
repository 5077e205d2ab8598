#include "mesh/detail/refine.h"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace vorohex::mesh::detail {
namespace {

using core::HexMesh;
using core::NodeId;
using core::Vec3;

// Lattice position of VTK corner c in {0,1}^3.
constexpr int kCornerBits[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

int corner_at(int x, int y, int z) {
  for (int c = 0; c < 8; ++c)
    if (kCornerBits[c][0] == x && kCornerBits[c][1] == y && kCornerBits[c][2] == z) return c;
  return -1;
}

using EdgeKey = std::pair<int, int>;
using FaceKey = std::array<int, 4>;

struct Counts {
  std::size_t edges = 0, faces = 0;
};

Counts count_entities(const HexMesh& coarse) {
  std::map<EdgeKey, int> edges;
  std::map<FaceKey, int> faces;
  static constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                        {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (const core::HexNodes& h : coarse.hexes()) {
    for (const auto& e : kEdges)
      edges[{std::min(h[e[0]], h[e[1]]), std::max(h[e[0]], h[e[1]])}] = 0;
    for (const auto& f : core::kHexFaces) {
      FaceKey k{h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
      std::sort(k.begin(), k.end());
      faces[k] = 0;
    }
  }
  return {edges.size(), faces.size()};
}

// A shared quadrilateral's inner nodes in a frame every hexahedron agrees on: corner q0 is
// the smallest node index, q1 its smaller neighbour; node (i, j) lies i steps along q0->q1
// and j along q0->q3 (1..n-1 each).
struct CanonicalFace {
  std::array<int, 4> q;  // cyclic order
  std::size_t base = 0;  // index of node (1, 1)
};

class Refiner {
 public:
  Refiner(const HexMesh& coarse, int n) : coarse_(coarse), n_(n) {}

  HexMesh run() {
    out_.reserve(refined_node_count(coarse_, n_), coarse_.num_hexes() * n_ * n_ * n_);
    for (std::size_t i = 0; i < coarse_.num_nodes(); ++i) {
      const NodeId id(static_cast<std::int32_t>(i));
      out_.add_node(coarse_.point(id), coarse_.node_class(id));
    }
    const int m = n_ + 1;
    std::vector<int> lattice(static_cast<std::size_t>(m) * m * m);
    for (std::size_t h = 0; h < coarse_.num_hexes(); ++h) {
      const core::HexNodes& hex = coarse_.hexes()[h];
      const std::array<Vec3, 8> c = coarse_.corners(core::HexId(static_cast<std::int32_t>(h)));
      for (int k = 0; k <= n_; ++k)
        for (int j = 0; j <= n_; ++j)
          for (int i = 0; i <= n_; ++i) lattice[i + m * (j + m * k)] = node(hex, c, {i, j, k});
      for (int k = 0; k < n_; ++k)
        for (int j = 0; j < n_; ++j)
          for (int i = 0; i < n_; ++i) {
            core::HexNodes fine;
            for (int v = 0; v < 8; ++v)
              fine[v] = lattice[(i + kCornerBits[v][0]) +
                                m * ((j + kCornerBits[v][1]) + m * (k + kCornerBits[v][2]))];
            out_.add_hex(fine, coarse_.sub_volumes()[h]);
          }
    }
    return std::move(out_);
  }

 private:
  Vec3 trilinear(const std::array<Vec3, 8>& c, const std::array<int, 3>& ijk) const {
    Vec3 p = Vec3::Zero();
    for (int v = 0; v < 8; ++v) {
      double w = 1;
      for (int d = 0; d < 3; ++d) {
        const double t = static_cast<double>(ijk[d]) / n_;
        w *= kCornerBits[v][d] ? t : 1 - t;
      }
      p += w * c[v];
    }
    return p;
  }

  int add(const Vec3& p) { return static_cast<int>(out_.add_node(p).value()); }

  int node(const core::HexNodes& hex, const std::array<Vec3, 8>& c, const std::array<int, 3>& ijk) {
    int free_dims[3], nfree = 0;
    std::array<int, 3> fixed{};  // the corner bit of each fixed coordinate
    for (int d = 0; d < 3; ++d) {
      if (ijk[d] == 0 || ijk[d] == n_)
        fixed[d] = ijk[d] == n_;
      else
        free_dims[nfree++] = d;
    }
    auto corner = [&](std::array<int, 3> bits) {
      return hex[corner_at(bits[0], bits[1], bits[2])];
    };
    if (nfree == 0) return corner(fixed);
    if (nfree == 3) return add(trilinear(c, ijk));
    if (nfree == 1) {
      const int d = free_dims[0];
      std::array<int, 3> b0 = fixed, b1 = fixed;
      b0[d] = 0, b1[d] = 1;
      const int a = corner(b0), b = corner(b1);
      const int step = a < b ? ijk[d] : n_ - ijk[d];  // counted from the smaller index
      const EdgeKey key{std::min(a, b), std::max(a, b)};
      auto it = edges_.find(key);
      if (it == edges_.end()) {
        const std::size_t base = out_.num_nodes();
        const Vec3 pa = coarse_.point(NodeId(key.first)), pb = coarse_.point(NodeId(key.second));
        for (int s = 1; s < n_; ++s) add(pa + (pb - pa) * (static_cast<double>(s) / n_));
        it = edges_.emplace(key, base).first;
      }
      return static_cast<int>(it->second + step - 1);
    }
    // A face: local corners in cyclic order with (s, t) along the two free dimensions.
    const int d1 = free_dims[0], d2 = free_dims[1];
    std::array<int, 4> local;
    const int st[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int q = 0; q < 4; ++q) {
      std::array<int, 3> b = fixed;
      b[d1] = st[q][0], b[d2] = st[q][1];
      local[q] = corner(b);
    }
    FaceKey key = local;
    std::sort(key.begin(), key.end());
    auto it = faces_.find(key);
    if (it == faces_.end()) {
      CanonicalFace f;
      const int r = static_cast<int>(std::min_element(local.begin(), local.end()) - local.begin());
      const bool forward = local[(r + 1) % 4] < local[(r + 3) % 4];
      for (int q = 0; q < 4; ++q) f.q[q] = local[(r + (forward ? q : 4 - q)) % 4];
      f.base = out_.num_nodes();
      std::array<Vec3, 4> p;
      for (int q = 0; q < 4; ++q) p[q] = coarse_.point(NodeId(f.q[q]));
      for (int i = 1; i < n_; ++i)
        for (int j = 1; j < n_; ++j) {
          const double u = static_cast<double>(i) / n_, v = static_cast<double>(j) / n_;
          add((1 - u) * (1 - v) * p[0] + u * (1 - v) * p[1] + u * v * p[2] + (1 - u) * v * p[3]);
        }
      it = faces_.emplace(key, f).first;
    }
    const CanonicalFace& f = it->second;
    // Lattice coordinates of the local corners in the canonical frame.
    auto canon = [&](int node_index) -> std::array<int, 2> {
      const int q = static_cast<int>(std::find(f.q.begin(), f.q.end(), node_index) - f.q.begin());
      return {st[q][0] * n_, st[q][1] * n_};
    };
    const std::array<int, 2> a = canon(local[0]), b = canon(local[1]), d = canon(local[3]);
    const int s = ijk[d1], t = ijk[d2];
    const int i = a[0] + s * (b[0] - a[0]) / n_ + t * (d[0] - a[0]) / n_;
    const int j = a[1] + s * (b[1] - a[1]) / n_ + t * (d[1] - a[1]) / n_;
    return static_cast<int>(f.base + static_cast<std::size_t>(i - 1) * (n_ - 1) + (j - 1));
  }

  const HexMesh& coarse_;
  const int n_;
  HexMesh out_;
  std::map<EdgeKey, std::size_t> edges_;
  std::map<FaceKey, CanonicalFace> faces_;
};

}  // namespace

std::size_t refined_node_count(const HexMesh& coarse, int n) {
  const Counts c = count_entities(coarse);
  const std::size_t k = static_cast<std::size_t>(n - 1);
  return coarse.num_nodes() + c.edges * k + c.faces * k * k + coarse.num_hexes() * k * k * k;
}

HexMesh refine_uniformly(const HexMesh& coarse, int n) {
  if (n < 1) throw std::invalid_argument("refine_uniformly: n must be at least 1");
  return Refiner(coarse, n).run();
}

}  // namespace vorohex::mesh::detail
