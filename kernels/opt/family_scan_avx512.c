/* AVX-512 family candidate scan.
 *
 * Formula and contract: those of kernels/ref/family_scan.c (see kernels.h). For each candidate k,
 *   dx = cx[k] - xi, dy = cy[k] - yi, dz = cz[k] - zi,  r2 = (dx*dx + dy*dy) + dz*dz  (no FMA)
 * and cand_id[k] is appended to out[] when r2 <= r2max and cand_id[k] != self, in candidate order.
 * The result equals the reference's exactly: same operations, same rounding, same order.
 *
 * Method: 16 candidates per step as two 8-lane double blocks; the two comparison masks form one
 * 16-bit mask that compresses the 16 ids (one zmm of int32) into the low lanes of a register
 * (vpcompressd, register form: the memory form is microcoded and slow on AMD Zen), which is stored
 * whole at out + count; count advances by the mask's popcount. The tail uses masked loads, so no
 * candidate array is read past its end. out needs n_cand + PDK_SCAN_OUT_PAD entries of room.
 * Compiled for AVX-512 through target attributes: the baseline build runs on any x86-64, and the
 * table in src/core/kernels.c installs these only when the CPU has AVX-512. */
#include "kernels.h"

PDK_KERNEL_FP_EXACT

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

#define PDK_AVX512_TARGET __attribute__((target("avx512f,avx512vl,avx512dq,avx512bw,popcnt")))

PDK_AVX512_TARGET
pdk_index pdk_kernel_family_scan2_avx512(pdk_index n_cand, const double *restrict cx,
                                         const double *restrict cy, double xi, double yi,
                                         double r2max, pdk_index self,
                                         const pdk_index *restrict cand_id,
                                         pdk_index *restrict out) {
  const __m512d vxi = _mm512_set1_pd(xi), vyi = _mm512_set1_pd(yi);
  const __m512d vr2 = _mm512_set1_pd(r2max);
  const __m512i vself = _mm512_set1_epi32(self);
  pdk_index count = 0, k = 0;
  for (; k + 16 <= n_cand; k += 16) {
    __m512d dx0 = _mm512_sub_pd(_mm512_loadu_pd(cx + k), vxi);
    __m512d dy0 = _mm512_sub_pd(_mm512_loadu_pd(cy + k), vyi);
    __m512d dx1 = _mm512_sub_pd(_mm512_loadu_pd(cx + k + 8), vxi);
    __m512d dy1 = _mm512_sub_pd(_mm512_loadu_pd(cy + k + 8), vyi);
    __m512d r20 = _mm512_add_pd(_mm512_mul_pd(dx0, dx0), _mm512_mul_pd(dy0, dy0));
    __m512d r21 = _mm512_add_pd(_mm512_mul_pd(dx1, dx1), _mm512_mul_pd(dy1, dy1));
    __mmask16 m = (__mmask16)(_mm512_cmp_pd_mask(r20, vr2, _CMP_LE_OQ) |
                              ((unsigned)_mm512_cmp_pd_mask(r21, vr2, _CMP_LE_OQ) << 8));
    __m512i ids = _mm512_loadu_si512((const void *)(cand_id + k));
    m = _mm512_mask_cmpneq_epi32_mask(m, ids, vself);
    _mm512_storeu_si512((void *)(out + count), _mm512_maskz_compress_epi32(m, ids));
    count += __builtin_popcount((unsigned)m);
  }
  if (k < n_cand) {
    const unsigned rest = (unsigned)(n_cand - k); /* 1..15 */
    const __mmask16 live = (__mmask16)((1u << rest) - 1u);
    const __mmask8 live0 = (__mmask8)(live & 0xffu), live1 = (__mmask8)(live >> 8);
    __m512d dx0 = _mm512_sub_pd(_mm512_maskz_loadu_pd(live0, cx + k), vxi);
    __m512d dy0 = _mm512_sub_pd(_mm512_maskz_loadu_pd(live0, cy + k), vyi);
    __m512d dx1 = _mm512_sub_pd(_mm512_maskz_loadu_pd(live1, cx + k + 8), vxi);
    __m512d dy1 = _mm512_sub_pd(_mm512_maskz_loadu_pd(live1, cy + k + 8), vyi);
    __m512d r20 = _mm512_add_pd(_mm512_mul_pd(dx0, dx0), _mm512_mul_pd(dy0, dy0));
    __m512d r21 = _mm512_add_pd(_mm512_mul_pd(dx1, dx1), _mm512_mul_pd(dy1, dy1));
    __mmask16 m =
        (__mmask16)(_mm512_mask_cmp_pd_mask(live0, r20, vr2, _CMP_LE_OQ) |
                    ((unsigned)_mm512_mask_cmp_pd_mask(live1, r21, vr2, _CMP_LE_OQ) << 8));
    __m512i ids = _mm512_maskz_loadu_epi32(live, cand_id + k);
    m = _mm512_mask_cmpneq_epi32_mask(m, ids, vself);
    _mm512_storeu_si512((void *)(out + count), _mm512_maskz_compress_epi32(m, ids));
    count += __builtin_popcount((unsigned)m);
  }
  return count;
}

PDK_AVX512_TARGET
pdk_index pdk_kernel_family_scan3_avx512(pdk_index n_cand, const double *restrict cx,
                                         const double *restrict cy, const double *restrict cz,
                                         double xi, double yi, double zi, double r2max,
                                         pdk_index self, const pdk_index *restrict cand_id,
                                         pdk_index *restrict out) {
  const __m512d vxi = _mm512_set1_pd(xi), vyi = _mm512_set1_pd(yi), vzi = _mm512_set1_pd(zi);
  const __m512d vr2 = _mm512_set1_pd(r2max);
  const __m512i vself = _mm512_set1_epi32(self);
  pdk_index count = 0, k = 0;
  for (; k + 16 <= n_cand; k += 16) {
    __m512d dx0 = _mm512_sub_pd(_mm512_loadu_pd(cx + k), vxi);
    __m512d dy0 = _mm512_sub_pd(_mm512_loadu_pd(cy + k), vyi);
    __m512d dz0 = _mm512_sub_pd(_mm512_loadu_pd(cz + k), vzi);
    __m512d dx1 = _mm512_sub_pd(_mm512_loadu_pd(cx + k + 8), vxi);
    __m512d dy1 = _mm512_sub_pd(_mm512_loadu_pd(cy + k + 8), vyi);
    __m512d dz1 = _mm512_sub_pd(_mm512_loadu_pd(cz + k + 8), vzi);
    __m512d r20 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx0, dx0), _mm512_mul_pd(dy0, dy0)),
                                _mm512_mul_pd(dz0, dz0));
    __m512d r21 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx1, dx1), _mm512_mul_pd(dy1, dy1)),
                                _mm512_mul_pd(dz1, dz1));
    __mmask16 m = (__mmask16)(_mm512_cmp_pd_mask(r20, vr2, _CMP_LE_OQ) |
                              ((unsigned)_mm512_cmp_pd_mask(r21, vr2, _CMP_LE_OQ) << 8));
    __m512i ids = _mm512_loadu_si512((const void *)(cand_id + k));
    m = _mm512_mask_cmpneq_epi32_mask(m, ids, vself);
    _mm512_storeu_si512((void *)(out + count), _mm512_maskz_compress_epi32(m, ids));
    count += __builtin_popcount((unsigned)m);
  }
  if (k < n_cand) {
    const unsigned rest = (unsigned)(n_cand - k); /* 1..15 */
    const __mmask16 live = (__mmask16)((1u << rest) - 1u);
    const __mmask8 live0 = (__mmask8)(live & 0xffu), live1 = (__mmask8)(live >> 8);
    __m512d dx0 = _mm512_sub_pd(_mm512_maskz_loadu_pd(live0, cx + k), vxi);
    __m512d dy0 = _mm512_sub_pd(_mm512_maskz_loadu_pd(live0, cy + k), vyi);
    __m512d dz0 = _mm512_sub_pd(_mm512_maskz_loadu_pd(live0, cz + k), vzi);
    __m512d dx1 = _mm512_sub_pd(_mm512_maskz_loadu_pd(live1, cx + k + 8), vxi);
    __m512d dy1 = _mm512_sub_pd(_mm512_maskz_loadu_pd(live1, cy + k + 8), vyi);
    __m512d dz1 = _mm512_sub_pd(_mm512_maskz_loadu_pd(live1, cz + k + 8), vzi);
    __m512d r20 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx0, dx0), _mm512_mul_pd(dy0, dy0)),
                                _mm512_mul_pd(dz0, dz0));
    __m512d r21 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx1, dx1), _mm512_mul_pd(dy1, dy1)),
                                _mm512_mul_pd(dz1, dz1));
    __mmask16 m =
        (__mmask16)(_mm512_mask_cmp_pd_mask(live0, r20, vr2, _CMP_LE_OQ) |
                    ((unsigned)_mm512_mask_cmp_pd_mask(live1, r21, vr2, _CMP_LE_OQ) << 8));
    __m512i ids = _mm512_maskz_loadu_epi32(live, cand_id + k);
    m = _mm512_mask_cmpneq_epi32_mask(m, ids, vself);
    _mm512_storeu_si512((void *)(out + count), _mm512_maskz_compress_epi32(m, ids));
    count += __builtin_popcount((unsigned)m);
  }
  return count;
}

#else /* not x86-64 GCC/Clang: never installed (no PDK_ISA_AVX512); keep the symbols defined */

pdk_index pdk_kernel_family_scan2_avx512(pdk_index n_cand, const double *restrict cx,
                                         const double *restrict cy, double xi, double yi,
                                         double r2max, pdk_index self,
                                         const pdk_index *restrict cand_id,
                                         pdk_index *restrict out) {
  return pdk_kernel_family_scan2_ref(n_cand, cx, cy, xi, yi, r2max, self, cand_id, out);
}

pdk_index pdk_kernel_family_scan3_avx512(pdk_index n_cand, const double *restrict cx,
                                         const double *restrict cy, const double *restrict cz,
                                         double xi, double yi, double zi, double r2max,
                                         pdk_index self, const pdk_index *restrict cand_id,
                                         pdk_index *restrict out) {
  return pdk_kernel_family_scan3_ref(n_cand, cx, cy, cz, xi, yi, zi, r2max, self, cand_id, out);
}
#endif
