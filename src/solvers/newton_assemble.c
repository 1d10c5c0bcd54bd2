/* Newton (newton.c), assembly of the tangent: by colored differences of trial forces, or the
 * model's analytic columns (the methods are described in newton.c). */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <string.h>

#include "newton_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/static.h"

/* ---- assembly ------------------------------------------------------------------------------- */

/* Writes the columns (and full-tangent diagonals) of the particles members[0..count-1], moved in
 * component d: upper = forces after the + move, lower = after the - move (central) or at the base
 * (forward). */
static void scatter(pdk_static *s, const pdk_index *members, pdk_index count, int d,
                    double *const *upper, double *const *lower, int central) {
  newton_state *ns = s->newton;
  const double *vol = pdk_particles_volume(s->p);
  const int *Ap = ns->Ap, *Ai = ns->Ai;
  double *Ax = ns->Ax;
  const pdk_index *dof_particle = ns->dof_particle;
  const uint8_t *dof_comp = ns->dof_comp;
  const int32_t *dof_d = ns->dof_of[d];
  double *diag_d = ns->diag_full[d];
  const double *hp = ns->h_plus, *hm = ns->h_minus;
  const int nt = s->ctx->num_threads;
#pragma omp parallel for default(none)                                                             \
    shared(members, count, d, upper, lower, central, vol, Ap, Ai, Ax, dof_particle, dof_comp,      \
           dof_d, diag_d, hp, hm) schedule(static) num_threads(nt)
  for (pdk_index q = 0; q < count; ++q) {
    const pdk_index i = members[q];
    const double denom = central ? hp[i] + hm[i] : hp[i];
    diag_d[i] = -vol[i] * (upper[d][i] - lower[d][i]) / denom;
    const int col = dof_d[i];
    if (col < 0) continue;
    for (int k = Ap[col]; k < Ap[col + 1]; ++k) {
      const int row = Ai[k];
      const pdk_index j = dof_particle[row];
      const int e = dof_comp[row];
      Ax[k] = -vol[j] * (upper[e][j] - lower[e][j]) / denom;
    }
  }
}

/* Difference tangent at the current x over groups of particles moved together:
 * group g holds members[group_start[g] .. group_start[g+1]-1]. x and "f" are left as they were. */
static int assemble(pdk_static *s, int num_groups, const pdk_index *group_start,
                    const pdk_index *members) {
  newton_state *ns = s->newton;
  const int dim = s->dim;
  const pdk_index n = s->n;
  const int central = s->opts.fd_scheme == PDK_FD_CENTRAL;
  const double h = s->opts.fd_step * s->horizon;
  const double t0 = pdk_wtime();
  double *f[3] = {NULL, NULL, NULL};
  double *fbase[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c)
    f[c] = pdk_newton_field(s->p, "f", c);
  /* "f" holds the forces at x (the last residual evaluation): keep them to put back */
  for (int c = 0; c < dim; ++c)
    fbase[c] = ns->x0[c]; /* x0 is free until the line search */
  for (int c = 0; c < dim; ++c)
    memcpy(fbase[c], f[c], (size_t)n * sizeof(double));
  if (!central) /* base forces at x for forward differences */
    for (int c = 0; c < dim; ++c)
      memcpy(ns->fa[c], f[c], (size_t)n * sizeof(double));
  for (int g = 0; g < num_groups; ++g) {
    const pdk_index *mem = members + group_start[g];
    const pdk_index count = group_start[g + 1] - group_start[g];
    for (int d = 0; d < dim; ++d) {
      double *x = pdk_newton_field(s->p, "x", d);
      for (pdk_index q = 0; q < count; ++q) {
        const pdk_index i = mem[q];
        ns->saved[i] = x[i];
        x[i] = ns->saved[i] + h;
        ns->h_plus[i] = x[i] - ns->saved[i];
      }
      int err = pdk_model_force_trial(s->m, NULL);
      s->stats.force_passes++;
      if (!err && central) {
        for (int c = 0; c < dim; ++c)
          memcpy(ns->fa[c], f[c], (size_t)n * sizeof(double));
        for (pdk_index q = 0; q < count; ++q) {
          const pdk_index i = mem[q];
          x[i] = ns->saved[i] - h;
          ns->h_minus[i] = ns->saved[i] - x[i];
        }
        err = pdk_model_force_trial(s->m, NULL);
        s->stats.force_passes++;
      }
      for (pdk_index q = 0; q < count; ++q)
        x[mem[q]] = ns->saved[mem[q]]; /* also on failure */
      if (err) return err;
      if (central)
        scatter(s, mem, count, d, ns->fa, f, 1);
      else
        scatter(s, mem, count, d, f, ns->fa, 0);
    }
  }
  for (int c = 0; c < dim; ++c)
    memcpy(f[c], fbase[c], (size_t)n * sizeof(double));
  double kmax = 0.0;
  for (int c = 0; c < dim; ++c)
    for (pdk_index i = 0; i < n; ++i)
      kmax = fmax(kmax, fabs(ns->diag_full[c][i]));
  ns->k_ref = kmax;
  s->stats.assemblies++;
  s->stats.time_assembly += pdk_wtime() - t0;
  return PDK_SUCCESS;
}

/* Particles held along a direction work in their frame (static_impl.h): the column's blocks
 * become R_j^T K_ji R_i (block q of row particle list[q], [e][c] at (q dim + e) dim + c). */
static void rotate_column(int dim, pdk_index i, pdk_index cnt, const pdk_index *list,
                          const int32_t *dir, const double (*frames)[3][3], double *block) {
  const double(*Ri)[3] = dir[i] >= 0 ? frames[dir[i]] : NULL;
  for (pdk_index q = 0; q < cnt; ++q) {
    const double(*Rj)[3] = dir[list[q]] >= 0 ? frames[dir[list[q]]] : NULL;
    if (!Ri && !Rj) continue;
    double *B = block + (size_t)q * (size_t)(dim * dim), T[9];
    for (int e = 0; e < dim; ++e) /* T = B R_i */
      for (int c = 0; c < dim; ++c) {
        double v = 0.0;
        for (int d = 0; d < dim; ++d)
          v += B[e * dim + d] * (Ri ? Ri[d][c] : (double)(d == c));
        T[e * dim + c] = v;
      }
    for (int e = 0; e < dim; ++e) /* B = R_j^T T */
      for (int c = 0; c < dim; ++c) {
        double v = 0.0;
        for (int d = 0; d < dim; ++d)
          v += (Rj ? Rj[d][e] : (double)(d == e)) * T[d * dim + c];
        B[e * dim + c] = v;
      }
  }
}

/* Analytic tangent at the current x (the model's tangent_column, see model_impl.h): one column
 * particle per iteration of a static parallel loop; each column is computed whole by one thread
 * into a dense block over its coupled particles (the pattern's list, same order), then copied to
 * the free entries. No sums cross columns, so the bits do not depend on the thread count. */
static int assemble_analytic(pdk_static *s) {
  newton_state *ns = s->newton;
  pdk_ctx *ctx = s->ctx;
  pdk_model *m = s->m;
  const int dim = s->dim, hops = s->hops, nt = ctx->num_threads;
  const pdk_index n = s->n;
  const double t0 = pdk_wtime();
  if (m->ops->tangent_prepare) PDK_CALL(m->ops->tangent_prepare(m));
  const pdk_bond_index *bs = pdk_families_bond_start(s->fam);
  const pdk_index *bj = pdk_families_bond_j(s->fam);
  if (!ns->col_scratch) {
    /* largest coupled list: bounds the dense column block */
    pdk_index fmax_ = 0;
    for (pdk_index i = 0; i < n; ++i)
      fmax_ = bs[i + 1] - bs[i] > fmax_ ? (pdk_index)(bs[i + 1] - bs[i]) : fmax_;
    double cap = 1.0 + (double)fmax_ + (hops > 1 ? (double)fmax_ * (double)fmax_ : 0.0);
    ns->block_capacity = cap < (double)n ? (pdk_index)cap : n;
    ns->col_scratch = malloc((size_t)nt * 3 * (size_t)n * sizeof *ns->col_scratch);
    ns->col_block = malloc((size_t)nt * (size_t)ns->block_capacity * (size_t)(dim * dim) *
                           sizeof *ns->col_block);
    PDK_CHECK(ns->col_scratch && ns->col_block, ctx, PDK_ERR_MEMORY,
              "newton: out of memory for the analytic tangent's scratch (%d threads, %d particles)",
              nt, (int)n);
  }
  pdk_index *scratch = ns->col_scratch;
  double *blocks = ns->col_block;
  const size_t cap = (size_t)ns->block_capacity;
  const int *Ap = ns->Ap;
  double *Ax = ns->Ax;
  int32_t *const *dof_of = ns->dof_of;
  double *const *diag_full = ns->diag_full;
  void (*column)(const pdk_model *, pdk_index, const pdk_index *, double *) =
      m->ops->tangent_column;
  const int32_t *dir = s->dir_of;
  const double(*frames)[3][3] = (const double(*)[3][3])s->dir_frame;
  const pdk_model *mc = m;
#pragma omp parallel default(none) shared(n, dim, hops, bs, bj, scratch, blocks, cap, Ap, Ax,      \
                                          dof_of, diag_full, column, mc, dir, frames)              \
    num_threads(nt)
  {
    const size_t tid = (size_t)omp_get_thread_num();
    pdk_index *stamp = scratch + 3 * (size_t)n * tid;
    pdk_index *list = stamp + n, *loc = list + n;
    double *block = blocks + cap * (size_t)(dim * dim) * tid;
    for (pdk_index k = 0; k < n; ++k) /* marks of the last assembly would hide neighbours */
      stamp[k] = -1;
#pragma omp for schedule(static)
    for (pdk_index i = 0; i < n; ++i) {
      const pdk_index cnt = pdk_newton_coupled(bs, bj, hops, i, stamp, list);
      for (pdk_index q = 0; q < cnt; ++q)
        loc[list[q]] = q;
      memset(block, 0, (size_t)cnt * (size_t)(dim * dim) * sizeof *block);
      column(mc, i, loc, block);
      if (dir) rotate_column(dim, i, cnt, list, dir, frames, block);
      const double *Kii = block + (size_t)loc[i] * (size_t)(dim * dim);
      for (int c = 0; c < dim; ++c) {
        diag_full[c][i] = Kii[c * dim + c];
        const int col = dof_of[c][i];
        if (col < 0) continue;
        int k = Ap[col];
        for (pdk_index q = 0; q < cnt; ++q)
          for (int e = 0; e < dim; ++e)
            if (dof_of[e][list[q]] >= 0) Ax[k++] = block[((size_t)q * dim + e) * dim + c];
      }
    }
  }
  double kmax = 0.0;
  for (int c = 0; c < dim; ++c)
    for (pdk_index i = 0; i < n; ++i)
      kmax = fmax(kmax, fabs(ns->diag_full[c][i]));
  ns->k_ref = kmax;
  s->stats.assemblies++;
  s->stats.time_assembly += pdk_wtime() - t0;
  return PDK_SUCCESS;
}

/* The solver's tangent: analytic or colored differences (opts.tangent). */
int pdk_newton_assemble_tangent(pdk_static *s) {
  newton_state *ns = s->newton;
  if (ns->analytic) return assemble_analytic(s);
  return assemble(s, s->num_colors, s->color_start, s->color_members);
}

int pdk_newton_tangent(pdk_static *s, int colored, int *num_cols, const int **col_start,
                       const int **row_index, const double **values) {
  newton_state *ns = s->newton;
  PDK_CHECK(ns && ns->Ap, s->ctx, PDK_ERR_ARG,
            "newton: no tangent (not a Newton solver, or no unknowns)");
  PDK_CHECK(colored == 2 || !s->dir_of, s->ctx, PDK_ERR_UNSUPPORTED,
            "newton: with a boundary condition along a direction only the analytic tangent "
            "(colored 2) is available");
  PDK_CHECK(colored != 2 || s->m->ops->tangent_column, s->ctx, PDK_ERR_UNSUPPORTED,
            "newton: model '%s' has no analytic tangent", pdk_model_kind_name(s->m->opts.kind));
  if (colored == 2)
    PDK_CALL(assemble_analytic(s));
  else if (colored) {
    PDK_CALL(pdk_static_color(s));
    PDK_CALL(assemble(s, s->num_colors, s->color_start, s->color_members));
  } else {
    if (!ns->ident) {
      ns->ident_start = malloc(((size_t)s->n + 1) * sizeof *ns->ident_start);
      ns->ident = malloc((size_t)s->n * sizeof *ns->ident);
      PDK_CHECK(ns->ident_start && ns->ident, s->ctx, PDK_ERR_MEMORY, "newton: out of memory");
      for (pdk_index i = 0; i <= s->n; ++i)
        ns->ident_start[i] = i;
      for (pdk_index i = 0; i < s->n; ++i)
        ns->ident[i] = i;
    }
    PDK_CALL(assemble(s, (int)s->n, ns->ident_start, ns->ident));
  }
  *num_cols = (int)ns->nf;
  *col_start = ns->Ap;
  *row_index = ns->Ai;
  *values = ns->Ax;
  return PDK_SUCCESS;
}
