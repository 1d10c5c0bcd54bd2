/* Reference correspondence kernels (non-ordinary state-based peridynamics, total Lagrangian,
 * nodal integration), 2-D plane strain and 3-D.
 *
 * Notation: particle i, bond b of i with neighbour j = bond_j[b], reference bond xi = X_j - X_i,
 * current bond Y = x_j - x_i, bond weight w_b = omega_b * alive_b (omega_b = influence function at
 * |xi|, alive_b = 1 intact / 0 broken; all intact when bond_alive == NULL), V_j the volume of j.
 * Tensors are d x d (d = 2 or 3), stored SoA: component T[a][c] is array a*d + c, each [n_pad].
 *
 * Shape (pdk_kernel_corr_shape_ref), once in total Lagrangian and again for a particle whose
 * intact-bond count changed:
 *   K_i = sum_b w_b V_j xi (x) xi        m_i = sum_b w_b V_j |xi|^2 (weighted volume)
 *   The family spans the space when det K_i >= span_rtol * (tr K_i / d)^d (and tr K_i > 0, all
 *   finite). det K / (tr K / d)^d is the ratio of the geometric to the arithmetic mean of the
 *   eigenvalues, to the power d: 1 for an isotropic family, 0 for collinear (2-D) or coplanar
 *   (3-D) bonds; span_rtol = 1e-6 (PDK_CORR_SPAN_RTOL) flags condition numbers beyond about
 *   4e6 (2-D). A family that does not span gets flag bit PDK_CORR_FLAG_SPAN and K^-1 = 0.
 *
 * Pass 1 (pdk_kernel_corr_pass1_ref), per particle i:
 *   N_i = sum_b w_b V_j Y (x) xi,   F_i = N_i K_i^-1,   P_i = law(F_i),   A_i = P_i K_i^-1,
 *   W_i = strain energy density of the law (per reference volume).
 *   Laws (lambda, mu Lame constants; 2-D plane strain: F, P, E are the in-plane 2 x 2 blocks and
 *   the out-of-plane stretch is 1, so J = det of the 2 x 2 F and tr(F^T F) - d = I_1 - 3):
 *     linear elastic  eps = sym(F) - I, P = sigma = lambda tr(eps) I + 2 mu eps,
 *                     W = lambda/2 tr(eps)^2 + mu eps:eps
 *     St Venant-K.    E = (F^T F - I)/2, S = lambda tr(E) I + 2 mu E, P = F S,
 *                     W = lambda/2 tr(E)^2 + mu E:E
 *     Neo-Hooke       J = det F, P = mu (F - F^-T) + lambda ln(J) F^-T,
 *                     W = mu/2 (tr(F^T F) - d) - mu ln J + lambda/2 (ln J)^2
 *     Johnson-Cook    P, W from pdk_jc_update (pdk/plasticity.h, kernels/ref/jc.c) with F_i, the
 *                     committed history of i as `in` and, in a commit pass, the same history as
 *                     `out` (advanced in place: i's history is read and written by i alone in
 *                     pass 1 and read by nobody else until the pass ends); in a trial pass `out`
 *                     is a local copy that is thrown away, so a trial changes no history. A
 *                     commit also adds the step's plastic and damage work to w_plastic, w_damage
 *                     and stores eps_p_rate. A failed particle (history failed = 1) gets P = 0
 *                     (or the compressive pressure of failed_mode) and flag bit
 *                     PDK_CORR_FLAG_FAILED, which also turns its stabilization off: it carries no
 *                     stress. In the commit pass where it fails (bit PDK_CORR_FLAG_FAILED_NOW),
 *                     pass 2 adds the Silling energy it would have held at this x to w_damage, so
 *                     the term's energy is accounted like the law's. A flagged (SPAN) particle's
 *                     history is frozen (eps_p_rate = 0).
 *                     Options (arrays non-NULL): damage triaxiality from sigma_m_avg[i]
 *                     (pdk_jc_update_avg), the commit writing sigma_m[i] = the step's effective
 *                     Cauchy mean stress; softened stabilization: the commit sets stab_factor[i]
 *                     = min(1, max(stab_floor, sigma_vm / (E eps_p))) when eps_p > 0 and i did
 *                     not fail and that is lower (it never rises), keeping the old value in
 *                     stab_prev[i] and the law's W in w_law[i] for the driver's energy account
 *                     (kernels.h); k_i below is then factor_i stab_modulus_i / m_i in every pass
 *                     and variant (pdk_corr_kst).
 *   A particle flagged by the shape gets F = 0, A = 0, W = 0. With Neo-Hooke or Johnson-Cook,
 *   J <= 0 (or a non-finite J) sets flag bit PDK_CORR_FLAG_INVERTED and A = 0, W = 0 for this
 *   pass (the bit is recomputed every pass; the JC history does not advance). So no NaN or
 *   infinity is ever stored.
 *   When bond_alive != NULL, pass 1 counts the intact bonds of i; if the count differs from
 *   num_alive[i] (bonds broke since K_i was computed), it recomputes the shape of i first.
 *
 * Pass 2 (pdk_kernel_corr_pass2_ref), force density [force / length^3 of reference volume]:
 *   f_i = sum_b V_j ( T_i<xi> - T_j<-xi> ),  T_i<xi> = w_b A_i xi + S_i<xi>,
 *   i.e. f_i = sum_b w_b V_j (A_i + A_j) xi + stabilization. A flagged particle has A = 0 and
 *   S = 0: it contributes no correspondence force (it still feels its neighbours' T_j).
 *   Stabilization, with z_i = Y - F_i xi (the non-uniform part of the deformation seen from i),
 *   z_j' = Y - F_j xi (the same bond seen from j, sign-flipped), k_i = stab_modulus / m_i (0 for a
 *   flagged particle):
 *     none       S = 0
 *     Silling    S_i<xi> = k_i w_b z_i          (Silling 2017, CMAME 322, 42-57)
 *                pair term: w_b V_j (k_i z_i + k_j z_j')
 *                energy:    W_i += k_i/2 sum_b w_b V_j |z_i|^2  (an exact potential: F_i is the
 *                w V-weighted least-squares fit of Y on xi, so sum_b w_b V_j z_i (x) xi = 0 and
 *                the variation of F drops out; hence f = -grad E holds with the term included)
 *     hourglass  S_i<xi> = k_i w_b (delta / |xi|) (z_i . e) e,  e = Y / |Y|   (Littlewood 2011,
 *                as in Peridigm's correspondence hourglass force: the Silling vector projected on
 *                the current bond, so every pair force is parallel to Y and angular momentum is
 *                conserved). pair term: w_b V_j (delta/|xi|) (k_i z_i.e + k_j z_j'.e) e.
 *                Not the gradient of an energy; it adds nothing to W.
 *   stab_modulus = C_s c_d K (K bulk modulus, C_s the user's coefficient; c_3 = 72/5, c_2 = 36/5),
 *   chosen so that for omega = 1 and a full continuum family (m = 4 pi delta^5 / 5 in 3-D,
 *   pi delta^4 h / 2 in 2-D with thickness h) k_i equals C_s c_PMB / delta, c_PMB the PMB
 *   micromodulus (18 K / (pi delta^4) in 3-D, 72 K / (5 pi h delta^3) in 2-D plane strain): the
 *   18 C_s K / (pi delta^5) of the Peridigm-derived implementations of Silling's term and the
 *   18 C_s K / (pi delta^4) / |xi| of Peridigm's hourglass force (with delta / |xi| above).
 *   Dividing by the particle's own m_i (rather than a constant) makes the term invariant under a
 *   rescaling of omega, like F and the correspondence force, and stiffer at surfaces, as LPS is.
 *   Why this and not another reading: see src/models/model_corr.c.
 *
 * Bond failure (pdk_kernel_corr_break_ref, commit passes only, bond_alive != NULL), after pass 2,
 * so the state it writes is read by the next pass: a bond intact at entry breaks when
 *   - (s0 != NULL) the LAMMPS s0 rule of kernels/ref/pmb.c: s = (|Y| - |xi|)/|xi| > min(s0_i,
 *     s0_j); s0_next_i = max over the bonds intact at entry of s00 - alpha s, DBL_MAX if none;
 *   - (break_failed) failed_i or failed_j, the histories just committed by pass 1.
 * Both ends decide identically: s is bit-identical from both ends (Y and xi only change sign) and
 * the failed test is symmetric, so a bond breaks from both ends in the same pass. Returns the
 * number of directed bonds broken; changed[i] = 3 marks the rows that lost bonds.
 *
 * After breaking (driver: src/models/model_corr.c), per commit pass with broken bonds:
 *   reshape  K, m recomputed from the intact family of every changed row (reference
 *            configuration); in semi-TL a changed row whose intact bonds no longer span (but are
 *            not none) is marked detach;
 *   cut      (semi-TL) every intact bond with a detached end breaks, from both ends; the rows
 *            that lost bonds are reshaped and the two steps repeat until nothing detaches;
 *   release  for every row that lost bonds in this pass (Johnson-Cook with break_stress
 *            continuous: first, if the row still carries stress, its C_p^-1 is remapped from this
 *            pass's F to the new family's F at the same x, pdk_jc_remap, so the stress and the
 *            law's energy do not jump): w_broken_i += W_i - W'_i, W_i the
 *            energy density of this pass (law + Silling term) and W'_i = the same at the same x
 *            with the new family, plus the plastic and damage work the jump of F would cause from
 *            the committed history (a trial update; nothing is written but w_broken). Only i's
 *            own family enters F_i, K_i, m_i and i's Silling term, so only changed rows jump:
 *            external work = kinetic + strain + plastic + damage + released holds across breaks.
 *
 * Contract: pure functions over particles [i0, i1); no allocation, no OpenMP region. A call writes
 * only per-particle entries i in [i0, i1) and bond entries of those particles' rows, and reads
 * neighbours' data written by an earlier pass, so the result for i does not depend on how the
 * range is split between threads. Families must be symmetric (j in H_i <=> i in H_j, same omega,
 * same alive state), as pdk_families_build makes them.
 */
#include <float.h>
#include <math.h>

#include "kernels.h"
#include "ref/corr_law.h"

/* ---- small dense tensors and the elastic laws: ref/corr_law.h ------------------------------- */

static void load_d(const int d, double *const *restrict src, pdk_index i, double T[3][3]) {
  for (int a = 0; a < d; ++a)
    for (int c = 0; c < d; ++c)
      T[a][c] = src[a * d + c][i];
}

static void store_d(const int d, double *const *restrict dst, pdk_index i, const double T[3][3]) {
  for (int a = 0; a < d; ++a)
    for (int c = 0; c < d; ++c)
      dst[a * d + c][i] = T[a][c];
}

static void store_zero_d(const int d, double *const *restrict dst, pdk_index i) {
  for (int c = 0; c < d * d; ++c)
    dst[c][i] = 0.0;
}

static int law_eval(const pdk_corr_consts *k, const double F[3][3], double P[3][3], double *W) {
  return pdk_corr_law_eval_d(k->dim, k, F, P, W);
}

/* ---- shape ------------------------------------------------------------------------------------
 */

/* Shape of one particle from its sums: K^-1 (or 0), m, the SPAN flag bit, the intact-bond count.
 * Returns 1 if the family does not span. */
int pdk_kernel_corr_shape_point_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                    pdk_index i, const double K[3][3], double m, int32_t count) {
  const int d = k->dim;
  double tr = 0.0;
  for (int c = 0; c < d; ++c)
    tr += K[c][c];
  const double det = pdk_det_d(d, K);
  const double mean = tr / d;
  const double scale = d == 2 ? mean * mean : mean * mean * mean;
  const int spans = tr > 0.0 && isfinite(tr) && isfinite(det) && det >= k->span_rtol * scale;
  if (spans) {
    double Kinv[3][3];
    pdk_inv_d(d, K, det, Kinv);
    store_d(d, a->Kinv, i, Kinv);
  } else {
    store_zero_d(d, a->Kinv, i);
  }
  if (a->m) a->m[i] = m;
  if (a->num_alive) a->num_alive[i] = count;
  a->flag[i] = (uint8_t)((a->flag[i] & ~PDK_CORR_FLAG_SPAN) | (spans ? 0u : PDK_CORR_FLAG_SPAN));
  return !spans;
}

/* Shape of one particle: sums over its family, then pdk_kernel_corr_shape_point_ref. */
static int shape_one(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i) {
  const int d = k->dim;
  const pdk_bond_index *restrict bond_start = a->bond_start;
  const pdk_index *restrict bond_j = a->bond_j;
  const double *restrict omega = a->bond_omega;
  const uint8_t *restrict alive = a->bond_alive;
  const double *restrict volume = a->volume;
  double K[3][3] = {{0}}, m = 0.0;
  int32_t count = 0;
  for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
    const pdk_index j = bond_j[b];
    const int on = alive ? alive[b] != 0 : 1;
    count += on;
    const double wv = on ? omega[b] * volume[j] : 0.0;
    double xi[3];
    for (int c = 0; c < d; ++c)
      xi[c] = a->X[c][j] - a->X[c][i];
    for (int r = 0; r < d; ++r) {
      m += wv * xi[r] * xi[r];
      for (int c = 0; c < d; ++c)
        K[r][c] += wv * xi[r] * xi[c];
    }
  }
  return pdk_kernel_corr_shape_point_ref(k, a, i, K, m, count);
}

pdk_index pdk_kernel_corr_shape_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                    pdk_index i0, pdk_index i1) {
  pdk_index flagged = 0;
  for (pdk_index i = i0; i < i1; ++i)
    flagged += shape_one(k, a, i);
  return flagged;
}

/* ---- Johnson-Cook history ---------------------------------------------------------------------
 */

static void jc_load(const pdk_corr_arrays *a, pdk_index i, pdk_jc_state *s) {
  for (int c = 0; c < 6; ++c)
    s->cp_inv[c] = a->cp_inv[c][i];
  s->eps_p = a->eps_p[i];
  s->damage = a->damage[i];
  s->temp_rise = a->temp_rise ? a->temp_rise[i] : 0.0;
  s->failed = a->failed[i];
}

static void jc_store(const pdk_corr_arrays *a, pdk_index i, const pdk_jc_state *s) {
  for (int c = 0; c < 6; ++c)
    a->cp_inv[c][i] = s->cp_inv[c];
  a->eps_p[i] = s->eps_p;
  a->damage[i] = s->damage;
  if (a->temp_rise) a->temp_rise[i] = s->temp_rise;
  a->failed[i] = (uint8_t)(s->failed != 0);
}

/* The material point update of particle i: with the family-averaged pressure when the arrays
 * have it. */
static int jc_step(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i, const int d,
                   const double F[3][3], const pdk_jc_state *in, pdk_jc_state *out,
                   double P[3][3], pdk_jc_result *res) {
  return pdk_jc_update_kernel(k->jc, d, F, k->dt, a->sigma_m_avg ? &a->sigma_m_avg[i] : NULL, in,
                              out, P, res);
}

/* Softened stabilization, commit pass: particle i's new factor from the step's von Mises stress
 * and plastic strain, min(f_old, max(floor, min(1, sigma_vm / (E eps_p)))) (unchanged while
 * eps_p = 0 and on the pass i fails, whose Silling energy at the old factor pass 2 books as
 * damage), and W_law for the driver's account (point_end has saved the old factor in stab_prev).
 * The factor never rises: the thesis' rule (eq. 6.20) is instantaneous, so a particle that unloads
 * and reloads gets its stiffness back while its non-affine motion is large, and that pumps energy
 * into the modes the term controls (measured on the two-hole plate at 1 mm after the first
 * failures: the Silling account went to -265 J against 95 J of external work by 2.5 ms). Under
 * monotonic loading the two rules agree (sigma_vm / eps_p falls as eps_p grows). */
static void soften(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i,
                   const pdk_jc_state *out, const pdk_jc_result *res) {
  if (!out->failed && out->eps_p > 0.0) {
    const double f = res->sigma_vm / (k->jc->young_modulus * out->eps_p);
    const double fc = f > 1.0 ? 1.0 : (f < k->stab_floor ? k->stab_floor : f);
    if (fc < a->stab_factor[i]) a->stab_factor[i] = fc; /* never rises again */
  }
  a->w_law[i] = res->W;
}

/* Johnson-Cook stress of particle i at F: A = P K^-1 and W stored, the history advanced when
 * k->commit. */
static void pass1_jc(const int d, const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i,
                     const double F[3][3], const double Kinv[3][3]) {
  pdk_jc_state in, out;
  pdk_jc_result res;
  double P[3][3], A[3][3];
  jc_load(a, i, &in);
  if (jc_step(k, a, i, d, F, &in, &out, P, &res)) {
    store_zero_d(d, a->A, i);
    a->W[i] = 0.0;
    a->flag[i] = (uint8_t)(a->flag[i] | PDK_CORR_FLAG_INVERTED);
    if (k->commit) a->eps_p_rate[i] = 0.0;
    return;
  }
  pdk_corr_mul_d(d, P, Kinv, A);
  store_d(d, a->A, i, A);
  a->W[i] = res.W;
  const unsigned failed = (out.failed ? PDK_CORR_FLAG_FAILED : 0u) |
                          (k->commit && out.failed && !in.failed ? PDK_CORR_FLAG_FAILED_NOW : 0u);
  a->flag[i] = (uint8_t)((a->flag[i] & ~(PDK_CORR_FLAG_INVERTED | PDK_CORR_FLAG_FAILED |
                                         PDK_CORR_FLAG_FAILED_NOW)) |
                         failed);
  if (k->commit) {
    jc_store(a, i, &out);
    a->w_plastic[i] += res.dW_plastic;
    a->w_damage[i] += res.dW_damage;
    a->eps_p_rate[i] = res.eps_p_rate;
    if (a->sigma_m) a->sigma_m[i] = res.sigma_m_eff;
    if (a->stab_factor) soften(k, a, i, &out, &res);
  }
}

/* ---- pass 1 -----------------------------------------------------------------------------------
 */

/* Stabilization coefficient k of particle p (0 when flagged or without a weighted volume). */
static double stab_coef(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index p) {
  return pdk_corr_kst(k, a, p);
}

/* The pass-2 data of particle i (kst, B, G and their float copies, whichever the arrays have),
 * from its final A, F and flag: B = A - k (F - I) (Silling; A otherwise), G = k (F - I). Taking
 * F - I rather than F keeps B and G of the size of the strain, so their float copies round
 * relative to the strain, not to k |F| ~ k. */
static void store_pair(const int d, const pdk_corr_consts *k, const pdk_corr_arrays *a,
                       pdk_index i) {
  if (!a->kst && !a->Bf[0]) return;
  const double ki = k->stab == PDK_KERNEL_STAB_NONE ? 0.0 : stab_coef(k, a, i);
  if (a->kst) a->kst[i] = ki;
  const int silling = k->stab == PDK_KERNEL_STAB_SILLING,
            hourglass = k->stab == PDK_KERNEL_STAB_HOURGLASS;
  for (int t = 0; t < d * d; ++t) {
    const double A = a->A[t][i], kF = ki * (a->F[t][i] - (t % (d + 1) == 0 ? 1.0 : 0.0));
    const double B = silling ? A - kF : A;
    if (a->B[0]) a->B[t][i] = B;
    if (a->G[0]) a->G[t][i] = kF;
    if (a->Bf[0]) a->Bf[t][i] = (float)B;
    if (hourglass && a->Gf[0]) a->Gf[t][i] = (float)kF;
  }
}

/* The per-particle end of pass 1 from N (disp = 0: F = N K^-1) or from D (disp = 1:
 * F = I + D K^-1). */
static void point_end(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i,
                      const double N[3][3], int disp) {
  pdk_corr_consts k_i; /* multi-material: particle i's lambda, mu, stabilization modulus */
  k = pdk_corr_consts_at(k, i, &k_i);
  const int d = k->dim;
  if (a->stab_factor && k->commit) { /* no change unless pass1_jc makes one */
    a->stab_prev[i] = a->stab_factor[i];
    a->w_law[i] = 0.0;
  }
  if (a->flag[i] & PDK_CORR_FLAG_SPAN) {
    store_zero_d(d, a->F, i);
    store_zero_d(d, a->A, i);
    a->W[i] = 0.0;
    if (k->law == PDK_KERNEL_LAW_JC && k->commit) a->eps_p_rate[i] = 0.0;
    store_pair(d, k, a, i);
    return;
  }
  double Kinv[3][3], F[3][3], P[3][3], A[3][3], W = 0.0;
  load_d(d, a->Kinv, i, Kinv);
  pdk_corr_mul_d(d, N, Kinv, F);
  if (disp)
    for (int c = 0; c < d; ++c)
      F[c][c] += 1.0;
  store_d(d, a->F, i, F);
  if (k->law == PDK_KERNEL_LAW_JC) {
    pass1_jc(d, k, a, i, F, Kinv);
  } else if (law_eval(k, F, P, &W)) {
    pdk_corr_mul_d(d, P, Kinv, A);
    store_d(d, a->A, i, A);
    a->W[i] = W;
    a->flag[i] = (uint8_t)(a->flag[i] & ~PDK_CORR_FLAG_INVERTED);
  } else {
    store_zero_d(d, a->A, i);
    a->W[i] = 0.0;
    a->flag[i] = (uint8_t)(a->flag[i] | PDK_CORR_FLAG_INVERTED);
  }
  store_pair(d, k, a, i);
}

void pdk_kernel_corr_point_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i,
                               const double N[3][3]) {
  point_end(k, a, i, N, 0);
}

void pdk_kernel_corr_point_disp_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                    pdk_index i, const double D[3][3]) {
  point_end(k, a, i, D, 1);
}

static void pass1_one(const int d, const pdk_corr_consts *k, const pdk_corr_arrays *a,
                      pdk_index i) {
  const pdk_bond_index *restrict bond_start = a->bond_start;
  const pdk_index *restrict bond_j = a->bond_j;
  const double *restrict omega = a->bond_omega;
  const uint8_t *restrict alive = a->bond_alive;
  const double *restrict volume = a->volume;
  double N[3][3] = {{0}};
  int32_t count = 0;
  for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
    const pdk_index j = bond_j[b];
    const int on = alive ? alive[b] != 0 : 1;
    count += on;
    const double wv = on ? omega[b] * volume[j] : 0.0;
    double xi[3], Y[3];
    for (int c = 0; c < d; ++c) {
      xi[c] = a->X[c][j] - a->X[c][i];
      Y[c] = a->x[c][j] - a->x[c][i];
    }
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c)
        N[r][c] += wv * Y[r] * xi[c];
  }
  if (alive && a->num_alive && count != a->num_alive[i]) shape_one(k, a, i);
  pdk_kernel_corr_point_ref(k, a, i, N);
}

void pdk_kernel_corr_pass1_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i0,
                               pdk_index i1) {
  /* The dimension is a literal in each loop so the small tensor loops are fully unrolled. */
  if (k->dim == 2)
    for (pdk_index i = i0; i < i1; ++i)
      pass1_one(2, k, a, i);
  else
    for (pdk_index i = i0; i < i1; ++i)
      pass1_one(3, k, a, i);
}

/* ---- pass 2 -----------------------------------------------------------------------------------
 */

static void pass2_one(const int d, const pdk_corr_consts *k, const pdk_corr_arrays *a,
                      pdk_index i) {
  const pdk_bond_index *restrict bond_start = a->bond_start;
  const pdk_index *restrict bond_j = a->bond_j;
  const double *restrict omega = a->bond_omega;
  const uint8_t *restrict alive = a->bond_alive;
  const double *restrict volume = a->volume;
  const int stab = k->stab != PDK_KERNEL_STAB_NONE;
  const int silling = k->stab == PDK_KERNEL_STAB_SILLING;
  double Ai[3][3], Fi[3][3];
  load_d(d, a->A, i, Ai);
  load_d(d, a->F, i, Fi);
  const double ki = stab_coef(k, a, i);
  double f[3] = {0.0, 0.0, 0.0}, zz = 0.0;
  for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
    if (alive && !alive[b]) continue;
    const pdk_index j = bond_j[b];
    const double wv = omega[b] * volume[j];
    double xi[3], Y[3], Aj[3][3], t[3];
    for (int c = 0; c < d; ++c) {
      xi[c] = a->X[c][j] - a->X[c][i];
      Y[c] = a->x[c][j] - a->x[c][i];
    }
    load_d(d, a->A, j, Aj);
    for (int r = 0; r < d; ++r) {
      double s = 0.0;
      for (int c = 0; c < d; ++c)
        s += (Ai[r][c] + Aj[r][c]) * xi[c];
      t[r] = s;
    }
    if (stab) {
      const double kj = stab_coef(k, a, j);
      double Fj[3][3], zi[3], zj[3];
      load_d(d, a->F, j, Fj);
      for (int r = 0; r < d; ++r) {
        double si = 0.0, sj = 0.0;
        for (int c = 0; c < d; ++c) {
          si += Fi[r][c] * xi[c];
          sj += Fj[r][c] * xi[c];
        }
        zi[r] = Y[r] - si;
        zj[r] = Y[r] - sj;
      }
      if (silling) {
        for (int r = 0; r < d; ++r) {
          t[r] += ki * zi[r] + kj * zj[r];
          zz += wv * zi[r] * zi[r];
        }
      } else { /* hourglass, projected on the current bond */
        double y2 = 0.0, x2 = 0.0;
        for (int c = 0; c < d; ++c) {
          y2 += Y[c] * Y[c];
          x2 += xi[c] * xi[c];
        }
        if (y2 > 0.0) {
          const double ylen = sqrt(y2);
          double zie = 0.0, zje = 0.0;
          for (int c = 0; c < d; ++c) {
            zie += zi[c] * Y[c];
            zje += zj[c] * Y[c];
          }
          /* (delta/|xi|) (k_i z_i.e + k_j z_j.e) e, with e = Y/|Y| */
          const double g = k->horizon / sqrt(x2) * (ki * zie + kj * zje) / (ylen * ylen);
          for (int r = 0; r < d; ++r)
            t[r] += g * Y[r];
        }
      }
    }
    for (int r = 0; r < d; ++r)
      f[r] += wv * t[r];
  }
  for (int r = 0; r < d; ++r)
    a->f[r][i] = f[r];
  if (silling) a->W[i] += 0.5 * ki * zz;
  /* A particle failing in this commit pass drops its Silling term with its stress: the energy the
   * term would hold at this x goes to the damage account, as the law's stored energy does. */
  if (silling && (a->flag[i] & PDK_CORR_FLAG_FAILED_NOW) && a->m[i] > 0.0)
    a->w_damage[i] += 0.5 * pdk_corr_kst_unflagged(k, a, i) * zz;
}

/* Pass 2 with float storage: the neighbour's part of the pair term from the float tensors pass 1
 * stored (Bf = A - k (F - I) for Silling, A otherwise; Gf = k (F - I) for hourglass), everything
 * else in double. The same sum as pass2_one, regrouped so that j enters through Bf_j, Gf_j, k_j
 * only (U = Y - xi, the relative displacement):
 *   Silling    w V [(A_i xi + k_i z_i) + (B_j xi + k_j U)]    (A_j xi + k_j z_j' = B_j xi + k_j U)
 *   hourglass  w V [(A_i + A_j) xi + (delta/|xi|) (k_i z_i.Y + k_j U.Y - (G_j xi).Y) Y / |Y|^2]
 */
static void pass2_one_float(const int d, const pdk_corr_consts *k, const pdk_corr_arrays *a,
                            pdk_index i) {
  const pdk_bond_index *restrict bond_start = a->bond_start;
  const pdk_index *restrict bond_j = a->bond_j;
  const double *restrict omega = a->bond_omega;
  const uint8_t *restrict alive = a->bond_alive;
  const double *restrict volume = a->volume;
  const int silling = k->stab == PDK_KERNEL_STAB_SILLING,
            hourglass = k->stab == PDK_KERNEL_STAB_HOURGLASS;
  double Ai[3][3], Fi[3][3];
  load_d(d, a->A, i, Ai);
  load_d(d, a->F, i, Fi);
  const double ki = stab_coef(k, a, i);
  double f[3] = {0.0, 0.0, 0.0}, zz = 0.0;
  for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
    if (alive && !alive[b]) continue;
    const pdk_index j = bond_j[b];
    const double wv = omega[b] * volume[j];
    const double kj = silling || hourglass ? a->kst[j] : 0.0;
    double xi[3], Y[3], t[3], zi[3], Gxi[3], y2 = 0.0, x2 = 0.0, ziY = 0.0, uY = 0.0, GY = 0.0;
    for (int c = 0; c < d; ++c) {
      xi[c] = a->X[c][j] - a->X[c][i];
      Y[c] = a->x[c][j] - a->x[c][i];
    }
    for (int r = 0; r < d; ++r) {
      double s = 0.0, si = 0.0, g = 0.0;
      for (int c = 0; c < d; ++c) {
        s += (Ai[r][c] + (double)a->Bf[r * d + c][j]) * xi[c];
        si += Fi[r][c] * xi[c];
        if (hourglass) g += (double)a->Gf[r * d + c][j] * xi[c];
      }
      t[r] = s;
      zi[r] = Y[r] - si;
      Gxi[r] = g;
    }
    for (int r = 0; r < d; ++r) {
      if (silling) {
        t[r] += ki * zi[r] + kj * (Y[r] - xi[r]);
        zz += wv * zi[r] * zi[r];
      }
      y2 += Y[r] * Y[r];
      x2 += xi[r] * xi[r];
      ziY += zi[r] * Y[r];
      uY += (Y[r] - xi[r]) * Y[r];
      GY += Gxi[r] * Y[r];
    }
    if (hourglass && y2 > 0.0) {
      const double g = k->horizon / sqrt(x2) * (ki * ziY + kj * uY - GY) / y2;
      for (int r = 0; r < d; ++r)
        t[r] += g * Y[r];
    }
    for (int r = 0; r < d; ++r)
      f[r] += wv * t[r];
  }
  for (int r = 0; r < d; ++r)
    a->f[r][i] = f[r];
  if (silling) a->W[i] += 0.5 * ki * zz;
  if (silling && (a->flag[i] & PDK_CORR_FLAG_FAILED_NOW) && a->m[i] > 0.0)
    a->w_damage[i] += 0.5 * pdk_corr_kst_unflagged(k, a, i) * zz;
}

void pdk_kernel_corr_pass2_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i0,
                               pdk_index i1) {
  const int fl = a->Bf[0] != NULL;
  for (pdk_index i = i0; i < i1; ++i) {
    if (k->dim == 2)
      fl ? pass2_one_float(2, k, a, i) : pass2_one(2, k, a, i);
    else
      fl ? pass2_one_float(3, k, a, i) : pass2_one(3, k, a, i);
  }
}

/* ---- bond failure -----------------------------------------------------------------------------
 */

pdk_bond_index pdk_kernel_corr_break_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                         pdk_index i0, pdk_index i1) {
  const int d = k->dim;
  const pdk_bond_index *restrict bond_start = a->bond_start;
  const pdk_index *restrict bond_j = a->bond_j;
  uint8_t *restrict alive = a->bond_alive;
  const double *restrict s0 = a->s0;
  double *restrict s0_next = a->s0_next;
  const uint8_t *restrict failed = k->break_failed ? a->failed : NULL;
  pdk_bond_index broken = 0;
  for (pdk_index i = i0; i < i1; ++i) {
    double s0_max = -DBL_MAX;
    const int failed_i = failed ? failed[i] != 0 : 0;
    int changed = 0;
    for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
      if (!alive[b]) continue;
      const pdk_index j = bond_j[b];
      int cut = failed ? (failed_i || failed[j] != 0) : 0;
      if (s0) {
        double x2 = 0.0, y2 = 0.0;
        for (int c = 0; c < d; ++c) {
          const double xi = a->X[c][j] - a->X[c][i], Y = a->x[c][j] - a->x[c][i];
          x2 += xi * xi;
          y2 += Y * Y;
        }
        const double r0 = sqrt(x2);
        const double s = (sqrt(y2) - r0) / r0;
        if (s > fmin(s0[i], s0[j])) cut = 1;
        s0_max = fmax(s0_max, k->s00 - k->alpha * s);
      }
      if (cut) {
        alive[b] = 0;
        ++broken;
        changed = 1;
      }
    }
    if (s0_next) s0_next[i] = s0_max == -DBL_MAX ? DBL_MAX : s0_max;
    if (a->changed) a->changed[i] = changed ? 3u : 0u;
  }
  return broken;
}

/* ---- after breaking: shape, semi-TL detachment, released energy -------------------------------
 */

pdk_index pdk_kernel_corr_reshape_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                      pdk_index i0, pdk_index i1) {
  pdk_index detached = 0;
  for (pdk_index i = i0; i < i1; ++i) {
    int detach = 0;
    if (a->changed[i] & 1u) {
      const int not_span = shape_one(k, a, i);
      detach = a->detach && not_span && a->num_alive[i] > 0;
    }
    if (a->detach) a->detach[i] = (uint8_t)detach;
    detached += detach;
  }
  return detached;
}

pdk_bond_index pdk_kernel_corr_cut_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a,
                                       pdk_index i0, pdk_index i1) {
  const pdk_bond_index *restrict bond_start = a->bond_start;
  const pdk_index *restrict bond_j = a->bond_j;
  uint8_t *restrict alive = a->bond_alive;
  const uint8_t *restrict detach = a->detach;
  pdk_bond_index broken = 0;
  for (pdk_index i = i0; i < i1; ++i) {
    const int detach_i = detach[i] != 0;
    int changed = 0;
    for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
      if (!alive[b] || !(detach_i || detach[bond_j[b]])) continue;
      alive[b] = 0;
      ++broken;
      changed = 1;
    }
    a->changed[i] = (uint8_t)((a->changed[i] & 2u) | (changed ? 3u : 0u));
  }
  (void)k;
  return broken;
}

/* F_i = N_i K_i^-1 at the current x over i's intact bonds, with the K^-1 the arrays hold. */
static void fit_F(const int d, const pdk_corr_arrays *a, pdk_index i, double F[3][3]) {
  const pdk_bond_index *restrict bond_start = a->bond_start;
  const pdk_index *restrict bond_j = a->bond_j;
  const double *restrict omega = a->bond_omega;
  const uint8_t *restrict alive = a->bond_alive;
  const double *restrict volume = a->volume;
  double N[3][3] = {{0}}, Kinv[3][3];
  for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
    const pdk_index j = bond_j[b];
    const double wv = alive[b] ? omega[b] * volume[j] : 0.0;
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c)
        N[r][c] += wv * (a->x[r][j] - a->x[r][i]) * (a->X[c][j] - a->X[c][i]);
  }
  load_d(d, a->Kinv, i, Kinv);
  pdk_corr_mul_d(d, N, Kinv, F);
}

/* Johnson-Cook, break_stress continuous: remap particle i's committed history from the F of this
 * pass (a->F, the old family) to Fn, the F of the new family at the same x (pdk_jc_remap), so the
 * break does not make the stress jump. Rows that carry no stress (failed, family not spanning,
 * inverted) are left alone. */
static void remap_one(const int d, const pdk_corr_arrays *a, pdk_index i, const double Fn[3][3]) {
  if (a->failed[i] || (a->flag[i] & (PDK_CORR_FLAG_SPAN | PDK_CORR_FLAG_INVERTED))) return;
  double Fo[3][3] = {{0}};
  load_d(d, a->F, i, Fo);
  pdk_jc_state s;
  jc_load(a, i, &s);
  if (pdk_jc_remap_kernel(d, Fo, Fn, &s) == PDK_SUCCESS)
    for (int c = 0; c < 6; ++c)
      a->cp_inv[c][i] = s.cp_inv[c];
}

/* Energy density of particle i at the current x and its F there (fit_F) with its current
 * (intact) family and the committed history: the law's W (for Johnson-Cook a trial update, plus
 * the plastic and damage work it would do) plus the Silling term (also in *silling). */
static double energy_one(const int d, const pdk_corr_consts *k, const pdk_corr_arrays *a,
                         pdk_index i, const double F[3][3], double *silling) {
  *silling = 0.0;
  pdk_corr_consts k_i;
  k = pdk_corr_consts_at(k, i, &k_i);
  const pdk_bond_index *restrict bond_start = a->bond_start;
  const pdk_index *restrict bond_j = a->bond_j;
  const double *restrict omega = a->bond_omega;
  const uint8_t *restrict alive = a->bond_alive;
  const double *restrict volume = a->volume;
  if (a->flag[i] & PDK_CORR_FLAG_SPAN) return 0.0;
  double P[3][3], e = 0.0;
  int stress_free = 0;
  if (k->law == PDK_KERNEL_LAW_JC) {
    pdk_jc_state in, out;
    pdk_jc_result res;
    jc_load(a, i, &in);
    if (jc_step(k, a, i, d, F, &in, &out, P, &res)) return 0.0;
    e = res.W + res.dW_plastic + res.dW_damage;
    stress_free = out.failed != 0;
  } else if (!law_eval(k, F, P, &e)) {
    return 0.0;
  }
  if (k->stab == PDK_KERNEL_STAB_SILLING && !stress_free && a->m[i] > 0.0) {
    double zz = 0.0;
    for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
      if (!alive[b]) continue;
      const pdk_index j = bond_j[b];
      const double wv = omega[b] * volume[j];
      for (int r = 0; r < d; ++r) {
        double s = 0.0;
        for (int c = 0; c < d; ++c)
          s += F[r][c] * (a->X[c][j] - a->X[c][i]);
        const double z = (a->x[r][j] - a->x[r][i]) - s;
        zz += wv * z * z;
      }
    }
    *silling = 0.5 * pdk_corr_kst_unflagged(k, a, i) * zz;
    e += *silling;
  }
  return e;
}

double pdk_kernel_corr_release_ref(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i0,
                                   pdk_index i1, int remap) {
  const int d = k->dim;
  double sum = 0.0;
  for (pdk_index i = i0; i < i1; ++i)
    if (a->changed[i] & 2u) {
      double F[3][3] = {{0}}, silling;
      if (!(a->flag[i] & PDK_CORR_FLAG_SPAN)) fit_F(d, a, i, F);
      if (remap) remap_one(d, a, i, F); /* first, so the new family is priced with it */
      const double released = a->W[i] - energy_one(d, k, a, i, F, &silling);
      /* softened stabilization: the next commit books the change of the factor from the
       * Silling energy of the new family */
      if (a->w_silling) a->w_silling[i] = silling;
      a->w_broken[i] += released;
      sum += a->volume[i] * released;
    }
  return sum;
}

int pdk_kernel_corr_law_ref(const pdk_corr_consts *k, const double F[3][3], double P[3][3],
                            double *W) {
  return law_eval(k, F, P, W);
}
