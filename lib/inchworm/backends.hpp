#pragma once
// The integrator behind each simulation method of vss.hpp: the one place that maps a Method to a
// backend type and its variant (CVODE Adams or BDF, odeint dopri5 or fehlberg78, GSL rk8pd,
// rkf45 or msadams, fixed-step RK4). solve_vss and the traces both go through it.
#include <utility>

#include "events/cvode_backend.hpp"
#include "events/exact_backend.hpp"
#include "events/fixed_step_backend.hpp"
#include "events/gsl_backend.hpp"
#include "events/odeint_backend.hpp"
#include "inchworm/vss.hpp"

namespace slipwalk::inchworm {

/// Builds the backend of simulation method `method` from `options` and calls f(backend) with
/// it; returns false, calling nothing, for the closed forms (exact, rootfind).
template <class F>
bool with_backend(Method method, const events::BackendOptions& options, F&& f) {
  auto run = [&](auto&& backend) {
    std::forward<F>(f)(backend);
    return true;
  };
  switch (method) {
    case Method::kExact:
    case Method::kRootfind:
      return false;
    case Method::kAnalytic:
      return run(events::ExactBackend(options));
    case Method::kCvode:
      return run(events::CvodeBackend(options, events::CvodeMethod::kAdams));
    case Method::kCvodeBdf:
      return run(events::CvodeBackend(options, events::CvodeMethod::kBdf));
    case Method::kOdeint:
      return run(events::OdeintBackend(options, events::OdeintStepper::kDopri5));
    case Method::kOdeintRkf78:
      return run(events::OdeintBackend(options, events::OdeintStepper::kFehlberg78));
    case Method::kGsl:
      return run(events::GslBackend(options, events::GslStepper::kRk8pd));
    case Method::kGslRkf45:
      return run(events::GslBackend(options, events::GslStepper::kRkf45));
    case Method::kGslMsadams:
      return run(events::GslBackend(options, events::GslStepper::kMsadams));
    case Method::kFixedRk4:
      return run(events::FixedStepBackend(options));
  }
  return false;
}

}  // namespace slipwalk::inchworm
