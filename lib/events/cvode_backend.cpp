#include "events/cvode_backend.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <cstdlib>

#include "core/error.hpp"

namespace slipwalk::events {

namespace {

N_Vector as_vector(void* v) { return static_cast<N_Vector>(v); }

}  // namespace

struct CvodeBackend::Callbacks {
  static int rhs(realtype /*t*/, N_Vector y, N_Vector ydot, void* user) {
    auto* self = static_cast<CvodeBackend*>(user);
    self->rhs_(self->flow_, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
    ++self->stats_.rhs_evals;
    return 0;
  }

  static int roots(realtype /*t*/, N_Vector y, realtype* gout, void* user) {
    auto* self = static_cast<CvodeBackend*>(user);
    self->guards_(self->flow_, N_VGetArrayPointer(y), gout);
    self->stats_.guard_evals += self->n_roots_;
    return 0;
  }

  /// The Jacobian of [p; v]' = [v; a] with a constant per mode: ∂ṗ/∂v = I, zero elsewhere.
  static int jacobian(realtype /*t*/, N_Vector /*y*/, N_Vector /*fy*/, SUNMatrix J, void* user,
                      N_Vector /*tmp1*/, N_Vector /*tmp2*/, N_Vector /*tmp3*/) {
    const auto n = static_cast<sunindextype>(static_cast<CvodeBackend*>(user)->n_state_ / 2);
    SUNMatZero(J);
    for (sunindextype i = 0; i < n; ++i) {
      SM_ELEMENT_D(J, i, n + i) = 1.0;
    }
    return 0;
  }

  static void error(int code, const char* /*module*/, const char* function, char* msg, void* user) {
    if (code >= 0) {
      return;  // a warning (e.g. t + h == t once); failures come with a negative code
    }
    static_cast<CvodeBackend*>(user)->error_ = std::string(function) + ": " + msg;
  }
};

CvodeBackend::CvodeBackend(const BackendOptions& options, CvodeMethod method)
    : options_(options), method_(method) {
  SUNContext context = nullptr;
  if (SUNContext_Create(nullptr, &context) != 0 || context == nullptr) {
    throw core::ComputationError("CVODE: SUNContext_Create failed");
  }
  context_ = context;
}

CvodeBackend::~CvodeBackend() {
  free_memory();
  auto context = static_cast<SUNContext>(context_);
  SUNContext_Free(&context);
}

void CvodeBackend::free_memory() {
  if (cvode_ != nullptr) {
    CVodeFree(&cvode_);
  }
  // Attached to CVODE, but not owned by it.
  if (nls_ != nullptr) {
    SUNNonlinSolFree(static_cast<SUNNonlinearSolver>(nls_));
    nls_ = nullptr;
  }
  if (linsol_ != nullptr) {
    SUNLinSolFree(static_cast<SUNLinearSolver>(linsol_));
    linsol_ = nullptr;
  }
  if (matrix_ != nullptr) {
    SUNMatDestroy(static_cast<SUNMatrix>(matrix_));
    matrix_ = nullptr;
  }
  for (void** v : {&y_, &dky_, &dky1_}) {
    if (*v != nullptr) {
      N_VDestroy(as_vector(*v));
      *v = nullptr;
    }
  }
  n_state_ = 0;
  n_roots_ = 0;
}

void CvodeBackend::fail(const char* what, int flag) {
  std::string message = std::string("CVODE: ") + what + " failed";
  if (char* name = CVodeGetReturnFlagName(flag)) {
    message += std::string(" (") + name + ")";
    std::free(name);  // CVodeGetReturnFlagName returns malloc'ed memory
  }
  if (!error_.empty()) {
    message += ": " + error_;
    error_.clear();
  }
  throw core::ComputationError(message);
}

void CvodeBackend::ensure_memory(int n_state, int n_roots) {
  if (cvode_ != nullptr && n_state == n_state_ && n_roots == n_roots_) {
    return;
  }
  free_memory();
  auto context = static_cast<SUNContext>(context_);
  for (void** v : {&y_, &dky_, &dky1_}) {
    N_Vector nv = N_VNew_Serial(n_state, context);
    if (nv == nullptr) {
      throw core::ComputationError("CVODE: N_VNew_Serial failed");
    }
    N_VConst(0.0, nv);
    *v = nv;
  }
  N_Vector y = as_vector(y_);
  cvode_ = CVodeCreate(method_ == CvodeMethod::kBdf ? CV_BDF : CV_ADAMS, context);
  if (cvode_ == nullptr) {
    throw core::ComputationError("CVODE: CVodeCreate failed");
  }
  int flag = CVodeSetErrHandlerFn(cvode_, &Callbacks::error, this);
  if (flag == CV_SUCCESS) {
    flag = CVodeInit(cvode_, &Callbacks::rhs, 0.0, y);
  }
  if (flag != CV_SUCCESS) {
    fail("CVodeInit", flag);
  }
  if ((flag = CVodeSStolerances(cvode_, options_.rtol, options_.atol)) != CV_SUCCESS) {
    fail("CVodeSStolerances", flag);
  }
  if ((flag = CVodeSetUserData(cvode_, this)) != CV_SUCCESS) {
    fail("CVodeSetUserData", flag);
  }
  if (method_ == CvodeMethod::kAdams) {
    // Adams with a fixed-point corrector: a non-stiff field needs no Newton iteration, hence no
    // Jacobian and no linear solver (m = 0: no Anderson acceleration).
    SUNNonlinearSolver nls = SUNNonlinSol_FixedPoint(y, 0, context);
    if (nls == nullptr) {
      throw core::ComputationError("CVODE: SUNNonlinSol_FixedPoint failed");
    }
    nls_ = nls;
    if ((flag = CVodeSetNonlinearSolver(cvode_, nls)) != CV_SUCCESS) {
      fail("CVodeSetNonlinearSolver", flag);
    }
  } else {
    // BDF with CVODE's default Newton corrector: a dense matrix, a dense direct solver and the
    // analytic Jacobian.
    SUNMatrix matrix = SUNDenseMatrix(n_state, n_state, context);
    if (matrix == nullptr) {
      throw core::ComputationError("CVODE: SUNDenseMatrix failed");
    }
    matrix_ = matrix;
    SUNLinearSolver linsol = SUNLinSol_Dense(y, matrix, context);
    if (linsol == nullptr) {
      throw core::ComputationError("CVODE: SUNLinSol_Dense failed");
    }
    linsol_ = linsol;
    if ((flag = CVodeSetLinearSolver(cvode_, linsol, matrix)) != CV_SUCCESS) {
      fail("CVodeSetLinearSolver", flag);
    }
    if ((flag = CVodeSetJacFn(cvode_, &Callbacks::jacobian)) != CV_SUCCESS) {
      fail("CVodeSetJacFn", flag);
    }
  }
  if ((flag = CVodeRootInit(cvode_, n_roots, &Callbacks::roots)) != CV_SUCCESS) {
    fail("CVodeRootInit", flag);
  }
  std::vector<int> rising(static_cast<std::size_t>(n_roots), 1);  // once per shape
  if ((flag = CVodeSetRootDirection(cvode_, rising.data())) != CV_SUCCESS) {
    fail("CVodeSetRootDirection", flag);
  }
  if ((flag = CVodeSetNoInactiveRootWarn(cvode_)) != CV_SUCCESS) {
    fail("CVodeSetNoInactiveRootWarn", flag);
  }
  n_state_ = n_state;
  n_roots_ = n_roots;
}

void CvodeBackend::start_segment(int n_state, int n_roots, double t0, const double* x0,
                                 double t_end) {
  ensure_memory(n_state, n_roots);
  std::copy(x0, x0 + n_state, N_VGetArrayPointer(as_vector(y_)));
  // A new mode is a discontinuity of the field: restart the multistep method there.
  int flag = CVodeReInit(cvode_, t0, as_vector(y_));
  if (flag != CV_SUCCESS) {
    fail("CVodeReInit", flag);
  }
  if (std::isfinite(t_end) && (flag = CVodeSetStopTime(cvode_, t_end)) != CV_SUCCESS) {
    fail("CVodeSetStopTime", flag);
  }
}

bool CvodeBackend::step(double t_end, double& t) {
  const int flag = CVode(cvode_, t_end, as_vector(y_), &t, CV_ONE_STEP);
  if (flag < 0) {
    fail("CVode", flag);
  }
  const double* y = N_VGetArrayPointer(as_vector(y_));
  if (!std::all_of(y, y + n_state_, [](double v) { return std::isfinite(v); })) {
    throw core::ComputationError("CVODE: the state is not finite at t = " + std::to_string(t));
  }
  // CV_ROOT_RETURN needs nothing more here: the step-end test in advance() sees the crossing
  // at the root CVODE returned (and locates it to event_tol).
  return flag == CV_TSTOP_RETURN || t >= t_end;
}

const double* CvodeBackend::returned_state() const { return N_VGetArrayPointer(as_vector(y_)); }

const double* CvodeBackend::interpolate(double t, int k) {
  N_Vector out = as_vector(k == 0 ? dky_ : dky1_);
  const int flag = CVodeGetDky(cvode_, t, k, out);
  if (flag != CV_SUCCESS) {
    fail("CVodeGetDky", flag);
  }
  return N_VGetArrayPointer(out);
}

void CvodeBackend::finish_segment() {
  long int steps = 0;
  if (CVodeGetNumSteps(cvode_, &steps) == CV_SUCCESS) {
    stats_.steps += steps;  // CVodeReInit resets the counter at each segment
  }
}

}  // namespace slipwalk::events
