/* Families refuse bad input with the right code and a message naming the value: horizon 0, -1,
 * NaN, Inf; a non-finite coordinate (names the particle); a bond count beyond opts.max_bytes (names
 * the count; a huge horizon over 1e5 particles fails at once, before allocating the bonds);
 * bad pre-crack geometry; a per-particle horizon field (not supported yet).
 * labels: unit */
#include <time.h>

#include "test_util.h"

static pdk_particles *grid(pdk_ctx *ctx, int dim, int side) {
  const int n = dim == 3 ? side * side * side : side * side;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_particles_create(ctx, dim, n, &p));
  for (int q = 0; q < n; ++q) {
    int idx[3] = {q % side, (q / side) % side, q / (side * side)};
    for (int a = 0; a < dim; ++a)
      pdk_particles_X(p, a)[q] = 0.25 + idx[a];
  }
  return p;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  pdk_particles *p2 = grid(ctx, 2, 10), *p3 = grid(ctx, 3, 6);
  pdk_families *f = NULL;
  pdk_families_opts o = pdk_families_opts_default();
  T_ASSERT(o.horizon == 0 && o.horizon_field == NULL && o.precracks == NULL &&
               o.num_precracks == 0 && o.max_bytes == 0,
           "defaults");

  /* Horizon. */
  o.horizon = 0;
  T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_ARG,
          "horizon must be a positive finite length, got 0");
  o.horizon = -1;
  T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_ARG, "got -1");
  o.horizon = NAN;
  T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_ARG, "got nan");
  o.horizon = INFINITY;
  T_FAILS(ctx, pdk_families_build(p3, &o, &f), PDK_ERR_ARG, "got inf");
  T_ASSERT(f == NULL, "no families on failure");
  T_ASSERT(pdk_families_cell_edge(p2, -1.0) == 0.0, "cell edge of a bad horizon");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "got -1"), "%s", pdk_ctx_error_message(ctx));

  /* Non-finite coordinates: the message names the particle. */
  o.horizon = 1.5;
  pdk_particles_X(p3, 1)[77] = NAN;
  T_FAILS(ctx, pdk_families_build(p3, &o, &f), PDK_ERR_NUMERIC, "particle 77");
  pdk_particles_X(p3, 1)[77] = 0.25;
  pdk_particles_X(p2, 0)[5] = -INFINITY;
  T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_NUMERIC, "particle 5 ");
  pdk_particles_X(p2, 0)[5] = 5.25;
  T_OK(ctx, pdk_families_build(p2, &o, &f)); /* repaired: builds */
  pdk_families_destroy(&f);

  /* Per-particle horizon: not supported yet. */
  o.horizon_field = "delta";
  T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_UNSUPPORTED, "horizon_field = 'delta'");
  o.horizon_field = NULL;

  /* Memory limit, small max_bytes: the message names the count. 10 x 10 grid at 1.5: 8 bonds in
   * the bulk, 684 in all (exact; the occupancy bound is far above). */
  o.max_bytes = 1000;
  T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_MEMORY, "directed bonds");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "limit of 1000 bytes") &&
               strstr(pdk_ctx_error_message(ctx), "smaller horizon"),
           "%s", pdk_ctx_error_message(ctx));
  o.max_bytes = 0;

  /* A huge horizon over 1e5 particles: 1e10 bonds (40 GB) exceed any default limit here; the
   * lower bound refuses at once, naming the count, without allocating. */
  {
    pdk_particles *big = grid(ctx, 3, 47); /* 103823 particles */
    const double n = 103823.0;
    o.horizon = 1e3;
    o.max_bytes = (size_t)1 << 30; /* 1 GiB: the limit a 24 GiB CI machine would have is 18 GiB */
    /* processor time, not wall time, which counts other processes' turns on a loaded machine:
     * enumerating the 1e10 pairs instead of bounding their count would take far more */
    const clock_t t0 = clock();
    const size_t rss0 = pdk_peak_memory_bytes();
    char count[64];
    snprintf(count, sizeof count, "at least %.0f directed bonds", n * (n - 1));
    T_FAILS(ctx, pdk_families_build(big, &o, &f), PDK_ERR_MEMORY, count);
    const double cpu = (double)(clock() - t0) / CLOCKS_PER_SEC;
    T_ASSERT(cpu < 2.0, "refusing a huge horizon took %g s of processor time", cpu);
    T_ASSERT(pdk_peak_memory_bytes() < rss0 + ((size_t)200 << 20), "refusing allocated %zu bytes",
             pdk_peak_memory_bytes() - rss0);
    o.max_bytes = 0; /* default limit: 3/4 of RAM, still far below 40 GB on this machine class */
    T_FAILS(ctx, pdk_families_build(big, &o, &f), PDK_ERR_MEMORY, count);
    pdk_particles_destroy(&big);
    o.horizon = 1.5;
  }

  /* Pre-crack geometry. */
  {
    const double seg[4] = {1.0, 1.0, 5.0, 5.0};
    const double seg3[6] = {1.0, 1.0, 5.0, 5.0, 2.0, 2.0};
    const double point[4] = {2.0, 3.0, 2.0, 3.0};
    const double nan_seg[4] = {1.0, NAN, 5.0, 5.0};
    pdk_precrack pc = {2, seg};
    o.precracks = &pc;
    o.num_precracks = 1;
    T_OK(ctx, pdk_families_build(p2, &o, &f)); /* valid */
    pdk_families_destroy(&f);
    pc.num_vertices = 3;
    pc.vertices = seg3;
    T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_ARG, "2 vertices, got 3");
    pc.num_vertices = 2;
    pc.vertices = point;
    T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_ARG, "coincide at (2, 3)");
    pc.vertices = nan_seg;
    T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_ARG,
            "vertex 0 has a non-finite coordinate 1 = nan");
    pc.vertices = NULL;
    T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_ARG, "vertices is NULL");
    o.precracks = NULL;
    T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_ARG, "opts.precracks is NULL");
    o.num_precracks = -2;
    T_FAILS(ctx, pdk_families_build(p2, &o, &f), PDK_ERR_ARG, "got -2");

    const double tri[9] = {1, 1, 1, 4, 1, 1, 1, 4, 1};
    const double two[6] = {1, 1, 1, 4, 1, 1};
    const double line[9] = {1, 1, 1, 2, 2, 2, 3, 3, 3};
    const double warped[12] = {0, 0, 0, 4, 0, 0, 4, 4, 0.5, 0, 4, 0};
    const double inf_tri[9] = {1, 1, 1, 4, INFINITY, 1, 1, 4, 1};
    pdk_precrack pg = {3, tri};
    o.precracks = &pg;
    o.num_precracks = 1;
    T_OK(ctx, pdk_families_build(p3, &o, &f)); /* valid */
    pdk_families_destroy(&f);
    pg.num_vertices = 2;
    pg.vertices = two;
    T_FAILS(ctx, pdk_families_build(p3, &o, &f), PDK_ERR_ARG, "at least 3 vertices, got 2");
    pg.num_vertices = 3;
    pg.vertices = line;
    T_FAILS(ctx, pdk_families_build(p3, &o, &f), PDK_ERR_ARG, "zero area");
    pg.num_vertices = 4;
    pg.vertices = warped;
    T_FAILS(ctx, pdk_families_build(p3, &o, &f), PDK_ERR_ARG, "not planar: vertex");
    pg.num_vertices = 3;
    pg.vertices = inf_tri;
    T_FAILS(ctx, pdk_families_build(p3, &o, &f), PDK_ERR_ARG,
            "vertex 1 has a non-finite coordinate 1 = inf");
    T_ASSERT(f == NULL, "no families on failure");
  }
  pdk_particles_destroy(&p2);
  pdk_particles_destroy(&p3);
  pdk_ctx_destroy(&ctx);
  return 0;
}
