/* Correspondence model: the force density is minus the gradient of the strain energy,
 * V_k f_k = -dE/dx_k, E = sum_i V_i W_i (including the Silling stabilization energy), checked by
 * central finite differences on small jittered lattices with a random finite displacement, for
 * every law, every influence function, without and with Silling's stabilization (the hourglass
 * form is not the gradient of an energy, see kernels/ref/corr.c). Also: in the small-strain limit
 * St Venant-Kirchhoff and Neo-Hooke give the linear elastic forces, with a difference of first
 * order in the strain.
 * labels: physics
 *
 * FD tolerance. Step h = 1e-5 dx. Truncation error h^2/6 |E'''| with |E'''| = O(modulus / dx)
 * = O(10): ~2e-10; cancellation eps E / h with E <= ~10: ~2e-10. Forces here are O(0.1..1), so the
 * check |FD + V f| <= 1e-7 max|V f| leaves a margin of ~100 (measured worst: see the failure
 * message, which prints it).
 */
#include "corr_util.h"

static double energy_at(pdk_ctx *ctx, pdk_model *m) {
  double e = 0.0;
  T_OK(ctx, pdk_model_force_trial(m, &e));
  return e;
}

static void check_gradient(pdk_ctx *ctx, int dim, int law, int infl, int stab) {
  const int N = dim == 2 ? 7 : 5;
  const double mh = dim == 2 ? 2.015 : 1.5;
  pdk_particles *p = cu_lattice(ctx, dim, N, 0.2, 5);
  pdk_families *fam = cu_families(ctx, p, mh);
  pdk_model_opts o = cu_opts(law, infl, stab, 0.3);
  pdk_model *m = cu_model(ctx, p, fam, &o);
  const pdk_index n = pdk_particles_count(p);
  const double *V = pdk_particles_volume(p);
  cu_random_x(p, 0.05, 1234);
  (void)energy_at(ctx, m);
  double *f[3];
  double fbig = 0.0;
  for (int a = 0; a < dim; ++a) {
    f[a] = malloc((size_t)n * sizeof(double));
    memcpy(f[a], cu_field(p, "f", a), (size_t)n * sizeof(double));
    for (pdk_index i = 0; i < n; ++i)
      fbig = fmax(fbig, fabs(V[i] * f[a][i]));
  }
  T_ASSERT(fbig > 1e-3, "forces too small to test (%g)", fbig);
  const double h = 1e-5, tol = 1e-7 * fbig;
  /* Every particle in 2-D (corners, edges, interior); a spread of 25 in 3-D. */
  const pdk_index stride = dim == 2 ? 1 : 5;
  for (pdk_index k = 0; k < n; k += stride)
    for (int a = 0; a < dim; ++a) {
      double *x = cu_field(p, "x", a);
      const double x0 = x[k];
      x[k] = x0 + h;
      const double ep = energy_at(ctx, m);
      x[k] = x0 - h;
      const double em = energy_at(ctx, m);
      x[k] = x0;
      const double grad = (ep - em) / (2.0 * h);
      const double err = fabs(grad + V[k] * f[a][k]);
      if (err > tol)
        T_FAIL("%d-D law %s influence %s stabilization %s: particle %d axis %d: -dE/dx = %.12g, "
               "V f = %.12g, |difference| %.3g > %.3g (1e-7 of max |V f| = %.3g)",
               dim, cu_law_name[law], cu_infl_name[infl], cu_stab_name[stab], (int)k, a, -grad,
               V[k] * f[a][k], err, tol, fbig);
    }
  for (int a = 0; a < dim; ++a)
    free(f[a]);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

/* max |f_law - f_linear| / max |f_linear| at displacement amplitude amp. */
static double small_strain_gap(pdk_ctx *ctx, int dim, int law, double amp) {
  const int N = dim == 2 ? 8 : 5;
  const double mh = dim == 2 ? 2.015 : 1.5;
  pdk_particles *p = cu_lattice(ctx, dim, N, 0.2, 6);
  pdk_families *fam = cu_families(ctx, p, mh);
  pdk_model_opts o_lin = cu_opts(PDK_LAW_LINEAR_ELASTIC, PDK_INFLUENCE_CUBIC, PDK_STAB_NONE, 0.0);
  pdk_model_opts o_law = cu_opts(law, PDK_INFLUENCE_CUBIC, PDK_STAB_NONE, 0.0);
  pdk_model *m_lin = cu_model(ctx, p, fam, &o_lin);
  const pdk_index n = pdk_particles_count(p);
  cu_random_x(p, amp, 77);
  T_OK(ctx, pdk_model_force(m_lin, NULL));
  double *f[3], fref = 0.0;
  for (int a = 0; a < dim; ++a) {
    f[a] = malloc((size_t)n * sizeof(double));
    memcpy(f[a], cu_field(p, "f", a), (size_t)n * sizeof(double));
    for (pdk_index i = 0; i < n; ++i)
      fref = fmax(fref, fabs(f[a][i]));
  }
  pdk_model_destroy(&m_lin);
  pdk_model *m_law = cu_model(ctx, p, fam, &o_law); /* shares the fields; x is kept */
  T_OK(ctx, pdk_model_force(m_law, NULL));
  double gap = 0.0;
  for (int a = 0; a < dim; ++a) {
    const double *g = cu_field(p, "f", a);
    for (pdk_index i = 0; i < n; ++i)
      gap = fmax(gap, fabs(g[i] - f[a][i]));
    free(f[a]);
  }
  pdk_model_destroy(&m_law);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return gap / fref;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  for (int dim = 2; dim <= 3; ++dim)
    for (int law = 0; law < 3; ++law)
      for (int infl = 0; infl < 6; ++infl)
        for (int stab = 0; stab < 2; ++stab)
          check_gradient(ctx, dim, law, infl, stab);

  /* Small-strain limit: the gap is O(strain), so it shrinks tenfold with the amplitude. */
  for (int dim = 2; dim <= 3; ++dim)
    for (int law = PDK_LAW_SVK; law <= PDK_LAW_NEO_HOOKE; ++law) {
      const double g4 = small_strain_gap(ctx, dim, law, 1e-4);
      const double g5 = small_strain_gap(ctx, dim, law, 1e-5);
      T_ASSERT(g4 <= 1e-2, "%d-D %s: relative force gap to linear elastic %.3g at strain ~1e-4",
               dim, cu_law_name[law], g4);
      T_ASSERT(g5 >= 0.05 * g4 && g5 <= 0.2 * g4,
               "%d-D %s: gap %.3g at amplitude 1e-5 vs %.3g at 1e-4 is not first order", dim,
               cu_law_name[law], g5, g4);
    }
  pdk_ctx_destroy(&ctx);
  return 0;
}
