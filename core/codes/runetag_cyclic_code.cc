#include "core/codes/runetag_cyclic_code.h"

#include <utility>
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

// A word as three 43-bit planes: bit i of plane b is bit b of sector i's symbol (a dot of
// ring 2 - b), so that a whole word compares in a few popcounts.
struct Planes {
  std::array<uint64_t, 3> bits{};
};

Planes PlanesOf(const RuneWord& word, int rotation) {
  Planes planes;
  for (int i = 0; i < kRuneSectors; ++i) {
    const uint8_t symbol = word[(i + rotation) % kRuneSectors];
    for (int b = 0; b < 3; ++b) planes.bits[b] |= static_cast<uint64_t>((symbol >> b) & 1) << i;
  }
  return planes;
}

// Every codeword at every rotation: index kRuneSectors * id + rotation.
const std::vector<Planes>& RotatedCodebook() {
  static const std::vector<Planes> rotated = [] {
    std::vector<Planes> all;
    for (const RuneWord& word : Codebook()) {
      for (int r = 0; r < kRuneSectors; ++r) all.push_back(PlanesOf(word, r));
    }
    return all;
  }();
  return rotated;
}

// The first codeword and rotation whose cost erasures + 2 * mismatches against `read` is at
// most `limit`, where count(read, expected, planes) gives {erasures, mismatches} over the
// first `planes` planes, a lower bound of the full count (so a candidate can be dropped
// after one plane, as most are).
template <typename Count>
std::optional<RuneDecoded> FirstWithin(const RuneWord& read, int limit, const Count& count) {
  const Planes read_planes = PlanesOf(read, 0);
  const std::vector<Planes>& rotated = RotatedCodebook();
  for (size_t k = 0; k < rotated.size(); ++k) {
    const auto [lower_erasures, lower_mismatches] = count(read_planes, rotated[k], 1);
    if (lower_erasures + 2 * lower_mismatches > limit) continue;
    const auto [erasures, mismatches] = count(read_planes, rotated[k], 3);
    if (erasures + 2 * mismatches <= limit) {
      return RuneDecoded{static_cast<int>(k / kRuneSectors),
                         static_cast<int>(k % kRuneSectors),
                         mismatches,
                         erasures};
    }
  }
  return std::nullopt;
}

}  // namespace

const RuneWord& RuneCodeword(int id) { return Codebook()[static_cast<size_t>(id)]; }

std::optional<RuneDecoded> RuneDecode(const RuneWord& read) {
  return FirstWithin(
      read, kRuneMinDistance - 1, [](const Planes& read, const Planes& expected, int planes) {
        const uint64_t seen = read.bits[0] | read.bits[1] | read.bits[2];
        uint64_t differ = 0;
        for (int b = 0; b < planes; ++b) differ |= read.bits[b] ^ expected.bits[b];
        // Only an empty sector is an erasure.
        return std::pair(__builtin_popcountll(differ & ~seen), __builtin_popcountll(differ & seen));
      });
}

std::optional<RuneDecoded> RuneDecodeMissingDots(const RuneWord& read) {
  return FirstWithin(read,
                     (kRuneMinDotDistance - 1) / 2,
                     [](const Planes& read, const Planes& expected, int planes) {
                       int lost = 0, added = 0;
                       for (int b = 0; b < planes; ++b) {
                         lost += __builtin_popcountll(expected.bits[b] & ~read.bits[b]);
                         added += __builtin_popcountll(read.bits[b] & ~expected.bits[b]);
                       }
                       return std::pair(lost, added);
                     });
}

}  // namespace markerbench
