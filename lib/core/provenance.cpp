#include "core/provenance.hpp"

#include <gsl/gsl_version.h>
#include <sundials/sundials_config.h>
#include <sys/utsname.h>

#include <Eigen/Core>
#include <boost/version.hpp>
#include <fstream>
#include <string>
#include <thread>

// SLIPWALK_GIT_COMMIT: the source state, read before every build (lib/git_id.cmake).
#include "slipwalk_git_id.hpp"
#ifndef SLIPWALK_VERSION
#define SLIPWALK_VERSION "0"
#endif
#ifndef SLIPWALK_COMPILER
#define SLIPWALK_COMPILER "unknown"
#endif

namespace slipwalk::core {

nlohmann::json machine_description() {
  std::string cpu = "unknown";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) {
        cpu = line.substr(line.find_first_not_of(" \t", colon + 1));
      }
      break;
    }
  }
  std::string os = "unknown";
  utsname u{};
  if (uname(&u) == 0) {
    os = std::string(u.sysname) + " " + u.release;
  }
  // How busy the machine was when the run started: timings taken under load are noisier.
  double load = -1.0;
  std::ifstream loadavg("/proc/loadavg");
  if (!(loadavg >> load)) {
    load = -1.0;
  }
  nlohmann::json out = {
      {"cpu", cpu}, {"logical_cores", std::thread::hardware_concurrency()}, {"os", os}};
  if (load >= 0.0) {
    out["load_average_1min"] = load;
  }
  return out;
}

nlohmann::json build_provenance() {
  return {
      {"slipwalk_version", SLIPWALK_VERSION},
      {"git_commit", SLIPWALK_GIT_COMMIT},
      {"compiler", SLIPWALK_COMPILER},
      {"libraries",
       {{"eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) +
                      "." + std::to_string(EIGEN_MINOR_VERSION)},
        {"sundials", SUNDIALS_VERSION},
        {"gsl", GSL_VERSION},
        {"boost", std::to_string(BOOST_VERSION / 100000) + "." +
                      std::to_string(BOOST_VERSION / 100 % 1000) + "." +
                      std::to_string(BOOST_VERSION % 100)}}},
      {"machine", machine_description()},
  };
}

}  // namespace slipwalk::core
