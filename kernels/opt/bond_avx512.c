/* AVX-512 PMB force and LPS dilation / force passes: 8 bonds per step, the body is
 * kernels/opt/bond_simd.h (method, contract and equality with the reference there); and the PMB
 * pass over the sliced layout, slices of 8 particles, kernels/opt/sell_simd.h. Compiled for
 * AVX-512 F/VL/DQ/BW by the target pragma below (FMA contraction stays off: PDK_KERNEL_FP_EXACT);
 * src/core/kernels.c installs these only on CPUs with AVX-512. */
#include "kernels.h"

PDK_KERNEL_FP_EXACT

#if defined(__x86_64__) && defined(__GNUC__)
#pragma GCC target("avx512f,avx512vl,avx512dq,avx512bw,avx2,fma")
#include <immintrin.h>

#define BS_W 8
#define BS_NAME(base) base##_avx512

/* rows p + 4 j[l] (32-byte aligned), transposed: c[m] lane l = p[4 j[l] + m]. Two rows per zmm,
 * unpack per 128-bit lane, then one two-source permute per component restores lane order. */
#define BS_ROW2(p, ja, jb)                                                                         \
  _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_load_pd((p) + 4 * (size_t)(ja))),              \
                     _mm256_load_pd((p) + 4 * (size_t)(jb)), 1)
#define BS_LOAD4(p, j, c)                                                                          \
  do {                                                                                             \
    const __m512d z01_ = BS_ROW2(p, (j)[0], (j)[1]), z23_ = BS_ROW2(p, (j)[2], (j)[3]);           \
    const __m512d z45_ = BS_ROW2(p, (j)[4], (j)[5]), z67_ = BS_ROW2(p, (j)[6], (j)[7]);           \
    const __m512d t0_ = _mm512_unpacklo_pd(z01_, z23_), t1_ = _mm512_unpackhi_pd(z01_, z23_);     \
    const __m512d t2_ = _mm512_unpacklo_pd(z45_, z67_), t3_ = _mm512_unpackhi_pd(z45_, z67_);     \
    const __m512i lo_ = _mm512_set_epi64(13, 9, 12, 8, 5, 1, 4, 0);                                \
    const __m512i hi_ = _mm512_set_epi64(15, 11, 14, 10, 7, 3, 6, 2);                              \
    (c)[0] = (bs_vd)_mm512_permutex2var_pd(t0_, lo_, t2_);                                         \
    (c)[1] = (bs_vd)_mm512_permutex2var_pd(t1_, lo_, t3_);                                         \
    (c)[2] = (bs_vd)_mm512_permutex2var_pd(t0_, hi_, t2_);                                         \
    (c)[3] = (bs_vd)_mm512_permutex2var_pd(t1_, hi_, t3_);                                         \
  } while (0)
#define BS_SQRT(v) ((bs_vd)_mm512_sqrt_pd((__m512d)(v)))
#define BS_SET1(a) ((bs_vd)_mm512_set1_pd(a))
#define BS_MIN(a, b) ((bs_vd)_mm512_min_pd((__m512d)(a), (__m512d)(b)))
#define BS_GATHER(p, j)                                                                            \
  ((bs_vd)_mm512_i32gather_pd(_mm256_load_si256((const __m256i *)(const void *)(j)), (p), 8))
#define BS_CVT_F(p) ((bs_vd)_mm512_cvtps_pd(_mm256_loadu_ps(p)))

#include "opt/bond_simd.h"
#include "opt/sell_simd.h"
#endif
