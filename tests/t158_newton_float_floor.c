/* Newton with float storage: the residual's round-off floor is detected and reported.
 *
 * With precision float, correspondence rounds the tensors of pass 2 to float at every force pass
 * (a relative 2^-24 of the stress), so the residual carries noise that no Newton step removes,
 * while Newton's default rtol is 1e-10 of the load norm. Without detection the steps stop
 * contracting, the line search stalls and the solve fails (here after 12 iterations and 11
 * tangents, at 1.2e-8 of the load). pdk accepts, when storage is float, a level whose residual is
 * below FLT_EPSILON of the load norm and which the last step reduced by less than half (or whose
 * line search stalled there), and counts it in stats.storage_floor_levels.
 *
 * Setup: 2-D bar 20 x 10, spacing 0.5, RF 3, Neo-Hooke correspondence with Silling
 * stabilization, cubic influence; left end held, right end pulled by 1e-2 (strain 5e-4: small
 * enough that the stress noise is near the default tolerance, large enough that the problem is
 * not trivial). Default Newton options in both precisions. Checks:
 *   - double storage converges to rtol 1e-10 with no level at the storage floor (the detection
 *     does not touch double runs);
 *   - float storage converges (does not fail) and, when a level stopped at the floor, its
 *     residual is at most FLT_EPSILON of the load norm (the acceptance bound);
 *   - the float solution agrees with the double one: the stored tensors differ by a relative
 *     2^-24 = 6e-8, the stopping residual by at most 1.2e-7 of the load norm; the condition of
 *     this small bar (RF 3, 40 x 20 particles) amplifies a relative force error into a relative
 *     displacement error by at most ~10 (softest mode against the mean), so max |u_f - u_d| <=
 *     1e-5 max |u_d| leaves a margin of ~10;
 *   - that the float run did reach the floor (storage_floor_levels >= 1): this is what makes the
 *     test fail if the detection were removed (the solve would then end with the line-search
 *     error).
 * labels: physics */
#include <float.h>

#include "solvers/static_impl.h"
#include "test_util.h"

static double *solve(pdk_ctx *ctx, pdk_precision prec, pdk_static_stats *out, pdk_index *n_out) {
  const double L = 20.0, H = 10.0, dx = 0.5, rf = 3.0;
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.node_type = 1;
  lo.spacing = dx;
  lo.hi[0] = L;
  lo.hi[1] = H;
  pdk_particles *p;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  T_OK(ctx, pdk_particles_reorder_morton(p, rf * dx, NULL));
  const double e = 0.25 * dx;
  double a0[3] = {-1, -1, -1}, a1[3] = {e, H + 1, 1};
  double c0[3] = {L - e, -1, -1}, c1[3] = {L + 1, H + 1, 1};
  pdk_region left = pdk_region_box(a0, a1), right = pdk_region_box(c0, c1);
  T_OK(ctx, pdk_particles_set_define(p, "left", &left, NULL));
  T_OK(ctx, pdk_particles_set_define(p, "right", &right, NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = rf * dx;
  pdk_families *fam;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_CORRESPONDENCE;
  mo.bulk_modulus = 1000.0 / 3.0;
  mo.shear_modulus = 500.0;
  mo.density = 1.0;
  mo.influence = PDK_INFLUENCE_CUBIC;
  mo.stabilization = PDK_STAB_SILLING;
  mo.law = PDK_LAW_NEO_HOOKE;
  mo.precision = prec;
  pdk_model *m;
  T_OK(ctx, pdk_model_create(p, fam, &mo, &m));
  pdk_bc bcs[2];
  memset(bcs, 0, sizeof bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:left";
  bcs[0].components = 3;
  bcs[1].kind = PDK_BC_DISPLACEMENT;
  bcs[1].set = "set:right";
  bcs[1].components = 1;
  bcs[1].value[0] = pdk_tfun_constant(1e-2);
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = 2;
  pdk_static *s;
  T_OK(ctx, pdk_static_create(m, &so, &s));
  T_OK(ctx, pdk_static_solve(s));
  *out = *pdk_static_stats_get(s);
  if (getenv("PDK_TEST_VERBOSE")) pdk_static_stats_print(out, stdout);
  const pdk_index n = pdk_particles_count(p);
  double *u = malloc(2 * (size_t)n * sizeof(double));
  for (int c = 0; c < 2; ++c) {
    const double *x = pdk_particles_field_data(p, "x", c), *X = pdk_particles_X(p, c);
    for (pdk_index i = 0; i < n; ++i) u[(size_t)c * n + i] = x[i] - X[i];
  }
  *n_out = n;
  pdk_static_destroy(&s);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return u;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  pdk_static_stats sd, sf;
  pdk_index n, nf;
  double *ud = solve(ctx, PDK_PRECISION_DOUBLE, &sd, &n);
  double *uf = solve(ctx, PDK_PRECISION_FLOAT, &sf, &nf);
  T_ASSERT(n == nf, "same body");
  T_ASSERT(sd.storage_floor_levels == 0, "double storage: %d levels at the storage floor",
           sd.storage_floor_levels);
  T_ASSERT(sd.residual <= 1e-10 * sd.load_norm || sd.residual <= sd.residual_floor,
           "double: residual %.3e of load %.3e", sd.residual, sd.load_norm);
  T_ASSERT(sf.storage_floor_levels >= 1,
           "float storage converged to rtol 1e-10 (residual %.3e of load %.3e): the floor was "
           "not reached, so this test no longer exercises its detection",
           sf.residual, sf.load_norm);
  T_ASSERT(sf.residual <= FLT_EPSILON * sf.load_norm, "float: accepted residual %.3e of load %.3e",
           sf.residual, sf.load_norm);
  double umax = 0.0, dmax = 0.0;
  for (size_t k = 0; k < 2 * (size_t)n; ++k) {
    umax = fmax(umax, fabs(ud[k]));
    dmax = fmax(dmax, fabs(uf[k] - ud[k]));
  }
  T_ASSERT(dmax <= 1e-5 * umax, "float vs double: max |du| %.3e, max |u| %.3e", dmax, umax);
  T_INFO("double: residual %.3e of load %.3e; float: %.3e (%d level(s) at the storage floor); "
         "max |u_f - u_d| / max |u| = %.2e\n",
         sd.residual, sd.load_norm, sf.residual, sf.storage_floor_levels, dmax / umax);
  free(ud);
  free(uf);
  pdk_ctx_destroy(&ctx);
  return 0;
}
