/* Johnson-Cook law in the correspondence model, homogeneous deformation (V-JC through the model).
 *
 * A small block (3-D simple cubic 10^3 and 2-D plane strain 12^2, unit spacing, horizon 2.015,
 * the V-JC steel with its elastic constants taken from the Johnson-Cook parameters) is moved
 * affinely, x = F0(s) X, along a path that yields (a stretch with shear and lateral contraction,
 * 30 steps to about 8 times the yield strain). Checked after every committing pass:
 *   - F is exact for affine motion at every particle: |F_i - F0| <= 1e-12 (round-off of N K^-1
 *     with entries of order 10; VALIDATION V-INV);
 *   - the model is the material point: running pdk_jc_update in the test on each particle's own F
 *     (read back from the "F" field) with the test's own copy of the history gives the model's
 *     history bit for bit (cp_inv, eps_p, damage, failed, eps_p_rate, and w_plastic, w_damage
 *     accumulated the same way), its W exactly and its A = P K^-1 to round-off (1e-13 of |P|: the
 *     test forms P K^-1 itself);
 *   - interior particles follow the material point driven by the exact F0: eps_p within 1e-9
 *     relative (the F round-off of 1e-15 moves the return by about that much, amplified by the
 *     plastic modulus ratio E / (dsigma_y/deps_p) <= 1e3), and they carry no force (uniform
 *     stress, point-symmetric families of i and of its neighbours: |f| <= 1e-11 |P| / spacing);
 *   - trial passes change nothing: a trial at a larger deformation (which would flow plastically)
 *     leaves every history field and the bond state bitwise as it was.
 * And the run really is plastic: eps_p > 5 yield strains at the end.
 * labels: physics */
#include "corr_util.h"
#include "jc_corr_util.h"
#include "jc_util.h"

#define NUM_STEPS 30
#define DT 1e-6 /* [s]: only eps_p_rate = d_eps_p / dt depends on it (no rate terms) */

/* F0(s) = I + s G0 (row-major 3 x 3; 2-D: the 2 x 2 block, F33 = 1). Nearly isochoric, so the
 * triaxiality stays low and no particle reaches D_c on the path. */
static void path(int dim, double s, double F[3][3]) {
  static const double G3[3][3] = {{1.0, 0.3, 0.0}, {0.1, -0.45, 0.2}, {0.0, -0.1, -0.35}};
  static const double G2[3][3] = {{0.5, 0.3, 0.0}, {0.1, -0.45, 0.0}, {0.0, 0.0, 0.0}};
  const double(*G0)[3] = dim == 3 ? G3 : G2;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      F[a][b] = (a == b ? 1.0 : 0.0) + (a < dim && b < dim ? s * G0[a][b] : 0.0);
}

static void move_affine(pdk_particles *p, const double F[3][3]) {
  const int d = pdk_particles_dim(p);
  double F0[9], c[3] = {0.0, 0.0, 0.0};
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b)
      F0[a * d + b] = F[a][b];
  cu_affine(p, F0, c);
}

static void check_block(pdk_ctx *ctx, int dim, int N) {
  pdk_particles *p = cu_lattice(ctx, dim, N, 0.0, 0);
  pdk_families *fam = cu_families(ctx, p, 2.015);
  pdk_model_opts o = pdk_model_opts_default();
  o.kind = PDK_MODEL_CORRESPONDENCE;
  o.law = PDK_LAW_JC; /* K, G, rho left 0: taken from o.jc */
  o.influence = PDK_INFLUENCE_CONSTANT;
  pdk_model *m = cu_model(ctx, p, fam, &o);
  T_OK(ctx, pdk_model_set_dt(m, DT));
  const pdk_jc_params *jc = &pdk_model_opts_get(m)->jc;
  const double E = jc->young_modulus, nu = jc->poisson_ratio;
  T_ASSERT(pdk_model_opts_get(m)->bulk_modulus == E / (3.0 * (1.0 - 2.0 * nu)) &&
               pdk_model_opts_get(m)->shear_modulus == E / (2.0 * (1.0 + nu)),
           "elastic constants not taken from the Johnson-Cook parameters");
  const pdk_index n = pdk_particles_count(p);
  const int reach = cu_reach(2.015);

  /* the test's own histories: per particle (model's F) and one driven by the exact F0 */
  pdk_jc_state *hist = malloc((size_t)n * sizeof *hist);
  double *wp = calloc((size_t)n, sizeof *wp), *wd = calloc((size_t)n, sizeof *wd);
  T_ASSERT(hist && wp && wd, "out of memory");
  for (pdk_index i = 0; i < n; ++i)
    hist[i] = pdk_jc_state_initial();
  pdk_jc_state exact = pdk_jc_state_initial();
  const double s_end = 8.0 * (jc->A / E) / 0.5; /* |G0| ~ 0.5 per unit s */

  for (int step = 1; step <= NUM_STEPS; ++step) {
    const double s = s_end * step / NUM_STEPS;
    double F0[3][3];
    /* trial first, beyond the step's state: nothing may change */
    jcu_snapshot before = jcu_snapshot_take(m);
    path(dim, s * 1.5, F0);
    move_affine(p, F0);
    T_OK(ctx, pdk_model_force_trial(m, NULL));
    T_ASSERT(jcu_snapshot_equal(m, &before), "%d-D step %d: a trial pass changed the history", dim,
             step);
    free(before.data);

    path(dim, s, F0);
    move_affine(p, F0);
    double energy = 0.0;
    T_OK(ctx, pdk_model_force(m, &energy));
    T_ASSERT(pdk_model_num_flagged(m) == 0 && pdk_model_num_failed(m) == 0,
             "%d-D step %d: %d flagged, %d failed", dim, step, (int)pdk_model_num_flagged(m),
             (int)pdk_model_num_failed(m));
    pdk_jc_result rex;
    double Pex[3][3];
    ju_update(jc, dim, F0, DT, &exact, &exact, Pex, &rex);
    double pmax = 0.0;
    for (int a = 0; a < dim; ++a)
      for (int b = 0; b < dim; ++b)
        pmax = fmax(pmax, fabs(Pex[a][b]));

    double esum = 0.0;
    for (pdk_index i = 0; i < n; ++i) {
      double F[3][3] = {{0}}, Kinv[3][3] = {{0}}, P[3][3];
      for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) {
          F[a][b] = cu_field(p, "F", a * dim + b)[i];
          Kinv[a][b] = cu_field(p, "Kinv", a * dim + b)[i];
          T_NEAR(F[a][b], F0[a][b], 0.0, 1e-12, "%d-D step %d: F[%d][%d] of particle %d", dim, step,
                 a, b, (int)i);
        }
      pdk_jc_result res;
      ju_update(jc, dim, F, DT, &hist[i], &hist[i], P, &res);
      wp[i] += res.dW_plastic;
      wd[i] += res.dW_damage;
      /* history: bitwise */
      for (int c = 0; c < 6; ++c)
        T_ASSERT(!memcmp(&cu_field(p, "cp_inv", c)[i], &hist[i].cp_inv[c], sizeof(double)),
                 "%d-D step %d: cp_inv[%d] of particle %d: %.17g vs %.17g", dim, step, c, (int)i,
                 cu_field(p, "cp_inv", c)[i], hist[i].cp_inv[c]);
      T_ASSERT(!memcmp(&cu_field(p, "eps_p", 0)[i], &hist[i].eps_p, sizeof(double)) &&
                   !memcmp(&cu_field(p, "damage", 0)[i], &hist[i].damage, sizeof(double)) &&
                   !memcmp(&cu_field(p, "eps_p_rate", 0)[i], &res.eps_p_rate, sizeof(double)) &&
                   !memcmp(&cu_field(p, "w_plastic", 0)[i], &wp[i], sizeof(double)) &&
                   !memcmp(&cu_field(p, "w_damage", 0)[i], &wd[i], sizeof(double)),
               "%d-D step %d: scalar history of particle %d differs from the material point "
               "(eps_p %.17g vs %.17g)",
               dim, step, (int)i, cu_field(p, "eps_p", 0)[i], hist[i].eps_p);
      T_ASSERT(((uint8_t *)pdk_particles_field_data(p, "failed", 0))[i] == hist[i].failed,
               "failed flag");
      /* stress: A = P K^-1 */
      for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) {
          double A = 0.0;
          for (int e = 0; e < dim; ++e)
            A += P[a][e] * Kinv[e][b];
          double Kscale = 0.0;
          for (int e = 0; e < dim; ++e)
            Kscale = fmax(Kscale, fabs(Kinv[e][b]));
          T_NEAR(cu_field(p, "A", a * dim + b)[i], A, 0.0, 1e-13 * pmax * Kscale,
                 "%d-D step %d: A[%d][%d] of particle %d", dim, step, a, b, (int)i);
        }
      esum += pdk_particles_volume(p)[i] * res.W;
      if (cu_inside(p, i, N, reach)) {
        T_NEAR(hist[i].eps_p, exact.eps_p, 1e-9, 1e-15,
               "%d-D step %d: eps_p of interior particle %d vs the material point at F0", dim, step,
               (int)i);
      }
      if (cu_inside(p, i, N, 2 * reach)) /* i and all its neighbours have full families */
        for (int a = 0; a < dim; ++a)
          T_NEAR(cu_field(p, "f", a)[i], 0.0, 0.0, 1e-11 * pmax,
                 "%d-D step %d: force on interior particle %d", dim, step, (int)i);
    }
    T_NEAR(energy, esum, 1e-12, 0.0, "%d-D step %d: strain energy", dim, step);
  }
  T_ASSERT(exact.eps_p > 5.0 * jc->A / E, "%d-D: the path hardly yielded (eps_p %g)", dim,
           exact.eps_p);
  double plastic = 0.0, damage = 0.0, breaking = -1.0;
  T_OK(ctx, pdk_model_plastic_work(m, &plastic, &damage, &breaking));
  double wsum = 0.0;
  for (pdk_index i = 0; i < n; ++i)
    wsum += pdk_particles_volume(p)[i] * wp[i];
  T_NEAR(plastic, wsum, 1e-12, 0.0, "%d-D: plastic work", dim);
  T_ASSERT(plastic > 0.0 && breaking == 0.0, "%d-D: plastic %g, breaking %g", dim, plastic,
           breaking);
  free(hist);
  free(wp);
  free(wd);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  check_block(ctx, 3, 10);
  check_block(ctx, 2, 12);
  pdk_ctx_destroy(&ctx);
  return 0;
}
