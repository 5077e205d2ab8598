#include "decompose/detail/piece_merges.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "mesh/map_block.h"
#include "mesh/mesh_sub_volumes.h"
#include "mesh/multisweep.h"
#include "mesh/revolve.h"
#include "mesh/sweep.h"
#include "occ/split_solid.h"

namespace vorohex::decompose::detail {

// Gluing the pieces of one exact split, or unions of them: they touch at faces and never
// cross, so OCCT's general fuse need not intersect their faces (HexMe i22: 65% of the
// cuts' time was spent gluing).
occ::GlueOptions touching_only() {
  occ::GlueOptions o;
  o.only_touching = true;
  return o;
}

// A block, a sweep, a prismatic part (o.multisweep) or a solid of revolution (o.revolve):
// what mesh::mesh_sub_volumes meshes.
// `glued`: a piece glued to the others (its sweep's linking sides may carry their imprints).
bool meshable(const occ::Solid& s, const PlaneCutOptions& o, bool glued) {
  return mesh::map_block_applicable(s).ok || mesh::sweep_applicable(s, glued).ok ||
         (o.multisweep && mesh::multisweep_applicable(s).ok) ||
         (o.revolve && mesh::revolve_applicable(s).ok);
}

// The pieces glued (imprinting each other's edges where they touch).
occ::ReadResult glued(const std::vector<const occ::Solid*>& pieces) {
  return occ::glue_solids(pieces, "The plane cut", touching_only());
}

// Each part of the glued pieces `g` a block, a sweep or prismatic (gluing imprints a
// neighbour's edges); `why` (when given) names the first that is none.
bool all_meshable(const occ::ReadResult& g, const PlaneCutOptions& o, std::string* why,
                  bool imprinted) {
  if (!g.ok()) {
    if (why) *why = g.diagnostics.empty() ? "they do not glue" : g.diagnostics[0].message;
    return false;
  }
  if (!why) {
    for (int k = 0; k < g.solid->num_solids(); ++k)
      if (!meshable(g.solid->part(k), o, imprinted)) return false;
    return true;
  }
  const mesh::SubVolumePlan plan =
      mesh::plan_sub_volumes(*g.solid, o.multisweep, o.revolve, imprinted);
  *why = plan.why_not;
  return plan.ok;
}

bool all_meshable(const std::vector<const occ::Solid*>& pieces, const PlaneCutOptions& o,
                  std::string* why, bool imprinted) {
  return all_meshable(glued(pieces), o, why, imprinted);
}

// The cut's own check: every piece has volume, and they fill the solid (OCCT's split of a
// cylinder against a nearly coincident face, or a union of such pieces, can leave one turned
// inside out). False with why; `volumes` gets each piece's.
bool volumes_fill(const std::vector<occ::Solid>& pieces, double whole, std::vector<double>& volumes,
                  std::string& why) {
  double sum = 0;
  volumes.clear();
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const double v = pieces[k].volume();
    volumes.push_back(v);
    if (!(v > 0)) {
      std::ostringstream m;
      m << "OCCT's cut along the surfaces of its concave edges left piece " << k + 1
        << " with volume " << v;
      why = m.str();
      return false;
    }
    sum += v;
  }
  if (std::abs(sum - whole) <= kVolumeTolerance * whole) return true;
  std::ostringstream m;
  m.precision(10);
  m << "OCCT's cut along the surfaces of its concave edges left pieces whose volumes sum to " << sum
    << ", not the solid's " << whole;
  why = m.str();
  return false;
}

namespace {

bool boxes_touch(const core::BoundingBox& p, const core::BoundingBox& q) {
  const double tol = 1e-6 * std::max(p.diagonal(), q.diagonal());
  for (int i = 0; i < 3; ++i)
    if (p.min[i] > q.max[i] + tol || q.min[i] > p.max[i] + tol) return false;
  return true;
}

// Gluing keeps each piece's extent: the glued part of a piece is the one with its box.
bool same_box(const core::BoundingBox& p, const core::BoundingBox& q) {
  const double tol = 1e-6 * std::max(p.diagonal(), q.diagonal());
  for (int i = 0; i < 3; ++i)
    if (std::abs(p.min[i] - q.min[i]) > tol || std::abs(p.max[i] - q.max[i]) > tol) return false;
  return true;
}

}  // namespace

// The bounding box of each solid (OCCT's optimal box walks the geometry: computed once).
std::vector<core::BoundingBox> boxes_of(const std::vector<const occ::Solid*>& solids) {
  std::vector<core::BoundingBox> out;
  for (const occ::Solid* s : solids) out.push_back(s->bounding_box());
  return out;
}

// The index in `boxes` of the piece whose box `part` has; -1 when none or several.
int piece_of(const occ::Solid& part, const std::vector<core::BoundingBox>& boxes) {
  const core::BoundingBox box = part.bounding_box();
  int found = -1;
  for (std::size_t g = 0; g < boxes.size(); ++g)
    if (same_box(box, boxes[g])) {
      if (found >= 0) return -1;
      found = int(g);
    }
  return found;
}

// Which pieces touch once glued (share a vertex, so also those sharing an edge or a face);
// a piece whose glued part cannot be told by its box touches every piece its box touches.
// `r`: the pieces glued.
Touching touching(const std::vector<const occ::Solid*>& pieces, const occ::ReadResult& r) {
  const std::size_t n = pieces.size();
  Touching t(n, std::vector<char>(n, 0));
  std::vector<char> known(n, 0);
  const std::vector<core::BoundingBox> boxes = boxes_of(pieces);
  if (r.ok()) {
    std::map<int, std::vector<std::size_t>> at_vertex;
    for (int k = 0; k < r.solid->num_solids(); ++k) {
      const occ::Solid part = r.solid->part(k);
      const int p = piece_of(part, boxes);
      if (p < 0) continue;
      known[p] = 1;
      const std::vector<int> ids = r.solid->part_ids(part, 0);
      for (std::size_t v = 1; v < ids.size(); ++v)
        if (ids[v] > 0) at_vertex[ids[v]].push_back(std::size_t(p));
    }
    for (const auto& [v, ps] : at_vertex)
      for (std::size_t i : ps)
        for (std::size_t j : ps)
          if (i != j) t[i][j] = 1;
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      if (i != j && (!known[i] || !known[j]) && boxes_touch(boxes[i], boxes[j]))
        t[i][j] = t[j][i] = 1;
  return t;
}

// Whether merging pieces a and b into `u` keeps every piece meshable once glued: the union
// and the pieces touching it (the only ones whose imprints change) are checked, glued with
// the pieces touching those (everything that imprints on them). Gluing this neighbourhood
// instead of all pieces: on HexMe i22's 80 pieces each check glued all of them (0.6 s; 43
// merges took the whole 30 s and stopped at 37 pieces, among them stacked multisweeps whose
// common cap the two mesh differently); so, 76 merges down to 4 pieces in 22 s.
namespace {

struct Neighbourhood {
  std::vector<std::size_t> glued;  // a and b's neighbours, then the pieces touching those
  std::size_t checked = 0;         // the first `checked` (and the union) are checked
};

Neighbourhood neighbourhood(std::size_t n, const Touching& touch, std::size_t a, std::size_t b) {
  Neighbourhood h;
  std::vector<char> taken(n, 0);
  taken[a] = taken[b] = 1;
  for (std::size_t k = 0; k < n; ++k)
    if (!taken[k] && (touch[a][k] || touch[b][k])) taken[k] = 1, h.glued.push_back(k);
  h.checked = h.glued.size();
  for (std::size_t k = 0; k < n; ++k) {
    if (taken[k]) continue;
    for (std::size_t i = 0; i < h.checked; ++i)
      if (touch[h.glued[i]][k]) {
        taken[k] = 1, h.glued.push_back(k);
        break;
      }
  }
  return h;
}

// Whether the first `checked` of `glued` are meshable once all are glued (the pieces of one
// exact split: each told by its box).
bool meshable_glued(const std::vector<const occ::Solid*>& glued, std::size_t checked,
                    const PlaneCutOptions& o) {
  occ::GlueOptions go = touching_only();
  go.check_overlap = false;   // the pieces of one exact split, and the union's volume checked
  go.check_manifold = false;  // pieces joined by faces outside the neighbourhood
  const occ::ReadResult r = occ::glue_solids(glued, "The plane cut", go);
  if (!r.ok()) return false;
  const std::vector<core::BoundingBox> boxes = boxes_of(glued);
  // One of the outer ring needs no check (the merge does not change what touches it); a
  // part told by no box, or by several, is checked.
  for (int k = 0; k < r.solid->num_solids(); ++k) {
    const occ::Solid part = r.solid->part(k);
    const int p = piece_of(part, boxes);
    if (p >= int(checked)) continue;
    if (!meshable(part, o)) return false;
  }
  return true;
}

enum class Kept { yes, not_the_union, not_a_neighbour };

// Whether merging into `u` keeps every piece of neighbourhood `h` meshable once glued. The
// union first, glued with the pieces touching it only (the only ones that imprint on it):
// where the merge fails, it mostly fails there (the keyed shaft of bench/run_parts.py: 17 of
// 24 checks), and a smaller glue is cheaper (0.05 to 0.1 s for 5 to 13 pieces, 0.18 s for 22).
Kept merge_keeps_meshable(const std::vector<occ::Solid>& pieces, const Neighbourhood& h,
                          const occ::Solid& u, const PlaneCutOptions& o) {
  std::vector<const occ::Solid*> glued{&u};
  for (std::size_t i = 0; i < h.checked; ++i) glued.push_back(&pieces[h.glued[i]]);
  if (!meshable_glued(glued, 1, o)) return Kept::not_the_union;
  for (std::size_t i = h.checked; i < h.glued.size(); ++i) glued.push_back(&pieces[h.glued[i]]);
  return meshable_glued(glued, 1 + h.checked, o) ? Kept::yes : Kept::not_a_neighbour;
}

// `touch` after pieces a < b were merged into one put last (as the merge loop does).
Touching merged_touching(const Touching& touch, std::size_t a, std::size_t b) {
  std::vector<std::size_t> kept;
  for (std::size_t k = 0; k < touch.size(); ++k)
    if (k != a && k != b) kept.push_back(k);
  Touching t(kept.size() + 1, std::vector<char>(kept.size() + 1, 0));
  for (std::size_t i = 0; i < kept.size(); ++i) {
    for (std::size_t j = 0; j < kept.size(); ++j) t[i][j] = touch[kept[i]][kept[j]];
    t[i][kept.size()] = t[kept.size()][i] = touch[a][kept[i]] || touch[b][kept[i]];
  }
  return t;
}

}  // namespace

// Merges neighbouring pieces while the union is a block, a sweep or prismatic (and, when
// `careful`, every piece around it stays so once glued: merge_keeps_meshable), each merge
// taking one piece away, until none is left or the time is up. `volume`, `touch`: per piece.
void merge_neighbours(std::vector<occ::Solid>& pieces, std::vector<double>& volume, Touching touch,
                      const PlaneCutOptions& options, bool careful, double cut_into,
                      const std::function<double()>& seconds, const core::Progress& progress,
                      MergeHistory* history) {
  // Pairs whose union is no block, sweep or prismatic part (or no union) stay so: they are
  // not fused again after each merge (ids: a merged piece gets a new one, its index in the
  // history).
  std::vector<int> id(pieces.size());
  for (std::size_t k = 0; k < id.size(); ++k) id[k] = int(k);
  int next_id = int(id.size());
  if (history) {
    *history = MergeHistory();
    for (const occ::Solid& p : pieces) history->solids.push_back(p.clone());
    history->from.assign(pieces.size(), {-1, -1});
  }
  std::set<std::pair<int, int>> no_union;
  // Pairs whose union left a neighbour without a scheme, with the ids glued around it then.
  std::map<std::pair<int, int>, std::vector<int>> not_kept, union_not_kept;
  occ::Fuser fuser;
  for (bool merged = true; merged && pieces.size() > 1 && seconds() < options.time_limit;) {
    // The second half: the merges, each taking one piece away.
    progress.report("plane_cuts", 0.5 + 0.5 * (1 - double(pieces.size()) / cut_into));
    merged = false;
    for (std::size_t a = 0; a < pieces.size() && !merged; ++a)
      for (std::size_t b = a + 1; b < pieces.size() && !merged; ++b) {
        if (seconds() >= options.time_limit || progress.cancelled()) break;
        if (!touch[a][b] || no_union.count({id[a], id[b]})) continue;
        // OCCT's face unification in the fuse can run without end (HexMe i15's cuts, with
        // the caps raised): it gets the time left.
        std::unique_ptr<occ::Solid> u =
            fuser.fuse(pieces[a], pieces[b], std::max(0.5, options.time_limit - seconds()),
                       /*split_faces_if_unification_fails=*/true);
        // A union OCCT turned inside out, or that lost volume, is no union.
        const double both = volume[a] + volume[b], uv = u ? u->volume() : 0;
        if (!u || !(uv > 0) || std::abs(uv - both) > kVolumeTolerance * both ||
            !meshable(*u, options)) {
          if (seconds() < options.time_limit) no_union.insert({id[a], id[b]});  // not cut short
          continue;
        }
        // Whether the neighbours stay meshable can change with later merges: not remembered.
        // Whether the pieces stay meshable changes only with the pieces glued around the
        // union: a check that failed is not made again while they are the same ones (the
        // keyed shaft of bench/run_parts.py: 8 of 45 checks; with the union checked first,
        // below, its pass would end after 6.7 s, not 9; it has 5.5 s and stops at 13 or 14
        // pieces, not 18 to 22).
        if (careful) {
          const Neighbourhood h = neighbourhood(pieces.size(), touch, a, b);
          // The ids around: those touching the union (which decide whether it is meshable),
          // then all glued (which decide whether they are).
          std::vector<int> touching, around;
          for (std::size_t i = 0; i < h.glued.size(); ++i)
            (i < h.checked ? touching : around).push_back(id[h.glued[i]]);
          std::sort(touching.begin(), touching.end());
          around.insert(around.end(), touching.begin(), touching.end());
          std::sort(around.begin(), around.end());
          const auto u_seen = union_not_kept.find({id[a], id[b]});
          const auto n_seen = not_kept.find({id[a], id[b]});
          if ((u_seen != union_not_kept.end() && u_seen->second == touching) ||
              (n_seen != not_kept.end() && n_seen->second == around))
            continue;
          const Kept kept = merge_keeps_meshable(pieces, h, *u, options);
          if (kept != Kept::yes) {
            if (seconds() < options.time_limit) {
              if (kept == Kept::not_the_union)
                union_not_kept[{id[a], id[b]}] = std::move(touching);
              else
                not_kept[{id[a], id[b]}] = std::move(around);
            }
            continue;
          }
        }
        std::vector<occ::Solid> next;
        std::vector<double> next_volume;
        std::vector<int> next_ids;
        for (std::size_t k = 0; k < pieces.size(); ++k)
          if (k != a && k != b)
            next.push_back(std::move(pieces[k])), next_volume.push_back(volume[k]),
                next_ids.push_back(id[k]);
        if (history) {
          history->solids.push_back(u->clone());
          history->from.push_back({id[a], id[b]});
        }
        next.push_back(std::move(*u));
        next_volume.push_back(uv);
        next_ids.push_back(next_id++);
        pieces = std::move(next);
        volume = std::move(next_volume);
        id = std::move(next_ids);
        touch = merged_touching(touch, a, b);
        merged = true;
      }
  }
  if (history) history->piece = id;
}

}  // namespace vorohex::decompose::detail

namespace vorohex::decompose {

int undo_unions(const MergeHistory& h, const occ::Solid& glued, const std::vector<int>& failed,
                std::vector<int>& pieces) {
  std::vector<const occ::Solid*> solids;
  for (int p : pieces) solids.push_back(&h.solids[p]);
  const std::vector<core::BoundingBox> boxes = detail::boxes_of(solids);
  std::vector<int> next = pieces;
  int undone = 0;
  for (int k : failed) {
    const int i = detail::piece_of(glued.part(k), boxes);
    if (i < 0) continue;
    const auto at = std::find(next.begin(), next.end(), pieces[i]);
    const std::array<int, 2> from = h.from[pieces[i]];
    if (at == next.end() || from[0] < 0) continue;
    next.erase(at);
    next.push_back(from[0]);
    next.push_back(from[1]);
    ++undone;
  }
  pieces = std::move(next);
  return undone;
}

}  // namespace vorohex::decompose
