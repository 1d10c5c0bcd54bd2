/* pdk_model_float_stretch_ratio: max |stretch| over intact bonds / 2^-24 for PMB and LPS with
 * float bond lengths, -1 where it does not apply (double storage, correspondence).
 *   - a square plate stretched uniformly by e along x: every bond's stretch is e (n_x)^2-weighted
 *     at most e (axial bonds exactly e), so the ratio is e / 2^-24 to the double round-off of
 *     the positions (relative 1e-9 at e = 1e-6 on coordinates of size 10: 1e-15 / 1e-6);
 *   - at rest the ratio is 0; with double storage and for correspondence it is -1;
 *   - 1 and 2 threads give the same value (a max is order independent: bitwise);
 *   - the CLI's threshold: e = 1e-6 lies below PDK_FLOAT_STRETCH_WARN (ratio 16.8), e = 1e-2 above.
 * labels: unit extreme */
#include "corr_util.h"

static double ratio(pdk_model_kind kind, pdk_precision prec, double e, int threads) {
  pdk_ctx *ctx = t_ctx(threads);
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = 1.0;
  lo.hi[0] = lo.hi[1] = 10.0;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  pdk_families *fam = cu_families(ctx, p, 3.015);
  pdk_model_opts o = cu_opts(PDK_LAW_LINEAR_ELASTIC, 0, 0, 0);
  o.kind = kind;
  o.precision = prec;
  pdk_model *m = cu_model(ctx, p, fam, &o);
  const pdk_index n = pdk_particles_count(p);
  double *x = cu_field(p, "x", 0);
  const double *X = pdk_particles_X(p, 0);
  for (pdk_index i = 0; i < n; ++i) x[i] = X[i] * (1.0 + e);
  const double r = pdk_model_float_stretch_ratio(m);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return r;
}

int main(void) {
  for (int k = 0; k < 2; ++k) {
    const pdk_model_kind kind = k ? PDK_MODEL_LPS : PDK_MODEL_PMB;
    for (int t = 1; t <= 2; ++t) {
      const double small = ratio(kind, PDK_PRECISION_FLOAT, 1e-6, t);
      T_NEAR(small, 1e-6 / 0x1p-24, 1e-6, 0.0, "kind %d, threads %d, e = 1e-6", k, t);
      T_ASSERT(small < PDK_FLOAT_STRETCH_WARN, "e = 1e-6 must warn (ratio %g)", small);
      const double large = ratio(kind, PDK_PRECISION_FLOAT, 1e-2, t);
      T_NEAR(large, 1e-2 / 0x1p-24, 1e-9, 0.0, "kind %d, threads %d, e = 1e-2", k, t);
      T_ASSERT(large >= PDK_FLOAT_STRETCH_WARN, "e = 1e-2 must not warn (ratio %g)", large);
      T_ASSERT(ratio(kind, PDK_PRECISION_FLOAT, 0.0, t) == 0.0, "at rest");
      T_ASSERT(ratio(kind, PDK_PRECISION_DOUBLE, 1e-6, t) == -1.0, "double storage");
    }
    T_ASSERT(ratio(kind, PDK_PRECISION_FLOAT, 1e-5, 1) == ratio(kind, PDK_PRECISION_FLOAT, 1e-5, 2),
             "1 vs 2 threads bitwise");
  }
  T_ASSERT(ratio(PDK_MODEL_CORRESPONDENCE, PDK_PRECISION_FLOAT, 1e-6, 1) == -1.0,
           "correspondence: not applicable");
  return 0;
}
