#include "core/codes/artkplus_id_code.h"

#include <gtest/gtest.h>

#include <bitset>
#include <iostream>
#include <random>
#include <vector>

#include "core/codes/artkplus_bch_code.h"
#include "core/codes/artkplus_simple_id_code.h"

namespace markerbench {
namespace {

constexpr uint64_t kWordMask = (1ULL << kArtkPlusWordBits) - 1;

int Weight(uint64_t word) { return static_cast<int>(std::bitset<64>(word).count()); }

// `count` distinct random bit positions of a 36-bit word.
uint64_t RandomErrors(int count, std::mt19937_64* rng) {
  uint64_t errors = 0;
  std::uniform_int_distribution<int> position(0, kArtkPlusWordBits - 1);
  while (Weight(errors) < count) errors |= 1ULL << position(*rng);
  return errors;
}

// Distance from `word` to the nearest codeword other than id's.
int DistanceToOtherCodeword(ArtkPlusIdMode mode, uint64_t word, int id) {
  int best = kArtkPlusWordBits;
  for (int other = 0; other < ArtkPlusIdCount(mode); ++other) {
    if (other != id) best = std::min(best, Weight(word ^ ArtkPlusEncode(mode, other)));
  }
  return best;
}

TEST(BchCode, GeneratorHasDegree24AndTheCodeMinimumDistance9) {
  const uint64_t g = BchGenerator();
  EXPECT_EQ(63 - __builtin_clzll(g), 24);
  EXPECT_EQ(g & 1, 1u);
  // The code is linear: its minimum distance is the least weight of a nonzero codeword.
  int min_weight = kArtkPlusWordBits, at_min = 0;
  for (int id = 1; id < kBchIds; ++id) {
    const int w = Weight(BchEncode(id) ^ kBchMask);
    if (w < min_weight) min_weight = w, at_min = 0;
    at_min += w == min_weight;
  }
  EXPECT_EQ(min_weight, ArtkPlusMinimumDistance(ArtkPlusIdMode::kBch));
  EXPECT_EQ(at_min, 10);
  EXPECT_EQ(BchEncode(0), kBchMask);
}

TEST(IdCode, EveryIdEncodesToA36BitWordAndDecodesCleanly) {
  for (ArtkPlusIdMode mode : {ArtkPlusIdMode::kBch, ArtkPlusIdMode::kSimple}) {
    for (int id = 0; id < ArtkPlusIdCount(mode); ++id) {
      const uint64_t word = ArtkPlusEncode(mode, id);
      ASSERT_EQ(word & ~kWordMask, 0u) << ToString(mode) << " id " << id;
      const std::optional<DecodedId> decoded = ArtkPlusDecode(mode, word);
      ASSERT_TRUE(decoded) << ToString(mode) << " id " << id;
      EXPECT_EQ(decoded->id, id);
      EXPECT_EQ(decoded->corrected_bits, 0);
    }
  }
}

TEST(BchCode, UpToFourRandomBitFlipsAreCorrected) {
  std::mt19937_64 rng(20070101);
  for (int id = 0; id < kBchIds; ++id) {
    for (int flips = 1; flips <= kBchCorrectableBits; ++flips) {
      const std::optional<DecodedId> decoded = BchDecode(BchEncode(id) ^ RandomErrors(flips, &rng));
      ASSERT_TRUE(decoded) << "id " << id << ", " << flips << " flips";
      EXPECT_EQ(decoded->id, id);
      EXPECT_EQ(decoded->corrected_bits, flips);
    }
  }
}

// With minimum distance 9 no decoder that corrects 4 errors can reject every 5-error word:
// a word 5 flips from id's codeword and 4 from another's is decoded as the other. The
// decoder must do that and nothing worse: any word it accepts lies within 4 bits of the
// codeword it returns, and every other 5..8-flip word is rejected.
TEST(BchCode, FiveToEightFlipsDecodeToAnotherIdOnlyWithinFourBitsOfItsCodeword) {
  std::mt19937_64 rng(20100301);
  std::uniform_int_distribution<int> any_id(0, kBchIds - 1);
  int wrong = 0, trials = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int id = any_id(rng);
    for (int flips = 5; flips <= 8; ++flips) {
      const uint64_t word = BchEncode(id) ^ RandomErrors(flips, &rng);
      const std::optional<DecodedId> decoded = BchDecode(word);
      const int nearest_other = DistanceToOtherCodeword(ArtkPlusIdMode::kBch, word, id);
      ++trials;
      if (!decoded) {
        EXPECT_GT(nearest_other, kBchCorrectableBits) << "id " << id << ", " << flips;
        continue;
      }
      ASSERT_NE(decoded->id, id) << "id " << id << ", " << flips << " flips";
      EXPECT_LE(Weight(word ^ BchEncode(decoded->id)), kBchCorrectableBits);
      EXPECT_EQ(decoded->corrected_bits, Weight(word ^ BchEncode(decoded->id)));
      ++wrong;
    }
  }
  EXPECT_LT(wrong, trials / 100) << "wrong ids are the rare words near a weight-9..12 codeword";
}

// Exhaustively, for two ids: the 5-flip words decoded as another id are exactly those on
// five of the nine bits of one of the ten weight-9 codewords, 10 * C(9,5) = 1260 of 376992.
TEST(BchCode, ExactlyThe1260FiveFlipWordsInsideAWeight9CodewordDecodeWrong) {
  for (int id : {0, 2741}) {
    const uint64_t codeword = BchEncode(id);
    int wrong = 0;
    for (int a = 0; a < 36; ++a)
      for (int b = a + 1; b < 36; ++b)
        for (int c = b + 1; c < 36; ++c)
          for (int d = c + 1; d < 36; ++d)
            for (int e = d + 1; e < 36; ++e) {
              const uint64_t errors = 1ULL << a | 1ULL << b | 1ULL << c | 1ULL << d | 1ULL << e;
              const std::optional<DecodedId> decoded = BchDecode(codeword ^ errors);
              if (!decoded) continue;
              ASSERT_NE(decoded->id, id);
              const uint64_t difference = (codeword ^ BchEncode(decoded->id));
              ASSERT_EQ(Weight(difference), 9);
              ASSERT_EQ(difference & errors, errors);
              ++wrong;
            }
    EXPECT_EQ(wrong, 1260) << "id " << id;
  }
}

TEST(SimpleIdCode, OneFlipIsCorrectedAndTwoAreDetected) {
  std::mt19937_64 rng(20070102);
  for (int id = 0; id < kSimpleIds; ++id) {
    const std::optional<DecodedId> one = SimpleIdDecode(SimpleIdEncode(id) ^ RandomErrors(1, &rng));
    ASSERT_TRUE(one);
    EXPECT_EQ(one->id, id);
    EXPECT_EQ(one->corrected_bits, 1);
    EXPECT_FALSE(SimpleIdDecode(SimpleIdEncode(id) ^ RandomErrors(2, &rng))) << "id " << id;
  }
  EXPECT_EQ(ArtkPlusMinimumDistance(ArtkPlusIdMode::kSimple), 4);
  EXPECT_EQ(Weight(SimpleIdEncode(0) ^ SimpleIdEncode(1)), 4);
}

TEST(IdCode, FourQuarterTurnsAreTheIdentity) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 100; ++i) {
    const uint64_t word = rng() & kWordMask;
    uint64_t turned = word;
    for (int k = 0; k < 4; ++k) turned = ArtkPlusQuarterTurn(turned);
    EXPECT_EQ(turned, word);
    EXPECT_EQ(Weight(ArtkPlusQuarterTurn(word)), Weight(word));
  }
  // The top-left cell (bit 35) goes to the top-right (bit 30).
  EXPECT_EQ(ArtkPlusQuarterTurn(1ULL << 35), 1ULL << 30);
}

// A turned codeword must not read as a codeword, or the marker's orientation (and so its
// corner order) would be ambiguous. Simple ids: no turned word even decodes. BCH: the few
// turned words within 4 bits of a codeword are counted, and none is a codeword itself.
TEST(IdCode, TurnedCodewordsDoNotReadAsCodewords) {
  for (int id = 0; id < kSimpleIds; ++id) {
    uint64_t word = SimpleIdEncode(id);
    for (int k = 1; k < 4; ++k) {
      word = ArtkPlusQuarterTurn(word);
      EXPECT_FALSE(SimpleIdDecode(word)) << "id " << id << " turned " << k;
    }
  }
  int decodable = 0;
  for (int id = 0; id < kBchIds; ++id) {
    uint64_t word = BchEncode(id);
    for (int k = 1; k < 4; ++k) {
      word = ArtkPlusQuarterTurn(word);
      const std::optional<DecodedId> decoded = BchDecode(word);
      if (!decoded) continue;
      EXPECT_GT(decoded->corrected_bits, 0) << "id " << id << " turned " << k;
      ++decodable;
    }
  }
  std::cout << "BCH: " << decodable << " of " << 3 * kBchIds
            << " turned codewords lie within 4 bits of a codeword\n";
  EXPECT_LT(decodable, 3 * kBchIds / 50);
}

}  // namespace
}  // namespace markerbench
