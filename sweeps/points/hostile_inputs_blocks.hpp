#pragma once
// The building blocks of the hostile-input generators (hostile_inputs.hpp): a per-case random
// stream, hostile values, and the template inputs (a frame, a robot, a CSV batch, scenes, a sweep
// spec) as lists of fields that a generator can set one at a time. The templates are small,
// valid inputs in the shape of the shipped examples (studies/ch3_legged, the DESIGN.md frame
// format), each a fraction of a second to run.
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "sweeps/points/hostile_inputs.hpp"

namespace slipwalk::sweeps::hostile {

/// The random stream of case `index` of class `cls` under `seed`: independent of every other
/// case, so a case replays alone.
class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t cls, long long index);
  double uniform(double lo, double hi);
  long long integer(long long lo, long long hi);  ///< [lo, hi]
  bool coin(double p = 0.5);
  template <class T>
  const T& pick(const std::vector<T>& v) {
    return v[static_cast<std::size_t>(integer(0, static_cast<long long>(v.size()) - 1))];
  }

 private:
  std::mt19937_64 g_;
};

enum class Syntax { kCli, kToml, kJson };

/// A hostile number as text: 0, −0, NaN, ±inf, subnormals, ±10^k for k in −320…308 with a
/// random mantissa, or a plain value near `typical` (×10^±3, either sign). NaN and inf are
/// written as each syntax allows (TOML nan/inf; JSON has none: 1e999 or a bare NaN).
std::string hostile_number(Rng& rng, Syntax syntax, double typical = 1.0);
/// A finite double as the syntax writes it (TOML: always with a '.' or an exponent).
std::string number_text(double x, Syntax syntax);
/// 10^U(lo, hi).
double log_uniform(Rng& rng, double lo, double hi);

/// A value of an input, as text in its syntax, and the key that holds it.
struct Field {
  std::string key;
  std::string value;
};
/// A TOML table: its header line ("[run]", "[[robot.leg]]") and its fields.
struct Table {
  std::string header;
  std::vector<Field> fields;
};

/// JSON object text with one key a line (so line numbers point at keys).
std::string json_object(const std::vector<Field>& fields, const std::string& eol = "\n");
std::string toml_text(const std::vector<Table>& tables, const std::string& eol = "\n");

/// The frame of the DESIGN.md format: three feet below a body, Mg = 9.81.
std::vector<Field> frame_fields();
/// The robot file of a CSV batch (3 legs) and its batch of `rows` frames.
std::vector<Field> robot_fields();
std::string batch_csv(Rng& rng, long long rows, const std::string& eol = "\n");
/// A numeric leaf of a JSON array value ("[[1, 2], [3, 4]]"): replaces a random one.
std::string replace_random_leaf(Rng& rng, const std::string& array, const std::string& with);

/// Scene templates of every robot and effect the scene format has, 0.2–0.5 s of 0.01 s steps.
std::vector<std::vector<Table>> scene_templates();
/// A sweep spec of `points` inchworm_vss points (study "test", name "grid").
std::vector<Table> spec_tables(long long points, const std::string& method = "exact");

/// Cases of the common commands (paths relative to the case folder).
Case model_case(const std::string& title, const std::string& frame_text, bool coulomb);
Case batch_case(const std::string& title, const std::string& robot_text,
                const std::string& csv_text);
Case scene_case(const std::string& title, const std::string& scene_text);
Case spec_case(const std::string& title, const std::string& spec_text);

}  // namespace slipwalk::sweeps::hostile
