/* Derived output fields of the correspondence kinds (TL, semi-TL and UL connectivity).
 *
 *   "von_mises"  von Mises equivalent of the Cauchy stress sigma [pressure], sqrt(3/2 dev sigma :
 *                dev sigma) with all three normal components, so in 2-D it includes the
 *                plane-strain sigma_zz. From the model's state after the last force pass:
 *                  laws with history (jc): the law's own (pdk_law_info.von_mises);
 *                  elastic laws: P = A K (A = P K^-1 and K^-1 are fields of the model;
 *                    updated-Lagrangian connectivity keeps no K, so there P is the law evaluated
 *                    again at the stored total F, as its pass did), then sigma from the law's
 *                    pdk_law_info.cauchy (P F^T / J; P itself for linear_elastic; in 2-D sigma_zz
 *                    from the law at F33 = 1);
 *                particles whose family does not span, or where the law is undefined (flag SPAN
 *                or INVERTED), give 0.
 */
#include <math.h>
#include <string.h>

#include "kernels.h"
#include "law.h"
#include "pdk/ctx.h"
#include "pdk/model.h"
#include "pdk/particles.h"

/* von Mises of a symmetric 3 x 3 stress. */
static double von_mises_of(const double S[3][3]) {
  const double a = S[0][0] - S[1][1], b = S[1][1] - S[2][2], c = S[2][2] - S[0][0];
  return sqrt(0.5 * (a * a + b * b + c * c) +
              3.0 * (S[0][1] * S[0][1] + S[1][2] * S[1][2] + S[0][2] * S[0][2]));
}

static int von_mises_elastic(const pdk_model *m, const pdk_law_info *law, double *vm) {
  pdk_particles *p = m->p;
  const int d = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const pdk_model_opts *mo = &m->opts;
  const double mu = mo->shear_modulus, lambda0 = mo->bulk_modulus - 2.0 * mu / 3.0;
  const int32_t *mat = mo->num_materials > 0 ? pdk_particles_field_data(p, "material", 0) : NULL;
  const uint8_t *flag = pdk_particles_field_data(p, "flag", 0);
  const double *Fc[9], *Ac[9], *Kc[9];
  /* TL and semi-TL: P = A K from the pass's own A; UL keeps no K (A = tau_r M^-1 there), so the
   * elastic laws are evaluated again at the total F, as its pass did */
  const int from_law = mo->connectivity == PDK_CONNECTIVITY_UL;
  int ok = vm && flag;
  for (int t = 0; t < d * d; ++t) {
    Fc[t] = pdk_particles_field_data(p, "F", t);
    Ac[t] = pdk_particles_field_data(p, "A", t);
    Kc[t] = pdk_particles_field_data(p, "Kinv", t);
    ok = ok && Fc[t] && (from_law || (Ac[t] && Kc[t]));
  }
  PDK_CHECK(ok, m->ctx, PDK_ERR_NOT_FOUND,
            "von_mises needs the correspondence fields F, flag%s; the model did not declare them",
            from_law ? "" : ", A, Kinv");
  pdk_corr_consts kc;
  memset(&kc, 0, sizeof kc);
  kc.dim = d;
  kc.law = (int)mo->law;
  kc.lambda = lambda0;
  kc.mu = mu;
  for (pdk_index i = 0; i < n; ++i) {
    double F[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 1}}, S[3][3] = {{0}};
    vm[i] = 0.0;
    if (flag[i] & (PDK_CORR_FLAG_SPAN | PDK_CORR_FLAG_INVERTED)) continue;
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c)
        F[a][c] = Fc[a * d + c][i];
    /* the particle's material's Lame constants (multi-material bodies) */
    pdk_corr_consts ki = kc;
    if (mat) {
      const pdk_material *q = &mo->materials[mat[i]];
      ki.mu = q->shear_modulus;
      ki.lambda = q->bulk_modulus - 2.0 * q->shear_modulus / 3.0;
    }
    double P[3][3] = {{0}};
    if (from_law) {
      double W;
      if (!pdk_kernel_corr_law_ref(&ki, F, P, &W)) continue;
    } else {
      /* P = A K, K = (K^-1)^-1 */
      double Ki[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 1}}, K[3][3];
      for (int a = 0; a < d; ++a)
        for (int c = 0; c < d; ++c)
          Ki[a][c] = Kc[a * d + c][i];
      const double detK = pdk_law_det3(Ki);
      if (!(fabs(detK) > 0) || !isfinite(detK)) continue;
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) {
          /* cofactor / det, transposed */
          const int a1 = (c + 1) % 3, a2 = (c + 2) % 3, c1 = (a + 1) % 3, c2 = (a + 2) % 3;
          K[a][c] = (Ki[a1][c1] * Ki[a2][c2] - Ki[a1][c2] * Ki[a2][c1]) / detK;
        }
      for (int a = 0; a < d; ++a)
        for (int c = 0; c < d; ++c)
          for (int e = 0; e < d; ++e)
            P[a][c] += Ac[a * d + e][i] * K[e][c];
    }
    if (!law->cauchy(d, ki.lambda, F, P, S)) continue;
    vm[i] = von_mises_of(S);
  }
  return PDK_SUCCESS;
}

int pdk_model_corr_derived(const pdk_model *m, const char *name, double dt, double *out) {
  PDK_CHECK(!strcmp(name, "von_mises"), m->ctx, PDK_ERR_NOT_FOUND,
            "the correspondence model derives no field '%s' (it derives von_mises)", name);
  const pdk_law_info *law = pdk_law_info_of(m->opts.law);
  if (law->von_mises) return law->von_mises(m, dt, out);
  return von_mises_elastic(m, law, out);
}
