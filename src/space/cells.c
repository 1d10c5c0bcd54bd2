/* Cell list: a uniform grid over the particles' bounding box, its occupied cells, and the particles
 * sorted by cell. Layout and guarantee: see cells.h.
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
 * The grid has floor(extent / edge) + 1 cells per axis, covering [lo, lo + num * edge), which holds
 * every particle. Only if that exceeds PDK_CELLS_MAX_AXIS on an axis does the edge grow (fewer,
 * fuller cells, the same neighbours).
 *
 * Binning. When the grid has at most 4 n + 4096 cells, a stable counting sort over the whole grid
 * (O(n + cells)); otherwise (a box much larger than the bodies in it) a stable radix sort of the
 * particles' cell keys, O(n) per 11-bit digit of the largest key. Either way the occupied cells
 * come out in ascending key order with the same slots, and their neighbour lists are found through
 * the dense grid's index or by binary search in the sorted keys.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "cells.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"

typedef struct grid {
  double lo[3], edge, inv_edge;
  int64_t num[3];
  double num_total; /* num[0] * num[1] * num[2], as a double (may exceed 2^53 only in sparse use) */
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
  double edge = horizon * (1.0 + 0x1p-26);
  if (!isfinite(edge)) edge = DBL_MAX;
  for (int iter = 0;; ++iter) {
    const double inv = 1.0 / edge;
    double axis_ratio = 0.0, num[3] = {1, 1, 1};
    for (int a = 0; a < dim; ++a) {
      num[a] = floor((hi[a] - g->lo[a]) * inv) + 1.0;
      axis_ratio =
          axis_ratio > num[a] / PDK_CELLS_MAX_AXIS ? axis_ratio : num[a] / PDK_CELLS_MAX_AXIS;
    }
    if (axis_ratio <= 1.0) {
      g->edge = edge;
      g->inv_edge = inv;
      for (int a = 0; a < 3; ++a)
        g->num[a] = (int64_t)num[a];
      g->num_total = num[0] * num[1] * num[2];
      return PDK_SUCCESS;
    }
    edge *= axis_ratio * 1.01; /* a few rounds at most */
    PDK_CHECK(iter < 100 && isfinite(edge), ctx, PDK_ERR_ARG,
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
  pdk_free_aligned(cl->key);
  pdk_free_aligned(cl->cell_start);
  pdk_free_aligned(cl->neighbours);
  pdk_free_aligned(cl->slot_id);
  pdk_free_aligned(cl->cell_of);
  for (int a = 0; a < 3; ++a)
    pdk_free_aligned(cl->x[a]);
  free(cl);
  *cells = NULL;
}

/* Dense binning: stable counting sort over every grid cell. pkey: [n] cell key of each particle.
 * Fills slot_id, cell_of, key, cell_start, and the dense index dense_to_cell [num_total] (-1 for
 * an empty cell), which the caller frees. */
static int bin_dense(pdk_ctx *ctx, pdk_cells *cl, const int64_t *pkey, int64_t num_total,
                     pdk_index **dense_to_cell) {
  const pdk_index n = cl->n;
  pdk_index *count = pdk_alloc_aligned((size_t)num_total + 1, sizeof *count);
  PDK_CHECK(count, ctx, PDK_ERR_MEMORY, "out of memory binning %d particles into %lld cells",
            (int)n, (long long)num_total);
  /* count[k] first counts cell k, then (inclusive prefix sum) holds its end; filling slots from the
   * last particle down leaves count[k] at the cell's start, particles in ascending order. */
  for (pdk_index i = 0; i < n; ++i)
    count[pkey[i]]++;
  pdk_index occupied = 0;
  for (int64_t k = 0; k < num_total; ++k)
    occupied += count[k] != 0;
  for (int64_t k = 1; k <= num_total; ++k)
    count[k] += count[k - 1];
  for (pdk_index i = n - 1; i >= 0; --i)
    cl->slot_id[--count[pkey[i]]] = i;
  cl->key = pdk_alloc_aligned((size_t)occupied, sizeof *cl->key);
  cl->cell_start = pdk_alloc_aligned((size_t)occupied + 1, sizeof *cl->cell_start);
  if (!cl->key || !cl->cell_start) {
    pdk_free_aligned(count);
    return pdk_ctx_error_set(ctx, PDK_ERR_MEMORY, __func__, "out of memory for %d cells",
                             (int)occupied);
  }
  /* Compress to the occupied cells; count[] becomes the dense -> occupied index. */
  pdk_index c = 0;
  for (int64_t k = 0; k < num_total; ++k) {
    const pdk_index start = count[k], end = count[k + 1];
    if (end > start) {
      cl->key[c] = k;
      cl->cell_start[c] = start;
      count[k] = c++;
    } else {
      count[k] = -1;
    }
  }
  cl->cell_start[c] = n;
  cl->num_cells = occupied;
  for (pdk_index i = 0; i < n; ++i)
    cl->cell_of[i] = count[pkey[i]];
  *dense_to_cell = count;
  return PDK_SUCCESS;
}

/* Sparse binning: stable LSD radix sort of the particles by cell key (11 bits per pass, as many
 * passes as the largest key needs). Fills slot_id, cell_of, key, cell_start. */
static int bin_sparse(pdk_ctx *ctx, pdk_cells *cl, const int64_t *pkey, int64_t max_key) {
  int err = PDK_SUCCESS;
  const pdk_index n = cl->n;
  enum { BITS = 11, BUCKETS = 1 << BITS };
  int64_t *k0 = malloc((size_t)n * sizeof *k0), *k1 = malloc((size_t)n * sizeof *k1);
  pdk_index *i0 = cl->slot_id, *i1 = malloc((size_t)n * sizeof *i1);
  size_t *bucket = malloc((BUCKETS + 1) * sizeof *bucket);
  PDK_CHECK_GOTO(k0 && k1 && i1 && bucket, ctx, PDK_ERR_MEMORY,
                 "out of memory sorting %d particles by cell", (int)n);
  for (pdk_index i = 0; i < n; ++i) {
    k0[i] = pkey[i];
    i0[i] = i;
  }
  for (int shift = 0; shift < 63 && (max_key >> shift) > 0; shift += BITS) {
    memset(bucket, 0, (BUCKETS + 1) * sizeof *bucket);
    for (pdk_index i = 0; i < n; ++i)
      bucket[((k0[i] >> shift) & (BUCKETS - 1)) + 1]++;
    for (int b = 0; b < BUCKETS; ++b)
      bucket[b + 1] += bucket[b];
    for (pdk_index i = 0; i < n; ++i) {
      const size_t dst = bucket[(k0[i] >> shift) & (BUCKETS - 1)]++;
      k1[dst] = k0[i];
      i1[dst] = i0[i];
    }
    int64_t *tk = k0;
    k0 = k1, k1 = tk;
    pdk_index *ti = i0;
    i0 = i1, i1 = ti;
  }
  if (i0 != cl->slot_id) { /* an odd number of passes left the order in the scratch array */
    memcpy(cl->slot_id, i0, (size_t)n * sizeof *i0);
    i1 = i0;
  }
  pdk_index occupied = 0;
  for (pdk_index s = 0; s < n; ++s)
    occupied += s == 0 || k0[s] != k0[s - 1];
  cl->key = pdk_alloc_aligned((size_t)occupied, sizeof *cl->key);
  cl->cell_start = pdk_alloc_aligned((size_t)occupied + 1, sizeof *cl->cell_start);
  PDK_CHECK_GOTO(cl->key && cl->cell_start, ctx, PDK_ERR_MEMORY, "out of memory for %d cells",
                 (int)occupied);
  pdk_index c = -1;
  for (pdk_index s = 0; s < n; ++s) {
    if (s == 0 || k0[s] != k0[s - 1]) {
      ++c;
      cl->key[c] = k0[s];
      cl->cell_start[c] = s;
    }
    cl->cell_of[cl->slot_id[s]] = c;
  }
  cl->cell_start[occupied] = n;
  cl->num_cells = occupied;
cleanup:
  free(k0);
  free(k1);
  free(i1 == cl->slot_id ? NULL : i1);
  free(bucket);
  return err;
}

/* Occupied cell with grid key k, or -1: binary search in the ascending keys. */
static pdk_index find_cell(const pdk_cells *cl, int64_t k) {
  pdk_index lo = 0, hi = cl->num_cells;
  while (lo < hi) {
    const pdk_index mid = lo + (hi - lo) / 2;
    if (cl->key[mid] < k)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < cl->num_cells && cl->key[lo] == k ? lo : -1;
}

int pdk_cells_build(pdk_particles *p, double horizon, pdk_cells **out) {
  int err = PDK_SUCCESS;
  pdk_ctx *ctx = pdk_particles_ctx(p);
  pdk_cells *cl = NULL;
  int64_t *pkey = NULL;
  pdk_index *dense_to_cell = NULL;
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
  cl->slot_id = pdk_alloc_aligned((size_t)n, sizeof *cl->slot_id);
  cl->cell_of = pdk_alloc_aligned((size_t)n, sizeof *cl->cell_of);
  pkey = malloc((size_t)n * sizeof *pkey);
  int ok = cl->slot_id && cl->cell_of && pkey;
  for (int a = 0; a < dim; ++a)
    ok = ok && (cl->x[a] = pdk_alloc_aligned((size_t)n_pad, sizeof(double)));
  PDK_CHECK_GOTO(ok, ctx, PDK_ERR_MEMORY, "out of memory building a cell list of %d particles",
                 (int)n);

  const double *X0 = pdk_particles_X(p, 0), *X1 = pdk_particles_X(p, 1);
  const double *X2 = dim == 3 ? pdk_particles_X(p, 2) : NULL;
  const int nthreads = ctx->num_threads;
  {
    const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2], inv = g.inv_edge;
    const int64_t n0 = g.num[0], n1 = g.num[1], n2 = g.num[2];
    /* Cell key of each particle; the cell coordinate is pdk_particles_reorder_morton's
     * expression. Clamped, though the grid was sized with that expression so the clamp never
     * acts. */
#pragma omp parallel for default(none) shared(pkey, X0, X1, X2, n)                                 \
    firstprivate(lo0, lo1, lo2, inv, n0, n1, n2) schedule(static) num_threads(nthreads)
    for (pdk_index i = 0; i < n; ++i) {
      int64_t cx = (int64_t)((X0[i] - lo0) * inv), cy = (int64_t)((X1[i] - lo1) * inv);
      int64_t cz = X2 ? (int64_t)((X2[i] - lo2) * inv) : 0;
      cx = cx < n0 ? cx : n0 - 1;
      cy = cy < n1 ? cy : n1 - 1;
      cz = cz < n2 ? cz : n2 - 1;
      pkey[i] = cx + n0 * (cy + n1 * cz);
    }
  }
  const double dense_cap = 4.0 * (double)n + 4096.0;
  if (g.num_total <= dense_cap) {
    PDK_CALL_GOTO(bin_dense(ctx, cl, pkey, (int64_t)g.num_total, &dense_to_cell));
  } else {
    cl->sparse = 1;
    PDK_CALL_GOTO(bin_sparse(ctx, cl, pkey, g.num[0] * g.num[1] * g.num[2] - 1));
  }
  free(pkey);
  pkey = NULL;

  /* Neighbour lists: the occupied cells among the 3^dim grid cells around each cell. */
  cl->neighbours = pdk_alloc_aligned((size_t)cl->num_cells * PDK_CELLS_NB, sizeof *cl->neighbours);
  PDK_CHECK_GOTO(cl->neighbours, ctx, PDK_ERR_MEMORY,
                 "out of memory listing neighbours of %d cells", (int)cl->num_cells);
  {
    const pdk_index num_cells = cl->num_cells;
    const pdk_cells *ccl = cl;
    pdk_index *nbr = cl->neighbours;
#pragma omp parallel for default(none) shared(ccl, nbr, dense_to_cell, num_cells, dim)             \
    schedule(static) num_threads(nthreads)
    for (pdk_index c = 0; c < num_cells; ++c) {
      const int64_t n0 = ccl->num[0], n1 = ccl->num[1], n2 = ccl->num[2], k = ccl->key[c];
      const int64_t cc[3] = {k % n0, (k / n0) % n1, k / (n0 * n1)};
      const int zr = dim == 3 ? 1 : 0;
      int q = 0;
      for (int dz = -zr; dz <= zr; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int64_t x = cc[0] + dx, y = cc[1] + dy, z = cc[2] + dz;
            pdk_index found = -1;
            if (x >= 0 && y >= 0 && z >= 0 && x < n0 && y < n1 && z < n2) {
              const int64_t k2 = x + n0 * (y + n1 * z);
              found = dense_to_cell ? dense_to_cell[k2] : find_cell(ccl, k2);
            }
            nbr[(size_t)c * PDK_CELLS_NB + q++] = found;
          }
      for (; q < PDK_CELLS_NB; ++q)
        nbr[(size_t)c * PDK_CELLS_NB + q] = -1;
    }
  }
  pdk_free_aligned(dense_to_cell);
  dense_to_cell = NULL;

  {
    double *x0 = cl->x[0], *x1 = cl->x[1], *x2 = cl->x[2];
    const pdk_index *slot_id = cl->slot_id;
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
  free(pkey);
  pdk_free_aligned(dense_to_cell);
  pdk_cells_destroy(&cl);
  return err;
}
