#pragma once
// Shared parameter grids and tolerance helpers for the inchworm tests.
#include <cmath>
#include <vector>

#include "inchworm/params.hpp"

namespace slipwalk::testing {

/// Relative difference |a − b| / |b|.
inline double rel_diff(double a, double b) { return std::abs(a - b) / std::abs(b); }

/// μ ∈ [0.05, 1] × F ∈ (μmg, 5Mg], both regimes and both ends of the force range.
inline std::vector<inchworm::Params> thesis_grid(int n_mu = 6, int n_force = 9) {
  std::vector<inchworm::Params> grid;
  for (int i = 0; i < n_mu; ++i) {
    const double mu = 0.05 + (1.0 - 0.05) * i / (n_mu - 1);
    for (int k = 0; k < n_force; ++k) {
      inchworm::Params p;
      p.mu = mu;
      const double lo = mu * p.m * p.g;
      const double hi = 5.0 * p.M * p.g;
      // Geometric spacing: dense near μmg, where the motion is slowest.
      p.F = lo * std::pow(hi / lo, (k + 1.0) / n_force);
      if (k == 0) {
        p.F = lo * (1.0 + 1e-3);
      }
      grid.push_back(p);
    }
  }
  return grid;
}

}  // namespace slipwalk::testing
