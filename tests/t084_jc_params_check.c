/* Johnson-Cook parameters: the defaults are the V-JC steel and pass the check; every out-of-range
 * parameter is refused with PDK_ERR_ARG and a message that names it; pdk_jc_update refuses bad
 * input (dim, det F <= 0, non-finite F, dt <= 0 with a rate term) without writing anything, and a
 * virgin point under F = 1 has no stress.
 * labels: unit
 */
#include "jc_util.h"

#define BAD(field, value, needle)                                                                  \
  do {                                                                                             \
    pdk_jc_params q_ = def;                                                                        \
    q_.field = value;                                                                              \
    T_FAILS(ctx, pdk_jc_params_check(ctx, &q_), PDK_ERR_ARG, needle);                              \
  } while (0)

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  const pdk_jc_params def = pdk_jc_params_default();
  T_OK(ctx, pdk_jc_params_check(ctx, &def));
  /* the V-JC values */
  T_ASSERT(def.density == 7830.0 && def.young_modulus == 200e9 && def.poisson_ratio == 0.29 &&
               def.A == 792e6 && def.B == 510e6 && def.n == 0.26 && def.D1 == 0.05 &&
               def.D2 == 3.44 && def.D3 == -2.12 && def.D_c == 0.3 && def.C == 0.0 &&
               def.thermal == 0 && def.D4 == 0.0 && def.D5 == 0.0 && def.damage == 1,
           "defaults are not the V-JC steel");

  BAD(density, 0.0, "density");
  BAD(young_modulus, -1.0, "young_modulus");
  BAD(poisson_ratio, 0.5, "poisson_ratio");
  BAD(poisson_ratio, NAN, "poisson_ratio");
  BAD(A, -1.0, "A = ");
  BAD(B, -1.0, "B = ");
  BAD(n, 0.0, "n = ");
  BAD(C, -0.1, "C = ");
  {
    pdk_jc_params q = def;
    q.C = 0.01;
    q.ref_rate = 0.0;
    T_FAILS(ctx, pdk_jc_params_check(ctx, &q), PDK_ERR_ARG, "ref_rate");
    q.A = 0.0;
    q.B = 0.0;
    q.ref_rate = 1.0;
    T_FAILS(ctx, pdk_jc_params_check(ctx, &q), PDK_ERR_ARG, "A + B");
  }
  BAD(thermal, 2, "thermal");
  BAD(D5, 0.5, "D5"); /* D5 without thermal */
  BAD(D_c, 0.0, "D_c");
  BAD(D_c, 1.5, "D_c");
  BAD(D4, -0.1, "D4");
  BAD(D1, INFINITY, "D1");
  BAD(damage, 3, "damage");
  BAD(coupling, (pdk_jc_coupling)7, "coupling");
  BAD(failed_mode, (pdk_jc_failed)7, "failed_mode");
  {
    pdk_jc_params q = def;
    q.thermal = 1;
    T_OK(ctx, pdk_jc_params_check(ctx, &q));
    q.T_melt = q.T_room;
    T_FAILS(ctx, pdk_jc_params_check(ctx, &q), PDK_ERR_ARG, "T_melt");
    q = def;
    q.thermal = 1;
    q.m = 0.0;
    T_FAILS(ctx, pdk_jc_params_check(ctx, &q), PDK_ERR_ARG, "m = ");
    q = def;
    q.thermal = 1;
    q.beta = 1.5;
    T_FAILS(ctx, pdk_jc_params_check(ctx, &q), PDK_ERR_ARG, "beta");
    q = def;
    q.thermal = 1;
    q.heat_capacity = 0.0;
    T_FAILS(ctx, pdk_jc_params_check(ctx, &q), PDK_ERR_ARG, "heat_capacity");
  }

  /* update: bad input refused, nothing written */
  pdk_jc_state in = pdk_jc_state_initial(), out;
  double F[3][3], P[3][3];
  pdk_jc_result r;
  memset(&out, 0x5a, sizeof out);
  const pdk_jc_state canary = out;
  ju_identity(F);
  T_ASSERT(pdk_jc_update(&def, 4, F, 1e-3, &in, &out, P, &r) == PDK_ERR_ARG, "dim 4 accepted");
  F[0][0] = -1.0;
  T_ASSERT(pdk_jc_update(&def, 3, F, 1e-3, &in, &out, P, &r) == PDK_ERR_NUMERIC,
           "det F < 0 accepted");
  F[0][0] = NAN;
  T_ASSERT(pdk_jc_update(&def, 2, F, 1e-3, &in, &out, P, &r) == PDK_ERR_NUMERIC, "NaN F accepted");
  ju_identity(F);
  pdk_jc_params pr = def;
  pr.C = 0.014;
  T_ASSERT(pdk_jc_update(&pr, 3, F, 0.0, &in, &out, P, &r) == PDK_ERR_ARG,
           "dt = 0 accepted with a rate term");
  T_ASSERT(ju_state_equal(&out, &canary), "a refused update wrote the history");
  /* without a rate term dt is not read */
  T_ASSERT(pdk_jc_update(&def, 3, F, 0.0, &in, &out, P, NULL) == 0, "dt = 0 refused without rate");
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      T_ASSERT(P[i][j] == 0.0, "P[%d][%d] = %g at F = 1", i, j, P[i][j]);
  T_ASSERT(ju_state_equal(&out, &in), "F = 1 changed a virgin history");
  pdk_ctx_destroy(&ctx);
  return 0;
}
