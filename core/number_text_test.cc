#include "core/number_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "core/random.h"

namespace markerbench {
namespace {

TEST(NumberText, IsShortForDecimalLiterals) {
  EXPECT_EQ(NumberText(0.1), "0.1");
  EXPECT_EQ(NumberText(2.25), "2.25");
  EXPECT_EQ(NumberText(-3.0), "-3");
  EXPECT_EQ(NumberText(1e-20), "1e-20");
}

// The shortest digits that read back, never padding (%.15g wrote 4.94065645841247e-324 for
// the smallest denormal).
TEST(NumberText, IsTheShortestRoundTrip) {
  EXPECT_EQ(NumberText(5e-324), "5e-324");
  EXPECT_EQ(NumberText(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(NumberText(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(NumberText(1e22), "1e+22");
  EXPECT_EQ(NumberText(INFINITY), "inf");
}

TEST(NumberText, ReadsBackExactly) {
  Rng rng(11);
  for (int i = 0; i < 10000; ++i) {
    const double mantissa = rng.Gaussian();
    const double value = mantissa * std::pow(10.0, rng.Uniform(-12.0, 12.0));
    EXPECT_EQ(std::strtod(NumberText(value).c_str(), nullptr), value) << NumberText(value);
  }
}

// Out of range is nullopt, never an undefined cast (loaders_fuzz found one in frames.csv).
TEST(ParseWholeNumber, ReadsWholeNumbersInRangeOnly) {
  EXPECT_EQ(ParseWholeNumber("12", 0, 100), 12);
  EXPECT_EQ(ParseWholeNumber("12.0", 0, 100), 12);
  for (const char* bad : {"12.5", "-1", "101", "8.65065e+13", "1e300", "", "x"}) {
    EXPECT_FALSE(ParseWholeNumber(bad, 0, 100).has_value()) << bad;
  }
}

TEST(ParseUnsigned64, KeepsEveryBit) {
  EXPECT_EQ(ParseUnsigned64("18446744073709551615"), UINT64_MAX);
  EXPECT_EQ(ParseUnsigned64("9007199254740993"), 9007199254740993ull);  // 2^53 + 1
  for (const char* bad : {"18446744073709551616", "-3", "1.0", "1e3", "", " 1"}) {
    EXPECT_FALSE(ParseUnsigned64(bad).has_value()) << bad;
  }
}

TEST(ParseFiniteNumber, ReadsWholeFieldsOnly) {
  EXPECT_EQ(ParseFiniteNumber("0.6"), 0.6);
  EXPECT_EQ(ParseFiniteNumber("-1e-3\r"), -1e-3);
  for (const char* bad : {"0.6abc", "", " ", "nan", "inf", "1e999", "0.6 ", "\r", "--1"}) {
    EXPECT_FALSE(ParseFiniteNumber(bad).has_value()) << bad;
  }
}

}  // namespace
}  // namespace markerbench
