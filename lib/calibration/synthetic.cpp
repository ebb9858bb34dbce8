// The synthetic BigANT of synthetic.hpp. Every reading is computed from the physics of a rigid
// chassis, six rigid legs and the floor; none from the calibration's model equations. The choices:
//
// ---- Nominal geometry (what the calibration is told) --------------------------------------------
// Legs and crank pivots of robots::bigant_legs() (HL ML FL HR MR FR; pivots at z = 0). Transducer
// k's nominal origin sits kTransducerHeight = 4 cm above its crank pivot; the left transducers'
// axes are the body axes, the right ones are turned by π about z (a mirrored mounting), so the
// nominal frames are not all the identity. G_robot = 8.18 kg · 9.81 m/s² = 80.2458 N (§4.1.1).
//
// ---- The leg (its centre of mass r_k(φ)) --------------------------------------------------------
// The leg module hangs on its transducer: its points are fixed in the TRUE transducer frame. In
// the nominal layout they are, relative to the crank pivot in body axes, the four-bar's points in
// the xz-plane (robots/four_bar.hpp; θ = θ₀ − 2πφ) and a motor part off that plane; in the
// transducer frame x_ft = R_N,kᵀ (x − (0, 0, kTransducerHeight)). The weight is shared
// (kLegMassShares):
//   motor/gearbox/bracket 50 %, a point at (0, ∓3.5 cm inboard, +2 cm) — fixed;
//   crank 8 % (bar O₂A), coupler 12 % (bar AB), toe 18 % (bar AP), rocker 12 % (bar O₄B),
// each bar uniform, so its centroid is its midpoint. r_k(φ) is the share-weighted mean of those
// centroids: it moves ≈ 2–3 cm over a turn in the leg's plane, its lateral coordinate constant.
//
// ---- The truth
// ----------------------------------------------------------------------------------- Offsets w_o:
// Table 4.1's printed estimates (force rows x y z, torque rows x y z; columns HL ML FL HR MR FR).
// Weights 6.2 6.2 6.2 6.1 6.2 6.4 N (Table 4.1). Chassis CoM c_B = (0.045, −0.037, 0.02) m: G_ch
// = 80.2458 − 37.3 = 42.9458 N and |c_B,xy| G_ch = 2.502 N·m, the "2.5 N·m bias" of §4.5. Mounting
// errors R̃_k = exp([θ_k]), θ_k ~ N(0, mounting_rotation² I), p̃_k ~ N(0, mounting_translation² I),
// drawn per transducer.
//
// ---- Random streams
// ------------------------------------------------------------------------------ Three
// std::mt19937_64 streams seeded by SplitMix64(seed ⊕ stream tag): truth (mounting errors), hanging
// (the four misalignments, then the readings' noise record by record), poses (a full Fisher–Yates
// shuffle of the 729 combinations, then per pose a fixed number of draws: tilt 2, heading 1,
// internal forces 3K, attitude noise 3, reading noise 6K). So the truth does not depend on `poses`,
// `cycles` or any noise; P poses are the first P of 729; the noise is drawn whatever noise_scale
// is. Normal deviates by Box–Muller on 53-bit uniforms (no std:: distributions).
//
// ---- Hanging
// ------------------------------------------------------------------------------------- Record "a"
// (a ∈ +x, −x, +z, −z): gravity along d = exp([s_a]) a in body axes, s_a ~ N(0,
// hanging_misalignment² I), constant over the record (the robot hangs still; all transducers see
// the same d). Transducer k reads w = [m_k g u; r_k(φ) × m_k g u] + w_o + n with u = R_kᵀ d,
// R_k = R_N,k R̃_k: the leg's gravity is the only load on the leg besides the transducer, so the
// leg applies exactly its gravity wrench to the chassis (eq. 4.4 and its companions).
//
// ---- Standing (the exact equilibrium) -----------------------------------------------------------
// Attitude R^W_C = exp([t]) Rz(ψ): the floor tilted by t = (t_x, t_y, 0), t ~ N(0, floor_tilt²),
// the robot under heading ψ ~ U[0, 2π), its body parallel to the floor (floor normal = body z).
// Gravity in body axes: d = R^W_Cᵀ (0, 0, −1); its up direction a = −d. The loads on the whole
// robot: G_ch d at c_B, m_k g d at x_k = T_k r_k(φ_k), and the ground forces F_j at the toes
// q_j = T_j ρ_j(φ_j) (T_k the true transducer frames). Particular solution: every foot pushes
// along a, F_j = λ_j a — the loads of equal vertical springs under the robot, the least-squares
// distribution —: Σλ_j = G_robot and (Σλ_j q_j − M) × a = 0 with M = G_ch c_B + Σ m_k g x_k,
// i.e. the components of Σλ_j q_j − M along two unit vectors ⊥ a vanish: 3 linear equations,
// λ their minimum-norm solution. Each such F_j lies inside the cone |t| ≤ tan(tilt) N. Then a
// self-equilibrated set: z ~ N(0, (internal_force G_robot / K)² I) in R^{3K}, projected on the null
// space of A = [I … I; [q_1] … [q_K]] (A F = total ground wrench about B), z − Aᵀ(AAᵀ)⁻¹A z, and
// halved until every normal load is ≥ half its particular value and every foot within 0.9 μ of
// its cone (μ = 1). The whole robot is then exactly at rest (to rounding). Leg k's free body: the
// transducer's pull, its gravity and F_k balance, so it applies to the chassis its gravity wrench
// plus F_k at its toe: w = [m_k g u + f; r_k × m_k g u + ρ_k × f] + w_o + n, f = R_kᵀ F_k.
// Oracle (tests/calibration/test_synthetic.cpp): Σ_k transform(T_k in C, w_k − w_o) + [G_ch d; 0]
// = 0 — the chassis' balance with the true frames, an independent statement of the equilibrium.
// The recorded attitude is R^W_C exp([η]), η ~ N(0, (noise_scale · attitude_noise)² I).
#include "calibration/synthetic.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "core/error.hpp"
#include "robots/four_bar.hpp"

namespace slipwalk::calibration {

namespace {

constexpr int kCombinations = 729;  // 3⁶ shaft-angle combinations of §4.1.2.1
constexpr double kPoseStep = 0.1;   // turns: 36° of shaft angle
constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Table 4.1: force rows x y z (N), torque rows x y z (N·m); columns HL ML FL HR MR FR.
constexpr std::array<std::array<double, 6>, 6> kTable41Offsets = {{
    {1.47, 1.419, 0.57, -8.49, -0.06, -0.93},
    {-1.30, -4.884, 3.71, -1.448, -0.123, 0.653},
    {-5.61, -0.406, -2.039, -2.43, -0.07, -2.183},
    {0.2457, -0.0136, 0.2176, -0.3159, -0.2392, -0.3611},
    {0.002, 0.0808, 0.0921, 0.3449, -0.0982, -0.153},
    {0.034, 0.0144, -0.0177, 0.001, 0.004, 0.0222},
}};
constexpr std::array<double, 6> kTable41Weights = {6.2, 6.2, 6.2, 6.1, 6.2, 6.4};
constexpr std::array<double, 3> kChassisCom = {0.045, -0.037, 0.02};

enum class Stream : std::uint64_t { truth = 1, hanging = 2, poses = 3 };

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30U)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27U)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31U);
}

/// A seeded stream of uniform and standard normal deviates, the same on every platform.
class Draws {
 public:
  Draws(std::uint64_t seed, Stream stream)
      : engine_(splitmix64(seed ^ (static_cast<std::uint64_t>(stream) * 0xD1B54A32D192ED03ULL))) {}

  double uniform() { return static_cast<double>(engine_() >> 11U) * 0x1.0p-53; }  // [0, 1)

  double normal() {  // Box–Muller, both deviates used
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(kTwoPi * u2);
    has_spare_ = true;
    return r * std::cos(kTwoPi * u2);
  }

  Eigen::Vector3d normal3(double sigma) {
    const double x = normal();
    const double y = normal();
    const double z = normal();
    return sigma * Eigen::Vector3d(x, y, z);
  }

  /// An integer in [0, n) by the 53-bit uniform (bias below 2⁻⁴³ for n ≤ 729).
  int below(int n) { return static_cast<int>(uniform() * static_cast<double>(n)); }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

void check_range(double value, double lo, double hi, bool hi_open, const char* field,
                 const char* what) {
  const bool ok = std::isfinite(value) && value >= lo && (hi_open ? value < hi : value <= hi);
  if (!ok) {
    throw core::InputError(std::string("synth.") + field,
                           std::string(what) + ", got " + std::to_string(value));
  }
}

/// The leg's centre of mass and toe in its transducer frame at a linkage pose (synthetic.cpp's
/// head): the points relative to the crank pivot in body axes, then R_N,kᵀ (x − (0, 0, h)).
struct LegPoints {
  Eigen::Vector3d com;
  Eigen::Vector3d toe;
};

LegPoints leg_points(const SyntheticTruth& truth, int leg, const robots::FourBarPose& pose) {
  const LegMassShares& s = kLegMassShares;
  const Eigen::Vector2d& o4 = truth.bigant.linkage.rocker_pivot;
  // The bars' centroids are their midpoints; the crank's O₂ is the origin.
  const Eigen::Vector2d planar = s.crank * 0.5 * pose.A + s.coupler * 0.5 * (pose.A + pose.B) +
                                 s.toe * 0.5 * (pose.A + pose.P) + s.rocker * 0.5 * (o4 + pose.B);
  const double inboard = truth.bigant.pivot(1, leg) > 0.0 ? -kMotorInboard : kMotorInboard;
  const Eigen::Vector3d motor(0.0, inboard, kMotorHeight);
  const double total = s.motor + s.crank + s.coupler + s.toe + s.rocker;
  const Eigen::Vector3d com_body =
      (s.motor * motor + Eigen::Vector3d(planar.x(), 0.0, planar.y())) / total;
  const Eigen::Vector3d up(0.0, 0.0, kTransducerHeight);
  const Eigen::Matrix3d& rn = truth.geometry.transducer[static_cast<std::size_t>(leg)].R;
  return {rn.transpose() * (com_body - up),
          rn.transpose() * (Eigen::Vector3d(pose.P.x(), 0.0, pose.P.y()) - up)};
}

robots::FourBarPose linkage_pose(const SyntheticTruth& truth, double phi) {
  return robots::four_bar_pose(truth.bigant.linkage, robots::kBigAntCrankPhase - kTwoPi * phi);
}

void check_leg(const SyntheticTruth& truth, int leg) {
  if (leg < 0 || leg >= truth.legs()) {
    throw core::InputError("leg", "index " + std::to_string(leg) + " outside [0, " +
                                      std::to_string(truth.legs()) + ")");
  }
}

/// The reading without noise from precomputed parts (transducer frame): gravity force f_g,
/// foot force f at the toe.
Wrench reading(const LegPoints& points, const Eigen::Vector3d& f_g, const Eigen::Vector3d& f,
               const Wrench& offset) {
  Wrench w;
  w.head<3>() = f_g + f;
  w.tail<3>() = points.com.cross(f_g) + points.toe.cross(f);
  return w + offset;
}

constexpr std::array<BodyAxis, 4> kHangingAxes = {BodyAxis::plus_x, BodyAxis::minus_x,
                                                  BodyAxis::plus_z, BodyAxis::minus_z};

/// The first draws of the hanging stream: each record's gravity direction in body axes.
std::vector<Eigen::Vector3d> hanging_gravity(Draws& draws, const SynthOptions& options) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(kHangingAxes.size());
  for (const BodyAxis axis : kHangingAxes) {
    out.push_back(rotation_from_vector(draws.normal3(options.hanging_misalignment)) *
                  axis_vector(axis));
  }
  return out;
}

}  // namespace

void validate(const SynthOptions& o) {
  if (o.cycles < 1 || o.cycles > 100) {
    throw core::InputError("synth.cycles", "must be in [1, 100], got " + std::to_string(o.cycles));
  }
  if (o.samples_per_cycle < 8 || o.samples_per_cycle > 100000) {
    throw core::InputError("synth.samples_per_cycle",
                           "must be in [8, 100000], got " + std::to_string(o.samples_per_cycle));
  }
  if (static_cast<long>(o.cycles) * o.samples_per_cycle > kMaxHangingSamples) {
    throw core::InputError(
        "synth.samples_per_cycle",
        "cycles × samples per cycle must be at most " + std::to_string(kMaxHangingSamples));
  }
  if (o.poses < 1 || o.poses > kCombinations) {
    throw core::InputError("synth.poses", "must be in [1, 729], got " + std::to_string(o.poses));
  }
  constexpr double kHuge = 1e300;
  check_range(o.noise_scale, 0.0, kHuge, false, "noise_scale", "must be finite and ≥ 0");
  check_range(o.hanging_force_noise, 0.0, kHuge, false, "hanging_force_noise",
              "must be finite and ≥ 0 (N)");
  check_range(o.hanging_torque_noise, 0.0, kHuge, false, "hanging_torque_noise",
              "must be finite and ≥ 0 (N·m)");
  check_range(o.pose_force_noise, 0.0, kHuge, false, "pose_force_noise",
              "must be finite and ≥ 0 (N)");
  check_range(o.pose_torque_noise, 0.0, kHuge, false, "pose_torque_noise",
              "must be finite and ≥ 0 (N·m)");
  check_range(o.hanging_misalignment, 0.0, 0.3, true, "hanging_misalignment",
              "must be in [0, 0.3) rad");
  check_range(o.attitude_noise, 0.0, 0.3, true, "attitude_noise", "must be in [0, 0.3) rad");
  check_range(o.floor_tilt, 0.0, 0.3, true, "floor_tilt", "must be in [0, 0.3) rad");
  check_range(o.mounting_rotation, 0.0, 0.3, true, "mounting_rotation", "must be in [0, 0.3) rad");
  check_range(o.internal_force, 0.0, 1.0, false, "internal_force", "must be in [0, 1]");
  check_range(o.mounting_translation, 0.0, 0.05, true, "mounting_translation",
              "must be in [0, 0.05) m");
}

Eigen::Vector3d SyntheticTruth::leg_com(int leg, double phi) const {
  check_leg(*this, leg);
  return leg_points(*this, leg, linkage_pose(*this, phi)).com;
}

Eigen::Vector3d SyntheticTruth::toe(int leg, double phi) const {
  check_leg(*this, leg);
  return leg_points(*this, leg, linkage_pose(*this, phi)).toe;
}

Frame SyntheticTruth::transducer_frame(int leg) const {
  check_leg(*this, leg);
  const auto k = static_cast<std::size_t>(leg);
  return geometry.transducer[k] * Frame{mounting_rotation[k], mounting_translation[k]};
}

Eigen::Vector3d SyntheticTruth::displacement(int leg) const {
  check_leg(*this, leg);
  const auto k = static_cast<std::size_t>(leg);
  return geometry.transducer[k].R * mounting_translation[k] - chassis_com;
}

double SyntheticTruth::chassis_weight() const {
  double legs_weight = 0.0;
  for (const double w : weight) {
    legs_weight += w;
  }
  return geometry.robot_weight - legs_weight;
}

double SyntheticTruth::com_torque_bias() const {
  return chassis_com.head<2>().norm() * chassis_weight();
}

SyntheticTruth synthetic_truth(const SynthOptions& options) {
  validate(options);
  SyntheticTruth truth;
  truth.bigant = robots::bigant_legs();
  const int n = static_cast<int>(truth.bigant.names.size());
  truth.geometry.legs = truth.bigant.names;
  truth.geometry.robot_weight = robots::kBigAntMass * robots::kGravity;
  const Eigen::Matrix3d mirrored =
      Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Draws draws(options.seed, Stream::truth);
  for (int k = 0; k < n; ++k) {
    const bool left = truth.bigant.pivot(1, k) > 0.0;
    Frame nominal;
    nominal.R = left ? Eigen::Matrix3d::Identity() : mirrored;
    nominal.p = truth.bigant.pivot.col(k) + Eigen::Vector3d(0.0, 0.0, kTransducerHeight);
    truth.geometry.transducer.push_back(nominal);
    Wrench offset;
    for (int r = 0; r < 6; ++r) {
      offset(r) = kTable41Offsets.at(static_cast<std::size_t>(r)).at(static_cast<std::size_t>(k));
    }
    truth.offset.push_back(offset);
    truth.weight.push_back(kTable41Weights.at(static_cast<std::size_t>(k)));
  }
  for (int k = 0; k < n; ++k) {
    truth.mounting_rotation.push_back(
        rotation_from_vector(draws.normal3(options.mounting_rotation)));
  }
  for (int k = 0; k < n; ++k) {
    truth.mounting_translation.push_back(draws.normal3(options.mounting_translation));
  }
  truth.chassis_com = Eigen::Vector3d(kChassisCom[0], kChassisCom[1], kChassisCom[2]);
  validate(truth.geometry);
  return truth;
}

std::vector<Eigen::Vector3d> synthetic_hanging_gravity(const SynthOptions& options) {
  validate(options);
  Draws draws(options.seed, Stream::hanging);
  return hanging_gravity(draws, options);
}

std::vector<HangingRecord> synthetic_hanging(const SyntheticTruth& truth,
                                             const SynthOptions& options) {
  validate(options);
  Draws draws(options.seed, Stream::hanging);
  const std::vector<Eigen::Vector3d> gravity = hanging_gravity(draws, options);
  const int legs = truth.legs();
  const Eigen::Index n = static_cast<Eigen::Index>(options.cycles) * options.samples_per_cycle;
  const double sf = options.noise_scale * options.hanging_force_noise;
  const double st = options.noise_scale * options.hanging_torque_noise;
  // The linkage pose depends only on φ, the same for every leg and record: compute it once.
  std::vector<robots::FourBarPose> poses;
  poses.reserve(static_cast<std::size_t>(options.samples_per_cycle));
  for (int i = 0; i < options.samples_per_cycle; ++i) {
    poses.push_back(linkage_pose(truth, static_cast<double>(i) / options.samples_per_cycle));
  }
  std::vector<HangingRecord> records;
  for (std::size_t r = 0; r < kHangingAxes.size(); ++r) {
    HangingRecord rec;
    rec.down = kHangingAxes.at(r);
    rec.source = "synthetic hanging " + std::string(axis_label(rec.down)) + " (seed " +
                 std::to_string(options.seed) + ")";
    rec.phi.resize(n, legs);
    rec.wrench.resize(n, 6 * static_cast<Eigen::Index>(legs));
    std::vector<Eigen::Vector3d> f_g;
    for (int k = 0; k < legs; ++k) {
      const Eigen::Matrix3d rk = truth.transducer_frame(k).R;
      f_g.push_back(truth.weight[static_cast<std::size_t>(k)] * (rk.transpose() * gravity[r]));
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      const double phi = static_cast<double>(i) / options.samples_per_cycle;
      const auto& pose = poses[static_cast<std::size_t>(i % options.samples_per_cycle)];
      for (int k = 0; k < legs; ++k) {
        const auto ks = static_cast<std::size_t>(k);
        rec.phi(i, k) = phi;
        Wrench w =
            reading(leg_points(truth, k, pose), f_g[ks], Eigen::Vector3d::Zero(), truth.offset[ks]);
        w.head<3>() += draws.normal3(sf);
        w.tail<3>() += draws.normal3(st);
        rec.wrench.block<1, 6>(i, 6 * static_cast<Eigen::Index>(k)) = w.transpose();
      }
    }
    records.push_back(std::move(rec));
  }
  return records;
}

SyntheticStanding synthetic_standing(const SyntheticTruth& truth, const SynthOptions& options) {
  validate(options);
  const int legs = truth.legs();
  if (legs != robots::kBigAntLegs) {
    throw core::InputError("synth.legs", "the standing poses are the 3⁶ combinations of six legs");
  }
  Draws draws(options.seed, Stream::poses);
  std::array<int, kCombinations> order{};
  for (int c = 0; c < kCombinations; ++c) {
    order.at(static_cast<std::size_t>(c)) = c;
  }
  for (int c = kCombinations - 1; c > 0; --c) {  // Fisher–Yates, every draw made
    std::swap(order.at(static_cast<std::size_t>(c)),
              order.at(static_cast<std::size_t>(draws.below(c + 1))));
  }
  const double g_robot = truth.geometry.robot_weight;
  const double g_chassis = truth.chassis_weight();
  const double mean_load = g_robot / legs;
  const Eigen::Index p_count = options.poses;
  SyntheticStanding out;
  out.poses.phi.resize(p_count, legs);
  out.poses.wrench.resize(p_count, 6 * static_cast<Eigen::Index>(legs));
  out.poses.source = "synthetic poses (seed " + std::to_string(options.seed) + ")";
  std::vector<Frame> frames;
  frames.reserve(static_cast<std::size_t>(legs));
  for (int k = 0; k < legs; ++k) {
    frames.push_back(truth.transducer_frame(k));
  }
  for (Eigen::Index p = 0; p < p_count; ++p) {
    int code = order.at(static_cast<std::size_t>(p));
    for (int k = 0; k < legs; ++k) {
      out.poses.phi(p, k) = kPoseStep * static_cast<double>(code % 3 - 1);
      code /= 3;
    }
    const double tx = options.floor_tilt * draws.normal();
    const double ty = options.floor_tilt * draws.normal();
    const double heading = kTwoPi * draws.uniform();
    const Eigen::Matrix3d attitude =
        rotation_from_vector(Eigen::Vector3d(tx, ty, 0.0)) *
        Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d down = attitude.transpose() * Eigen::Vector3d(0.0, 0.0, -1.0);
    const Eigen::Vector3d up = -down;

    // The legs' points in B and the weight moment M (synthetic.cpp's head).
    std::vector<LegPoints> points;
    Eigen::Matrix3Xd toe(3, legs);
    Eigen::Vector3d moment = g_chassis * truth.chassis_com;
    for (int k = 0; k < legs; ++k) {
      const auto ks = static_cast<std::size_t>(k);
      points.push_back(leg_points(truth, k, linkage_pose(truth, out.poses.phi(p, k))));
      toe.col(k) = frames[ks] * points[ks].toe;
      moment += truth.weight[ks] * (frames[ks] * points[ks].com);
    }
    // Particular solution F_j = λ_j a: Σλ = G, (Σλ q − M)·e_i = 0 for e₁, e₂ ⊥ a.
    const Eigen::Vector3d e1 = up.unitOrthogonal();
    const Eigen::Vector3d e2 = up.cross(e1);
    Eigen::Matrix<double, 3, Eigen::Dynamic> m(3, legs);
    m.row(0).setOnes();
    m.row(1) = e1.transpose() * toe;
    m.row(2) = e2.transpose() * toe;
    const Eigen::Vector3d rhs(g_robot, e1.dot(moment), e2.dot(moment));
    const Eigen::VectorXd lambda = m.transpose() * (m * m.transpose()).ldlt().solve(rhs);
    Eigen::Matrix3Xd force = up * lambda.transpose();

    // A self-equilibrated set: the projection of a random z on the null space of A.
    Eigen::MatrixXd a(6, 3 * legs);
    for (int k = 0; k < legs; ++k) {
      a.block<3, 3>(0, 3 * static_cast<Eigen::Index>(k)).setIdentity();
      a.block<3, 3>(3, 3 * static_cast<Eigen::Index>(k)) = skew(toe.col(k));
    }
    Eigen::VectorXd z(3 * legs);
    for (int k = 0; k < legs; ++k) {
      z.segment<3>(3 * static_cast<Eigen::Index>(k)) =
          draws.normal3(options.internal_force * mean_load);
    }
    z -= a.transpose() * (a * a.transpose()).ldlt().solve(a * z);
    // Admissible: every normal load at least half its particular value, every foot within
    // 0.9 μ of its cone. The particular solution itself must be (λ > 0, tilt < atan 0.9).
    const Eigen::VectorXd base_normal = force.row(2).transpose();  // the floor normal is body z
    const auto admissible = [&](const Eigen::Matrix3Xd& f) {
      for (int k = 0; k < legs; ++k) {
        const double normal = f(2, k);
        if (!(normal >= 0.5 * base_normal(k)) ||
            f.col(k).head<2>().norm() > 0.9 * kFrictionCoefficient * normal) {
          return false;
        }
      }
      return true;
    };
    if (base_normal.minCoeff() <= 0.0 || !admissible(force)) {
      throw core::ComputationError("synthetic pose " + std::to_string(p) +
                                   ": the feet cannot hold the robot within the friction cone "
                                   "(floor tilt " +
                                   std::to_string(std::hypot(tx, ty)) + " rad)");
    }
    double scale = 1.0;
    Eigen::Matrix3Xd trial = force + scale * z.reshaped(3, legs);
    for (int halving = 0; halving < 30 && !admissible(trial); ++halving) {
      scale *= 0.5;
      trial = force + scale * z.reshaped(3, legs);
    }
    if (admissible(trial)) {
      force = trial;
    }

    // The readings.
    const Eigen::Vector3d eta = draws.normal3(options.noise_scale * options.attitude_noise);
    for (int k = 0; k < legs; ++k) {
      const auto ks = static_cast<std::size_t>(k);
      const Eigen::Matrix3d& rk = frames[ks].R;
      Wrench w = reading(points[ks], truth.weight[ks] * (rk.transpose() * down),
                         rk.transpose() * force.col(k), truth.offset[ks]);
      w.head<3>() += draws.normal3(options.noise_scale * options.pose_force_noise);
      w.tail<3>() += draws.normal3(options.noise_scale * options.pose_torque_noise);
      out.poses.wrench.block<1, 6>(p, 6 * static_cast<Eigen::Index>(k)) = w.transpose();
    }
    out.poses.attitude.push_back(attitude * rotation_from_vector(eta));
    out.attitude.push_back(attitude);
    out.foot_force.push_back(force);
    out.toe.push_back(toe);
  }
  return out;
}

StandingPoses synthetic_poses(const SyntheticTruth& truth, const SynthOptions& options) {
  return synthetic_standing(truth, options).poses;
}

Wrench true_reading(const SyntheticTruth& truth, int leg, double phi, const Eigen::Vector3d& down,
                    const Eigen::Vector3d& foot_force) {
  check_leg(truth, leg);
  const auto k = static_cast<std::size_t>(leg);
  const Eigen::Matrix3d rk = truth.transducer_frame(leg).R;
  return reading(leg_points(truth, leg, linkage_pose(truth, phi)),
                 truth.weight[k] * (rk.transpose() * down), rk.transpose() * foot_force,
                 truth.offset[k]);
}

}  // namespace slipwalk::calibration
