#include "pipeline/detail/fallback_bytes.h"

#include <cstdint>
#include <cstring>
#include <type_traits>

namespace vorohex::pipeline::detail {
namespace {

constexpr std::uint32_t kMagic = 0x56484642;  // "VHFB"

class Writer {
 public:
  template <class T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void pods(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    pod(std::uint64_t(v.size()));
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  // Eigen's vectors are not trivially copyable: their coordinates are.
  void points(const std::vector<core::Vec3>& v) {
    std::vector<double> xyz;
    xyz.reserve(3 * v.size());
    for (const core::Vec3& p : v) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
    pods(xyz);
  }
  void text(const std::string& s) {
    pod(std::uint64_t(s.size()));
    out += s;
  }
  void texts(const std::vector<std::string>& v) {
    pod(std::uint64_t(v.size()));
    for (const std::string& s : v) text(s);
  }
  std::string out;
};

class Reader {
 public:
  explicit Reader(const std::string& bytes) : in(bytes) {}
  template <class T>
  bool pod(T& v) {
    if (at + sizeof v > in.size()) return false;
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
    return true;
  }
  template <class T>
  bool pods(std::vector<T>& v) {
    std::uint64_t n = 0;
    if (!pod(n) || n > (in.size() - at) / sizeof(T)) return false;
    v.resize(n);
    std::memcpy(v.data(), in.data() + at, n * sizeof(T));
    at += n * sizeof(T);
    return true;
  }
  bool points(std::vector<core::Vec3>& v) {
    std::vector<double> xyz;
    if (!pods(xyz) || xyz.size() % 3 != 0) return false;
    v.resize(xyz.size() / 3);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
    return true;
  }
  bool text(std::string& s) {
    std::uint64_t n = 0;
    if (!pod(n) || n > in.size() - at) return false;
    s.assign(in, at, n);
    at += n;
    return true;
  }
  bool texts(std::vector<std::string>& v) {
    std::uint64_t n = 0;
    if (!pod(n) || n > in.size() - at) return false;
    v.resize(n);
    for (std::string& s : v)
      if (!text(s)) return false;
    return true;
  }
  bool done() const { return at == in.size(); }

 private:
  const std::string& in;
  std::size_t at = 0;
};

}  // namespace

std::string fallback_to_bytes(const MeshResult& r, bool flag) {
  Writer w;
  w.pod(kMagic);
  w.pod(std::uint8_t(flag));
  w.pod(std::uint8_t(r.ok));
  const MeshStats& s = r.stats;
  w.pod(s.size_used);
  w.pod(s.intervals);
  w.pod(s.seconds_meshing), w.pod(s.seconds_smoothing), w.pod(s.seconds_checking);
  w.pod(s.min_sj_before_smoothing), w.pod(s.mean_sj_before_smoothing);
  w.pod(s.sub_volumes);
  w.text(s.scheme);
  w.texts(s.sub_volume_schemes);
  w.texts(s.sub_volume_types);
  w.pod(s.absorbed_deviation);
  w.pod(std::uint64_t(s.local_sizes.size()));
  for (const core::LocalSize& l : s.local_sizes) w.text(l.entity), w.pod(l.size);
  w.pod(std::uint64_t(r.diagnostics.size()));
  for (const core::Diagnostic& d : r.diagnostics) {
    w.pod(d.severity);
    w.text(d.code);
    w.text(d.message);
    w.texts(d.entities);
  }
  w.points(r.mesh.points());
  w.pods(r.mesh.node_classes());
  w.pods(r.mesh.hexes());
  w.pods(r.mesh.sub_volumes());
  w.pods(r.mesh.mid_edge_nodes());
  const grid::SmallFeatures& a = r.absorbed;
  w.pods(a.absorbed_face);
  w.pods(a.absorbed_edge);
  w.pods(a.composite_of_face);
  w.pod(std::uint64_t(a.composites.size()));
  for (const grid::Composite& c : a.composites) {
    w.pod(c.host);
    w.pods(c.faces);
  }
  w.pod(a.small);
  w.points(a.samples);
  std::vector<core::Vec3> corners;
  for (const core::BoundingBox& b : a.face_boxes)
    corners.push_back(b.min), corners.push_back(b.max);
  w.points(corners);
  return std::move(w.out);
}

bool fallback_from_bytes(const std::string& bytes, MeshResult& r, bool& flag) {
  Reader in(bytes);
  std::uint32_t magic = 0;
  std::uint8_t second = 0, ok = 0;
  if (!in.pod(magic) || magic != kMagic || !in.pod(second) || !in.pod(ok)) return false;
  flag = second != 0;
  r = MeshResult();
  r.ok = ok != 0;
  MeshStats& s = r.stats;
  if (!in.pod(s.size_used) || !in.pod(s.intervals) || !in.pod(s.seconds_meshing) ||
      !in.pod(s.seconds_smoothing) || !in.pod(s.seconds_checking) ||
      !in.pod(s.min_sj_before_smoothing) || !in.pod(s.mean_sj_before_smoothing) ||
      !in.pod(s.sub_volumes) || !in.text(s.scheme) || !in.texts(s.sub_volume_schemes) ||
      !in.texts(s.sub_volume_types) || !in.pod(s.absorbed_deviation))
    return false;
  std::uint64_t n = 0;
  if (!in.pod(n) || n > bytes.size()) return false;
  s.local_sizes.resize(n);
  for (core::LocalSize& l : s.local_sizes)
    if (!in.text(l.entity) || !in.pod(l.size)) return false;
  if (!in.pod(n) || n > bytes.size()) return false;
  r.diagnostics.resize(n);
  for (core::Diagnostic& d : r.diagnostics)
    if (!in.pod(d.severity) || !in.text(d.code) || !in.text(d.message) || !in.texts(d.entities))
      return false;
  std::vector<core::Vec3> points;
  std::vector<core::NodeClass> classes;
  std::vector<core::HexNodes> hexes;
  std::vector<std::int32_t> sub_volumes;
  if (!in.points(points) || !in.pods(classes) || !in.pods(hexes) || !in.pods(sub_volumes) ||
      classes.size() != points.size() || sub_volumes.size() != hexes.size())
    return false;
  r.mesh.reserve(points.size(), hexes.size());
  for (std::size_t i = 0; i < points.size(); ++i) r.mesh.add_node(points[i], classes[i]);
  for (std::size_t h = 0; h < hexes.size(); ++h) {
    for (std::int32_t v : hexes[h])
      if (v < 0 || std::size_t(v) >= points.size()) return false;
    r.mesh.add_hex(hexes[h], sub_volumes[h]);
  }
  std::vector<core::MidEdgeNodes> mid;
  if (!in.pods(mid) || (!mid.empty() && mid.size() != hexes.size())) return false;
  for (const core::MidEdgeNodes& m : mid)
    for (std::int32_t v : m)
      if (v < 0 || std::size_t(v) >= points.size()) return false;
  r.mesh.set_mid_edge_nodes(std::move(mid));
  grid::SmallFeatures& a = r.absorbed;
  if (!in.pods(a.absorbed_face) || !in.pods(a.absorbed_edge) || !in.pods(a.composite_of_face) ||
      !in.pod(n) || n > bytes.size())
    return false;
  a.composites.resize(n);
  for (grid::Composite& c : a.composites)
    if (!in.pod(c.host) || !in.pods(c.faces)) return false;
  std::vector<core::Vec3> corners;
  if (!in.pod(a.small) || !in.points(a.samples) || !in.points(corners) || corners.size() % 2 != 0)
    return false;
  for (std::size_t i = 0; i < corners.size(); i += 2)
    a.face_boxes.push_back({corners[i], corners[i + 1]});
  return in.done();
}

}  // namespace vorohex::pipeline::detail
