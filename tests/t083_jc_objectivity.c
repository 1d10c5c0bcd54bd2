/* Johnson-Cook plasticity is objective (frame-indifferent), 3-D and plane strain.
 *  A. A point deformed plastically to F0 is then rotated rigidly, F = R(theta_k) F0, in 60 steps
 *     of 0.13 rad (7.8 rad > 2 pi in total) about a skew axis (about z in plane strain): the von
 *     Mises stress, eps_p, D, W and C_p^-1 stay what they were, the Cauchy stress is R sigma0 R^T
 *     and P = R P0. Once for a point on the yield surface (at the end of plastic loading) and once
 *     for a point inside it (after partial elastic unloading), where the rotation steps are
 *     elastic and the history must not change by a single bit.
 *  B. Superposed rotations during plastic loading: a non-proportional path F_k (stretch, shear,
 *     rotating stretch axes) and the same path seen from a rotating frame, Q_k F_k, with Q_k
 *     jumping by 0.37 rad per step (several turns over the run), rate and damage terms on: the
 *     histories agree and sigma_B = Q sigma_A Q^T at every step.
 * labels: unit physics
 *
 * Tolerances: rotation changes b_tr = F C_p^-1 F^T into R b_tr R^T only up to round-off (a few
 * ulps per product), which the eigen-decomposition passes on; a point exactly on the yield
 * surface may take plastic steps of round-off size. Measured deviations are ~1e-15 relative
 * per step; after 60 steps 1e-12 relative (stresses, W, C_p^-1) and 1e-13 absolute (eps_p, D)
 * leave a wide margin while still catching any rotation-dependent term (a hypoelastic update
 * without an objective rate errs by O(1) here).
 */
#include "jc_util.h"

/* |A - B| max entry, d x d */
static double max_diff(int dim, const double A[3][3], const double B[3][3]) {
  double m = 0.0;
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j)
      m = fmax(m, fabs(A[i][j] - B[i][j]));
  return m;
}

static double max_abs(int dim, const double A[3][3]) {
  double m = 0.0;
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j)
      m = fmax(m, fabs(A[i][j]));
  return m;
}

static void sym_from_voigt(const double v[6], double M[3][3]) {
  M[0][0] = v[0];
  M[1][1] = v[1];
  M[2][2] = v[2];
  M[1][2] = M[2][1] = v[3];
  M[0][2] = M[2][0] = v[4];
  M[0][1] = M[1][0] = v[5];
}

/* R S R^T */
static void rotate_sym(const double R[3][3], const double S[3][3], double out[3][3]) {
  double T[3][3];
  ju_mul(R, S, T);
  ju_mul_bt(T, R, out);
}

static void check_rigid_rotation(const pdk_jc_params *p, int dim, int unload, const char *what) {
  const double axis3[3] = {0.48, -0.6, 0.64}, axisz[3] = {0.0, 0.0, 1.0};
  const double *axis = dim == 3 ? axis3 : axisz;
  pdk_jc_state st = pdk_jc_state_initial();
  double F0[3][3], P0[3][3];
  pdk_jc_result r0;
  /* plastic loading: stretch and shear in 40 steps */
  for (int k = 1; k <= 40; ++k) {
    const double t = 0.01 * k;
    ju_identity(F0);
    F0[0][0] = exp(t);
    F0[1][1] = exp((dim == 3 ? -0.55 : -1.0) * t);
    F0[0][1] = 0.4 * t;
    if (dim == 3) {
      F0[2][2] = exp(-0.45 * t);
      F0[1][2] = -0.2 * t;
    }
    ju_update(p, dim, F0, 1e-4, &st, &st, P0, &r0);
  }
  T_ASSERT(r0.plastic && !st.failed && st.eps_p > 0.1,
           "%s: loading not plastic or failed (eps_p %g, D %g)", what, st.eps_p, st.damage);
  if (unload) { /* partial elastic unloading: back along the last increment, 30% of the way */
    F0[0][0] *= exp(-0.001);
    F0[1][1] *= exp(dim == 3 ? 0.00055 : 0.001);
    ju_update(p, dim, F0, 1e-4, &st, &st, P0, &r0);
    T_ASSERT(!r0.plastic && r0.tau_vm < 0.999 * r0.yield_stress, "%s: unloading not elastic", what);
  }
  const pdk_jc_state s0 = st;
  double sig0[3][3];
  sym_from_voigt(r0.sigma, sig0);
  const double sscale = ju_von_mises(sig0), Pscale = max_abs(dim, P0);
  for (int k = 1; k <= 60; ++k) {
    double R[3][3], F[3][3], P[3][3], RP[3][3], sig[3][3], Rsig[3][3];
    pdk_jc_result r;
    ju_rotation(axis, 0.13 * k, R);
    ju_mul(R, F0, F);
    ju_update(p, dim, F, 1e-4, &st, &st, P, &r);
    T_NEAR(r.tau_vm, r0.tau_vm, 1e-12, 0.0, "%s, rotation step %d: tau_vm", what, k);
    T_NEAR(r.sigma_vm, r0.sigma_vm, 1e-12, 0.0, "%s, rotation step %d: sigma_vm", what, k);
    T_NEAR(st.eps_p, s0.eps_p, 0.0, 1e-13, "%s, rotation step %d: eps_p", what, k);
    T_NEAR(st.damage, s0.damage, 0.0, 1e-13, "%s, rotation step %d: D", what, k);
    T_NEAR(r.W, r0.W, 1e-12, 0.0, "%s, rotation step %d: W", what, k);
    for (int c = 0; c < 6; ++c)
      T_NEAR(st.cp_inv[c], s0.cp_inv[c], 0.0, 1e-12, "%s, rotation step %d: C_p^-1[%d]", what, k,
             c);
    if (unload)
      T_ASSERT(ju_state_equal(&st, &s0),
               "%s, rotation step %d: elastic rotation changed the history", what, k);
    sym_from_voigt(r.sigma, sig);
    rotate_sym(R, sig0, Rsig);
    const double es = max_diff(3, sig, Rsig);
    if (es > 1e-12 * sscale)
      T_FAIL("%s, rotation step %d (%.2f rad): |sigma - R sigma0 R^T| = %.3g > 1e-12 * %.3g", what,
             k, 0.13 * k, es, sscale);
    ju_mul(R, P0, RP);
    const double ep = max_diff(dim, P, RP);
    if (ep > 1e-12 * Pscale)
      T_FAIL("%s, rotation step %d: |P - R P0| = %.3g > 1e-12 * %.3g", what, k, ep, Pscale);
  }
}

static void check_superposed(const pdk_jc_params *p, int dim, const char *what) {
  const double axis3[3] = {-0.36, 0.48, 0.8}, axisz[3] = {0.0, 0.0, 1.0};
  const double *axis = dim == 3 ? axis3 : axisz;
  pdk_jc_state sa = pdk_jc_state_initial(), sb = pdk_jc_state_initial();
  for (int k = 1; k <= 60; ++k) {
    const double t = 0.008 * k;
    double F[3][3], U[3][3], Rt[3][3], Q[3][3], FB[3][3], PA[3][3], PB[3][3], QPA[3][3];
    pdk_jc_result ra, rb;
    /* stretch with rotating axes, then shear: non-proportional */
    ju_identity(U);
    U[0][0] = exp(t);
    U[1][1] = exp((dim == 3 ? -0.5 : -1.0) * t);
    if (dim == 3) U[2][2] = exp(-0.5 * t);
    ju_rotation(axisz, 2.0 * t, Rt);
    double T[3][3];
    ju_mul(Rt, U, T);
    double V[3][3], S[3][3];
    ju_mul_bt(T, Rt, V);
    ju_identity(S); /* simple shear, det 1 */
    S[0][1] = 0.3 * t;
    ju_mul(V, S, F);
    ju_rotation(axis, 0.37 * k, Q);
    ju_mul(Q, F, FB);
    ju_update(p, dim, F, 2e-6, &sa, &sa, PA, &ra);
    ju_update(p, dim, FB, 2e-6, &sb, &sb, PB, &rb);
    T_ASSERT(ra.plastic == rb.plastic && sa.failed == sb.failed, "%s, step %d: plastic %d/%d", what,
             k, ra.plastic, rb.plastic);
    T_NEAR(sb.eps_p, sa.eps_p, 0.0, 1e-13, "%s, step %d: eps_p", what, k);
    T_NEAR(sb.damage, sa.damage, 0.0, 1e-13, "%s, step %d: D", what, k);
    for (int c = 0; c < 6; ++c)
      T_NEAR(sb.cp_inv[c], sa.cp_inv[c], 0.0, 1e-12, "%s, step %d: C_p^-1[%d]", what, k, c);
    T_NEAR(rb.W, ra.W, 1e-12, 0.0, "%s, step %d: W", what, k);
    T_NEAR(rb.dW_plastic, ra.dW_plastic, 1e-10, 1e-3, "%s, step %d: dW_plastic", what, k);
    double sa_m[3][3], sb_m[3][3], Qsa[3][3];
    sym_from_voigt(ra.sigma, sa_m);
    sym_from_voigt(rb.sigma, sb_m);
    rotate_sym(Q, sa_m, Qsa);
    const double scale = fmax(ju_von_mises(sa_m), 1.0);
    const double es = max_diff(3, sb_m, Qsa);
    if (es > 1e-12 * scale)
      T_FAIL("%s, step %d: |sigma_B - Q sigma_A Q^T| = %.3g > 1e-12 * %.3g", what, k, es, scale);
    ju_mul(Q, PA, QPA);
    const double ep = max_diff(dim, PB, QPA);
    if (ep > 1e-12 * fmax(max_abs(dim, PA), 1.0))
      T_FAIL("%s, step %d: |P_B - Q P_A| = %.3g", what, k, ep);
  }
  T_ASSERT(sa.eps_p > 0.2, "%s: path too mild (eps_p %g)", what, sa.eps_p);
}

int main(void) {
  const pdk_jc_params def = pdk_jc_params_default();
  for (int dim = 2; dim <= 3; ++dim) {
    const char *d = dim == 3 ? "3-D" : "plane strain";
    char what[96];
    snprintf(what, sizeof what, "%s, on the yield surface", d);
    check_rigid_rotation(&def, dim, 0, what);
    snprintf(what, sizeof what, "%s, inside the yield surface", d);
    check_rigid_rotation(&def, dim, 1, what);
    pdk_jc_params p = def;
    p.C = 0.014;
    p.D4 = 0.002;
    p.coupling = PDK_JC_COUPLING_EFFECTIVE;
    snprintf(what, sizeof what, "%s, superposed rotations, rate on, coupled damage", d);
    check_superposed(&p, dim, what);
    p.thermal = 1;
    p.D5 = 0.61;
    snprintf(what, sizeof what, "%s, superposed rotations, thermal", d);
    check_superposed(&p, dim, what);
  }
  return 0;
}
