#include "inchworm/closed_form.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <cmath>
#include <memory>

#include "core/error.hpp"

namespace slipwalk::inchworm {

StrokeAccelerations stroke_accelerations(const Params& p) {
  StrokeAccelerations s{};
  const double fm = p.mu * p.m * p.g;
  const double fM = p.mu * p.M * p.g;
  s.a_x = (p.F - fm) / p.m;
  s.b = (p.F + fM) / p.M;
  s.r1 = p.F / p.m + p.F / p.M;
  s.kappa = p.F / (p.F + fM);
  s.regime = regime_of(p);
  if (s.regime == Regime::kOne) {
    // M held by static friction: only m moves; the CoM gains (F − μmg)/(m + M).
    s.r2 = s.a_x;
    s.a2 = (p.F - fm) / (p.m + p.M);
  } else {
    // M slides back at (F − μMg)/M; net friction on the CoM is μg(M − m) forward.
    s.r2 = s.a_x + (p.F - fM) / p.M;
    s.a2 = p.mu * p.g * p.swap_ratio();
  }
  return s;
}

Stroke stroke_map(const Params& p, double c0) {
  if (!(c0 >= 0.0)) {
    throw core::ComputationError("stroke_map: the closed form needs c0 >= 0");
  }
  const StrokeAccelerations s = stroke_accelerations(p);
  const double dL = p.stroke();
  Stroke out{};
  const double t1 = c0 / s.b;
  const double phase1_length = 0.5 * s.r1 * t1 * t1;
  if (phase1_length >= dL) {
    // The length limit comes before M stops: one phase, CoM decelerating at μg.
    const double T = std::sqrt(2.0 * dL / s.r1);
    out.c_next = c0 - p.mu * p.g * T;
    out.duration = T;
    out.t1 = T;
    out.t2 = 0.0;
    out.displacement = c0 * T - 0.5 * p.mu * p.g * T * T;
    out.ends_before_M_stops = true;
    return out;
  }
  // eq. 2.9 (corrected): ½ r2 t2² + (r1 t1) t2 − R = 0, R the length left after phase 1.
  const double R = dL - phase1_length;
  const double rate = s.r1 * t1;
  const double t2 = 2.0 * R / (rate + std::sqrt(rate * rate + 2.0 * s.r2 * R));
  const double c1 = s.kappa * c0;
  out.c_next = c1 + s.a2 * t2;
  out.duration = t1 + t2;
  out.t1 = t1;
  out.t2 = t2;
  out.displacement = 0.5 * (c0 + c1) * t1 + c1 * t2 + 0.5 * s.a2 * t2 * t2;
  out.ends_before_M_stops = false;
  return out;
}

namespace {

SteadyState finish(const Params& p, const StrokeAccelerations& s, double c0, double t1, double t2) {
  SteadyState st{};
  st.c0 = c0;
  st.t1 = t1;
  st.t2 = t2;
  st.period = t1 + t2;
  st.regime = s.regime;
  st.v_ss = 0.5 * (1.0 + s.kappa) * c0 + p.swap_ratio() * p.stroke() / (2.0 * st.period);
  // d c_next / d c0 = κ + a2 dt2/dc0, dt2/dc0 from differentiating the length equation.
  const double dt2 = -s.r1 * (t1 + t2) / (s.b * (s.r2 * t2 + s.r1 * t1));
  st.contraction = s.kappa + s.a2 * dt2;
  return st;
}

}  // namespace

SteadyState steady_state_closed_form(const Params& p) {
  const StrokeAccelerations s = stroke_accelerations(p);
  const double one_minus_kappa = p.mu * p.M * p.g / (p.F + p.mu * p.M * p.g);
  const double u = one_minus_kappa / s.a2;  // t2 / c0
  const double v = 1.0 / s.b;               // t1 / c0
  const double Q = 0.5 * s.r1 * v * v + s.r1 * v * u + 0.5 * s.r2 * u * u;
  const double c0 = std::sqrt(p.stroke() / Q);
  return finish(p, s, c0, c0 * v, c0 * u);
}

SteadyState steady_state_fixed_point(const Params& p) {
  // h(c0) = c_next(c0) − c0: h(0) > 0 (the CoM gains speed in phase 2 from rest), and h < 0 for
  // large c0 (a stroke that ends before M stops only loses speed). Bracket by doubling.
  auto h = [](double c0, void* params) {
    const auto* pp = static_cast<const Params*>(params);
    return stroke_map(*pp, c0).c_next - c0;
  };
  Params copy = p;
  gsl_function fn{+h, &copy};
  double lo = 0.0;
  double hi = std::sqrt(p.stroke() * p.g);
  int doublings = 0;
  while (h(hi, &copy) >= 0.0) {
    lo = hi;
    hi *= 2.0;
    if (++doublings > 200) {
      throw core::ComputationError("steady_state_fixed_point: no bracket for the fixed point");
    }
  }
  std::unique_ptr<gsl_root_fsolver, decltype(&gsl_root_fsolver_free)> solver(
      gsl_root_fsolver_alloc(gsl_root_fsolver_brent), &gsl_root_fsolver_free);
  gsl_root_fsolver_set(solver.get(), &fn, lo, hi);
  int status = GSL_CONTINUE;
  int iter = 0;
  double root = 0.5 * (lo + hi);
  while (status == GSL_CONTINUE && iter < 200) {
    ++iter;
    gsl_root_fsolver_iterate(solver.get());
    root = gsl_root_fsolver_root(solver.get());
    status = gsl_root_test_interval(gsl_root_fsolver_x_lower(solver.get()),
                                    gsl_root_fsolver_x_upper(solver.get()), 0.0, 1e-15);
  }
  if (status != GSL_SUCCESS) {
    throw core::ComputationError("steady_state_fixed_point: Brent did not converge");
  }
  const Stroke st = stroke_map(p, root);
  SteadyState out = finish(p, stroke_accelerations(p), root, st.t1, st.t2);
  out.iterations = iter;
  return out;
}

double governing_law_eq_2_6(double mu, double f_tilde) {
  return 0.073 * mu * (1.0 - 0.178 * mu * mu) * f_tilde + 0.11 * mu + 0.20;
}

}  // namespace slipwalk::inchworm
