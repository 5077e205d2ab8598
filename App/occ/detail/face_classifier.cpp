#include "occ/detail/face_classifier.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Plane.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <cmath>

namespace vorohex::occ::detail {
namespace {

constexpr std::uint8_t kUnknown = 0, kIn = 1, kOut = 2;

// Marks the cells a pcurve passes through. Each piece of the curve is halved until its middle
// lies within a quarter of a cell of its chord, then the chord is walked in quarter cells.
// False when the curve cannot be followed (too many pieces: then no raster at all).
class Rasteriser {
 public:
  Rasteriser(std::vector<std::uint8_t>& marks, int n, double u0, double v0, double du, double dv)
      : marks_(marks), n_(n), u0_(u0), v0_(v0), du_(du), dv_(dv) {}

  bool curve(const Geom2d_Curve& c, double first, double last) {
    constexpr int kStart = 16;  // so that a wave whose middle is on its chord is not missed
    gp_Pnt2d a = c.Value(first);
    for (int k = 1; k <= kStart; ++k) {
      const double t0 = first + (last - first) * (k - 1) / kStart;
      const double t1 = first + (last - first) * k / kStart;
      const gp_Pnt2d b = c.Value(t1);
      if (!piece(c, t0, a, t1, b, 0)) return false;
      a = b;
    }
    return true;
  }

 private:
  bool piece(const Geom2d_Curve& c, double t0, const gp_Pnt2d& a, double t1, const gp_Pnt2d& b,
             int depth) {
    if (++pieces_ > 200000) return false;
    const gp_Pnt2d m = c.Value(0.5 * (t0 + t1));
    const double off_u = (m.X() - 0.5 * (a.X() + b.X())) / du_;
    const double off_v = (m.Y() - 0.5 * (a.Y() + b.Y())) / dv_;
    if (!std::isfinite(off_u) || !std::isfinite(off_v)) return false;
    if (std::max(std::abs(off_u), std::abs(off_v)) > 0.25) {
      if (depth > 24) return false;
      return piece(c, t0, a, 0.5 * (t0 + t1), m, depth + 1) &&
             piece(c, 0.5 * (t0 + t1), m, t1, b, depth + 1);
    }
    const double cells = std::max(std::abs(b.X() - a.X()) / du_, std::abs(b.Y() - a.Y()) / dv_);
    const int steps = int(std::ceil(4 * cells)) + 1;
    // A chord can cross the box a few times at most; far longer, the pcurve runs far outside
    // the face's parameter box (bad geometry): no raster.
    if (steps > 16 * (n_ + 2)) return false;
    for (int s = 0; s <= steps; ++s) {
      const double w = double(s) / steps;
      mark((1 - w) * a.X() + w * b.X(), (1 - w) * a.Y() + w * b.Y());
    }
    return true;
  }

  // A point outside the box marks the cell of the box nearest to it (conservative).
  void mark(double u, double v) {
    const int i = std::clamp(int(std::floor((u - u0_) / du_)), 0, n_ - 1);
    const int j = std::clamp(int(std::floor((v - v0_) / dv_)), 0, n_ - 1);
    marks_[std::size_t(j) * n_ + i] = 1;
  }

  std::vector<std::uint8_t>& marks_;
  int n_;
  double u0_, v0_, du_, dv_;
  long pieces_ = 0;
};

// The face, FORWARD, with a stored pcurve on every edge. An edge on a plane often has none
// (STEP and OCCT's own booleans leave them out), and OCCT then projects its 3D curve onto the
// plane each time one is asked for (BRep_Tool::CurveOnPlane): its exact classifier, which
// answers the points near the boundary, asks for every edge's pcurve on every call. That was
// a quarter of the tet split's smoothing on HexMe i03 (perf). The pcurves stored are the ones
// it would project (the same answers), on a copy: the caller's shape is left as it was.
TopoDS_Face with_stored_pcurves(const TopoDS_Face& face) {
  const TopoDS_Face forward = TopoDS::Face(face.Oriented(TopAbs_FORWARD));
  TopLoc_Location location;
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(forward, location);
  if (surface.IsNull() || !surface->IsKind(STANDARD_TYPE(Geom_Plane))) return forward;
  bool missing = false;
  for (TopExp_Explorer ex(forward, TopAbs_EDGE); ex.More() && !missing; ex.Next()) {
    Standard_Boolean stored = Standard_True;
    double first = 0, last = 0;
    BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), forward, first, last, &stored);
    missing = !stored;
  }
  if (!missing) return forward;
  try {
    BRepBuilderAPI_Copy copy(forward, /*copyGeom=*/false, /*copyMesh=*/false);
    const TopoDS_Face copied = TopoDS::Face(copy.Shape());
    for (TopExp_Explorer ex(copied, TopAbs_EDGE); ex.More(); ex.Next())
      BRepLib::BuildPCurveForEdgeOnPlane(TopoDS::Edge(ex.Current()), copied);
    return copied;
  } catch (const Standard_Failure&) {
    return forward;  // OCCT projects them on each call, as before
  }
}

}  // namespace

FaceClassifier::FaceClassifier(const TopoDS_Face& face, double tolerance, int resolution)
    : face_(with_stored_pcurves(face)),
      tolerance_(tolerance),
      resolution_(std::max(resolution, 4)),
      occt_(std::make_unique<BRepTopAdaptor_FClass2d>(face_, tolerance)) {}

bool FaceClassifier::ensure_raster() const {
  if (asked_.load(std::memory_order_relaxed) < kQuestionsBeforeRaster &&
      asked_.fetch_add(1, std::memory_order_relaxed) < kQuestionsBeforeRaster)
    return false;
  std::call_once(built_, [this] {
    try {
      build();
    } catch (const Standard_Failure&) {
      cells_.clear();
    }
  });
  return true;
}

FaceClassifier::~FaceClassifier() = default;

void FaceClassifier::build() const {
  const TopoDS_Face& forward = face_;
  const double tolerance = tolerance_;
  const int n = resolution_;
  double u1 = 0, v1 = 0;
  BRepTools::UVBounds(forward, u0_, u1, v0_, v1);
  if (!(std::isfinite(u0_) && std::isfinite(u1) && std::isfinite(v0_) && std::isfinite(v1))) return;
  if (!(u1 > u0_) || !(v1 > v0_)) return;
  n_ = n;
  du_ = (u1 - u0_) / n, dv_ = (v1 - v0_) / n;
  // OCCT answers ON within its tolerance of the boundary: that band must lie in the cells
  // left to it.
  if (tolerance > 0.25 * std::min(du_, dv_)) return;
  const BRepAdaptor_Surface surface(forward, false);
  wraps_ = (surface.IsUPeriodic() && u1 - u0_ > surface.UPeriod() - 2 * du_) ||
           (surface.IsVPeriodic() && v1 - v0_ > surface.VPeriod() - 2 * dv_);

  std::vector<std::uint8_t> marks(std::size_t(n) * n, 0);
  Rasteriser raster(marks, n, u0_, v0_, du_, dv_);
  for (TopExp_Explorer ex(forward, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
    double first = 0, last = 0;
    const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(e, forward, first, last);
    if (c.IsNull() || !std::isfinite(first) || !std::isfinite(last)) return;
    if (!raster.curve(*c, first, last)) return;
  }
  // The neighbours of a crossed cell too: the boundary passes within a quarter of a cell of
  // the walked chords, and OCCT's tolerance band is narrower than that.
  std::vector<std::uint8_t> near(marks);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (!marks[std::size_t(j) * n + i]) continue;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int a = i + di, b = j + dj;
          if (a >= 0 && a < n && b >= 0 && b < n) near[std::size_t(b) * n + a] = 1;
        }
    }
  // Each region of cells the boundary does not reach is wholly in or out: asked of OCCT at
  // three of its cells, which must agree (else the region is left to OCCT).
  std::vector<std::uint8_t> cells(std::size_t(n) * n, kUnknown);
  std::vector<char> seen(near.begin(), near.end());
  std::vector<int> region, stack;
  for (int start = 0; start < n * n; ++start) {
    if (seen[start]) continue;
    region.clear();
    stack.assign(1, start);
    seen[start] = 1;
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      region.push_back(c);
      const int i = c % n, j = c / n;
      const int next[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
      for (const auto& [a, b] : next)
        if (a >= 0 && a < n && b >= 0 && b < n && !seen[b * n + a])
          seen[b * n + a] = 1, stack.push_back(b * n + a);
    }
    std::uint8_t state = kUnknown;
    bool agree = true;
    for (int c : {region.front(), region[region.size() / 2], region.back()}) {
      const gp_Pnt2d centre(u0_ + (c % n + 0.5) * du_, v0_ + (c / n + 0.5) * dv_);
      const TopAbs_State s = occt_->Perform(centre, false);
      const std::uint8_t here = s == TopAbs_IN ? kIn : s == TopAbs_OUT ? kOut : kUnknown;
      if (here == kUnknown || (state != kUnknown && here != state)) agree = false;
      state = here;
    }
    if (agree)
      for (int c : region) cells[c] = state;
  }
  cells_ = std::move(cells);
}

bool FaceClassifier::rastered() const {
  return asked_.load() >= kQuestionsBeforeRaster && ensure_raster() && !cells_.empty();
}

double FaceClassifier::share_known() const {
  if (!rastered()) return 0;
  return double(std::count_if(cells_.begin(), cells_.end(), [](auto c) { return c != 0; })) /
         double(cells_.size());
}

TopAbs_State FaceClassifier::perform(double u, double v, bool recadre_on_periodic) const {
  if (ensure_raster() && !cells_.empty()) {
    const double x = (u - u0_) / du_, y = (v - v0_) / dv_;
    if (x >= 0 && y >= 0 && x < n_ && y < n_) {
      const std::uint8_t c = cells_[std::size_t(y) * n_ + std::size_t(x)];
      if (c == kIn) return TopAbs_IN;
      if (c == kOut && !(recadre_on_periodic && wraps_)) return TopAbs_OUT;
    }
  }
  return occt_->Perform(gp_Pnt2d(u, v), recadre_on_periodic);
}

}  // namespace vorohex::occ::detail
