/* Johnson-Cook plasticity and damage: defaults, parameter checks, and the public per-point
 * functions, each a call of its pure kernel in kernels/ref/jc.c (formulation and definitions in
 * its header comment) after the argument checks. */
#include <math.h>
#include <string.h>

#include "kernels.h"
#include "core/pdk_impl.h"
#include "pdk/plasticity.h"
#include "pdk/ctx.h"

pdk_jc_params pdk_jc_params_default(void) {
  pdk_jc_params p;
  memset(&p, 0, sizeof p);
  p.density = 7830.0;        /* kg/m^3 */
  p.young_modulus = 200.0e9; /* Pa */
  p.poisson_ratio = 0.29;
  p.A = 792.0e6; /* Pa */
  p.B = 510.0e6; /* Pa */
  p.n = 0.26;
  p.C = 0.0;        /* rate term off (Johnson-Cook 4340: 0.014) */
  p.ref_rate = 1.0; /* 1/s */
  p.thermal = 0;
  p.m = 1.03;
  p.T_room = 293.0;  /* K */
  p.T_melt = 1793.0; /* K */
  p.T_initial = 293.0;
  p.beta = 0.9;
  p.heat_capacity = 477.0; /* J/(kg K) */
  p.damage = 1;
  p.D1 = 0.05;
  p.D2 = 3.44;
  p.D3 = -2.12;
  p.D4 = 0.0; /* Johnson-Cook 4340: 0.002 */
  p.D5 = 0.0; /* Johnson-Cook 4340: 0.61 */
  p.D_c = 0.3;
  p.coupling = PDK_JC_COUPLING_NONE;
  p.failed_mode = PDK_JC_FAILED_ZERO;
  return p;
}

pdk_jc_state pdk_jc_state_initial(void) {
  pdk_jc_state s;
  memset(&s, 0, sizeof s);
  s.cp_inv[0] = s.cp_inv[1] = s.cp_inv[2] = 1.0;
  return s;
}

int pdk_jc_params_check(pdk_ctx *ctx, const pdk_jc_params *p) {
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CHECK(p, ctx, PDK_ERR_ARG,
            "Johnson-Cook parameters are NULL; start from pdk_jc_params_default()");
  PDK_CHECK(isfinite(p->density) && p->density > 0, ctx, PDK_ERR_ARG,
            "Johnson-Cook density = %g: must be finite and > 0 [mass/length^3]", p->density);
  PDK_CHECK(isfinite(p->young_modulus) && p->young_modulus > 0, ctx, PDK_ERR_ARG,
            "Johnson-Cook young_modulus E = %g: must be finite and > 0", p->young_modulus);
  PDK_CHECK(isfinite(p->poisson_ratio) && p->poisson_ratio > -1.0 && p->poisson_ratio < 0.5, ctx,
            PDK_ERR_ARG, "Johnson-Cook poisson_ratio nu = %g: must lie in (-1, 0.5)",
            p->poisson_ratio);
  PDK_CHECK(isfinite(p->A) && p->A >= 0, ctx, PDK_ERR_ARG,
            "Johnson-Cook A = %g: initial yield stress must be finite and >= 0", p->A);
  PDK_CHECK(isfinite(p->B) && p->B >= 0, ctx, PDK_ERR_ARG,
            "Johnson-Cook B = %g: hardening modulus must be finite and >= 0", p->B);
  PDK_CHECK(p->A + p->B > 0, ctx, PDK_ERR_ARG,
            "Johnson-Cook A = %g and B = %g: A + B must be > 0 (a material with no strength)", p->A,
            p->B);
  PDK_CHECK(isfinite(p->n) && p->n > 0, ctx, PDK_ERR_ARG,
            "Johnson-Cook n = %g: hardening exponent must be finite and > 0", p->n);
  PDK_CHECK(isfinite(p->C) && p->C >= 0, ctx, PDK_ERR_ARG,
            "Johnson-Cook C = %g: rate sensitivity must be finite and >= 0 (0 turns the rate "
            "term off)",
            p->C);
  PDK_CHECK((p->C == 0 && (!p->damage || p->D4 == 0)) || (isfinite(p->ref_rate) && p->ref_rate > 0),
            ctx, PDK_ERR_ARG,
            "Johnson-Cook ref_rate = %g: the reference strain rate must be finite and > 0 when "
            "C or D4 is not 0",
            p->ref_rate);
  PDK_CHECK(p->thermal == 0 || p->thermal == 1, ctx, PDK_ERR_ARG,
            "Johnson-Cook thermal = %d: must be 0 (off) or 1 (on)", p->thermal);
  if (p->thermal) {
    PDK_CHECK(isfinite(p->m) && p->m > 0, ctx, PDK_ERR_ARG,
              "Johnson-Cook m = %g: thermal softening exponent must be finite and > 0 "
              "(thermal = 1)",
              p->m);
    PDK_CHECK(isfinite(p->T_room) && isfinite(p->T_melt) && p->T_melt > p->T_room, ctx, PDK_ERR_ARG,
              "Johnson-Cook T_melt = %g, T_room = %g: must be finite with T_melt > T_room",
              p->T_melt, p->T_room);
    PDK_CHECK(isfinite(p->T_initial), ctx, PDK_ERR_ARG,
              "Johnson-Cook T_initial = %g: must be finite", p->T_initial);
    PDK_CHECK(isfinite(p->beta) && p->beta >= 0 && p->beta <= 1, ctx, PDK_ERR_ARG,
              "Johnson-Cook beta = %g: the Taylor-Quinney fraction must lie in [0, 1]", p->beta);
    PDK_CHECK(isfinite(p->heat_capacity) && p->heat_capacity > 0, ctx, PDK_ERR_ARG,
              "Johnson-Cook heat_capacity c_p = %g: must be finite and > 0 (thermal = 1)",
              p->heat_capacity);
  }
  PDK_CHECK(p->damage == 0 || p->damage == 1, ctx, PDK_ERR_ARG,
            "Johnson-Cook damage = %d: must be 0 (off) or 1 (on)", p->damage);
  if (p->damage) {
    PDK_CHECK(isfinite(p->D1) && isfinite(p->D2) && isfinite(p->D3), ctx, PDK_ERR_ARG,
              "Johnson-Cook D1 = %g, D2 = %g, D3 = %g: must be finite", p->D1, p->D2, p->D3);
    PDK_CHECK(p->D1 + p->D2 > 0, ctx, PDK_ERR_ARG,
              "Johnson-Cook D1 = %g, D2 = %g: the failure strain at zero triaxiality, D1 + D2, "
              "must be > 0",
              p->D1, p->D2);
    PDK_CHECK(isfinite(p->D4) && p->D4 >= 0, ctx, PDK_ERR_ARG,
              "Johnson-Cook D4 = %g: must be finite and >= 0 (0 turns the rate term off)", p->D4);
    PDK_CHECK(isfinite(p->D5), ctx, PDK_ERR_ARG, "Johnson-Cook D5 = %g: must be finite", p->D5);
    PDK_CHECK(p->D5 == 0 || p->thermal, ctx, PDK_ERR_ARG,
              "Johnson-Cook D5 = %g has no effect with thermal = 0 (T* is not tracked); set "
              "thermal = 1 or D5 = 0",
              p->D5);
    PDK_CHECK(p->D5 >= -1, ctx, PDK_ERR_ARG,
              "Johnson-Cook D5 = %g: must be >= -1 so that 1 + D5 T* >= 0 for T* in [0, 1]", p->D5);
    PDK_CHECK(isfinite(p->D_c) && p->D_c > 0 && p->D_c <= 1, ctx, PDK_ERR_ARG,
              "Johnson-Cook D_c = %g: critical damage must lie in (0, 1] (the point fails when "
              "D >= D_c; D_c = 1 is plain Johnson-Cook 1985)",
              p->D_c);
    PDK_CHECK((unsigned)p->coupling <= PDK_JC_COUPLING_EFFECTIVE, ctx, PDK_ERR_ARG,
              "Johnson-Cook coupling = %d: must be PDK_JC_COUPLING_NONE (0) or "
              "PDK_JC_COUPLING_EFFECTIVE (1)",
              (int)p->coupling);
    PDK_CHECK((unsigned)p->failed_mode <= PDK_JC_FAILED_COMPRESSION, ctx, PDK_ERR_ARG,
              "Johnson-Cook failed_mode = %d: must be PDK_JC_FAILED_ZERO (0) or "
              "PDK_JC_FAILED_COMPRESSION (1)",
              (int)p->failed_mode);
  }
  return PDK_SUCCESS;
}

int pdk_jc_update(const pdk_jc_params *p, int dim, const double F[3][3], double dt,
                  const pdk_jc_state *in, pdk_jc_state *out, double P[3][3], pdk_jc_result *res) {
  if (!p || !F || !in || !out || !P) return PDK_ERR_ARG;
  return pdk_jc_update_full_kernel(p, dim, F, dt, NULL, in, out, P, res);
}

int pdk_jc_update_avg(const pdk_jc_params *p, int dim, const double F[3][3], double dt,
                      double sigma_m_avg, const pdk_jc_state *in, pdk_jc_state *out, double P[3][3],
                      pdk_jc_result *res) {
  if (!p || !F || !in || !out || !P || !isfinite(sigma_m_avg)) return PDK_ERR_ARG;
  return pdk_jc_update_full_kernel(p, dim, F, dt, &sigma_m_avg, in, out, P, res);
}

int pdk_jc_remap(int dim, const double F_old[3][3], const double F_new[3][3], pdk_jc_state *s) {
  return pdk_jc_remap_kernel(dim, F_old, F_new, s);
}

double pdk_jc_flow_stress(const pdk_jc_params *p, double eps_p, double rate_star, double T_star) {
  return pdk_jc_flow_stress_kernel(p, eps_p, rate_star, T_star);
}

double pdk_jc_failure_strain(const pdk_jc_params *p, double eta, double rate_star, double T_star) {
  return pdk_jc_failure_strain_kernel(p, eta, rate_star, T_star);
}
