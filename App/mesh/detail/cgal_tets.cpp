#include "mesh/detail/cgal_tets.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Polyhedron_incremental_builder_3.h>
#include <CGAL/Random.h>
#include <CGAL/make_mesh_3.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <stdexcept>

namespace vorohex::mesh::detail {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polyhedron = CGAL::Mesh_polyhedron_3<K>::type;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;
using core::Vec3;

class Builder : public CGAL::Modifier_base<Polyhedron::HalfedgeDS> {
 public:
  explicit Builder(const TetSurface& s) : s_(s) {}
  void operator()(Polyhedron::HalfedgeDS& hds) override {
    CGAL::Polyhedron_incremental_builder_3<Polyhedron::HalfedgeDS> b(hds, true);
    b.begin_surface(s_.points.size(), s_.triangles.size());
    for (const Vec3& p : s_.points) b.add_vertex(K::Point_3(p.x(), p.y(), p.z()));
    for (std::size_t i = 0; i < s_.triangles.size(); ++i) {
      const auto& t = s_.triangles[i];
      if (!b.test_facet(t.begin(), t.end())) {
        error = "the boundary triangulation is not a manifold surface";
        b.rollback();
        return;
      }
      auto h = b.add_facet(t.begin(), t.end());
      h->facet()->set_patch_id(s_.patch[i]);
    }
    b.end_surface();
    if (b.error()) error = "the boundary triangulation could not be built";
  }
  std::string error;

 private:
  const TetSurface& s_;
};

C3t3 refine(const Domain& domain, const Criteria& criteria, TetOptimiser optimiser) {
  namespace params = CGAL::parameters;
  // No exuder: on HexMe i15 it sent a NaN weight into GMP (SIGFPE). No time limits: the
  // perturber's default (as long as refinement took) made the result depend on the
  // machine's load; the caller bounds the time by killing the child process instead.
  if (optimiser == TetOptimiser::odt)
    return CGAL::make_mesh_3<C3t3>(
        domain, criteria, params::odt(params::time_limit = 0, params::max_iteration_number = 20),
        params::perturb(params::time_limit = 0), params::no_exude());
  return CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_odt(), params::no_lloyd(),
                                 params::perturb(params::time_limit = 0), params::no_exude());
}

template <class T>
void put(std::string& out, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  if (n > 0) out.append(reinterpret_cast<const char*>(v.data()), n * sizeof(T));
}

template <class T>
bool get(const std::string& in, std::size_t& at, std::vector<T>& v) {
  std::uint64_t n = 0;
  if (in.size() - at < sizeof n) return false;
  std::memcpy(&n, in.data() + at, sizeof n);
  at += sizeof n;
  if (n > (in.size() - at) / sizeof(T)) return false;
  v.resize(n);
  if (n > 0) std::memcpy(static_cast<void*>(v.data()), in.data() + at, n * sizeof(T));
  at += n * sizeof(T);
  return true;
}

}  // namespace

Tetrahedra mesh_tetrahedra(const TetRequest& request) {
  Polyhedron poly;
  Builder builder(request.surface);
  poly.delegate(builder);
  if (!builder.error.empty()) throw std::runtime_error(builder.error);
  if (!poly.is_closed()) throw std::runtime_error("the boundary triangulation is not closed");

  std::vector<std::vector<K::Point_3>> polylines;
  for (const auto& pl : request.features) {
    if (pl.size() < 2) continue;
    std::vector<K::Point_3> line;
    for (const Vec3& p : pl) line.emplace_back(p.x(), p.y(), p.z());
    polylines.push_back(std::move(line));
  }
  Domain domain(poly);
  domain.add_features(polylines.begin(), polylines.end());
  namespace params = CGAL::parameters;
  const double s = request.size;
  Criteria criteria(params::edge_size = s, params::facet_angle = 25, params::facet_size = s,
                    params::facet_distance = 0.1 * s, params::cell_radius_edge_ratio = 2.5,
                    params::cell_size = s);
  // The same tetrahedra for the same input (the perturber draws from CGAL's default
  // random generator, seeded differently per process otherwise).
  CGAL::get_default_random() = CGAL::Random(0);
  C3t3 c3t3;
  try {
    c3t3 = refine(domain, criteria, request.optimiser);
  } catch (const std::exception& ex) {
    throw std::runtime_error(std::string("CGAL could not mesh the volume: ") + ex.what());
  }

  Tetrahedra t;
  std::map<Tr::Vertex_handle, int> index;
  auto node = [&](Tr::Vertex_handle v) {
    auto [it, added] = index.emplace(v, static_cast<int>(t.points.size()));
    if (added) {
      const auto& p = v->point().point();
      t.points.emplace_back(p.x(), p.y(), p.z());
      t.dimension.push_back(c3t3.in_dimension(v));
    }
    return it->second;
  };
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c)
    t.tets.push_back(
        {node(c->vertex(0)), node(c->vertex(1)), node(c->vertex(2)), node(c->vertex(3))});
  // Pinched edges: an edge of more than two boundary facets has two fans of tetrahedra
  // around it with a gap between them. Where the gap lies inside the solid (cells CGAL left
  // out of the complex, whose centroid the domain puts inside) it is filled; otherwise the
  // hex mesh's boundary would not be closed there (HexMe i02 at a model edge).
  {
    const Tr& tr = c3t3.triangulation();
    const auto inside = domain.is_in_domain_object();
    std::set<Tr::Cell_handle> added;
    auto in = [&](Tr::Cell_handle c) { return c3t3.is_in_complex(c) || added.count(c) > 0; };
    // Filling a gap can pinch a neighbouring edge: repeated a few times.
    for (int round = 0; round < 5; ++round) {
      std::map<std::pair<Tr::Vertex_handle, Tr::Vertex_handle>, int> boundary_count;
      auto count_cell = [&](Tr::Cell_handle c) {
        for (int f = 0; f < 4; ++f) {
          if (in(c->neighbor(f))) continue;
          for (int a = 0; a < 3; ++a) {
            Tr::Vertex_handle u = c->vertex((f + 1 + a) % 4);
            Tr::Vertex_handle v = c->vertex((f + 1 + (a + 1) % 3) % 4);
            if (v < u) std::swap(u, v);
            ++boundary_count[{u, v}];
          }
        }
      };
      for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c)
        count_cell(c);
      for (Tr::Cell_handle c : added) count_cell(c);
      std::size_t before = added.size();
      for (const auto& [edge, count] : boundary_count) {
        if (count <= 2) continue;
        Tr::Cell_handle cell;
        int i = 0, j = 0;
        if (!tr.is_edge(edge.first, edge.second, cell, i, j)) continue;
        auto circ = tr.incident_cells(cell, i, j), done = circ;
        do {
          const Tr::Cell_handle c = circ;
          if (!tr.is_infinite(c) && !in(c)) {
            K::Vector_3 sum(0, 0, 0);
            for (int k = 0; k < 4; ++k) sum = sum + (tr.point(c, k).point() - CGAL::ORIGIN);
            if (inside(CGAL::ORIGIN + sum / 4.0)) added.insert(c);
          }
        } while (++circ != done);
      }
      if (added.size() == before) break;
    }
    for (Tr::Cell_handle c : added)
      t.tets.push_back(
          {node(c->vertex(0)), node(c->vertex(1)), node(c->vertex(2)), node(c->vertex(3))});
    t.filled = static_cast<int>(added.size());
  }
  for (auto e = c3t3.edges_in_complex_begin(); e != c3t3.edges_in_complex_end(); ++e) {
    const auto a = index.find(e->first->vertex(e->second));
    const auto b = index.find(e->first->vertex(e->third));
    if (a == index.end() || b == index.end()) continue;
    t.feature_edges.push_back({std::min(a->second, b->second), std::max(a->second, b->second)});
  }
  for (auto f = c3t3.facets_in_complex_begin(); f != c3t3.facets_in_complex_end(); ++f) {
    std::array<int, 3> k;
    bool known = true;
    for (int j = 0; j < 3; ++j) {
      const auto it = index.find(f->first->vertex((f->second + 1 + j) % 4));
      if (it == index.end())
        known = false;
      else
        k[j] = it->second;
    }
    if (!known) continue;
    std::sort(k.begin(), k.end());
    t.facets.push_back(k);
    t.facet_patch.push_back(static_cast<int>(c3t3.surface_patch_index(*f)));
  }
  return t;
}

std::string to_bytes(const Tetrahedra& t) {
  std::string out;
  std::vector<double> xyz;
  xyz.reserve(3 * t.points.size());
  for (const Vec3& p : t.points) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  put(out, xyz);
  put(out, t.dimension);
  put(out, t.tets);
  put(out, t.feature_edges);
  put(out, t.facets);
  put(out, t.facet_patch);
  put(out, std::vector<int>{t.filled});
  return out;
}

bool from_bytes(const std::string& bytes, Tetrahedra& t) {
  std::size_t at = 0;
  std::vector<double> xyz;
  if (!get(bytes, at, xyz) || xyz.size() % 3 != 0 || !get(bytes, at, t.dimension) ||
      !get(bytes, at, t.tets) || !get(bytes, at, t.feature_edges) || !get(bytes, at, t.facets) ||
      !get(bytes, at, t.facet_patch))
    return false;
  std::vector<int> filled;
  if (!get(bytes, at, filled) || filled.size() != 1 || at != bytes.size()) return false;
  t.filled = filled[0];
  t.points.clear();
  for (std::size_t i = 0; i < xyz.size(); i += 3)
    t.points.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  const int n = static_cast<int>(t.points.size());
  if (t.dimension.size() != t.points.size() || t.facets.size() != t.facet_patch.size())
    return false;
  auto in_range = [n](const auto& ids) {
    return std::all_of(ids.begin(), ids.end(), [n](int i) { return i >= 0 && i < n; });
  };
  return std::all_of(t.tets.begin(), t.tets.end(), in_range) &&
         std::all_of(t.feature_edges.begin(), t.feature_edges.end(), in_range) &&
         std::all_of(t.facets.begin(), t.facets.end(), in_range);
}

}  // namespace vorohex::mesh::detail
