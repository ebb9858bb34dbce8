#include "core/provenance.hpp"

#include <gsl/gsl_version.h>
#include <sundials/sundials_config.h>

#include <Eigen/Core>
#include <boost/version.hpp>
#include <string>

#ifndef SLIPWALK_GIT_COMMIT
#define SLIPWALK_GIT_COMMIT "unknown"
#endif
#ifndef SLIPWALK_VERSION
#define SLIPWALK_VERSION "0"
#endif
#ifndef SLIPWALK_COMPILER
#define SLIPWALK_COMPILER "unknown"
#endif

namespace slipwalk::core {

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
  };
}

}  // namespace slipwalk::core
