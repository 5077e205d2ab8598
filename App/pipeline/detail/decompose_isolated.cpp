#include "pipeline/detail/decompose_isolated.h"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <stdexcept>

#include "core/isolated_call.h"
#include "decompose/decompose.h"
#include "occ/shape_io.h"
#include "occ/split_solid.h"
#include "voronoi/voronoi_graph.h"

namespace vorohex::pipeline::detail {

namespace {

// Runs in the child: "<before merge>\n" then the sub-volumes as one BREP compound, or
// throws with the reason.
std::string decompose_to_text(const occ::Solid& solid, double time_limit) {
  const voronoi::VoronoiResult graph = voronoi::compute_voronoi_graph(solid);
  if (!graph.ok()) throw std::runtime_error("its Voronoi graph could not be computed");
  decompose::DecomposeOptions options;
  options.split_time_limit = std::min(30.0, time_limit);
  const decompose::DecompositionResult d = decompose::decompose(solid, graph, options);
  if (!d.ok()) {
    for (const core::Diagnostic& diag : d.diagnostics)
      if (diag.severity != core::Severity::info) {
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
    solids.push_back(sv.solid.get());
  }
  const std::string brep = occ::compound_brep_string(solids);
  if (brep.empty()) throw std::runtime_error("its sub-volumes could not be written");
  return std::to_string(d.stats.sub_volumes_before_merge) + "\n" + brep;
}

}  // namespace

IsolatedDecomposition decompose_isolated(const occ::Solid& solid, double time_limit,
                                         const core::Progress& progress) {
  IsolatedDecomposition out;
  const auto t0 = std::chrono::steady_clock::now();
  core::IsolatedCallOptions io;
  io.stage = "decompose";
  const core::IsolatedResult run =
      core::isolated_call([&] { return decompose_to_text(solid, time_limit); },
                          progress.with_time_limit(time_limit), io);
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
      s << "its decomposition did not finish within " << time_limit << " s";
      out.why_not = out.cancelled ? "its decomposition was cancelled" : s.str();
      return out;
    }
  }
  const std::size_t eol = run.data.find('\n');
  if (eol == std::string::npos) {
    out.why_not = "its decomposition returned nothing";
    return out;
  }
  out.before_merge = std::atoi(run.data.substr(0, eol).c_str());
  occ::ReadOptions ro;
  ro.several_solids = true;
  occ::ReadResult r = occ::read_solid_from_brep_string(run.data.substr(eol + 1), ro);
  if (!r.ok()) {
    std::string m = r.diagnostics.empty() ? std::string() : r.diagnostics.front().message;
    out.why_not = "its sub-volumes could not be glued (" + m + ")";
    return out;
  }
  out.pieces = std::move(r.solid);
  return out;
}

}  // namespace vorohex::pipeline::detail
