// The MuJoCo peer: MJCF of our legged robots, loading from memory, and state in and out
// (peer.hpp). MuJoCo 2.2.2's C API: mj_loadXML from a virtual file system, mj_makeData, mj_step,
// mj_forward, mj_contactForce.
#include "peers/mujoco/peer.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>

#include "core/error.hpp"
#include "peers/mujoco/mjcf_loader.hpp"

namespace slipwalk::peers::mujoco {

namespace {

/// Loading and compiling are serialized: MuJoCo 2.2's XML loader keeps the last model globally.
std::mutex& loader_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

mjModel* load_mjcf(const std::string& xml, const char* name) {
  const std::lock_guard<std::mutex> lock(loader_mutex());
  // mjVFS holds 2000 file names of 1000 bytes: on the heap, not the stack.
  const auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0) {
    throw core::ComputationError("MuJoCo: cannot create the in-memory MJCF file");
  }
  const int file = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[file], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* model = mj_loadXML(name, vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (model == nullptr) {
    throw core::ComputationError(std::string("MuJoCo could not compile ") + name + ": " + error);
  }
  return model;
}

// --- model and data
// ---------------------------------------------------------------------------------

PeerModel::PeerModel(PeerSpec spec) : spec_(std::move(spec)) {
  model_ = load_mjcf(mjcf(spec_), "slipwalk_peer.xml");
  const int n = legs();
  qpos_slide.resize(static_cast<std::size_t>(n));
  qvel_slide.resize(static_cast<std::size_t>(n));
  ctrl_slide.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const std::string s = "slide" + std::to_string(k);
    const int joint = mj_name2id(model_, mjOBJ_JOINT, s.c_str());
    const auto uk = static_cast<std::size_t>(k);
    qpos_slide[uk] = model_->jnt_qposadr[joint];
    qvel_slide[uk] = model_->jnt_dofadr[joint];
    ctrl_slide[uk] = 3 * k;  // actuators are written slide, yaw, pitch per leg, in leg order
  }
  foot_of_geom.assign(static_cast<std::size_t>(model_->ngeom), -1);
  for (int k = 0; k < n; ++k) {
    const std::string f = "foot" + std::to_string(k);
    foot_of_geom[static_cast<std::size_t>(mj_name2id(model_, mjOBJ_GEOM, f.c_str()))] = k;
  }
  body_id = mj_name2id(model_, mjOBJ_BODY, "body");
}

PeerModel::~PeerModel() { mj_deleteModel(model_); }

PeerData::PeerData(const PeerModel& model)
    : q(Eigen::Matrix3Xd::Zero(3, model.legs())),
      contact(static_cast<std::size_t>(model.legs()), 0),
      Fz(Eigen::VectorXd::Zero(model.legs())),
      Fxy(Eigen::Matrix2Xd::Zero(2, model.legs())) {
  const mjModel* m = model.mj();
  data_ = mj_makeData(m);
  if (data_ == nullptr) {
    throw core::ComputationError("MuJoCo: mj_makeData failed");
  }
  saved_.assign(static_cast<std::size_t>(m->nq + 2 * m->nv + m->nu), 0.0);
}

PeerData::~PeerData() { mj_deleteData(data_); }

// --- state in
// ---------------------------------------------------------------------------------------

int set_state(const PeerModel& model, PeerData& data, const BodyState& body,
              const Eigen::Matrix3Xd& q, const Eigen::Matrix3Xd& qdot) {
  const mjModel* m = model.mj();
  mjData* d = data.mj();
  // Free joint: position, then the unit quaternion of yaw · pitch · roll. To first order the
  // height of a foot is z + q_z − β q_x + α q_y, eq. 3.6.
  d->qpos[0] = body.x;
  d->qpos[1] = body.y;
  d->qpos[2] = body.z;
  const double cy = std::cos(body.theta / 2), sy = std::sin(body.theta / 2);
  const double cp = std::cos(body.beta / 2), sp = std::sin(body.beta / 2);
  const double cr = std::cos(body.alpha / 2), sr = std::sin(body.alpha / 2);
  d->qpos[3] = cy * cp * cr + sy * sp * sr;
  d->qpos[4] = cy * cp * sr - sy * sp * cr;
  d->qpos[5] = cy * sp * cr + sy * cp * sr;
  d->qpos[6] = sy * cp * cr - cy * sp * sr;
  // Free joint velocity: linear in the world frame, angular in the body frame.
  const double c = std::cos(body.theta), s = std::sin(body.theta);
  d->qvel[0] = c * body.v_body(0) - s * body.v_body(1);
  d->qvel[1] = s * body.v_body(0) + c * body.v_body(1);
  d->qvel[2] = 0.0;
  d->qvel[3] = 0.0;
  d->qvel[4] = 0.0;
  d->qvel[5] = body.v_body(2);
  int unreachable = 0;
  LegJoints j, r;
  for (int k = 0; k < model.legs(); ++k) {
    const auto uk = static_cast<std::size_t>(k);
    if (!leg_inverse(model.spec().legs[uk], q.col(k), qdot.col(k), j, r)) {
      ++unreachable;
      continue;
    }
    const int p = model.qpos_slide[uk], v = model.qvel_slide[uk], u = model.ctrl_slide[uk];
    d->qpos[p] = d->ctrl[u] = j.slide;
    d->qpos[p + 1] = d->ctrl[u + 1] = j.yaw;
    d->qpos[p + 2] = d->ctrl[u + 2] = j.pitch;
    d->qvel[v] = r.slide;
    d->qvel[v + 1] = r.yaw;
    d->qvel[v + 2] = r.pitch;
  }
  d->time = 0.0;
  mju_zero(d->qacc_warmstart, m->nv);
  return unreachable;
}

void warm_start(const PeerModel& model, PeerData& data) {
  mj_forward(model.mj(), data.mj());
  mju_copy(data.mj()->qacc_warmstart, data.mj()->qacc, model.mj()->nv);
}

void checkpoint(const PeerModel& model, PeerData& data) {
  const mjModel* m = model.mj();
  const mjData* d = data.mj();
  double* out = data.saved_.data();
  mju_copy(out, d->qpos, m->nq);
  mju_copy(out + m->nq, d->qvel, m->nv);
  mju_copy(out + m->nq + m->nv, d->qacc_warmstart, m->nv);
  mju_copy(out + m->nq + 2 * m->nv, d->ctrl, m->nu);
}

void rewind(const PeerModel& model, PeerData& data) {
  const mjModel* m = model.mj();
  mjData* d = data.mj();
  const double* in = data.saved_.data();
  mju_copy(d->qpos, in, m->nq);
  mju_copy(d->qvel, in + m->nq, m->nv);
  mju_copy(d->qacc_warmstart, in + m->nq + m->nv, m->nv);
  mju_copy(d->ctrl, in + m->nq + 2 * m->nv, m->nu);
  d->time = 0.0;
}

void step(const PeerModel& model, PeerData& data) { mj_step(model.mj(), data.mj()); }

void forward(const PeerModel& model, PeerData& data) { mj_forward(model.mj(), data.mj()); }

// --- state out
// --------------------------------------------------------------------------------------

BodyState body_state(const PeerModel& model, const PeerData& data) {
  const mjData* d = data.mj();
  const mjtNum* R = d->xmat + 9 * model.body_id;  // row-major body-to-world rotation
  BodyState b;
  b.x = d->qpos[0];
  b.y = d->qpos[1];
  b.z = d->qpos[2];
  b.theta = std::atan2(R[3], R[0]);
  // R's third row is the world z axis in body coordinates: (−sin β, sin α cos β, ·) for the
  // yaw · pitch · roll order of set_state.
  b.beta = -std::asin(std::clamp(R[6], -1.0, 1.0));
  b.alpha = std::atan2(R[7], R[8]);
  const double c = std::cos(b.theta), s = std::sin(b.theta);
  b.v_body << c * d->qvel[0] + s * d->qvel[1], -s * d->qvel[0] + c * d->qvel[1], 0.0;
  // ω_z of the world frame from the body-frame angular velocity.
  b.v_body(2) = R[6] * d->qvel[3] + R[7] * d->qvel[4] + R[8] * d->qvel[5];
  return b;
}

int read_feet(const PeerModel& model, PeerData& data) {
  const mjModel* m = model.mj();
  const mjData* d = data.mj();
  const mjtNum* R = d->xmat + 9 * model.body_id;
  const mjtNum* p = d->xpos + 3 * model.body_id;
  const double theta = std::atan2(R[3], R[0]);
  const double c = std::cos(theta), s = std::sin(theta);
  data.Fz.setZero();
  data.Fxy.setZero();
  std::fill(data.contact.begin(), data.contact.end(), 0);
  for (int g = 0; g < m->ngeom; ++g) {
    const int k = model.foot_of_geom[static_cast<std::size_t>(g)];
    if (k < 0) {
      continue;
    }
    // Foot centre in the body frame: Rᵀ (x_foot − x_body).
    const mjtNum* x = d->geom_xpos + 3 * g;
    const Eigen::Vector3d dx(x[0] - p[0], x[1] - p[1], x[2] - p[2]);
    data.q.col(k) << R[0] * dx(0) + R[3] * dx(1) + R[6] * dx(2),
        R[1] * dx(0) + R[4] * dx(1) + R[7] * dx(2), R[2] * dx(0) + R[5] * dx(1) + R[8] * dx(2);
  }
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& con = d->contact[i];
    int k = model.foot_of_geom[static_cast<std::size_t>(con.geom2)];
    double sign = 1.0;  // the force of geom1 on geom2 (its normal points from geom1 to geom2)
    if (k < 0) {
      k = model.foot_of_geom[static_cast<std::size_t>(con.geom1)];
      sign = -1.0;
    }
    if (k < 0) {
      continue;
    }
    mjtNum f[6];
    mj_contactForce(m, d, i, f);
    // World force: rows of con.frame are the normal and the two tangents.
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    for (int a = 0; a < 3; ++a) {
      for (int r = 0; r < 3; ++r) {
        w(a) += f[r] * con.frame[3 * r + a];
      }
    }
    w *= sign;
    data.contact[static_cast<std::size_t>(k)] = 1;
    data.Fz(k) += w(2);
    data.Fxy(0, k) += c * w(0) + s * w(1);
    data.Fxy(1, k) += -s * w(0) + c * w(1);
  }
  return d->ncon;
}

int solver_iterations(const PeerData& data) { return data.mj()->solver_iter; }

std::string version() { return mj_versionString(); }

}  // namespace slipwalk::peers::mujoco
