// One sub-volume of a decomposition as mesh_sub_volumes plans it: its solid, the structure of
// its scheme and its entities' ids among all the glued pieces'; and the way its sweep can
// be turned round.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "core/geometry.h"
#include "mesh/sweep.h"
#include "occ/prismatic.h"
#include "occ/solid.h"

namespace vorohex::mesh::detail {

struct Part {
  explicit Part(occ::Solid s) : solid(std::move(s)) {}
  occ::Solid solid;
  std::array<std::vector<core::EdgeId>, 3> block;  // non-empty: mapped block
  SweepStructure sweep;                            // else: sweep
  bool multisweep = false;                         // else: a multisweep (prismatic part)
  bool revolve = false;                            // else: a solid of revolution
  core::Vec3 origin = core::Vec3::Zero(), axis = core::Vec3::UnitZ();  // its axis
  std::vector<double> turns;  // by part edge id: detail::turns_about_axis (a revolve's)
  std::shared_ptr<const occ::PrismaticStructure> prismatic;  // its structure
  std::vector<bool> shared_edge;   // by part edge id: a neighbour has it too
  std::vector<int> shared_faces;   // part face ids shared with a neighbour
  std::vector<int> avoid_sources;  // part face ids its sweep avoids as source
  bool imprinted = false;          // its sweep's linking sides may carry imprints (sweep.h)
  std::vector<int> whole_face;     // by part face id
  std::vector<int> whole_edge;     // by part edge id
  bool is_block() const { return !block[0].empty(); }
  bool is_sweep() const { return !is_block() && sweep.source.valid(); }
  bool has_scheme() const { return is_block() || sweep.source.valid() || multisweep || revolve; }
  const char* scheme() const {
    return is_block() ? "map" : is_sweep() ? "sweep" : revolve ? "revolve" : "multisweep";
  }
};

// The sweep of `p` the other way: its target taken as source, every other face avoided as one
// (sweep_structure); `ok` where its structure allows that.
struct ReversedSweep {
  bool ok = false;
  SweepStructure sweep;
  std::vector<int> avoid_sources;
};
ReversedSweep reversed(const Part& p);
void take(Part& p, ReversedSweep r);

// A face the quad mesher meshes freely (not one loop of four edges: a hole in it).
bool free_face(const occ::Solid& s, core::FaceId f);

}  // namespace vorohex::mesh::detail
