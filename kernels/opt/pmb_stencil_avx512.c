/* PMB force and LPS dilation / force passes on the lattice (stencil layout) for AVX-512 CPUs (8
 * sites per vector): the bodies are kernels/opt/pmb_stencil.h and lps_stencil.h. FMA contraction
 * stays off (PDK_KERNEL_FP_EXACT); src/core/kernels.c installs it only on CPUs with AVX-512. */
#include <math.h>

#include "kernels.h"

PDK_KERNEL_FP_EXACT

#if defined(__x86_64__) && defined(__GNUC__)
#pragma GCC target("avx512f,avx512vl,avx512dq,avx512bw,avx2,fma")
#include <immintrin.h>
#define SC_W 8
#define SC_U 2
#define SC_SQRT(v) ((sc_vd)_mm512_sqrt_pd((__m512d)(v)))
#define SC_MIN(a, b) ((sc_vd)_mm512_min_pd((__m512d)(a), (__m512d)(b)))
#define SC_NAME(base) base##_avx512
#include "opt/pmb_stencil.h"
#include "opt/lps_stencil.h"
#else /* never installed without the ISA; keep the symbol defined */
pdk_bond_index pdk_kernel_pmb_stencil_avx512(const pdk_pmb_consts *k,
                                            const pdk_stencil_arrays *a, int64_t r0, int64_t r1) {
  return pdk_kernel_pmb_stencil_base(k, a, r0, r1);
}
void pdk_kernel_lps_stencil_dilation_avx512(const pdk_lps_consts *k, const pdk_stencil_arrays *a,
                                          int64_t r0, int64_t r1) {
  pdk_kernel_lps_stencil_dilation_base(k, a, r0, r1);
}
pdk_bond_index pdk_kernel_lps_stencil_force_avx512(const pdk_lps_consts *k, const pdk_stencil_arrays *a,
                                             int64_t r0, int64_t r1) {
  return pdk_kernel_lps_stencil_force_base(k, a, r0, r1);
}
#endif
