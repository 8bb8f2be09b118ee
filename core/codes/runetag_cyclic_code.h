// The RUNETag code (Bergamasco et al., CVPR 2011 and TPAMI 2016; baselines.md), built as the
// original library builds it, so that markers are interchangeable with it: the cyclic code
// of length 43 over GF(7) whose generator g(x) has the zeros w^8..w^35 (and their
// conjugates; 36 in all) of w = x^5 + 4x^4 + 5x^2 + 6x, an element of order 43 of GF(7^6)
// (gf7_6.h). Its dimension is 7; its designed distance is 29, so 2 × errors + erasures ≤ 28
// are corrected (as the original's decoder does), and its true minimum distance is 30. Each sector
// prints the symbol value + 1 (1..7: 3 bits, the inner ring most significant), so every sector has
// a dot; an empty sector read is an erasure.
//
// A marker's id is the original's index: the base-7 digits d0..d5 of the first six
// coefficients of word / g(x) (d0 least significant), taken of the word's canonical
// rotation, the one whose discrete Fourier coefficient Σ_j ω^j c_j over GF(173) (ω = 2^4, of
// order 43) is 2^k with k < 4. The ids are the original's code list: the first 17000
// distinct indices met while encoding the messages 0, 1, 2, ... (6 base-7 digits times
// x^k g(x)) and turning each to its canonical rotation, the last word met for an index kept.
// Shared with core's marker generator (core/marker_yaml.cc).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace markerbench {

inline constexpr int kRuneSectors = 43;
// The printed layout (baselines.md): ring radii as fractions of R, innermost first, and
// dot radius = ring radius / kRuneDotRadiusRatio.
inline constexpr std::array<double, 3> kRuneRingFractions = {4.0 / 6.0, 5.0 / 6.0, 1.0};
inline constexpr double kRuneDotRadiusRatio = 17.8;
inline constexpr int kRuneIdCount = 17000;
inline constexpr int kRuneDesignedDistance = 29;  // 28 consecutive zeros (the BCH bound)
inline constexpr int kRuneMinDistance = 30;       // runetag_cyclic_code_test checks it exactly

using RuneWord = std::array<uint8_t, kRuneSectors>;  // symbols 1..7; 0 = erased (a read)

// g(x): its 37 coefficients in GF(7), x^0 first.
const std::array<int, 37>& RuneGenerator();

bool IsRuneId(int id);
const std::vector<int>& RuneIds();  // ascending
// The codeword of an id (IsRuneId): symbol of sector i, i counter-clockwise from +x.
const RuneWord& RuneCodeword(int id);

struct RuneDecoded {
  int id = -1;
  int rotation = 0;    // read[i] = codeword[(i + rotation) % 43] for every sector read
  int mismatches = 0;  // sectors read with another symbol
  int erasures = 0;
};

// Bounded-distance decoding with erasures (syndromes, Berlekamp-Massey on the erasure-
// modified syndromes, Chien search and Forney's magnitudes): the codeword with
// 2 × mismatches + erasures < kRuneDesignedDistance, when it exists and is a marker's.
std::optional<RuneDecoded> RuneDecode(const RuneWord& read);

// For reads of `id`'s marker that lost dots (small, noisy or merged dots the detector
// missed), counted per dot: erasures = codeword dots not read, mismatches = dots read where
// the codeword has none. The rotation with erasures + 2 × mismatches ≤ (kRuneMinDistance -
// 1) / 2 is accepted; it is unique, since two words differing in d sectors differ in at
// least d dots. Only `id` is tried, so this confirms a marker and never names another.
std::optional<RuneDecoded> RuneDecodeMissingDots(const RuneWord& read, int id);

}  // namespace markerbench
