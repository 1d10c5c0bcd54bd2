/* Helpers shared by the Johnson-Cook material-point tests (t08x): small tensors, a call that must
 * succeed, stresses recomputed from P, and a bracketed root finder for the lateral stretch of
 * mixed (stress-controlled) loading. */
#ifndef PDK_JC_UTIL_H
#define PDK_JC_UTIL_H

#include <float.h>

#include "pdk/plasticity.h"
#include "test_util.h"

/* pdk_jc_update that must succeed. */
static inline void ju_update(const pdk_jc_params *p, int dim, const double F[3][3], double dt,
                             const pdk_jc_state *in, pdk_jc_state *out, double P[3][3],
                             pdk_jc_result *res) {
  int err = pdk_jc_update(p, dim, F, dt, in, out, P, res);
  if (err) T_FAIL("pdk_jc_update returned %d", err);
}

/* Histories equal bit for bit (field by field: struct padding is not compared). */
static inline int ju_state_equal(const pdk_jc_state *a, const pdk_jc_state *b) {
  return memcmp(a->cp_inv, b->cp_inv, sizeof a->cp_inv) == 0 &&
         memcmp(&a->eps_p, &b->eps_p, sizeof(double)) == 0 &&
         memcmp(&a->damage, &b->damage, sizeof(double)) == 0 &&
         memcmp(&a->temp_rise, &b->temp_rise, sizeof(double)) == 0 && a->failed == b->failed;
}

static inline void ju_identity(double M[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      M[i][j] = i == j ? 1.0 : 0.0;
}

/* C = A B (3 x 3) */
static inline void ju_mul(const double A[3][3], const double B[3][3], double C[3][3]) {
  double T[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      T[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j] + A[i][2] * B[2][j];
  memcpy(C, T, sizeof T);
}

/* C = A B^T */
static inline void ju_mul_bt(const double A[3][3], const double B[3][3], double C[3][3]) {
  double T[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      T[i][j] = A[i][0] * B[j][0] + A[i][1] * B[j][1] + A[i][2] * B[j][2];
  memcpy(C, T, sizeof T);
}

static inline double ju_det(const double T[3][3]) {
  return T[0][0] * (T[1][1] * T[2][2] - T[1][2] * T[2][1]) -
         T[0][1] * (T[1][0] * T[2][2] - T[1][2] * T[2][0]) +
         T[0][2] * (T[1][0] * T[2][1] - T[1][1] * T[2][0]);
}

/* Rotation by angle t about the unit axis k (Rodrigues). */
static inline void ju_rotation(const double k[3], double t, double R[3][3]) {
  const double c = cos(t), s = sin(t), v = 1.0 - c;
  R[0][0] = c + k[0] * k[0] * v;
  R[0][1] = k[0] * k[1] * v - k[2] * s;
  R[0][2] = k[0] * k[2] * v + k[1] * s;
  R[1][0] = k[1] * k[0] * v + k[2] * s;
  R[1][1] = c + k[1] * k[1] * v;
  R[1][2] = k[1] * k[2] * v - k[0] * s;
  R[2][0] = k[2] * k[0] * v - k[1] * s;
  R[2][1] = k[2] * k[1] * v + k[0] * s;
  R[2][2] = c + k[2] * k[2] * v;
}

/* Kirchhoff stress tau = P F^T from the d x d block of P (plane strain: tau_zz from the result,
 * as P does not carry it). */
static inline void ju_kirchhoff(int dim, const double P[3][3], const double F[3][3],
                                const pdk_jc_result *r, double tau[3][3]) {
  double Pf[3][3] = {{0}}, Ff[3][3];
  ju_identity(Ff);
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j) {
      Pf[i][j] = P[i][j];
      Ff[i][j] = F[i][j];
    }
  if (dim == 2) Pf[2][2] = r->sigma[2] * r->J;
  ju_mul_bt(Pf, Ff, tau);
}

/* von Mises of a 3 x 3 (not necessarily symmetric: the symmetric part is used) stress. */
static inline double ju_von_mises(const double t[3][3]) {
  const double m = (t[0][0] + t[1][1] + t[2][2]) / 3.0;
  double ss = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double s = 0.5 * (t[i][j] + t[j][i]) - (i == j ? m : 0.0);
      ss += s * s;
    }
  return sqrt(1.5 * ss);
}

/* Root of an increasing function g on [lo, hi] (g(lo) < 0 < g(hi) expected), Illinois
 * regula falsi; stops when |g| <= gtol or the bracket is a few ulps wide. */
typedef double (*ju_fn)(double x, void *data);
static inline double ju_root(ju_fn g, void *data, double lo, double hi, double gtol) {
  double glo = g(lo, data), ghi = g(hi, data);
  if (!(glo < 0.0 && ghi > 0.0))
    T_FAIL("ju_root: no bracket: g(%g) = %g, g(%g) = %g", lo, glo, hi, ghi);
  int side = 0;
  for (int it = 0; it < 400; ++it) {
    double x = (lo * ghi - hi * glo) / (ghi - glo);
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    const double gx = g(x, data);
    if (fabs(gx) <= gtol || hi - lo <= 4.0 * DBL_EPSILON * fmax(fabs(lo), fabs(hi))) return x;
    if (gx < 0.0) {
      lo = x;
      glo = gx;
      if (side == -1) ghi *= 0.5;
      side = -1;
    } else {
      hi = x;
      ghi = gx;
      if (side == 1) glo *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (lo + hi);
}

#endif
