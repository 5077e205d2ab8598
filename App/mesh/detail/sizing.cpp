#include "mesh/detail/sizing.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/face_cusp.h"

namespace vorohex::mesh::detail {

using core::Vec3;

namespace {

// Samples per edge for the integral: fine enough that the size changes little between two.
int samples(double length, const core::SizeField& field) {
  const double step = 0.25 * field.min_size();
  return std::clamp(int(std::ceil(length / step)), 32, 2000);
}

}  // namespace

bool graded(const core::SizeField* field) {
  return field != nullptr && !field->uniform();
}

double size_at(const Vec3& p, double size, const core::SizeField* field) {
  return graded(field) ? field->at(p) : size;
}

double edge_segments(const core::MeshDomain& s, core::EdgeId e, double size,
                     const core::SizeField* field) {
  const double length = s.edge_length(e);
  if (!graded(field)) return length / size;
  return field->segments_along(s.edge_points_by_length(e, samples(length, *field)));
}

namespace {

// Where the n-1 inner points at equal shares of a cumulative integral fall: per point, the
// sample k before it and the fraction w of the way to sample k + 1.
std::vector<std::pair<std::size_t, double>> equal_shares(const std::vector<double>& c, int n) {
  std::vector<std::pair<std::size_t, double>> out;
  std::size_t k = 0;
  for (int i = 1; i < n; ++i) {
    const double t = c.back() * double(i) / n;
    while (k + 2 < c.size() && c[k + 1] < t) ++k;
    const double span = c[k + 1] - c[k];
    out.emplace_back(k, span > 0 ? std::clamp((t - c[k]) / span, 0.0, 1.0) : 0.0);
  }
  return out;
}

}  // namespace

std::vector<Vec3> graded_points(const std::vector<Vec3>& polyline, int n,
                                const core::SizeField& field) {
  std::vector<Vec3> out;
  out.reserve(n + 1);
  out.push_back(polyline.front());
  for (const auto& [k, w] : equal_shares(field.cumulative(polyline), n))
    out.push_back((1 - w) * polyline[k] + w * polyline[k + 1]);
  out.push_back(polyline.back());
  return out;
}

namespace {

// The corner angle a quad at a cusp should get at least (its hexahedra's scaled Jacobian
// there is about its sine: 0.3).
const double kCuspAngle = std::asin(0.3);

// A cusp's angle as edge e (one of its two) sees it: with e's chord at l_e and the other's
// at l_o.
struct CuspSide {
  CuspSide(const core::MeshDomain& domain, const core::Cusp& cusp, bool in)
      : s(domain), c(cusp), e_is_in(in) {
    tiny = 0.01 * std::min(own_length(), other_length());
    tangents = angle(tiny, tiny);
  }
  const core::MeshDomain& s;
  const core::Cusp& c;
  bool e_is_in;
  double tiny = 0;      // a chord length that stands for the tangent
  double tangents = 0;  // the angle between the two edges' tangents (about 0)
  double angle(double l_e, double l_o) const {
    return e_is_in ? core::cusp_signed_angle(s, c, l_e, l_o)
                   : core::cusp_signed_angle(s, c, l_o, l_e);
  }
  double other_length() const { return s.edge_length((e_is_in ? c.out : c.in).edge); }
  double own_length() const { return s.edge_length((e_is_in ? c.in : c.out).edge); }
  // e's own part of the angle: its chord at l against the other's tangent.
  double part(double l) const { return angle(l, tiny) - tangents; }
  CuspSide other() const { return {s, c, !e_is_in}; }
};

// Where both edges of a point curve the same way (a crescent between a circle and a larger
// one: HexMe i11's plate, rounded with radius 65, tangent to its tube of radius 37.5), the
// edge that curves less closes the corner as its chord lengthens (its part is negative): its
// segment at the point is shortened, to at least a quarter, until it takes at most a fifth of
// what the other edge's chord opens (estimated at `from`, or that edge's length). Else the
// chords cross once the other edge's segment is capped (i11: at a vertex 8 units along it,
// with segments of 9 along the larger circle), and no quad mesh of the face exists.
double closing_segment(const CuspSide& side, double from) {
  const double opens = std::max(0.0, side.other().part(std::min(from, side.other_length())));
  double l = from;
  while (l > 0.25 * from && side.part(l) < -0.2 * opens) l = std::max(0.25 * from, 0.8 * l);
  return l;
}

// What an end of an edge at a point asks for (cusp_segment).
struct CuspEnd {
  double length = 0;     // the segment at the point; 0: no point at that end
  bool closing = false;  // shortened (closing_segment), and graded up from there
  double second = 0;     // closing: the second node's distance from the point (0: graded)
};

// Where an edge closes the corner (closing_segment), the ladder's quad at the point has
// this edge's first two nodes and the other edge's first: its corner at the first node is
// nearly straight, 180 degrees less the turn of this edge's chords there (on a circle of
// radius R, the second node's distance over 2 R). The second node goes as far as that turn
// takes to reach kCuspAngle, at most `farthest` and 1.4 times the other edge's first node
// (farther, the quad's corner at the second node closes). With segments graded from the
// short first one, the turn stayed near 9 degrees: a plate's outline of radius 20 with a
// boss of radius 10 inside, tangent to it, at size 2.3: hexahedra at 0.159 there.
// 0 (graded as before) where the other edge ends before its first node opens the point to
// kCuspAngle: that node is then all the quad reaches across, and a second node far along
// this edge leaves the quad no positive corner (HexMe i11: the other edge ends 8 units from
// the point, at a seam's vertex, and its face's quad mesh failed).
double second_node(const CuspSide& side, double first, double farthest) {
  const CuspSide other = side.other();
  const double other_most = std::min(farthest, other.own_length());
  double lo = std::min(2 * first, other_most);  // the other edge's first node, lengthened
  while (lo < other_most && other.angle(lo, first) < kCuspAngle)
    lo = std::min(other_most, 1.2 * lo);
  if (other.angle(lo, first) < kCuspAngle) return 0;
  const double most = std::min(farthest, 1.4 * lo);
  double l = 2 * first;
  while (l < most && -side.part(l) < kCuspAngle) l = std::min(most, 1.2 * l);
  return l > 1.5 * first ? l : 0;
}

// How long the segment of edge e next to vertex v should be where a face of e comes to a
// point there (core/face_cusp.h; 0 where none does): long enough that the chords from v along
// both edges of the point open to kCuspAngle, at most `most`. A quad at such a corner has the
// angle of those chords; with segments of the size, a plate's outline tangent to a tube of
// radius r gives about size / (2 r) radians (HexMe i14: 7 degrees, hexahedra at 0.08-0.15).
// An edge whose chord closes the corner instead is shortened (closing_segment); the other
// edge's lengthening then counts with that.
// `at_last`: at the edge's last vertex (a closed edge has the vertex at both ends; a wire
// runs into a point along the edge that ends there and out along the one that starts there).
CuspEnd cusp_segment(const core::MeshDomain& s, core::EdgeId e, bool at_last, double from,
                     double most, double farthest) {
  const core::VertexId v = at_last ? s.edge_last_vertex(e) : s.edge_first_vertex(e);
  double longest = 0, shortest = 0, second = 0;  // 0: none asked for
  for (core::FaceId f : s.edge_faces(e))
    for (const core::Cusp& c : core::cusps_at(s, f, v)) {
      const bool in = c.in.edge == e && c.in.forward == at_last;
      const bool out = c.out.edge == e && c.out.forward != at_last;
      if (c.vertex != v || (!in && !out)) continue;
      const CuspSide side(s, c, in);
      if (side.part(from) < 0) {
        const double l = closing_segment(side, from);
        if (shortest <= 0 || l < shortest) second = second_node(side, l, farthest);
        shortest = shortest > 0 ? std::min(shortest, l) : l;
        continue;
      }
      const CuspSide other = side.other();
      const double other_from = std::min(from, other.own_length());
      const bool other_closes = other.part(other_from) < 0;
      const double l_other = other_closes ? closing_segment(other, other_from) : 0;
      double l = from;
      while (l < most && side.angle(l, other_closes ? l_other : l) < kCuspAngle)
        l = std::min(most, 1.2 * l);
      longest = std::max(longest, l);
    }
  if (shortest > 0) return {shortest, true, second};
  return {longest, false, 0};
}

// `points` (n + 1 on edge e, first to last vertex) with the first and last segments
// lengthened where a face comes to a point at that end (cusp_segment), the inner points
// moved proportionally between them.
std::vector<Vec3> widened_at_cusps(const core::MeshDomain& s, core::EdgeId e,
                                   std::vector<Vec3> points) {
  const int n = int(points.size()) - 1;
  if (n < 2 || s.edge_is_degenerated(e)) return points;
  // Fractions of the length along the points' own chords.
  std::vector<double> u(n + 1, 0.0);
  for (int i = 1; i <= n; ++i) u[i] = u[i - 1] + (points[i] - points[i - 1]).norm();
  const double length = u[n];
  if (!(length > 0)) return points;
  for (double& x : u) x /= length;
  // At most three segments' worth, and leaving the other segments at least half their
  // mean length (with points at both ends, each end gets half of what is left for both).
  const double mean = length / n;
  const double most = std::min(3.0 * mean, length - 0.5 * (n - 1) * mean);
  const double farthest = std::min(4.5 * mean, length - 0.5 * (n - 1) * mean);
  CuspEnd e0 = cusp_segment(s, e, false, u[1] * length, most, farthest);
  CuspEnd e1 = cusp_segment(s, e, true, (1 - u[n - 1]) * length, most, farthest);
  if (e0.length <= 0 && e1.length <= 0) return points;
  const double both = length - 0.5 * (n - 2) * mean;  // what the two end segments may have
  if (!e0.closing && !e1.closing && e0.length > 0 && e1.length > 0 &&
      e0.length + e1.length > both) {
    const double share = std::max(0.5 * both, mean);
    e0.length = std::min(e0.length, share), e1.length = std::min(e1.length, share);
  }
  // The nodes' distances from each end that a point asks for: the lengthened segment; or
  // the shortened one, then segments growing by 1.5 while shorter than the mean (a ladder
  // of quads at the point needs two nodes of this edge where the other edge has one:
  // cusp_ladder.h), using at most half the inner nodes.
  auto ends = [&](const CuspEnd& c) {
    std::vector<double> at;
    if (c.length <= 0) return at;
    if (!c.closing) return std::vector<double>{c.length};
    if (c.second > c.length && (n - 1) / 2 >= 2) return std::vector<double>{c.length, c.second};
    double segment = c.length, sum = 0;
    while (int(at.size()) < std::max(1, (n - 1) / 2)) {
      at.push_back(sum += segment);
      if ((segment *= 1.5) >= 0.9 * mean) break;
    }
    return at;
  };
  const std::vector<double> head = ends(e0), tail = ends(e1);
  std::vector<double> w(n + 1, 0.0);
  w[n] = 1;
  const int h = int(head.size()), t = int(tail.size());
  if (h + t > n - 1) {  // two inner nodes asked for, one there (n == 2)
    w[1] = 0.5 * (head.front() + length - tail.front()) / length;
  } else {
    for (int i = 1; i <= h; ++i) w[i] = head[i - 1] / length;
    for (int i = 1; i <= t; ++i) w[n - i] = 1 - tail[i - 1] / length;
    // The nodes between keep their spacing, stretched between the two ends'.
    const double a = w[h], b = w[n - t], ua = u[h], ub = u[n - t];
    for (int i = h + 1; i < n - t; ++i)
      w[i] = a + (b - a) * (u[i] - ua) / std::max(ub - ua, 1e-300);
  }
  bool same = true;
  for (int i = 1; i < n && same; ++i) same = std::abs(w[i] - u[i]) <= 1e-12;
  if (same) return points;
  // The new points on a dense polyline of the edge, put on it.
  const int m = std::max(64, 16 * n);
  const std::vector<Vec3> dense = s.edge_points_by_length(e, m);
  std::vector<double> c(dense.size(), 0.0);
  for (std::size_t k = 1; k < dense.size(); ++k) c[k] = c[k - 1] + (dense[k] - dense[k - 1]).norm();
  std::size_t k = 0;
  for (int i = 1; i < n; ++i) {
    const double t = w[i] * c.back();
    while (k + 2 < c.size() && c[k + 1] < t) ++k;
    const double span = c[k + 1] - c[k];
    const double f = span > 0 ? std::clamp((t - c[k]) / span, 0.0, 1.0) : 0.0;
    points[i] = s.project_to_edge(e, (1 - f) * dense[k] + f * dense[k + 1]);
  }
  return points;
}

}  // namespace

std::vector<Vec3> edge_points(const core::MeshDomain& s, core::EdgeId e, int n,
                              const core::SizeField* field) {
  if (!graded(field) || n <= 1) return widened_at_cusps(s, e, s.edge_points_by_length(e, n));
  const std::vector<Vec3> dense =
      s.edge_points_by_length(e, std::max(samples(s.edge_length(e), *field), 4 * n));
  std::vector<Vec3> out = graded_points(dense, n, *field);
  for (int i = 1; i < n; ++i) out[i] = s.project_to_edge(e, out[i]);
  return widened_at_cusps(s, e, std::move(out));
}

std::vector<double> graded_parameters(const Vec3& a, const Vec3& b, int n,
                                      const core::SizeField* field) {
  std::vector<double> t(n + 1);
  for (int i = 0; i <= n; ++i) t[i] = double(i) / n;
  if (!graded(field) || n <= 1) return t;
  const int m = std::max(samples((b - a).norm(), *field), 4 * n);
  std::vector<Vec3> line(m + 1);
  for (int k = 0; k <= m; ++k) line[k] = a + (b - a) * (double(k) / m);
  int i = 1;
  for (const auto& [k, w] : equal_shares(field->cumulative(line), n)) t[i++] = (double(k) + w) / m;
  return t;
}

std::vector<Vec3> edge_points(const core::MeshDomain& s, core::EdgeId e, int n,
                              const core::SizeField* field,
                              const std::vector<std::vector<Vec3>>& given) {
  const std::size_t k = std::size_t(e.value());
  if (k < given.size() && n >= 0 && given[k].size() == std::size_t(n) + 1) return given[k];
  return edge_points(s, e, n, field);
}

}  // namespace vorohex::mesh::detail
