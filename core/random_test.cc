#include "core/random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace markerbench {
namespace {

TEST(Random, GaussianMomentsMatchStandardNormal) {
  Rng rng(SeedFor(1, 2, 3, SeedPurpose::kNoise));
  constexpr int kDraws = 2'000'000;
  double m1 = 0, m2 = 0, m4 = 0;
  int beyond3 = 0;
  for (int i = 0; i < kDraws; ++i) {
    const double z = rng.Gaussian();
    m1 += z;
    m2 += z * z;
    m4 += z * z * z * z;
    beyond3 += std::abs(z) > 3.0;
  }
  m1 /= kDraws;
  m2 /= kDraws;
  m4 /= kDraws;
  // Tolerances are about 5 standard errors at 2e6 draws.
  EXPECT_LE(std::abs(m1), 0.004);
  EXPECT_LE(std::abs(m2 - 1.0), 0.005);
  EXPECT_LE(std::abs(m4 - 3.0), 0.03);
  // P(|z| > 3) = 0.0026998: exercises the tail and wedge branches.
  EXPECT_NEAR(beyond3 / static_cast<double>(kDraws), 0.0026998, 0.0002);
}

TEST(Random, FillGaussianMomentsMatchStandardNormal) {
  Rng rng(SeedFor(4, 5, 6, SeedPurpose::kNoise));
  constexpr int kDraws = 2'000'000;
  std::vector<float> z(kDraws);
  rng.FillGaussian(2.0f, kDraws, z.data());
  double m1 = 0, m2 = 0, m4 = 0;
  int beyond3 = 0;
  for (float v : z) {
    const double x = v / 2.0;
    m1 += x;
    m2 += x * x;
    m4 += x * x * x * x;
    beyond3 += std::abs(x) > 3.0;
  }
  EXPECT_LE(std::abs(m1 / kDraws), 0.004);
  EXPECT_LE(std::abs(m2 / kDraws - 1.0), 0.005);
  EXPECT_LE(std::abs(m4 / kDraws - 3.0), 0.03);
  EXPECT_NEAR(beyond3 / static_cast<double>(kDraws), 0.0026998, 0.0002);
}

TEST(Random, UniformInUnitInterval) {
  Rng rng(5);
  double sum = 0;
  for (int i = 0; i < 100000; ++i) {
    const double u = rng.Uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  EXPECT_NEAR(sum / 100000, 0.5, 0.005);
}

TEST(Random, SameSeedSameStreamDifferentSeedDifferentStream) {
  Rng a(SeedFor(7, 0, 1, SeedPurpose::kPose)), b(SeedFor(7, 0, 1, SeedPurpose::kPose));
  Rng c(SeedFor(7, 0, 1, SeedPurpose::kNoise));
  bool any_difference = false;
  for (int i = 0; i < 100; ++i) {
    const uint64_t x = a.NextU64();
    EXPECT_EQ(x, b.NextU64());
    any_difference |= x != c.NextU64();
  }
  EXPECT_TRUE(any_difference);
}

}  // namespace
}  // namespace markerbench
