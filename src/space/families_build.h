/* Private to the family build (src/space/families.c: the driver, bounds, storage; src/space/families_scan.c:
 * the candidate scan of a cell; src/space/precrack.c: pre-crack geometry and exact orientation
 * predicates). Include it last: it turns off floating-point contraction for the rest of the file.
 */
#ifndef PDK_FAMILIES_BUILD_H
#define PDK_FAMILIES_BUILD_H

#include "cells.h"
#include "families_impl.h"
#include "kernels.h"
#include "pdk/ctx.h"
#include "pdk/families.h"

/* Orientation filters below bound the round-off of a specific sequence of roundings; fused
 * multiply-adds would change it. */
PDK_KERNEL_FP_EXACT

/* max and min of finite numbers: one instruction each, where fmax/fmin are library calls that
 * handle NaN. */
static inline double max_d(double a, double b) { return a > b ? a : b; }
static inline double min_d(double a, double b) { return a < b ? a : b; }

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
int pdk_cracks_prepare(pdk_ctx *ctx, int dim, const pdk_families_opts *o, crack **out);
/* Exact side (-1, 0, +1) of the point x with respect to the crack's line (2-D) or plane (3-D). */
int pdk_crack_side(const crack *c, int dim, const double x[3]);
/* 1 if the closed bond segment p-q meets the closed crack segment (2-D) or polygon (3-D); sp, sq:
 * pdk_crack_side of p and q. */
int pdk_crack_cuts2(const crack *c, const double p[2], const double q[2], int sp, int sq);
int pdk_crack_cuts3(const crack *c, const double p[3], const double q[3], int sp, int sq);
/* 1 if the box [lo, hi] lies strictly on one side of the crack's line (2-D) or plane (3-D). */
int pdk_crack_box_one_side(const crack *c, int dim, const double lo[3], const double hi[3]);


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

void pdk_families_scan_buf_free(scan_buf *t);
int pdk_families_scan_buf_alloc(scan_buf *t, const scan_shared *sh);
/* Scans cell c: the family of each of its particles (to count[i] in the count pass, bond_j == NULL;
 * else to bond_j + bond_start[i]). Returns the cell's bond count. */
int64_t pdk_families_scan_cell(const scan_shared *sh, int64_t c, scan_buf *t, pdk_index *count,
                               const pdk_bond_index *bond_start, pdk_index *bond_j);


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

#endif
