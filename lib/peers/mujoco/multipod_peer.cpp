// The MuJoCo Multipod driven along the §5.3.2 gait and recorded (multipod_peer.hpp).
#include "peers/mujoco/multipod_peer.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "peers/mujoco/mjcf_loader.hpp"

namespace slipwalk::peers::mujoco {

namespace {

int require_id(const mjModel* m, mjtObj type, const std::string& name) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) {
    throw core::ComputationError("MuJoCo Multipod: no object named " + name);
  }
  return id;
}

/// Section i's heading: its long axis (body x) projected on the floor.
double section_heading(const mjData* d, int body) {
  const mjtNum* r =
      d->xmat + 9 * static_cast<std::ptrdiff_t>(body);  // row-major; column 0 is the body's x axis
  return std::atan2(r[3], r[0]);
}

/// qpos address of module i's joint r (0: θ_y1, 1: θ_r, 2: θ_y2).
int joint_adr(const MultipodModel& model, int i, int r) {
  return model.qpos_joint[3 * static_cast<std::size_t>(i) + static_cast<std::size_t>(r)];
}

/// The motors' targets: the gait's angles leading by (d / kp) θ̇ (multipod_spec.hpp).
void write_targets(const MultipodModel& model, mjData* d, const robots::MultipodJoints& joints,
                   const robots::MultipodJoints& rates, double lead) {
  for (int i = 0; i < model.modules(); ++i) {
    for (int r = 0; r < 3; ++r) {
      d->ctrl[3 * i + r] = joints(r, i) + lead * rates(r, i);
    }
  }
}

}  // namespace

// --- model and data
// ---------------------------------------------------------------------------------

MultipodModel::MultipodModel(MultipodPeerSpec spec) : spec_(std::move(spec)) {
  model_ = load_mjcf(multipod_mjcf(spec_), "slipwalk_multipod.xml");
  const int m = modules();
  for (int i = 1; i <= m; ++i) {
    const std::string id = std::to_string(i);
    section_body.push_back(require_id(model_, mjOBJ_BODY, "section" + id));
    for (const char* j : {"yaw1_", "roll_", "yaw2_"}) {
      qpos_joint.push_back(model_->jnt_qposadr[require_id(model_, mjOBJ_JOINT, j + id)]);
    }
  }
  leg_of_geom.assign(static_cast<std::size_t>(model_->ngeom), -1);
  for (int k = 0; k < legs(); ++k) {
    const std::string leg = multipod_leg_name(legs(), k);
    qpos_spring.push_back(model_->jnt_qposadr[require_id(model_, mjOBJ_JOINT, leg + "_spring")]);
    const int geom = require_id(model_, mjOBJ_GEOM, leg + "_foot");
    foot_geom.push_back(geom);
    leg_of_geom[static_cast<std::size_t>(geom)] = k;
  }
}

MultipodModel::~MultipodModel() { mj_deleteModel(model_); }

MultipodData::MultipodData(const MultipodModel& model)
    : joints(robots::MultipodJoints::Zero(3, model.modules())),
      rates(robots::MultipodJoints::Zero(3, model.modules())),
      Fz(Eigen::VectorXd::Zero(model.legs())) {
  data_ = mj_makeData(model.mj());
  if (data_ == nullptr) {
    throw core::ComputationError("MuJoCo: mj_makeData failed");
  }
}

MultipodData::~MultipodData() { mj_deleteData(data_); }

// --- state in and out
// -------------------------------------------------------------------------------

void multipod_place(const MultipodModel& model, MultipodData& data,
                    const Eigen::Ref<const robots::MultipodJoints>& joints) {
  const mjModel* m = model.mj();
  mjData* d = data.mj();
  mj_resetData(m, d);  // section 1 level at the origin, springs at rest
  for (int i = 0; i < model.modules(); ++i) {
    for (int r = 0; r < 3; ++r) {
      d->qpos[joint_adr(model, i, r)] = joints(r, i);
      d->ctrl[3 * i + r] = joints(r, i);
    }
  }
  mj_kinematics(m, d);
  double lowest = d->geom_xpos[3 * model.foot_geom[0] + 2];
  for (int g : model.foot_geom) {
    lowest = std::min(lowest, d->geom_xpos[3 * g + 2]);
  }
  d->qpos[2] += model.spec().foot_radius - lowest;  // the lowest foot touches the floor
  mj_forward(m, d);
}

core::Pose2 multipod_pose(const MultipodModel& model, const MultipodData& data) {
  const mjData* d = data.mj();
  const int m = model.modules();
  const int first = model.section_body[0];
  const double psi0 = section_heading(d, first);
  double x = 0.0, y = 0.0, dpsi = 0.0;
  for (int b : model.section_body) {
    const mjtNum* p = d->xpos + 3 * static_cast<std::ptrdiff_t>(b);
    x += p[0];
    y += p[1];
    dpsi += core::wrap_angle(section_heading(d, b) - psi0);  // sections differ by well under π
  }
  return {x / m, y / m, core::wrap_angle(psi0 + dpsi / m)};
}

void multipod_measured_joints(const MultipodModel& model, const MultipodData& data,
                              Eigen::Ref<robots::MultipodJoints> joints) {
  for (int i = 0; i < model.modules(); ++i) {
    for (int r = 0; r < 3; ++r) {
      joints(r, i) = data.mj()->qpos[joint_adr(model, i, r)];
    }
  }
}

void multipod_loads(const MultipodModel& model, MultipodData& data) {
  const mjModel* m = model.mj();
  const mjData* d = data.mj();
  data.Fz.setZero();
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& con = d->contact[i];
    int k = model.leg_of_geom[static_cast<std::size_t>(con.geom1)];
    if (k < 0) {
      k = model.leg_of_geom[static_cast<std::size_t>(con.geom2)];
    }
    if (k < 0) {
      continue;
    }
    mjtNum f[6];
    mj_contactForce(m, d, i, f);
    data.Fz(k) += f[0] * std::abs(con.frame[2]);  // normal force; the floor is horizontal
  }
}

void multipod_hold(const MultipodModel& model, MultipodData& data, double seconds) {
  const auto steps = std::llround(seconds / model.mj()->opt.timestep);
  for (long long n = 0; n < steps; ++n) {
    mj_step(model.mj(), data.mj());
  }
}

// --- the trial
// --------------------------------------------------------------------------------------

namespace {

void check_options(const TrialOptions& o, double timestep) {
  if (!(o.cycles > 0.0 && o.cycles <= 1000.0)) {
    throw core::InputError("trial.cycles", "must be in (0, 1000], got " + std::to_string(o.cycles));
  }
  if (!(o.settle >= 0.0 && o.settle <= 100.0)) {
    throw core::InputError("trial.settle",
                           "must be in [0, 100] s, got " + std::to_string(o.settle));
  }
  const double per = 1.0 / (o.sample_rate * timestep);
  if (!(o.sample_rate > 0.0) || !std::isfinite(per) || per < 1.0 - 1e-9 ||
      std::abs(per - std::round(per)) > 1e-9 * per) {
    throw core::InputError("trial.sample_rate", "must make a sample period of whole timesteps (" +
                                                    std::to_string(timestep) + " s), got " +
                                                    std::to_string(o.sample_rate) + " Hz");
  }
}

/// Throws core::ComputationError when the state is not finite or a section is upside down.
void check_state(const MultipodModel& model, const mjData* d, double t) {
  const mjModel* m = model.mj();
  bool finite = true;
  for (int i = 0; i < m->nq; ++i) {
    finite = finite && std::isfinite(d->qpos[i]);
  }
  for (int i = 0; i < m->nv; ++i) {
    finite = finite && std::isfinite(d->qvel[i]);
  }
  std::ostringstream msg;
  if (!finite) {
    msg << "MuJoCo Multipod: the state is not finite at t = " << t << " s (the simulation blew up)";
    throw core::ComputationError(msg.str());
  }
  for (int b : model.section_body) {
    if (d->xmat[9 * b + 8] < 0.0) {  // the section's z axis points down
      msg << "MuJoCo Multipod: a section turned over at t = " << t << " s";
      throw core::ComputationError(msg.str());
    }
  }
}

}  // namespace

residual::MotionTrial record_trial(const MultipodModel& model, MultipodData& data,
                                   const robots::UndulationGait& gait, const TrialOptions& o) {
  robots::validate(gait);
  if (gait.legs != model.legs()) {
    throw core::InputError("multipod.legs", "the gait has " + std::to_string(gait.legs) +
                                                " legs, the MuJoCo robot " +
                                                std::to_string(model.legs()));
  }
  const mjModel* m = model.mj();
  mjData* d = data.mj();
  const double h = m->opt.timestep;
  check_options(o, h);
  const MultipodPeerSpec& spec = model.spec();
  const double lead = spec.joint_damping / spec.kp;
  const int modules = model.modules();

  // Stand in the gait's t = 0 pose (targets there, no lead: the rates are the gait's later).
  robots::multipod_gait_joints(gait, 0.0, data.joints, data.rates);
  multipod_place(model, data, data.joints);
  multipod_hold(model, data, o.settle);
  check_state(model, d, -o.settle);

  const double duration = o.cycles / gait.frequency;
  const auto every = std::llround(1.0 / (o.sample_rate * h));
  const auto samples = static_cast<Eigen::Index>(std::floor(duration * o.sample_rate + 1e-9)) + 1;
  residual::MotionTrial trial;
  std::ostringstream label;
  label << "MuJoCo Multipod, f = " << gait.frequency
        << " Hz, dphi = " << gait.dphi / std::numbers::pi << "pi";
  trial.label = label.str();
  trial.t.resize(samples);
  trial.pose.resize(samples, 3);
  trial.joints.resize(samples, 3 * static_cast<Eigen::Index>(modules));
  robots::MultipodJoints measured(3, modules);
  double theta_prev = 0.0;
  for (Eigen::Index j = 0; j < samples; ++j) {
    // Sample j at step j · every: the state there, then the steps to the next sample.
    const double t = static_cast<double>(j * every) * h;
    mj_kinematics(m, d);
    check_state(model, d, t);
    const core::Pose2 pose = multipod_pose(model, data);
    // Unwrap: samples are far less than half a turn apart.
    const double theta =
        j == 0 ? pose.theta : theta_prev + core::wrap_angle(pose.theta - theta_prev);
    theta_prev = theta;
    trial.t(j) = t;
    trial.pose.row(j) << pose.x, pose.y, theta;
    multipod_measured_joints(model, data, measured);
    for (int i = 0; i < modules; ++i) {
      trial.joints.block<1, 3>(j, 3 * static_cast<Eigen::Index>(i)) = measured.col(i).transpose();
    }
    if (j + 1 == samples) {
      break;
    }
    for (long long n = 0; n < every; ++n) {
      robots::multipod_gait_joints(gait, static_cast<double>(j * every + n) * h, data.joints,
                                   data.rates);
      write_targets(model, d, data.joints, data.rates, lead);
      mj_step(m, d);
    }
  }
  return trial;
}

}  // namespace slipwalk::peers::mujoco
