// The hostile-input classes about files, signals and devices (hostile_inputs.hpp): signals during
// runs, paths that are no plain files, full devices, outputs that are inputs, duplicate keys and
// CRLF line ends.
#include <signal.h>

#include <algorithm>
#include <string>
#include <vector>

#include "sweeps/points/hostile_inputs.hpp"
#include "sweeps/points/hostile_inputs_blocks.hpp"

namespace slipwalk::sweeps::hostile {

Case signal_case(std::uint64_t seed, long long index);
Case path_case(std::uint64_t seed, long long index);
Case loss_case(std::uint64_t seed, long long index);

namespace {

/// A scene of a few seconds of work (BigANT's tripod under Coulomb friction, 8 s of 1 ms steps).
std::string long_scene() {
  std::vector<Table> s = scene_templates()[1];
  s[2].fields = {{"duration", "8.0"}, {"dt", "0.001"}};
  return toml_text(s);
}

/// A plan of a few steps (BigANT walking straight, planning/plan_file.hpp).
std::string short_plan() {
  return "[plan]\nrobot = \"bigant\"\nsteps = 5\n\n[goal]\ntwist = [0.2, 0.0, 0.0]\n";
}

/// The commands with a file output, as (args before the output, the output option, the inputs).
struct Command {
  std::string name;
  std::vector<std::string> args;  ///< the output's value is appended after `option`
  std::string option;
  std::vector<InputFile> inputs;
  bool sidecar = false;  ///< run: <out>.json beside the CSV
};

std::vector<Command> commands(Rng& rng) {
  return {
      {"run",
       {"run", "scene.toml"},
       "--out",
       {{"scene.toml", toml_text(scene_templates()[0]), ""}},
       true},
      {"trace", {"inchworm", "trace", "--force=45", "--mu=1", "--cycles=1"}, "--out", {}, false},
      {"model",
       {"model", "--in", "frame.json"},
       "--out",
       {{"frame.json", json_object(frame_fields()), ""}},
       false},
      {"batch",
       {"model", "--robot", "robot.json", "--in", "frames.csv"},
       "--out",
       {{"robot.json", json_object(robot_fields()), ""}, {"frames.csv", batch_csv(rng, 3), ""}},
       false},
      {"sweep",
       {"sweep", "grid.toml", "--jobs", "1", "--no-timing"},
       "--data",
       {{"grid.toml", toml_text(spec_tables(2)), ""}},
       false},
      {"plan", {"plan", "plan.toml"}, "--out", {{"plan.toml", short_plan(), ""}}, true},
  };
}

/// The commands for which `keep` holds, in the order of commands().
template <class Keep>
std::vector<Command> commands_where(Rng& rng, Keep keep) {
  std::vector<Command> all = commands(rng);
  std::vector<Command> out;
  for (Command& c : all) {
    if (keep(c)) {
      out.push_back(std::move(c));
    }
  }
  return out;
}

/// The outputs a command with output `out` leaves on success.
std::vector<std::string> outputs_of(const Command& cmd, const std::string& out) {
  if (cmd.option == "--data") {
    const std::string folder = out.substr(0, out.find_last_not_of('/') + 1);
    return {folder + "/test/grid.csv", folder + "/test/grid.json"};
  }
  std::vector<std::string> o = {out};
  if (cmd.sidecar) {
    o.push_back(out.substr(0, out.rfind('.')) + ".json");
  }
  return o;
}

Case with_output(const Command& cmd, const std::string& out) {
  Case c;
  c.files = cmd.inputs;
  c.run.args = cmd.args;
  c.run.args.push_back(cmd.option);
  c.run.args.push_back(out);
  c.place = cmd.option;
  c.outputs = outputs_of(cmd, out);
  return c;
}

}  // namespace

// ---- 4. signals and failures after a good start ---------------------------------------------

Case signal_case(std::uint64_t seed, long long index) {
  Rng rng(seed, 4, index);
  Case c;
  const int sig = rng.pick(std::vector<int>{SIGINT, SIGTERM, SIGKILL});
  const double after = rng.uniform(0.02, 0.4);
  const std::string when = std::to_string(after).substr(0, 4) + " s";
  const std::string sig_name = sig == SIGINT ? "SIGINT" : (sig == SIGTERM ? "SIGTERM" : "SIGKILL");
  switch (rng.integer(0, 3)) {
    case 0: {
      c.title = "run, " + sig_name + " after " + when;
      c.files = {{"scene.toml", long_scene(), ""}};
      c.run.args = {"run", "scene.toml", "--out", "out.csv"};
      c.outputs = {"out.csv", "out.json"};
      break;
    }
    case 1: {
      c.title = "trace, " + sig_name + " after " + when;
      c.run.args = {"inchworm",    "trace",     "--force=45", "--mu=1",
                    "--cycles=30", "--dt=1e-4", "--out",      "t.csv"};
      c.outputs = {"t.csv"};
      break;
    }
    case 2: {
      const long long points = 5000;
      c.title = "sweep of " + std::to_string(points) + " points, " + sig_name + " after " + when +
                ", then --resume";
      c.files = {{"grid.toml", toml_text(spec_tables(points, "analytic")), ""}};
      c.run.args = {"sweep", "grid.toml", "--data", "data", "--jobs", "1", "--no-timing"};
      c.outputs = {"data/test/grid.csv", "data/test/grid.json"};
      c.after_signal = {"data/test/grid.partial"};
      c.twin = Twin::kResume;
      c.second.args = c.run.args;
      c.second.args.emplace_back("--resume");
      c.resume_points = points;
      break;
    }
    default: {  // bad input found only after a long good start: nothing may be written
      if (rng.coin()) {
        const long long rows = static_cast<long long>(log_uniform(rng, 100, 20000));
        const long long bad = rng.integer(rows / 2, rows);
        std::string csv = batch_csv(rng, rows);
        std::size_t at = 0;
        for (long long r = 0; r < bad; ++r) {
          at = csv.find('\n', at) + 1;
        }
        csv.insert(at, rng.pick(std::vector<std::string>{"x", "1e999", ",", "0,"}));
        c = batch_case(
            "batch of " + std::to_string(rows) + " frames, frame " + std::to_string(bad) + " bad",
            json_object(robot_fields()), csv);
        c.place = "frames.csv:" + std::to_string(bad + 1);
      } else {
        const long long points = rng.integer(50, 2000);
        std::vector<Table> s = spec_tables(points);
        const std::string F = rng.pick(std::vector<std::string>{"-1.0", "0.0", "nan", "\"x\""});
        s.push_back({"[[block]]", {{"axes.F", "[45.0, " + F + "]"}}});
        c.title = "sweep of " + std::to_string(points) + " good points, then F = " + F;
        c.files = {{"grid.toml", toml_text(s), ""}};
        c.run.args = {"sweep", "grid.toml", "--data", "data", "--jobs", "1", "--no-timing"};
        c.place = "grid.toml";
        c.place_line = true;
      }
      c.outputs.clear();
      c.exits = {2};
      return c;
    }
  }
  c.run.signal = sig;
  c.run.signal_after_s = after;
  c.exits = {0};
  c.limit_s = 20.0;
  if (sig == SIGKILL) {  // killed without a chance to clean: the same command again must
    c.twin = c.twin == Twin::kResume ? Twin::kResume : Twin::kCleanAfterKill;
    c.second.args = c.run.args;  // remove (or report) the stale temporary and succeed
    if (c.twin == Twin::kResume) {
      c.second.args.emplace_back("--resume");
    }
  }
  return c;
}

// ---- 5. paths that are no plain files --------------------------------------------------------

Case path_case(std::uint64_t seed, long long index) {
  Rng rng(seed, 5, index);
  const std::vector<Command> cmds = commands(rng);
  const Command& cmd = rng.pick(cmds);
  Case c;
  if (!cmd.inputs.empty() && rng.coin(0.4)) {
    // A bad input: one of the command's input files replaced by something that is not one.
    const InputFile& victim = rng.pick(cmd.inputs);
    c = with_output(cmd, cmd.option == "--data" ? "data" : "out.csv");
    std::erase_if(c.files, [&](const InputFile& f) { return f.name == victim.name; });
    c.place = victim.name;
    c.exits = {2};
    switch (rng.integer(0, 6)) {
      case 0:
        c.folders = {victim.name};
        c.title = cmd.name + ": input " + victim.name + " is a folder";
        break;
      case 1:
        c.title = cmd.name + ": input " + victim.name + " missing";
        break;
      case 2:
        c.fifos = {victim.name};
        c.title = cmd.name + ": input " + victim.name + " is a named pipe";
        c.limit_s = 5.0;
        break;
      case 3:
        c.files.push_back({victim.name, "", ""});
        c.title = cmd.name + ": input " + victim.name + " empty";
        break;
      case 4: {
        std::string bytes;
        const long long n = rng.integer(1, 4096);
        for (long long i = 0; i < n; ++i) {
          bytes.push_back(static_cast<char>(rng.integer(0, 255)));
        }
        c.files.push_back({victim.name, bytes, "head -c " + std::to_string(n) + " /dev/urandom"});
        c.title =
            cmd.name + ": input " + victim.name + " is " + std::to_string(n) + " random bytes";
        break;
      }
      case 5:
        c.symlinks = {{victim.name, "/dev/null"}};
        c.title = cmd.name + ": input " + victim.name + " is a link to /dev/null";
        break;
      default: {  // a folder where the input's parent should be
        c.files.push_back({"x", "", ""});
        for (std::string& a : c.run.args) {
          if (a == victim.name) {
            a = "x/" + victim.name;
          }
        }
        c.place = "x/" + victim.name;
        c.title = cmd.name + ": input x/" + victim.name + " where x is a file";
        break;
      }
    }
    return c;
  }
  // A bad output.
  std::string out;
  std::string what;
  std::set<int> exits = {2};
  std::vector<std::string> folders;
  std::vector<InputFile> extra;
  // --data names a folder: an existing one, or one with a trailing slash, is a good one; '.',
  // '..' and '/' are good ones too, and outside the case folder, so they are not tried.
  const bool data = cmd.option == "--data";
  switch (rng.integer(0, 9)) {
    case 0:
      out = "outdir";
      folders = {"outdir"};
      what = "an existing folder";
      exits = {data ? 0 : 2};
      break;
    case 1:
      out = "";
      what = "empty";
      break;
    case 2:
      out = data ? "" : rng.pick(std::vector<std::string>{".", "..", "/", "./"});
      what = "'" + out + "'";
      break;
    case 3:
      out = "out.csv/";
      what = "with a trailing slash";
      exits = {data ? 0 : 2};
      break;
    case 4:
      out = std::string(static_cast<std::size_t>(rng.integer(256, 4000)), 'a') + ".csv";
      what = "a name of " + std::to_string(out.size()) + " characters";
      break;
    case 5: {
      const long long depth = rng.integer(2100, 3000);
      for (long long i = 0; i < depth; ++i) {
        out += "d/";
      }
      out += "o.csv";
      what = "a path of " + std::to_string(out.size()) + " characters";
      break;
    }
    case 6:
      out = "x/y/out.csv";
      what = "in missing folders";
      exits = {0, 2};
      break;
    case 7:
      out = "x/out.csv";
      extra = {{"x", "a file", ""}};
      what = "under a plain file";
      break;
    case 8:
      out = "out.csv";
      extra = {{"out.csv", "old\n", ""}};
      what = "an existing file (replaced)";
      exits = {data ? 2 : 0};
      break;
    default:
      out = "out.csv";
      folders = {data ? "out.csv/test/grid.csv" : "out.json"};
      what = data ? "holding a folder where the CSV goes" : "whose sidecar name is a folder";
      exits = cmd.sidecar || data ? std::set<int>{2} : std::set<int>{0};
      break;
  }
  c = with_output(cmd, out);
  c.title = cmd.name + ": " + cmd.option + " " + what;
  c.folders = folders;
  c.files.insert(c.files.end(), extra.begin(), extra.end());
  c.exits = exits;
  return c;
}

// ---- 6. silent loss ---------------------------------------------------------------------------

namespace {

std::string crlf(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    if (ch == '\n') {
      out += '\r';
    }
    out += ch;
  }
  return out;
}

}  // namespace

Case loss_case(std::uint64_t seed, long long index) {
  Rng rng(seed, 6, index);
  Case c;
  switch (rng.integer(0, 4)) {
    case 0: {  // stdout on a full device
      const std::vector<std::vector<std::string>> stdout_commands = {
          {"inchworm", "vss", "--force=45", "--mu=1"},
          {"inchworm", "vss", "--force=45", "--mu=1", "--json", "--method=analytic"},
          {"model", "--in", "frame.json"},
          {"inchworm", "trace", "--force=45", "--mu=1", "--cycles=2", "--out", "-"},
          {"kinds"},
          {"kinds", "--json"},
          {"--help"},
          {"inchworm", "vss", "--help"},
          {"run", "--help"}};
      c.run.args = rng.pick(stdout_commands);
      c.files = {{"frame.json", json_object(frame_fields()), ""}};
      c.run.stdout_to = "/dev/full";
      c.title = "stdout on /dev/full:";
      for (const std::string& a : c.run.args) {
        c.title += " " + a;
      }
      c.exits = {1};
      return c;
    }
    case 1: {  // --out on a full device
      // Not a command with a sidecar (it would go beside /dev/full), nor sweep (--data is a
      // folder).
      const std::vector<Command> cmds = commands_where(
          rng, [](const Command& cmd) { return !cmd.sidecar && cmd.option != "--data"; });
      const Command& cmd = rng.pick(cmds);
      c = with_output(cmd, "/dev/full");
      c.title = cmd.name + ": --out /dev/full";
      c.outputs.clear();
      c.exits = {1};
      return c;
    }
    case 2: {  // the output is the input, however spelled
      const std::vector<Command> cmds =
          commands_where(rng, [](const Command& cmd) { return !cmd.inputs.empty(); });
      const Command& cmd = rng.pick(cmds);
      const InputFile& victim = rng.pick(cmd.inputs);
      std::string out = victim.name;
      Case base;
      switch (rng.integer(0, 3)) {
        case 0:
          break;
        case 1:
          out = "./" + out;
          break;
        case 2:
          out = "sub/../" + out;
          base.folders = {"sub"};
          break;
        default:
          out = "link";
          base.symlinks = {{"link", victim.name}};
          break;
      }
      if (cmd.option == "--data") {  // the spec where the sweep's CSV goes
        c = with_output(cmd, "data");
        c.files = {{"data/test/grid.csv", toml_text(spec_tables(2)), ""}};
        c.run.args[1] = "data/test/grid.csv";
        c.title = "sweep: the spec is data/test/grid.csv";
      } else if (cmd.sidecar && rng.coin()) {  // run: the sidecar is the scene
        c = with_output(cmd, "scene.csv");
        c.files[0].name = "scene.json";
        c.run.args[1] = "scene.json";
        c.title = "run scene.json --out scene.csv (the sidecar is the scene)";
      } else {
        c = with_output(cmd, out);
        c.folders = base.folders;
        c.symlinks = base.symlinks;
        c.title = cmd.name + ": --out " + out + " is the input " + victim.name;
      }
      c.exits = {2};
      return c;
    }
    case 3: {  // a key or a table given twice
      switch (rng.integer(0, 3)) {
        case 0: {
          std::vector<Field> f = frame_fields();
          const Field twin = rng.pick(f);
          f.insert(f.begin() + rng.integer(0, static_cast<long long>(f.size())), twin);
          c = model_case("frame JSON with '" + twin.key + "' twice", json_object(f), false);
          break;
        }
        case 1: {
          std::vector<Field> f = robot_fields();
          const Field twin = rng.pick(f);
          f.push_back(twin);
          c = batch_case("robot JSON with '" + twin.key + "' twice", json_object(f),
                         batch_csv(rng, 2));
          c.place = "robot.json";
          break;
        }
        case 2: {
          std::vector<Table> s = rng.pick(scene_templates());
          if (rng.coin()) {
            Table& t = s[static_cast<std::size_t>(rng.integer(0, 2))];
            t.fields.push_back(rng.pick(t.fields));
            c = scene_case("scene with a key of " + t.header + " twice", toml_text(s));
          } else {
            // [run] twice (an array of tables such as [[robot.leg]] may repeat; a table not)
            const auto run = std::find_if(s.begin(), s.end(),
                                          [](const Table& t) { return t.header == "[run]"; });
            s.push_back(*run);
            c = scene_case("scene with [run] twice", toml_text(s));
          }
          break;
        }
        default: {
          std::vector<Table> s = spec_tables(2);
          s[1].fields.push_back({"mu", "0.5"});
          c = spec_case("spec with mu twice", toml_text(s));
          break;
        }
      }
      c.outputs.clear();
      c.exits = {2};
      c.place_line = true;
      return c;
    }
    default: {  // CRLF line ends: the same data, the same result
      switch (rng.integer(0, 3)) {
        case 0: {
          const std::string lf = json_object(frame_fields());
          c = model_case("frame JSON with CRLF line ends", crlf(lf), false);
          c.files.push_back({"lf.json", lf, ""});
          c.second.args = {"model", "--in", "lf.json"};
          c.exits = {0};
          break;
        }
        case 1: {
          const std::string lf = toml_text(rng.pick(scene_templates()));
          c = scene_case("scene with CRLF line ends", crlf(lf));
          c.files.push_back({"lf.toml", lf, ""});
          c.second.args = {"run", "lf.toml", "--out", "lf.csv"};
          c.twin_output = "lf.csv";
          c.exits = {0};
          break;
        }
        case 2: {
          const std::string lf = batch_csv(rng, rng.integer(1, 20));
          c = batch_case("CSV batch with CRLF line ends", json_object(robot_fields()), crlf(lf));
          c.files.push_back({"lf.csv", lf, ""});
          c.second.args = {"model", "--robot", "robot.json", "--in", "lf.csv", "--out", "o2.csv"};
          c.twin_output = "o2.csv";
          c.exits = {0, 2};
          c.place = "frames.csv";
          c.place_line = true;
          break;
        }
        default: {
          c = spec_case("spec with CRLF line ends", crlf(toml_text(spec_tables(3))));
          c.exits = {0};
          return c;
        }
      }
      c.twin = Twin::kSameOutput;
      return c;
    }
  }
}

}  // namespace slipwalk::sweeps::hostile
