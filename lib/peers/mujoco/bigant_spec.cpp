// BigANT of thesis §3.5.4 as an MJCF text, without MuJoCo (bigant_spec.hpp).
#include "peers/mujoco/bigant_spec.hpp"

#include <cmath>
#include <sstream>
#include <variant>

#include "core/error.hpp"

namespace slipwalk::peers::mujoco {

namespace {

void check_spec(const BigAntPeerSpec& s) {
  const auto bad = [](const std::string& what) {
    throw core::InputError("bigant peer spec", what);
  };
  const int n = s.legs();
  if (n < 1 || static_cast<int>(s.leg_names.size()) != n || static_cast<int>(s.mu.size()) != n) {
    bad("need at least one leg and as many names and mu as nominal points");
  }
  if (!s.nominal.allFinite()) {
    bad("nominal foot points must be finite");
  }
  for (int k = 0; k < n; ++k) {
    const double mu = s.mu[static_cast<std::size_t>(k)];
    if (!(mu >= 0.0) || !std::isfinite(mu)) {
      bad("mu[" + std::to_string(k) + "]: must be >= 0");
    }
  }
  if (!(s.link_mass > 0.0) || !(s.total_mass > 3.0 * n * s.link_mass) ||
      !std::isfinite(s.total_mass)) {
    bad("need link_mass > 0 and total_mass > the legs' mass");
  }
  if (!(s.chassis_inertia.minCoeff() > 0.0) || !s.chassis_inertia.allFinite() ||
      !(s.chassis_half_size.minCoeff() > 0.0)) {
    bad("chassis inertia and size must be positive");
  }
  for (double x : {s.foot_radius, s.gravity, s.timestep, s.tolerance, s.kp_xy, s.kp_z,
                   s.solref_timeconst, s.solref_dampratio}) {
    if (!(x > 0.0) || !std::isfinite(x)) {
      bad("foot_radius, gravity, timestep, tolerance, kp_xy, kp_z, solref: must be positive");
    }
  }
  if (s.iterations < 1 || s.noslip_iterations < 0 || !(s.damping >= 0.0) ||
      !std::isfinite(s.damping)) {
    bad("iterations must be >= 1, noslip_iterations >= 0 and damping >= 0");
  }
  terrain::validate(s.terrain);  // InputError "terrain.angle", "terrain.tread", ...
  if (const auto* st = std::get_if<terrain::Stairs>(&s.terrain)) {
    if (!s.stairs_extent.allFinite() || !(s.stairs_extent(0) < s.stairs_extent(1)) ||
        !((s.stairs_extent(1) - s.stairs_extent(0)) / st->tread < kMaxStairBoxes - 2)) {
      throw core::InputError("bigant peer spec: stairs_extent",
                             "must be finite, first < second, and span at most " +
                                 std::to_string(kMaxStairBoxes - 2) + " treads");
    }
    if (!(s.stairs_half_width > 0.0) || !std::isfinite(s.stairs_half_width) ||
        !(s.stairs_depth > 0.0) || !std::isfinite(s.stairs_depth)) {
      throw core::InputError("bigant peer spec: stairs_half_width, stairs_depth",
                             "must be positive and finite");
    }
  }
}

/// The ground: a plane one foot radius below z = 0 (flat, and a slope whose tilt is in gravity),
/// or stairs: a box per tread, top at i·riser − r, all down to one base (bigant_spec.hpp).
void write_ground(std::ostringstream& x, const BigAntPeerSpec& s) {
  const auto* st = std::get_if<terrain::Stairs>(&s.terrain);
  if (st == nullptr) {
    x << "    <geom name=\"floor\" type=\"plane\" size=\"0 0 1\" pos=\"0 0 " << -s.foot_radius
      << "\" conaffinity=\"1\" friction=\"0 0 0\"/>\n";
    return;
  }
  const Eigen::Vector2i treads = bigant_treads(s, *st);
  const double base = treads(0) * st->riser - s.foot_radius - s.stairs_depth;
  const double c = std::cos(st->heading), sn = std::sin(st->heading);
  for (int i = treads(0); i <= treads(1); ++i) {
    const double top = i * st->riser - s.foot_radius;
    const double along = (i + 0.5) * st->tread;
    x << "    <geom name=\"tread" << i << "\" type=\"box\" size=\"" << 0.5 * st->tread << ' '
      << s.stairs_half_width << ' ' << 0.5 * (top - base) << "\" pos=\"" << along * c << ' '
      << along * sn << ' ' << 0.5 * (top + base) << "\" euler=\"0 0 " << st->heading
      << "\" conaffinity=\"1\" friction=\"0 0 0\"/>\n";
  }
}

}  // namespace

BigAntPeerSpec bigant_peer_spec(const robots::Walker& walker, int samples) {
  if (!walker.feet || samples < 1) {
    throw core::InputError("bigant peer spec", "the walker needs a gait and samples >= 1");
  }
  contact::validate(walker.robot);
  const int n = walker.legs();
  BigAntPeerSpec spec;
  spec.leg_names = walker.leg_names;
  if (static_cast<int>(spec.leg_names.size()) != n) {  // unnamed legs: leg0, leg1, ...
    spec.leg_names.clear();
    for (int k = 0; k < n; ++k) {
      spec.leg_names.push_back("leg" + std::to_string(k));
    }
  }
  spec.total_mass = walker.robot.Mg / spec.gravity;
  spec.nominal = Eigen::Matrix3Xd::Zero(3, n);
  Eigen::Matrix3Xd q(3, n), qdot(3, n);
  for (int i = 0; i < samples; ++i) {
    walker.feet(walker.period * i / samples, q, qdot);
    spec.nominal += q;
  }
  spec.nominal /= samples;
  for (int k = 0; k < n; ++k) {
    spec.mu.push_back(walker.robot.mu(k));
  }
  return spec;
}

Eigen::Vector3d bigant_gravity(const BigAntPeerSpec& spec) {
  if (const auto* slope = std::get_if<terrain::Slope>(&spec.terrain)) {
    // eq. 5.1 in the plane's frame: the normal part g cos σ, the rest g sin σ down −ψ.
    const double along = spec.gravity * std::sin(slope->angle);
    return {-along * std::cos(slope->heading), -along * std::sin(slope->heading),
            -spec.gravity * std::cos(slope->angle)};
  }
  return {0.0, 0.0, -spec.gravity};
}

Eigen::Vector2i bigant_treads(const BigAntPeerSpec& spec, const terrain::Stairs& s) {
  return {static_cast<int>(std::floor(spec.stairs_extent(0) / s.tread)),
          static_cast<int>(std::ceil(spec.stairs_extent(1) / s.tread)) - 1};
}

std::string bigant_mjcf(const BigAntPeerSpec& s) {
  check_spec(s);
  std::ostringstream x;
  x.precision(17);
  const double chassis_mass = s.total_mass - 3.0 * s.link_mass * s.legs();
  // Link inertia: tiny but positive (MuJoCo rejects massless moving bodies); slides do not rotate.
  const double link_inertia = s.link_mass * 1e-4;
  const Eigen::Vector3d g = bigant_gravity(s);
  x << "<mujoco model=\"slipwalk_bigant\">\n"
    << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
    << "  <option timestep=\"" << s.timestep << "\" gravity=\"" << g(0) << ' ' << g(1) << ' '
    << g(2) << "\" noslip_iterations=\"" << s.noslip_iterations
    << "\" solver=\"Newton\" iterations=\"" << s.iterations << "\" tolerance=\"" << s.tolerance
    << "\" cone=\"" << (s.elliptic ? "elliptic" : "pyramidal")
    << "\"/>\n"
    // Only feet and floor collide (feet contype 1, floor conaffinity 1). Both carry the solref, so
    // the contact's (the mix of the two geoms') is it.
    << "  <default><geom contype=\"0\" conaffinity=\"0\" condim=\"3\" solref=\""
    << s.solref_timeconst << ' ' << s.solref_dampratio << "\"/></default>\n"
    << "  <worldbody>\n";
  // The contact's friction is the larger of the two geoms': a frictionless ground leaves the
  // foot's μ.
  write_ground(x, s);
  x << "    <body name=\"chassis\" pos=\"0 0 0.2\">\n"
    << "      <freejoint name=\"root\"/>\n"
    << "      <inertial pos=\"0 0 0\" mass=\"" << chassis_mass << "\" diaginertia=\""
    << s.chassis_inertia(0) << ' ' << s.chassis_inertia(1) << ' ' << s.chassis_inertia(2)
    << "\"/>\n"
    << "      <geom type=\"box\" size=\"" << s.chassis_half_size(0) << ' ' << s.chassis_half_size(1)
    << ' ' << s.chassis_half_size(2) << "\"/>\n";
  const char* axes[3] = {"x", "y", "z"};
  const char* dirs[3] = {"1 0 0", "0 1 0", "0 0 1"};
  for (int k = 0; k < s.legs(); ++k) {
    const std::string& leg = s.leg_names[static_cast<std::size_t>(k)];
    x << "      <body name=\"" << leg << "_x\" pos=\"" << s.nominal(0, k) << ' ' << s.nominal(1, k)
      << ' ' << s.nominal(2, k) << "\">\n";
    for (int a = 0; a < 3; ++a) {
      if (a > 0) {
        x << "      <body name=\"" << leg << '_' << axes[a] << "\">\n";
      }
      x << "        <inertial pos=\"0 0 0\" mass=\"" << s.link_mass << "\" diaginertia=\""
        << link_inertia << ' ' << link_inertia << ' ' << link_inertia << "\"/>"
        << "<joint name=\"" << leg << '_' << axes[a] << "\" type=\"slide\" axis=\"" << dirs[a]
        << "\" limited=\"false\" damping=\"" << s.damping << "\"/>\n";
    }
    x << "        <geom name=\"" << leg << "_foot\" type=\"sphere\" size=\"" << s.foot_radius
      << "\" contype=\"1\" friction=\"" << s.mu[static_cast<std::size_t>(k)]
      << " 0.005 0.0001\"/>\n"
      << "      </body></body></body>\n";
  }
  x << "    </body>\n  </worldbody>\n  <actuator>\n";
  for (int k = 0; k < s.legs(); ++k) {
    const std::string& leg = s.leg_names[static_cast<std::size_t>(k)];
    for (int a = 0; a < 3; ++a) {
      x << "    <position joint=\"" << leg << '_' << axes[a] << "\" kp=\""
        << (a < 2 ? s.kp_xy : s.kp_z) << "\"/>\n";
    }
  }
  x << "  </actuator>\n</mujoco>\n";
  return x.str();
}

void bigant_targets(const BigAntPeerSpec& spec, const Eigen::Matrix3Xd& q,
                    const Eigen::Matrix3Xd& qdot, bool lead, Eigen::Matrix3Xd& targets) {
  targets = q - spec.nominal;
  if (lead) {
    const Eigen::Vector3d tau(spec.damping / spec.kp_xy, spec.damping / spec.kp_xy,
                              spec.damping / spec.kp_z);
    targets += tau.asDiagonal() * qdot;
  }
}

}  // namespace slipwalk::peers::mujoco
