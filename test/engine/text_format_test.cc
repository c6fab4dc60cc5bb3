#include "vb/engine/text_format.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace vb {
namespace {

TEST(TextFormat, FormatExactRoundTripsBitForBit) {
  for (double v : {0.1, 1.0 / 3.0, -2.5e-300, 6.02214076e23, 29.615000000000002}) {
    EXPECT_EQ(std::strtod(FormatExact(v).c_str(), nullptr), v) << FormatExact(v);
  }
  EXPECT_EQ(FormatExact(2.0), "2");
}

TEST(TextFormat, CsvFieldQuotesOnlyWhenNeeded) {
  EXPECT_EQ(CsvField("reached the goal"), "reached the goal");
  EXPECT_EQ(CsvField("a,b"), "\"a,b\"");
  EXPECT_EQ(CsvField("key 'x': \"bad\""), "\"key 'x': \"\"bad\"\"\"");
  EXPECT_EQ(CsvField("two\nlines"), "\"two\nlines\"");
}

}  // namespace
}  // namespace vb
