// The simple-id code of ARToolKitPlus-style markers (baselines.md): the 9-bit id repeated 4
// times, copy k XORed with kSimpleIdMasks[k] and stored in bits 27-9k..35-9k. Minimum
// distance 4, so one bit error is corrected and two are detected (three errors on the
// copies of one id bit read as another id).
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "core/codes/artkplus_id_code.h"

namespace markerbench {

// Chosen so that no codeword is a 90/180/270-degree rotation of another (artkplus_id_code_test).
inline constexpr std::array<uint32_t, 4> kSimpleIdMasks = {0x1a5, 0x0e3, 0x13c, 0x05a};
inline constexpr int kSimpleIds = 512;

uint64_t SimpleIdEncode(int id);
std::optional<DecodedId> SimpleIdDecode(uint64_t word);

}  // namespace markerbench
