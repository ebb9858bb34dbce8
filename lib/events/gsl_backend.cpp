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

  static gsl_odeiv2_system system(GslBackend* self) {
    return {&rhs, nullptr, static_cast<std::size_t>(self->n_state_), self};
  }
};

GslBackend::GslBackend(const BackendOptions& options) : options_(options) {}

GslBackend::~GslBackend() { free_memory(); }

void GslBackend::free_memory() {
  if (evolve_ != nullptr) {
    gsl_odeiv2_evolve_free(evolve_);
    evolve_ = nullptr;
  }
  if (control_ != nullptr) {
    gsl_odeiv2_control_free(control_);
    control_ = nullptr;
  }
  if (step_ != nullptr) {
    gsl_odeiv2_step_free(step_);
    step_ = nullptr;
  }
  n_state_ = 0;
}

void GslBackend::ensure_memory(int n_state) {
  if (n_state == n_state_) {
    return;
  }
  free_memory();
  const auto n = static_cast<std::size_t>(n_state);
  step_ = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, n);
  control_ = gsl_odeiv2_control_y_new(options_.atol, options_.rtol);
  evolve_ = gsl_odeiv2_evolve_alloc(n);
  if (step_ == nullptr || control_ == nullptr || evolve_ == nullptr) {
    free_memory();
    throw core::ComputationError("GSL: could not allocate the odeiv2 rk8pd stepper");
  }
  y_.assign(n, 0.0);
  y_start_.assign(n, 0.0);
  y_try_.assign(n, 0.0);
  dy_try_.assign(n, 0.0);
  y_err_.assign(n, 0.0);
  work_.assign(3 * n, 0.0);
  n_state_ = n_state;
}

void GslBackend::start_segment(int n_state, const double* x0) {
  ensure_memory(n_state);
  gsl_odeiv2_evolve_reset(evolve_);
  gsl_odeiv2_step_reset(step_);
  std::copy(x0, x0 + n_state, y_.begin());
  h_ = initial_step();
}

void GslBackend::step(double& t, double t_end) {
  std::copy(y_.begin(), y_.end(), y_start_.begin());
  const gsl_odeiv2_system system = Callbacks::system(this);
  const double t_before = t;
  const int status =
      gsl_odeiv2_evolve_apply(evolve_, control_, step_, &system, &t, t_end, &h_, y_.data());
  if (status != GSL_SUCCESS) {
    throw core::ComputationError(std::string("GSL: gsl_odeiv2_evolve_apply failed at t = ") +
                                 std::to_string(t_before) + ": " + gsl_strerror(status));
  }
  if (!(t > t_before) ||
      !std::all_of(y_.begin(), y_.end(), [](double v) { return std::isfinite(v); })) {
    throw core::ComputationError("GSL: no progress or a non-finite state at t = " +
                                 std::to_string(t_before));
  }
  ++stats_.steps;
}

const double* GslBackend::step_end_derivative() const { return evolve_->dydt_out; }

const double* GslBackend::reintegrate(double t_lo, double tau) {
  std::copy(y_start_.begin(), y_start_.end(), y_try_.begin());
  if (tau > 0.0) {
    // evolve_->dydt_in is the field at (t_lo, y_start_), kept by gsl_odeiv2_evolve_apply.
    const gsl_odeiv2_system system = Callbacks::system(this);
    const int status = gsl_odeiv2_step_apply(step_, t_lo, tau, y_try_.data(), y_err_.data(),
                                             evolve_->dydt_in, nullptr, &system);
    if (status != GSL_SUCCESS) {
      throw core::ComputationError(std::string("GSL: gsl_odeiv2_step_apply failed: ") +
                                   gsl_strerror(status));
    }
  }
  return y_try_.data();
}

double GslBackend::initial_step() {
  // Hairer, Nørsett & Wanner, Solving ODEs I, II.4: a first step whose Euler error is about
  // 1% of the tolerance, for a method of order 8 (exponent 1/9), in the controller's norm.
  const auto n = static_cast<std::size_t>(n_state_);
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
  const double h1 = d <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / d, 1.0 / 9.0);
  return std::min(100.0 * h0, h1);
}

}  // namespace slipwalk::events
