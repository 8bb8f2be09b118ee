#include "trackers/runetag/cyclic_code.h"

#include <vector>

namespace markerbench {
namespace {

// SplitMix64 (Steele, Lea and Flood 2014): portable, so the codebook is the same everywhere.
uint64_t SplitMix64(uint64_t* state) {
  uint64_t z = (*state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Sectors where a and b rotated by r differ.
int RotatedDistance(const RuneWord& a, const RuneWord& b, int r) {
  int d = 0;
  for (int i = 0; i < kRuneSectors; ++i) d += a[i] != b[(i + r) % kRuneSectors];
  return d;
}

std::vector<RuneWord> BuildCodebook() {
  std::vector<RuneWord> book;
  uint64_t state = 20110620;  // fixed: the codebook is part of the marker definition
  while (static_cast<int>(book.size()) < kRuneIds) {
    RuneWord candidate;
    for (uint8_t& s : candidate) s = static_cast<uint8_t>(1 + SplitMix64(&state) % 7);
    bool far = true;
    for (int r = 1; r < kRuneSectors && far; ++r) {
      far = RotatedDistance(candidate, candidate, r) >= kRuneMinDistance;
    }
    for (size_t k = 0; k < book.size() && far; ++k) {
      for (int r = 0; r < kRuneSectors && far; ++r) {
        far = RotatedDistance(candidate, book[k], r) >= kRuneMinDistance;
      }
    }
    if (far) book.push_back(candidate);
  }
  return book;
}

const std::vector<RuneWord>& Codebook() {
  static const std::vector<RuneWord> book = BuildCodebook();
  return book;
}

// The first codeword and rotation whose cost against `read` is at most `limit`: a sector
// read as its symbol costs 0, one that is_erasure(read, expected) 1, any other 2.
template <typename IsErasure>
std::optional<RuneDecoded> FirstWithin(const RuneWord& read,
                                       int limit,
                                       const IsErasure& is_erasure) {
  const std::vector<RuneWord>& book = Codebook();
  for (size_t id = 0; id < book.size(); ++id) {
    for (int r = 0; r < kRuneSectors; ++r) {
      int erasures = 0, mismatches = 0;
      for (int i = 0; i < kRuneSectors && erasures + 2 * mismatches <= limit; ++i) {
        const uint8_t expected = book[id][(i + r) % kRuneSectors];
        if (read[i] == expected) continue;
        if (is_erasure(read[i], expected)) {
          ++erasures;
        } else {
          ++mismatches;
        }
      }
      if (erasures + 2 * mismatches <= limit) {
        return RuneDecoded{static_cast<int>(id), r, mismatches, erasures};
      }
    }
  }
  return std::nullopt;
}

}  // namespace

const RuneWord& RuneCodeword(int id) { return Codebook()[static_cast<size_t>(id)]; }

std::optional<RuneDecoded> RuneDecode(const RuneWord& read) {
  return FirstWithin(read, kRuneMinDistance - 1, [](uint8_t read_symbol, uint8_t) {
    return read_symbol == 0;  // only an empty sector is an erasure
  });
}

std::optional<RuneDecoded> RuneDecodeMissingDots(const RuneWord& read) {
  return FirstWithin(read, (kRuneMinDistance - 1) / 2, [](uint8_t read_symbol, uint8_t expected) {
    return (read_symbol & ~expected) == 0;  // dots lost, none added (empty included)
  });
}

}  // namespace markerbench
