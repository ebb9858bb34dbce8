#include "robots/four_bar.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/range.hpp"

namespace slipwalk::robots {

namespace {

/// v turned by +90°.
Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

double cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  return p.x() * q.y() - p.y() * q.x();
}

// A link of a leg: from a tenth of a millimetre to 10 m keeps the loop closure's squares and
// the Cramer determinant (products of four lengths) normal.
void require_length(const char* field, double value) {
  core::require_in(std::string("four_bar.") + field, value, core::closed(1e-4, 10.0, "m"));
}

}  // namespace

void validate(const FourBar& f) {
  require_length("crank", f.crank);
  require_length("coupler", f.coupler);
  require_length("rocker", f.rocker);
  require_length("toe_distance", f.toe_distance);
  for (int i = 0; i < 2; ++i) {
    core::require_in("four_bar.rocker_pivot[" + std::to_string(i) + "]", f.rocker_pivot(i),
                     core::closed(-10.0, 10.0, "m"));
  }
  core::require_in("four_bar.toe_angle", f.toe_angle, core::closed(-1e3, 1e3, "rad"));
  if (f.branch != 1 && f.branch != -1) {
    throw core::InputError("four_bar.branch", "must be +1 or -1, got " + std::to_string(f.branch));
  }
  // The crank pin A sweeps ℓ = |O₄ − A| over [d − a, d + a]; B exists and the coupler and rocker
  // stay off collinear (toggle) positions iff |b − c| < d − a and d + a < b + c (Grashof).
  const double d = f.rocker_pivot.norm();
  const double a = f.crank;
  if (!(d - a > std::abs(f.coupler - f.rocker)) || !(d + a < f.coupler + f.rocker)) {
    throw core::InputError("four_bar",
                           "not a crank-rocker: need |coupler - rocker| < ground - crank and "
                           "ground + crank < coupler + rocker (ground = |rocker_pivot| = " +
                               core::format_double(d) + ")");
  }
}

FourBarPose four_bar_pose(const FourBar& f, double theta) {
  const double a = f.crank;
  const double b = f.coupler;
  const double c = f.rocker;
  const Eigen::Vector2d& O4 = f.rocker_pivot;
  const double s = f.branch;

  FourBarPose p{};
  p.A = {a * std::cos(theta), a * std::sin(theta)};
  p.dA = perp(p.A);

  // Loop closure: intersection of the circles |B − A| = b and |B − O₄| = c.
  const Eigen::Vector2d D = O4 - p.A;
  const double l = D.norm();
  const Eigen::Vector2d u = D / l;
  const double x = (b * b - c * c + l * l) / (2.0 * l);
  const double h = std::sqrt(std::max(b * b - x * x, 0.0));
  p.B = p.A + x * u + s * h * perp(u);

  // Velocity: [(B − A)ᵀ; (B − O₄)ᵀ] B' = [(B − A)·A'; 0] (differentiated constraints).
  const Eigen::Vector2d r3 = p.B - p.A;
  const Eigen::Vector2d r4 = p.B - O4;
  const double det = cross(r3, r4);
  const double rhs = r3.dot(p.dA);
  // Cramer's rule on rows r3ᵀ, r4ᵀ with right-hand side (rhs, 0).
  p.dB = {rhs * r4.y() / det, -rhs * r4.x() / det};

  // The toe: P = A + (e/b) R(γ) (B − A), rigid on the coupler.
  const double cg = std::cos(f.toe_angle);
  const double sg = std::sin(f.toe_angle);
  const double k = f.toe_distance / b;
  const Eigen::Vector2d dr3 = p.dB - p.dA;
  p.P = p.A + k * Eigen::Vector2d(cg * r3.x() - sg * r3.y(), sg * r3.x() + cg * r3.y());
  p.dP = p.dA + k * Eigen::Vector2d(cg * dr3.x() - sg * dr3.y(), sg * dr3.x() + cg * dr3.y());

  p.coupler_angle = std::atan2(r3.y(), r3.x());
  p.rocker_angle = std::atan2(r4.y(), r4.x());
  p.transmission_sin = det / (b * c);
  return p;
}

}  // namespace slipwalk::robots
