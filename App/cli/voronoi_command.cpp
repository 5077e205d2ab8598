// `vorohex voronoi IN -o graph.json [--vtp graph.vtp] [--eps E] [--delta D] [--max-depth N]
//                  [--linear-tolerance T]`: the embedded Voronoi graph for inspection.
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "occ/shape_io.h"
#include "voronoi/graph_io.h"
#include "voronoi/voronoi_graph.h"

namespace vorohex::cli {

const char* const kVoronoiUsage =
    "usage: vorohex voronoi IN -o GRAPH.json [--vtp GRAPH.vtp] [--eps E] [--delta D]\n"
    "                       [--max-depth N] [--linear-tolerance T]\n"
    "  IN    a solid as STEP, BREP or IGES\n"
    "  -o    the graph as JSON: every Voronoi vertex, edge and face with its governors\n"
    "        (FreeCAD names such as Face3, Edge5), kind, geometry and f_s flag\n"
    "  --vtp FILE             the graph as VTK PolyData for ParaView\n"
    "  --eps E                merge tolerance, x bounding-box diagonal (default 0.01)\n"
    "  --delta D              embedding accuracy, x bounding-box diagonal (default 0.001)\n"
    "  --max-depth N          maximum octree depth, 1..12 (default 9)\n"
    "  --linear-tolerance T   chord tolerance for curved entities, x diagonal (0.005)\n"
    "exit: 0 graph written, 1 graph could not be computed, 2 bad input\n";

namespace {

bool parse_number(const std::string& text, double* out) {
  std::size_t used = 0;
  try {
    *out = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size() && std::isfinite(*out);
}

int fail_usage(const std::string& message) {
  std::cerr << "vorohex: " << message << "\n" << kVoronoiUsage;
  return kExitBadInput;
}

}  // namespace

int run_voronoi(const std::vector<std::string>& args) {
  std::string input, json_path, vtp_path;
  voronoi::VoronoiOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const bool has_value = i + 1 < args.size();
    auto number = [&](double* field) {
      if (!has_value) return false;
      return parse_number(args[++i], field);
    };
    if (a == "-o" || a == "--output") {
      if (!has_value) return fail_usage("option " + a + " needs a value");
      json_path = args[++i];
    } else if (a == "--vtp") {
      if (!has_value) return fail_usage("option --vtp needs a value");
      vtp_path = args[++i];
    } else if (a == "--eps") {
      if (!number(&options.eps)) return fail_usage("--eps must be a number");
    } else if (a == "--delta") {
      if (!number(&options.delta)) return fail_usage("--delta must be a number");
    } else if (a == "--linear-tolerance") {
      if (!number(&options.linear_tolerance))
        return fail_usage("--linear-tolerance must be a number");
    } else if (a == "--max-depth") {
      double depth = 0;
      if (!number(&depth) || depth != std::floor(depth) || depth < 1 || depth > 12)
        return fail_usage("--max-depth must be a whole number from 1 to 12");
      options.max_depth = static_cast<int>(depth);
    } else if (!a.empty() && a[0] == '-') {
      return fail_usage("unknown option " + a);
    } else if (input.empty()) {
      input = a;
    } else {
      return fail_usage("expected exactly one input file");
    }
  }
  if (input.empty()) return fail_usage("missing the input file");
  if (json_path.empty()) return fail_usage("missing -o GRAPH.json");
  if (const std::string why = options.validate(); !why.empty()) return fail_usage(why);

  occ::ReadResult read = occ::read_solid(input);
  if (!read.ok()) {
    for (const auto& d : read.diagnostics) std::cerr << "vorohex: " << core::format(d) << "\n";
    return kExitBadInput;
  }
  const voronoi::VoronoiResult result = voronoi::compute_voronoi_graph(*read.solid, options);
  for (const auto& d : result.diagnostics)
    if (d.severity != core::Severity::info) std::cerr << "vorohex: " << core::format(d) << "\n";
  if (!result.ok()) return kExitInvalid;
  std::string error;
  if (!voronoi::write_voronoi_graph(result, json_path, vtp_path, &error)) {
    std::cerr << "vorohex: " << error << "\n";
    return kExitBadInput;
  }
  std::size_t counts[3] = {0, 0, 0};
  for (const auto& e : result.graph.elements) ++counts[static_cast<int>(e.kind)];
  std::cout << "Voronoi graph of " << input << ": " << counts[2] << " vertices, " << counts[1]
            << " edges, " << counts[0] << " faces (" << result.graph.fs_faces().size() << " f_s), "
            << result.stats.cells << " octree cells, " << result.stats.seconds << " s\nwrote "
            << json_path << (vtp_path.empty() ? "" : " and " + vtp_path) << "\n";
  return kExitOk;
}

}  // namespace vorohex::cli
