/* Private to libpdk: what the updated-Lagrangian model and checkpoints need of families beyond
 * include/pdk/families.h. */
#ifndef PDK_FAMILIES_IMPL_H
#define PDK_FAMILIES_IMPL_H

#include "pdk/families.h"
#include "core/pdk_impl.h"
#include "pdk/ctx.h"

/* The pre-cracks the families were built with (a copy owned by the families; vertices in the
 * reference coordinates "X"); returns their count, *out NULL when there are none. */
int pdk_families_precracks(const pdk_families *f, const pdk_precrack **out);

/* Removes from f every bond i-j whose closed segment X_i X_j, over the coordinates X[a] [n], meets
 * one of the pre-cracks (the rule of pdk_families_build, the same exact predicates, each bond
 * tested from its lower-index end, so i-j and j-i agree). Bonds keep their order. Errors: bad
 * pre-crack geometry (PDK_ERR_ARG), memory. Serial: bonds x pre-cracks tests, each a few exact
 * orientation signs after a bounding-box reject. */
int pdk_families_remove_cut(pdk_families *f, int dim, const double *const X[3],
                            const pdk_precrack *precracks, int num_precracks);

/* Families from CSR arrays (copied): bond_start [n+1] from 0, non-decreasing; bond_j
 * [bond_start[n]] in [0, n), no self bonds. Malformed arrays are refused (PDK_ERR_IO, naming the
 * first bad entry): they come from files. */
int pdk_families_from_csr(pdk_ctx *ctx, pdk_index n, double horizon,
                          const pdk_bond_index *bond_start, const pdk_index *bond_j,
                          pdk_families **out);

#endif
