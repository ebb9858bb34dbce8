// BigANT in MuJoCo driven along our gait (bigant_peer.hpp).
#include "peers/mujoco/bigant_peer.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "peers/mujoco/mjcf_loader.hpp"

namespace slipwalk::peers::mujoco {

// --- model and data
// ---------------------------------------------------------------------------------

BigAntModel::BigAntModel(BigAntPeerSpec spec) : spec_(std::move(spec)) {
  model_ = load_mjcf(bigant_mjcf(spec_), "slipwalk_bigant.xml");
  const int n = legs();
  for (int k = 0; k < n; ++k) {
    const std::string& leg = spec_.leg_names[static_cast<std::size_t>(k)];
    const int joint = mj_name2id(model_, mjOBJ_JOINT, (leg + "_x").c_str());
    qpos_leg.push_back(model_->jnt_qposadr[joint]);
    qvel_leg.push_back(model_->jnt_dofadr[joint]);
  }
  leg_of_geom.assign(static_cast<std::size_t>(model_->ngeom), -1);
  for (int k = 0; k < n; ++k) {
    const std::string foot = spec_.leg_names[static_cast<std::size_t>(k)] + "_foot";
    const int geom = mj_name2id(model_, mjOBJ_GEOM, foot.c_str());
    leg_of_geom[static_cast<std::size_t>(geom)] = k;
    foot_geom.push_back(geom);
  }
}

BigAntModel::~BigAntModel() { mj_deleteModel(model_); }

BigAntData::BigAntData(const BigAntModel& model)
    : q(Eigen::Matrix3Xd::Zero(3, model.legs())),
      qdot(Eigen::Matrix3Xd::Zero(3, model.legs())),
      targets(Eigen::Matrix3Xd::Zero(3, model.legs())),
      slides(Eigen::Matrix3Xd::Zero(3, model.legs())),
      Fz(Eigen::VectorXd::Zero(model.legs())),
      contact(static_cast<std::size_t>(model.legs()), 0),
      Fxy(Eigen::Matrix2Xd::Zero(2, model.legs())),
      slip(Eigen::Matrix2Xd::Zero(2, model.legs())) {
  data_ = mj_makeData(model.mj());
  if (data_ == nullptr) {
    throw core::ComputationError("MuJoCo: mj_makeData failed");
  }
}

BigAntData::~BigAntData() { mj_deleteData(data_); }

// --- state in and out
// -------------------------------------------------------------------------------

namespace {

/// Actuators are written x, y, z per leg in leg order (bigant_mjcf).
void write_ctrl(const BigAntModel& model, mjData* d, const Eigen::Matrix3Xd& targets) {
  for (int k = 0; k < model.legs(); ++k) {
    for (int a = 0; a < 3; ++a) {
      d->ctrl[3 * k + a] = targets(a, k);
    }
  }
}

}  // namespace

void bigant_place(const BigAntModel& model, BigAntData& data, double z, double alpha, double beta,
                  const Eigen::Matrix3Xd& targets) {
  const mjModel* m = model.mj();
  mjData* d = data.mj();
  mj_resetData(m, d);
  d->qpos[0] = 0.0;
  d->qpos[1] = 0.0;
  d->qpos[2] = z;
  // Pitch · roll (yaw 0): to first order a foot's height is z + q_z − β q_x + α q_y, eq. 3.6.
  const double cp = std::cos(beta / 2), sp = std::sin(beta / 2);
  const double cr = std::cos(alpha / 2), sr = std::sin(alpha / 2);
  d->qpos[3] = cp * cr;
  d->qpos[4] = cp * sr;
  d->qpos[5] = sp * cr;
  d->qpos[6] = -sp * sr;
  for (int k = 0; k < model.legs(); ++k) {
    const int p = model.qpos_leg[static_cast<std::size_t>(k)];
    for (int a = 0; a < 3; ++a) {
      d->qpos[p + a] = targets(a, k);
    }
  }
  write_ctrl(model, d, targets);
  data.targets = targets;
  mj_forward(m, d);
}

core::Pose2 bigant_pose(const BigAntData& data) {
  const mjtNum* qp = data.mj()->qpos + 3;  // free joint quaternion (w, x, y, z)
  const double yaw = std::atan2(2.0 * (qp[0] * qp[3] + qp[1] * qp[2]),
                                1.0 - 2.0 * (qp[2] * qp[2] + qp[3] * qp[3]));
  return {data.mj()->qpos[0], data.mj()->qpos[1], yaw};
}

double bigant_height(const BigAntData& data) { return data.mj()->qpos[2]; }

Eigen::Vector3d bigant_position(const BigAntData& data) {
  const mjtNum* p = data.mj()->qpos;
  return {p[0], p[1], p[2]};
}

Eigen::Vector2d bigant_tilt(const BigAntData& data) {
  const mjtNum* q = data.mj()->qpos + 3;  // (w, x, y, z)
  // The z components of the chassis' x and y axes: R(2, 0) and R(2, 1) of the quaternion.
  const double x_up = 2.0 * (q[1] * q[3] - q[0] * q[2]);
  const double y_up = 2.0 * (q[2] * q[3] + q[0] * q[1]);
  return {std::asin(std::clamp(y_up, -1.0, 1.0)), std::asin(std::clamp(x_up, -1.0, 1.0))};
}

void bigant_read_legs(const BigAntModel& model, BigAntData& data) {
  const mjModel* m = model.mj();
  const mjData* d = data.mj();
  for (int k = 0; k < model.legs(); ++k) {
    const int p = model.qpos_leg[static_cast<std::size_t>(k)];
    data.slides.col(k) << d->qpos[p], d->qpos[p + 1], d->qpos[p + 2];
  }
  data.Fz.setZero();
  data.Fxy.setZero();
  std::fill(data.contact.begin(), data.contact.end(), 0);
  // World → chassis yaw frame (the planar body frame of our model's forces and slip).
  const double yaw = bigant_pose(data).theta;
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& con = d->contact[i];
    int k = model.leg_of_geom[static_cast<std::size_t>(con.geom2)];
    if (k < 0) {
      k = model.leg_of_geom[static_cast<std::size_t>(con.geom1)];
    }
    if (k < 0) {
      continue;
    }
    mjtNum f[6];
    mj_contactForce(m, d, i, f);
    // f[0] is the normal force (≥ 0) along the contact normal con.frame[0..2]; the floor is
    // horizontal, so its vertical part is f[0] |n_z|.
    data.Fz(k) += f[0] * std::abs(con.frame[2]);
    data.contact[static_cast<std::size_t>(k)] = 1;
    // f[0..2] in the contact frame (rows of con.frame: normal, two tangents) is the force geom1
    // exerts on geom2 (the normal points from geom1 to geom2): world force = frameᵀ f, negated
    // when the foot is geom1.
    const double sign = model.leg_of_geom[static_cast<std::size_t>(con.geom2)] == k ? 1.0 : -1.0;
    double fw[2] = {0.0, 0.0};
    for (int a = 0; a < 2; ++a) {
      for (int r = 0; r < 3; ++r) {
        fw[a] += con.frame[3 * r + a] * f[r];
      }
    }
    data.Fxy(0, k) += sign * (c * fw[0] + s * fw[1]);
    data.Fxy(1, k) += sign * (-s * fw[0] + c * fw[1]);
  }
  for (int k = 0; k < model.legs(); ++k) {
    mjtNum v[6];  // (angular, linear) at the geom's centre, world axes
    mj_objectVelocity(m, d, mjOBJ_GEOM, model.foot_geom[static_cast<std::size_t>(k)], v, 0);
    data.slip.col(k) << c * v[3] + s * v[4], -s * v[3] + c * v[4];
  }
}

int bigant_edge_contacts(const BigAntModel& model, const BigAntData& data) {
  const double cos_limit = std::cos(10.0 * std::numbers::pi / 180.0);
  const mjData* d = data.mj();
  int edges = 0;
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& con = d->contact[i];
    const bool foot = model.leg_of_geom[static_cast<std::size_t>(con.geom1)] >= 0 ||
                      model.leg_of_geom[static_cast<std::size_t>(con.geom2)] >= 0;
    edges += foot && std::abs(con.frame[2]) < cos_limit ? 1 : 0;
  }
  return edges;
}

// --- tracking
// ---------------------------------------------------------------------------------------

Eigen::Vector3d BigAntTracking::rmse() const {
  const double n = static_cast<double>(std::max<long long>(steps, 1)) *
                   static_cast<double>(std::max<Eigen::Index>(sum_sq.cols(), 1));
  return (sum_sq.rowwise().sum() / n).cwiseSqrt();
}

Eigen::Matrix3Xd BigAntTracking::rmse_per_foot() const {
  return (sum_sq / static_cast<double>(std::max<long long>(steps, 1))).cwiseSqrt();
}

double BigAntTracking::swing_z_rmse() const {
  const double n = swing_steps.sum();
  return n > 0 ? std::sqrt(swing_z_sum_sq.sum() / n) : 0.0;
}

// --- the run
// ----------------------------------------------------------------------------------------

BigAntDriveSummary bigant_drive(const BigAntModel& model, BigAntData& data,
                                const robots::FootKinematics& feet, double z, double alpha,
                                double beta, const BigAntDriveOptions& o, const BigAntSink& sink) {
  if (!(o.duration > 0.0) || !std::isfinite(o.duration) || !(o.settle >= 0.0) ||
      !std::isfinite(o.settle) || !(o.sample > 0.0) || !std::isfinite(o.sample) || !feet) {
    throw core::InputError("bigant drive", "need duration > 0, settle >= 0, sample > 0, a gait");
  }
  const mjModel* m = model.mj();
  mjData* d = data.mj();
  const BigAntPeerSpec& spec = model.spec();
  const double h = m->opt.timestep;
  const double Mg = spec.total_mass * spec.gravity;
  const int n_legs = model.legs();

  // Place the robot with the gait's first feet and let it settle under those targets.
  feet(0.0, data.q, data.qdot);
  data.qdot.setZero();
  bigant_targets(spec, data.q, data.qdot, false, data.targets);
  bigant_place(model, data, z, alpha, beta, data.targets);
  const auto settle_steps = static_cast<long long>(std::llround(o.settle / h));
  for (long long i = 0; i < settle_steps; ++i) {
    mj_step(m, d);
  }

  BigAntDriveSummary out;
  BigAntTracking& tr = out.tracking;
  tr.sum_sq = Eigen::Matrix3Xd::Zero(3, n_legs);
  tr.swing_z_sum_sq = Eigen::VectorXd::Zero(n_legs);
  tr.swing_steps = Eigen::VectorXd::Zero(n_legs);
  out.settled = bigant_pose(data);
  const core::Pose2 to_start = core::inverse(out.settled);
  const long long every = std::max(1LL, static_cast<long long>(std::llround(o.sample / h)));
  const auto steps = static_cast<long long>(std::llround(o.duration / h));
  double theta_prev = 0.0, turns = 0.0, contacts_sum = 0.0;
  Eigen::Matrix3Xd err(3, n_legs);
  for (long long n = 0; n <= steps; ++n) {
    const double t = static_cast<double>(n) * h;
    // The state at t: the feet's offsets from where the gait wants them.
    feet(t, data.q, data.qdot);
    bigant_read_legs(model, data);  // slides at t (contacts here are those of the previous step)
    err = data.slides - (data.q - spec.nominal);
    if (n % every == 0 || n == steps) {
      core::Pose2 rel = core::compose(to_start, bigant_pose(data));
      // Unwrap the yaw: samples are far closer than half a turn apart.
      const double jump = rel.theta - theta_prev;
      turns -= std::round(jump / (2.0 * std::numbers::pi));
      theta_prev = rel.theta;
      rel.theta += 2.0 * std::numbers::pi * turns;
      int down = 0;
      for (char c : data.contact) {
        down += c != 0 ? 1 : 0;
      }
      out.end = rel;
      if (sink) {
        sink(BigAntSample{t, rel, bigant_height(data), down, data.Fz.sum()});
      }
    }
    if (n == steps) {
      break;
    }
    bigant_targets(spec, data.q, data.qdot, o.lead, data.targets);
    write_ctrl(model, d, data.targets);
    mj_step(m, d);  // forward at t (contacts at t), then integrate to t + h
    bigant_read_legs(model, data);
    // Contact forces of the state at t: the tracking error's stance / swing split, and the load.
    tr.sum_sq += err.cwiseAbs2();
    int down = 0;
    for (int k = 0; k < n_legs; ++k) {
      if (data.contact[static_cast<std::size_t>(k)] == 0) {
        tr.swing_z_sum_sq(k) += err(2, k) * err(2, k);
        tr.swing_steps(k) += 1.0;
      } else {
        ++down;
      }
    }
    contacts_sum += down;
    out.max_Fz_error = std::max(out.max_Fz_error, std::abs(data.Fz.sum() - Mg) / Mg);
    out.edge_steps += bigant_edge_contacts(model, data) > 0 ? 1 : 0;
    ++tr.steps;
  }
  out.mean_contacts = contacts_sum / static_cast<double>(std::max<long long>(tr.steps, 1));
  return out;
}

}  // namespace slipwalk::peers::mujoco
