#pragma once
// An independent oracle for the spring-support search (thesis §3.3): the direct minimization of
// the convex, C¹ potential
//   U(α, β, z) = Σ_j ½ K_j min(h_j, 0)² + Mg z,   h_j = −β q_x,j + α q_y,j + q_z,j + z,
// whose minimizer is the force/moment balance. GSL's BFGS (vector_bfgs2) brings the state close,
// then a semismooth Newton method with an Armijo line search (generalized Hessian of the feet with
// h < 0) polishes it to rounding. Nothing here uses the library's search. Valid only where a
// minimizer exists (the CoM inside the support polygon of all feet).
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multimin.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

namespace slipwalk::testing {

/// A spring-support problem in the oracle's own terms.
struct SupportProblem {
  Eigen::Matrix3Xd q;  ///< (3 x N) feet in the body frame
  Eigen::VectorXd K;   ///< (N) stiffnesses
  double Mg = 1.0;
};

struct OracleResult {
  double alpha = 0.0;
  double beta = 0.0;
  double z = 0.0;
  double U = 0.0;
  double grad = 0.0;  ///< |∇U| in the scaled variables (α L, β L, z), N
  int bfgs_iterations = 0;
  int newton_iterations = 0;
  Eigen::VectorXd h;   ///< foot heights at the minimizer
  Eigen::VectorXd Fz;  ///< loads −K min(h, 0)
};

/// U at (α, β, z).
inline double support_potential(const SupportProblem& p, double alpha, double beta, double z) {
  double u = p.Mg * z;
  for (int j = 0; j < p.q.cols(); ++j) {
    const double h = -beta * p.q(0, j) + alpha * p.q(1, j) + p.q(2, j) + z;
    if (h < 0.0) {
      u += 0.5 * p.K(j) * h * h;
    }
  }
  return u;
}

/// The horizontal size L = max |q_xy| (1 if all feet are at the origin).
inline double support_size(const SupportProblem& p) {
  double L = 0.0;
  for (int j = 0; j < p.q.cols(); ++j) {
    L = std::max(L, std::hypot(p.q(0, j), p.q(1, j)));
  }
  return L > 0.0 ? L : 1.0;
}

namespace oracle_detail {

struct Scaled {
  const SupportProblem* p;
  double L;
  // x = (α L, β L, z)
  [[nodiscard]] double value(const double* x) const {
    return support_potential(*p, x[0] / L, x[1] / L, x[2]);
  }
  void gradient(const double* x, double* g) const {
    g[0] = 0.0;
    g[1] = 0.0;
    g[2] = p->Mg;
    for (int j = 0; j < p->q.cols(); ++j) {
      const double ax = p->q(1, j) / L;
      const double ay = -p->q(0, j) / L;
      const double h = ax * x[0] + ay * x[1] + x[2] + p->q(2, j);
      if (h < 0.0) {
        const double kh = p->K(j) * h;
        g[0] += kh * ax;
        g[1] += kh * ay;
        g[2] += kh;
      }
    }
  }
};

inline double f(const gsl_vector* x, void* params) {
  return static_cast<const Scaled*>(params)->value(x->data);
}
inline void df(const gsl_vector* x, void* params, gsl_vector* g) {
  static_cast<const Scaled*>(params)->gradient(x->data, g->data);
}
inline void fdf(const gsl_vector* x, void* params, double* value, gsl_vector* g) {
  *value = f(x, params);
  df(x, params, g);
}

}  // namespace oracle_detail

/// Minimizes U. Starts at zero tilt with the lowest foot just touching (not at the library's z*).
inline OracleResult minimize_support_potential(const SupportProblem& p) {
  gsl_set_error_handler_off();
  const int n = static_cast<int>(p.q.cols());
  const double L = support_size(p);
  oracle_detail::Scaled scaled{&p, L};
  double ksum = p.K.sum();
  double zscale = p.Mg / ksum;
  for (int j = 0; j < n; ++j) {
    zscale = std::max(zscale, std::abs(p.q(2, j)) * 1e-3);
  }

  // ---- BFGS ----------------------------------------------------------------------------------
  gsl_multimin_function_fdf fn;
  fn.n = 3;
  fn.f = &oracle_detail::f;
  fn.df = &oracle_detail::df;
  fn.fdf = &oracle_detail::fdf;
  fn.params = &scaled;
  gsl_vector* x = gsl_vector_alloc(3);
  gsl_vector_set(x, 0, 0.0);
  gsl_vector_set(x, 1, 0.0);
  gsl_vector_set(x, 2, -p.q.row(2).minCoeff());
  gsl_multimin_fdfminimizer* m =
      gsl_multimin_fdfminimizer_alloc(gsl_multimin_fdfminimizer_vector_bfgs2, 3);
  gsl_multimin_fdfminimizer_set(m, &fn, x, zscale, 0.1);
  OracleResult r;
  double xs[3] = {0.0, 0.0, gsl_vector_get(x, 2)};
  for (int it = 0; it < 20000; ++it) {
    const int status = gsl_multimin_fdfminimizer_iterate(m);
    r.bfgs_iterations = it + 1;
    if (status != GSL_SUCCESS) {
      break;
    }
    if (gsl_multimin_test_gradient(m->gradient, 1e-13 * p.Mg) == GSL_SUCCESS) {
      break;
    }
  }
  for (int i = 0; i < 3; ++i) {
    xs[i] = gsl_vector_get(m->x, i);
  }
  gsl_multimin_fdfminimizer_free(m);
  gsl_vector_free(x);

  // ---- semismooth Newton polish --------------------------------------------------------------
  Eigen::Vector3d u(xs[0], xs[1], xs[2]);
  for (int it = 0; it < 200; ++it) {
    Eigen::Vector3d g;
    scaled.gradient(u.data(), g.data());
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector3d a(p.q(1, j) / L, -p.q(0, j) / L, 1.0);
      if (a.dot(u) + p.q(2, j) < 0.0) {
        H += p.K(j) * a * a.transpose();
      }
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(H);
    // Pseudo-inverse Newton direction (singular H: rows of feet on a line, CoM on it).
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    const double lmax = es.eigenvalues()(2);
    for (int i = 0; i < 3; ++i) {
      const double l = es.eigenvalues()(i);
      if (l > 1e-11 * lmax) {
        d -= es.eigenvectors().col(i) * (es.eigenvectors().col(i).dot(g) / l);
      }
    }
    if (!(g.dot(d) < 0.0)) {
      break;
    }
    // Exact line search on the derivative φ'(t) = ∇U(u + t d)·d, which is non-decreasing (U is
    // convex): U itself is too flat near the minimum to compare values (Mg z dominates it).
    auto slope = [&](double t) {
      const Eigen::Vector3d at = u + t * d;
      Eigen::Vector3d gx;
      scaled.gradient(at.data(), gx.data());
      return gx.dot(d);
    };
    double t = 1.0;
    if (slope(1.0) > 0.0) {
      double lo = 0.0;
      double hi = 1.0;
      for (int k = 0; k < 200 && lo < hi; ++k) {
        const double mid = 0.5 * (lo + hi);
        if (mid == lo || mid == hi) {
          break;
        }
        (slope(mid) > 0.0 ? hi : lo) = mid;
      }
      t = hi;
    }
    const Eigen::Vector3d next = u + t * d;
    if (next == u) {
      break;
    }
    u = next;
    r.newton_iterations = it + 1;
  }
  Eigen::Vector3d g;
  scaled.gradient(u.data(), g.data());
  r.grad = g.norm();
  r.alpha = u(0) / L;
  r.beta = u(1) / L;
  r.z = u(2);
  r.U = support_potential(p, r.alpha, r.beta, r.z);
  r.h.resize(n);
  r.Fz.resize(n);
  for (int j = 0; j < n; ++j) {
    r.h(j) = -r.beta * p.q(0, j) + r.alpha * p.q(1, j) + p.q(2, j) + r.z;
    r.Fz(j) = r.h(j) < 0.0 ? -p.K(j) * r.h(j) : 0.0;
  }
  return r;
}

}  // namespace slipwalk::testing
