// The MuJoCo Multipod of thesis §5.3 as an MJCF text, without MuJoCo (multipod_spec.hpp).
#include "peers/mujoco/multipod_spec.hpp"

#include <cmath>
#include <random>
#include <sstream>

#include "core/error.hpp"

namespace slipwalk::peers::mujoco {

namespace {

constexpr double kNominalStiffness = 1000.0;  // N/m, robots::UndulationGait's K
constexpr double kNominalFriction = 1.0;      // the template's μ (robots::multipod)

void check_legs(int legs) {
  if (legs != 6 && legs != 8 && legs != 10 && legs != 12) {
    throw core::InputError("multipod.legs", "must be 6, 8, 10 or 12 (the thesis' Multipods), got " +
                                                std::to_string(legs));
  }
}

/// Uniform on [0, 1) from the generator's top 53 bits: exact, so the same on every platform.
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

/// Zero mean, unit variance, bounded by ±2√3: a sum of four uniforms (Irwin–Hall), centred and
/// scaled (the sum's variance is 4/12).
double bell(std::mt19937_64& rng) {
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    sum += uniform01(rng);
  }
  return std::sqrt(3.0) * (sum - 2.0);
}

/// Inertia of a solid box of full sizes a, b, c about its centre (principal), kg·m².
std::string box_inertia(double m, double a, double b, double c) {
  std::ostringstream x;
  x.precision(17);
  x << m * (b * b + c * c) / 12.0 << ' ' << m * (a * a + c * c) / 12.0 << ' '
    << m * (a * a + b * b) / 12.0;
  return x.str();
}

}  // namespace

double asymmetry_ratio(double x) { return x >= 0.0 ? 1.0 + x : 1.0 / (1.0 - x); }

MultipodAsymmetry symmetric_legs(int legs) {
  check_legs(legs);
  const auto n = static_cast<std::size_t>(legs);
  MultipodAsymmetry a;
  a.stiffness.assign(n, kNominalStiffness);
  a.mu.assign(n, kNominalFriction);
  a.mount_yaw.assign(n, 0.0);
  a.foot_drop.assign(n, 0.0);
  return a;
}

MultipodAsymmetry draw_asymmetry(int legs, std::uint64_t seed, double scale) {
  MultipodAsymmetry a = symmetric_legs(legs);
  if (!(scale >= 0.0 && scale <= kMaxAsymmetryScale)) {
    throw core::InputError("asymmetry.scale",
                           "must be in [0, 2] (0: the symmetric robot, 1: the default spreads), "
                           "got " +
                               std::to_string(scale));
  }
  if (scale == 0.0) {
    return a;  // exactly nominal, whatever the seed
  }
  std::mt19937_64 rng(seed);
  for (double& k : a.stiffness) {
    k *= asymmetry_ratio(scale * kStiffnessSpread * bell(rng));
  }
  for (double& mu : a.mu) {
    mu *= asymmetry_ratio(scale * kFrictionSpread * bell(rng));
  }
  for (double& d : a.mount_yaw) {
    d = scale * kMountYawSpread * bell(rng);
  }
  for (double& e : a.foot_drop) {
    e = scale * kFootDropSpread * bell(rng);
  }
  return a;
}

double MultipodPeerSpec::section_mass() const {
  const int m = modules();
  const double others =
      legs * foot_mass + m * leg_pair_mass + (m - 1) * connector_mass + 2.0 * stub_mass;
  return (weight / gravity - others) / m;
}

MultipodPeerSpec multipod_peer_spec(int legs, std::uint64_t seed, double scale) {
  MultipodPeerSpec spec;
  spec.legs = legs;
  spec.asymmetry = draw_asymmetry(legs, seed, scale);
  spec.weight = static_cast<double>(legs);  // Mg = N newtons (robots/multipod.cpp)
  return spec;
}

void validate(const MultipodPeerSpec& s) {
  const std::string where = "multipod peer spec";
  const auto bad = [&](const std::string& field, const std::string& what) {
    throw core::InputError(where + "." + field, what);
  };
  check_legs(s.legs);
  const MultipodAsymmetry& a = s.asymmetry;
  const auto n = static_cast<std::size_t>(s.legs);
  if (a.stiffness.size() != n || a.mu.size() != n || a.mount_yaw.size() != n ||
      a.foot_drop.size() != n) {
    bad("asymmetry", "needs one stiffness, mu, mount_yaw and foot_drop per leg (" +
                         std::to_string(s.legs) + ")");
  }
  for (std::size_t k = 0; k < n; ++k) {
    std::string idx("[");
    idx.append(std::to_string(k)).append("]");
    if (!(a.stiffness[k] > 0.0) || !std::isfinite(a.stiffness[k])) {
      bad("asymmetry.stiffness" + idx, "must be > 0 N/m, got " + std::to_string(a.stiffness[k]));
    }
    if (!(a.mu[k] >= 0.0) || !std::isfinite(a.mu[k])) {
      bad("asymmetry.mu" + idx, "must be >= 0, got " + std::to_string(a.mu[k]));
    }
    if (!(std::abs(a.mount_yaw[k]) <= 0.5)) {
      bad("asymmetry.mount_yaw" + idx, "must be in [-0.5, 0.5] rad");
    }
    if (!(std::abs(a.foot_drop[k]) <= 0.02)) {
      bad("asymmetry.foot_drop" + idx, "must be in [-0.02, 0.02] m");
    }
  }
  const robots::MultipodGeometry& g = s.geometry;
  const auto positive = [&](const char* field, double v) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      bad(field, "must be > 0, got " + std::to_string(v));
    }
  };
  const auto nonnegative = [&](const char* field, double v) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      bad(field, "must be >= 0, got " + std::to_string(v));
    }
  };
  positive("geometry.section", g.section);
  positive("geometry.connector", g.connector);
  positive("geometry.foot_lateral", g.foot_lateral);
  positive("geometry.foot_depth", g.foot_depth);
  positive("gravity", s.gravity);
  positive("timestep", s.timestep);
  if (s.timestep > 0.002) {
    bad("timestep", "must be <= 0.002 s (the contact's 5 ms time constant needs two steps)");
  }
  if (s.iterations < 1) {
    bad("iterations", "must be >= 1");
  }
  positive("tolerance", s.tolerance);
  positive("kp", s.kp);
  nonnegative("joint_damping", s.joint_damping);
  nonnegative("armature", s.armature);
  nonnegative("torque_limit", s.torque_limit);
  nonnegative("leg_damping", s.leg_damping);
  positive("foot_radius", s.foot_radius);
  if (s.foot_radius >= g.foot_depth) {
    bad("foot_radius", "must be smaller than geometry.foot_depth");
  }
  positive("foot_mass", s.foot_mass);
  positive("leg_pair_mass", s.leg_pair_mass);
  positive("connector_mass", s.connector_mass);
  positive("stub_mass", s.stub_mass);
  positive("solref_timeconst", s.solref_timeconst);
  positive("solref_dampratio", s.solref_dampratio);
  positive("weight", s.weight);
  if (!(s.section_mass() > 0.0)) {
    bad("weight", "must exceed the feet', leg pairs', connectors' and stubs' weight");
  }
}

std::string multipod_leg_name(int legs, int k) {
  const int m = legs / 2;
  std::string name(1, k < m ? 'L' : 'R');
  name.append(std::to_string(k % m + 1));
  return name;
}

Eigen::Vector3d multipod_foot_mount(const MultipodPeerSpec& s, int k) {
  const auto kk = static_cast<std::size_t>(k);
  const double w = k < s.modules() ? s.geometry.foot_lateral : -s.geometry.foot_lateral;
  const double d = s.asymmetry.mount_yaw[kk];
  // (0, w, −h) turned by δ about the vertical, then lowered by the foot drop.
  return {-w * std::sin(d), w * std::cos(d), -s.geometry.foot_depth - s.asymmetry.foot_drop[kk]};
}

std::string multipod_mjcf(const MultipodPeerSpec& s) {
  validate(s);
  const robots::MultipodGeometry& g = s.geometry;
  const int m = s.modules();
  const double half = 0.5 * g.section;
  std::ostringstream x;
  x.precision(17);
  // Every motor joint: hinge, damping, armature; unlimited (the gait stays far from ±π).
  const auto motor = [&](const std::string& name, const char* axis, double px) {
    x << "<joint name=\"" << name << "\" type=\"hinge\" axis=\"" << axis << "\" pos=\"" << px
      << " 0 0\" limited=\"false\" damping=\"" << s.joint_damping << "\" armature=\"" << s.armature
      << "\"/>";
  };
  const double stub_len = 0.03;
  x << "<mujoco model=\"slipwalk_multipod\">\n"
    << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
    << "  <option timestep=\"" << s.timestep << "\" gravity=\"0 0 " << -s.gravity
    << "\" solver=\"Newton\" iterations=\"" << s.iterations << "\" tolerance=\"" << s.tolerance
    << "\" cone=\"elliptic\"/>\n"
    // Only feet and floor collide (feet contype 1, floor conaffinity 1); both carry the solref.
    << "  <default><geom contype=\"0\" conaffinity=\"0\" condim=\"3\" solref=\""
    << s.solref_timeconst << ' ' << s.solref_dampratio << "\"/></default>\n"
    << "  <worldbody>\n"
    << "    <geom name=\"floor\" type=\"plane\" size=\"0 0 1\" conaffinity=\"1\" "
       "friction=\"0 0 0\"/>\n";
  // Section 1 starts level, its feet' centres one radius above the floor (the peer re-places it).
  x << "    <body name=\"section1\" pos=\"0 0 " << g.foot_depth + s.foot_radius << "\">\n"
    << "      <freejoint name=\"root\"/>\n";
  // The head stub, turned by −θ_y1,1 relative to section 1 (the template's connector in front).
  x << "      <body name=\"head\" pos=\"" << half << " 0 0\"><inertial pos=\"" << 0.5 * stub_len
    << " 0 0\" mass=\"" << s.stub_mass << "\" diaginertia=\""
    << box_inertia(s.stub_mass, stub_len, 0.02, 0.02) << "\"/>";
  motor("yaw1_1", "0 0 -1", 0.0);
  x << "<geom type=\"box\" pos=\"" << 0.5 * stub_len << " 0 0\" size=\"" << 0.5 * stub_len
    << " 0.01 0.01\"/></body>\n";
  std::string close;
  for (int i = 1; i <= m; ++i) {
    const std::string id = std::to_string(i);
    if (i > 1) {
      // Section i in its connector's frame: the front yaw axis at the connector's end, the centre
      // half a section further; turned by +θ_y1,i about the front yaw axis.
      x << "      <body name=\"section" << id << "\" pos=\"" << -(g.connector + half) << " 0 0\">";
      motor("yaw1_" + id, "0 0 1", half);
      x << "\n";
    }
    x << "      <inertial pos=\"0 0 0\" mass=\"" << s.section_mass() << "\" diaginertia=\""
      << box_inertia(s.section_mass(), g.section, 0.06, 0.03) << "\"/>\n"
      << "      <geom type=\"box\" size=\"" << half << " 0.03 0.015\"/>\n";
    // The leg pair: rolls about the section's long axis (θ_r > 0 lifts the left foot).
    x << "      <body name=\"legs" << id << "\" pos=\"0 0 0\"><inertial pos=\"0 0 0\" mass=\""
      << s.leg_pair_mass << "\" diaginertia=\""
      << box_inertia(s.leg_pair_mass, 0.01, 2.0 * g.foot_lateral, 0.01) << "\"/>";
    motor("roll_" + id, "1 0 0", 0.0);
    x << "\n";
    for (int side = 0; side < 2; ++side) {
      const int k = side * m + (i - 1);
      const std::string leg = multipod_leg_name(s.legs, k);
      const Eigen::Vector3d p = multipod_foot_mount(s, k);
      const double fi = 0.4 * s.foot_mass * s.foot_radius * s.foot_radius;
      x << "        <body name=\"" << leg << "_foot\" pos=\"" << p.x() << ' ' << p.y() << ' '
        << p.z() << "\"><inertial pos=\"0 0 0\" mass=\"" << s.foot_mass << "\" diaginertia=\"" << fi
        << ' ' << fi << ' ' << fi << "\"/>"
        << "<joint name=\"" << leg << "_spring\" type=\"slide\" axis=\"0 0 1\" limited=\"false\" "
        << "stiffness=\"" << s.asymmetry.stiffness[static_cast<std::size_t>(k)]
        << "\" springref=\"0\" damping=\"" << s.leg_damping << "\"/>"
        << "<geom name=\"" << leg << "_foot\" type=\"sphere\" size=\"" << s.foot_radius
        << "\" contype=\"1\" friction=\"" << s.asymmetry.mu[static_cast<std::size_t>(k)]
        << " 0 0\"/></body>\n";
    }
    x << "      </body>\n";
    // Behind the section: the rear yaw joint turns the connector (or the tail stub) by −θ_y2,i.
    const bool tail = i == m;
    const double len = tail ? stub_len : g.connector;
    const double mass = tail ? s.stub_mass : s.connector_mass;
    x << "      <body name=\"" << (tail ? std::string("tail") : "connector" + id) << "\" pos=\""
      << -half << " 0 0\"><inertial pos=\"" << -0.5 * len << " 0 0\" mass=\"" << mass
      << "\" diaginertia=\"" << box_inertia(mass, len, 0.02, 0.02) << "\"/>";
    motor("yaw2_" + id, "0 0 -1", 0.0);
    x << "<geom type=\"box\" pos=\"" << -0.5 * len << " 0 0\" size=\"" << 0.5 * len
      << " 0.01 0.01\"/>\n";
    if (tail) {
      x << "      </body>\n";
    }
    close += i < m ? "      </body></body>\n" : "    </body>\n";
  }
  x << close << "  </worldbody>\n  <actuator>\n";
  for (int i = 1; i <= m; ++i) {
    for (const char* j : {"yaw1_", "roll_", "yaw2_"}) {
      x << "    <position joint=\"" << j << i << "\" kp=\"" << s.kp << '"';
      if (s.torque_limit > 0.0) {
        x << " forcelimited=\"true\" forcerange=\"" << -s.torque_limit << ' ' << s.torque_limit
          << '"';
      }
      x << "/>\n";
    }
  }
  x << "  </actuator>\n</mujoco>\n";
  return x.str();
}

}  // namespace slipwalk::peers::mujoco
