// The hostile-input classes (hostile_inputs.hpp): the table, and the generators of the classes
// whose inputs are values — nesting depth and size, runaway loops, extreme magnitudes. The
// classes about files, signals and devices are in hostile_inputs_files.cpp.
#include "sweeps/points/hostile_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sweeps/points/hostile_inputs_blocks.hpp"

namespace slipwalk::sweeps::hostile {

Case signal_case(std::uint64_t seed, long long index);
Case path_case(std::uint64_t seed, long long index);
Case loss_case(std::uint64_t seed, long long index);

namespace {

std::string repeat(const std::string& s, long long n) {
  std::string out;
  out.reserve(s.size() * static_cast<std::size_t>(n));
  for (long long i = 0; i < n; ++i) {
    out += s;
  }
  return out;
}

/// A Python string literal inside a shell double-quoted argument.
std::string py(const std::string& s) {
  std::string out = "'";
  for (const char c : s) {
    out += c == '"' ? std::string("\\\"") : (c == '\n' ? std::string("\\n") : std::string(1, c));
  }
  return out + "'";
}

/// A shell line writing before, open×n, middle, close×n, after (replays of deep files).
std::string nest_recipe(const std::string& open, const std::string& close, long long n,
                        const std::string& before = "", const std::string& middle = "",
                        const std::string& after = "") {
  const std::string k = std::to_string(n);
  return "python3 -c \"import sys; sys.stdout.write(" + py(before) + " + " + py(open) + " * " + k +
         " + " + py(middle) + " + " + py(close) + " * " + k + " + " + py(after) + ")\"";
}

std::string option_place(const std::string& arg) { return arg.substr(0, arg.find('=')); }

// ---- 1. nesting depth, long strings, huge numbers ------------------------------------------

Case depth_case(std::uint64_t seed, long long index) {
  Rng rng(seed, 1, index);
  const auto d = static_cast<long long>(std::llround(log_uniform(rng, 10.0, 1e6)));
  const std::string n = std::to_string(d);
  Case c;
  switch (rng.integer(0, 8)) {
    case 0: {  // a frame file that is nothing but nested arrays or objects
      const bool arrays = rng.coin();
      const std::string open = arrays ? "[" : "{\"a\":";
      const std::string close = arrays ? "]" : "}";
      c = model_case("frame JSON of " + n + " nested " + (arrays ? "arrays" : "objects"),
                     repeat(open, d) + (arrays ? "" : "1") + repeat(close, d), false);
      c.files[0].recipe = nest_recipe(open, close, d, "", arrays ? "" : "1");
      break;
    }
    case 1: {  // a frame whose q is nested d deep
      c = model_case("frame JSON with q nested " + n + " deep",
                     "{\"q\": " + repeat("[", d) + "0.1" + repeat("]", d) + "}", rng.coin());
      c.files[0].recipe = nest_recipe("[", "]", d, "{\"q\": ", "0.1", "}");
      break;
    }
    case 2: {  // the robot file of a batch, nested
      Rng rows(seed, 101, index);
      c = batch_case("robot JSON with K nested " + n + " deep",
                     "{\"K\": " + repeat("[", d) + repeat("]", d) + "}", batch_csv(rows, 3));
      c.place = "robot.json";
      c.files[0].recipe = nest_recipe("[", "]", d, "{\"K\": ", "", "}");
      break;
    }
    case 3: {  // a scene's w as nested arrays
      std::vector<Table> s = scene_templates()[2];
      s[3].fields[1].value = repeat("[", d) + "0.5" + repeat("]", d);
      c = scene_case("scene with w nested " + n + " deep", toml_text(s));
      break;
    }
    case 4: {  // a scene with nested inline tables
      std::vector<Table> s = scene_templates()[0];
      s[2].fields.push_back({"x", repeat("{a = ", d) + "1" + repeat("}", d)});
      c = scene_case("scene with inline tables nested " + n + " deep", toml_text(s));
      break;
    }
    case 5: {  // a sweep spec's axis as nested arrays
      std::vector<Table> s = spec_tables(2);
      s[2].fields[0].value = repeat("[", d) + "0.5" + repeat("]", d);
      c = spec_case("spec axis nested " + n + " deep", toml_text(s));
      break;
    }
    case 6: {  // a long string where a value or a name belongs
      const auto len = static_cast<long long>(log_uniform(rng, 1e3, 3e6));
      const std::string text(static_cast<std::size_t>(len), 'x');
      const std::string l = std::to_string(len);
      switch (rng.integer(0, 3)) {
        case 0: {
          std::vector<Field> f = frame_fields();
          f[3].value = "\"" + text + "\"";
          c = model_case("frame JSON with Mg a string of " + l + " chars", json_object(f), false);
          break;
        }
        case 1: {
          std::vector<Table> s = scene_templates()[0];
          s[0].fields[0].value = "\"" + text + "\"";
          c = scene_case("scene with a robot name of " + l + " chars", toml_text(s));
          break;
        }
        case 2: {
          std::vector<Table> s = spec_tables(2);
          s[0].fields[1].value = "\"" + text + "\"";
          c = spec_case("spec name of " + l + " chars", toml_text(s));
          break;
        }
        default: {
          c.title = "--force of " + std::to_string(std::min(len, 100000LL)) + " letters";
          c.run.args = {
              "inchworm", "vss", "--mu", "1",
              "--force=" + text.substr(0, static_cast<std::size_t>(std::min(len, 100000LL)))};
          c.place = "--force";
          break;
        }
      }
      c.exits = {2};
      return c;
    }
    case 7: {  // a number literal with thousands of digits
      const auto digits = static_cast<long long>(log_uniform(rng, 1e2, 1e5));
      const std::string k(static_cast<std::size_t>(digits), rng.coin() ? '0' : '9');
      const std::vector<std::string> forms = {"1" + k, "0." + k + "1", "1e" + k, "-1" + k};
      const std::string lit = rng.pick(forms);
      const std::string what = "a number of " + std::to_string(lit.size()) + " characters";
      switch (rng.integer(0, 3)) {
        case 0: {
          std::vector<Field> f = frame_fields();
          f[3].value = lit;
          c = model_case("frame JSON with Mg " + what, json_object(f), false);
          c.place_line = true;
          break;
        }
        case 1: {
          std::vector<Table> s = scene_templates()[0];
          s[2].fields[0].value =
              lit.find('.') == std::string::npos && lit.find('e') == std::string::npos ? lit + ".0"
                                                                                       : lit;
          c = scene_case("scene duration " + what, toml_text(s));
          c.place_line = true;
          break;
        }
        default: {
          c.title = "--force " + what;
          c.run.args = {"inchworm", "vss",    "--mu",
                        "1",        "--json", "--force=" + lit.substr(0, 100000)};
          c.place = "--force";
          c.output_kind = Output::kJson;
          break;
        }
      }
      c.exits = {0, 1, 2};
      return c;
    }
    default: {  // a TOML table header of d dotted keys
      const long long k = std::min(d, 100000LL);
      std::vector<Table> s = scene_templates()[0];
      const std::string head = toml_text(s);
      s.push_back({"[" + repeat("a.", k) + "a]", {{"x", "1"}}});
      c = scene_case("scene table header of " + std::to_string(k) + " dotted keys", toml_text(s));
      c.files[0].recipe = nest_recipe("a.", "", k, head + "[", "a]\nx = 1\n", "");
      break;
    }
  }
  c.exits = {2};
  return c;
}

// ---- 2. loops that must end -------------------------------------------------------------------

const std::vector<std::string> kIntegrators = {"analytic",  "cvode",     "odeint",   "gsl",
                                               "fixed_rk4", "cvode_bdf", "gsl_rkf45"};

std::string force_text(Rng& rng) {
  switch (rng.integer(0, 3)) {
    case 0:
      return "45";
    case 1:
      return "9.82";  // just above the small mass' sliding threshold μ m g
    default:
      return number_text(log_uniform(rng, 15.0, 1e308), Syntax::kCli);
  }
}

Case runaway_case(std::uint64_t seed, long long index) {
  Rng rng(seed, 2, index);
  Case c;
  c.limit_s = 20.0;
  c.place = "";
  switch (rng.integer(0, 5)) {
    case 0: {
      const std::string method = rng.pick(kIntegrators);
      const std::string dt = number_text(log_uniform(rng, 1e-320, 1e-1), Syntax::kCli);
      const std::string cycles = rng.pick(std::vector<std::string>{"1", "6", "100", "10000"});
      c.title = "trace by " + method + ", dt " + dt + ", " + cycles + " cycles";
      c.run.args = {"inchworm",
                    "trace",
                    "--mu=1",
                    "--force=" + force_text(rng),
                    "--method=" + method,
                    "--dt=" + dt,
                    "--cycles=" + cycles,
                    "--rtol=" + number_text(log_uniform(rng, 1e-15, 1e-2), Syntax::kCli),
                    "--out",
                    "t.csv"};
      c.outputs = {"t.csv"};
      c.output = "t.csv";
      c.output_kind = Output::kCsv;
      break;
    }
    case 1: {
      const std::string method = rng.pick(kIntegrators);
      const std::string strokes = std::to_string(
          rng.pick(std::vector<long long>{8, 9, 100, 10000, rng.integer(8, 1'000'000'000)}));
      c.title = "vss by " + method + ", max strokes " + strokes;
      c.run.args = {"inchworm",
                    "vss",
                    "--json",
                    "--mu=1",
                    "--force=" + force_text(rng),
                    "--method=" + method,
                    "--rtol=" + number_text(log_uniform(rng, 1e-16, 0.5), Syntax::kCli),
                    "--max-strokes=" + strokes,
                    "--stop=" + rng.pick(std::vector<std::string>{"estimate", "difference"})};
      c.output_kind = Output::kJson;
      break;
    }
    case 2: {
      std::vector<Table> s = rng.pick(scene_templates());
      Table& run = s[s.size() > 3 && s[0].fields[0].value == "\"legs\"" ? 5 : 2];
      // A run the contract allows (at most scene::kMaxSteps rows) may still take minutes; the
      // steps asked for are either modest (at most 3·10^4, well under a second) or past that bound,
      // which must be refused at once.
      double duration = log_uniform(rng, 1e-3, 1e308);
      if (rng.coin()) {
        const double dt = log_uniform(rng, 1e-320, 10.0);
        if (duration / dt > 3e4 && duration / dt < 1.1e7) {
          duration = 1e3 * dt;
        }
        run.fields[1].value = number_text(dt, Syntax::kToml);
      } else {
        const double steps = rng.coin() ? log_uniform(rng, 1, 3e4) : log_uniform(rng, 1.1e7, 1e9);
        run.fields[1] = {"steps", std::to_string(static_cast<long long>(steps))};
      }
      run.fields[0].value = number_text(duration, Syntax::kToml);
      c = scene_case("scene of duration " + run.fields[0].value + ", " + run.fields[1].key + " " +
                         run.fields[1].value,
                     toml_text(s));
      c.limit_s = 20.0;
      break;
    }
    case 3: {  // Coulomb friction on many feet at random
      const long long legs = rng.integer(3, 300);
      std::string q = "[";
      std::string qd = "[";
      for (long long k = 0; k < legs; ++k) {
        q += std::string(k ? ", " : "") + "[" + number_text(rng.uniform(-0.5, 0.5), Syntax::kJson) +
             ", " + number_text(rng.uniform(-0.5, 0.5), Syntax::kJson) + ", " +
             number_text(rng.uniform(-0.12, -0.08), Syntax::kJson) + "]";
        qd += std::string(k ? ", " : "") + "[" + number_text(rng.uniform(-1, 1), Syntax::kJson) +
              ", " + number_text(rng.uniform(-1, 1), Syntax::kJson) + ", 0.0]";
      }
      c = model_case("Coulomb frame of " + std::to_string(legs) + " random feet",
                     json_object({{"q", q + "]"}, {"qdot", qd + "]"}, {"Mg", "9.81"}}), true);
      c.limit_s = 20.0;
      break;
    }
    case 4: {  // the Coulomb solver's tolerance and iteration bound
      std::vector<Table> s = scene_templates()[1];
      s[3].fields[1].value = number_text(log_uniform(rng, 1e-300, 1.0), Syntax::kToml);
      s[3].fields[2].value = std::to_string(static_cast<long long>(log_uniform(rng, 1.0, 1e12)));
      c = scene_case(
          "Coulomb scene, tol " + s[3].fields[1].value + ", max_iterations " + s[3].fields[2].value,
          toml_text(s));
      c.limit_s = 20.0;
      break;
    }
    default: {  // a long batch of frames
      const auto rows = static_cast<long long>(log_uniform(rng, 1.0, 1e5));
      c = batch_case("batch of " + std::to_string(rows) + " frames", json_object(robot_fields()),
                     batch_csv(rng, rows));
      c.files[1].recipe = "";
      c.limit_s = 20.0;
      break;
    }
  }
  return c;
}

// ---- 3. extreme magnitudes ----------------------------------------------------------------

struct CliNumber {
  std::string option;
  double typical;
};
const std::vector<CliNumber> kModelOptions = {
    {"--force", 45.0}, {"--mu", 1.0},    {"--mu-s", 1.0}, {"--m", 1.0},     {"--M", 1.5},
    {"--L-min", 0.02}, {"--L-max", 0.5}, {"--g", 9.81},   {"--alpha", 1.0}, {"--rtol", 1e-10}};

/// A numeric field of a TOML or JSON input (its value starts like a number or an array).
bool numeric(const Field& f) {
  const char c = f.value.empty() ? ' ' : f.value.front();
  return c == '[' || c == '-' || (c >= '0' && c <= '9');
}

/// Sets one numeric leaf of `fields` to a hostile value; returns its key.
std::string mutate(Rng& rng, std::vector<Field>& fields, Syntax syntax) {
  std::vector<Field*> candidates;
  for (Field& f : fields) {
    if (numeric(f)) {
      candidates.push_back(&f);
    }
  }
  Field& f = *rng.pick(candidates);
  const std::string value = hostile_number(rng, syntax, 1.0);
  f.value = f.value.front() == '[' ? replace_random_leaf(rng, f.value, value) : value;
  return f.key + " = " + value;
}

Case magnitude_case(std::uint64_t seed, long long index) {
  Rng rng(seed, 3, index);
  Case c;
  switch (rng.integer(0, 5)) {
    case 0:
    case 1: {
      const bool vss = rng.coin(0.6);
      const CliNumber& o = rng.pick(kModelOptions);
      const std::string value = "=" + hostile_number(rng, Syntax::kCli, o.typical);
      c.run.args = {"inchworm", vss ? "vss" : "trace", "--mu=1", "--force=45"};
      if (o.option == "--alpha") {
        c.run.args.emplace_back("--model=dm");
      }
      if (!vss && rng.coin(0.3)) {
        c.run.args.push_back("--dt=" + hostile_number(rng, Syntax::kCli, 1e-3));
      } else {
        c.run.args.push_back(o.option + value);
      }
      c.place = option_place(c.run.args.back());
      // The thresholds F > μ_s m g, F > μ_s M g (§2.3), M > m and L_max > L_min tie options
      // together; the message may name the other one of a pair.
      const std::vector<std::string> force = {"--force", "--mu", "--mu-s", "--m", "--M", "--g"};
      const std::vector<std::string> length = {"--L-min", "--L-max"};
      for (const auto* group : {&force, &length}) {
        if (std::find(group->begin(), group->end(), c.place) != group->end()) {
          c.also = *group;
        }
      }
      const std::string method =
          rng.pick(std::vector<std::string>{"exact", "rootfind", "analytic", "cvode"});
      c.run.args.push_back("--method=" + method);
      c.title = std::string(vss ? "vss" : "trace") + " " + c.run.args[c.run.args.size() - 2] +
                " by " + method;
      if (vss) {
        c.run.args.emplace_back("--json");
        c.output_kind = Output::kJson;
      } else {
        c.run.args.insert(c.run.args.end(), {"--cycles=1", "--out", "t.csv"});
        c.outputs = {"t.csv"};
        c.output = "t.csv";
        c.output_kind = Output::kCsv;
      }
      break;
    }
    case 2: {
      std::vector<Field> f = frame_fields();
      const std::string what = mutate(rng, f, Syntax::kJson);
      c = model_case("frame " + what, json_object(f), rng.coin());
      c.place_line = true;
      break;
    }
    case 3: {
      std::vector<Field> f = robot_fields();
      Rng rows(seed, 103, index);
      std::string csv = batch_csv(rows, 4);
      std::string what;
      if (rng.coin()) {
        what = "robot " + mutate(rng, f, Syntax::kJson);
        c = batch_case("batch, " + what, json_object(f), csv);
        c.place = "robot.json";
      } else {
        // one cell of the CSV: row 2..5, column 0..18
        const long long row = rng.integer(1, 4);
        const long long col = rng.integer(0, 18);
        std::size_t at = 0;
        for (long long r = 0; r < row; ++r) {
          at = csv.find('\n', at) + 1;
        }
        for (long long k = 0; k < col; ++k) {
          at = csv.find(',', at) + 1;
        }
        const std::size_t end = csv.find_first_of(",\n", at);
        const std::string value = hostile_number(rng, Syntax::kCli, 0.1);
        csv.replace(at, end - at, value);
        c = batch_case("batch, frame " + std::to_string(row) + " column " + std::to_string(col) +
                           " = " + value,
                       json_object(f), csv);
        c.place = "frames.csv";
      }
      c.place_line = true;
      break;
    }
    case 4: {
      std::vector<Table> s = rng.pick(scene_templates());
      std::vector<Table*> numeric_tables;
      for (Table& t : s) {
        if (std::any_of(t.fields.begin(), t.fields.end(), numeric)) {
          numeric_tables.push_back(&t);
        }
      }
      Table& t = *rng.pick(numeric_tables);
      const std::string what = mutate(rng, t.fields, Syntax::kToml);
      c = scene_case("scene " + t.header + " " + what, toml_text(s));
      c.place_line = true;
      break;
    }
    default: {
      std::vector<Table> s = spec_tables(2);
      const std::string key =
          rng.pick(std::vector<std::string>{"rtol", "mu", "mu_s", "m", "M", "g", "L_min"});
      const std::string value = hostile_number(rng, Syntax::kToml, key == "rtol" ? 1e-10 : 1.0);
      bool set = false;
      for (Field& f : s[1].fields) {
        if (f.key == key) {
          f.value = value;
          set = true;
        }
      }
      if (!set) {
        s[1].fields.push_back({key, value});
      }
      c = spec_case("spec " + key + " = " + value, toml_text(s));
      c.place_line = true;
      break;
    }
  }
  c.exits = {0, 1, 2};
  return c;
}

}  // namespace

const std::vector<HostileClass>& classes() {
  static const std::vector<HostileClass> table = {
      {"depth", "crash: nesting depth, long strings, huge numbers",
       "frame, robot, scene and spec files nested 10 to 10^6 levels; strings of 10^3 to 3·10^6 "
       "characters; number literals of 10^2 to 10^5 digits",
       depth_case},
      {"runaway", "runs that never end or fill the disk",
       "traces and vss by every integrator with dt 10^-320 to 0.1, rtol 10^-16 to 0.5, forces to "
       "10^308, 8 to 10^9 strokes; scenes of duration to 10^308 and dt to 10^-320 or 10^9 "
       "steps; Coulomb frames of up to 300 feet; solver tolerances to 10^-300; batches of up to "
       "10^5 frames",
       runaway_case},
      {"magnitude", "success reported for non-finite results",
       "one value of every numeric option, frame, robot, CSV, scene and spec field set to 0, "
       "-0, NaN, ±inf, subnormals, ±10^-320 to 10^308 or a plain value of either sign",
       magnitude_case},
      {"signals", "output left behind",
       "SIGINT, SIGTERM, SIGKILL at 0.02 to 0.4 s into run, trace and sweep; SIGKILL then the same "
       "command "
       "again; a sweep resumed after a signal; inputs that fail after thousands of good rows or "
       "points",
       signal_case},
      {"paths", "wrong exit code or a message without a place",
       "inputs that are folders, missing, named pipes, empty, binary or /dev/null; outputs that "
       "are folders, empty, '.', '/', too long, with a trailing slash or a missing parent, for "
       "every command",
       path_case},
      {"loss", "silent loss",
       "stdout or --out on /dev/full; an output that is the input (spelled ./x, a/../x, a "
       "symlink, the sidecar); duplicate JSON and TOML keys and tables; CRLF frame, scene, CSV "
       "and spec files",
       loss_case},
  };
  return table;
}

const HostileClass* find_class(const std::string& id) {
  for (const HostileClass& c : classes()) {
    if (c.id == id) {
      return &c;
    }
  }
  return nullptr;
}

}  // namespace slipwalk::sweeps::hostile
