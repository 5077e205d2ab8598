// Revolved sweeps of solids of revolution (turned parts: shafts, pulleys, flanges, rings;
// occ/revolution.h): the meridian section is meshed with conforming quads (face_set.h) and
// turned about the axis in sectors (their number from the size, a multiple of four). Where
// the section lies along the axis, a coaxial core is cut out of it and swept along the axis
// from an O-grid disc (a square of m x m quads and four blocks to the circle), whose rim
// nodes are the revolved nodes at the core's radius: no hexahedron degenerates on the axis.
#pragma once

#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/progress.h"
#include "core/size_field.h"
#include "occ/solid.h"

namespace vorohex::mesh {

struct RevolveOptions {
  double size = 1.0;           // target edge length, model units (> 0)
  int max_intervals = 100000;  // per edge and for the sectors (> 0)
  int smoothing_passes = 30;   // of section faces meshed by the general quad mesher (>= 0)
  // Local sizes (null or uniform: `size` everywhere): the section is graded where the field
  // asks at any angle; the sectors take the finest count any section node asks for. Not owned.
  const core::SizeField* size_field = nullptr;
  // Meshed beside neighbours (mesh_sub_volumes): the sectors' count (0: from the size; else a
  // multiple of 4, at least 8), a point off the axis the first sector's half-plane passes
  // through (a vertex of a circle a neighbour shares: it meshes that circle from there), and
  // per solid edge id (entry 0 unused; 0 or missing: free) the counts of meridian edges (a
  // seam a neighbour shares).
  int sectors = 0;
  bool has_start = false;
  core::Vec3 start = core::Vec3::Zero();
  std::vector<int> edge_intervals;
  // Per solid edge id (entry 0 unused; empty: free): a meridian edge's nodes as a neighbour
  // meshed before placed them, first to last vertex (its count and positions are kept).
  std::vector<std::vector<core::Vec3>> edge_nodes;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct RevolveApplicability {
  bool ok = false;
  std::string reason;  // why not, naming the face or edge
  core::Vec3 origin = core::Vec3::Zero(), axis = core::Vec3::UnitZ();
  int cores = 0;  // coaxial cores (where the section lies on the axis)
};

RevolveApplicability revolve_applicable(const core::MeshDomain& solid);

struct RevolveEstimate {
  int sectors = 0;
  std::size_t nodes = 0, hexes = 0;  // exactly what revolve() produces (0 when refused)
};
RevolveEstimate revolve_evaluate(const core::MeshDomain& solid, const RevolveOptions& options);

struct RevolveResult {
  core::HexMesh mesh;
  core::Vec3 origin = core::Vec3::Zero(), axis = core::Vec3::UnitZ();
  int sectors = 0, cores = 0;
  double core_radius = 0;
  double section_min_quality = 0, section_mean_quality = 0;  // 2-D quad scaled Jacobian
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
};

// Errors: not_applicable (with the reason), intervals_infeasible, quad_face_failed,
// too_many_intervals, inverted_elements, cancelled.
RevolveResult revolve(const core::MeshDomain& solid, const RevolveOptions& options,
                      const core::Progress& progress = {});

}  // namespace vorohex::mesh
