/* The explicit solver's part of a checkpoint (/solver; src/core/state.h): the scalars a step reads
 * besides the particle fields and the model's state, so a restored run continues bitwise:
 *   time, step, dt, dt_created   where the run is and the step it takes (and was created with)
 *   strain, external_work        the strain energy of the last force pass, the work done so far
 *   dt_stable, dt_step0, dt_time0, est_step, est_broken, num_estimates, num_dt_changes
 *                                the dt_update state: the latest stable estimate, where dt last
 *                                changed, the last estimate's step and broken-bond count, the
 *                                counters
 *   auto_ratio                   dt_update auto: the bond length ratio at its last estimate
 *                                (only once one ran)
 */
#include <stdlib.h>
#include <string.h>

#include "explicit_impl.h"
#include "core/state.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/model.h"

pdk_model *pdk_explicit_model(const pdk_explicit *e) { return e->m; }

int pdk_explicit_state_save(const pdk_explicit *e, pdk_state *s) {
  PDK_CALL(pdk_state_put_f64(s, "time", e->time));
  PDK_CALL(pdk_state_put_i64(s, "step", e->step));
  PDK_CALL(pdk_state_put_f64(s, "dt", e->dt));
  PDK_CALL(pdk_state_put_f64(s, "dt_created", e->dt_created));
  PDK_CALL(pdk_state_put_f64(s, "strain", e->strain));
  PDK_CALL(pdk_state_put_f64(s, "external_work", e->external_work));
  PDK_CALL(pdk_state_put_f64(s, "dt_stable", e->dt_stable));
  PDK_CALL(pdk_state_put_i64(s, "dt_step0", e->dt_step0));
  PDK_CALL(pdk_state_put_f64(s, "dt_time0", e->dt_time0));
  PDK_CALL(pdk_state_put_i64(s, "est_step", e->est_step));
  PDK_CALL(pdk_state_put_i64(s, "est_broken", e->est_broken));
  PDK_CALL(pdk_state_put_i64(s, "num_estimates", e->num_estimates));
  PDK_CALL(pdk_state_put_i64(s, "num_dt_changes", e->num_dt_changes));
  /* auto: only once a re-estimate moved it (files of runs without one stay as they were) */
  if (e->opts.dt_update == PDK_DT_UPDATE_AUTO && e->num_estimates > 1)
    PDK_CALL(pdk_state_put_f64(s, "auto_ratio", e->auto_ratio));
  char key[32];
  for (int w = 0; w < e->num_walls; ++w) { /* walls only: runs without keep their files */
    snprintf(key, sizeof key, "wall_impulse_%d", w);
    PDK_CALL(pdk_state_put_f64(s, key, e->wall_impulse[w]));
  }
  if (e->num_walls) PDK_CALL(pdk_state_put_f64(s, "contact_work", e->contact_work));
  return PDK_SUCCESS;
}

int pdk_explicit_state_info(pdk_state *s, pdk_checkpoint_solver *out) {
  int64_t v;
  memset(out, 0, sizeof *out);
  PDK_CALL(pdk_state_get_i64(s, "step", &v));
  out->step = (long)v;
  PDK_CALL(pdk_state_get_f64(s, "time", &out->time));
  PDK_CALL(pdk_state_get_f64(s, "dt", &out->dt));
  PDK_CALL(pdk_state_get_f64(s, "dt_created", &out->dt_created));
  PDK_CALL(pdk_state_get_f64(s, "dt_stable", &out->dt_stable));
  PDK_CALL(pdk_state_get_i64(s, "dt_step0", &v));
  out->dt_step0 = (long)v;
  PDK_CALL(pdk_state_get_f64(s, "dt_time0", &out->dt_time0));
  return PDK_SUCCESS;
}

int pdk_explicit_state_load(pdk_explicit *e, pdk_state *s) {
  int64_t v;
  PDK_CALL(pdk_state_get_f64(s, "time", &e->time));
  PDK_CALL(pdk_state_get_i64(s, "step", &v));
  e->step = (long)v;
  PDK_CALL(pdk_state_get_f64(s, "dt", &e->dt));
  PDK_CALL(pdk_state_get_f64(s, "strain", &e->strain));
  PDK_CALL(pdk_state_get_f64(s, "external_work", &e->external_work));
  e->acct_set = 0; /* the energy account's baseline is taken again at the next step */
  free(e->auto_x); /* dt_update auto reads the bonds in full at the next step */
  e->auto_x = NULL;
  e->acct_streak = 0;
  if (pdk_state_has(s, "dt_step0")) { /* the dt_update state (files before it: none) */
    PDK_CALL(pdk_state_get_f64(s, "dt_stable", &e->dt_stable));
    PDK_CALL(pdk_state_get_i64(s, "dt_step0", &v));
    e->dt_step0 = (long)v;
    PDK_CALL(pdk_state_get_f64(s, "dt_time0", &e->dt_time0));
    PDK_CALL(pdk_state_get_i64(s, "est_step", &v));
    e->est_step = (long)v;
    PDK_CALL(pdk_state_get_i64(s, "est_broken", &v));
    e->est_broken = (pdk_bond_index)v;
    PDK_CALL(pdk_state_get_i64(s, "num_estimates", &v));
    e->num_estimates = (int)v;
    PDK_CALL(pdk_state_get_i64(s, "num_dt_changes", &v));
    e->num_dt_changes = (int)v;
  }
  /* without it the ratio of creation stands: no auto re-estimate ran before the checkpoint */
  if (pdk_state_has(s, "auto_ratio")) PDK_CALL(pdk_state_get_f64(s, "auto_ratio", &e->auto_ratio));
  char key[32];
  for (int w = 0; w < e->num_walls; ++w) {
    snprintf(key, sizeof key, "wall_impulse_%d", w);
    if (pdk_state_has(s, key)) PDK_CALL(pdk_state_get_f64(s, key, &e->wall_impulse[w]));
  }
  if (pdk_state_has(s, "contact_work"))
    PDK_CALL(pdk_state_get_f64(s, "contact_work", &e->contact_work));
  return PDK_SUCCESS;
}

double pdk_explicit_dt_created(const pdk_explicit *e) { return e->dt_created; }

void pdk_explicit_restart_dt(pdk_explicit *e, double dt, long step0, double time0) {
  e->dt = dt;
  e->dt_step0 = step0;
  e->dt_time0 = time0;
}
