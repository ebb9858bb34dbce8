#pragma once
// Frames for the numeric fuzz targets (spring support, Coulomb friction), from arbitrary bytes in
// one of two forms: text starting with '{' is the frame format of `slipwalk model`
// (contact::parse_frame_json, validated as the tool validates it), so the shipped robots seed
// the corpus; anything else is decoded as a robot of 1 … 64 legs and one frame of it, the
// doubles drawn from every class (raw bit patterns: NaN, ±inf, subnormals; 10^-320 … 10^308;
// ordinary values), and refused through contact::validate and contact::check_frame exactly as
// the tool refuses a bad frame.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>

#include "contact/frame_json.hpp"
#include "contact/robot.hpp"
#include "core/error.hpp"

namespace slipwalk::fuzz {

/// Reads bytes front to back; past the end every read gives zeros.
class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}

  std::uint8_t byte() {
    return pos_ < bytes_.size() ? static_cast<std::uint8_t>(bytes_[pos_++]) : std::uint8_t{0};
  }

  /// A double of a class picked by one byte: raw bits, a special value, a power of ten from
  /// 10^-320 to 10^308, or (most often) a value from −32.768 to 32.767 in steps of 0.001.
  double number() {
    const std::uint8_t tag = byte();
    switch (tag % 8) {
      case 0: {
        std::uint64_t bits = 0;
        for (int i = 0; i < 8; ++i) {
          bits = bits << 8U | byte();
        }
        double x = 0.0;
        std::memcpy(&x, &bits, sizeof x);
        return x;
      }
      case 1: {
        using limits = std::numeric_limits<double>;
        constexpr double kSpecial[] = {0.0,
                                       -0.0,
                                       1.0,
                                       -1.0,
                                       limits::quiet_NaN(),
                                       limits::infinity(),
                                       -limits::infinity(),
                                       limits::max(),
                                       -limits::max(),
                                       limits::min(),
                                       limits::denorm_min(),
                                       limits::epsilon(),
                                       1e-320,
                                       1e308};
        return kSpecial[byte() % std::size(kSpecial)];
      }
      case 2: {
        const int exponent = word() % 629 - 320;
        const double mantissa = static_cast<double>(static_cast<std::int8_t>(byte())) / 16.0;
        return mantissa * std::pow(10.0, exponent);
      }
      default: {
        return static_cast<double>(word() - 32768) / 1000.0;
      }
    }
  }

 private:
  /// Two bytes, low first: 0 … 65535.
  int word() {
    const int low = byte();
    return low | byte() << 8;
  }

  std::string_view bytes_;
  std::size_t pos_ = 0;
};

/// The robot and frame the bytes describe, or nullopt if the tool would refuse them.
inline std::optional<contact::FrameInput> decode_frame(std::string_view bytes) {
  if (!bytes.empty() && bytes.front() == '{') {
    try {
      return contact::parse_frame_json(bytes, "fuzz.json");
    } catch (const core::InputError&) {
      return std::nullopt;
    }
  }
  ByteReader in(bytes);
  const int legs = 1 + in.byte() % 64;
  const std::uint8_t shape = in.byte();  // which constants vary per leg
  contact::Robot robot = contact::uniform_robot(legs);
  const double K = in.number();
  const double mu = in.number();
  for (int j = 0; j < legs; ++j) {
    robot.K(j) = (shape & 1U) != 0 ? in.number() : K;
    robot.mu(j) = (shape & 2U) != 0 ? in.number() : mu;
    if ((shape & 4U) != 0) {
      robot.w(0, j) = in.number();
      robot.w(1, j) = in.number();
    }
  }
  robot.Mg = (shape & 8U) != 0 ? in.number() : 1.0;
  try {
    contact::validate(robot);
  } catch (const core::InputError&) {
    return std::nullopt;
  }
  contact::FrameInput input(robot);
  for (int j = 0; j < legs; ++j) {
    for (int i = 0; i < 3; ++i) {
      input.frame.q(i, j) = in.number();
    }
    for (int i = 0; i < 3; ++i) {
      input.frame.qdot(i, j) = in.number();
    }
  }
  input.frame.theta = in.number();
  try {
    contact::check_frame(input.robot, input.frame);
  } catch (const core::InputError&) {
    return std::nullopt;
  }
  return input;
}

}  // namespace slipwalk::fuzz
