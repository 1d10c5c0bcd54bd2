/* The kernel-variant table: filled once per context from the CPU's features or the user's forced
 * choice (PDK_KERNELS=ref|simd). Drivers call through the table and never branch on variants. */
#include <string.h>

#include "kernels.h"
#include "pdk_impl.h"

static void fill_ref(pdk_kernel_table *t) {
  t->name = "ref";
  t->family_scan2 = pdk_kernel_family_scan2_ref;
  t->family_scan3 = pdk_kernel_family_scan3_ref;
}

static void fill_simd(pdk_kernel_table *t, unsigned isa) {
  fill_ref(t); /* every kind starts from its reference; optimized variants override below */
  t->name = "simd";
  /* Family candidate scan: AVX-512 (16 candidates per step, vpcompressd) over AVX2 (4 per step,
   * shuffle table); both reproduce the reference exactly. */
  if (isa & PDK_ISA_AVX2) {
    t->family_scan2 = pdk_kernel_family_scan2_avx2;
    t->family_scan3 = pdk_kernel_family_scan3_avx2;
  }
  if (isa & PDK_ISA_AVX512) {
    t->family_scan2 = pdk_kernel_family_scan2_avx512;
    t->family_scan3 = pdk_kernel_family_scan3_avx512;
  }
}

int pdk_kernels_select(const char *name, unsigned isa, pdk_kernel_table *out) {
  memset(out, 0, sizeof *out);
  if (!name || !strcmp(name, "simd") || !strcmp(name, "auto")) {
    fill_simd(out, isa);
    return PDK_SUCCESS;
  }
  if (!strcmp(name, "ref")) {
    fill_ref(out);
    return PDK_SUCCESS;
  }
  return PDK_ERR_ARG;
}
