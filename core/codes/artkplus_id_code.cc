#include "core/codes/artkplus_id_code.h"

#include "core/codes/artkplus_bch_code.h"
#include "core/codes/artkplus_simple_id_code.h"

namespace markerbench {

const char* ToString(ArtkPlusIdMode mode) {
  return mode == ArtkPlusIdMode::kBch ? "bch" : "simple";
}

std::optional<ArtkPlusIdMode> ArtkPlusIdModeFromString(const std::string& name) {
  if (name == "bch") return ArtkPlusIdMode::kBch;
  if (name == "simple") return ArtkPlusIdMode::kSimple;
  return std::nullopt;
}

int ArtkPlusIdCount(ArtkPlusIdMode mode) {
  return mode == ArtkPlusIdMode::kBch ? kBchIds : kSimpleIds;
}

int ArtkPlusMinimumDistance(ArtkPlusIdMode mode) {
  return mode == ArtkPlusIdMode::kBch ? 2 * kBchCorrectableBits + 1 : 4;
}

uint64_t ArtkPlusEncode(ArtkPlusIdMode mode, int id) {
  return mode == ArtkPlusIdMode::kBch ? BchEncode(id) : SimpleIdEncode(id);
}

std::optional<DecodedId> ArtkPlusDecode(ArtkPlusIdMode mode, uint64_t word) {
  return mode == ArtkPlusIdMode::kBch ? BchDecode(word) : SimpleIdDecode(word);
}

uint64_t ArtkPlusQuarterTurn(uint64_t word) {
  const auto bit = [](int r, int c) { return 35 - (6 * r + c); };
  uint64_t turned = 0;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) turned |= (word >> bit(5 - c, r) & 1) << bit(r, c);
  }
  return turned;
}

}  // namespace markerbench
