// The RUNETag-style code (baselines.md): 43 sectors, each holding a symbol 1..7 (3 bits, the
// inner ring most significant, so every sector has at least one dot). The original uses an
// algebraic cyclic code over GF(7); ours is a codebook built greedily from a fixed seed so
// that every codeword differs from every rotation of every other codeword, and from its own
// nontrivial rotations, in at least kRuneMinDistance sectors. A read is decoded by matching
// all 43 rotations of every codeword, with unseen or empty sectors as erasures. Shared with
// core's marker generator (core/marker_bits.cc).
#pragma once

#include <array>
#include <cstdint>
#include <optional>

namespace markerbench {

inline constexpr int kRuneSectors = 43;
// The printed layout (baselines.md): ring radii as fractions of R, innermost first, and
// dot radius = ring radius / kRuneDotRadiusRatio.
inline constexpr std::array<double, 3> kRuneRingFractions = {4.0 / 6.0, 5.0 / 6.0, 1.0};
inline constexpr double kRuneDotRadiusRatio = 17.8;
inline constexpr int kRuneIds = 128;
// The rotation-aware minimum Hamming distance over symbols that the codebook reaches
// (runetag_cyclic_code_test checks it over every pair and rotation). 29 equals the original's GF(7)
// code (2 * errors + erasures <= 28); 30 would take seconds of greedy search at start-up.
inline constexpr int kRuneMinDistance = 29;
// The same minimum counted in dots (slots printed in one word and not in the other): every
// sector that differs differs in at least one dot, and most in two or three.
inline constexpr int kRuneMinDotDistance = 39;

using RuneWord = std::array<uint8_t, kRuneSectors>;  // symbols; 0 = erased (decoder input only)

// The codeword of id (0 <= id < kRuneIds): symbol of sector i, i counter-clockwise from +x.
const RuneWord& RuneCodeword(int id);

struct RuneDecoded {
  int id = -1;
  int rotation = 0;    // read[i] = codeword[(i + rotation) % 43] for every sector read
  int mismatches = 0;  // sectors read with another symbol
  int erasures = 0;
};

// Bounded-distance decoding with erasures: the codeword and rotation with
// 2 * mismatches + erasures < kRuneMinDistance (unique when it exists), or nullopt.
std::optional<RuneDecoded> RuneDecode(const RuneWord& read);

// For reads that lost dots (small, noisy or merged dots the detector missed), counted per
// dot: erasures = codeword dots not read, mismatches = dots read where the codeword has none.
// The codeword and rotation with erasures + 2 * mismatches <= (kRuneMinDotDistance - 1) / 2
// is accepted; it is unique, since each dot where two codewords differ costs at least 1
// against one of them.
std::optional<RuneDecoded> RuneDecodeMissingDots(const RuneWord& read);

}  // namespace markerbench
