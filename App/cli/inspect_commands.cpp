// The inspection commands, which show the method's intermediate results:
//   vorohex voronoi IN -o GRAPH.json [--vtp G.vtp]          the embedded Voronoi graph
//   vorohex decompose IN -o PARTS.brep [--report D.json]    the sub-volumes
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/report.h"
#include "core/isolated_call.h"
#include "decompose/decompose.h"
#include "decompose/decomposition_io.h"
#include "decompose/plane_cuts.h"
#include "occ/shape_io.h"
#include "occ/split_solid.h"
#include "voronoi/graph_io.h"
#include "voronoi/voronoi_graph.h"

namespace vorohex::cli {

#define VOROHEX_GRAPH_OPTIONS_HELP                                                     \
  "  --eps E                merge tolerance, x bounding-box diagonal (default 0.01)\n" \
  "  --delta D              embedding accuracy, x bounding-box diagonal (0.001)\n"     \
  "  --max-depth N          maximum octree depth, 1..12 (default 9)\n"                 \
  "  --linear-tolerance T   chord tolerance for curved entities, x diagonal (0.005)\n"

const char* const kVoronoiUsage =
    "usage: vorohex voronoi IN -o GRAPH.json [--vtp GRAPH.vtp] [graph options]\n"
    "  IN    a solid as STEP, BREP or IGES\n"
    "  -o    the graph as JSON: every Voronoi vertex, edge and face with its governors\n"
    "        (FreeCAD names such as Face3, Edge5), kind, geometry and f_s flag\n"
    "  --vtp FILE             the graph as VTK PolyData for ParaView\n" VOROHEX_GRAPH_OPTIONS_HELP
    "exit: 0 graph written, 1 graph could not be computed, 2 bad input\n";

const char* const kDecomposeUsage =
    "usage: vorohex decompose IN -o PARTS.brep [--report DECOMPOSITION.json] [--vtp FACES.vtp]\n"
    "                         [--sharp-angle DEG] [--no-merge] [--plane-cuts [--tangent-planes]]\n"
    "                         [--auto] [--time-limit S] [--quiet] [graph options]\n"
    "  IN    a solid as STEP, BREP or IGES\n"
    "  -o    the sub-volumes as solids in one BREP compound (open it in FreeCAD)\n"
    "  --auto                 the sub-volumes the mesher meshes: the solid whole where one\n"
    "                         scheme takes it; else the --plane-cuts where every piece has\n"
    "                         a scheme (within half the time limit); else the Voronoi\n"
    "                         graph's within a fifth of it (the mesher's 6 s by default;\n"
    "                         its options apply; --report describes the one used;\n"
    "                         --vtp is not taken)\n"
    "  --plane-cuts           the mesher's second way instead of the Voronoi graph: exact\n"
    "                         cuts along the planes and cylinders of the faces at concave\n"
    "                         edges, neighbours merged while the union has a scheme; the\n"
    "                         pieces are written also when one has no scheme (exit 1);\n"
    "                         with it, only -o, --no-merge, --time-limit and --quiet (the\n"
    "                         options below are the Voronoi one's)\n"
    "  --tangent-planes       with --plane-cuts: a cylinder that a planar face touches\n"
    "                         tangently is replaced by the plane tangent to it across its\n"
    "                         concave edges (what the mesher tries where the pieces have\n"
    "                         knife edges and do not mesh: a lug as wide as its tube)\n"
    "  --time-limit S         seconds the whole may take (default 30): the split and the\n"
    "                         merging get what is left; stopped before the split ends, it\n"
    "                         fails (error time_limit, naming the step); stopped later, the\n"
    "                         merging ends and the sub-volumes it has are checked and written\n"
    "  --quiet                no progress lines\n"
    "  --report FILE          edge types, vertex rules, decomposition faces, sub-volumes\n"
    "                         with type (Vs/Ve), scheme and reason, counts before/after merging\n"
    "  --vtp FILE             the decomposition faces as VTK PolyData for ParaView\n"
    "  --sharp-angle DEG      dihedral angle below which a [1] edge becomes [1s] (60)\n"
    "  --no-merge             keep the sub-volumes of the first split (with --plane-cuts:\n"
    "                         the pieces of the cut, each checked for a "
    "scheme)\n" VOROHEX_GRAPH_OPTIONS_HELP
    "exit: 0 written, 1 decomposition failed (the report, if asked for, says why), 2 bad input\n";

#undef VOROHEX_GRAPH_OPTIONS_HELP

namespace {

// A tiny option table: each option either takes a value (a handler that returns false
// when the value is wrong) or is a flag.
struct OptionTable {
  std::map<std::string, std::function<bool(const std::string&)>> values;
  std::map<std::string, std::function<void()>> flags;
};

bool parse_number(const std::string& text, double* out) {
  std::size_t used = 0;
  try {
    *out = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size() && std::isfinite(*out);
}

// Returns an empty string on success, else the usage error; the one positional argument
// goes to *input.
std::string parse(const std::vector<std::string>& args, const OptionTable& table,
                  std::string* input) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (auto f = table.flags.find(a); f != table.flags.end()) {
      f->second();
    } else if (auto v = table.values.find(a); v != table.values.end()) {
      if (i + 1 >= args.size()) return "option " + a + " needs a value";
      if (!v->second(args[++i])) return "bad value for " + a + ": '" + args[i] + "'";
    } else if (!a.empty() && a[0] == '-') {
      return "unknown option " + a;
    } else if (input->empty()) {
      *input = a;
    } else {
      return "expected exactly one input file";
    }
  }
  if (input->empty()) return "missing the input file";
  return {};
}

void add_graph_options(OptionTable& t, voronoi::VoronoiOptions& o) {
  auto number = [](double* field) {
    return [field](const std::string& s) { return parse_number(s, field); };
  };
  t.values["--eps"] = number(&o.eps);
  t.values["--delta"] = number(&o.delta);
  t.values["--linear-tolerance"] = number(&o.linear_tolerance);
  t.values["--max-depth"] = [&o](const std::string& s) {
    double d = 0;
    if (!parse_number(s, &d) || d != std::floor(d) || d < 1 || d > 12) return false;
    o.max_depth = static_cast<int>(d);
    return true;
  };
}

int usage_error(const std::string& message, const char* usage) {
  std::cerr << "vorohex: " << message << "\n" << usage_hint(usage);
  return kExitBadInput;
}

void print_problems(const std::vector<core::Diagnostic>& diagnostics) {
  for (const auto& d : diagnostics)
    if (d.severity != core::Severity::info) std::cerr << "vorohex: " << core::format(d) << "\n";
}

// Reads the solid and computes its graph; returns an exit code, or -1 to go on.
int read_and_graph(const std::string& input, const voronoi::VoronoiOptions& options,
                   std::unique_ptr<occ::Solid>* solid, voronoi::VoronoiResult* graph) {
  occ::ReadResult read = occ::read_solid(input);
  if (!read.ok()) {
    print_problems(read.diagnostics);
    return kExitBadInput;
  }
  *solid = std::move(read.solid);
  *graph = voronoi::compute_voronoi_graph(**solid, options);
  print_problems(graph->diagnostics);
  return graph->ok() ? -1 : kExitInvalid;
}

}  // namespace

int run_voronoi(const std::vector<std::string>& args) {
  std::string input, json_path, vtp_path;
  voronoi::VoronoiOptions options;
  OptionTable t;
  add_graph_options(t, options);
  t.values["-o"] =
      t.values["--output"] = [&](const std::string& s) { return !(json_path = s).empty(); };
  t.values["--vtp"] = [&](const std::string& s) { return !(vtp_path = s).empty(); };
  if (std::string e = parse(args, t, &input); !e.empty()) return usage_error(e, kVoronoiUsage);
  if (json_path.empty()) return usage_error("missing -o GRAPH.json", kVoronoiUsage);
  if (std::string why = options.validate(); !why.empty()) return usage_error(why, kVoronoiUsage);

  std::unique_ptr<occ::Solid> solid;
  voronoi::VoronoiResult result;
  if (int code = read_and_graph(input, options, &solid, &result); code >= 0) return code;
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

// vorohex decompose --plane-cuts: the pieces, each with the scheme it gets once glued to the
// others (or why it has none).
int print_plane_cuts(const std::string& input, const std::string& brep_path,
                     const decompose::PlaneCutResult& cut, bool merge);

int run_plane_cuts(const std::string& input, const std::string& brep_path, double time_limit,
                   bool tangent_planes, bool merge, const core::Progress& progress) {
  occ::ReadResult read = occ::read_solid(input);
  print_problems(read.diagnostics);
  if (!read.ok()) return kExitBadInput;
  decompose::PlaneCutOptions options;
  options.time_limit = time_limit;
  options.tangent_planes = tangent_planes;
  options.merge = merge;
  const decompose::PlaneCutResult cut =
      decompose::cut_at_concave_edges(*read.solid, options, progress.with_time_limit(time_limit));
  return print_plane_cuts(input, brep_path, cut, merge);
}

// --plane-cuts is the mesher's first cut only: where it fails, the mesher goes on.
constexpr const char* kMesherGoesOn =
    "; these are the cuts at concave edges alone: where they fail the mesher goes on (planes "
    "around holes, across the feet of chamfers and fillets, along fillets' strips), and "
    "`vorohex decompose --auto` shows the sub-volumes it meshes";

// The plane cuts' pieces written to `brep_path` and described, each with its scheme.
int print_plane_cuts(const std::string& input, const std::string& brep_path,
                     const decompose::PlaneCutResult& cut, bool merge) {
  if (cut.pieces.empty()) {
    std::cerr << "vorohex: the plane cuts of " << input << " failed: " << cut.why_not
              << " (nothing written)" << kMesherGoesOn << "\n";
    return kExitInvalid;
  }
  std::vector<const occ::Solid*> pieces;
  for (const occ::Solid& s : cut.pieces) pieces.push_back(&s);
  std::string error;
  if (!occ::write_compound_brep(pieces, brep_path, &error)) {
    std::cerr << "vorohex: " << error << "\n";
    return kExitBadInput;
  }
  auto count = [](int n, const char* what) {
    return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
  };
  std::cout << "plane cuts of " << input << ": " << count(cut.planes, "plane") << ", "
            << count(cut.cylinders, "cylinder") << ", " << count(cut.pieces_before_merge, "piece")
            << (merge ? ", " + std::to_string(cut.pieces.size()) + " after merging"
                      : " (not merged)")
            << "\n";
  const std::string along = decompose::used_surfaces_text(cut, cut.surfaces.size(), true);
  if (!along.empty()) std::cout << "  cut along: " << along << "\n";
  if (const std::string left_out = decompose::left_out_text(cut); !left_out.empty())
    std::cout << "  left out (OCCT's cut along them with the others failed): " << left_out << "\n";
  if (cut.octants > 0)
    std::cout << "  " << count(cut.octants, "octant")
              << " of a ball (as at a corner where three fillets meet) parted like a cube's "
                 "corner into four blocks each, the fillets' strips beside them into three; not "
                 "merged\n";
  if (cut.merges_checked_each)
    std::cout << "  merged again with each merge's neighbours checked (merged without, a piece "
                 "had no scheme once glued)\n";
  if (!cut.afresh.empty())
    std::cout << "  split afresh at the faces they share: the same " << cut.afresh.size()
              << " pieces without the traces of the cuts merged back (not unified); the mesher "
                 "meshes those too where these mesh below 0.2, and keeps the better\n";
  if (cut.knife_edges)
    std::cout << "  knife edges: pieces meet a planar face that touches a cylinder cut along at "
                 "an angle near zero; where they do not mesh, the mesher cuts with "
                 "--tangent-planes\n";
  const decompose::PlaneCutSchemes schemes = decompose::plane_cut_schemes(cut);
  if (!schemes.glue_error.empty()) std::cerr << "vorohex: " << schemes.glue_error << "\n";
  for (std::size_t i = 0; i < cut.pieces.size(); ++i) {
    std::cout << "  piece " << i + 1 << " (volume " << cut.pieces[i].volume() << ")";
    if (schemes.glue_error.empty())
      std::cout << ": " << (schemes.schemes[i].empty() ? schemes.reasons[i] : schemes.schemes[i]);
    std::cout << "\n";
  }
  std::cout << "wrote " << brep_path << "\n";
  if (!cut.ok)
    std::cerr << "vorohex: the plane cuts failed: " << cut.why_not << kMesherGoesOn << "\n";
  return cut.ok ? kExitOk : kExitInvalid;
}

// Where a file is written before it is renamed to `path` ("" stays "").
std::string partial(const std::string& path) {
  return path.empty() ? path : path + ".partial";
}

// Renames each partial file to its path; false (with why) at the first that fails.
bool renamed(const std::vector<std::string>& paths, std::string* error) {
  for (const std::string& path : paths)
    if (!path.empty() && std::rename(partial(path).c_str(), path.c_str()) != 0) {
      *error = "could not write " + path + " (renaming " + partial(path) + " failed)";
      return false;
    }
  return true;
}

void remove_partials(const std::vector<std::string>& paths) {
  for (const std::string& path : paths)
    if (!path.empty()) std::remove(partial(path).c_str());
}

// vorohex decompose --auto, its first two steps: the solid whole where one scheme takes it,
// else the plane cuts where each piece has a scheme (the tangent planes where the first
// cut's pieces have knife edges), within half of `time_limit`. The exit code when one of
// them is the answer (written and described); -1 (with the reason printed) when the
// Voronoi decomposition is to follow.
int auto_first_steps(const std::string& input, const occ::Solid& solid,
                     const std::string& brep_path, const std::string& json_path,
                     const decompose::DecomposeOptions& options, double time_limit,
                     const core::Progress& progress) {
  auto report = [&](const std::string& text) {
    if (json_path.empty()) return true;
    std::ofstream out(json_path);
    out << text << "\n";
    if (out) return true;
    std::cerr << "vorohex: could not write " << json_path << "\n";
    return false;
  };
  std::string why;
  std::pair<core::FaceId, core::FaceId> ends;
  const decompose::Scheme whole = decompose::whole_solid_scheme(solid, options, &why, &ends);
  if (whole != decompose::Scheme::none) {
    std::string error;
    if (!occ::write_compound_brep({&solid}, brep_path, &error)) {
      std::cerr << "vorohex: " << error << "\n";
      return kExitBadInput;
    }
    if (!report(decompose::whole_solid_json(whole, why, solid.volume(), ends)))
      return kExitBadInput;
    std::cout << "decomposition of " << input << ": not cut, the mesher meshes it whole\n"
              << "  sub-volume 0 (" << decompose::scheme_name(whole) << "): " << why << "\n"
              << "wrote " << brep_path << "\n";
    return kExitOk;
  }
  decompose::PlaneCutOptions cuts;
  cuts.time_limit = 0.5 * time_limit;
  cuts.merge = options.merge;
  cuts.multisweep = options.multisweep;
  const decompose::PlaneCutResult cut =
      decompose::cut_as_the_mesher(solid, cuts, progress.with_time_limit(cuts.time_limit));
  if (cut.ok) {
    if (!report(
            decompose::plane_cuts_json(cut, decompose::plane_cut_schemes(cut, cuts.multisweep))))
      return kExitBadInput;
    return print_plane_cuts(input, brep_path, cut, options.merge);
  }
  std::cout << "not cut along the faces at its concave edges: " << cut.why_not
            << "; along its Voronoi graph instead" << std::endl;  // before the child forks
  return -1;
}

int run_decompose(const std::vector<std::string>& args) {
  std::string input, brep_path, json_path, vtp_path;
  voronoi::VoronoiOptions graph_options;
  decompose::DecomposeOptions options;
  OptionTable t;
  add_graph_options(t, graph_options);
  t.values["-o"] =
      t.values["--output"] = [&](const std::string& s) { return !(brep_path = s).empty(); };
  t.values["--report"] = [&](const std::string& s) { return !(json_path = s).empty(); };
  t.values["--vtp"] = [&](const std::string& s) { return !(vtp_path = s).empty(); };
  t.values["--sharp-angle"] = [&](const std::string& s) {
    return parse_number(s, &options.sharp_angle);
  };
  t.flags["--no-merge"] = [&] { options.merge = false; };
  // Every option but -o and --no-merge is the Voronoi decomposition's: noted, to refuse it
  // with --plane-cuts.
  std::string voronoi_option;
  for (auto& [name, handler] : t.values)
    if (name != "-o" && name != "--output")
      handler = [&, name = name, inner = handler](const std::string& v) {
        voronoi_option = name;
        return inner(v);
      };
  for (auto& [name, handler] : t.flags)
    if (name != "--no-merge")
      handler = [&, name = name, inner = handler] {
        voronoi_option = name;
        inner();
      };
  bool plane_cuts = false, tangent_planes = false, quiet = false, auto_method = false;
  double time_limit = 30;
  t.flags["--plane-cuts"] = [&] { plane_cuts = true; };
  t.flags["--auto"] = [&] { auto_method = true; };
  t.flags["--tangent-planes"] = [&] { tangent_planes = true; };
  t.flags["--quiet"] = [&] { quiet = true; };
  t.values["--time-limit"] = [&](const std::string& s) {
    return parse_number(s, &time_limit) && time_limit > 0;
  };
  if (std::string e = parse(args, t, &input); !e.empty()) return usage_error(e, kDecomposeUsage);
  if (brep_path.empty()) return usage_error("missing -o PARTS.brep", kDecomposeUsage);
  // The deadline counts from here: reading the file and the graph are part of the whole.
  const core::Progress printer = progress_printer(quiet);
  core::Progress progress = printer.with_time_limit(time_limit);
  if (auto_method && plane_cuts)
    return usage_error("--auto and --plane-cuts: one or the other", kDecomposeUsage);
  if (plane_cuts) {
    if (!voronoi_option.empty())
      return usage_error(voronoi_option +
                             " is an option of the Voronoi decomposition; --plane-cuts takes "
                             "only -o, --no-merge, --time-limit and --quiet",
                         kDecomposeUsage);
    return run_plane_cuts(input, brep_path, time_limit, tangent_planes, options.merge, progress);
  }
  if (tangent_planes)
    return usage_error("--tangent-planes is an option of --plane-cuts", kDecomposeUsage);
  if (std::string why = graph_options.validate(); !why.empty())
    return usage_error(why, kDecomposeUsage);
  if (std::string why = options.validate(); !why.empty()) return usage_error(why, kDecomposeUsage);
  if (auto_method && !vtp_path.empty())
    return usage_error(
        "--vtp is an option of the Voronoi decomposition alone; --auto does not take it",
        kDecomposeUsage);
  const auto t0 = std::chrono::steady_clock::now();
  occ::ReadResult read = occ::read_solid(input);
  if (!read.ok()) {
    print_problems(read.diagnostics);
    std::string error;
    if (!json_path.empty() &&
        !write_json(input_error_json(input, read.diagnostics), json_path, &error))
      std::cerr << "vorohex: " << error << "\n";
    return kExitBadInput;
  }
  if (auto_method) {
    if (const int code = auto_first_steps(input, *read.solid, brep_path, json_path, options,
                                          time_limit, progress);
        code >= 0)
      return code;
    // The Voronoi decomposition gets what is left, at most a fifth of the limit: the 6 s
    // `vorohex mesh` gives it with its default decomposition time limit of 60 s (a tenth).
    time_limit = std::max(
        1.0,
        std::min(0.2 * time_limit,
                 time_limit -
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()));
    progress = printer.with_time_limit(time_limit);
  }
  // As the mesher: where the Voronoi decomposition leaves a sub-volume without a scheme, or
  // fails, `vorohex mesh` meshes the solid with its fallback.
  const auto fallback_note = [&](int code, const std::string& out) {
    if (auto_method && (code != kExitOk || out.find(" (none): ") != std::string::npos))
      std::cout << "as the mesher: not every sub-volume has a scheme, so vorohex mesh meshes "
                   "the solid with its fallback (the grid mesher) instead\n";
    return code;
  };

  // The graph and the decomposition run in a child process: they stop themselves at the
  // deadline where they can, and the child is killed a little after it where OCCT's split
  // does not return (HexMe i09: 20 s past its limit). Its stderr is this process's; what
  // it prints on stdout comes back, after the exit code, on the first line.
  const occ::Solid& solid = *read.solid;
  core::IsolatedJob job(
      [&](const core::Progress& in_child) {
        in_child.report("voronoi", 0.0);
        const voronoi::VoronoiResult graph = voronoi::compute_voronoi_graph(solid, graph_options);
        print_problems(graph.diagnostics);
        if (!graph.ok()) return std::to_string(kExitInvalid) + "\n";
        in_child.report("voronoi", 1.0);
        const decompose::DecompositionResult result =
            decompose::decompose(solid, graph, options, in_child);
        print_problems(result.diagnostics);
        std::string error;
        if (!result.ok()) {
          // The report says why (status failed, the diagnostics); no sub-volumes are written.
          if (!json_path.empty() && !decompose::write_decomposition(result, "", json_path, &error))
            std::cerr << "vorohex: " << error << "\n";
          return std::to_string(kExitInvalid) + "\n";
        }
        // Written beside and renamed once all are: a child stopped while writing leaves
        // what the user had at those paths.
        if (!decompose::write_decomposition(result, partial(brep_path), partial(json_path), &error,
                                            partial(vtp_path)) ||
            !renamed({brep_path, json_path, vtp_path}, &error)) {
          remove_partials({brep_path, json_path, vtp_path});
          std::cerr << "vorohex: " << error << "\n";
          return std::to_string(kExitBadInput) + "\n";
        }
        std::ostringstream out;
        out << kExitOk << "\n"
            << "decomposition of " << input << ": " << result.stats.sub_volumes_before_merge
            << (result.stats.sub_volumes_before_merge == 1 ? " sub-volume" : " sub-volumes")
            << " before merging, " << result.stats.sub_volumes << " after, "
            << result.stats.decomposition_faces
            << (result.stats.decomposition_faces == 1 ? " decomposition face\n"
                                                      : " decomposition faces\n");
        for (std::size_t i = 0; i < result.sub_volumes.size(); ++i)
          out << "  sub-volume " << i << " ("
              << decompose::scheme_name(result.sub_volumes[i].scheme)
              << "): " << result.sub_volumes[i].reason << "\n";
        if (result.status == decompose::DecompositionStatus::partial)
          out << "partial: " << decompose::partial_reason(result) << "\n";
        out << "wrote " << brep_path << (json_path.empty() ? "" : ", " + json_path)
            << (vtp_path.empty() ? "" : ", " + vtp_path) << "\n";
        return out.str();
      },
      progress);
  const core::IsolatedResult got =
      job.take(printer.with_time_limit(progress.seconds_left() + decompose::stop_grace(time_limit)),
               {"decompose"});
  if (got.ok()) {
    const std::size_t eol = got.data.find('\n');
    std::cout << got.data.substr(eol + 1);
    return fallback_note(std::stoi(got.data.substr(0, eol)), got.data);
  }
  decompose::DecompositionResult failed;  // status failed
  if (got.status == core::IsolatedResult::Status::cancelled) {
    failed.diagnostics.push_back(decompose::not_stopped_error(time_limit));
  } else {
    failed.diagnostics.push_back(core::make_error(
        "decomposition_crashed",
        "The decomposition " +
            std::string(got.status == core::IsolatedResult::Status::crashed ? "crashed: "
                                                                            : "failed: ") +
            got.message));
  }
  print_problems(failed.diagnostics);
  remove_partials({brep_path, json_path, vtp_path});
  std::string error;
  if (!json_path.empty() && !decompose::write_decomposition(failed, "", json_path, &error))
    std::cerr << "vorohex: " << error << "\n";
  return fallback_note(kExitInvalid, "");
}

}  // namespace vorohex::cli
