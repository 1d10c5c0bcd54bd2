/* Peridynamic Galerkin (PG), Bubnov-Galerkin form (PBG), reference kernels: pure loops over
 * arrays, gather-only (families are written by their own particle, forces gathered by theirs), so
 * results do not depend on how the ranges are split over threads.
 *
 * Notation (Bode 2021, "Peridynamic Galerkin methods for nonlinear solid mechanics", ch. 4-5; Bode,
 * Weissenfels, Wriggers 2022, "Peridynamic Galerkin method: an attractive alternative to finite
 * elements"). Family H_k = {k} and its neighbours (members j = 0 .. N_k, 0 = k), volumes V_j,
 * V_H = sum_{j in H_k} V_j (thesis eq. 4.26). dN^{kji} = dN^{kji}/dX: family k, evaluation point
 * j, support node i.
 *
 * Shape functions (thesis section 5.2.2, Table 5.1), with dX^{ji} = X_i - X_j:
 *   taylor (MTE1, eq. 5.52, moving weights w^{ji} = 1/|dX^{ji}|^2, eq. 5.42):
 *     M^{kj} = sum_{i in H_k, i != j} w^{ji} V_i dX^{ji} (x) dX^{ji}
 *     dN^{kji} = w^{ji} V_i (M^{kj})^-1 dX^{ji}   (i != j),   dN^{kjj} = -sum_{i != j} dN^{kji}
 *   wls (WLS1 = WTE1, static weights w^{ki}, eq. 5.41): the same with j replaced by k, for every
 *     evaluation point j (one gradient per family: classical correspondence, eqs. 4.3-4.6).
 * Both satisfy sum_i dN^{kji} = 0 (5.8) and sum_i dX^{ki} (x) dN^{kji} = I (5.9).
 * bond (the bond-mapping correction, eq. 5.55; k->bond): for every evaluation point j != k,
 *   dN^{kji} <- (1 - n (x) n) dN^{kji} + delta_ji dX^{kj} / |dX^{kj}|^2,  n = dX^{kj} / |dX^{kj}|,
 *   so F^{kj} dX^{kj} = dx^{kj} (the bond is mapped exactly); (5.9) still holds, (5.8) does not,
 *   which the difference form of F (below) does not need.
 *
 * Trial (eq. 4.11, difference form): F^{kj} = I + sum_{i in H_k} (u_i - u_k) (x) dN^{kji}.
 * PBG internal virtual work (eq. 4.25): dW_k = sum_j w_kj P^{kj} : dF^{kj}, w_kj = V_k V_j / V_H,
 * energy E = sum_k sum_j w_kj W(F^{kj}) (eq. 4.47), so family k adds to node i (i != k)
 *   G^k_i = dE_k/du_i = sum_j w_kj P^{kj} dN^{kji}   (a vector: (P dN)_a = sum_B P_aB dN_B)
 * and to its own particle G^k_k = -sum_{i != k} G^k_i (the nodal forces of thesis Table 4.1 / eq.
 * 4.30 written per family). Pass 2 gathers f_i = -(1/V_i) sum_{k : i in H_k} G^k_i (force
 * density, as every pdk kind).
 * Area vectors (eq. 4.35, 5.18): A_i = sum_{k : i in H_k} sum_j w_kj dN^{kji} (the k = i term with
 * the difference form: -sum_{l != i} of its own family's), i.e. the nodal force of a unit
 * constant stress: a constant P gives f_i = -(1/V_i) P A_i.
 *
 * VC1 correction functions (thesis eq. 5.64 without the bond projector; Bode et al. eq. 79 with
 * delta_JI, see docs/validation/galerkin.md): psi^{ki} = N^{kki}_MLS1 - delta_ki, the linear
 * moving least squares values at X_k with w^{kk} = 0:
 *   M1 = sum_{i != k} w^{ki} V_i p^{ki} (x) p^{ki},  p^{ki} = (1, dX^{ki}),
 *   N^{kki} = w^{ki} V_i p^{ki} . M1^-1 e_0,  N^{kkk} = 0.
 * sum_i psi^{ki} = 0 and sum_i dX^{ki} psi^{ki} = 0 (linear reproduction), so adding
 * psi^{ki} alpha_k to every dN^{kji} keeps (5.8) and (5.9) (eq. 5.57).
 */
#include <math.h>

#include "kernels.h"
#include "ref/law_linear_elastic.h"
#include "ref/law_neo_hooke.h"
#include "ref/law_svk.h"
#include "ref/tensor_d.h"

PDK_KERNEL_FP_EXACT

static inline pdk_index member_j(const pdk_galerkin_arrays *a, pdk_index k, int m) {
  return m == 0 ? k : a->bond_j[a->bond_start[k] + m - 1];
}

/* Relative determinant floor of a moment matrix: below it the family does not span. */
#define PDK_GALERKIN_DET_RTOL 1e-12

pdk_index pdk_kernel_galerkin_shape_ref(const pdk_galerkin_consts *k, const pdk_galerkin_arrays *a,
                                        pdk_index k0, pdk_index k1) {
  const int d = k->dim;
  pdk_index bad = 0;
  for (pdk_index kk = k0; kk < k1; ++kk) {
    const int nm = (int)(a->bond_start[kk + 1] - a->bond_start[kk]) + 1;
    double *dk = a->d + a->dstart[kk];
    for (int j = 0; j < nm; ++j) {
      /* the centre of the expansion: the evaluation point (taylor) or the family's particle */
      const int c0 = k->basis == 1 ? 0 : j;
      const pdk_index pc = member_j(a, kk, c0);
      double M[3][3] = {{0}}, tr = 0.0;
      for (int i = 0; i < nm; ++i) {
        if (i == c0) continue;
        const pdk_index pi = member_j(a, kk, i);
        double dx[3] = {0, 0, 0}, r2 = 0.0;
        for (int c = 0; c < d; ++c) {
          dx[c] = a->X[c][pi] - a->X[c][pc];
          r2 += dx[c] * dx[c];
        }
        const double wv = a->volume[pi] / r2;
        for (int r = 0; r < d; ++r)
          for (int c = 0; c < d; ++c)
            M[r][c] += wv * dx[r] * dx[c];
      }
      for (int c = 0; c < d; ++c)
        tr += M[c][c];
      const double det = pdk_det_d(d, M);
      double Mi[3][3] = {{0}};
      const int ok = tr > 0 && fabs(det) > PDK_GALERKIN_DET_RTOL * pow(tr / d, d);
      if (ok)
        pdk_inv_d(d, M, det, Mi);
      else
        ++bad;
      double *dj = dk + (size_t)j * nm * d;
      double sum[3] = {0, 0, 0};
      for (int i = 0; i < nm; ++i) {
        for (int c = 0; c < d; ++c)
          dj[i * d + c] = 0.0;
        if (i == c0 || !ok) continue;
        const pdk_index pi = member_j(a, kk, i);
        double dx[3] = {0, 0, 0}, r2 = 0.0;
        for (int c = 0; c < d; ++c) {
          dx[c] = a->X[c][pi] - a->X[c][pc];
          r2 += dx[c] * dx[c];
        }
        const double wv = a->volume[pi] / r2;
        for (int r = 0; r < d; ++r) {
          double s = 0.0;
          for (int c = 0; c < d; ++c)
            s += Mi[r][c] * dx[c];
          dj[i * d + r] = wv * s;
          sum[r] += wv * s;
        }
      }
      for (int c = 0; c < d; ++c)
        dj[c0 * d + c] = -sum[c];
      if (k->bond && j > 0 && ok) {
        /* bond-mapping correction (thesis eq. 5.55): dN <- (1 - n (x) n) dN + delta_ji dX/|dX|^2,
         * n = dX^{kj}/|dX^{kj}|, so F^{kj} dX^{kj} = dx^{kj} exactly */
        const pdk_index pj = member_j(a, kk, j);
        double r[3] = {0, 0, 0}, r2 = 0.0;
        for (int c = 0; c < d; ++c) {
          r[c] = a->X[c][pj] - a->X[c][kk];
          r2 += r[c] * r[c];
        }
        for (int i = 0; i < nm; ++i) {
          double dn = 0.0;
          for (int c = 0; c < d; ++c)
            dn += r[c] * dj[i * d + c];
          for (int c = 0; c < d; ++c)
            dj[i * d + c] -= r[c] * dn / r2;
        }
        for (int c = 0; c < d; ++c)
          dj[j * d + c] += r[c] / r2;
      }
    }
  }
  return bad;
}

/* Solves the n x n system A x = b (n <= 4) by Gaussian elimination with partial pivoting; returns
 * 0 when a pivot is below rtol times the largest entry. */
static int solve_small(int n, double A[4][4], double b[4], double rtol) {
  double amax = 0.0;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      amax = fmax(amax, fabs(A[r][c]));
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (fabs(A[r][c]) > fabs(A[p][c])) p = r;
    if (!(fabs(A[p][c]) > rtol * amax)) return 0;
    if (p != c) {
      for (int e = 0; e < n; ++e) {
        const double t = A[c][e];
        A[c][e] = A[p][e];
        A[p][e] = t;
      }
      const double t = b[c];
      b[c] = b[p];
      b[p] = t;
    }
    for (int r = c + 1; r < n; ++r) {
      const double f = A[r][c] / A[c][c];
      for (int e = c; e < n; ++e)
        A[r][e] -= f * A[c][e];
      b[r] -= f * b[c];
    }
  }
  for (int r = n - 1; r >= 0; --r) {
    double s = b[r];
    for (int e = r + 1; e < n; ++e)
      s -= A[r][e] * b[e];
    b[r] = s / A[r][r];
  }
  return 1;
}

pdk_index pdk_kernel_galerkin_psi_ref(const pdk_galerkin_consts *k, const pdk_galerkin_arrays *a,
                                      double *psi, pdk_index k0, pdk_index k1) {
  const int d = k->dim, np = d + 1;
  pdk_index bad = 0;
  for (pdk_index kk = k0; kk < k1; ++kk) {
    const int nm = (int)(a->bond_start[kk + 1] - a->bond_start[kk]) + 1;
    double *pk = psi + a->bond_start[kk] + kk;
    /* the moment matrix is scaled by the mean bond length h so its entries are of one order */
    double h = 0.0;
    for (int i = 1; i < nm; ++i) {
      const pdk_index pi = member_j(a, kk, i);
      double r2 = 0.0;
      for (int c = 0; c < d; ++c) {
        const double t = a->X[c][pi] - a->X[c][kk];
        r2 += t * t;
      }
      h += sqrt(r2);
    }
    h = nm > 1 ? h / (nm - 1) : 1.0;
    double M[4][4] = {{0}}, c1[4] = {1, 0, 0, 0};
    for (int i = 1; i < nm; ++i) {
      const pdk_index pi = member_j(a, kk, i);
      double p[4] = {1, 0, 0, 0}, r2 = 0.0;
      for (int c = 0; c < d; ++c) {
        const double t = a->X[c][pi] - a->X[c][kk];
        p[c + 1] = t / h;
        r2 += t * t;
      }
      const double wv = a->volume[pi] / r2;
      for (int r = 0; r < np; ++r)
        for (int c = 0; c < np; ++c)
          M[r][c] += wv * p[r] * p[c];
    }
    const int ok = nm > 1 && solve_small(np, M, c1, PDK_GALERKIN_DET_RTOL);
    if (!ok) ++bad;
    pk[0] = ok ? -1.0 : 0.0;
    for (int i = 1; i < nm; ++i) {
      const pdk_index pi = member_j(a, kk, i);
      double p[4] = {1, 0, 0, 0}, r2 = 0.0;
      for (int c = 0; c < d; ++c) {
        const double t = a->X[c][pi] - a->X[c][kk];
        p[c + 1] = t / h;
        r2 += t * t;
      }
      double s = 0.0;
      for (int r = 0; r < np; ++r)
        s += p[r] * c1[r];
      pk[i] = ok ? a->volume[pi] / r2 * s : 0.0;
    }
  }
  return bad;
}

static inline int law_eval(const pdk_galerkin_consts *k, const double F[3][3], double P[3][3],
                           double *W) {
  switch (k->law) {
  case PDK_KERNEL_LAW_LINEAR_ELASTIC:
    return pdk_law_linear_elastic_eval_d(k->dim, k->lambda, k->mu, F, P, W);
  case PDK_KERNEL_LAW_SVK: return pdk_law_svk_eval_d(k->dim, k->lambda, k->mu, F, P, W);
  case PDK_KERNEL_LAW_NEO_HOOKE: return pdk_law_neo_hooke_eval_d(k->dim, k->lambda, k->mu, F, P, W);
  }
  return 0;
}

/* Pass 1 of one family in dimension D (a constant at each call, so the small loops unroll): the
 * family's displacements relative to u_k are gathered once into du, the per-member forces summed
 * in g and stored once. */
static inline pdk_index pass1_family(const int D, const pdk_galerkin_consts *k,
                                     const pdk_galerkin_arrays *a, int unit, pdk_index kk) {
  double du[3][PDK_GALERKIN_MAX_MEMBERS], g[3][PDK_GALERKIN_MAX_MEMBERS];
  const int nm = (int)(a->bond_start[kk + 1] - a->bond_start[kk]) + 1;
  const double *dk = a->d + a->dstart[kk];
  const pdk_bond_index s0 = a->bond_start[kk] + kk;
  const pdk_index *nbr = a->bond_j + a->bond_start[kk] - 1; /* nbr[i], i >= 1 */
  double uk[3] = {0, 0, 0};
  for (int c = 0; c < D; ++c)
    uk[c] = a->x[c][kk] - a->X[c][kk];
  for (int i = 1; i < nm; ++i)
    for (int c = 0; c < D; ++c) {
      du[c][i] = (a->x[c][nbr[i]] - a->X[c][nbr[i]]) - uk[c];
      g[c][i] = 0.0;
    }
  const double wk = a->volume[kk] / a->vfam[kk];
  double energy = 0.0;
  pdk_index bad = 0;
  for (int j = 0; j < nm; ++j) {
    const double *dj = dk + (size_t)j * nm * D;
    const double w = wk * a->volume[j == 0 ? kk : nbr[j]];
    if (unit) {
      for (int i = 1; i < nm; ++i)
        for (int c = 0; c < D; ++c)
          g[c][i] += w * dj[i * D + c];
      continue;
    }
    double F[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int i = 1; i < nm; ++i)
      for (int r = 0; r < D; ++r)
        for (int c = 0; c < D; ++c)
          F[r][c] += du[r][i] * dj[i * D + c];
    if (j == 0)
      for (int r = 0; r < D; ++r)
        for (int c = 0; c < D; ++c)
          a->F[r * D + c][kk] = F[r][c];
    double P[3][3] = {{0}}, Wj = 0.0;
    if (!law_eval(k, F, P, &Wj)) {
      ++bad;
      continue;
    }
    energy += w * Wj;
    double wP[3][3];
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c)
        wP[r][c] = w * P[r][c];
    for (int i = 1; i < nm; ++i)
      for (int r = 0; r < D; ++r) {
        double t = 0.0;
        for (int c = 0; c < D; ++c)
          t += wP[r][c] * dj[i * D + c];
        g[r][i] += t;
      }
  }
  for (int c = 0; c < D; ++c) {
    double sum = 0.0;
    for (int i = 1; i < nm; ++i) {
      a->G[c][s0 + i] = g[c][i];
      sum += g[c][i];
    }
    a->G[c][s0] = -sum;
  }
  if (a->W) a->W[kk] = energy;
  return bad;
}

pdk_index pdk_kernel_galerkin_pass1_ref(const pdk_galerkin_consts *k, const pdk_galerkin_arrays *a,
                                        int unit, pdk_index k0, pdk_index k1) {
  pdk_index bad = 0;
  for (pdk_index kk = k0; kk < k1; ++kk)
    bad += k->dim == 3 ? pass1_family(3, k, a, unit, kk) : pass1_family(2, k, a, unit, kk);
  return bad;
}

void pdk_kernel_galerkin_pass2_ref(const pdk_galerkin_consts *k, const pdk_galerkin_arrays *a,
                                   int area, pdk_index i0, pdk_index i1) {
  const int d = k->dim;
  for (pdk_index i = i0; i < i1; ++i) {
    double s[3];
    const pdk_bond_index own = a->bond_start[i] + i;
    for (int c = 0; c < d; ++c)
      s[c] = a->G[c][own];
    for (pdk_bond_index b = a->bond_start[i]; b < a->bond_start[i + 1]; ++b) {
      const pdk_index j = a->bond_j[b];
      const pdk_bond_index slot = a->bond_start[j] + j + a->rev[b];
      for (int c = 0; c < d; ++c)
        s[c] += a->G[c][slot];
    }
    const double f = area ? 1.0 : -1.0 / a->volume[i];
    for (int c = 0; c < d; ++c)
      a->f[c][i] = f * s[c];
  }
}
