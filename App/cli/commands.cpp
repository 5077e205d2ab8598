#include "cli/commands.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include <unistd.h>

#include "cli/report.h"
#include "io/mesh_io.h"
#include "occ/shape_io.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::cli {

const char* const kMeshUsage =
    "usage: vorohex mesh IN -o OUT [--size H] [--size-at ENTITY=H ...] [--size-grading G]\n"
    "                    [--report REPORT.json] [--max-hexes N]\n"
    "                    [--smooth-iterations N] [--smooth-passes N] [--no-smooth]\n"
    "                    [--no-decompose] [--decomposition-time-limit S] [--sharp-angle A]\n"
    "                    [--eps E] [--delta D] [--max-depth N] [--no-fallback]\n"
    "                    [--fallback-scheme grid|tet-split] [--schemes LIST]\n"
    "                    [--time-limit S] [--keep-invalid] [--quiet]\n"
    "                    [--order 1|2] [--element TYPE]\n"
    "  IN    a solid as STEP (.step/.stp), BREP (.brep/.brp) or IGES (.iges/.igs)\n"
    "  OUT   the hex mesh: .vtu (ParaView), .msh (Gmsh 4.1) or .inp (Abaqus/CalculiX), with\n"
    "        named groups per CAD face, edge and vertex (Face7, Edge3, Vertex1) in .inp/.msh\n"
    "  --size H        target edge length in model units (default: diagonal / 20)\n"
    "  --size-at ENTITY[,ENTITY...]=H  a smaller size at CAD faces, edges or vertices\n"
    "                  (Face7, Edge3, Vertex2: FreeCAD's names), graded into --size; repeatable\n"
    "  --size-grading G  growth of the size per unit distance from a --size-at entity,\n"
    "                  in (0, 10] (default 0.3: 1 mm away the size is 0.3 mm larger)\n"
    "  --order N       1: 8-node hexahedra (default); 2: 20-node, mid-edge nodes on the CAD\n"
    "  --element TYPE  .inp element: C3D8, C3D8I, C3D8R (order 1), C3D20, C3D20R (order 2);\n"
    "                  default C3D8I / C3D20R, replaced where known to fail (C3D8 on distorted\n"
    "                  hexes, C3D20 one element through a thickness); a reduced-integration\n"
    "                  type asked for on a mesh one element thick is refused (exit 2)\n"
    "  --report FILE   write the quality and validity report as JSON\n"
    "  --max-hexes N   refuse up front when the predicted mesh is larger (default 50000000)\n"
    "  --time-limit S  stop after S seconds like a cancel (error time_limit, nothing written)\n"
    "  --smooth-iterations N  Laplacian sweeps of the global smoothing (default 20)\n"
    "  --smooth-passes N      untangling/optimisation passes of the smoothing (default 10)\n"
    "  --no-smooth     no smoothing (same as both counts 0)\n"
    "  --no-decompose  do not cut a solid no single scheme meshes into sub-volumes along its\n"
    "                  Voronoi graph (by default its sub-volumes are meshed into one mesh)\n"
    "  --decomposition-time-limit S  seconds the decomposition may take (default 60; the\n"
    "                  exact cuts at most a half, the Voronoi graph's a tenth), then the\n"
    "                  fallback takes over\n"
    "  --sharp-angle A dihedral angle (degrees, default 60) below which the decomposition\n"
    "                  cuts along both faces of a model edge ([1s] edges)\n"
    "  --eps E, --delta D, --max-depth N  the Voronoi graph the decomposition cuts along\n"
    "                  (as for vorohex voronoi: 0.01, 0.001 of the diagonal, depth 9)\n"
    "  --schemes LIST  the single-solid schemes to try, in order, comma-separated (default\n"
    "                  map,sweep,multisweep,revolve,midpoint); one left out is never used\n"
    "  --no-fallback   refuse a solid that neither one scheme nor its\n"
    "                  decomposition meshes, instead of meshing it with the grid mesher\n"
    "  --fallback-scheme S  the fallback: grid (default: core grid, pillow layer, features\n"
    "                  captured) or tet-split (tetrahedra split into hexahedra, for comparison)\n"
    "  --keep-invalid  write the mesh even when it fails the validity check\n"
    "  --quiet         no progress lines\n"
    "exit: 0 valid mesh written, 1 meshing failed or mesh invalid, 2 bad input\n";

const char* const kCheckUsage =
    "usage: vorohex check MESH [--cad IN] [--report REPORT.json]\n"
    "                     [--volume-tol R] [--distance-tol R]\n"
    "  MESH  a hex mesh: .vtu or .msh (Gmsh 2.2 / 4.1), 8- or 20-node hexahedra (the latter\n"
    "        also judged at their 27 Gauss points); other cells are ignored\n"
    "  --cad IN          the solid it should fill: adds volume and distance-to-CAD checks\n"
    "  --volume-tol R    relative volume tolerance (default 1e-9, plus the chord allowance)\n"
    "  --distance-tol R  boundary node distance tolerance, x bounding-box diagonal (1e-6)\n"
    "exit: 0 valid, 1 invalid, 2 bad input\n";

namespace {

// Thrown for usage errors; main turns it into exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::string> values;                 // --name value
  std::map<std::string, bool> flags;                         // --name
  std::map<std::string, std::vector<std::string>> repeated;  // --name value, given any times
};

Args parse(const std::vector<std::string>& args, const std::vector<std::string>& value_options,
           const std::vector<std::string>& flag_options,
           const std::vector<std::string>& repeat_options = {}) {
  Args out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.size() > 1 && a[0] == '-') {
      bool known = false;
      for (const auto& r : repeat_options) {
        if (a == r) {
          if (i + 1 >= args.size()) throw UsageError("option " + a + " needs a value");
          out.repeated[a].push_back(args[++i]);
          known = true;
        }
      }
      for (const auto& v : value_options) {
        if (a == v) {
          if (i + 1 >= args.size()) throw UsageError("option " + a + " needs a value");
          if (out.values.count(a)) throw UsageError("option " + a + " given twice");
          out.values[a] = args[++i];
          known = true;
        }
      }
      for (const auto& f : flag_options) {
        if (a == f) {
          out.flags[a] = true;
          known = true;
        }
      }
      if (!known) throw UsageError("unknown option " + a);
    } else {
      out.positional.push_back(a);
    }
  }
  return out;
}

double parse_positive(const std::string& name, const std::string& text) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    throw UsageError(name + " must be a number, got '" + text + "'");
  }
  if (used != text.size()) throw UsageError(name + " must be a number, got '" + text + "'");
  if (!std::isfinite(v) || v <= 0)
    throw UsageError(name + " must be a positive finite number, got '" + text + "'");
  return v;
}

// "Face7=0.5" or "Face7,Edge3=0.5": entity names (checked here for their form, against the
// solid by the pipeline) and one size.
std::vector<core::LocalSize> parse_size_at(const std::string& text) {
  const std::size_t eq = text.rfind('=');
  if (eq == std::string::npos)
    throw UsageError("--size-at needs ENTITY=SIZE (e.g. Face7=0.5), got '" + text + "'");
  const double size = parse_positive("--size-at " + text.substr(0, eq), text.substr(eq + 1));
  std::vector<core::LocalSize> out;
  const std::string names = text.substr(0, eq);
  for (std::size_t start = 0; start <= names.size();) {
    const std::size_t comma = std::min(names.find(',', start), names.size());
    std::string name = names.substr(start, comma - start);
    name.erase(0, name.find_first_not_of(" \t"));  // "Face7, Edge3=1": spaces after commas
    name.erase(name.find_last_not_of(" \t") + 1);
    char kind = 0;
    int id = 0;
    if (!core::parse_entity_name(name, kind, id))
      throw UsageError("--size-at: '" + name +
                       "' is not an entity name (expected FaceN, EdgeN or VertexN, as in FreeCAD)");
    out.push_back({name, size});
    start = comma + 1;
  }
  return out;
}

std::size_t parse_count(const std::string& name, const std::string& text) {
  const double v = parse_positive(name, text);
  if (v != std::floor(v) || v > 9e15)
    throw UsageError(name + " must be a whole number, got '" + text + "'");
  return static_cast<std::size_t>(v);
}

int parse_count_or_zero(const std::string& name, const std::string& text) {
  if (text == "0") return 0;
  const std::size_t v = parse_count(name, text);
  if (v > 100000) throw UsageError(name + " is unreasonably large: " + text);
  return static_cast<int>(v);
}

}  // namespace

core::Progress progress_printer(bool quiet) {
  if (quiet) return {};
  auto t0 = std::chrono::steady_clock::now();
  auto last_stage = std::make_shared<std::string>();
  auto last_quarter = std::make_shared<int>(-1);
  return core::Progress([=](std::string_view stage, double fraction) {
    const int quarter = static_cast<int>(fraction * 4);
    if (stage == *last_stage && quarter == *last_quarter) return;
    *last_stage = std::string(stage);
    *last_quarter = quarter;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "[%7.2fs] %-8s %3d%%\n", s, std::string(stage).c_str(),
                 static_cast<int>(100 * fraction));
  });
}

namespace {

void print_diagnostics(const std::vector<core::Diagnostic>& diagnostics) {
  for (const auto& d : diagnostics) std::cerr << "vorohex: " << core::format(d) << "\n";
}

// Writes to a temporary file beside the target and renames it only on success, so a
// failed run never leaves a partial file or clobbers what the user had.
bool write_atomically(const core::HexMesh& mesh, const std::string& path,
                      const io::WriteOptions& options, std::string* error) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path tmp = target.parent_path() /
                       (".vorohex-tmp-" + target.filename().string() + target.extension().string());
  if (!io::write_mesh(mesh, tmp.string(), options, error)) {
    std::error_code ec;
    fs::remove(tmp, ec);
    return false;
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    *error = "cannot move the mesh into place at " + path + ": " + ec.message();
    fs::remove(tmp, ec);
    return false;
  }
  return true;
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

bool known_mesh_extension(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".vtu" || ext == ".msh" || ext == ".inp";
}

// Checked before any work (a mesh of minutes must not end in "cannot open" for a folder
// that does not exist): the file's folder exists and can be written to, and the path is
// not a folder itself. Throws std::invalid_argument (exit 2, no usage text).
void check_writable(const std::string& path, const char* option) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw std::invalid_argument(std::string(option) + " '" + path + "' is a folder, not a file");
  const fs::path folder = fs::path(path).parent_path();
  const fs::path where = folder.empty() ? fs::path(".") : folder;
  if (!fs::is_directory(where, ec))
    throw std::invalid_argument(std::string(option) + " '" + path + "': the folder '" +
                                where.string() + "' does not exist");
  if (::access(where.c_str(), W_OK) != 0)
    throw std::invalid_argument(std::string(option) + " '" + path + "': the folder '" +
                                where.string() + "' is not writable");
}

int mesh_command(const std::vector<std::string>& argv) {
  const Args args =
      parse(argv,
            {"-o", "--output", "--size", "--report", "--max-hexes", "--smooth-iterations",
             "--smooth-passes", "--time-limit", "--decomposition-time-limit", "--sharp-angle",
             "--eps", "--delta", "--max-depth", "--schemes", "--fallback-scheme", "--order",
             "--element", "--size-grading"},
            {"--no-smooth", "--no-fallback", "--no-decompose", "--keep-invalid", "--quiet"},
            {"--size-at"});
  if (args.positional.size() != 1)
    throw UsageError("expected exactly one input file, got " +
                     std::to_string(args.positional.size()));
  std::string out_path;
  if (args.values.count("-o")) out_path = args.values.at("-o");
  if (args.values.count("--output")) out_path = args.values.at("--output");
  if (out_path.empty()) throw UsageError("missing -o OUT (the mesh file to write)");
  if (!known_mesh_extension(out_path))
    throw UsageError("cannot write '" + out_path + "': use a .vtu, .msh or .inp file name");
  check_writable(out_path, "-o");
  if (args.values.count("--report")) check_writable(args.values.at("--report"), "--report");

  pipeline::MeshOptions options;
  if (args.values.count("--size"))
    options.size = parse_positive("--size", args.values.at("--size"));
  if (args.repeated.count("--size-at"))
    for (const std::string& text : args.repeated.at("--size-at"))
      for (core::LocalSize& l : parse_size_at(text)) options.local_sizes.push_back(std::move(l));
  if (args.values.count("--size-grading"))
    options.size_grading = parse_positive("--size-grading", args.values.at("--size-grading"));
  if (args.values.count("--max-hexes"))
    options.max_hexes = parse_count("--max-hexes", args.values.at("--max-hexes"));
  if (args.values.count("--smooth-iterations"))
    options.smoothing.laplacian_iterations =
        parse_count_or_zero("--smooth-iterations", args.values.at("--smooth-iterations"));
  if (args.values.count("--smooth-passes"))
    options.smoothing.optimisation_passes =
        parse_count_or_zero("--smooth-passes", args.values.at("--smooth-passes"));
  if (args.flags.count("--no-smooth"))
    options.smoothing.laplacian_iterations = options.smoothing.optimisation_passes = 0;
  options.fallback = args.flags.count("--no-fallback") == 0;
  options.decompose = args.flags.count("--no-decompose") == 0;
  if (args.values.count("--fallback-scheme")) {
    options.fallback_scheme = args.values.at("--fallback-scheme");
    if (options.fallback_scheme != "grid" && options.fallback_scheme != "tet-split")
      throw UsageError("--fallback-scheme must be grid or tet-split, got '" +
                       options.fallback_scheme + "'");
  }
  if (args.values.count("--decomposition-time-limit"))
    options.decomposition_time_limit =
        parse_positive("--decomposition-time-limit", args.values.at("--decomposition-time-limit"));
  if (args.values.count("--time-limit"))
    options.time_limit = parse_positive("--time-limit", args.values.at("--time-limit"));
  if (args.values.count("--sharp-angle"))
    options.sharp_angle = parse_positive("--sharp-angle", args.values.at("--sharp-angle"));
  if (args.values.count("--eps"))
    options.graph.eps = parse_positive("--eps", args.values.at("--eps"));
  if (args.values.count("--delta"))
    options.graph.delta = parse_positive("--delta", args.values.at("--delta"));
  if (args.values.count("--max-depth"))
    options.graph.max_depth =
        int(std::min<std::size_t>(parse_count("--max-depth", args.values.at("--max-depth")), 1000));
  if (args.values.count("--schemes")) {
    options.schemes.clear();
    std::string list = args.values.at("--schemes");
    for (std::size_t start = 0; start <= list.size();) {
      const std::size_t comma = std::min(list.find(',', start), list.size());
      const std::string name = list.substr(start, comma - start);
      if (name.empty()) throw UsageError("--schemes has an empty name in '" + list + "'");
      options.schemes.push_back(name);
      start = comma + 1;
    }
  }
  if (args.values.count("--order")) {
    const std::string& text = args.values.at("--order");
    if (text != "1" && text != "2")
      throw UsageError("--order must be 1 (8-node hexahedra) or 2 (20-node), got '" + text + "'");
    options.order = text == "1" ? 1 : 2;
  }
  io::ElementChoiceOptions element_options;
  if (args.values.count("--element")) {
    element_options.requested = args.values.at("--element");
    const auto type = io::parse_element_type(element_options.requested);
    if (!type)
      throw UsageError("unknown element type '" + element_options.requested +
                       "' (use C3D8, C3D8I, C3D8R, C3D20 or C3D20R)");
    if (io::element_order(*type) != options.order)
      throw UsageError(std::string(io::element_type_name(*type)) + " is a " +
                       (io::element_order(*type) == 1 ? "first" : "second") +
                       "-order element; it needs --order " +
                       std::to_string(io::element_order(*type)));
    if (lower_extension(out_path) != ".inp")
      throw UsageError("--element sets the element type of an .inp file, not of '" + out_path +
                       "'");
  }
  options.validate();  // before reading the file: a bad combination is a usage error
  const bool quiet = args.flags.count("--quiet") > 0;

  const auto t0 = std::chrono::steady_clock::now();
  occ::ReadOptions read_options;
  read_options.several_solids = true;  // glued at common faces, meshed as one
  occ::ReadResult read = occ::read_solid(args.positional[0], read_options);
  if (!read.ok()) {
    print_diagnostics(read.diagnostics);
    if (args.values.count("--report")) {
      nlohmann::json j = input_error_json(args.positional[0], read.diagnostics);
      j["output"] = "";
      std::string error;
      if (!write_json(j, args.values.at("--report"), &error))
        std::cerr << "vorohex: " << error << "\n";
    }
    return kExitBadInput;
  }
  const core::Progress progress = progress_printer(quiet);
  pipeline::MeshResult result = pipeline::generate_mesh(*read.solid, options, progress);

  std::vector<core::Diagnostic> all = read.diagnostics;
  all.insert(all.end(), result.diagnostics.begin(), result.diagnostics.end());
  const bool meshed = result.mesh.num_hexes() > 0;
  if (meshed) {
    // Intervals per direction only where a scheme has three (a block or a sweep; a
    // multisweep or revolve gives its layers, several sub-volumes none).
    const auto& n = result.stats.intervals;
    std::cout << "mesh of " << args.positional[0] << " (scheme " << result.stats.scheme << ", size "
              << result.stats.size_used;
    if (n[0] > 0 && n[1] > 0)
      std::cout << ", intervals " << n[0] << " x " << n[1] << " x " << n[2];
    else if (n[2] > 0)
      std::cout << ", " << n[2] << " layers";
    std::cout << ")\n";
    if (!result.stats.local_sizes.empty()) {
      std::cout << "local sizes         ";
      for (const core::LocalSize& l : result.stats.local_sizes)
        std::cout << " " << l.entity << " " << l.size;
      std::cout << " (grading " << options.size_grading << ")\n";
    }
    std::cout << "before smoothing     min " << result.stats.min_sj_before_smoothing << "  mean "
              << result.stats.mean_sj_before_smoothing << "\n";
    // The check's warnings and errors are among the result's, printed below with the others
    // (some with more said: every edge a boundary quad spans): not twice.
    quality::CheckReport check = result.check;
    check.diagnostics.erase(std::remove_if(check.diagnostics.begin(), check.diagnostics.end(),
                                           [](const core::Diagnostic& d) {
                                             return d.severity != core::Severity::info;
                                           }),
                            check.diagnostics.end());
    print_check_report(std::cout, check);
    std::vector<core::Diagnostic> notable;  // warnings and errors (the fallback, ...)
    for (const core::Diagnostic& d : all)
      if (d.severity != core::Severity::info) notable.push_back(d);
    print_diagnostics(notable);
  } else {
    print_diagnostics(all);
  }

  if (meshed) print_groups(std::cout, result.groups);
  bool written = false;
  double seconds_writing = 0;
  std::string element_name;
  if (meshed && (result.ok || args.flags.count("--keep-invalid"))) {
    const auto tw = std::chrono::steady_clock::now();
    if (!quiet) progress.report("write", 0.0);
    io::WriteOptions write_options;
    write_options.scaled_jacobian = result.scaled_jacobian;
    write_options.groups = result.groups;
    if (lower_extension(out_path) == ".inp") {
      const io::ElementChoice choice =
          io::choose_element_type(result.mesh, result.scaled_jacobian, element_options);
      print_diagnostics(choice.diagnostics);
      all.insert(all.end(), choice.diagnostics.begin(), choice.diagnostics.end());
      if (!choice.ok) {
        std::cerr << "vorohex: nothing written\n";
        return kExitBadInput;
      }
      write_options.element = choice.type;
      element_name = io::element_type_name(choice.type);
      std::cout << "element " << element_name << "\n";
    }
    std::string error;
    if (!write_atomically(result.mesh, out_path, write_options, &error)) {
      std::cerr << "vorohex: " << error << "\n";
      return kExitBadInput;
    }
    if (!quiet) progress.report("write", 1.0);
    seconds_writing = std::chrono::duration<double>(std::chrono::steady_clock::now() - tw).count();
    written = true;
    std::cout << "wrote " << out_path << "\n";
  } else if (meshed) {
    std::cerr << "vorohex: the mesh is invalid; nothing written (use --keep-invalid to write it)\n";
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (args.values.count("--report")) {
    nlohmann::json j;
    j["input"] = args.positional[0];
    j["output"] = written ? out_path : "";
    j["ok"] = result.ok;
    j["scheme"] = result.stats.scheme;
    j["size"] = result.stats.size_used;
    j["size_grading"] = options.size_grading;
    j["local_sizes"] = nlohmann::json::object();
    for (const core::LocalSize& l : result.stats.local_sizes) j["local_sizes"][l.entity] = l.size;
    j["intervals"] = result.stats.intervals;
    j["sub_volumes"] = result.stats.sub_volumes;
    j["order"] = options.order;
    // The Abaqus element type written to an INP file; null for the other formats (VTU and
    // Gmsh's write VTK's and Gmsh's own hexahedra of the order asked).
    if (element_name.empty())
      j["element"] = nullptr;
    else
      j["element"] = element_name;
    j["groups"] = groups_json(result.groups);
    j["sub_volume_schemes"] = result.stats.sub_volume_schemes;
    j["sub_volume_types"] = result.stats.sub_volume_types;
    if (!result.absorbed.empty()) {  // the grid mesher's composites (grid/composites.h)
      nlohmann::json a;
      a["entities"] = nlohmann::json::array();
      for (const core::Diagnostic& d : result.diagnostics)
        if (d.code == "features_absorbed") a["entities"] = d.entities;
      a["composites"] = nlohmann::json::array();
      for (const grid::Composite& c : result.absorbed.composites)
        a["composites"].push_back(c.name());
      a["max_deviation"] = result.stats.absorbed_deviation;
      j["absorbed"] = a;
    }
    j["decomposition"] = {{"decompose", options.decompose},
                          {"sharp_angle", options.sharp_angle},
                          {"eps", options.graph.eps},
                          {"delta", options.graph.delta},
                          {"max_depth", options.graph.max_depth}};
    j["smoothing"] = {{"laplacian_iterations", options.smoothing.laplacian_iterations},
                      {"optimisation_passes", options.smoothing.optimisation_passes},
                      {"min_scaled_jacobian_before", result.stats.min_sj_before_smoothing},
                      {"mean_scaled_jacobian_before", result.stats.mean_sj_before_smoothing}};
    j["seconds"] = {{"meshing", result.stats.seconds_meshing},
                    {"smoothing", result.stats.seconds_smoothing},
                    {"checking", result.stats.seconds_checking},
                    {"writing", seconds_writing},
                    {"total", total}};
    j["fallback_beside"] = result.stats.fallback_beside;
    if (meshed) j["check"] = check_report_json(result.check);
    j["diagnostics"] = diagnostics_json(all);
    std::string error;
    if (!write_json(j, args.values.at("--report"), &error)) {
      std::cerr << "vorohex: " << error << "\n";
      return kExitBadInput;
    }
  }
  return result.ok ? kExitOk : kExitInvalid;
}

int check_command(const std::vector<std::string>& argv) {
  const Args args = parse(argv, {"--cad", "--report", "--volume-tol", "--distance-tol"}, {});
  if (args.positional.size() != 1)
    throw UsageError("expected exactly one mesh file, got " +
                     std::to_string(args.positional.size()));
  quality::CheckOptions options;
  if (args.values.count("--volume-tol"))
    options.volume_rel_tol = parse_positive("--volume-tol", args.values.at("--volume-tol"));
  if (args.values.count("--distance-tol"))
    options.distance_rel_tol = parse_positive("--distance-tol", args.values.at("--distance-tol"));

  // A mesh or CAD file that cannot be read: said on stderr and in the report (valid false).
  auto refused = [&](const std::string& input, const std::vector<core::Diagnostic>& why) {
    print_diagnostics(why);
    if (args.values.count("--report")) {
      std::string error;
      if (!write_json(input_error_json(input, why, "valid"), args.values.at("--report"), &error))
        std::cerr << "vorohex: " << error << "\n";
    }
    return kExitBadInput;
  };
  io::ReadMeshResult mesh = io::read_mesh(args.positional[0]);
  if (!mesh.ok) return refused(args.positional[0], mesh.diagnostics);
  std::unique_ptr<occ::Solid> cad;
  if (args.values.count("--cad")) {
    occ::ReadOptions read_options;
    read_options.several_solids = true;
    occ::ReadResult read = occ::read_solid(args.values.at("--cad"), read_options);
    if (!read.ok()) return refused(args.values.at("--cad"), read.diagnostics);
    cad = std::move(read.solid);
  }
  const quality::CheckReport report = quality::check_mesh(mesh.mesh, cad.get(), options);
  for (const auto& d : mesh.diagnostics) std::cout << "  " << core::format(d) << "\n";
  std::cout << "check of " << args.positional[0] << "\n";
  print_check_report(std::cout, report);
  if (args.values.count("--report")) {
    nlohmann::json j = check_report_json(report);
    j["input"] = args.positional[0];
    std::string error;
    if (!write_json(j, args.values.at("--report"), &error)) {
      std::cerr << "vorohex: " << error << "\n";
      return kExitBadInput;
    }
  }
  return report.valid ? kExitOk : kExitInvalid;
}

// Runs a command, turning usage errors and option validation into exit code 2.
template <class F>
int guarded(F&& f, const std::vector<std::string>& args, const char* usage) {
  try {
    return f(args);
  } catch (const UsageError& e) {
    std::cerr << "vorohex: " << e.what() << "\n" << usage_hint(usage);
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "vorohex: " << e.what() << "\n";
    return kExitBadInput;
  }
}

}  // namespace

int run_mesh(const std::vector<std::string>& args) {
  return guarded(mesh_command, args, kMeshUsage);
}
int run_check(const std::vector<std::string>& args) {
  return guarded(check_command, args, kCheckUsage);
}

}  // namespace vorohex::cli
