// Features smaller than the size, absorbed into composite faces of a virtual topology
// (issue 23, item 5; the paper's §6 overlay): the grid mesher does not resolve engravings,
// tiny edges or sliver faces; it meshes the composite they form with a neighbouring face, with
// each node on the nearest of the composite's real faces, and reports how far its boundary
// strays from the real surface. The solid itself is never modified.
#pragma once

#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "core/hex_mesh.h"
#include "core/mesh_domain.h"
#include "occ/tessellate.h"

namespace vorohex::grid {

// One composite face: a host (a face the mesh resolves) and the absorbed faces attached to
// it through absorbed edges. Its edges inside (between its faces) get no chain of mesh edges.
struct Composite {
  core::FaceId host;
  std::vector<core::FaceId> faces;  // host first, then the absorbed faces
  std::string name() const;         // "Face3+Face12+Face13"
  std::string summary() const;      // name(), or "Face3 with 60 absorbed faces" when long
};

struct SmallFeatures {
  // By id value (index 0 unused). A face is absorbed when it is a sliver (narrower than
  // `small`: twice its area over its perimeter) or enclosed: all its edges absorbed and every
  // point of it within the size of its neighbours across them (the floor of an engraving).
  // An edge is absorbed when shorter than `small` or on an absorbed face.
  std::vector<char> absorbed_face, absorbed_edge;
  std::vector<int> composite_of_face;  // index into composites, -1 when in none
  std::vector<Composite> composites;
  double small = 0;  // a quarter of the size
  // Points of the absorbed faces (on their triangulation, a quarter of the size apart): the real
  // surface the deviation is measured from, besides the mesh's side.
  std::vector<core::Vec3> samples;
  std::vector<core::BoundingBox> face_boxes;  // of the composites' faces, by id value
  bool empty() const { return composites.empty(); }
  // The nearest point of face f's composite (of f itself when in none) to p; `face`
  // receives the face it lies on.
  core::Vec3 project(const core::MeshDomain& solid, core::FaceId f, const core::Vec3& p,
                     core::FaceId& face) const;
  // Whether faces a and b belong to one composite.
  bool same_composite(int a, int b) const;
};

// The absorbed faces and edges of `solid` at this size, grouped into composites: clusters of
// absorbed faces joined across absorbed edges, each attached to the resolved face it shares
// the most absorbed edge length with. `tess` gives the points tested for enclosed faces.
SmallFeatures find_small_features(const core::MeshDomain& solid, const occ::Tessellation& tess,
                                  double size);

struct CompositeDeviation {
  double max = 0;        // model units: the larger of the two directions below
  double mesh_side = 0;  // boundary quads on a composite: farthest point from its faces
  double cad_side = 0;   // points of absorbed faces: farthest from the mesh's boundary
  core::Vec3 where{0, 0, 0};
  std::size_t quads = 0;  // boundary quads on composites
};

// Largest deviation between the mesh's boundary on the composites and their real faces, in
// both directions (sampled: quads at 3 x 3 points and edge midpoints; absorbed faces at
// their samples). Nodes on no composite are not measured here (the check measures them).
CompositeDeviation composite_deviation(const core::HexMesh& mesh, const core::MeshDomain& solid,
                                       const SmallFeatures& features);

// The info `absorbed_deviation`: the composites (their faces as entities) and the number.
core::Diagnostic deviation_diagnostic(const SmallFeatures& features, const CompositeDeviation& d);

}  // namespace vorohex::grid
