// The `vorohex` command: mesh CAD solids into all-hex meshes and check hex meshes.
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cli/commands.h"

namespace {

const char* const kUsage =
    "vorohex " VOROHEX_VERSION
    " - all-hexahedral meshing of CAD solids\n"
    "\n"
    "usage: vorohex <command> [options]\n"
    "  mesh IN -o OUT [--size H] [--report R.json]   mesh a STEP/BREP/IGES solid\n"
    "  check MESH [--cad IN] [--report R.json]       validity and quality of a hex mesh\n"
    "  voronoi IN -o GRAPH.json [--vtp G.vtp]        the embedded Voronoi graph of a solid\n"
    "  decompose IN -o PARTS.brep [--report D.json]  its sub-volumes (sweep/map/...)\n"
    "  --help, -h                                    this text; `vorohex <command> --help`\n"
    "  --version                                     the version\n";

}  // namespace

int main(int argc, char** argv) {
  using namespace vorohex::cli;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    std::cerr << kUsage;
    return kExitBadInput;
  }
  const std::string command = args[0];
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  const bool help = rest.size() == 1 && (rest[0] == "--help" || rest[0] == "-h");
  try {
    if (command == "--help" || command == "-h" || command == "help") {
      std::cout << kUsage;
      return kExitOk;
    }
    if (command == "--version") {
      std::cout << "vorohex " VOROHEX_VERSION "\n";
      return kExitOk;
    }
    if (command == "mesh") {
      if (help) return std::cout << kMeshUsage, kExitOk;
      return run_mesh(rest);
    }
    if (command == "check") {
      if (help) return std::cout << kCheckUsage, kExitOk;
      return run_check(rest);
    }
    if (command == "voronoi") {
      if (help) return std::cout << kVoronoiUsage, kExitOk;
      return run_voronoi(rest);
    }
    if (command == "decompose") {
      if (help) return std::cout << kDecomposeUsage, kExitOk;
      return run_decompose(rest);
    }
    std::cerr << "vorohex: unknown command '" << command << "'\n" << kUsage;
    return kExitBadInput;
  } catch (const std::exception& e) {
    // An unexpected failure is still reported, never a silent crash.
    std::cerr << "vorohex: internal error: " << e.what() << "\n";
    return 3;
  }
}
