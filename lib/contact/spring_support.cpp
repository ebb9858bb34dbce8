// The spring-support search of thesis §3.3 (Alg. 1). The derivations behind every choice are
// written out here, because the printed equations need corrections in three places.
//
// ---- Coordinates -------------------------------------------------------------------------------
// The search runs in the scaled state u = (αL, βL, z), all in metres, with L = max_j |q_xy,j|.
// Foot j's height (eq. 3.6) is then  h_j = a_j·u + q_z,j  with  a_j = (q_y,j/L, −q_x,j/L, 1),
// so that the Hessians below are well scaled whatever the robot's size.
//
// ---- The potential and the balance (eqs. 3.7-3.9) ----------------------------------------------
// U(u) = Σ_j ½K_j min(h_j, 0)² + Mg z is convex and C¹ with gradient
//   ∇U = Σ_j K_j min(h_j, 0) a_j + Mg e_z = (M_x/L, M_y/L, Mg − ΣF_z),
// (F_z,j = −K_j min(h_j, 0), M_x = Σ −q_y F_z, M_y = Σ q_x F_z), so the balance ΣF_z = Mg,
// M_x = M_y = 0 is exactly ∇U = 0 and a balanced state is a global minimizer. On the cell where
// the contact set C is fixed, U = U_C is quadratic with Hessian H_C = Σ_{k∈C} K_k a_k a_kᵀ.
// In the thesis' unknowns (β, α, z) and rows (ΣF_z = Mg, M_x = 0, M_y = 0) eq. 3.9 reads
//   Σ_k K_k [ −q_x      q_y      1   ] [β]   [ −Mg − Σ K_k q_z,k     ]
//           [ −q_x q_y  q_y²     q_y ] [α] = [ −Σ K_k q_y,k q_z,k    ]
//           [  q_x²    −q_x q_y −q_x ] [z]   [  Σ K_k q_x,k q_z,k    ]
// (row 2 is M_x = Σ K q_y h = 0, row 3 is M_y = −Σ K q_x h = 0). The printed matrix mixes signs
// in row 2 (its z entry and right side belong to the negated row), and its row 3 has q_y where
// q_x q_y and q_x belong (and q_y q_z for q_x q_z on the right). Here the same system is solved
// in the scaled state as H_C d = −∇U.
//
// ---- The path and why it ends -------------------------------------------------------------------
// Start: α = β = 0 and z* from the sorted heights (§3.3.1), so ΣF_z = Mg and ∇U(u_0) = g_0 =
// (M_x/L, M_y/L, 0). Each step moves u along a direction d within one cell, to the first contact
// change (eq. 3.10: feet touching down and feet lifting off) or to the step's end:
//  * Newton step (the contacts can balance the current moment, eq. 3.9): d = −H_C⁺ ∇U, target
//    u + d. Along it ∇U_C(u + t d) = (1 − t) ∇U(u): U falls strictly (a convex quadratic toward
//    its minimizer) and the gradient keeps its direction.
//  * Tilt step (the moment has a part g_N in the null space of H_C, the motions that keep every
//    contact's compression: one foot, two feet, or contacts in a row with the CoM off the row):
//    d = −g_N. Along it ∇U is constant and U falls linearly, dU/dt = −|g_N|² < 0. No contact lifts
//    (their compressions are fixed); if no foot touches down either, U → −∞: no balance exists,
//    the robot tips (kUnsupported).
// Eq. 3.11 (one contact, foot at q_1) in these terms: the null space is {a_1·d = 0}, and
// −g_N ∝ (q_y,1, −q_x,1, −(q_x,1² + q_y,1²)) in (α, β, z), which is the printed vector with p the
// foot's body-frame position: the body turns about the horizontal axis through the foot normal to
// the foot–CoM line, the CoM goes down, dU/dt = −Mg r² < 0. The printed sign is right.
// Eq. 3.12 (two contacts): the null vector is a_1 × a_2 ∝ (δx, δy, c) in (α, β, z) order, with
// δx = q_x,1 − q_x,2, δy = q_y,1 − q_y,2, c = q_y,1 q_x,2 − q_y,2 q_x,1, and ∇U·(δx, δy, c) = Mg c,
// so the descent direction is −sign(c)(δx, δy, c): the printed sign −c/|c| is right, but its
// vector [δy, δx, c] only keeps both feet's compressions when read in the (β, α, z) order of eq.
// 3.9, not in the stated [δα, δβ, δz] order (read that way, the feet would be lifted or pressed
// in). Both cases are instances of d = −g_N, which is what is computed (also for ≥ 3 collinear
// contacts, and for singular systems in general).
// Termination. Every step keeps ∇U = λ g_0 with λ ∈ [0, 1] non-increasing (Newton steps scale it
// by 1 − t, tilt steps keep it), and U strictly decreases over every step of positive length. The
// points with ∇U = λ g_0 minimize U − λ g_0·u, a convex function; in the interior of a cell with
// a nonsingular H_C that minimizer is unique, so in general position a cell with three or more
// contacts is visited on one stretch of λ only; a two-contact cell is only entered at the single λ
// its moment balance allows, and left by a touch-down, which only a later Newton step (λ falling)
// could undo. So, in general position, every cell of the arrangement of the N planes h_j = 0 is
// visited at most once and the search ends after fewer than 1 + N + C(N,2) + C(N,3) contact
// changes, either balanced (a full Newton step, hence the global minimizer) or tipping.
// Ties (several feet reaching their planes at one point, feet exactly touching at the balance,
// duplicate feet) give steps of zero length. Three rules keep them from switching a foot back and
// forth: a foot at its plane changes only on a rate above the rounding error of the step (about
// ε |H| |d| |H⁻¹a_j|); the foot that has just changed is not checked in the next step of a
// nonsingular cell or a tilt, since it keeps its way there (first_change); and the final balance
// is polished with the contact set read off the heights (polish). In fuzzing with exact ties, rows
// of feet, feet under the CoM and stiffnesses over six decades (5·10⁶ frames) no search needed
// more than 34 contact changes; the iteration limit stays as the guard the proof does not cover.
#include "contact/spring_support.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "contact/support_newton.hpp"

namespace slipwalk::contact {

namespace {

using Status = SupportSummary::Status;
using Eigen::Matrix3d;
using Eigen::Vector3d;

using detail::kEps;
using detail::kInf;
using detail::kPolished;
// An eigenvalue of G = Σ a_k a_kᵀ below kRankTol × the largest is a null direction (a motion that
// keeps the contacts' compressions): contacts in a row or at one point (to ~3e-7 L).
constexpr double kRankTol = 1e-13;
// A null-space moment |g_N| below kFlatTol × Mg is zero: the CoM is on the contacts' line.
constexpr double kFlatTol = 1e-12;
// A foot whose height changes by less than kRateTol × |d| along a tilt d stays at its height.
constexpr double kRateTol = 1e-13;
// The rounding error of a height h_j = a_j·u + q_z,j, relative to |u|₁ + |q_z,j|.
constexpr double kNoise = 8.0 * kEps;

// The per-call geometry and the search state, in the scaled coordinates u = (αL, βL, z).
struct Search {
  const Robot& robot;
  Frame& f;
  double L = 1.0;         // horizontal size, m
  double inv_L = 1.0;     // 1 / L
  Vector3d u;             // current state
  std::vector<char>& in;  // the search's contact set (frame.contact, reused as scratch)

  Search(const Robot& r, Frame& frame)
      : robot(r), f(frame), u(Vector3d::Zero()), in(frame.contact) {
    double size = 0.0;
    for (int j = 0; j < f.legs(); ++j) {
      size = std::max(size, f.q(0, j) * f.q(0, j) + f.q(1, j) * f.q(1, j));
    }
    if (size > 0.0) {
      L = std::sqrt(size);
      inv_L = 1.0 / L;
    }
  }

  [[nodiscard]] Vector3d a(int j) const { return {f.q(1, j) * inv_L, -f.q(0, j) * inv_L, 1.0}; }
  [[nodiscard]] double height(int j, const Vector3d& at) const { return a(j).dot(at) + f.q(2, j); }
  [[nodiscard]] int contacts() const {
    return static_cast<int>(std::count(in.begin(), in.end(), char{1}));
  }
  void record(std::vector<SupportStep>* path, int changed) const {
    if (path != nullptr) {
      path->push_back({u(0) * inv_L, u(1) * inv_L, u(2), contacts(), changed});
    }
  }
};

// The quadratic model of the current cell: ∇U, H_C, and the split of the state space into the
// motions that change some contact's compression (the range of H_C) and those that keep all of
// them (its null space). The split is taken from the unweighted G = Σ_{k∈C} a_k a_kᵀ, which has
// the same null space as H_C but does not depend on the stiffnesses: with K over many decades the
// null directions of H_C are only known to ε·K_max/K_min, those of G to ε.
struct CellModel {
  Vector3d grad;
  Matrix3d H;
  Matrix3d basis;  // eigenvectors of G, ascending: the first 3 − rank span the null space
  int rank = 0;

  [[nodiscard]] Vector3d null_part(const Vector3d& v) const {
    Vector3d r = Vector3d::Zero();
    for (int i = 0; i < 3 - rank; ++i) {
      r += basis.col(i) * basis.col(i).dot(v);
    }
    return r;
  }
  // The Newton system in the range of H_C: A = Rᵀ H_C R with R the range basis (R = I for a
  // nonsingular cell), factored once per cell.
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;
  using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
  Eigen::LLT<Small> llt;
  double norm_A = 0.0;  // trace(A) ≥ |A|₂

  void factor() {
    if (rank == 0) {
      return;
    }
    const auto R = basis.rightCols(rank);
    const Small A = rank == 3 ? Small(H) : Small(R.transpose() * H * R);
    norm_A = A.trace();
    llt.compute(A);
  }
  // −H_C⁺ v: the Newton step within the range of H_C.
  [[nodiscard]] Vector3d newton(const Vector3d& v) const {
    if (rank == 0) {
      return Vector3d::Zero();
    }
    if (rank == 3) {
      return llt.solve(-v);
    }
    const auto R = basis.rightCols(rank);
    const SmallVec w = llt.solve(SmallVec(-(R.transpose() * v)));
    return R * w;
  }
  // The rounding error of a_j·d for the Newton step d: the error of d is about H⁺ e with
  // |e| ≲ ε|A||d|, so a_j·d is off by about ε |A| |d| |H⁺ a_j|.
  [[nodiscard]] double rate_error(const Vector3d& a, double step) const {
    if (rank == 0) {
      return 0.0;
    }
    return kNoise * norm_A * step * newton(a).norm();
  }
};

CellModel cell_model(const Search& s) {
  CellModel m;
  m.H.setZero();
  Matrix3d G = Matrix3d::Zero();
  m.grad = Vector3d(0.0, 0.0, s.robot.Mg);
  for (int j = 0; j < s.f.legs(); ++j) {
    if (s.in[j] != 0) {
      const Vector3d a = s.a(j);
      const double K = s.robot.K(j);
      G.noalias() += a * a.transpose();
      m.H.noalias() += K * a * a.transpose();
      m.grad += (K * s.height(j, s.u)) * a;
    }
  }
  // Three contacts off a line (the common case) without an eigen-decomposition: λ_min(G) ≥
  // det G / tr(G)², so det G > kRankTol tr(G)³ guarantees rank 3 by the criterion below.
  const double tr = G.trace();
  if (G.determinant() > kRankTol * tr * tr * tr) {
    m.basis.setIdentity();
    m.rank = 3;
  } else {
    const Eigen::SelfAdjointEigenSolver<Matrix3d> es(G);
    m.basis = es.eigenvectors();
    const double threshold = kRankTol * es.eigenvalues()(2);
    m.rank = 0;
    for (int i = 0; i < 3; ++i) {
      m.rank += es.eigenvalues()(i) > threshold && es.eigenvalues()(i) > 0.0 ? 1 : 0;
    }
  }
  m.factor();
  return m;
}

// The first contact change on u + t d, t ∈ (0, t_max] (eq. 3.10, both directions): a foot in the
// set rising to h = 0, or a foot outside it coming down to h = 0. Along a tilt the contacts keep
// their heights by construction and only feet in the air are checked. Along a Newton step a foot
// at its contact plane whose height changes by less than the rounding error of the height and of
// the step (ε |H| |d| |H⁻¹a_j|) over the whole step does not change contact (at a tie at the
// balance itself its rate is rounding noise, and acting on it would switch the foot back and
// forth). The foot `exempt`, which changed at the step's start, is not checked: it keeps moving the
// way it changed (for nonsingular cells by Sherman–Morrison, a_j·d' = (1 − t) a_j·d / (1 + K_j a_jᵀ
// H_C⁻¹ a_j), and likewise for the tilts), or stays at h_j = 0 when it carries nothing at the
// balance, and then a computed rate of the other sign is rounding noise amplified by the condition
// of H_C. Returns the leg (−1 if none before t_max) and sets t. Ties go to the lowest index.
int first_change(const Search& s, const CellModel& m, const Vector3d& d, double t_max, bool tilt,
                 int exempt, double& t, bool& suppressed) {
  suppressed = false;
  const double size = d.norm();
  const double state_size = s.u.cwiseAbs().sum();
  t = t_max;
  int leg = -1;
  for (int j = 0; j < s.f.legs(); ++j) {
    if ((tilt && s.in[j] != 0) || j == exempt) {
      continue;
    }
    const Vector3d a = s.a(j);
    const double r = a.dot(d);
    const double h = s.height(j, s.u);
    // A foot at its contact plane (h_j = 0 to rounding) changes only on a rate above the rounding
    // error of the step; any other foot on any rate that reaches the plane within the step.
    const double h_noise = kNoise * (state_size + std::abs(s.f.q(2, j)));
    const double plain_noise = kRateTol * size * a.lpNorm<1>();  // |a|₁ ≥ |a|, no sqrt
    double noise = plain_noise;
    if (!tilt && std::abs(h) <= h_noise) {
      noise = std::max(noise, h_noise + m.rate_error(a, size));
    }
    if (std::abs(r) <= noise) {
      suppressed = suppressed || std::abs(r) > plain_noise;
      continue;
    }
    double tj = kInf;
    if (s.in[j] != 0 && r > 0.0) {
      tj = std::max(-h, 0.0) / r;
    } else if (s.in[j] == 0 && r < 0.0) {
      tj = std::max(h, 0.0) / -r;
    }
    if (tj < t) {
      t = tj;
      leg = j;
    }
  }
  return leg;
}

// §3.3.1: α = β = 0 and ΣF_z = Mg, i.e. z* solves F(z) = Σ_j K_j max(−q_z,j − z, 0) = Mg. The
// thesis sorts the feet by height and adds them lowest first; here F (convex, piecewise linear,
// decreasing) is solved by Newton's method from the left, z ← −(Σ_C K q_z + Mg)/Σ_C K over the
// feet C below −z: starting from all feet (their linear extension lies below F) it rises
// monotonically and ends on z*'s piece once C stops changing, after a few passes over the feet
// without data-dependent branches (a sort's comparisons are mispredicted about half the time,
// which made it the search's largest per-leg cost). Marks the feet below −z* in contact — those
// with F(−q_z,j) < Mg, the sorted search's test; ties at equal heights go in or out together.
double initial_height(Search& s) {
  const int n = s.f.legs();
  const auto& q = s.f.q;
  double z = -kInf;
  for (int it = 0; it <= n; ++it) {  // each pass drops at least one foot, so n + 1 bound it
    double sum_k = 0.0;              // Σ K over the feet below −z
    double sum_kq = 0.0;             // Σ K q_z over them
    for (int j = 0; j < n; ++j) {
      const double w = q(2, j) < -z ? s.robot.K(j) : 0.0;
      sum_k += w;
      sum_kq += w * q(2, j);
    }
    const double next = -(sum_kq + s.robot.Mg) / sum_k;
    if (!(next > z)) {  // the same piece again (or rounding): z is the root
      break;
    }
    z = next;
  }
  for (int j = 0; j < n; ++j) {
    s.in[j] = q(2, j) < -z ? 1 : 0;
  }
  return z;
}

// For kLine / kPoint: the tilt is free along the null space of H_C (the contacts' compressions
// and the loads do not change). Move toward the least |(α, β)| along it, stopping where a foot in
// the air would touch down. Exact for a one-dimensional null space (kLine).
void reduce_free_tilt(Search& s, const CellModel& m) {
  const int k = 3 - m.rank;  // 1 (kLine) or 2 (kPoint)
  if (k < 1 || k > 2) {
    return;
  }
  // Least squares for the tilt part of u + N w, N the null basis.
  Eigen::Matrix2d BtB = Eigen::Matrix2d::Identity();
  Eigen::Vector2d Btu = Eigen::Vector2d::Zero();
  for (int i = 0; i < k; ++i) {
    const Eigen::Vector2d vi = m.basis.col(i).head<2>();
    Btu(i) = vi.dot(s.u.head<2>());
    for (int l = 0; l < k; ++l) {
      BtB(i, l) = vi.dot(m.basis.col(l).head<2>());
    }
  }
  if (!(std::abs(BtB.determinant()) > kRankTol)) {
    return;
  }
  const Eigen::Vector2d w = -BtB.inverse() * Btu;
  Vector3d d = m.basis.col(0) * w(0);
  if (k == 2) {
    d += m.basis.col(1) * w(1);
  }
  // Only feet in the air can block; the contacts' heights do not change along the null space.
  double t = 1.0;
  const double rate_tol = kRateTol * d.norm();
  for (int j = 0; j < s.f.legs(); ++j) {
    const Vector3d a = s.a(j);
    const double r = a.dot(d);
    if (s.in[j] == 0 && r < -rate_tol * a.lpNorm<1>()) {
      t = std::min(t, std::max(s.height(j, s.u), 0.0) / -r);
    }
  }
  s.u += t * d;
}

// The contact convention of the outputs: foot j touches at u iff h_j < 0 beyond the rounding
// error of h_j itself (so h_j = 0, an exactly touching foot, does not); sets h.
bool touching(const Search& s, int j, const Vector3d& u, double& h) {
  h = s.height(j, u);
  const double noise = 4.0 * kEps *
                       (std::abs(s.f.q(2, j)) + std::abs(u(2)) + std::abs(u(0) * s.a(j)(0)) +
                        std::abs(u(1) * s.a(j)(1)));
  return h < -noise;
}

// max(|ΣF_z − Mg|/Mg, |M_x|/(Mg L), |M_y|/(Mg L)) at u with the loads of eq. 3.7.
double balance_residual(const Search& s, const Vector3d& u) {
  double fz = 0.0;
  double mx = 0.0;
  double my = 0.0;
  for (int j = 0; j < s.f.legs(); ++j) {
    double h = 0.0;
    const double F = touching(s, j, u, h) ? -s.robot.K(j) * h : 0.0;
    fz += F;
    mx -= s.f.q(1, j) * F;
    my += s.f.q(0, j) * F;
  }
  const double mg = s.robot.Mg;
  return std::max({std::abs(fz - mg) / mg, std::abs(mx) / (mg * s.L), std::abs(my) / (mg * s.L)});
}

// Polish the final balance: one Newton correction with the final contact set (iterative
// refinement: the step was solved to ε·cond(H_C), which with soft and stiff legs together leaves
// feet that carry nothing at the balance compressed by a little), then up to two with the contact
// set read off the heights (a foot the search did not count because its rate was below the
// step's rounding error). Each is kept only if it balances better.
void polish(Search& s) {
  double best = balance_residual(s, s.u);
  for (int pass = 0; pass < 3 && best > kPolished; ++pass) {
    if (pass > 0) {
      for (int j = 0; j < s.f.legs(); ++j) {
        double h = 0.0;
        s.in[j] = touching(s, j, s.u, h) ? 1 : 0;
      }
    }
    const CellModel m = cell_model(s);
    if (m.rank == 0) {
      return;
    }
    const Vector3d u = s.u + m.newton(m.grad);
    const double r = balance_residual(s, u);
    if (r < best) {
      s.u = u;
      best = r;
    }
  }
}

// The reported outputs from the final state: contacts, loads (eq. 3.7), the balance residual.
void write_outputs(Search& s) {
  Frame& f = s.f;
  f.alpha = s.u(0) * s.inv_L;
  f.beta = s.u(1) * s.inv_L;
  f.z = s.u(2);
  for (int j = 0; j < f.legs(); ++j) {
    double h = 0.0;
    const bool on = touching(s, j, s.u, h);
    f.contact[j] = on ? 1 : 0;
    f.Fz(j) = on ? -s.robot.K(j) * h : 0.0;
  }
  f.support.residual = balance_residual(s, s.u);
}

// Out of line: the cold path of flag_non_finite.
[[gnu::noinline, gnu::cold]] void mark_non_finite(SupportSummary& summary) {
  summary.status = Status::kNonFinite;
  summary.message = "the state or the loads are not finite (inputs outside the model's ranges)";
}

// The end-of-solve check: a state, a load or a residual that is not finite is no result (inputs
// outside contact::limits can overflow K h or Mg/K), whatever the route reported. The sum tests
// all loads at once: a sum with a non-finite term is not finite.
void flag_non_finite(Frame& f) {
  if (!std::isfinite(f.alpha + f.beta + f.z + f.support.residual + f.Fz.sum())) [[unlikely]] {
    mark_non_finite(f.support);
  }
}

}  // namespace

int default_support_iterations(int n) {
  const auto m = static_cast<std::int64_t>(std::max(n, 0));
  const std::int64_t cells = 1 + m + m * (m - 1) / 2 + m * (m - 1) * (m - 2) / 6;
  return static_cast<int>(std::min<std::int64_t>(cells, std::numeric_limits<int>::max()));
}

const char* status_name(SupportSummary::Status status) {
  switch (status) {
    case Status::kBalanced:
      return "balanced";
    case Status::kLine:
      return "line";
    case Status::kPoint:
      return "point";
    case Status::kUnsupported:
      return "unsupported";
    case Status::kIterationLimit:
      return "iteration-limit";
    case Status::kNonFinite:
      return "non-finite";
  }
  return "unknown";
}

void forget_balance(Frame& frame) {
  frame.alpha = std::numeric_limits<double>::quiet_NaN();
  frame.beta = frame.alpha;
  frame.z = frame.alpha;
}

void spring_support(const Robot& robot, Frame& frame, const SupportOptions& options) {
  // The range of q is tested by the Newton route's first pass, and by check_frame below where
  // that route does not certify (it certifies only feet in range): no pass of its own.
  check_frame_except_positions(robot, frame);
  SupportSummary& summary = frame.support;
  // A warm start needs a previous balance: a state the frame's last search certified or ended
  // balanced on (checked before the summary is reset below).
  const bool warm = options.warm_start && summary.status == Status::kBalanced &&
                    std::isfinite(frame.alpha) && std::isfinite(frame.beta) &&
                    std::isfinite(frame.z);
  summary.status = Status::kBalanced;
  summary.route = SupportSummary::Route::kPath;
  summary.iterations = 0;
  summary.newton_steps = 0;
  summary.residual = 0.0;
  summary.message.clear();

  // ---- the fast route: active-set Newton on U, certified or handed over ----------------------
  // Its certificate implies finite outputs (no end-of-solve check needed): a certified residual
  // ≤ 1e-10 makes ΣF_z = Mg − ∂U/∂z finite, a sum of the same non-negative products K_j h_j the
  // outputs hold, and a non-finite state fails the contact test of every foot (residual 1).
  if (options.newton && options.path == nullptr &&
      (warm ? detail::support_by_newton_warm(robot, frame,
                                             Vector3d(frame.alpha, frame.beta, frame.z))
            : detail::support_by_newton(robot, frame))) {
    return;
  }
  check_frame(robot, frame);

  Search s(robot, frame);
  const int limit = options.max_iterations > 0 ? options.max_iterations
                                               : default_support_iterations(frame.legs());

  // ---- §3.3.1: the initial height z* at zero tilt ---------------------------------------------
  s.u = Vector3d(0.0, 0.0, initial_height(s));
  s.record(options.path, -1);

  // ---- §3.3.2-3.3.3: follow the path to the balance, one contact change per step -------------
  int last = -1;             // the leg whose contact changed at the end of the previous step
  bool held_at_tie = false;  // a foot at its plane was held there on a rounding-level rate
  for (;;) {
    const CellModel m = cell_model(s);
    // Direction: tilt under the moment the contacts cannot take (eqs. 3.11, 3.12), else the
    // Newton step to the balance of the current contacts (eq. 3.9).
    const Vector3d g_null = m.null_part(m.grad);
    const bool tilt = g_null.norm() > kFlatTol * robot.Mg;
    const Vector3d d = tilt ? Vector3d(-g_null) : m.newton(m.grad);
    double t = 0.0;
    // The leg that changed last keeps its way (see first_change) along a tilt or a Newton step of
    // a nonsingular cell; a least-norm step of a singular cell has an arbitrary null component
    // and is checked for every leg.
    const int exempt = tilt || m.rank == 3 ? last : -1;
    bool suppressed = false;
    const int leg = first_change(s, m, d, tilt ? kInf : 1.0, tilt, exempt, t, suppressed);
    held_at_tie = held_at_tie || suppressed;
    if (leg < 0) {
      if (tilt) {
        // Nothing stops the tilt: U is unbounded below, the robot tips over.
        summary.status = Status::kUnsupported;
        summary.message = "the CoM is outside the support polygon: the robot tips";
        s.record(options.path, -1);
        break;
      }
      // The balance of the current contacts is consistent with them: the global minimizer.
      s.u += d;
      if (held_at_tie) {
        polish(s);
      }
      // Contacts in a row or at one point under the CoM leave a free tilt.
      const CellModel final_cell = held_at_tie ? cell_model(s) : m;
      if (final_cell.rank == 2) {
        summary.status = Status::kLine;
        reduce_free_tilt(s, final_cell);
      } else if (final_cell.rank < 2) {
        summary.status = Status::kPoint;
        reduce_free_tilt(s, final_cell);
      }
      s.record(options.path, -1);
      break;
    }
    // Eq. 3.10: stop at the first contact change and switch that foot.
    s.u += t * d;
    s.in[leg] = s.in[leg] != 0 ? 0 : 1;
    last = leg;
    ++summary.iterations;
    s.record(options.path, leg);
    if (summary.iterations >= limit) {
      summary.status = Status::kIterationLimit;
      summary.message = "stopped after " + std::to_string(limit) + " contact changes";
      break;
    }
  }
  write_outputs(s);
  flag_non_finite(frame);
}

}  // namespace slipwalk::contact
