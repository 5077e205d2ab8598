#include "mesh/detail/sizing.h"

#include <algorithm>
#include <cmath>
#include <utility>

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

std::vector<Vec3> edge_points(const core::MeshDomain& s, core::EdgeId e, int n,
                              const core::SizeField* field) {
  if (!graded(field) || n <= 1) return s.edge_points_by_length(e, n);
  const std::vector<Vec3> dense =
      s.edge_points_by_length(e, std::max(samples(s.edge_length(e), *field), 4 * n));
  std::vector<Vec3> out = graded_points(dense, n, *field);
  for (int i = 1; i < n; ++i) out[i] = s.project_to_edge(e, out[i]);
  return out;
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
