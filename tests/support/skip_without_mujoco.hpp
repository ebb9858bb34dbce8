#pragma once
// SKIP_WITHOUT_MUJOCO(): the first statement of a test that needs the MuJoCo peer; in a build
// without it (SLIPWALK_MUJOCO=OFF or libmujoco-dev missing) the test is skipped and says why.
#include <gtest/gtest.h>

#ifdef SLIPWALK_HAVE_MUJOCO
#define SKIP_WITHOUT_MUJOCO()
#else
#define SKIP_WITHOUT_MUJOCO() \
  GTEST_SKIP() << "built without MuJoCo (SLIPWALK_MUJOCO=OFF or libmujoco-dev missing)"
#endif
