// The calibration's files (files.hpp): readers and writers of the two experiments' recordings, the
// geometry, and the JSON of the estimates and of a synthetic robot's truth.
//
// Hanging CSV (one file or several; `slipwalk calibrate --hanging H.csv [H2.csv ...]`):
//   orientation,phi_HL,fx_HL,fy_HL,fz_HL,tx_HL,ty_HL,tz_HL,phi_ML,...
//   +x,0,6.19,0.02,-0.11,0.001,0.35,-0.02,0,...
//   orientation  the body axis that points along gravity: +x -x +y -y +z -z (U+2212 '−' is read as
//                '-'); −z is the upright robot (the naive tare's record)
//   phi_L        leg L's shaft angle, turns, as recorded (not wrapped)
//   fx_L..tz_L   transducer L's reading, N and N·m, in its own axes
// The rows of one orientation are one record, in sample order, and must be together; the same
// orientation in two files is refused before calibrating (check_hanging_pairs).
//
// Poses CSV (`--poses P.csv`): one row per standing pose (the median of a settled window):
//   qw,qx,qy,qz,phi_HL,fx_HL,...
//   qw..qz       the attitude R^W_C (body axes in the world) as a quaternion, scalar first; its
//                norm must be within 1e-6 of 1 (it is then normalised)
// Both: a header line naming the columns, in any order; columns the format does not name are
// ignored; '#' starts a comment; blank lines are skipped; CRLF and a UTF-8 BOM are accepted. Every
// needed column exactly once; every cell a finite number. Errors name file:line:col.
//
// Geometry TOML (`--geometry G.toml`), every key required, no others:
//   robot_weight = 80.2458          # N, the whole robot with its legs (> 0)
//   [[transducer]]                  # one per leg, in the order of the estimates
//   leg = "HL"                      # [A-Za-z0-9_]+, unique
//   position = [0.35, 0.2, 0.04]    # m, N_k's origin in the body frame (|p| <= 100)
//   rotation = [0.0, 0.0, 3.14159]  # rad, the rotation vector of N_k's axes in B (|θ| <= π)
//
// params.json (calibration_json; `slipwalk calibrate` adds the command, its inputs and options,
// the wall time and provenance):
//   legs[k]: leg; offset [fx fy fz tx ty tz] (N, N·m) and offset_se; weight and weight_se (N);
//            com {harmonics H, coefficients: rows x, y, z of c₀, a₁, b₁, ... (m, transducer
//            frame)}, com_samples (how many), com_fit_rms (m); pairs (each opposite pair's down,
//            up, axis, f_minus, d, s_plus, s_minus, weight, offset and their SEs); rotation (the
//            rotation vector of R̃_k, rad), rotation_matrix (rows), rotation_se; displacement u_k
//            (m) and displacement_se
//   robot_weight; hanging {model, com, variances, harmonics, max_phi_mismatch}; mounting {model,
//   solver, target, chassis_weight, rss, poses, dof, iterations, converged, seconds,
//   smallest_singular_value}; models (Table 4.2: model, dof, rss, cv_mse, bic); seconds_hanging,
//   seconds_standing. The CoM samples themselves are not written (90,000 per leg in the thesis).
//
// truth.json (truth_json): the options, the geometry, and per leg the true offset, weight,
// mounting rotation (rotation vector, rad), translation p̃_k (m), displacement u_k (m), and the CoM
// r_k(φ) tabulated at φ = i / kTruthComSamples turns; chassis_com, chassis_weight, com_torque_bias.
//
// Numbers are written with core::format_double, so that a file read back gives the numbers
// written: CSV and JSON round trips are exact; a rotation goes through a rotation vector or a
// quaternion and comes back to rounding (1e-15).
#include "calibration/files.hpp"

#include <Eigen/Geometry>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <set>

#include "calibration/standing.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/json_input.hpp"
#include "core/toml_input.hpp"
#include "scene/toml_reader.hpp"

namespace slipwalk::calibration {

namespace {

using core::InputError;

/// The per-leg columns, in order: the shaft angle, then the six readings.
constexpr std::array<std::string_view, 7> kLegColumns = {"phi", "fx", "fy", "fz", "tx", "ty", "tz"};
constexpr std::array<std::string_view, 4> kQuaternionColumns = {"qw", "qx", "qy", "qz"};
constexpr std::string_view kOrientationColumn = "orientation";
/// The tolerance on a pose quaternion's norm.
constexpr double kQuaternionTolerance = 1e-6;
/// The CoM table of truth_json: samples per turn.
constexpr int kTruthComSamples = 72;
/// Geometry limits (model.hpp's validate states the same).
constexpr double kMaxPosition = 100.0;
constexpr double kMaxRobotWeight = 1e6;

std::string leg_column(std::string_view what, const std::string& leg) {
  return std::string(what) + "_" + leg;
}

std::vector<std::string> columns_with(std::vector<std::string> lead, const Geometry& geometry) {
  for (const std::string& leg : geometry.legs) {
    for (std::string_view c : kLegColumns) {
      lead.push_back(leg_column(c, leg));
    }
  }
  return lead;
}

/// Where each needed column is (cell indices), from the header line: `lead` first, then 7 per leg.
struct Layout {
  std::vector<int> column;  // needed column i → cell index
  std::size_t cells = 0;
};

Layout read_header(std::string_view content, const std::string& where,
                   const std::vector<std::string>& needed, std::string_view what,
                   std::vector<std::string_view>& cells, std::vector<int>& starts) {
  core::split_cells(content, cells, starts);
  std::map<std::string_view, std::size_t> index;
  for (std::size_t i = 0; i < needed.size(); ++i) {
    index.emplace(needed[i], i);
  }
  Layout layout;
  layout.cells = cells.size();
  layout.column.assign(needed.size(), -1);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const std::string_view name = core::trim_blanks(cells[c]);
    const auto it = index.find(name);
    if (it == index.end()) {
      continue;  // a column the format does not name: ignored
    }
    int& slot = layout.column[it->second];
    if (slot >= 0) {
      throw InputError(
          where + ":" + std::to_string(starts[c] + static_cast<int>(name.data() - cells[c].data())),
          "column '" + std::string(name) + "' appears twice (first at column " +
              std::to_string(starts[static_cast<std::size_t>(slot)]) + ")");
    }
    slot = static_cast<int>(c);
  }
  for (std::size_t i = 0; i < needed.size(); ++i) {
    if (layout.column[i] < 0) {
      const std::size_t lead = needed.size() % kLegColumns.size();
      const std::string whose =
          i < lead ? std::string()
                   : " (leg " + needed[i].substr(needed[i].find('_') + 1) + " of the geometry)";
      throw InputError(where, "no column '" + needed[i] + "'" + whose + "; " + std::string(what));
    }
  }
  return layout;
}

/// One CSV's rows, read against the needed columns: `row(where, text_cell, number_cell)` once per
/// data row, after the header. Returns the header's place.
template <typename Row>
std::string read_rows(std::string_view text, const std::string& source,
                      const std::vector<std::string>& needed, std::string_view what, Row&& row) {
  std::vector<std::string_view> cells;
  std::vector<int> starts;
  std::optional<Layout> layout;
  std::string header_at;
  core::LineReader lines(text);
  bool any = false;
  for (std::string_view line; lines.next(line);) {
    const std::string_view content = line.substr(0, line.find('#'));
    if (core::trim_blanks(content).empty()) {
      continue;
    }
    const std::string where = source + ":" + std::to_string(lines.line_number());
    if (!layout) {
      layout = read_header(content, where, needed, what, cells, starts);
      header_at = where;
      continue;
    }
    core::split_cells(content, cells, starts);
    if (cells.size() != layout->cells) {
      throw InputError(where, "the row has " + std::to_string(cells.size()) +
                                  " cells, the header " + std::to_string(layout->cells));
    }
    const auto cell_of = [&](std::size_t i) {
      return core::trim_blanks(cells[static_cast<std::size_t>(layout->column[i])]);
    };
    const auto at = [&](std::size_t i) {
      const auto c = static_cast<std::size_t>(layout->column[i]);
      return where + ":" +
             std::to_string(starts[c] + static_cast<int>(cell_of(i).data() - cells[c].data()));
    };
    const auto number = [&](std::size_t i) {
      const std::string_view cell = cell_of(i);
      double x = 0.0;
      const auto [ptr, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), x);
      if (cell.empty() || ec != std::errc() || ptr != cell.data() + cell.size() ||
          !std::isfinite(x)) {
        throw InputError(at(i),
                         needed[i] + ": '" + core::text_excerpt(cell) + "' is not a finite number");
      }
      return x;
    };
    row(where, cell_of, at, number);
    any = true;
  }
  if (!layout) {
    throw InputError(source + ":" + std::to_string(std::max(lines.line_number(), 1LL)),
                     "no header line; " + std::string(what));
  }
  if (!any) {
    throw InputError(header_at, "no rows after the header");
  }
  return header_at;
}

/// A record being read, row-major.
struct Pending {
  BodyAxis down = BodyAxis::minus_z;
  std::vector<double> phi;
  std::vector<double> wrench;
  std::vector<std::string> rows;
};

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::MatrixXd matrix_of(const std::vector<double>& v, Eigen::Index rows, Eigen::Index cols) {
  return Eigen::Map<const RowMajor>(v.data(), rows, cols);
}

/// Leg k's seven cells of a row (φ, then the reading) into `phi` and `wrench`.
template <typename Number>
void read_legs(int legs, std::size_t lead, Number& number, std::vector<double>& phi,
               std::vector<double>& wrench) {
  for (int k = 0; k < legs; ++k) {
    const std::size_t base = lead + static_cast<std::size_t>(k) * kLegColumns.size();
    phi.push_back(number(base));
    for (std::size_t j = 1; j < kLegColumns.size(); ++j) {
      wrench.push_back(number(base + j));
    }
  }
}

template <typename Writer>
void write_legs(Writer& csv, const Eigen::MatrixXd& phi, const Eigen::MatrixXd& wrench,
                Eigen::Index i) {
  for (Eigen::Index k = 0; k < phi.cols(); ++k) {
    csv.cell(phi(i, k));
    for (Eigen::Index j = 0; j < 6; ++j) {
      csv.cell(wrench(i, 6 * k + j));
    }
  }
}

void check_widths(const Eigen::MatrixXd& phi, const Eigen::MatrixXd& wrench, const Geometry& g,
                  const std::string& what) {
  if (phi.cols() != g.size() || wrench.cols() != 6 * phi.cols() || wrench.rows() != phi.rows()) {
    throw InputError(what, "shaft angles " + std::to_string(phi.rows()) + " × " +
                               std::to_string(phi.cols()) + ", readings " +
                               std::to_string(wrench.rows()) + " × " +
                               std::to_string(wrench.cols()) + "; the geometry has " +
                               std::to_string(g.size()) + " legs (K and 6K columns)");
  }
}

std::string hanging_needs(const Geometry& g) {
  return "a hanging file needs the columns orientation and, per leg L of the geometry (" +
         std::to_string(g.size()) + "), phi_L, fx_L, fy_L, fz_L, tx_L, ty_L, tz_L";
}

std::string poses_needs(const Geometry& g) {
  return "a poses file needs the columns qw, qx, qy, qz and, per leg L of the geometry (" +
         std::to_string(g.size()) + "), phi_L, fx_L, fy_L, fz_L, tx_L, ty_L, tz_L";
}

// ---- geometry TOML -----------------------------------------------------------------------------

constexpr std::array<std::string_view, 2> kTopKeys = {"robot_weight", "transducer"};
constexpr std::array<std::string_view, 3> kTransducerKeys = {"leg", "position", "rotation"};

template <std::size_t N>
void check_keys(const toml::table& table, const std::array<std::string_view, N>& keys,
                const std::string& source, std::string_view table_name) {
  const std::vector<std::string_view> valid(keys.begin(), keys.end());
  for (const auto& [key, node] : table) {
    const std::string_view k = key.str();
    if (std::find(valid.begin(), valid.end(), k) == valid.end()) {
      std::string what =
          "unknown key '" + core::text_excerpt(k) + "' in " + std::string(table_name);
      if (const std::string_view guess = scene::nearest(k, valid); !guess.empty()) {
        what.append("; did you mean '").append(guess).append("'?");
      }
      throw InputError(scene::origin_of(key.source(), source), what);
    }
  }
}

double toml_number(const toml::node& node, const std::string& where, const std::string& key) {
  std::optional<double> v;
  if (const auto* f = node.as_floating_point()) {
    v = f->get();
  } else if (const auto* i = node.as_integer()) {
    v = static_cast<double>(i->get());
  }
  if (!v) {
    throw InputError(where, key + ": must be a number, got " + scene::type_name(node));
  }
  if (!std::isfinite(*v)) {
    throw InputError(where, key + ": must be finite");
  }
  return *v;
}

Eigen::Vector3d toml_vector(const toml::node& node, const std::string& source,
                            const std::string& key) {
  const toml::array* a = node.as_array();
  if (a == nullptr || a->size() != 3) {
    throw InputError(scene::origin_of(node.source(), source),
                     key + ": must be an array of 3 numbers");
  }
  Eigen::Vector3d v;
  for (std::size_t i = 0; i < 3; ++i) {
    const toml::node& e = *a->get(i);
    v(static_cast<Eigen::Index>(i)) =
        toml_number(e, scene::origin_of(e.source(), source), key + "[" + std::to_string(i) + "]");
  }
  return v;
}

bool well_formed_name(std::string_view name) {
  if (name.empty()) {
    return false;
  }
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

nlohmann::json vec(const Eigen::VectorXd& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

nlohmann::json mat(const Eigen::Matrix3d& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < 3; ++r) {
    rows.push_back({m(r, 0), m(r, 1), m(r, 2)});
  }
  return rows;
}

nlohmann::json fit_json(const PeriodicFit& fit) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < 3; ++r) {
    rows.push_back(vec(fit.coefficients.row(r).transpose()));
  }
  return {{"harmonics", fit.harmonics()}, {"coefficients", rows}};
}

std::string_view hanging_model_label(HangingModel m) {
  switch (m) {
    case HangingModel::exact:
      return "exact";
    case HangingModel::thesis_first_order:
      return "thesis_first_order";
    case HangingModel::no_misalignment:
      return "no_misalignment";
  }
  return "exact";
}

}  // namespace

std::vector<std::string> hanging_columns(const Geometry& geometry) {
  return columns_with({std::string(kOrientationColumn)}, geometry);
}

std::vector<std::string> pose_columns(const Geometry& geometry) {
  return columns_with({kQuaternionColumns.begin(), kQuaternionColumns.end()}, geometry);
}

std::vector<HangingRecord> parse_hanging(std::string_view text, const std::string& source,
                                         const Geometry& geometry) {
  const std::vector<std::string> needed = hanging_columns(geometry);
  const int legs = geometry.size();
  std::vector<HangingRecord> records;
  std::map<BodyAxis, std::string> started;  // orientation → the place its run began
  Pending pending;
  bool open = false;
  const auto close = [&] {
    HangingRecord r;
    r.down = pending.down;
    const auto n = static_cast<Eigen::Index>(pending.rows.size());
    r.phi = matrix_of(pending.phi, n, legs);
    r.wrench = matrix_of(pending.wrench, n, Eigen::Index{6} * legs);
    r.source = pending.rows.front();
    r.rows = std::move(pending.rows);
    records.push_back(std::move(r));
    pending = Pending{};
  };
  (void)read_rows(text, source, needed, hanging_needs(geometry),
                  [&](const std::string& where, auto& cell_of, auto& at, auto& number) {
                    // A typographic minus (U+2212, as the thesis prints it) reads as '-'.
                    constexpr std::string_view kMinus = "\xE2\x88\x92";
                    const std::string_view cell = cell_of(0);
                    const std::string label = cell.substr(0, kMinus.size()) == kMinus
                                                  ? "-" + std::string(cell.substr(kMinus.size()))
                                                  : std::string(cell);
                    const std::optional<BodyAxis> axis = parse_axis(label);
                    if (!axis) {
                      throw InputError(at(0), "orientation: '" + core::text_excerpt(cell_of(0)) +
                                                  "' is not one of +x -x +y -y +z -z (the body "
                                                  "axis along gravity)");
                    }
                    if (!open || *axis != pending.down) {
                      if (const auto it = started.find(*axis); it != started.end()) {
                        throw InputError(at(0), "orientation " + label +
                                                    " comes back after another (its rows began "
                                                    "at " +
                                                    it->second +
                                                    "; the rows of one orientation must be "
                                                    "together)");
                      }
                      if (open) {
                        close();
                      }
                      started.emplace(*axis, where);
                      pending.down = *axis;
                      open = true;
                    }
                    pending.rows.push_back(where);
                    read_legs(legs, 1, number, pending.phi, pending.wrench);
                  });
  close();
  return records;
}

StandingPoses parse_poses(std::string_view text, const std::string& source,
                          const Geometry& geometry) {
  const std::vector<std::string> needed = pose_columns(geometry);
  const int legs = geometry.size();
  std::vector<double> phi;
  std::vector<double> wrench;
  StandingPoses poses;
  poses.source =
      read_rows(text, source, needed, poses_needs(geometry),
                [&](const std::string& where, auto& /*cell_of*/, auto& at, auto& number) {
                  const Eigen::Quaterniond q(number(0), number(1), number(2), number(3));
                  const double norm = q.norm();
                  if (!(std::abs(norm - 1.0) <= kQuaternionTolerance)) {
                    throw InputError(at(0), "the attitude quaternion (qw, qx, qy, qz) has norm " +
                                                core::format_double(norm) +
                                                "; it must be a unit quaternion (within 1e-6)");
                  }
                  poses.attitude.push_back(q.normalized().toRotationMatrix());
                  poses.rows.push_back(where);
                  read_legs(legs, kQuaternionColumns.size(), number, phi, wrench);
                });
  const auto n = static_cast<Eigen::Index>(poses.rows.size());
  poses.phi = matrix_of(phi, n, legs);
  poses.wrench = matrix_of(wrench, n, Eigen::Index{6} * legs);
  return poses;
}

std::vector<HangingRecord> read_hanging(const std::filesystem::path& path,
                                        const Geometry& geometry) {
  return parse_hanging(
      core::read_input_file(path, "a hanging-experiment CSV file", kMaxCalibrationFileBytes),
      path.string(), geometry);
}

StandingPoses read_poses(const std::filesystem::path& path, const Geometry& geometry) {
  return parse_poses(
      core::read_input_file(path, "a standing-poses CSV file", kMaxCalibrationFileBytes),
      path.string(), geometry);
}

void write_hanging(std::ostream& out, const std::vector<HangingRecord>& records,
                   const Geometry& geometry) {
  core::CsvWriter csv(out, hanging_columns(geometry));
  for (const HangingRecord& r : records) {
    check_widths(r.phi, r.wrench, geometry, r.source.empty() ? "hanging record" : r.source);
    for (Eigen::Index i = 0; i < r.samples(); ++i) {
      csv.cell(axis_label(r.down));
      write_legs(csv, r.phi, r.wrench, i);
      csv.end_row();
    }
  }
}

void write_poses(std::ostream& out, const StandingPoses& poses, const Geometry& geometry) {
  check_widths(poses.phi, poses.wrench, geometry, poses.source.empty() ? "poses" : poses.source);
  if (static_cast<Eigen::Index>(poses.attitude.size()) != poses.poses()) {
    throw InputError("poses", std::to_string(poses.attitude.size()) + " attitudes for " +
                                  std::to_string(poses.poses()) + " poses");
  }
  core::CsvWriter csv(out, pose_columns(geometry));
  for (Eigen::Index i = 0; i < poses.poses(); ++i) {
    Eigen::Quaterniond q(poses.attitude[static_cast<std::size_t>(i)]);
    if (q.w() < 0.0) {
      q.coeffs() = -q.coeffs();  // the same rotation, written with qw >= 0
    }
    csv.cell(q.w()).cell(q.x()).cell(q.y()).cell(q.z());
    write_legs(csv, poses.phi, poses.wrench, i);
    csv.end_row();
  }
}

Geometry parse_geometry(std::string_view text, const std::string& source) {
  const toml::table doc = core::parse_toml(text, source);
  check_keys(doc, kTopKeys, source, "the geometry file");
  const std::string file_at = source + ":1:1";
  Geometry g;
  const toml::node* weight = doc.get("robot_weight");
  if (weight == nullptr) {
    throw InputError(file_at, "missing required key 'robot_weight' (N, the whole robot)");
  }
  const std::string weight_at = scene::origin_of(weight->source(), source);
  g.robot_weight = toml_number(*weight, weight_at, "robot_weight");
  if (!(g.robot_weight > 0.0 && g.robot_weight <= kMaxRobotWeight)) {
    throw InputError(weight_at, "robot_weight: must be in (0, 1e6] N, got " +
                                    core::format_double(g.robot_weight));
  }
  const toml::node* list = doc.get("transducer");
  if (list == nullptr) {
    throw InputError(file_at, "no [[transducer]] tables: one per leg (leg, position, rotation)");
  }
  const toml::array* tables = list->as_array();
  if (tables == nullptr || !tables->is_array_of_tables() || tables->empty()) {
    throw InputError(scene::origin_of(list->source(), source),
                     "transducer: must be an array of tables, [[transducer]] (leg, position, "
                     "rotation)");
  }
  std::map<std::string, std::string> seen;
  for (const toml::node& node : *tables) {
    const toml::table& t = *node.as_table();
    const std::string at = scene::origin_of(t.source(), source);
    check_keys(t, kTransducerKeys, source, "[[transducer]]");
    const auto required = [&](std::string_view key) -> const toml::node& {
      const toml::node* n = t.get(key);
      if (n == nullptr) {
        throw InputError(at, "[[transducer]]: missing required key '" + std::string(key) + "'");
      }
      return *n;
    };
    const toml::node& leg = required("leg");
    const std::string leg_at = scene::origin_of(leg.source(), source);
    const auto* name = leg.as_string();
    if (name == nullptr || !well_formed_name(name->get())) {
      throw InputError(leg_at, "leg: must be a name of letters, digits and '_'");
    }
    const std::string& leg_name = name->get();
    if (const auto [it, fresh] = seen.emplace(leg_name, leg_at); !fresh) {
      throw InputError(leg_at, "leg " + leg_name + " appears twice (first at " + it->second + ")");
    }
    const toml::node& position = required("position");
    const std::string position_at = scene::origin_of(position.source(), source);
    const Eigen::Vector3d p = toml_vector(position, source, "position");
    if (p.norm() > kMaxPosition) {
      throw InputError(position_at, "position: farther than 100 m from the body origin");
    }
    const toml::node& rotation = required("rotation");
    const std::string rotation_at = scene::origin_of(rotation.source(), source);
    const Eigen::Vector3d theta = toml_vector(rotation, source, "rotation");
    if (theta.norm() > std::numbers::pi + 1e-9) {
      throw InputError(rotation_at, "rotation: a rotation vector of angle " +
                                        core::format_double(theta.norm()) +
                                        " rad; write the angle in [0, π]");
    }
    g.legs.push_back(leg_name);
    g.transducer.push_back({rotation_from_vector(theta), p});
  }
  validate(g);  // the library's own statement of a valid geometry (every check above passed)
  return g;
}

Geometry read_geometry(const std::filesystem::path& path) {
  return parse_geometry(core::read_input_file(path, "a geometry TOML file"), path.string());
}

void write_geometry(std::ostream& out, const Geometry& geometry) {
  validate(geometry);
  out << "# The design geometry of the F/T calibration (lib/calibration/files.cpp has the "
         "format).\n"
      << "robot_weight = " << core::format_double(geometry.robot_weight) << "  # N\n";
  const auto triple = [](const Eigen::Vector3d& v) {
    std::string s = "[";
    s.append(core::format_double(v(0))).append(", ").append(core::format_double(v(1)));
    s.append(", ").append(core::format_double(v(2))).append("]");
    return s;
  };
  for (int k = 0; k < geometry.size(); ++k) {
    const Frame& f = geometry.transducer[static_cast<std::size_t>(k)];
    out << "\n[[transducer]]\n"
        << "leg = \"" << geometry.legs[static_cast<std::size_t>(k)] << "\"\n"
        << "position = " << triple(f.p) << "  # m\n"
        << "rotation = " << triple(rotation_vector(f.R)) << "  # rad\n";
  }
}

void check_hanging_pairs(const std::vector<HangingRecord>& records, double max_phi_mismatch,
                         Eigen::Index min_samples) {
  std::map<BodyAxis, const HangingRecord*> by_axis;
  for (const HangingRecord& r : records) {
    if (const auto [it, fresh] = by_axis.emplace(r.down, &r); !fresh) {
      throw InputError(r.source, "orientation " + std::string(axis_label(r.down)) +
                                     " is given twice (first at " + it->second->source + ")");
    }
  }
  std::vector<const HangingRecord*> paired;
  int pairs = 0;
  for (const HangingRecord& r : records) {
    const bool has_opposite = by_axis.count(opposite(r.down)) > 0;
    if (!has_opposite && r.down != BodyAxis::minus_z) {
      throw InputError(r.source, "orientation " + std::string(axis_label(r.down)) + " has no " +
                                     std::string(axis_label(opposite(r.down))) +
                                     " record: the hanging records come in opposite pairs "
                                     "(§4.3.1)");
    }
    if (has_opposite) {
      paired.push_back(&r);
      pairs += 1;
    }
  }
  pairs /= 2;
  if (pairs < 2) {
    throw InputError(records.empty() ? std::string("hanging") : records.front().source,
                     std::to_string(pairs) +
                         " complete opposite pair(s) of hanging records; the hanging stage needs "
                         "two about different axes (e.g. ±x and ±z, §4.3.1)");
  }
  const HangingRecord& first = *paired.front();
  for (const HangingRecord* r : paired) {
    if (r->samples() < min_samples) {
      throw InputError(r->source, "orientation " + std::string(axis_label(r->down)) + " has " +
                                      std::to_string(r->samples()) +
                                      " samples; the calibration needs at least " +
                                      std::to_string(min_samples));
    }
    if (r->samples() != first.samples() || r->phi.cols() != first.phi.cols()) {
      throw InputError(r->source, "orientation " + std::string(axis_label(r->down)) + " has " +
                                      std::to_string(r->samples()) + " samples, " +
                                      std::string(axis_label(first.down)) + " (" + first.source +
                                      ") " + std::to_string(first.samples()) +
                                      ": paired records are matched sample by sample");
    }
    for (Eigen::Index i = 0; i < r->samples(); ++i) {
      for (Eigen::Index k = 0; k < r->phi.cols(); ++k) {
        if (!(std::abs(r->phi(i, k) - first.phi(i, k)) <= max_phi_mismatch)) {
          const std::string where = static_cast<std::size_t>(i) < r->rows.size()
                                        ? r->rows[static_cast<std::size_t>(i)]
                                        : r->source + ", sample " + std::to_string(i);
          throw InputError(where, "shaft angle " + core::format_double(r->phi(i, k)) + " of leg " +
                                      std::to_string(k + 1) + " differs from " +
                                      core::format_double(first.phi(i, k)) + " of " +
                                      std::string(axis_label(first.down)) + "'s sample " +
                                      std::to_string(i) + " by more than " +
                                      core::format_double(max_phi_mismatch) +
                                      " turns: the records do not pair");
        }
      }
    }
  }
}

nlohmann::json calibration_json(const Calibration& c) {
  const Geometry& g = c.geometry;
  nlohmann::json legs = nlohmann::json::array();
  for (int k = 0; k < g.size(); ++k) {
    const auto ks = static_cast<std::size_t>(k);
    nlohmann::json leg = {{"leg", g.legs[ks]}};
    if (ks < c.hanging.legs.size()) {
      const LegEstimate& e = c.hanging.legs[ks];
      nlohmann::json pairs = nlohmann::json::array();
      for (const HangingPair& p : e.pairs) {
        pairs.push_back({{"down", axis_label(p.down)},
                         {"up", axis_label(opposite(p.down))},
                         {"axis", vec(p.axis)},
                         {"f_minus", vec(p.f_minus)},
                         {"d", vec(p.d)},
                         {"s_plus", vec(p.s_plus)},
                         {"s_minus", vec(p.s_minus)},
                         {"weight", p.weight},
                         {"weight_se", p.weight_se},
                         {"offset", vec(p.offset)},
                         {"offset_se", vec(p.offset_se)}});
      }
      leg["offset"] = vec(e.offset);
      leg["offset_se"] = vec(e.offset_se);
      leg["weight"] = e.weight;
      leg["weight_se"] = e.weight_se;
      leg["com"] = fit_json(e.com);
      leg["com_samples"] = e.com_phi.size();
      leg["com_fit_rms"] = e.com_fit_rms;
      leg["pairs"] = pairs;
    }
    const MountingEstimate& m = c.mounting;
    if (ks < m.rotation.size()) {
      leg["rotation"] = vec(rotation_vector(m.rotation[ks]));
      leg["rotation_matrix"] = mat(m.rotation[ks]);
    }
    if (ks < m.rotation_se.size()) {
      leg["rotation_se"] = vec(m.rotation_se[ks]);
    }
    if (ks < m.displacement.size()) {
      leg["displacement"] = vec(m.displacement[ks]);
    }
    if (ks < m.displacement_se.size()) {
      leg["displacement_se"] = vec(m.displacement_se[ks]);
    }
    legs.push_back(leg);
  }
  const HangingOptions& h = c.hanging.options;
  const MountingEstimate& m = c.mounting;
  nlohmann::json models = nlohmann::json::array();
  for (const ModelScore& s : c.models) {
    models.push_back({{"model", model_label(s.model)},
                      {"dof", s.dof},
                      {"rss", s.rss},
                      {"cv_mse", s.cv_mse},
                      {"bic", s.bic}});
  }
  return {
      {"legs", legs},
      {"robot_weight", g.robot_weight},
      {"hanging",
       {{"model", hanging_model_label(h.model)},
        {"com", h.com == ComEstimator::smoother ? "smoother" : "pointwise"},
        {"transition_variance", h.transition_variance},
        {"observation_variance", h.observation_variance},
        {"harmonics", h.harmonics},
        {"max_phi_mismatch", h.max_phi_mismatch}}},
      {"mounting",
       {{"model", model_label(m.model)},
        {"solver", solver_label(m.solver)},
        {"target", m.target == BalanceTarget::chassis ? "chassis" : "thesis_literal"},
        {"chassis_weight", m.chassis_weight},
        {"rss", m.rss},
        {"poses", m.poses},
        {"dof", m.dof},
        {"iterations", m.iterations},
        {"converged", m.converged},
        {"seconds", m.seconds},
        {"smallest_singular_value", m.smallest_singular_value}}},
      {"models", models},
      {"seconds_hanging", c.seconds_hanging},
      {"seconds_standing", c.seconds_standing},
  };
}

nlohmann::json truth_json(const SyntheticTruth& truth, const SynthOptions& o) {
  const Geometry& g = truth.geometry;
  nlohmann::json phi = nlohmann::json::array();
  for (int i = 0; i < kTruthComSamples; ++i) {
    phi.push_back(static_cast<double>(i) / kTruthComSamples);
  }
  nlohmann::json legs = nlohmann::json::array();
  for (int k = 0; k < truth.legs(); ++k) {
    const auto ks = static_cast<std::size_t>(k);
    const Frame& n = g.transducer[ks];
    nlohmann::json com = nlohmann::json::array();
    for (int i = 0; i < kTruthComSamples; ++i) {
      com.push_back(vec(truth.leg_com(k, static_cast<double>(i) / kTruthComSamples)));
    }
    legs.push_back({{"leg", g.legs[ks]},
                    {"position", vec(n.p)},
                    {"rotation", vec(rotation_vector(n.R))},
                    {"offset", vec(truth.offset[ks])},
                    {"weight", truth.weight[ks]},
                    {"mounting_rotation", vec(rotation_vector(truth.mounting_rotation[ks]))},
                    {"mounting_translation", vec(truth.mounting_translation[ks])},
                    {"displacement", vec(truth.displacement(k))},
                    {"com", com}});
  }
  return {
      {"options",
       {{"seed", o.seed},
        {"noise_scale", o.noise_scale},
        {"cycles", o.cycles},
        {"samples_per_cycle", o.samples_per_cycle},
        {"hanging_force_noise", o.hanging_force_noise},
        {"hanging_torque_noise", o.hanging_torque_noise},
        {"hanging_misalignment", o.hanging_misalignment},
        {"poses", o.poses},
        {"pose_force_noise", o.pose_force_noise},
        {"pose_torque_noise", o.pose_torque_noise},
        {"attitude_noise", o.attitude_noise},
        {"floor_tilt", o.floor_tilt},
        {"internal_force", o.internal_force},
        {"mounting_rotation", o.mounting_rotation},
        {"mounting_translation", o.mounting_translation}}},
      {"robot_weight", g.robot_weight},
      {"chassis_com", vec(truth.chassis_com)},
      {"chassis_weight", truth.chassis_weight()},
      {"com_torque_bias", truth.com_torque_bias()},
      {"com_phi", phi},
      {"legs", legs},
  };
}

}  // namespace slipwalk::calibration
