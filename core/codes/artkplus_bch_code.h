// The (36,12) binary BCH code of ARToolKitPlus's BCH-id markers (baselines.md): the
// narrow-sense primitive BCH code of length 63 over GF(2^6) (primitive polynomial
// x^6 + x + 1) with designed distance 9, i.e. generator g(x) = lcm of the minimal polynomials
// of alpha^1..alpha^8 (degree 24), shortened to length 36. Its true minimum distance is also
// 9 (ten codewords of weight 9), so it corrects up to 4 bit errors; five errors that fall on
// five of the nine bits of a weight-9 codeword are decoded, necessarily, as another id.
// Words are systematic (id in bits 24..35) and XORed with kBchMask.
#pragma once

#include <cstdint>
#include <optional>

#include "core/codes/artkplus_id_code.h"

namespace markerbench {

inline constexpr uint64_t kBchMask = 0x8f80b8750ULL;
inline constexpr int kBchIds = 4096;
inline constexpr int kBchCorrectableBits = 4;

// g(x), bit i holding the coefficient of x^i.
uint64_t BchGenerator();
// The masked codeword of id (0 <= id < 4096).
uint64_t BchEncode(int id);
// Syndromes, Berlekamp-Massey and a Chien search over the 36 positions that exist; nullopt
// when more than 4 errors are detected.
std::optional<DecodedId> BchDecode(uint64_t word);

}  // namespace markerbench
