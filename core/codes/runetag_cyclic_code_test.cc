#include "core/codes/runetag_cyclic_code.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "core/codes/gf7_6.h"

namespace markerbench {
namespace {

constexpr Gf76::Element kW = 6 * 7 + 5 * 49 + 4 * 2401 + 16807;  // x^5 + 4x^4 + 5x^2 + 6x

RuneWord Rotated(const RuneWord& word, int rotation) {
  RuneWord read;
  for (int i = 0; i < kRuneSectors; ++i) read[i] = word[(i + rotation) % kRuneSectors];
  return read;
}

TEST(Gf76, TablesAgreeWithPolynomialArithmetic) {
  const Gf76& f = Gf76::Get();
  std::mt19937 rng(1);
  for (int k = 0; k < 2000; ++k) {
    const Gf76::Element a = rng() % Gf76::kSize, b = rng() % Gf76::kSize;
    EXPECT_EQ(f.Multiply(a, b), Gf76::MultiplyByPolynomials(a, b));
    if (a != 0) {
      EXPECT_EQ(f.Multiply(a, f.Inverse(a)), 1u);
    }
    EXPECT_EQ(Gf76::Add(a, Gf76::Negate(a)), 0u);
  }
  // GF(7) is the subfield of the constants.
  for (Gf76::Element a = 0; a < 7; ++a) {
    for (Gf76::Element b = 0; b < 7; ++b) EXPECT_EQ(f.Multiply(a, b), a * b % 7);
  }
}

TEST(RuneCode, WHasOrder43) {
  const Gf76& f = Gf76::Get();
  EXPECT_EQ(f.Power(kW, 43), 1u);
  EXPECT_NE(f.Power(kW, 1), 1u);  // 43 is prime, so any order above 1 is 43
}

// g(x) is over GF(7), monic, of degree 36, has the 28 consecutive zeros w^8..w^35 (the BCH
// bound: distance >= 29) and divides x^43 - 1, so the code is cyclic of dimension 7.
TEST(RuneCode, GeneratorHasTheConsecutiveZerosAndDividesX43Minus1) {
  const std::array<int, 37>& g = RuneGenerator();
  EXPECT_EQ(g[36], 1);
  const Gf76& f = Gf76::Get();
  for (int j = 8; j <= 35; ++j) {
    Gf76::Element value = 0;
    for (int k = 36; k >= 0; --k) {
      value = Gf76::Add(f.Multiply(value, f.Power(kW, j)), static_cast<Gf76::Element>(g[k]));
    }
    EXPECT_EQ(value, 0u) << "w^" << j;
  }
  std::vector<int> remainder(44, 0);  // x^43 - 1 divided by g over GF(7)
  remainder[43] = 1;
  remainder[0] = 6;
  for (int k = 43; k >= 36; --k) {
    const int c = remainder[k];
    for (int i = 0; i <= 36; ++i)
      remainder[k - 36 + i] = (remainder[k - 36 + i] + 7 * 7 - c * g[i]) % 7;
  }
  EXPECT_TRUE(std::all_of(remainder.begin(), remainder.end(), [](int c) { return c == 0; }));
}

// The minimum distance is exactly 30, one above the designed 29: the least weight of the 7^7 - 1
// nonzero codewords m(x) g(x), deg m <= 6 (the cyclic code is linear).
TEST(RuneCode, MinimumDistanceIsExactly30) {
  const std::array<int, 37>& g = RuneGenerator();
  int least = kRuneSectors;
  for (int message = 1; message < 823543; ++message) {
    std::array<int, kRuneSectors> c{};
    int digits = message;
    for (int shift = 0; digits > 0; ++shift, digits /= 7) {
      const int d = digits % 7;
      if (d == 0) continue;
      for (int i = 0; i < 37; ++i) c[shift + i] = (c[shift + i] + d * g[i]) % 7;
    }
    least =
        std::min<int>(least, kRuneSectors - static_cast<int>(std::count(c.begin(), c.end(), 0)));
  }
  EXPECT_EQ(least, kRuneMinDistance);
}

// The original's list: 17000 ids in [8, 7^6), each codeword in its canonical rotation
// (decodes to itself at rotation 0), symbols 1..7; every rotation of a codeword is the same
// marker turned (the cyclic structure).
TEST(RuneCode, TheCodeListHasTheOriginalsStructure) {
  const std::vector<int>& ids = RuneIds();
  ASSERT_EQ(ids.size(), static_cast<size_t>(kRuneIdCount));
  // The first and last ids, as an independent (Python) re-implementation of the list found.
  EXPECT_EQ(ids.front(), 8);
  EXPECT_EQ(ids.back(), 117647);
  EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
  EXPECT_FALSE(IsRuneId(0));
  std::mt19937 rng(2);
  for (int k = 0; k < 300; ++k) {
    const int id = ids[rng() % ids.size()];
    const RuneWord& word = RuneCodeword(id);
    for (uint8_t s : word) {
      EXPECT_GE(s, 1);
      EXPECT_LE(s, 7);
    }
    const int rotation = static_cast<int>(rng() % kRuneSectors);
    const std::optional<RuneDecoded> decoded = RuneDecode(Rotated(word, rotation));
    ASSERT_TRUE(decoded.has_value()) << id;
    EXPECT_EQ(decoded->id, id);
    EXPECT_EQ(decoded->rotation, rotation);
    EXPECT_EQ(decoded->mismatches + decoded->erasures, 0);
  }
}

// Any 2 × errors + erasures <= 28 is corrected, with the counts reported.
TEST(RuneCode, CorrectsErrorsAndErasuresUpToTheBound) {
  const std::vector<int>& ids = RuneIds();
  std::mt19937 rng(3);
  for (int trial = 0; trial < 400; ++trial) {
    const int id = ids[rng() % ids.size()];
    const int rotation = static_cast<int>(rng() % kRuneSectors);
    const int erasures = static_cast<int>(rng() % 29);
    const int errors = static_cast<int>(rng() % ((28 - erasures) / 2 + 1));
    RuneWord read = Rotated(RuneCodeword(id), rotation);
    std::vector<int> positions(kRuneSectors);
    for (int i = 0; i < kRuneSectors; ++i) positions[i] = i;
    std::shuffle(positions.begin(), positions.end(), rng);
    for (int k = 0; k < erasures; ++k) read[positions[k]] = 0;
    for (int k = erasures; k < erasures + errors; ++k) {
      read[positions[k]] = static_cast<uint8_t>(1 + (read[positions[k]] + rng() % 6) % 7);
    }
    const std::optional<RuneDecoded> decoded = RuneDecode(read);
    ASSERT_TRUE(decoded.has_value()) << "errors " << errors << " erasures " << erasures;
    EXPECT_EQ(decoded->id, id);
    EXPECT_EQ(decoded->rotation, rotation);
    EXPECT_EQ(decoded->mismatches, errors);
    EXPECT_EQ(decoded->erasures, erasures);
  }
}

TEST(RuneCode, EmptyAndConstantReadsDecodeToNoMarker) {
  RuneWord read{};
  EXPECT_FALSE(RuneDecode(read).has_value());
  read.fill(7);
  EXPECT_FALSE(RuneDecode(read).has_value());
}

TEST(RuneCode, LostDotsOfTheExpectedMarkerAreRecovered) {
  const int id = RuneIds()[5];
  RuneWord read = Rotated(RuneCodeword(id), 11);
  int lost = 0;
  for (int i = 0; i < kRuneSectors && lost < 14; i += 3) {
    const uint8_t lowest = read[i] & static_cast<uint8_t>(-read[i]);
    if (read[i] != lowest) {  // keep at least one dot: an empty sector is another case
      read[i] = static_cast<uint8_t>(read[i] & ~lowest);
      ++lost;
    }
  }
  const std::optional<RuneDecoded> decoded = RuneDecodeMissingDots(read, id);
  ASSERT_TRUE(decoded.has_value());
  EXPECT_EQ(decoded->rotation, 11);
  EXPECT_EQ(decoded->erasures, lost);
  EXPECT_FALSE(RuneDecodeMissingDots(read, RuneIds()[6]).has_value());
}

}  // namespace
}  // namespace markerbench
