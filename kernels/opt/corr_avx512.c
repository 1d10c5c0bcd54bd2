/* Correspondence shape, pass 1 and pass 2 for AVX-512 (F, VL, DQ, BW): kernels/opt/corr_simd.h
 * compiled for this target with 256-bit vectors: the gain over AVX2 is the 32 vector registers
 * (the pass-2 loop keeps i's F, centre and 17 neighbour streams live and spills with 16) and
 * masked remainders; 512-bit vectors measured slower (bench/log.md, "Correspondence
 * kernels"). The baseline build runs on any x86-64; src/core/kernels.c installs these only when the
 * CPU has AVX-512. */
#include "kernels.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#pragma GCC target("avx512f,avx512vl,avx512dq,avx512bw,fma,prefer-vector-width=256")
#elif defined(__x86_64__) && defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx512f,avx512vl,avx512dq,avx512bw,fma"))),    \
                             apply_to = function)
#endif

#define CORR_SFX avx512
#include "opt/corr_simd.h"

#if defined(__x86_64__) && defined(__clang__)
#pragma clang attribute pop
#endif
