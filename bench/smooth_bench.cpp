// Throughput of smooth_mesh on a perturbed mapped box: hexes x Laplacian sweeps per second,
// and the time of the whole smoothing (Laplacian + untangling + optimisation).
//
//   smooth_bench [--cells N] [--sweeps K] [--amplitude A] [--seed S]
// meshes the unit cube with N^3 hexes (default 100: 1M), moves every non-vertex node by up
// to A times the cell size along its entity, then times K sweeps.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include "mesh/map_block.h"
#include "occ/primitives.h"
#include "quality/check_mesh.h"
#include "quality/scaled_jacobian.h"
#include "smooth/smooth_mesh.h"

namespace {

using namespace vorohex;
using core::Vec3;

void perturb(core::HexMesh& m, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    const core::NodeId id(static_cast<std::int32_t>(i));
    Vec3 p = m.point(id);
    const core::NodeClass c = m.node_class(id);
    if (c.dim == 0) continue;
    // On the unit cube a coordinate at 0 or 1 is pinned by the face it lies on.
    for (int k = 0; k < 3; ++k)
      if (p[k] > 1e-12 && p[k] < 1 - 1e-12) p[k] += u(rng);
    m.set_point(id, p);
  }
}

std::size_t inverted(const core::HexMesh& m) {
  std::size_t n = 0;
  for (double v : quality::scaled_jacobians(m)) n += v <= 0;
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  int cells = 100, sweeps = 10;
  double amplitude = 0.2;
  unsigned seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--cells")
      cells = std::atoi(argv[i + 1]);
    else if (a == "--sweeps")
      sweeps = std::atoi(argv[i + 1]);
    else if (a == "--amplitude")
      amplitude = std::atof(argv[i + 1]);
    else if (a == "--seed")
      seed = static_cast<unsigned>(std::atoi(argv[i + 1]));
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  const occ::Solid box = occ::make_box(1, 1, 1);
  mesh::MapBlockOptions mo;
  mo.size = 1.0 / cells;
  mesh::MapBlockResult mapped = mesh::map_block(box, mo);
  if (!mapped.ok) return 1;
  core::HexMesh base = std::move(mapped.mesh);
  perturb(base, amplitude / cells, seed);
  std::printf("mesh: %zu hexes, %zu nodes, perturbation %.2f x cell size, %zu inverted\n",
              base.num_hexes(), base.num_nodes(), amplitude, inverted(base));

  // Laplacian phase alone: tolerance 0 so no node counts as converged.
  core::HexMesh m = base;
  smooth::SmoothOptions lo;
  lo.laplacian_iterations = sweeps;
  lo.optimisation_passes = 0;
  lo.tolerance = 0;
  const smooth::SmoothResult lr = smooth::smooth_mesh(m, box, lo);
  const double throughput = double(m.num_hexes()) * lr.laplacian_sweeps / lr.seconds_laplacian;
  std::printf(
      "laplacian: %d sweeps in %.3f s (total with set-up and stats %.3f s): "
      "%.3g hex-sweeps/s, %zu moves; min SJ %.4f -> %.4f, mean %.4f -> %.4f\n",
      lr.laplacian_sweeps, lr.seconds_laplacian, lr.seconds, throughput, lr.laplacian_moves,
      lr.min_before, lr.min_after, lr.mean_before, lr.mean_after);

  // Default options end to end.
  core::HexMesh f = base;
  const smooth::SmoothResult fr = smooth::smooth_mesh(f, box, smooth::SmoothOptions{});
  std::printf(
      "default options: %s in %.3f s (laplacian %d sweeps %.3f s, optimisation %.3f s, "
      "%zu steps); min SJ %.4f -> %.4f, mean %.4f -> %.4f, inverted %zu -> %zu\n",
      smooth::status_name(fr.status), fr.seconds, fr.laplacian_sweeps, fr.seconds_laplacian,
      fr.seconds_optimisation, fr.optimisation_moves, fr.min_before, fr.min_after, fr.mean_before,
      fr.mean_after, fr.inverted_before, fr.inverted_after);
  quality::CheckOptions co;
  co.distance_rel_tol = 1e-7;
  const quality::CheckReport check = quality::check_mesh(f, &box, co);
  std::printf("check_mesh: %s, max boundary distance %.2g x diagonal\n",
              check.valid ? "valid" : "INVALID", check.max_boundary_distance_rel);
  return check.valid ? 0 : 1;
}
