#include "cli/report.h"

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace vorohex::cli {

void print_check_report(std::ostream& out, const quality::CheckReport& r) {
  const auto& sj = r.scaled_jacobian;
  out << "hexahedra            " << r.hexes << "\n";
  out << "nodes                " << r.nodes << "\n";
  out << std::setprecision(4);
  out << "scaled Jacobian      min " << sj.min << "  mean " << sj.mean << "  max " << sj.max
      << "\n";
  out << "  below 0.2          " << 100.0 * sj.fraction_below_0_2 << " %\n";
  out << "  inverted (<= 0)    " << sj.inverted << "\n";
  if (!r.worst.empty()) {
    // Where the worst hexahedron is, and on which CAD entities its nodes lie.
    const quality::WorstHex& w = r.worst.front();
    out << "  worst              " << w.scaled_jacobian << " (hex " << w.hex << " at "
        << w.centre.x() << ", " << w.centre.y() << ", " << w.centre.z();
    for (std::size_t i = 0; i < w.entities.size(); ++i)
      out << (i ? ", " : "; on ") << w.entities[i];
    out << ")\n";
  }
  if (r.degenerate) out << "  flat (< 1e-6)      " << r.degenerate << "\n";
  out << "  histogram          ";
  // Only the non-negative half: bins [0,0.1) ... [0.9,1.0].
  for (int i = quality::QualityStats::kBins / 2; i < quality::QualityStats::kBins; ++i)
    out << sj.histogram[i] << (i + 1 < quality::QualityStats::kBins ? " " : "");
  out << "  (bins of 0.1 from 0 to 1)\n";
  out << "conformity           " << r.interior_quads << " inner quads, " << r.boundary_quads
      << " boundary quads, " << r.non_manifold_quads << " shared by more than two hexes, "
      << r.folded_quads << " folded\n";
  out << "boundary             " << (r.open_boundary_edges == 0 ? "closed" : "OPEN") << " ("
      << r.open_boundary_edges << " open edges)\n";
  if (r.has_cad) {
    out << std::setprecision(6);
    out << "volume               mesh " << r.mesh_volume << "  CAD " << r.cad_volume
        << "  relative error " << std::scientific << std::setprecision(2) << r.volume_rel_error
        << std::defaultfloat << "\n";
    out << "distance to CAD      max " << std::scientific << std::setprecision(2)
        << r.max_boundary_distance << " (" << r.max_boundary_distance_rel << " x diagonal)"
        << std::defaultfloat << "\n";
  }
  if (r.order == 2)
    out << "second order         20-node, " << r.non_positive_gauss
        << " with det J <= 0 at a Gauss point\n";
  out << "valid                " << (r.valid ? "yes" : "NO") << "\n";
  for (const auto& d : r.diagnostics) out << "  " << core::format(d) << "\n";
}

nlohmann::json diagnostics_json(const std::vector<core::Diagnostic>& diagnostics) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& d : diagnostics)
    list.push_back({{"severity", core::severity_name(d.severity)},
                    {"code", d.code},
                    {"message", d.message},
                    {"entities", d.entities}});
  return list;
}

nlohmann::json check_report_json(const quality::CheckReport& r) {
  const auto& sj = r.scaled_jacobian;
  nlohmann::json j;
  j["valid"] = r.valid;
  j["nodes"] = r.nodes;
  j["hexes"] = r.hexes;
  j["scaled_jacobian"] = {{"min", sj.min},
                          {"mean", sj.mean},
                          {"max", sj.max},
                          {"inverted", sj.inverted},
                          {"degenerate", r.degenerate},
                          {"fraction_below_0_2", sj.fraction_below_0_2},
                          {"histogram_bins", "20 bins of 0.1 from -1 to 1"},
                          {"histogram", sj.histogram}};
  nlohmann::json worst = nlohmann::json::array();
  for (const quality::WorstHex& w : r.worst)
    worst.push_back({{"hex", w.hex},
                     {"scaled_jacobian", w.scaled_jacobian},
                     {"centre", {w.centre.x(), w.centre.y(), w.centre.z()}},
                     {"entities", w.entities}});
  j["scaled_jacobian"]["worst"] = worst;
  j["conformity"] = {
      {"interior_quads", r.interior_quads},           {"boundary_quads", r.boundary_quads},
      {"non_manifold_quads", r.non_manifold_quads},   {"folded_quads", r.folded_quads},
      {"open_boundary_edges", r.open_boundary_edges}, {"unused_nodes", r.unused_nodes}};
  if (r.has_cad) {
    j["cad"] = {{"mesh_volume", r.mesh_volume},
                {"cad_volume", r.cad_volume},
                {"volume_rel_error", r.volume_rel_error},
                {"volume_allowance", r.volume_allowance},
                {"max_boundary_distance", r.max_boundary_distance},
                {"max_boundary_distance_rel", r.max_boundary_distance_rel}};
  }
  j["diagnostics"] = diagnostics_json(r.diagnostics);
  return j;
}

void print_groups(std::ostream& out, const std::vector<io::NamedGroup>& groups) {
  int count[3] = {0, 0, 0};
  for (const auto& g : groups) ++count[g.dim];
  out << "groups               " << count[2] << " faces, " << count[1] << " edges, " << count[0]
      << " vertices:";
  std::size_t shown = 0;
  for (const auto& g : groups) {
    if (shown++ == 40) {
      out << " ... (all in the --report JSON)";
      break;
    }
    out << " " << g.name;
  }
  out << "\n";
}

nlohmann::json groups_json(const std::vector<io::NamedGroup>& groups) {
  static const char* const kKind[] = {"vertex", "edge", "face"};
  nlohmann::json list = nlohmann::json::array();
  for (const auto& g : groups)
    list.push_back({{"name", g.name},
                    {"kind", kKind[g.dim]},
                    {"id", g.id},
                    {"nodes", g.nodes.size()},
                    {"element_faces", g.faces.size()},
                    {"mesh_edges", g.edges.size()}});
  return list;
}

std::string usage_hint(const char* usage) {
  std::istringstream words(usage);
  std::string usage_word, program, command;
  words >> usage_word >> program >> command;
  return "(`" + program + " " + command + " --help` lists the options)\n";
}

bool write_json(const nlohmann::json& j, const std::string& path, std::string* error) {
  std::ofstream f(path);
  if (!f) {
    *error = "cannot open " + path + " for writing";
    return false;
  }
  f << std::setw(2) << j << "\n";
  f.close();
  if (!f) {
    *error = "could not write " + path;
    return false;
  }
  return true;
}

nlohmann::json input_error_json(const std::string& input,
                                const std::vector<core::Diagnostic>& diagnostics,
                                const char* verdict) {
  nlohmann::json j;
  j["input"] = input;
  j[verdict] = false;
  j["diagnostics"] = diagnostics_json(diagnostics);
  return j;
}

}  // namespace vorohex::cli
