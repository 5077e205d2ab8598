#include "mesh/detail/sub_volume_part.h"

namespace vorohex::mesh::detail {

ReversedSweep reversed(const Part& p) {
  ReversedSweep r;
  for (core::FaceId f : p.solid.faces())
    if (f != p.sweep.target) r.avoid_sources.push_back(f.value());
  r.sweep = sweep_structure(p.solid, r.avoid_sources, p.imprinted);
  r.ok = r.sweep.source == p.sweep.target;
  return r;
}

void take(Part& p, ReversedSweep r) {
  p.sweep = std::move(r.sweep);
  p.avoid_sources = std::move(r.avoid_sources);
}

bool free_face(const occ::Solid& s, core::FaceId f) {
  const auto wires = s.face_wires(f);
  return wires.size() != 1 || wires[0].size() != 4;
}

}  // namespace vorohex::mesh::detail
