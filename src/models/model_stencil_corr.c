/* The stencil layout's correspondence passes (the layout itself: model_stencil.c). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "model_stencil_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

/* ---- correspondence ----------------------------------------------------------------------------
 * Set-up takes xi and omega per offset from the first bond of each offset and checks every other
 * bond against them (a particle off its lattice point by round-off only: |xi_b - xi_o| <=
 * STENCIL_CORR_XI_TOL h per component, |omega_b - omega_o| <= STENCIL_CORR_OMEGA_RTOL omega_o);
 * K^-1 and m stay the general path's (computed at set-up from the families). Per site: the
 * displacement in the x arrays, the pass-2 data cB, ck (and cBf with float storage). The passes
 * (pdk_stencil_corr_passes): scatter u, pass 1 over the rows, barrier, pass 2 over the rows, in
 * one parallel region. Bond breaking stays the general path's (over the families, after pass 2);
 * the driver then refreshes the mask of the rows that lost bonds (pdk_stencil_mask_rows). */
#define STENCIL_CORR_XI_TOL 1e-10
#define STENCIL_CORR_OMEGA_RTOL 1e-9

const char *pdk_stencil_corr_refusal(const pdk_model_opts *o) {
  if (o->connectivity == PDK_CONNECTIVITY_UL)
    return "correspondence with ul connectivity (its families are rebuilt in the current "
           "configuration)";
  if (o->connectivity != PDK_CONNECTIVITY_TL)
    return "correspondence with semi_tl connectivity (its bond list is compacted)";
  if (o->stabilization == PDK_STAB_HOURGLASS)
    return "correspondence with hourglass stabilization (the stencil passes implement none and "
           "silling)";
  return NULL;
}

int pdk_stencil_corr_setup(pdk_model *m, const double *bond_omega, int float_storage) {
  pdk_stencil *st = m->stencil;
  pdk_ctx *ctx = m->ctx;
  if (!st) return PDK_SUCCESS;
  const int dim = st->dim, no = st->num_offsets;
  const pdk_index n = st->n;
  const int64_t *ids = pdk_particles_id(m->p);
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const double *X[3] = {NULL, NULL, NULL};
  for (int a = 0; a < dim; ++a)
    X[a] = pdk_particles_X(m->p, a);
  /* the bond-breaking copies of the PMB pass are not used: breaking stays the general path's */
  pdk_free_aligned(st->s0);
  pdk_free_aligned(st->changed);
  st->s0 = NULL;
  st->changed = NULL;
  const size_t nof = (size_t)(no > 0 ? no : 1);
  for (int a = 0; a < dim; ++a) {
    st->xi_off[a] = malloc(nof * sizeof(double));
    PDK_CHECK(st->xi_off[a], ctx, PDK_ERR_MEMORY, "stencil: out of memory");
  }
  st->omega_off = malloc(nof * sizeof(double));
  uint8_t *seen = calloc(nof, 1);
  PDK_CHECK(st->omega_off && seen, ctx, PDK_ERR_MEMORY, "stencil: out of memory");
  char *why = m->stencil_why;
  const size_t why_len = sizeof m->stencil_why;
  int bad = 0;
  for (pdk_index i = 0; i < n && !bad; ++i)
    for (pdk_bond_index b = bs[i]; b < bs[i + 1] && !bad; ++b) {
      const pdk_index j = bj[b];
      const int o = pdk_stencil_offset_of(st, st->particle_site[i], st->particle_site[j]);
      double xi[3] = {0, 0, 0}, r2 = 0.0;
      for (int a = 0; a < dim; ++a) {
        xi[a] = X[a][j] - X[a][i];
        r2 += xi[a] * xi[a];
      }
      if (!seen[o]) {
        seen[o] = 1;
        for (int a = 0; a < dim; ++a)
          st->xi_off[a][o] = xi[a];
        st->omega_off[o] = bond_omega[b];
        continue;
      }
      const double tol = STENCIL_CORR_XI_TOL * sqrt(r2);
      for (int a = 0; a < dim; ++a)
        if (fabs(xi[a] - st->xi_off[a][o]) > tol) {
          snprintf(why, why_len,
                   "correspondence: the bond from particle id %lld to %lld differs from another "
                   "bond along the same lattice offset by %.3g along axis %c (more than %g of its "
                   "length); the correspondence stencil takes one reference bond per offset, so "
                   "particles must sit on their lattice points to round-off",
                   (long long)ids[i], (long long)ids[j], fabs(xi[a] - st->xi_off[a][o]), "xyz"[a],
                   STENCIL_CORR_XI_TOL);
          bad = 1;
          break;
        }
      if (!bad && fabs(bond_omega[b] - st->omega_off[o]) >
                      STENCIL_CORR_OMEGA_RTOL * fabs(st->omega_off[o])) {
        snprintf(why, why_len,
                 "correspondence: the influence weight of the bond from particle id %lld to %lld "
                 "(%.17g) differs from another bond along the same lattice offset (%.17g); the "
                 "correspondence stencil takes one weight per offset",
                 (long long)ids[i], (long long)ids[j], bond_omega[b], st->omega_off[o]);
        bad = 1;
      }
    }
  free(seen); /* every offset is some bond's (the offsets are the union of the families') */
  /* pass 1 takes the offsets in pairs o, no - 1 - o: the list must be symmetric, with opposite xi
   * and equal omega (families are symmetric, so it is; checked to the same tolerances) */
  for (int o = 0; o < no && !bad; ++o) {
    const int o2 = no - 1 - o;
    double r2 = 0.0, dev = 0.0;
    for (int a = 0; a < dim; ++a) {
      r2 += st->xi_off[a][o] * st->xi_off[a][o];
      dev = fmax(dev, fabs(st->xi_off[a][o] + st->xi_off[a][o2]));
    }
    if (st->offset[o2] != -st->offset[o] || dev > STENCIL_CORR_XI_TOL * sqrt(r2) ||
        fabs(st->omega_off[o] - st->omega_off[o2]) >
            STENCIL_CORR_OMEGA_RTOL * fabs(st->omega_off[o])) {
      snprintf(why, why_len,
               "correspondence: the bond offsets are not symmetric (offset %d of %d: the families "
               "are not symmetric, or xi / omega differ between a bond and its reverse)",
               o, no);
      bad = 1;
    }
  }
  if (bad) {
    pdk_stencil_destroy(&m->stencil);
    PDK_CHECK(m->opts.stencil != PDK_STENCIL_ON, ctx, PDK_ERR_UNSUPPORTED,
              "correspondence model: stencil on, but the stencil path does not apply: %s; use "
              "stencil auto (the general path then) or off",
              why);
    return PDK_SUCCESS;
  }
  const size_t ns_all = (size_t)(st->num_sites + PDK_STENCIL_SLACK);
  for (int a = 0; a < dim; ++a) {
    st->wxi_off[a] = malloc(nof * sizeof(double));
    st->cs[a] = pdk_alloc_aligned(ns_all, sizeof(double));
    PDK_CHECK(st->wxi_off[a] && st->cs[a], ctx, PDK_ERR_MEMORY, "stencil: out of memory");
    memset(st->cs[a], 0, ns_all * sizeof(double));
    for (int o = 0; o < no; ++o)
      st->wxi_off[a][o] = st->omega_off[o] * st->xi_off[a][o];
  }
  /* the pair (o, no - 1 - o) uses omega_o and -wxi_o for both: make the stored pair exact */
  for (int o = no / 2; o < no; ++o) {
    st->omega_off[o] = st->omega_off[no - 1 - o];
    for (int a = 0; a < dim; ++a)
      st->wxi_off[a][o] = -st->wxi_off[a][no - 1 - o];
  }
  for (pdk_index i = 0; i < n; ++i)
    pdk_stencil_corr_s(st, i);
  /* the pass-2 site arrays in one block with a fixed stride (a multiple of 8 doubles, so every
   * component starts 64-byte aligned): pass 2 addresses its 14 (2-D: 8) streams from one pointer.
   * The grid's x (which holds u) and volume move into it. */
  const int64_t cstr = (int64_t)((ns_all + 7) / 8 * 8);
  const int ncomp = dim + 2 + dim * dim;
  double *blk = pdk_alloc_aligned((size_t)(ncomp * cstr), sizeof(double));
  PDK_CHECK(blk, ctx, PDK_ERR_MEMORY, "stencil: out of memory for a grid of %lld sites",
            (long long)st->num_sites);
  memset(blk, 0, (size_t)(ncomp * cstr) * sizeof(double));
  memcpy(blk + dim * cstr, st->volume, ns_all * sizeof(double));
  pdk_free_aligned(st->volume);
  st->volume = blk + dim * cstr;
  for (int a = 0; a < dim; ++a) { /* x holds displacements: 0 at empty sites and in the slack */
    pdk_free_aligned(st->x[a]);
    st->x[a] = blk + a * cstr;
  }
  st->ck = blk + (dim + 1) * cstr;
  for (int t = 0; t < dim * dim; ++t)
    st->cB[t] = blk + (dim + 2 + t) * cstr;
  st->cblk = blk;
  st->cstride = cstr;
  if (float_storage) {
    st->cBfblk = pdk_alloc_aligned((size_t)(dim * dim * cstr), sizeof(float));
    PDK_CHECK(st->cBfblk, ctx, PDK_ERR_MEMORY, "stencil: out of memory");
    memset(st->cBfblk, 0, (size_t)(dim * dim * cstr) * sizeof(float));
    for (int t = 0; t < dim * dim; ++t)
      st->cBf[t] = st->cBfblk + t * cstr;
  }
  /* tiles for the pass-2 neighbour data: u, V, k and B (double, or its float copy) */
  PDK_CHECK(pdk_stencil_make_rows(st, 8.0 * (dim + 2) + (float_storage ? 4.0 : 8.0) * dim * dim) ==
                0,
            ctx, PDK_ERR_MEMORY, "stencil: out of memory");
  return PDK_SUCCESS;
}

void pdk_stencil_mask_rows(pdk_model *m, pdk_stencil *st, const uint8_t *changed) {
  if (!st || !st->mask) return;
  const pdk_bond_index *bs = pdk_families_bond_start(m->fam);
  const pdk_index *bj = pdk_families_bond_j(m->fam);
  const uint8_t *alive = m->bond_alive;
  const pdk_index n = st->n;
  const int64_t ns = st->num_sites;
  const pdk_stencil *cst = st;
  uint8_t *mask = st->mask;
#pragma omp parallel for default(none) shared(n, bs, bj, alive, cst, mask, ns, changed)            \
    schedule(static) num_threads(m->ctx->num_threads)
  for (pdk_index i = 0; i < n; ++i) {
    if (!(changed[i] & 2u)) continue;
    const int64_t si = cst->particle_site[i];
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      const int o = pdk_stencil_offset_of(cst, si, cst->particle_site[bj[b]]);
      mask[(int64_t)o * ns + si] = alive ? alive[b] : 1;
    }
    if (cst->cs[0]) pdk_stencil_corr_s((pdk_stencil *)cst, i);
  }
}

int pdk_stencil_corr_passes(pdk_model *m, pdk_stencil *st, const pdk_corr_consts *k,
                            const pdk_corr_arrays *c) {
  pdk_ctx *ctx = m->ctx;
  const int dim = st->dim;
  PDK_CHECK(st->ck && st->omega_off, ctx, PDK_ERR_ARG,
            "stencil: the correspondence arrays were not set up");
  if (st->mask && st->version != m->bond_state_version) pdk_stencil_load_mask(m, st);
  pdk_stencil_arrays arr;
  pdk_stencil_arrays_lattice(st, &arr);
  arr.volume = st->volume;
  arr.mask = st->mask;
  for (int a = 0; a < dim; ++a) {
    arr.u[a] = st->x[a];
    arr.wxi_off[a] = st->wxi_off[a];
    arr.cs[a] = st->cs[a];
  }
  arr.omega_off = st->omega_off;
  for (int t = 0; t < dim * dim; ++t) {
    arr.cB[t] = st->cB[t];
    arr.cBf[t] = st->cBf[t];
  }
  arr.ck = st->ck;
  arr.cbase = st->cblk;
  arr.cbase_f = st->cBfblk;
  arr.cstride = st->cstride;
  const pdk_stencil_arrays *a = &arr;
  const pdk_stencil *cst = st;
  const pdk_corr_stencil_fn pass1 = ctx->kernels.corr_stencil_pass1;
  const pdk_corr_stencil_fn pass2 = ctx->kernels.corr_stencil_pass2;
  const pdk_index n = st->n;
  const int64_t num_rows = st->num_rows;
  double *gu[3] = {st->x[0], st->x[1], dim == 3 ? st->x[2] : NULL};
#pragma omp parallel default(none) num_threads(ctx->num_threads)                                   \
    shared(n, cst, c, gu, dim, num_rows, pass1, pass2, k, a)
  {
#pragma omp for schedule(static)
    for (pdk_index i = 0; i < n; ++i) {
      const int64_t s = cst->particle_site[i];
      for (int d = 0; d < dim; ++d)
        gu[d][s] = c->x[d][i] - c->X[d][i];
    }
    /* implicit barrier: every site's u is in place before a neighbour reads it */
#pragma omp for schedule(static)
    for (int64_t r = 0; r < num_rows; ++r)
      pass1(k, c, a, r, r + 1);
      /* implicit barrier: pass 2 reads the neighbours' B and k */
#pragma omp for schedule(static)
    for (int64_t r = 0; r < num_rows; ++r)
      pass2(k, c, a, r, r + 1);
  }
  return PDK_SUCCESS;
}
