/* Private to the correspondence model, total and semi-total Lagrangian (model_corr.c,
 * model_corr_bonds.c): its data and the pieces both files use. */
#ifndef PDK_MODEL_CORR_IMPL_H
#define PDK_MODEL_CORR_IMPL_H

#include "kernels.h"
#include "model_impl.h"
#include "model_stencil.h"
#include "core/state.h"
#include "pdk/ctx.h"
#include "pdk/model.h"

/* Particles per block: the unit of work of both passes and of the energy reduction. A constant,
 * not the thread count, so the reduction order never depends on how many threads run. */
#define PDK_CORR_BLOCK 256

typedef struct corr_impl {
  pdk_corr_consts k;
  double *bond_omega;   /* [num_bonds] omega(|xi|) >= 0 */
  double *W;            /* [n_pad] strain energy density of the last pass */
  double *m;            /* [n_pad] weighted volume; NULL without stabilization */
  int32_t *num_alive;   /* [n] intact bonds when K^-1 was computed; NULL without failure */
  double *s0_next;      /* [n_pad] critical stretch for the next pass; NULL without s0 */
  double *block_energy; /* [num_blocks] */
  pdk_index num_blocks;
  uint8_t *changed; /* [n_pad] rows that lost bonds (bits, see kernels.h); NULL: no failure */
  uint8_t *detach;  /* [n_pad] semi-TL detach marks; NULL in TL */
  /* semi-TL compacted list of intact bonds; NULL before the first compaction */
  pdk_bond_index *c_start; /* [n+1] */
  pdk_index *c_j;          /* [c_len] */
  double *c_omega;         /* [c_len] */
  uint8_t *c_alive;        /* [c_len] */
  pdk_bond_index c_len;    /* entries in the list the passes walk (families' before compaction) */
  pdk_bond_index c_dead;   /* broken entries still in that list (counted since creation or the
                              last compaction) */
  pdk_index failed_seen;   /* failed particles when the break kernel last ran */
  /* Kernels (from the context's table at setup) and the pass-2 data they need
   * (pdk_corr_pair_layout): kst [n_pad], B, G [9][n_pad] double, Bf, Gf [9][n_pad] float. */
  pdk_index (*shape)(const pdk_corr_consts *, const pdk_corr_arrays *, pdk_index, pdk_index);
  void (*pass1)(const pdk_corr_consts *, const pdk_corr_arrays *, pdk_index, pdk_index);
  void (*pass2)(const pdk_corr_consts *, const pdk_corr_arrays *, pdk_index, pdk_index);
  double *kst, *B[9], *G[9];
  float *Bf[9], *Gf[9];
  void *pair_d, *pair_f; /* the allocations behind kst, B, G and Bf, Gf */
  /* Packed rows (layout bit 32, pdk_corr_arrays): ref4, cur4, own [4 n_pad]; row or rowf [n_pad] */
  double *ref4, *cur4, *own;
  pdk_corr_row *row;
  pdk_corr_rowf *rowf;
  /* Softened stabilization: the commit pass's scratch (kernels.h); NULL when off */
  double *stab_prev, *w_law;
} corr_impl;

/* Block range of particles [i0, i1) for block blk. */
#define CORR_BLOCK_RANGE(blk, n, i0, i1)                                                           \
  const pdk_index i0 = (blk)*PDK_CORR_BLOCK;                                                       \
  const pdk_index i1 = i0 + PDK_CORR_BLOCK < (n) ? i0 + PDK_CORR_BLOCK : (n)

/* Points the kernel arrays at the current fields. */
void pdk_corr_arrays_of(pdk_model *m, pdk_corr_arrays *a);
/* Frees the semi-TL compacted list (back to the families' CSR). */
void pdk_corr_free_compacted(corr_impl *c);
/* After the break kernel broke `broken` bonds in a commit pass (model_corr_bonds.c). */
int pdk_corr_after_breaking(pdk_model *m, const pdk_corr_consts *k, pdk_bond_index broken,
                            double *released);

#endif
