/* PMB force and LPS dilation / force passes on the lattice (stencil layout) for AVX2 + FMA CPUs (4
 * sites per vector): the bodies are kernels/opt/pmb_stencil.h and lps_stencil.h. FMA contraction
 * stays off (PDK_KERNEL_FP_EXACT); src/core/kernels.c installs it only on CPUs with AVX2. */
#include <math.h>

#include "kernels.h"

PDK_KERNEL_FP_EXACT

#if defined(__x86_64__) && defined(__GNUC__)
#pragma GCC target("avx2,fma")
#include <immintrin.h>
#define SC_W 4
#define SC_U 2
#define SC_SQRT(v) ((sc_vd)_mm256_sqrt_pd((__m256d)(v)))
#define SC_MIN(a, b) ((sc_vd)_mm256_min_pd((__m256d)(a), (__m256d)(b)))
#define SC_NAME(base) base##_avx2
#include "opt/pmb_stencil.h"
#include "opt/lps_stencil.h"
#else /* never installed without the ISA; keep the symbol defined */
pdk_bond_index pdk_kernel_pmb_stencil_avx2(const pdk_pmb_consts *k, const pdk_stencil_arrays *a,
                                          int64_t r0, int64_t r1) {
  return pdk_kernel_pmb_stencil_base(k, a, r0, r1);
}
void pdk_kernel_lps_stencil_dilation_avx2(const pdk_lps_consts *k, const pdk_stencil_arrays *a,
                                          int64_t r0, int64_t r1) {
  pdk_kernel_lps_stencil_dilation_base(k, a, r0, r1);
}
pdk_bond_index pdk_kernel_lps_stencil_force_avx2(const pdk_lps_consts *k, const pdk_stencil_arrays *a,
                                             int64_t r0, int64_t r1) {
  return pdk_kernel_lps_stencil_force_base(k, a, r0, r1);
}
#endif
