#include "events/gsl_backend.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace slipwalk::events {

struct GslBackend::Callbacks {
  static int rhs(double /*t*/, const double y[], double dydt[], void* params) {
    auto* self = static_cast<GslBackend*>(params);
    self->rhs_(self->flow_, y, dydt);
    ++self->stats_.rhs_evals;
    return GSL_SUCCESS;
  }

  static const gsl_odeiv2_system& system(const GslBackend* self) {
    return *static_cast<const gsl_odeiv2_system*>(self->system_);
  }
};

namespace {

const gsl_odeiv2_step_type* step_type(GslStepper stepper) {
  switch (stepper) {
    case GslStepper::kRkf45:
      return gsl_odeiv2_step_rkf45;
    case GslStepper::kMsadams:
      return gsl_odeiv2_step_msadams;
    case GslStepper::kRk8pd:
      break;
  }
  return gsl_odeiv2_step_rk8pd;
}

}  // namespace

GslBackend::GslBackend(const BackendOptions& options, GslStepper stepper)
    : options_(options), stepper_(stepper) {}

GslBackend::~GslBackend() { free_memory(); }

void GslBackend::free_memory() {
  if (driver_ != nullptr) {
    gsl_odeiv2_driver_free(driver_);  // frees its step, control and evolve objects
    driver_ = nullptr;
  }
  delete static_cast<gsl_odeiv2_system*>(system_);
  system_ = nullptr;
  n_state_ = 0;
}

void GslBackend::ensure_memory(int n_state) {
  if (n_state == n_state_) {
    return;
  }
  free_memory();
  const auto n = static_cast<std::size_t>(n_state);
  // The driver keeps a pointer to the system: it lives on the heap, as long as the driver.
  system_ = new gsl_odeiv2_system{&Callbacks::rhs, nullptr, n, this};
  // The driver sets itself on the step (msadams needs it), control and evolve objects; its
  // hstart is never used (evolve_apply is given the step size).
  driver_ = gsl_odeiv2_driver_alloc_y_new(static_cast<const gsl_odeiv2_system*>(system_),
                                          step_type(stepper_), 1e-6, options_.atol, options_.rtol);
  if (driver_ == nullptr) {
    free_memory();
    throw core::ComputationError("GSL: could not allocate the odeiv2 driver");
  }
  y_.assign(n, 0.0);
  y_start_.assign(n, 0.0);
  dy_start_.assign(n, 0.0);
  y_try_.assign(n, 0.0);
  dy_try_.assign(n, 0.0);
  y_err_.assign(n, 0.0);
  work_.assign(3 * n, 0.0);
  n_state_ = n_state;
}

void GslBackend::start_segment(int n_state, const double* x0) {
  ensure_memory(n_state);
  gsl_odeiv2_evolve_reset(driver_->e);
  gsl_odeiv2_step_reset(driver_->s);
  std::copy(x0, x0 + n_state, y_.begin());
  h_ = initial_step();
}

void GslBackend::step(double& t, double t_end) {
  if (options_.max_steps > 0 && stats_.steps >= options_.max_steps) {
    throw core::BudgetExhausted(step_budget_message(kName, options_.max_steps));
  }
  std::copy(y_.begin(), y_.end(), y_start_.begin());
  const double t_before = t;
  const int status = gsl_odeiv2_evolve_apply(driver_->e, driver_->c, driver_->s,
                                             &Callbacks::system(this), &t, t_end, &h_, y_.data());
  if (status != GSL_SUCCESS) {
    throw core::ComputationError(
        std::string("GSL: gsl_odeiv2_evolve_apply (") + gsl_odeiv2_step_name(driver_->s) +
        ") failed at t = " + std::to_string(t_before) + ": " + gsl_strerror(status));
  }
  if (!(t > t_before) ||
      !std::all_of(y_.begin(), y_.end(), [](double v) { return std::isfinite(v); })) {
    throw core::ComputationError("GSL: no progress or a non-finite state at t = " +
                                 std::to_string(t_before));
  }
  // evolve_apply evaluated the field at the step start (dydt_in) for every stepper here.
  std::copy(driver_->e->dydt_in, driver_->e->dydt_in + n_state_, dy_start_.begin());
  ++stats_.steps;
}

const double* GslBackend::step_end_derivative() const { return driver_->e->dydt_out; }

const double* GslBackend::state_at(double t_lo, double t_hi, double t) {
  const auto n = static_cast<std::size_t>(n_state_);
  if (interpolates()) {
    // Cubic Hermite on [t_lo, t_hi] through the end states and fields; its derivative too.
    const double h = t_hi - t_lo;
    const double s = (t - t_lo) / h;
    const double s2 = s * s;
    const double s3 = s2 * s;
    const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    const double h10 = s3 - 2.0 * s2 + s;
    const double h01 = -2.0 * s3 + 3.0 * s2;
    const double h11 = s3 - s2;
    const double d00 = (6.0 * s2 - 6.0 * s) / h;
    const double d10 = 3.0 * s2 - 4.0 * s + 1.0;
    const double d01 = -d00;
    const double d11 = 3.0 * s2 - 2.0 * s;
    const double* f1 = driver_->e->dydt_out;
    for (std::size_t i = 0; i < n; ++i) {
      y_try_[i] = h00 * y_start_[i] + h10 * h * dy_start_[i] + h01 * y_[i] + h11 * h * f1[i];
      dy_try_[i] = d00 * y_start_[i] + d10 * dy_start_[i] + d01 * y_[i] + d11 * f1[i];
    }
    return y_try_.data();
  }
  std::copy(y_start_.begin(), y_start_.end(), y_try_.begin());
  const double tau = t - t_lo;
  if (tau > 0.0) {
    // One step of size tau from the last step's start; dy_start_ is the field there.
    const int status = gsl_odeiv2_step_apply(driver_->s, t_lo, tau, y_try_.data(), y_err_.data(),
                                             dy_start_.data(), nullptr, &Callbacks::system(this));
    if (status != GSL_SUCCESS) {
      throw core::ComputationError(std::string("GSL: gsl_odeiv2_step_apply failed: ") +
                                   gsl_strerror(status));
    }
  }
  return y_try_.data();
}

double GslBackend::initial_step() {
  // Hairer, Nørsett & Wanner, Solving ODEs I, II.4: a first step whose Euler error is about
  // 1% of the tolerance, for a method of the stepper's order q (exponent 1/(q + 1)), in the
  // controller's norm.
  const auto n = static_cast<std::size_t>(n_state_);
  const double order = std::max(1U, gsl_odeiv2_step_order(driver_->s));
  double* f0 = work_.data();
  double* y1 = f0 + n;
  double* f1 = y1 + n;
  rhs_(flow_, y_.data(), f0);
  auto norm = [&](auto&& component) {
    double s = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double c = component(i) / (options_.atol + options_.rtol * std::abs(y_[i]));
      s += c * c;
    }
    return std::sqrt(s / static_cast<double>(n));
  };
  const double d0 = norm([&](std::size_t i) { return y_[i]; });
  const double d1 = norm([&](std::size_t i) { return f0[i]; });
  const double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  for (std::size_t i = 0; i < n; ++i) {
    y1[i] = y_[i] + h0 * f0[i];
  }
  rhs_(flow_, y1, f1);
  stats_.rhs_evals += 2;
  const double d2 = norm([&](std::size_t i) { return f1[i] - f0[i]; }) / h0;
  const double d = std::max(d1, d2);
  const double h1 =
      d <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / d, 1.0 / (order + 1.0));
  return std::min(100.0 * h0, h1);
}

}  // namespace slipwalk::events
