// The building blocks of the hostile-input generators (hostile_inputs_blocks.hpp).
#include "sweeps/points/hostile_inputs_blocks.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace slipwalk::sweeps::hostile {

namespace {

std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30U)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27U)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31U);
}

}  // namespace

Rng::Rng(std::uint64_t seed, std::uint64_t cls, long long index)
    : g_(splitmix(splitmix(splitmix(seed) ^ cls) ^ static_cast<std::uint64_t>(index))) {}

double Rng::uniform(double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(g_);
}
long long Rng::integer(long long lo, long long hi) {
  return std::uniform_int_distribution<long long>(lo, hi)(g_);
}
bool Rng::coin(double p) { return uniform(0.0, 1.0) < p; }

double log_uniform(Rng& rng, double lo, double hi) {
  return std::pow(10.0, rng.uniform(std::log10(lo), std::log10(hi)));
}

std::string number_text(double x, Syntax syntax) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  std::string s = buf;
  if (syntax == Syntax::kToml && s.find_first_of(".e") == std::string::npos) {
    s += ".0";
  }
  return s;
}

std::string hostile_number(Rng& rng, Syntax syntax, double typical) {
  const auto nonfinite = [&](int sign, bool nan) -> std::string {
    switch (syntax) {
      case Syntax::kCli:
        return nan ? (sign < 0 ? "-nan" : "nan") : (sign < 0 ? "-inf" : "inf");
      case Syntax::kToml:
        return nan ? "nan" : (sign < 0 ? "-inf" : "inf");
      case Syntax::kJson:
        return nan ? (rng.coin() ? "NaN" : "1e999") : (sign < 0 ? "-1e999" : "1e999");
    }
    return "nan";
  };
  const int sign = rng.coin() ? 1 : -1;
  switch (rng.integer(0, 9)) {
    case 0:
      return rng.coin() ? number_text(0.0, syntax) : (syntax == Syntax::kToml ? "-0.0" : "-0");
    case 1:
      return nonfinite(sign, true);
    case 2:
      return nonfinite(sign, false);
    case 3: {  // subnormal: below the smallest normal double
      const double x = std::numeric_limits<double>::denorm_min() *
                       static_cast<double>(rng.integer(1, 1'000'000'000));
      return number_text(sign * x, syntax);
    }
    case 4:
    case 5:
    case 6: {  // any magnitude of a double
      const double e = rng.uniform(-320.0, 308.2);
      return number_text(sign * rng.uniform(1.0, 9.99) * std::pow(10.0, std::floor(e)), syntax);
    }
    case 7:  // the edges: largest, smallest normal
      return number_text(sign * (rng.coin() ? std::numeric_limits<double>::max()
                                            : std::numeric_limits<double>::min()),
                         syntax);
    default:  // near the usual value, either sign
      return number_text((rng.coin(0.8) ? 1 : -1) * typical * log_uniform(rng, 1e-3, 1e3), syntax);
  }
}

std::string json_object(const std::vector<Field>& fields, const std::string& eol) {
  std::string s = "{" + eol;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    s += "  \"" + fields[i].key + "\": " + fields[i].value + (i + 1 < fields.size() ? "," : "") +
         eol;
  }
  return s + "}" + eol;
}

std::string toml_text(const std::vector<Table>& tables, const std::string& eol) {
  std::string s;
  for (const Table& t : tables) {
    if (!t.header.empty()) {
      s += t.header + eol;
    }
    for (const Field& f : t.fields) {
      s += f.key + " = " + f.value + eol;
    }
  }
  return s;
}

std::vector<Field> frame_fields() {
  return {{"q", "[[0.3, 0.2, -0.1], [-0.3, 0.2, -0.1], [0.0, -0.25, -0.1]]"},
          {"qdot", "[[-0.1, 0.0, 0.0], [-0.1, 0.01, 0.0], [-0.12, 0.0, 0.0]]"},
          {"K", "[100.0, 100.0, 100.0]"},
          {"Mg", "9.81"},
          {"mu", "[1.0, 1.0, 1.0]"},
          {"w", "[[0.0, 0.0], [0.1, 0.0], [0.0, 0.2]]"},
          {"theta", "0.0"}};
}

std::vector<Field> robot_fields() {
  return {{"K", "[100.0, 100.0, 100.0]"}, {"mu", "[1.0, 1.0, 1.0]"}, {"Mg", "9.81"}};
}

std::string batch_csv(Rng& rng, long long rows, const std::string& eol) {
  std::string s =
      "theta,q0x,q0y,q0z,qd0x,qd0y,qd0z,q1x,q1y,q1z,qd1x,qd1y,qd1z,q2x,q2y,q2z,qd2x,"
      "qd2y,qd2z" +
      eol;
  for (long long r = 0; r < rows; ++r) {
    const double th = rng.uniform(-0.5, 0.5);
    const double vx = rng.uniform(-0.2, 0.2);
    s += number_text(th, Syntax::kCli) + ",0.2,0.1,-0.1," + number_text(vx, Syntax::kCli) +
         ",0,0,-0.2,0.1,-0.1," + number_text(vx, Syntax::kCli) + ",0,0,0,-0.15,-0.1,-0.2,0,0" + eol;
  }
  return s;
}

std::string replace_random_leaf(Rng& rng, const std::string& array, const std::string& with) {
  // The leaves are the runs of characters between '[', ',' and ']'.
  std::vector<std::pair<std::size_t, std::size_t>> leaves;
  std::size_t start = std::string::npos;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const char c = array[i];
    if (c == '[' || c == ',' || c == ']') {
      if (start != std::string::npos && i > start) {
        leaves.emplace_back(start, i);
      }
      start = c == ']' ? std::string::npos : i + 1;
    }
  }
  if (leaves.empty()) {
    return with;
  }
  const auto [a, b] =
      leaves[static_cast<std::size_t>(rng.integer(0, static_cast<long long>(leaves.size()) - 1))];
  return array.substr(0, a) + " " + with + array.substr(b);
}

std::vector<std::vector<Table>> scene_templates() {
  const Table run = {"[run]", {{"duration", "0.3"}, {"dt", "0.01"}}};
  const Table viscous = {"[friction]", {{"law", "\"viscous\""}}};
  std::vector<std::vector<Table>> out;
  out.push_back({{"[robot]", {{"name", "\"disk\""}, {"legs", "6"}, {"radius", "0.3"}}},
                 {"[gait]", {{"kind", "\"disk\""}}},
                 run,
                 viscous});
  out.push_back(
      {{"[robot]", {{"name", "\"bigant\""}}},
       {"[gait]", {{"kind", "\"tripod\""}, {"frequency", "0.5"}, {"steer", "0.1"}}},
       run,
       {"[friction]",
        {{"law", "\"coulomb\""}, {"tol", "1e-10"}, {"max_iterations", "500"}, {"w", "[0.3, 0.1]"}}},
       {"[filter]", {{"gamma", "0.15"}}},
       {"[noise]", {{"sigma", "0.001"}, {"sigma_theta", "0.01"}, {"seed", "3"}}}});
  out.push_back({{"[robot]", {{"name", "\"bigant\""}}},
                 {"[gait]", {{"kind", "\"metachronal\""}, {"frequency", "0.5"}}},
                 run,
                 {"[friction]", {{"law", "\"anisotropic\""}, {"w", "[0.5, 0.0]"}}},
                 {"[terrain]",
                  {{"kind", "\"slope\""},
                   {"angle_deg", "10.0"},
                   {"heading_deg", "0.0"},
                   {"com_height", "0.05"}}}});
  out.push_back({{"[robot]", {{"name", "\"multipod\""}, {"legs", "8"}, {"stiffness", "1000.0"}}},
                 {"[gait]", {{"kind", "\"undulation\""}, {"frequency", "0.5"}}},
                 run,
                 viscous,
                 {"[terrain]", {{"kind", "\"stairs\""}, {"tread", "0.3"}, {"riser", "0.12"}}}});
  out.push_back({{"[robot]", {{"name", "\"quadruped\""}}},
                 {"[gait]", {{"kind", "\"trot\""}, {"frequency", "1.0"}}},
                 run,
                 viscous});
  std::vector<Table> legs = {{"[robot]", {{"name", "\"legs\""}, {"mass", "8.18"}}}};
  const char* hips[] = {"[0.3, 0.2, 0.0]", "[0.0, -0.2, 0.0]", "[-0.3, 0.2, 0.0]"};
  for (int k = 0; k < 3; ++k) {
    legs.push_back(
        {"[[robot.leg]]",
         {{"hip", hips[k]}, {"K", "2675.0"}, {"mu", "1.0"}, {"phase", k == 1 ? "0.5" : "0.0"}}});
  }
  legs.push_back({"[gait]",
                  {{"kind", "\"foot_path\""},
                   {"frequency", "0.5"},
                   {"stride", "0.1"},
                   {"height", "0.1"},
                   {"lift", "0.03"}}});
  legs.push_back(run);
  legs.push_back(viscous);
  out.push_back(legs);
  return out;
}

std::vector<Table> spec_tables(long long points, const std::string& method) {
  return {
      {"", {{"study", "\"test\""}, {"name", "\"grid\""}, {"kind", "\"inchworm_vss\""}}},
      {"[params]", {{"rtol", "1e-10"}, {"method", "\"" + method + "\""}, {"mu", "1.0"}}},
      {"[axes]", {{"F_frac", "{ linspace = [0.2, 0.9], n = " + std::to_string(points) + " }"}}}};
}

Case model_case(const std::string& title, const std::string& frame_text, bool coulomb) {
  Case c;
  c.title = title;
  c.files = {{"frame.json", frame_text, ""}};
  c.run.args = {"model", "--in", "frame.json"};
  if (coulomb) {
    c.run.args.insert(c.run.args.end(), {"--friction", "coulomb"});
  }
  c.place = "frame.json";
  c.output_kind = Output::kJson;
  return c;
}

Case batch_case(const std::string& title, const std::string& robot_text,
                const std::string& csv_text) {
  Case c;
  c.title = title;
  c.files = {{"robot.json", robot_text, ""}, {"frames.csv", csv_text, ""}};
  c.run.args = {"model", "--robot", "robot.json", "--in", "frames.csv", "--out", "out.csv"};
  c.outputs = {"out.csv"};
  c.output = "out.csv";
  c.output_kind = Output::kCsv;
  return c;
}

Case scene_case(const std::string& title, const std::string& scene_text) {
  Case c;
  c.title = title;
  c.files = {{"scene.toml", scene_text, ""}};
  c.run.args = {"run", "scene.toml", "--out", "out.csv"};
  c.place = "scene.toml";
  c.outputs = {"out.csv", "out.json"};
  c.output = "out.csv";
  c.output_kind = Output::kCsv;
  return c;
}

Case spec_case(const std::string& title, const std::string& spec_text) {
  Case c;
  c.title = title;
  c.files = {{"grid.toml", spec_text, ""}};
  c.run.args = {"sweep", "grid.toml", "--data", "data", "--jobs", "1", "--no-timing"};
  c.place = "grid.toml";
  c.outputs = {"data/test/grid.csv", "data/test/grid.json"};
  return c;
}

}  // namespace slipwalk::sweeps::hostile
