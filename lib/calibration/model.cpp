#include "calibration/model.hpp"

#include <Eigen/QR>
#include <array>
#include <cmath>
#include <numbers>
#include <set>

#include "core/error.hpp"

namespace slipwalk::calibration {

namespace {

constexpr std::array<std::string_view, 6> kAxisLabels = {"+x", "-x", "+y", "-y", "+z", "-z"};

bool well_formed_name(const std::string& name) {
  if (name.empty()) {
    return false;
  }
  for (const char c : name) {
    const bool ok =
        (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) {
      return false;
    }
  }
  return true;
}

}  // namespace

void validate(const Geometry& geometry) {
  if (geometry.legs.empty()) {
    throw core::InputError("geometry.legs", "names no transducer");
  }
  if (geometry.transducer.size() != geometry.legs.size()) {
    throw core::InputError("geometry.transducer",
                           "has " + std::to_string(geometry.transducer.size()) + " frames for " +
                               std::to_string(geometry.legs.size()) + " legs");
  }
  std::set<std::string> seen;
  for (std::size_t k = 0; k < geometry.legs.size(); ++k) {
    const std::string& name = geometry.legs[k];
    const std::string where = "geometry.legs[" + std::to_string(k) + "]";
    if (!well_formed_name(name)) {
      throw core::InputError(where, "'" + name + "' is not a name of letters, digits and '_'");
    }
    if (!seen.insert(name).second) {
      throw core::InputError(where, "'" + name + "' names two legs");
    }
    const Frame& frame = geometry.transducer[k];
    const std::string fwhere = "geometry.transducer[" + name + "]";
    if (!frame.R.allFinite() || !frame.p.allFinite()) {
      throw core::InputError(fwhere, "is not finite");
    }
    if ((frame.R.transpose() * frame.R - Eigen::Matrix3d::Identity()).norm() > 1e-9 ||
        frame.R.determinant() <= 0.0) {
      throw core::InputError(fwhere + ".rotation", "is not a proper rotation");
    }
    if (frame.p.norm() > 100.0) {
      throw core::InputError(fwhere + ".position", "lies more than 100 m from the body origin");
    }
  }
  if (!std::isfinite(geometry.robot_weight) || geometry.robot_weight <= 0.0) {
    throw core::InputError("geometry.robot_weight", "must be a positive weight in N");
  }
}

std::string_view axis_label(BodyAxis axis) {
  return kAxisLabels.at(static_cast<std::size_t>(axis));
}

std::optional<BodyAxis> parse_axis(std::string_view label) {
  for (std::size_t i = 0; i < kAxisLabels.size(); ++i) {
    if (kAxisLabels[i] == label) {
      return static_cast<BodyAxis>(i);
    }
  }
  return std::nullopt;
}

Eigen::Vector3d axis_vector(BodyAxis axis) {
  const auto i = static_cast<int>(axis);
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  v(i / 2) = (i % 2 == 0) ? 1.0 : -1.0;
  return v;
}

BodyAxis opposite(BodyAxis axis) {
  const auto i = static_cast<int>(axis);
  return static_cast<BodyAxis>(i % 2 == 0 ? i + 1 : i - 1);
}

Eigen::Vector3d PeriodicFit::operator()(double phi) const {
  Eigen::Vector3d value = coefficients.col(0);
  for (Eigen::Index h = 1; h <= harmonics(); ++h) {
    const double a = 2.0 * std::numbers::pi * static_cast<double>(h) * phi;
    value += coefficients.col(2 * h - 1) * std::cos(a) + coefficients.col(2 * h) * std::sin(a);
  }
  return value;
}

PeriodicFit fit_periodic(const Eigen::VectorXd& phi, const Eigen::Matrix3Xd& values,
                         int harmonics) {
  if (harmonics < 0) {
    throw core::InputError("harmonics", "must be 0 or more");
  }
  const Eigen::Index columns = 1 + 2 * harmonics;
  if (phi.size() != values.cols() || phi.size() < columns) {
    throw core::InputError("harmonics", std::to_string(harmonics) + " harmonics need at least " +
                                            std::to_string(columns) + " samples, got " +
                                            std::to_string(phi.size()));
  }
  Eigen::MatrixXd basis(phi.size(), columns);
  for (Eigen::Index i = 0; i < phi.size(); ++i) {
    basis(i, 0) = 1.0;
    for (Eigen::Index h = 1; h <= harmonics; ++h) {
      const double a = 2.0 * std::numbers::pi * static_cast<double>(h) * phi(i);
      basis(i, 2 * h - 1) = std::cos(a);
      basis(i, 2 * h) = std::sin(a);
    }
  }
  PeriodicFit fit;
  fit.coefficients = basis.colPivHouseholderQr().solve(values.transpose()).transpose();
  return fit;
}

}  // namespace slipwalk::calibration
