#include "core/codes/runetag_cyclic_code.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace markerbench {
namespace {

RuneWord Rotated(const RuneWord& word, int rotation) {
  RuneWord read;
  for (int i = 0; i < kRuneSectors; ++i) read[i] = word[(i + rotation) % kRuneSectors];
  return read;
}

int Distance(const RuneWord& a, const RuneWord& b) {
  int d = 0;
  for (int i = 0; i < kRuneSectors; ++i) d += a[i] != b[i];
  return d;
}

TEST(RuneCode, SymbolsAreOneToSeven) {
  for (int id = 0; id < kRuneIds; ++id) {
    for (uint8_t s : RuneCodeword(id)) {
      EXPECT_GE(s, 1);
      EXPECT_LE(s, 7);
    }
  }
}

// The documented minimum distance, over every pair of codewords and every rotation, and
// between each codeword and its own nontrivial rotations; it is reached.
TEST(RuneCode, MinimumDistanceOverAllRotationsIsTheDocumentedOne) {
  int smallest = kRuneSectors;
  for (int a = 0; a < kRuneIds; ++a) {
    for (int b = a; b < kRuneIds; ++b) {
      for (int r = a == b ? 1 : 0; r < kRuneSectors; ++r) {
        smallest = std::min(smallest, Distance(RuneCodeword(a), Rotated(RuneCodeword(b), r)));
      }
    }
  }
  EXPECT_EQ(smallest, kRuneMinDistance);
}

TEST(RuneCode, MinimumDotDistanceOverAllRotationsIsTheDocumentedOne) {
  int smallest = 3 * kRuneSectors;
  for (int a = 0; a < kRuneIds; ++a) {
    for (int b = a; b < kRuneIds; ++b) {
      for (int r = a == b ? 1 : 0; r < kRuneSectors; ++r) {
        const RuneWord rotated = Rotated(RuneCodeword(b), r);
        int dots = 0;
        for (int i = 0; i < kRuneSectors; ++i) {
          dots += __builtin_popcount(RuneCodeword(a)[i] ^ rotated[i]);
        }
        smallest = std::min(smallest, dots);
      }
    }
  }
  EXPECT_EQ(smallest, kRuneMinDotDistance);
}

TEST(RuneCode, EveryIdDecodesAtEveryRotation) {
  for (int id = 0; id < kRuneIds; ++id) {
    for (int r = 0; r < kRuneSectors; ++r) {
      const std::optional<RuneDecoded> decoded = RuneDecode(Rotated(RuneCodeword(id), r));
      ASSERT_TRUE(decoded) << id << " " << r;
      EXPECT_EQ(decoded->id, id);
      EXPECT_EQ(decoded->rotation, r);
      EXPECT_EQ(decoded->mismatches, 0);
    }
  }
}

// Up to the design limit 2 * errors + erasures <= kRuneMinDistance - 1, at random rotations
// and positions (seeded).
TEST(RuneCode, ErrorsAndErasuresUpToTheDesignLimitAreCorrected) {
  std::mt19937 rng(2016);
  std::vector<int> sectors(kRuneSectors);
  for (int i = 0; i < kRuneSectors; ++i) sectors[i] = i;
  for (int id = 0; id < kRuneIds; ++id) {
    for (int errors = 0; 2 * errors < kRuneMinDistance; ++errors) {
      const int erasures = kRuneMinDistance - 1 - 2 * errors;
      const int r = static_cast<int>(rng() % kRuneSectors);
      RuneWord read = Rotated(RuneCodeword(id), r);
      std::shuffle(sectors.begin(), sectors.end(), rng);
      for (int k = 0; k < erasures; ++k) read[sectors[k]] = 0;
      for (int k = erasures; k < erasures + errors; ++k) {
        read[sectors[k]] = static_cast<uint8_t>(read[sectors[k]] % 7 + 1);  // another symbol
      }
      const std::optional<RuneDecoded> decoded = RuneDecode(read);
      ASSERT_TRUE(decoded) << id << ": " << errors << " errors, " << erasures << " erasures";
      EXPECT_EQ(decoded->id, id);
      EXPECT_EQ(decoded->rotation, r);
      EXPECT_EQ(decoded->mismatches, errors);
      EXPECT_EQ(decoded->erasures, erasures);
    }
  }
}

// Lost dots: up to (kRuneMinDotDistance - 1) / 2 of them, at random slots and rotations
// (seeded); then with extra dots, each costing two lost ones.
TEST(RuneCode, ReadsThatLostDotsDecodeUpToHalfTheDotDistance) {
  std::mt19937 rng(43);
  constexpr int kLimit = (kRuneMinDotDistance - 1) / 2;
  for (int id = 0; id < kRuneIds; ++id) {
    const int r = static_cast<int>(rng() % kRuneSectors);
    const int extra = id % 3;  // 0, 1 or 2 dots added
    RuneWord read = Rotated(RuneCodeword(id), r);
    std::vector<int> printed, blank;  // slots 3 * sector + bit
    for (int i = 0; i < kRuneSectors; ++i) {
      for (int bit = 0; bit < 3; ++bit)
        (read[i] & (1 << bit) ? printed : blank).push_back(3 * i + bit);
    }
    std::shuffle(printed.begin(), printed.end(), rng);
    std::shuffle(blank.begin(), blank.end(), rng);
    const int lost = kLimit - 2 * extra;
    for (int k = 0; k < lost; ++k)
      read[printed[k] / 3] &= static_cast<uint8_t>(~(1 << printed[k] % 3));
    for (int k = 0; k < extra; ++k) read[blank[k] / 3] |= static_cast<uint8_t>(1 << blank[k] % 3);
    const std::optional<RuneDecoded> decoded = RuneDecodeMissingDots(read);
    ASSERT_TRUE(decoded) << id;
    EXPECT_EQ(decoded->id, id);
    EXPECT_EQ(decoded->rotation, r);
    EXPECT_EQ(decoded->erasures, lost);
    EXPECT_EQ(decoded->mismatches, extra);
  }
  RuneWord lost_too_many = RuneCodeword(9);
  int lost = 0;
  for (int i = 0; lost <= kLimit; ++i) {
    lost += __builtin_popcount(lost_too_many[i]);
    lost_too_many[i] = 0;
  }
  EXPECT_FALSE(RuneDecodeMissingDots(lost_too_many));
}

TEST(RuneCode, RandomWordsAndHalfCodewordsBeyondTheLimitDoNotDecode) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 2000; ++trial) {
    RuneWord read;
    for (uint8_t& s : read) s = static_cast<uint8_t>(1 + rng() % 7);
    EXPECT_FALSE(RuneDecode(read)) << trial;
    EXPECT_FALSE(RuneDecodeMissingDots(read)) << trial;
  }
  RuneWord erased = RuneCodeword(5);
  std::fill(erased.begin(), erased.begin() + kRuneMinDistance, 0);
  EXPECT_FALSE(RuneDecode(erased));
}

}  // namespace
}  // namespace markerbench
