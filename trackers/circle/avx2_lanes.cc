#include "trackers/circle/avx2_lanes.h"

namespace markerbench {

#if defined(__x86_64__)
const bool kCpuHasAvx2 = [] {
  __builtin_cpu_init();  // a static initializer may run before the one that reads the CPU
  return __builtin_cpu_supports("avx2") != 0;
}();
#endif

}  // namespace markerbench
