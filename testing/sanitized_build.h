// Whether this test program was built with AddressSanitizer or UBSan (CMake defines
// MARKERBENCH_ASAN / MARKERBENCH_UBSAN: clang 14 defines no __SANITIZE_* macro, and neither
// compiler one for UBSan). There the trackers run 5-9 times slower per frame than in Release
// (Eigen's expressions no longer inlined; measured in CI's tree, which leaves out UBSan's null,
// alignment and object-size checks and holds the fuzzers' coverage instrumentation: without
// it 3-5 times, with every UBSan check 10-20), so a test that repeats one check over many
// frames checks a sample of them (`SanitizedStride`; every frame would add about 3 minutes
// to CI's sanitizer run), and a long test whose claim is a count over many
// frames skips (`kSanitizedBuild`): the sanitizers look for memory errors and undefined
// behaviour, and CI runs every frame and every count in the optimised build.
#pragma once

namespace markerbench {

#if defined(MARKERBENCH_ASAN) || defined(MARKERBENCH_UBSAN)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif

// Every `stride`-th of a test's frames under the sanitizers, every frame otherwise.
constexpr int SanitizedStride(int stride) { return kSanitizedBuild ? stride : 1; }

}  // namespace markerbench
