// The grid mesher alone on one solid, called directly (grid::grid_mesh with its own
// optimisation, not the pipeline's smoothing): its diagnostics, the check's verdict and the
// seconds of each stage (core, pillow, features, optimisation), with the local refinement's
// levels as an argument. (bench/run_grid.py measures the pipeline's grid scheme on every
// HexMe model: `vorohex mesh --schemes grid --no-decompose`.)
//
//   cmake --build build --target grid_bench
//   build/bench/grid_bench MODEL.step [SIZE [MAX_LEVELS [OUT.vtu]]]
// SIZE: default diagonal / 20; MAX_LEVELS: GridOptions::max_levels (default 2; 0 = the
// uniform grid only).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "grid/grid_mesh.h"
#include "io/mesh_io.h"
#include "occ/shape_io.h"
#include "quality/check_mesh.h"

int main(int argc, char** argv) {
  using namespace vorohex;
  if (argc < 2) {
    std::fprintf(stderr, "usage: grid_bench MODEL.step [SIZE [MAX_LEVELS [OUT.vtu]]]\n");
    return 2;
  }
  occ::ReadResult read = occ::read_solid(argv[1]);
  if (!read.ok()) {
    std::fprintf(stderr, "cannot read %s\n", argv[1]);
    return 2;
  }
  const occ::Solid& solid = *read.solid;
  grid::GridOptions o;
  o.size = argc > 2 && std::atof(argv[2]) > 0 ? std::atof(argv[2]) : solid.diagonal() / 20;
  if (argc > 3) o.max_levels = std::atoi(argv[3]);
  const auto t0 = std::chrono::steady_clock::now();
  const grid::GridResult g = grid::grid_mesh(solid, o);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const core::Diagnostic& d : g.diagnostics)
    std::printf("%s: %s\n", d.code.c_str(), d.message.c_str());
  const quality::CheckReport c = quality::check_mesh(g.mesh, &solid);
  std::printf(
      "ok %d, valid %d: %zu hexahedra, min SJ %.3f, %zu inverted, volume error %.2e; %.1f s "
      "(core %.1f, pillow %.1f, features %.1f, optimisation %.1f); %zu features missed\n",
      int(g.ok), int(c.valid), g.mesh.num_hexes(), c.scaled_jacobian.min, c.non_positive,
      c.volume_rel_error, seconds, g.stats.seconds_core, g.stats.seconds_pillow,
      g.stats.seconds_features, g.stats.seconds_optimisation, g.stats.features_missed);
  for (const core::Diagnostic& d : c.diagnostics)
    std::printf("  check %s: %s\n", d.code.c_str(), d.message.c_str());
  std::string error;
  if (argc > 4 && !io::write_mesh(g.mesh, argv[4], {}, &error))
    std::fprintf(stderr, "cannot write %s: %s\n", argv[4], error.c_str());
  return c.valid ? 0 : 1;
}
