/* Peridynamic Galerkin on Bode et al.'s manufactured field (2022 section 7.3, eqs. 86-87):
 * u = (sin(pi X/2) cos(pi Y/2), cos(pi X/2) sin(pi Y/2)) on [-1, 1]^2, its body force
 * (pi^2/2)(lambda + 2 mu) u, the exact values on the edge particles, the irregular cloud of the
 * patch test (n1 = 9, 17, 33 nodes a side, jitter 0.3 h), horizon 2.51 h, Newton; relative L2
 * error of u (the same runs as bench/bench_pg_tradeoff.c).
 * labels: galerkin physics
 *
 * What must hold, and why these bounds. Bode et al. report order 2 in L2 for the PG method
 * (their Fig. 6). Measured orders 9 -> 17 -> 33: taylor vc1 2.23, 2.08; with the bond correction
 * 2.19, 1.84 (2.00 and 1.96 further on, docs/tradeoff.md); asserted >= 1.7 on each step, a first-
 * order method fails it. The bond correction's error is lower (measured 2.7x at n1 = 33;
 * asserted lower). Correspondence with Silling's stabilization on the same particles and
 * families converges at first order at best here (measured 0.85, 1.01); asserted: its error at
 * n1 = 33 above 3 times galerkin's (measured 7.6x).
 */
#include "galerkin_util.h"

#include "../tests/galerkin_util.h"

static void exact(int problem, double X, double Y, double u[2]) {
  if (problem == 0) {
    u[0] = pg_H[0][0] * X + pg_H[0][1] * Y;
    u[1] = pg_H[1][0] * X + pg_H[1][1] * Y;
  } else {
    const double a = M_PI * X / 2, b = M_PI * Y / 2;
    u[0] = sin(a) * cos(b);
    u[1] = cos(a) * sin(b);
  }
}

/* One run (model: 0 correspondence Silling, 2 galerkin taylor vc1, 3 the same with the bond
 * correction): the relative L2 error of u. */
static double run(pdk_ctx *ctx, int problem, int model, int n1) {
  const double h = 2.0 / (n1 - 1);
  pdk_particles *p = pg_cloud(ctx, n1, 0.3, 1);
  const pdk_index n = pdk_particles_count(p);
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 2.51 * h;
  pdk_families *fam;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  pdk_model_opts mo = pg_model_opts(PDK_GALERKIN_TAYLOR, PDK_GALERKIN_VC1);
  if (model < 2) {
    mo.kind = PDK_MODEL_CORRESPONDENCE;
    mo.influence = model == 0 ? PDK_INFLUENCE_CONSTANT : PDK_INFLUENCE_INV_R2;
    mo.stabilization = model == 0 ? PDK_STAB_SILLING : PDK_STAB_NONE;
    mo.stab_coefficient = 0.1;
  }
  mo.galerkin.bond = model == 3;
  pdk_model *m;
  T_OK(ctx, pdk_model_create(p, fam, &mo, &m));
  T_OK(ctx, pdk_particles_field_add(p, "u_exact", PDK_F64, 2));
  T_OK(ctx, pdk_particles_field_add(p, "b_mms", PDK_F64, 2));
  const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1), *V = pdk_particles_volume(p);
  const double kb = M_PI * M_PI / 2 * (pg_lambda() + 2 * pg_mu());
  for (pdk_index k = 0; k < n; ++k) {
    double u[2];
    exact(problem, X[k], Y[k], u);
    for (int c = 0; c < 2; ++c) {
      ((double *)pdk_particles_field_data(p, "u_exact", c))[k] = u[c];
      ((double *)pdk_particles_field_data(p, "b_mms", c))[k] = problem == 1 ? kb * u[c] : 0.0;
    }
  }
  pdk_bc bcs[2];
  memset(bcs, 0, sizeof bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:surface";
  bcs[0].components = 3;
  bcs[0].value[0] = bcs[0].value[1] = pdk_tfun_constant(1.0);
  bcs[0].scale_field = "u_exact";
  bcs[1].kind = PDK_BC_BODY_FORCE;
  bcs[1].set = NULL;
  bcs[1].components = 3;
  bcs[1].value[0] = bcs[1].value[1] = pdk_tfun_constant(1.0);
  bcs[1].scale_field = "b_mms";
  pdk_static_opts so = pdk_static_opts_default(PDK_STATIC_NEWTON);
  so.bcs = bcs;
  so.num_bcs = problem == 1 ? 2 : 1;
  so.rtol = 1e-12;
  pdk_static *s;
  T_OK(ctx, pdk_static_create(m, &so, &s));
  T_OK(ctx, pdk_static_solve(s));
  pdk_static_destroy(&s);
  const double *x[2] = {pdk_particles_field_data(p, "x", 0), pdk_particles_field_data(p, "x", 1)};
  double e = 0.0, nn = 0.0;
  for (pdk_index k = 0; k < n; ++k) {
    double u[2];
    exact(problem, X[k], Y[k], u);
    const double uh[2] = {x[0][k] - X[k], x[1][k] - Y[k]};
    for (int c = 0; c < 2; ++c) {
      e += V[k] * (uh[c] - u[c]) * (uh[c] - u[c]);
      nn += V[k] * u[c] * u[c];
    }
  }
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  return sqrt(e / nn);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);
  const int n1s[3] = {9, 17, 33};
  double e[4][3];
  for (int model = 0; model < 4; ++model) {
    if (model == 1) continue;
    for (int r = 0; r < 3; ++r) {
      e[model][r] = run(ctx, 1, model, n1s[r]);
      T_INFO("model %d n1 %d: L2 %.4e%s", model, n1s[r], e[model][r], r ? "" : "\n");
      if (r) T_INFO(" order %.3f\n", log(e[model][r - 1] / e[model][r]) / log(2.0));
    }
  }
  for (int model = 2; model < 4; ++model)
    for (int r = 1; r < 3; ++r) {
      const double order = log(e[model][r - 1] / e[model][r]) / log(2.0);
      T_ASSERT(order >= 1.7, "galerkin (model %d): order %.3f from n1 %d to %d", model, order,
               n1s[r - 1], n1s[r]);
    }
  T_ASSERT(e[3][2] < e[2][2], "bond correction: %.3e, without %.3e", e[3][2], e[2][2]);
  T_ASSERT(e[0][2] > 3 * e[2][2], "correspondence %.3e against galerkin %.3e", e[0][2], e[2][2]);
  pdk_ctx_destroy(&ctx);
  return 0;
}
