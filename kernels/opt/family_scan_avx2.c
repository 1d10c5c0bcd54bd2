/* AVX2 family candidate scan.
 *
 * Formula and contract: those of kernels/ref/family_scan.c (see kernels.h). For each candidate k,
 *   dx = cx[k] - xi, dy = cy[k] - yi, dz = cz[k] - zi,  r2 = (dx*dx + dy*dy) + dz*dz  (no FMA)
 * and cand_id[k] is appended to out[] when r2 <= r2max and cand_id[k] != self, in candidate order.
 * The result equals the reference's exactly: same operations, same rounding, same order.
 *
 * Method: 4 candidates per step (one ymm of doubles). The 4-bit acceptance mask picks a row of a
 * 16 x 16 byte-shuffle table that moves the accepted int32 ids to the low lanes of an xmm, which is
 * stored whole at out + count; count advances by the mask's popcount. The tail (< 4 candidates) is
 * the scalar formula. out needs n_cand + PDK_SCAN_OUT_PAD entries of room. Compiled for AVX2
 * through target attributes; src/core/kernels.c installs these only when the CPU has AVX2. */
#include <stdint.h>

#include "kernels.h"

PDK_KERNEL_FP_EXACT

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

#define PDK_AVX2_TARGET __attribute__((target("avx2,popcnt")))

/* compact_lut[m]: pshufb control moving the int32 lanes l with bit l of m set to the front, in
 * lane order; the remaining bytes are zeroed (control byte 0x80). */
#define Z 0x80
static const uint8_t compact_lut[16][16] = {
    {Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z},
    {0, 1, 2, 3, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z},
    {4, 5, 6, 7, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z},
    {0, 1, 2, 3, 4, 5, 6, 7, Z, Z, Z, Z, Z, Z, Z, Z},
    {8, 9, 10, 11, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z},
    {0, 1, 2, 3, 8, 9, 10, 11, Z, Z, Z, Z, Z, Z, Z, Z},
    {4, 5, 6, 7, 8, 9, 10, 11, Z, Z, Z, Z, Z, Z, Z, Z},
    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, Z, Z, Z, Z},
    {12, 13, 14, 15, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z, Z},
    {0, 1, 2, 3, 12, 13, 14, 15, Z, Z, Z, Z, Z, Z, Z, Z},
    {4, 5, 6, 7, 12, 13, 14, 15, Z, Z, Z, Z, Z, Z, Z, Z},
    {0, 1, 2, 3, 4, 5, 6, 7, 12, 13, 14, 15, Z, Z, Z, Z},
    {8, 9, 10, 11, 12, 13, 14, 15, Z, Z, Z, Z, Z, Z, Z, Z},
    {0, 1, 2, 3, 8, 9, 10, 11, 12, 13, 14, 15, Z, Z, Z, Z},
    {4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, Z, Z, Z, Z},
    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15},
};
#undef Z

/* Appends the ids of the 4 lanes of `ids` whose bit is set in `m` (4 bits) at out + count. */
PDK_AVX2_TARGET
static inline pdk_index compact4(__m128i ids, int m, pdk_index count, pdk_index *restrict out) {
  __m128i ctl = _mm_loadu_si128((const __m128i *)compact_lut[m]);
  _mm_storeu_si128((__m128i *)(out + count), _mm_shuffle_epi8(ids, ctl));
  return count + __builtin_popcount((unsigned)m);
}

PDK_AVX2_TARGET
pdk_index pdk_kernel_family_scan2_avx2(pdk_index n_cand, const double *restrict cx,
                                       const double *restrict cy, double xi, double yi,
                                       double r2max, pdk_index self,
                                       const pdk_index *restrict cand_id, pdk_index *restrict out) {
  const __m256d vxi = _mm256_set1_pd(xi), vyi = _mm256_set1_pd(yi);
  const __m256d vr2 = _mm256_set1_pd(r2max);
  const __m128i vself = _mm_set1_epi32(self);
  pdk_index count = 0, k = 0;
  for (; k + 4 <= n_cand; k += 4) {
    __m256d dx = _mm256_sub_pd(_mm256_loadu_pd(cx + k), vxi);
    __m256d dy = _mm256_sub_pd(_mm256_loadu_pd(cy + k), vyi);
    __m256d r2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
    int m = _mm256_movemask_pd(_mm256_cmp_pd(r2, vr2, _CMP_LE_OQ));
    __m128i ids = _mm_loadu_si128((const __m128i *)(cand_id + k));
    m &= ~_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(ids, vself)));
    count = compact4(ids, m & 0xf, count, out);
  }
  for (; k < n_cand; ++k) {
    double dx = cx[k] - xi, dy = cy[k] - yi;
    double r2 = dx * dx + dy * dy;
    if (r2 <= r2max && cand_id[k] != self) out[count++] = cand_id[k];
  }
  return count;
}

PDK_AVX2_TARGET
pdk_index pdk_kernel_family_scan3_avx2(pdk_index n_cand, const double *restrict cx,
                                       const double *restrict cy, const double *restrict cz,
                                       double xi, double yi, double zi, double r2max,
                                       pdk_index self, const pdk_index *restrict cand_id,
                                       pdk_index *restrict out) {
  const __m256d vxi = _mm256_set1_pd(xi), vyi = _mm256_set1_pd(yi), vzi = _mm256_set1_pd(zi);
  const __m256d vr2 = _mm256_set1_pd(r2max);
  const __m128i vself = _mm_set1_epi32(self);
  pdk_index count = 0, k = 0;
  for (; k + 4 <= n_cand; k += 4) {
    __m256d dx = _mm256_sub_pd(_mm256_loadu_pd(cx + k), vxi);
    __m256d dy = _mm256_sub_pd(_mm256_loadu_pd(cy + k), vyi);
    __m256d dz = _mm256_sub_pd(_mm256_loadu_pd(cz + k), vzi);
    __m256d r2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)),
                               _mm256_mul_pd(dz, dz));
    int m = _mm256_movemask_pd(_mm256_cmp_pd(r2, vr2, _CMP_LE_OQ));
    __m128i ids = _mm_loadu_si128((const __m128i *)(cand_id + k));
    m &= ~_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(ids, vself)));
    count = compact4(ids, m & 0xf, count, out);
  }
  for (; k < n_cand; ++k) {
    double dx = cx[k] - xi, dy = cy[k] - yi, dz = cz[k] - zi;
    double r2 = dx * dx + dy * dy + dz * dz;
    if (r2 <= r2max && cand_id[k] != self) out[count++] = cand_id[k];
  }
  return count;
}

#else /* not x86-64 GCC/Clang: never installed (no PDK_ISA_AVX2); keep the symbols defined */

pdk_index pdk_kernel_family_scan2_avx2(pdk_index n_cand, const double *restrict cx,
                                       const double *restrict cy, double xi, double yi,
                                       double r2max, pdk_index self,
                                       const pdk_index *restrict cand_id, pdk_index *restrict out) {
  return pdk_kernel_family_scan2_ref(n_cand, cx, cy, xi, yi, r2max, self, cand_id, out);
}

pdk_index pdk_kernel_family_scan3_avx2(pdk_index n_cand, const double *restrict cx,
                                       const double *restrict cy, const double *restrict cz,
                                       double xi, double yi, double zi, double r2max,
                                       pdk_index self, const pdk_index *restrict cand_id,
                                       pdk_index *restrict out) {
  return pdk_kernel_family_scan3_ref(n_cand, cx, cy, cz, xi, yi, zi, r2max, self, cand_id, out);
}
#endif
