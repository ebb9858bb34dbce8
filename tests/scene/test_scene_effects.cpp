// The optional effects of a scene: anisotropic friction, the residual B of §5.3.1 and measurement
// noise. Oracles: every parser error names file:line:col (residual files file:line[:col]);
// effects switched off or neutral (w = 0, B = 0, σ = 0) are bit-identical to the plain kernel;
// the anisotropic forces are eq. 3.19's H u recomputed from the reported slip, and anisotropic
// Coulomb's are solve_coulomb's on the robot with that w, on the rim of the same ellipse along the
// same direction (sliding feet) or inside it (static ones); the residual adds
// exactly B·vec(q̇) to the balance's velocity; the noise is the same for a seed, other for another
// seed, has mean ≈ 0 and recovers σ, and leaves the simulated motion untouched.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "friction/solvers.hpp"
#include "scene/effects.hpp"
#include "scene/reference_kernel.hpp"
#include "scene/run_writer.hpp"
#include "scene/scene.hpp"
#include "support/count_allocations.hpp"
#include "sweeps/engine/study.hpp"

namespace slipwalk::scene {
namespace {

/// BigANT's tripod for 1 s in 20 steps with `effects` appended (tables and keys).
std::string scene_text(const std::string& friction, const std::string& effects = "") {
  return "[robot]\nname = \"bigant\"\n[gait]\nkind = \"tripod\"\nfrequency = 0.5\n"
         "[run]\nduration = 1.0\ndt = 0.05\n[friction]\n" +
         friction + "\n" + effects;
}

const std::string kViscous = "law = \"viscous\"";
const std::string kAnisotropic = "law = \"anisotropic\"\nw = [0.8, 0.3]";
const std::string kCoulomb = "law = \"coulomb\"";
const std::string kAnisotropicCoulomb = "law = \"coulomb\"\nw = [0.8, 0.3]";

/// Lines before `needle` in `text`, plus one: the line `needle` is on.
int line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

void expect_error(const std::string& text, const std::string& at, const std::string& part,
                  const std::string& path = "s.toml") {
  try {
    (void)parse_scene(text, path);
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), at) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

/// A temporary folder with files, removed at the end of the test.
struct TempDir {
  std::filesystem::path dir;
  TempDir() {
    dir = std::filesystem::temp_directory_path() /
          ("slipwalk_effects_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
           "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir);
  }
  ~TempDir() { std::filesystem::remove_all(dir); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
};

/// A 3 x 12 residual file's text with entries b0 + 0.001 (3c + r).
std::string residual_csv(double b0) {
  std::string out = "# B for BigANT: rows v_x, v_y, omega; columns qdot_x, qdot_y per leg\n";
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 12; ++c) {
      out.append(c == 0 ? "" : ", ").append(std::to_string(b0 + 0.001 * (3 * c + r)));
    }
    out.append("\n");
  }
  return out;
}

struct Frame {
  core::Pose2 pose;
  core::Pose2 measured;
  Eigen::Vector3d v_body;
  Eigen::Vector3d v_model;
  Eigen::Matrix3Xd qdot;
  Eigen::VectorXd Fz;
  Eigen::Matrix2Xd Fxy;
  Eigen::Matrix2Xd slip;
};

std::vector<Frame> run(const Scene& scene) {
  std::vector<Frame> out;
  const Simulator sim = compose(scene);
  (void)sim.run([&](const connection::TrajectoryStep& s) {
    out.push_back(
        {s.pose, s.measured, s.v_body, s.v_model, s.frame.qdot, s.frame.Fz, s.frame.Fxy, s.slip});
  });
  return out;
}

void expect_same_motion(const std::vector<Frame>& a, const std::vector<Frame>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].pose.x, b[i].pose.x) << i;
    EXPECT_EQ(a[i].pose.y, b[i].pose.y) << i;
    EXPECT_EQ(a[i].pose.theta, b[i].pose.theta) << i;
    EXPECT_EQ(a[i].v_body, b[i].v_body) << i;
    EXPECT_EQ(a[i].Fxy, b[i].Fxy) << i;
  }
}

// ---- the benchmark's yardstick ----------------------------------------------------------------

/// The largest change of the body velocity between two runs of the same frames, and the largest
/// body speed of a run.
double largest_change(const std::vector<Frame>& a, const std::vector<Frame>& b) {
  double change = 0.0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    change = std::max(change, (b[i].v_body - a[i].v_body).norm());
  }
  return change;
}

double largest_speed(const std::vector<Frame>& run) {
  double size = 0.0;
  for (const Frame& f : run) {
    size = std::max(size, f.v_body.norm());
  }
  return size;
}

TEST(SceneEffects, HandWrittenKernelGivesTheComposedFlatSceneBitForBit) {
  // bench_scene and the scene_cost point compare the two for speed; they must compute the same.
  const Scene scene = parse_scene(scene_text(kViscous), "s.toml");
  const Simulator sim = compose(scene);
  const std::vector<Frame> composed = run(scene);
  std::vector<Frame> hand;
  connection::TrajectoryData data(sim.walker.robot);
  (void)run_flat_viscous(sim.walker, sim.options, data, [&](const connection::TrajectoryStep& s) {
    hand.push_back(
        {s.pose, s.measured, s.v_body, s.v_model, s.frame.qdot, s.frame.Fz, s.frame.Fxy, s.slip});
  });
  expect_same_motion(composed, hand);
  for (std::size_t i = 0; i < hand.size(); ++i) {
    EXPECT_EQ(composed[i].slip, hand[i].slip) << i;
    EXPECT_EQ(composed[i].Fz, hand[i].Fz) << i;
  }
}

// ---- anisotropic friction ---------------------------------------------------------------------

TEST(SceneEffects, AnisotropicReadsOneOrPerLegW) {
  const Scene one = parse_scene(scene_text(kAnisotropic), "s.toml");
  EXPECT_TRUE(one.friction.anisotropic);
  ASSERT_EQ(one.friction.w.cols(), 1);
  EXPECT_EQ(one.friction.w(0, 0), 0.8);
  const Simulator sim = compose(one);
  EXPECT_EQ(sim.kernel_name, "anisotropic");
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(sim.walker.robot.w.col(k), Eigen::Vector2d(0.8, 0.3));
  }
  const Scene per_leg = parse_scene(
      scene_text("law = \"anisotropic\"\nw = [[0.8, 0.3], [0.8, 0.3], [0.8, 0.3], [0.8, 0.3], "
                 "[0.8, 0.3], [0.8, 0.3]]"),
      "s.toml");
  EXPECT_EQ(per_leg.friction.w.cols(), 6);
  expect_same_motion(run(one), run(per_leg));
  EXPECT_EQ(to_json(one)["friction"]["law"], "anisotropic");
  EXPECT_EQ(to_json(one)["friction"]["w"][0][1], 0.3);
}

TEST(SceneEffects, AnisotropicWithZeroWIsIsotropicBitForBit) {
  // w = 0 is the isotropic law of eq. 3.19 (H ∝ I + w wᵀ).
  expect_same_motion(run(parse_scene(scene_text("law = \"anisotropic\"\nw = [0, 0]"), "s.toml")),
                     run(parse_scene(scene_text(kViscous), "s.toml")));
}

TEST(SceneEffects, AnisotropicForcesAreHTimesSlip) {
  // Eq. 3.19: F_k = −μ_k F_z,k (I + w wᵀ) u_k for feet in contact, recomputed from the sink's
  // slip; and the planar balance Σ F = 0, Σ q × F = 0. With this w the motion differs from the
  // isotropic one (the effect is really on).
  const Scene scene = parse_scene(scene_text(kAnisotropic), "s.toml");
  const Simulator sim = compose(scene);
  const Eigen::Vector2d w(0.8, 0.3);
  const Eigen::Matrix2d G = Eigen::Matrix2d::Identity() + w * w.transpose();
  (void)sim.run([&](const connection::TrajectoryStep& s) {
    Eigen::Vector2d force = Eigen::Vector2d::Zero();
    double moment = 0.0;
    double size = 0.0;
    for (int k = 0; k < s.frame.legs(); ++k) {
      const Eigen::Vector2d F = s.frame.Fxy.col(k);
      const Eigen::Vector2d expected =
          -sim.walker.robot.mu(k) * s.frame.Fz(k) * (G * s.slip.col(k));
      EXPECT_LE((F - expected).norm(), 1e-12 * (1.0 + expected.norm())) << s.n << " " << k;
      force += F;
      moment += s.frame.q(0, k) * F(1) - s.frame.q(1, k) * F(0);
      size += F.norm();
    }
    EXPECT_LE(force.norm(), 1e-12 * (1.0 + size)) << s.n;
    EXPECT_LE(std::abs(moment), 1e-12 * (1.0 + size)) << s.n;
  });
  const std::vector<Frame> iso = run(parse_scene(scene_text(kViscous), "s.toml"));
  const std::vector<Frame> aniso = run(scene);
  EXPECT_GT(largest_change(iso, aniso), 0.01 * largest_speed(iso));
}

// ---- anisotropic Coulomb friction (eq. 3.19's ellipse, §3.4) ----------------------------------

TEST(SceneEffects, CoulombReadsOneOrPerLegWAndRecordsItInTheSidecar) {
  const Scene one = parse_scene(scene_text(kAnisotropicCoulomb), "s.toml");
  EXPECT_EQ(one.friction.law, connection::FrictionLaw::kCoulomb);
  ASSERT_EQ(one.friction.w.cols(), 1);
  const Simulator sim = compose(one);
  EXPECT_EQ(sim.kernel_name, "coulomb");
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(sim.walker.robot.w.col(k), Eigen::Vector2d(0.8, 0.3));
  }
  const Scene per_leg = parse_scene(
      scene_text("law = \"coulomb\"\nw = [[0.8, 0.3], [0.8, 0.3], [0.8, 0.3], [0.8, 0.3], "
                 "[0.8, 0.3], [0.8, 0.3]]"),
      "s.toml");
  EXPECT_EQ(per_leg.friction.w.cols(), 6);
  expect_same_motion(run(one), run(per_leg));
  EXPECT_EQ(to_json(one)["friction"]["law"], "coulomb");
  EXPECT_EQ(to_json(one)["friction"]["w"][0][0], 0.8);
  EXPECT_EQ(to_json(one)["friction"]["w"][0][1], 0.3);
  // Without w the sidecar says nothing of it, and the robot stays isotropic.
  const Scene plain = parse_scene(scene_text(kCoulomb), "s.toml");
  EXPECT_FALSE(to_json(plain)["friction"].contains("w"));
  EXPECT_TRUE(compose(plain).walker.robot.w.isZero(0.0));
}

TEST(SceneEffects, CoulombWithZeroWIsTheIsotropicCoulombRunBitForBit) {
  // w = 0 is the isotropic ellipse (the disk) of eq. 3.19.
  expect_same_motion(run(parse_scene(scene_text("law = \"coulomb\"\nw = [0, 0]"), "s.toml")),
                     run(parse_scene(scene_text(kCoulomb), "s.toml")));
}

TEST(SceneEffects, AnisotropicCoulombFramesAreSolveCoulombOnTheRobotWithThatW) {
  // Each frame's friction, recomputed here from its inputs (q, q̇, contact, F_z) by
  // solve_coulomb on the isotropic scene's robot with w set by hand, is the scene's bit for bit;
  // and the run differs from the isotropic one (the effect is really on).
  const Scene scene = parse_scene(scene_text(kAnisotropicCoulomb), "s.toml");
  const Simulator sim = compose(scene);
  contact::Robot robot = compose(parse_scene(scene_text(kCoulomb), "s.toml")).walker.robot;
  robot.w.setZero(2, robot.legs());
  robot.w.colwise() += Eigen::Vector2d(0.8, 0.3);
  long long frames = 0;
  (void)sim.run([&](const connection::TrajectoryStep& s) {
    contact::Frame f(robot);
    f.q = s.frame.q;
    f.qdot = s.frame.qdot;
    f.contact = s.frame.contact;
    f.Fz = s.frame.Fz;
    friction::solve_coulomb(robot, f, scene.friction.coulomb);
    EXPECT_EQ(f.v_body, s.v_model) << s.n;
    EXPECT_EQ(f.Fxy, s.frame.Fxy) << s.n;
    EXPECT_TRUE(s.frame.friction.converged) << s.n << ": " << s.frame.friction.message;
    ++frames;
  });
  EXPECT_EQ(frames, sim.options.steps + 1);
  const std::vector<Frame> iso = run(parse_scene(scene_text(kCoulomb), "s.toml"));
  const std::vector<Frame> aniso = run(scene);
  EXPECT_GT(largest_change(iso, aniso), 0.01 * largest_speed(iso));
}

TEST(SceneEffects, AnisotropicCoulombAndAnisotropicViscousHonourTheSameEllipse) {
  // Eq. 3.19 with G = I + w wᵀ: the viscous law of the anisotropic scene is F = −c G u; Coulomb
  // with the same w puts a sliding foot's force on the rim of the ellipse Fᵀ G⁻¹ F = c² along
  // that same direction, F = −c G u / ‖W u‖ (‖W u‖² = uᵀ G u), and a static foot's inside it.
  const Scene coulomb = parse_scene(scene_text(kAnisotropicCoulomb), "s.toml");
  const Scene viscous = parse_scene(scene_text(kAnisotropic), "s.toml");
  const Simulator sim = compose(coulomb);
  ASSERT_EQ(sim.walker.robot.w, compose(viscous).walker.robot.w);
  const Eigen::Vector2d w(0.8, 0.3);
  const Eigen::Matrix2d G = Eigen::Matrix2d::Identity() + w * w.transpose();
  const Eigen::Matrix2d Ginv =
      Eigen::Matrix2d::Identity() - w * w.transpose() / (1.0 + w.squaredNorm());
  int sliding = 0;
  int held = 0;
  (void)sim.run([&](const connection::TrajectoryStep& s) {
    for (int k = 0; k < s.frame.legs(); ++k) {
      if (s.frame.contact[static_cast<std::size_t>(k)] == 0) {
        continue;
      }
      const double c = sim.walker.robot.mu(k) * s.frame.Fz(k);
      const Eigen::Vector2d F = s.frame.Fxy.col(k);
      const Eigen::Vector2d u = s.slip.col(k);
      const double rim = F.dot(Ginv * F) / (c * c);
      EXPECT_LE(rim, 1.0 + 1e-9) << s.n << " " << k;
      const double Wu = std::sqrt(u.dot(G * u));
      if (Wu > 1e-6 * (1.0 + s.frame.qdot.col(k).head<2>().norm())) {
        const Eigen::Vector2d viscous_direction = -c * (G * u);
        EXPECT_LE((F * Wu - viscous_direction).norm(), 1e-7 * viscous_direction.norm())
            << s.n << " " << k;
        EXPECT_NEAR(rim, 1.0, 1e-9) << s.n << " " << k;
        ++sliding;
      } else {
        ++held;
      }
    }
  });
  EXPECT_GT(sliding, 0);
  EXPECT_GT(held, 0);  // the tripod's feet that do not slip: the ellipse's inside is used too
}

TEST(SceneEffects, AnisotropicErrors) {
  const std::string w_given = scene_text("law = \"viscous\"\nw = [0.5, 0]");
  expect_error(
      w_given, "s.toml:" + std::to_string(line_of(w_given, "law") + 1) + ":5",
      "friction.w: a parameter of the anisotropic and coulomb laws, given with law = 'viscous'");
  const std::string missing = scene_text("law = \"anisotropic\"");
  expect_error(missing, "s.toml:" + std::to_string(line_of(missing, "[friction]")) + ":1",
               "missing required key 'w' in [friction]");
  const std::string misspelt = scene_text("law = \"anisotropc\"");
  expect_error(misspelt, "s.toml:" + std::to_string(line_of(misspelt, "law")) + ":7",
               "did you mean 'anisotropic'?");
  const std::string wrong_type = scene_text("law = \"anisotropic\"\nw = 0.5");
  expect_error(wrong_type, "s.toml:" + std::to_string(line_of(wrong_type, "law") + 1) + ":5",
               "friction.w: expected [wx, wy] or one pair per leg, got a float");
  const std::string three = scene_text("law = \"anisotropic\"\nw = [0.5, 0, 1]");
  expect_error(three, "s.toml:" + std::to_string(line_of(three, "law") + 1) + ":5",
               "expected a pair [wx, wy], got an array of 3");
  const std::string legs = scene_text("law = \"anisotropic\"\nw = [[0.5, 0], [0.5, 0]]");
  expect_error(legs, "s.toml:" + std::to_string(line_of(legs, "law") + 1) + ":5",
               "the robot has 6 legs, got 2 pairs");
  const std::string text = scene_text("law = \"anisotropic\"\nw = [0.5, \"x\"]");
  expect_error(text, "s.toml:" + std::to_string(line_of(text, "law") + 1) + ":11",
               "friction.w: expected a number, got a string");
  const std::string misspelt_key = scene_text("law = \"anisotropic\"\nww = [0.5, 0]");
  expect_error(misspelt_key, "s.toml:" + std::to_string(line_of(misspelt_key, "ww")) + ":1",
               "did you mean 'w'?");
}

// ---- residual B (§5.3.1) ----------------------------------------------------------------------

TEST(SceneEffects, ResidualAddsBTimesQdot) {
  const TempDir tmp;
  tmp.write("B.csv", residual_csv(0.01));
  const std::string path =
      tmp.write("s.toml", scene_text(kViscous, "[residual]\nfile = \"B.csv\"\n"));
  const Scene scene = read_scene(path);
  ASSERT_TRUE(scene.residual.has_value());
  EXPECT_EQ(scene.residual->file, (tmp.dir / "B.csv").string());
  EXPECT_EQ(scene.residual->B(1, 4), 0.01 + 0.001 * 13);
  const Simulator sim = compose(scene);
  EXPECT_EQ(sim.kernel_name, "viscous+residual");
  const std::vector<Frame> frames = run(scene);
  const std::vector<Frame> plain = run(parse_scene(scene_text(kViscous), "s.toml"));
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const Frame& f = frames[i];
    Eigen::VectorXd qdot(12);
    for (int k = 0; k < 6; ++k) {
      qdot.segment<2>(2 * static_cast<Eigen::Index>(k)) = f.qdot.col(k).head<2>();
    }
    const Eigen::Vector3d expected = f.v_model + scene.residual->B * qdot;
    EXPECT_LE((f.v_body - expected).norm(), 1e-15 * (1.0 + expected.norm())) << i;
    // The balance itself is the plain kernel's (B changes the pose, not the frame's model).
    if (i == 0) {
      EXPECT_EQ(f.v_model, plain[i].v_model);
    }
  }
  EXPECT_NE(frames.back().pose.x, plain.back().pose.x);
}

TEST(SceneEffects, ConstantResidualAddsNoNetDisplacementOverWholeCycles) {
  // §5.3.1 with a constant B: the body-frame velocity gains B q̇(t) = d/dt (B q(t)), so over whole
  // cycles of a periodic gait it adds B (q(T) − q(0)) = 0. With B acting on v_y only and a
  // tripod that does not turn, the sideways offset it causes comes and goes within each cycle and
  // nets out (up to the step's quadrature error).
  const TempDir tmp;
  std::string csv;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 12; ++c) {
      csv.append(c == 0 ? "" : ",").append(r == 1 && c % 2 == 0 ? "0.05" : "0");
    }
    csv.append("\n");
  }
  tmp.write("B.csv", csv);
  const std::string text =
      "[robot]\nname = \"bigant\"\n[gait]\nkind = \"tripod\"\nfrequency = "
      "0.5\n[run]\nduration = 4.0\ndt = 0.01\n[friction]\nlaw = \"viscous\"\n";
  const std::vector<Frame> with =
      run(read_scene(tmp.write("s.toml", text + "[residual]\nfile = \"B.csv\"\n")));
  const std::vector<Frame> without = run(parse_scene(text, "s.toml"));
  double peak = 0.0;
  for (std::size_t i = 0; i < with.size(); ++i) {
    peak = std::max(peak, std::abs(with[i].pose.y - without[i].pose.y));
  }
  const double end = std::abs(with.back().pose.y - without.back().pose.y);
  EXPECT_GT(peak, 1e-3);                // B moves the body sideways within a cycle ...
  EXPECT_LT(end, 0.02 * peak) << peak;  // ... and not over whole cycles
}

TEST(SceneEffects, ZeroResidualIsThePlainKernelBitForBit) {
  const TempDir tmp;
  tmp.write("B.csv", "0,0,0,0,0,0,0,0,0,0,0,0\n0,0,0,0,0,0,0,0,0,0,0,0\n0,0,0,0,0,0,0,0,0,0,0,0\n");
  const std::string path =
      tmp.write("s.toml", scene_text(kViscous, "[residual]\nfile = \"B.csv\"\n"));
  expect_same_motion(run(read_scene(path)), run(parse_scene(scene_text(kViscous), "s.toml")));
}

TEST(SceneEffects, ResidualFileErrorsNameFileAndLine) {
  const std::string f = "B.csv";
  auto err = [&](const std::string& text, const std::string& at, const std::string& part) {
    try {
      (void)parse_residual(text, f, 2);
      ADD_FAILURE() << text;
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.where(), at) << e.what();
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  const Eigen::Matrix<double, 3, Eigen::Dynamic> B =
      parse_residual("# c\n\n1, 2, 3, 4  # row 1\n 5,6,7,8\n9,10,11,1.2e1\n", f, 2);
  EXPECT_EQ(B(2, 3), 12.0);
  EXPECT_EQ(B(0, 0), 1.0);
  err("1,2,3,4\n1,2,3\n1,2,3,4\n", "B.csv:2", "row 2 has 3 values; the robot's 2 legs need 4");
  err("1,2,3,4\n1,2,x,4\n1,2,3,4\n", "B.csv:2:5", "'x' is not a finite number");
  err("1,2,3,4\n1,2,,4\n1,2,3,4\n", "B.csv:2:5", "'' is not a finite number");
  err("1,2,3,4\n1,2,3,4\n", "B.csv:2", "B has 3 rows (v_x, v_y, omega), the file has 2");
  err("1,2,3,4\n1,2,3,4\n1,2,3,4\n1,2,3,4\n", "B.csv:4", "a fourth row");
  err("1,2,3,4\n1,2,3,nan\n1,2,3,4\n", "B.csv:2:7", "'nan' is not a finite number");
  err("", "B.csv:1", "the file has 0");

  // Through a scene: a missing file, a wrong type, a misspelt key, a wrong size for the robot
  // (the file's first row), a missing key.
  const TempDir tmp;
  tmp.write("small.csv", "1,2,3,4\n1,2,3,4\n1,2,3,4\n");
  auto scene_err = [&](const std::string& residual, const std::string& at,
                       const std::string& part) {
    const std::string text = scene_text(kViscous, "[residual]\n" + residual);
    const std::string path = tmp.write("s.toml", text);
    try {
      (void)read_scene(path);
      ADD_FAILURE() << text;
    } catch (const core::InputError& e) {
      const std::string& where = e.where();
      const std::string expected = at.rfind("B:", 0) == 0
                                       ? (tmp.dir / "small.csv").string() + at.substr(1)
                                       : path + ":" + at;
      EXPECT_EQ(where, expected) << e.what();
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  const int line = line_of(scene_text(kViscous, "[residual]\n"), "[residual]") + 1;
  scene_err("file = \"none.csv\"\n", std::to_string(line) + ":8", "residual.file: cannot read");
  scene_err("file = 3\n", std::to_string(line) + ":8", "expected a string (a file name)");
  scene_err("fil = \"B.csv\"\n", std::to_string(line) + ":1", "did you mean 'file'?");
  scene_err("", std::to_string(line - 1) + ":1", "missing required key 'file' in [residual]");
  scene_err("file = \"small.csv\"\n", "B:1", "row 1 has 4 values; the robot's 6 legs need 12");
}

// ---- measurement noise ------------------------------------------------------------------------

std::string noise(const std::string& keys) { return "[noise]\n" + keys + "\n"; }

TEST(SceneEffects, NoiseIsDeterministicForASeedAndLeavesTheMotionAlone) {
  const Scene a = parse_scene(scene_text(kViscous, noise("sigma = 0.01\nseed = 7")), "s.toml");
  EXPECT_EQ(compose(a).kernel_name, "viscous+noise");
  const std::vector<Frame> first = run(a);
  const std::vector<Frame> second = run(a);
  const std::vector<Frame> other =
      run(parse_scene(scene_text(kViscous, noise("sigma = 0.01\nseed = 8")), "s.toml"));
  const std::vector<Frame> plain = run(parse_scene(scene_text(kViscous), "s.toml"));
  expect_same_motion(first, plain);  // the simulated motion is not touched
  int differ = 0;
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].measured.x, second[i].measured.x) << i;
    EXPECT_EQ(first[i].measured.y, second[i].measured.y) << i;
    EXPECT_EQ(first[i].measured.theta, first[i].pose.theta) << i;  // sigma_theta = 0
    differ += first[i].measured.x != other[i].measured.x ? 1 : 0;
  }
  EXPECT_EQ(differ, static_cast<int>(first.size()));
}

TEST(SceneEffects, ZeroNoiseIsThePlainKernelBitForBit) {
  const std::vector<Frame> quiet =
      run(parse_scene(scene_text(kViscous, noise("sigma = 0.0\nseed = 3")), "s.toml"));
  const std::vector<Frame> plain = run(parse_scene(scene_text(kViscous), "s.toml"));
  expect_same_motion(quiet, plain);
  for (std::size_t i = 0; i < quiet.size(); ++i) {
    EXPECT_EQ(quiet[i].measured.x, plain[i].pose.x);
    EXPECT_EQ(quiet[i].measured.y, plain[i].pose.y);
    EXPECT_EQ(quiet[i].measured.theta, plain[i].pose.theta);
  }
}

TEST(SceneEffects, NoiseHasMeanZeroAndRecoversSigma) {
  // 20 001 frames: the sample mean of n normals is within 4 σ/√n of 0 and the sample standard
  // deviation within 4·σ/√(2n) (≈ 2 %) of σ, except with probability ~1e-4 (fixed seeds: the
  // test is deterministic; these bounds say why it is not fitted to them).
  const std::string text =
      "[robot]\nname = \"bigant\"\n[gait]\nkind = \"tripod\"\n[run]\nduration = 200.0\n"
      "dt = 0.01\n[friction]\nlaw = \"viscous\"\n[noise]\nsigma = 0.002\nsigma_theta = 0.03\n"
      "seed = 12345\n";
  const Scene scene = parse_scene(text, "s.toml");
  const Simulator sim = compose(scene);
  double n = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum2 = Eigen::Vector3d::Zero();
  (void)sim.run([&](const connection::TrajectoryStep& s) {
    const Eigen::Vector3d e(s.measured.x - s.pose.x, s.measured.y - s.pose.y,
                            s.measured.theta - s.pose.theta);
    n += 1;
    sum += e;
    sum2 += e.cwiseProduct(e);
  });
  ASSERT_EQ(n, 20001);
  const Eigen::Vector3d sigma(0.002, 0.002, 0.03);
  for (int i = 0; i < 3; ++i) {
    const double mean = sum(i) / n;
    const double sd = std::sqrt(sum2(i) / n - mean * mean);
    EXPECT_LE(std::abs(mean), 4.0 * sigma(i) / std::sqrt(n)) << i;
    EXPECT_LE(std::abs(sd / sigma(i) - 1.0), 4.0 / std::sqrt(2.0 * n)) << i;
  }
}

TEST(SceneEffects, NoiseErrors) {
  auto at = [](const std::string& text, const std::string& needle, int col) {
    return "s.toml:" + std::to_string(line_of(text, needle)) + ":" + std::to_string(col);
  };
  const std::string negative = scene_text(kViscous, noise("sigma = -0.1"));
  expect_error(negative, at(negative, "sigma = ", 9),
               "noise.sigma: must be in [0, 1000] m, got -0.1");
  const std::string missing = scene_text(kViscous, noise("seed = 1"));
  expect_error(missing, at(missing, "[noise]", 1), "missing required key 'sigma' in [noise]");
  const std::string seed_type = scene_text(kViscous, noise("sigma = 0.1\nseed = 1.5"));
  expect_error(seed_type, at(seed_type, "seed", 8), "noise.seed: expected an integer");
  const std::string seed_range = scene_text(kViscous, noise("sigma = 0.1\nseed = -2"));
  expect_error(seed_range, at(seed_range, "seed", 8), "noise.seed: must be >= 0, got -2");
  const std::string theta = scene_text(kViscous, noise("sigma = 0.1\nsigma_theta = \"a\""));
  expect_error(theta, at(theta, "sigma_theta", 15), "noise.sigma_theta: expected a number");
  const std::string misspelt = scene_text(kViscous, noise("sigma = 0.1\nsigma_thet = 0.1"));
  expect_error(misspelt, at(misspelt, "sigma_thet", 1), "did you mean 'sigma_theta'?");
  // A parameter of the noise without [noise]: in another table, or at the top level.
  const std::string elsewhere = scene_text(kViscous, "[filter]\nsigma = 0.1\n");
  expect_error(elsewhere, at(elsewhere, "sigma", 1), "it belongs in [noise]");
  const std::string top = "seed = 3\n" + scene_text(kViscous);
  expect_error(top, "s.toml:1:1", "it belongs in [noise]");
  const std::string residual_elsewhere = scene_text(kViscous, "[filter]\nfile = \"B.csv\"\n");
  expect_error(residual_elsewhere, at(residual_elsewhere, "file", 1), "it belongs in [residual]");
}

TEST(SceneEffects, RunCsvReportsTheMeasuredAndTheTruePose) {
  // With [noise] x, y, theta are the measured pose and x_true, y_true, theta_true come last; with
  // the residual the balance's velocity is in vx_model, vy_model, omega_model.
  const TempDir tmp;
  tmp.write("B.csv", residual_csv(0.01));
  const std::string path = tmp.write(
      "s.toml", scene_text(kViscous, "[residual]\nfile = \"B.csv\"\n" +
                                         noise("sigma = 0.01\nsigma_theta = 0.02\nseed = 1")));
  const Scene scene = read_scene(path);
  const Simulator sim = compose(scene);
  const RunResult result = write_run(scene, sim, tmp.dir / "out.csv", {}, nullptr);
  const std::vector<std::string>& cols = result.columns;
  ASSERT_GE(cols.size(), 10U);
  EXPECT_EQ(cols[7], "vx_model");
  EXPECT_EQ(cols[cols.size() - 3], "x_true");
  EXPECT_EQ(cols.back(), "theta_true");
  std::ifstream in(tmp.dir / "out.csv");
  std::string header;
  std::string row;
  std::getline(in, header);
  std::getline(in, row);
  std::getline(in, row);  // the second frame (t = dt)
  std::vector<double> cells;
  std::size_t start = 0;
  while (start <= row.size()) {
    const std::size_t comma = row.find(',', start);
    cells.push_back(std::stod(row.substr(start, comma - start)));
    if (comma == std::string::npos) {
      break;
    }
    start = comma + 1;
  }
  ASSERT_EQ(cells.size(), cols.size());
  const std::vector<Frame> frames = run(scene);
  EXPECT_EQ(cells[1], frames[1].measured.x);
  EXPECT_EQ(cells[cells.size() - 3], frames[1].pose.x);
  EXPECT_NE(cells[1], cells[cells.size() - 3]);
}

TEST(SceneEffects, StepsDoNotAllocateWithEveryEffectOn) {
  // Anisotropy, Coulomb, filter, residual, noise and a slope at once: between the second frame
  // and the last nothing is allocated (the sink itself allocates nothing).
  const TempDir tmp;
  tmp.write("B.csv", residual_csv(0.01));
  for (const std::string& law : {kAnisotropic, kCoulomb, kAnisotropicCoulomb}) {
    const std::string path =
        tmp.write("s.toml", scene_text(law, "[filter]\n[residual]\nfile = \"B.csv\"\n" +
                                                noise("sigma = 0.01\nsigma_theta = 0.02") +
                                                "[terrain]\nkind = \"slope\"\nangle_deg = 5\n"));
    const Simulator sim = compose(read_scene(path));
    EXPECT_EQ(sim.kernel_name.find("+filter+residual+noise"), sim.kernel_name.find('+'))
        << sim.kernel_name;
    long long first = 0;
    long long last = -1;
    const long long steps = sim.options.steps;
    (void)sim.run([&](const connection::TrajectoryStep& s) {
      if (s.n == 1) {
        first = slipwalk::testing::allocation_count();
      } else if (s.n == steps) {
        last = slipwalk::testing::allocation_count();
      }
    });
    EXPECT_EQ(last, first) << law;
  }
}

TEST(SceneEffects, StudyLawOverrideKeepsTheScenesWAndRefusesALawWithoutIt) {
  // A [[scene]] override equals writing the key in the scene file: law = "coulomb" next to w is
  // anisotropic Coulomb (the same ellipses), law = "viscous" next to w an error; so are the
  // overrides.
  const TempDir tmp;
  std::filesystem::create_directories(tmp.dir / "scenes");
  tmp.write("scenes/a.toml", scene_text(kAnisotropic));
  tmp.write("scenes/c.toml", scene_text(kAnisotropicCoulomb));
  tmp.write(
      "study.toml",
      "title = \"t\"\n[[scene]]\nname = \"s\"\nfile = \"scenes/a.toml\"\nlaw = \"coulomb\"\n");
  const scene::Scene switched = sweeps::load_study(tmp.dir).scenes.at(0).scene;
  const scene::Scene written = read_scene(tmp.dir / "scenes/c.toml");
  EXPECT_EQ(switched.friction.law, connection::FrictionLaw::kCoulomb);
  EXPECT_FALSE(switched.friction.anisotropic);
  EXPECT_EQ(switched.friction.w, written.friction.w);
  expect_same_motion(run(switched), run(written));
  for (const char* file : {"a.toml", "c.toml"}) {
    tmp.write("study.toml", std::string("title = \"t\"\n[[scene]]\nname = \"s\"\nfile = "
                                        "\"scenes/") +
                                file + "\"\nlaw = \"viscous\"\n");
    try {
      (void)sweeps::load_study(tmp.dir);
      ADD_FAILURE() << "no error for " << file;
    } catch (const core::InputError& e) {
      EXPECT_NE(e.where().find("study.toml:5:7"), std::string::npos) << e.where();
      EXPECT_NE(std::string(e.what()).find("w (anisotropy)"), std::string::npos) << e.what();
    }
  }
  tmp.write("study.toml", "title = \"t\"\n[[scene]]\nname = \"s\"\nfile = \"scenes/a.toml\"\n");
  EXPECT_TRUE(sweeps::load_study(tmp.dir).scenes.at(0).scene.friction.anisotropic);
}

}  // namespace
}  // namespace slipwalk::scene
