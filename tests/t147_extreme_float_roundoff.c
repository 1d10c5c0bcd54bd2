/* Stability at the extremes: float storage (opts.precision = float).
 *   - correspondence UL refuses it: PDK_ERR_UNSUPPORTED, the message names float storage and says
 *     to use precision double; TL accepts it (tests/t148_corr_float_storage.c, including a body
 *     1e4 spacings from the origin under a 1e-6 strain);
 *   - PMB and LPS store bond lengths as floats: a body far from the origin (X ~ 1e4 spacings)
 *     under a stretch of 1e-6, close to the float stretch resolution 2^-24 = 6e-8, gives finite
 *     forces within the float error bound of the double ones, and not equal to them.
 * labels: physics extreme */
#include "extreme_util.h"

static void forces(pdk_ctx *ctx, int kind, int precision, double *out, pdk_index *n_out) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = 1.0;
  lo.lo[0] = lo.lo[1] = 1e4;
  lo.hi[0] = lo.hi[1] = 1e4 + 10;
  pdk_particles *p;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  pdk_families *fam = cu_families(ctx, p, 3.015);
  pdk_model_opts o = cu_opts(PDK_LAW_LINEAR_ELASTIC, 0, 0, 0);
  o.kind = (pdk_model_kind)kind;
  o.precision = (pdk_precision)precision;
  pdk_model *m = cu_model(ctx, p, fam, &o);
  const pdk_index n = pdk_particles_count(p);
  double *x = cu_field(p, "x", 0);
  for (pdk_index i = 0; i < n; ++i) x[i] += 1e-6 * (pdk_particles_X(p, 0)[i] - 1e4);
  T_OK(ctx, pdk_model_force_trial(m, NULL));
  memcpy(out, cu_field(p, "f", 0), (size_t)n * sizeof(double));
  *n_out = n;
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  for (int ul = 1; ul <= 1; ++ul) {
    pdk_particles *p = cu_lattice(ctx, 2, 6, 0.0, 1);
    pdk_families *fam = cu_families(ctx, p, 2.015);
    pdk_model_opts o = cu_opts(PDK_LAW_NEO_HOOKE, 0, 0, 0);
    o.precision = PDK_PRECISION_FLOAT;
    if (ul) o.connectivity = PDK_CONNECTIVITY_UL;
    pdk_model *m = NULL;
    T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "float storage");
    T_ASSERT(strstr(pdk_ctx_error_message(ctx), "precision double"), "no fix in '%s'", pdk_ctx_error_message(ctx));
    T_ASSERT(m == NULL, "no model on refusal");
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }
  /* PMB and LPS store the bond lengths as floats. The rounding is relative to the bond length
   * (2^-24 r0), not to the coordinates, so a body 10^4 spacings from the origin loses nothing more
   * than one at the origin; what the user must know is the stretch resolution, 2^-24 = 6e-8. Here
   * the stretch is 1e-6 (x = X + 1e-6 (X - 1e4)), so the float forces may differ from the double
   * ones by up to about 2^-24 / 1e-6 = 6 % per bond (t027 derives the bound; the sums of a family
   * do not add the errors coherently, hence the limit of 25 % of the largest force here), and must
   * differ (the option used to be accepted and silently ignored). */
  for (int kind = PDK_MODEL_PMB; kind <= PDK_MODEL_LPS; ++kind) {
    pdk_index n;
    static double fd[200], ff[200];
    forces(ctx, kind, PDK_PRECISION_DOUBLE, fd, &n);
    forces(ctx, kind, PDK_PRECISION_FLOAT, ff, &n);
    T_ASSERT(n <= 200, "body of %d particles", (int)n);
    double fmax = 0, dmax = 0;
    for (pdk_index i = 0; i < n; ++i) {
      T_ASSERT(isfinite(ff[i]), "float force of particle %d is %g", (int)i, ff[i]);
      fmax = fmax > fabs(fd[i]) ? fmax : fabs(fd[i]);
      dmax = dmax > fabs(ff[i] - fd[i]) ? dmax : fabs(ff[i] - fd[i]);
    }
    T_INFO("%s: max |f_float - f_double| = %.3g of max |f| = %.3g\n", kind ? "lps" : "pmb",
           dmax / fmax, fmax);
    T_ASSERT(fmax > 0 && dmax > 0, "%s: float storage gave the double forces exactly (ignored?)",
             kind ? "lps" : "pmb");
    T_ASSERT(dmax <= 0.25 * fmax, "%s: float error %.3g of the largest force, above 0.25",
             kind ? "lps" : "pmb", dmax / fmax);
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
