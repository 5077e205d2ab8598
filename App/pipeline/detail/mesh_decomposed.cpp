#include "pipeline/detail/mesh_decomposed.h"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/progress.h"
#include "core/size_field.h"
#include "mesh/mesh_sub_volumes.h"
#include "occ/shape_io.h"
#include "pipeline/detail/decompose_isolated.h"
#include "quality/check_mesh.h"
#include "smooth/restore_topology.h"

namespace vorohex::pipeline::detail {

std::string joined_schemes(const std::vector<std::string>& schemes) {
  // In one order whatever the sub-volumes' (which OCCT's split may give in another order from
  // run to run): the structured schemes, simplest first, then the fallbacks.
  static const char* const kOrder[] = {"map",      "sweep", "multisweep", "revolve",
                                       "midpoint", "grid",  "tet-split"};
  std::vector<std::string> seen;
  for (const std::string& s : schemes)
    if (std::find(seen.begin(), seen.end(), s) == seen.end()) seen.push_back(s);
  auto rank = [&](const std::string& s) {
    const auto it = std::find(std::begin(kOrder), std::end(kOrder), s);
    return it - std::begin(kOrder);
  };
  std::stable_sort(seen.begin(), seen.end(),
                   [&](const std::string& a, const std::string& b) { return rank(a) < rank(b); });
  std::string out;
  for (const std::string& s : seen) out += (out.empty() ? "" : "+") + s;
  return out;
}

namespace {

using core::seconds_since;

// Nodes of the mesh's boundary that restore_topology made interior: they lie on a cut, so
// the sub-volumes' meshes leave a gap inside the solid there (the join check, made against
// the pieces, sees the cut as boundary and passes it).
std::size_t boundary_nodes_inside(const core::HexMesh& mesh) {
  const std::vector<char> boundary = core::boundary_nodes(mesh);
  std::size_t n = 0;
  for (std::size_t i = 0; i < boundary.size(); ++i)
    n += boundary[i] && mesh.node_classes()[i].is_interior();
  return n;
}

// Below this minimum scaled Jacobian before smoothing, the pieces split afresh are meshed too.
constexpr double kPoorDecomposition = 0.2;

// Halvings of the size where the sub-volumes did not mesh (mesh_pieces).
constexpr int kFinerAttempts = 2;

// Rounds of undoing the plane cuts' unions in which a sub-volume did not mesh (mesh_pieces).
constexpr int kUndoRounds = 3;

// The parts of the glued `pieces` that have one of the faces `names` ("Face116").
std::vector<int> parts_with_faces(const occ::Solid& pieces, const std::vector<std::string>& names) {
  std::vector<int> faces, out;
  for (const std::string& name : names) {
    char kind = 0;
    int id = 0;
    if (core::parse_entity_name(name, kind, id) && kind == 'f') faces.push_back(id);
  }
  for (int k = 0; k < pieces.num_solids(); ++k) {
    const std::vector<int> ids = pieces.part_ids(pieces.part(k), 2);
    if (std::any_of(ids.begin(), ids.end(), [&](int f) {
          return f > 0 && std::find(faces.begin(), faces.end(), f) != faces.end();
        }))
      out.push_back(k);
  }
  return out;
}

// Whether sub-volumes that did not mesh may mesh at a smaller size: where what failed is the
// quad meshing of a face (folded where the face is narrower than the size), and nothing else.
// Not a sweep's folded layers or meshes that do not match where they meet: a knife edge does
// not go away at a smaller size (HexMe i14, its lug cut off its tube along the tube's
// cylinder: its plane cuts with tangent planes are the way, and two attempts at smaller sizes
// cost it 9 s for nothing).
bool retry_finer(const mesh::SubVolumeMeshResult& m) {
  bool quads = false;
  for (const core::Diagnostic& d : m.diagnostics) {
    if (d.severity != core::Severity::error) continue;
    if (d.code != "quad_face_failed") return false;
    quads = true;
  }
  return quads;
}

// The decomposition's sub-volumes meshed into one conforming mesh, put back onto the
// solid's own topology: true when result.mesh holds it; else false with `why_not`, or a
// `cancelled` error.
bool mesh_pieces(const occ::Solid& solid, const IsolatedDecomposition& d,
                 const MeshOptions& options, const core::SizeField& sizes,
                 const core::Progress& progress, std::chrono::steady_clock::time_point t0,
                 MeshResult& result, std::string& why_not) {
  mesh::SubVolumeMeshOptions o;
  o.size = sizes.global();
  o.size_field = &sizes;
  o.max_hexes = options.max_hexes;
  o.multisweep = std::find(options.schemes.begin(), options.schemes.end(), "multisweep") !=
                 options.schemes.end();
  int n = d.pieces->num_solids();
  // One set of glued pieces meshed: the mesh, its minimum before smoothing, or why not.
  struct Attempt {
    mesh::SubVolumeMeshResult m;
    double min = -1;
    double size = 0;
    std::string why_not;
  };
  auto attempt = [&](const occ::Solid& pieces) {
    Attempt a;
    a.m = mesh::mesh_sub_volumes(pieces, o, progress);
    a.size = o.size;
    if (!a.m.ok) {
      std::string errors;
      for (const core::Diagnostic& diag : a.m.diagnostics)
        if (diag.severity == core::Severity::error) {
          std::string msg = diag.message;
          if (!msg.empty() && msg.back() == '.') msg.pop_back();
          errors += (errors.empty() ? "" : "; ") + msg;
        }
      a.why_not =
          "its " + std::to_string(n) + " sub-volumes could not be meshed together (" + errors + ")";
      return a;
    }
    // Faces two sub-volumes share are meshed by both (mesh/mesh_sub_volumes.h): identical
    // for grids and lattices, not always for unstructured sweep ends. A mesh that does not
    // conform across them is no result; the fallback takes over.
    quality::CheckOptions conformity;
    conformity.volume_rel_tol = 1;  // the final check measures the volume; this one, the joins
    const quality::CheckReport joined = quality::check_mesh(a.m.mesh, &pieces, conformity);
    if (!joined.valid) {
      a.why_not = "the meshes of its " + std::to_string(n) +
                  " sub-volumes do not match where they meet (" +
                  core::error_codes(joined.diagnostics) + ")";
      a.m.ok = false;
      for (const core::Diagnostic& diag : joined.diagnostics)  // whose meshes do not match
        if (diag.code == "non_conforming_interface")
          a.m.failed = parts_with_faces(pieces, diag.entities);
      return a;
    }
    a.min = joined.scaled_jacobian.min;
    return a;
  };
  Attempt a = attempt(*d.pieces);
  // The same pieces split afresh at their common faces (plane cuts: without the traces of the
  // cuts merged back), meshed too where these did not mesh or meshed poorly; the better kept.
  const occ::Solid* pieces = d.pieces.get();
  if (d.afresh && !progress.cancelled() && (!a.m.ok || a.min < kPoorDecomposition)) {
    Attempt b = attempt(*d.afresh);
    if (b.m.ok && (!a.m.ok || b.min > a.min + 0.01)) {
      a = std::move(b);
      pieces = d.afresh.get();
    }
  }
  // Pieces that all have a scheme but did not mesh at the size asked for (a source face's
  // quads fold in a ligament narrower than the size: a gear blank's web between its
  // lightening holes and its hub) are meshed again at half the size, twice at most: a
  // structured mesh finer than asked beats the grid mesher's, which refines as much there.
  core::SizeField finer = sizes;
  std::string coarse_why;
  for (int k = 0; k < kFinerAttempts && !a.m.ok && retry_finer(a.m) && !progress.cancelled(); ++k) {
    if (coarse_why.empty()) coarse_why = a.why_not;
    finer = finer.scaled(0.5);
    o.size = finer.global();
    o.size_field = &finer;
    Attempt b = attempt(*pieces);
    if (!b.m.ok) continue;
    a = std::move(b);
  }
  std::string reduced;
  if (!coarse_why.empty() && a.m.ok) {
    std::ostringstream s;
    s << "The decomposition did not mesh at size " << sizes.global() << " (" << coarse_why
      << "); made again at size " << a.size
      << ", it meshes: that mesh is used, finer than the size asked for.";
    reduced = s.str();
  }
  // Unions made by the plane cuts' merge pass in which a sub-volume did not mesh (a sweep's
  // layers fold in it; the pass judges schemes, not meshes) are undone, and the two pieces
  // each was made of meshed in its place, kUndoRounds times at most. Where the careful pass
  // stops depends on the time it has: a V-belt pulley's 41 to 43 pieces meshed, its 30 to
  // 35 (sooner done) did not, two sweeps' layers folding in the unions across its groove.
  std::unique_ptr<occ::Solid> undone;
  int unions_undone = 0;
  std::string undone_why;
  if (!a.m.ok && !d.merges.empty() && !a.m.failed.empty() && pieces == d.pieces.get() &&
      !progress.cancelled()) {
    o.size = sizes.global();
    o.size_field = &sizes;
    std::vector<int> nodes = d.merges.piece;
    const occ::Solid* glued = d.pieces.get();
    Attempt last = std::move(a);
    for (int round = 0;
         round < kUndoRounds && !last.m.ok && !last.m.failed.empty() && !progress.cancelled();
         ++round) {
      std::vector<int> next = nodes;
      const int undoing = decompose::undo_unions(d.merges, *glued, last.m.failed, next);
      if (undoing == 0) break;
      std::vector<const occ::Solid*> solids;
      for (int node : next) solids.push_back(&d.merges.solids[node]);
      occ::GlueOptions go;
      go.only_touching = true;  // pieces of one exact split
      occ::ReadResult g = occ::glue_solids(solids, "The plane cut", go);
      if (!g.ok()) break;
      if (undone_why.empty()) undone_why = last.why_not;
      unions_undone += undoing;
      nodes = std::move(next);
      undone = std::move(g.solid);
      glued = undone.get();
      n = glued->num_solids();
      last = attempt(*glued);
    }
    if (last.m.ok) {
      pieces = glued;
    } else {
      unions_undone = 0;
      n = d.pieces->num_solids();
      last.why_not = undone_why.empty() ? last.why_not : undone_why;
    }
    a = std::move(last);
  }
  const bool afresh = pieces == d.afresh.get();
  if (!a.m.ok) {
    if (progress.cancelled()) {
      result.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
      return false;
    }
    why_not = a.why_not;
    return false;
  }
  mesh::SubVolumeMeshResult& m = a.m;
  const double tolerance = std::max(1e-9 * solid.diagonal(), solid.tolerance());
  const smooth::RestoreStats restored = smooth::restore_topology(m.mesh, *pieces, solid, tolerance);
  if (const std::size_t gap = boundary_nodes_inside(m.mesh); gap > 0) {
    why_not = "the meshes of its " + std::to_string(n) + " sub-volumes leave a gap inside it (" +
              std::to_string(gap) + " nodes of the mesh's boundary lie on the cuts)";
    return false;
  }
  result.mesh = std::move(m.mesh);
  std::map<std::string, int> count;
  for (const std::string& s : m.stats.schemes) ++count[s];
  result.stats.scheme = joined_schemes(m.stats.schemes);
  result.stats.sub_volume_schemes = m.stats.schemes;
  result.stats.sub_volume_types = m.stats.types;
  result.stats.sub_volumes = n;
  result.stats.intervals = {0, 0, 0};
  result.stats.seconds_meshing = seconds_since(t0);
  std::ostringstream s;
  s << (d.method == "voronoi"
            ? "Cut along its Voronoi graph into "
            : "Cut along " + d.cut_kind + (d.along.empty() ? std::string() : " (" + d.along + ")") +
                  ", extended through it" +
                  (d.left_out.empty() ? std::string()
                                      : " (but not along " + d.left_out +
                                            ", with which OCCT's cut "
                                            "failed)") +
                  ", into ")
    << n << " sub-volumes (" << d.before_merge << " before merging"
    << (afresh ? ", then the solid split afresh at the faces they share only" : "") << "; ";
  bool first = true;
  for (const auto& [name, k] : count)
    s << (first ? "" : ", ") << k << " "
      << (name == "map"          ? "mapped"
          : name == "multisweep" ? "multiswept"
          : name == "revolve"    ? "revolved"
                                 : "swept"),
        first = false;
  s << "), meshed with one interval assignment over " << m.stats.curves << " curves and "
    << m.stats.constraints << " constraints, joined (" << m.stats.nodes_merged << " nodes merged); "
    << restored.interior << " nodes on the cuts are inside the solid again. Decomposition "
    << std::fixed << std::setprecision(1) << d.seconds << " s.";
  result.diagnostics.push_back(core::make_info("decomposed", s.str()));
  if (unions_undone > 0)
    result.diagnostics.push_back(core::make_info(
        "merges_undone",
        std::to_string(unions_undone) + " unions made in merging the cut's pieces did not mesh (" +
            undone_why + "): undone, the pieces each was made of are meshed instead."));
  if (!reduced.empty()) {
    result.diagnostics.push_back(core::make_warning("size_reduced", reduced));
    result.stats.size_used = a.size;
  }
  return true;
}

}  // namespace

bool mesh_decomposed(const occ::Solid& solid, const MeshOptions& options,
                     const core::SizeField& sizes, const core::Progress& progress,
                     MeshResult& result, std::string& why_not) {
  const auto t0 = std::chrono::steady_clock::now();
  const IsolatedDecomposition d = decompose_isolated(solid, options, progress);
  if (d.cancelled) {
    result.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
    return false;
  }
  if (!d.pieces) {
    why_not = d.why_not;
    return false;
  }
  if (mesh_pieces(solid, d, options, sizes, progress, t0, result, why_not)) return true;
  if (d.method != "plane cuts" || progress.cancelled()) return false;
  auto spent = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  // Another decomposition (`method`, within `seconds`) meshed; else why not is appended
  // (`what` before it, `end` after it) or, when the user stopped it, a `cancelled` error.
  auto again = [&](DecompositionMethods method, double seconds, const std::string& what,
                   const char* end) {
    MeshOptions o = options;
    o.decomposition_time_limit = seconds;
    const IsolatedDecomposition e = decompose_isolated(solid, o, progress, method);
    if (e.cancelled) {
      result.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
      return false;
    }
    std::string why;
    if (e.pieces && mesh_pieces(solid, e, options, sizes, progress, t0, result, why)) return true;
    why_not += what + (e.pieces ? why : e.why_not) + end;
    return false;
  };
  // Pieces with knife edges (a cylinder cut along where a planar face touches it) that did
  // not mesh: the cuts with the planes tangent to those cylinders instead (HexMe i14: a lug
  // as wide as its tube, cut off it along the tube's cylinder, folded its sweep's layers).
  if (d.knife_edges && spent() < 0.5 * options.decomposition_time_limit) {
    if (again(DecompositionMethods::tangent_plane_cuts,
              std::max(5.0, 0.5 * options.decomposition_time_limit - spent()),
              "; with planes tangent to the cylinders that planar faces touch, ", ""))
      return true;
    if (progress.cancelled()) return false;
  }
  // The exact cuts' sub-volumes did not mesh together: the Voronoi decomposition, within
  // what is left of the decomposition's time (the attempt to mesh the cuts' sub-volumes
  // counts too: HexMe i22's 45 took 20 s).
  return again(DecompositionMethods::voronoi,
               std::max(5.0, std::min(options.decomposition_time_limit - spent(),
                                      voronoi_share(options.decomposition_time_limit))),
               "; the Voronoi decomposition did not help either (", ")");
}

}  // namespace vorohex::pipeline::detail
