/* Static solvers: ADR and Newton reach the same equilibrium for PMB, LPS and (stabilized)
 * correspondence, in a 2-D bar and a 3-D block, under end displacement or end traction; the Newton
 * residual ends at round-off; a linear problem matches the analytical uniaxial displacement.
 * labels: physics
 *
 * Tolerances.
 * - ADR vs Newton. ADR stops when ||r|| <= rtol ||F_ext|| with rtol = 1e-8. The displacement error
 *   left is e = K^-1 r. ADR's critically damped update kills the stiff modes first, so what is
 *   left of r lies in the softest modes, which also carry most of the solution; along them
 *   |e| / |u| ~ |r| / |F| = 1e-8. The residual is not purely in one mode, so we allow a factor
 *   1000 for the spread over the spectrum: max |u_adr - u_newton| <= 1e-5 max |u|. (Measured:
 *   about 5e-8.)
 * - Newton residual at round-off. Positions are absolute, so rounding every coordinate by half an
 *   ulp changes r by about eps |x|_max ||K||_F (K the tangent, computed here independently of the
 *   solver's own floor); the final residual must be below that, and below 1e-9 ||F_ext|| at these
 *   strains (1e-3).
 * - Uniaxial displacement. Correspondence with the small-strain linear law is exactly linear; with
 *   nu = 0 the continuum solution of a bar held at x = 0 and pulled by a traction T at x = L is
 *   u_x = T x / E (no lateral contraction). The discrete solution differs through the one-horizon
 *   surface layers, where families are one-sided: there K^-1, hence A = sigma K^-1, is larger and
 * the uniform stress is no longer an equilibrium (correspondence surface stiffening), plus the end
 *   rows (traction applied as a body force on one row). In this thin bar the free lateral surfaces
 *   dominate: their layers hold a fraction 2 delta / H of the section, carrying a stress error of
 *   order one, so |u(L) / (T L / E) - 1| <= delta / H (half that share). At fixed RF = delta/h
 *   the error is O(h) (V-Q3: order 1): halving h must halve it (ratio in [1.6, 2.4]).
 */
#include "solvers/static_impl.h"
#include "test_util.h"

typedef struct body {
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  pdk_index n_right; /* particles on the loaded end */
} body;

/* Node-type lattice [0, L] x [0, H] (x [0, H] in 3-D), sets "left" (x = 0) and "right" (x = L). */
static body build(pdk_ctx *ctx, int dim, double L, double H, double dx, double rf,
                  pdk_model_kind kind, pdk_law law) {
  body b;
  memset(&b, 0, sizeof b);
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = dim == 2 ? PDK_LATTICE_SQUARE : PDK_LATTICE_CUBIC;
  lo.node_type = 1;
  lo.spacing = dx;
  lo.hi[0] = L;
  lo.hi[1] = H;
  lo.hi[2] = H;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &b.p));
  T_OK(ctx, pdk_particles_reorder_morton(b.p, rf * dx, NULL));
  const double e = 0.25 * dx;
  double a0[3] = {-1, -1, -1}, a1[3] = {e, H + 1, H + 1};
  double c0[3] = {L - e, -1, -1}, c1[3] = {L + 1, H + 1, H + 1};
  pdk_region left = pdk_region_box(a0, a1), right = pdk_region_box(c0, c1);
  T_OK(ctx, pdk_particles_set_define(b.p, "left", &left, NULL));
  T_OK(ctx, pdk_particles_set_define(b.p, "right", &right, &b.n_right));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = rf * dx;
  T_OK(ctx, pdk_families_build(b.p, &fo, &b.fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = kind;
  const double E = 1000.0, nu = 0.0; /* LPS and correspondence; PMB fixes nu = 1/4 itself */
  mo.bulk_modulus = E / (3.0 * (1.0 - 2.0 * nu));
  mo.shear_modulus = E / (2.0 * (1.0 + nu));
  mo.density = 1.0;
  mo.influence = PDK_INFLUENCE_CUBIC;
  mo.stabilization = PDK_STAB_SILLING;
  mo.law = law;
  T_OK(ctx, pdk_model_create(b.p, b.fam, &mo, &b.m));
  return b;
}

static void destroy(body *b) {
  pdk_model_destroy(&b->m);
  pdk_families_destroy(&b->fam);
  pdk_particles_destroy(&b->p);
}

/* Left end held (all components); right end pulled by u_x = u_end (traction = 0) or by the
 * traction T (body force T A / (N V) on the end row, A = H^(dim-1)). Returns the solver's stats
 * and the displacement [dim][n] in u (malloc'ed); *residual and *floor from an independent check
 * when newton_check. */
static void solve(pdk_ctx *ctx, body *b, int dim, double H, pdk_static_method method, double u_end,
                  double traction, double **u, double *rel_residual, double *floor) {
  pdk_bc bcs[2];
  memset(bcs, 0, sizeof bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:left";
  bcs[0].components = dim == 3 ? 7 : 3;
  bcs[1].set = "set:right";
  bcs[1].components = 1;
  if (traction != 0.0) {
    const double area = dim == 3 ? H * H : H; /* 2-D: thickness 1 */
    bcs[1].kind = PDK_BC_BODY_FORCE;
    bcs[1].value[0] =
        pdk_tfun_constant(traction * area / (b->n_right * pdk_particles_volume(b->p)[0]));
  } else {
    bcs[1].kind = PDK_BC_DISPLACEMENT;
    bcs[1].value[0] = pdk_tfun_constant(u_end);
  }
  pdk_static_opts so = pdk_static_opts_default(method);
  so.bcs = bcs;
  so.num_bcs = 2;
  if (method == PDK_STATIC_ADR) so.rtol = 1e-8;
  pdk_static *s;
  T_OK(ctx, pdk_static_create(b->m, &so, &s));
  T_OK(ctx, pdk_static_solve(s));
  const pdk_static_stats *st = pdk_static_stats_get(s);
  if (getenv("PDK_TEST_VERBOSE")) pdk_static_stats_print(st, stdout);
  const pdk_index n = pdk_particles_count(b->p);
  *u = malloc((size_t)dim * (size_t)n * sizeof(double));
  for (int c = 0; c < dim; ++c) {
    const double *x = pdk_particles_field_data(b->p, "x", c), *X = pdk_particles_X(b->p, c);
    for (pdk_index i = 0; i < n; ++i)
      (*u)[(size_t)c * n + i] = x[i] - X[i];
  }
  if (method == PDK_STATIC_NEWTON) {
    /* Independent residual: trial forces at the solution, r = V (f + b) on free components. */
    T_OK(ctx, pdk_model_force_trial(b->m, NULL));
    const double *vol = pdk_particles_volume(b->p);
    const uint8_t *left = pdk_particles_field_data(b->p, "set:left", 0);
    const uint8_t *right = pdk_particles_field_data(b->p, "set:right", 0);
    double r2 = 0.0, F2 = 0.0, xmax = 0.0;
    for (int c = 0; c < dim; ++c) {
      const double *f = pdk_particles_field_data(b->p, "f", c);
      const double *x = pdk_particles_field_data(b->p, "x", c);
      for (pdk_index i = 0; i < n; ++i) {
        xmax = fmax(xmax, fabs(x[i]));
        const double load = c == 0 && right[i] ? bcs[1].value[0].a : 0.0;
        const int fixed = left[i] || (c == 0 && right[i] && bcs[1].kind == PDK_BC_DISPLACEMENT);
        const double ri = vol[i] * (f[i] + (bcs[1].kind == PDK_BC_BODY_FORCE ? load : 0.0));
        if (fixed)
          F2 += ri * ri;
        else {
          r2 += ri * ri;
          F2 += (vol[i] * load) * (vol[i] * load) * (bcs[1].kind == PDK_BC_BODY_FORCE);
        }
      }
    }
    int ncol;
    const int *Ap, *Ai;
    const double *Ax;
    T_OK(ctx, pdk_newton_tangent(s, 1, &ncol, &Ap, &Ai, &Ax));
    double kf = 0.0;
    for (int k = 0; k < Ap[ncol]; ++k)
      kf += Ax[k] * Ax[k];
    *floor = 2.220446049250313e-16 * xmax * sqrt(kf);
    *rel_residual = sqrt(r2) / sqrt(F2);
    T_ASSERT(sqrt(r2) <= *floor, "Newton residual %.3e is above the round-off floor %.3e", sqrt(r2),
             *floor);
    T_ASSERT(st->iterations <= 4, "a near-linear problem took %ld Newton iterations",
             st->iterations);
  }
  pdk_static_destroy(&s);
}

static void compare(pdk_ctx *ctx, int dim, double L, double H, double dx, double rf,
                    pdk_model_kind kind, pdk_law law, double u_end, double traction) {
  double *u[2];
  double rel = 0.0, floor = 0.0;
  pdk_index n = 0;
  for (int method = 0; method < 2; ++method) {
    body b = build(ctx, dim, L, H, dx, rf, kind, law);
    n = pdk_particles_count(b.p);
    solve(ctx, &b, dim, H, (pdk_static_method)method, u_end, traction, &u[method], &rel, &floor);
    destroy(&b);
  }
  double dmax = 0.0, umax = 0.0;
  for (size_t k = 0; k < (size_t)dim * (size_t)n; ++k) {
    dmax = fmax(dmax, fabs(u[0][k] - u[1][k]));
    umax = fmax(umax, fabs(u[1][k]));
  }
  if (getenv("PDK_TEST_VERBOSE"))
    printf("%dD %s: ADR-Newton %.3e of max |u| %.3e; Newton residual %.3e of the load\n", dim,
           pdk_model_kind_name(kind), dmax / umax, umax, rel);
  T_ASSERT(umax > 0, "no displacement");
  T_ASSERT(dmax <= 1e-5 * umax, "%dD %s: ADR and Newton differ by %.3e (max |u| %.3e)", dim,
           pdk_model_kind_name(kind), dmax, umax);
  T_ASSERT(rel <= 1e-9, "%dD %s: Newton residual %.3e of the load", dim, pdk_model_kind_name(kind),
           rel);
  free(u[0]);
  free(u[1]);
}

/* Mean u_x of the loaded end, Newton, correspondence with the linear law, traction T. */
static double end_displacement(pdk_ctx *ctx, double L, double H, double dx, double rf, double T) {
  body b = build(ctx, 2, L, H, dx, rf, PDK_MODEL_CORRESPONDENCE, PDK_LAW_LINEAR_ELASTIC);
  double *u, rel, floor;
  solve(ctx, &b, 2, H, PDK_STATIC_NEWTON, 0.0, T, &u, &rel, &floor);
  const uint8_t *right = pdk_particles_field_data(b.p, "set:right", 0);
  double sum = 0.0;
  for (pdk_index i = 0; i < pdk_particles_count(b.p); ++i)
    if (right[i]) sum += u[i];
  const double mean = sum / b.n_right;
  free(u);
  destroy(&b);
  return mean;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const double L = 20.0, H = 4.0, dx = 0.5, rf = 2.015; /* 2-D bar: 41 x 9 particles */

  /* 2-D bar: end displacement (PMB), end traction (LPS, correspondence). */
  compare(ctx, 2, L, H, dx, rf, PDK_MODEL_PMB, PDK_LAW_LINEAR_ELASTIC, 0.02, 0.0);
  compare(ctx, 2, L, H, dx, rf, PDK_MODEL_LPS, PDK_LAW_LINEAR_ELASTIC, 0.0, 1.0);
  compare(ctx, 2, L, H, dx, rf, PDK_MODEL_CORRESPONDENCE, PDK_LAW_LINEAR_ELASTIC, 0.0, 1.0);
  /* 3-D block 4 x 2 x 2 (9 x 5 x 5 particles): traction (PMB), displacement (LPS), and the
   * nonlinear St Venant-Kirchhoff law under traction (correspondence). */
  compare(ctx, 3, 4.0, 2.0, 0.5, 1.515, PDK_MODEL_PMB, PDK_LAW_LINEAR_ELASTIC, 0.0, 1.0);
  compare(ctx, 3, 4.0, 2.0, 0.5, 1.515, PDK_MODEL_LPS, PDK_LAW_LINEAR_ELASTIC, 0.004, 0.0);
  compare(ctx, 3, 4.0, 2.0, 0.5, 1.515, PDK_MODEL_CORRESPONDENCE, PDK_LAW_SVK, 0.0, 1.0);

  /* Linear problem against u(L) = T L / E, at h and h/2. */
  const double T = 1.0, exact = T * L / 1000.0;
  const double e1 = end_displacement(ctx, L, H, dx, rf, T) / exact - 1.0;
  const double e2 = end_displacement(ctx, L, H, 0.5 * dx, rf, T) / exact - 1.0;
  if (getenv("PDK_TEST_VERBOSE"))
    printf("uniaxial: error %.4e (h = %g), %.4e (h = %g), ratio %.3f\n", e1, dx, e2, 0.5 * dx,
           e1 / e2);
  T_ASSERT(fabs(e1) <= rf * dx / H,
           "uniaxial end displacement off by %.3e (allowed delta/H = %.3e)", e1, rf * dx / H);
  T_ASSERT(fabs(e2) <= rf * 0.5 * dx / H,
           "uniaxial end displacement off by %.3e at h/2 (allowed %.3e)", e2, rf * 0.5 * dx / H);
  T_ASSERT(e1 / e2 >= 1.6 && e1 / e2 <= 2.4, "error ratio %.3f on halving h is not first order",
           e1 / e2);
  pdk_ctx_destroy(&ctx);
  return 0;
}
