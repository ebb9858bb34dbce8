// The friction law table (friction_laws.hpp): one entry per law. A new law is one entry here (and,
// if it needs a policy type of its own, that type in LawPolicy).
#include "scene/friction_laws.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "contact/robot.hpp"
#include "core/csv.hpp"
#include "scene/effects.hpp"
#include "scene/ranges.hpp"

namespace slipwalk::scene {

namespace {

void nothing_to_read(const TableReader&, int, FrictionEffect&) {}
void no_parameters(const FrictionEffect&, nlohmann::json&) {}
void robot_as_is(const FrictionEffect&, contact::Robot&) {}

// The anisotropy w of eq. 3.19 (H ∝ I + w wᵀ; Coulomb's ellipse Fᵀ G⁻¹ F ≤ (μ F_z)², G = I + w wᵀ),
// shared by the laws that take it: one reader, one JSON form, one way onto the robot. An effect
// without w (0 columns) leaves the robot isotropic.

void w_json(const FrictionEffect& effect, nlohmann::json& out) {
  if (effect.w.cols() == 0) {
    return;
  }
  nlohmann::json w = nlohmann::json::array();
  for (Eigen::Index k = 0; k < effect.w.cols(); ++k) {
    w.push_back({effect.w(0, k), effect.w(1, k)});
  }
  out["w"] = w;
}

void fit_w(const FrictionEffect& effect, contact::Robot& robot) {
  if (effect.w.cols() == 0) {
    return;
  }
  // One w for every leg, or one per leg (the reader checked the count).
  if (effect.w.cols() == 1) {
    robot.w = effect.w.replicate(1, robot.legs());
  } else {
    robot.w = effect.w;
  }
  contact::validate(robot);
}

}  // namespace

const std::vector<FrictionLawEntry>& friction_laws() {
  using connection::FrictionLaw;
  using nlohmann::json;
  static const std::vector<FrictionLawEntry> laws = {
      // Viscous-Coulomb, isotropic (§3.4): the robot's own μ, w = 0.
      {
          .name = "viscous",
          .law = FrictionLaw::kViscousCoulomb,
          .anisotropic = false,
          .keys = {},
          .read = &nothing_to_read,
          .to_json = &no_parameters,
          .policy = [](const FrictionEffect&) -> LawPolicy {
            return connection::ViscousCoulombKernel{};
          },
          .fit_robot = &robot_as_is,
      },
      // Viscous-Coulomb with H_k ∝ I + w_k w_kᵀ (eq. 3.19): the same solver, w on the robot.
      {
          .name = "anisotropic",
          .law = FrictionLaw::kViscousCoulomb,
          .anisotropic = true,
          .keys = {"w"},
          .read =
              [](const TableReader& friction, int legs, FrictionEffect& effect) {
                effect.w = read_anisotropy(friction, friction.required("w"), legs);
              },
          .to_json = &w_json,
          .policy = [](const FrictionEffect&) -> LawPolicy {
            return connection::ViscousCoulombKernel{};
          },
          .fit_robot = &fit_w,
      },
      // Classical Coulomb friction (§3.4), the reference, solved to a relative duality gap;
      // optionally anisotropic (the friction ellipses of eq. 3.19's G = I + w wᵀ, the same w as
      // the anisotropic viscous law). `anisotropic` stays false: it names the viscous entry.
      {
          .name = "coulomb",
          .law = FrictionLaw::kCoulomb,
          .anisotropic = false,
          .keys = {"tol", "max_iterations", "w"},
          .read =
              [](const TableReader& friction, int legs, FrictionEffect& effect) {
                if (const toml::node* w = friction.find("w")) {
                  effect.w = read_anisotropy(friction, *w, legs);
                }
                friction.read_in("tol", ranges::kCoulombTolerance, effect.coulomb.tol);
                if (const toml::node* n = friction.find("max_iterations")) {
                  const long long m = friction.integer(*n, "max_iterations");
                  friction.check(m >= 1 && m <= 1'000'000, *n, "max_iterations",
                                 "must be from 1 to 1000000, got " + std::to_string(m));
                  effect.coulomb.max_iterations = static_cast<int>(m);
                }
              },
          .to_json =
              [](const FrictionEffect& effect, json& out) {
                out["tol"] = effect.coulomb.tol;
                out["max_iterations"] = effect.coulomb.max_iterations;
                w_json(effect, out);
              },
          .policy = [](const FrictionEffect& effect) -> LawPolicy {
            return connection::CoulombKernel{effect.coulomb};
          },
          .fit_robot = &fit_w,
      },
  };
  return laws;
}

const FrictionLawEntry& friction_law_of(const FrictionEffect& effect) {
  for (const FrictionLawEntry& entry : friction_laws()) {
    if (entry.law == effect.law && entry.anisotropic == effect.anisotropic) {
      return entry;
    }
  }
  throw std::logic_error("scene: a friction effect without a table entry");
}

const FrictionLawEntry* find_friction_law(std::string_view name) {
  for (const FrictionLawEntry& entry : friction_laws()) {
    if (entry.name == name) {
      return &entry;
    }
  }
  return nullptr;
}

std::vector<std::string_view> friction_table_keys() {
  std::vector<std::string_view> keys = {"law"};
  for (const FrictionLawEntry& entry : friction_laws()) {
    for (std::string_view k : entry.keys) {
      if (!contains(keys, k)) {
        keys.push_back(k);
      }
    }
  }
  return keys;
}

FrictionEffect read_friction(const TableReader& friction, int legs) {
  std::vector<std::string_view> names;
  for (const FrictionLawEntry& entry : friction_laws()) {
    names.push_back(entry.name);
  }
  const std::string law = friction.choice(friction.required("law"), "law", names);
  const std::string chosen = "law = '" + law + "'";
  const std::vector<std::string_view> keys = friction_table_keys();
  for (auto key = keys.begin() + 1; key != keys.end(); ++key) {
    std::vector<std::string_view> owners;
    for (const FrictionLawEntry& entry : friction_laws()) {
      if (contains(entry.keys, *key)) {
        owners.push_back(entry.name);
      }
    }
    if (!contains(owners, law)) {
      friction.forbid(*key, owner_phrase(owners, "law"), chosen);
    }
  }
  const auto entry = std::find_if(friction_laws().begin(), friction_laws().end(),
                                  [&](const FrictionLawEntry& e) { return e.name == law; });
  FrictionEffect effect;
  effect.law = entry->law;
  effect.anisotropic = entry->anisotropic;
  entry->read(friction, legs, effect);
  return effect;
}

nlohmann::json friction_json(const FrictionEffect& effect) {
  const FrictionLawEntry& entry = friction_law_of(effect);
  nlohmann::json out = {{"law", std::string(entry.name)}};
  entry.to_json(effect, out);
  return out;
}

}  // namespace slipwalk::scene
