// FOGLAB_SIMD_CLONES: compile a hot loop twice, for AVX2 (x86-64-v3) and for
// the x86-64 baseline the library is built for, and let the loader pick the
// one the processor can run (GCC and clang function multiversioning,
// target_clones). On the 2e7-sample octave OADEV the AVX2 clone is about
// 1.6 times as fast (bench/RESULTS.md). Elsewhere, and where
// FOGLAB_NO_SIMD_CLONES is defined, the function is compiled once.
// A helper a cloned function calls must be FOGLAB_CLONED_INLINE: inlined
// into each clone, it is compiled for that clone's instruction set (left
// out of line, the compiler builds it once, for the baseline).
#pragma once

#define FOGLAB_CLONED_INLINE [[gnu::always_inline]] inline

#if defined(__x86_64__) && defined(__linux__) && !defined(FOGLAB_NO_SIMD_CLONES)
#if defined(__clang__)
#define FOGLAB_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define FOGLAB_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
#else
#define FOGLAB_SIMD_CLONES
#endif
