// core::Range: the interval test agrees with its printed description at every kind of end, and
// the error names the place, the range and the value.
#include <gtest/gtest.h>

#include <limits>

#include "core/range.hpp"

namespace slipwalk::core {
namespace {

TEST(Range, OpenAndClosedEndsAdmitExactlyWhatTheyPrint) {
  const Range r = positive_up_to(10.0, "kg");
  EXPECT_EQ(r.describe(), "(0, 10] kg");
  EXPECT_FALSE(r.contains(0.0));
  EXPECT_TRUE(r.contains(5e-324));
  EXPECT_TRUE(r.contains(10.0));
  EXPECT_FALSE(r.contains(std::nextafter(10.0, 11.0)));
  const Range c = closed(-1.0, 1.0);
  EXPECT_EQ(c.describe(), "[-1, 1]");
  EXPECT_TRUE(c.contains(-1.0));
  EXPECT_TRUE(c.contains(1.0));
}

TEST(Range, NonFiniteValuesAreNeverAdmitted) {
  const double inf = std::numeric_limits<double>::infinity();
  const Range everything{-inf, inf, false, false, ""};
  EXPECT_FALSE(everything.contains(inf));
  EXPECT_FALSE(everything.contains(-inf));
  EXPECT_FALSE(everything.contains(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_TRUE(everything.contains(1e308));
}

TEST(Range, TheErrorNamesPlaceRangeAndValue) {
  try {
    require_in("--m", 1e-320, closed(1e-6, 1e6, "kg"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "--m");
    EXPECT_NE(std::string(e.what()).find("must be in [1e-06, 1000000] kg, got "), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace slipwalk::core
