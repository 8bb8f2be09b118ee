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

TEST(NumberText, ReadsBackExactly) {
  Rng rng(11);
  for (int i = 0; i < 10000; ++i) {
    const double value = rng.Gaussian() * std::pow(10.0, rng.Uniform(-12.0, 12.0));
    EXPECT_EQ(std::strtod(NumberText(value).c_str(), nullptr), value) << NumberText(value);
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
