/* AVX2 PMB force and LPS dilation / force passes: 4 bonds per step, the body is
 * kernels/opt/bond_simd.h (method, contract and equality with the reference there); and the PMB
 * pass over the sliced layout, slices of 4 particles, kernels/opt/sell_simd.h. Compiled for
 * AVX2 + FMA by the target pragma below (FMA contraction stays off: PDK_KERNEL_FP_EXACT), so the
 * baseline build runs on any x86-64 and src/core/kernels.c installs these only on CPUs with AVX2. */
#include "kernels.h"

PDK_KERNEL_FP_EXACT

#if defined(__x86_64__) && defined(__GNUC__)
#pragma GCC target("avx2,fma")
#include <immintrin.h>

#define BS_W 4
#define BS_NAME(base) base##_avx2

/* rows p + 4 j[l] (32-byte aligned), transposed: c[m] lane l = p[4 j[l] + m] */
#define BS_LOAD4(p, j, c)                                                                          \
  do {                                                                                             \
    const __m256d r0_ = _mm256_load_pd((p) + 4 * (size_t)(j)[0]);                                 \
    const __m256d r1_ = _mm256_load_pd((p) + 4 * (size_t)(j)[1]);                                 \
    const __m256d r2_ = _mm256_load_pd((p) + 4 * (size_t)(j)[2]);                                 \
    const __m256d r3_ = _mm256_load_pd((p) + 4 * (size_t)(j)[3]);                                 \
    const __m256d t0_ = _mm256_unpacklo_pd(r0_, r1_), t1_ = _mm256_unpackhi_pd(r0_, r1_);         \
    const __m256d t2_ = _mm256_unpacklo_pd(r2_, r3_), t3_ = _mm256_unpackhi_pd(r2_, r3_);         \
    (c)[0] = (bs_vd)_mm256_permute2f128_pd(t0_, t2_, 0x20);                                        \
    (c)[1] = (bs_vd)_mm256_permute2f128_pd(t1_, t3_, 0x20);                                        \
    (c)[2] = (bs_vd)_mm256_permute2f128_pd(t0_, t2_, 0x31);                                        \
    (c)[3] = (bs_vd)_mm256_permute2f128_pd(t1_, t3_, 0x31);                                        \
  } while (0)
#define BS_SQRT(v) ((bs_vd)_mm256_sqrt_pd((__m256d)(v)))
#define BS_SET1(a) ((bs_vd)_mm256_set1_pd(a))
#define BS_MIN(a, b) ((bs_vd)_mm256_min_pd((__m256d)(a), (__m256d)(b)))
#define BS_GATHER(p, j)                                                                            \
  ((bs_vd)_mm256_i32gather_pd((p), _mm_load_si128((const __m128i *)(const void *)(j)), 8))
#define BS_CVT_F(p) ((bs_vd)_mm256_cvtps_pd(_mm_loadu_ps(p)))

#include "opt/bond_simd.h"
#include "opt/sell_simd.h"
#endif
