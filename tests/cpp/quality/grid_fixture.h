// Structured hex grids for the quality tests.
#pragma once

#include <array>

#include "core/hex_mesh.h"

namespace vorohex::quality::testing {

// nx x ny x nz unit-spaced cells (spacing h) starting at origin; node (i, j, k) has index
// i + (nx + 1) * (j + (ny + 1) * k). All nodes interior-classified.
inline core::HexMesh structured_grid(int nx, int ny, int nz, double h = 1.0,
                                     const core::Vec3& origin = core::Vec3::Zero()) {
  core::HexMesh m;
  m.reserve(std::size_t(nx + 1) * (ny + 1) * (nz + 1), std::size_t(nx) * ny * nz);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.add_node(origin + h * core::Vec3(i, j, k));
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.add_hex({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                   id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                   id(i, j + 1, k + 1)});
  return m;
}

// Corners of the axis-aligned box [0,a]x[0,b]x[0,c] in VTK order.
inline std::array<core::Vec3, 8> box_corners(double a = 1, double b = 1, double c = 1) {
  return {core::Vec3(0, 0, 0), core::Vec3(a, 0, 0), core::Vec3(a, b, 0), core::Vec3(0, b, 0),
          core::Vec3(0, 0, c), core::Vec3(a, 0, c), core::Vec3(a, b, c), core::Vec3(0, b, c)};
}

}  // namespace vorohex::quality::testing
