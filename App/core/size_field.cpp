#include "core/size_field.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/option_checks.h"

namespace vorohex::core {

namespace {

double box_distance(const BoundingBox& b, const Vec3& p) {
  const Vec3 d = (b.min - p).cwiseMax(p - b.max).cwiseMax(Vec3::Zero());
  return d.norm();
}

std::string number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace

bool parse_entity_name(const std::string& name, char& kind, int& id) {
  static const std::pair<const char*, char> kinds[] = {
      {"Face", 'f'}, {"Edge", 'e'}, {"Vertex", 'v'}};
  for (const auto& [prefix, k] : kinds) {
    const std::string pre(prefix);
    if (name.compare(0, pre.size(), pre) != 0) continue;
    const std::string digits = name.substr(pre.size());
    if (digits.empty() || digits.size() > 9 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return false;
    kind = k;
    id = std::stoi(digits);
    return id >= 1;
  }
  return false;
}

SizeField::SizeField(double global_size) : global_(global_size) {
  require_positive("size", global_size);
}

SizeField::SizeField(const MeshDomain& domain, double global_size,
                     const std::vector<LocalSize>& sizes, double grading)
    : domain_(&domain), global_(global_size), grading_(grading) {
  require_positive("size", global_size);
  require_positive("size grading", grading);
  std::map<std::pair<char, int>, double> chosen;  // entity -> smallest size given
  for (const LocalSize& l : sizes) {
    char kind = 0;
    int id = 0;
    if (!parse_entity_name(l.entity, kind, id))
      throw std::invalid_argument("Local size: '" + l.entity +
                                  "' is not an entity name (expected FaceN, EdgeN or VertexN)");
    const int count = kind == 'f'   ? domain.num_faces()
                      : kind == 'e' ? domain.num_edges()
                                    : domain.num_vertices();
    if (id > count) {
      const char* what = kind == 'f' ? "faces" : kind == 'e' ? "edges" : "vertices";
      throw std::invalid_argument("Local size: the solid has no " + l.entity + " (it has " +
                                  std::to_string(count) + " " + what + ")");
    }
    if (!(std::isfinite(l.size) && l.size > 0))
      throw std::invalid_argument("Local size of " + l.entity + " must be finite and > 0, got " +
                                  number(l.size));
    auto [it, fresh] = chosen.emplace(std::make_pair(kind, id), l.size);
    if (!fresh) it->second = std::min(it->second, l.size);
  }
  for (const auto& [key, size] : chosen) {
    const auto [kind, id] = key;
    const std::string name = kind == 'f'   ? entity_name(FaceId(id))
                             : kind == 'e' ? entity_name(EdgeId(id))
                                           : entity_name(VertexId(id));
    if (size >= global_) {
      diagnostics_.push_back(make_warning("local_size_not_finer",
                                          "The local size " + number(size) + " of " + name +
                                              " is not below the global size " + number(global_) +
                                              "; local sizes only refine, so it has no effect.",
                                          {name}));
      continue;
    }
    Source s{kind == 'f'   ? Source::face
             : kind == 'e' ? Source::edge
                           : Source::vertex,
             id,
             size,
             {}};
    if (s.kind == Source::face) s.box = domain.face_bounding_box(FaceId(id));
    if (s.kind == Source::edge) s.box = domain.edge_bounding_box(EdgeId(id));
    if (s.kind == Source::vertex) s.box.min = s.box.max = domain.vertex_point(VertexId(id));
    sources_.push_back(s);
    applied_.push_back({name, size});
  }
}

double SizeField::distance(const Source& s, const Vec3& p) const {
  switch (s.kind) {
    case Source::vertex:
      return (p - s.box.min).norm();
    case Source::edge:
      return domain_->distance_to_edge(EdgeId(s.id), p);
    case Source::face:
      return domain_->distance_to_face(FaceId(s.id), p);
  }
  return 0;
}

double SizeField::graded_cells() const {
  // Closed forms of the integrals over u = size_i + grading d, from size_i to the global H,
  // less the H^-3 the volume term already counts (a midpoint rule misses the peak at d = 0
  // for a tiny size).
  constexpr double kPi = 3.14159265358979323846;
  const double H = global_, g = grading_;
  double cells = 0;
  for (const Source& src : sources_) {
    const double s = src.size, reach = (H - s) / g;
    if (src.kind == Source::face) {
      cells += domain_->area(FaceId(src.id)) *
               ((1 / (s * s) - 1 / (H * H)) / (2 * g) - reach / (H * H * H));
    } else if (src.kind == Source::edge) {
      cells +=
          domain_->edge_length(EdgeId(src.id)) * kPi *
          ((1 / (2 * s) - 1 / H + s / (2 * H * H)) / (g * g) - reach * reach / (2 * H * H * H));
    } else {
      cells += 0.5 * kPi *
               ((std::log(H / s) - 1.5 + 2 * s / H - s * s / (2 * H * H)) / (g * g * g) -
                reach * reach * reach / (3 * H * H * H));
    }
  }
  return cells;
}

double SizeField::min_size() const {
  double m = global_;
  for (const Source& s : sources_) m = std::min(m, s.size);
  return m;
}

SizeField SizeField::extruded(const Vec3& origin, const Vec3& axis,
                              std::vector<double> heights) const {
  SizeField f = *this;
  const Vec3 a = axis.normalized();
  f.views_.clear();
  for (double z : heights)
    f.views_.push_back(
        [origin, a, z](const Vec3& p) { return Vec3(p + (z - (p - origin).dot(a)) * a); });
  return f;
}

SizeField SizeField::scaled(double factor) const {
  SizeField f = *this;
  f.global_ *= factor;
  f.grading_ *= factor;
  for (Source& s : f.sources_) s.size *= factor;
  for (LocalSize& l : f.applied_) l.size *= factor;
  return f;
}

SizeField SizeField::revolved(const Vec3& origin, const Vec3& axis, int turns) const {
  SizeField f = *this;
  const Vec3 a = axis.normalized();
  f.views_.clear();
  for (int k = 0; k < std::max(1, turns); ++k) {
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(2 * 3.14159265358979323846 * k / std::max(1, turns), a)
            .toRotationMatrix();
    f.views_.push_back([origin, r](const Vec3& p) { return Vec3(origin + r * (p - origin)); });
  }
  return f;
}

double SizeField::at(const Vec3& p) const {
  if (views_.empty() || sources_.empty()) return at_point(p);
  double h = global_;
  for (const auto& view : views_) h = std::min(h, at_point(view(p)));
  return h;
}

double SizeField::at_point(const Vec3& p) const {
  double h = global_;
  for (const Source& s : sources_) {
    if (s.size + grading_ * box_distance(s.box, p) >= h) continue;  // cannot lower h
    h = std::min(h, s.size + grading_ * distance(s, p));
  }
  return h;
}

std::vector<double> SizeField::cumulative(const std::vector<Vec3>& polyline) const {
  std::vector<double> c(polyline.size(), 0.0);
  if (polyline.empty()) return c;
  double inv_prev = 1.0 / at(polyline[0]);
  for (std::size_t k = 1; k < polyline.size(); ++k) {
    const double inv = 1.0 / at(polyline[k]);
    c[k] = c[k - 1] + (polyline[k] - polyline[k - 1]).norm() * 0.5 * (inv + inv_prev);
    inv_prev = inv;
  }
  return c;
}

double SizeField::segments_along(const std::vector<Vec3>& polyline) const {
  if (uniform()) {
    double length = 0;
    for (std::size_t k = 1; k < polyline.size(); ++k)
      length += (polyline[k] - polyline[k - 1]).norm();
    return length / global_;
  }
  const std::vector<double> c = cumulative(polyline);
  return c.empty() ? 0.0 : c.back();
}

}  // namespace vorohex::core
