// Interval assignment (paper §5.1): the number of mesh segments on every curve of a set of
// sub-volumes, chosen together so that their meshes conform. One integer program, solved by
// COIN-OR CBC: integer counts n_c >= 1 close to their targets, length_c / size or the
// local size field's count along the curve (weighted absolute
// deviation), subject to equal sums (opposite sides of mapped faces, the two sides of a
// sweep's linking face, the layers of a sweep) and even sums (loops of faces meshed with
// unstructured quads) and lower bounds on sums (a loop of quads has at least 4 segments).
#pragma once

#include <string>
#include <vector>

#include "core/diagnostic.h"

namespace vorohex::mesh {

struct IntervalProblem {
  // Per curve: its length (model units, > 0) and a name for diagnostics ("Edge7").
  std::vector<double> lengths;
  std::vector<std::string> names;
  // sum(n[lhs]) == sum(n[rhs]); `why` names what asks for it ("Face3: opposite sides").
  struct Equal {
    std::vector<int> lhs, rhs;
    std::string why;
  };
  std::vector<Equal> equal;
  // sum(n[curves]) is even, or a multiple of `multiple` (>= 2).
  struct Even {
    std::vector<int> curves;
    std::string why;
    int multiple = 2;
  };
  std::vector<Even> even;
  // sum(n[curves]) >= minimum.
  struct AtLeast {
    std::vector<int> curves;
    int minimum = 1;
    std::string why;
  };
  std::vector<AtLeast> at_least;
  // Per curve: a count it must have (0 or missing: free), e.g. a curve whose nodes a
  // neighbour has already placed.
  std::vector<int> fixed;
  // Per curve: the count it should have (0 or missing: length / size); local sizes give
  // the integral of ds / h along the curve (core::SizeField). A target above length / size
  // (a refined curve) costs a thousand times more when missed from below than from above:
  // in effect a soft lower bound, so the finest request wins an equality.
  std::vector<double> targets;

  // Its index; target as in `targets`.
  int add_curve(double length, std::string name, double target = 0);
  double target(int curve, double size) const;
};

struct IntervalOptions {
  double size = 1.0;           // target segment length, model units (> 0)
  int max_intervals = 100000;  // per curve (>= 1)
  double time_limit = 20;      // seconds CBC may search (> 0); the best count found stands
  void validate() const;       // throws std::invalid_argument naming the bad field
};

enum class IntervalStatus { optimal, feasible, infeasible };

struct IntervalResult {
  std::vector<int> intervals;  // per curve (empty unless ok())
  IntervalStatus status = IntervalStatus::infeasible;
  double deviation = 0;  // objective: sum over curves of |n - target| / max(1, target)
  std::vector<core::Diagnostic> diagnostics;  // infeasible: error naming the constraints
  bool ok() const { return status != IntervalStatus::infeasible; }
};

// Throws std::invalid_argument on invalid options or a constraint naming a curve that does
// not exist; an infeasible system is a status with an `intervals_infeasible` error.
IntervalResult assign_intervals(const IntervalProblem& problem, const IntervalOptions& options);

}  // namespace vorohex::mesh
