/* Bond families: neighbour search over a cell list, pre-cracks, CSR storage. See
 * include/pdk/families.h for the neighbour rule and the guarantees.
 *
 * Storage:
 *   bond_start: [n+1] int64; bonds of particle i are bond_start[i] .. bond_start[i+1]-1
 *   bond_j:     [num_bonds] int32; the neighbour of each bond, ascending within a family
 *
 * Method.
 *  1. Cells (src/space/cells.c): grid of edge slightly above the horizon; the occupied cells, each with
 *     its occupied neighbours, and the particles sorted by cell into contiguous coordinate arrays.
 *  2. Bound the bond count before allocating anything large: an upper bound from cell occupancies
 *     (every particle of the 3^d cells around a particle's cell). When that exceeds the memory
 *     limit, a lower bound (cell pairs whose particles are all within the horizon of each other)
 *     fails a huge horizon at once, and otherwise the count pass below stops as soon as the count
 *     passes the limit.
 *  3. Per cell c, gather the candidates: the particles of the 3^d neighbour cells that lie within
 *     the horizon of c's bounding box (on the 10^6 cube, 375 per particle of the 696 there), in
 *     ascending particle index: neighbour cells are visited in the order of their first particle,
 *     and merged when their index ranges interleave. Every particle i of c then scans this one
 *     contiguous buffer with the family_scan kernel of the context's table; the kernel keeps
 *     candidate order, so each family comes out ascending without a sort. When the store was
 *     reordered with pdk_families_cell_edge's edge, cells are contiguous index ranges and no merge
 *     happens.
 *  4. Pre-cracks remove the bonds they cut. A cell tests only the cracks whose bounding box meets
 *     its own grown by the horizon and whose line or plane does not leave that grown box on one
 *     side; a bond only those its bounding box touches, first by the exact sides of its ends.
 *  5. Threads: the cells, in the order of their first particle, are split into one block per
 *     thread with equal particle counts (a static schedule). A first parallel pass counts each
 *     family, a prefix sum gives bond_start, a second pass writes bond_j. Every family depends
 *     only on its particle, so the result is bitwise the same for any thread count.
 *     Why scan twice: a single pass into per-thread buffers would first-touch bond-sized memory
 *     twice (buffers, then bond_j), and on the reference VM first touch costs 0.12-0.3 s per
 *     471 MB (the 10^6 cube's bond_j) on 2 threads, more than the count pass (about 0.1 s).
 */
#define _DEFAULT_SOURCE /* sysconf(_SC_PHYS_PAGES) */
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "families_build.h"
#include "pdk/ctx.h"
#include "pdk/families.h"
#include "pdk/particles.h"

struct pdk_families {
  pdk_ctx *ctx;
  pdk_index n;
  double horizon;             /* [length] */
  pdk_bond_index num_bonds;   /* directed bonds */
  pdk_bond_index *bond_start; /* [n+1] */
  pdk_index *bond_j;          /* [num_bonds] (allocated for at least one entry) */
  int num_precracks;          /* the pre-cracks of the build, copied (src/space/families_impl.h) */
  pdk_precrack *precracks;
  double *precrack_vertices;
};

pdk_families_opts pdk_families_opts_default(void) {
  pdk_families_opts o;
  memset(&o, 0, sizeof o);
  return o;
}

/* ---- bounds on the bond count ---------------------------------------------------------------- */

/* Upper bound on the directed bonds (every pair of particles in neighbouring cells, self
 * excluded) and the most candidates of any cell. */
static void bound_upper(const pdk_cells *cl, const int64_t *cells, int64_t num_cells, int nthreads,
                        int64_t *upper, pdk_index *max_cand) {
  int64_t up = 0, mx = 0;
#pragma omp parallel for default(none) shared(cl, cells, num_cells) reduction(+ : up) \
    reduction(max : mx) schedule(static) num_threads(nthreads)
  for (int64_t k = 0; k < num_cells; ++k) {
    const int64_t c = cells[k];
    int64_t cand = 0;
    FOR_EACH_NEIGHBOUR_CELL(cl, c, c2, { cand += cl->cell_start[c2 + 1] - cl->cell_start[c2]; });
    const int64_t occ = cl->cell_start[c + 1] - cl->cell_start[c];
    up += occ * (cand - 1);
    mx = cand > mx ? cand : mx;
  }
  *upper = up;
  *max_cand = (pdk_index)mx;
}

/* Lower bound on the directed bonds: pairs of (neighbouring or equal) cells whose particles'
 * bounding boxes are everywhere within the horizon of each other contribute all their pairs. */
static int bound_lower(pdk_ctx *ctx, const pdk_cells *cl, const int64_t *cells, int64_t num_cells,
                       double r2max, int64_t *lower) {
  const int dim = cl->dim, nthreads = ctx->num_threads;
  double *box = malloc((size_t)cl->num_cells * 6 * sizeof *box); /* [num_cells][lo 3, hi 3] */
  PDK_CHECK(box, ctx, PDK_ERR_MEMORY, "out of memory bounding the bond count");
#pragma omp parallel for default(none) shared(cl, cells, num_cells, box, dim) schedule(static)     \
    num_threads(nthreads)
  for (int64_t k = 0; k < num_cells; ++k) {
    const int64_t c = cells[k];
    double *b = box + 6 * c;
    for (int a = 0; a < 3; ++a)
      b[a] = b[3 + a] = 0;
    for (int a = 0; a < dim; ++a) {
      b[a] = b[3 + a] = cl->x[a][cl->cell_start[c]];
      for (pdk_index s = cl->cell_start[c]; s < cl->cell_start[c + 1]; ++s) {
        b[a] = min_d(b[a], cl->x[a][s]);
        b[3 + a] = max_d(b[3 + a], cl->x[a][s]);
      }
    }
  }
  int64_t lo = 0;
#pragma omp parallel for default(none) shared(cl, cells, num_cells, box, dim, r2max) \
    reduction(+ : lo) schedule(static) num_threads(nthreads)
  for (int64_t k = 0; k < num_cells; ++k) {
    const int64_t c = cells[k];
    const double *b = box + 6 * c;
    const int64_t occ = cl->cell_start[c + 1] - cl->cell_start[c];
    FOR_EACH_NEIGHBOUR_CELL(cl, c, c2, {
      const double *b2 = box + 6 * c2;
      double d2 = 0;
      for (int a = 0; a < dim; ++a) {
        double e = max_d(b[3 + a] - b2[a], b2[3 + a] - b[a]);
        d2 += e * e;
      }
      if (d2 * (1.0 + 1e-9) <= r2max)
        lo += occ * (cl->cell_start[c2 + 1] - cl->cell_start[c2] - (c2 == c ? 1 : 0));
    });
  }
  free(box);
  *lower = lo;
  return PDK_SUCCESS;
}

/* Bytes held for `bonds` directed bonds of n particles (bond_j + bond_start), saturating. */
static double families_bytes(pdk_index n, double bonds) {
  return bonds * (double)sizeof(pdk_index) + ((double)n + 1.0) * (double)sizeof(pdk_bond_index);
}

static size_t default_max_bytes(void) {
  long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return SIZE_MAX;
  return (size_t)((double)pages * (double)page * 0.75);
}

/* bond_j: not zeroed, since the fill pass writes every entry, and so first touched by the threads
 * that fill it. (Transparent huge pages were measured and not used: on the reference VM their
 * first touch in a fresh process took 0.6-1 s for 471 MB, against 0.13-0.3 s for 4 KiB pages.) */
static pdk_index *alloc_bond_j(size_t count) {
  if (count > (SIZE_MAX - PDK_ALIGN) / sizeof(pdk_index)) return NULL;
  const size_t bytes = count * sizeof(pdk_index);
  return aligned_alloc(PDK_ALIGN, (bytes + PDK_ALIGN - 1) / PDK_ALIGN * PDK_ALIGN);
}

/* Keeps a copy of the pre-cracks in f (for rebuilds in another configuration). */
static int copy_precracks(pdk_ctx *ctx, pdk_families *f, int dim, const pdk_families_opts *o) {
  if (o->num_precracks <= 0) return PDK_SUCCESS;
  size_t nv = 0;
  for (int k = 0; k < o->num_precracks; ++k)
    nv += (size_t)o->precracks[k].num_vertices;
  f->precracks = calloc((size_t)o->num_precracks, sizeof *f->precracks);
  f->precrack_vertices = malloc(nv * (size_t)dim * sizeof(double));
  PDK_CHECK(f->precracks && f->precrack_vertices, ctx, PDK_ERR_MEMORY,
            "out of memory keeping %d pre-cracks", o->num_precracks);
  size_t at = 0;
  for (int k = 0; k < o->num_precracks; ++k) {
    const size_t len = (size_t)o->precracks[k].num_vertices * (size_t)dim;
    memcpy(f->precrack_vertices + at, o->precracks[k].vertices, len * sizeof(double));
    f->precracks[k].num_vertices = o->precracks[k].num_vertices;
    f->precracks[k].vertices = f->precrack_vertices + at;
    at += len;
  }
  f->num_precracks = o->num_precracks;
  return PDK_SUCCESS;
}

/* ---- the driver ------------------------------------------------------------------------------ */

/* Splits the cells (in `cells` order) into nblocks blocks of about equal particle counts:
 * block b covers cells[block_start[b] .. block_start[b+1]-1]. */
static void split_blocks(const pdk_cells *cl, const int64_t *cells, int64_t num_cells, int nblocks,
                         int64_t *block_start) {
  int64_t k = 0, seen = 0;
  block_start[0] = 0;
  for (int b = 1; b < nblocks; ++b) {
    const int64_t target = (int64_t)cl->n * b / nblocks;
    while (k < num_cells && seen < target) {
      seen += cl->cell_start[cells[k] + 1] - cl->cell_start[cells[k]];
      ++k;
    }
    block_start[b] = k;
  }
  block_start[nblocks] = num_cells;
}

/* Runs one pass of the scan over all cells, one block per thread. Count pass (bond_j NULL):
 * family sizes to count[], stopping early once more than `limit` bonds are found (sets *over).
 * Fill pass: families to bond_j. Returns an error if a thread could not allocate its buffers. */
static int scan_pass(pdk_ctx *ctx, const scan_shared *sh, const int64_t *cells,
                     const int64_t *block_start, int nblocks, pdk_index *count,
                     const pdk_bond_index *bond_start, pdk_index *bond_j, int64_t limit,
                     int *over) {
  int failed = 0, stop = 0;
  int64_t found = 0;
  const int nthreads = ctx->num_threads;
#pragma omp parallel default(none)                                                                 \
    shared(sh, cells, block_start, nblocks, count, bond_start, bond_j, limit, failed, stop, found) \
        num_threads(nthreads)
  {
    scan_buf t;
    const int bad = pdk_families_scan_buf_alloc(&t, sh);
    if (bad) {
#pragma omp atomic write
      failed = 1;
    }
#pragma omp for schedule(static)
    for (int b = 0; b < nblocks; ++b) {
      if (bad) continue;
      for (int64_t k = block_start[b]; k < block_start[b + 1]; ++k) {
        int halt;
#pragma omp atomic read
        halt = stop;
        if (halt) break;
        const int64_t nc = pdk_families_scan_cell(sh, cells[k], &t, count, bond_start, bond_j);
        if (!bond_j) {
          int64_t now;
#pragma omp atomic capture
          now = found += nc;
          if (now > limit) {
#pragma omp atomic write
            stop = 1;
          }
        }
      }
    }
    pdk_families_scan_buf_free(&t);
  }
  if (over) *over = stop;
  PDK_CHECK(!failed, ctx, PDK_ERR_MEMORY,
            "out of memory allocating the neighbour-scan buffers (%d candidates per cell)",
            (int)sh->max_cand);
  return PDK_SUCCESS;
}

/* cells: [num_cells] the non-empty cells in the order of their first particle, so a store
 * sorted by cell (Morton) is walked in index order. malloc'ed; the caller frees. */
static int order_cells(pdk_ctx *ctx, const pdk_cells *cl, int64_t **cells, int64_t *num_cells) {
  uint8_t *seen = calloc((size_t)cl->num_cells, 1);
  int64_t *order = malloc((size_t)cl->n * sizeof *order);
  if (!seen || !order) {
    free(seen);
    free(order);
    return pdk_ctx_error_set(ctx, PDK_ERR_MEMORY, __func__, "out of memory ordering %lld cells",
                             (long long)cl->num_cells);
  }
  int64_t m = 0;
  for (pdk_index i = 0; i < cl->n; ++i) {
    const pdk_index c = cl->cell_of[i];
    if (!seen[c]) seen[c] = 1, order[m++] = c;
  }
  free(seen);
  *cells = order;
  *num_cells = m;
  return PDK_SUCCESS;
}

int pdk_families_build(pdk_particles *p, const pdk_families_opts *opts_in, pdk_families **out) {
  int err = PDK_SUCCESS;
  pdk_families_opts opts = opts_in ? *opts_in : pdk_families_opts_default();
  pdk_ctx *ctx = pdk_particles_ctx(p);
  pdk_cells *cl = NULL;
  crack *cracks = NULL;
  int64_t *cells = NULL, *block_start = NULL;
  pdk_index *count = NULL;
  pdk_families *f = NULL;
  PDK_CHECK_ARG(out, ctx);
  *out = NULL;
  PDK_CHECK_ARG(p, NULL);

  PDK_CHECK(!opts.horizon_field, ctx, PDK_ERR_UNSUPPORTED,
            "opts.horizon_field = '%s': per-particle horizons are not supported yet; leave "
            "horizon_field NULL and give a uniform opts.horizon",
            opts.horizon_field);
  PDK_CHECK(isfinite(opts.horizon) && opts.horizon > 0, ctx, PDK_ERR_ARG,
            "the horizon must be a positive finite length, got %g", opts.horizon);
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const int nthreads = ctx->num_threads;
  PDK_CALL(pdk_cracks_prepare(ctx, dim, &opts, &cracks));
  PDK_CALL_GOTO(pdk_cells_build(p, opts.horizon, &cl));

  int64_t num_cells = 0;
  PDK_CALL_GOTO(order_cells(ctx, cl, &cells, &num_cells));
  {
    scan_shared sh;
    memset(&sh, 0, sizeof sh);
    sh.cl = cl;
    sh.dim = dim;
    sh.r2max = opts.horizon * opts.horizon * (1.0 + PDK_HORIZON_RTOL);
    sh.prune2 = sh.r2max * (1.0 + 1e-9);
    sh.reach = sqrt(sh.prune2);
    for (int a = 0; a < dim; ++a)
      sh.X[a] = pdk_particles_X(p, a);
    sh.cracks = cracks;
    sh.num_cracks = opts.num_precracks;
    sh.kern = ctx->kernels;

    /* Bound the bond count before allocating for it. */
    const size_t limit_bytes = opts.max_bytes ? opts.max_bytes : default_max_bytes();
    const double limit_bonds_d =
        ((double)limit_bytes - families_bytes(n, 0)) / (double)sizeof(pdk_index);
    const int64_t limit_bonds =
        limit_bonds_d < 0 ? -1 : (limit_bonds_d > 4e18 ? INT64_MAX : (int64_t)limit_bonds_d);
    int64_t upper = 0;
    bound_upper(cl, cells, num_cells, nthreads, &upper, &sh.max_cand);
    const int need_count = upper > limit_bonds;
    if (need_count) {
      int64_t lower = 0;
      PDK_CALL_GOTO(bound_lower(ctx, cl, cells, num_cells, sh.r2max, &lower));
      PDK_CHECK_GOTO(lower <= limit_bonds, ctx, PDK_ERR_MEMORY,
                     "the families would hold at least %lld directed bonds (%.4g bytes for bond_j "
                     "and bond_start), more than the limit of %zu bytes (opts.max_bytes; 0 means "
                     "3/4 of RAM); use a smaller horizon than %g",
                     (long long)lower, families_bytes(n, (double)lower), limit_bytes, opts.horizon);
    }

    const int nblocks = nthreads;
    block_start = malloc((size_t)(nblocks + 1) * sizeof *block_start);
    count = pdk_alloc_aligned((size_t)n, sizeof *count);
    f = calloc(1, sizeof *f);
    PDK_CHECK_GOTO(block_start && count && f, ctx, PDK_ERR_MEMORY,
                   "out of memory building the families of %d particles", (int)n);
    split_blocks(cl, cells, num_cells, nblocks, block_start);

    /* Pass 1: family sizes (stops early past the limit when the upper bound did not clear it). */
    int over = 0;
    PDK_CALL_GOTO(scan_pass(ctx, &sh, cells, block_start, nblocks, count, NULL, NULL,
                            need_count ? limit_bonds : INT64_MAX, &over));
    PDK_CHECK_GOTO(!over, ctx, PDK_ERR_MEMORY,
                   "the families would hold more than %lld directed bonds (%.4g bytes for bond_j "
                   "and bond_start), more than the limit of %zu bytes (opts.max_bytes; 0 means 3/4 "
                   "of RAM); use a smaller horizon than %g",
                   (long long)limit_bonds, families_bytes(n, (double)limit_bonds), limit_bytes,
                   opts.horizon);

    f->ctx = ctx;
    f->n = n;
    f->horizon = opts.horizon;
    f->bond_start = pdk_alloc_aligned((size_t)n + 1, sizeof *f->bond_start);
    PDK_CHECK_GOTO(f->bond_start, ctx, PDK_ERR_MEMORY,
                   "out of memory for bond_start of %d particles", (int)n);
    for (pdk_index i = 0; i < n; ++i)
      f->bond_start[i + 1] = f->bond_start[i] + count[i];
    f->num_bonds = f->bond_start[n];
    PDK_CHECK_GOTO(f->num_bonds <= limit_bonds, ctx, PDK_ERR_MEMORY,
                   "the families would hold %lld directed bonds (%.4g bytes for bond_j and "
                   "bond_start), more than the limit of %zu bytes (opts.max_bytes; 0 means 3/4 of "
                   "RAM); use a smaller horizon than %g",
                   (long long)f->num_bonds, families_bytes(n, (double)f->num_bonds), limit_bytes,
                   opts.horizon);
    f->bond_j = alloc_bond_j((size_t)f->num_bonds + 1);
    PDK_CHECK_GOTO(f->bond_j, ctx, PDK_ERR_MEMORY,
                   "out of memory allocating %lld directed bonds (%.4g bytes)",
                   (long long)f->num_bonds, families_bytes(n, (double)f->num_bonds));

    /* Pass 2: the families. */
    PDK_CALL_GOTO(scan_pass(ctx, &sh, cells, block_start, nblocks, count, f->bond_start, f->bond_j,
                            INT64_MAX, NULL));
  }
  PDK_CALL_GOTO(copy_precracks(ctx, f, dim, &opts));
  *out = f;
  f = NULL;
cleanup:
  pdk_families_destroy(&f);
  pdk_cells_destroy(&cl);
  free(cracks);
  free(cells);
  free(block_start);
  pdk_free_aligned(count);
  return err;
}

void pdk_families_destroy(pdk_families **f) {
  if (!f || !*f) return;
  pdk_free_aligned((*f)->bond_start);
  pdk_free_aligned((*f)->bond_j);
  free((*f)->precracks);
  free((*f)->precrack_vertices);
  free(*f);
  *f = NULL;
}

double pdk_families_cell_edge(pdk_particles *p, double horizon) {
  double edge = 0;
  if (!p) return 0.0;
  if (pdk_cells_edge(p, horizon, &edge)) return 0.0;
  return edge;
}

pdk_index pdk_families_num_particles(const pdk_families *f) { return f ? f->n : 0; }
pdk_bond_index pdk_families_num_bonds(const pdk_families *f) { return f ? f->num_bonds : 0; }
const pdk_bond_index *pdk_families_bond_start(const pdk_families *f) {
  return f ? f->bond_start : NULL;
}
const pdk_index *pdk_families_bond_j(const pdk_families *f) { return f ? f->bond_j : NULL; }
double pdk_families_horizon(const pdk_families *f) { return f ? f->horizon : NAN; }
size_t pdk_families_memory_bytes(const pdk_families *f) {
  if (!f) return 0;
  return (size_t)(f->n + 1) * sizeof *f->bond_start + (size_t)f->num_bonds * sizeof *f->bond_j;
}

int pdk_families_precracks(const pdk_families *f, const pdk_precrack **out) {
  *out = f->num_precracks > 0 ? f->precracks : NULL;
  return f->num_precracks;
}

int pdk_families_remove_cut(pdk_families *f, int dim, const double *const X[3],
                            const pdk_precrack *precracks, int num_precracks) {
  pdk_ctx *ctx = f->ctx;
  if (num_precracks <= 0) return PDK_SUCCESS;
  pdk_families_opts o = pdk_families_opts_default();
  o.precracks = precracks;
  o.num_precracks = num_precracks;
  crack *cr = NULL;
  PDK_CALL(pdk_cracks_prepare(ctx, dim, &o, &cr));
  pdk_bond_index kept = 0, start = 0;
  for (pdk_index i = 0; i < f->n; ++i) {
    const pdk_bond_index end = f->bond_start[i + 1];
    double xi[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a)
      xi[a] = X[a][i];
    for (pdk_bond_index b = start; b < end; ++b) {
      const pdk_index j = f->bond_j[b];
      double xj[3] = {0, 0, 0};
      for (int a = 0; a < dim; ++a)
        xj[a] = X[a][j];
      int cut = 0;
      for (int k = 0; k < num_precracks && !cut; ++k) {
        const crack *c = &cr[k];
        int touch = 1;
        for (int a = 0; a < dim; ++a)
          touch = touch && min_d(xi[a], xj[a]) <= c->hi[a] && max_d(xi[a], xj[a]) >= c->lo[a];
        if (!touch) continue;
        const int si = pdk_crack_side(c, dim, xi), sj = pdk_crack_side(c, dim, xj);
        if (si * sj > 0) continue;
        if (i < j)
          cut = dim == 2 ? pdk_crack_cuts2(c, xi, xj, si, sj) : pdk_crack_cuts3(c, xi, xj, si, sj);
        else
          cut = dim == 2 ? pdk_crack_cuts2(c, xj, xi, sj, si) : pdk_crack_cuts3(c, xj, xi, sj, si);
      }
      if (!cut) f->bond_j[kept++] = j;
    }
    start = end;
    f->bond_start[i + 1] = kept;
  }
  f->num_bonds = kept;
  free(cr);
  return PDK_SUCCESS;
}

int pdk_families_from_csr(pdk_ctx *ctx, pdk_index n, double horizon,
                          const pdk_bond_index *bond_start, const pdk_index *bond_j,
                          pdk_families **out) {
  *out = NULL;
  PDK_CHECK(n >= 0 && bond_start[0] == 0, ctx, PDK_ERR_IO,
            "families: bond_start[0] is %lld, expected 0", (long long)bond_start[0]);
  for (pdk_index i = 0; i < n; ++i)
    PDK_CHECK(bond_start[i + 1] >= bond_start[i], ctx, PDK_ERR_IO,
              "families: bond_start decreases at particle %d (%lld then %lld)", (int)i,
              (long long)bond_start[i], (long long)bond_start[i + 1]);
  const pdk_bond_index nb = bond_start[n];
  for (pdk_index i = 0; i < n; ++i)
    for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b)
      PDK_CHECK(bond_j[b] >= 0 && bond_j[b] < n && bond_j[b] != i, ctx, PDK_ERR_IO,
                "families: bond %lld of particle %d names neighbour %d (particles 0..%d, no self "
                "bonds)",
                (long long)b, (int)i, (int)bond_j[b], (int)n - 1);
  pdk_families *f = calloc(1, sizeof *f);
  PDK_CHECK(f, ctx, PDK_ERR_MEMORY, "out of memory for families of %d particles", (int)n);
  f->ctx = ctx;
  f->n = n;
  f->horizon = horizon;
  f->num_bonds = nb;
  f->bond_start = pdk_alloc_aligned((size_t)n + 1, sizeof *f->bond_start);
  f->bond_j = alloc_bond_j((size_t)nb + 1);
  if (!f->bond_start || !f->bond_j) {
    pdk_families_destroy(&f);
    return pdk_ctx_error_set(ctx, PDK_ERR_MEMORY, __func__,
                             "out of memory for families of %lld bonds", (long long)nb);
  }
  memcpy(f->bond_start, bond_start, ((size_t)n + 1) * sizeof *bond_start);
  if (nb) memcpy(f->bond_j, bond_j, (size_t)nb * sizeof *bond_j);
  *out = f;
  return PDK_SUCCESS;
}
