// Classical Coulomb friction (eq. 3.13) as a convex program, with a certificate.
//
// Problem. With r_k(y) = B_k y + d_k = c_k W_k u_k(y) (c_k = μ_k F_z,k, W_k = (I + w_k w_kᵀ)^{1/2},
// B_k = c_k W_k J̃_k, d_k = c_k W_k q̇_k in the scaled coordinates of friction/balance.hpp) the
// balance of F_k = −c_k W_k r_k/‖r_k‖ is the optimality condition of the dissipation
//   D(y) = Σ_k ‖r_k(y)‖ = Σ_k μ_k F_z,k ‖W_k u_k‖      (a sum of Euclidean norms; convex).
// Anisotropy: the friction force set of foot k is the ellipse {F : Fᵀ G_k⁻¹ F ≤ c_k²} (semi-axis
// c_k √(1 + ‖w_k‖²) along w_k, c_k across: eq. 3.19's ellipse), whose support function is
// c_k ‖W_k u‖; maximum dissipation then gives F_k = −c_k G_k u_k/‖W_k u_k‖, the viscous force
// −c_k G_k u_k rescaled, so eq. 3.14's family joins the two laws for any w.
//
// Dual. ‖r‖ = max_{‖λ‖≤1} λᵀr gives  max Σ_k λ_kᵀ d_k  over  ‖λ_k‖ ≤ 1, Σ_k B_kᵀ λ_k = 0: with
// F_k = −c_k W_k λ_k this is "maximize Σ F_k·(−q̇_k) over balanced forces in the friction
// ellipses". Any such λ bounds D from below; the relative gap (D(y) − Σ λ_kᵀ d_k) / max(D(y), D(0))
// is the certificate. A candidate λ with imbalance h = Σ B_kᵀλ_k is made balanced by the
// least-norm correction λ_k −= B_k μ, μ = M₂⁺h (M₂ = Σ B_kᵀB_k), which changes its value by −μᵀb₂
// (b₂ = Σ B_kᵀd_k) and each ‖λ_k‖ by at most √(μᵀM₂μ); scaled into the disks it is feasible. So
// the gap of a candidate is known from a few sums, without a pass over the feet (bound()).
//
// Cost model. Everything per foot is precomputed once: B_k and d_k (rows of frame.work_rows).
// A pass over the feet then costs six multiply-adds for r_k, one square root and one division,
// and returns all a Newton step needs (Sums: D, gradient, Hessian, the data of the certificate),
// so a step is one pass. The line search is folded into the next pass (a full step is accepted
// by the pass that assembles the next step), and the certificate needs no pass (see Dual), so a
// solve costs about (Newton steps + 3) passes.
//
// Algorithm (always terminates: every loop is bounded by options.max_iterations).
//  1. Start at the viscous-Coulomb solution (if nothing slips there, certify that at once).
//  2. Smoothing path: damped Newton steps (Armijo) on D_δ(y) = Σ √(‖r_k‖² + δ²) (smooth,
//     convex, its Hessian regularized only along directions no foot feels); a stage ends when
//     the Newton decrement falls below 3δ (or after 8 steps), and δ is then divided by 10, from
//     δ₀ = 0.1 D(start)/N down to δ_min = 0.1 tol D/N, where the smoothing error alone is within
//     the tolerance. Near δ_min the path's own dual λ_k = r_k/√(‖r_k‖² + δ²) is certified too.
//  3. Polish at the end of each stage (active set): feet with ‖r_k‖ ≤ min(10 δ, 0.01 D/N) are
//     static, and so is the slowest other foot if it is clearly apart (‖r‖ ≤ 0.1 × the next
//     and ≤ 10³ δ: a static foot whose force lies near the rim of its disk keeps
//     ‖r‖ = δ t/√(1 − t²) on the path). The body velocity is restricted to where the static feet
//     do not slip — a point if they span two distinct points, the rotations about their common
//     point if one, all of R³ if none — and the exact D of the sliding feet is minimized there
//     by Newton's method, which is smooth and converges quadratically if the static set is right
//     (the attempt is abandoned as soon as it does not: a step cut below 1/2, or a decrement
//     not falling 4× per step). Its dual: the sliding feet's directions linearized at the Newton
//     point, λ_k = n_k + n_k⊥ (t_kᵀp)/‖r_k‖ (t_k = B_kᵀn_k⊥, p the step), which the Newton
//     equation balances exactly and whose norms exceed 1 by O(‖p‖²): a second-order certificate
//     at the current point; the static feet's dual forces are those that balance the sliding
//     feet (for static feet at distinct points, whose internal force is free, a balancing choice
//     inside the disks: fit_static_forces). A right static set certifies to ~1e-15 in 1–3 steps.
//  4. Certificate: the final pass (finish) builds the forces of the winning dual candidate, makes
//     them exactly balanced and scales them into the disks, so the reported gap is the true one of
//     the reported forces (up to rounding), whatever the quality of y. Converged ⇔ gap ≤ tol.
// Cost: 5–9 Newton steps on random frames (more static feet → more steps); see
// tests/bench/bench_friction.cpp for the time against the viscous-Coulomb solve.
//
// Non-uniqueness. At an optimum with dual λ, a direction e keeps y optimal iff B_k e ∥ λ_k for
// sliding feet and for static feet on the disk's rim (with λ_kᵀ B_k e ≥ 0 there: the foot starts
// sliding along its force) and B_k e = 0 for static feet inside their disk. The first two are
// linear: e must lie in the null space of Q = Σ B_kᵀ P_k B_k (P_k the projector across λ_k, or I).
// A null vector of Q (eigenvalue ≤ 1e-10 trace) that passes the sign test means a flat
// direction of D at the optimum: a continuum of minimizers (the even-N 1-D example of §3.1.2).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/csv.hpp"
#include "friction/balance.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::friction {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kBig = 1e300;  // ‖r‖² of a foot a pass does not visit, for the minimum
constexpr int kSlip = 0;
constexpr int kStatic = 1;
constexpr int kInactive = -1;
constexpr double kDelta0 = 0.1;  // δ₀ = kDelta0 · D(viscous)/N
constexpr double kSigma = 0.1;   // δ ← kSigma δ at the end of a stage
constexpr double kKappa = 10.0;  // static: ‖r_k‖ ≤ kKappa δ
constexpr int kKinkSteps = 12;   // the fast path's steps before the smoothing path takes over

/// The sums of one pass over the feet at a point y with smoothing δ (δ = 0: the exact D).
struct Sums {
  double f = 0.0;                               ///< Σ ρ_k, ρ_k = √(‖r_k‖² + δ²)
  Eigen::Vector3d g = Eigen::Vector3d::Zero();  ///< gradient Σ B_kᵀ r_k/ρ_k
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();  ///< Hessian Σ B_kᵀ (δ² I + r⊥r⊥ᵀ) B_k/ρ_k³
  double inv_rho = 0.0;                         ///< Σ 1/ρ_k (value of the smoothing dual)
  double rho_max = 0.0;                         ///< max ρ_k
  double r2_min = kInf;                         ///< min ‖r_k‖²
};

/// A dual candidate, as finish() builds it: the smoothing path's λ_k = r_k/ρ_k (δ² = d2) for
/// every foot, or the polish's λ_k = n_k + n_k⊥ (t_kᵀp)/‖r_k‖ for sliding feet and work_2n for
/// static ones; h = Σ B_kᵀλ_k, its imbalance, known from the pass that assembled it.
struct Dual {
  bool path = false;
  double d2 = 0.0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d h = Eigen::Vector3d::Zero();
  int kink = -1;  ///< a foot whose λ is in work_2n whatever its state (kink_newton)
};

/// The minimizer of the kink model m(p) = gᵀp + ½ pᵀHp + ‖r + Bp‖ (kink_step()).
struct KinkStep {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();    ///< the step
  Eigen::Vector2d lam = Eigen::Vector2d::Zero();  ///< the kink foot's dual at the minimizer
  bool stick = false;                             ///< r + Bp = 0: the foot does not slip there
  double decrease = 0.0;                          ///< m(0) − m(p)
};

/// Minimizes m(p) = gᵀp + ½ pᵀHp + ‖r + Bp‖ over p ∈ R³: the sliding feet by their quadratic
/// model (g, H) and one foot (r = r_s(y), B = B_s = [B_xy | b_ω]) exactly, kink included.
/// Coordinates: with s̃ = B_xy⁻¹ b_ω (the foot's lever), p = (z − s̃α, α) gives u = r + Bp =
/// r + B_xy z, and α (rotation about the foot) enters only the quadratic; eliminating it (H must
/// resist that rotation: h_αα > 0) leaves ½(u − r)ᵀK(u − r) + g̃ᵀ(u − r) + ‖u‖ over u ∈ R². Its
/// minimizer is u = 0 (stick) if the force λ₀ = K r − g̃ lies in the unit disk, else
/// (K + I/τ) u = λ₀ with ‖u‖ = τ, a secular equation in τ (as in trust-region methods), solved
/// by Newton's method in K's eigenbasis. Returns false when the model is degenerate (h_αα ≈ 0,
/// or K singular with λ₀ outside the disk: m unbounded below).
bool kink_step(const Eigen::Vector3d& g, const Eigen::Matrix3d& H,
               const Eigen::Matrix<double, 2, 3>& B, const Eigen::Vector2d& r, KinkStep& out) {
  const Eigen::Matrix2d Bxy_inv = B.leftCols<2>().inverse();
  const Eigen::Vector2d sl = Bxy_inv * B.col(2);
  // TᵀHT and Tᵀg for T = [I −s̃; 0 1].
  const Eigen::Matrix2d Hzz = H.topLeftCorner<2, 2>();
  const Eigen::Vector2d hza = H.topRightCorner<2, 1>() - Hzz * sl;
  const double haa = H(2, 2) - 2.0 * sl.dot(H.topRightCorner<2, 1>()) + sl.dot(Hzz * sl);
  const double ga = g(2) - sl.dot(g.head<2>());
  if (!(haa > 1e-12 * H.trace() * (1.0 + sl.squaredNorm()))) {
    return false;
  }
  // α eliminated, then z = B_xy⁻¹(u − r).
  const Eigen::Matrix2d K = Bxy_inv.transpose() * (Hzz - hza * (hza.transpose() / haa)) * Bxy_inv;
  const Eigen::Vector2d gt = Bxy_inv.transpose() * (g.head<2>() - hza * (ga / haa));
  const Eigen::Vector2d lam0 = K * r - gt;
  Eigen::Vector2d u = Eigen::Vector2d::Zero();
  out.stick = lam0.squaredNorm() <= 1.0;
  if (out.stick) {
    out.lam = lam0;
  } else {
    // (K + I/τ) u = λ₀ gives u = τ (a + τ b)/P(τ) with a = λ₀, b = adj(K) λ₀ and
    // P(τ) = det(I + τK) = 1 + τ tr K + τ² det K, so ‖u‖ = τ reads ‖a + τb‖ = P(τ): Newton's
    // method on ψ(τ) = 1 − P/‖a + τb‖ (= 1 − 1/√Σ l_i²/(κ_iτ + 1)² in K's eigenbasis, nearly
    // linear in τ) rises monotonically to the root from the lower bound (‖λ₀‖ − 1)/tr K. It
    // stops once a step is below 1e-8 τ: the error is then of its square (an inexact u only
    // enters the certificate through h, which is exact).
    const double tr = K(0, 0) + K(1, 1);
    const double det = K(0, 0) * K(1, 1) - K(0, 1) * K(0, 1);
    if (!(det > 1e-12 * tr * tr)) {
      return false;
    }
    const Eigen::Vector2d b(K(1, 1) * lam0(0) - K(0, 1) * lam0(1),
                            K(0, 0) * lam0(1) - K(0, 1) * lam0(0));
    const double ab = lam0.dot(b);
    const double bb = b.squaredNorm();
    const double aa = lam0.squaredNorm();
    double tau = (std::sqrt(aa) - 1.0) / tr;
    for (int it = 0; it < 50; ++it) {
      const double n2 = aa + tau * (2.0 * ab + tau * bb);  // ‖a + τb‖²
      const double n = std::sqrt(n2);
      const double P = 1.0 + tau * (tr + tau * det);
      const double dP = tr + 2.0 * tau * det;
      const double step = (n - P) * n2 / (dP * n2 - P * (ab + tau * bb));
      tau += step;
      if (!(std::abs(step) > 1e-8 * tau)) {
        break;
      }
    }
    const Eigen::Vector2d v = lam0 + tau * b;
    out.lam = v / v.norm();
    u = tau * out.lam;
  }
  const Eigen::Vector2d z = Bxy_inv * (u - r);
  const double alpha = -(ga + hza.dot(z)) / haa;
  out.p << z - sl * alpha, alpha;
  out.decrease = -(g.dot(out.p) + 0.5 * out.p.dot(H * out.p) + u.norm() - r.norm());
  return out.p.allFinite() && out.decrease > 0.0;
}

/// Solves M x = b for a symmetric M through its adjugate: one division, where LDLᵀ chains three
/// (a 3 × 3 solve sits on the serial path of every Newton step). Returns false unless M is
/// positive definite with the pivots of its LDLᵀ above tol · trace — checked as ratios of
/// leading minors, without dividing.
bool solve_spd3(const Eigen::Matrix3d& M, const Eigen::Vector3d& b, double tol,
                Eigen::Vector3d& x) {
  const double m00 = M(0, 0), m01 = M(0, 1), m02 = M(0, 2);
  const double m11 = M(1, 1), m12 = M(1, 2), m22 = M(2, 2);
  const double a00 = m11 * m22 - m12 * m12;
  const double a01 = m02 * m12 - m01 * m22;
  const double a02 = m01 * m12 - m02 * m11;
  const double a11 = m00 * m22 - m02 * m02;
  const double a12 = m01 * m02 - m00 * m12;
  const double a22 = m00 * m11 - m01 * m01;
  const double det = m00 * a00 + m01 * a01 + m02 * a02;
  const double t = tol * (m00 + m11 + m22);
  if (!(m00 > t && a22 > t * m00 && det > t * a22)) {
    return false;
  }
  const double inv = 1.0 / det;
  x << (a00 * b(0) + a01 * b(1) + a02 * b(2)) * inv, (a01 * b(0) + a11 * b(1) + a12 * b(2)) * inv,
      (a02 * b(0) + a12 * b(1) + a22 * b(2)) * inv;
  return true;
}

/// What the static feet of a polish contribute to its dual (static_duals()).
struct StaticDual {
  double lmax = 0.0;                                ///< max ‖λ_s‖
  double value = 0.0;                               ///< Σ λ_sᵀ d_s
  double primal = 0.0;                              ///< Σ ‖r_s(y)‖ (0 up to rounding)
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< Σ B_sᵀ λ_s
};

class CoulombSolver {
 public:
  CoulombSolver(const contact::Robot& robot, contact::Frame& frame, const CoulombOptions& options)
      : robot_(robot), frame_(frame), options_(options) {}

  void run() {
    auto& s = frame_.friction;
    s.iterations = 0;
    s.message.clear();

    // ---- per-foot constants, Σ B_kᵀB_k (dual projection, degeneracy), the viscous start -----
    setup();
    dual_.factorize(M2_);
    Eigen::Vector3d y = -viscous_.solve(b1_);

    // ---- trivial cases: no friction, nothing moves, or the viscous start slips nowhere -------
    const int n = std::max(cs_.active, 1);
    Sums S;
    assemble<true>(y, 0.0, S);  // D(y) and ‖r_k‖² (g, H are not finite if some r_k = 0)
    const double D = S.f;
    const double Dref = std::max(D, D0_);
    if (cs_.active == 0 || Dref == 0.0) {
      classify(0.0);  // y = 0 (the viscous least-norm answer) is exact, forces zero
      zero_static_duals();
      finish(y, Dual{});
      return;
    }
    if (D <= 1e-12 * Dref) {
      classify(1e-9 * Dref / n);
      Eigen::Vector3d yp = y;
      Dual dual;
      if (polish(yp, 0.0, dual)) {
        finish(yp, dual);
        return;
      }
      classify(0.0);
    }

    // ---- the fast path: Newton with the foot nearest to rest modelled exactly ------------------
    if (S.r2_min > 1e-28 * D0_ * D0_) {
      const Eigen::Vector3d start = y;
      Dual dual;
      if (kink_newton(y, S, Dref, dual)) {
        finish(y, dual);
        return;
      }
      // Several feet near rest at once (e.g. a mirror-symmetric pair): the path takes over from
      // the viscous start, every foot sliding.
      y = start;
      classify(0.0);
    }

    // ---- the smoothing path, with polish attempts at the end of each stage --------------------
    const double delta_min = std::max(0.1 * options_.tol * Dref / n, 64.0 * kEps * Dref / n);
    double delta = std::max(kDelta0 * value<true>(y, 0.0) / n, delta_min);
    assemble<true>(y, delta * delta, S);
    int stage_steps = 0;
    bool stalled = false;
    bool fresh = true;  // row kR2Row holds ‖r_k(y)‖² (try_polish classifies from it)
    while (s.iterations < options_.max_iterations) {
      const Eigen::Vector3d p = smoothing_step(S);
      const double slope = S.g.dot(p);
      if (!(-slope > 3.0 * delta) || stalled || stage_steps >= 8 || delta <= delta_min) {
        // End of a stage at y.
        if (delta <= 1e3 * delta_min) {
          // The smoothing path's own dual λ_k = r_k/ρ_k: its gap is O(N δ / D), so it is only
          // worth checking near the end of the path.
          const Dual dual{true, delta * delta, Eigen::Vector3d::Zero(), S.g};
          if (path_bound(y, S, delta) <= options_.tol) {
            classify(kKappa * delta);
            finish(y, dual);
            return;
          }
        }
        if (!fresh) {
          assemble<true>(y, delta * delta, S);  // ‖r_k(y)‖² back into row kR2Row
        }
        Eigen::Vector3d yp = y;
        Dual dual;
        fresh = false;  // a polish moves y
        if (try_polish(yp, std::min(kKappa * delta, 1e-2 * Dref / n), delta, dual)) {
          finish(yp, dual);
          return;
        }
        if (delta > delta_min) {
          delta = std::max(kSigma * delta, delta_min);
          assemble<true>(y, delta * delta, S);
          fresh = true;
          stage_steps = 0;
          stalled = false;
          continue;
        }
      }
      // One damped Newton step on D_δ (Armijo); the pass at the trial point is the next step's.
      ++s.iterations;
      ++stage_steps;
      stalled = !(slope < 0.0) || !line_search<true>(y, p, slope, delta * delta, 60, 0.0, S);
      fresh = fresh || !stalled;
    }
    // Out of iterations: the last point of the path with its own dual.
    classify(kKappa * delta);
    finish(y, Dual{true, delta * delta, Eigen::Vector3d::Zero(), S.g});
  }

 private:
  // ---- per-foot constants (rows of frame.work_rows, one column per foot) ------------------
  // Rows 0–5: B_k column-major (B₀₀ B₁₀ B₀₁ B₁₁ B₀₂ B₁₂), 6–7: d_k, 8: 1 for a foot with
  // friction, 9: 1 for a sliding foot (the feet a polish pass visits), 10: ‖r_k‖² of the last
  // path pass, 11: c_k. An odd count of feet is padded with a zero column.
  static constexpr int kActiveRow = 8;
  static constexpr int kSlideRow = 9;
  static constexpr int kR2Row = 10;
  static constexpr int kWeightRow = 11;
  [[nodiscard]] double at(int row, int k) const { return frame_.work_rows(row, k); }
  [[nodiscard]] double weight(int k) const { return at(kWeightRow, k); }
  [[nodiscard]] int state(int k) const { return frame_.work_idx[static_cast<std::size_t>(k)]; }
  void set_state(int k, int st) {
    frame_.work_idx[static_cast<std::size_t>(k)] = st;
    frame_.work_rows(kSlideRow, k) = st == kSlip ? 1.0 : 0.0;
  }
  [[nodiscard]] Eigen::Matrix<double, 2, 3> B(int k) const {
    Eigen::Matrix<double, 2, 3> Bk;
    Bk << at(0, k), at(2, k), at(4, k), at(1, k), at(3, k), at(5, k);
    return Bk;
  }
  [[nodiscard]] Eigen::Vector2d d(int k) const { return {at(6, k), at(7, k)}; }
  [[nodiscard]] Eigen::Vector2d residual(int k, const Eigen::Vector3d& y) const {
    return B(k) * y + d(k);
  }

  /// One pass: B_k = c W J̃_k, d_k = c W q̇_k, the states, the contact summary (balance.hpp's
  /// prepare(), merged in) and the 3 × 3 constants: the viscous system M₁ = Σ B_kᵀB_k/c_k
  /// (= Σ c J̃ᵀGJ̃ of balance.hpp), b₁ = Σ B_kᵀd_k/c_k, the dual metric M₂ = Σ B_kᵀB_k,
  /// b₂ = Σ B_kᵀd_k and D(0) = Σ ‖d_k‖. The lever scale L is known only at the end, so the
  /// lever column is built from S q (unscaled) and scaled afterwards, rows and sums alike.
  void setup() {
    auto& R = frame_.work_rows;
    R.rightCols(R.cols() - frame_.legs()).setZero();
    double L2 = 0.0;
    // Upper triangles of M₁, M₂ (00 01 02 11 12 22) and b₁, b₂.
    double m1[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    double m2[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    double v1[3] = {0.0, 0.0, 0.0};
    double v2[3] = {0.0, 0.0, 0.0};
    D0_ = 0.0;
    cs_ = detail::Contacts{};
    for (int k = 0; k < frame_.legs(); ++k) {
      const double c = detail::friction_weight(robot_, frame_, k);
      frame_.Fxy.col(k).setZero();
      if (c == 0.0) {
        R.col(k).setZero();
        frame_.work_idx[static_cast<std::size_t>(k)] = kInactive;
        continue;
      }
      ++cs_.active;
      cs_.c_sum += c;
      const double qx = frame_.q(0, k);
      const double qy = frame_.q(1, k);
      L2 = std::max(L2, qx * qx + qy * qy);
      // cW (symmetric; c I when isotropic), cW S q and cW q̇.
      double w00 = c;
      double w01 = 0.0;
      double w11 = c;
      const auto w = robot_.w.col(k);
      const double ww = w.squaredNorm();
      if (ww > 0.0) {
        cs_.anisotropic = true;
        const double al = c / (1.0 + std::sqrt(1.0 + ww));  // c α of W = I + α w wᵀ
        w00 += al * w(0) * w(0);
        w01 = al * w(0) * w(1);
        w11 += al * w(1) * w(1);
      }
      const double b4 = -w00 * qy + w01 * qx;
      const double b5 = -w01 * qy + w11 * qx;
      const double d0 = w00 * frame_.qdot(0, k) + w01 * frame_.qdot(1, k);
      const double d1 = w01 * frame_.qdot(0, k) + w11 * frame_.qdot(1, k);
      const double col[8] = {w00, w01, w01, w11, b4, b5, d0, d1};
      for (int i = 0; i < 8; ++i) {
        R(i, k) = col[i];
      }
      R(kActiveRow, k) = 1.0;
      R(kWeightRow, k) = c;
      set_state(k, kSlip);
      // BᵀB and Bᵀd for B = [cW | cW S q]; M₁ takes them over c.
      const double bb[6] = {w00 * w00 + w01 * w01, w00 * w01 + w01 * w11, w00 * b4 + w01 * b5,
                            w01 * w01 + w11 * w11, w01 * b4 + w11 * b5,   b4 * b4 + b5 * b5};
      const double bd[3] = {w00 * d0 + w01 * d1, w01 * d0 + w11 * d1, b4 * d0 + b5 * d1};
      const double ic = 1.0 / c;
      for (int i = 0; i < 6; ++i) {
        m2[i] += bb[i];
        m1[i] += bb[i] * ic;
      }
      for (int i = 0; i < 3; ++i) {
        v2[i] += bd[i];
        v1[i] += bd[i] * ic;
      }
      D0_ += std::sqrt(d0 * d0 + d1 * d1);
    }
    cs_.L = L2 > 0.0 ? std::sqrt(L2) : 1.0;
    cs_.inv_L = 1.0 / cs_.L;
    // The lever column over L: rows 4–5 of B, row/column 2 of M (twice for the corner), b(2).
    const double il = cs_.inv_L;
    R.row(4) *= il;
    R.row(5) *= il;
    auto fill = [il](const double* m, const double* v, Eigen::Matrix3d& M, Eigen::Vector3d& b) {
      M << m[0], m[1], m[2] * il, m[1], m[3], m[4] * il, m[2] * il, m[4] * il, m[5] * il * il;
      b << v[0], v[1], v[2] * il;
    };
    fill(m1, v1, M1_, b1_);
    fill(m2, v2, M2_, b2_);
    viscous_.factorize(M1_);
  }

  // ---- passes over the feet: two feet per step, Eigen::Array2d being one SSE2 register -----
  // A foot a pass does not visit (mask 0) gets ρ ≥ 1 (finite) and the weight 0 in every sum.
  // The row pointers are read once: the stores to row kR2Row would otherwise make the compiler
  // reload them for every pair of feet.
  using A2 = Eigen::Array2d;
  struct Rows {
    const double* b[8];  ///< B_k (6 rows) and d_k (2 rows)
    const double* mask;
    double* r2;
    Eigen::Index cols;
    [[nodiscard]] A2 at(int i, Eigen::Index j) const { return Eigen::Map<const A2>(b[i] + j); }
  };
  [[nodiscard]] Rows rows(int mask_row) {
    auto& R = frame_.work_rows;
    Rows out{};
    for (int i = 0; i < 8; ++i) {
      out.b[i] = R.row(i).data();
    }
    out.mask = R.row(mask_row).data();
    out.r2 = R.row(kR2Row).data();
    out.cols = R.cols();
    return out;
  }

  /// Σ √(‖r_k(y)‖² + δ²) over the visited feet (kAll: all with friction, else the sliding ones;
  /// kStore: leaves ‖r_k‖² in row kR2Row).
  template <bool kAll, bool kStore = false>
  double value(const Eigen::Vector3d& y, double d2) {
    const Rows R = rows(kAll ? kActiveRow : kSlideRow);
    const double y0 = y(0), y1 = y(1), y2 = y(2);
    A2 f = A2::Zero();
    for (Eigen::Index j = 0; j < R.cols; j += 2) {
      const A2 m = Eigen::Map<const A2>(R.mask + j);
      const A2 r0 = R.at(0, j) * y0 + R.at(2, j) * y1 + R.at(4, j) * y2 + R.at(6, j);
      const A2 r1 = R.at(1, j) * y0 + R.at(3, j) * y1 + R.at(5, j) * y2 + R.at(7, j);
      const A2 rr = r0 * r0 + r1 * r1;
      if constexpr (kStore) {
        Eigen::Map<A2>(R.r2 + j) = rr;
      }
      f += m * (rr + d2).sqrt();
    }
    return f.sum();
  }

  /// The Sums of D_δ over the visited feet at y (one pass, the solver's cost); leaves ‖r_k‖² of
  /// every foot in row kR2Row. With δ = 0 the Hessian term is t_k t_kᵀ/‖r_k‖
  /// (t_k = B_kᵀ n_k⊥); a visited foot with r_k = 0 then gives r2_min = 0 and a non-finite H,
  /// which the caller rejects.
  template <bool kAll>
  void assemble(const Eigen::Vector3d& y, double d2, Sums& S) {
    if (d2 > 0.0) {
      assemble<kAll, true>(y, d2, S);
    } else {
      assemble<kAll, false>(y, 0.0, S);
    }
  }
  template <bool kAll, bool kSmooth>
  void assemble(const Eigen::Vector3d& y, double d2, Sums& S) {
    const Rows R = rows(kAll ? kActiveRow : kSlideRow);
    const double y0 = y(0), y1 = y(1), y2 = y(2);
    A2 f = A2::Zero(), inv = A2::Zero(), rho_max = A2::Zero(), r2_min = A2::Constant(kInf);
    A2 g0 = A2::Zero(), g1 = A2::Zero(), g2 = A2::Zero();
    A2 h00 = A2::Zero(), h01 = A2::Zero(), h02 = A2::Zero();
    A2 h11 = A2::Zero(), h12 = A2::Zero(), h22 = A2::Zero();
    for (Eigen::Index j = 0; j < R.cols; j += 2) {
      const A2 m = Eigen::Map<const A2>(R.mask + j);
      const A2 b0 = R.at(0, j), b1 = R.at(1, j), b2 = R.at(2, j);
      const A2 b3 = R.at(3, j), b4 = R.at(4, j), b5 = R.at(5, j);
      const A2 r0 = b0 * y0 + b2 * y1 + b4 * y2 + R.at(6, j);
      const A2 r1 = b1 * y0 + b3 * y1 + b5 * y2 + R.at(7, j);
      const A2 rr = r0 * r0 + r1 * r1;
      Eigen::Map<A2>(R.r2 + j) = rr;
      const A2 rho = (rr + d2 + (1.0 - m)).sqrt();  // ρ_k, or ≥ 1 where m = 0 (1 − m is exact)
      const A2 ir = m / rho;
      f += m * rho;
      if constexpr (kSmooth) {
        inv += ir;
        rho_max = rho_max.max(m * rho);
      } else {
        r2_min = r2_min.min(rr + (1.0 - m) * kBig);
      }
      // ∇ρ = Bᵀr/ρ;  ∇²ρ = Bᵀ(δ² I + r⊥r⊥ᵀ)B/ρ³ with v = Bᵀr⊥.
      g0 += (b0 * r0 + b1 * r1) * ir;
      g1 += (b2 * r0 + b3 * r1) * ir;
      g2 += (b4 * r0 + b5 * r1) * ir;
      const A2 v0 = b1 * r0 - b0 * r1;
      const A2 v1 = b3 * r0 - b2 * r1;
      const A2 v2 = b5 * r0 - b4 * r1;
      const A2 w = ir * ir * ir;
      const A2 wv0 = w * v0;
      const A2 wv1 = w * v1;
      h00 += wv0 * v0;
      h01 += wv0 * v1;
      h02 += wv0 * v2;
      h11 += wv1 * v1;
      h12 += wv1 * v2;
      h22 += w * v2 * v2;
      if constexpr (kSmooth) {
        const A2 wd = w * d2;
        h00 += wd * (b0 * b0 + b1 * b1);
        h01 += wd * (b0 * b2 + b1 * b3);
        h02 += wd * (b0 * b4 + b1 * b5);
        h11 += wd * (b2 * b2 + b3 * b3);
        h12 += wd * (b2 * b4 + b3 * b5);
        h22 += wd * (b4 * b4 + b5 * b5);
      }
    }
    S.f = f.sum();
    S.inv_rho = inv.sum();
    S.rho_max = rho_max.maxCoeff();
    S.r2_min = r2_min.minCoeff();
    S.g << g0.sum(), g1.sum(), g2.sum();
    const double H00 = h00.sum(), H01 = h01.sum(), H02 = h02.sum();
    const double H11 = h11.sum(), H12 = h12.sum(), H22 = h22.sum();
    S.H << H00, H01, H02, H01, H11, H12, H02, H12, H22;
  }

  /// Armijo line search along p from y (Sums S at y), folded into the passes: the pass at the
  /// full step is also the next step's assembly; only a rejected step costs extra (value passes,
  /// t halved at most `halvings` times, never below t_min). On success y and S move to the
  /// accepted point; on failure they stay.
  template <bool kAll>
  bool line_search(Eigen::Vector3d& y, const Eigen::Vector3d& p, double slope, double d2,
                   int halvings, double t_min, Sums& S) {
    const double f0 = S.f;
    const double slack = 8.0 * kEps * f0;
    Sums T;
    assemble<kAll>(y + p, d2, T);
    if (T.f <= f0 + 1e-4 * slope + slack) {
      y += p;
      S = T;
      return true;
    }
    double t = 0.5;
    for (int j = 1; j < halvings && t >= t_min; ++j, t *= 0.5) {
      if (value<kAll>(y + t * p, d2) <= f0 + 1e-4 * t * slope + slack) {
        y += t * p;
        assemble<kAll>(y, d2, S);
        return true;
      }
    }
    return false;
  }

  /// The Newton step of the smoothing path. H is positive definite on the range of M₂ (whatever
  /// δ: no rank threshold here, the directions of a foot near rest are legitimately stiff); its
  /// null space (contacts at one point) is filled in so that the step has no component there.
  [[nodiscard]] Eigen::Vector3d smoothing_step(const Sums& S) const {
    Eigen::Matrix3d H = S.H;
    dual_.add_null_space(H, H.trace());
    detail::Psd3 solver;
    if (!solver.factorize_definite(H, 0.0)) {
      solver.factorize(H);
    }
    return -solver.solve(S.g);
  }

  // ---- the fast path --------------------------------------------------------------------------
  /// Newton's method on the exact D from y (S: its sums over every foot, all sliding), with the
  /// foot nearest to rest — the one whose kink a quadratic model would step across — modelled
  /// exactly (kink_step): the step makes it stick when its force fits in its disk, and slide
  /// past its kink otherwise. Where the plain Newton step moves that foot's slip by less than
  /// half of it, its quadratic model is good and the plain step is taken. At the optimum the
  /// model is exact for that foot and Newton's quadratic convergence holds for the others (they
  /// slide), so a frame with at most one static foot (the generic case) certifies in a few
  /// steps. Points are certified with the model's dual (polish_bound's, plus the kink foot's λ)
  /// once the model's predicted decrease is small enough for that to be possible. Returns false
  /// (y moved downhill, states arbitrary) when the model degenerates or stops converging: the
  /// smoothing path takes over.
  bool kink_newton(Eigen::Vector3d& y, Sums& S, double Dref, Dual& dual) {
    auto& s = frame_.friction;
    int held = -1;  // the foot held static: y lies on its line r_held(y) = 0
    double D = S.f;
    for (int it = 0;; ++it) {
      // The kink foot: the held one, or the sliding foot slowest in slip speed ‖r_k‖/c_k.
      int ks = held;
      if (ks < 0) {
        double best = kInf;
        for (int k = 0; k < frame_.legs(); ++k) {
          const double c = weight(k);
          if (state(k) == kSlip && at(kR2Row, k) < best * c * c) {
            best = at(kR2Row, k) / (c * c);
            ks = k;
          }
        }
      }
      const auto Bk = B(ks);
      const Eigen::Vector2d r = Bk * y + d(ks);
      const double nr = r.norm();
      Eigen::Vector3d g = S.g;
      Eigen::Matrix3d H = S.H;
      KinkStep st;
      int kink = -1;
      bool newton_ok = false;
      if (held < 0 && solve_spd3(H, -g, detail::kRankTol, st.p)) {
        st.decrease = -0.5 * g.dot(st.p);
        newton_ok = st.decrease > 0.0;
      }
      if (!newton_ok || (Bk * st.p).squaredNorm() > 0.25 * nr * nr) {
        const KinkStep plain = st;
        if (held < 0) {  // take the kink foot's quadratic model out of the sums
          const Eigen::Vector2d n = r / nr;
          const Eigen::Vector3d t = Bk.transpose() * Eigen::Vector2d(-n(1), n(0));
          g -= Bk.transpose() * n;
          H -= t * (t.transpose() / nr);
        }
        if (!kink_step(g, H, Bk, r, st)) {
          // A degenerate model: the other sliding feet's quadratic models are flat along their
          // slip (e.g. only two of them), and with the kink foot sliding it is unbounded there.
          // The plain step if there is one, else the model with a little curvature of M₂ added
          // (a damped step: the line search judges it, the certificate uses the true H).
          if (!newton_ok) {
            const double eps = 1e-2 * H.trace() / M2_.trace();
            if (!kink_step(g, Eigen::Matrix3d(H + eps * M2_), Bk, r, st)) {
              return false;
            }
            kink = ks;
          } else {
            g = S.g;
            H = S.H;
            st = plain;
          }
        } else {
          kink = ks;
        }
      }
      // The dual at y: the sliding feet's λ linearized along p (polish_bound), the kink foot's λ.
      // Tried once the predicted decrease is below 1e-3 tol D, as the path's polish does: the
      // certificate would often pass earlier, but finish() reports y + p, and this makes that
      // Newton point exact to ~1e-13 (a continuous, mirror-symmetric answer for symmetric gaits).
      if (st.decrease <= 1e-3 * options_.tol * Dref) {
        const double fo = kink >= 0 && held < 0 ? S.f - nr : S.f;
        const Eigen::Vector3d gp = g + H * st.p;
        const double dec = st.p.dot(H * st.p);
        double lmax = std::sqrt(1.0 + std::max(dec, 0.0) / std::sqrt(S.r2_min));
        Eigen::Vector3d h = gp;
        double value = fo - gp.dot(y);
        if (kink >= 0) {
          lmax = std::max(lmax, st.lam.norm());
          h += Bk.transpose() * st.lam;
          value += st.lam.dot(d(ks));
        }
        if (bound(kink >= 0 ? fo + nr : fo, value, lmax, h) <= options_.tol) {
          if (kink >= 0) {
            set_state(ks, st.stick ? kStatic : kSlip);
            frame_.work_2n.col(ks) = st.lam;
          }
          dual = Dual{false, 0.0, st.p, h, kink};
          return true;
        }
      }
      if (it >= kKinkSteps || s.iterations >= options_.max_iterations) {
        return false;
      }
      // Armijo on D against the model's decrease; the pass at the full step is the next step's.
      ++s.iterations;
      const bool stick = kink >= 0 && st.stick;
      const double slack = 8.0 * kEps * D;
      set_state(ks, stick ? kStatic : kSlip);
      Sums T;
      const Eigen::Vector3d trial = y + st.p;
      assemble<false>(trial, 0.0, T);
      const double Dt = T.f + (stick ? residual(ks, trial).norm() : 0.0);
      if (Dt <= D - 1e-4 * st.decrease + slack && T.r2_min > 1e-28 * D0_ * D0_) {
        y = trial;
        S = T;
        D = Dt;
        held = stick ? ks : -1;
        continue;
      }
      // Backtracking: off the full step a sticking foot slips again, unless it was held and
      // the step keeps it on its line.
      const bool keep = stick && held == ks;
      set_state(ks, keep ? kStatic : kSlip);
      bool accepted = false;
      for (double t = 0.5; t >= 1.0 / 16.0 && !accepted; t *= 0.5) {
        const Eigen::Vector3d yt = y + t * st.p;
        const double Dv =
            keep ? value<false>(yt, 0.0) + residual(ks, yt).norm() : value<true>(yt, 0.0);
        if (Dv <= D - 1e-4 * t * st.decrease + slack) {
          y = yt;
          D = Dv;
          accepted = true;
        }
      }
      if (!accepted) {
        return false;
      }
      assemble<false>(y, 0.0, S);
      if (!(S.r2_min > 1e-28 * D0_ * D0_)) {
        return false;
      }
      held = keep ? ks : -1;
    }
  }

  // ---- certificates without a pass (see Dual in the header) ---------------------------------
  /// The relative gap of a dual candidate of value `value`, imbalance h and largest ‖λ_k‖ lmax,
  /// against the primal `primal` (an upper bound of D(y) will do).
  [[nodiscard]] double bound(double primal, double value, double lmax,
                             const Eigen::Vector3d& h) const {
    const Eigen::Vector3d mu = dual_.solve(h);
    const double shrink = 1.0 / std::max(1.0, lmax + std::sqrt(std::max(mu.dot(h), 0.0)));
    const double dual = shrink * (value - mu.dot(b2_));
    const double denom = std::max(primal, D0_);
    return denom > 0.0 ? std::max(primal - dual, 0.0) / denom : 0.0;
  }

  /// The smoothing dual λ_k = r_k/ρ_k at y: Σ λᵀd = Σ ‖r‖²/ρ − yᵀg, ‖λ_k‖ ≤ √(1 − δ²/ρ_max²),
  /// imbalance g; D(y) ≤ Σ ρ and max(D, D(0)) ≥ max(Σ ρ − N δ, D(0)).
  [[nodiscard]] double path_bound(const Eigen::Vector3d& y, const Sums& S, double delta) const {
    const double d2 = delta * delta;
    const double value = S.f - d2 * S.inv_rho - y.dot(S.g);
    const double lmax = std::sqrt(std::max(1.0 - d2 / (S.rho_max * S.rho_max), 0.0));
    const double lower = std::max(S.f - cs_.active * delta, 0.0);
    const double gap = bound(S.f, value, lmax, S.g);
    const double denom = std::max(S.f, D0_);
    return gap * denom / std::max(std::max(lower, D0_), kEps * denom);
  }

  /// The polish dual at y with step p (Sums S of the sliding feet): Σ_slide B_kᵀλ_k = g + H p =
  /// g', Σ_slide λ_kᵀd_k = Σ ‖r_k‖ − g'ᵀy (as n_k⊥ ⊥ r_k), ‖λ_k‖² = 1 + (t_kᵀp)²/‖r_k‖² ≤
  /// 1 + pᵀHp/min ‖r‖; the static feet balance g' (static_duals, written to work_2n).
  double polish_bound(const Eigen::Vector3d& y, const Sums& S, const Eigen::Vector3d& p, int dim,
                      int n_static, Dual& dual) {
    const Eigen::Vector3d gp = S.g + S.H * p;
    const double dec = p.dot(S.H * p);
    double lmax = S.r2_min < kInf ? std::sqrt(1.0 + std::max(dec, 0.0) / std::sqrt(S.r2_min)) : 1.0;
    StaticDual st;
    if (n_static > 0 && dim > 0) {
      st = static_duals(y, gp);
      lmax = std::max(lmax, st.lmax);
    }
    dual = Dual{false, 0.0, p, gp + st.force};
    return bound(S.f + st.primal, S.f - gp.dot(y) + st.value, lmax, dual.h);
  }

  /// Static feet at one point (dim 1) share the force that balances g' in proportion to c_k:
  /// c_k W_k λ_k = −(c_k/Σ_S c) g'_xy, i.e. B_k,xy λ_k = −(c_k/Σ_S c) g'_xy; the moment about
  /// their point is then balanced too when eᵀg' = 0 (the Newton equation along e). Writes λ_k to
  /// work_2n.
  StaticDual static_duals(const Eigen::Vector3d& y, const Eigen::Vector3d& gp) {
    StaticDual st;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) != kStatic) {
        continue;
      }
      const auto Bk = B(k);
      const Eigen::Vector2d lam = Bk.leftCols<2>().partialPivLu().solve(
          Eigen::Vector2d(-(weight(k) / c_static_) * gp.head<2>()));
      frame_.work_2n.col(k) = lam;
      st.lmax = std::max(st.lmax, lam.norm());
      st.value += lam.dot(d(k));
      st.force += Bk.transpose() * lam;
      st.primal += residual(k, y).norm();
    }
    return st;
  }

  void zero_static_duals() {
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kStatic) {
        frame_.work_2n.col(k).setZero();
      }
    }
  }

  // ---- the active set ---------------------------------------------------------------------------
  /// Marks feet with ‖r_k‖ ≤ threshold static (from ‖r_k‖² in row kR2Row); returns how many.
  int classify(double threshold) {
    const double t2 = threshold * threshold;
    int n = 0;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kInactive) {
        continue;
      }
      const bool st = at(kR2Row, k) <= t2;
      set_state(k, st ? kStatic : kSlip);
      n += st ? 1 : 0;
    }
    return n;
  }

  /// A polish attempt at the end of a smoothing stage (‖r_k(y)‖² in row kR2Row): the feet with
  /// ‖r_k‖ ≤ threshold are static, and the slowest other foot too if it is clearly apart (step 3
  /// of the header).
  bool try_polish(Eigen::Vector3d& y, double threshold, double delta, Dual& dual) {
    const double t2 = threshold * threshold;
    // Classify, and find the three slowest sliding feet: k1, k2 with ‖r‖² = r1 ≤ r2 ≤ r3.
    int k1 = -1;
    int k2 = -1;
    double r1 = kInf;
    double r2 = kInf;
    double r3 = kInf;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kInactive) {
        continue;
      }
      const double nr = at(kR2Row, k);
      set_state(k, nr <= t2 ? kStatic : kSlip);
      if (state(k) == kStatic) {
        continue;
      }
      if (nr < r1) {
        r3 = r2;
        r2 = r1;
        k2 = k1;
        r1 = nr;
        k1 = k;
      } else if (nr < r2) {
        r3 = r2;
        r2 = nr;
        k2 = k;
      } else if (nr < r3) {
        r3 = nr;
      }
    }
    const double apart = 1e3 * delta * 1e3 * delta;
    if (k2 >= 0 && r2 <= 0.01 * r3 && r2 <= apart) {
      set_state(k1, kStatic);  // two feet clearly apart (e.g. a rigid pair: their forces are
      set_state(k2, kStatic);  // not unique, and either may sit on its rim)
    } else if (k1 >= 0 && r1 <= 0.01 * r2 && r1 <= apart) {
      set_state(k1, kStatic);
    }
    return polish(y, delta, dual);
  }

  /// Active-set polish from y (a point of the smoothing path at δ) with the static feet marked
  /// in work_idx. On success (relative gap ≤ tol) y and `dual` are the certified pair (static
  /// feet's λ in work_2n).
  bool polish(Eigen::Vector3d& y, double delta, Dual& dual) {
    auto& s = frame_.friction;
    // ---- where the static feet do not slip: all of R³, a line or a point --------------------
    // The path's dual of the static feet (λ = r/ρ) goes to work_2n as a start for
    // fit_static_forces.
    int n_static = 0;
    int first = -1;
    bool one_point = true;
    Eigen::Matrix3d MS = Eigen::Matrix3d::Zero();
    Eigen::Vector3d bS = Eigen::Vector3d::Zero();
    Eigen::Matrix2d GS = Eigen::Matrix2d::Zero();
    Eigen::Vector2d hS = Eigen::Vector2d::Zero();
    c_static_ = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) != kStatic) {
        continue;
      }
      ++n_static;
      if (first < 0) {
        first = k;
      } else if ((frame_.q.col(k).head<2>() - frame_.q.col(first).head<2>()).norm() >
                 1e-6 * cs_.L) {
        one_point = false;
      }
      const auto Bk = B(k);
      const Eigen::Vector2d r = residual(k, y);
      const double rho = std::sqrt(r.squaredNorm() + delta * delta);
      frame_.work_2n.col(k) = delta > 0.0 ? Eigen::Vector2d(r / rho) : Eigen::Vector2d::Zero();
      MS += Bk.transpose() * Bk;
      bS += Bk.transpose() * d(k);
      GS += Bk.leftCols<2>().transpose() * Bk.leftCols<2>();
      hS += Bk.leftCols<2>().transpose() * d(k);
      c_static_ += weight(k);
    }
    int dim = 3;
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    detail::Psd3 static_solver;
    if (n_static > 0 && one_point) {
      // v = −q̇_S − ω̃ s̃_p: the static feet's common point p stays put; ω̃ is free. s̃_p is the
      // lever of the first static foot: B_xy⁻¹ B_ω.
      dim = 1;
      const auto Bf = B(first);
      const Eigen::Vector2d sp = Bf.leftCols<2>().partialPivLu().solve(Eigen::Vector2d(Bf.col(2)));
      y.head<2>() = -(GS.inverse() * hS) - y(2) * sp;
      e = Eigen::Vector3d(-sp(0), -sp(1), 1.0).normalized();
    } else if (n_static > 0) {
      // Two or more distinct static points fix y; feet that then do not slip either (a rigid
      // gait) join the static set, for the dual below.
      dim = 0;
      static_solver.factorize(MS);
      y = -static_solver.solve(bS);
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) == kSlip && residual(k, y).norm() <= 1e-12 * D0_) {
          set_state(k, kStatic);
          frame_.work_2n.col(k).setZero();
          ++n_static;
          MS += B(k).transpose() * B(k);
        }
      }
      static_solver.factorize(MS);
    }
    Sums S;
    assemble<false>(y, 0.0, S);
    if (!(S.r2_min > 1e-28 * D0_ * D0_)) {
      return false;  // a sliding foot is at rest: the static set is wrong
    }
    if (dim == 0) {
      return fixed_point_dual(y, S, static_solver, n_static, dual);
    }

    // ---- exact Newton on the sliding feet's D over that set (quadratic, or give up) ---------
    // Armijo steps; the attempt is given up as soon as a step after the first needs damping
    // below 1/2 or the decrement does not fall 4× per step. Each point is first checked with
    // the dual of its Newton step, then (when the step is tiny) with the plain directions.
    double prev = kInf;
    for (int it = 0;; ++it) {
      Eigen::Vector3d p;
      double decrement;
      if (dim == 3) {
        detail::Psd3 solver;
        solver.factorize(S.H);
        p = -solver.solve(S.g);
        decrement = -S.g.dot(p);
      } else {
        // e is felt by no sliding foot (e.g. all at the static point): nothing to do.
        const double ge = S.g.dot(e);
        const double he = e.dot(S.H * e);
        const bool felt = he > detail::kRankTol * S.H.trace();
        p = felt ? Eigen::Vector3d(-(ge / he) * e) : Eigen::Vector3d::Zero();
        decrement = felt ? ge * ge / he : 0.0;
      }
      // Certified only once the decrement is tiny (then finish()'s Newton point y + p is exact
      // to ~1e-13, see kink_newton); near a sliding foot at rest the linearized dual is loose,
      // the plain directions n_k (p = 0) are not.
      if (!(decrement > 1e-3 * options_.tol * std::max(S.f, D0_))) {
        return polish_bound(y, S, p, dim, n_static, dual) <= options_.tol ||
               polish_bound(y, S, Eigen::Vector3d::Zero(), dim, n_static, dual) <= options_.tol;
      }
      if ((it >= 2 && decrement > 0.25 * prev) || it >= 8 ||
          s.iterations >= options_.max_iterations) {
        return false;  // not converging quadratically: a kink nearby, wrong static set
      }
      prev = decrement;
      ++s.iterations;
      if (!line_search<false>(y, p, -decrement, 0.0, it == 0 ? 30 : 2, it == 0 ? 0.0 : 0.5, S) ||
          !(S.r2_min > 1e-28 * D0_ * D0_)) {
        return false;  // damping needed after the first step: a kink nearby
      }
    }
  }

  /// The dual when two or more distinct static points fix y (no Newton step): unit directions
  /// for sliding feet, least-norm balancing forces for static ones, fitted into their disks.
  bool fixed_point_dual(const Eigen::Vector3d& y, const Sums& S, const detail::Psd3& static_solver,
                        int n_static, Dual& dual) {
    if (n_static > 2) {
      fit_static_forces(static_solver, S.g, n_static);
    } else {
      const Eigen::Vector3d mu = -static_solver.solve(S.g);
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) == kStatic) {
          frame_.work_2n.col(k) = B(k) * mu;
        }
      }
      fit_static_forces(static_solver, S.g, n_static);
    }
    StaticDual st;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kStatic) {
        const Eigen::Vector2d lam = frame_.work_2n.col(k);
        st.lmax = std::max(st.lmax, lam.norm());
        st.value += lam.dot(d(k));
        st.force += B(k).transpose() * lam;
        st.primal += residual(k, y).norm();
      }
    }
    dual = Dual{false, 0.0, Eigen::Vector3d::Zero(), S.g + st.force};
    return bound(S.f + st.primal, S.f - S.g.dot(y) + st.value, std::max(1.0, st.lmax), dual.h) <=
           options_.tol;
  }

  /// Static feet at two or more distinct points balance the sliding ones (Σ_S B_kᵀλ_k = −g) with
  /// an undetermined internal force, so a balancing choice inside the disks must be searched.
  /// Two feet (work_2n = the least-norm choice): the internal force is a multiple t of the push
  /// along the line between them, each disk allows an interval of t, and the t nearest 0 in both
  /// is taken. More feet (work_2n = the smoothing path's λ, O(δ) from an optimal dual):
  /// alternating projections between the balance and the disks, at most 200 (rigid gaits only).
  void fit_static_forces(const detail::Psd3& static_solver, const Eigen::Vector3d& g,
                         int n_static) {
    auto lam = [this](int k) { return frame_.work_2n.col(k); };
    double worst = 0.0;
    int a = -1;
    int b = -1;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) == kStatic) {
        worst = std::max(worst, lam(k).squaredNorm());
        (a < 0 ? a : b) = k;
      }
    }
    if (n_static == 2 && worst <= 1.0) {
      return;
    }
    worst = 2.0;  // several feet: always enforce the balance first
    if (n_static == 2) {
      // λ_a + t z_a, λ_b + t z_b with c_a W_a z_a = dq = −c_b W_b z_b, dq ∥ q_a − q_b.
      const Eigen::Vector2d dq = frame_.q.col(a).head<2>() - frame_.q.col(b).head<2>();
      const Eigen::Vector2d za = B(a).leftCols<2>().partialPivLu().solve(dq);
      const Eigen::Vector2d zb = -B(b).leftCols<2>().partialPivLu().solve(dq);
      double lo = -kInf;
      double hi = kInf;
      for (const auto& [k, z] : {std::pair{a, za}, std::pair{b, zb}}) {
        const Eigen::Vector2d l0 = lam(k);
        const double A = z.squaredNorm();
        const double Bz = l0.dot(z);
        const double disc = Bz * Bz - A * (l0.squaredNorm() - 1.0);
        if (!(A > 0.0) || disc < 0.0) {
          return;  // this disk cannot be reached: no feasible choice, the certificate will say
        }
        const double root = std::sqrt(disc);
        lo = std::max(lo, (-Bz - root) / A);
        hi = std::min(hi, (-Bz + root) / A);
      }
      if (lo <= hi) {
        const double t = std::clamp(0.0, lo, hi);
        lam(a) += t * za;
        lam(b) += t * zb;
      }
      return;
    }
    for (int it = 0; it < 200 && worst > 1.0; ++it) {
      // Project onto the disks (not before the first balance), then back onto the balance
      // Σ_S B_kᵀλ_k = −g (least-norm correction).
      Eigen::Vector3d imbalance = g;
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) == kStatic) {
          const double n2 = lam(k).squaredNorm();
          if (n2 > 1.0 && it > 0) {
            lam(k) /= std::sqrt(n2);
          }
          imbalance += B(k).transpose() * lam(k);
        }
      }
      const Eigen::Vector3d mu = static_solver.solve(imbalance);
      worst = 0.0;
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) == kStatic) {
          lam(k) -= B(k) * mu;
          worst = std::max(worst, lam(k).squaredNorm());
        }
      }
      worst = worst > 1.0 + 1e-14 ? worst : 0.0;
    }
  }

  // ---- the answer -------------------------------------------------------------------------------
  /// One pass: builds the dual candidate's λ_k, balances it (λ_k −= B_k μ, μ = M₂⁺h), writes the
  /// forces F_k = −c_k W_k λ_k = −B_k,xy λ_k and sums what the summary needs; then scales the
  /// forces into the disks, and reports the candidate's exact gap as the certificate.
  void finish(Eigen::Vector3d y, const Dual& dual) {
    auto& s = frame_.friction;
    const Eigen::Vector3d mu = dual_.solve(dual.h);
    detail::BalanceSum sum;
    double scale = 0.0;
    double primal = 0.0;   // D(y)
    double stepped = 0.0;  // D(y + p): the answer unless higher
    double value = 0.0;
    double lmax2 = 0.0;
    int n_static = 0;
    bool distinct = false;
    int first = -1;
    double q[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};  // Σ t tᵀ/c_k of sliding feet (Q's upper part)
    const auto& R = frame_.work_rows;
    for (int k = 0; k < frame_.legs(); ++k) {
      const int st = state(k);
      if (st == kInactive) {
        frame_.Fxy.col(k).setZero();
        continue;
      }
      // Written out in scalars: this loop runs once per solve over every foot.
      const double b0 = R(0, k), b1 = R(1, k), b2 = R(2, k), b3 = R(3, k), b4 = R(4, k);
      const double b5 = R(5, k), d0 = R(6, k), d1 = R(7, k), c = R(kWeightRow, k);
      const double r0 = b0 * y(0) + b2 * y(1) + b4 * y(2) + d0;
      const double r1 = b1 * y(0) + b3 * y(1) + b5 * y(2) + d1;
      const double rr = r0 * r0 + r1 * r1;
      const double nr = std::sqrt(rr);
      primal += nr;
      const double s0 = r0 + b0 * dual.p(0) + b2 * dual.p(1) + b4 * dual.p(2);
      const double s1 = r1 + b1 * dual.p(0) + b3 * dual.p(1) + b5 * dual.p(2);
      stepped += std::sqrt(s0 * s0 + s1 * s1);
      double l0;
      double l1;
      if (st == kSlip && nr > 0.0) {
        // n = r/‖r‖ and t = Bᵀn⊥: the linearized dual's direction and the flat test's Q.
        const double inr = 1.0 / nr;
        const double n0 = r0 * inr;
        const double n1 = r1 * inr;
        const double t0 = b1 * n0 - b0 * n1;
        const double t1 = b3 * n0 - b2 * n1;
        const double t2 = b5 * n0 - b4 * n1;
        const double ic = 1.0 / c;
        q[0] += t0 * t0 * ic;
        q[1] += t0 * t1 * ic;
        q[2] += t0 * t2 * ic;
        q[3] += t1 * t1 * ic;
        q[4] += t1 * t2 * ic;
        q[5] += t2 * t2 * ic;
        const double tp = (t0 * dual.p(0) + t1 * dual.p(1) + t2 * dual.p(2)) * inr;
        l0 = n0 - n1 * tp;
        l1 = n1 + n0 * tp;
      } else {
        l0 = frame_.work_2n(0, k);
        l1 = frame_.work_2n(1, k);
      }
      if (dual.path) {
        const double ir = 1.0 / std::sqrt(rr + dual.d2);
        l0 = r0 * ir;
        l1 = r1 * ir;
      } else if (k == dual.kink) {
        l0 = frame_.work_2n(0, k);
        l1 = frame_.work_2n(1, k);
      }
      l0 -= b0 * mu(0) + b2 * mu(1) + b4 * mu(2);
      l1 -= b1 * mu(0) + b3 * mu(1) + b5 * mu(2);
      frame_.work_2n(0, k) = l0;
      frame_.work_2n(1, k) = l1;
      lmax2 = std::max(lmax2, l0 * l0 + l1 * l1);
      value += l0 * d0 + l1 * d1;
      const double F0 = -(b0 * l0 + b2 * l1);
      const double F1 = -(b1 * l0 + b3 * l1);
      frame_.Fxy(0, k) = F0;
      frame_.Fxy(1, k) = F1;
      sum.add(frame_, k, Eigen::Vector2d(F0, F1));
      scale += cs_.anisotropic ? c * std::sqrt(1.0 + robot_.w.col(k).squaredNorm()) : c;
      if (st == kStatic) {
        ++n_static;
        if (first < 0) {
          first = k;
        } else if ((frame_.q.col(k).head<2>() - frame_.q.col(first).head<2>()).norm() >
                   1e-6 * cs_.L) {
          distinct = true;
        }
      }
    }
    Eigen::Matrix3d Q;
    Q << q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5];
    if (lmax2 > 1.0) {
      const double shrink = 1.0 / std::sqrt(lmax2);
      frame_.Fxy *= shrink;
      frame_.work_2n *= shrink;
      sum.force *= shrink;
      sum.moment *= shrink;
      value *= shrink;
    }
    if (stepped <= primal + 8.0 * kEps * primal) {
      // The Newton point: D agrees to rounding near the optimum, but the step zeroes the
      // gradient, which places y far more precisely than a comparison of values can.
      y += dual.p;
      primal = stepped;
    }
    const double denom = std::max(primal, D0_);
    const double cert = denom > 0.0 ? std::max(primal - value, 0.0) / denom : 0.0;
    s.certificate = cert;
    s.converged = cert <= options_.tol;
    s.static_feet = n_static;
    s.unique = cs_.active > 0 && dual_.rank() == 3 && !flat_direction(Q, n_static);
    // Least norm along directions no foot feels (contacts at one point), then the body velocity.
    y = dual_.project_to_range(y);
    detail::set_velocity(frame_, y, cs_.L);
    s.dissipation = primal;
    s.residual = sum.residual(scale, cs_.L);
    if (cs_.active == 0) {
      s.message = "no foot with friction in contact: body velocity undetermined, set to 0";
    } else if (!s.converged) {
      s.message = "iteration limit: relative duality gap " + core::format_double(cert) +
                  " above the tolerance " + core::format_double(options_.tol);
    } else if (dual_.rank() < 3) {
      s.message = "all contacts at one point: rotation about it undetermined (least-norm solution)";
    } else if (!s.unique) {
      s.message = "flat minimum of the dissipation: a continuum of body velocities balance";
    } else if (distinct) {
      s.message =
          "static feet at distinct points: their internal force is undetermined (least-norm "
          "forces reported)";
    }
  }

  /// Whether D has a flat direction at the optimum (see the header comment), given the sliding
  /// feet's part of Q and the certified dual λ in work_2n.
  bool flat_direction(Eigen::Matrix3d Q, int n_static) const {
    if (n_static > 0) {
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) != kStatic) {
          continue;
        }
        const Eigen::Vector2d lam = frame_.work_2n.col(k);
        const double nl = lam.norm();
        const auto Bk = B(k);
        if (nl >= 1.0 - 1e-9) {
          const Eigen::Vector2d np(-lam(1) / nl, lam(0) / nl);
          const Eigen::Vector3d t = Bk.transpose() * np;
          Q += t * t.transpose() / weight(k);
        } else {
          Q += Bk.transpose() * Bk / weight(k);
        }
      }
    }
    const double tr = Q.trace();
    if (!(tr > 0.0)) {
      return true;
    }
    // Quick exit: pivots ≥ 1e-3 tr bound the smallest eigenvalue below by ~1e-9 tr.
    detail::Psd3 quick;
    if (quick.factorize_definite(Q, 1e-3)) {
      return false;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(Q);
    for (int i = 0; i < 3; ++i) {
      if (es.eigenvalues()(i) > 1e-10 * tr) {
        continue;
      }
      const Eigen::Vector3d e = es.eigenvectors().col(i);
      // Static feet on the rim must start sliding along their force: λ_kᵀ B_k e of one sign.
      bool plus = true;
      bool minus = true;
      for (int k = 0; k < frame_.legs(); ++k) {
        if (state(k) != kStatic) {
          continue;
        }
        const Eigen::Vector2d lam = frame_.work_2n.col(k);
        if (lam.norm() < 1.0 - 1e-9) {
          continue;
        }
        const Eigen::Vector2d Be = B(k) * e;
        const double t = lam.dot(Be);
        const double tol = 1e-9 * Be.norm();
        plus = plus && t >= -tol;
        minus = minus && t <= tol;
      }
      if (plus || minus) {
        return true;
      }
    }
    return false;
  }

  const contact::Robot& robot_;
  contact::Frame& frame_;
  detail::Contacts cs_;  ///< filled by setup()
  CoulombOptions options_;
  detail::Psd3 dual_;     ///< M₂ = Σ B_kᵀB_k (least norm on its range)
  detail::Psd3 viscous_;  ///< M₁, the viscous-Coulomb system
  Eigen::Matrix3d M1_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d M2_ = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b1_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d b2_ = Eigen::Vector3d::Zero();
  double D0_ = 0.0;
  double c_static_ = 0.0;  ///< Σ c_k over the static feet of the current polish
};

}  // namespace

void solve_coulomb(const contact::Robot& robot, contact::Frame& frame,
                   const CoulombOptions& options) {
  CoulombSolver(robot, frame, options).run();
}

}  // namespace slipwalk::friction
