#include "core/codes/artkplus_simple_id_code.h"

namespace markerbench {
namespace {

constexpr int kIdBits = 9;
constexpr uint32_t kIdMask = (1u << kIdBits) - 1;

int CopyShift(int k) { return 27 - kIdBits * k; }

}  // namespace

uint64_t SimpleIdEncode(int id) {
  uint64_t word = 0;
  for (int k = 0; k < 4; ++k) {
    word |= static_cast<uint64_t>((static_cast<uint32_t>(id) ^ kSimpleIdMasks[k]) & kIdMask)
            << CopyShift(k);
  }
  return word;
}

std::optional<DecodedId> SimpleIdDecode(uint64_t word) {
  DecodedId decoded{0, 0};
  for (int b = 0; b < kIdBits; ++b) {
    int ones = 0;
    for (int k = 0; k < 4; ++k) {
      ones += static_cast<int>(((word >> CopyShift(k)) ^ kSimpleIdMasks[k]) >> b & 1);
    }
    if (ones >= 3) decoded.id |= 1 << b;
    decoded.corrected_bits += ones >= 3 ? 4 - ones : ones;
  }
  if (decoded.corrected_bits > 1) return std::nullopt;  // half the minimum distance of 4
  return decoded;
}

}  // namespace markerbench
