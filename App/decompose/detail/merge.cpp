#include "decompose/detail/merge.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "core/isolated_call.h"
#include "decompose/detail/topology.h"
#include "mesh/map_block.h"
#include "mesh/mesh_sub_volumes.h"
#include "mesh/midpoint.h"
#include "mesh/multisweep.h"
#include "mesh/revolve.h"
#include "mesh/sweep.h"
#include "occ/shape_io.h"
#include "occ/split_solid.h"

namespace vorohex::decompose::detail {

using voronoi::VoronoiGraph;
using Clock = std::chrono::steady_clock;

namespace {

// Whether a union of sub-volumes is one the merge pass keeps: a sweep, else (when the
// options allow) a multisweep, or a revolve when it is the whole solid.
bool union_has_scheme(const occ::Solid& u, bool whole, const DecomposeOptions& options) {
  return mesh::sweep_applicable(u).ok ||
         (options.multisweep && mesh::multisweep_applicable(u).ok) ||
         (whole && options.revolve && mesh::revolve_applicable(u).ok);
}

// Decomposition faces that are not a quadrilateral between two sub-volumes.
int invalid_faces(const DecompositionResult& r) {
  int n = 0;
  for (const DecompositionFace& df : r.faces)
    n += df.num_edges != 4 || df.sub_volumes[0] < 0 || df.sub_volumes[1] < 0;
  return n;
}

// The schemes of the sub-volumes `which` once glued to each other, as the meshing of
// several sub-volumes judges them (mesh/mesh_sub_volumes.h): a face a neighbour's
// interface splits is no longer one face, and a sweep across it may not be one any more.
// No value when the pieces do not glue. OCCT's general fuse can crash on pieces it cannot
// glue (a block with two crossing holes: SIGSEGV in BOPTools_AlgoTools::
// CorrectCurveOnSurface, which ended the whole decomposition), so the pieces are glued and
// judged in a child process: a crash there is a union that does not glue.
std::optional<mesh::SubVolumePlan> glued_plan(const DecompositionResult& r,
                                              const std::vector<int>& which, bool multisweep) {
  if (which.size() == 1) return mesh::plan_sub_volumes(*r.sub_volumes[which[0]].solid, multisweep);
  std::vector<const occ::Solid*> solids;
  for (int i : which) solids.push_back(r.sub_volumes[i].solid.get());
  // The plan crosses back as lines: "1" or "0", then "<scheme>\t<reason>" per sub-volume.
  const core::IsolatedResult got = core::isolated_call([&]() -> std::string {
    const occ::ReadResult glued = occ::glue_solids(solids, "The sub-volumes");
    if (!glued.ok() || glued.solid->num_solids() != int(solids.size()))
      throw std::runtime_error("the pieces do not glue");
    const mesh::SubVolumePlan plan = mesh::plan_sub_volumes(*glued.solid, multisweep);
    std::string out = plan.ok ? "1" : "0";
    for (std::size_t k = 0; k < plan.schemes.size(); ++k) {
      std::string reason = plan.reasons[k];
      std::replace(reason.begin(), reason.end(), '\n', ' ');
      out += "\n" + plan.schemes[k] + "\t" + reason;
    }
    return out;
  });
  if (!got.ok()) return std::nullopt;
  mesh::SubVolumePlan plan;
  std::istringstream lines(got.data);
  std::string line;
  std::getline(lines, line);
  plan.ok = line == "1";
  while (std::getline(lines, line)) {
    const std::size_t tab = line.find('\t');
    plan.schemes.push_back(line.substr(0, tab));
    plan.reasons.push_back(tab == std::string::npos ? "" : line.substr(tab + 1));
  }
  if (plan.schemes.size() != solids.size()) return std::nullopt;
  return plan;
}

// Whether the union at index u of `trial` keeps a scheme glued to its neighbours, and so
// does every neighbour that has one alone. Only they are glued (one OCCT general fuse of a
// few pieces per try, not of all): the judgement of the whole is judge_glued's, at the end.
bool union_meshable_glued(const DecompositionResult& trial, int u,
                          const std::vector<int>& neighbours, bool multisweep) {
  std::vector<int> which{u};
  which.insert(which.end(), neighbours.begin(), neighbours.end());
  const std::optional<mesh::SubVolumePlan> plan = glued_plan(trial, which, multisweep);
  if (!plan || plan->schemes[0].empty()) return false;
  for (std::size_t k = 1; k < which.size(); ++k)
    if (trial.sub_volumes[which[k]].scheme != Scheme::none && plan->schemes[k].empty())
      return false;
  return true;
}

}  // namespace

// Step 6: type and scheme of one sub-volume, judged by the meshers in the pipeline's order:
// a mapped block, a sweep (first for a Vs), a multisweep, a revolve (the solid's only
// sub-volume), midpoint subdivision.
void type_sub_volume(const VoronoiGraph& g, const DecompositionResult& r, int index,
                     const DecomposeOptions& options, SubVolume& sv) {
  std::set<int> originals;
  for (const VirtualFace& vf : r.topology.faces)
    if (vf.sub_volume == index && vf.original.valid()) originals.insert(vf.original.value());
  sv.type = SubVolumeType::ve;
  sv.fs_face = -1;
  for (int f : g.fs_faces()) {
    const auto& gov = g.elements[f].governors;
    if (gov.size() == 2 && originals.count(gov[0].id) && originals.count(gov[1].id)) {
      sv.type = SubVolumeType::vs;
      sv.fs_face = f;
      break;
    }
  }
  const mesh::SweepApplicability sweep = mesh::sweep_applicable(*sv.solid);
  const mesh::Applicability map = mesh::map_block_applicable(*sv.solid);
  auto use_sweep = [&](const std::string& why) {
    sv.scheme = Scheme::sweep;
    sv.source = sweep.source;
    sv.target = sweep.target;
    sv.reason = why;
  };
  if (sv.type == SubVolumeType::vs && sweep.ok) {
    use_sweep("Vs: sweep between the faces across its f_s face");
    return;
  }
  if (map.ok) {
    sv.scheme = Scheme::map;
    sv.reason = sv.type == SubVolumeType::vs
                    ? "Vs not sweepable (" + sweep.reason + "), a topological hexahedron"
                    : "Ve: a topological hexahedron";
    return;
  }
  if (sweep.ok) return use_sweep("Ve: sweep along its Voronoi edges");
  std::string why = "no scheme: sweep: " + sweep.reason + "; map: " + map.reason;
  if (options.multisweep) {
    const mesh::MultisweepApplicability multi = mesh::multisweep_applicable(*sv.solid);
    if (multi.ok) {
      sv.scheme = Scheme::multisweep;
      sv.reason = "prismatic: a multisweep along its axis (" + std::to_string(multi.levels) +
                  " levels, " + std::to_string(multi.regions) + " regions)";
      return;
    }
    why += "; multisweep: " + multi.reason;
  }
  if (options.revolve && r.sub_volumes.size() == 1) {
    const mesh::RevolveApplicability rev = mesh::revolve_applicable(*sv.solid);
    if (rev.ok) {
      sv.scheme = Scheme::revolve;
      sv.reason = "a solid of revolution (revolved about its axis; meshed on its own only)";
      return;
    }
    why += "; revolve: " + rev.reason;
  }
  if (const mesh::Applicability mid = mesh::midpoint_applicable(*sv.solid); mid.ok) {
    sv.scheme = Scheme::midpoint;
    sv.reason = "Ve: a convex cell (midpoint subdivision)";
  } else {
    sv.scheme = Scheme::none;
    sv.reason = why + "; midpoint: " + mid.reason;
  }
}

// A block, sweep or multisweep alone that is none once glued to its neighbours gets no
// scheme: the report says what the meshing of several sub-volumes will find (and the
// pipeline then tries other cuts instead of failing there).
void judge_glued(DecompositionResult& r, bool multisweep) {
  if (r.sub_volumes.size() < 2) return;
  std::vector<int> all(r.sub_volumes.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
  const std::optional<mesh::SubVolumePlan> plan = glued_plan(r, all, multisweep);
  if (!plan) return;
  for (std::size_t i = 0; i < r.sub_volumes.size(); ++i) {
    SubVolume& sv = r.sub_volumes[i];
    const bool joined =
        sv.scheme == Scheme::map || sv.scheme == Scheme::sweep || sv.scheme == Scheme::multisweep;
    if (!joined || !plan->schemes[i].empty()) continue;
    sv.reason = std::string(sv.scheme == Scheme::map     ? "a topological hexahedron"
                            : sv.scheme == Scheme::sweep ? "a sweep"
                                                         : "prismatic") +
                " alone, but no scheme once glued to its neighbours: " + plan->reasons[i];
    sv.scheme = Scheme::none;
  }
}

// Merge pass (§7): unite sub-volumes whose union is a sweep (or a multisweep, or the whole
// solid revolved: union_has_scheme). Candidates, largest first:
// all sub-volumes, each one with all its neighbours across decomposition faces, each
// neighbouring pair. A union is kept only if no decomposition face becomes invalid: a
// union whose face is partly a model face and partly the interface to a neighbour would
// leave a T-shaped, non-conforming interface (the thick L's corner with one leg), and only
// if, glued to its neighbours, it still has a scheme and so does every neighbour that has
// one alone (the L with a hole in each leg: its corner and one leg make a sweep alone, but
// the other leg's interface splits its end face). Repeats
// until nothing qualifies. A rejected group is not fused again (its solids are unchanged),
// and the pass stops at the time limit (or when `progress` is cancelled): each try is an
// OCCT fuse.
void merge_pass(const occ::Solid& solid, const VoronoiGraph& g, double tol, double time_limit,
                const DecomposeOptions& options, const core::Progress& progress,
                DecompositionResult& r) {
  std::set<std::vector<const occ::Solid*>> rejected;
  const auto start = Clock::now();
  occ::Fuser fuser;  // the unions' unifications in one child process
  for (bool merged = true; merged;) {
    merged = false;
    const int n = int(r.sub_volumes.size());
    if (n < 2) return;
    std::vector<std::set<int>> around(n);
    for (const DecompositionFace& df : r.faces)
      if (df.sub_volumes[0] >= 0 && df.sub_volumes[1] >= 0) {
        around[df.sub_volumes[0]].insert(df.sub_volumes[1]);
        around[df.sub_volumes[1]].insert(df.sub_volumes[0]);
      }
    std::vector<std::vector<int>> groups;
    std::vector<int> all(n);
    for (int i = 0; i < n; ++i) all[i] = i;
    groups.push_back(all);
    for (int i = 0; i < n; ++i) {
      std::vector<int> star{i};
      star.insert(star.end(), around[i].begin(), around[i].end());
      std::sort(star.begin(), star.end());
      if (star.size() > 1) groups.push_back(star);
      for (int j : around[i])
        if (i < j) groups.push_back({i, j});
    }
    std::stable_sort(groups.begin(), groups.end(),
                     [](const auto& a, const auto& b) { return a.size() > b.size(); });
    groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
    const int invalid_now = invalid_faces(r);
    for (const std::vector<int>& group : groups) {
      std::vector<const occ::Solid*> key;
      for (int i : group) key.push_back(r.sub_volumes[i].solid.get());
      std::sort(key.begin(), key.end());
      if (rejected.count(key)) continue;
      if (progress.cancelled() ||
          (time_limit > 0 &&
           std::chrono::duration<double>(Clock::now() - start).count() > time_limit)) {
        r.diagnostics.push_back(core::make_info(
            "merge_stopped", "The merge pass stopped at the time limit (" +
                                 std::to_string(r.sub_volumes.size()) + " sub-volumes left)"));
        return;
      }
      // All sub-volumes together are the solid itself (the self-check found them a
      // partition): take it exactly. Fusing the pieces instead keeps the vertices the split
      // put on model edges and the slivers of slightly tilted cuts, and the union of a
      // prism's pieces was then no sweep.
      std::unique_ptr<occ::Solid> u;
      if (int(group.size()) == n) {
        u = std::make_unique<occ::Solid>(solid.clone());
      } else {
        // OCCT's face unification in a fuse can run without end: with a limit, it gets
        // the time left (occ::Fuser).
        auto left = [&] {
          const double spent = std::chrono::duration<double>(Clock::now() - start).count();
          return time_limit > 0 ? std::max(0.5, time_limit - spent) : 0.0;
        };
        u = fuser.fuse(*r.sub_volumes[group[0]].solid, *r.sub_volumes[group[1]].solid, left());
        for (std::size_t k = 2; u && k < group.size(); ++k)
          u = fuser.fuse(*u, *r.sub_volumes[group[k]].solid, left());
      }
      if (!u || !union_has_scheme(*u, int(group.size()) == n, options)) {
        rejected.insert(key);
        continue;
      }
      DecompositionResult trial = r;
      SubVolume sv;
      sv.volume = u->volume();
      sv.merged_from = 0;
      for (int i : group) sv.merged_from += r.sub_volumes[i].merged_from;
      sv.solid = std::shared_ptr<const occ::Solid>(std::move(u));
      trial.sub_volumes[group[0]] = std::move(sv);
      for (auto it = group.rbegin(); it + 1 != group.rend(); ++it)
        trial.sub_volumes.erase(trial.sub_volumes.begin() + *it);
      detail::build_topology(solid, tol, trial);
      if (invalid_faces(trial) > invalid_now) {
        rejected.insert(key);
        continue;
      }
      // The union's neighbours, by their index in the trial (the group's other members,
      // all above group[0], are gone from it).
      std::vector<int> neighbours;
      for (int i : group)
        for (int j : around[i])
          if (std::find(group.begin(), group.end(), j) == group.end())
            neighbours.push_back(j - int(std::count_if(group.begin() + 1, group.end(),
                                                       [&](int k) { return k < j; })));
      std::sort(neighbours.begin(), neighbours.end());
      neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
      if (!union_meshable_glued(trial, group[0], neighbours, options.multisweep)) {
        rejected.insert(key);
        continue;
      }
      r = std::move(trial);
      for (std::size_t i = 0; i < r.sub_volumes.size(); ++i)
        type_sub_volume(g, r, int(i), options, r.sub_volumes[i]);
      merged = true;
      break;
    }
  }
}

// Where the split's pieces fail the self-check (a sliver lost, a piece not closed) but
// the solid as a whole has a scheme, the merge pass would have united all pieces into the
// solid itself had they been sound: the solid becomes the one sub-volume, and the
// pieces' errors are reported as a warning (split_check_failed; the status is partial).
// False (nothing changed) when the solid has no scheme as a whole.
bool take_whole_solid(const occ::Solid& solid, const VoronoiGraph& g, double tol,
                      const DecomposeOptions& options, DecompositionResult& r) {
  if (!union_has_scheme(solid, true, options)) return false;
  std::string errors;
  for (const core::Diagnostic& d : r.diagnostics)
    if (d.severity == core::Severity::error) {
      std::string m = d.message;
      if (!m.empty() && m.back() == '.') m.pop_back();
      errors += (errors.empty() ? "" : "; ") + d.code + ": " + m;
    }
  r.diagnostics.erase(std::remove_if(r.diagnostics.begin(), r.diagnostics.end(),
                                     [](const core::Diagnostic& d) {
                                       return d.severity == core::Severity::error ||
                                              d.code == "invalid_decomposition_face";
                                     }),
                      r.diagnostics.end());
  const int pieces = int(r.sub_volumes.size());
  SubVolume whole;
  whole.solid = std::make_shared<const occ::Solid>(solid.clone());
  whole.volume = whole.solid->volume();
  whole.merged_from = pieces;
  r.sub_volumes.assign(1, std::move(whole));
  detail::build_topology(solid, tol, r);
  type_sub_volume(g, r, 0, options, r.sub_volumes[0]);
  r.diagnostics.push_back(core::make_warning(
      "split_check_failed",
      "The split into " + std::to_string(pieces) + " pieces failed its self-check (" + errors +
          "); the solid as a whole is a " + scheme_name(r.sub_volumes[0].scheme) +
          ", so it is the one sub-volume (all pieces merged, taken as the solid itself)"));
  r.status = DecompositionStatus::ok;
  return true;
}
}  // namespace vorohex::decompose::detail

namespace vorohex::decompose {

Scheme whole_solid_scheme(const occ::Solid& solid, const DecomposeOptions& options,
                          std::string* reason, std::pair<core::FaceId, core::FaceId>* ends) {
  const mesh::Applicability map = mesh::map_block_applicable(solid);
  if (map.ok) return *reason = "a topological hexahedron", Scheme::map;
  const mesh::SweepApplicability sweep = mesh::sweep_applicable(solid);
  if (sweep.ok) {
    if (ends) *ends = {sweep.source, sweep.target};
    return *reason = "a sweep from " + core::entity_name(sweep.source) + " to " +
                     core::entity_name(sweep.target),
           Scheme::sweep;
  }
  std::string why = "map: " + map.reason + "; sweep: " + sweep.reason;
  if (options.multisweep) {
    const mesh::MultisweepApplicability multi = mesh::multisweep_applicable(solid);
    if (multi.ok) return *reason = "prismatic: a multisweep along its axis", Scheme::multisweep;
    why += "; multisweep: " + multi.reason;
  }
  if (options.revolve) {
    const mesh::RevolveApplicability rev = mesh::revolve_applicable(solid);
    if (rev.ok) return *reason = "a solid of revolution", Scheme::revolve;
    why += "; revolve: " + rev.reason;
  }
  const mesh::Applicability mid = mesh::midpoint_applicable(solid);
  if (mid.ok) {
    // A poor one is what the mesher holds while it tries the decomposition (generate_mesh).
    const double q = mesh::midpoint_coarse_quality(solid);
    if (q >= mesh::kPoorMidpointQuality)
      return *reason = "a convex cell (midpoint subdivision)", Scheme::midpoint;
    std::ostringstream m;
    m.precision(3);
    m << "; midpoint: a convex cell whose subdivision is poor (min scaled Jacobian " << q
      << "): the mesher tries its decomposition first";
    *reason = why + m.str();
    return Scheme::none;
  }
  *reason = why + "; midpoint: " + mid.reason;
  return Scheme::none;
}

}  // namespace vorohex::decompose
