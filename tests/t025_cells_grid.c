/* Cell list invariants on the three binning paths: dense (a lattice), sparse (two clusters far
 * apart: the grid would have ~1e13 cells, stored are only the occupied ones, edge not coarsened),
 * and coarsened (a box wider than 2^21 horizons). For each: every particle in exactly one slot,
 * slots ascending within a cell, cell_of consistent, keys ascending, every particle inside its
 * cell's grid box, neighbour lists equal to a direct search over all cells, sorted coordinates
 * equal to the store's; the edge just above the horizon; and after a Morton reorder with
 * pdk_cells_edge every cell is one contiguous index range.
 * labels: unit */
#include <stdint.h>

#include "space/cells.h"
#include "test_util.h"

static uint64_t rng_next(uint64_t *s) {
  uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
static double rng_unit(uint64_t *s) { return (double)(rng_next(s) >> 11) * 0x1p-53; }

static void check_cells(const char *what, pdk_particles *p, const pdk_cells *cl, double h) {
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  T_ASSERT(cl->n == n && cl->dim == dim, "%s", what);
  T_ASSERT(cl->edge > h, "%s: edge %.17g not above the horizon %.17g", what, cl->edge, h);
  for (int a = 0; a < 3; ++a)
    T_ASSERT(cl->num[a] >= 1 && cl->num[a] <= PDK_CELLS_MAX_AXIS, "%s: %lld cells on axis %d", what,
             (long long)cl->num[a], a);
  T_ASSERT(cl->cell_start[0] == 0 && cl->cell_start[cl->num_cells] == n, "%s", what);
  uint8_t *seen = calloc((size_t)n, 1);
  for (pdk_index c = 0; c < cl->num_cells; ++c) {
    T_ASSERT(cl->cell_start[c + 1] > cl->cell_start[c], "%s: cell %d is empty", what, (int)c);
    if (c > 0) T_ASSERT(cl->key[c] > cl->key[c - 1], "%s: keys not ascending at %d", what, (int)c);
    const int64_t k = cl->key[c];
    const int64_t cc[3] = {k % cl->num[0], (k / cl->num[0]) % cl->num[1],
                           k / (cl->num[0] * cl->num[1])};
    for (pdk_index s = cl->cell_start[c]; s < cl->cell_start[c + 1]; ++s) {
      const pdk_index i = cl->slot_id[s];
      T_ASSERT(i >= 0 && i < n && !seen[i], "%s: slot %d holds %d", what, (int)s, (int)i);
      seen[i] = 1;
      if (s > cl->cell_start[c])
        T_ASSERT(i > cl->slot_id[s - 1], "%s: cell %d not ascending", what, (int)c);
      T_ASSERT(cl->cell_of[i] == c, "%s: cell_of[%d] = %d, slot in %d", what, (int)i,
               (int)cl->cell_of[i], (int)c);
      for (int a = 0; a < dim; ++a) {
        const double x = pdk_particles_X(p, a)[i];
        T_ASSERT(cl->x[a][s] == x, "%s: sorted coordinate differs", what);
        /* inside its cell's box, up to the round-off of the cell coordinate */
        const double u = (x - cl->lo[a]) / cl->edge;
        T_ASSERT(u >= cc[a] - 1e-9 && u < cc[a] + 1 + 1e-9,
                 "%s: particle %d at u = %.17g in cell %lld", what, (int)i, u, (long long)cc[a]);
      }
    }
    /* neighbours: every occupied cell whose coordinates differ by at most 1, found directly */
    int expect = 0, got = 0;
    for (pdk_index c2 = 0; c2 < cl->num_cells; ++c2) {
      const int64_t k2 = cl->key[c2];
      const int64_t d[3] = {k2 % cl->num[0] - cc[0], (k2 / cl->num[0]) % cl->num[1] - cc[1],
                            k2 / (cl->num[0] * cl->num[1]) - cc[2]};
      if (llabs(d[0]) > 1 || llabs(d[1]) > 1 || llabs(d[2]) > 1) continue;
      ++expect;
      int q = (int)((d[2] + (dim == 3)) * 9 + (d[1] + 1) * 3 + (d[0] + 1));
      T_ASSERT(cl->neighbours[(size_t)c * PDK_CELLS_NB + q] == c2,
               "%s: cell %d neighbour %d is %d, "
               "expected %d",
               what, (int)c, q, (int)cl->neighbours[(size_t)c * PDK_CELLS_NB + q], (int)c2);
    }
    for (int q = 0; q < PDK_CELLS_NB; ++q)
      got += cl->neighbours[(size_t)c * PDK_CELLS_NB + q] >= 0;
    T_ASSERT(got == expect, "%s: cell %d lists %d neighbours, %d exist", what, (int)c, got, expect);
  }
  for (pdk_index i = 0; i < n; ++i)
    T_ASSERT(seen[i], "%s: particle %d in no slot", what, (int)i);
  free(seen);
}

static pdk_cells *build(pdk_ctx *ctx, pdk_particles *p, double h) {
  pdk_cells *cl = NULL;
  T_OK(ctx, pdk_cells_build(p, h, &cl));
  return cl;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  uint64_t seed = 99;

  /* Dense: a 3-D lattice; then Morton-reordered with the cell edge, every cell contiguous. */
  {
    const int side = 17, n = side * side * side;
    const double h = 3.015 * 0.1;
    pdk_particles *p = NULL;
    T_OK(ctx, pdk_particles_create(ctx, 3, n, &p));
    for (int q = 0; q < n; ++q) {
      pdk_particles_X(p, 0)[q] = 1.5 + 0.1 * (q % side);
      pdk_particles_X(p, 1)[q] = -2.0 + 0.1 * ((q / side) % side);
      pdk_particles_X(p, 2)[q] = 0.25 + 0.1 * (q / (side * side));
    }
    pdk_cells *cl = build(ctx, p, h);
    T_ASSERT(!cl->sparse, "a lattice bins densely");
    T_ASSERT(cl->edge < h * (1 + 1e-7), "edge %.17g for horizon %.17g", cl->edge, h);
    check_cells("dense lattice", p, cl, h);
    double edge = 0;
    T_OK(ctx, pdk_cells_edge(p, h, &edge));
    T_ASSERT(edge == cl->edge, "pdk_cells_edge agrees with the build");
    pdk_cells_destroy(&cl);
    T_OK(ctx, pdk_particles_reorder_morton(p, edge, NULL));
    cl = build(ctx, p, h);
    check_cells("dense lattice, Morton order", p, cl, h);
    for (pdk_index c = 0; c < cl->num_cells; ++c)
      for (pdk_index s = cl->cell_start[c]; s < cl->cell_start[c + 1]; ++s)
        T_ASSERT(cl->slot_id[s] == cl->slot_id[cl->cell_start[c]] + (s - cl->cell_start[c]),
                 "after the Morton reorder cell %d is not a contiguous index range", (int)c);
    pdk_cells_destroy(&cl);
    pdk_cells_destroy(&cl); /* NULL accepted */
    pdk_particles_destroy(&p);
  }
  /* Sparse: two clusters 1e4 horizons apart on every axis (1e12 grid cells). */
  for (int dim = 2; dim <= 3; ++dim) {
    const int n = 4000;
    const double h = 0.05;
    pdk_particles *p = NULL;
    T_OK(ctx, pdk_particles_create(ctx, dim, n, &p));
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < dim; ++a)
        pdk_particles_X(p, a)[i] = (i % 2 ? 500.0 : 0.0) + rng_unit(&seed);
    pdk_cells *cl = build(ctx, p, h);
    T_ASSERT(cl->sparse, "%d-D: two far clusters bin sparsely", dim);
    T_ASSERT(cl->edge < h * (1 + 1e-7), "%d-D: sparse binning keeps the edge: %.17g", dim,
             cl->edge);
    T_ASSERT(cl->num_cells <= n, "%d-D: only occupied cells stored", dim);
    check_cells(dim == 2 ? "sparse 2-D" : "sparse 3-D", p, cl, h);
    pdk_cells_destroy(&cl);
    pdk_particles_destroy(&p);
  }
  /* Coarsened: 3 * 2^21 horizons wide along x. */
  {
    const int n = 500;
    const double h = 1.0, width = 3.0 * (1 << 21);
    pdk_particles *p = NULL;
    T_OK(ctx, pdk_particles_create(ctx, 3, n, &p));
    for (int i = 0; i < n; ++i) {
      pdk_particles_X(p, 0)[i] = width * rng_unit(&seed);
      pdk_particles_X(p, 1)[i] = 10 * rng_unit(&seed);
      pdk_particles_X(p, 2)[i] = 10 * rng_unit(&seed);
    }
    pdk_particles_X(p, 0)[0] = 0;
    pdk_particles_X(p, 0)[1] = width;
    pdk_cells *cl = build(ctx, p, h);
    T_ASSERT(cl->edge > width / PDK_CELLS_MAX_AXIS, "coarsened edge %g", cl->edge);
    check_cells("coarsened", p, cl, h);
    pdk_cells_destroy(&cl);
    pdk_particles_destroy(&p);
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
