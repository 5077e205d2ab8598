// The octree walk of the Voronoi stage (private to App/voronoi): the candidate entities of
// each cell, its leaves and the labels of the finest cells. Header-only; one walker per
// task and thread.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include "voronoi/detail/distance_field.h"
#include "voronoi/voronoi_graph.h"

namespace vorohex::voronoi::detail {

constexpr int kMaxLabels = 12;

// The distinct entities seen at a cell's sample points (at most kMaxLabels).
struct LabelSet {
  std::array<int, kMaxLabels> v{};
  int n = 0;
  void add(int e) {
    if (e < 0) return;
    for (int i = 0; i < n; ++i)
      if (v[i] == e) return;
    if (n < kMaxLabels) v[n++] = e;
  }
  void sort() { std::sort(v.begin(), v.begin() + n); }
  std::vector<int> vec() const { return std::vector<int>(v.begin(), v.begin() + n); }
};

struct FineCell {
  int i, j, k;
  LabelSet labels;
};

struct OctNode {
  int child = -1;      // first of 8 children, or -1 for a leaf
  int entity = -1;     // uniform leaf: the owning entity; -1 outside or mixed
  int cand_begin = 0;  // mixed leaf: candidates in the pool
  int cand_count = 0;
};

// Builds the octree below one cell (a task): candidates, leaves and the finest cells'
// labels. Each thread has its own; node and pool indices are local to the walker and
// fine_ / pairs_ list the findings in depth-first order (merged by Builder in task order).
class Walker {
 public:
  struct Params {
    Vec3 origin{0, 0, 0};
    double h = 0, tie = 0;
    int level = 1;
    int task_depth = 99;  // cells at this depth are not visited but queued as tasks
  };
  struct Task {
    int node = 0;  // in the caller's numbering
    Vec3 lo{0, 0, 0};
    double size = 0, bound = 0;
    int depth = 0;
    std::vector<int> cands;  // the parent's candidates, their distance and zone distance
    std::vector<double> dist, zone;
    size_t fine_mark = 0, pair_mark = 0;  // where its findings go among the caller's
  };
  struct Pair {
    std::pair<int, int> key;
    Vec3 c;
    double depth;
  };

  Walker(const DistanceField& field, const Params& p)
      : field_(field),
        origin_(p.origin),
        h_(p.h),
        field_tie_(p.tie),
        level_(p.level),
        task_depth_(p.task_depth) {}

  // The whole subtree of the task's cell; its root is local node 0.
  void run(const Task& t) {
    arena_ = t.cands;
    dist_ = t.dist;
    zone_ = t.zone;
    nodes_.emplace_back();
    visit(0, t.lo, t.size, t.depth, 0, int(arena_.size()), t.bound);
  }

  std::vector<OctNode> nodes_;
  std::vector<int> pool_;
  std::vector<FineCell> fine_;
  std::vector<Pair> pairs_;
  std::vector<Task> tasks_;
  VoronoiStats stats_;

 private:
  // Candidates of the cell from its parent's, then leaf or split. `bound` is at least the
  // boundary distance of the centre (the parent's plus the distance between the centres).
  // arena_[pbeg, pbeg + pcount) are the parent's candidates, with their distance and zone
  // distance from the parent's centre in dist_ and zone_ (lower bounds for the child's).
  void visit(int node, const Vec3& lo, double size, int depth, int pbeg, int pcount, double bound) {
    ++stats_.cells;
    const Vec3 c = lo + Vec3::Constant(0.5 * size);
    const double r = 0.5 * std::sqrt(3.0) * size;
    const double D = field_.boundary_distance(c, bound);
    // Parent centre to child centre is r; both distances are 1-Lipschitz.
    const double slack = depth > 0 ? r + field_tie_ : kInf;
    const int beg = int(arena_.size());
    int ents[4];
    int nent = 0;
    for (int k = pbeg; k < pbeg + pcount; ++k) {
      if (dist_[k] - slack > D + 2 * r || zone_[k] - slack > r) continue;
      const int i = arena_[k];
      const Prim& pr = field_.prim(i);
      const Vec3 d = (pr.lo - c).cwiseMax(c - pr.hi).cwiseMax(0.0);
      if (d.norm() > D + 2 * r) continue;
      double dist, zone;
      field_.bounds(i, c, D + 2 * r, &dist, &zone);
      if (dist > D + 2 * r || zone > r) continue;
      arena_.push_back(i);
      dist_.push_back(dist);
      zone_.push_back(zone);
      if (nent < 4 && std::find(ents, ents + nent, pr.entity) == ents + nent)
        ents[nent++] = pr.entity;
      else if (nent == 4 && std::find(ents, ents + 4, pr.entity) == ents + 4)
        nent = 5;
    }
    const int count = int(arena_.size()) - beg;
    auto pop = [&] {
      arena_.resize(beg);
      dist_.resize(beg);
      zone_.resize(beg);
    };
    OctNode& self = nodes_[node];
    if (count == 0) {
      ++stats_.leaves;
      pop();
      return;
    }
    if (D > r) {
      sort_candidates(beg, count);
      if (owner(c, 0.0) < 0) {  // wholly outside
        ++stats_.leaves;
        pop();
        return;
      }
    }
    if (nent == 1) {
      self.entity = ents[0];
      ++stats_.leaves;
      pop();
      return;
    }
    if (nent == 2 && depth > 0) {
      // Only two regions can meet here: at most a piece of their Voronoi face. Its evidence
      // only counts if deeper than what this walker has seen before (the first of equal
      // depths is kept), so the sampling is skipped otherwise.
      const std::pair<int, int> key(std::min(ents[0], ents[1]), std::max(ents[0], ents[1]));
      auto seen = deepest_.find(key);
      if (seen == deepest_.end() || seen->second < D) {
        if (!(D > r)) sort_candidates(beg, count);
        LabelSet labels = sample(lo, size, 2, nent);
        if (labels.n == 2) add_pair(labels, c, D);
      }
      store_leaf(node, beg, count);
      pop();
      return;
    }
    if (depth < level_) {
      const int first = int(nodes_.size());
      nodes_[node].child = first;
      nodes_.resize(first + 8);
      const double half = 0.5 * size;
      for (int q = 0; q < 8; ++q) {
        const Vec3 clo = lo + half * Vec3(q & 1, (q >> 1) & 1, (q >> 2) & 1);
        if (depth + 1 == task_depth_)
          tasks_.push_back({first + q, clo, half, D + 0.5 * r, depth + 1,
                            std::vector<int>(arena_.begin() + beg, arena_.end()),
                            std::vector<double>(dist_.begin() + beg, dist_.end()),
                            std::vector<double>(zone_.begin() + beg, zone_.end()), fine_.size(),
                            pairs_.size()});
        else
          visit(first + q, clo, half, depth + 1, beg, count, D + 0.5 * r);
      }
      pop();
      return;
    }
    ++stats_.finest_cells;
    if (!(D > r)) sort_candidates(beg, count);
    LabelSet labels = sample(lo, size, 3, nent);
    labels.sort();
    if (labels.n == 2) add_pair(labels, c, D);
    if (labels.n >= 3) {
      const Vec3 rel = (lo - origin_) / h_;
      fine_.push_back({int(std::lround(rel.x())), int(std::lround(rel.y())),
                       int(std::lround(rel.z())), labels});
    }
    store_leaf(node, beg, count);
    pop();
  }

  // The cell's candidates arena_[beg, beg + count) ordered by distance from its centre c_,
  // for owner_sorted.
  void sort_candidates(int beg, int count) {
    pos_.resize(count);
    std::iota(pos_.begin(), pos_.end(), 0);
    std::sort(pos_.begin(), pos_.end(), [&](int a, int b) {
      const double da = dist_[beg + a], db = dist_[beg + b];
      return da != db ? da < db : a < b;
    });
    sorted_.resize(count);
    sorted_dist_.resize(count);
    for (int k = 0; k < count; ++k) {
      sorted_[k] = arena_[beg + pos_[k]];
      sorted_dist_[k] = dist_[beg + pos_[k]];
    }
  }

  // Owner of p, at most `reach` from the centre of the cell of the last sort_candidates.
  int owner(const Vec3& p, double reach) const {
    return field_.owner_sorted(p, sorted_.data(), pos_.data(), sorted_dist_.data(),
                               int(sorted_.size()), reach);
  }

  void store_leaf(int node, int beg, int count) {
    ++stats_.leaves;
    OctNode& n = nodes_[node];
    n.cand_begin = int(pool_.size());
    n.cand_count = count;
    pool_.insert(pool_.end(), arena_.begin() + beg, arena_.begin() + beg + count);
  }

  // Owners at an s x s x s grid of points of the cell (corners included). The labels are
  // among the candidates' `nent` entities (5: more than 4): once all are seen, no other
  // sample can add one.
  LabelSet sample(const Vec3& lo, double size, int s, int nent) {
    LabelSet labels;
    const double step = size / (s - 1 > 0 ? s - 1 : 1);
    const Vec3 c = lo + Vec3::Constant(0.5 * size);
    for (int a = 0; a < s; ++a)
      for (int b = 0; b < s; ++b)
        for (int k = 0; k < s; ++k) {
          const Vec3 p = lo + step * Vec3(a, b, k);
          labels.add(owner(p, (p - c).norm()));
          if (labels.n == nent && nent <= 4) return labels;
        }
    return labels;
  }

  // `depth`: the boundary distance of c.
  void add_pair(LabelSet labels, const Vec3& c, double depth) {
    labels.sort();
    const auto key = std::make_pair(labels.v[0], labels.v[1]);
    pairs_.push_back({key, c, depth});
    double& d = deepest_.try_emplace(key, depth).first->second;
    d = std::max(d, depth);
  }

  const DistanceField& field_;
  Vec3 origin_;
  double h_, field_tie_;
  int level_, task_depth_;
  std::vector<int> arena_;
  std::vector<double> dist_, zone_;  // per arena_ entry: from its cell's centre
  std::vector<int> pos_, sorted_;    // candidates of the current cell by distance
  std::vector<double> sorted_dist_;
  std::map<std::pair<int, int>, double> deepest_;  // deepest evidence of each pair so far
};

}  // namespace vorohex::voronoi::detail
