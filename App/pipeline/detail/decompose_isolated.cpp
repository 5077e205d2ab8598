#include "pipeline/detail/decompose_isolated.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/isolated_call.h"
#include "core/progress.h"
#include "decompose/decompose.h"
#include "decompose/plane_cuts.h"
#include "occ/shape_io.h"
#include "occ/split_solid.h"
#include "voronoi/voronoi_graph.h"

namespace vorohex::pipeline::detail {

namespace {

// The stage the child reports as the Voronoi decomposition starts (and the parent watches for).
constexpr std::string_view kVoronoiStage = "voronoi";

// Seconds the Voronoi decomposition gets when it starts `elapsed` seconds into a
// decomposition of `time_limit`: what is left, at most voronoi_share of it unless it is the
// only method.
double voronoi_seconds(double time_limit, double elapsed, DecompositionMethods methods) {
  const double left = time_limit - elapsed;
  return methods == DecompositionMethods::voronoi ? left
                                                  : std::min(left, voronoi_share(time_limit));
}

// Between the sub-volumes' BREP compound and the compound of the same split afresh; before
// the merge pass's unions (decompose::MergeHistory: a line of the unions' two
// indices, "a b" each, a line of the pieces' indices, then the solids' compound).
const char* const kAfresh = "\n@afresh@\n";
const char* const kMerges = "\n@merges@\n";

std::string merges_text(const decompose::MergeHistory& h) {
  if (h.empty()) return std::string();
  std::vector<const occ::Solid*> solids;
  for (const occ::Solid& s : h.solids) solids.push_back(&s);
  const std::string brep = occ::compound_brep_string(solids);
  if (brep.empty()) return std::string();
  std::ostringstream s;
  for (const auto& [a, b] : h.from) s << a << " " << b << " ";
  s << "\n";
  for (int p : h.piece) s << p << " ";
  s << "\n" << brep;
  return kMerges + s.str();
}

// The history merges_text wrote (empty where it does not read back whole).
decompose::MergeHistory merges_from_text(const std::string& text) {
  decompose::MergeHistory h;
  const std::size_t eol = text.find('\n');
  const std::size_t eol2 = eol == std::string::npos ? eol : text.find('\n', eol + 1);
  if (eol2 == std::string::npos) return h;
  std::istringstream from(text.substr(0, eol)), piece(text.substr(eol + 1, eol2 - eol - 1));
  for (int a, b; from >> a >> b;) h.from.push_back({a, b});
  for (int p; piece >> p;) h.piece.push_back(p);
  h.solids = occ::solids_from_brep_string(text.substr(eol2 + 1));
  const int n = int(h.solids.size());
  bool whole = n == int(h.from.size());
  for (const auto& [a, b] : h.from) whole = whole && a < n && b < n;
  for (int p : h.piece) whole = whole && p >= 0 && p < n;
  if (!whole) h = decompose::MergeHistory();
  return h;
}

// "<before merge>\n<method>[\t<surfaces left out>\t<surfaces used>\t<knife edges: 0 or 1>]\n"
// then the sub-volumes as one BREP compound, and after kAfresh the same split afresh
// (decompose::PlaneCutResult::afresh) where there is one.
std::string to_text(int before_merge, const char* method,
                    const std::vector<const occ::Solid*>& solids,
                    const std::vector<const occ::Solid*>& afresh = {},
                    const decompose::MergeHistory& merges = {}) {
  const std::string brep = occ::compound_brep_string(solids);
  if (brep.empty()) throw std::runtime_error("its sub-volumes could not be written");
  std::string text = std::to_string(before_merge) + "\n" + method + "\n" + brep;
  if (!afresh.empty())
    if (const std::string again = occ::compound_brep_string(afresh); !again.empty())
      text += kAfresh + again;
  return text + merges_text(merges);
}

// Runs in the child: the Voronoi decomposition, or throws with the reason. `seconds`, what
// is left of the decomposition's time, bound the whole (graph, split, merging): the
// decomposition stops itself at them, with the step it was in, before the parent's kill
// at the decomposition's limit. Its steps are reported to `reports` (no deadline).
std::string voronoi_decomposition(const occ::Solid& solid, const MeshOptions& mesh_options,
                                  double seconds, const core::Progress& reports) {
  const core::Progress deadline = reports.with_time_limit(std::max(1.0, seconds));
  reports.report(kVoronoiStage, 0.0);
  const voronoi::VoronoiResult graph = voronoi::compute_voronoi_graph(solid, mesh_options.graph);
  if (!graph.ok()) throw std::runtime_error("its Voronoi graph could not be computed");
  reports.report(kVoronoiStage, 1.0);
  decompose::DecomposeOptions options;
  options.sharp_angle = mesh_options.sharp_angle;
  options.stop_at_open_gap = true;
  const auto allowed = [&](const char* scheme) {
    return std::find(mesh_options.schemes.begin(), mesh_options.schemes.end(), scheme) !=
           mesh_options.schemes.end();
  };
  options.multisweep = allowed("multisweep");
  options.revolve = allowed("revolve");
  const decompose::DecompositionResult d = decompose::decompose(solid, graph, options, deadline);
  if (!d.ok()) {
    // Why it failed: its first error (a warning before it, such as an open vertex gap, is
    // no reason: HexMe i03 named one while its split had run out of time), else a warning.
    for (const core::Severity severity : {core::Severity::error, core::Severity::warning})
      for (const core::Diagnostic& diag : d.diagnostics)
        if (diag.severity == severity) {
          std::string m = diag.message;
          if (!m.empty() && m.back() == '.') m.pop_back();
          throw std::runtime_error("its decomposition failed (" + m + ")");
        }
    throw std::runtime_error("its decomposition failed");
  }
  // A partial decomposition (an open gap, an unusable Voronoi edge, a decomposition face
  // that is not four-sided) is still tried when every sub-volume has a scheme: the meshes
  // must conform and the final check decides.
  if (d.sub_volumes.size() < 2)
    throw std::runtime_error("its decomposition gives one sub-volume, which no scheme meshes");
  std::vector<const occ::Solid*> solids;
  for (std::size_t k = 0; k < d.sub_volumes.size(); ++k) {
    const decompose::SubVolume& sv = d.sub_volumes[k];
    if (sv.scheme == decompose::Scheme::none)
      throw std::runtime_error("sub-volume " + std::to_string(k + 1) + " of its decomposition " +
                               "has no scheme (" + sv.reason + ")");
    if (sv.scheme == decompose::Scheme::midpoint || sv.scheme == decompose::Scheme::revolve)
      throw std::runtime_error(
          "sub-volume " + std::to_string(k + 1) + " of its decomposition " + "is " +
          (sv.scheme == decompose::Scheme::midpoint ? "a convex cell for midpoint subdivision"
                                                    : "a solid of revolution") +
          ", which is meshed only on its own (not joined to swept or "
          "mapped neighbours)");
    solids.push_back(sv.solid.get());
  }
  return to_text(d.stats.sub_volumes_before_merge, "voronoi", solids);
}

// Runs in the child: exact cuts at the concave edges (with at most half the time), else the
// Voronoi decomposition (with what is left, at most voronoi_share); or only the latter. The
// steps (plane_cuts, voronoi, decompose) are reported to `reports`, which has no deadline:
// each step keeps its own time limit, as before the reports crossed to the parent.
std::string decompose_to_text(const occ::Solid& solid, const MeshOptions& mesh_options,
                              DecompositionMethods methods, const core::Progress& reports) {
  const auto t0 = std::chrono::steady_clock::now();
  const double time_limit = mesh_options.decomposition_time_limit;
  std::string why;
  if (methods != DecompositionMethods::voronoi) {
    decompose::PlaneCutOptions options;
    options.multisweep = std::find(mesh_options.schemes.begin(), mesh_options.schemes.end(),
                                   "multisweep") != mesh_options.schemes.end();
    options.tangent_planes = methods == DecompositionMethods::tangent_plane_cuts;
    options.time_limit = std::max(1.0, options.tangent_planes ? time_limit : 0.5 * time_limit);
    const decompose::PlaneCutResult cut = decompose::cut_as_the_mesher(solid, options, reports);
    if (cut.ok) {
      std::vector<const occ::Solid*> solids, afresh;
      for (const occ::Solid& s : cut.pieces) solids.push_back(&s);
      for (const occ::Solid& s : cut.afresh) afresh.push_back(&s);
      const std::string method = "plane cuts\t" + decompose::left_out_text(cut) + "\t" +
                                 decompose::used_surfaces_text(cut) + "\t" +
                                 (cut.knife_edges ? "1" : "0") + "\t" +
                                 decompose::cut_kind_text(cut);
      return to_text(cut.pieces_before_merge, method.c_str(), solids, afresh, cut.merges);
    }
    why =
        "cutting along the faces at its concave edges did not give sub-volumes that all have "
        "a scheme (" +
        cut.why_not + ")";
    if (methods == DecompositionMethods::tangent_plane_cuts) throw std::runtime_error(why);
  }
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  try {
    return voronoi_decomposition(solid, mesh_options, voronoi_seconds(time_limit, elapsed, methods),
                                 reports);
  } catch (const std::exception& e) {
    if (why.empty()) throw;
    throw std::runtime_error(why + "; " + e.what());
  }
}

}  // namespace

IsolatedDecomposition decompose_isolated(const occ::Solid& solid, const MeshOptions& options,
                                         const core::Progress& progress,
                                         DecompositionMethods methods) {
  const double time_limit = options.decomposition_time_limit;
  IsolatedDecomposition out;
  const auto t0 = std::chrono::steady_clock::now();
  core::IsolatedCallOptions io;
  io.stage = "decompose";
  // The child's steps are reported here as they happen (the job's progress pipe); the
  // decomposition's own limits, not the job's deadline, stop its steps. But OCCT's split
  // does not heed them: once the child starts the Voronoi decomposition, the job is stopped
  // when that step's seconds and their grace (decompose::stop_grace) have passed, not at the
  // whole limit. (A block with its four top edges filleted: its graph's split returned after
  // 34 s, into a piece with no scheme, and the mesher's grid mesh, ready beside it after 2 s,
  // waited 47 s in all.)
  std::atomic<bool> stop{false};
  bool voronoi_stopped = false;
  double voronoi_budget = 0;
  std::optional<std::chrono::steady_clock::time_point> voronoi_until;
  const core::Progress watched =
      core::Progress(
          [&](std::string_view stage, double f) {
            progress.report(stage, f);
            if (progress.cancelled()) stop = true;
            const auto now = std::chrono::steady_clock::now();
            if (!voronoi_until && stage == kVoronoiStage) {
              voronoi_budget =
                  std::max(0.0, voronoi_seconds(time_limit, core::seconds_since(t0), methods));
              voronoi_until =
                  now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(voronoi_budget +
                                                          decompose::stop_grace(voronoi_budget)));
            }
            if (voronoi_until && now > *voronoi_until) stop = voronoi_stopped = true;
          },
          &stop)
          .with_time_limit(time_limit);
  core::IsolatedResult run =
      core::IsolatedJob([&](const core::Progress& in_child) {
        const core::Progress reports = core::Progress(
            [in_child](std::string_view stage, double f) { in_child.report(stage, f); });
        return decompose_to_text(solid, options, methods, reports);
      }).take(watched, io);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  switch (run.status) {
    case core::IsolatedResult::Status::ok:
      break;
    case core::IsolatedResult::Status::failed:
      out.why_not = run.message;
      return out;
    case core::IsolatedResult::Status::crashed:
      out.why_not = "its decomposition crashed (" + run.message + ")";
      return out;
    case core::IsolatedResult::Status::cancelled: {
      out.cancelled = progress.cancelled();
      std::ostringstream s;
      if (voronoi_stopped && !out.cancelled) {
        // (The plane cuts' own reason stays in the child; that it reached the Voronoi step
        // says they failed.)
        if (methods != DecompositionMethods::voronoi)
          s << "cutting along the faces at its concave edges did not give sub-volumes that all "
            << "have a scheme; ";
        s << "its Voronoi decomposition did not stop within its " << std::fixed
          << std::setprecision(1) << voronoi_budget << " s (OCCT's split did not return) and was "
          << "stopped " << decompose::stop_grace(voronoi_budget) << " s after it";
      } else {
        s << "its decomposition did not finish within " << time_limit << " s";
      }
      out.why_not = out.cancelled ? "its decomposition was cancelled" : s.str();
      return out;
    }
  }
  const std::size_t eol = run.data.find('\n');
  const std::size_t eol2 = eol == std::string::npos ? eol : run.data.find('\n', eol + 1);
  if (eol2 == std::string::npos) {
    out.why_not = "its decomposition returned nothing";
    return out;
  }
  out.before_merge = std::atoi(run.data.substr(0, eol).c_str());
  out.method = run.data.substr(eol + 1, eol2 - eol - 1);
  // "plane cuts\t<surfaces left out>\t<surfaces used>\t<knife edges: 1/0>\t<cut_kind_text>"
  std::vector<std::string> fields;
  for (std::size_t at = 0;;) {
    const std::size_t tab = out.method.find('\t', at);
    fields.push_back(out.method.substr(at, tab == std::string::npos ? tab : tab - at));
    if (tab == std::string::npos) break;
    at = tab + 1;
  }
  out.method = fields[0];
  if (fields.size() == 5) {
    out.left_out = fields[1];
    out.along = fields[2];
    out.knife_edges = fields[3] == "1";
    out.cut_kind = fields[4];
  }
  std::size_t end = run.data.find(kMerges, eol2 + 1);
  if (end != std::string::npos) {
    out.merges = merges_from_text(run.data.substr(end + std::char_traits<char>::length(kMerges)));
    run.data.resize(end);
  }
  occ::ReadOptions ro;
  ro.several_solids = true;
  const std::size_t afresh = run.data.find(kAfresh, eol2 + 1);
  occ::ReadResult r = occ::read_solid_from_brep_string(
      run.data.substr(eol2 + 1, afresh == std::string::npos ? afresh : afresh - eol2 - 1), ro);
  if (!r.ok()) {
    std::string m = r.diagnostics.empty() ? std::string() : r.diagnostics.front().message;
    out.why_not = "its sub-volumes could not be glued (" + m + ")";
    return out;
  }
  out.pieces = std::move(r.solid);
  if (afresh != std::string::npos) {
    occ::ReadResult again = occ::read_solid_from_brep_string(
        run.data.substr(afresh + std::char_traits<char>::length(kAfresh)), ro);
    if (again.ok() && again.solid->num_solids() == out.pieces->num_solids())
      out.afresh = std::move(again.solid);
  }
  return out;
}

}  // namespace vorohex::pipeline::detail
