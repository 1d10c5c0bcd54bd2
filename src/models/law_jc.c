/* Correspondence law jc: finite J2 plasticity with Johnson-Cook hardening and damage (opts.jc;
 * the material point is src/models/plasticity.c and kernels/ref/jc.c, the pass kernels/ref/corr.c). Its
 * history fields are listed in include/pdk/model.h. */
#include <stdio.h>

#include "kernels.h"
#include "law.h"
#include "pdk/ctx.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/plasticity.h"

_Static_assert(PDK_KERNEL_LAW_JC == (int)PDK_LAW_JC, "law values");

static const char *const jc_history[] = {"eps_p",    "damage",     "failed", "w_plastic",
                                         "w_damage", "eps_p_rate", NULL};

static int jc_rate_terms(const pdk_model_opts *o, char *buf, size_t len) {
  const pdk_jc_params *jc = &o->jc;
  if (jc->C == 0.0 && !(jc->damage && jc->D4 != 0.0)) return 0;
  snprintf(buf, len, "the Johnson-Cook rate terms (C = %g, D4 = %g)", jc->C,
           jc->damage ? jc->D4 : 0.0);
  return 1;
}

static int jc_breaks_bonds(const pdk_model_opts *o) {
  return o->jc.damage && !o->failed_keeps_bonds;
}

/* von Mises of each particle: a trial update of the committed history at the stored F
 * (pdk_jc_update with a scratch output: nothing changes), whose returned stress is the one of the
 * pass to round-off; failed particles and those whose family does not span (or where the law is
 * undefined) give 0. */
static int jc_von_mises(const pdk_model *m, double dt, double *vm) {
  pdk_particles *p = m->p;
  const int d = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const pdk_model_opts *mo = &m->opts;
  const uint8_t *flag = pdk_particles_field_data(p, "flag", 0);
  const double *Fc[9];
  int ok = vm && flag;
  for (int t = 0; t < d * d; ++t) {
    Fc[t] = pdk_particles_field_data(p, "F", t);
    ok = ok && Fc[t];
  }
  const double *cp[6] = {0}, *eps_p = NULL, *damage = NULL, *temp = NULL;
  const uint8_t *failed = NULL;
  for (int c = 0; c < 6; ++c) {
    cp[c] = pdk_particles_field_data(p, "cp_inv", c);
    ok = ok && cp[c];
  }
  eps_p = pdk_particles_field_data(p, "eps_p", 0);
  damage = pdk_particles_field_data(p, "damage", 0);
  failed = pdk_particles_field_data(p, "failed", 0);
  temp = mo->jc.thermal ? pdk_particles_field_data(p, "temp_rise", 0) : NULL;
  ok = ok && eps_p && damage && failed && (!mo->jc.thermal || temp);
  PDK_CHECK(ok, m->ctx, PDK_ERR_NOT_FOUND,
            "von_mises needs the correspondence fields F, flag%s; the model did not declare them",
            " and the Johnson-Cook history");
  for (pdk_index i = 0; i < n; ++i) {
    double F[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 1}};
    vm[i] = 0.0;
    if (flag[i] & (PDK_CORR_FLAG_SPAN | PDK_CORR_FLAG_INVERTED)) continue;
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c)
        F[a][c] = Fc[a * d + c][i];
    if (failed[i]) continue;
    pdk_jc_state in, scratch;
    for (int c = 0; c < 6; ++c)
      in.cp_inv[c] = cp[c][i];
    in.eps_p = eps_p[i];
    in.damage = damage[i];
    in.temp_rise = temp ? temp[i] : 0.0;
    in.failed = 0;
    double P[3][3];
    pdk_jc_result res;
    if (!pdk_jc_update(&mo->jc, d, F, dt, &in, &scratch, P, &res)) vm[i] = res.sigma_vm;
  }
  return PDK_SUCCESS;
}

const pdk_law_info pdk_law_jc = {
    .law = PDK_LAW_JC,
    .name = "jc",
    .flags = PDK_LAWF_HISTORY | PDK_LAWF_ONE_MATERIAL | PDK_LAWF_PLASTICITY,
    .one_material_why = "the Johnson-Cook law takes one material (material.johnson_cook); several "
                        "materials work with the elastic laws",
    .history_fields = jc_history,
    .history_hint = " (it is Johnson-Cook history: set model.law: jc)",
    .von_mises = jc_von_mises,
    .rate_terms = jc_rate_terms,
    .breaks_bonds = jc_breaks_bonds};
