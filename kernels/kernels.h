/* Kernel prototypes. A kernel is a pure function: restrict pointers and counts in, results out;
 * no allocation, no error paths, no OpenMP region. kernels/ref/ holds the readable oracle of each;
 * kernels/opt/ holds the variants that src/kernels.c puts in the table. */
#ifndef PDK_KERNELS_H
#define PDK_KERNELS_H

#include "pdk/ctx.h"

/* Kernels whose result must match the reference bit for bit open with PDK_KERNEL_FP_EXACT: it turns
 * off floating-point contraction (a*b + c fused into one FMA), which the compiler would otherwise
 * apply to plain C and to vector intrinsics alike whenever the target has FMA, and which would
 * change the rounding of a sum of squares. */
#if defined(__clang__)
#define PDK_KERNEL_FP_EXACT _Pragma("STDC FP_CONTRACT OFF")
#elif defined(__GNUC__)
#define PDK_KERNEL_FP_EXACT _Pragma("GCC optimize(\"fp-contract=off\")")
#else
#define PDK_KERNEL_FP_EXACT
#endif

/* Family candidate scan.
 *   Appends to out[] the ids cand_id[k] of the candidates k in 0..n_cand-1 whose squared distance
 *   to (xi, yi[, zi]) is <= r2max, except the particle `self`, in candidate order; returns how many
 *   it appended.
 *   Squared distance, each operation rounded to double (no FMA), in this order:
 *     dx = cx[k] - xi, dy = cy[k] - yi, dz = cz[k] - zi;  r2 = (dx*dx + dy*dy) + dz*dz
 *   so every variant gives the same set, and r2(i, j) == r2(j, i) bit for bit.
 *   cx, cy, cz: [n_cand] candidate coordinates (cell-sorted copies); cand_id: [n_cand].
 *   out: room for n_cand + PDK_SCAN_OUT_PAD entries; a variant may write (but not count) entries
 *   past its result, up to that room. */
#define PDK_SCAN_OUT_PAD 16

pdk_index pdk_kernel_family_scan2_ref(pdk_index n_cand, const double *restrict cx,
                                      const double *restrict cy, double xi, double yi,
                                      double r2max, pdk_index self,
                                      const pdk_index *restrict cand_id, pdk_index *restrict out);
pdk_index pdk_kernel_family_scan3_ref(pdk_index n_cand, const double *restrict cx,
                                      const double *restrict cy, const double *restrict cz,
                                      double xi, double yi, double zi, double r2max,
                                      pdk_index self, const pdk_index *restrict cand_id,
                                      pdk_index *restrict out);

/* AVX2 variants (kernels/opt/family_scan_avx2.c): 4 candidates per step, compaction through a
 * byte-shuffle table. Call only when the CPU has AVX2 (PDK_ISA_AVX2). */
pdk_index pdk_kernel_family_scan2_avx2(pdk_index n_cand, const double *restrict cx,
                                       const double *restrict cy, double xi, double yi,
                                       double r2max, pdk_index self,
                                       const pdk_index *restrict cand_id, pdk_index *restrict out);
pdk_index pdk_kernel_family_scan3_avx2(pdk_index n_cand, const double *restrict cx,
                                       const double *restrict cy, const double *restrict cz,
                                       double xi, double yi, double zi, double r2max,
                                       pdk_index self, const pdk_index *restrict cand_id,
                                       pdk_index *restrict out);

/* AVX-512 variants (kernels/opt/family_scan_avx512.c): 16 candidates per step, compaction with
 * vpcompressd into a register. Call only when the CPU has AVX-512 F/VL/DQ/BW (PDK_ISA_AVX512). */
pdk_index pdk_kernel_family_scan2_avx512(pdk_index n_cand, const double *restrict cx,
                                         const double *restrict cy, double xi, double yi,
                                         double r2max, pdk_index self,
                                         const pdk_index *restrict cand_id,
                                         pdk_index *restrict out);
pdk_index pdk_kernel_family_scan3_avx512(pdk_index n_cand, const double *restrict cx,
                                         const double *restrict cy, const double *restrict cz,
                                         double xi, double yi, double zi, double r2max,
                                         pdk_index self, const pdk_index *restrict cand_id,
                                         pdk_index *restrict out);

#endif
