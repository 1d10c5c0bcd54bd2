/* Johnson-Cook failures of a correspondence pass, shared by both connectivities (src/models/model_corr.c,
 * src/models/model_corr_ul.c): which particle's material-point update failed, and the run's error. */
#include <math.h>
#include <stdio.h>

#include "kernels.h"
#include "model_impl.h"
#include "pdk/ctx.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/plasticity.h"

/* Johnson-Cook, after a committing pass: the first particle (index order) whose update failed
 * (flag INVERTED without SPAN), unless it had failed with FAILED_ZERO (it carries no stress
 * whatever F is), into *first (-1: none), and how many there are. */
pdk_index pdk_model_corr_jc_first_failure(const pdk_model *m, const uint8_t *flag,
                                          const uint8_t *failed, pdk_index *first) {
  const pdk_index n = pdk_particles_count(m->p);
  const int zero = m->opts.jc.failed_mode == PDK_JC_FAILED_ZERO;
  pdk_index count = 0;
  *first = -1;
  for (pdk_index i = 0; i < n; ++i)
    if ((flag[i] & (PDK_CORR_FLAG_SPAN | PDK_CORR_FLAG_INVERTED)) == PDK_CORR_FLAG_INVERTED &&
        !(zero && failed && failed[i])) {
      if (*first < 0) *first = i;
      ++count;
    }
  return count;
}

/* The error for `count` failed updates, the first at particle i: why (NULL: read from its "F",
 * which the pass wrote before the update: not finite, det F <= 0, or a trial elastic stretch that
 * is not positive). Such a particle got zero stress for the pass; carrying on would commit a
 * state the law does not define, so the run stops naming it. */
int pdk_model_corr_jc_failure_error(pdk_model *m, pdk_index i, pdk_index count, const char *why) {
  const int d = pdk_particles_dim(m->p);
  char buf[160];
  if (!why) {
    double F[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, fmax = 0.0;
    int finite = 1;
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c) {
        F[r][c] = ((const double *)pdk_particles_field_data(m->p, "F", r * d + c))[i];
        finite = finite && isfinite(F[r][c]);
        fmax = fabs(F[r][c]) > fmax ? fabs(F[r][c]) : fmax;
      }
    const double J = F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) -
                     F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
                     F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
    const double *sm_avg = pdk_particles_field_data(m->p, "sigma_m_avg", 0);
    if (!finite)
      snprintf(buf, sizeof buf, "its deformation gradient F has a non-finite entry");
    else if (!(J > 0.0))
      snprintf(buf, sizeof buf, "det F = %.3g (its family is turned inside out)", J);
    else if (sm_avg && !isfinite(sm_avg[i]))
      snprintf(buf, sizeof buf, "its family-averaged pressure is %g", sm_avg[i]);
    else
      snprintf(buf, sizeof buf,
               "the trial elastic stretch is not positive (round-off at an extreme deformation: "
               "det F = %.3g, largest |F| entry %.3g)",
               J, fmax);
    why = buf;
  }
  const double *x[3] = {NULL, NULL, NULL};
  for (int a = 0; a < d; ++a)
    x[a] = pdk_particles_field_data(m->p, "x", a);
  char where[128];
  snprintf(where, sizeof where, d == 3 ? "(%.4g, %.4g, %.4g)" : "(%.4g, %.4g)", x[0][i], x[1][i],
           d == 3 ? x[2][i] : 0.0);
  return pdk_ctx_error_set(
      m->ctx, PDK_ERR_NUMERIC, "correspondence force pass",
      "the Johnson-Cook update failed for particle %d (id %lld, now at %s): %s; %lld particle(s) "
      "in all in this pass. The stress is undefined there, so the run stops instead of carrying "
      "zero stress: the step (the model's time step %g; a static solve's load step) may be too "
      "large for the loading, or a load, velocity or displacement too large for the body; take "
      "smaller steps or check the boundary conditions' values",
      (int)i, (long long)pdk_particles_id(m->p)[i], where, why, (long long)count, m->dt);
}
