#include "smooth/smooth_mesh.h"

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/progress.h"
#include "quality/detail/parallel.h"
#include "quality/quality_stats.h"
#include "quality/scaled_jacobian.h"
#include "smooth/detail/hex_jacobian.h"
#include "smooth/detail/node_objective.h"
#include "smooth/detail/topology.h"

namespace vorohex::smooth {
namespace {

using core::EdgeId;
using core::FaceId;
using core::HexMesh;
using core::NodeClass;
using core::Vec3;
using detail::IncidentHex;

using core::seconds_since;

// Valid hexes may fall to this scaled Jacobian (no lower) while inverted ones are untangled.
constexpr double kUntangleFloor = 1e-3;
// Scaled corner determinant the untangling model lifts every frame towards.
constexpr double kUntangleTarget = 0.2;
// Hexes the untangling takes on: inverted ones, and those flat up to rounding (the check's
// degenerate_elements), which the optimisation's moves, each keeping every hex at least as
// good, cannot lift when a quad lies folded flat on a face.
constexpr double kFlat = 1e-6;

// What a trial position must respect, besides the per-hex floor rule.
enum class Mode {
  strict,    // every incident hex: new >= min(old, floor) (inverted hexes may only improve)
  untangle,  // valid incident hexes as strict; inverted ones follow the objective
};

class Smoother {
 public:
  Smoother(HexMesh& mesh, const occ::Solid& solid, const SmoothOptions& options,
           const core::Progress& progress, SmoothResult& result)
      : mesh_(mesh), solid_(solid), options_(options), progress_(progress), result_(result) {}

  void run() {
    topology_ = detail::build_topology(mesh_);
    for (core::EdgeId e : solid_.edges()) {
      const std::vector<FaceId> ef = solid_.edge_faces(e);
      for (std::size_t i = 0; i < ef.size(); ++i)
        for (std::size_t j = i + 1; j < ef.size(); ++j)
          if (ef[i] != ef[j])
            face_pairs_.emplace_back(std::min(ef[i].value(), ef[j].value()),
                                     std::max(ef[i].value(), ef[j].value()));
    }
    std::sort(face_pairs_.begin(), face_pairs_.end());
    classify_movable();
    sj_ = quality::scaled_jacobians(mesh_);
    const quality::QualityStats before = quality::quality_stats(sj_);
    result_.min_before = before.min;
    result_.mean_before = before.mean;
    result_.inverted_before = before.inverted;
    floor_ = std::max(options_.quality_target, before.min);
    input_min_ = before.min;
    const std::vector<double> input_sj = sj_;
    const std::vector<Vec3> input_points = mesh_.points();
    const std::vector<NodeClass> input_classes = mesh_.node_classes();  // untangling may change
    // Local sizes: the size at every node, once (nodes move little), for the weights.
    if (options_.size_field != nullptr && !options_.size_field->uniform()) {
      node_size_.resize(mesh_.num_nodes());
      for (std::size_t n = 0; n < mesh_.num_nodes(); ++n)
        node_size_[n] = options_.size_field->at(mesh_.points()[n]);
    }

    const auto t0 = std::chrono::steady_clock::now();
    laplacian_phase();
    result_.seconds_laplacian = seconds_since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    if (!cancelled()) optimisation_phase(true);
    if (!cancelled()) optimisation_phase(false);
    if (!cancelled() && maxmin_phase(false) > 0 && !cancelled())
      optimisation_phase(false);  // what max-min traded, where it can
    // The optimisation and max-min moved the neighbours of what is still inverted: the
    // untangling may now get further (a few rounds, while the count of inverted falls).
    for (int round = 0, left = count_inverted(); round < 3 && left > 0 && !cancelled(); ++round) {
      optimisation_phase(true);
      if (!cancelled()) optimisation_phase(false);
      const int now = count_inverted();
      if (now >= left) break;
      left = now;
    }
    // Last, max-min with tying moves (shortfall_step), from where the phases above left the
    // mesh, so the minimum ends at least where they took it; then the Laplacian (guarded as
    // always) around the nodes it moved wins back the mean the ties traded. Ties are a way
    // to raise the minimum: when it did not rise by the max-min's own 1e-4, they are undone
    // (HexMe i16 kept 0.313 and lost 0.035 of its mean).
    if (!cancelled() && count_inverted() == 0 && !sj_.empty()) {
      const std::vector<Vec3> before_ties = mesh_.points();
      const std::vector<double> sj_before_ties = sj_;
      const double min_before_ties = *std::min_element(sj_.begin(), sj_.end());
      if (maxmin_phase(true) > 0 && !cancelled()) {
        local_laplacian(tied_);
        if (!cancelled()) maxmin_phase(false);
      }
      if (!(*std::min_element(sj_.begin(), sj_.end()) > min_before_ties + 1e-4)) {
        for (std::size_t n = 0; n < before_ties.size(); ++n)
          mesh_.set_point(core::NodeId(static_cast<std::int32_t>(n)), before_ties[n]);
        sj_ = sj_before_ties;
      }
    }
    result_.seconds_optimisation = seconds_since(t1);

    // Recomputed from scratch, not taken from the running values.
    std::vector<double> after_sj = quality::scaled_jacobians(mesh_);
    quality::QualityStats after = quality::quality_stats(after_sj);
    // Untangling may deepen one inverted hex to clear others; the result must never have a
    // lower minimum than its input, so such a trade is undone as a whole.
    if (after.min < before.min) {
      for (std::size_t n = 0; n < input_points.size(); ++n) {
        mesh_.set_point(core::NodeId(static_cast<std::int32_t>(n)), input_points[n]);
        mesh_.set_node_class(core::NodeId(static_cast<std::int32_t>(n)), input_classes[n]);
      }
      std::ostringstream s;
      s << "Smoothing lowered the minimum scaled Jacobian from " << before.min << " to "
        << after.min << " (" << after.inverted << " inverted instead of " << before.inverted
        << "); the input node positions were restored.";
      result_.diagnostics.push_back(core::make_warning("smoothing_reverted", s.str()));
      after_sj = input_sj;
      after = before;
      result_.edge_nodes_released = 0;
    }
    result_.min_after = after.min;
    result_.mean_after = after.mean;
    result_.inverted_after = after.inverted;
    for (std::size_t h = 0; h < after_sj.size(); ++h)
      if (input_sj[h] <= 0 && after_sj[h] > 0) ++result_.untangled;
    if (result_.edge_nodes_released > 0) {
      std::ostringstream s;
      s << result_.edge_nodes_released << " nodes on model edges were moved onto a face of "
        << "their edge to untangle hexahedra that no move along the edge could: the mesh "
        << "cuts the edge there.";
      result_.diagnostics.push_back(core::make_warning("edge_nodes_released", s.str()));
    }
    if (result_.status != SmoothStatus::cancelled && after.inverted > 0) {
      result_.status = SmoothStatus::inverted_remain;
      std::ostringstream s;
      s << after.inverted << " of " << after_sj.size()
        << " hexahedra are still inverted after untangling (minimum scaled Jacobian " << after.min
        << ").";
      result_.diagnostics.push_back(core::make_error("inverted_elements", s.str()));
    }
  }

 private:
  bool cancelled() {
    if (result_.status == SmoothStatus::cancelled) return true;
    if (!progress_.cancelled()) return false;
    result_.status = SmoothStatus::cancelled;
    result_.diagnostics.push_back(core::make_warning(
        "cancelled", "Smoothing was cancelled; the mesh keeps the moves made so far."));
    return true;
  }

  int count_inverted() const {
    int n = 0;
    for (double v : sj_) n += v <= kFlat;
    return n;
  }

  // Vertex nodes, nodes without neighbours, nodes naming no entity of the solid and the
  // nodes the options fix stay put.
  void classify_movable() {
    const std::size_t nn = mesh_.num_nodes();
    movable_.assign(nn, 0);
    const int counts[3] = {solid_.num_vertices(), solid_.num_edges(), solid_.num_faces()};
    std::vector<std::string> bad;
    std::size_t num_bad = 0;
    for (std::size_t n = 0; n < nn; ++n) {
      const NodeClass c = mesh_.node_classes()[n];
      bool known = c.dim == 3 || (c.dim >= 0 && c.dim <= 2 && c.id >= 1 && c.id <= counts[c.dim]);
      if (known && c.dim == 1 && solid_.edge_is_degenerated(EdgeId(c.id))) known = c.dim != 1;
      if (!known) {
        if (bad.size() < 5) bad.push_back("node " + std::to_string(n));
        ++num_bad;
      }
      movable_[n] = known && c.dim != 0 && topology_.neighbours.size(n) > 0 &&
                    topology_.node_hexes.size(n) > 0 &&
                    !(n < options_.fixed.size() && options_.fixed[n]);
      if (!movable_[n]) ++result_.fixed_nodes;
    }
    if (num_bad > 0) {
      std::ostringstream s;
      s << num_bad << " nodes are classified on no entity of the solid (or on a degenerated "
        << "edge) and were kept fixed.";
      result_.diagnostics.push_back(core::make_warning("unknown_entity", s.str(), bad));
    }
  }

  // Scaled Jacobian of hex h with its local corner c at x.
  double hex_sj(std::int32_t item, const Vec3& x) const {
    const auto& hex = mesh_.hexes()[item / 8];
    const auto& pts = mesh_.points();
    std::array<Vec3, 8> p;
    for (int i = 0; i < 8; ++i) p[i] = pts[hex[i]];
    p[item % 8] = x;
    return detail::hex_scaled_jacobian(p);
  }

  // Evaluates the incident hexes with node n at x into `trial`; true if the floor rule holds.
  bool acceptable(std::size_t n, const Vec3& x, Mode mode, std::vector<double>& trial) const {
    trial.clear();
    for (std::int64_t k = topology_.node_hexes.begin(n); k < topology_.node_hexes.end(n); ++k) {
      const std::int32_t item = topology_.node_hexes.items[k];
      const double old_sj = sj_[item / 8];
      const double new_sj = hex_sj(item, x);
      // Untangling may trade quality of valid hexes (never their validity) for fewer
      // inverted ones, and an inverted hex may get worse, never below the input's minimum;
      // the optimisation phase then raises what fell below the target.
      const bool ok =
          mode == Mode::strict
              ? new_sj >= std::min(old_sj, floor_)
              : (old_sj <= 0 ? new_sj >= input_min_ : new_sj >= std::min(old_sj, kUntangleFloor));
      if (!ok) return false;
      trial.push_back(new_sj);
    }
    return true;
  }

  // Writes node n and its incident hexes' values. Nodes of one colour share no hex, so
  // concurrent commits of such nodes touch disjoint entries.
  void commit(std::size_t n, const Vec3& x, const std::vector<double>& trial,
              FaceId face = FaceId()) {
    mesh_.set_point(core::NodeId(static_cast<std::int32_t>(n)), x);
    if (face.value() > 0)
      mesh_.set_node_class(core::NodeId(static_cast<std::int32_t>(n)), NodeClass::on(face));
    std::size_t i = 0;
    for (std::int64_t k = topology_.node_hexes.begin(n); k < topology_.node_hexes.end(n); ++k)
      sj_[topology_.node_hexes.items[k] / 8] = trial[i++];
  }

  // The normal of face f at node n's point x: kept per node for as long as the node stays
  // at x on f (a line search asks for it at each of its trial steps, and each is a CAD
  // projection; the same value, so the same mesh).
  Vec3 face_normal(std::size_t n, int f, const Vec3& x) const {
    if (normals_.size() != mesh_.points().size()) normals_.assign(mesh_.points().size(), {});
    KnownNormal& k = normals_[n];
    if (k.face != f || k.at != x) k = {f, x, solid_.face_normal(FaceId(f), x)};
    return k.normal;
  }

  // Moves node n from x by d on its entity: a tangent step then a projection for face nodes,
  // a projection for edge nodes. False when the projection jumps far from the step.
  bool constrained_move(std::size_t n, const Vec3& x, Vec3 d, Vec3& y) const {
    const NodeClass c = mesh_.node_classes()[n];
    if (c.dim == 3) {
      y = x + d;
      return true;
    }
    const double step = d.norm();
    if (c.dim == 2) {
      const Vec3 normal = face_normal(n, c.id, x);
      d -= d.dot(normal) * normal;
      y = solid_.project_to_face(FaceId(c.id), x + d);
    } else {
      y = solid_.project_to_edge(EdgeId(c.id), x + d);
    }
    return y.allFinite() && (y - x).norm() <= 3 * step;
  }

  // As constrained_move, for a face node while untangling: where the step leaves the node's
  // face (its projection is held at the face's boundary, so nodes pile up there: a quad of
  // a pillow layer pressed flat against a boundary edge of its face), the node may cross
  // onto the adjacent face nearest to the step's target; *face is then that face.
  bool untangling_move(std::size_t n, const Vec3& x, const Vec3& d, Vec3& y, FaceId* face) const {
    *face = FaceId();
    const NodeClass c = mesh_.node_classes()[n];
    if (!constrained_move(n, x, d, y)) return false;
    if (c.dim != 2) return true;
    const Vec3 normal = face_normal(n, c.id, x);
    const Vec3 target = x + d - d.dot(normal) * normal;
    const double held = (y - target).norm();
    if (!(held > 0.25 * d.norm())) return true;
    const FaceId g = solid_.nearest_face(target);
    if (g.value() <= 0 || g.value() == c.id || !adjacent_faces(c.id, g.value())) return true;
    const Vec3 z = solid_.project_to_face(g, target);
    if (!z.allFinite() || !((z - target).norm() < held) || (z - x).norm() > 3 * d.norm())
      return true;
    y = z;
    *face = g;
    return true;
  }

  // A face node lying on its face's boundary, whose hexes no move on its face untangles (a
  // quad folded flat onto the face along an edge it straddles: every step in the face's
  // tangent plane keeps it flat), tries the moves of a node on each adjacent face it also
  // lies on; the first that is accepted classifies it on that face. An edge node that no
  // move along its edge untangles (a quad with all four nodes on one straight line of model
  // edges) tries those of a node on each face of the edge: it then leaves the edge, which
  // the mesh no longer follows there (counted, and reported).
  bool untangle_across(std::size_t n) {
    const NodeClass c = mesh_.node_classes()[n];
    const core::NodeId id(static_cast<std::int32_t>(n));
    if (c.dim == 1) {
      for (FaceId f : solid_.edge_faces(EdgeId(c.id))) {
        mesh_.set_node_class(id, NodeClass::on(f));
        if (descend(n, Mode::untangle) || untangle_node(n)) {
          ++result_.edge_nodes_released;
          return true;
        }
        mesh_.set_node_class(id, c);
      }
      return false;
    }
    if (c.dim != 2) return false;
    const Vec3 x = mesh_.points()[n];
    double mean_edge = 0;
    const auto& nb = topology_.neighbours;
    for (std::int64_t k = nb.begin(n); k < nb.end(n); ++k)
      mean_edge += (mesh_.points()[nb.items[k]] - x).norm();
    mean_edge /= static_cast<double>(std::max<std::int64_t>(nb.size(n), 1));
    for (const auto& [a, b] : face_pairs_) {
      if (a != c.id && b != c.id) continue;
      const FaceId g(a == c.id ? b : a);
      if (!(solid_.distance_to_face(g, x) <= 1e-6 * mean_edge)) continue;
      mesh_.set_node_class(id, NodeClass::on(g));
      if (descend(n, Mode::untangle) || untangle_node(n)) return true;
      mesh_.set_node_class(id, c);
    }
    return false;
  }

  bool adjacent_faces(int f, int g) const {
    return std::binary_search(face_pairs_.begin(), face_pairs_.end(),
                              std::make_pair(std::min(f, g), std::max(f, g)));
  }

  // Greedy colouring of the movable interior nodes so that nodes of one colour share no hex
  // (8 colours on a structured grid); boundary nodes and overflow stay serial because the
  // CAD projections are not known to be thread-safe.
  void colour_nodes() {
    const std::size_t nn = mesh_.num_nodes();
    constexpr int kMaxColours = 64;
    std::vector<std::int8_t> colour(nn, -1);
    for (std::size_t n = 0; n < nn; ++n) {
      if (!movable_[n]) continue;
      if (!mesh_.node_classes()[n].is_interior()) {
        serial_nodes_.push_back(static_cast<std::int32_t>(n));
        continue;
      }
      std::uint64_t used = 0;
      for (std::int64_t k = topology_.node_hexes.begin(n); k < topology_.node_hexes.end(n); ++k)
        for (std::int32_t m : mesh_.hexes()[topology_.node_hexes.items[k] / 8])
          if (colour[m] >= 0) used |= std::uint64_t{1} << colour[m];
      int c = 0;
      while (c < kMaxColours && (used >> c) & 1) ++c;
      if (c == kMaxColours) {
        serial_nodes_.push_back(static_cast<std::int32_t>(n));
        continue;
      }
      colour[n] = static_cast<std::int8_t>(c);
      if (static_cast<std::size_t>(c) >= colour_classes_.size()) colour_classes_.resize(c + 1);
      colour_classes_[c].push_back(static_cast<std::int32_t>(n));
    }
  }

  // One Laplacian move of node n: 0 = none, 1 = accepted but below the tolerance,
  // 2 = accepted and larger.
  int laplacian_step(std::size_t n, std::vector<double>& trial) {
    if (options_.active_below < 1) {
      bool active = false;
      for (std::int64_t k = topology_.node_hexes.begin(n);
           k < topology_.node_hexes.end(n) && !active; ++k)
        active = sj_[topology_.node_hexes.items[k] / 8] < options_.active_below;
      if (!active) return 0;
    }
    const auto& nb = topology_.neighbours;
    const auto& pts = mesh_.points();
    const Vec3 x = pts[n];
    // With local sizes each neighbour weighs 1 / (the size along the edge to it): at rest
    // the edges are then as long as the sizes ask (a graded mesh stays graded).
    Vec3 sum = Vec3::Zero();
    double length = 0, weights = 0;
    for (std::int64_t k = nb.begin(n); k < nb.end(n); ++k) {
      const Vec3& q = pts[nb.items[k]];
      const double w = node_size_.empty() ? 1.0 : 2.0 / (node_size_[n] + node_size_[nb.items[k]]);
      sum += w * q;
      weights += w;
      length += (q - x).norm();
    }
    const double count = static_cast<double>(nb.size(n));
    const Vec3 d = options_.relaxation * (sum / weights - x);
    const double tol = options_.tolerance * length / count;
    if (!(d.norm() > tol)) return 0;
    Vec3 y;
    if (!constrained_move(n, x, d, y) || !acceptable(n, y, Mode::strict, trial)) return 0;
    commit(n, y, trial);
    return (y - x).norm() > tol ? 2 : 1;
  }

  void laplacian_phase() {
    const int sweeps = options_.laplacian_iterations;
    if (sweeps == 0) return;
    colour_nodes();
    for (int it = 0; it < sweeps; ++it) {
      if (cancelled()) return;
      report(0.5 * it / sweeps);
      std::atomic<std::size_t> moves{0}, moved{0};
      for (const auto& nodes : colour_classes_) {
        quality::detail::parallel_chunks(nodes.size(), 4096,
                                         [&](std::size_t, std::size_t b, std::size_t e) {
                                           std::vector<double> trial;
                                           std::size_t local_moves = 0, local_moved = 0;
                                           for (std::size_t i = b; i < e; ++i) {
                                             const int r = laplacian_step(nodes[i], trial);
                                             local_moves += r > 0;
                                             local_moved += r > 1;
                                           }
                                           moves += local_moves;
                                           moved += local_moved;
                                         });
      }
      for (std::int32_t n : serial_nodes_) {
        const int r = laplacian_step(n, trial_sj_);
        moves += r > 0;
        moved += r > 1;
      }
      result_.laplacian_moves += moves;
      ++result_.laplacian_sweeps;
      if (moved == 0) break;
    }
  }

  // Laplacian sweeps (guarded as in laplacian_phase) over the given nodes and their
  // neighbours only: where the tying max-min moved nodes, to win back the mean it traded
  // (the whole mesh again cost a 40,000-hex grid mesh 8 s).
  void local_laplacian(std::vector<std::int32_t> seeds) {
    std::sort(seeds.begin(), seeds.end());
    seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
    std::vector<std::int32_t> nodes = seeds;
    const auto& nb = topology_.neighbours;
    for (std::int32_t n : seeds)
      for (std::int64_t k = nb.begin(n); k < nb.end(n); ++k) nodes.push_back(nb.items[k]);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    nodes.erase(
        std::remove_if(nodes.begin(), nodes.end(), [&](std::int32_t n) { return !movable_[n]; }),
        nodes.end());
    for (int it = 0; it < options_.laplacian_iterations && !cancelled(); ++it) {
      std::size_t moved = 0;
      for (std::int32_t n : nodes) {
        const int r = laplacian_step(n, trial_sj_);
        result_.laplacian_moves += r > 0;
        moved += r > 1;
      }
      if (moved == 0) break;
    }
  }

  // Gathers the incident hexes of node n for the local objective.
  void gather(std::size_t n) {
    incident_.clear();
    const auto& pts = mesh_.points();
    for (std::int64_t k = topology_.node_hexes.begin(n); k < topology_.node_hexes.end(n); ++k) {
      const std::int32_t item = topology_.node_hexes.items[k];
      IncidentHex h;
      const auto& hex = mesh_.hexes()[item / 8];
      for (int i = 0; i < 8; ++i) h.points[i] = pts[hex[i]];
      h.corner = item % 8;
      incident_.push_back(h);
    }
  }

  // The descent direction restricted to the node's entity (zero when there is none).
  Vec3 feasible_direction(std::size_t n, const Vec3& x, Vec3 d) const {
    const NodeClass c = mesh_.node_classes()[n];
    if (c.dim == 2) {
      const Vec3 normal = face_normal(n, c.id, x);
      d -= d.dot(normal) * normal;
    } else if (c.dim == 1) {
      const auto& nb = topology_.neighbours;
      const auto& pts = mesh_.points();
      Vec3 t = nb.size(n) >= 2 ? Vec3(pts[nb.items[nb.begin(n) + 1]] - pts[nb.items[nb.begin(n)]])
                               : Vec3(pts[nb.items[nb.begin(n)]] - x);
      const double len = t.norm();
      if (!(len > 0)) return Vec3::Zero();
      t /= len;
      d = d.dot(t) * t;
    }
    return d;
  }

  // One descent step of node n on the local objective with a backtracking line search.
  bool descend(std::size_t n, Mode mode) {
    gather(n);
    const Vec3 x = mesh_.points()[n];
    detail::ObjectiveValue v = detail::node_objective(incident_, x, 0);
    const double delta = detail::choose_delta(v.min_det, v.mean_edge);
    if (delta > 0) v = detail::node_objective(incident_, x, delta);
    if (!std::isfinite(v.value)) return false;
    Vec3 d = feasible_direction(n, x, -v.gradient);
    const double norm = d.norm();
    if (!(norm > 0) || !std::isfinite(norm)) return false;
    d /= norm;
    double step = 0.25 * v.mean_edge;
    const double decrease = 1e-12 * std::abs(v.value);
    for (int tries = 0; tries < 14; ++tries, step *= 0.5) {
      Vec3 y;
      FaceId face;
      if (!(mode == Mode::untangle ? untangling_move(n, x, step * d, y, &face)
                                   : constrained_move(n, x, step * d, y)))
        continue;
      const double value = detail::node_objective_value(incident_, y, delta);
      if (!(value < v.value - decrease)) continue;
      if (!acceptable(n, y, mode, trial_sj_)) continue;
      commit(n, y, trial_sj_, face);
      ++result_.optimisation_moves;
      return true;
    }
    return false;
  }

  // One untangling step of node n: the convex Knupp-style model of its frames, minimised
  // in the node's feasible directions, then backtracked until the move is acceptable.
  bool untangle_node(std::size_t n) {
    gather(n);
    const Vec3 x = mesh_.points()[n];
    const std::vector<detail::AffineFrame> frames = detail::affine_frames(incident_, x);
    const double u0 = detail::untangle_value(frames, Vec3::Zero(), kUntangleTarget);
    if (!(u0 > 0)) return false;
    const NodeClass c = mesh_.node_classes()[n];
    Eigen::Matrix<double, 3, Eigen::Dynamic> basis;
    if (c.dim == 3) {
      basis = Eigen::Matrix3d::Identity();
    } else {
      const Vec3 t = feasible_direction(n, x, Vec3::UnitX());
      const Vec3 t2 = feasible_direction(n, x, Vec3::UnitY());
      const Vec3 t3 = feasible_direction(n, x, Vec3::UnitZ());
      // An orthonormal basis of the span of the projected axes (tangent plane or line).
      Eigen::Matrix3d m;
      m << t, t2, t3;
      Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU);
      const auto& sv = svd.singularValues();
      const int rank = (sv.array() > 1e-6 * std::max(sv(0), 1e-300)).count();
      if (rank == 0) return false;
      basis = svd.matrixU().leftCols(std::min(rank, c.dim == 2 ? 2 : 1));
    }
    double mean_edge = 0;
    const auto& nb = topology_.neighbours;
    for (std::int64_t k = nb.begin(n); k < nb.end(n); ++k)
      mean_edge += (mesh_.points()[nb.items[k]] - x).norm();
    mean_edge /= static_cast<double>(nb.size(n));
    const Vec3 d = detail::untangle_step(frames, kUntangleTarget, basis, mean_edge);
    if (!(d.norm() > 1e-12 * mean_edge)) return false;
    double scale = 1;
    for (int tries = 0; tries < 12; ++tries, scale *= 0.5) {
      Vec3 y;
      FaceId face;
      if (!untangling_move(n, x, scale * d, y, &face)) continue;
      if (!(detail::untangle_value(frames, y - x, kUntangleTarget) < u0)) continue;
      if (!acceptable(n, y, Mode::untangle, trial_sj_)) continue;
      commit(n, y, trial_sj_, face);
      ++result_.optimisation_moves;
      return true;
    }
    return false;
  }

  // Untangling (inverted hexes, `untangle` = true) or optimisation (hexes below the target):
  // nodes of the worst hexes first; when a pass moves nothing, the neighbourhood widens.
  void optimisation_phase(bool untangle) {
    const int passes = options_.optimisation_passes;
    const std::size_t nh = mesh_.num_hexes();
    std::vector<char> seen(mesh_.num_nodes(), 0);
    std::vector<std::int32_t> nodes;
    int ring = 0;
    std::size_t last_count = 0;
    double last_worst = 0;
    for (int pass = 0; pass < passes; ++pass) {
      if (cancelled()) return;
      report((untangle ? 0.5 : 0.75) + 0.25 * pass / passes);
      std::vector<std::pair<double, std::int32_t>> bad;
      for (std::size_t h = 0; h < nh; ++h) {
        const bool is_bad = untangle ? sj_[h] <= kFlat : sj_[h] < options_.quality_target;
        if (is_bad) bad.emplace_back(sj_[h], static_cast<std::int32_t>(h));
      }
      if (bad.empty()) return;
      std::sort(bad.begin(), bad.end());
      // Raising the minimum is the aim: the worst hexes lead. On meshes where most hexes are
      // below the target (tetrahedra split into hexahedra: mean about 0.4) a pass over all
      // of them took minutes (HexMe i07, 135,556 hexes: 320 s) for little gain in the
      // minimum; the rest is the Laplacian phase's.
      if (!untangle) bad.resize(std::min(bad.size(), std::max<std::size_t>(2000, nh / 20)));
      // No fewer bad hexes and no better worst one since the last pass: widen the set.
      if (pass > 0 && bad.size() >= last_count && bad[0].first <= last_worst + 1e-9) {
        if (ring >= 2) return;
        ++ring;
      }
      last_count = bad.size();
      last_worst = bad[0].first;
      nodes.clear();
      auto add = [&](std::int32_t node) {
        if (seen[node]) return;
        seen[node] = 1;
        nodes.push_back(node);
      };
      for (const auto& [value, h] : bad)
        for (std::int32_t node : mesh_.hexes()[h]) add(node);
      for (int r = 0; r < ring; ++r) {  // widen by whole rings of hexes
        const std::size_t end = nodes.size();
        for (std::size_t i = 0; i < end; ++i)
          for (std::int64_t k = topology_.node_hexes.begin(nodes[i]);
               k < topology_.node_hexes.end(nodes[i]); ++k)
            for (std::int32_t node : mesh_.hexes()[topology_.node_hexes.items[k] / 8]) add(node);
      }
      std::size_t moves = 0;
      const Mode mode = untangle ? Mode::untangle : Mode::strict;
      for (std::int32_t node : nodes) {
        seen[node] = 0;
        if (!movable_[node]) continue;
        for (int step = 0; step < 4; ++step) {
          // Untangling alternates per pass which model leads: the mean-ratio descent keeps
          // neighbours good, the convex Knupp model escapes where that one stalls.
          const bool knupp_first = untangle && pass % 2 == 1;
          bool moved = knupp_first ? untangle_node(node) : descend(node, mode);
          if (!moved && untangle) moved = knupp_first ? descend(node, mode) : untangle_node(node);
          if (!moved && untangle) moved = untangle_across(node);
          if (!moved) break;
          ++moves;
        }
      }
      if (moves == 0 && ring >= 2) return;
    }
  }

  // Max-min: the optimisation above accepts a move only if no incident hex gets worse
  // (below the target), which on meshes where most hexes are below it (tetrahedra split
  // into hexahedra) leaves the worst ones where they are (HexMe s11: 0.062 before and
  // after). Here a node of a hex below the target moves along the gradient of its worst
  // incident hexes whenever that raises the smallest scaled Jacobian around it: every hex
  // it changes ends above the old local minimum, so the global minimum never falls.
  // Returns the number of moves made. Each pass takes the 200 worst hexes (the minimum is
  // the aim; 2000 cost HexMe i08, 189,000 hexes, minutes); passes stop once three in a row
  // raised the smallest positive scaled Jacobian by less than 1e-4.
  std::size_t maxmin_phase(bool ties) {
    const int passes = 3 * options_.optimisation_passes;
    const std::size_t nh = mesh_.num_hexes();
    std::vector<char> seen(mesh_.num_nodes(), 0);
    std::size_t total = 0;
    double last_worst = -1;
    int stalled = 0;
    for (int pass = 0; pass < passes; ++pass) {
      if (cancelled()) return total;
      report(0.95 + 0.05 * pass / passes);
      std::vector<std::pair<double, std::int32_t>> bad;
      for (std::size_t h = 0; h < nh; ++h)
        if (sj_[h] > 0 && sj_[h] < options_.quality_target)
          bad.emplace_back(sj_[h], static_cast<std::int32_t>(h));
      if (bad.empty()) return total;
      std::sort(bad.begin(), bad.end());
      if (bad[0].first < last_worst + 1e-4) {
        if (++stalled >= 3) return total;
      } else {
        stalled = 0;
        last_worst = bad[0].first;
      }
      bad.resize(std::min<std::size_t>(bad.size(), 200));
      std::vector<std::int32_t> nodes;
      for (const auto& [value, h] : bad)
        for (std::int32_t node : mesh_.hexes()[h])
          if (!seen[node] && movable_[node]) seen[node] = 1, nodes.push_back(node);
      std::size_t moves = 0;
      for (std::int32_t node : nodes) {
        seen[node] = 0;
        for (int step = 0; step < 8 && maxmin_step(node, ties); ++step) ++moves;
      }
      result_.optimisation_moves += moves;
      total += moves;
      if (moves == 0) return total;
    }
    return total;
  }

  // One max-min move of node n; true if the smallest incident scaled Jacobian rose.
  bool maxmin_step(std::size_t n, bool ties) {
    const Vec3 x = mesh_.points()[n];
    double m0 = std::numeric_limits<double>::infinity();
    for (std::int64_t k = topology_.node_hexes.begin(n); k < topology_.node_hexes.end(n); ++k)
      m0 = std::min(m0, sj_[topology_.node_hexes.items[k] / 8]);
    if (!(m0 > 0) || m0 >= options_.quality_target) return false;
    const auto& nb = topology_.neighbours;
    double mean_edge = 0;
    for (std::int64_t k = nb.begin(n); k < nb.end(n); ++k)
      mean_edge += (mesh_.points()[nb.items[k]] - x).norm();
    mean_edge /= static_cast<double>(nb.size(n));
    // Ascent direction: the summed (central-difference) gradients of the incident hexes
    // within 0.02 of the worst (the scaled Jacobian is a minimum over corners: a
    // subgradient is what there is).
    const double h = 1e-5 * mean_edge;
    Vec3 g = Vec3::Zero();
    for (std::int64_t k = topology_.node_hexes.begin(n); k < topology_.node_hexes.end(n); ++k) {
      const std::int32_t item = topology_.node_hexes.items[k];
      if (sj_[item / 8] > m0 + 0.02) continue;
      Vec3 gi;
      for (int i = 0; i < 3; ++i) {
        Vec3 e = Vec3::Zero();
        e[i] = h;
        gi[i] = (hex_sj(item, x + e) - hex_sj(item, x - e)) / (2 * h);
      }
      if (gi.allFinite()) g += gi;
    }
    // No ascent direction on its entity: nothing to try, not even a tie (as measured in
    // bench/results/hexme.md; ties there too are untried).
    const std::optional<Vec3> up = unit_feasible(n, x, g);
    if (!up) return false;
    const bool rose = search_along(n, x, *up, mean_edge, [&](const Vec3&) {
      double m1 = std::numeric_limits<double>::infinity();
      for (double v : trial_sj_) m1 = std::min(m1, v);
      return m1 > m0 + 1e-6;
    });
    if (rose) return true;
    return ties && shortfall_step(n, x, mean_edge);
  }

  // The frames (centre and corners) of node n's hexes with n at x, hex by hex.
  void incident_frames(std::size_t n, const Vec3& x, std::vector<double>& out) const {
    const auto& pts = mesh_.points();
    out.clear();
    for (std::int64_t k = topology_.node_hexes.begin(n); k < topology_.node_hexes.end(n); ++k) {
      const std::int32_t item = topology_.node_hexes.items[k];
      const auto& hex = mesh_.hexes()[item / 8];
      std::array<Vec3, 8> p;
      for (int i = 0; i < 8; ++i) p[i] = pts[hex[i]];
      p[item % 8] = x;
      const std::array<double, 9> v = detail::hex_frame_jacobians(p);
      out.insert(out.end(), v.begin(), v.end());
    }
  }

  // How far the frames of node n's hexes fall short of the target with n at x: the sum over
  // the incident hexes' nine frames of max(0, target - value)^2.
  double shortfall(std::size_t n, const Vec3& x) {
    incident_frames(n, x, frames_);
    const double t = options_.quality_target;
    double sum = 0;
    for (double v : frames_)
      if (v < t) sum += (t - v) * (t - v);
    return sum;
  }

  // A max-min move that ties, for a node that cannot raise its worst hex alone (a swept
  // column under a thin source quad is worst at its bottom and its top corner alike): a move
  // that keeps every incident hex at or above min(its value, the target) and reduces the
  // shortfall of the frames it changes. The other layer's node then raises the hex.
  bool shortfall_step(std::size_t n, const Vec3& x, double mean_edge) {
    const double s0 = shortfall(n, x);
    if (!(s0 > 0)) return false;
    const double h = 1e-5 * mean_edge;
    Vec3 g;
    for (int i = 0; i < 3; ++i) {
      Vec3 e = Vec3::Zero();
      e[i] = h;
      g[i] = (shortfall(n, x - e) - shortfall(n, x + e)) / (2 * h);  // descent
    }
    const std::optional<Vec3> down = unit_feasible(n, x, g);
    if (!down) return false;
    const bool tied = search_along(n, x, *down, mean_edge, [&](const Vec3& y) {
      std::size_t i = 0;  // no incident hex below min(its value, the target)
      for (std::int64_t k = topology_.node_hexes.begin(n); k < topology_.node_hexes.end(n); ++k)
        if (!(trial_sj_[i++] >=
              std::min(sj_[topology_.node_hexes.items[k] / 8], options_.quality_target)))
          return false;
      return shortfall(n, y) < s0 * (1 - 1e-6);
    });
    if (tied) tied_.push_back(static_cast<std::int32_t>(n));
    return tied;
  }

  // The unit direction along the feasible part of g at node n's position x, if there is one.
  std::optional<Vec3> unit_feasible(std::size_t n, const Vec3& x, const Vec3& g) const {
    const Vec3 d = feasible_direction(n, x, g);
    const double norm = d.norm();
    if (!(norm > 0) || !std::isfinite(norm)) return std::nullopt;
    return Vec3(d / norm);
  }

  // Backtracking along the unit direction d from node n's position x: steps of 0.2, 0.1, ...
  // x mean_edge (12 tries); at each the incident hexes' values go to trial_sj_ and
  // `accept(y)` decides; the first accepted position is committed.
  template <class Accept>
  bool search_along(std::size_t n, const Vec3& x, const Vec3& d, double mean_edge, Accept accept) {
    double step = 0.2 * mean_edge;
    for (int tries = 0; tries < 12; ++tries, step *= 0.5) {
      Vec3 y;
      if (!constrained_move(n, x, step * d, y)) continue;
      trial_sj_.clear();
      for (std::int64_t k = topology_.node_hexes.begin(n); k < topology_.node_hexes.end(n); ++k)
        trial_sj_.push_back(hex_sj(topology_.node_hexes.items[k], y));
      if (!accept(y)) continue;
      commit(n, y, trial_sj_);
      return true;
    }
    return false;
  }

  HexMesh& mesh_;
  const occ::Solid& solid_;
  const SmoothOptions& options_;
  const core::Progress& progress_;
  double reported_ = 0;  // the fraction reported so far: the phases run again in rounds
  // Never going back (a later round of the untangling reports the fraction reached).
  void report(double f) { progress_.report("smooth", reported_ = std::max(reported_, f)); }
  SmoothResult& result_;
  detail::SmoothTopology topology_;
  std::vector<char> movable_;
  std::vector<double> sj_;          // current scaled Jacobian per hex
  std::vector<double> node_size_;   // per node: the local size (empty: uniform)
  std::vector<double> trial_sj_;    // incident values of the last serial acceptable() call
  std::vector<double> frames_;      // shortfall()'s frames
  std::vector<std::int32_t> tied_;  // nodes the tying max-min moved
  std::vector<std::vector<std::int32_t>> colour_classes_;  // interior nodes by colour
  std::vector<std::int32_t> serial_nodes_;                 // boundary and uncoloured nodes
  std::vector<IncidentHex> incident_;
  std::vector<std::pair<int, int>> face_pairs_;  // faces sharing an edge, (lower, higher)
  double floor_ = 0;
  double input_min_ = 0;  // the input's minimum, which no hex may fall below
  // face_normal()'s values: only face nodes ask, and they move one at a time.
  struct KnownNormal {
    int face = 0;
    Vec3 at = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    Vec3 normal = Vec3::Zero();
  };
  mutable std::vector<KnownNormal> normals_;
};

}  // namespace

bool untangle_folded(core::HexMesh& mesh, const occ::Solid& solid, const std::vector<char>& fixed,
                     const core::SizeField* size_field, const core::Progress& progress,
                     double min_quality) {
  SmoothOptions o;
  o.fixed = fixed;
  o.size_field = size_field;
  const SmoothResult r = smooth_mesh(mesh, solid, o, progress);
  return r.status == SmoothStatus::ok && r.inverted_after == 0 && r.min_after >= min_quality;
}

void SmoothOptions::validate() const {
  auto fail = [](const std::string& field, const std::string& rule, double value) {
    std::ostringstream s;
    s << field << " must be " << rule << ", got " << value;
    throw std::invalid_argument(s.str());
  };
  if (laplacian_iterations < 0) fail("laplacian_iterations", ">= 0", laplacian_iterations);
  if (optimisation_passes < 0) fail("optimisation_passes", ">= 0", optimisation_passes);
  if (!(quality_target > 0 && quality_target <= 1))
    fail("quality_target", "in (0, 1]", quality_target);
  if (!(relaxation > 0 && relaxation <= 1)) fail("relaxation", "in (0, 1]", relaxation);
  if (!(tolerance >= 0) || !std::isfinite(tolerance)) fail("tolerance", ">= 0", tolerance);
  if (!(active_below > 0 && active_below <= 1)) fail("active_below", "in (0, 1]", active_below);
}

const char* status_name(SmoothStatus s) {
  switch (s) {
    case SmoothStatus::ok:
      return "ok";
    case SmoothStatus::inverted_remain:
      return "inverted_remain";
    case SmoothStatus::cancelled:
      return "cancelled";
  }
  return "unknown";
}

SmoothResult smooth_mesh(HexMesh& mesh, const occ::Solid& solid, const SmoothOptions& options,
                         const core::Progress& progress) {
  options.validate();
  const auto t0 = std::chrono::steady_clock::now();
  SmoothResult result;
  if (mesh.num_hexes() > 0) {
    Smoother smoother(mesh, solid, options, progress, result);
    smoother.run();
  }
  result.seconds = seconds_since(t0);
  progress.report("smooth", 1.0);
  return result;
}

}  // namespace vorohex::smooth
