/* Reference correspondence kernels, updated Lagrangian (UL) connectivity (Bergel & Li, Comput.
 * Mech. 2016; docs/validation/targets.md V-BL), 2-D plane strain and 3-D.
 *
 * Configurations. 0: the initial one (X, V0: the store's "X", "volume"); r: the configuration of
 * the last rebuild (X_r, V_r, with F_ref the deformation gradient from 0 to r and J_ref = det
 * F_ref; at creation r = 0, F_ref = I); the current one (x). The families are those of r: bond b
 * of particle i with neighbour j, xi = X_r,j - X_r,i, Y = x_j - x_i, w_b = omega(|xi|) at
 * creation and omega(min(|X_j - X_i|, |xi|)) after a rebuild (src/models/model_corr_ul.c, "Weights";
 * fixed between rebuilds: Bergel & Li's omega(xi) dV = omega_t dv), V_j = V_r,j.
 *
 * Rebuild shape (pdk_kernel_corr_ul_shape_ref), at creation and after each rebuild:
 *   K_i = sum_b w_b V_j xi (x) xi, m_i = sum_b w_b V_j |xi|^2; flag bit SPAN as the TL kernels
 *   (det K_i >= span_rtol (tr K_i / d)^d). K itself is not kept: UL never uses it.
 *
 * Pass 1 (pdk_kernel_corr_ul_pass1_ref), per particle i:
 *   N_i = sum_b w_b V_j Y (x) xi                  two-point tensor (Bergel & Li eq. 15)
 *   M_i = sum_b w_b V_j Y (x) Y                   spatial shape tensor (eq. 36), symmetric
 *   F^_i = M_i N_i^-T                             the deformed-bond gradient (eqs. 33, 35), from r
 *   F_i = F^_i F_ref,i                            total deformation gradient (stored in "F")
 *   P_i = law(F_i), W_i = law energy              first Piola-Kirchhoff stress and energy per
 *                                                 initial volume (the TL kernels' laws)
 *   tau_i = sym(P_i F_i^T)                        Kirchhoff stress J sigma (symmetric already for
 *                                                 the objective laws; symmetrised so that angular
 *                                                 momentum holds for linear_elastic too)
 *   A_i = (tau_i / J_ref,i) M_i^-1                Kirchhoff stress relative to r, times M^-1
 *   F^ is exact for affine motion Y = G xi: N = G K, M = G K G^T, so M N^-T = G (Prop. 3.5).
 *   F^^-1 = N^T M^-1 is the least-squares spatial gradient of X_r over the current bonds (eq.
 *   71); F = N K^-1 (TL) is the least-squares material gradient of x. Both err by O(delta^2) for
 *   smooth motion, F^ with the larger constant (13 R X1 h^2 against 4 R X1 h^2 for x1 = X1^4, see
 *   the notes and tests/t131_vbl_convergence.c).
 *   Flags: SPAN (from the rebuild shape) gives F = A = 0, W = 0 as in TL; INVERTED, recomputed
 *   every pass, when M_i does not span (det M < span_rtol (tr M / d)^d: the current family
 *   collapsed onto a line or plane), det N_i <= 0 (F^ would not preserve orientation), or the
 *   law is undefined at F (J <= 0): then A = 0, W = 0 (F and F^ keep the last values they had
 *   when M or N was the cause).
 *   Johnson-Cook: as the TL kernels (history advanced in place in a commit pass, into a discarded
 *   copy in a trial; FAILED / FAILED_NOW bits), with the total F.
 *
 * Pass 2 (pdk_kernel_corr_ul_pass2_ref), force density per initial volume:
 *   f_i = J_ref,i sum_b w_b V_j (A_i + A_j) Y + stabilization
 *   This is the spatial force state of Bergel & Li (77), T_i<Y> = w tau_i M_i^-1 Y (Cauchy stress
 *   sigma M^-1 Y weighted with omega_t dv = J omega dV), in the conservative pairing pdk's TL uses
 *   (T_i<Y> - T_j<-Y>): it is minus the derivative, with respect to the velocities, of the
 *   internal power sum_i V_r,i tau_r,i : l_i with the spatial velocity gradient
 *   l_i = [sum_b w_b V_j (v_j - v_i) (x) Y] M_i^-1 (eq. 58 applied to v), per rebuild volume;
 *   J_ref,i = V_r,i / V0_i converts it to the initial volume the solvers divide by. Hence:
 *   - linear momentum is exact (each pair term is antisymmetric), and so is angular momentum:
 *     sum_b w_b V_j (A_i Y) x Y is the axial vector of A_i M_i = tau_r,i, symmetric (eq. 87);
 *   - zero under rigid motion (tau = 0), zero at interior particles under affine motion;
 *   - for smooth motion and point-symmetric families in r it approximates Div P to O(delta^2)
 *     (expand A_j and Y about i: the first moments give A_i (grad F : K) + (grad A) F K, which is
 *     Div (A F K) = Div P because A F K = tau F^-T = P). Bergel & Li recommend the difference
 *     form J sum w V (sigma_j - sigma_i) M_i^-1 Y (their eq. 90) instead; it is not used: it
 *     conserves neither momentum nor energy and does not make free surfaces traction-free (notes
 *     004, section 5, items 10-11). On interior particles both agree to O(delta^2).
 *   Unlike TL the force is not the gradient of an energy (l is not exactly dF/dt F^-1 for the
 *   discrete F^), so an undamped run drifts in energy by the discretization error.
 *   Stabilization (opts.stabilization), with z_i = Y - F^_i xi and z_j' = Y - F^_j xi, the part of
 *   the motion since the rebuild that F^ does not fit, k_i = stab_modulus / m_i (0 if flagged):
 *     Silling    pair term w_b V_j (k_i z_i + k_j z_j'),  W_i += J_ref,i k_i/2 sum_b w_b V_j
 * |z_i|^2 hourglass  pair term w_b V_j (delta/|xi|) (k_i z_i.e + k_j z_j'.e) e, e = Y/|Y| (the TL
 * forms with F^ for F; F^ is not the least-squares fit of Y, so the Silling term is not an exact
 * potential here). Both see only the motion since the last rebuild: a rebuild resets z to 0 and
 * forgets the non-affine motion before it (see docs/connectivity.md).
 *
 * Contract: as kernels/ref/corr.c: pure functions over particles [i0, i1); a call writes only
 * entries of particles in [i0, i1) and reads neighbours' data written by an earlier pass.
 * Families must be symmetric with the same omega from both ends (pdk_families_build_coords).
 */
#include <math.h>

#include "kernels.h"
#include "ref/tensor_d.h" /* pdk_det_d, pdk_inv_d */

/* ---- small dense tensors (row-major, d x d in the top-left of 3 x 3; det and inverse:
 * ref/tensor_d.h) ---------------------------------------------------------------------------- */

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

/* det T >= rtol (tr T / d)^d with tr T > 0, all finite: T (symmetric PSD) spans the space. */
static int spans_d(const int d, const double T[3][3], double rtol) {
  double tr = 0.0;
  for (int c = 0; c < d; ++c)
    tr += T[c][c];
  const double det = pdk_det_d(d, T);
  const double mean = tr / d;
  const double scale = d == 2 ? mean * mean : mean * mean * mean;
  return tr > 0.0 && isfinite(tr) && isfinite(det) && det >= rtol * scale;
}

/* ---- rebuild shape ----------------------------------------------------------------------------
 */

pdk_index pdk_kernel_corr_ul_shape_ref(const pdk_corr_consts *k, const pdk_corr_ul_arrays *ua,
                                       pdk_index i0, pdk_index i1) {
  const pdk_corr_arrays *a = &ua->base;
  const int d = k->dim;
  const pdk_bond_index *restrict bond_start = a->bond_start;
  const pdk_index *restrict bond_j = a->bond_j;
  const double *restrict omega = a->bond_omega;
  const double *restrict volume = a->volume;
  pdk_index flagged = 0;
  for (pdk_index i = i0; i < i1; ++i) {
    double K[3][3] = {{0}}, m = 0.0;
    for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
      const pdk_index j = bond_j[b];
      const double wv = omega[b] * volume[j];
      double xi[3];
      for (int c = 0; c < d; ++c)
        xi[c] = a->X[c][j] - a->X[c][i];
      for (int r = 0; r < d; ++r) {
        m += wv * xi[r] * xi[r];
        for (int c = 0; c < d; ++c)
          K[r][c] += wv * xi[r] * xi[c];
      }
    }
    const int spans = spans_d(d, K, k->span_rtol);
    if (a->m) a->m[i] = m;
    a->flag[i] = (uint8_t)((a->flag[i] & ~PDK_CORR_FLAG_SPAN) | (spans ? 0u : PDK_CORR_FLAG_SPAN));
    flagged += !spans;
  }
  return flagged;
}

/* ---- pass 1 -----------------------------------------------------------------------------------
 */

/* A = (sym(P F^T) / J_ref) M^-1, stored. */
static void store_A(const int d, const pdk_corr_arrays *a, pdk_index i, const double P[3][3],
                    const double F[3][3], const double Minv[3][3], double J_ref) {
  double tau[3][3], A[3][3];
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c) {
      double s = 0.0;
      for (int e = 0; e < d; ++e)
        s += P[r][e] * F[c][e];
      tau[r][c] = s;
    }
  const double inv_J_ref = 1.0 / J_ref;
  for (int r = 0; r < d; ++r)
    for (int c = r; c < d; ++c)
      tau[r][c] = tau[c][r] = 0.5 * (tau[r][c] + tau[c][r]) * inv_J_ref;
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c) {
      double s = 0.0;
      for (int e = 0; e < d; ++e)
        s += tau[r][e] * Minv[e][c];
      A[r][c] = s;
    }
  store_d(d, a->A, i, A);
}

static void mark_inverted(const int d, const pdk_corr_consts *k, const pdk_corr_arrays *a,
                          pdk_index i) {
  store_zero_d(d, a->A, i);
  a->W[i] = 0.0;
  a->flag[i] = (uint8_t)(a->flag[i] | PDK_CORR_FLAG_INVERTED);
  if (k->law == PDK_KERNEL_LAW_JC && k->commit) a->eps_p_rate[i] = 0.0;
}

/* Johnson-Cook stress at the total F: as kernels/ref/corr.c pass1_jc, with A from tau. */
static void pass1_jc(const int d, const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index i,
                     const double F[3][3], const double Minv[3][3], double J_ref) {
  pdk_jc_state in, out;
  pdk_jc_result res;
  double P[3][3];
  for (int c = 0; c < 6; ++c)
    in.cp_inv[c] = a->cp_inv[c][i];
  in.eps_p = a->eps_p[i];
  in.damage = a->damage[i];
  in.temp_rise = a->temp_rise ? a->temp_rise[i] : 0.0;
  in.failed = a->failed[i];
  if (pdk_jc_update_kernel(k->jc, d, F, k->dt, NULL, &in, &out, P, &res)) {
    mark_inverted(d, k, a, i);
    return;
  }
  store_A(d, a, i, P, F, Minv, J_ref);
  a->W[i] = res.W;
  const unsigned failed = (out.failed ? PDK_CORR_FLAG_FAILED : 0u) |
                          (k->commit && out.failed && !in.failed ? PDK_CORR_FLAG_FAILED_NOW : 0u);
  a->flag[i] = (uint8_t)((a->flag[i] & ~(PDK_CORR_FLAG_INVERTED | PDK_CORR_FLAG_FAILED |
                                         PDK_CORR_FLAG_FAILED_NOW)) |
                         failed);
  if (k->commit) {
    for (int c = 0; c < 6; ++c)
      a->cp_inv[c][i] = out.cp_inv[c];
    a->eps_p[i] = out.eps_p;
    a->damage[i] = out.damage;
    if (a->temp_rise) a->temp_rise[i] = out.temp_rise;
    a->failed[i] = (uint8_t)(out.failed != 0);
    a->w_plastic[i] += res.dW_plastic;
    a->w_damage[i] += res.dW_damage;
    a->eps_p_rate[i] = res.eps_p_rate;
  }
}

static void pass1_one(const int d, const pdk_corr_consts *k, const pdk_corr_ul_arrays *ua,
                      pdk_index i) {
  pdk_corr_consts k_i;
  k = pdk_corr_consts_at(k, i, &k_i);
  const pdk_corr_arrays *a = &ua->base;
  const pdk_bond_index *restrict bond_start = a->bond_start;
  const pdk_index *restrict bond_j = a->bond_j;
  const double *restrict omega = a->bond_omega;
  const double *restrict volume = a->volume;
  if (a->flag[i] & PDK_CORR_FLAG_SPAN) {
    store_zero_d(d, a->F, i);
    if (ua->F_inc[0]) store_zero_d(d, ua->F_inc, i);
    store_zero_d(d, a->A, i);
    a->W[i] = 0.0;
    if (k->law == PDK_KERNEL_LAW_JC && k->commit) a->eps_p_rate[i] = 0.0;
    return;
  }
  double N[3][3] = {{0}}, M[3][3] = {{0}};
  for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
    const pdk_index j = bond_j[b];
    const double wv = omega[b] * volume[j];
    double xi[3], Y[3];
    for (int c = 0; c < d; ++c) {
      xi[c] = a->X[c][j] - a->X[c][i];
      Y[c] = a->x[c][j] - a->x[c][i];
    }
    for (int r = 0; r < d; ++r) {
      const double wy = wv * Y[r];
      for (int c = 0; c < d; ++c) {
        N[r][c] += wy * xi[c];
        M[r][c] += wy * Y[c];
      }
    }
  }
  const double detN = pdk_det_d(d, N), detM = pdk_det_d(d, M);
  if (!spans_d(d, M, k->span_rtol) || !(detN > 0.0) || !isfinite(detN)) {
    mark_inverted(d, k, a, i);
    return;
  }
  double Ninv[3][3], Minv[3][3], Finc[3][3], Fref[3][3], F[3][3], P[3][3], W = 0.0;
  pdk_inv_d(d, N, detN, Ninv);
  pdk_inv_d(d, M, detM, Minv);
  for (int r = 0; r < d; ++r) /* F^ = M N^-T: (N^-T)[e][c] = N^-1[c][e] */
    for (int c = 0; c < d; ++c) {
      double s = 0.0;
      for (int e = 0; e < d; ++e)
        s += M[r][e] * Ninv[c][e];
      Finc[r][c] = s;
    }
  load_d(d, ua->F_ref, i, Fref);
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < d; ++c) {
      double s = 0.0;
      for (int e = 0; e < d; ++e)
        s += Finc[r][e] * Fref[e][c];
      F[r][c] = s;
    }
  store_d(d, a->F, i, F);
  if (ua->F_inc[0]) store_d(d, ua->F_inc, i, Finc);
  const double J_ref = ua->J_ref[i];
  if (k->law == PDK_KERNEL_LAW_JC) {
    pass1_jc(d, k, a, i, F, Minv, J_ref);
    return;
  }
  if (!pdk_kernel_corr_law_ref(k, F, P, &W)) {
    mark_inverted(d, k, a, i);
    return;
  }
  store_A(d, a, i, P, F, Minv, J_ref);
  a->W[i] = W;
  a->flag[i] = (uint8_t)(a->flag[i] & ~PDK_CORR_FLAG_INVERTED);
}

void pdk_kernel_corr_ul_pass1_ref(const pdk_corr_consts *k, const pdk_corr_ul_arrays *a,
                                  pdk_index i0, pdk_index i1) {
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

static double stab_coef(const pdk_corr_consts *k, const pdk_corr_arrays *a, pdk_index p) {
  if (k->stab == PDK_KERNEL_STAB_NONE || a->flag[p] || !(a->m[p] > 0.0)) return 0.0;
  return (k->stab_p ? k->stab_p[p] : k->stab_modulus) / a->m[p];
}

static void pass2_one(const int d, const pdk_corr_consts *k, const pdk_corr_ul_arrays *ua,
                      pdk_index i) {
  const pdk_corr_arrays *a = &ua->base;
  const pdk_bond_index *restrict bond_start = a->bond_start;
  const pdk_index *restrict bond_j = a->bond_j;
  const double *restrict omega = a->bond_omega;
  const double *restrict volume = a->volume;
  const int stab = k->stab != PDK_KERNEL_STAB_NONE;
  const int silling = k->stab == PDK_KERNEL_STAB_SILLING;
  double Ai[3][3], Fi[3][3] = {{0}};
  load_d(d, a->A, i, Ai);
  if (stab) load_d(d, ua->F_inc, i, Fi);
  const double ki = stab ? stab_coef(k, a, i) : 0.0;
  double f[3] = {0.0, 0.0, 0.0}, zz = 0.0;
  for (pdk_bond_index b = bond_start[i]; b < bond_start[i + 1]; ++b) {
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
        s += (Ai[r][c] + Aj[r][c]) * Y[c];
      t[r] = s;
    }
    if (stab) {
      const double kj = stab_coef(k, a, j);
      double Fj[3][3], zi[3], zj[3];
      load_d(d, ua->F_inc, j, Fj);
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
        if (y2 > 0.0 && x2 > 0.0) {
          double zie = 0.0, zje = 0.0;
          for (int c = 0; c < d; ++c) {
            zie += zi[c] * Y[c];
            zje += zj[c] * Y[c];
          }
          const double g = k->horizon / sqrt(x2) * (ki * zie + kj * zje) / y2;
          for (int r = 0; r < d; ++r)
            t[r] += g * Y[r];
        }
      }
    }
    for (int r = 0; r < d; ++r)
      f[r] += wv * t[r];
  }
  const double J_ref = ua->J_ref[i];
  for (int r = 0; r < d; ++r)
    a->f[r][i] = J_ref * f[r];
  if (silling) a->W[i] += J_ref * 0.5 * ki * zz;
  if (silling && (a->flag[i] & PDK_CORR_FLAG_FAILED_NOW) && a->m[i] > 0.0)
    a->w_damage[i] += J_ref * 0.5 * (k->stab_modulus / a->m[i]) * zz;
}

void pdk_kernel_corr_ul_pass2_ref(const pdk_corr_consts *k, const pdk_corr_ul_arrays *a,
                                  pdk_index i0, pdk_index i1) {
  if (k->dim == 2)
    for (pdk_index i = i0; i < i1; ++i)
      pass2_one(2, k, a, i);
  else
    for (pdk_index i = i0; i < i1; ++i)
      pass2_one(3, k, a, i);
}
