// Keyways, as a new user cuts them in PartDesign: parts whose plane cuts give sub-volumes that
// all have a scheme, and whose meshes must match where the sub-volumes meet. Both were the
// grid mesher's (or no valid mesh) because two neighbours meshed a shared face or edge each
// its own way.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "fixtures/diagnostics.h"
#include "occ/shape_io.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline {
namespace {

MeshResult mesh_file(const std::string& name, double size = 0) {
  const occ::ReadResult in =
      occ::read_solid(std::string(VOROHEX_SOURCE_DIR) + "/tests/data/" + name);
  if (!in.ok()) throw std::runtime_error(name + " does not load");
  MeshOptions opt;
  opt.fallback = false;
  opt.size = size;
  return generate_mesh(*in.solid, opt);
}

void expect_structured(const MeshResult& r, double min) {
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.scheme.find("grid"), std::string::npos) << r.stats.scheme;
  EXPECT_GE(r.stats.sub_volumes, 2);
  EXPECT_TRUE(r.check.valid);
  EXPECT_EQ(r.check.open_boundary_edges, 0u);
  EXPECT_EQ(r.check.non_manifold_quads, 0u);
  EXPECT_GE(r.check.scaled_jacobian.min, min);
  EXPECT_NE(testing::find_diagnostic(r.diagnostics, "decomposed"), nullptr);
}

// A shaft (radius 12, 80 long, its ends chamfered 1) with an end-milled keyway: 8 wide, 4 deep,
// round ends of radius 4 (tests/data/keyed_shaft.step, made by bench/run_parts.py). Its
// plane cuts give blocks, sweeps and multisweeps; at size 2.2 a block and a sweep beside the
// keyway's round end each spaced the nodes on the curve where that end meets the shaft by its
// own faces (one part's face has a cusp there, whose end nodes are widened), 0.42 apart: the
// meshes did not match, and the grid mesher's 88,431 hexahedra were the result. The shared
// edges' nodes are now placed once, on the glued sub-volumes.
TEST(Keyways, AShaftsEndMilledKeywayMeshesStructuredAtAFineSize) {
  for (double size : {0.0, 2.2}) {
    SCOPED_TRACE(size);
    const MeshResult r = mesh_file("keyed_shaft.step", size);
    expect_structured(r, 0.4);
    if (size > 0) EXPECT_LE(r.mesh.num_hexes(), 6000u);
  }
}

// A V-belt pulley (a revolved profile: rim, web, hub, bore of radius 8) with a keyway 5 wide
// in its bore (tests/data/vbelt_pulley_keyway.step). Cut at its concave edges, the hub
// beside the keyway is two multisweeps and the material over the keyway a sweep between
// their walls: the sweep's source and target are faces the multisweeps meshed (rows extruded)
// and its own lattice there was smoothed, the same cells 1.2 apart. It takes the
// multisweeps' quads on both ends now, paired by their connectivity. Before: the grid's
// (invalid, 522 hexahedra inverted) and the tet split's (invalid) after 164 s.
TEST(Keyways, APulleysBoreKeywayIsBridgedBetweenItsMultisweeps) {
  const MeshResult r = mesh_file("vbelt_pulley_keyway.step");
  expect_structured(r, 0.4);
  EXPECT_NE(r.stats.scheme.find("multisweep"), std::string::npos) << r.stats.scheme;
}

}  // namespace
}  // namespace vorohex::pipeline
