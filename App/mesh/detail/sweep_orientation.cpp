#include "mesh/detail/sweep_orientation.h"

#include <algorithm>

namespace vorohex::mesh::detail {

void orient_sweeps(std::vector<Part>& parts) {
  const int n = int(parts.size());
  // Two sweeps meeting at a face mesh it alike only when both take it as source (each
  // meshes its source; a target gets the projection of the far end). Where one has that
  // face as its source although it avoids shared faces (its other end cannot be a source),
  // the neighbour takes it as its source too, when it can.
  for (int k = 0; k < n; ++k) {
    const Part& a = parts[k];
    if (!a.is_sweep()) continue;
    const int face = a.whole_face[a.sweep.source.value()];
    if (std::find(a.shared_faces.begin(), a.shared_faces.end(), a.sweep.source.value()) ==
        a.shared_faces.end())
      continue;
    for (int j = 0; j < n; ++j) {
      Part& b = parts[j];
      if (j == k || !b.is_sweep() || b.whole_face[b.sweep.target.value()] != face) continue;
      if (ReversedSweep r = reversed(b); r.ok) take(b, std::move(r));
    }
  }

  // Two sweeps whose targets are one shared face meshed freely (not four-sided: a hole in
  // it) each put the far end's nodes there, which do not match: both take it as their
  // source instead, when both can (a countersunk hole's block and slab, cut where the cone
  // meets the cylinder: both swept towards the cut).
  for (int k = 0; k < n; ++k)
    for (int j = k + 1; j < n; ++j) {
      Part &a = parts[k], &b = parts[j];
      if (!a.is_sweep() || !b.is_sweep() ||
          a.whole_face[a.sweep.target.value()] != b.whole_face[b.sweep.target.value()] ||
          !free_face(a.solid, a.sweep.target))
        continue;
      ReversedSweep ra = reversed(a), rb = reversed(b);
      if (!ra.ok || !rb.ok) continue;
      take(a, std::move(ra));
      take(b, std::move(rb));
    }

  // Sweeps meeting two by two at faces meshed freely, in a row or a ring, where two still
  // have one such face as their target (the strips around a pocket's floor fillets, ended by
  // mitre planes at its corners: a ring of four): from one of them on, each after it takes
  // the face it shares with the one before as its source, so that every face is meshed once
  // and carried on (a ring's last target is its first source: given to it, below).
  {
    auto face = [&](const Part& p, core::FaceId f) { return p.whole_face[f.value()]; };
    std::vector<char> done(n, 0);
    for (int k = 0; k < n; ++k) {
      if (!parts[k].is_sweep() || done[k] || !free_face(parts[k].solid, parts[k].sweep.target))
        continue;
      bool twice = false;
      for (int j = 0; j < n && !twice; ++j)
        twice = j != k && parts[j].is_sweep() &&
                face(parts[j], parts[j].sweep.target) == face(parts[k], parts[k].sweep.target);
      if (!twice) continue;
      done[k] = 1;
      for (int cur = k;;) {
        const int shared = face(parts[cur], parts[cur].sweep.target);
        if (!free_face(parts[cur].solid, parts[cur].sweep.target)) break;
        int next = -1;
        for (int j = 0; j < n && next < 0; ++j)
          if (!done[j] && parts[j].is_sweep() &&
              (face(parts[j], parts[j].sweep.target) == shared ||
               face(parts[j], parts[j].sweep.source) == shared))
            next = j;
        if (next < 0) break;
        if (face(parts[next], parts[next].sweep.source) != shared) {
          ReversedSweep r = reversed(parts[next]);
          if (!r.ok) break;
          take(parts[next], std::move(r));
        }
        done[next] = 1;
        cur = next;
      }
    }
  }

  // A sweep whose target is a face a multisweep shares, meshed freely: the multisweep meshes
  // that face as a cap, the sweep would put the far end's nodes there; it takes the face as
  // its source instead, when it can (a pocket with drafted walls cut at its floor: the slab
  // with the tapered hole above the block).
  for (Part& b : parts) {
    if (!b.is_sweep() || !free_face(b.solid, b.sweep.target)) continue;
    const int face = b.whole_face[b.sweep.target.value()];
    bool with_multisweep = false;
    for (const Part& a : parts)
      if (a.multisweep)
        for (std::size_t f = 1; f < a.whole_face.size(); ++f)
          with_multisweep = with_multisweep || a.whole_face[f] == face;
    if (!with_multisweep) continue;
    if (ReversedSweep r = reversed(b); r.ok) take(b, std::move(r));
  }
}

}  // namespace vorohex::mesh::detail
