/* Peridynamic Galerkin with the WLS1 basis and no correction is the classical correspondence
 * model: every evaluation point of family k has the gradient F^k of K^-1 (Bode 2021 section 4.2.1:
 * WLS1 = U1; thesis eqs. 4.3-4.6), the PBG weights of a family sum to V_k, so the energy is
 * sum_k V_k W(F^k) and the force its gradient, which is what correspondence (omega = 1/r^2, no
 * stabilization) computes. On the irregular cloud of the patch test with a random displacement
 * (2e-3 of the spacing) and each elastic law, forces and energies must agree to round-off: the
 * two sum the same terms in different orders and through different intermediate tensors, so
 * |f_gal - f_corr| <= 1e-9 max |f| (measured 2e-14) and the energies to 1e-10 relative.
 * Also: at rest the force is exactly 0 and F = I (the difference form of eq. 4.11).
 * labels: unit galerkin */
#include "galerkin_util.h"

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const int n1 = 21;
  const double h = 2.0 / (n1 - 1);
  const pdk_law laws[3] = {PDK_LAW_LINEAR_ELASTIC, PDK_LAW_SVK, PDK_LAW_NEO_HOOKE};
  for (int l = 0; l < 3; ++l) {
    pdk_particles *p = pg_cloud(ctx, n1, 0.3, 7);
    pdk_families_opts fo = pdk_families_opts_default();
    fo.horizon = 2.51 * h;
    pdk_families *fam;
    T_OK(ctx, pdk_families_build(p, &fo, &fam));
    const pdk_index n = pdk_particles_count(p);
    pdk_model_opts go = pg_model_opts(PDK_GALERKIN_WLS, PDK_GALERKIN_NONE);
    go.law = laws[l];
    pdk_model *mg, *mc;
    T_OK(ctx, pdk_model_create(p, fam, &go, &mg));
    /* at rest */
    double e0 = -1.0;
    T_OK(ctx, pdk_model_force_trial(mg, &e0));
    T_ASSERT(e0 == 0.0, "energy at rest %.3e", e0);
    for (int c = 0; c < 2; ++c) {
      const double *f = pdk_particles_field_data(p, "f", c);
      for (pdk_index i = 0; i < n; ++i)
        T_ASSERT(f[i] == 0.0, "force at rest %.3e at %d", f[i], (int)i);
    }
    /* random displacement */
    uint64_t s = 99;
    for (int c = 0; c < 2; ++c) {
      double *x = pdk_particles_field_data(p, "x", c);
      const double *X = pdk_particles_X(p, c);
      for (pdk_index i = 0; i < n; ++i)
        x[i] = X[i] + 2e-3 * h * (2 * pg_rand(&s) - 1) + 0.01 * X[i];
    }
    double eg, ec;
    T_OK(ctx, pdk_model_force_trial(mg, &eg));
    double *fg[2];
    for (int c = 0; c < 2; ++c) {
      fg[c] = malloc((size_t)n * sizeof(double));
      memcpy(fg[c], pdk_particles_field_data(p, "f", c), (size_t)n * sizeof(double));
    }
    pdk_model_destroy(&mg);
    pdk_model_opts co = pdk_model_opts_default();
    co.kind = PDK_MODEL_CORRESPONDENCE;
    co.bulk_modulus = go.bulk_modulus;
    co.shear_modulus = go.shear_modulus;
    co.density = 1.0;
    co.law = laws[l];
    co.influence = PDK_INFLUENCE_INV_R2;
    co.stabilization = PDK_STAB_NONE;
    T_OK(ctx, pdk_model_create(p, fam, &co, &mc));
    T_OK(ctx, pdk_model_force_trial(mc, &ec));
    double fm = 0.0, dmax = 0.0;
    for (int c = 0; c < 2; ++c) {
      const double *f = pdk_particles_field_data(p, "f", c);
      for (pdk_index i = 0; i < n; ++i) {
        fm = fmax(fm, fabs(f[i]));
        dmax = fmax(dmax, fabs(f[i] - fg[c][i]));
      }
      free(fg[c]);
    }
    T_INFO("law %d: force difference %.3e of %.3e, energies %.17g %.17g\n", (int)laws[l], dmax, fm,
           eg, ec);
    T_ASSERT(fm > 0 && dmax <= 1e-9 * fm,
             "law %d: galerkin wls and correspondence differ by "
             "%.3e (max |f| %.3e)",
             (int)laws[l], dmax, fm);
    T_NEAR(eg, ec, 1e-10, 0.0, "law %d: energies", (int)laws[l]);
    pdk_model_destroy(&mc);
    pdk_families_destroy(&fam);
    pdk_particles_destroy(&p);
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
