/* Helpers shared by the PMB/LPS tests (t030-t032): bodies, displacements, a pair-loop bond
 * list independent of the library's families, and model set-up. */
#ifndef PDK_BOND_MODELS_TEST_H
#define PDK_BOND_MODELS_TEST_H

#include <stdint.h>

#include "test_util.h"

static inline uint64_t bm_rng_next(uint64_t *s) { /* splitmix64 */
  uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
/* Uniform in [-1, 1). */
static inline double bm_rng_sym(uint64_t *s) {
  return 2.0 * (double)(bm_rng_next(s) >> 11) * 0x1p-53 - 1.0;
}

/* A box of nx x ny (x nz) lattice points of spacing h (square or simple cubic), jittered by
 * `jitter` spacings; volumes scaled by 1 + vol_noise * U(-1, 1) when vol_noise > 0. */
static inline pdk_particles *bm_body(pdk_ctx *ctx, int dim, int nx, int ny, int nz, double h,
                                     double jitter, double vol_noise, uint64_t seed) {
  pdk_lattice_opts o = pdk_lattice_opts_default();
  o.type = dim == 3 ? PDK_LATTICE_CUBIC : PDK_LATTICE_SQUARE;
  o.lo[0] = o.lo[1] = o.lo[2] = -0.3 * h; /* off the origin: coordinates are not multiples of h */
  o.hi[0] = o.lo[0] + nx * h;
  o.hi[1] = o.lo[1] + ny * h;
  o.hi[2] = o.lo[2] + nz * h;
  o.spacing = h;
  o.jitter = jitter;
  o.seed = seed;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, &o, &p));
  pdk_index n = pdk_particles_count(p);
  T_ASSERT(n == (pdk_index)nx * ny * (dim == 3 ? nz : 1), "lattice count %d", (int)n);
  if (vol_noise > 0) {
    double *v = pdk_particles_volume(p);
    uint64_t s = seed ^ 0x5bd1e995u;
    for (pdk_index i = 0; i < n; ++i)
      v[i] *= 1.0 + vol_noise * bm_rng_sym(&s);
  }
  return p;
}

static inline pdk_families *bm_families(pdk_ctx *ctx, pdk_particles *p, double horizon) {
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = horizon;
  pdk_families *f = NULL;
  T_OK(ctx, pdk_families_build(p, &fo, &f));
  return f;
}

/* Sets "x" = X + amp * U(-1, 1) per component (declares "x" if needed). */
static inline void bm_displace_random(pdk_particles *p, double amp, uint64_t seed) {
  pdk_ctx *ctx = pdk_particles_ctx(p);
  int dim = pdk_particles_dim(p);
  T_OK(ctx, pdk_particles_field_add(p, "x", PDK_F64, dim));
  uint64_t s = seed;
  for (int c = 0; c < dim; ++c) {
    double *x = pdk_particles_field_data(p, "x", c);
    const double *X = pdk_particles_X(p, c);
    for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
      x[i] = X[i] + amp * bm_rng_sym(&s);
  }
}

/* Sets "x" = F X + t (F row-major dim x dim). */
static inline void bm_displace_affine(pdk_particles *p, const double *F, const double *t) {
  pdk_ctx *ctx = pdk_particles_ctx(p);
  int dim = pdk_particles_dim(p);
  T_OK(ctx, pdk_particles_field_add(p, "x", PDK_F64, dim));
  pdk_index n = pdk_particles_count(p);
  for (int a = 0; a < dim; ++a) {
    double *x = pdk_particles_field_data(p, "x", a);
    for (pdk_index i = 0; i < n; ++i) {
      double v = t[a];
      for (int b = 0; b < dim; ++b)
        v += F[a * dim + b] * pdk_particles_X(p, b)[i];
      x[i] = v;
    }
  }
}

static inline pdk_model *bm_model(pdk_ctx *ctx, pdk_particles *p, pdk_families *f,
                                  pdk_model_kind kind, double K, double G, double lattice,
                                  double s00, double alpha) {
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = kind;
  mo.bulk_modulus = K;
  mo.shear_modulus = G;
  mo.density = 7.8e3;
  mo.lattice_constant = lattice;
  mo.critical_stretch = s00;
  mo.alpha = alpha;
  pdk_model *m = NULL;
  T_OK(ctx, pdk_model_create(p, f, &mo, &m));
  return m;
}

/* Bond list by testing every pair, the rule of families.h: (dx*dx + dy*dy) + dz*dz <= h^2 (1 +
 * 1e-12). start [n+1], nb [start[n]]; ascending j within a row. */
static inline void bm_pairs(pdk_particles *p, double h, int64_t **start_out, int32_t **nb_out) {
  int dim = pdk_particles_dim(p);
  pdk_index n = pdk_particles_count(p);
  const double *X[3] = {pdk_particles_X(p, 0), pdk_particles_X(p, 1),
                        dim == 3 ? pdk_particles_X(p, 2) : NULL};
  const double r2max = h * h * (1.0 + 1e-12);
  int64_t *start = calloc((size_t)n + 1, sizeof *start);
  size_t cap = 1024, num = 0;
  int32_t *nb = malloc(cap * sizeof *nb);
  for (pdk_index i = 0; i < n; ++i) {
    start[i] = (int64_t)num;
    for (pdk_index j = 0; j < n; ++j) {
      if (j == i) continue;
      volatile double dx = X[0][j] - X[0][i], dy = X[1][j] - X[1][i];
      volatile double dz = dim == 3 ? X[2][j] - X[2][i] : 0.0;
      volatile double sxy = dx * dx + dy * dy;
      volatile double r2 = sxy + dz * dz;
      if (r2 <= r2max) {
        if (num == cap) nb = realloc(nb, (cap *= 2) * sizeof *nb);
        nb[num++] = j;
      }
    }
  }
  start[n] = (int64_t)num;
  *start_out = start;
  *nb_out = nb;
}

/* Bond index of (j -> i) in j's row, -1 if absent. */
static inline int64_t bm_find_bond(const pdk_bond_index *bond_start, const pdk_index *bond_j,
                                   pdk_index j, pdk_index i) {
  for (int64_t b = bond_start[j]; b < bond_start[j + 1]; ++b)
    if (bond_j[b] == i) return b;
  return -1;
}

#endif
