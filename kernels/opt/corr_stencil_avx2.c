/* Correspondence passes on the lattice (stencil layout) for AVX2 + FMA CPUs: 4 sites per vector,
 * one vector per block (pass 1 keeps 11 accumulators of 4 lanes, pass 2 nine, in the 16 ymm
 * registers); the body is kernels/opt/corr_stencil.h. src/core/kernels.c installs it only on CPUs with
 * AVX2. */
#include "kernels.h"

#if defined(__x86_64__) && defined(__GNUC__)
#pragma GCC target("avx2,fma")
#define SC_W 4
#define SC_U 1
#define SC_NAME(base) base##_avx2
#include "opt/corr_stencil.h"
#else /* never installed without the ISA; keep the symbols defined */
void pdk_kernel_corr_stencil_pass1_avx2(const pdk_corr_consts *k, const pdk_corr_arrays *c,
                                        const pdk_stencil_arrays *a, int64_t r0, int64_t r1) {
  pdk_kernel_corr_stencil_pass1_base(k, c, a, r0, r1);
}
void pdk_kernel_corr_stencil_pass2_avx2(const pdk_corr_consts *k, const pdk_corr_arrays *c,
                                        const pdk_stencil_arrays *a, int64_t r0, int64_t r1) {
  pdk_kernel_corr_stencil_pass2_base(k, c, a, r0, r1);
}
#endif
