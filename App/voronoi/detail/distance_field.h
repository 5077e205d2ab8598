// Exact distances from points to the primitives of a BRepModel's linearisation, with the
// ownership rule of the Voronoi stage. Private to App/voronoi; tested directly.
//
// Ownership: a point inside the solid belongs to the entity whose relative interior
// contains its nearest boundary point. For a polygon that means the projection falls
// inside it on the material side; for a segment, inside its slab; for a corner, inside its
// normal cone. Only governing primitives (polygons, concave segments and corners) can
// own interior points. Primitives that approximate one model entity all answer with that
// entity (this is the paper's uniting of linearised elements, done on the fly); a concave
// segment or corner of an entity that does not govern (a smooth edge, a corner inside a
// curved face) answers with a face it bounds.
#pragma once

#include <limits>
#include <vector>

#include <Eigen/Core>

#include "model/brep_model.h"

namespace vorohex::voronoi::detail {

using core::Vec3;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Prim {
  enum Type : unsigned char { polygon, segment, corner };
  Type type = polygon;
  int source = 0;   // polygon piece (internal) / the model's linear segment / corner index
  int entity = -1;  // dense model index of the entity owning points nearest to its interior
  Vec3 lo, hi;      // bounding box
};

class DistanceField {
 public:
  explicit DistanceField(const model::BRepModel& model);

  int size() const { return int(prims_.size()); }
  const Prim& prim(int i) const { return prims_[i]; }
  // Primitives that can own interior points.
  const std::vector<int>& governing() const { return governing_; }
  // Governing primitives of a dense entity index.
  const std::vector<int>& entity_prims(int entity) const { return entity_prims_[entity]; }
  int num_entities() const { return int(entity_prims_.size()); }

  // Supporting plane of a polygon primitive (a point on it and its outward normal).
  void plane(int i, Vec3* origin, Vec3* normal) const {
    *origin = polys_[prims_[i].source].origin;
    *normal = polys_[prims_[i].source].normal;
  }
  // Distance to the closed primitive, and its nearest point.
  double distance(int i, const Vec3& p, Vec3* nearest = nullptr) const;
  // Distance if the nearest point lies in the primitive's relative interior and p is on
  // the material side (polygons), else infinity.
  double restricted(int i, const Vec3& p) const;
  // A lower bound on the distance from p to the zone of points the primitive may own
  // (1-Lipschitz in p; 0 if unknown).
  double zone_distance(int i, const Vec3& p) const;
  // Both of the above in one pass; stops early (returning a lower bound on the distance)
  // once the distance is known to exceed `limit`.
  void bounds(int i, const Vec3& p, double limit, double* distance, double* zone) const;
  // Distance from p to the whole boundary (all polygons), through a bounding-volume
  // hierarchy. `bound`, if given, is known to be at least the distance (e.g. a neighbour's
  // distance plus the gap): the search then skips farther nodes; same result.
  double boundary_distance(const Vec3& p, double bound = kInf) const;
  // Distance to an entity's governing primitives (closed) and the nearest point.
  double entity_distance(int entity, const Vec3& p, Vec3* nearest = nullptr) const;
  // Owner of p among the candidate primitives: the dense entity index, or -1 when p is
  // outside the solid (no candidate's relative interior holds the nearest point).
  // `margin` gets the gap to the nearest other entity (restricted distances).
  int owner(const Vec3& p, const int* candidates, int n, double* distance = nullptr,
            double* margin = nullptr) const;
  // owner(p, candidates, n) when only the entity is needed, faster: the candidates come
  // sorted by their closed distance `dist0` from a point within `reach` of p (ties by
  // `pos`, their place in the candidate list owner() would get); those that cannot be
  // nearer than the best so far are skipped. Same answer as owner().
  int owner_sorted(const Vec3& p, const int* sorted, const int* pos, const double* dist0, int n,
                   double reach) const;
  // The same over all governing primitives (brute force, for tests and checks).
  int owner(const Vec3& p, double* distance = nullptr, double* margin = nullptr) const;

  long long evaluations() const { return evaluations_; }

 private:
  struct Poly {
    Vec3 origin, normal, u, v;
    std::vector<Eigen::Vector2d> pts;  // all loops, each closed by loop_end
    std::vector<int> loop_end;         // one past the last point of each loop
  };
  struct Seg {
    Vec3 a, dir;  // unit direction
    double length = 0;
  };
  struct Corner {
    Vec3 p;
    std::vector<Vec3> away;  // unit directions to neighbours (cone lies behind all of them)
  };
  struct Node {  // bounding-volume hierarchy over polygons
    Vec3 lo, hi;
    int left = -1, right = -1, first = 0, count = 0;
  };
  int build(int first, int count, int depth);
  double boundary_distance_below(const Vec3& p, double limit) const;
  // 2-D: squared distance to the loops and whether the point is inside.
  double poly_query(const Poly& q, const Vec3& p, double* h, bool* inside,
                    Eigen::Vector2d* nearest2) const;

  const model::BRepModel& model_;
  std::vector<Prim> prims_;
  std::vector<Poly> polys_;
  std::vector<Seg> segs_;
  std::vector<Corner> corners_;
  std::vector<int> governing_;
  std::vector<std::vector<int>> entity_prims_;
  std::vector<Node> nodes_;
  std::vector<int> order_;  // polygon primitive indices in BVH order
  double tie_ = 0;          // absolute tolerance for equal distances
  mutable long long evaluations_ = 0;
};

}  // namespace vorohex::voronoi::detail
