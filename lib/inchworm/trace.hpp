#pragma once
// A time series of the inchworm from rest (Figs. 2.2, 2.6): positions and velocities of the
// masses and the CoM, the friction modes, and a row just before and just after every impact.
#include <ostream>

#include "inchworm/params.hpp"
#include "inchworm/vss.hpp"

namespace slipwalk::inchworm {

struct TraceOptions {
  int cycles = 6;           ///< cycles (two strokes each) from rest
  double sample_dt = 1e-3;  ///< s; the exact method samples on this grid, integrators
                            ///< report their own accepted steps
  double rtol = 1e-10;      ///< integrators' tolerance
};

/// Writes CSV columns t,x,y,z,com,xdot,ydot,zdot,comdot,phase,slide_x,slide_y,side,event to
/// `out`: x the end mass without the load, y the one carrying it, z the moving mass Δm (dm model;
/// the instant model writes z = y), phase 0 stroke / 1 swap, slide_y the m–m body's mode during a
/// swap. Events: start, m_stops, M_stops, collision_before/_after, body_stops,
/// arrival_before/_after, and empty for samples. Methods: analytic (also for exact/rootfind,
/// which have no time series) and every integrator of vss.hpp's Method (fixed_rk4 with the step
/// rtol s).
void write_trace(const Params& p, Method method, const TraceOptions& opt, std::ostream& out);

}  // namespace slipwalk::inchworm
