/* Private to libpdk: the sliced family layout (SELL-C-sigma) of the PMB force pass, built from the
 * CSR families (model layout sell, include/pdk/model.h).
 *
 * Rows and slices. The n particles become rows; rows are grouped in slices of C consecutive rows
 * (C = the kernel table's sell_width: the SIMD lanes), the last slice filled up with padding rows
 * r >= n. Row order: the store's order (Morton order, when the caller sorted the store), except
 * that inside each window of sigma consecutive rows (windows start at multiples of sigma, sigma a
 * multiple of C) the rows are sorted by descending family length (ties: ascending particle index),
 * so the rows of a slice have nearly equal lengths and little padding, while a row never leaves its
 * window, which keeps the neighbour data of a slice as local as Morton order made it. sigma = C
 * sorts nothing (a slice is sorted or not, the padding is the same).
 *
 * Entries. Slice s holds len_s = max over its rows of the family length columns, stored
 * column-major: entry slice_start[s] + col C + l is bond col of row s C + l (the CSR bond
 * bond_start[i] + col of its particle i), or padding when col is past that family's end: padding
 * points at the particle itself and is flagged broken (kernels/kernels.h, pdk_sell_arrays).
 *
 * Bond state. alive [num_entries] mirrors the CSR bond state entry for entry (padding 0): built
 * from it, refreshed from it by pdk_sell_sync_alive (after something else wrote the CSR state, as a
 * checkpoint restore), and kept equal to it by the kernels, which clear a breaking bond in both.
 *
 * Memory: per entry 4 B (neighbour) + 1 B (state, when bonds can break) + 4 B (float storage);
 * 8 B per row, 8 B per slice.
 */
#ifndef PDK_SELL_H
#define PDK_SELL_H

#include "kernels.h"
#include "pdk/families.h"
#include "core/pdk_impl.h"
#include "pdk/ctx.h"

/* Default sorting window, in slices: sigma = PDK_SELL_SIGMA_SLICES C rows. */
#define PDK_SELL_SIGMA_SLICES 32

typedef struct pdk_sell {
  pdk_sell_arrays a; /* the kernels' view of the arrays below */
  int sigma;         /* sorting window [rows] */
  int64_t num_slices;
  int64_t num_entries; /* stored entries, padding included */
  pdk_bond_index num_bonds;
  pdk_index *row_i;     /* [num_slices C] */
  int64_t *slice_start; /* [num_slices + 1] */
  pdk_index *sj;        /* [num_entries] */
  uint8_t *alive;       /* [num_entries] or NULL */
  float *r0;            /* [num_entries] or NULL */
} pdk_sell;

/* Builds the layout of fam for width C (1..16) and window sigma rows (0: PDK_SELL_SIGMA_SLICES C;
 * rounded up to a multiple of C). csr_alive [num_bonds] (NULL: no bond state) and csr_r0
 * [num_bonds] (NULL: double, lengths from X) are copied into the layout's order. Threads: the
 * context's, every result independent of their number. Errors: bad width (PDK_ERR_ARG), memory
 * (PDK_ERR_MEMORY, naming the bytes). */
int pdk_sell_build(pdk_ctx *ctx, const pdk_families *fam, int width, int sigma,
                   const uint8_t *csr_alive, const float *csr_r0, pdk_sell *out);
void pdk_sell_free(pdk_sell *s);
/* alive from the CSR state csr_alive [num_bonds] (padding stays 0). */
void pdk_sell_sync_alive(pdk_ctx *ctx, pdk_sell *s, const pdk_families *fam,
                         const uint8_t *csr_alive);
/* The fraction of stored entries that are padding: (num_entries - num_bonds) / num_entries (0 when
 * there are no entries). */
double pdk_sell_padding_fraction(const pdk_sell *s);

#endif
