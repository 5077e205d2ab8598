// Point-in-face classification in a face's (u, v) parameters, the same answers as OCCT's
// BRepTopAdaptor_FClass2d, sooner. OCCT tests a point against the polygon of the face's
// boundary, a cost in the number of its points on every call; projecting boundary nodes onto
// their faces (smoothing, the fallbacks) calls it millions of times, and it was more than half
// of the time of meshing HexMe i05 (perf, session 22). A raster of the face's parameter box
// answers most points at once: the cells the boundary curves pass through, and their
// neighbours, are left to OCCT; every other cell lies wholly inside or wholly outside the
// face, known from OCCT's answer at a few cells of each connected region of such cells.
#pragma once

#include <TopAbs_State.hxx>
#include <TopoDS_Face.hxx>

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

class BRepTopAdaptor_FClass2d;

namespace vorohex::occ::detail {

class FaceClassifier {
 public:
  // face: in any orientation (classified as FORWARD, like OCCT's); tolerance: OCCT's, in
  // (u, v); resolution: raster cells per parameter direction (at least 4).
  FaceClassifier(const TopoDS_Face& face, double tolerance, int resolution = 256);
  ~FaceClassifier();

  // BRepTopAdaptor_FClass2d::Perform(uv, recadre_on_periodic): IN, OUT or ON. Thread-safe.
  TopAbs_State perform(double u, double v, bool recadre_on_periodic = true) const;

  // Whether a raster was built (not for faces whose pcurves could not be sampled, or whose
  // parameter box is degenerate), and the share of its cells that answer without OCCT.
  bool rastered() const;
  double share_known() const;

 private:
  // The raster is built once a face has been asked kQuestionsBeforeRaster times (OCCT answers
  // until then): most solids the decomposition makes of its pieces are asked a few questions
  // per face, fewer than building a raster is worth. Once, also from several threads.
  static constexpr int kQuestionsBeforeRaster = 256;
  bool ensure_raster() const;
  void build() const;
  TopoDS_Face face_;  // FORWARD
  double tolerance_;
  int resolution_;
  std::unique_ptr<BRepTopAdaptor_FClass2d> occt_;
  mutable std::atomic<int> asked_{0};
  mutable std::once_flag built_;
  mutable std::vector<std::uint8_t> cells_;  // n_ x n_, row-major in v; 0 unknown, 1 in, 2 out
  mutable int n_ = 0;
  mutable double u0_ = 0, v0_ = 0, du_ = 1, dv_ = 1;
  // A periodic surface whose face spans (almost) a whole period: OCCT may find a point
  // outside the box inside it after shifting it by a period, so OUT cells ask OCCT.
  mutable bool wraps_ = false;
};

}  // namespace vorohex::occ::detail
