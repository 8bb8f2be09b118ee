// The two id codes of ARToolKitPlus-style markers (baselines.md): a 36-bit word sampled from
// the 6x6 interior, cell (r, c) holding bit 35 - (6r + c), a set bit printed white. Shared by
// the marker generator (core/marker_bits) and the tracker, so both use one definition.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace markerbench {

enum class ArtkPlusIdMode {
  kBch,     // (36,12) BCH, corrects up to 4 bit errors, 4096 ids (artkplus_bch_code.h)
  kSimple,  // 9-bit id repeated 4 times with XOR masks, corrects 1 bit error, 512 ids
};

const char* ToString(ArtkPlusIdMode mode);  // "bch", "simple"
std::optional<ArtkPlusIdMode> ArtkPlusIdModeFromString(const std::string& name);

inline constexpr int kArtkPlusWordBits = 36;

struct DecodedId {
  int id = -1;
  int corrected_bits = 0;  // Hamming distance from the word read to the codeword
};

int ArtkPlusIdCount(ArtkPlusIdMode mode);
// Minimum Hamming distance between two codewords (9 for BCH, 4 for simple).
int ArtkPlusMinimumDistance(ArtkPlusIdMode mode);
// The 36-bit word printed for `id` (0 <= id < ArtkPlusIdCount(mode)).
uint64_t ArtkPlusEncode(ArtkPlusIdMode mode, int id);
// Bounded-distance decoding: the id whose codeword is within the mode's correction limit of
// `word`, or nullopt.
std::optional<DecodedId> ArtkPlusDecode(ArtkPlusIdMode mode, uint64_t word);
// The word of the same 6x6 pattern turned a quarter turn clockwise as seen from the front:
// new cell (r, c) = old cell (5 - c, r).
uint64_t ArtkPlusQuarterTurn(uint64_t word);

}  // namespace markerbench
