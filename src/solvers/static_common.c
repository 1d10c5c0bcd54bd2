/* Static solvers, the pieces ADR (adr.c) and Newton (newton.c) share: prescribed displacements,
 * the residual and its norms, the convergence test, the non-finite report, the coloring of the
 * coupling graph and difference perturbations (src/solvers/static_impl.h).
 *
 * Reductions (norms) are summed per block of PDK_STATIC_BLOCK particles, particles in index order
 * within a block and blocks in order, so they do not depend on the thread count.
 */
#include <math.h>
#include <string.h>

#include "space/cells.h"
#include "static_impl.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/static.h"

static double *field(pdk_particles *p, const char *name, int c) {
  return pdk_particles_field_data(p, name, c);
}

void pdk_static_apply_prescribed(pdk_static *s) {
  for (int c = 0; c < s->dim; ++c) {
    double *x = field(s->p, "x", c);
    const double *X = pdk_particles_X(s->p, c);
    const uint8_t *fixed = s->fixed[c];
    const double *u = s->u_level[c];
    for (pdk_index i = 0; i < s->n; ++i)
      if (fixed[i] && !pdk_static_frame(s, i)) x[i] = X[i] + u[i];
  }
  if (!s->dir_of) return;
  for (pdk_index i = 0; i < s->n; ++i) { /* along a direction n: u.n = u_level[0] */
    const double(*R)[3] = pdk_static_frame(s, i);
    if (!R) continue;
    double un = 0.0;
    for (int c = 0; c < s->dim; ++c)
      un += (field(s->p, "x", c)[i] - pdk_particles_X(s->p, c)[i]) * R[c][0];
    for (int c = 0; c < s->dim; ++c)
      field(s->p, "x", c)[i] += (s->u_level[0][i] - un) * R[c][0];
  }
}

int pdk_static_residual(pdk_static *s) {
  PDK_CALL(pdk_model_force_trial(s->m, NULL));
  s->stats.force_passes++;
  const int dim = s->dim;
  const pdk_index n = s->n, num_blocks = s->num_blocks;
  const double *vol = pdk_particles_volume(s->p);
  const double *f[3] = {NULL, NULL, NULL}, *b[3] = {NULL, NULL, NULL};
  const uint8_t *fixed[3] = {NULL, NULL, NULL};
  double *r[3] = {NULL, NULL, NULL};
  for (int c = 0; c < dim; ++c) {
    f[c] = field(s->p, "f", c);
    b[c] = s->b_level[c];
    fixed[c] = s->fixed[c];
    r[c] = s->r[c];
  }
  double *part = s->block_part;
  const int nt = s->ctx->num_threads;
#pragma omp parallel for default(none) shared(s, f, b, fixed, r, vol, part, n, num_blocks, dim)    \
    schedule(static) num_threads(nt)
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    const pdk_index i0 = blk * PDK_STATIC_BLOCK;
    const pdk_index i1 = i0 + PDK_STATIC_BLOCK < n ? i0 + PDK_STATIC_BLOCK : n;
    double rs = 0.0, fs = 0.0;
    for (pdk_index i = i0; i < i1; ++i) {
      double rv[3] = {0, 0, 0}, lv[3] = {0, 0, 0};
      for (int c = 0; c < dim; ++c) {
        lv[c] = vol[i] * b[c][i];
        rv[c] = vol[i] * f[c][i] + lv[c];
      }
      const double(*R)[3] = pdk_static_frame(s, i);
      if (R) { /* held along a direction: the residual and load in the particle's frame */
        double rq[3] = {0, 0, 0}, lq[3] = {0, 0, 0};
        for (int q = 0; q < dim; ++q)
          for (int c = 0; c < dim; ++c) {
            rq[q] += R[c][q] * rv[c];
            lq[q] += R[c][q] * lv[c];
          }
        memcpy(rv, rq, sizeof rv);
        memcpy(lv, lq, sizeof lv);
      }
      for (int c = 0; c < dim; ++c) {
        const double load = lv[c];
        const double ri = rv[c];
        r[c][i] = ri;
        if (fixed[c][i])
          fs += ri * ri;
        else {
          rs += ri * ri;
          fs += load * load;
        }
      }
    }
    part[2 * blk] = rs;
    part[2 * blk + 1] = fs;
  }
  double rs = 0.0, fs = 0.0;
  for (pdk_index blk = 0; blk < num_blocks; ++blk) {
    rs += part[2 * blk];
    fs += part[2 * blk + 1];
  }
  s->rnorm = sqrt(rs);
  s->fnorm = sqrt(fs);
  return PDK_SUCCESS;
}

int pdk_static_converged(const pdk_static *s) {
  return s->rnorm <= fmax(s->opts.rtol * s->fnorm + s->opts.atol, s->floor);
}

int pdk_static_nonfinite(pdk_static *s, const char *method, long iteration, const char *hint) {
  /* What went non-finite: the first particle (index order) with a non-finite position, else the
   * first with a non-finite residual force; when both are finite everywhere, the norms overflowed
   * (squares beyond the double range): the particle with the largest residual force. */
  const int64_t *ids = pdk_particles_id(s->p);
  pdk_index bad = -1, big = -1, far = -1;
  int bad_c = 0, big_c = 0, far_c = 0, bad_what = 0; /* 1 position, 2 force */
  double bad_v = 0.0, rmax = -1.0, umax = -1.0;
  for (pdk_index i = 0; i < s->n && bad < 0; ++i)
    for (int c = 0; c < s->dim; ++c) {
      const double x = field(s->p, "x", c)[i], ri = s->r[c][i];
      if (!isfinite(x) || !isfinite(ri)) {
        bad = i, bad_c = c, bad_what = isfinite(x) ? 2 : 1, bad_v = isfinite(x) ? ri : x;
        break;
      }
      const double u = fabs(x - pdk_particles_X(s->p, c)[i]);
      if (fabs(ri) > rmax) rmax = fabs(ri), big = i, big_c = c;
      if (u > umax) umax = u, far = i, far_c = c;
    }
  char what[320];
  if (bad_what == 1)
    snprintf(what, sizeof what, "particle %d (id %lld) has a non-finite position along %c (%g)",
             (int)bad, (long long)ids[bad], "xyz"[bad_c], bad_v);
  else if (bad_what == 2)
    snprintf(what, sizeof what, "the residual force on particle %d (id %lld) along %c is %g",
             (int)bad, (long long)ids[bad], "xyz"[bad_c], bad_v);
  else if (big >= 0)
    snprintf(what, sizeof what,
             "every force and position is finite, but the %s norm overflowed: the largest "
             "residual force is %.3g on particle %d (id %lld) along %c, the largest displacement "
             "%.3g on particle %d (id %lld) along %c",
             isfinite(s->rnorm) ? "load" : "residual", rmax, (int)big, (long long)ids[big],
             "xyz"[big_c], umax, (int)far, (long long)ids[far], "xyz"[far_c]);
  else
    snprintf(what, sizeof what, "the body has no particle");
  /* the largest prescribed displacement of the level, and its condition's set */
  double umax_bc = 0.0;
  int bc = -1;
  for (int c = 0; c < s->dim; ++c)
    for (pdk_index i = 0; i < s->n; ++i)
      if (s->fixed[c][i] && !(fabs(s->u_level[c][i]) <= umax_bc))
        umax_bc = fabs(s->u_level[c][i]), bc = s->owner[c][i];
  char bcs[200] = "";
  if (bc >= 0 && bc < s->opts.num_bcs) {
    const char *set = s->bcs[bc].set ? s->bcs[bc].set : "(every particle)";
    snprintf(bcs, sizeof bcs,
             " (the largest prescribed displacement of this level is %g, %.3g horizons, boundary "
             "condition %d on set '%s')",
             umax_bc, umax_bc / s->horizon, bc, strncmp(set, "set:", 4) ? set : set + 4);
  }
  return pdk_ctx_error_set(s->ctx, PDK_ERR_NUMERIC, method,
                           "the residual became non-finite at load level %d (load factor %g), "
                           "round %d, iteration %ld: %s; check the boundary conditions' values%s "
                           "and the load steps; %s",
                           s->level, s->lambda, s->round, iteration, what, bcs, hint);
}

/* Coloring of the coupling graph for difference tangents.
 *
 * Particles i and k are coupled (K_ik != 0 possible) when k is within `hops` hops of i in the
 * family graph: P(i) = B_hops(i). Two columns can be perturbed together when no row sees both, i.e.
 * when B_hops(i) and B_hops(k) are disjoint, i.e. when the hop distance d(i, k) > 2 hops (a path
 * through a shared row has length <= 2 hops, and conversely). So a proper coloring is a distance-2
 * coloring of the coupling graph = a coloring where particles within 2 hops family hops differ.
 *
 * Greedy, in index order (Morton order after the usual reordering): particle i takes the smallest
 * color not used by an earlier particle within 2 hops hops, found by a breadth-first search over
 * the family CSR (all bonds, intact or not, like the pattern). Cost ~ n |B_2hops| f (f the family
 * size): 2-D RF 1.5 ~ 10^3 per particle, 3-D RF 1.5 ~ 10^4. When that estimate exceeds 4e9 (large
 * horizons in 3-D) the coloring falls back to geometry: colors differ within the ball of radius
 * R = 2 hops delta (a family is a ball of radius delta, so d(i, k) <= 2 hops implies |X_i - X_k|
 * <= R): a superset of the conflicts, about 1.5 times more colors, scanned over a cell list. */
static int color_greedy(pdk_static *s, pdk_index *stamp, int *num_colors_out) {
  const pdk_index n = s->n;
  const int depth = 2 * s->hops;
  const pdk_bond_index *bs = pdk_families_bond_start(s->fam);
  const pdk_index *bj = pdk_families_bond_j(s->fam);
  pdk_index *seen = malloc((size_t)n * sizeof *seen); /* BFS visit mark: particle being colored */
  pdk_index *queue = malloc((size_t)n * sizeof *queue);
  if (!seen || !queue) {
    free(seen);
    free(queue);
    return pdk_ctx_error_set(s->ctx, PDK_ERR_MEMORY, __func__,
                             "static solver: out of memory coloring %d particles", (int)n);
  }
  for (pdk_index k = 0; k < n; ++k)
    seen[k] = -1;
  int num_colors = 0;
  for (pdk_index i = 0; i < n; ++i) {
    pdk_index head = 0, tail = 0;
    queue[tail++] = i;
    seen[i] = i;
    for (int level = 0; level < depth; ++level) {
      const pdk_index end = tail;
      for (; head < end; ++head) {
        const pdk_index j = queue[head];
        for (pdk_bond_index b = bs[j]; b < bs[j + 1]; ++b) {
          const pdk_index k = bj[b];
          if (seen[k] == i) continue;
          seen[k] = i;
          queue[tail++] = k;
          if (k < i) stamp[s->color_of[k]] = i;
        }
      }
    }
    int col = 0;
    while (stamp[col] == i)
      ++col;
    s->color_of[i] = col;
    if (col + 1 > num_colors) num_colors = col + 1;
  }
  free(seen);
  free(queue);
  *num_colors_out = num_colors;
  return PDK_SUCCESS;
}

static int color_geometric(pdk_static *s, pdk_index *stamp, int *num_colors_out) {
  const pdk_index n = s->n;
  const int dim = s->dim;
  pdk_cells *cells = NULL;
  const double R = 2.0 * s->hops * s->horizon * (1.0 + 1e-9);
  const double R2 = R * R;
  PDK_CALL(pdk_cells_build(s->p, R, &cells));
  int num_colors = 0;
  const double *X[3] = {pdk_particles_X(s->p, 0), pdk_particles_X(s->p, 1),
                        dim == 3 ? pdk_particles_X(s->p, 2) : NULL};
  const int nb = dim == 3 ? 27 : 9;
  for (pdk_index i = 0; i < n; ++i) {
    const pdk_index ci = cells->cell_of[i];
    for (int q = 0; q < nb; ++q) {
      const pdk_index cn = cells->neighbours[(int64_t)ci * PDK_CELLS_NB + q];
      if (cn < 0) continue;
      for (pdk_index sl = cells->cell_start[cn]; sl < cells->cell_start[cn + 1]; ++sl) {
        const pdk_index j = cells->slot_id[sl];
        if (j >= i) continue; /* only already-colored particles */
        double d2 = 0.0;
        for (int a = 0; a < dim; ++a) {
          const double d = X[a][j] - X[a][i];
          d2 += d * d;
        }
        if (d2 <= R2) stamp[s->color_of[j]] = i;
      }
    }
    int col = 0;
    while (stamp[col] == i)
      ++col;
    s->color_of[i] = col;
    if (col + 1 > num_colors) num_colors = col + 1;
  }
  pdk_cells_destroy(&cells);
  *num_colors_out = num_colors;
  return PDK_SUCCESS;
}

int pdk_static_color(pdk_static *s) {
  if (s->color_of) return PDK_SUCCESS;
  pdk_ctx *ctx = s->ctx;
  int err = PDK_SUCCESS;
  pdk_index *stamp = NULL; /* [n+1] stamp[color] == i: color taken near particle i */
  const pdk_index n = s->n;
  const double t0 = pdk_wtime();
  s->color_of = malloc((size_t)n * sizeof *s->color_of);
  s->color_members = malloc((size_t)n * sizeof *s->color_members);
  stamp = malloc((size_t)(n + 1) * sizeof *stamp);
  PDK_CHECK_GOTO(s->color_of && s->color_members && stamp, ctx, PDK_ERR_MEMORY,
                 "static solver: out of memory coloring %d particles", (int)n);
  for (pdk_index k = 0; k <= n; ++k)
    stamp[k] = -1;
  /* cost estimate of the graph search: n f^2 (2 hops)^dim */
  const double f = (double)pdk_families_num_bonds(s->fam) / (double)n;
  const double cost = (double)n * f * f * pow(2.0 * s->hops, s->dim);
  int num_colors = 0;
  s->stats.coloring_geometric = cost > 4e9;
  if (cost > 4e9)
    PDK_CALL_GOTO(color_geometric(s, stamp, &num_colors));
  else
    PDK_CALL_GOTO(color_greedy(s, stamp, &num_colors));
  s->color_start = calloc((size_t)num_colors + 1, sizeof *s->color_start);
  PDK_CHECK_GOTO(s->color_start, ctx, PDK_ERR_MEMORY, "static solver: out of memory for colors");
  for (pdk_index i = 0; i < n; ++i)
    s->color_start[s->color_of[i] + 1]++;
  for (int k = 0; k < num_colors; ++k)
    s->color_start[k + 1] += s->color_start[k];
  for (int k = 0; k <= num_colors; ++k)
    stamp[k] = s->color_start[k];
  for (pdk_index i = 0; i < n; ++i)
    s->color_members[stamp[s->color_of[i]]++] = i;
  s->num_colors = num_colors;
  s->stats.num_colors = num_colors;
  s->stats.time_setup += pdk_wtime() - t0;
cleanup:
  free(stamp);
  if (err) {
    free(s->color_of);
    free(s->color_members);
    free(s->color_start);
    s->color_of = s->color_members = s->color_start = NULL;
  }
  return err;
}

void pdk_static_perturb(pdk_static *s, int k, int c, double step, double *h_actual) {
  double *x = field(s->p, "x", c);
  for (pdk_index q = s->color_start[k]; q < s->color_start[k + 1]; ++q) {
    const pdk_index i = s->color_members[q];
    const double x0 = x[i];
    x[i] = x0 + step;
    if (h_actual) h_actual[i] = x[i] - x0; /* exact: the perturbation actually applied */
  }
}

void pdk_static_restore(pdk_static *s, int k, int c, const double *saved) {
  double *x = field(s->p, "x", c);
  for (pdk_index q = s->color_start[k]; q < s->color_start[k + 1]; ++q) {
    const pdk_index i = s->color_members[q];
    x[i] = saved[i];
  }
}
