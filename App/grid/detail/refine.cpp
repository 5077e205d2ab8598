#include "grid/detail/refine.h"

#include <algorithm>
#include <bitset>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

namespace vorohex::grid::detail {
namespace {

// Template points in the cell's local coordinates, sixths of its edge: [0, 6]^3.
using Local = std::array<int, 3>;
using LocalHex = std::array<Local, 8>;  // face A (4 points), then face B, corresponding

// Marked corner 0: a cube at the corner, a third of the cell, and one hexahedron on each
// of its three inner faces reaching the opposite faces of the cell.
std::vector<LocalHex> one_corner() {
  return {
      {{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2}}},
      {{{2, 0, 0}, {2, 2, 0}, {2, 2, 2}, {2, 0, 2}, {6, 0, 0}, {6, 6, 0}, {6, 6, 6}, {6, 0, 6}}},
      {{{0, 2, 0}, {2, 2, 0}, {2, 2, 2}, {0, 2, 2}, {0, 6, 0}, {6, 6, 0}, {6, 6, 6}, {0, 6, 6}}},
      {{{0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2}, {0, 0, 6}, {6, 0, 6}, {6, 6, 6}, {0, 6, 6}}}};
}

// Marked corners 0 and 1 (the edge along x at y = z = 0): three cubes along the edge, and
// the rest of the cell's cross-section (the two big quads of the one-corner face pattern)
// swept along x as the face pattern of a marked edge: three segments on the cubes' side,
// one on the far side (two points between, at half the depth).
std::vector<LocalHex> two_corners() {
  std::vector<LocalHex> out;
  for (int i = 0; i < 3; ++i) {
    const int x = 2 * i;
    out.push_back({{{x, 0, 0},
                    {x + 2, 0, 0},
                    {x + 2, 2, 0},
                    {x, 2, 0},
                    {x, 0, 2},
                    {x + 2, 0, 2},
                    {x + 2, 2, 2},
                    {x, 2, 2}}});
  }
  // The face pattern of a marked edge, (x, 2s): s = 0 on the cubes, 1 on the far side.
  const int quads[4][4][2] = {{{0, 0}, {2, 0}, {2, 1}, {0, 2}},
                              {{2, 0}, {4, 0}, {4, 1}, {2, 1}},
                              {{4, 0}, {6, 0}, {6, 2}, {4, 1}},
                              {{2, 1}, {4, 1}, {6, 2}, {0, 2}}};
  // The two regions of the cross-section (y, z) at s = 0, 1/2, 1 (rows) for t = 0, 1 (t = 1:
  // the diagonal both share).
  const int region[2][3][2][2] = {{{{2, 0}, {2, 2}}, {{4, 0}, {4, 4}}, {{6, 0}, {6, 6}}},
                                  {{{0, 2}, {2, 2}}, {{0, 4}, {4, 4}}, {{0, 6}, {6, 6}}}};
  for (const auto& r : region)
    for (const auto& q : quads) {
      LocalHex h;
      for (int t = 0; t < 2; ++t)
        for (int c = 0; c < 4; ++c) h[4 * t + c] = {q[c][0], r[q[c][1]][t][0], r[q[c][1]][t][1]};
      out.push_back(h);
    }
  return out;
}

// Marked corners 0-3 (the face z = 0): a layer of 9 cubes, a layer of 9 hexahedra up to a
// 4 x 4 net of points (corners of the cell's top, points on the side faces at two thirds,
// inner points at half the height), then three hexahedra that join each row's three
// quads into one (the marked edge's face pattern, swept along y) and one that joins the
// three rows into the cell's top.
std::vector<LocalHex> four_corners() {
  std::vector<LocalHex> out;
  auto net = [](int i, int j) -> Local {
    const bool ci = i == 0 || i == 3, cj = j == 0 || j == 3;
    return {2 * i, 2 * j, ci && cj ? 6 : ci || cj ? 4 : 3};
  };
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const int x = 2 * i, y = 2 * j;
      out.push_back({{{x, y, 0},
                      {x + 2, y, 0},
                      {x + 2, y + 2, 0},
                      {x, y + 2, 0},
                      {x, y, 2},
                      {x + 2, y, 2},
                      {x + 2, y + 2, 2},
                      {x, y + 2, 2}}});
      out.push_back({{{x, y, 2},
                      {x + 2, y, 2},
                      {x + 2, y + 2, 2},
                      {x, y + 2, 2},
                      net(i, j),
                      net(i + 1, j),
                      net(i + 1, j + 1),
                      net(i, j + 1)}});
    }
  for (int j = 0; j < 3; ++j)
    out.push_back({{net(1, j), net(2, j), net(3, j), net(0, j), net(1, j + 1), net(2, j + 1),
                    net(3, j + 1), net(0, j + 1)}});
  out.push_back(
      {{net(0, 1), net(3, 1), net(3, 2), net(0, 2), net(0, 0), net(3, 0), net(3, 3), net(0, 3)}});
  return out;
}

// The 48 symmetries of the cube: axis permutation and mirror per axis.
struct Symmetry {
  std::array<int, 3> axis;
  std::array<bool, 3> mirror;
  Local apply(const Local& p) const {
    Local q;
    for (int a = 0; a < 3; ++a) q[a] = mirror[a] ? 6 - p[axis[a]] : p[axis[a]];
    return q;
  }
  int corner(int b) const {  // the corner bit pattern b maps to
    const Local q = apply({6 * (b & 1), 6 * ((b >> 1) & 1), 6 * (b >> 2)});
    return (q[0] / 6) | ((q[1] / 6) << 1) | ((q[2] / 6) << 2);
  }
};

std::vector<Symmetry> symmetries() {
  std::vector<Symmetry> out;
  std::array<int, 3> perm = {0, 1, 2};
  do {
    for (int m = 0; m < 8; ++m) out.push_back({perm, {bool(m & 1), bool(m & 2), bool(m & 4)}});
  } while (std::next_permutation(perm.begin(), perm.end()));
  return out;
}

// Per set of marked corners (bit b: corner b, VTK-free order b = x + 2y + 4z): the
// template (0: one corner, 1: an edge, 2: a face; -1: none fits) and the symmetry that
// carries the template's marked corners onto the set.
struct Choice {
  int kind = -1, symmetry = 0;
};

struct Templates {
  std::vector<Symmetry> sym = symmetries();
  std::array<std::vector<LocalHex>, 3> hexes = {one_corner(), two_corners(), four_corners()};
  std::array<Choice, 256> choice;
  Templates() {
    const int canonical[3] = {0b1, 0b11, 0b1111};
    for (int kind = 0; kind < 3; ++kind)
      for (int s = 0; s < int(sym.size()); ++s) {
        int mask = 0;
        for (int b = 0; b < 8; ++b)
          if (canonical[kind] >> b & 1) mask |= 1 << sym[s].corner(b);
        if (choice[mask].kind < 0) choice[mask] = {kind, s};
      }
  }
};

const Templates& templates() {
  static const Templates t;
  return t;
}

bool allowed(int mask) {
  return mask == 0 || mask == 255 || templates().choice[mask].kind >= 0;
}

// The smallest set of corners containing `mask` that a template fits (all eight when
// none smaller does): three corners of a face complete the face, not the cell.
int completion(int mask) {
  static const std::array<int, 256> table = [] {
    std::array<int, 256> out{};
    for (int m = 0; m < 256; ++m) {
      int best = 255;
      for (int s = 0; s < 256; ++s)
        if ((s & m) == m && allowed(s) && std::bitset<8>(s).count() < std::bitset<8>(best).count())
          best = s;
      out[m] = best;
    }
    return out;
  }();
  return table[mask];
}

LatticePoint corner_of(const LevelCell& c, int b) {
  return {c.origin[0] + c.extent * (b & 1), c.origin[1] + c.extent * ((b >> 1) & 1),
          c.origin[2] + c.extent * (b >> 2)};
}

}  // namespace

core::Vec3 lattice_point(const GridFrame& frame, std::int64_t unit, const LatticePoint& p) {
  core::Vec3 out = core::Vec3::Zero();
  for (int a = 0; a < 3; ++a) {
    const std::vector<double>& lines = frame.lines[a];
    const std::int64_t cell = std::min<std::int64_t>(p[a] / unit, std::int64_t(lines.size()) - 2);
    const double f = double(p[a] - cell * unit) / double(unit);
    out += frame.axes[a] * (lines[cell] + f * (lines[cell + 1] - lines[cell]));
  }
  return out;
}

RefinedGrid refine_grid(const GridFrame& frame, int max_level, const RefineChoice& choose,
                        std::size_t max_hexes) {
  if (max_level < 0 || max_level > 6)
    throw std::invalid_argument("refine_grid: max_level must be in [0, 6]");
  RefinedGrid g;
  g.max_level = max_level;
  for (int l = 0; l < max_level; ++l) g.unit *= 3;
  const std::array<std::int64_t, 3> box = {frame.cells(0) * g.unit, frame.cells(1) * g.unit,
                                           frame.cells(2) * g.unit};
  std::unordered_map<LatticePoint, std::int32_t, LatticeHash> node_of;
  auto node = [&](const LatticePoint& p) {
    auto [it, fresh] = node_of.try_emplace(p, std::int32_t(g.lattice.size()));
    if (fresh) g.lattice.push_back(p), g.points.push_back(lattice_point(frame, g.unit, p));
    return it->second;
  };
  auto emit = [&](std::array<LatticePoint, 8> p, int level) {
    // Positive orientation (VTK): the mean edge directions along the three local axes.
    auto edge = [&](int a, int b, int c, int d, int e, int f, int g2, int h, int axis) {
      return double(p[b][axis] - p[a][axis] + p[c][axis] - p[d][axis] + p[f][axis] - p[e][axis] +
                    p[g2][axis] - p[h][axis]);
    };
    core::Vec3 ex, ey, ez;
    for (int a = 0; a < 3; ++a) {
      ex[a] = edge(0, 1, 2, 3, 4, 5, 6, 7, a);
      ey[a] = edge(0, 3, 2, 1, 4, 7, 6, 5, a);
      ez[a] = edge(0, 4, 5, 1, 3, 7, 6, 2, a);
    }
    if (ex.dot(ey.cross(ez)) < 0)
      for (int c = 0; c < 4; ++c) std::swap(p[c], p[c + 4]);
    std::array<std::int32_t, 8> h;
    for (int c = 0; c < 8; ++c) h[c] = node(p[c]);
    g.hexes.push_back(h);
    g.level.push_back(std::int8_t(level));
  };
  // VTK corner order of a cell from the bit pattern order (x + 2y + 4z).
  constexpr int kVtk[8] = {0, 1, 3, 2, 4, 5, 7, 6};

  std::vector<LevelCell> cells;
  for (std::int64_t k = 0; k < frame.cells(2); ++k)
    for (std::int64_t j = 0; j < frame.cells(1); ++j)
      for (std::int64_t i = 0; i < frame.cells(0); ++i)
        cells.push_back({{i * g.unit, j * g.unit, k * g.unit}, g.unit});
  const Templates& t = templates();
  for (int level = 0; !cells.empty(); ++level) {
    std::vector<char> want;
    if (level < max_level) want = choose(level, cells);
    want.resize(cells.size(), 0);
    const std::int64_t e = cells.front().extent;
    // Corners on the border of this level's region (level > 0) are never marked.
    std::unordered_set<LatticePoint, LatticeHash> active;
    if (level > 0)
      for (const LevelCell& c : cells) active.insert(c.origin);
    auto border = [&](const LatticePoint& v) {
      if (level == 0) return false;
      for (int d = 0; d < 8; ++d) {
        LatticePoint o = {v[0] - e * (d & 1), v[1] - e * ((d >> 1) & 1), v[2] - e * (d >> 2)};
        bool in_box = true;
        for (int a = 0; a < 3; ++a) in_box = in_box && o[a] >= 0 && o[a] + e <= box[a];
        if (in_box && !active.count(o)) return true;
      }
      return false;
    };
    std::unordered_set<LatticePoint, LatticeHash> marked, banned;
    for (std::size_t c = 0; c < cells.size(); ++c)
      if (want[c])
        for (int b = 0; b < 8; ++b) {
          const LatticePoint v = corner_of(cells[c], b);
          if (banned.count(v)) continue;
          if (border(v))
            banned.insert(v);
          else
            marked.insert(v);
        }
    auto mask_of = [&](const LevelCell& c) {
      int m = 0;
      for (int b = 0; b < 8; ++b) m |= int(marked.count(corner_of(c, b)) != 0) << b;
      return m;
    };
    // Closure: a cell whose marked corners fit no template gets the fewest more marks that
    // make one fit (all eight: it is refined whole), unless one of those corners may not be
    // marked; then its marks go (and those corners stay unmarked).
    for (bool changed = !marked.empty(); changed;) {
      changed = false;
      for (const LevelCell& c : cells) {
        const int m = mask_of(c);
        if (allowed(m)) continue;
        const int full = completion(m);
        bool blocked = false;
        for (int b = 0; b < 8 && !blocked; ++b)
          if (!(m >> b & 1) && (full >> b & 1)) {
            const LatticePoint v = corner_of(c, b);
            blocked = banned.count(v) || border(v);
          }
        for (int b = 0; b < 8; ++b) {
          const LatticePoint v = corner_of(c, b);
          if (blocked) {
            if (marked.erase(v)) banned.insert(v);
          } else if (!(m >> b & 1) && (full >> b & 1)) {
            marked.insert(v);
          }
        }
        changed = true;
      }
    }
    // The hexahedra this refinement would give at least (the next level's cells whole).
    std::size_t at_least = g.hexes.size();
    for (const LevelCell& cell : cells) {
      const int m = mask_of(cell);
      at_least += m == 255 ? 27 : m == 0 ? 1 : t.hexes[t.choice[m].kind].size();
    }
    if (at_least > max_hexes) marked.clear(), g.budget_reached = true;
    std::vector<LevelCell> next;
    for (const LevelCell& cell : cells) {
      const int m = mask_of(cell);
      if (m == 255) {
        ++g.templates[3];
        const std::int64_t f = e / 3;
        for (int k = 0; k < 3; ++k)
          for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i)
              next.push_back(
                  {{cell.origin[0] + i * f, cell.origin[1] + j * f, cell.origin[2] + k * f}, f});
        continue;
      }
      if (m == 0) {
        std::array<LatticePoint, 8> p;
        for (int b = 0; b < 8; ++b) p[kVtk[b]] = corner_of(cell, b);
        emit(p, level);
        continue;
      }
      const Choice& ch = t.choice[m];
      ++g.templates[ch.kind];
      const Symmetry& s = t.sym[ch.symmetry];
      const std::int64_t sixth = e / 6;
      for (const LocalHex& lh : t.hexes[ch.kind]) {
        std::array<LatticePoint, 8> p;
        for (int c = 0; c < 8; ++c) {
          const Local q = s.apply(lh[c]);
          p[c] = {cell.origin[0] + sixth * q[0], cell.origin[1] + sixth * q[1],
                  cell.origin[2] + sixth * q[2]};
        }
        emit(p, level);
      }
    }
    cells = std::move(next);
  }
  return g;
}

}  // namespace vorohex::grid::detail
