#pragma once
// A time series of the inchworm from rest (Figs. 2.2, 2.6): positions and velocities of the
// masses and the CoM, the friction modes, and a row just before and just after every impact.
#include <ostream>

#include "inchworm/params.hpp"
#include "inchworm/vss.hpp"

namespace slipwalk::inchworm {

struct TraceOptions {
  int cycles = 6;           ///< cycles (two strokes each) from rest
  double sample_dt = 1e-3;  ///< s; the exact method samples on this grid, integrators write
                            ///< their first accepted step at or after each grid time
  double rtol = 1e-10;      ///< integrators' tolerance
  long long max_rows = kDefaultMaxRows;  ///< fail (core::ComputationError) past this many rows
  long long max_steps = 0;               ///< integrators' step budget; 0 = kDefaultMaxSteps
};

/// What a trace will write, estimated from the closed-form period before it starts: rows ≈
/// 2 cycles (period / dt + the ≤ 8 event rows of a half cycle), at ~170 bytes a row; NaN where
/// there is no closed form. Strokes from rest are of the steady strokes' order; the row bound
/// (TraceOptions::max_rows) holds at run time whatever the estimate.
struct TraceSize {
  double rows;
  double bytes;
};
[[nodiscard]] TraceSize estimate_trace_size(const Params& p, const TraceOptions& opt);

/// Throws core::InputError when the trace would exceed its bounds: naming --dt when the
/// estimated rows exceed max_rows (the message gives the estimate in rows and bytes), --rtol
/// when fixed_rk4's step h = rtol s would take more steps than the budget.
void check_trace_size(const Params& p, Method method, const TraceOptions& opt);

/// Writes CSV columns t,x,y,z,com,xdot,ydot,zdot,comdot,phase,slide_x,slide_y,side,event to
/// `out`: x the end mass without the load, y the one carrying it, z the moving mass Δm (dm model;
/// the instant model writes z = y), phase 0 stroke / 1 swap, slide_y the m–m body's mode during a
/// swap. Events: start, m_stops, M_stops, collision_before/_after, body_stops,
/// arrival_before/_after, and empty for samples. Throws core::ComputationError when the state
/// becomes non-finite, a step or row bound is reached, or the run cannot finish. Methods: analytic
/// (also for exact/rootfind, which have no time series) and every integrator of vss.hpp's Method
/// (fixed_rk4 with the step rtol s).
void write_trace(const Params& p, Method method, const TraceOptions& opt, std::ostream& out);

}  // namespace slipwalk::inchworm
