/* Helpers shared by the stability-at-the-extremes tests (t14x): unit-spacing lattices and models
 * from corr_util.h, the first Piola stress recovered from the model's fields, and field scans. */
#ifndef PDK_EXTREME_UTIL_H
#define PDK_EXTREME_UTIL_H

#include "corr_util.h"
#include "pdk/explicit.h"

/* P = A K at particle i (correspondence: "A" = P K^-1, "Kinv"), 2-D only; P row-major 2x2. */
static inline void ex_piola_2d(pdk_particles *p, pdk_index i, double P[4]) {
  double Ki[4], A[4];
  for (int t = 0; t < 4; ++t) {
    Ki[t] = cu_field(p, "Kinv", t)[i];
    A[t] = cu_field(p, "A", t)[i];
  }
  const double det = Ki[0] * Ki[3] - Ki[1] * Ki[2];
  const double K[4] = {Ki[3] / det, -Ki[1] / det, -Ki[2] / det, Ki[0] / det};
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c) P[a * 2 + c] = A[a * 2 + 0] * K[0 * 2 + c] + A[a * 2 + 1] * K[1 * 2 + c];
}

/* Largest |f| component over the store; 1 in *nonfinite when some entry is not finite. */
static inline double ex_max_force(pdk_particles *p, int *nonfinite) {
  const int d = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  double worst = 0.0;
  *nonfinite = 0;
  for (int a = 0; a < d; ++a) {
    const double *f = cu_field(p, "f", a);
    for (pdk_index i = 0; i < n; ++i) {
      if (!isfinite(f[i])) *nonfinite = 1;
      worst = fmax(worst, fabs(f[i]));
    }
  }
  return worst;
}

/* Particle nearest to the point c (2-D or 3-D). */
static inline pdk_index ex_nearest(pdk_particles *p, const double *c) {
  const int d = pdk_particles_dim(p);
  pdk_index best = 0;
  double bd = 1e300;
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
    double r2 = 0;
    for (int a = 0; a < d; ++a) {
      const double dx = pdk_particles_X(p, a)[i] - c[a];
      r2 += dx * dx;
    }
    if (r2 < bd) bd = r2, best = i;
  }
  return best;
}

/* Stable-step estimate of a model (a probe solver with default options). */
static inline double ex_stable_dt(pdk_ctx *ctx, pdk_model *m) {
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  pdk_explicit *e = NULL;
  T_OK(ctx, pdk_explicit_create(m, &eo, &e));
  const double dt = pdk_explicit_stable_dt(e);
  pdk_explicit_destroy(&e);
  return dt;
}

static inline int ex_verbose(void) { return getenv("PDK_TEST_VERBOSE") != NULL; }

#endif
