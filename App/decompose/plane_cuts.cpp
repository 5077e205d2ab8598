#include "decompose/plane_cuts.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "core/option_checks.h"
#include "decompose/detail/ball_octants.h"
#include "decompose/detail/cut_surfaces.h"
#include "decompose/detail/fillet_strips.h"
#include "decompose/detail/foot_planes.h"
#include "decompose/detail/hole_planes.h"
#include "decompose/detail/piece_merges.h"
#include "decompose/detail/piece_regions.h"
#include "mesh/map_block.h"
#include "mesh/mesh_sub_volumes.h"
#include "mesh/multisweep.h"
#include "mesh/revolve.h"
#include "mesh/sweep.h"
#include "occ/shape_io.h"
#include "occ/split_solid.h"

namespace vorohex::decompose {

using core::EdgeId;
using core::FaceId;
using core::Vec3;

void PlaneCutOptions::validate() const {
  core::require_at_least("PlaneCutOptions.max_planes", max_planes, 1);
  core::require_at_least("PlaneCutOptions.max_pieces", max_pieces, 2);
  core::require_positive("PlaneCutOptions.time_limit", time_limit);
}

namespace {

using detail::add_plane;
using detail::all_meshable;
using detail::Band;
using detail::beside_fillet;
using detail::Cylinder;
using detail::glued;
using detail::kVolumeTolerance;
using detail::merge_neighbours;
using detail::meshable;
using detail::on_a_hole;
using detail::Plane;
using detail::same_cylinder;
using detail::Touching;
using detail::touching;
using detail::volumes_fill;
using detail::within;

// The solid cut along the planes and cylinders at once; true when it gives two pieces or
// more that fill it (`pieces`, their `volumes`), else false with why (and the pieces, if any).
bool split_at_once(const occ::Solid& solid, const std::vector<Plane>& planes,
                   const std::vector<Cylinder>& cylinders, double whole, double seconds,
                   std::vector<occ::Solid>& pieces, std::vector<double>& volumes, std::string& why,
                   bool& timed_out) {
  std::vector<std::vector<Vec3>> tools;
  for (const Plane& pl : planes) tools.push_back(detail::tool_of(solid, pl));
  std::vector<occ::CutCylinder> round;
  for (const Cylinder& c : cylinders) round.push_back(c.surface);
  occ::SplitResult split =
      occ::split_solid(solid, tools, round, 1e-6 * solid.diagonal(), std::max(1.0, seconds));
  pieces = std::move(split.pieces);
  timed_out = split.timed_out;
  if (!split.ok) {
    why = "OCCT could not cut it along the surfaces of its concave edges";
    if (!split.diagnostics.empty()) {
      std::string m = split.diagnostics.front().message;
      if (!m.empty() && m.back() == '.') m.pop_back();
      why += " (" + m + ")";
    }
    return false;
  }
  if (pieces.size() < 2) {
    why = "OCCT's cut along the surfaces of its concave edges left it whole";
    return false;
  }
  return volumes_fill(pieces, whole, volumes, why);
}

// The solid cut along the surfaces of its concave edges. OCCT's splitter can fail on a set of
// surfaces it cuts along one by one: HexMe i18's 10 planes and 4 cylinders (two of them
// tangent to a cut plane) gave the solid back whole, while each alone cut it. So when the cut
// along all at once fails (not for lack of time), the surfaces are added one at a time,
// planes first, and one after which the pieces no longer fill the solid, or are fewer, is
// left out (`kept`: per surface, planes first, whether it was used); `planes` and
// `cylinders` keep the surfaces used. False with why when no cut is left.
bool split_along(const occ::Solid& solid, std::vector<Plane>& planes,
                 std::vector<Cylinder>& cylinders, double whole, double seconds,
                 std::vector<occ::Solid>& pieces, std::vector<double>& volumes,
                 std::vector<char>& kept, std::string& why) {
  const auto t0 = std::chrono::steady_clock::now();
  auto left = [&] {
    return seconds - std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  bool timed_out = false;
  const std::size_t n = planes.size() + cylinders.size();
  kept.assign(n, 1);
  if (split_at_once(solid, planes, cylinders, whole, left(), pieces, volumes, why, timed_out))
    return true;
  if (timed_out) return false;
  std::vector<Plane> used_planes;
  std::vector<Cylinder> used_cylinders;
  std::vector<occ::Solid> best;
  std::vector<double> best_volumes;
  for (std::size_t k = 0; k < n; ++k) {
    if (left() <= 0) return false;  // `why` and `pieces` stay those of the cut at once
    std::vector<Plane> p = used_planes;
    std::vector<Cylinder> c = used_cylinders;
    if (k < planes.size())
      p.push_back(planes[k]);
    else
      c.push_back(cylinders[k - planes.size()]);
    std::vector<occ::Solid> next;
    std::vector<double> next_volumes;
    std::string next_why;
    if (split_at_once(solid, p, c, whole, left(), next, next_volumes, next_why, timed_out) &&
        next.size() >= best.size()) {
      used_planes = std::move(p), used_cylinders = std::move(c);
      best = std::move(next), best_volumes = std::move(next_volumes);
      continue;
    }
    if (timed_out) return false;
    kept[k] = 0;
  }
  if (best.empty()) return false;
  planes = std::move(used_planes);
  cylinders = std::move(used_cylinders);
  pieces = std::move(best);
  volumes = std::move(best_volumes);
  return true;
}

std::vector<const occ::Solid*> pointers(const std::vector<occ::Solid>& v) {
  std::vector<const occ::Solid*> out;
  for (const occ::Solid& s : v) out.push_back(&s);
  return out;
}

// Copies sharing the same OCCT shapes.
std::vector<occ::Solid> clones(const std::vector<occ::Solid>& v) {
  std::vector<occ::Solid> out;
  out.reserve(v.size());
  for (const occ::Solid& s : v) out.push_back(s.clone());
  return out;
}

// The planes at the feet in `feet` added to `with` (kind `foot_plane`); those at concave
// fillets' feet only where `concave` (they are tried with every axis's at once).
void add_foot_planes(std::vector<Plane>& with, const std::vector<detail::FootPlane>& feet,
                     bool concave, double tol) {
  for (const detail::FootPlane& f : feet) {
    if (f.concave && !concave) continue;
    Plane pl{f.normal, f.offset, f.face, f.edges};
    pl.at_foot = true;
    add_plane(with, pl, tol);
  }
}

// The solid split afresh at the faces the merged pieces share only (occ::split_at_interfaces),
// where that gives as many pieces of the same volumes, each still with its scheme; else
// none. Merged pieces keep the traces of the cuts they were merged across: vertices and
// edges on their faces, and a cylinder unified round into a closed face has its seam where
// two pieces met (HexMe i11: a seam's vertex 8 units from the point of a crescent, where the
// quads at the point need their first node farther: 0.169 at best). Split afresh, the
// solid's own faces are not unified either (a cylinder in two halves stays so), which may
// mesh worse: the mesher judges (PlaneCutResult::afresh).
std::vector<occ::Solid> split_afresh(const occ::Solid& solid, const std::vector<occ::Solid>& pieces,
                                     const PlaneCutOptions& options, bool imprinted,
                                     double seconds) {
  const occ::ReadResult g = glued(pointers(pieces));
  if (!g.ok()) return {};
  const double tol = std::max(solid.tolerance(), 1e-7 * solid.diagonal());
  occ::SplitResult s = occ::split_at_interfaces(solid, *g.solid, tol, seconds);
  if (!s.ok || s.pieces.size() != pieces.size() || s.dropped_internal_faces > 0) return {};
  std::vector<double> before, after;
  for (const occ::Solid& p : pieces) before.push_back(p.volume());
  for (const occ::Solid& p : s.pieces) after.push_back(p.volume());
  std::sort(before.begin(), before.end());
  std::sort(after.begin(), after.end());
  const double whole = std::abs(solid.volume());
  for (std::size_t k = 0; k < before.size(); ++k)
    if (std::abs(before[k] - after[k]) > kVolumeTolerance * whole) return {};
  std::string why;
  if (!all_meshable(pointers(s.pieces), options, &why, imprinted)) return {};
  return std::move(s.pieces);
}

// The solid cut along these surfaces and the pieces merged, in `time_limit` seconds.
// Pieces with a face on one of `holes` are not merged (the planes around a hole: its piece
// sweeps along it; merged, a tube's half with the hole through its wall was a sweep whose
// layers fold).
PlaneCutResult cut_along(const occ::Solid& solid, std::vector<Plane> planes,
                         std::vector<Cylinder> cylinders, PlaneCutOptions options,
                         double time_limit, const core::Progress& progress,
                         const std::vector<occ::CutCylinder>& holes = {},
                         const std::vector<occ::CutCylinder>& walls = {},
                         const std::vector<Band>& bands = {}) {
  const bool merge_to_schemes = !bands.empty();
  options.time_limit = time_limit;
  PlaneCutResult r;
  const auto t0 = std::chrono::steady_clock::now();
  auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  if (planes.empty() && cylinders.empty()) {
    r.why_not = "it has no concave edge to cut at";
    return r;
  }
  // Bounded planes (mitres, each within a corner of two strips) do not count.
  const auto whole_surfaces =
      cylinders.size() + std::size_t(std::count_if(planes.begin(), planes.end(),
                                                   [](const Plane& p) { return p.quad.empty(); }));
  if (int(whole_surfaces) > options.max_planes) {
    r.why_not = "its concave edges give " + std::to_string(whole_surfaces) +
                " cut surfaces, more than " + std::to_string(options.max_planes);
    return r;
  }
  progress.report("plane_cuts", 0.0);
  for (const Plane& pl : planes)
    r.surfaces.push_back({false, pl.tangent, pl.face, pl.edges, true, pl.around_hole, pl.at_foot,
                          false, pl.beyond, pl.mitre, pl.corner});
  for (const Cylinder& c : cylinders)
    r.surfaces.push_back(
        {true, false, c.face, c.edges, true, false, c.at_foot, c.ring, false, false, c.corner});
  const double whole = solid.volume();
  std::vector<occ::Solid> pieces;
  std::vector<double> volume;  // per piece (an adaptive integration each: computed once)
  std::vector<char> kept;
  if (!split_along(solid, planes, cylinders, whole, options.time_limit - seconds(), pieces, volume,
                   kept, r.why_not)) {
    // The pieces of the cut along all surfaces at once, if any, for inspection.
    r.planes = int(planes.size());
    r.cylinders = int(cylinders.size());
    r.pieces_before_merge = int(pieces.size());
    r.pieces = std::move(pieces);
    return r;
  }
  for (std::size_t k = 0; k < r.surfaces.size(); ++k) r.surfaces[k].used = kept[k];
  r.planes = int(planes.size());
  r.cylinders = int(cylinders.size());
  r.pieces_before_merge = int(pieces.size());
  if (r.pieces_before_merge > options.max_pieces) {
    r.why_not = "the surfaces of its concave edges cut it into " +
                std::to_string(r.pieces_before_merge) + " pieces, more than " +
                std::to_string(options.max_pieces);
    return r;
  }
  // Octants of a ball where three fillets meet, left by planes across their feet: each
  // parted into four blocks (detail/ball_octants.h; a cube with all its edges rounded: 27
  // pieces, 51 with its eight corners parted, counted as 27 against the cap).
  r.octants = detail::split_ball_octants(pieces, volume,
                                         std::max(1.0, 0.1 * (options.time_limit - seconds())));
  r.pieces_before_merge = int(pieces.size());
  // Gluing many pieces is slow (HexMe i23's 89: 43 s); past kGlueFirst pieces, each must
  // have a scheme on its own before they are glued (gluing imprints edges on a piece, which
  // seldom gives it a scheme it had not). Not the fillets' strips, whose pieces are merged
  // before their schemes are asked (a T-shaped pocket's floor: 71 pieces, the corners'
  // halves without one).
  constexpr std::size_t kGlueFirst = 60;
  if (pieces.size() > kGlueFirst && !merge_to_schemes)
    for (std::size_t k = 0; k < pieces.size(); ++k)
      if (!meshable(pieces[k], options)) {
        r.why_not = "the surfaces of its concave edges cut it into " +
                    std::to_string(pieces.size()) + " pieces, and piece " + std::to_string(k + 1) +
                    " is neither a block, a sweep nor prismatic on its own";
        r.pieces = std::move(pieces);
        return r;
      }
  std::string why;
  // Glued once: whether every piece has a scheme, and which touch (both merge passes start
  // from it; gluing HexMe i22's 80 pieces takes about a second).
  // `merge_to_schemes`: pieces that have a scheme only once merged (the halves of a corner
  // that the mitre between two fillets' strips cuts: each joins its strip) are merged first.
  const occ::ReadResult cut_glued = glued(pointers(pieces));
  if (!all_meshable(cut_glued, options, &why) && !(merge_to_schemes && cut_glued.ok())) {
    r.why_not = "the surfaces of its concave edges cut it into " + std::to_string(pieces.size()) +
                " pieces: " + why;
    r.pieces = std::move(pieces);
    return r;
  }
  // The pieces as cut, each with a scheme (checked above); also where octants of a ball were
  // parted: merged, the fillets' strips beside them became multisweeps along other axes than
  // their neighbours', whose meshes do not match on the faces they share (a box with its top
  // and vertical edges filleted: 30 pieces merged to 17, 560 quads apart); as cut they do.
  if (!options.merge || r.octants > 0) {
    progress.report("plane_cuts", 1.0);
    r.pieces = std::move(pieces);
    r.ok = r.pieces.size() >= 2;
    if (!r.ok) r.why_not = "its cuts leave it in one piece";
    return r;
  }
  progress.report("plane_cuts", 0.5);
  // Merge neighbours while the union is a block, a sweep or prismatic and all pieces stay so once
  // glued (a union must not leave a T-junction on a neighbour's face). First without checking
  // each merge's neighbours (merge_keeps_meshable: gluing them, most of a merge's time), the
  // whole checked once at the end; where that fails, again from the cut with each merge's
  // neighbours checked. HexMe i22 (80 pieces, 76 merges, each of whose checks passed): the
  // merges 18 -> 6 s.
  const std::vector<occ::Solid> cut = clones(pieces);
  const std::vector<double> cut_volume = volume;
  Touching cut_touch = touching(pointers(pieces), cut_glued);
  for (std::size_t k = 0; k < pieces.size() && !holes.empty(); ++k)
    if (on_a_hole(pieces[k], holes))
      for (std::size_t m = 0; m < pieces.size(); ++m) cut_touch[k][m] = cut_touch[m][k] = 0;
  // A piece in a fillet's strip is merged only with pieces in a strip with it (the strip's
  // middle with the halves of its corners, not with the blocks beside it).
  if (!bands.empty()) {
    std::vector<std::vector<char>> in(pieces.size(), std::vector<char>(bands.size(), 0));
    std::vector<char> any(pieces.size(), 0);
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      std::vector<char> beside(bands.size(), 0);
      int bands_in = 0, besides = 0;
      for (std::size_t b = 0; b < bands.size(); ++b)
        if ((in[k][b] = within(pieces[k], bands[b]))) {
          ++bands_in;
          besides += beside[b] = beside_fillet(pieces[k], bands[b]);
        }
      // In two strips' planes, beside one's fillet only (an L-shaped pocket's long side where
      // the planes of the strip at its inner corner cross it): in that strip only.
      for (std::size_t b = 0; b < bands.size(); ++b) {
        if (bands_in >= 2 && besides > 0) in[k][b] = in[k][b] && beside[b];
        any[k] |= in[k][b];
      }
    }
    for (std::size_t k = 0; k < pieces.size(); ++k)
      for (std::size_t m = 0; m < pieces.size(); ++m) {
        bool common = false;
        for (std::size_t b = 0; b < bands.size(); ++b) common = common || (in[k][b] && in[m][b]);
        if ((any[k] || any[m]) && !common) cut_touch[k][m] = 0;
      }
  }
  for (const occ::CutCylinder& c : walls) {
    std::vector<char> inside(pieces.size());
    for (std::size_t k = 0; k < pieces.size(); ++k) inside[k] = within(pieces[k], c);
    for (std::size_t k = 0; k < pieces.size(); ++k)
      for (std::size_t m = 0; m < pieces.size(); ++m)
        if (inside[k] != inside[m]) cut_touch[k][m] = 0;
  }
  const double cut_into = double(pieces.size());
  // Each pass's unions, for the mesher to undo those that do not mesh (MergeHistory).
  MergeHistory first_merges;
  merge_neighbours(pieces, volume, cut_touch, options, /*careful=*/false, cut_into, seconds,
                   progress, &first_merges);
  bool fills = volumes_fill(pieces, whole, volume, r.why_not);
  bool meshes = fills && all_meshable(pointers(pieces), options, &why);
  std::vector<occ::Solid> first = meshes ? std::vector<occ::Solid>() : clones(pieces);
  if (meshes) r.merges = std::move(first_merges);
  if (!meshes && seconds() < options.time_limit) {
    r.merges_checked_each = true;
    pieces = clones(cut);
    volume = cut_volume;
    merge_neighbours(pieces, volume, cut_touch, options, /*careful=*/true, cut_into, seconds,
                     progress, &r.merges);
    fills = volumes_fill(pieces, whole, volume, r.why_not);
    // The merges were checked on their neighbourhoods; the whole is checked once more.
    meshes = fills && all_meshable(pointers(pieces), options, &why);
  }
  // Still not: the first merge's pieces, then these, whose sweeps' linking sides carry their
  // neighbours' imprints (strips around a pocket's floor fillets ended by mitre planes, the
  // blocks beside them split at the other strips' ends): mesh/sweep.h `imprinted`.
  bool imprinted = false;
  if (!meshes && fills && seconds() < options.time_limit) {
    std::string imprinted_why;
    if (!first.empty() && volumes_fill(first, whole, volume, r.why_not) &&
        all_meshable(pointers(first), options, &imprinted_why, true)) {
      pieces = std::move(first);
      r.merges = std::move(first_merges);
      meshes = imprinted = true;
    } else if (volumes_fill(pieces, whole, volume, r.why_not) &&
               all_meshable(pointers(pieces), options, &imprinted_why, true)) {
      meshes = imprinted = true;
    }
  }
  progress.report("plane_cuts", 1.0);
  if (!fills) return r;
  if (!meshes) {
    r.why_not = "its " + std::to_string(pieces.size()) + " pieces after merging: " + why;
    r.pieces = std::move(pieces);
    return r;
  }
  if (pieces.size() >= 2 && seconds() < options.time_limit)
    r.afresh = split_afresh(solid, pieces, options, imprinted, options.time_limit - seconds());
  r.pieces = std::move(pieces);
  r.ok = r.pieces.size() >= 2;
  if (!r.ok) r.why_not = "its cuts merge back into one piece";
  return r;
}

}  // namespace

PlaneCutResult cut_at_concave_edges(const occ::Solid& solid, const PlaneCutOptions& options,
                                    const core::Progress& progress) {
  options.validate();
  std::vector<Plane> planes;
  std::vector<Cylinder> cylinders;
  PlaneCutResult r;
  if (!detail::concave_surfaces(solid, planes, cylinders, r.why_not)) return r;
  std::vector<Plane> tangent_planes = planes;
  std::vector<Cylinder> other_cylinders = cylinders;
  const bool tangent = detail::tangent_planes_instead(solid, tangent_planes, other_cylinders);
  if (options.tangent_planes) {
    if (!tangent) {
      r.why_not = "no cylinder it is cut along is touched tangently by a planar face";
      return r;
    }
    planes = std::move(tangent_planes);
    cylinders = std::move(other_cylinders);
  }
  r = cut_along(solid, std::move(planes), std::move(cylinders), options, options.time_limit,
                progress);
  r.knife_edges = !options.tangent_planes && tangent && detail::adds_knife_edges(solid, r.pieces);
  return r;
}

// The fifth try: the planes of the strips that the concave fillets along floors lie on, ended
// by the planes of their mitres (detail/fillet_strips.h), with the concave edges' planes
// except those of the faces the fillets are tangent to, within `seconds`.
PlaneCutResult cut_at_fillet_strips(const occ::Solid& solid, const PlaneCutOptions& options,
                                    const core::Progress& progress, double seconds) {
  PlaneCutResult none;
  const detail::FilletStrips strips = detail::fillet_strips(solid);
  std::vector<Plane> planes;
  std::vector<Cylinder> cylinders;
  if (strips.planes.empty() || seconds <= 0 ||
      !detail::concave_surfaces(solid, planes, cylinders, none.why_not))
    return none;
  const double tol = 1e-7 * solid.diagonal();
  // The floors and walls the fillets touch: a point of each and its unit normal.
  std::vector<std::pair<Vec3, Vec3>> touched;
  for (FaceId f : strips.tangent_faces) {
    const Vec3 p = solid.vertex_point(solid.edge_first_vertex(solid.face_wires(f)[0][0].edge));
    touched.push_back({p, solid.face_normal(f, p).normalized()});
  }
  std::vector<Plane> with;
  for (const Plane& pl : planes) {
    const bool tangent = std::any_of(touched.begin(), touched.end(), [&](const auto& t) {
      return std::abs(pl.normal.dot(t.second)) > 1 - 1e-9 &&
             std::abs(pl.normal.dot(t.first) - pl.offset) <= 1e3 * tol;
    });
    if (!tangent) with.push_back(pl);
  }
  for (const detail::StripPlane& sp : strips.planes) {
    Plane pl{sp.normal, sp.offset, sp.face, sp.edges};
    pl.at_foot = sp.kind == detail::StripPlane::across;
    pl.beyond = sp.kind == detail::StripPlane::beyond;
    pl.mitre = sp.kind == detail::StripPlane::mitre;
    pl.corner = sp.kind == detail::StripPlane::corner;
    pl.quad = sp.quad;
    add_plane(with, pl, tol);
  }
  std::vector<Cylinder> other;
  for (const Cylinder& c : cylinders)
    if (std::find(strips.fillets.begin(), strips.fillets.end(), c.face) == strips.fillets.end())
      other.push_back(c);
  cylinders = std::move(other);
  for (const detail::StripCylinder& c : strips.cylinders) {  // sectors round rounded corners
    Cylinder cyl{c.surface, c.face, {c.edge}, true, c.beyond, true};
    cylinders.push_back(cyl);
  }
  PlaneCutOptions o = options;
  o.time_limit = seconds;
  // Each fillet's strip: between its plane across the foot and its plane beyond the wall.
  std::vector<Band> bands;
  for (const detail::StripPlane& a : strips.planes)
    for (const detail::StripPlane& b : strips.planes)
      if (a.kind == detail::StripPlane::across && b.kind == detail::StripPlane::beyond &&
          a.face == b.face)
        bands.push_back({a.normal, std::min(a.offset, b.offset), std::max(a.offset, b.offset),
                         solid.face_bounding_box(a.face)});
  return cut_along(solid, std::move(with), std::move(cylinders), o, seconds, progress, {}, {},
                   bands);
}

PlaneCutResult cut_as_the_mesher(const occ::Solid& solid, const PlaneCutOptions& options,
                                 const core::Progress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  auto left = [&] {
    return options.time_limit -
           std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  PlaneCutResult cut = cut_at_concave_edges(solid, options, progress);
  if (cut.ok || options.tangent_planes) return cut;
  if (cut.knife_edges && left() > 0) {
    PlaneCutOptions tangent = options;
    tangent.tangent_planes = true;
    tangent.time_limit = left();
    PlaneCutResult second = cut_at_concave_edges(solid, tangent, progress);
    if (second.ok) return second;
  }
  // Then without the oblique planes whose concave edges other surfaces cut along already (a
  // gusset's sloped face between the legs of an angle: its plane cut wedges out of both legs).
  {
    std::vector<Plane> planes;
    std::vector<Cylinder> cylinders;
    std::string why;
    if (left() > 0 && detail::concave_surfaces(solid, planes, cylinders, why) &&
        detail::drop_oblique_planes(solid, planes, cylinders)) {
      PlaneCutResult without =
          cut_along(solid, std::move(planes), std::move(cylinders), options, left(), progress);
      if (without.ok) return without;
    }
  }
  // Third: with planes around the holes that cross the part's other direction. A part a few
  // planes around its holes make structured is a simple one (a tube with a cross hole: 0.6
  // s): these cuts get at most a quarter of the time, kAroundSeconds and kAroundPieces pieces
  // (HexMe's parts with many holes, which they never make structured, waited up to 15 s more
  // for them: i24), and are not tried where the cut at concave edges alone gave more than
  // half that many pieces (more planes only add to them: HexMe i02, i24 and n05, 31 to 38
  // pieces, 95 to 232 with the planes, 3 to 4 s each). Not less than twice what a simple
  // part's cut takes here: a ring with three radial holes takes 3 s, and with 4 it was
  // stopped wherever the grid mesher beside it and another job shared the two cores (the tet
  // split's 78,452 hexahedra at 0.105 in 85 s instead of 666 at 0.500 in 6 s, run to run).
  constexpr int kAroundPieces = 40;
  std::vector<Plane> planes;
  std::vector<Cylinder> cylinders;
  std::string why;
  if (left() <= 0 || !detail::concave_surfaces(solid, planes, cylinders, why)) return cut;
  constexpr double kAroundSeconds = 8;
  PlaneCutOptions around_options = options;
  around_options.max_pieces = std::min(options.max_pieces, kAroundPieces);
  const double until = left() - std::min(0.25 * options.time_limit, kAroundSeconds);
  const double tol = 1e-7 * solid.diagonal();
  const auto sets = cut.pieces_before_merge > kAroundPieces / 2
                        ? std::vector<std::vector<detail::HolePlane>>{}
                        : detail::hole_plane_sets(solid);
  for (const std::vector<detail::HolePlane>& set : sets) {
    if (left() <= until) break;
    std::vector<Plane> with = planes;
    std::vector<occ::CutCylinder> holes;
    for (const detail::HolePlane& h : set) {
      add_plane(with, {h.normal, h.offset, h.hole, {}, false, true}, tol);
      holes.push_back(h.cylinder);
    }
    PlaneCutResult around = cut_along(solid, std::move(with), cylinders, around_options,
                                      left() - until, progress, holes);
    if (around.ok) return around;
  }
  // Fourth: with planes across the feet of its tapered or rounded faces (a block with
  // chamfered or filleted top edges, which has no concave edge: a block and a slab), each
  // axis's set in turn, within the same share of the time as the planes around holes. First
  // without the planes of the faces tapered to that axis (a pocket with drafted walls: its
  // walls' planes cut wedges off the block; cut at its floor alone, a block and a slab with
  // a tapered hole, swept), then with them.
  const double feet_until = left() - std::min(0.25 * options.time_limit, kAroundSeconds);
  // Without the tapered faces' planes only where the cut at concave edges was a simple one
  // (at most as many pieces as the planes around holes allow, as many surfaces as the cuts
  // take): HexMe's industrial models whose cuts fail then split with fewer surfaces, each
  // for nothing (i25 25 -> 38 s, i03 30 -> 42 s).
  const bool simple = cut.pieces_before_merge <= kAroundPieces / 2 &&
                      int(planes.size() + cylinders.size()) <= options.max_planes;
  // Then the planes of every axis at once, where the cut at concave edges was simple (a box
  // whose top and vertical edges are filleted: each axis alone leaves fillets across the
  // axis; all at once, blocks, the fillets' strips and the octants of a ball at its corners).
  // The planes at the feet of concave fillets on walls (an L bracket's inner edge rounded:
  // across each leg where the fillet meets it) only there, all axes at once: each axis alone
  // leaves the fillet across the other, and a pocket's filleted floor, whose strips the fifth
  // try takes, would pay a cut per axis for nothing.
  std::vector<detail::FootPlaneSet> foot_sets = detail::foot_plane_sets(solid);
  std::optional<detail::FootPlaneSet> concave_feet;
  if (simple && !foot_sets.empty()) {
    detail::FootPlaneSet all = foot_sets[0];
    bool concave = false;
    for (std::size_t k = 1; k < foot_sets.size(); ++k)
      all.planes.insert(all.planes.end(), foot_sets[k].planes.begin(), foot_sets[k].planes.end());
    for (const detail::FootPlane& f : all.planes) concave = concave || f.concave;
    if (concave)  // tried after the strips (a pocket's filleted floor: their way)
      concave_feet = std::move(all);
    else if (foot_sets.size() >= 2)
      foot_sets.push_back(std::move(all));
  }
  for (const detail::FootPlaneSet& set : foot_sets) {
    if (std::all_of(set.planes.begin(), set.planes.end(),
                    [](const detail::FootPlane& f) { return f.concave; }))
      continue;  // nothing to cut along on this axis alone
    std::vector<Plane> untapered;
    for (const Plane& pl : planes) {
      const double c = std::abs(pl.normal.dot(set.axis));
      if (c < 1e-6 || c > 1 - 1e-6) untapered.push_back(pl);
    }
    for (bool all : {false, true}) {
      if (!all && !simple) continue;
      if (all && simple && untapered.size() == planes.size()) break;  // tried: the same
      if (left() <= feet_until) return cut;
      std::vector<Plane> with = all ? planes : untapered;
      add_foot_planes(with, set.planes, false, tol);
      PlaneCutResult feet = cut_along(solid, std::move(with), cylinders, around_options,
                                      left() - feet_until, progress);
      if (feet.ok) return feet;
    }
  }
  // Fifth: the strips of the concave fillets along floors, ended at their mitres (a pocket
  // whose floor edges are rounded), within what time is left (cut_at_fillet_strips).
  // Sixth: with cylinders through the feet of concave round fillets on their floors (a boss
  // whose root is filleted has no concave edge: cut there, the boss with its fillet is a solid
  // of revolution and the plate a sweep with a round hole), with what time is left.
  if (PlaneCutResult strips = cut_at_fillet_strips(solid, options, progress, left()); strips.ok)
    return strips;
  if (concave_feet && left() > 0) {  // the fourth's planes of every axis with the concave ones
    std::vector<Plane> with = planes;
    add_foot_planes(with, concave_feet->planes, true, tol);
    PlaneCutResult feet =
        cut_along(solid, std::move(with), cylinders, around_options, left(), progress);
    if (feet.ok) return feet;
  }
  const std::vector<detail::FootCylinder> fillets = detail::foot_cylinders(solid);
  if (fillets.empty() || left() <= 0) return cut;
  std::vector<Cylinder> with = cylinders;
  for (const detail::FootCylinder& f : fillets) {
    auto same = std::find_if(with.begin(), with.end(), [&](const Cylinder& c) {
      return same_cylinder(c.surface, f.surface, tol);
    });
    if (same != with.end() && !f.ring)
      same->edges.push_back(f.edge);
    else if (same == with.end())
      with.push_back(
          {f.surface, f.face, f.ring ? std::vector<EdgeId>{} : std::vector{f.edge}, true, f.ring});
  }
  PlaneCutOptions revolved = around_options;
  revolved.revolve = true;
  // A piece within such a cylinder is not merged with one outside it (a column under the boss
  // merged into the block below, the block's cap would be meshed unlike the boss's end).
  std::vector<occ::CutCylinder> walls;
  for (const detail::FootCylinder& f : fillets) walls.push_back(f.surface);
  // With the planes across the feet along the fillets' axis too (the plate's own top edges
  // filleted: a slab with a round hole over a block), then without.
  std::vector<Plane> with_feet = planes;
  for (const detail::FootPlaneSet& set : detail::foot_plane_sets(solid))
    if (std::abs(set.axis.dot(fillets[0].surface.axis)) > 1 - 1e-9)
      add_foot_planes(with_feet, set.planes, false, tol);
  for (const std::vector<Plane>* p : {&with_feet, &planes}) {
    if (left() <= 0 || (p == &planes && with_feet.size() == planes.size())) break;
    PlaneCutResult feet = cut_along(solid, *p, with, revolved, left(), progress, {}, walls);
    if (feet.ok) return feet;
  }
  return cut;
}

}  // namespace vorohex::decompose
