#pragma once
// Internal to friction/: the Coulomb solver (friction::solve_coulomb, solve_coulomb_loaded). The
// algorithm, the dual and the certificate are described in coulomb.cpp (the fast path, the
// answer, the load) and coulomb_path.cpp (the smoothing path and its active-set polish, the
// fallback); this header holds what both share: the per-foot rows, the passes over the feet and
// the solver's state. A planar load on the body (kLoaded) adds the linear term −f̃ᵀy to every pass
// and anchors the certificate at a balanced dual point inside the disks (Interior); without it
// none of that code exists (if constexpr), so the flat solve is unchanged.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "core/lanes.hpp"
#include "friction/balance.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::friction::coulomb {

inline constexpr double kEps = std::numeric_limits<double>::epsilon();
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kBig = 1e300;  // ‖r‖² of a foot a pass does not visit, for the minimum
inline constexpr int kSlip = 0;
inline constexpr int kStatic = 1;
inline constexpr int kInactive = -1;
inline constexpr int kHeldMax = 8;  // static feet a warm start holds over (Solver::hold_over)
using Mat23 = Eigen::Matrix<double, 2, 3>;

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
/// every foot, or the linearized λ_k = n_k + n_k⊥ (t_kᵀp)/‖r_k‖ for sliding feet and work_2n for
/// static ones and the kink foot; h = Σ B_kᵀλ_k, its imbalance, known from the pass that
/// assembled it.
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

/// What the static feet of a polish contribute to its dual (static_duals()).
struct StaticDual {
  double lmax = 0.0;                                ///< max ‖λ_s‖
  double value = 0.0;                               ///< Σ λ_sᵀ d_s
  double primal = 0.0;                              ///< Σ ‖r_s(y)‖ (0 up to rounding)
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< Σ B_sᵀ λ_s
};

/// A dual point that balances the load strictly inside the disks (loaded solves only): certificates
/// whose candidate leaves its disks are mixed with it instead of scaled toward 0 (which would no
/// longer balance the load; coulomb.cpp, "The load"). Either the c-weighted balance of the load,
/// λ⁰_k = B_k μ/c_k with M₁ μ = f̃, or the smoothing path's corrected dual at (y, δ²),
/// λ⁰_k = r_k(y)/√(‖r_k(y)‖² + δ²) − B_k μ.
struct Interior {
  bool path = false;
  Eigen::Vector3d y = Eigen::Vector3d::Zero();
  double d2 = 1.0;
  Eigen::Vector3d mu = Eigen::Vector3d::Zero();
  double rho = 0.0;    ///< max_k ‖λ⁰_k‖ (< 1 for a usable anchor)
  double value = 0.0;  ///< Σ λ⁰_kᵀ d_k
};

/// What finish_pass() sums.
struct FinishSums {
  double primal = 0.0;                              ///< D(y)
  double stepped = 0.0;                             ///< D(y + p): the answer unless higher
  double value = 0.0;                               ///< Σ λ_kᵀd_k of the balanced candidate
  double lmax2 = 0.0;                               ///< max ‖λ_k‖² of the balanced candidate
  Eigen::Vector2d force = Eigen::Vector2d::Zero();  ///< Σ F_k
  double moment = 0.0;                              ///< Σ (q_k × F_k)_z
  double q[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};     ///< upper part of Q = Σ t tᵀ/c_k, sliding
};

/// Minimizes gᵀp + ½ pᵀHp + ‖r + Bp‖ (the kink model of kink_newton; coulomb.cpp).
bool kink_step(const Eigen::Vector3d& g, const Eigen::Matrix3d& H,
               const Eigen::Matrix<double, 2, 3>& B, const Eigen::Vector2d& r, double nr,
               KinkStep& out);

/// Solves M x = b for a symmetric positive definite M (false unless it is; coulomb.cpp).
bool solve_spd3(const Eigen::Matrix3d& M, const Eigen::Vector3d& b, double tol, Eigen::Vector3d& x);

/// One solve: solve_coulomb() constructs it on the stack and calls run(); solve_coulomb_loaded()
/// constructs Solver<true> with the load (F_x, F_y, M_z), body frame.
template <bool kLoaded>
class Solver {
 public:
  Solver(const contact::Robot& robot, contact::Frame& frame, const CoulombOptions& options,
         const Eigen::Vector3d& load = Eigen::Vector3d::Zero())
      : robot_(robot), frame_(frame), options_(options), load_raw_(load) {}

  /// Writes frame.v_body, frame.Fxy and frame.friction (coulomb.cpp).
  void run();

 private:
  // ---- per-foot constants (frame.coulomb, contact/robot.hpp: one column per foot) ---------
  [[nodiscard]] double weight(int k) const { return frame_.coulomb.weight(k); }
  [[nodiscard]] double slip2(int k) const { return frame_.coulomb.r2(k); }  ///< ‖r_k‖²
  [[nodiscard]] int state(int k) const { return frame_.work_idx[static_cast<std::size_t>(k)]; }
  void set_state(int k, int st) {
    frame_.work_idx[static_cast<std::size_t>(k)] = st;
    frame_.coulomb.sliding(k) = st == kSlip ? 1.0 : 0.0;
  }
  [[nodiscard]] Eigen::Matrix<double, 2, 3> B(int k) const {
    const auto& b = frame_.coulomb.B;
    Eigen::Matrix<double, 2, 3> Bk;
    Bk << b(0, k), b(2, k), b(4, k), b(1, k), b(3, k), b(5, k);
    return Bk;
  }
  [[nodiscard]] Eigen::Vector2d d(int k) const {
    return {frame_.coulomb.d(0, k), frame_.coulomb.d(1, k)};
  }
  [[nodiscard]] Eigen::Vector2d residual(int k, const Eigen::Vector3d& y) const {
    return B(k) * y + d(k);
  }

  /// One pass: B_k = c W J̃_k, d_k = c W q̇_k, the states, the contact summary (balance.hpp's
  /// prepare(), merged in) and the 3 × 3 constants: the viscous system M₁ = Σ B_kᵀB_k/c_k
  /// (= Σ c J̃ᵀGJ̃ of balance.hpp), b₁ = Σ B_kᵀd_k/c_k, the dual metric M₂ = Σ B_kᵀB_k,
  /// b₂ = Σ B_kᵀd_k and D(0) = Σ ‖d_k‖. The lever scale L is known only at the end, so the
  /// lever column is built from S q (unscaled) and scaled afterwards, rows and sums alike.
  void setup();
  /// M₁ factorized, on first use: a warm start whose static feet certify never needs it.
  const detail::Psd3& viscous() {
    if (!viscous_ready_) {
      viscous_.factorize(M1_);
      viscous_ready_ = true;
    }
    return viscous_;
  }
  /// options.warm_start: `warm` (frame.v_body, the previous frame's answer, in scaled
  /// coordinates) as the start if Φ is no higher there than at rest (D(0)) and no foot is
  /// exactly at rest, else `cold`; S assembled at the start returned (coulomb.cpp, step 1).
  Eigen::Vector3d warm_start(const Eigen::Vector3d& cold, const Eigen::Vector3d& warm, Sums& S);
  /// options.warm_start: the feet marked static by the previous solve of this frame (work_idx,
  /// before setup() clears it), at most kHeldMax of them (none if more); how many.
  int held_static(std::array<int, kHeldMax>& held) const;
  /// options.warm_start: the active-set polish with the previous static feet (those still with
  /// friction) static, from y (any point, NaN included: the polish then fails); true when it
  /// certified and finished the solve, else the states are all sliding again and the row r2 is
  /// stale.
  bool hold_over(const std::array<int, kHeldMax>& held, int n_held, const Eigen::Vector3d& y);

  // ---- passes over the feet: two feet per step, Eigen::Array2d being one SSE2 register -----
  // The long passes are [[gnu::flatten]]: GCC's inlining budget otherwise leaves some of their
  // two-lane Eigen expressions as out-of-line calls, whose spills cost a third of the pass.
  // A foot a pass does not visit (mask 0) gets ρ ≥ 1 (finite) and the weight 0 in every sum.
  // The row pointers are read once: the stores to the row r2 would otherwise make the compiler
  // reload them for every pair of feet.
  using A2 = Eigen::Array2d;
  /// x where w > 0, else +0 (a NaN in x included), lane by lane and without a branch. Eigen 3.4
  /// evaluates select() a coefficient at a time, with a branch and a store each, which the next
  /// load of the pair then waits on (the store cannot be forwarded to the wider load).
  static A2 where_positive(const A2& w, const A2& x) {
    using L = core::Lanes<2>;
    A2 out;
    L::store(out.data(), L::select(L::load(w.data()) > 0.0, L::load(x.data())));
    return out;
  }
  struct Rows {
    const double* b[8];  ///< B_k (6 rows) and d_k (2 rows)
    const double* mask;
    double* r2;
    Eigen::Index cols;
    [[nodiscard]] A2 at(int i, Eigen::Index j) const { return Eigen::Map<const A2>(b[i] + j); }
  };
  /// The rows of a pass over every foot with friction (all) or over the sliding ones.
  [[nodiscard]] Rows rows(bool all) {
    contact::CoulombScratch& R = frame_.coulomb;
    Rows out{};
    for (int i = 0; i < 6; ++i) {
      out.b[i] = R.B.row(i).data();
    }
    out.b[6] = R.d.row(0).data();
    out.b[7] = R.d.row(1).data();
    out.mask = all ? R.active.data() : R.sliding.data();
    out.r2 = R.r2.data();
    out.cols = R.B.cols();
    return out;
  }

  /// Σ √(‖r_k(y)‖² + δ²) over the visited feet (kAll: all with friction, else the sliding ones),
  /// minus the load's power f̃ᵀy when loaded: the objective Φ_δ.
  template <bool kAll>
  double value(const Eigen::Vector3d& y, double d2) {
    const Rows R = rows(kAll);
    const double y0 = y(0), y1 = y(1), y2 = y(2);
    A2 f = A2::Zero();
    for (Eigen::Index j = 0; j < R.cols; j += 2) {
      const A2 m = Eigen::Map<const A2>(R.mask + j);
      const A2 r0 = R.at(0, j) * y0 + R.at(2, j) * y1 + R.at(4, j) * y2 + R.at(6, j);
      const A2 r1 = R.at(1, j) * y0 + R.at(3, j) * y1 + R.at(5, j) * y2 + R.at(7, j);
      f += m * (r0 * r0 + r1 * r1 + d2).sqrt();
    }
    if constexpr (kLoaded) {
      return f.sum() - load_.dot(y);
    } else {
      return f.sum();
    }
  }

  /// The Sums of D_δ over the visited feet at y (one pass, the solver's cost; loaded: of
  /// Φ_δ = D_δ − f̃ᵀy, so f and g carry the load's power and −f̃); leaves ‖r_k‖² of
  /// every foot in the row r2. With δ = 0 the Hessian term is t_k t_kᵀ/‖r_k‖
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
  [[gnu::flatten]] void assemble(const Eigen::Vector3d& y, double d2, Sums& S) {
    const Rows R = rows(kAll);
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
    if constexpr (kLoaded) {
      S.f -= load_.dot(y);
      S.g -= load_;
    }
    const double H00 = h00.sum(), H01 = h01.sum(), H02 = h02.sum();
    const double H11 = h11.sum(), H12 = h12.sum(), H22 = h22.sum();
    S.H << H00, H01, H02, H01, H11, H12, H02, H12, H22;
  }

  // ---- the load (coulomb.cpp) ---------------------------------------------------------------
  /// The dissipation D(y) from the objective's value Φ(y) at y (Φ itself when unloaded).
  [[nodiscard]] double dissipation(double phi, const Eigen::Vector3d& y) const {
    if constexpr (kLoaded) {
      return phi + load_.dot(y);
    } else {
      (void)y;
      return phi;
    }
  }
  /// The size of the terms that make up Φ(y) = D(y) − f̃ᵀy, D(y) + |f̃ᵀy| (Φ = D unloaded): its
  /// rounding is ε times this, whatever the sign of Φ.
  [[nodiscard]] double rounding_scale(double phi, const Eigen::Vector3d& y) const {
    if constexpr (kLoaded) {
      const double power = load_.dot(y);
      return phi + power + std::abs(power);
    } else {
      (void)y;
      return phi;
    }
  }
  /// The scaled load f̃ and the anchor λ⁰ = c-weighted balance of it (one pass); false when the
  /// load cannot be held, with the recession slope in sliding_ (a translation along the load
  /// that all feet together cannot resist, or a load no contact feels).
  bool setup_load();
  /// The recession slope ρ(e) = Σ_k ‖B_k e‖ − f̃ᵀe of Φ along a unit direction e (one pass).
  [[nodiscard]] double recession(const Eigen::Vector3d& e) const;
  /// Loaded: whether y has run away (‖y‖ > 10⁸ V) along a direction of unbounded descent; the
  /// slope goes to sliding_.
  bool ran_away(const Eigen::Vector3d& y);
  /// No quasi-static balance: v_body = 0, no forces, the recession slope as the certificate.
  void report_sliding();
  /// Brings the balanced candidate in work_2n (largest norm m > 1) into the disks: scaled by 1/m
  /// (unloaded), or mixed with the anchor (loaded, which scaling would unbalance); rewrites
  /// work_2n, Fxy, `sum` (without the load) and `value`. False when loaded and there is no
  /// anchor inside the disks.
  bool into_disks(double m, detail::BalanceSum& sum, double& value);
  /// Loaded, the c-weighted anchor not inside the disks (near the holding limit): Newton's method
  /// on the smoothing Φ_δ at a fixed δ (D(start)/N, the start's mean slip) to its minimizer, whose
  /// corrected dual r_k/ρ_k is strictly inside the disks and becomes the anchor (coulomb_path.cpp).
  /// False when Φ_δ runs away along a direction of unbounded descent (sliding_ set), or no anchor
  /// was found (sliding_ stays 0: the load is at its holding limit to rounding).
  bool find_anchor(Eigen::Vector3d y);
  /// Loaded: the recession slopes along to − from and along to, the lower into sliding_ if
  /// negative (a proof of sliding from the way an iteration went).
  void moved_downhill(const Eigen::Vector3d& from, const Eigen::Vector3d& to);
  /// Loaded, the feet at rest: y = 0 with the anchor's forces (finish()).
  void hold_at_rest();
  /// The anchor's λ⁰_k.
  [[nodiscard]] Eigen::Vector2d interior(int k) const;
  /// Loaded: the smoothing path's corrected dual at (y, δ) as the anchor if it lies deeper inside
  /// the disks than the current one (one pass).
  void adopt_interior(const Eigen::Vector3d& y, const Sums& S, double delta);

  // ---- the fast path and the answer (coulomb.cpp) ----------------------------------------------
  /// Newton's method on the exact D from y (S: its sums over every foot, all sliding), with the
  /// foot nearest to rest — the one whose kink a quadratic model would step across — modelled
  /// exactly (kink_step): the step makes it stick when its force fits in its disk, and slide
  /// past its kink otherwise. Where the plain Newton step moves that foot's slip by less than
  /// its size (it cannot reach the kink), its quadratic model serves and the plain step is taken.
  /// At the optimum the model is exact for that foot and Newton's quadratic convergence holds for
  /// the others (they slide), so a frame with at most one static foot (the generic case) certifies
  /// in a few steps. Points are certified with the model's dual (polish_bound's, plus the kink
  /// foot's λ) once the predicted decrease is below 1e-3 tol D (coulomb.cpp, step 2). Returns
  /// false (y moved downhill, states arbitrary) when the model degenerates or stops converging: the
  /// smoothing path takes over.
  bool kink_newton(Eigen::Vector3d& y, Sums& S, double Dref, Dual& dual);
  /// The fast path with foot `held` static and a step that crossed the kink of `other` (or the
  /// two slowest feet): the active-set polish with both static; on success y and dual are the
  /// certified pair (finish() them), else every foot but `held` slides again and the row r2 is
  /// stale (assemble at y before it is read).
  bool hold_pair(int held, int other, Eigen::Vector3d& y, Dual& dual);
  /// The two sliding feet slowest in slip speed ‖r_k(y)‖/c_k (−1 where there are fewer).
  [[nodiscard]] std::pair<int, int> slowest_two(const Eigen::Vector3d& y) const;
  /// The sliding foot whose slip the step p from y changes most relative to its size, if that is
  /// more than 1 (the step crosses its kink), else −1 (one pass; after a failed line search).
  [[nodiscard]] int most_crossed(const Eigen::Vector3d& y, const Eigen::Vector3d& p) const;
  /// The relative gap of a dual candidate of value `value`, imbalance h and largest ‖λ_k‖ lmax,
  /// against the primal `primal` at y (an upper bound of Φ(y) will do): the candidate balanced by
  /// M₂'s correction, then scaled into the disks (unloaded) or mixed with the anchor (loaded).
  [[nodiscard]] double bound(double primal, double value, double lmax, const Eigen::Vector3d& h,
                             const Eigen::Vector3d& y) const;
  /// The pass of finish(), two feet per step like assemble(): λ_k of the candidate (kPath: the
  /// smoothing path's r_k/ρ_k; else the linearized n_k + n_k⊥ (t_kᵀp)/‖r_k‖ for sliding feet,
  /// work_2n for static ones and the kink foot), balanced (λ_k −= B_k μ) and written back to
  /// work_2n, the forces F_k = −B_k,xy λ_k to Fxy (unscaled), and the sums.
  template <bool kPath>
  [[gnu::flatten]] FinishSums finish_pass(const Eigen::Vector3d& y, const Dual& dual,
                                          const Eigen::Vector3d& mu);
  /// The answer from a point y and a dual candidate: one pass (finish_pass) builds, balances and
  /// writes the forces, which are then scaled into the disks; the reported velocity is the Newton
  /// point y + p unless D is higher there, and the certificate is the candidate's exact gap.
  [[gnu::flatten]] void finish(Eigen::Vector3d y, const Dual& dual);
  /// Whether D has a flat direction at the optimum (coulomb.cpp, non-uniqueness), given the sliding
  /// feet's part of Q and the certified dual λ in work_2n.
  bool flat_direction(Eigen::Matrix3d Q, int n_static) const;
  /// Balances the forces of finish() again where M₂'s correction cannot (weights spanning many
  /// decades): λ_k −= B_k μ/c_k with M₁ μ = Σ B_kᵀλ_k, scaled into the disks; rewrites Fxy,
  /// work_2n and `sum` and returns the dual value Σ λ_kᵀd_k.
  double rebalance(detail::BalanceSum& sum);
  /// Whether every foot with friction lies within 1e-6 L of the first (contacts at one point).
  [[nodiscard]] bool one_point() const;

  // ---- the smoothing path and its polish (coulomb_path.cpp) ------------------------------------
  /// The fallback: the smoothing path from y with polish attempts at the end of each stage; S
  /// is scratch. Always finishes the solve.
  void path(Eigen::Vector3d y, Sums& S, double Dref);
  /// Armijo line search along p from y (Sums S at y), folded into the passes: the pass at the
  /// full step is also the next step's assembly; only a rejected step costs extra (value passes,
  /// t halved at most `halvings` times, never below t_min). On success y and S move to the
  /// accepted point; on failure they stay.
  template <bool kAll>
  bool line_search(Eigen::Vector3d& y, const Eigen::Vector3d& p, double slope, double d2,
                   int halvings, double t_min, Sums& S);
  /// The Newton step of the smoothing path. H is positive definite on the range of M₂ (whatever
  /// δ: no rank threshold here, the directions of a foot near rest are legitimately stiff); its
  /// null space (contacts at one point) is filled in so that the step has no component there.
  [[nodiscard]] Eigen::Vector3d smoothing_step(const Sums& S) const;
  /// The smoothing dual λ_k = r_k/ρ_k at y: Σ λᵀd = Σ ‖r‖²/ρ − yᵀg, ‖λ_k‖ ≤ √(1 − δ²/ρ_max²),
  /// imbalance g; D(y) ≤ Σ ρ and max(D, D(0)) ≥ max(Σ ρ − N δ, D(0)).
  [[nodiscard]] double path_bound(const Eigen::Vector3d& y, const Sums& S, double delta) const;
  /// The polish dual at y with step p (Sums S of the sliding feet): Σ_slide B_kᵀλ_k = g + H p =
  /// g', Σ_slide λ_kᵀd_k = Σ ‖r_k‖ − g'ᵀy (as n_k⊥ ⊥ r_k), ‖λ_k‖² = 1 + (t_kᵀp)²/‖r_k‖² ≤
  /// 1 + pᵀHp/min ‖r‖; the static feet balance g' (static_duals, written to work_2n).
  double polish_bound(const Eigen::Vector3d& y, const Sums& S, const Eigen::Vector3d& p, int dim,
                      int n_static, Dual& dual);
  /// Static feet at one point (dim 1) share the force that balances g' in proportion to c_k:
  /// c_k W_k λ_k = −(c_k/Σ_S c) g'_xy, i.e. B_k,xy λ_k = −(c_k/Σ_S c) g'_xy; the moment about
  /// their point is then balanced too when eᵀg' = 0 (the Newton equation along e). Writes λ_k to
  /// work_2n.
  StaticDual static_duals(const Eigen::Vector3d& y, const Eigen::Vector3d& gp);
  void zero_static_duals();
  // ---- the active set ---------------------------------------------------------------------------
  /// Marks feet with ‖r_k‖ ≤ threshold static (from ‖r_k‖² in the row r2); returns how many.
  int classify(double threshold);
  /// A polish attempt at the end of a smoothing stage (‖r_k(y)‖² in the row r2): the feet with
  /// ‖r_k‖ ≤ threshold are static, and the slowest other foot too if it is clearly apart (step 2
  /// of coulomb_path.cpp).
  bool try_polish(Eigen::Vector3d& y, double threshold, double delta, Dual& dual);
  /// Active-set polish from y (a point of the smoothing path at δ) with the static feet marked
  /// in work_idx. On success (relative gap ≤ tol) y and `dual` are the certified pair (static
  /// feet's λ in work_2n).
  [[gnu::flatten]] bool polish(Eigen::Vector3d& y, double delta, Dual& dual);
  /// The dual when two or more distinct static points fix y (no Newton step): unit directions
  /// for sliding feet, least-norm balancing forces for static ones, fitted into their disks.
  bool fixed_point_dual(const Eigen::Vector3d& y, const Sums& S, const detail::Psd3& static_solver,
                        int n_static, Dual& dual);
  /// Static feet at two or more distinct points balance the sliding ones (Σ_S B_kᵀλ_k = −g) with
  /// an undetermined internal force, so a balancing choice inside the disks must be searched.
  /// Two feet (work_2n = the least-norm choice): the internal force is a multiple t of the push
  /// along the line between them, each disk allows an interval of t, and the t nearest 0 in both
  /// is taken. More feet (work_2n = the smoothing path's λ, O(δ) from an optimal dual):
  /// alternating projections between the balance and the disks, at most 200 (rigid gaits only).
  void fit_static_forces(const detail::Psd3& static_solver, const Eigen::Vector3d& g, int n_static);

  const contact::Robot& robot_;
  contact::Frame& frame_;
  detail::Contacts cs_;  ///< filled by setup()
  CoulombOptions options_;
  Eigen::Vector3d load_raw_;                        ///< (F_x, F_y, M_z), N, N, N m
  Eigen::Vector3d load_ = Eigen::Vector3d::Zero();  ///< f̃ = (F_x, F_y, M_z / L)
  Interior anchor_;                                 ///< loaded: λ⁰
  double V_ = 0.0;                                  ///< loaded: velocity scale (runaway test)
  double sliding_ = 0.0;                            ///< loaded: recession slope < 0 once found
  detail::Psd3 dual_;     ///< M₂ = Σ B_kᵀB_k (least norm on its range)
  detail::Psd3 viscous_;  ///< M₁, the viscous-Coulomb system (through viscous())
  bool viscous_ready_ = false;
  Eigen::Matrix3d M1_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d M2_ = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b1_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d b2_ = Eigen::Vector3d::Zero();
  double D0_ = 0.0;
  double c_static_ = 0.0;  ///< Σ c_k over the static feet of the current polish
  double scale_ = 0.0;     ///< Σ c_k √(1 + ‖w_k‖²): the size of the cancelling forces
};

}  // namespace slipwalk::friction::coulomb
