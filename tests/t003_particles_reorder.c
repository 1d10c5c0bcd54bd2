/* Particle store: permutation, compaction, Morton and row reordering carry every registered field
 * and keep the original id; the Morton order is the documented Z-order of cells, the row order the
 * lattice indices z, y, x (stable), and the result is bitwise the same with 1 and 2 threads.
 * labels: unit threads */
#include "test_util.h"

static uint64_t lcg(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return *s >> 11;
}

/* Fills a store with a random cloud and a few fields whose values are functions of the id. */
static pdk_particles *cloud(pdk_ctx *ctx, int dim, pdk_index n, uint64_t seed) {
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_particles_create(ctx, dim, n, &p));
  T_OK(ctx, pdk_particles_field_add(p, "a", PDK_F32, 2));
  T_OK(ctx, pdk_particles_field_add(p, "set:top", PDK_U8, 1));
  T_OK(ctx, pdk_particles_field_add(p, "k", PDK_I32, 1));
  float *a0 = pdk_particles_field_data(p, "a", 0), *a1 = pdk_particles_field_data(p, "a", 1);
  uint8_t *top = pdk_particles_field_data(p, "set:top", 0);
  int32_t *k = pdk_particles_field_data(p, "k", 0);
  double *vol = pdk_particles_volume(p);
  for (pdk_index i = 0; i < n; ++i) {
    for (int c = 0; c < dim; ++c) pdk_particles_X(p, c)[i] = (double)(lcg(&seed) % 100000) * 1e-4;
    a0[i] = (float)i * 0.5f;
    a1[i] = -(float)i;
    top[i] = (uint8_t)(i % 3 == 0);
    k[i] = 7 * i;
    vol[i] = 1.0 + i;
  }
  return p;
}

/* Every field value still matches the function of the particle's original id. */
static void check_carried(pdk_particles *p) {
  pdk_index n = pdk_particles_count(p);
  int64_t *id = pdk_particles_id(p);
  float *a0 = pdk_particles_field_data(p, "a", 0), *a1 = pdk_particles_field_data(p, "a", 1);
  uint8_t *top = pdk_particles_field_data(p, "set:top", 0);
  int32_t *k = pdk_particles_field_data(p, "k", 0);
  double *vol = pdk_particles_volume(p);
  for (pdk_index i = 0; i < n; ++i) {
    int64_t o = id[i];
    T_ASSERT(a0[i] == (float)o * 0.5f && a1[i] == -(float)o, "a at %d (id %lld)", (int)i, (long long)o);
    T_ASSERT(top[i] == (uint8_t)(o % 3 == 0) && k[i] == 7 * o && vol[i] == 1.0 + (double)o, "fields at %d", (int)i);
  }
  /* Padding stays neutral (zero). */
  for (pdk_index i = n; i < pdk_particles_count_padded(p); ++i)
    T_ASSERT(vol[i] == 0.0 && a0[i] == 0.0f, "padding %d not zero", (int)i);
}

int main(void) {
  /* Morton keys interleave x, y(, z) bits with x lowest. */
  T_ASSERT(pdk_morton2(1, 0) == 1 && pdk_morton2(0, 1) == 2 && pdk_morton2(3, 3) == 15, "morton2");
  T_ASSERT(pdk_morton3(1, 0, 0) == 1 && pdk_morton3(0, 1, 0) == 2 && pdk_morton3(0, 0, 1) == 4, "morton3");
  T_ASSERT(pdk_morton3(0x1fffff, 0x1fffff, 0x1fffff) == 0x7fffffffffffffffull, "morton3 full");
  T_ASSERT(pdk_morton2(0xffffffffu, 0) == 0x5555555555555555ull, "morton2 full");

  pdk_ctx *ctx = t_ctx(1);
  for (int dim = 2; dim <= 3; ++dim) {
    const pdk_index n = 5003;
    pdk_particles *p = cloud(ctx, dim, n, 99 + (uint64_t)dim);
    /* Explicit permutation: reverse. */
    pdk_index *perm = malloc((size_t)n * sizeof *perm);
    for (pdk_index i = 0; i < n; ++i) perm[i] = n - 1 - i;
    T_OK(ctx, pdk_particles_permute(p, perm));
    T_ASSERT(pdk_particles_id(p)[0] == n - 1, "reversed");
    check_carried(p);
    perm[0] = perm[1];
    T_FAILS(ctx, pdk_particles_permute(p, perm), PDK_ERR_ARG, "not a permutation");

    /* Morton order: keys computed here independently must be non-decreasing. */
    const double edge = 0.05;
    T_OK(ctx, pdk_particles_reorder_morton(p, edge, perm));
    check_carried(p);
    double lo[3] = {1e300, 1e300, 1e300};
    for (int c = 0; c < dim; ++c)
      for (pdk_index i = 0; i < n; ++i) lo[c] = fmin(lo[c], pdk_particles_X(p, c)[i]);
    uint64_t prev = 0;
    for (pdk_index i = 0; i < n; ++i) {
      uint32_t q[3] = {0, 0, 0};
      for (int c = 0; c < dim; ++c) q[c] = (uint32_t)((pdk_particles_X(p, c)[i] - lo[c]) / edge);
      uint64_t key = dim == 2 ? pdk_morton2(q[0], q[1]) : pdk_morton3(q[0], q[1], q[2]);
      T_ASSERT(key >= prev, "Morton keys decrease at %d", (int)i);
      prev = key;
    }
    /* Same order from 2 threads, bitwise (positions and ids). */
    pdk_particles *q2 = cloud(ctx, dim, n, 99 + (uint64_t)dim);
    pdk_particles *q1 = cloud(ctx, dim, n, 99 + (uint64_t)dim);
    T_OK(ctx, pdk_particles_reorder_morton(q1, edge, NULL));
    T_OK(ctx, pdk_ctx_set_num_threads(ctx, 2));
    T_OK(ctx, pdk_particles_reorder_morton(q2, edge, NULL));
    T_OK(ctx, pdk_ctx_set_num_threads(ctx, 1));
    for (int c = 0; c < dim; ++c)
      T_ASSERT(!memcmp(pdk_particles_X(q1, c), pdk_particles_X(q2, c), (size_t)n * sizeof(double)), "X differs 1 vs 2 threads");
    T_ASSERT(!memcmp(pdk_particles_id(q1), pdk_particles_id(q2), (size_t)n * sizeof(int64_t)), "ids differ");
    pdk_particles_destroy(&q1);
    pdk_particles_destroy(&q2);

    /* Row order (pdk_particles_reorder_rows): the nearest lattice indices (z, y, x) never
     * decrease, x fastest; particles at the same lattice point (the spacing is coarse, so there
     * are some) keep their previous relative order (stable); the same bits from 2 threads. */
    {
      const double h = 0.5; /* the cloud spans [0, 10): 20 lattice points per axis */
      int64_t *before = malloc((size_t)n * sizeof *before); /* ids before the sort */
      pdk_index *rank = malloc((size_t)n * sizeof *rank);   /* id -> position before the sort */
      for (pdk_index i = 0; i < n; ++i) {
        before[i] = pdk_particles_id(p)[i];
        rank[pdk_particles_id(p)[i]] = i;
      }
      T_OK(ctx, pdk_ctx_set_num_threads(ctx, 2));
      T_OK(ctx, pdk_particles_reorder_rows(p, h, perm));
      T_OK(ctx, pdk_ctx_set_num_threads(ctx, 1));
      check_carried(p);
      for (pdk_index i = 0; i < n; ++i)
        T_ASSERT(before[perm[i]] == pdk_particles_id(p)[i], "perm_out is not new -> old at %d",
                 (int)i);
      double rlo[3] = {1e300, 1e300, 1e300};
      for (int c = 0; c < dim; ++c)
        for (pdk_index i = 0; i < n; ++i)
          rlo[c] = fmin(rlo[c], pdk_particles_X(p, c)[i]);
      int ties = 0;
      for (pdk_index i = 1; i < n; ++i) {
        int cmp = 0; /* sign of key(i) - key(i - 1), z first */
        for (int c = dim - 1; c >= 0 && !cmp; --c) {
          const long a = lround((pdk_particles_X(p, c)[i] - rlo[c]) / h);
          const long b = lround((pdk_particles_X(p, c)[i - 1] - rlo[c]) / h);
          cmp = (a > b) - (a < b);
        }
        T_ASSERT(cmp >= 0, "row keys decrease at %d", (int)i);
        if (!cmp) {
          ++ties;
          T_ASSERT(rank[pdk_particles_id(p)[i]] > rank[pdk_particles_id(p)[i - 1]],
                   "row order is not stable at %d", (int)i);
        }
      }
      T_ASSERT(ties > 0, "no two particles share a lattice point: stability unchecked");
      pdk_particles *r1 = cloud(ctx, dim, n, 99 + (uint64_t)dim);
      T_OK(ctx, pdk_particles_reorder_rows(r1, h, NULL));
      pdk_particles *r2 = cloud(ctx, dim, n, 99 + (uint64_t)dim);
      T_OK(ctx, pdk_ctx_set_num_threads(ctx, 2));
      T_OK(ctx, pdk_particles_reorder_rows(r2, h, NULL));
      T_OK(ctx, pdk_ctx_set_num_threads(ctx, 1));
      for (int c = 0; c < dim; ++c)
        T_ASSERT(
            !memcmp(pdk_particles_X(r1, c), pdk_particles_X(r2, c), (size_t)n * sizeof(double)),
            "row order: X differs 1 vs 2 threads");
      pdk_particles_destroy(&r1);
      pdk_particles_destroy(&r2);
      T_FAILS(ctx, pdk_particles_reorder_rows(p, 0.0, NULL), PDK_ERR_ARG, "lattice spacing");
      T_FAILS(ctx, pdk_particles_reorder_rows(p, 1e-300, NULL), PDK_ERR_ARG, "row key");
      free(before);
      free(rank);
    }

    /* Compaction keeps the chosen particles in order with their fields. */
    uint8_t *keep = calloc((size_t)n, 1);
    pdk_index kept = 0;
    for (pdk_index i = 0; i < n; ++i) kept += (keep[i] = (uint8_t)(pdk_particles_id(p)[i] % 5 != 1));
    T_OK(ctx, pdk_particles_compact(p, keep));
    T_ASSERT(pdk_particles_count(p) == kept, "compacted count");
    check_carried(p);
    for (pdk_index i = 0; i < kept; ++i) T_ASSERT(pdk_particles_id(p)[i] % 5 != 1, "removed one kept");
    memset(keep, 0, (size_t)n);
    T_FAILS(ctx, pdk_particles_compact(p, keep), PDK_ERR_ARG, "leave none");
    T_FAILS(ctx, pdk_particles_reorder_morton(p, 0.0, NULL), PDK_ERR_ARG, "cell edge");
    T_FAILS(ctx, pdk_particles_reorder_morton(p, 1e-300, NULL), PDK_ERR_ARG, "Morton key");
    free(keep);
    free(perm);
    pdk_particles_destroy(&p);
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
