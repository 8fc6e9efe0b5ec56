// Private to the airlight sources (render/src/airlight_*.cpp): the global adaptive
// Gauss-Kronrod (7/15) integrator in double and the ray-march length of an infinite ray.
#pragma once
#include <functional>
#include <vector>

#include "nimbus/render/airlight.hpp"

namespace nimbus::render::detail {

struct QuadratureResult {
  double value = 0.0;
  double error = 0.0;  // estimated absolute error (|K15 - G7| per interval, summed)
  int intervals = 0;
};

// Integral of f over [a, b] (finite, a <= b), split first at the given interior points, then
// bisecting the interval of largest error until the summed error is below
// max(rel_tol * |value|, abs_tol) or max_intervals is reached.
QuadratureResult integrate_adaptive(const std::function<double(double)>& f, double a, double b,
                                    const std::vector<double>& breakpoints, double rel_tol,
                                    double abs_tol = 0.0, int max_intervals = 2000);

// The length airlight_raymarch marches: Dvp, or for Dvp = inf the cut-off beyond which the rest
// of the integral is below 1e-9 of the whole (render/src/airlight_raymarch.cpp).
double raymarch_length(const AirlightQuery& q);

}  // namespace nimbus::render::detail
