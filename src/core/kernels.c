/* The kernel-variant table: filled once per context from the CPU's features or the user's forced
 * choice (PDK_KERNELS=ref|simd, or avx2|avx512: simd limited to that ISA). Drivers call through
 * the table and never branch on variants. */
#include <string.h>

#include "kernels.h"
#include "pdk_impl.h"
#include "pdk/ctx.h"
#include "pdk/model.h"

/* The drivers copy pdk_stabilization (pdk/model.h) into pdk_corr_consts; the kernels read it as
 * the values of kernels/kernel_types.h (each law's file, src/law_*.c, checks its pdk_law value). */
_Static_assert(PDK_KERNEL_STAB_NONE == (int)PDK_STAB_NONE, "stabilization values");
_Static_assert(PDK_KERNEL_STAB_SILLING == (int)PDK_STAB_SILLING, "stabilization values");
_Static_assert(PDK_KERNEL_STAB_HOURGLASS == (int)PDK_STAB_HOURGLASS, "stabilization values");

static void fill_ref(pdk_kernel_table *t) {
  t->name = "ref";
  t->family_scan2 = pdk_kernel_family_scan2_ref;
  t->family_scan3 = pdk_kernel_family_scan3_ref;
  t->corr_shape = pdk_kernel_corr_shape_ref;
  t->corr_pass1 = pdk_kernel_corr_pass1_ref;
  t->corr_pass2 = pdk_kernel_corr_pass2_ref;
  t->corr_opt = 0;
  t->bond_rows = 0;
  t->pmb_force = pdk_kernel_pmb_force_ref;
  t->lps_dilation = pdk_kernel_lps_dilation_ref;
  t->lps_force = pdk_kernel_lps_force_ref;
  t->sell_width = 8;
  t->pmb_force_sell = pdk_kernel_pmb_force_sell_ref;
  t->lps_dilation_sell = pdk_kernel_lps_dilation_sell_ref;
  t->lps_force_sell = pdk_kernel_lps_force_sell_ref;
  /* The stencil pass has no reference of its own (its oracle is the general path, tests/t160);
   * the ref family runs it compiled for the baseline ISA. */
  t->pmb_stencil = pdk_kernel_pmb_stencil_base;
  t->lps_stencil_dilation = pdk_kernel_lps_stencil_dilation_base;
  t->lps_stencil_force = pdk_kernel_lps_stencil_force_base;
  t->corr_stencil_pass1 = pdk_kernel_corr_stencil_pass1_base;
  t->corr_stencil_pass2 = pdk_kernel_corr_stencil_pass2_base;
  t->galerkin_shape = pdk_kernel_galerkin_shape_ref;
  t->galerkin_psi = pdk_kernel_galerkin_psi_ref;
  t->galerkin_pass1 = pdk_kernel_galerkin_pass1_ref;
  t->galerkin_pass2 = pdk_kernel_galerkin_pass2_ref;
}

static void fill_simd(pdk_kernel_table *t, unsigned isa) {
  fill_ref(t); /* every kind starts from its reference; optimized variants override below */
  t->name = "simd";
  /* Family candidate scan: AVX-512 (16 candidates per step, vpcompressd) over AVX2 (4 per step,
   * shuffle table); both reproduce the reference exactly. */
  if (isa & PDK_ISA_AVX2) {
    t->family_scan2 = pdk_kernel_family_scan2_avx2;
    t->family_scan3 = pdk_kernel_family_scan3_avx2;
    t->corr_shape = pdk_kernel_corr_shape_avx2;
    t->corr_pass1 = pdk_kernel_corr_pass1_avx2;
    t->corr_pass2 = pdk_kernel_corr_pass2_avx2;
    t->corr_opt = 1;
  }
  if (isa & PDK_ISA_AVX512) {
    t->family_scan2 = pdk_kernel_family_scan2_avx512;
    t->family_scan3 = pdk_kernel_family_scan3_avx512;
    t->corr_shape = pdk_kernel_corr_shape_avx512;
    t->corr_pass1 = pdk_kernel_corr_pass1_avx512;
    t->corr_pass2 = pdk_kernel_corr_pass2_avx512;
  }
  /* PMB and LPS passes over packed rows (kernels/opt/bond_simd.h): each bond's terms equal the
   * reference's bit for bit, the family sums are taken in another order. */
  if (isa & PDK_ISA_AVX2) {
    t->bond_rows = 1;
    t->pmb_force = pdk_kernel_pmb_force_avx2;
    t->lps_dilation = pdk_kernel_lps_dilation_avx2;
    t->lps_force = pdk_kernel_lps_force_avx2;
    t->sell_width = 4;
    t->pmb_force_sell = pdk_kernel_pmb_force_sell_avx2;
    t->lps_dilation_sell = pdk_kernel_lps_dilation_sell_avx2;
    t->lps_force_sell = pdk_kernel_lps_force_sell_avx2;
    t->pmb_stencil = pdk_kernel_pmb_stencil_avx2;
    t->lps_stencil_dilation = pdk_kernel_lps_stencil_dilation_avx2;
    t->lps_stencil_force = pdk_kernel_lps_stencil_force_avx2;
    t->corr_stencil_pass1 = pdk_kernel_corr_stencil_pass1_avx2;
    t->corr_stencil_pass2 = pdk_kernel_corr_stencil_pass2_avx2;
  }
  if (isa & PDK_ISA_AVX512) {
    t->pmb_force = pdk_kernel_pmb_force_avx512;
    t->lps_dilation = pdk_kernel_lps_dilation_avx512;
    t->lps_force = pdk_kernel_lps_force_avx512;
    t->sell_width = 8;
    t->pmb_force_sell = pdk_kernel_pmb_force_sell_avx512;
    t->lps_dilation_sell = pdk_kernel_lps_dilation_sell_avx512;
    t->lps_force_sell = pdk_kernel_lps_force_sell_avx512;
    t->pmb_stencil = pdk_kernel_pmb_stencil_avx512;
    t->lps_stencil_dilation = pdk_kernel_lps_stencil_dilation_avx512;
    t->lps_stencil_force = pdk_kernel_lps_stencil_force_avx512;
    t->corr_stencil_pass1 = pdk_kernel_corr_stencil_pass1_avx512;
    t->corr_stencil_pass2 = pdk_kernel_corr_stencil_pass2_avx512;
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
  /* The simd family limited to one ISA (benchmarks and tests compare them); refused when the CPU
   * lacks it. */
  if (!strcmp(name, "avx2") && (isa & PDK_ISA_AVX2)) {
    fill_simd(out, PDK_ISA_AVX2);
    out->name = "avx2";
    return PDK_SUCCESS;
  }
  if (!strcmp(name, "avx512") && (isa & PDK_ISA_AVX512)) {
    fill_simd(out, isa & (PDK_ISA_AVX2 | PDK_ISA_AVX512));
    out->name = "avx512";
    return PDK_SUCCESS;
  }
  return PDK_ERR_ARG;
}
