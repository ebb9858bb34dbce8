#pragma once
// Shared by the tests of shards and MPI sweeps: their spec, a sweep's CSV without the columns its
// kind marks as timings (which alone may differ between two runs with timing on), and the ids of
// its rows.
#include <cstddef>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "sweeps/engine/point_kind.hpp"

namespace slipwalk::test_support {

/// 2 × 9 × 3 = 54 points of study "test", name "mixed": closed forms, the analytic stroke map
/// and CVODE, so that points differ in cost as in real sweeps.
inline std::string mixed_spec(const std::string& description) {
  return "study = \"test\"\nname = \"mixed\"\nkind = \"inchworm_vss\"\ndescription = \"" +
         description +
         "\"\n[params]\nrtol = 1e-9\n[axes]\nmu = [1.0, 0.2]\nF_frac = { linspace = [0.05, "
         "1.0], n = 9 }\nmethod = [\"exact\", \"analytic\", \"cvode\"]\n";
}

/// The cells of one CSV line, split at every comma: the tests' specs write no quoted cells.
inline std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  for (std::size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1) {
    cells.push_back(line.substr(start, comma - start));
  }
  cells.push_back(line.substr(start));
  return cells;
}

/// `csv` with the cells of `kind`'s timing columns dropped from every line (the header too).
inline std::string without_timing(const std::string& csv, const sweeps::PointKind& kind) {
  std::istringstream in(csv);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    const std::vector<std::string> cells = csv_cells(line);
    std::string kept;
    bool first = true;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (i < kind.columns.size() && kind.columns[i].timing) {
        continue;
      }
      kept += (first ? "" : ",") + cells[i];
      first = false;
    }
    out += kept + "\n";
  }
  return out;
}

/// The ids (first cells) of a CSV's rows, below its header.
inline std::multiset<long long> row_ids(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::multiset<long long> ids;
  while (std::getline(in, line)) {
    ids.insert(std::stoll(line.substr(0, line.find(','))));
  }
  return ids;
}

}  // namespace slipwalk::test_support
