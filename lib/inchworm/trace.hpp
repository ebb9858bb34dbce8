#pragma once
// A time series of the instant-swap inchworm from rest (Fig. 2.2): positions and velocities of
// m, M and the CoM, the friction modes, and a row just before and just after every event.
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

/// Writes CSV columns t,x,y,com,xdot,ydot,comdot,slide_m,slide_M,side,event to `out`
/// (event: empty, m_stops, M_stops, collision_before, collision_after). Methods: analytic (also
/// for exact/rootfind, which have no time series), cvode, odeint, gsl.
void write_trace(const Params& p, Method method, const TraceOptions& opt, std::ostream& out);

}  // namespace slipwalk::inchworm
