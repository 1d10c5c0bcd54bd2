/* Small dense tensors, d x d in the top-left of a 3 x 3 row-major array (d = 2 or 3): the
 * determinant, the inverse by the adjugate and the product, shared by the correspondence kernels
 * (kernels/ref/corr_law.h, corr_ul.c) and the Johnson-Cook update (kernels/ref/jc.c). A caller
 * with a constant d gets the branch folded away. */
#ifndef PDK_KERNELS_TENSOR_D_H
#define PDK_KERNELS_TENSOR_D_H

static inline double pdk_det_d(const int d, const double T[3][3]) {
  if (d == 2) return T[0][0] * T[1][1] - T[0][1] * T[1][0];
  return T[0][0] * (T[1][1] * T[2][2] - T[1][2] * T[2][1]) -
         T[0][1] * (T[1][0] * T[2][2] - T[1][2] * T[2][0]) +
         T[0][2] * (T[1][0] * T[2][1] - T[1][1] * T[2][0]);
}

/* Inverse by the adjugate; the caller checks det != 0. */
static inline void pdk_inv_d(const int d, const double T[3][3], double det, double R[3][3]) {
  const double s = 1.0 / det;
  if (d == 2) {
    R[0][0] = T[1][1] * s;
    R[0][1] = -T[0][1] * s;
    R[1][0] = -T[1][0] * s;
    R[1][1] = T[0][0] * s;
    return;
  }
  R[0][0] = (T[1][1] * T[2][2] - T[1][2] * T[2][1]) * s;
  R[0][1] = (T[0][2] * T[2][1] - T[0][1] * T[2][2]) * s;
  R[0][2] = (T[0][1] * T[1][2] - T[0][2] * T[1][1]) * s;
  R[1][0] = (T[1][2] * T[2][0] - T[1][0] * T[2][2]) * s;
  R[1][1] = (T[0][0] * T[2][2] - T[0][2] * T[2][0]) * s;
  R[1][2] = (T[0][2] * T[1][0] - T[0][0] * T[1][2]) * s;
  R[2][0] = (T[1][0] * T[2][1] - T[1][1] * T[2][0]) * s;
  R[2][1] = (T[0][1] * T[2][0] - T[0][0] * T[2][1]) * s;
  R[2][2] = (T[0][0] * T[1][1] - T[0][1] * T[1][0]) * s;
}

/* R = S T (d x d). */
static inline void pdk_corr_mul_d(const int d, const double S[3][3], const double T[3][3],
                                  double R[3][3]) {
  for (int a = 0; a < d; ++a)
    for (int c = 0; c < d; ++c) {
      double s = 0.0;
      for (int e = 0; e < d; ++e)
        s += S[a][e] * T[e][c];
      R[a][c] = s;
    }
}

#endif
