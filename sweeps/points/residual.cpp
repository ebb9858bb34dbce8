// Point kinds of the residual transfer, thesis §5.3: the Multipod walking the §5.3.2 gait in
// MuJoCo (the "real" robot: legs of unequal stiffness and friction, mounting errors;
// peers/mujoco/multipod_spec.hpp), the template model along its trials (residual/template.hpp)
// and the constant residual B of §5.3.1 fitted to them (residual/fit.hpp).
//
//   multipod_trial      one MuJoCo trial; a row per recorded sample (t, pose, measured joints).
//                       The sweep's CSV is a multi-trial file for `slipwalk residual fit` (grouped
//                       by id, residual/trial.hpp).
//   residual_transfer   B fitted on training trials (train_frequency, train_dphi_pi), evaluated
//                       along one test trial (test_frequency, test_dphi_pi); a row per test
//                       snapshot: measured v_true, template v_model = A(q) q̇, v_fit = (A(q) + B) q̇
//                       (Figs. 5.5, 5.6).
//   residual_errors     the same fit; one row: RMSE of v − v_true on the training and the test
//                       snapshots, means over the test snapshots (the drift), the fit's rank,
//                       conditioning and λ, ‖B‖_F.
//   residual_training   the training-set size curve (§5.3.2: "the validation error stopped
//                       decreasing" at four trials): k trials drawn without replacement from the
//                       26-grid less the validation trials, `draws` times; a row per draw with the
//                       RMSE on the held-out validation trials.
//
// Shared parameters (defaults): cycles = 8 (recorded, thesis 8–10), skip_cycles = 1 (the first
// recorded cycle's snapshots are a transient, dropped from fits and errors), seed = 1 and
// asymmetry = 1 (peers::mujoco::draw_asymmetry's seed and scale; 0 = the symmetric MuJoCo robot),
// settle = 0.5 s, timestep = 0.001 s, sample_rate = 125 Hz (the thesis' motion capture). The
// robot has 8 legs (4 modules), the thesis' robot for §5.3.
//
// Estimators: "pinv" (the thesis' Moore–Penrose inverse, residual::fit_residual) or "ridge"
// (residual::fit_residual_ridge with λ chosen by leave-one-trial-out cross-validation,
// residual::validate_ridge, over λ ∈ {0} ∪ {σ²_max · 10^k, k = −12 … 3}, σ_max the largest
// singular value of the training q̇ matrix: a grid that scales with the data, from the
// pseudo-inverse (λ = 0) to B ≈ 0 (λ = 1000 σ²_max shrinks every direction by at least 1000), so
// the cross-validated choice can be either end: the thesis' fit or no residual at all).
//
// Trials come from a process-wide cache (residual.hpp): a trial is recorded once per process
// whichever kinds and sweeps ask for it. Without MuJoCo every point fails and says why.
#include "sweeps/points/residual.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstddef>
#include <future>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "peers/mujoco/multipod_spec.hpp"
#include "residual/fit.hpp"
#include "residual/template.hpp"
#include "residual/trial.hpp"
#include "robots/robots.hpp"
#include "sweeps/engine/once_cache.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"
#ifdef SLIPWALK_HAVE_MUJOCO
#include "peers/mujoco/multipod_peer.hpp"
#endif

namespace slipwalk::sweeps::points {

// --- the trial cache ----------------------------------------------------------------------------

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The thesis' Multipod for §5.3: 8 legs, 4 modules. The trial rows' joint columns are sized
/// for it.
constexpr int kLegs = 8;
constexpr int kModules = kLegs / 2;
constexpr std::size_t kJoints = 12;  // θ_y1, θ_r, θ_y2 of each module
static_assert(kJoints == 3 * static_cast<std::size_t>(kModules));

#ifdef SLIPWALK_HAVE_MUJOCO
/// MuJoCo's Multipod with the key's asymmetry, walking the §5.3.2 gait.
residual::MotionTrial mujoco_trial(const MultipodTrialKey& key) {
  namespace peer = peers::mujoco;
  peer::MultipodPeerSpec spec = peer::multipod_peer_spec(key.legs, key.seed, key.asymmetry);
  spec.timestep = key.timestep;
  const peer::MultipodModel model(spec);
  peer::MultipodData data(model);
  robots::UndulationGait gait;
  gait.legs = key.legs;
  gait.dphi = key.dphi_pi * std::numbers::pi;
  gait.frequency = key.frequency;
  peer::TrialOptions options;
  options.cycles = key.cycles;
  options.sample_rate = key.sample_rate;
  options.settle = key.settle;
  residual::MotionTrial trial = peer::record_trial(model, data, gait, options);
  trial.label = trial_label(key);
  return trial;
}
#endif

residual::MotionTrial default_trial(const MultipodTrialKey& key) {
#ifdef SLIPWALK_HAVE_MUJOCO
  return mujoco_trial(key);
#else
  throw core::ComputationError(
      trial_label(key) +
      ": built without MuJoCo (SLIPWALK_MUJOCO=OFF or libmujoco-dev missing): no trial recorded");
#endif
}

struct TrialCache {
  std::mutex source_mutex;
  TrialSource source;  // empty: default_trial
  engine::OnceCache<MultipodTrialKey, residual::MotionTrial> trials;
  engine::OnceCache<MultipodTrialKey, residual::TemplatePrediction> predictions;

  TrialSource current_source() {
    const std::lock_guard lock(source_mutex);
    return source ? source : TrialSource(default_trial);
  }
};

TrialCache& cache() {
  static TrialCache c;
  return c;
}

/// The template robot of `legs` legs, built once per leg count.
const residual::TemplateRobot& template_robot(int legs) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<const residual::TemplateRobot>> robots;
  const std::lock_guard lock(mutex);
  auto& slot = robots[legs];
  if (!slot) {
    slot = std::make_unique<const residual::TemplateRobot>(residual::multipod_template(legs));
  }
  return *slot;
}

MultipodTrialKey canonical(MultipodTrialKey key) {
  key.dphi_pi = quantize_dphi_pi(key.dphi_pi);
  return key;
}

}  // namespace

double quantize_dphi_pi(double dphi_pi) { return std::round(dphi_pi * 1e12) / 1e12; }

std::string trial_label(const MultipodTrialKey& key) {
  return "Multipod trial dphi = " + core::format_double(key.dphi_pi) +
         " pi, f = " + core::format_double(key.frequency) + " Hz, asymmetry " +
         core::format_double(key.asymmetry) + " (seed " + std::to_string(key.seed) + ")";
}

std::shared_ptr<const residual::MotionTrial> cached_trial(MultipodTrialKey key) {
  key = canonical(key);
  return cache().trials.get(
      key, [&] { return cache().current_source()(key); }, trial_label);
}

std::shared_ptr<const residual::TemplatePrediction> cached_prediction(MultipodTrialKey key) {
  key = canonical(key);
  return cache().predictions.get(
      key,
      [&] {
        const std::shared_ptr<const residual::MotionTrial> trial = cached_trial(key);
        return residual::predict(template_robot(key.legs), *trial);
      },
      trial_label);
}

TrialSource set_trial_source(TrialSource source) {
  TrialCache& c = cache();
  TrialSource previous;
  {
    const std::lock_guard lock(c.source_mutex);
    previous = std::exchange(c.source, std::move(source));
  }
  clear_trial_cache();
  return previous;
}

void clear_trial_cache() {
  cache().trials.clear();
  cache().predictions.clear();
}

std::vector<double> thesis_dphi_grid() {
  std::vector<double> grid = linspace(0.2, 1.8, 26);
  for (double& x : grid) {
    x = quantize_dphi_pi(x);
  }
  return grid;
}

namespace {

/// SplitMix64's finalizer: spreads (seed, k, draw) over a 64-bit seed for mt19937_64.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27U)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31U);
}

/// Uniform on {0, …, n − 1} from mt19937_64's output by rejection: outputs below 2^64 mod n are
/// redrawn, so the rest fall evenly on the n residues.
std::uint64_t below(std::mt19937_64& rng, std::uint64_t n) {
  const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
  for (;;) {
    const std::uint64_t u = rng();
    if (u >= threshold) {
      return u % n;
    }
  }
}

}  // namespace

std::vector<std::vector<int>> draw_subsets(std::uint64_t seed, int k, int pool, int draws) {
  if (k < 1 || k > pool || draws < 0) {
    throw std::logic_error("draw_subsets: need 1 <= k <= pool and draws >= 0");
  }
  std::vector<std::vector<int>> out;
  out.reserve(static_cast<std::size_t>(draws));
  for (int d = 0; d < draws; ++d) {
    std::mt19937_64 rng(mix(
        seed ^ mix(static_cast<std::uint64_t>(k) * 1000003ULL + static_cast<std::uint64_t>(d))));
    std::vector<int> order(static_cast<std::size_t>(pool));
    for (int i = 0; i < pool; ++i) {
      order[static_cast<std::size_t>(i)] = i;
    }
    for (int i = 0; i < k; ++i) {  // partial Fisher–Yates: the first k places
      const auto j = static_cast<std::size_t>(i) +
                     static_cast<std::size_t>(below(rng, static_cast<std::uint64_t>(pool - i)));
      std::swap(order[static_cast<std::size_t>(i)], order[j]);
    }
    std::vector<int> subset(order.begin(), order.begin() + k);
    std::sort(subset.begin(), subset.end());
    out.push_back(std::move(subset));
  }
  return out;
}

// --- the kinds' inputs --------------------------------------------------------------------------

namespace {

const std::vector<std::string_view> kSharedKeys = {
    "cycles", "skip_cycles", "seed", "asymmetry", "settle", "timestep", "sample_rate"};

std::vector<std::string_view> keys_with(std::vector<std::string_view> own) {
  own.insert(own.end(), kSharedKeys.begin(), kSharedKeys.end());
  return own;
}

const core::Range kFrequency = core::closed(0.05, 5.0, "Hz");
const core::Range kDphiPi = core::closed(0.0, 2.0, "(multiples of pi)");

/// Largest MuJoCo steps of one trial, samples of one trial, and MuJoCo steps of one point.
constexpr double kMaxTrialSteps = 1e7;
constexpr double kMaxTrialSamples = 1e5;
constexpr double kMaxPointSteps = 1e8;

struct Shared {
  double cycles = 8.0;
  double skip_cycles = 1.0;
  std::uint64_t seed = 1;
  double asymmetry = 1.0;
  double settle = 0.5;
  double timestep = 0.001;
  double sample_rate = 125.0;

  [[nodiscard]] MultipodTrialKey key(double dphi_pi, double frequency) const {
    MultipodTrialKey k;
    k.dphi_pi = quantize_dphi_pi(dphi_pi);
    k.frequency = frequency;
    k.cycles = cycles;
    k.seed = seed;
    k.asymmetry = asymmetry;
    k.settle = settle;
    k.timestep = timestep;
    k.sample_rate = sample_rate;
    k.legs = kLegs;
    return k;
  }
  /// MuJoCo steps of one trial at f.
  [[nodiscard]] double steps(double frequency) const {
    return (settle + cycles / frequency) / timestep;
  }
};

Shared read_shared(const Reader& r) {
  Shared s;
  s.cycles = r.number("cycles", 8.0, core::closed(0.5, 20.0, "cycles"));
  s.skip_cycles = r.number("skip_cycles", 1.0, 0.0, 20.0, true);
  if (s.skip_cycles >= s.cycles) {
    r.fail("skip_cycles", "must be less than cycles (" + core::format_double(s.cycles) + ")");
  }
  s.seed = static_cast<std::uint64_t>(r.integer("seed", 1, 0, 4294967295LL));
  s.asymmetry =
      r.number("asymmetry", 1.0, core::closed(0.0, peers::mujoco::kMaxAsymmetryScale, "(scale)"));
  s.settle = r.number("settle", 0.5, core::closed(0.0, 10.0, "s"));
  s.timestep = r.number("timestep", 0.001, core::closed(1e-5, 0.002, "s"));
  s.sample_rate = r.number("sample_rate", 125.0, core::closed(1.0, 1000.0, "Hz"));
  if (1.0 / s.sample_rate < s.timestep) {
    r.fail("sample_rate", "the sample interval 1/sample_rate must be at least timestep (" +
                              core::format_double(s.timestep) + " s)");
  }
  // MuJoCo records on whole steps (peers::mujoco::TrialOptions).
  const double per_sample = 1.0 / (s.sample_rate * s.timestep);
  if (std::abs(per_sample - std::round(per_sample)) > 1e-9 * per_sample) {
    r.fail("sample_rate", "1 / (sample_rate · timestep) = " + core::format_double(per_sample) +
                              " must be a whole number of MuJoCo steps");
  }
  return s;
}

/// Bounds on the trials at frequency f: MuJoCo steps and samples of one trial, and enough
/// snapshots after the skipped cycles for a fit (10).
void check_trial(const Reader& r, const Shared& s, std::string_view frequency_key,
                 double frequency) {
  r.limit_work("timestep", "(settle + cycles / frequency) / timestep MuJoCo steps of a trial",
               s.steps(frequency), kMaxTrialSteps);
  r.limit_work("sample_rate", "cycles / frequency · sample_rate samples of a trial",
               s.cycles / frequency * s.sample_rate, kMaxTrialSamples);
  if ((s.cycles - s.skip_cycles) / frequency * s.sample_rate < 10.0) {
    r.fail(frequency_key.empty() ? "cycles" : frequency_key,
           "fewer than 10 samples after the skipped cycles: (cycles − skip_cycles) / frequency "
           "· sample_rate = " +
               core::format_double((s.cycles - s.skip_cycles) / frequency * s.sample_rate));
  }
}

/// A text of space-separated Δφ/π values, each in [0, 2], quantized, distinct, between `least`
/// and `most` of them.
std::vector<double> read_dphi_list(const Reader& r, std::string_view key, const std::string& text,
                                   std::size_t least, std::size_t most) {
  std::vector<double> out;
  std::size_t at = 0;
  while (at < text.size()) {
    if (text[at] == ' ') {
      ++at;
      continue;
    }
    std::size_t end = text.find(' ', at);
    end = end == std::string::npos ? text.size() : end;
    const std::string token = text.substr(at, end - at);
    double x = 0.0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), x);
    if (ec != std::errc() || ptr != token.data() + token.size() || !kDphiPi.contains(x)) {
      r.fail(key, "expected space-separated multiples of pi in " + kDphiPi.describe() + ", got '" +
                      token + "'");
    }
    x = quantize_dphi_pi(x);
    if (std::find(out.begin(), out.end(), x) != out.end()) {
      r.fail(key, "Δφ " + token + " is listed twice");
    }
    out.push_back(x);
    at = end;
  }
  if (out.size() < least || out.size() > most) {
    r.fail(key, "expected " + std::to_string(least) + " to " + std::to_string(most) +
                    " values, got " + std::to_string(out.size()));
  }
  return out;
}

std::string dphi_text(const std::vector<double>& values) {
  std::string out;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) {
      out += ' ';
    }
    out += core::format_double(values[i]);
  }
  return out;
}

// --- multipod_trial -----------------------------------------------------------------------------

struct TrialInputs {
  Shared shared;
  double dphi_pi = 1.0;
  double frequency = 0.3;
};

TrialInputs read_trial(const Point& point) {
  const Reader r(point, "multipod_trial", keys_with({"dphi_pi", "frequency"}));
  TrialInputs in;
  in.shared = read_shared(r);
  in.dphi_pi = r.number("dphi_pi", 1.0, kDphiPi);
  in.frequency = r.number("frequency", 0.3, kFrequency);
  check_trial(r, in.shared, "frequency", in.frequency);
  return in;
}

/// The joint columns' names (residual::trial_columns after t, x, y, theta: the trial file's).
std::vector<std::string> joint_columns() {
  const std::vector<std::string> all = residual::trial_columns(kModules);
  if (all.size() != 4 + kJoints || all[0] != "t" || all[1] != "x" || all[2] != "y" ||
      all[3] != "theta") {
    throw std::logic_error("multipod_trial: residual::trial_columns is not t, x, y, theta, joints");
  }
  return {all.begin() + 4, all.end()};
}

struct TrialRow {
  long long id = 0;
  double dphi_pi = 0.0;
  double frequency = 0.0;
  double asymmetry = 0.0;
  double t = 0.0;
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  std::array<double, kJoints> joints{};

  static std::vector<Column<TrialRow>> columns() {
    using R = TrialRow;
    std::vector<Column<R>> out = {value("id", &R::id),
                                  value("dphi_pi", &R::dphi_pi),
                                  value("frequency", &R::frequency, "Hz"),
                                  value("asymmetry", &R::asymmetry),
                                  value("t", &R::t, "s"),
                                  value("x", &R::x, "m"),
                                  value("y", &R::y, "m"),
                                  value("theta", &R::theta, "rad")};
    const std::vector<std::string> names = joint_columns();
    for (std::size_t j = 0; j < kJoints; ++j) {
      out.push_back(value_at(names[j], &R::joints, j, "rad"));
    }
    return out;
  }
};

template <class Row>
Rows<Row> failed(const std::string& message) {
  Rows<Row> out;
  out.failed = true;
  out.message = message;
  return out;
}

Rows<TrialRow> run_trial(const Point& point) {
  const TrialInputs in = read_trial(point);
  const MultipodTrialKey key = in.shared.key(in.dphi_pi, in.frequency);
  std::shared_ptr<const residual::MotionTrial> trial;
  try {
    trial = cached_trial(key);
  } catch (const core::ComputationError& e) {
    return failed<TrialRow>(e.what());
  }
  if (trial->joints.cols() != static_cast<Eigen::Index>(kJoints)) {
    return failed<TrialRow>(trial->label + ": " + std::to_string(trial->joints.cols()) +
                            " joint columns, expected " + std::to_string(kJoints));
  }
  Rows<TrialRow> out;
  out.rows.reserve(static_cast<std::size_t>(trial->samples()));
  for (Eigen::Index i = 0; i < trial->samples(); ++i) {
    TrialRow r;
    r.id = point.id;
    r.dphi_pi = key.dphi_pi;
    r.frequency = key.frequency;
    r.asymmetry = key.asymmetry;
    r.t = trial->t(i);
    r.x = trial->pose(i, 0);
    r.y = trial->pose(i, 1);
    r.theta = trial->pose(i, 2);
    for (std::size_t j = 0; j < kJoints; ++j) {
      r.joints[j] = trial->joints(i, static_cast<Eigen::Index>(j));
    }
    out.rows.push_back(r);
  }
  return out;
}

// --- the fit and its evaluation -----------------------------------------------------------------

using BMatrix = Eigen::Matrix<double, 3, Eigen::Dynamic>;

/// The snapshots of a prediction at t ≥ t0 (the skipped cycles' dropped).
residual::TemplatePrediction after(const residual::TemplatePrediction& p, double t0) {
  Eigen::Index first = 0;
  while (first < p.t.size() && p.t(first) < t0) {
    ++first;
  }
  const Eigen::Index n = p.t.size() - first;
  residual::TemplatePrediction out;
  out.t = p.t.tail(n);
  out.v_true = p.v_true.bottomRows(n);
  out.v_model = p.v_model.bottomRows(n);
  out.qdot = p.qdot.bottomRows(n);
  out.contacts = p.contacts.tail(n);
  return out;
}

/// The snapshots of the trial of `key` after skip_cycles (the trial's prediction is cached).
residual::TemplatePrediction snapshots(const Shared& s, const MultipodTrialKey& key) {
  const std::shared_ptr<const residual::TemplatePrediction> p = cached_prediction(key);
  // A sample at t = skip/f exactly belongs to the kept cycles: allow for rounding of t.
  residual::TemplatePrediction out = after(*p, s.skip_cycles / key.frequency - 1e-9);
  if (out.t.size() == 0) {
    throw core::ComputationError(trial_label(key) + ": no snapshots after the skipped cycles");
  }
  return out;
}

/// Sums of squared errors and of values per component, and the count, over many snapshots.
struct Accumulator {
  Eigen::Vector3d sq = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Index n = 0;

  void add(const Eigen::MatrixX3d& v, const Eigen::MatrixX3d& truth) {
    sq += (v - truth).colwise().squaredNorm().transpose();
    sum += v.colwise().sum().transpose();
    n += v.rows();
  }
  [[nodiscard]] Eigen::Vector3d rmse() const {
    return n > 0 ? Eigen::Vector3d((sq / static_cast<double>(n)).cwiseSqrt())
                 : Eigen::Vector3d::Constant(kNaN);
  }
  [[nodiscard]] Eigen::Vector3d mean() const {
    return n > 0 ? Eigen::Vector3d(sum / static_cast<double>(n)) : Eigen::Vector3d::Constant(kNaN);
  }
};

/// B by the estimator over the training snapshots (see the file's head for the ridge grid).
residual::ResidualFit fit(const std::vector<residual::TemplatePrediction>& train,
                          const std::string& estimator) {
  std::vector<residual::ResidualTrial> trials;
  trials.reserve(train.size());
  for (const residual::TemplatePrediction& p : train) {
    trials.push_back(residual::residual_trial(p));
  }
  residual::ResidualFit pinv = residual::fit_residual(trials);
  if (estimator == "pinv") {
    return pinv;
  }
  const double s_max = pinv.singular_values.size() > 0 ? pinv.singular_values(0) : 0.0;
  std::vector<double> lambdas = {0.0};
  for (int k = -12; k <= 3; ++k) {
    lambdas.push_back(s_max * s_max * std::pow(10.0, k));
  }
  const residual::RidgeValidation v = residual::validate_ridge(trials, lambdas);
  return residual::fit_residual_ridge(trials, v.best);
}

// --- residual_transfer and residual_errors ------------------------------------------------------

struct TransferInputs {
  Shared shared;
  double train_frequency = 0.3;
  std::vector<double> train_dphi_pi;
  double test_frequency = 0.3;
  double test_dphi_pi = 1.0;
  std::string estimator = "pinv";
};

/// The Fig. 5.5 training gaits.
constexpr const char* kFigureTraining = "0.65 0.9 1.1 1.35";
/// At most this many training trials per point (the 26-grid and a few more).
constexpr std::size_t kMaxTrainingTrials = 32;

TransferInputs read_transfer(const Point& point, std::string_view kind) {
  const Reader r(point, kind,
                 keys_with({"train_frequency", "train_dphi_pi", "test_frequency", "test_dphi_pi",
                            "estimator"}));
  TransferInputs in;
  in.shared = read_shared(r);
  in.test_frequency = r.number("test_frequency", 0.3, kFrequency);
  // The training frequency defaults to the test's: B trained at the gait's own frequency.
  in.train_frequency = r.number("train_frequency", in.test_frequency, kFrequency);
  in.test_dphi_pi = quantize_dphi_pi(r.number("test_dphi_pi", 1.0, kDphiPi));
  in.train_dphi_pi = read_dphi_list(
      r, "train_dphi_pi", r.text("train_dphi_pi").value_or(kFigureTraining), 1, kMaxTrainingTrials);
  in.estimator = r.choice("estimator", {"pinv", "ridge"});
  if (in.estimator == "ridge" && in.train_dphi_pi.size() < 2) {
    r.fail("estimator",
           "ridge chooses λ by leave-one-trial-out cross-validation: give at least two "
           "training trials in train_dphi_pi");
  }
  check_trial(r, in.shared, "train_frequency", in.train_frequency);
  check_trial(r, in.shared, "test_frequency", in.test_frequency);
  r.limit_work("train_dphi_pi", "MuJoCo steps of the point's trials",
               static_cast<double>(in.train_dphi_pi.size()) * in.shared.steps(in.train_frequency) +
                   in.shared.steps(in.test_frequency),
               kMaxPointSteps);
  return in;
}

/// A transfer point computed: the training and test snapshots, the fit, v_fit on both.
struct Transfer {
  std::vector<residual::TemplatePrediction> train;
  residual::TemplatePrediction test;
  residual::ResidualFit fit;
  std::vector<Eigen::MatrixX3d> train_fit;
  Eigen::MatrixX3d test_fit;
  double wall_s = 0.0;  ///< the fit and the evaluation (trials and predictions cached apart)
};

Transfer transfer(const TransferInputs& in) {
  Transfer out;
  for (double dphi : in.train_dphi_pi) {
    out.train.push_back(snapshots(in.shared, in.shared.key(dphi, in.train_frequency)));
  }
  out.test = snapshots(in.shared, in.shared.key(in.test_dphi_pi, in.test_frequency));
  const auto start = Clock::now();
  out.fit = fit(out.train, in.estimator);
  for (const residual::TemplatePrediction& p : out.train) {
    out.train_fit.push_back(residual::with_residual(p, out.fit.B));
  }
  out.test_fit = residual::with_residual(out.test, out.fit.B);
  out.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

struct TransferRow {
  long long id = 0;
  double train_frequency = 0.0;
  double test_frequency = 0.0;
  double test_dphi_pi = 0.0;
  std::string estimator;
  double asymmetry = 0.0;
  double t = 0.0;
  std::array<double, 3> v_true{};
  std::array<double, 3> v_model{};
  std::array<double, 3> v_fit{};

  static std::vector<Column<TransferRow>> columns() {
    using R = TransferRow;
    std::vector<Column<R>> out = {value("id", &R::id),
                                  value("train_frequency", &R::train_frequency, "Hz"),
                                  value("test_frequency", &R::test_frequency, "Hz"),
                                  value("test_dphi_pi", &R::test_dphi_pi),
                                  value("estimator", &R::estimator),
                                  value("asymmetry", &R::asymmetry),
                                  value("t", &R::t, "s")};
    const std::array<const char*, 3> axes = {"x", "y", "w"};
    const std::array<const char*, 3> units = {"m/s", "m/s", "rad/s"};
    for (auto [name, member] :
         {std::pair{"v_true_", &R::v_true}, std::pair{"v_model_", &R::v_model},
          std::pair{"v_fit_", &R::v_fit}}) {
      for (std::size_t c = 0; c < 3; ++c) {
        out.push_back(value_at(std::string(name) + axes[c], member, c, units[c]));
      }
    }
    return out;
  }
};

/// A point's work that failed (a trial, the template, the fit): the point fails with the message.
template <class Row, class Work>
Rows<Row> guarded(Work&& work) {
  try {
    return work();
  } catch (const core::ComputationError& e) {
    return failed<Row>(e.what());
  } catch (const core::InputError& e) {  // the fit refusing its snapshots
    return failed<Row>(e.what());
  }
}

Rows<TransferRow> run_transfer(const Point& point) {
  const TransferInputs in = read_transfer(point, "residual_transfer");
  return guarded<TransferRow>([&] {
    const Transfer x = transfer(in);
    Rows<TransferRow> out;
    out.rows.reserve(static_cast<std::size_t>(x.test.t.size()));
    for (Eigen::Index j = 0; j < x.test.t.size(); ++j) {
      TransferRow r;
      r.id = point.id;
      r.train_frequency = in.train_frequency;
      r.test_frequency = in.test_frequency;
      r.test_dphi_pi = in.test_dphi_pi;
      r.estimator = in.estimator;
      r.asymmetry = in.shared.asymmetry;
      r.t = x.test.t(j);
      for (Eigen::Index c = 0; c < 3; ++c) {
        const auto k = static_cast<std::size_t>(c);
        r.v_true[k] = x.test.v_true(j, c);
        r.v_model[k] = x.test.v_model(j, c);
        r.v_fit[k] = x.test_fit(j, c);
      }
      out.rows.push_back(r);
    }
    return out;
  });
}

struct ErrorsRow {
  long long id = 0;
  double train_frequency = 0.0;
  std::string train_dphi_pi;
  double test_frequency = 0.0;
  double test_dphi_pi = 0.0;
  std::string estimator;
  double asymmetry = 0.0;
  double lambda = 0.0;
  long long rank = 0;
  double condition = 0.0;
  long long snapshots = 0;
  std::array<double, 3> train_rmse_model{};
  std::array<double, 3> train_rmse_fit{};
  std::array<double, 3> test_rmse_model{};
  std::array<double, 3> test_rmse_fit{};
  std::array<double, 3> test_mean_true{};
  std::array<double, 3> test_mean_model{};
  std::array<double, 3> test_mean_fit{};
  double b_norm = 0.0;
  double wall_s = 0.0;

  static std::vector<Column<ErrorsRow>> columns() {
    using R = ErrorsRow;
    std::vector<Column<R>> out = {value("id", &R::id),
                                  value("train_frequency", &R::train_frequency, "Hz"),
                                  value("train_dphi_pi", &R::train_dphi_pi),
                                  value("test_frequency", &R::test_frequency, "Hz"),
                                  value("test_dphi_pi", &R::test_dphi_pi),
                                  value("estimator", &R::estimator),
                                  value("asymmetry", &R::asymmetry),
                                  value("lambda", &R::lambda),
                                  value("rank", &R::rank),
                                  value("condition", &R::condition),
                                  value("snapshots", &R::snapshots)};
    const std::array<const char*, 3> axes = {"x", "y", "w"};
    const std::array<const char*, 3> units = {"m/s", "m/s", "rad/s"};
    for (auto [name, member] : {std::pair{"train_rmse_model_", &R::train_rmse_model},
                                std::pair{"train_rmse_fit_", &R::train_rmse_fit},
                                std::pair{"test_rmse_model_", &R::test_rmse_model},
                                std::pair{"test_rmse_fit_", &R::test_rmse_fit},
                                std::pair{"test_mean_true_", &R::test_mean_true},
                                std::pair{"test_mean_model_", &R::test_mean_model},
                                std::pair{"test_mean_fit_", &R::test_mean_fit}}) {
      for (std::size_t c = 0; c < 3; ++c) {
        out.push_back(value_at(std::string(name) + axes[c], member, c, units[c]));
      }
    }
    out.push_back(value("b_norm", &R::b_norm));
    out.push_back(timing("wall_s", &R::wall_s));
    return out;
  }
};

void put(std::array<double, 3>& to, const Eigen::Vector3d& from) {
  for (std::size_t c = 0; c < 3; ++c) {
    to[c] = from(static_cast<Eigen::Index>(c));
  }
}

Rows<ErrorsRow> run_errors(const Point& point) {
  const TransferInputs in = read_transfer(point, "residual_errors");
  return guarded<ErrorsRow>([&] {
    const Transfer x = transfer(in);
    Accumulator train_model;
    Accumulator train_fit;
    for (std::size_t i = 0; i < x.train.size(); ++i) {
      train_model.add(x.train[i].v_model, x.train[i].v_true);
      train_fit.add(x.train_fit[i], x.train[i].v_true);
    }
    Accumulator test_true;
    Accumulator test_model;
    Accumulator test_fit;
    test_true.add(x.test.v_true, x.test.v_true);
    test_model.add(x.test.v_model, x.test.v_true);
    test_fit.add(x.test_fit, x.test.v_true);
    ErrorsRow r;
    r.id = point.id;
    r.train_frequency = in.train_frequency;
    r.train_dphi_pi = dphi_text(in.train_dphi_pi);
    r.test_frequency = in.test_frequency;
    r.test_dphi_pi = in.test_dphi_pi;
    r.estimator = in.estimator;
    r.asymmetry = in.shared.asymmetry;
    r.lambda = x.fit.lambda;
    r.rank = static_cast<long long>(x.fit.rank);
    r.condition = x.fit.condition;
    r.snapshots = static_cast<long long>(x.fit.snapshots);
    put(r.train_rmse_model, train_model.rmse());
    put(r.train_rmse_fit, train_fit.rmse());
    put(r.test_rmse_model, test_model.rmse());
    put(r.test_rmse_fit, test_fit.rmse());
    put(r.test_mean_true, test_true.mean());
    put(r.test_mean_model, test_model.mean());
    put(r.test_mean_fit, test_fit.mean());
    r.b_norm = x.fit.B.norm();
    r.wall_s = x.wall_s;
    Rows<ErrorsRow> out;
    out.rows.push_back(r);
    return out;
  });
}

// --- residual_training --------------------------------------------------------------------------

constexpr const char* kValidation = "0.2 0.52 0.84 1.16 1.48 1.8";
constexpr long long kMaxDraws = 100;

struct TrainingInputs {
  Shared shared;
  double frequency = 0.3;
  int train_trials = 4;
  int draws = 20;
  std::vector<double> validation;
  std::vector<double> pool;  ///< the 26-grid less the validation trials
};

TrainingInputs read_training(const Point& point) {
  const Reader r(point, "residual_training",
                 keys_with({"frequency", "train_trials", "draws", "validate_dphi_pi"}));
  TrainingInputs in;
  in.shared = read_shared(r);
  in.frequency = r.number("frequency", 0.3, kFrequency);
  in.draws = static_cast<int>(r.integer("draws", 20, 1, kMaxDraws));
  in.validation = read_dphi_list(r, "validate_dphi_pi",
                                 r.text("validate_dphi_pi").value_or(kValidation), 1, 26);
  for (double x : thesis_dphi_grid()) {
    if (std::find(in.validation.begin(), in.validation.end(), x) == in.validation.end()) {
      in.pool.push_back(x);
    }
  }
  in.train_trials = static_cast<int>(r.integer("train_trials", 4, 1, 26));
  if (in.pool.empty() || static_cast<std::size_t>(in.train_trials) > in.pool.size()) {
    r.fail("train_trials", "at most the " + std::to_string(in.pool.size()) +
                               " trials of the 26-grid outside validate_dphi_pi");
  }
  check_trial(r, in.shared, "frequency", in.frequency);
  const double trials = static_cast<double>(
      in.validation.size() +
      std::min(in.pool.size(), static_cast<std::size_t>(in.train_trials * in.draws)));
  r.limit_work("draws", "MuJoCo steps of the point's trials",
               trials * in.shared.steps(in.frequency), kMaxPointSteps);
  return in;
}

struct TrainingRow {
  long long id = 0;
  double frequency = 0.0;
  long long train_trials = 0;
  long long draw = 0;
  std::string train_dphi_pi;
  std::array<double, 3> validation_rmse_model{};
  std::array<double, 3> validation_rmse_fit{};

  static std::vector<Column<TrainingRow>> columns() {
    using R = TrainingRow;
    std::vector<Column<R>> out = {value("id", &R::id), value("frequency", &R::frequency, "Hz"),
                                  value("train_trials", &R::train_trials), value("draw", &R::draw),
                                  value("train_dphi_pi", &R::train_dphi_pi)};
    const std::array<const char*, 3> axes = {"x", "y", "w"};
    const std::array<const char*, 3> units = {"m/s", "m/s", "rad/s"};
    for (auto [name, member] : {std::pair{"validation_rmse_model_", &R::validation_rmse_model},
                                std::pair{"validation_rmse_fit_", &R::validation_rmse_fit}}) {
      for (std::size_t c = 0; c < 3; ++c) {
        out.push_back(value_at(std::string(name) + axes[c], member, c, units[c]));
      }
    }
    return out;
  }
};

Rows<TrainingRow> run_training(const Point& point) {
  const TrainingInputs in = read_training(point);
  return guarded<TrainingRow>([&] {
    std::vector<residual::TemplatePrediction> validation;
    Accumulator model;
    for (double dphi : in.validation) {
      validation.push_back(snapshots(in.shared, in.shared.key(dphi, in.frequency)));
      model.add(validation.back().v_model, validation.back().v_true);
    }
    Rows<TrainingRow> out;
    const auto subsets =
        draw_subsets(in.shared.seed, in.train_trials, static_cast<int>(in.pool.size()), in.draws);
    for (std::size_t d = 0; d < subsets.size(); ++d) {
      std::vector<double> dphis;
      std::vector<residual::TemplatePrediction> train;
      for (int i : subsets[d]) {
        dphis.push_back(in.pool[static_cast<std::size_t>(i)]);
        train.push_back(snapshots(in.shared, in.shared.key(dphis.back(), in.frequency)));
      }
      const residual::ResidualFit f = fit(train, "pinv");
      Accumulator with_b;
      for (const residual::TemplatePrediction& p : validation) {
        with_b.add(residual::with_residual(p, f.B), p.v_true);
      }
      TrainingRow r;
      r.id = point.id;
      r.frequency = in.frequency;
      r.train_trials = in.train_trials;
      r.draw = static_cast<long long>(d);
      r.train_dphi_pi = dphi_text(dphis);
      put(r.validation_rmse_model, model.rmse());
      put(r.validation_rmse_fit, with_b.rmse());
      out.rows.push_back(r);
    }
    return out;
  });
}

}  // namespace

std::vector<PointKind> residual_kinds() {
  return {
      make_point_kind<TrialRow>(
          "multipod_trial",
          "§5.3.2: one trial of MuJoCo's asymmetric Multipod walking the undulation gait (Δφ, "
          "f); a row per recorded sample: body pose and measured joints (a trial file for "
          "`slipwalk residual fit`, grouped by id)",
          Timed::kNo, [](const Point& p) { (void)read_trial(p); }, run_trial),
      make_point_kind<TransferRow>(
          "residual_transfer",
          "§5.3, Figs. 5.5-5.6: the residual B fitted on training trials, evaluated along a test "
          "trial; a row per test snapshot: measured, template and template + B body velocity",
          Timed::kNo, [](const Point& p) { (void)read_transfer(p, "residual_transfer"); },
          run_transfer),
      make_point_kind<ErrorsRow>(
          "residual_errors",
          "§5.3: the residual fit's errors on its training and test trials (RMSE, mean drift), "
          "rank, conditioning, λ and ‖B‖; one row per point (wall_s: the fit and evaluation, "
          "measured while other points may run)",
          Timed::kNo, [](const Point& p) { (void)read_transfer(p, "residual_errors"); },
          run_errors),
      make_point_kind<TrainingRow>(
          "residual_training",
          "§5.3.2: validation error of B against the number of training trials k, drawn at "
          "random from the 26-grid less the validation trials; a row per draw",
          Timed::kNo, [](const Point& p) { (void)read_training(p); }, run_training),
  };
}

}  // namespace slipwalk::sweeps::points
