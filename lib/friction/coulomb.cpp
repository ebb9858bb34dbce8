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
// Cost model. Everything per foot is computed once (setup): B_k, d_k and c_k, stored as rows of
// frame.coulomb (contact/robot.hpp) so that a pass over the feet handles two feet per SSE2
// instruction. A pass costs six multiply-adds for r_k, one square root and one division per foot,
// and returns all a Newton step needs (Sums: D, gradient, Hessian); the line search is folded into
// the next pass (the pass at a full step is the next step's), and the certificate needs no pass
// (bound()). A solve is then setup + (Newton steps + 1) passes + one final pass (finish) that
// writes the forces; what remains per step is 3 × 3 algebra, kept free of chained divisions.
//
// Algorithm (always terminates: every loop is bounded by options.max_iterations).
//  1. Start at the viscous-Coulomb solution (if nothing slips there, certify that at once).
//     Along a trajectory (options.warm_start) start instead at the frame's v_body, the previous
//     frame's answer: successive frames differ little, so it lies within a Newton step or two of
//     the answer and its static foot is already the slowest (the kink model's choice below),
//     where the viscous start, which has no static friction, is typically 4 steps away. Safe
//     whatever v_body holds: the certificate (step 4) is built from the final point alone, so a
//     start only costs iterations; it is taken only where Φ is no higher than at rest, D(0)
//     (a NaN or a runaway v_body compares false) and no foot is exactly at rest there (the fast
//     path needs r_k ≠ 0), and the fallback (step 3) always restarts from the viscous start.
//     The previous frame's static feet (the marks in frame.work_idx) are tried first: the
//     active-set polish (coulomb_path.cpp) with them static certifies a static pair at once
//     (two distinct points fix the velocity) and a single static foot in 1–3 steps; if it does
//     not certify, the solve goes on as if it had not been tried (one pass and a polish lost).
//  2. Fast path (kink_newton): Newton's method on the exact D, in which the foot nearest to rest
//     (slowest in slip speed ‖r_k‖/c_k) is modelled exactly, kink included, whenever the plain
//     Newton step would change its slip by more than its size: the step minimizes the quadratic
//     model of the others plus ‖r_s + B_s p‖ (kink_step), which makes the foot stick if its
//     force fits in its friction disk and slide past its kink otherwise. A frame with at most
//     one static foot — the generic case — thus converges quadratically, in 3–5 steps. The
//     dual of a point y with step p: the sliding feet's directions linearized at the Newton
//     point, λ_k = n_k + n_k⊥ (t_kᵀp)/‖r_k‖ (t_k = B_kᵀn_k⊥), which the Newton equation balances
//     exactly and whose norms exceed 1 by O(‖p‖²), and the kink foot's λ from its model. It is
//     tried once the predicted decrease is below 1e-3 tol D; the answer is then the Newton point
//     y + p (finish), exact to ~1e-13 whatever the tolerance. Two feet at rest at once (on a
//     turning walk the inner pair, in one frame in eight) defeat the one-foot model: the plain
//     steps oscillate across the second foot's kink. The fast path then tries the active-set
//     polish with both static, once when a step with a foot held is cut short (the held foot and
//     the foot the step crossed), and once after kPairAfter steps (the two slowest feet).
//  3. Fallback (coulomb_path.cpp), when the fast path stalls — several feet at rest at once, a
//     degenerate model: the smoothing path from the viscous start with an active-set polish at
//     the end of each stage, which also handles static feet at distinct points.
//  4. Certificate: the final pass (finish) builds the forces of the winning dual candidate, makes
//     them exactly balanced and scales them into the disks, so the reported gap is the true one of
//     the reported forces (up to rounding), whatever the quality of y. Converged ⇔ gap ≤ tol.
// Cost: see tests/bench/bench_friction.cpp for the time against the viscous-Coulomb solve.
//
// The load. An external planar wrench on the body (gravity along a slope, §5.2.1, eq. 5.1), in
// scaled coordinates f̃ = (F_x, F_y, M_z/L), adds its power to the balance: the velocity minimizes
//   Φ(y) = D(y) − f̃ᵀy,
// whose dual is the same with the balance Σ_k B_kᵀλ_k = f̃ (the forces F_k = −c_k W_k λ_k hold
// the load). Φ is bounded below iff the disks can hold f̃; otherwise a unit direction e with
// recession slope ρ(e) = Σ_k ‖B_k e‖ − f̃ᵀe < 0 proves that no quasi-static balance exists: the
// robot slides. Every pass subtracts f̃ᵀy and f̃ (assemble, value), which is all Newton's method,
// the kink model, the smoothing path and the polish need: their balance equations already read
// "Σ Bᵀλ = what the gradient says". Two things change. (1) Scaling a candidate λ into the disks
// no longer keeps it balanced (Σ Bᵀ(sλ) = s f̃); instead it is mixed with an anchor λ⁰ that
// balances f̃ strictly inside them (max ‖λ⁰_k‖ = ρ₀ < 1): θλ + (1 − θ)λ⁰ with
// θ = (1 − ρ₀)/(m − ρ₀) is balanced and feasible (m the candidate's largest norm), and its value
// is θ v + (1 − θ) v⁰. Unloaded, λ⁰ = 0 and this is the scaling by 1/m. The anchor is the
// c-weighted balance of the load, λ⁰_k = B_k μ/c_k with M₁μ = f̃ (each foot a share of the load in
// proportion to its friction limit; on a slope with the CoM centred, ‖λ⁰_k‖ ≈ tan σ/μ), and the
// smoothing path replaces it by its own corrected dual where that lies deeper inside (near a
// holding limit). (2) The relative gap is taken against max(D(y), D(0)), dissipations, as Φ may
// be negative. Sliding is detected before any iteration (all feet sliding together along the
// load: Σ_k ‖B_k e‖ < ‖f̃_xy‖; a load with a component no foot feels) and whenever an iterate runs
// away (‖y‖ > 10⁸ V), by the recession slope along it.
//
// Non-uniqueness. At an optimum with dual λ, a direction e keeps y optimal iff B_k e ∥ λ_k for
// sliding feet and for static feet on the disk's rim (with λ_kᵀ B_k e ≥ 0 there: the foot starts
// sliding along its force) and B_k e = 0 for static feet inside their disk. The first two are
// linear: e must lie in the null space of Q = Σ B_kᵀ P_k B_k (P_k the projector across λ_k, or I).
// A null vector of Q (eigenvalue ≤ 1e-10 trace) that passes the sign test means a flat
// direction of D at the optimum: a continuum of minimizers (the even-N 1-D example of §3.1.2).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "core/csv.hpp"
#include "core/sym3.hpp"
#include "friction/coulomb_solver.hpp"

namespace slipwalk::friction {

namespace coulomb {

namespace {
constexpr int kKinkSteps = 40;  // the fast path's steps before the smoothing path takes over
// The fast path's steps before its two slowest feet are tried as a static pair (kink_newton):
// a frame with at most one static foot certifies in 3–5 (the hexapod study's mean is 4.1).
constexpr int kPairAfter = 6;
// The shortest step the fast path's backtracking tries (halving from 1/2). Far from the optimum
// the Newton model of a sum of norms can promise more decrease than D itself (it has no
// curvature along a sliding foot's slip, so a foot whose slip the step reverses is modelled as
// losing dissipation it cannot lose): on the spring-supported hexapod frames of the ch3_legged
// study, 6 % of the first steps needed t ≈ 1/64 … 1/1000. Stopping at 1/16 sent those frames to
// the smoothing path (≈ 5 µs each, 15 % of the study's Coulomb time); a value pass per extra
// halving is far cheaper, and the next Newton step is full again.
constexpr double kMinStep = 1.0 / 4096.0;
// Such a cut (below 1/16) marks a frame whose Newton model is poorly conditioned near the answer
// (e.g. a mirror pair of feet slowing together). There the Newton point y + p is exact to ~1e-13
// only once the predicted decrease is below kCutPrecision tol D instead of 1e-3 tol D (a mirror-
// symmetric gait turned by ~3e-12 rad/s otherwise, tests/connection/test_trajectory.cpp): a
// stricter trigger, one more Newton step on those frames only.
constexpr double kDeepCut = 1.0 / 16.0;
constexpr double kCutPrecision = 1e-6;
// Balance of the reported forces, relative to their scale, that a certificate needs where the
// dual's correction cannot enforce it (finish()); rounding leaves ~1e-15 with 50 feet.
constexpr double kBalanced = 1e-12;
}  // namespace

/// Minimizes m(p) = gᵀp + ½ pᵀHp + ‖r + Bp‖ over p ∈ R³: the sliding feet by their quadratic
/// model (g, H) and one foot (r = r_s(y), B = B_s = [B_xy | b_ω]) exactly, kink included.
/// Coordinates: with s̃ = B_xy⁻¹ b_ω (the foot's lever), p = (z − s̃α, α) gives u = r + Bp =
/// r + B_xy z, and α (rotation about the foot) enters only the quadratic; eliminating it (H must
/// resist that rotation: h_αα > 0) leaves ½(u − r)ᵀK(u − r) + g̃ᵀ(u − r) + ‖u‖ over u ∈ R². Its
/// minimizer is u = 0 (stick) if the force λ₀ = K r − g̃ lies in the unit disk, else
/// (K + I/τ) u = λ₀ with ‖u‖ = τ, a secular equation in τ (as in trust-region methods), solved
/// by Newton's method. Returns false when the model is degenerate (h_αα ≈ 0, or K singular with
/// λ₀ outside the disk: m unbounded below).
bool kink_step(const Eigen::Vector3d& g, const Eigen::Matrix3d& H,
               const Eigen::Matrix<double, 2, 3>& B, const Eigen::Vector2d& r, double nr,
               KinkStep& out) {
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
  const double ihaa = 1.0 / haa;
  const Eigen::Matrix2d K = Bxy_inv.transpose() * (Hzz - (hza * ihaa) * hza.transpose()) * Bxy_inv;
  const Eigen::Vector2d gt = Bxy_inv.transpose() * (g.head<2>() - hza * (ga * ihaa));
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
  const double alpha = -(ga + hza.dot(z)) * ihaa;
  out.p << z - sl * alpha, alpha;
  // ‖u‖ = τ (0 when sticking), ‖r‖ = nr.
  out.decrease = -(g.dot(out.p) + 0.5 * out.p.dot(H * out.p) + (out.stick ? 0.0 : u.norm()) - nr);
  return out.p.allFinite() && out.decrease > 0.0;
}

/// Solves M x = b for a symmetric M through its adjugate: one division, where LDLᵀ chains three
/// (a 3 × 3 solve sits on the serial path of every Newton step). Returns false unless M is
/// positive definite with the pivots of its LDLᵀ above tol · trace — checked as ratios of
/// leading minors, without dividing.
bool solve_spd3(const Eigen::Matrix3d& M, const Eigen::Vector3d& b, double tol,
                Eigen::Vector3d& x) {
  // (The upper triangle: M may be symmetric only to rounding, H − t tᵀ/‖r‖ in kink_newton.)
  const core::Sym3Adjugate<double> a =
      core::sym3_adjugate(M(0, 0), M(0, 1), M(1, 1), M(0, 2), M(1, 2), M(2, 2));
  const double t = tol * (M(0, 0) + M(1, 1) + M(2, 2));
  if (!(M(0, 0) > t && a.c22 > t * M(0, 0) && a.det > t * a.c22)) {
    return false;
  }
  const double inv = 1.0 / a.det;
  x << (a.c00 * b(0) + a.c01 * b(1) + a.c02 * b(2)) * inv,
      (a.c01 * b(0) + a.c11 * b(1) + a.c12 * b(2)) * inv,
      (a.c02 * b(0) + a.c12 * b(1) + a.c22 * b(2)) * inv;
  return true;
}

template <bool kLoaded>
void Solver<kLoaded>::run() {
  auto& s = frame_.friction;
  s.iterations = 0;
  s.message.clear();
  s.route = contact::FrictionSummary::Route::kDirect;

  // ---- per-foot constants, Σ B_kᵀB_k (dual projection, degeneracy), the viscous start -----
  // A warm start also keeps the previous solve's static feet (setup() overwrites the marks).
  std::array<int, kHeldMax> held{};
  int n_held = 0;
  if (options_.warm_start) {
    n_held = held_static(held);
  }
  setup();
  dual_.factorize(M2_);
  Eigen::Vector3d y;
  if constexpr (kLoaded) {
    if (!setup_load()) {
      report_sliding();
      return;
    }
    // Near the holding limit the c-weighted anchor leaves the disks: the smoothing path's
    // minimizer at a fixed δ gives one (found from the viscous-Coulomb velocity under the load,
    // which that minimizer approaches for large δ), or proves sliding as it runs away. If
    // neither (a load at its limit to rounding), the fast path is skipped and the smoothing
    // path below tries again at every stage.
    const Eigen::Vector3d creep = viscous().solve(load_ - b1_);
    y = -viscous().solve(b1_);
    V_ = std::max({creep.norm(), y.norm(), D0_ / std::max(cs_.c_sum, kEps)});
    if (!(anchor_.rho < 1.0) && !find_anchor(creep) && sliding_ < 0.0) {
      report_sliding();
      return;
    }
    if (anchor_.rho < 1.0 && D0_ - anchor_.value <= options_.tol * D0_) {
      hold_at_rest();  // the feet do not move (q̇ = 0): the anchor holds the load, y = 0
      return;
    }
  }
  // The start: the viscous-Coulomb velocity, without the load. With it, the viscous ansatz (no
  // static friction) creeps along the load at ~tan σ/μ m/s on a slope, ten times the gait's
  // speed at 17°, while Coulomb friction mostly holds it with static feet: its answer lies near
  // the unloaded one (on BigANT's 17° frames 4.5 Newton steps from here, 7 from the creep).
  // Along a trajectory (options.warm_start) the previous frame's answer, where it is better;
  // its static feet are held first (the polish needs no pass at the start, nor the viscous
  // velocity: unloaded, M₁ is factorized only if they do not certify).
  const Eigen::Vector3d warm(frame_.v_body(0), frame_.v_body(1), frame_.v_body(2) * cs_.L);
  if (options_.warm_start && n_held > 0 && D0_ > 0.0 && hold_over(held, n_held, warm)) {
    return;
  }
  if constexpr (!kLoaded) {
    y = -viscous().solve(b1_);
  }
  const Eigen::Vector3d cold = y;
  Sums S;
  if (options_.warm_start) {
    y = warm_start(cold, warm, S);
  } else {
    assemble<true>(y, 0.0, S);  // Φ(y) and ‖r_k‖² (g, H are not finite if some r_k = 0)
  }

  // ---- trivial cases: no friction, nothing moves, or the start slips nowhere ---------------
  const int n = std::max(cs_.active, 1);
  const double D = dissipation(S.f, y);
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
  s.route = contact::FrictionSummary::Route::kPath;
  bool anchored = true;  // loaded: the fast path certifies only with an anchor inside the disks
  if constexpr (kLoaded) {
    anchored = anchor_.rho < 1.0;
  }
  if (options_.fast_path && anchored && S.r2_min > 1e-28 * D0_ * D0_) {
    Dual dual;
    s.route = contact::FrictionSummary::Route::kFastPath;
    if (kink_newton(y, S, Dref, dual)) {
      finish(y, dual);
      return;
    }
    if constexpr (kLoaded) {
      if (sliding_ < 0.0) {
        report_sliding();
        return;
      }
    }
    // Several feet near rest at once (e.g. a mirror-symmetric pair): the path takes over from
    // the viscous start (also after a warm start: the fallback is the same with or without),
    // every foot sliding.
    s.route = contact::FrictionSummary::Route::kFallback;
    y = cold;
    classify(0.0);
  }

  // ---- the fallback: the smoothing path (coulomb_path.cpp) -----------------------------------
  path(y, S, Dref);
}

template <bool kLoaded>
Eigen::Vector3d Solver<kLoaded>::warm_start(const Eigen::Vector3d& cold,
                                            const Eigen::Vector3d& warm, Sums& S) {
  // The start is taken where Φ is no higher than at rest, Φ(0) = D(0) (known from setup: no
  // pass; a NaN or a runaway start compares false), and no foot is exactly at rest (the answer
  // of this very frame, solved again: the fast path needs r_k ≠ 0 to start). A refused start
  // costs one assembly more.
  assemble<true>(warm, 0.0, S);
  if (S.f <= D0_ && S.r2_min > 1e-28 * D0_ * D0_) {
    return warm;
  }
  assemble<true>(cold, 0.0, S);
  return cold;
}

template <bool kLoaded>
int Solver<kLoaded>::held_static(std::array<int, kHeldMax>& held) const {
  const auto n = static_cast<std::size_t>(frame_.legs());
  int count = 0;
  for (std::size_t k = 0; k < frame_.work_idx.size() && k < n; ++k) {
    if (frame_.work_idx[k] == kStatic) {
      if (count == kHeldMax) {
        return 0;  // a rigid many-legged stance: the fast path and the fallback find it
      }
      held[static_cast<std::size_t>(count++)] = static_cast<int>(k);
    }
  }
  return count;
}

template <bool kLoaded>
bool Solver<kLoaded>::hold_over(const std::array<int, kHeldMax>& held, int n_held,
                                const Eigen::Vector3d& y) {
  // The active-set polish (coulomb_path.cpp) with those feet static: a static pair at distinct
  // points fixes y and is certified without a Newton step, one static foot in 1–3 steps. The
  // fast path alone needs its 40 steps and then the fallback for a pair (it models one foot
  // exactly), and on a walk a pair holds for many frames (the inner feet of a turn).
  int marked = 0;
  for (int i = 0; i < n_held; ++i) {
    const int k = held[static_cast<std::size_t>(i)];
    if (state(k) != kInactive) {  // still in contact, with friction
      set_state(k, kStatic);
      ++marked;
    }
  }
  if (marked > 0) {
    Eigen::Vector3d yp = y;
    Dual dual;
    frame_.friction.route = contact::FrictionSummary::Route::kFastPath;
    if (polish(yp, 0.0, dual)) {
      finish(yp, dual);
      return true;
    }
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) != kInactive) {
        set_state(k, kSlip);
      }
    }
  }
  return false;
}

template <bool kLoaded>
void Solver<kLoaded>::setup() {
  // Raw row pointers: Eigen's row and block expressions cost more than the arithmetic here.
  contact::CoulombScratch& R = frame_.coulomb;
  if (!R.fits(frame_.legs())) {  // a frame resized after construction
    R = contact::CoulombScratch(frame_.legs());
    frame_.work_idx.resize(static_cast<std::size_t>(frame_.legs()));
    frame_.work_2n.resize(Eigen::NoChange, frame_.legs());
  }
  double* const B[6] = {R.B.row(0).data(), R.B.row(1).data(), R.B.row(2).data(),
                        R.B.row(3).data(), R.B.row(4).data(), R.B.row(5).data()};
  double* const d[2] = {R.d.row(0).data(), R.d.row(1).data()};
  double* const active_row = R.active.data();
  double* const slide_row = R.sliding.data();
  double* const weight_row = R.weight.data();
  double* const inv_c2_row = R.inv_weight2.data();
  // Every row: the padding column and the column of a foot without friction are zero in all.
  double* const row[] = {B[0], B[1],       B[2],      B[3],        B[4],       B[5],      d[0],
                         d[1], active_row, slide_row, R.r2.data(), weight_row, inv_c2_row};
  const int n = frame_.legs();
  if (R.B.cols() > n) {  // the padding column of an odd count of feet: no foot, mask 0
    for (double* r : row) {
      r[n] = 0.0;
    }
  }
  double L2 = 0.0;
  // Upper triangles of M₁, M₂ (00 01 02 11 12 22) and b₁, b₂.
  double m1[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  double m2[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  double v1[3] = {0.0, 0.0, 0.0};
  double v2[3] = {0.0, 0.0, 0.0};
  // Local sums (members and the rows are both double: a store to a row could alias them).
  double scale = 0.0;
  double c_sum = 0.0;
  int active = 0;
  bool aniso = false;
  for (int k = 0; k < n; ++k) {
    const double c = detail::friction_weight(robot_, frame_, k);
    if (c == 0.0) {
      for (double* r : row) {
        r[k] = 0.0;
      }
      frame_.work_idx[static_cast<std::size_t>(k)] = kInactive;
      continue;
    }
    ++active;
    c_sum += c;
    const double qx = frame_.q(0, k);
    const double qy = frame_.q(1, k);
    L2 = std::max(L2, qx * qx + qy * qy);
    // cW (symmetric; c I when isotropic), cW S q and cW q̇.
    double w00 = c;
    double w01 = 0.0;
    double w11 = c;
    const double wx = robot_.w(0, k);
    const double wy = robot_.w(1, k);
    const double ww = wx * wx + wy * wy;
    double cw = c;  // c ‖W‖², the balance's force scale
    if (ww > 0.0) {
      aniso = true;
      const double root = std::sqrt(1.0 + ww);
      const double al = c / (1.0 + root);  // c α of W = I + α w wᵀ
      w00 += al * wx * wx;
      w01 = al * wx * wy;
      w11 += al * wy * wy;
      cw = c * root;
    }
    scale += cw;
    const double b4 = -w00 * qy + w01 * qx;
    const double b5 = -w01 * qy + w11 * qx;
    const double d0 = w00 * frame_.qdot(0, k) + w01 * frame_.qdot(1, k);
    const double d1 = w01 * frame_.qdot(0, k) + w11 * frame_.qdot(1, k);
    // Divisions and square roots share one slow unit: one per foot here, D(0)'s norms below
    // two feet at a time.
    const double ic = 1.0 / c;
    B[0][k] = w00;
    B[1][k] = w01;
    B[2][k] = w01;
    B[3][k] = w11;
    B[4][k] = b4;
    B[5][k] = b5;
    d[0][k] = d0;
    d[1][k] = d1;
    active_row[k] = 1.0;
    slide_row[k] = 1.0;
    weight_row[k] = c;
    inv_c2_row[k] = ic * ic;
    frame_.work_idx[static_cast<std::size_t>(k)] = kSlip;
    // BᵀB and Bᵀd for B = [cW | cW S q]; M₁ takes them over c.
    const double bb[6] = {w00 * w00 + w01 * w01, w00 * w01 + w01 * w11, w00 * b4 + w01 * b5,
                          w01 * w01 + w11 * w11, w01 * b4 + w11 * b5,   b4 * b4 + b5 * b5};
    const double bd[3] = {w00 * d0 + w01 * d1, w01 * d0 + w11 * d1, b4 * d0 + b5 * d1};
    for (int i = 0; i < 6; ++i) {
      m2[i] += bb[i];
      m1[i] += bb[i] * ic;
    }
    for (int i = 0; i < 3; ++i) {
      v2[i] += bd[i];
      v1[i] += bd[i] * ic;
    }
  }
  cs_ = detail::Contacts{};
  cs_.active = active;
  cs_.c_sum = c_sum;
  cs_.anisotropic = aniso;
  cs_.set_lever_scale(L2);
  // D(0) = Σ ‖d_k‖ two feet at a time, and the lever column over L: rows 4–5 of B, row and
  // column 2 of M (twice for the corner), b(2).
  const double il = cs_.inv_L;
  A2 D0 = A2::Zero();
  for (Eigen::Index j = 0; j < R.B.cols(); j += 2) {
    const A2 d0 = Eigen::Map<const A2>(d[0] + j);
    const A2 d1 = Eigen::Map<const A2>(d[1] + j);
    D0 += (d0 * d0 + d1 * d1).sqrt();
    Eigen::Map<A2>(B[4] + j) *= il;
    Eigen::Map<A2>(B[5] + j) *= il;
  }
  D0_ = D0.sum();
  scale_ = scale;
  auto fill = [il](const double* m, const double* v, Eigen::Matrix3d& M, Eigen::Vector3d& b) {
    M << m[0], m[1], m[2] * il, m[1], m[3], m[4] * il, m[2] * il, m[4] * il, m[5] * il * il;
    b << v[0], v[1], v[2] * il;
  };
  fill(m1, v1, M1_, b1_);
  fill(m2, v2, M2_, b2_);
  viscous_ready_ = false;  // factorized on first use (viscous())
}

// ---- the load ---------------------------------------------------------------------------------
template <bool kLoaded>
bool Solver<kLoaded>::setup_load() {
  load_ << load_raw_(0), load_raw_(1), load_raw_(2) * cs_.inv_L;
  const double f_norm = load_.norm();
  if (cs_.active == 0) {
    sliding_ = -f_norm;  // nothing holds it: every direction with f̃ᵀe > 0 is one of descent
    return false;
  }
  // The anchor: M₁ μ = f̃ (least norm); a load M₁ cannot reproduce has a part no foot feels.
  const Eigen::Vector3d mu = viscous().solve(load_);
  const Eigen::Vector3d miss = load_ - M1_ * mu;
  if (!(miss.norm() <= 1e-9 * f_norm)) {
    const double slope = recession(miss / miss.norm());  // ≈ −‖miss‖: no foot feels it
    if (slope < 0.0) {
      sliding_ = slope;
      return false;
    }
  }
  // One pass: ρ₀ = max_k ‖B_k μ‖/c_k, and Σ_k ‖B_k e‖ for the translation e along the load.
  const contact::CoulombScratch& R = frame_.coulomb;
  const double fxy = load_.head<2>().norm();
  const double ex = fxy > 0.0 ? load_(0) / fxy : 0.0;
  const double ey = fxy > 0.0 ? load_(1) / fxy : 0.0;
  double rho2 = 0.0;
  double along = 0.0;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (R.active(k) == 0.0) {
      continue;
    }
    const Mat23 Bk = B(k);
    rho2 = std::max(rho2, (Bk * mu).squaredNorm() * R.inv_weight2(k));
    along += (Bk.leftCols<2>() * Eigen::Vector2d(ex, ey)).norm();
  }
  if (along < fxy) {
    sliding_ = along - fxy;  // all feet sliding together along the load cannot hold it
    return false;
  }
  anchor_ = Interior{false, Eigen::Vector3d::Zero(), 1.0, mu, std::sqrt(rho2), mu.dot(b1_)};
  return true;
}

template <bool kLoaded>
double Solver<kLoaded>::recession(const Eigen::Vector3d& e) const {
  double r = -load_.dot(e);
  for (int k = 0; k < frame_.legs(); ++k) {
    if (frame_.coulomb.active(k) != 0.0) {
      r += (B(k) * e).norm();
    }
  }
  return r;
}

template <bool kLoaded>
bool Solver<kLoaded>::ran_away(const Eigen::Vector3d& y) {
  const double ny = y.norm();
  if (!(ny > 1e8 * V_) || !std::isfinite(ny)) {
    return false;
  }
  const double slope = recession(y / ny);
  sliding_ = slope < 0.0 ? slope : sliding_;
  return slope < 0.0;
}

template <bool kLoaded>
[[gnu::cold, gnu::noinline]] void Solver<kLoaded>::report_sliding() {
  frame_.v_body.setZero();
  frame_.Fxy.setZero();
  auto& s = frame_.friction;
  s.converged = false;
  s.residual = 0.0;
  const double scale = scale_ + load_.norm();
  s.certificate = scale > 0.0 ? sliding_ / scale : sliding_;
  s.unique = false;
  s.static_feet = 0;
  s.dissipation = 0.0;
  s.message =
      "sliding: the friction forces cannot hold the external load (no quasi-static balance)";
}

template <bool kLoaded>
void Solver<kLoaded>::hold_at_rest() {
  // Φ(0) = D(0) and the anchor's value v⁰ ≥ (1 − tol) D(0): y = 0 is certified by the anchor
  // itself (inside the disks, balanced). Every foot with friction is static.
  Dual dual;
  dual.h = -load_;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) == kInactive) {
      continue;
    }
    set_state(k, kStatic);
    const Eigen::Vector2d lam = interior(k);
    frame_.work_2n.col(k) = lam;
    dual.h += B(k).transpose() * lam;
  }
  finish(Eigen::Vector3d::Zero(), dual);
}

template <bool kLoaded>
Eigen::Vector2d Solver<kLoaded>::interior(int k) const {
  const Mat23 Bk = B(k);
  if (anchor_.path) {
    const Eigen::Vector2d r = residual(k, anchor_.y);
    return r / std::sqrt(r.squaredNorm() + anchor_.d2) - Bk * anchor_.mu;
  }
  return (Bk * anchor_.mu) / weight(k);
}

// ---- the fast path --------------------------------------------------------------------------
template <bool kLoaded>
bool Solver<kLoaded>::kink_newton(Eigen::Vector3d& y, Sums& S, double Dref, Dual& dual) {
  auto& s = frame_.friction;
  int held = -1;  // the foot held static: y lies on its line r_held(y) = 0
  double D = S.f;
  double precision = 1e-3;  // the certificate is tried below precision · tol · D (see kDeepCut)
  int forced = -1;          // a kink foot chosen after a failed line search (below)
  double lm = 0.0;          // curvature of M₂ added to the kink model after failed steps (below)
  bool retried = false;     // a plain step retried with the foot it crossed
  bool paired = false;      // the held foot and the foot a step crossed tried as a static pair
  bool slow_pair = false;   // the two slowest feet tried as a static pair (kPairAfter)
  for (int it = 0;; ++it) {
    if (it == kPairAfter && !slow_pair) {
      // Still uncertified: the two feet slowest in slip speed (the held one first) as a
      // static pair, e.g. a mirror pair the kink model alternates between.
      slow_pair = true;
      const auto [a, b] = slowest_two(y);
      const int first = held >= 0 ? held : a;
      const int second = held >= 0 ? a : b;
      if (second >= 0) {
        set_state(first, kStatic);
        if (hold_pair(first, second, y, dual)) {
          return true;
        }
        set_state(first, held >= 0 ? kStatic : kSlip);
        assemble<false>(y, 0.0, S);
      }
    }
    // The kink foot: the held one, or the sliding foot slowest in slip speed ‖r_k‖/c_k
    // (found without branches: which foot it is varies from frame to frame).
    int ks = held >= 0 ? held : forced;
    if (ks < 0) {
      const contact::CoulombScratch& R = frame_.coulomb;
      double best = kInf;
      for (int k = 0; k < frame_.legs(); ++k) {
        const double v = R.sliding(k) > 0.0 ? R.r2(k) * R.inv_weight2(k) : kInf;
        ks = v < best ? k : ks;
        best = std::min(v, best);
      }
      if (ks < 0) {
        return false;  // no foot slides at a finite slip speed (constants out of scale)
      }
    }
    const Mat23 Bk = B(ks);
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
    if (!newton_ok || forced >= 0 || lm > 0.0 || (Bk * st.p).squaredNorm() > nr * nr) {
      const KinkStep plain = st;
      if (held < 0) {  // take the kink foot's quadratic model out of the sums
        const double inr = 1.0 / nr;
        const Eigen::Vector2d n = r * inr;
        const Eigen::Vector3d t = Bk.transpose() * Eigen::Vector2d(-n(1), n(0));
        g -= Bk.transpose() * n;
        H -= (t * inr) * t.transpose();
      }
      if (lm > 0.0 || !kink_step(g, H, Bk, r, nr, st)) {
        // A degenerate model: the other sliding feet's quadratic models are flat along their
        // slip (e.g. only two of them), and with the kink foot sliding it is unbounded there —
        // or a model whose steps failed (lm > 0). The model with some curvature of M₂ added (a
        // damped step: the line search judges it, the certificate uses the true H), else the
        // plain step if there is one. (The plain step alone would cross this foot's kink again
        // and again at a crawl.)
        const double eps = std::max(lm, 1e-2) * H.trace() / M2_.trace();
        if (kink_step(g, Eigen::Matrix3d(H + eps * M2_), Bk, r, nr, st)) {
          kink = ks;
        } else if (newton_ok) {
          g = S.g;
          H = S.H;
          st = plain;
        } else {
          return false;
        }
      } else {
        kink = ks;
      }
    }
    // The dual at y: the sliding feet's λ linearized along p (polish_bound), the kink foot's λ.
    // Tried once the predicted decrease is below 1e-3 tol D, as the path's polish does: the
    // certificate would often pass earlier, but finish() reports y + p, and this makes that
    // Newton point exact to ~1e-13 (a continuous, mirror-symmetric answer for symmetric gaits).
    // (Or once the decrease is at the rounding of D itself, where no step can take it lower:
    // with a load, whose power enters D's rounding, a deep cut's trigger can lie below that.)
    if (st.decrease <=
        std::max(precision * options_.tol * Dref, 4.0 * kEps * rounding_scale(D, y))) {
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
      if (bound(kink >= 0 ? fo + nr : fo, value, lmax, h, y) <= options_.tol) {
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
    const double slack = 8.0 * kEps * rounding_scale(D, y);
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
      forced = -1;
      lm = lm > 1e-6 ? 0.1 * lm : 0.0;
      retried = false;
      if constexpr (kLoaded) {
        if (ran_away(y)) {
          return false;
        }
      }
      continue;
    }
    // Backtracking: off the full step a sticking foot slips again, unless it was held and
    // the step keeps it on its line.
    const bool keep = stick && held == ks;
    set_state(ks, keep ? kStatic : kSlip);
    bool accepted = false;
    const Eigen::Vector3d from = y;
    for (double t = 0.5; t >= kMinStep && !accepted; t *= 0.5) {
      const Eigen::Vector3d yt = y + t * st.p;
      const double Dv =
          keep ? value<false>(yt, 0.0) + residual(ks, yt).norm() : value<true>(yt, 0.0);
      if (Dv <= D - 1e-4 * t * st.decrease + slack) {
        y = yt;
        D = Dv;
        accepted = true;
        precision = t < kDeepCut ? kCutPrecision : precision;
      }
    }
    if (keep && !paired) {
      // A foot held static and a step D cuts short: it crossed the kink of a foot the model
      // (one foot exact) cannot see, typically a second foot at rest (on a turning walk the
      // inner feet, for many frames), about which the plain steps would oscillate until
      // kKinkSteps and the fallback. The active-set polish with both static certifies such a
      // pair without a Newton step (two distinct static points fix y); tried once per solve.
      paired = true;
      const int other = most_crossed(from, st.p);
      if (other >= 0 && hold_pair(ks, other, y, dual)) {
        return true;
      }
    }
    if (!accepted) {
      // The model promised a decrease D does not show. If it modelled a foot exactly, that
      // model again with more curvature added each time (Levenberg–Marquardt: its minimizer can
      // lie far out along a direction the other feet barely resist); if it took the plain step,
      // once per point, the step crossed the kink of a foot it did not model (another than the
      // slowest, or the slowest whose exact model was degenerate): the foot whose slip it
      // changes most relative to its size.
      if (kink >= 0) {
        lm = lm > 0.0 ? 10.0 * lm : 1e-2;
        if (lm > 1e4) {
          return false;
        }
        forced = held >= 0 ? -1 : ks;
      } else {
        const int cross = retried ? -1 : most_crossed(y, st.p);
        if (cross < 0) {
          return false;
        }
        retried = true;
        forced = cross;
      }
      set_state(ks, held == ks ? kStatic : kSlip);
      continue;
    }
    retried = false;
    lm = lm > 1e-6 ? 0.1 * lm : 0.0;
    forced = -1;
    assemble<false>(y, 0.0, S);
    if (!(S.r2_min > 1e-28 * D0_ * D0_)) {
      return false;
    }
    held = keep ? ks : -1;
  }
}

template <bool kLoaded>
std::pair<int, int> Solver<kLoaded>::slowest_two(const Eigen::Vector3d& y) const {
  int a = -1;
  int b = -1;
  double va = kInf;
  double vb = kInf;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) != kSlip) {
      continue;
    }
    const double v = residual(k, y).squaredNorm() * frame_.coulomb.inv_weight2(k);
    if (v < va) {
      b = a;
      vb = va;
      a = k;
      va = v;
    } else if (v < vb) {
      b = k;
      vb = v;
    }
  }
  return {a, b};
}

template <bool kLoaded>
bool Solver<kLoaded>::hold_pair(int held, int other, Eigen::Vector3d& y, Dual& dual) {
  set_state(other, kStatic);
  Eigen::Vector3d yp = y;
  if (polish(yp, 0.0, dual)) {
    y = yp;
    return true;
  }
  for (int k = 0; k < frame_.legs(); ++k) {  // the polish may have marked more feet static
    if (state(k) != kInactive && k != held) {
      set_state(k, kSlip);
    }
  }
  return false;
}

template <bool kLoaded>
[[gnu::cold, gnu::noinline]] int Solver<kLoaded>::most_crossed(const Eigen::Vector3d& y,
                                                               const Eigen::Vector3d& p) const {
  int best = -1;
  double ratio = 1.0;  // only a foot whose slip the step changes by more than its size
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) != kSlip) {
      continue;
    }
    const double r2 = residual(k, y).squaredNorm();
    const double q = (B(k) * p).squaredNorm();
    if (q > ratio * r2) {
      ratio = q / r2;
      best = k;
    }
  }
  return best;
}

// ---- certificates without a pass (see Dual in the header) ---------------------------------
template <bool kLoaded>
double Solver<kLoaded>::bound(double primal, double value, double lmax, const Eigen::Vector3d& h,
                              const Eigen::Vector3d& y) const {
  const Eigen::Vector3d mu = dual_.solve(h);
  const double m = lmax + std::sqrt(std::max(mu.dot(h), 0.0));
  double dual = value - mu.dot(b2_);
  if constexpr (kLoaded) {
    if (m > 1.0) {
      if (!(anchor_.rho < 1.0)) {
        return kInf;  // no anchor inside the disks yet: only a candidate inside them certifies
      }
      const double theta = (1.0 - anchor_.rho) / (m - anchor_.rho);
      dual = theta * dual + (1.0 - theta) * anchor_.value;
    }
  } else {
    dual *= 1.0 / std::max(1.0, m);
  }
  const double denom = std::max(dissipation(primal, y), D0_);
  return denom > 0.0 ? std::max(primal - dual, 0.0) / denom : 0.0;
}

template <bool kLoaded>
template <bool kPath>
FinishSums Solver<kLoaded>::finish_pass(const Eigen::Vector3d& y, const Dual& dual,
                                        const Eigen::Vector3d& mu) {
  const Rows R = rows(true);
  const double* slide = frame_.coulomb.sliding.data();
  const double* c = frame_.coulomb.weight.data();
  const double* ic2 = frame_.coulomb.inv_weight2.data();
  const Eigen::Index n = frame_.legs();
  double* const lam = frame_.work_2n.data();
  double* const force = frame_.Fxy.data();
  const double y0 = y(0), y1 = y(1), y2 = y(2);
  const double p0 = dual.p(0), p1 = dual.p(1), p2 = dual.p(2);
  const double mu0 = mu(0), mu1 = mu(1), mu2 = mu(2);
  A2 primal = A2::Zero(), stepped = A2::Zero(), value = A2::Zero(), lmax2 = A2::Zero();
  A2 fx = A2::Zero(), fy = A2::Zero(), mz = A2::Zero();
  A2 q00 = A2::Zero(), q01 = A2::Zero(), q02 = A2::Zero();
  A2 q11 = A2::Zero(), q12 = A2::Zero(), q22 = A2::Zero();
  for (Eigen::Index j = 0; j < R.cols; j += 2) {
    const Eigen::Index j1 = std::min(j + 1, n - 1);  // the padding column reads foot j again
    const A2 m = Eigen::Map<const A2>(R.mask + j);
    const A2 ms = Eigen::Map<const A2>(slide + j);
    const A2 b0 = R.at(0, j), b1 = R.at(1, j), b2 = R.at(2, j);
    const A2 b3 = R.at(3, j), b4 = R.at(4, j), b5 = R.at(5, j);
    const A2 d0 = R.at(6, j), d1 = R.at(7, j);
    const A2 r0 = b0 * y0 + b2 * y1 + b4 * y2 + d0;
    const A2 r1 = b1 * y0 + b3 * y1 + b5 * y2 + d1;
    const A2 rr = r0 * r0 + r1 * r1;
    const A2 nr = rr.sqrt();
    primal += m * nr;
    const A2 s0 = r0 + b0 * p0 + b2 * p1 + b4 * p2;
    const A2 s1 = r1 + b1 * p0 + b3 * p1 + b5 * p2;
    stepped += m * (s0 * s0 + s1 * s1).sqrt();
    // n = r/‖r‖ and t = Bᵀn⊥ of sliding feet (others get a finite stand-in, weight 0).
    const A2 inr = 1.0 / (nr + (1.0 - ms));
    const A2 n0 = r0 * inr;
    const A2 n1 = r1 * inr;
    const A2 t0 = b1 * n0 - b0 * n1;
    const A2 t1 = b3 * n0 - b2 * n1;
    const A2 t2 = b5 * n0 - b4 * n1;
    const A2 w = ms * Eigen::Map<const A2>(c + j) * Eigen::Map<const A2>(ic2 + j);  // 1/c_k
    const A2 wt0 = w * t0;
    const A2 wt1 = w * t1;
    q00 += wt0 * t0;
    q01 += wt0 * t1;
    q02 += wt0 * t2;
    q11 += wt1 * t1;
    q12 += wt1 * t2;
    q22 += w * t2 * t2;
    // The lanes whose candidate this loop builds (weight 1; 0 for no foot, and for the feet
    // whose λ is given in work_2n: static ones and the kink foot, added after the loop from
    // there, so that a stale λ of a sliding foot is never read).
    A2 use = m;
    A2 l0;
    A2 l1;
    if constexpr (kPath) {
      const A2 ir = 1.0 / (rr + dual.d2 + (1.0 - m)).sqrt();
      l0 = r0 * ir;
      l1 = r1 * ir;
    } else {
      const A2 lane(static_cast<double>(j - dual.kink), static_cast<double>(j + 1 - dual.kink));
      use = ms * lane.abs().min(1.0);
      const A2 tp = (t0 * p0 + t1 * p1 + t2 * p2) * inr;
      l0 = n0 - n1 * tp;
      l1 = n1 + n0 * tp;
    }
    // A select, not use · (…): the kink foot may sit exactly at r = 0, where n = r/‖r‖ is NaN.
    const A2 c0 = where_positive(use, l0 - (b0 * mu0 + b2 * mu1 + b4 * mu2));
    const A2 c1 = where_positive(use, l1 - (b1 * mu0 + b3 * mu1 + b5 * mu2));
    lmax2 = lmax2.max(c0 * c0 + c1 * c1);
    value += c0 * d0 + c1 * d1;
    const A2 F0 = -(b0 * c0 + b2 * c1);
    const A2 F1 = -(b1 * c0 + b3 * c1);
    fx += F0;
    fy += F1;
    const A2 qx(frame_.q(0, j), frame_.q(0, j1));
    const A2 qy(frame_.q(1, j), frame_.q(1, j1));
    mz += qx * F1 - qy * F0;
    for (Eigen::Index i = 0; i < 2 && j + i < n; ++i) {
      if (use(i) == 0.0 && m(i) != 0.0) {
        continue;  // a given λ, written after the loop
      }
      lam[2 * (j + i)] = c0(i);
      lam[2 * (j + i) + 1] = c1(i);
      force[2 * (j + i)] = F0(i);
      force[2 * (j + i) + 1] = F1(i);
    }
  }
  FinishSums out;
  if constexpr (!kPath) {
    // The given λ_k (static feet, the kink foot), balanced like the others.
    double lm2 = 0.0;
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) != kStatic && k != dual.kink) {
        continue;
      }
      const Mat23 Bk = B(k);
      const Eigen::Vector2d l = Eigen::Vector2d(frame_.work_2n.col(k)) - Bk * mu;
      const Eigen::Vector2d F = -(Bk.leftCols<2>() * l);
      lm2 = std::max(lm2, l.squaredNorm());
      out.value += l.dot(d(k));
      out.force += F;
      out.moment += frame_.q(0, k) * F(1) - frame_.q(1, k) * F(0);
      frame_.work_2n.col(k) = l;
      frame_.Fxy.col(k) = F;
    }
    out.lmax2 = lm2;
  }
  out.primal = primal.sum();
  out.stepped = stepped.sum();
  out.value += value.sum();
  out.lmax2 = std::max(out.lmax2, lmax2.maxCoeff());
  out.force += Eigen::Vector2d(fx.sum(), fy.sum());
  out.moment += mz.sum();
  const double qs[6] = {q00.sum(), q01.sum(), q02.sum(), q11.sum(), q12.sum(), q22.sum()};
  std::copy(qs, qs + 6, out.q);
  return out;
}

template <bool kLoaded>
void Solver<kLoaded>::finish(Eigen::Vector3d y, const Dual& dual) {
  auto& s = frame_.friction;
  const Eigen::Vector3d mu = dual_.solve(dual.h);
  const FinishSums fs =
      dual.path ? finish_pass<true>(y, dual, mu) : finish_pass<false>(y, dual, mu);
  detail::BalanceSum sum;
  sum.force = fs.force;
  sum.moment = fs.moment;
  double primal = fs.primal;
  const double stepped = fs.stepped;
  double value = fs.value;
  const double lmax2 = fs.lmax2;
  Eigen::Matrix3d Q;
  Q << fs.q[0], fs.q[1], fs.q[2], fs.q[1], fs.q[3], fs.q[4], fs.q[2], fs.q[4], fs.q[5];
  int n_static = 0;
  bool distinct = false;
  int first = -1;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) == kStatic) {
      ++n_static;
      if (first < 0) {
        first = k;
      } else if ((frame_.q.col(k).head<2>() - frame_.q.col(first).head<2>()).squaredNorm() >
                 1e-12 * cs_.L * cs_.L) {
        distinct = true;
      }
    }
  }
  bool feasible = !(lmax2 > 1.0) || into_disks(std::sqrt(lmax2), sum, value);
  // Φ at y and at the Newton point (D itself when unloaded).
  double phi = primal;
  double phi_stepped = stepped;
  if constexpr (kLoaded) {
    phi -= load_.dot(y);
    phi_stepped -= load_.dot(y + dual.p);
  }
  if (phi_stepped <= phi + 8.0 * kEps * rounding_scale(phi, y)) {
    // The Newton point: D agrees to rounding near the optimum, but the step zeroes the
    // gradient, which places y far more precisely than a comparison of values can.
    y += dual.p;
    primal = stepped;
    phi = phi_stepped;
  }
  // M₂ weighs the feet by c_k², so it is rank-deficient to rounding not only when the contacts
  // are at one point but also when the weights span more than ~6 decades and only the lightest
  // feet feel a direction. Those feet do feel it: y must not be projected along it (D would
  // change after the certificate), and the dual's correction does not balance along it; the
  // forces are then balanced again in the viscous metric M₁ (∝ c_k, rebalance()), and the
  // certificate holds only if they balance (checked on the forces themselves).
  double force_scale = scale_;
  if constexpr (kLoaded) {  // the forces balance the load: Σ F_k + f = 0, Σ M_k + M_z = 0
    sum.force += load_raw_.head<2>();
    sum.moment += load_raw_(2);
    force_scale += load_.norm();
  }
  const bool light = dual_.rank() < 3 && !one_point();
  if (light && !(sum.residual(force_scale, cs_.L) <= kBalanced)) {
    value = rebalance(sum);
    feasible = std::isfinite(value);
  }
  s.residual = sum.residual(force_scale, cs_.L);
  const double denom = std::max(primal, D0_);
  // Without forces inside the disks nothing is proven: a relative gap of 1 says so.
  const double cert = !feasible ? 1.0 : (denom > 0.0 ? std::max(phi - value, 0.0) / denom : 0.0);
  const bool unbalanced = light && !(s.residual <= kBalanced);
  s.certificate = cert;
  s.converged = cert <= options_.tol && !unbalanced;
  s.static_feet = n_static;
  s.unique = cs_.active > 0 && (dual_.rank() == 3 || light) && !flat_direction(Q, n_static);
  // Least norm along directions no foot feels (contacts at one point), then the body velocity.
  if (!light) {
    y = dual_.project_to_range(y);
  }
  detail::set_velocity(frame_, y, cs_.L);
  s.dissipation = primal;
  if (cs_.active == 0) {
    s.message = "no foot with friction in contact: body velocity undetermined, set to 0";
  } else if (unbalanced) {
    s.message =
        "friction weights mu_k F_z,k spread over too many decades: the certifying forces "
        "do not balance along a direction only the lightest feet feel (residual " +
        core::format_double(s.residual) + ")";
  } else if (!feasible) {
    s.message =
        "no balanced forces inside the friction disks found near the holding limit: not "
        "certified (certificate 1: nothing proven)";
  } else if (!s.converged) {
    s.message = "iteration limit: relative duality gap " + core::format_double(cert) +
                " above the tolerance " + core::format_double(options_.tol);
  } else if (light) {
    if (!s.unique) {
      s.message = "flat minimum of the dissipation: a continuum of body velocities balance";
    }
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

template <bool kLoaded>
[[gnu::cold, gnu::noinline]] double Solver<kLoaded>::rebalance(detail::BalanceSum& sum) {
  // λ_k −= B_k μ / c_k with M₁ μ = h = Σ B_kᵀλ_k: the correction of each foot is in units of its
  // own disk, so a light foot takes its share of the direction only it feels.
  Eigen::Vector3d h = Eigen::Vector3d::Zero();
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) != kInactive) {
      h += B(k).transpose() * Eigen::Vector2d(frame_.work_2n.col(k));
    }
  }
  if constexpr (kLoaded) {
    h -= load_;
  }
  const Eigen::Vector3d mu = viscous().solve(h);
  double lmax2 = 0.0;
  double value = 0.0;
  sum = detail::BalanceSum{};
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) == kInactive) {
      continue;
    }
    const Mat23 Bk = B(k);
    const Eigen::Vector2d lam = frame_.work_2n.col(k) - Bk * mu / weight(k);
    lmax2 = std::max(lmax2, lam.squaredNorm());
    value += lam.dot(d(k));
    frame_.work_2n.col(k) = lam;
    frame_.Fxy.col(k) = -(Bk.leftCols<2>() * lam);  // F_k = −c_k W_k λ_k
    sum.add(frame_, k, frame_.Fxy.col(k));
  }
  if (lmax2 > 1.0 && !into_disks(std::sqrt(lmax2), sum, value)) {
    return -kInf;
  }
  if constexpr (kLoaded) {
    sum.force += load_raw_.head<2>();
    sum.moment += load_raw_(2);
  }
  return value;
}

template <bool kLoaded>
bool Solver<kLoaded>::into_disks(double m, detail::BalanceSum& sum, double& value) {
  if constexpr (!kLoaded) {  // a common scale keeps the balance
    const double shrink = 1.0 / m;
    frame_.Fxy *= shrink;
    frame_.work_2n *= shrink;
    sum.force *= shrink;
    sum.moment *= shrink;
    value *= shrink;
    return true;
  }
  // Loaded: mixed with the anchor, which keeps the load's balance.
  if (!(anchor_.rho < 1.0)) {
    return false;
  }
  const double theta = (1.0 - anchor_.rho) / (m - anchor_.rho);
  sum = detail::BalanceSum{};
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) == kInactive) {
      continue;
    }
    const Eigen::Vector2d lam =
        theta * Eigen::Vector2d(frame_.work_2n.col(k)) + (1.0 - theta) * interior(k);
    frame_.work_2n.col(k) = lam;
    frame_.Fxy.col(k) = -(B(k).template leftCols<2>() * lam);  // F_k = −c_k W_k λ_k
    sum.add(frame_, k, frame_.Fxy.col(k));
  }
  value = theta * value + (1.0 - theta) * anchor_.value;
  return true;
}

template <bool kLoaded>
[[gnu::cold, gnu::noinline]] bool Solver<kLoaded>::one_point() const {
  int first = -1;
  for (int k = 0; k < frame_.legs(); ++k) {
    if (state(k) == kInactive) {
      continue;
    }
    if (first < 0) {
      first = k;
    } else if ((frame_.q.col(k).head<2>() - frame_.q.col(first).head<2>()).norm() > 1e-6 * cs_.L) {
      return false;
    }
  }
  return true;
}

template <bool kLoaded>
bool Solver<kLoaded>::flat_direction(Eigen::Matrix3d Q, int n_static) const {
  if (n_static > 0) {
    // Scalar sums read off the rows (small Eigen sums stall on store forwarding): t tᵀ/c_k with
    // t = B_kᵀ n⊥ (n = λ_k/‖λ_k‖) on the rim, B_kᵀB_k/c_k inside.
    const contact::CoulombScratch& R = frame_.coulomb;
    double q[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (int k = 0; k < frame_.legs(); ++k) {
      if (state(k) != kStatic) {
        continue;
      }
      const double l0 = frame_.work_2n(0, k);
      const double l1 = frame_.work_2n(1, k);
      const double nl = std::sqrt(l0 * l0 + l1 * l1);
      const double b0 = R.B(0, k), b1 = R.B(1, k), b2 = R.B(2, k);
      const double b3 = R.B(3, k), b4 = R.B(4, k), b5 = R.B(5, k);
      const double ic = 1.0 / weight(k);
      if (nl >= 1.0 - 1e-9) {
        const double a = ic / (nl * nl);  // t = B_kᵀ(−λ₁, λ₀)/‖λ‖
        const double t0 = b1 * l0 - b0 * l1;
        const double t1 = b3 * l0 - b2 * l1;
        const double t2 = b5 * l0 - b4 * l1;
        q[0] += a * t0 * t0;
        q[1] += a * t0 * t1;
        q[2] += a * t0 * t2;
        q[3] += a * t1 * t1;
        q[4] += a * t1 * t2;
        q[5] += a * t2 * t2;
      } else {
        q[0] += ic * (b0 * b0 + b1 * b1);
        q[1] += ic * (b0 * b2 + b1 * b3);
        q[2] += ic * (b0 * b4 + b1 * b5);
        q[3] += ic * (b2 * b2 + b3 * b3);
        q[4] += ic * (b2 * b4 + b3 * b5);
        q[5] += ic * (b4 * b4 + b5 * b5);
      }
    }
    Q(0, 0) += q[0];
    Q(0, 1) += q[1];
    Q(0, 2) += q[2];
    Q(1, 1) += q[3];
    Q(1, 2) += q[4];
    Q(2, 2) += q[5];
    Q(1, 0) = Q(0, 1);
    Q(2, 0) = Q(0, 2);
    Q(2, 1) = Q(1, 2);
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

template class Solver<false>;
template class Solver<true>;

}  // namespace coulomb

void solve_coulomb(const contact::Robot& robot, contact::Frame& frame,
                   const CoulombOptions& options) {
  coulomb::Solver<false>(robot, frame, options).run();
  detail::flag_non_finite(frame, frame.Fxy.sum());
}

void solve_coulomb_loaded(const contact::Robot& robot, contact::Frame& frame,
                          const Eigen::Vector3d& load, const CoulombOptions& options) {
  if (load(0) == 0.0 && load(1) == 0.0 && load(2) == 0.0) {
    // No load is the flat problem (a slope of angle 0 is flat bit for bit).
    solve_coulomb(robot, frame, options);
    return;
  }
  coulomb::Solver<true>(robot, frame, options, load).run();
  detail::flag_non_finite(frame, frame.Fxy.sum());
}

}  // namespace slipwalk::friction
