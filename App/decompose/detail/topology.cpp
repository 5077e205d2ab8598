#include "decompose/detail/topology.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>

#include "model/brep_model.h"
#include "occ/split_solid.h"

namespace vorohex::decompose::detail {

using core::EdgeId;
using core::FaceId;
using core::Vec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The original face a sample lies on, or an invalid id.
FaceId original_face(const occ::Solid& solid, const occ::FaceSample& s, double tol) {
  for (FaceId f : solid.faces()) {
    if (solid.distance_to_face(f, s.point) > tol) continue;
    if (solid.face_normal(f, s.point).dot(s.normal) > 0.5) return f;
  }
  return FaceId();
}

bool boxes_overlap(const core::BoundingBox& a, const core::BoundingBox& b, double tol) {
  for (int k = 0; k < 3; ++k)
    if (a.min[k] > b.max[k] + tol || b.min[k] > a.max[k] + tol) return false;
  return true;
}

// The smallest interior angle of the sub-volumes at the edges of each decomposition face
// (DecompositionFace::min_angle), from the dihedral angles of each sub-volume's edges.
void measure_face_angles(DecompositionResult& r) {
  for (DecompositionFace& df : r.faces) df.min_angle = 180;
  for (std::size_t i = 0; i < r.sub_volumes.size(); ++i) {
    const model::ModelResult m = model::build_model(*r.sub_volumes[i].solid);
    if (!m.ok()) continue;
    for (const VirtualFace& vf : r.topology.faces) {
      if (vf.sub_volume != int(i) || vf.decomposition_face < 0) continue;
      DecompositionFace& df = r.faces[vf.decomposition_face];
      for (EdgeId e : m.model->face(vf.face).edges) {
        const model::ModelEdge& me = m.model->edge(e);
        if (me.faces.size() == 2 && !me.degenerated)
          df.min_angle = std::min(df.min_angle, me.dihedral * 180 / kPi);
      }
    }
  }
}

}  // namespace

// Steps 4-5: virtual topology of the pieces and the merged decomposition faces.
void build_topology(const occ::Solid& solid, double tol, DecompositionResult& r) {
  r.topology.faces.clear();
  r.faces.clear();
  std::vector<std::vector<occ::FaceSample>> samples;
  for (std::size_t i = 0; i < r.sub_volumes.size(); ++i) {
    samples.push_back(occ::sample_faces(*r.sub_volumes[i].solid));
    for (const occ::FaceSample& s : samples.back()) {
      VirtualFace vf;
      vf.sub_volume = int(i);
      vf.face = s.face;
      vf.original = original_face(solid, s, tol);
      vf.num_edges = s.num_edges;
      vf.area = s.area;
      r.topology.faces.push_back(vf);
    }
  }
  // Decomposition faces: pair up the non-original faces of different sub-volumes.
  std::size_t k = 0;
  for (std::size_t i = 0; i < samples.size(); ++i)
    for (std::size_t j = 0; j < samples[i].size(); ++j, ++k) {
      VirtualFace& vf = r.topology.faces[k];
      if (vf.original.valid() || vf.decomposition_face >= 0) continue;
      DecompositionFace df;
      df.sub_volumes = {int(i), -1};
      df.num_edges = vf.num_edges;
      df.area = vf.area;
      df.point = samples[i][j].point;
      vf.decomposition_face = int(r.faces.size());
      std::size_t k2 = 0;
      for (std::size_t i2 = 0; i2 < samples.size(); ++i2)
        for (std::size_t j2 = 0; j2 < samples[i2].size(); ++j2, ++k2) {
          VirtualFace& other = r.topology.faces[k2];
          if (i2 == i || other.original.valid() || other.decomposition_face >= 0) continue;
          if (r.sub_volumes[i2].solid->distance_to_face(other.face, df.point) > tol) continue;
          other.decomposition_face = vf.decomposition_face;
          df.sub_volumes[1] = int(i2);
        }
      for (std::size_t q = 0; q < r.quads.size(); ++q) {
        const auto& pts = r.quads[q].points;
        Vec3 c(0, 0, 0);
        for (const Vec3& p : pts) c += p;
        c /= double(pts.size());
        if (r.sub_volumes[i].solid->distance_to_face(vf.face, c) <= tol) {
          df.quads.push_back(int(q));
          df.elements.push_back(r.quads[q].element);
        }
      }
      std::sort(df.elements.begin(), df.elements.end());
      df.elements.erase(std::unique(df.elements.begin(), df.elements.end()), df.elements.end());
      r.faces.push_back(std::move(df));
    }
  r.stats.decomposition_faces = int(r.faces.size());
}

// Step 5b, once the sub-volumes are final: where every edge of every sub-volume lies.
// Checked at its two ends and its middle: on an original edge if all three are within
// `tol` of it; else in the original face of an adjacent sub-volume face lying on one, or
// of the original face its middle lies on (a sliver touching the boundary along a line).
void build_virtual_edges(const occ::Solid& solid, double tol, DecompositionResult& r) {
  r.topology.edges.clear();
  // Boxes of the original edges and faces (from samples, widened for the chords) to skip
  // the exact distances that cannot succeed.
  auto box_of = [](const std::vector<Vec3>& pts, double margin) {
    core::BoundingBox b;
    b.min = b.max = pts.front();
    for (const Vec3& p : pts) b.min = b.min.cwiseMin(p), b.max = b.max.cwiseMax(p);
    b.min -= Vec3::Constant(margin), b.max += Vec3::Constant(margin);
    return b;
  };
  auto inside = [](const core::BoundingBox& b, const Vec3& p) {
    return (p.array() >= b.min.array()).all() && (p.array() <= b.max.array()).all();
  };
  std::vector<core::BoundingBox> edge_box;
  for (EdgeId e : solid.edges()) {
    const std::vector<Vec3> pts = solid.edge_points_by_length(e, 16);
    edge_box.push_back(
        box_of(pts, tol + 0.05 * (pts.front() - pts.back()).norm() + 0.02 * solid.diagonal()));
  }
  for (std::size_t i = 0; i < r.sub_volumes.size(); ++i) {
    const occ::Solid& piece = *r.sub_volumes[i].solid;
    std::map<int, FaceId> original_of;  // the piece's faces on original faces
    for (const VirtualFace& vf : r.topology.faces)
      if (vf.sub_volume == int(i) && vf.original.valid())
        original_of[vf.face.value()] = vf.original;
    for (EdgeId e : piece.edges()) {
      VirtualEdge ve;
      ve.sub_volume = int(i);
      ve.edge = e;
      const std::vector<Vec3> pts = piece.edge_points_by_length(e, 2);
      const bool point = piece.edge_is_degenerated(e);  // a pole: on a pole, not a seam
      for (EdgeId o : solid.edges()) {
        if (point != solid.edge_is_degenerated(o) || !inside(edge_box[o.value() - 1], pts[1]))
          continue;
        bool on = true;
        for (const Vec3& p : pts) on = on && solid.distance_to_edge(o, p) <= tol;
        if (on) {
          ve.original = o;
          break;
        }
      }
      if (!ve.original.valid()) {
        for (FaceId f : piece.edge_faces(e))
          if (const auto it = original_of.find(f.value()); it != original_of.end())
            ve.original_face = it->second;
        for (FaceId f : solid.faces())
          if (!ve.original_face.valid() && solid.distance_to_face(f, pts[1]) <= tol)
            ve.original_face = f;
      }
      r.topology.edges.push_back(ve);
    }
  }
}

// The invariants of a decomposition (docs/decomposition.md): closed sub-volumes, pairwise
// disjoint, volumes summing to the solid's, every decomposition face a quadrilateral
// between two sub-volumes meeting its neighbours at no angle below `sharp_angle`
// (degrees). A violation downgrades the status: never an invalid "ok". `pairs`: the final
// check, also with the pairwise booleans and the angles (the costly part).
void self_check(const occ::Solid& solid, double tol, bool pairs, double sharp_angle,
                DecompositionResult& r) {
  const double total = solid.volume();
  bool partition = true, faces_ok = true;
  double sum = 0;
  for (std::size_t i = 0; i < r.sub_volumes.size(); ++i) {
    const SubVolume& sv = r.sub_volumes[i];
    sum += sv.volume;
    if (!(sv.volume > 0) || !occ::is_closed(*sv.solid)) {
      partition = false;
      r.diagnostics.push_back(
          core::make_error("invalid_sub_volume", "Sub-volume " + std::to_string(i) +
                                                     " is not a closed solid "
                                                     "of positive volume (" +
                                                     std::to_string(sv.volume) + ")"));
    }
  }
  if (std::abs(sum - total) > 1e-9 * total) {
    partition = false;
    char text[160];
    std::snprintf(text, sizeof text,
                  "The sub-volumes sum to %.12g but the solid's volume is %.12g (relative error "
                  "%.2e, allowed 1e-9)",
                  sum, total, std::abs(sum - total) / total);
    r.diagnostics.push_back(core::make_error("volume_mismatch", text));
  }
  // Disjointness: a boolean per pair whose boxes meet (pieces of one split and their
  // unions are disjoint by construction; this catches OCCT slips).
  std::vector<core::BoundingBox> box;
  for (const SubVolume& sv : r.sub_volumes) box.push_back(sv.solid->bounding_box());
  for (std::size_t i = 0; pairs && i < r.sub_volumes.size(); ++i)
    for (std::size_t j = i + 1; j < r.sub_volumes.size(); ++j) {
      if (!boxes_overlap(box[i], box[j], tol)) continue;
      const double c = occ::common_volume(*r.sub_volumes[i].solid, *r.sub_volumes[j].solid);
      if (c >= 0 && c < 1e-9 * total) continue;
      partition = false;
      if (c < 0) {  // the boolean failed: not known to be disjoint, which is no partition
        r.diagnostics.push_back(core::make_error(
            "overlap_unchecked", "OCCT could not intersect sub-volumes " + std::to_string(i) +
                                     " and " + std::to_string(j) +
                                     " to check that they do not overlap"));
        continue;
      }
      r.diagnostics.push_back(core::make_error("overlapping_sub_volumes",
                                               "Sub-volumes " + std::to_string(i) + " and " +
                                                   std::to_string(j) + " overlap (common volume " +
                                                   std::to_string(c) + ")"));
    }
  if (pairs) measure_face_angles(r);
  for (std::size_t f = 0; f < r.faces.size(); ++f) {
    const DecompositionFace& df = r.faces[f];
    std::string why;
    if (df.num_edges != 4) {
      why = std::to_string(df.num_edges) + " edges, not 4";
    } else if (df.sub_volumes[0] < 0 || df.sub_volumes[1] < 0) {
      why = "it bounds only sub-volume " +
            std::to_string(std::max(df.sub_volumes[0], df.sub_volumes[1]));
    } else if (df.min_angle < sharp_angle) {
      char text[120];
      std::snprintf(text, sizeof text,
                    "it meets a neighbouring face at %.1f degrees, below the sharp angle %.1f",
                    df.min_angle, sharp_angle);
      why = text;
    }
    if (why.empty()) continue;
    faces_ok = false;
    std::vector<std::string> elements;
    for (int e : df.elements) elements.push_back("Voronoi element " + std::to_string(e));
    r.diagnostics.push_back(core::make_warning(
        "invalid_decomposition_face",
        "Decomposition face " + std::to_string(f) + " is invalid: " + why, elements));
  }
  if (!partition)
    r.status = DecompositionStatus::failed;
  else if (!faces_ok && r.status == DecompositionStatus::ok)
    r.status = DecompositionStatus::partial;
}

}  // namespace vorohex::decompose::detail
