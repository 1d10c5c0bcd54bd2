/* Correspondence model: requests it refuses, with messages that say why.
 * labels: unit
 */
#include "corr_util.h"

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  pdk_particles *p = cu_lattice(ctx, 2, 4, 0.0, 0);
  pdk_families *fam = cu_families(ctx, p, 1.5);
  pdk_model *m = NULL;

  /* Float storage is implemented for TL (t148) but not for UL connectivity. */
  pdk_model_opts o = cu_opts(PDK_LAW_SVK, PDK_INFLUENCE_CUBIC, PDK_STAB_NONE, 0.0);
  o.precision = PDK_PRECISION_FLOAT;
  o.connectivity = PDK_CONNECTIVITY_UL;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_UNSUPPORTED, "float");
  T_ASSERT(m == NULL, "no model on failure");
  o.connectivity = PDK_CONNECTIVITY_TL;
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);

  /* Two particles at the same reference position: a zero-length bond, named by the ids. */
  T_OK(ctx, pdk_particles_create(ctx, 2, 3, &p));
  double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1), *V = pdk_particles_volume(p);
  const double xs[3] = {0.0, 1.0, 1.0}, ys[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < 3; ++i)
    X[i] = xs[i], Y[i] = ys[i], V[i] = 1.0;
  fam = cu_families(ctx, p, 1.5);
  o.precision = PDK_PRECISION_DOUBLE;
  T_FAILS(ctx, pdk_model_create(p, fam, &o, &m), PDK_ERR_ARG, "ids 1 and 2");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "same reference position") != NULL, "%s",
           pdk_ctx_error_message(ctx));
  T_ASSERT(m == NULL, "no model on failure");
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
