// The mesher's decomposition keeps to its time: a step that does not return in its share is
// stopped there, and the fallback's mesh, made beside it, is taken.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "fixtures/diagnostics.h"
#include "occ/primitives.h"
#include "occ/shape_io.h"
#include "occ/split_solid.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline {
namespace {

// A block with two crossing through-holes of one radius (bench/run_parts.py's): no scheme
// takes it whole, it has no concave edge to cut at, so the mesher tries its Voronoi graph's
// decomposition, which gets a tenth of the decomposition's 60 s; OCCT's split of its 213
// decomposition faces does not return within it. On the block with its top edges filleted
// (block_top_fillets.step, now cut at the fillets' feet and mapped), that split returned only
// after about 34 s, and the child running it was stopped at the whole 60 s limit: the grid
// mesh, made beside it in 2 s, waited 47 s. Now the decomposition ends within the Voronoi
// step's 6 s and their grace: stopped by the parent where the split runs on past them, or by its
// own deadline where the split is interrupted in time (which of the two depends on where OCCT is
// when the 6 s run out: on a loaded machine the split stopped itself). Either way the message
// names the 6 s, never the whole limit. (The block with its top and vertical edges filleted
// served here until its corners were parted: it is meshed structured now.)
TEST(GenerateMesh, AVoronoiSplitThatDoesNotReturnIsStoppedAtItsShareOfTheTime) {
  const std::unique_ptr<occ::Solid> one =
      occ::cut_solids(occ::make_box(20, 20, 20), occ::make_cylinder(4, 20, {10, 0, 10}, {0, 1, 0}));
  ASSERT_NE(one, nullptr);
  const std::unique_ptr<occ::Solid> block =
      occ::cut_solids(*one, occ::make_cylinder(4, 20, {0, 10, 10}, {1, 0, 0}));
  ASSERT_NE(block, nullptr);
  const occ::Solid* in_solid = block.get();
  const MeshResult r = generate_mesh(*in_solid, MeshOptions{});
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
  EXPECT_EQ(r.stats.scheme, "grid");
  EXPECT_TRUE(r.check.valid);
  const core::Diagnostic* d = testing::find_diagnostic(r.diagnostics, "fallback");
  ASSERT_NE(d, nullptr);
  const std::string& m = d->message;
  EXPECT_NE(m.find("cutting along the faces at its concave edges did not give sub-volumes that "
                   "all have a scheme"),
            std::string::npos)
      << m;
  const bool stopped_by_the_parent =
      m.find(
          "its Voronoi decomposition did not stop within its 6.0 s (OCCT's split did not "
          "return) and was stopped 2.0 s after it") != std::string::npos;
  const bool stopped_itself = m.find("within 6 s)") != std::string::npos;
  EXPECT_TRUE(stopped_by_the_parent || stopped_itself) << m;
  EXPECT_EQ(m.find("within 60"), std::string::npos) << m;
}

}  // namespace
}  // namespace vorohex::pipeline
