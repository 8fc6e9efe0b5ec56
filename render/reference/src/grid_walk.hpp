// The cells of a grid that a ray crosses, in order: a 3D DDA (Amanatides & Woo 1987). One walk
// for the tracer's brick majorants (traced_media.hpp, TracedCloud::march) and the light volume's
// cells (light_volume_builder.cpp). Internal to render/reference.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/glm.hpp>

namespace nimbus::render::traced {

// Walks the ray u(t) = uo + t ud, t in [t0, t1), through the grid's cells [0, n) of unit side (uo
// and ud in cells, t in the ray's own units): f(ijk, s0, s1) for each cell's part [s0, s1), in
// order, until f returns false. A caller whose cells are k units wide passes uo / k and ud / k
// (a power of two scales exactly, so the walk's numbers are the unscaled walk's to the bit).
template <typename F>
void walk_cells(const glm::dvec3& uo, const glm::dvec3& ud, const int n[3], double t0, double t1, F f) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {  // clip to [0, n)
    if (ud[a] == 0.0) {
      if (uo[a] < 0.0 || uo[a] >= n[a]) return;
      continue;
    }
    double ta = (0.0 - uo[a]) / ud[a], tb = (n[a] - uo[a]) / ud[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 < t1)) return;
  glm::ivec3 cell;
  int step[3];
  double t_next[3], t_delta[3];
  for (int a = 0; a < 3; ++a) {
    cell[a] = std::clamp(static_cast<int>(std::floor(uo[a] + t0 * ud[a])), 0, n[a] - 1);
    if (ud[a] > 0.0) {
      step[a] = 1;
      t_next[a] = ((cell[a] + 1) - uo[a]) / ud[a];
      t_delta[a] = 1.0 / ud[a];
    } else if (ud[a] < 0.0) {
      step[a] = -1;
      t_next[a] = (cell[a] - uo[a]) / ud[a];
      t_delta[a] = -1.0 / ud[a];
    } else {
      step[a] = 0;
      t_next[a] = kInf;
      t_delta[a] = kInf;
    }
  }
  double t = t0;
  while (t < t1) {
    const int a = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2) : (t_next[1] < t_next[2] ? 1 : 2);
    const double s1 = std::min(t_next[a], t1);
    if (s1 > t && !f(cell, t, s1)) return;
    t = s1;
    cell[a] += step[a];
    if (cell[a] < 0 || cell[a] >= n[a]) return;
    t_next[a] += t_delta[a];
  }
}

}  // namespace nimbus::render::traced
