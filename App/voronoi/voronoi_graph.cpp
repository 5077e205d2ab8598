#include "voronoi/voronoi_graph.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <thread>
#include <unordered_map>

#include "voronoi/detail/distance_field.h"
#include "voronoi/detail/octree_walker.h"

namespace vorohex::voronoi {
namespace {

using detail::DistanceField;
using detail::FineCell;
using detail::kInf;
using detail::LabelSet;
using detail::OctNode;
using detail::Prim;
using detail::Walker;

unsigned long long cell_key(long long i, long long j, long long k) {
  return (static_cast<unsigned long long>(i & 0x1fffff) << 42) |
         (static_cast<unsigned long long>(j & 0x1fffff) << 21) |
         static_cast<unsigned long long>(k & 0x1fffff);
}

class Subdivision final : public RegionLocator {
 public:
  Subdivision(std::shared_ptr<const model::BRepModel> m) : model_(std::move(m)), field_(*model_) {}

  EntityRef region(const Vec3& p) const override {
    Vec3 lo = origin_;
    double size = size_;
    if (((p - lo).array() < 0).any() || ((p - lo).array() > size).any()) return {};
    int n = 0;
    while (nodes_[n].child >= 0) {
      size *= 0.5;
      int c = 0;
      for (int a = 0; a < 3; ++a)
        if (p[a] >= lo[a] + size) {
          c |= 1 << a;
          lo[a] += size;
        }
      n = nodes_[n].child + c;
    }
    const OctNode& leaf = nodes_[n];
    int e = leaf.entity;
    if (leaf.cand_count > 0) e = field_.owner(p, pool_.data() + leaf.cand_begin, leaf.cand_count);
    return e < 0 ? EntityRef{} : model_->entity(e);
  }

  std::shared_ptr<const model::BRepModel> model_;
  DistanceField field_;
  Vec3 origin_{0, 0, 0};
  double size_ = 1;
  std::vector<OctNode> nodes_;
  std::vector<int> pool_;
};

class Builder {
 public:
  Builder(Subdivision& sub, const VoronoiOptions& opt, VoronoiResult& result)
      : sub_(sub), field_(sub.field_), model_(*sub.model_), opt_(opt), result_(result) {
    const double diag = model_.diagonal();
    eps_ = opt.eps * diag;
    delta_ = opt.delta * diag;
    const core::BoundingBox box = model_.bounding_box();
    const double extent = (box.max - box.min).maxCoeff();
    // A little larger than the box, shifted off-centre so that symmetry planes of the solid
    // do not fall on cell faces and sample points.
    sub_.size_ = extent * 1.0731 + 1e-12;
    sub_.origin_ = 0.5 * (box.min + box.max) - Vec3::Constant(0.5 * sub_.size_) +
                   Vec3(0.0123, 0.0071, 0.0047) * extent;
    level_ = std::clamp(int(std::ceil(std::log2(sub_.size_ / eps_))), 1, opt.max_depth);
    h_ = sub_.size_ / double(1 << level_);
    field_tie_ = 1e-9 * diag;
    threads_ = opt.threads > 0 ? opt.threads : int(std::thread::hardware_concurrency());
    result_.stats.finest_level = level_;
  }

  void run();

 private:
  // Extended distance to an entity (the supporting plane / line / point of its nearest
  // governing primitive) and its gradient: smooth, and equal to the true distance where
  // the entity is nearest.
  // With `closed`, the distance to the nearest primitive itself (what verify() checks; its
  // gradient turns at facet edges), for a second attempt where the smooth one fails.
  double extended(const DistanceField& field, int entity, const Vec3& x, Vec3* grad,
                  bool closed = false) const {
    Vec3 near;
    double best = kInf;
    int which = -1;
    for (int i : field.entity_prims(entity)) {
      const Prim& pr = field.prim(i);
      if ((pr.lo - x).cwiseMax(x - pr.hi).cwiseMax(0.0).norm() >= best) continue;
      const double d = field.distance(i, x, nullptr);
      if (d < best) {
        best = d;
        which = i;
      }
    }
    if (which < 0) return kInf;
    const double dn = field.distance(which, x, &near);
    const Prim& pr = field.prim(which);
    if (closed) {
      *grad = dn > 0 ? Vec3((x - near) / dn) : Vec3(0, 0, 0);
      return dn;
    }
    const model::Linearization& lin = model_.linear();
    Vec3 w;
    if (pr.type == Prim::polygon) {
      // Distance to the supporting plane (exact where the projection is on the polygon, a
      // smooth continuation elsewhere).
      Vec3 o, n;
      field.plane(which, &o, &n);
      const double hp = (x - o).dot(n);
      *grad = hp >= 0 ? n : Vec3(-n);
      return std::abs(hp);
    }
    if (pr.type == Prim::segment) {
      const auto& s = lin.segments[pr.source];
      const Vec3 a = lin.points[s.a], dir = (lin.points[s.b] - a).normalized();
      w = (x - a) - (x - a).dot(dir) * dir;
    } else {
      w = x - near;
    }
    const double d = w.norm();
    *grad = d > 0 ? Vec3(w / d) : Vec3(0, 0, 0);
    return d;
  }

  // Gauss-Newton on "equidistant from all governors": unknowns x and the distance t.
  // Returns the residual (max |d_i - t|) and updates x, t.
  double solve(const DistanceField& field, const std::vector<int>& govs, Vec3& x, double& t,
               int iterations, bool closed = false) const {
    const int m = int(govs.size());
    Eigen::MatrixXd J(m, 4);
    Eigen::VectorXd f(m);
    double res = kInf;
    for (int it = 0; it <= iterations; ++it) {
      Vec3 g;
      res = 0;
      for (int i = 0; i < m; ++i) {
        const double d = extended(field, govs[i], x, &g, closed);
        if (!std::isfinite(d)) return kInf;
        f[i] = d - t;
        J.row(i) << g.x(), g.y(), g.z(), -1.0;
        res = std::max(res, std::abs(f[i]));
      }
      if (it == iterations || res < 1e-3 * delta_) break;
      Eigen::Vector4d step;
      if (m >= 4) {
        Eigen::Matrix4d A = J.transpose() * J;
        A.diagonal().array() += 1e-12;
        step = A.ldlt().solve(J.transpose() * f);
      } else {  // under-determined: the smallest step onto the solution set
        Eigen::MatrixXd JJt = J * J.transpose();
        JJt.diagonal().array() += 1e-12;
        step = J.transpose() * JJt.ldlt().solve(f);
      }
      // Damping: never move much farther than a few finest cells per step.
      const double len = step.head<3>().norm(), cap = 4 * h_;
      if (len > cap) step *= cap / len;
      x -= step.head<3>();
      t -= step[3];
    }
    return res;
  }

  // Equidistant within delta and no other entity nearer than delta.
  bool verify(const DistanceField& field, const std::vector<int>& govs, const Vec3& x,
              double t) const {
    for (int g : govs)
      if (std::abs(field.entity_distance(g, x) - t) > delta_) return false;
    return field.boundary_distance(x) >= t - delta_;
  }

  // Runs fn(field, i) for i in [0, n) on all threads, each with a private copy of the
  // field (its evaluation counter is not shared).
  template <class Fn>
  void parallel_for(int n, const Fn& fn) {
    std::atomic<int> next{0};
    std::atomic<long long> evaluations{0};
    auto work = [&] {
      const DistanceField field(field_);
      const long long before = field.evaluations();
      for (int i; (i = next++) < n;) fn(field, i);
      evaluations += field.evaluations() - before;
    };
    const int threads = std::clamp(threads_, 1, std::max(1, n / 16));
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    result_.stats.distance_evaluations += evaluations;
  }

  std::vector<EntityRef> refs(const std::vector<int>& govs) const {
    std::vector<EntityRef> out;
    for (int g : govs) out.push_back(model_.entity(g));
    std::sort(out.begin(), out.end());
    return out;
  }

  void extract();

  Subdivision& sub_;
  const DistanceField& field_;
  const model::BRepModel& model_;
  const VoronoiOptions& opt_;
  VoronoiResult& result_;
  double eps_ = 0, delta_ = 0, h_ = 0;
  int level_ = 1;
  double field_tie_ = 0;
  int threads_ = 1;
  std::vector<FineCell> fine_;
  std::map<std::pair<int, int>, std::pair<Vec3, double>> pairs_;  // evidence, its depth
};

void Builder::run() {
  // Subtrees below depth 2 are independent tasks, spread over the threads; their findings
  // are merged in depth-first order, so the result does not depend on the thread count.
  Walker::Params params{sub_.origin_, h_, field_tie_, level_, 2};
  const std::vector<int>& all = field_.governing();
  Walker top(field_, params);
  // Nothing known about the root's candidates yet: no lower bounds.
  top.run({0, sub_.origin_, sub_.size_, kInf, 0, all, std::vector<double>(all.size(), 0.0),
           std::vector<double>(all.size(), 0.0), 0, 0});
  const std::vector<Walker::Task>& tasks = top.tasks_;
  std::vector<std::unique_ptr<Walker>> walkers(tasks.size());
  std::atomic<int> next{0};
  std::atomic<long long> evaluations{0};
  auto work = [&] {
    // A private copy of the field: its evaluation counter is not shared.
    const DistanceField field(field_);
    const long long before = field.evaluations();
    for (int t; (t = next++) < int(tasks.size());) {
      walkers[t] = std::make_unique<Walker>(field, params);
      walkers[t]->run(tasks[t]);
    }
    evaluations += field.evaluations() - before;
  };
  const int threads = std::clamp(threads_, 1, std::max(1, int(tasks.size())));
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  result_.stats.distance_evaluations += evaluations;

  // Merge: the top walker's nodes keep their numbers; each task's subtree is appended.
  sub_.nodes_ = std::move(top.nodes_);
  sub_.pool_ = std::move(top.pool_);
  std::vector<Walker::Pair> events;
  size_t fine_done = 0, pairs_done = 0;
  auto add_stats = [&](const VoronoiStats& s) {
    result_.stats.cells += s.cells;
    result_.stats.leaves += s.leaves;
    result_.stats.finest_cells += s.finest_cells;
  };
  add_stats(top.stats_);
  for (size_t t = 0; t < tasks.size(); ++t) {
    Walker& w = *walkers[t];
    fine_.insert(fine_.end(), top.fine_.begin() + fine_done,
                 top.fine_.begin() + tasks[t].fine_mark);
    events.insert(events.end(), top.pairs_.begin() + pairs_done,
                  top.pairs_.begin() + tasks[t].pair_mark);
    fine_done = tasks[t].fine_mark;
    pairs_done = tasks[t].pair_mark;
    fine_.insert(fine_.end(), w.fine_.begin(), w.fine_.end());
    events.insert(events.end(), w.pairs_.begin(), w.pairs_.end());
    add_stats(w.stats_);
    const int offset = int(sub_.nodes_.size()) - 1;  // local node k > 0 becomes offset + k
    const int pool_offset = int(sub_.pool_.size());
    for (size_t k = 0; k < w.nodes_.size(); ++k) {
      OctNode n = w.nodes_[k];
      if (n.child >= 0) n.child += offset;
      n.cand_begin += pool_offset;
      if (k == 0)
        sub_.nodes_[tasks[t].node] = n;
      else
        sub_.nodes_.push_back(n);
    }
    sub_.pool_.insert(sub_.pool_.end(), w.pool_.begin(), w.pool_.end());
    walkers[t].reset();
  }
  fine_.insert(fine_.end(), top.fine_.begin() + fine_done, top.fine_.end());
  events.insert(events.end(), top.pairs_.begin() + pairs_done, top.pairs_.end());
  // The deepest evidence of each pair (the first of equal depths).
  for (const Walker::Pair& e : events) {
    auto it = pairs_.find(e.key);
    if (it == pairs_.end() || it->second.second < e.depth) pairs_[e.key] = {e.c, e.depth};
  }
  extract();
}

bool subset(const std::vector<int>& a, const std::vector<int>& b) {  // a in b, both sorted
  return std::includes(b.begin(), b.end(), a.begin(), a.end());
}

void Builder::extract() {
  VoronoiGraph& graph = result_.graph;
  std::unordered_map<unsigned long long, int> at;
  at.reserve(fine_.size() * 2);
  for (int i = 0; i < int(fine_.size()); ++i) at[cell_key(fine_[i].i, fine_[i].j, fine_[i].k)] = i;
  auto centre = [&](const FineCell& c) {
    return Vec3(sub_.origin_ + h_ * Vec3(c.i + 0.5, c.j + 0.5, c.k + 0.5));
  };
  // Connected pieces (26-neighbourhood, widened by `reach` cells) of cells passing `keep`.
  auto components = [&](auto keep, auto same, int reach) {
    std::vector<int> comp(fine_.size(), -1);
    std::vector<std::vector<int>> out;
    for (int s = 0; s < int(fine_.size()); ++s) {
      if (comp[s] >= 0 || !keep(fine_[s])) continue;
      std::vector<int> members{s};
      comp[s] = int(out.size());
      for (size_t q = 0; q < members.size(); ++q) {
        const FineCell& c = fine_[members[q]];
        for (int dx = -reach; dx <= reach; ++dx)
          for (int dy = -reach; dy <= reach; ++dy)
            for (int dz = -reach; dz <= reach; ++dz) {
              auto it = at.find(cell_key(c.i + dx, c.j + dy, c.k + dz));
              if (it == at.end() || comp[it->second] >= 0) continue;
              const FineCell& o = fine_[it->second];
              if (!keep(o) || !same(fine_[s], o)) continue;
              comp[it->second] = comp[s];
              members.push_back(it->second);
            }
      }
      out.push_back(std::move(members));
    }
    return std::make_pair(out, comp);
  };

  // Vertices: pieces of cells where four or more regions meet.
  auto [vcomps, vcomp] = components([](const FineCell& c) { return c.labels.n >= 4; },
                                    [](const FineCell&, const FineCell&) { return true; }, 1);
  std::vector<int> vertex_element(vcomps.size(), -1);
  std::vector<std::vector<int>> vgov(vcomps.size());
  for (int v = 0; v < int(vcomps.size()); ++v) {
    LabelSet all;
    Vec3 sum(0, 0, 0), lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
    for (int s : vcomps[v]) {
      for (int q = 0; q < fine_[s].labels.n; ++q) all.add(fine_[s].labels.v[q]);
      const Vec3 c = centre(fine_[s]);
      sum += c;
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
    all.sort();
    vgov[v] = all.vec();
    VoronoiElement el;
    el.governors = refs(vgov[v]);
    el.point = sum / double(vcomps[v].size());
    // A long piece is a degenerate Voronoi edge (e.g. governed by two faces and the two
    // edges between them and a third face), not a vertex.
    const bool elongated = (hi - lo).norm() > 4 * std::max(eps_, h_);
    el.kind = elongated ? ElementKind::edge : ElementKind::vertex;
    Vec3 x = el.point;
    double t = field_.boundary_distance(x);
    if (!elongated) {
      const double res = solve(field_, vgov[v], x, t, 12);
      const double reach = 3 * std::max(eps_, h_);
      if (res <= delta_ && (x - el.point).norm() <= reach && verify(field_, vgov[v], x, t)) {
        el.point = x;
        el.verified = true;
      } else {
        // The plane continuation can stall where the nearest facet changes; retry on the
        // closed distances (what verify checks), from the cluster centre and from each of
        // its cells.
        std::vector<Vec3> starts{el.point};
        for (int s : vcomps[v])
          if (starts.size() < 4) starts.push_back(centre(fine_[s]));
        for (const Vec3& start : starts) {
          x = start;
          t = field_.boundary_distance(x);
          if (solve(field_, vgov[v], x, t, 30, true) <= delta_ && (x - el.point).norm() <= reach &&
              verify(field_, vgov[v], x, t)) {
            el.point = x;
            el.verified = true;
            break;
          }
        }
      }
    } else {
      for (int s : vcomps[v]) el.polyline.push_back(centre(fine_[s]));
    }
    el.radius = el.verified ? t : field_.boundary_distance(el.point);
    // Regions also meet on the boundary (at a concave edge's end, say): those points are
    // ends of Voronoi edges, not Voronoi vertices.
    if (el.radius <= std::max(delta_, el.verified ? 0.0 : 1.5 * h_)) continue;
    if (!el.verified) {
      std::vector<std::string> names;
      for (const EntityRef& g : el.governors) names.push_back(g.name());
      result_.diagnostics.push_back(core::make_warning(
          elongated ? "degenerate_edge" : "vertex_not_verified",
          elongated ? "A degenerate Voronoi edge is approximated by cell centres"
                    : "A Voronoi vertex could not be placed exactly; its cluster centre is used",
          names));
    }
    vertex_element[v] = int(graph.elements.size());
    graph.elements.push_back(std::move(el));
  }

  // Edges: pieces of cells seeing exactly the same three regions.
  auto [ecomps, ecomp] = components([](const FineCell& c) { return c.labels.n == 3; },
                                    [](const FineCell& a, const FineCell& b) {
                                      return std::equal(a.labels.v.begin(), a.labels.v.begin() + 3,
                                                        b.labels.v.begin());
                                    },
                                    2);
  // Ends: vertex pieces within two cells whose governors contain the triple. Pieces of one
  // triple ending at the same vertex are one edge (sampling can cut an edge's cells).
  std::vector<int> parent(ecomps.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::vector<std::vector<int>> ends(ecomps.size());
  std::map<std::pair<std::vector<int>, int>, int> by_end;
  for (int e = 0; e < int(ecomps.size()); ++e) {
    const std::vector<int> triple = fine_[ecomps[e][0]].labels.vec();
    for (int s : ecomps[e]) {
      const FineCell& c = fine_[s];
      for (int dx = -2; dx <= 2; ++dx)
        for (int dy = -2; dy <= 2; ++dy)
          for (int dz = -2; dz <= 2; ++dz) {
            auto it = at.find(cell_key(c.i + dx, c.j + dy, c.k + dz));
            if (it == at.end() || vcomp[it->second] < 0) continue;
            const int v = vcomp[it->second];
            if (!subset(triple, vgov[v])) continue;
            if (std::find(ends[e].begin(), ends[e].end(), v) == ends[e].end()) ends[e].push_back(v);
          }
    }
    for (int v : ends[e]) {
      auto key = std::make_pair(triple, v);
      auto it = by_end.find(key);
      if (it == by_end.end())
        by_end[key] = e;
      else
        parent[root(e)] = root(it->second);
    }
  }
  std::map<int, std::vector<int>> merged;  // root -> pieces
  for (int e = 0; e < int(ecomps.size()); ++e) merged[root(e)].push_back(e);
  std::vector<std::pair<int, int>> arcs;
  // Points on the edges: each cell centre moved onto the equidistant curve (independent
  // solves, on all threads).
  struct Placement {
    int cell;
    const std::vector<int>* triple;
    Vec3 x;
    bool ok = false;
  };
  std::vector<Placement> placed;
  std::vector<std::vector<int>> triples;
  triples.reserve(merged.size());
  for (const auto& [r, pieces] : merged) {
    triples.push_back(fine_[ecomps[r][0]].labels.vec());
    for (int e : pieces)
      for (int s : ecomps[e]) placed.push_back({s, &triples.back(), Vec3::Zero()});
  }
  parallel_for(int(placed.size()), [&](const DistanceField& field, int i) {
    Placement& q = placed[i];
    Vec3 x = centre(fine_[q.cell]);
    double t = field.boundary_distance(x);
    const double res = solve(field, *q.triple, x, t, 8);
    q.ok = res <= delta_ && t > delta_ && (x - centre(fine_[q.cell])).norm() <= 2 * h_ &&
           verify(field, *q.triple, x, t);
    q.x = x;
  });
  size_t next_placed = 0;
  for (const auto& [r, pieces] : merged) {
    const std::vector<int> triple = fine_[ecomps[r][0]].labels.vec();
    std::vector<int> cells, vends;
    for (int e : pieces) {
      cells.insert(cells.end(), ecomps[e].begin(), ecomps[e].end());
      for (int v : ends[e])
        if (std::find(vends.begin(), vends.end(), v) == vends.end()) vends.push_back(v);
    }
    VoronoiElement el;
    el.kind = ElementKind::edge;
    el.governors = refs(triple);
    std::vector<Vec3> pts;
    for (size_t k = 0; k < cells.size(); ++k, ++next_placed)
      if (placed[next_placed].ok) pts.push_back(placed[next_placed].x);
    // Cells along a boundary edge see the regions meeting there; no interior point of such
    // a piece is equidistant: it is not a Voronoi edge.
    if (pts.empty()) {
      double deepest = 0;
      for (int s : cells) deepest = std::max(deepest, field_.boundary_distance(centre(fine_[s])));
      if (deepest <= 2 * h_) continue;
    }
    // Points that could not be placed (near the solid's boundary, say) are left out.
    el.verified = !pts.empty();
    if (pts.empty())
      for (int s : cells) pts.push_back(centre(fine_[s]));
    // Order: from an end vertex (or the point farthest from the middle), nearest next.
    Vec3 start;
    vends.erase(
        std::remove_if(vends.begin(), vends.end(), [&](int v) { return vertex_element[v] < 0; }),
        vends.end());
    if (!vends.empty()) {
      start = graph.elements[vertex_element[vends[0]]].point;
    } else {
      Vec3 mean = Vec3::Zero();
      for (const Vec3& p : pts) mean += p;
      mean /= double(pts.size());
      start = *std::max_element(pts.begin(), pts.end(), [&](const Vec3& a, const Vec3& b) {
        return (a - mean).squaredNorm() < (b - mean).squaredNorm();
      });
    }
    std::vector<Vec3> chain;
    if (!vends.empty()) chain.push_back(start);
    Vec3 cur = start;
    std::vector<char> used(pts.size(), 0);
    for (size_t n = 0; n < pts.size(); ++n) {
      int best = -1;
      double bd = kInf;
      for (int i = 0; i < int(pts.size()); ++i)
        if (!used[i] && (pts[i] - cur).squaredNorm() < bd) {
          bd = (pts[i] - cur).squaredNorm();
          best = i;
        }
      used[best] = 1;
      cur = pts[best];
      if (chain.empty() || (cur - chain.back()).norm() >= 0.5 * h_) chain.push_back(cur);
    }
    if (vends.size() >= 2) chain.push_back(graph.elements[vertex_element[vends[1]]].point);
    el.polyline = std::move(chain);
    el.point = el.polyline[el.polyline.size() / 2];
    el.radius = field_.boundary_distance(el.point);
    const int id = int(graph.elements.size());
    for (int v : vends)
      if (vertex_element[v] >= 0) arcs.emplace_back(id, vertex_element[v]);
    graph.elements.push_back(std::move(el));
  }

  // Faces: pairs of regions seen side by side.
  std::map<std::pair<int, int>, int> face_of;
  std::vector<std::pair<std::pair<int, int>, std::pair<Vec3, double>>> evidences(pairs_.begin(),
                                                                                 pairs_.end());
  std::vector<Placement> face_points(evidences.size());
  parallel_for(int(evidences.size()), [&](const DistanceField& field, int i) {
    const std::vector<int> govs{evidences[i].first.first, evidences[i].first.second};
    Vec3 x = evidences[i].second.first;
    double t = field.boundary_distance(x);
    face_points[i].ok =
        solve(field, govs, x, t, 8) <= delta_ && t > delta_ && verify(field, govs, x, t);
    face_points[i].x = x;
  });
  for (size_t i = 0; i < evidences.size(); ++i) {
    const auto& [pair, evidence] = evidences[i];
    const Vec3 c = evidence.first;
    VoronoiElement el;
    el.kind = ElementKind::face;
    const std::vector<int> govs{pair.first, pair.second};
    el.governors = refs(govs);
    el.point = c;
    if (face_points[i].ok) {
      el.point = face_points[i].x;
      el.verified = true;
    }
    // Seen only at the boundary (two faces meeting at a concave edge): not a Voronoi face.
    if (!el.verified && evidence.second <= 3 * h_) continue;
    el.radius = field_.boundary_distance(el.point);
    const EntityRef a = el.governors[0], b = el.governors[1];
    el.fs = a.kind == model::EntityKind::face && b.kind == model::EntityKind::face &&
            model_.unconnected(a, b);
    face_of[pair] = int(graph.elements.size());
    graph.elements.push_back(std::move(el));
  }
  // Face arcs: to every edge and vertex whose governors contain the pair.
  for (int i = 0; i < int(graph.elements.size()); ++i) {
    const VoronoiElement& el = graph.elements[i];
    if (el.kind == ElementKind::face) continue;
    std::vector<int> govs;
    for (const EntityRef& g : el.governors) govs.push_back(model_.index(g));
    std::sort(govs.begin(), govs.end());
    for (size_t a = 0; a < govs.size(); ++a)
      for (size_t b = a + 1; b < govs.size(); ++b) {
        auto it = face_of.find({govs[a], govs[b]});
        if (it != face_of.end()) arcs.emplace_back(i, it->second);
      }
  }
  for (const auto& [a, b] : arcs) {
    graph.elements[a].incident.push_back(b);
    graph.elements[b].incident.push_back(a);
  }
  for (VoronoiElement& el : graph.elements) {
    std::sort(el.incident.begin(), el.incident.end());
    el.incident.erase(std::unique(el.incident.begin(), el.incident.end()), el.incident.end());
  }
}

}  // namespace

const char* element_kind_name(ElementKind k) {
  switch (k) {
    case ElementKind::face:
      return "face";
    case ElementKind::edge:
      return "edge";
    case ElementKind::vertex:
      return "vertex";
  }
  return "?";
}

std::string VoronoiOptions::validate() const {
  if (!(eps > 0 && eps <= 0.25))
    return "eps must be in (0, 0.25] (relative to the bounding-box diagonal)";
  if (!(delta > 0 && delta <= eps))
    return "delta must be in (0, eps] (relative to the bounding-box diagonal)";
  if (max_depth < 1 || max_depth > 12) return "max_depth must be in 1..12";
  if (threads < 0) return "threads must be 0 (automatic) or more";
  if (!(linear_tolerance > 0 && linear_tolerance < 0.5))
    return "linear_tolerance must be in (0, 0.5) (relative to the bounding-box diagonal)";
  return {};
}

std::vector<int> VoronoiGraph::of_kind(ElementKind k) const {
  std::vector<int> out;
  for (int i = 0; i < int(elements.size()); ++i)
    if (elements[i].kind == k) out.push_back(i);
  return out;
}

std::vector<int> VoronoiGraph::fs_faces() const {
  std::vector<int> out;
  for (int i = 0; i < int(elements.size()); ++i)
    if (elements[i].fs) out.push_back(i);
  return out;
}

std::vector<int> VoronoiGraph::bounding_edges(int face) const {
  std::vector<int> out;
  for (int i : elements.at(face).incident)
    if (elements[i].kind == ElementKind::edge) out.push_back(i);
  return out;
}

std::vector<int> VoronoiGraph::edge_vertices(int edge) const {
  std::vector<int> out;
  for (int i : elements.at(edge).incident)
    if (elements[i].kind == ElementKind::vertex) out.push_back(i);
  return out;
}

std::vector<int> VoronoiGraph::find(std::vector<EntityRef> governors) const {
  std::sort(governors.begin(), governors.end());
  std::vector<int> out;
  for (int i = 0; i < int(elements.size()); ++i)
    if (elements[i].governors == governors) out.push_back(i);
  return out;
}

VoronoiResult compute_voronoi_graph(std::shared_ptr<const model::BRepModel> model,
                                    const VoronoiOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  VoronoiResult result;
  if (std::string why = options.validate(); !why.empty()) {
    result.diagnostics.push_back(core::make_error("invalid_options", why));
    return result;
  }
  if (!model || model->linear().polygons.empty()) {
    result.diagnostics.push_back(
        core::make_error("empty_model", "The solid has no faces to work on"));
    return result;
  }
  auto sub = std::make_shared<Subdivision>(model);
  Builder builder(*sub, options, result);
  builder.run();
  result.stats.distance_evaluations += sub->field_.evaluations();
  result.model = model;
  result.locator = sub;
  result.status = core::has_error(result.diagnostics) ? VoronoiStatus::failed
                  : result.diagnostics.empty()        ? VoronoiStatus::ok
                                                      : VoronoiStatus::partial;
  result.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

VoronoiResult compute_voronoi_graph(const occ::Solid& solid, const VoronoiOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  VoronoiResult result;
  if (std::string why = options.validate(); !why.empty()) {
    result.diagnostics.push_back(core::make_error("invalid_options", why));
    return result;
  }
  model::ModelOptions mopt;
  mopt.linear_tolerance = options.linear_tolerance;
  model::ModelResult m = model::build_model(solid, mopt);
  const double model_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!m.ok()) {
    result.diagnostics = std::move(m.diagnostics);
    return result;
  }
  result =
      compute_voronoi_graph(std::shared_ptr<const model::BRepModel>(std::move(m.model)), options);
  result.stats.model_seconds = model_seconds;
  result.stats.seconds += model_seconds;
  return result;
}

}  // namespace vorohex::voronoi
