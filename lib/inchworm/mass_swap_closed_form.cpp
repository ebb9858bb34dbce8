#include "inchworm/mass_swap_closed_form.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::inchworm {

namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();

/// Smallest τ > 0 with q τ + ½ r τ² = R (R > 0), or +inf if there is none: the root
/// 2R / (q + sqrt(q² + 2 r R)), which has no cancellation whatever the signs of q and r.
double time_to_cover(double R, double q, double r) {
  if (R <= 0.0) {
    return 0.0;
  }
  const double disc = q * q + 2.0 * r * R;
  if (disc < 0.0) {
    return kNever;  // the relative motion turns back before covering R
  }
  const double den = q + std::sqrt(disc);
  return den > 0.0 ? 2.0 * R / den : kNever;
}

int sign_or(double v, int at_rest) {
  if (v > 0.0) {
    return 1;
  }
  if (v < 0.0) {
    return -1;
  }
  return at_rest;
}

/// Time until a body sliding in direction `slide` with acceleration `a` comes to rest.
double time_to_rest(int slide, double v, double a) {
  return slide != 0 && slide * a < 0.0 ? -v / a : kNever;
}

/// A point mass under constant acceleration: velocity and displacement.
struct Moving {
  double v;
  double dx = 0.0;
  void advance(double a, double tau) {
    dx += v * tau + 0.5 * a * tau * tau;
    v += a * tau;
  }
};

}  // namespace

DmStroke dm_stroke_map(const Params& p, double c0) {
  const double fm = p.mu * p.m * p.g;
  const double fM = p.mu * p.M * p.g;
  // At rest: x breaks away forward (F > μ_s m g), y backward if F > μ_s M g.
  const int x_at_rest = p.F > p.static_mu() * p.m * p.g ? 1 : 0;
  const int y_at_rest = p.F > p.static_mu() * p.M * p.g ? -1 : 0;
  // ẍ and ÿ by sliding direction (−1, 0, +1).
  const auto accel_x = [&](int slide) {
    return slide < 0 ? (p.F + fm) / p.m : slide > 0 ? (p.F - fm) / p.m : 0.0;
  };
  const auto accel_y = [&](int slide) {
    return slide < 0 ? (fM - p.F) / p.M : slide > 0 ? -(p.F + fM) / p.M : 0.0;
  };

  DmStroke out;
  Moving x{c0};
  Moving y{c0};
  int sx = sign_or(c0, x_at_rest);
  int sy = sign_or(c0, y_at_rest);
  out.small_slid_back = sx < 0;
  out.large_slid_back = sy < 0;
  const bool driven_back = p.F > fM;  // y sliding back accelerates backward
  out.large_driven_back = sy < 0 && driven_back;
  double left = p.stroke();  // what x − y still has to grow
  double t = 0.0;
  for (int phase = 1; phase <= 3; ++phase) {
    const double ax = accel_x(sx);
    const double ay = accel_y(sy);
    const double q = x.v - y.v;
    const double r = ax - ay;
    const double tx = time_to_rest(sx, x.v, ax);
    const double ty = time_to_rest(sy, y.v, ay);
    const double te = std::min(tx, ty);
    const double tg = time_to_cover(left, q, r);
    out.phases = phase;
    if (std::isfinite(tg) && tg <= te) {
      // The length limit: the last phase.
      x.advance(ax, tg);
      y.advance(ay, tg);
      t += tg;
      out.v_x = x.v;
      out.v_y = y.v;
      out.c_next = (p.m * x.v + p.M * y.v) / (p.m + p.M);
      out.duration = t;
      out.displacement = (p.m * x.dx + p.M * y.dx) / (p.m + p.M);
      return out;
    }
    if (!std::isfinite(te)) {
      break;
    }
    left -= q * te + 0.5 * r * te * te;
    x.advance(ax, te);
    y.advance(ay, te);
    t += te;
    if (tx <= ty) {
      x.v = 0.0;
      sx = x_at_rest;
    }
    if (ty <= tx) {
      y.v = 0.0;
      sy = y_at_rest;
      if (sy < 0) {
        out.large_slid_back = true;
        out.large_driven_back = driven_back;
        out.large_stopped_then_slid_back = true;
      }
    }
  }
  throw core::ComputationError("dm_stroke_map: the stroke does not reach its length limit (c0 = " +
                               core::format_double(c0) + ")");
}

DmSwap dm_swap_map(const Params& p, int side, double v) {
  const double s = side > 0 ? 1.0 : -1.0;
  const double dm = p.M - p.m;
  const double total = 2.0 * p.m + dm;
  const double P = p.alpha * p.F;
  const double Fb = p.mu * p.g * total;
  // At rest the body breaks away along −s if the push exceeds its static friction.
  const int body_at_rest = P > p.static_mu() * p.g * total ? -1 : 0;
  const double a_dm = P / dm;  // free Δm, along s
  // The body's acceleration along s by its sliding direction along s.
  const auto accel_body = [&](int slide) {
    return slide == 0 ? 0.0 : (-P - slide * Fb) / (2.0 * p.m);
  };

  DmSwap out;
  Moving body{s * v};
  Moving mass{s * v};
  int slide = sign_or(body.v, body_at_rest);
  out.stuck_at_start = slide == 0;
  out.broke_away = body.v == 0.0 && slide < 0;
  double left = side > 0 ? p.L_max : p.L_min;  // Δm's travel still to go, relative to the body
  double t = 0.0;
  for (int phase = 1; phase <= 3; ++phase) {
    double A = accel_body(slide);
    double a = a_dm;
    // Held mode: free Δm would accelerate into the end it left; all three slide together.
    const bool held = a - A < 0.0;
    if (held) {
      A = -slide * p.mu * p.g;
      a = A;
      out.held = true;
    }
    const double q = mass.v - body.v;
    const double te = time_to_rest(slide, body.v, A);
    const double tg = held ? kNever : time_to_cover(left, q, a - A);
    out.phases = phase;
    if (std::isfinite(tg) && tg <= te) {
      body.advance(A, tg);
      mass.advance(a, tg);
      t += tg;
      out.v_body = s * body.v;
      out.v_dm = s * mass.v;
      out.c_next = s * (2.0 * p.m * body.v + dm * mass.v) / total;
      out.duration = t;
      out.displacement = s * (2.0 * p.m * body.dx + dm * mass.dx) / total;
      return out;
    }
    if (!std::isfinite(te)) {
      break;
    }
    left -= q * te + 0.5 * (a - A) * te * te;
    body.advance(A, te);
    mass.advance(a, te);
    t += te;
    body.v = 0.0;
    if (held) {
      mass.v = 0.0;  // Δm stopped with the body
    }
    slide = body_at_rest;
    if (slide == 0) {
      out.stopped = true;
    } else {
      out.broke_away = true;
    }
  }
  throw core::ComputationError("dm_swap_map: Δm does not arrive (v = " + core::format_double(v) +
                               ")");
}

DmHalfCycle dm_half_cycle(const Params& p, int side, double c0) {
  DmHalfCycle h;
  h.stroke = dm_stroke_map(p, c0);
  h.swap = dm_swap_map(p, side, h.stroke.c_next);
  h.c_next = h.swap.c_next;
  h.duration = h.stroke.duration + h.swap.duration;
  h.displacement = h.stroke.displacement + h.swap.displacement;
  return h;
}

DmCycle dm_cycle_map(const Params& p, double c0) {
  DmCycle c;
  c.extension = dm_half_cycle(p, 1, c0);
  c.contraction = dm_half_cycle(p, -1, c.extension.c_next);
  c.c_next = c.contraction.c_next;
  c.duration = c.extension.duration + c.contraction.duration;
  c.displacement = c.extension.displacement + c.contraction.displacement;
  return c;
}

namespace {

double fixed_point_residual(double c, void* params) {
  return dm_cycle_map(*static_cast<const Params*>(params), c).c_next - c;
}

}  // namespace

DmSteadyState dm_steady_state(const Params& p) {
  validate(p);
  Params copy = p;
  const auto h = [&](double c) { return fixed_point_residual(c, &copy); };
  const double scale = std::sqrt(p.g * p.stroke());  // a velocity scale, ~2 m/s

  // Start where the simulation starts: at rest, then a few cycles (c* may be negative, so the
  // bracket cannot start at 0 as for the instant swap).
  double c = 0.0;
  for (int k = 0; k < 8; ++k) {
    c = dm_cycle_map(p, c).c_next;
  }
  // Bracket outward from c: h > 0 below c*, h < 0 above (G' < 1 there).
  const double hc = h(c);
  double lo = c;
  double hi = c;
  if (hc != 0.0) {
    const double dir = hc > 0.0 ? 1.0 : -1.0;
    double step = std::max(std::abs(hc), 1e-12 * scale);
    double far = c + dir * step;
    int doublings = 0;
    while (dir * h(far) > 0.0) {
      c = far;
      step *= 2.0;
      far = c + dir * step;
      if (++doublings > 200) {
        throw core::ComputationError("dm_steady_state: no bracket for the fixed point");
      }
    }
    lo = std::min(c, far);
    hi = std::max(c, far);
  }

  double root = lo;
  int iter = 0;
  if (hi > lo) {
    gsl_function fn{&fixed_point_residual, &copy};
    std::unique_ptr<gsl_root_fsolver, decltype(&gsl_root_fsolver_free)> solver(
        gsl_root_fsolver_alloc(gsl_root_fsolver_brent), &gsl_root_fsolver_free);
    gsl_root_fsolver_set(solver.get(), &fn, lo, hi);
    int status = GSL_CONTINUE;
    while (status == GSL_CONTINUE && iter < 200) {
      ++iter;
      gsl_root_fsolver_iterate(solver.get());
      root = gsl_root_fsolver_root(solver.get());
      status = gsl_root_test_interval(gsl_root_fsolver_x_lower(solver.get()),
                                      gsl_root_fsolver_x_upper(solver.get()), 1e-16 * scale, 1e-15);
    }
    if (status != GSL_SUCCESS) {
      throw core::ComputationError("dm_steady_state: Brent did not converge");
    }
  }

  DmSteadyState out;
  out.cycle = dm_cycle_map(p, root);
  out.residual = std::abs(out.cycle.c_next - root);
  if (!(out.residual <= 1e-12 * scale)) {
    // A sign change of G(c) − c at a jump of G (μ_s > μ), not a fixed point.
    throw core::ComputationError(
        "dm_steady_state: the cycle map has no fixed point near c = " + core::format_double(root) +
        " (jump of " + core::format_double(out.cycle.c_next - root) + " m/s)");
  }
  out.iterations = iter;
  out.c0 = root;
  out.c_contraction = out.cycle.extension.c_next;
  out.v_ss = out.cycle.displacement / out.cycle.duration;
  out.period = 0.5 * out.cycle.duration;
  out.regime_extension = stroke_regime(out.cycle.extension.stroke);
  out.regime_contraction = stroke_regime(out.cycle.contraction.stroke);
  out.regime = out.regime_contraction;
  // "Stop during swap" (§2.5.2): the body stood still in a swap, stopping in it or stuck from
  // its start (MassSwapSystem::kSwapStopped).
  const auto stood_still = [](const DmSwap& w) { return w.stopped || w.stuck_at_start; };
  out.swap_stopped =
      stood_still(out.cycle.extension.swap) || stood_still(out.cycle.contraction.swap);
  out.held = out.cycle.extension.swap.held || out.cycle.contraction.swap.held;
  const double delta = 1e-6 * scale;
  out.contraction =
      (dm_cycle_map(p, root + delta).c_next - dm_cycle_map(p, root - delta).c_next) / (2.0 * delta);
  return out;
}

}  // namespace slipwalk::inchworm
