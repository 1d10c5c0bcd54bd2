/* Kernel prototypes. A kernel is a pure function: restrict pointers and counts in, results out;
 * no allocation, no error paths, no OpenMP region. kernels/ref/ holds the readable oracle of each;
 * kernels/opt/ holds the variants that src/kernels.c puts in the table. */
#ifndef PDK_KERNELS_H
#define PDK_KERNELS_H

#include "pdk/ctx.h"

/* Family candidate scan.
 *   Appends to out[] the ids cand_id[k] of the candidates k in 0..n_cand-1 whose squared distance
 *   to (xi, yi[, zi]) is <= r2max, except the particle `self`; returns how many it appended.
 *   cx, cy, cz: [n_cand] candidate coordinates (cell-sorted copies).
 *   out must have room for n_cand entries (a variant may write, but not count, past the result). */
pdk_index pdk_kernel_family_scan2_ref(pdk_index n_cand, const double *restrict cx,
                                      const double *restrict cy, double xi, double yi,
                                      double r2max, pdk_index self,
                                      const pdk_index *restrict cand_id, pdk_index *restrict out);
pdk_index pdk_kernel_family_scan3_ref(pdk_index n_cand, const double *restrict cx,
                                      const double *restrict cy, const double *restrict cz,
                                      double xi, double yi, double zi, double r2max,
                                      pdk_index self, const pdk_index *restrict cand_id,
                                      pdk_index *restrict out);

#endif
