/* Reference family candidate scan: j is a neighbour of i when |X_j - X_i|^2 <= r2max and j != i.
 *
 * Contract (kernels.h): the squared distance is (dx*dx + dy*dy) + dz*dz with dx = X_j - X_i, each
 * operation rounded to double, no FMA; it is symmetric in i and j bit for bit, so
 * j in H_i <=> i in H_j. Accepted ids are appended in candidate order; the count is returned. This
 * is the oracle every optimized variant must reproduce exactly (same ids, same order). */
#include "kernels.h"

PDK_KERNEL_FP_EXACT

pdk_index pdk_kernel_family_scan2_ref(pdk_index n_cand, const double *restrict cx,
                                      const double *restrict cy, double xi, double yi, double r2max,
                                      pdk_index self, const pdk_index *restrict cand_id,
                                      pdk_index *restrict out) {
  pdk_index count = 0;
  for (pdk_index k = 0; k < n_cand; ++k) {
    double dx = cx[k] - xi, dy = cy[k] - yi;
    double r2 = dx * dx + dy * dy;
    if (r2 <= r2max && cand_id[k] != self) out[count++] = cand_id[k];
  }
  return count;
}

pdk_index pdk_kernel_family_scan3_ref(pdk_index n_cand, const double *restrict cx,
                                      const double *restrict cy, const double *restrict cz,
                                      double xi, double yi, double zi, double r2max, pdk_index self,
                                      const pdk_index *restrict cand_id, pdk_index *restrict out) {
  pdk_index count = 0;
  for (pdk_index k = 0; k < n_cand; ++k) {
    double dx = cx[k] - xi, dy = cy[k] - yi, dz = cz[k] - zi;
    double r2 = dx * dx + dy * dy + dz * dz;
    if (r2 <= r2max && cand_id[k] != self) out[count++] = cand_id[k];
  }
  return count;
}
