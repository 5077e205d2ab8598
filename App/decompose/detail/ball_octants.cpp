#include "decompose/detail/ball_octants.h"

#include <array>
#include <cmath>

#include "occ/split_solid.h"

namespace vorohex::decompose::detail {

using core::FaceId;
using core::Vec3;
using core::VertexId;

namespace {

// The inner cube's edge, a share of the ball's radius: its far corner at about half the
// radius along the diagonal, so that the three outer blocks are about as deep as it is wide.
constexpr double kInnerCube = 0.32;

struct Octant {
  Vec3 centre = Vec3::Zero();
  std::array<Vec3, 3> axes;  // unit, from the centre to the three vertices on the sphere
  double radius = 0;
};

bool octant_of(const occ::Solid& piece, Octant& o) {
  if (piece.num_faces() != 4 || piece.num_vertices() != 4) return false;
  int spheres = 0;
  std::vector<core::SurfaceInfo> planes;
  for (int f = 1; f <= 4; ++f) {
    const core::SurfaceInfo info = piece.surface_info(FaceId(f));
    if (info.kind == core::SurfaceKind::sphere) {
      ++spheres;
      o.centre = info.origin;
      o.radius = info.radius;
    } else if (info.kind == core::SurfaceKind::plane) {
      planes.push_back(info);
    }
  }
  if (spheres != 1 || planes.size() != 3 || !(o.radius > 0)) return false;
  const double tol = 1e-6 * o.radius + piece.tolerance();
  bool centre_is_vertex = false;
  int on_sphere = 0;
  for (int v = 1; v <= 4; ++v) {
    const Vec3 p = piece.vertex_point(VertexId(v));
    const double d = (p - o.centre).norm();
    if (d <= tol) {
      centre_is_vertex = true;
    } else if (std::abs(d - o.radius) <= tol && on_sphere < 3) {
      o.axes[on_sphere++] = (p - o.centre) / d;
    }
  }
  if (!centre_is_vertex || on_sphere != 3) return false;
  for (const core::SurfaceInfo& pl : planes)
    if (std::abs(pl.direction.normalized().dot(o.centre - pl.origin)) > tol) return false;
  for (int i = 0; i < 3; ++i)
    if (std::abs(o.axes[i].dot(o.axes[(i + 1) % 3])) > 1e-6) return false;
  return true;
}

// The point at s, t, u along the octant's axes i, i + 1, i + 2 from its centre.
Vec3 at(const Octant& o, int i, double s, double t, double u) {
  return o.centre + s * o.axes[i] + t * o.axes[(i + 1) % 3] + u * o.axes[(i + 2) % 3];
}

// The six faces that part the octant: the inner cube's three faces inside it, and from each
// of the cube's three edges away from the centre the diagonal plane between two blocks, out
// past the sphere.
std::vector<std::vector<Vec3>> parting_faces(const Octant& o) {
  const double a = kInnerCube * o.radius, far = 1.5 * o.radius;
  std::vector<std::vector<Vec3>> tools;
  for (int i = 0; i < 3; ++i) {
    // The cube's face across axis i; the plane where i and i + 1 are equal, i + 2 below both.
    tools.push_back({at(o, i, a, 0, 0), at(o, i, a, a, 0), at(o, i, a, a, a), at(o, i, a, 0, a)});
    tools.push_back(
        {at(o, i, a, a, 0), at(o, i, far, far, 0), at(o, i, far, far, far), at(o, i, a, a, a)});
  }
  return tools;
}

// The faces that part a fillet's strip beside octant `o` across its axis i (the strip runs
// from the octant's face across that axis away from it, `length` at most): the octant's
// parting faces along that axis carried along the strip, so that its three blocks meet the
// octant's.
std::vector<std::vector<Vec3>> strip_parting_faces(const Octant& o, int i, double length) {
  const double a = kInnerCube * o.radius, far = 1.5 * o.radius;
  const double from = -length, to = 0.5 * a;
  const auto p = [&](double s, double t, double u) { return at(o, i, s, t, u); };
  return {{p(from, a, 0), p(to, a, 0), p(to, a, a), p(from, a, a)},           // across i + 1
          {p(from, 0, a), p(to, 0, a), p(to, a, a), p(from, a, a)},           // across i + 2
          {p(from, a, a), p(to, a, a), p(to, far, far), p(from, far, far)}};  // i + 1 = i + 2
}

// Whether `piece` is a fillet's strip beside octant `o` across its axis i: it has the
// octant's cylinder about the line through the centre along that axis, and lies on the far
// side of the octant's face across it.
bool is_strip_beside(const occ::Solid& piece, const Octant& o, int i) {
  const Vec3& d = o.axes[i];
  const double tol = 1e-6 * o.radius + piece.tolerance();
  bool cylinder = false;
  for (int f = 1; f <= piece.num_faces() && !cylinder; ++f) {
    const core::SurfaceInfo info = piece.surface_info(FaceId(f));
    if (info.kind != core::SurfaceKind::cylinder || std::abs(info.radius - o.radius) > tol)
      continue;
    const Vec3 axis = info.direction.normalized();
    const Vec3 off = info.origin - o.centre;
    cylinder = std::abs(std::abs(axis.dot(d)) - 1) < 1e-9 && (off - off.dot(d) * d).norm() <= tol;
  }
  if (!cylinder) return false;
  const core::BoundingBox b = piece.bounding_box();
  const Vec3 mid = 0.5 * (b.min + b.max);
  return (mid - o.centre).dot(d) < 0;
}

}  // namespace

int split_ball_octants(std::vector<occ::Solid>& pieces, std::vector<double>& volume,
                       double time_limit) {
  // Parts `pieces[k]` by `tools` into `parts` blocks; false (nothing changed) otherwise.
  std::vector<char> parted(pieces.size(), 0);
  std::vector<std::vector<occ::Solid>> blocks(pieces.size());
  std::vector<std::vector<double>> block_volumes(pieces.size());
  auto part = [&](std::size_t k, const std::vector<std::vector<Vec3>>& tools, std::size_t parts,
                  double tol) {
    occ::SplitResult s = occ::split_solid(pieces[k], tools, tol, time_limit);
    if (!s.ok || s.pieces.size() != parts) return false;
    std::vector<double> v;
    double sum = 0;
    for (const occ::Solid& b : s.pieces) sum += v.emplace_back(b.volume());
    if (std::abs(sum - volume[k]) > 1e-6 * volume[k]) return false;
    blocks[k] = std::move(s.pieces);
    block_volumes[k] = std::move(v);
    parted[k] = 1;
    return true;
  };
  std::vector<Octant> octants;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    Octant o;
    if (octant_of(pieces[k], o) && part(k, parting_faces(o), 4, 1e-7 * o.radius))
      octants.push_back(o);
  }
  // The fillets' strips beside them, each parted once (a strip between two corners is beside
  // both: the same faces).
  for (const Octant& o : octants)
    for (int i = 0; i < 3; ++i)
      for (std::size_t k = 0; k < pieces.size(); ++k) {
        if (parted[k] || !is_strip_beside(pieces[k], o, i)) continue;
        const double length = pieces[k].bounding_box().diagonal() + o.radius;
        part(k, strip_parting_faces(o, i, length), 3, 1e-7 * o.radius);
      }
  std::vector<occ::Solid> out;
  std::vector<double> out_volume;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    if (!parted[k]) {
      out.push_back(std::move(pieces[k]));
      out_volume.push_back(volume[k]);
      continue;
    }
    for (std::size_t b = 0; b < blocks[k].size(); ++b) {
      out_volume.push_back(block_volumes[k][b]);
      out.push_back(std::move(blocks[k][b]));
    }
  }
  pieces = std::move(out);
  volume = std::move(out_volume);
  return int(octants.size());
}

}  // namespace vorohex::decompose::detail
