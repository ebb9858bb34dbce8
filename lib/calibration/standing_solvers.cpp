// The standing stage's solvers (standing.hpp states the balance, the models and the covariance).
//
// The balance (standing.hpp, eq. 4.8) with R_k = R_N,k R̃_k, c_k = p_N,k + u_k:
//   force  F_p = G_ch ĝ_p + Σ_k R_k f̂_pk
//   torque T_p = Σ_k R_k τ̂_pk + c_k × v_pk  (− Σ_k R_k r_pk × m_k g ĝ_p for thesis_literal),
//   v_pk = R_k f̂_pk  (chassis)  or  R_k f̂_pk − m_k g ĝ_p  (thesis_literal: the leg's weight taken
//   off its wrench, at x_pk = c_k + R_k r_pk, so c_k multiplies the difference).
// So with the rotations fixed F_p does not depend on u and T_p = a_p − Σ_k [v_pk] u_k is linear in
// u: the displacement step is one linear least-squares problem (K = diag(1, κ) weights only the
// torque rows, which all carry the same κ, so κ drops out of it). A shared displacement has the
// single column block −[Σ_k v_pk].
//
// Parametrisations of R̃_k: Cayley parameters (the alternating solver's rotation step, wrench.hpp;
// R(q) = ((1 − qᵀq) I + 2 q qᵀ − 2[q]) / (1 + qᵀq), the closed form of (I − [q])(I + [q])⁻¹, since
// the two factors commute), unit quaternions on Ceres' EigenQuaternionManifold (the joint solver)
// and rotation vectors (the covariance: its Jacobian is taken in the rotation vector θ_k of R̃_k,
// the quantity whose standard error is reported).
//
// The covariance. The noise n_k of each transducer enters e_p through the constant wrench transform
// of its (fixed) frame into C, so e_p's 6 × 6 covariance Σ in C is the same for every pose, and
// correlates force with torque (c_k × R_k n_f). It is estimated from the residuals at the solution,
// Σ̂ = Σ_p e_p e_pᵀ / (P − DOF/6) (6P residuals, DOF parameters), and the estimator's covariance is
// the sandwich H⁻¹ (Σ_p J_pᵀ K Σ̂ K J_p) H⁻¹, H = Σ_p J_pᵀ K J_p (pseudo-inverse: H is singular in
// no model on tilted poses, but nearly so along the gauge of standing.hpp on level ground).
#include "calibration/standing_solvers.hpp"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>

#include "core/error.hpp"

namespace slipwalk::calibration::standing_detail {

namespace {

enum class RotationParam { cayley, quaternion, rotation_vector };

constexpr int parameter_size(RotationParam kind) {
  return kind == RotationParam::quaternion ? 4 : 3;
}

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Mat3 = Eigen::Matrix<T, 3, 3>;

template <typename T>
Mat3<T> skew_t(const Vec3<T>& v) {
  Mat3<T> s;
  s << T(0.0), -v.z(), v.y(), v.z(), T(0.0), -v.x(), -v.y(), v.x(), T(0.0);
  return s;
}

template <typename T>
Mat3<T> rotation_of(RotationParam kind, const T* x) {
  switch (kind) {
    case RotationParam::cayley: {
      const Vec3<T> q(x[0], x[1], x[2]);
      const T n = q.squaredNorm();
      return ((T(1.0) - n) * Mat3<T>::Identity() + T(2.0) * q * q.transpose() -
              T(2.0) * skew_t(q)) /
             (T(1.0) + n);
    }
    case RotationParam::quaternion:
      return Eigen::Map<const Eigen::Quaternion<T>>(x).toRotationMatrix();
    case RotationParam::rotation_vector: {
      Mat3<T> r;
      ceres::AngleAxisToRotationMatrix(x, r.data());  // column-major, as Eigen's default
      return r;
    }
  }
  return Mat3<T>::Identity();
}

/// The balance of one pose, generic over the scalar: `rotation(k)` gives R̃_k, `displacement(k)`
/// gives u_k. Returns [F; √κ T].
template <typename T, typename RotationAt, typename DisplacementAt>
Eigen::Matrix<T, 6, 1> weighted_residual(const BalanceData& data, Eigen::Index p,
                                         RotationAt&& rotation, DisplacementAt&& displacement) {
  // Mixed double × T products (Ceres declares them to Eigen) keep the differentiated part small:
  // only R̃_k and u_k carry derivatives.
  const PoseTerms& pose = data.poses[static_cast<std::size_t>(p)];
  Vec3<T> force = (data.chassis_weight * pose.down).template cast<T>();
  Vec3<T> torque = Vec3<T>::Zero();
  for (int k = 0; k < data.legs; ++k) {
    const auto ks = static_cast<std::size_t>(k);
    const Mat3<T> tilt = rotation(k);
    const Eigen::Matrix3d& nominal = data.nominal_rotation[ks];
    const Vec3<T> c = displacement(k) + data.nominal_position[ks];
    const Vec3<T> v = nominal * (tilt * pose.force.col(k));
    force += v;
    torque += nominal * (tilt * pose.torque.col(k)) + c.cross(v);
    if (data.target == BalanceTarget::thesis_literal) {
      const Eigen::Vector3d w = data.leg_weight[ks] * pose.down;
      const Vec3<T> x = c + nominal * (tilt * pose.com.col(k));
      torque -= x.cross(w.cast<T>());
    }
  }
  Eigen::Matrix<T, 6, 1> e;
  e << force, T(data.sqrt_kappa) * torque;
  return e;
}

/// Ceres' residual block of one pose: parameter blocks R̃_0..R̃_{K−1} then u_0..u_{K−1} (or one
/// shared u).
class PoseBalance {
 public:
  PoseBalance(const BalanceData* data, Eigen::Index pose, RotationParam kind, bool shared)
      : data_(data), pose_(pose), kind_(kind), shared_(shared) {}

  template <typename T>
  bool operator()(T const* const* x, T* residual) const {
    const int legs = data_->legs;
    const auto rotation = [&](int k) { return rotation_of<T>(kind_, x[k]); };
    const auto displacement = [&](int k) {
      const T* u = x[legs + (shared_ ? 0 : k)];
      return Vec3<T>(u[0], u[1], u[2]);
    };
    Eigen::Map<Eigen::Matrix<T, 6, 1>> out(residual);
    out = weighted_residual<T>(*data_, pose_, rotation, displacement);
    return true;
  }

 private:
  const BalanceData* data_;
  Eigen::Index pose_;
  RotationParam kind_;
  bool shared_;
};

constexpr int kStride = 10;  // derivative components per automatic-differentiation pass

/// The parameters of one Ceres problem: K rotation blocks and K (or one) displacement blocks.
struct Blocks {
  RotationParam kind = RotationParam::cayley;
  std::vector<double> rotation;      ///< K × parameter_size(kind)
  std::vector<double> displacement;  ///< K × 3 or 3
  bool shared = false;

  double* rotation_block(int k) {
    return rotation.data() + static_cast<std::ptrdiff_t>(k) * parameter_size(kind);
  }
  double* displacement_block(int k) {
    return displacement.data() + (shared ? 0 : 3 * static_cast<std::ptrdiff_t>(k));
  }

  Blocks(RotationParam param, int legs, bool shared_u)
      : kind(param),
        rotation(static_cast<std::size_t>(legs * parameter_size(param)), 0.0),
        displacement(static_cast<std::size_t>(shared_u ? 3 : 3 * legs), 0.0),
        shared(shared_u) {}

  void set_rotation(int k, const Eigen::Matrix3d& r) {
    double* x = rotation_block(k);
    switch (kind) {
      case RotationParam::cayley:
        Eigen::Map<Eigen::Vector3d>{x} = cayley_inverse(r);
        break;
      case RotationParam::quaternion:
        Eigen::Map<Eigen::Vector4d>{x} = Eigen::Quaterniond(r).normalized().coeffs();
        break;
      case RotationParam::rotation_vector:
        Eigen::Map<Eigen::Vector3d>{x} = calibration::rotation_vector(r);
        break;
    }
  }
  [[nodiscard]] Eigen::Matrix3d get_rotation(int k) {
    return rotation_of<double>(kind, rotation_block(k));
  }
  void set_displacement(const std::vector<Eigen::Vector3d>& u) {
    if (shared) {
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const auto& v : u) {
        mean += v;
      }
      Eigen::Map<Eigen::Vector3d>{displacement.data()} = mean / static_cast<double>(u.size());
      return;
    }
    for (std::size_t k = 0; k < u.size(); ++k) {
      Eigen::Map<Eigen::Vector3d>{displacement.data() + 3 * k} = u[k];
    }
  }
  [[nodiscard]] std::vector<Eigen::Vector3d> get_displacement(int legs) {
    std::vector<Eigen::Vector3d> u(static_cast<std::size_t>(legs));
    for (int k = 0; k < legs; ++k) {
      u[static_cast<std::size_t>(k)] = Eigen::Map<const Eigen::Vector3d>(displacement_block(k));
    }
    return u;
  }
};

/// Adds every pose's residual block to `problem` over `blocks`.
void add_poses(ceres::Problem& problem, const BalanceData& data, Blocks& blocks) {
  const int displacements = blocks.shared ? 1 : data.legs;
  std::vector<double*> pointers;
  pointers.reserve(static_cast<std::size_t>(data.legs) + static_cast<std::size_t>(displacements));
  for (int k = 0; k < data.legs; ++k) {
    pointers.push_back(blocks.rotation_block(k));
  }
  for (int k = 0; k < displacements; ++k) {
    pointers.push_back(blocks.displacement_block(k));
  }
  for (std::size_t p = 0; p < data.poses.size(); ++p) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<PoseBalance, kStride>(
        new PoseBalance(&data, static_cast<Eigen::Index>(p), blocks.kind, blocks.shared));
    for (int k = 0; k < data.legs; ++k) {
      cost->AddParameterBlock(parameter_size(blocks.kind));
    }
    for (int k = 0; k < displacements; ++k) {
      cost->AddParameterBlock(3);
    }
    cost->SetNumResiduals(6);
    problem.AddResidualBlock(cost, nullptr, pointers);
  }
}

bool rotations_free(MountingModel model) {
  return model == MountingModel::full || model == MountingModel::shared_translation;
}
bool shared_displacement(MountingModel model) {
  return model == MountingModel::shared_translation || model == MountingModel::com_only;
}

ceres::Solver::Options solver_options(int max_iterations, double function_tolerance) {
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = function_tolerance;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  return options;
}

void check_usable(const ceres::Solver::Summary& summary) {
  if (!summary.IsSolutionUsable() || !std::isfinite(summary.final_cost)) {
    throw core::ComputationError("standing: the Ceres solve failed: " + summary.message);
  }
}

std::vector<Eigen::Matrix3d> start_rotations(const BalanceData& data, MountingModel model,
                                             const MountingStart& start) {
  std::vector<Eigen::Matrix3d> r(static_cast<std::size_t>(data.legs), Eigen::Matrix3d::Identity());
  if (rotations_free(model) && start.rotation.size() == r.size()) {
    r = start.rotation;
  }
  return r;
}

std::vector<Eigen::Vector3d> start_displacements(const BalanceData& data,
                                                 const MountingStart& start) {
  std::vector<Eigen::Vector3d> u(static_cast<std::size_t>(data.legs), Eigen::Vector3d::Zero());
  if (start.displacement.size() == u.size()) {
    u = start.displacement;
  }
  return u;
}

}  // namespace

Vector6d residual_in_c(const BalanceData& data, Eigen::Index pose,
                       const std::vector<Eigen::Matrix3d>& rotation,
                       const std::vector<Eigen::Vector3d>& displacement) {
  Vector6d e = weighted_residual<double>(
      data, pose, [&](int k) { return rotation[static_cast<std::size_t>(k)]; },
      [&](int k) { return displacement[static_cast<std::size_t>(k)]; });
  e.tail<3>() /= data.sqrt_kappa;
  return e;
}

double weighted_rss(const BalanceData& data, const std::vector<Eigen::Matrix3d>& rotation,
                    const std::vector<Eigen::Vector3d>& displacement) {
  double rss = 0.0;
  for (std::size_t p = 0; p < data.poses.size(); ++p) {
    rss += weighted_residual<double>(
               data, static_cast<Eigen::Index>(p),
               [&](int k) { return rotation[static_cast<std::size_t>(k)]; },
               [&](int k) { return displacement[static_cast<std::size_t>(k)]; })
               .squaredNorm();
  }
  return rss;
}

std::vector<Eigen::Vector3d> solve_displacements(const BalanceData& data,
                                                 const std::vector<Eigen::Matrix3d>& rotation,
                                                 bool shared) {
  const auto poses = static_cast<Eigen::Index>(data.poses.size());
  const int columns = shared ? 3 : 3 * data.legs;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(3 * poses, columns);
  Eigen::VectorXd b(3 * poses);
  const std::vector<Eigen::Vector3d> zero(static_cast<std::size_t>(data.legs),
                                          Eigen::Vector3d::Zero());
  for (Eigen::Index p = 0; p < poses; ++p) {
    // T_p at u = 0 is a_p; T_p = a_p − Σ_k [v_pk] u_k.
    b.segment<3>(3 * p) = residual_in_c(data, p, rotation, zero).tail<3>();
    const PoseTerms& pose = data.poses[static_cast<std::size_t>(p)];
    for (int k = 0; k < data.legs; ++k) {
      const auto ks = static_cast<std::size_t>(k);
      Eigen::Vector3d v = data.nominal_rotation[ks] * rotation[ks] * pose.force.col(k);
      if (data.target == BalanceTarget::thesis_literal) {
        v -= data.leg_weight[ks] * pose.down;
      }
      a.block<3, 3>(3 * p, shared ? 0 : 3 * k) -= skew(v);
    }
  }
  // a u + b = T: minimise |a u + b|.
  const Eigen::VectorXd u = a.colPivHouseholderQr().solve(-b);
  std::vector<Eigen::Vector3d> out(static_cast<std::size_t>(data.legs));
  for (int k = 0; k < data.legs; ++k) {
    out[static_cast<std::size_t>(k)] = u.segment<3>(shared ? 0 : 3 * k);
  }
  return out;
}

SolveResult solve_alternating(const BalanceData& data, MountingModel model,
                              const MountingOptions& options, const MountingStart& start) {
  const bool shared = shared_displacement(model);
  SolveResult result;
  result.rotation = start_rotations(data, model, start);
  result.displacement = start_displacements(data, start);
  if (!rotations_free(model)) {  // linear: one exact solve
    result.displacement = solve_displacements(data, result.rotation, shared);
    result.iterations = 1;
    result.converged = true;
    return result;
  }
  Blocks blocks(RotationParam::cayley, data.legs, shared);
  for (int k = 0; k < data.legs; ++k) {
    blocks.set_rotation(k, result.rotation[static_cast<std::size_t>(k)]);
  }
  ceres::Problem problem;
  add_poses(problem, data, blocks);
  for (int k = 0; k < (shared ? 1 : data.legs); ++k) {
    problem.SetParameterBlockConstant(blocks.displacement_block(k));
  }
  // The rotation step is solved to its own optimum each sweep: the sweeps' convergence is what
  // `tolerance` measures.
  const ceres::Solver::Options ceres_options = solver_options(200, 1e-15);
  for (int sweep = 1; sweep <= options.max_iterations; ++sweep) {
    const std::vector<Eigen::Vector3d> u = solve_displacements(data, result.rotation, shared);
    double change = 0.0;
    for (std::size_t k = 0; k < u.size(); ++k) {
      change = std::max(change, (u[k] - result.displacement[k]).lpNorm<Eigen::Infinity>());
    }
    result.displacement = u;
    blocks.set_displacement(u);
    const std::vector<double> before = blocks.rotation;
    ceres::Solver::Summary summary;
    ceres::Solve(ceres_options, &problem, &summary);
    check_usable(summary);
    for (std::size_t i = 0; i < before.size(); ++i) {
      change = std::max(change, std::abs(blocks.rotation[i] - before[i]));
    }
    for (int k = 0; k < data.legs; ++k) {
      result.rotation[static_cast<std::size_t>(k)] = blocks.get_rotation(k);
    }
    result.iterations = sweep;
    if (change < options.tolerance) {
      result.converged = true;
      break;
    }
  }
  return result;
}

SolveResult solve_joint(const BalanceData& data, MountingModel model,
                        const MountingOptions& options, const MountingStart& start) {
  const bool shared = shared_displacement(model);
  Blocks blocks(RotationParam::quaternion, data.legs, shared);
  const std::vector<Eigen::Matrix3d> r0 = start_rotations(data, model, start);
  for (int k = 0; k < data.legs; ++k) {
    blocks.set_rotation(k, r0[static_cast<std::size_t>(k)]);
  }
  blocks.set_displacement(start_displacements(data, start));
  ceres::Problem problem;
  add_poses(problem, data, blocks);
  for (int k = 0; k < data.legs; ++k) {
    problem.SetManifold(blocks.rotation_block(k), new ceres::EigenQuaternionManifold);
    if (!rotations_free(model)) {
      problem.SetParameterBlockConstant(blocks.rotation_block(k));
    }
  }
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options(options.max_iterations, options.tolerance), &problem, &summary);
  check_usable(summary);
  SolveResult result;
  for (int k = 0; k < data.legs; ++k) {
    result.rotation.push_back(blocks.get_rotation(k));
  }
  result.displacement = blocks.get_displacement(data.legs);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;  // iteration 0 is the start
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  return result;
}

namespace {

/// The weighted residuals (6P: [F; √κ T] per pose) and their Jacobian in the free parameters (the
/// rotation vectors θ_k of R̃_k where the model frees them, then u_k or the shared u).
struct Linearisation {
  Eigen::MatrixXd jacobian;
  std::vector<double> residual;
};

Linearisation linearise(const BalanceData& data, MountingModel model,
                        const std::vector<Eigen::Matrix3d>& rotation,
                        const std::vector<Eigen::Vector3d>& displacement) {
  const int legs = data.legs;
  const bool shared = shared_displacement(model);
  const bool free_rotations = rotations_free(model);
  Blocks blocks(RotationParam::rotation_vector, legs, shared);
  for (int k = 0; k < legs; ++k) {
    blocks.set_rotation(k, rotation[static_cast<std::size_t>(k)]);
  }
  blocks.set_displacement(displacement);
  ceres::Problem problem;
  add_poses(problem, data, blocks);
  ceres::Problem::EvaluateOptions evaluate;
  for (int k = 0; k < legs; ++k) {
    if (free_rotations) {
      evaluate.parameter_blocks.push_back(blocks.rotation_block(k));
    } else {  // blocks left out of the Jacobian must be constant
      problem.SetParameterBlockConstant(blocks.rotation_block(k));
    }
  }
  for (int k = 0; k < (shared ? 1 : legs); ++k) {
    evaluate.parameter_blocks.push_back(blocks.displacement_block(k));
  }
  Linearisation out;
  ceres::CRSMatrix crs;
  double cost = 0.0;
  problem.Evaluate(evaluate, &cost, &out.residual, nullptr, &crs);
  out.jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row) {
    for (int i = crs.rows[static_cast<std::size_t>(row)];
         i < crs.rows[static_cast<std::size_t>(row) + 1]; ++i) {
      out.jacobian(row, crs.cols[static_cast<std::size_t>(i)]) =
          crs.values[static_cast<std::size_t>(i)];
    }
  }
  return out;
}

/// β D and β c of the errors-in-variables term 2Pκσ² Σ_k |c_k|² (half its Hessian and gradient),
/// over the free parameters (zero on the rotations).
struct NoiseTerm {
  Eigen::VectorXd diagonal;
  Eigen::VectorXd gradient;
};

NoiseTerm noise_term(const BalanceData& data, MountingModel model,
                     const std::vector<Eigen::Vector3d>& displacement, double variance,
                     Eigen::Index parameters) {
  const double beta =
      2.0 * static_cast<double>(data.poses.size()) * data.sqrt_kappa * data.sqrt_kappa * variance;
  NoiseTerm term{Eigen::VectorXd::Zero(parameters), Eigen::VectorXd::Zero(parameters)};
  const bool shared = shared_displacement(model);
  const Eigen::Index first = parameters - (shared ? 3 : 3 * Eigen::Index{data.legs});
  for (int k = 0; k < data.legs; ++k) {
    const Eigen::Index at = first + (shared ? 0 : 3 * Eigen::Index{k});
    const auto ks = static_cast<std::size_t>(k);
    term.diagonal.segment<3>(at).array() += beta;
    term.gradient.segment<3>(at) += beta * (data.nominal_position[ks] + displacement[ks]);
  }
  return term;
}

}  // namespace

double estimate_force_noise_variance(const BalanceData& data, const SolveResult& fit, int dof) {
  double sum = 0.0;
  for (std::size_t p = 0; p < data.poses.size(); ++p) {
    sum += residual_in_c(data, static_cast<Eigen::Index>(p), fit.rotation, fit.displacement)
               .head<3>()
               .squaredNorm();
  }
  // tr Σ_FF = 3 K σ² for K transducers of equal isotropic noise.
  return sum / (static_cast<double>(data.poses.size()) - dof / 6.0) / (3.0 * data.legs);
}

bool correct_errors_in_variables(const BalanceData& data, MountingModel model, double variance,
                                 SolveResult& fit) {
  const bool free_rotations = rotations_free(model);
  const SolveResult plain = fit;
  for (int step = 0; step < 50; ++step) {
    const Linearisation lin = linearise(data, model, fit.rotation, fit.displacement);
    const NoiseTerm noise =
        noise_term(data, model, fit.displacement, variance, lin.jacobian.cols());
    const Eigen::Map<const Eigen::VectorXd> r(lin.residual.data(),
                                              static_cast<Eigen::Index>(lin.residual.size()));
    Eigen::MatrixXd hessian = lin.jacobian.transpose() * lin.jacobian;
    hessian.diagonal() -= noise.diagonal;
    const Eigen::VectorXd gradient = lin.jacobian.transpose() * r - noise.gradient;
    // The corrected score has a minimum only where its Hessian is positive definite: a noise
    // variance that is large against the forces' spread across poses (σ_f of ~1 N on BigANT)
    // makes it fall without bound along the weakly determined directions. There the correction
    // is undefined and the plain fit stands.
    const Eigen::LLT<Eigen::MatrixXd> llt(hessian);
    if (llt.info() != Eigen::Success) {
      fit = plain;
      return false;
    }
    const Eigen::VectorXd delta = -llt.solve(gradient);
    if (!delta.allFinite()) {
      fit = plain;
      return false;
    }
    Eigen::Index at = 0;
    if (free_rotations) {
      for (auto& rotation : fit.rotation) {
        rotation =
            rotation_from_vector(calibration::rotation_vector(rotation) + delta.segment<3>(at));
        at += 3;
      }
    }
    const bool shared = shared_displacement(model);
    for (std::size_t k = 0; k < fit.displacement.size(); ++k) {
      fit.displacement[k] += delta.segment<3>(at + (shared ? 0 : 3 * static_cast<Eigen::Index>(k)));
    }
    // Parameters are metres and radians of order 0.01–1: 1e-12 is round-off of the solve.
    if (delta.lpNorm<Eigen::Infinity>() < 1e-12) {
      return true;
    }
  }
  fit = plain;
  return false;
}

void standard_errors(const BalanceData& data, MountingEstimate& estimate) {
  const int legs = data.legs;
  const bool shared = shared_displacement(estimate.model);
  const bool free_rotations = rotations_free(estimate.model);
  const Linearisation lin =
      linearise(data, estimate.model, estimate.rotation, estimate.displacement);
  const Eigen::MatrixXd& jacobian = lin.jacobian;
  const std::vector<double>& residuals = lin.residual;
  const auto poses = static_cast<Eigen::Index>(data.poses.size());
  const Eigen::Map<const Eigen::MatrixXd> weighted(residuals.data(), 6,
                                                   poses);  // K^{1/2} e_p per column
  const Eigen::Matrix<double, 6, 6> sigma =
      weighted * weighted.transpose() / (static_cast<double>(poses) - estimate.dof / 6.0);
  Eigen::MatrixXd hessian = jacobian.transpose() * jacobian;
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(hessian.rows(), hessian.cols());
  for (Eigen::Index p = 0; p < poses; ++p) {
    const auto jp = jacobian.middleRows(6 * p, 6);
    meat.noalias() += jp.transpose() * sigma * jp;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(hessian);
  estimate.smallest_singular_value = std::sqrt(std::max(eigen.eigenvalues().minCoeff(), 0.0));
  if (estimate.force_noise_variance > 0.0) {  // the corrected objective's curvature
    hessian.diagonal() -= noise_term(data, estimate.model, estimate.displacement,
                                     estimate.force_noise_variance, hessian.cols())
                              .diagonal;
  }
  const Eigen::MatrixXd bread = hessian.completeOrthogonalDecomposition().pseudoInverse();
  const Eigen::MatrixXd covariance = bread * meat * bread;
  const Eigen::VectorXd se = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  estimate.rotation_se.assign(static_cast<std::size_t>(legs), Eigen::Vector3d::Zero());
  estimate.displacement_se.assign(static_cast<std::size_t>(legs), Eigen::Vector3d::Zero());
  Eigen::Index column = 0;
  if (free_rotations) {
    for (int k = 0; k < legs; ++k, column += 3) {
      estimate.rotation_se[static_cast<std::size_t>(k)] = se.segment<3>(column);
    }
  }
  for (int k = 0; k < legs; ++k) {
    estimate.displacement_se[static_cast<std::size_t>(k)] =
        se.segment<3>(column + (shared ? 0 : 3 * k));
  }
}

}  // namespace slipwalk::calibration::standing_detail
