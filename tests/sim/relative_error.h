// Relative 2-norm difference of two same-length vectors, ||a - r|| / ||r||: the force and
// position errors the backend tests report. Infinite when the lengths differ or r is zero.
#pragma once

#include <cmath>
#include <vector>

inline double relative_error(const std::vector<double>& a, const std::vector<double>& r) {
  double n = 0, d = 0;
  for (std::size_t i = 0; i < r.size() && i < a.size(); ++i) {
    n += (a[i] - r[i]) * (a[i] - r[i]);
    d += r[i] * r[i];
  }
  return a.size() == r.size() && d > 0 ? std::sqrt(n / d) : INFINITY;
}
