// Numbers as the reports print them for a reader.
#include <gtest/gtest.h>

#include <cmath>

#include "base/number_text.h"

namespace crowdprof {
namespace {

TEST(NumberText, SignificantDigitsNeverUseAnExponent) {
  EXPECT_EQ(significant(1370.4, 3), "1370");
  EXPECT_EQ(significant(0.73142, 3), "0.731");
  EXPECT_EQ(significant(86.0, 3), "86.0");
  EXPECT_EQ(significant(5.886, 3), "5.89");
  EXPECT_EQ(significant(0.0, 3), "0");
  EXPECT_EQ(significant(NAN, 3), "n/a");
}

TEST(NumberText, DurationsAreMicrosecondsBelowAMillisecond) {
  EXPECT_EQ(duration_text(0.7314), "731 µs");
  EXPECT_EQ(duration_text(0.0123), "12.3 µs");
  EXPECT_EQ(duration_text(1.0105), "1.01 ms");
  EXPECT_EQ(duration_text(16.66), "16.7 ms");
  EXPECT_EQ(duration_text(266.2), "266 ms");
}

TEST(NumberText, CountsHaveThousandsSeparated) {
  EXPECT_EQ(with_thousands(0), "0");
  EXPECT_EQ(with_thousands(999), "999");
  EXPECT_EQ(with_thousands(168334), "168,334");
  EXPECT_EQ(with_thousands(4042192), "4,042,192");
}

}  // namespace
}  // namespace crowdprof
