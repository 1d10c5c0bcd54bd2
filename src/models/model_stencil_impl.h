/* Private to the stencil layout (model_stencil.c, model_stencil_corr.c): its insides and the
 * pieces both files use. */
#ifndef PDK_MODEL_STENCIL_IMPL_H
#define PDK_MODEL_STENCIL_IMPL_H

#include "model_stencil.h"
#include "pdk/ctx.h"
#include "pdk/model.h"

#define STENCIL_POS_TOL 1e-6 /* lattice test: |X - (origin + k h)| <= tol h per axis */
#define STENCIL_MAX_REACH 64 /* largest bond offset component, in spacings */

struct pdk_stencil {
  int dim;
  pdk_index n;
  int pad;            /* P: largest offset component */
  int64_t nx, ny, nz; /* padded grid (nz = 1 in 2-D) */
  int num_offsets;
  int64_t *offset; /* [num_offsets] ascending */
  int64_t num_sites, num_rows;
  int64_t *row_lo, *row_hi; /* [num_rows] */
  int64_t tile;             /* rows per tile along y (3-D), see stencil_rows */
  pdk_index *site_particle; /* [num_sites] */
  int64_t *particle_site;   /* [n] */
  int64_t lut_min;          /* lut[d - lut_min]: offset index of site offset d, or -1 */
  int16_t *lut;             /* [lut_len] */
  int64_t lut_len;
  double *X[3], *x[3], *volume; /* [num_sites] */
  double *s0;                   /* [num_sites] when bonds can break */
  double *r0_off, *beta_off;    /* [num_offsets] float storage */
  uint8_t *mask;                /* [num_offsets * num_sites] or NULL */
  uint8_t *changed;             /* [num_sites] when bonds can break */
  unsigned long version;        /* m->bond_state_version the mask holds */
  double *inv_m, *theta;        /* LPS [num_sites + slack]: 1/m, dilation (0 at empty sites) */
  /* correspondence: xi and omega per offset [num_offsets]; per site [num_sites + slack] B (d*d
   * arrays), its float copy (float storage) and k; x then holds the displacements */
  double *xi_off[3], *wxi_off[3], *omega_off;
  double *cs[3]; /* [num_sites + slack] sum of omega V_j xi over the intact bonds */
  double *cB[9], *ck;
  float *cBf[9];
  /* correspondence: one block of the pass-2 site arrays, component c at cblk + c * cstride
   * (u_0 .. u_{d-1}, V, k, B_0 .. B_{d^2-1}; x, volume, ck and cB point into it), and the float
   * copies of B at cBfblk + t * cstride; NULL before set-up */
  double *cblk;
  float *cBfblk;
  int64_t cstride;
};

/* Offset index of the bond from site si to site sj (-1: not in the list). */
static inline int pdk_stencil_offset_of(const pdk_stencil *st, int64_t si, int64_t sj) {
  const int64_t d = sj - si - st->lut_min;
  return d >= 0 && d < st->lut_len ? st->lut[d] : -1;
}

/* Correspondence: cs of particle i's site, sum over the offsets whose bond is present (mask, or
 * an occupied site without one) of omega V_j xi. */
void pdk_stencil_corr_s(pdk_stencil *st, pdk_index i);
/* mask[o][s] = bond present in the family and intact; the whole mask from m's families. */
void pdk_stencil_load_mask(pdk_model *m, pdk_stencil *st);
/* The row list, in tiles of rows along y in 3-D (model_stencil.c); -1 when out of memory. */
int pdk_stencil_make_rows(pdk_stencil *st, double site_bytes);
/* The lattice part of the kernels' arrays (dimension, offsets, sites, rows), the rest zeroed. */
void pdk_stencil_arrays_lattice(const pdk_stencil *st, pdk_stencil_arrays *arr);

#endif
