#include "vb/engine/text_format.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include "support/lcg.h"

namespace vb {
namespace {

std::string Printf17g(double v) {
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

TEST(TextFormat, FormatExactRoundTripsBitForBit) {
  for (double v : {0.1, 1.0 / 3.0, -2.5e-300, 6.02214076e23, 29.615000000000002}) {
    EXPECT_EQ(std::strtod(FormatExact(v).c_str(), nullptr), v) << FormatExact(v);
  }
  EXPECT_EQ(FormatExact(2.0), "2");
}

// FormatExact is std::to_chars(general, 17); every result file was written with snprintf's
// "%.17g" before, and must keep its bytes.
TEST(TextFormat, FormatExactIsPrintfsPercent17g) {
  const double inf = std::numeric_limits<double>::infinity();
  for (double v : {0.0, -0.0, 1.0, -1.0, 0.1, 1e-320, -4.9e-324, 1.7976931348623157e308, inf, -inf,
                   std::nan(""), -std::nan(""), 1e15, 1e16, 1e17, 1e-5, 9.9999999999999995e-5,
                   28.35, 0.005 * 5671}) {
    EXPECT_EQ(FormatExact(v), Printf17g(v));
  }
  test::UniformLcg u(24);
  std::string appended;
  std::string expected;
  for (int i = 0; i < 200000; ++i) {
    const double r = u();
    double v;
    if (i % 3 == 0) {   // any bit pattern
      const std::uint64_t bits =
          (static_cast<std::uint64_t>(r * 4294967296.0) << 32) ^
          static_cast<std::uint64_t>(u() * 4294967296.0);
      std::memcpy(&v, &bits, sizeof(v));
    } else if (i % 3 == 1) {   // magnitudes from 1e-20 to 1e20
      v = (u() - 0.5) * std::pow(10.0, std::floor(r * 40.0) - 20.0);
    } else {   // multiples of a step, as trajectory times and rounded values
      v = std::floor(r * 1e6) * 0.005;
    }
    ASSERT_EQ(FormatExact(v), Printf17g(v)) << i;
    if (i < 1000) {
      AppendExact(v, &appended);
      appended += ',';
      expected += Printf17g(v) + ",";
    }
  }
  EXPECT_EQ(appended, expected);
}

TEST(TextFormat, CsvFieldQuotesOnlyWhenNeeded) {
  EXPECT_EQ(CsvField("reached the goal"), "reached the goal");
  EXPECT_EQ(CsvField("a,b"), "\"a,b\"");
  EXPECT_EQ(CsvField("key 'x': \"bad\""), "\"key 'x': \"\"bad\"\"\"");
  EXPECT_EQ(CsvField("two\nlines"), "\"two\nlines\"");
}

}  // namespace
}  // namespace vb
