// The histogram of byte values (grey levels, their differences), counted in four histograms in
// turn and summed when read: neighbouring values mostly fall in the same few bins (paper, a
// smoothed image, small differences), and one histogram's increments would each wait on the
// last.
#pragma once

#include <array>
#include <cstdint>

namespace markerbench {

class ByteHistogram {
 public:
  // Counts values[0, n).
  void Add(const uint8_t* values, int n);
  // How many values were counted at each level.
  std::array<int, 256> Counts() const;
  int total() const { return total_; }
  // The median level (the lower one of an even count; 0 where none was counted).
  int Median() const;

 private:
  static constexpr int kLanes = 4;
  std::array<std::array<int, 256>, kLanes> lanes_{};
  int total_ = 0;
};

}  // namespace markerbench
