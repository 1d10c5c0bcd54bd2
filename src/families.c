/* Bond families: neighbour search over a cell list, pre-cracks, CSR storage. See
 * include/pdk/families.h for the neighbour rule and the guarantees.
 *
 * Storage:
 *   bond_start: [n+1] int64; bonds of particle i are bond_start[i] .. bond_start[i+1]-1
 *   bond_j:     [num_bonds] int32; the neighbour of each bond, ascending within a family
 *
 * Method.
 *  1. Cells (src/cells.c): grid of edge slightly above the horizon; the occupied cells, each with
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
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "cells.h"
#include "families_impl.h"
#include "kernels.h"

/* Orientation filters below bound the round-off of a specific sequence of roundings; fused
 * multiply-adds would change it. */
PDK_KERNEL_FP_EXACT

struct pdk_families {
  pdk_ctx *ctx;
  pdk_index n;
  double horizon;             /* [length] */
  pdk_bond_index num_bonds;   /* directed bonds */
  pdk_bond_index *bond_start; /* [n+1] */
  pdk_index *bond_j;          /* [num_bonds] (allocated for at least one entry) */
  int num_precracks;          /* the pre-cracks of the build, copied (src/families_impl.h) */
  pdk_precrack *precracks;
  double *precrack_vertices;
};

pdk_families_opts pdk_families_opts_default(void) {
  pdk_families_opts o;
  memset(&o, 0, sizeof o);
  return o;
}

/* max and min of finite numbers: one instruction each, where fmax/fmin are library calls that
 * handle NaN. */
static inline double max_d(double a, double b) { return a > b ? a : b; }
static inline double min_d(double a, double b) { return a < b ? a : b; }

/* ---- exact orientation predicates ------------------------------------------------------------
 * orient2d(a, b, c) = det [a - c; b - c] and orient3d(a, b, c, d) = det [a - d; b - d; c - d], as
 * exact signs. A floating-point evaluation with Shewchuk's forward error bound (doubled here for
 * margin) decides almost every case; the rest are evaluated exactly as sums of products of the
 * input coordinates, each product split into non-overlapping doubles with fma, summed into a
 * non-overlapping expansion (Shewchuk's Grow-Expansion) whose largest component gives the sign.
 * Exact as long as no product underflows or overflows (|coordinates| within 1e-70 .. 1e70). */

/* Adds b to the expansion e[0..m-1] (non-overlapping, increasing magnitude, no zeros); returns
 * the new length. */
static int expansion_grow(double *e, int m, double b) {
  int k = 0;
  double q = b;
  for (int i = 0; i < m; ++i) {
    double sum = q + e[i];
    double bv = sum - q, av = sum - bv;
    double err = (q - av) + (e[i] - bv);
    q = sum;
    if (err != 0.0) e[k++] = err;
  }
  if (q != 0.0) e[k++] = q;
  return k;
}

/* Adds sign * a * b to the expansion, exactly. */
static int expansion_add_product(double *e, int m, double sign, double a, double b) {
  double p = a * b, err = fma(a, b, -p);
  m = expansion_grow(e, m, sign * p);
  return expansion_grow(e, m, sign * err);
}

/* Adds sign * a * b * c to the expansion, exactly. */
static int expansion_add_triple(double *e, int m, double sign, double a, double b, double c) {
  double p = a * b, err = fma(a, b, -p);
  m = expansion_add_product(e, m, sign, p, c);
  return expansion_add_product(e, m, sign, err, c);
}

static int expansion_sign(const double *e, int m) { return m == 0 ? 0 : (e[m - 1] > 0 ? 1 : -1); }

static int orient2d_sign(const double a[2], const double b[2], const double c[2]) {
  const double eps = 0x1p-53;
  double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  double detright = (a[1] - c[1]) * (b[0] - c[0]);
  double det = detleft - detright;
  double bound = 2.0 * (3.0 + 16.0 * eps) * eps * (fabs(detleft) + fabs(detright));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  /* det = ax by - ax cy - ay bx + ay cx + bx cy - by cx */
  double e[12];
  int m = 0;
  m = expansion_add_product(e, m, 1, a[0], b[1]);
  m = expansion_add_product(e, m, -1, a[0], c[1]);
  m = expansion_add_product(e, m, -1, a[1], b[0]);
  m = expansion_add_product(e, m, 1, a[1], c[0]);
  m = expansion_add_product(e, m, 1, b[0], c[1]);
  m = expansion_add_product(e, m, -1, b[1], c[0]);
  return expansion_sign(e, m);
}

/* Adds sign * det [p; q; r] (3 x 3, rows p, q, r) to the expansion. */
static int expansion_add_det3(double *e, int m, double sign, const double p[3], const double q[3],
                              const double r[3]) {
  m = expansion_add_triple(e, m, sign, p[0], q[1], r[2]);
  m = expansion_add_triple(e, m, -sign, p[0], q[2], r[1]);
  m = expansion_add_triple(e, m, -sign, p[1], q[0], r[2]);
  m = expansion_add_triple(e, m, sign, p[1], q[2], r[0]);
  m = expansion_add_triple(e, m, sign, p[2], q[0], r[1]);
  m = expansion_add_triple(e, m, -sign, p[2], q[1], r[0]);
  return m;
}

static int orient3d_sign(const double a[3], const double b[3], const double c[3],
                         const double d[3]) {
  const double eps = 0x1p-53;
  double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  double bc = bdy * cdz - bdz * cdy, ca = cdy * adz - cdz * ady, ab = ady * bdz - adz * bdy;
  double det = adx * bc + bdx * ca + cdx * ab;
  double permanent = (fabs(bdy * cdz) + fabs(bdz * cdy)) * fabs(adx) +
                     (fabs(cdy * adz) + fabs(cdz * ady)) * fabs(bdx) +
                     (fabs(ady * bdz) + fabs(adz * bdy)) * fabs(cdx);
  double bound = 2.0 * (7.0 + 56.0 * eps) * eps * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  /* det [a-d; b-d; c-d] = det [a 1; b 1; c 1; d 1] = -|b c d| + |a c d| - |a b d| + |a b c| */
  double e[96];
  int m = 0;
  m = expansion_add_det3(e, m, -1, b, c, d);
  m = expansion_add_det3(e, m, 1, a, c, d);
  m = expansion_add_det3(e, m, -1, a, b, d);
  m = expansion_add_det3(e, m, 1, a, b, c);
  return expansion_sign(e, m);
}

/* ---- pre-cracks ------------------------------------------------------------------------------ */

typedef struct crack {
  int num_vertices;
  const double *v;     /* [num_vertices][dim], caller-owned */
  double lo[3], hi[3]; /* bounding box */
  /* 3-D only */
  double normal[3];   /* Newell normal (twice the area vector) */
  int plane[3];       /* three vertices spanning the plane, for the exact side test */
  int axis_u, axis_w; /* projection axes: the dominant normal axis dropped */
} crack;

/* Checks the pre-crack geometry and precomputes what the bond tests need. */
static int cracks_prepare(pdk_ctx *ctx, int dim, const pdk_families_opts *o, crack **out) {
  *out = NULL;
  PDK_CHECK(o->num_precracks >= 0, ctx, PDK_ERR_ARG, "opts.num_precracks must be >= 0, got %d",
            o->num_precracks);
  if (o->num_precracks == 0) return PDK_SUCCESS;
  PDK_CHECK(o->precracks, ctx, PDK_ERR_ARG, "opts.num_precracks is %d but opts.precracks is NULL",
            o->num_precracks);
  for (int k = 0; k < o->num_precracks; ++k) {
    const pdk_precrack *pc = &o->precracks[k];
    if (dim == 2)
      PDK_CHECK(pc->num_vertices == 2, ctx, PDK_ERR_ARG,
                "pre-crack %d: a 2-D pre-crack is a segment with 2 vertices, got %d vertices", k,
                pc->num_vertices);
    else
      PDK_CHECK(pc->num_vertices >= 3, ctx, PDK_ERR_ARG,
                "pre-crack %d: a 3-D pre-crack is a planar polygon with at least 3 vertices, got "
                "%d vertices",
                k, pc->num_vertices);
    PDK_CHECK(pc->vertices, ctx, PDK_ERR_ARG, "pre-crack %d: vertices is NULL", k);
    for (int v = 0; v < pc->num_vertices; ++v)
      for (int a = 0; a < dim; ++a)
        PDK_CHECK(isfinite(pc->vertices[v * dim + a]), ctx, PDK_ERR_ARG,
                  "pre-crack %d: vertex %d has a non-finite coordinate %d = %g", k, v, a,
                  pc->vertices[v * dim + a]);
  }
  crack *cr = calloc((size_t)o->num_precracks, sizeof *cr);
  PDK_CHECK(cr, ctx, PDK_ERR_MEMORY, "out of memory preparing %d pre-cracks", o->num_precracks);
  for (int k = 0; k < o->num_precracks; ++k) {
    const pdk_precrack *pc = &o->precracks[k];
    crack *c = &cr[k];
    const int nv = pc->num_vertices;
    const double *v = pc->vertices;
    c->num_vertices = nv;
    c->v = v;
    for (int a = 0; a < dim; ++a) {
      c->lo[a] = c->hi[a] = v[a];
      for (int q = 1; q < nv; ++q) {
        c->lo[a] = fmin(c->lo[a], v[q * dim + a]);
        c->hi[a] = fmax(c->hi[a], v[q * dim + a]);
      }
    }
    double size = 0;
    for (int a = 0; a < dim; ++a)
      size = fmax(size, c->hi[a] - c->lo[a]);
    if (dim == 2) {
      if (!(size > 0)) {
        free(cr);
        return pdk_ctx_error_set(ctx, PDK_ERR_ARG, __func__,
                                 "pre-crack %d: its two vertices coincide at (%g, %g); a crack "
                                 "segment needs a positive length",
                                 k, v[0], v[1]);
      }
      continue;
    }
    /* Newell normal: n = sum over edges (v_q - v_{q+1}) x-ish terms, robust for any planar
     * polygon, convex or not; |n| is twice the area. */
    double n[3] = {0, 0, 0};
    for (int q = 0; q < nv; ++q) {
      const double *p0 = &v[q * 3], *p1 = &v[((q + 1) % nv) * 3];
      n[0] += (p0[1] - p1[1]) * (p0[2] + p1[2]);
      n[1] += (p0[2] - p1[2]) * (p0[0] + p1[0]);
      n[2] += (p0[0] - p1[0]) * (p0[1] + p1[1]);
    }
    double nlen = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(size > 0) || !(nlen > 1e-12 * size * size)) {
      free(cr);
      return pdk_ctx_error_set(ctx, PDK_ERR_ARG, __func__,
                               "pre-crack %d: the polygon has zero area (its %d vertices are "
                               "repeated or collinear)",
                               k, nv);
    }
    for (int q = 0; q < nv; ++q) {
      double dist =
          ((v[q * 3] - v[0]) * n[0] + (v[q * 3 + 1] - v[1]) * n[1] + (v[q * 3 + 2] - v[2]) * n[2]) /
          nlen;
      if (!(fabs(dist) <= 1e-9 * size)) {
        free(cr);
        return pdk_ctx_error_set(ctx, PDK_ERR_ARG, __func__,
                                 "pre-crack %d: the polygon is not planar: vertex %d lies %g off "
                                 "the plane of vertex 0 (polygon size %g)",
                                 k, q, dist, size);
      }
    }
    memcpy(c->normal, n, sizeof n);
    /* Plane for the exact side test: vertex 0, the vertex farthest from it, and the vertex that
     * makes the largest triangle with those two. */
    int ib = 0, ic = 0;
    double best = -1;
    for (int q = 1; q < nv; ++q) {
      double d0 = v[q * 3] - v[0], d1 = v[q * 3 + 1] - v[1], d2 = v[q * 3 + 2] - v[2];
      double d = d0 * d0 + d1 * d1 + d2 * d2;
      if (d > best) best = d, ib = q;
    }
    best = -1;
    for (int q = 1; q < nv; ++q) {
      double e1[3], e2[3], x[3];
      for (int a = 0; a < 3; ++a)
        e1[a] = v[ib * 3 + a] - v[a], e2[a] = v[q * 3 + a] - v[a];
      x[0] = e1[1] * e2[2] - e1[2] * e2[1];
      x[1] = e1[2] * e2[0] - e1[0] * e2[2];
      x[2] = e1[0] * e2[1] - e1[1] * e2[0];
      double d = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
      if (d > best) best = d, ic = q;
    }
    c->plane[0] = 0;
    c->plane[1] = ib;
    c->plane[2] = ic;
    int drop = 0;
    for (int a = 1; a < 3; ++a)
      if (fabs(n[a]) > fabs(n[drop])) drop = a;
    c->axis_u = (drop + 1) % 3;
    c->axis_w = (drop + 2) % 3;
  }
  *out = cr;
  return PDK_SUCCESS;
}

/* Exact side (-1, 0, +1) of the point x with respect to the crack's line (2-D: through its two
 * vertices) or plane (3-D: through three of its vertices, see cracks_prepare). */
static int crack_side(const crack *c, int dim, const double x[3]) {
  if (dim == 2) return orient2d_sign(c->v, c->v + 2, x);
  return orient3d_sign(c->v + 3 * c->plane[0], c->v + 3 * c->plane[1], c->v + 3 * c->plane[2], x);
}

/* 1 if the closed bond segment p-q meets the closed crack segment; a bond on the crack's line is
 * not cut. sp, sq: crack_side of p and q. */
static int crack_cuts2(const crack *c, const double p[2], const double q[2], int sp, int sq) {
  if (sp == 0 && sq == 0) return 0;
  if (sp * sq > 0) return 0;
  const double *a = c->v, *b = c->v + 2;
  int o3 = orient2d_sign(p, q, a), o4 = orient2d_sign(p, q, b);
  return o3 * o4 <= 0;
}

/* 1 if the point x (on the crack's plane) lies inside the polygon: crossing number in the
 * projection that drops the dominant normal axis. */
static int crack_contains3(const crack *c, const double x[3]) {
  const int u = c->axis_u, w = c->axis_w, nv = c->num_vertices;
  const double *v = c->v;
  int inside = 0;
  for (int a = 0, b = nv - 1; a < nv; b = a++) {
    double ua = v[a * 3 + u], wa = v[a * 3 + w], ub = v[b * 3 + u], wb = v[b * 3 + w];
    if ((wa > x[w]) != (wb > x[w])) {
      double ucross = ua + (x[w] - wa) * (ub - ua) / (wb - wa);
      if (x[u] < ucross) inside = !inside;
    }
  }
  return inside;
}

/* 1 if the closed bond segment p-q passes through the crack polygon; a bond lying in the crack's
 * plane is not cut. sp, sq: crack_side of p and q (exact); the crossing point is computed in
 * floating point. */
static int crack_cuts3(const crack *c, const double p[3], const double q[3], int sp, int sq) {
  if (sp == 0 && sq == 0) return 0;
  if (sp * sq > 0) return 0;
  double x[3];
  if (sp == 0) {
    memcpy(x, p, sizeof x);
  } else if (sq == 0) {
    memcpy(x, q, sizeof x);
  } else {
    const double *n = c->normal, *o = c->v;
    double dp = (p[0] - o[0]) * n[0] + (p[1] - o[1]) * n[1] + (p[2] - o[2]) * n[2];
    double dq = (q[0] - o[0]) * n[0] + (q[1] - o[1]) * n[1] + (q[2] - o[2]) * n[2];
    double t = dp / (dp - dq);
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    if (!isfinite(t)) t = 0.5;
    for (int k = 0; k < 3; ++k)
      x[k] = p[k] + t * (q[k] - p[k]);
  }
  return crack_contains3(c, x);
}

/* 1 if the box [lo, hi] lies strictly on one side of the crack's line (2-D) or plane (3-D): its
 * corners do (exact signs), and the sign of an affine function over a box is extreme at corners. */
static int crack_box_one_side(const crack *c, int dim, const double lo[3], const double hi[3]) {
  int first = 0;
  for (int k = 0; k < (1 << dim); ++k) {
    const double x[3] = {k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]};
    const int sign = crack_side(c, dim, x);
    if (sign == 0 || (k > 0 && sign != first)) return 0;
    first = sign;
  }
  return 1;
}

/* ---- the scan ------------------------------------------------------------------------------- */

/* Read-only inputs of the scan, shared by all threads. */
typedef struct scan_shared {
  const pdk_cells *cl;
  int dim;
  double r2max;       /* horizon^2 (1 + PDK_HORIZON_RTOL): the neighbour rule */
  double prune2;      /* r2max (1 + 1e-9): keeps every candidate within reach of the cell's box */
  double reach;       /* sqrt(prune2) */
  const double *X[3]; /* [n] store-order coordinates (pre-crack tests) */
  const crack *cracks;
  int num_cracks;
  pdk_kernel_table kern;
  pdk_index max_cand; /* the most candidates any cell can have (3^d cells' occupancy) */
} scan_shared;

/* Per-thread buffers of the scan; all [max_cand] entries unless stated. */
typedef struct scan_buf {
  double *cx, *cy, *cz;       /* candidates of the current cell, ascending particle index */
  pdk_index *cid;             /* [max_cand + PDK_SCAN_OUT_PAD] their particle indices */
  double *tx, *ty, *tz;       /* merge target; swapped with cx.. after a merge */
  pdk_index *tid;             /* [max_cand + PDK_SCAN_OUT_PAD] */
  pdk_index *perm, *perm_tmp; /* merge permutations */
  pdk_index *out;             /* [max_cand + PDK_SCAN_OUT_PAD] one family before it is stored */
  int *crack_list;            /* [num_cracks] cracks that may cut a bond of the current cell */
  int *side_i;                /* [num_cracks] side of the current particle for each listed crack */
  int num_crack_list;
} scan_buf;

static void scan_buf_free(scan_buf *t) {
  if (!t) return;
  void *ptrs[] = {t->cx,  t->cy,   t->cz,       t->cid, t->tx,         t->ty,    t->tz,
                  t->tid, t->perm, t->perm_tmp, t->out, t->crack_list, t->side_i};
  for (size_t k = 0; k < sizeof ptrs / sizeof ptrs[0]; ++k)
    pdk_free_aligned(ptrs[k]);
  memset(t, 0, sizeof *t);
}

static int scan_buf_alloc(scan_buf *t, const scan_shared *sh) {
  const size_t m = (size_t)sh->max_cand + PDK_SCAN_OUT_PAD;
  memset(t, 0, sizeof *t);
  t->cx = pdk_alloc_aligned(m, sizeof(double));
  t->cy = pdk_alloc_aligned(m, sizeof(double));
  t->cz = pdk_alloc_aligned(m, sizeof(double));
  t->tx = pdk_alloc_aligned(m, sizeof(double));
  t->ty = pdk_alloc_aligned(m, sizeof(double));
  t->tz = pdk_alloc_aligned(m, sizeof(double));
  t->cid = pdk_alloc_aligned(m, sizeof(pdk_index));
  t->tid = pdk_alloc_aligned(m, sizeof(pdk_index));
  t->perm = pdk_alloc_aligned(m, sizeof(pdk_index));
  t->perm_tmp = pdk_alloc_aligned(m, sizeof(pdk_index));
  t->out = pdk_alloc_aligned(m, sizeof(pdk_index));
  t->crack_list = pdk_alloc_aligned((size_t)sh->num_cracks + 1, sizeof(int));
  t->side_i = pdk_alloc_aligned((size_t)sh->num_cracks + 1, sizeof(int));
  if (t->cx && t->cy && t->cz && t->tx && t->ty && t->tz && t->cid && t->tid && t->perm &&
      t->perm_tmp && t->out && t->crack_list && t->side_i)
    return 0;
  scan_buf_free(t);
  return 1;
}

/* Sorts the candidate buffer by particle index. It holds num_runs ascending runs starting at
 * run_start[r] (run_start[num_runs] = m); runs are merged pairwise, bottom-up, through a
 * permutation, and the coordinates gathered once at the end. Indices are unique, so the result is
 * the one ascending order. */
static void merge_runs(scan_buf *t, pdk_index m, pdk_index *run_start, int num_runs) {
  pdk_index *a = t->perm, *b = t->perm_tmp;
  for (pdk_index k = 0; k < m; ++k)
    a[k] = k;
  const pdk_index *id = t->cid;
  while (num_runs > 1) {
    int r_out = 0;
    for (int r = 0; r < num_runs; r += 2) {
      pdk_index lo = run_start[r], mid = run_start[r + 1];
      pdk_index hi = r + 2 <= num_runs ? run_start[r + 2] : mid;
      pdk_index i = lo, j = mid, k = lo;
      while (i < mid && j < hi)
        b[k++] = id[a[i]] < id[a[j]] ? a[i++] : a[j++];
      while (i < mid)
        b[k++] = a[i++];
      while (j < hi)
        b[k++] = a[j++];
      run_start[r_out++] = lo;
    }
    run_start[r_out] = m;
    num_runs = r_out;
    pdk_index *s = a;
    a = b;
    b = s;
  }
  for (pdk_index k = 0; k < m; ++k) {
    const pdk_index q = a[k];
    t->tx[k] = t->cx[q];
    t->ty[k] = t->cy[q];
    t->tz[k] = t->cz[q];
    t->tid[k] = t->cid[q];
  }
  double *d;
  d = t->cx, t->cx = t->tx, t->tx = d;
  d = t->cy, t->cy = t->ty, t->ty = d;
  d = t->cz, t->cz = t->tz, t->tz = d;
  pdk_index *p = t->cid;
  t->cid = t->tid, t->tid = p;
}

/* Visits the occupied cells c2 among the 3^d grid cells around cell c (c itself included). */
#define FOR_EACH_NEIGHBOUR_CELL(cl, c, c2, BODY)                                                   \
  do {                                                                                             \
    const pdk_index *nb_ = (cl)->neighbours + (size_t)(c)*PDK_CELLS_NB;                            \
    for (int q_ = 0; q_ < PDK_CELLS_NB; ++q_) {                                                    \
      const int64_t c2 = nb_[q_];                                                                  \
      if (c2 < 0) continue;                                                                        \
      BODY                                                                                         \
    }                                                                                              \
  } while (0)

/* Fills t's candidate buffer for cell c (see the file comment, step 3) and its crack list;
 * returns the number of candidates. */
static pdk_index gather_candidates(const scan_shared *sh, int64_t c, scan_buf *t) {
  const pdk_cells *cl = sh->cl;
  const int dim = sh->dim;
  const pdk_index *cs = cl->cell_start, *slot_id = cl->slot_id;
  const double *x0 = cl->x[0], *x1 = cl->x[1], *x2 = cl->x[2];
  /* Bounding box of the cell's own particles. */
  double blo[3] = {0, 0, 0}, bhi[3] = {0, 0, 0};
  for (int a = 0; a < dim; ++a) {
    const double *x = cl->x[a];
    blo[a] = bhi[a] = x[cs[c]];
    for (pdk_index s = cs[c] + 1; s < cs[c + 1]; ++s) {
      blo[a] = x[s] < blo[a] ? x[s] : blo[a];
      bhi[a] = x[s] > bhi[a] ? x[s] : bhi[a];
    }
  }
  /* Neighbour cells, ordered by their first (smallest) particle index (insertion sort). */
  int64_t nb[27];
  pdk_index first[27];
  int num_nb = 0;
  FOR_EACH_NEIGHBOUR_CELL(cl, c, c2, {
    const pdk_index f = slot_id[cs[c2]];
    int k = num_nb++;
    while (k > 0 && first[k - 1] > f) {
      first[k] = first[k - 1];
      nb[k] = nb[k - 1];
      --k;
    }
    first[k] = f;
    nb[k] = c2;
  });
  /* Copy the candidates within reach of the box (a conservative test: the kernel decides);
   * branch-free append, two candidates per step with SSE2 (baseline x86-64). */
  pdk_index run_start[28];
  int num_runs = 0, sorted = 1;
  pdk_index m = 0;
  double *cx = t->cx, *cy = t->cy, *cz = t->cz;
  pdk_index *cid = t->cid;
  const double prune2 = sh->prune2;
  /* Distance of a point to the box per axis: max(lo - x, 0) + max(x - hi, 0) (at most one term is
   * positive), branch free. */
  const double lo0 = blo[0], lo1 = blo[1], lo2 = blo[2], hi0 = bhi[0], hi1 = bhi[1], hi2 = bhi[2];
  for (int k = 0; k < num_nb; ++k) {
    const pdk_index s0 = cs[nb[k]], s1 = cs[nb[k] + 1];
    const pdk_index m0 = m;
    if (dim == 3) {
      pdk_index s = s0;
#if defined(__SSE2__)
      /* two candidates per step; the same arithmetic as the scalar loop below */
      const __m128d vlo0 = _mm_set1_pd(lo0), vlo1 = _mm_set1_pd(lo1), vlo2 = _mm_set1_pd(lo2);
      const __m128d vhi0 = _mm_set1_pd(hi0), vhi1 = _mm_set1_pd(hi1), vhi2 = _mm_set1_pd(hi2);
      const __m128d zero = _mm_setzero_pd(), vprune2 = _mm_set1_pd(prune2);
      for (; s + 2 <= s1; s += 2) {
        const __m128d px = _mm_loadu_pd(x0 + s), py = _mm_loadu_pd(x1 + s),
                      pz = _mm_loadu_pd(x2 + s);
        const __m128d ex = _mm_add_pd(_mm_max_pd(_mm_sub_pd(vlo0, px), zero),
                                      _mm_max_pd(_mm_sub_pd(px, vhi0), zero));
        const __m128d ey = _mm_add_pd(_mm_max_pd(_mm_sub_pd(vlo1, py), zero),
                                      _mm_max_pd(_mm_sub_pd(py, vhi1), zero));
        const __m128d ez = _mm_add_pd(_mm_max_pd(_mm_sub_pd(vlo2, pz), zero),
                                      _mm_max_pd(_mm_sub_pd(pz, vhi2), zero));
        const __m128d d2 =
            _mm_add_pd(_mm_add_pd(_mm_mul_pd(ex, ex), _mm_mul_pd(ey, ey)), _mm_mul_pd(ez, ez));
        const int keep = _mm_movemask_pd(_mm_cmple_pd(d2, vprune2));
        const pdk_index id0 = slot_id[s], id1 = slot_id[s + 1];
        _mm_storel_pd(cx + m, px); /* stores from registers: no reload after a store */
        _mm_storel_pd(cy + m, py);
        _mm_storel_pd(cz + m, pz);
        cid[m] = id0;
        m += keep & 1;
        _mm_storeh_pd(cx + m, px);
        _mm_storeh_pd(cy + m, py);
        _mm_storeh_pd(cz + m, pz);
        cid[m] = id1;
        m += keep >> 1;
      }
#endif
      for (; s < s1; ++s) {
        const double px = x0[s], py = x1[s], pz = x2[s];
        const double ex = max_d(lo0 - px, 0.0) + max_d(px - hi0, 0.0);
        const double ey = max_d(lo1 - py, 0.0) + max_d(py - hi1, 0.0);
        const double ez = max_d(lo2 - pz, 0.0) + max_d(pz - hi2, 0.0);
        cx[m] = px;
        cy[m] = py;
        cz[m] = pz;
        cid[m] = slot_id[s];
        m += (ex * ex + ey * ey) + ez * ez <= prune2;
      }
    } else {
      pdk_index s = s0;
#if defined(__SSE2__)
      const __m128d vlo0 = _mm_set1_pd(lo0), vlo1 = _mm_set1_pd(lo1);
      const __m128d vhi0 = _mm_set1_pd(hi0), vhi1 = _mm_set1_pd(hi1);
      const __m128d zero = _mm_setzero_pd(), vprune2 = _mm_set1_pd(prune2);
      for (; s + 2 <= s1; s += 2) {
        const __m128d px = _mm_loadu_pd(x0 + s), py = _mm_loadu_pd(x1 + s);
        const __m128d ex = _mm_add_pd(_mm_max_pd(_mm_sub_pd(vlo0, px), zero),
                                      _mm_max_pd(_mm_sub_pd(px, vhi0), zero));
        const __m128d ey = _mm_add_pd(_mm_max_pd(_mm_sub_pd(vlo1, py), zero),
                                      _mm_max_pd(_mm_sub_pd(py, vhi1), zero));
        const __m128d d2 = _mm_add_pd(_mm_mul_pd(ex, ex), _mm_mul_pd(ey, ey));
        const int keep = _mm_movemask_pd(_mm_cmple_pd(d2, vprune2));
        const pdk_index id0 = slot_id[s], id1 = slot_id[s + 1];
        _mm_storel_pd(cx + m, px);
        _mm_storel_pd(cy + m, py);
        cid[m] = id0;
        m += keep & 1;
        _mm_storeh_pd(cx + m, px);
        _mm_storeh_pd(cy + m, py);
        cid[m] = id1;
        m += keep >> 1;
      }
#endif
      for (; s < s1; ++s) {
        const double px = x0[s], py = x1[s];
        const double ex = max_d(lo0 - px, 0.0) + max_d(px - hi0, 0.0);
        const double ey = max_d(lo1 - py, 0.0) + max_d(py - hi1, 0.0);
        cx[m] = px;
        cy[m] = py;
        cid[m] = slot_id[s];
        m += ex * ex + ey * ey <= prune2;
      }
    }
    if (m > m0) {
      if (num_runs > 0 && cid[m0] < cid[m0 - 1]) sorted = 0;
      run_start[num_runs++] = m0;
    }
  }
  run_start[num_runs] = m;
  if (!sorted) merge_runs(t, m, run_start, num_runs);
  /* Cracks that may cut a bond of this cell: every such bond lies in the cell's box grown by the
   * reach (plus a margin for the rounding of the growth), so a crack whose box misses it, or whose
   * line/plane has that whole box strictly on one side, cuts none. */
  t->num_crack_list = 0;
  if (sh->num_cracks) {
    double glo[3] = {0, 0, 0}, ghi[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a) {
      const double grow = sh->reach * (1.0 + 1e-6) + 1e-12 * (fabs(blo[a]) + fabs(bhi[a]));
      glo[a] = blo[a] - grow;
      ghi[a] = bhi[a] + grow;
    }
    for (int k = 0; k < sh->num_cracks; ++k) {
      const crack *cr = &sh->cracks[k];
      int near = 1;
      for (int a = 0; a < dim; ++a)
        near = near && cr->lo[a] <= ghi[a] && cr->hi[a] >= glo[a];
      if (near && !crack_box_one_side(cr, dim, glo, ghi)) t->crack_list[t->num_crack_list++] = k;
    }
  }
  return m;
}

/* Removes from the family out[0..count-1] of particle i the bonds a listed crack cuts; returns the
 * new count. Each bond is tested with its lower-index end first, so i-j and j-i agree. */
static pdk_index cut_bonds(const scan_shared *sh, scan_buf *t, pdk_index i, pdk_index *out,
                           pdk_index count) {
  const int dim = sh->dim;
  double xi[3] = {0, 0, 0};
  for (int a = 0; a < dim; ++a)
    xi[a] = sh->X[a][i];
  /* the side of i, once per crack; exact, so the same from either end of a bond */
  for (int k = 0; k < t->num_crack_list; ++k)
    t->side_i[k] = crack_side(&sh->cracks[t->crack_list[k]], dim, xi);
  pdk_index kept = 0;
  for (pdk_index b = 0; b < count; ++b) {
    const pdk_index j = out[b];
    double xj[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a)
      xj[a] = sh->X[a][j];
    int cut = 0;
    for (int k = 0; k < t->num_crack_list && !cut; ++k) {
      const crack *cr = &sh->cracks[t->crack_list[k]];
      int touch = 1;
      for (int a = 0; a < dim; ++a)
        touch = touch && min_d(xi[a], xj[a]) <= cr->hi[a] && max_d(xi[a], xj[a]) >= cr->lo[a];
      if (!touch) continue;
      const int si = t->side_i[k], sj = crack_side(cr, dim, xj);
      if (si * sj > 0) continue;
      /* the rest of the test in floating point (3-D crossing point) from the lower index */
      if (i < j)
        cut = dim == 2 ? crack_cuts2(cr, xi, xj, si, sj) : crack_cuts3(cr, xi, xj, si, sj);
      else
        cut = dim == 2 ? crack_cuts2(cr, xj, xi, sj, si) : crack_cuts3(cr, xj, xi, sj, si);
    }
    if (!cut) out[kept++] = j;
  }
  return kept;
}

/* Scans cell c: the family of each of its particles, written to t->out then stored. With
 * bond_j == NULL (count pass) the size of each family goes to count[i]; otherwise the family goes
 * to bond_j + bond_start[i]. Returns the cell's bond count. */
static int64_t scan_cell(const scan_shared *sh, int64_t c, scan_buf *t, pdk_index *count,
                         const pdk_bond_index *bond_start, pdk_index *bond_j) {
  const pdk_cells *cl = sh->cl;
  const pdk_index m = gather_candidates(sh, c, t);
  int64_t total = 0;
  for (pdk_index s = cl->cell_start[c]; s < cl->cell_start[c + 1]; ++s) {
    const pdk_index i = cl->slot_id[s];
    pdk_index nb;
    if (sh->dim == 3)
      nb = sh->kern.family_scan3(m, t->cx, t->cy, t->cz, cl->x[0][s], cl->x[1][s], cl->x[2][s],
                                 sh->r2max, i, t->cid, t->out);
    else
      nb = sh->kern.family_scan2(m, t->cx, t->cy, cl->x[0][s], cl->x[1][s], sh->r2max, i, t->cid,
                                 t->out);
    if (t->num_crack_list) nb = cut_bonds(sh, t, i, t->out, nb);
    if (bond_j)
      memcpy(bond_j + bond_start[i], t->out, (size_t)nb * sizeof *bond_j);
    else
      count[i] = nb;
    total += nb;
  }
  return total;
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
    const int bad = scan_buf_alloc(&t, sh);
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
        const int64_t nc = scan_cell(sh, cells[k], &t, count, bond_start, bond_j);
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
    scan_buf_free(&t);
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
  PDK_CALL(cracks_prepare(ctx, dim, &opts, &cracks));
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
  PDK_CALL(cracks_prepare(ctx, dim, &o, &cr));
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
        const int si = crack_side(c, dim, xi), sj = crack_side(c, dim, xj);
        if (si * sj > 0) continue;
        if (i < j)
          cut = dim == 2 ? crack_cuts2(c, xi, xj, si, sj) : crack_cuts3(c, xi, xj, si, sj);
        else
          cut = dim == 2 ? crack_cuts2(c, xj, xi, sj, si) : crack_cuts3(c, xj, xi, sj, si);
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
