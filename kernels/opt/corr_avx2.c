/* Correspondence shape, pass 1 and pass 2 for AVX2 + FMA (256-bit vectors): kernels/opt/corr_simd.h
 * compiled for this target. The baseline build runs on any x86-64; src/core/kernels.c installs these
 * only when the CPU has AVX2 and FMA. */
#include "kernels.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#pragma GCC target("avx2,fma")
#elif defined(__x86_64__) && defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,fma"))), apply_to = function)
#endif

#define CORR_SFX avx2
#include "opt/corr_simd.h"

#if defined(__x86_64__) && defined(__clang__)
#pragma clang attribute pop
#endif
