/* Cell list: a uniform grid over the particles' bounding box and a stable counting sort by cell.
 * Layout and guarantee: see cells.h.
 *
 * Why the edge is a little larger than the horizon. A neighbour j of i satisfies, in computed
 * arithmetic, r2 <= r2max = horizon^2 (1 + PDK_HORIZON_RTOL), so the true distance can exceed the
 * horizon by a relative 5e-13 (plus a few units of round-off). The cell coordinate
 * u = fl(fl(X - lo) * fl(1/edge)) carries a relative error below 3 * 2^-53, that is an absolute
 * error below 3 * 2^-53 * N on an axis of N cells; for two particles the difference of their u is
 * off by less than 6 * 2^-53 * N <= 1.4e-9 with N <= 2^21. With edge = horizon * (1 + 2^-26) the
 * exact u difference of two neighbours is at most (1 + 5.1e-13) / (1 + 1.49e-8) < 1 - 1.4e-8, so
 * the computed difference stays below 1 and the integer cell coordinates differ by at most 1.
 * An edge of exactly the horizon would not do: lattice points at exactly the horizon, which the
 * tolerance exists to admit, would land two cells apart when round-off puts one just below a cell
 * face.
 *
 * The cell count is an integer number of such cells per axis, floor(extent / edge) + 1, covering
 * [lo, lo + num * edge) which holds every particle. When that grid would exceed PDK_CELLS_MAX_AXIS
 * cells on an axis or 4 n + 4096 cells in all (a huge box or a tiny horizon), the edge grows until
 * it fits: fewer, fuller cells, the same neighbours.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "cells.h"

typedef struct grid {
  double lo[3], edge, inv_edge;
  int64_t num[3], num_cells;
} grid;

/* Picks the grid for store p and `horizon`; see the file comment. */
static int grid_setup(pdk_particles *p, double horizon, grid *g) {
  pdk_ctx *ctx = pdk_particles_ctx(p);
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  PDK_CHECK(isfinite(horizon) && horizon > 0, ctx, PDK_ERR_ARG,
            "the horizon must be a positive finite length, got %g", horizon);
  PDK_CALL(pdk_particles_check_finite(p));
  memset(g, 0, sizeof *g);
  double hi[3] = {0, 0, 0};
  const int nthreads = ctx->num_threads;
  for (int a = 0; a < dim; ++a) {
    const double *x = pdk_particles_X(p, a);
    double mn = x[0], mx = x[0];
#pragma omp parallel for default(none) shared(x, n) reduction(min                                  \
                                                              : mn) reduction(max                  \
                                                                              : mx)                \
    schedule(static) num_threads(nthreads)
    for (pdk_index i = 0; i < n; ++i) {
      mn = x[i] < mn ? x[i] : mn;
      mx = x[i] > mx ? x[i] : mx;
    }
    g->lo[a] = mn;
    hi[a] = mx;
    PDK_CHECK(isfinite(mx - mn), ctx, PDK_ERR_ARG,
              "the particles span %g to %g along axis %d, a width beyond the range of a double; "
              "rescale the coordinates",
              mn, mx, a);
  }
  const double cap_total = fmin(4.0 * (double)n + 4096.0, (double)(INT32_MAX - 1));
  double edge = horizon * (1.0 + 0x1p-26);
  if (!isfinite(edge)) edge = DBL_MAX;
  for (int iter = 0;; ++iter) {
    const double inv = 1.0 / edge;
    double total = 1.0, axis_ratio = 0.0, num[3] = {1, 1, 1};
    for (int a = 0; a < dim; ++a) {
      num[a] = floor((hi[a] - g->lo[a]) * inv) + 1.0;
      total *= num[a];
      axis_ratio = fmax(axis_ratio, num[a] / PDK_CELLS_MAX_AXIS);
    }
    if (axis_ratio <= 1.0 && total <= cap_total) {
      g->edge = edge;
      g->inv_edge = inv;
      for (int a = 0; a < 3; ++a)
        g->num[a] = (int64_t)num[a];
      g->num_cells = g->num[0] * g->num[1] * g->num[2];
      return PDK_SUCCESS;
    }
    /* Grow by the factor that would fit, and at least 5 % so the loop ends quickly. */
    double grow = fmax(axis_ratio, pow(total / cap_total, 1.0 / dim));
    edge *= fmax(grow, 1.0) * 1.05;
    PDK_CHECK(iter < 1000 && isfinite(edge), ctx, PDK_ERR_ARG,
              "no cell grid fits %d particles spanning %g x %g x %g with a horizon of %g", (int)n,
              hi[0] - g->lo[0], hi[1] - g->lo[1], hi[2] - g->lo[2], horizon);
  }
}

int pdk_cells_edge(pdk_particles *p, double horizon, double *edge) {
  grid g;
  *edge = 0.0;
  PDK_CALL(grid_setup(p, horizon, &g));
  *edge = g.edge;
  return PDK_SUCCESS;
}

void pdk_cells_destroy(pdk_cells **cells) {
  if (!cells || !*cells) return;
  pdk_cells *cl = *cells;
  pdk_free_aligned(cl->cell_start);
  pdk_free_aligned(cl->slot_id);
  pdk_free_aligned(cl->cell_of);
  for (int a = 0; a < 3; ++a)
    pdk_free_aligned(cl->x[a]);
  free(cl);
  *cells = NULL;
}

int pdk_cells_build(pdk_particles *p, double horizon, pdk_cells **out) {
  int err = PDK_SUCCESS;
  pdk_ctx *ctx = pdk_particles_ctx(p);
  pdk_cells *cl = NULL;
  grid g;
  *out = NULL;
  PDK_CALL(grid_setup(p, horizon, &g));
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p), n_pad = pdk_particles_count_padded(p);
  cl = calloc(1, sizeof *cl);
  PDK_CHECK(cl, ctx, PDK_ERR_MEMORY, "out of memory creating a cell list");
  cl->dim = dim;
  cl->n = n;
  memcpy(cl->lo, g.lo, sizeof g.lo);
  cl->edge = g.edge;
  cl->inv_edge = g.inv_edge;
  memcpy(cl->num, g.num, sizeof g.num);
  cl->num_cells = g.num_cells;
  cl->cell_start = pdk_alloc_aligned((size_t)g.num_cells + 1, sizeof *cl->cell_start);
  cl->slot_id = pdk_alloc_aligned((size_t)n, sizeof *cl->slot_id);
  cl->cell_of = pdk_alloc_aligned((size_t)n, sizeof *cl->cell_of);
  int ok = cl->cell_start && cl->slot_id && cl->cell_of;
  for (int a = 0; a < dim; ++a)
    ok = ok && (cl->x[a] = pdk_alloc_aligned((size_t)n_pad, sizeof(double)));
  PDK_CHECK_GOTO(ok, ctx, PDK_ERR_MEMORY,
                 "out of memory building a cell list of %lld cells for %d particles",
                 (long long)g.num_cells, (int)n);

  const double *X0 = pdk_particles_X(p, 0), *X1 = pdk_particles_X(p, 1);
  const double *X2 = dim == 3 ? pdk_particles_X(p, 2) : NULL;
  const int nthreads = ctx->num_threads;
  pdk_index *cell_of = cl->cell_of, *cell_start = cl->cell_start, *slot_id = cl->slot_id;
  {
    const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2], inv = g.inv_edge;
    const int64_t n0 = g.num[0], n1 = g.num[1], n2 = g.num[2];
    /* Cell of each particle; the same expression as pdk_particles_reorder_morton's. Clamped,
     * though the grid was sized with that expression so the clamp never acts. */
#pragma omp parallel for default(none) shared(cell_of, X0, X1, X2, n)                              \
    firstprivate(lo0, lo1, lo2, inv, n0, n1, n2) schedule(static) num_threads(nthreads)
    for (pdk_index i = 0; i < n; ++i) {
      int64_t cx = (int64_t)((X0[i] - lo0) * inv), cy = (int64_t)((X1[i] - lo1) * inv);
      int64_t cz = X2 ? (int64_t)((X2[i] - lo2) * inv) : 0;
      cx = cx < n0 ? cx : n0 - 1;
      cy = cy < n1 ? cy : n1 - 1;
      cz = cz < n2 ? cz : n2 - 1;
      cell_of[i] = (pdk_index)(cx + n0 * (cy + n1 * cz));
    }
  }
  /* Stable counting sort: cell_start[c] first counts cell c, then (inclusive prefix sum) holds its
   * end; filling slots from the last particle down leaves cell_start[c] at the cell's start with
   * the particles of a cell in ascending index order. */
  for (pdk_index i = 0; i < n; ++i)
    cell_start[cell_of[i]]++;
  for (int64_t c = 1; c <= g.num_cells; ++c)
    cell_start[c] += cell_start[c - 1];
  for (pdk_index i = n - 1; i >= 0; --i)
    slot_id[--cell_start[cell_of[i]]] = i;
  {
    double *x0 = cl->x[0], *x1 = cl->x[1], *x2 = cl->x[2];
#pragma omp parallel for default(none) shared(x0, x1, x2, X0, X1, X2, slot_id, n) schedule(static) \
    num_threads(nthreads)
    for (pdk_index s = 0; s < n; ++s) {
      const pdk_index i = slot_id[s];
      x0[s] = X0[i];
      x1[s] = X1[i];
      if (x2) x2[s] = X2[i];
    }
  }
  *out = cl;
  return PDK_SUCCESS;
cleanup:
  pdk_cells_destroy(&cl);
  return err;
}
