#include "trackers/circle/normal_tables.h"

#include "trackers/circle/blurred_design.h"

namespace markerbench {

NormalTailTable::NormalTailTable() {
  for (int i = 0; i < kNodes; ++i) {
    const double z = -kEnd + static_cast<double>(i) / kPerUnit;
    const double tail = 0.5 * std::erfc(z / std::sqrt(2.0));
    minus_log_tail_[i] = -std::log(tail);
    mills_[i] = NormalDensity(z) / tail;
    mills_slope_[i] = mills_[i] * (mills_[i] - z);
  }
}

const NormalTailTable kNormalTailTable;

NormalCdfTable::NormalCdfTable() {
  for (int i = 0; i < kNodes; ++i) {
    const double z = -kEnd + static_cast<double>(i) / kPerUnit;
    cdf_[i] = NormalCdf(z);
    density_[i] = NormalDensity(z);
    density_slope_[i] = -z * density_[i];
  }
}

const NormalCdfTable kNormalCdfTable;

}  // namespace markerbench
