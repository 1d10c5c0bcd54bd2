/* The run loop: a scene's simulation to its end with its output, checkpoints, restart and stop
 * (include/pdk/run.h). `pdk run` (src/cli/run.c) is this plus arguments, signals and printing.
 *
 * One call goes through these stages, each failure reported with its stage:
 *   restart (opts.restart: pdk_sim_restart, and the scene text stored in the checkpoint)
 *   -> the folder -> event BEGIN -> the output (appending to the checkpoint run's output when dir
 *   holds it; it must reach the checkpoint) -> the first records (unless appended) -> stepping
 *   with the records at their intervals -> the checkpoint at the end or at the stop (explicit),
 *   handed to the output -> closing the output.
 */
#include <errno.h>
#include <string.h>
#include <sys/stat.h>

#include "core/comm.h"
#include "core/h5io.h"
#include "pdk/output.h"
#include "pdk/run.h"
#include "core/pdk_impl.h"
#include "run_impl.h"
#include "pdk/comm.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/model.h"
#include "pdk/particles.h"
#include "pdk/scene.h"
#include "pdk/static.h"

/* Steps per pdk_explicit_run call at most: how often a stop request is seen and progress told. */
#define RUN_CHUNK 100

pdk_run_opts pdk_run_opts_default(void) {
  pdk_run_opts o;
  memset(&o, 0, sizeof o);
  o.plot = 1;
  return o;
}

typedef struct run_state {
  pdk_ctx *ctx;
  pdk_sim *sim;
  const pdk_scene *scene;
  const pdk_run_opts *opts;
  pdk_run_report *rep;
  const pdk_scene_output *so;
  char *dir, *ckpt;
  pdk_output *out;
} run_state;

static void emit(run_state *r, pdk_run_event_kind kind, long step, long total,
                 const pdk_history *h) {
  if (!r->opts->on_event) return;
  pdk_run_event ev;
  memset(&ev, 0, sizeof ev);
  ev.kind = kind;
  ev.step = step;
  ev.total = total;
  ev.history = h;
  ev.report = r->rep;
  r->opts->on_event(r->opts->arg, &ev);
}

/* On several ranks the ranks agree (a sum over them): a rank that saw the request leaves the loop
 * only with the others, at the same step (every rank calls this at the same points). */
static int stop_requested(const run_state *r) {
  int64_t stop = r->opts->stop && *r->opts->stop;
  if (pdk_comm_sum_i64(r->ctx, &stop)) return 1;
  return stop != 0;
}

static int fail(run_state *r, pdk_run_stage stage, int err) {
  r->rep->status = PDK_RUN_FAILED;
  r->rep->stage = stage;
  return err;
}

/* mkdir -p: every prefix of dir ending before a '/', then dir; an existing one is fine. */
static int make_folder(run_state *r) {
  char *buf = strdup(r->dir);
  if (!buf) return pdk_ctx_error_set(r->ctx, PDK_ERR_MEMORY, NULL, "out of memory");
  int rc = 0;
  for (char *q = buf + 1; *q && !rc; ++q) {
    if (*q != '/') continue;
    *q = '\0';
    if (mkdir(buf, 0777) && errno != EEXIST) rc = -1;
    *q = '/';
  }
  if (!rc && mkdir(buf, 0777) && errno != EEXIST) rc = -1;
  free(buf);
  if (!rc) return PDK_SUCCESS;
  r->rep->os_error = errno;
  return pdk_ctx_error_set(r->ctx, PDK_ERR_IO, NULL, "cannot create the output folder '%s': %s",
                           r->dir, strerror(errno));
}

/* The records of a field output at step: derived fields refreshed, then the scene's fields. */
static int write_fields(run_state *r, long step, double time) {
  PDK_CALL(pdk_sim_update_output_fields(r->sim));
  return pdk_output_write_fields(r->out, pdk_sim_particles(r->sim), step, time, r->so->fields,
                                 r->so->num_fields);
}

/* The checkpoint at the end of a run or at a stop: written complete under a temporary name
 * (<ckpt>.part) and handed to the output, whose closing phase renames it with the run's other
 * files, so a kill in that phase never leaves this run's checkpoint beside an earlier run's
 * output (the periodic checkpoints of output.checkpoint_interval are committed at once: a killed
 * run must leave one; a restart checks that the output it continues reaches it). */
static int final_checkpoint(run_state *r) {
  char *part = pdk_str_printf("%s.part", r->ckpt);
  if (!part) return pdk_ctx_error_set(r->ctx, PDK_ERR_MEMORY, NULL, "out of memory");
  int err = pdk_checkpoint_write(r->ctx, part, pdk_sim_explicit(r->sim), pdk_scene_text(r->scene));
  if (!err) err = pdk_output_adopt(r->out, part, r->ckpt);
  if (err) remove(part);
  free(part);
  return err;
}

static int run_explicit(run_state *r, int appended) {
  pdk_sim *sim = r->sim;
  pdk_explicit *e = pdk_sim_explicit(sim);
  pdk_run_report *rep = r->rep;
  const pdk_scene_output *so = r->so;
  long total = pdk_sim_num_steps(sim); /* grows when a solver.dt_update lowers dt */
  int dt_changes = pdk_explicit_num_dt_changes(e);
  const long hist_every = so->history_interval > 0 ? so->history_interval : 1;
  const long field_every = so->field_interval;
  const long ckpt_every = so->checkpoint_interval;
  pdk_history h;
  memset(&h, 0, sizeof h);
  int err = pdk_explicit_run(e, 0, &h);
  rep->first = h;
  if (!appended) { /* a continued output has the records up to the checkpoint already */
    if (!err) err = pdk_output_write_history(r->out, &h);
    if (!err) err = write_fields(r, h.step, h.time);
  }
  rep->wtime_stepping = pdk_wtime();
  while (!err && pdk_explicit_step(e) < total && !stop_requested(r)) {
    long s = pdk_explicit_step(e);
    long next = total;
    const long cand[3] = {(s / hist_every + 1) * hist_every,
                          field_every > 0 ? (s / field_every + 1) * field_every : total,
                          ckpt_every > 0 ? (s / ckpt_every + 1) * ckpt_every : total};
    for (int k = 0; k < 3; ++k)
      next = cand[k] < next ? cand[k] : next;
    const long chunk = next - s < RUN_CHUNK ? next - s : RUN_CHUNK;
    if ((err = pdk_explicit_run(e, chunk, &h))) break;
    s = pdk_explicit_step(e);
    rep->step = s;
    rep->last = h;
    if (pdk_explicit_num_dt_changes(e) != dt_changes) {
      dt_changes = pdk_explicit_num_dt_changes(e);
      total = pdk_sim_num_steps(sim);
      rep->total = total;
      emit(r, PDK_RUN_EVENT_DT_LOWERED, s, total, &h);
    }
    if (s % hist_every == 0 || s == total) err = pdk_output_write_history(r->out, &h);
    if (!err && ((field_every > 0 && s % field_every == 0) || s == total))
      err = write_fields(r, s, h.time);
    if (!err && ckpt_every > 0 && s % ckpt_every == 0 && s < total)
      err = pdk_checkpoint_write(r->ctx, r->ckpt, e, pdk_scene_text(r->scene));
    if (!err) emit(r, PDK_RUN_EVENT_STEPPED, s, total, &h);
  }
  rep->step = pdk_explicit_step(e);
  rep->total = total;
  rep->last = h;
  if (err) return fail(r, PDK_RUN_STAGE_STEP, err);
  rep->stopped = stop_requested(r);
  if ((err = final_checkpoint(r))) return fail(r, PDK_RUN_STAGE_CHECKPOINT, err);
  if ((err = pdk_output_close(&r->out, 1))) return fail(r, PDK_RUN_STAGE_CLOSE, err);
  rep->status = rep->stopped ? PDK_RUN_STOPPED : PDK_RUN_DONE;
  return PDK_SUCCESS;
}

/* A static run failed at a load step (err, its message in the context): the load steps solved
 * before it are complete records, so the output is closed with them. */
static int keep_solved(run_state *r, int err) {
  pdk_static *st = pdk_sim_static(r->sim);
  if (pdk_static_levels_solved(st) <= 0) return err;
  char msg[PDK_ERRMSG_MAX];
  snprintf(msg, sizeof msg, "%s", pdk_ctx_error_message(r->ctx));
  if (pdk_output_close(&r->out, 1))
    snprintf(r->rep->keep_error, sizeof r->rep->keep_error, "%s", pdk_ctx_error_message(r->ctx));
  else
    r->rep->kept_steps = pdk_static_levels_solved(st);
  return pdk_ctx_error_set(r->ctx, err, NULL, "%s", msg); /* the first error stays the error */
}

static int run_static(run_state *r) {
  pdk_sim *sim = r->sim;
  pdk_run_report *rep = r->rep;
  const pdk_scene_output *so = r->so;
  const long total = pdk_sim_num_steps(sim);
  const long hist_every = so->history_interval > 0 ? so->history_interval : 1;
  const long field_every = so->field_interval;
  pdk_history h;
  memset(&h, 0, sizeof h);
  int err = pdk_sim_static_history(sim, &h);
  rep->first = h;
  if (!err) err = pdk_output_write_history(r->out, &h);
  if (!err) err = write_fields(r, h.step, h.time);
  rep->wtime_stepping = pdk_wtime();
  rep->total = total;
  while (!err && h.step < total && !stop_requested(r)) {
    if ((err = pdk_sim_static_step(sim, &h))) break;
    const long s = h.step;
    rep->step = s;
    rep->last = h;
    if (s % hist_every == 0 || s == total) err = pdk_output_write_history(r->out, &h);
    if (!err && ((field_every > 0 && s % field_every == 0) || s == total))
      err = write_fields(r, s, h.time);
    if (!err) emit(r, PDK_RUN_EVENT_STEPPED, s, total, &h);
  }
  rep->step = h.step;
  rep->last = h;
  if (err) return fail(r, PDK_RUN_STAGE_STEP, keep_solved(r, err));
  rep->stopped = stop_requested(r);
  if ((err = pdk_output_close(&r->out, 1))) return fail(r, PDK_RUN_STAGE_CLOSE, err);
  rep->status = rep->stopped ? PDK_RUN_STOPPED : PDK_RUN_DONE;
  return PDK_SUCCESS;
}

/* A restart into the folder of its run continues that output, which must reach the checkpoint:
 * its history up to the last record due at or before the checkpoint's step, and its fields
 * likewise (a run killed after a later periodic checkpoint left an output that does not). */
static int check_continued(run_state *r) {
  const pdk_scene_output *so = r->so;
  const long step = r->rep->restart.step;
  const long hist_every = so->history_interval > 0 ? so->history_interval : 1;
  const long need_h = step / hist_every * hist_every;
  const long need_f = so->field_interval > 0 ? step / so->field_interval * so->field_interval : 0;
  const long last_h = pdk_output_last_history_step(r->out);
  const long last_f = pdk_output_last_field_step(r->out);
  const char *name = pdk_scene_name(r->scene);
  if (last_h >= need_h && last_f >= need_f) return PDK_SUCCESS;
  return pdk_ctx_error_set(
      r->ctx, PDK_ERR_ARG, NULL,
      "the output in '%s' ends at step %ld (history) and %ld (fields), before the checkpoint's "
      "step %ld (records due at %ld and %ld): it is not the output of the run that wrote the "
      "checkpoint (that run may have been killed before its output was complete); restart into "
      "another folder (-o), or move %s.h5, %s.xmf and %s_history.csv out of '%s'",
      r->dir, last_h, last_f, step, need_h, need_f, name, name, name, r->dir);
}

static int run(run_state *r) {
  pdk_sim *sim = r->sim;
  const pdk_run_opts *opts = r->opts;
  pdk_run_report *rep = r->rep;
  char *ckpt_scene = NULL; /* the scene text stored in the checkpoint */
  int err = PDK_SUCCESS;
  const char *name = pdk_scene_name(r->scene);
  r->dir = opts->dir ? strdup(opts->dir) : pdk_str_printf("out/%s", name);
  r->ckpt = r->dir ? pdk_str_printf("%s/%s_checkpoint.h5", r->dir, name) : NULL;
  if (!r->ckpt)
    return fail(r, PDK_RUN_STAGE_SETUP,
                pdk_ctx_error_set(r->ctx, PDK_ERR_MEMORY, NULL, "out of memory"));
  if (!r->dir[0])
    return fail(r, PDK_RUN_STAGE_SETUP,
                pdk_ctx_error_set(r->ctx, PDK_ERR_ARG, "pdk_sim_run",
                                  "the output folder is empty (''); give a folder, or NULL "
                                  "for out/<scene name>"));
  if (opts->restart && pdk_comm_size() > 1)
    return fail(r, PDK_RUN_STAGE_RESTART,
                pdk_ctx_error_set(r->ctx, PDK_ERR_UNSUPPORTED, "pdk_sim_run",
                                  "a restart runs on one rank only so far; this run has %d ranks: "
                                  "restart without mpiexec (or with mpiexec -n 1)",
                                  pdk_comm_size()));
  if (opts->restart) {
    if ((err = pdk_sim_restart_text(sim, r->scene, opts->restart, &rep->restart, &ckpt_scene)))
      return fail(r, PDK_RUN_STAGE_RESTART, err);
    rep->start_step = rep->step = rep->restart.step;
    rep->total = rep->restart.end_step;
    if (rep->restart.end_step == rep->restart.step) {
      free(ckpt_scene);
      rep->status = PDK_RUN_NOTHING_TO_DO;
      return PDK_SUCCESS;
    }
    emit(r, PDK_RUN_EVENT_RESTARTED, rep->step, rep->total, NULL);
  } else {
    pdk_explicit *e = pdk_sim_explicit(sim);
    rep->start_step = rep->step = e ? pdk_explicit_step(e) : 0;
    rep->total = pdk_sim_num_steps(sim);
  }
  if ((err = make_folder(r))) {
    free(ckpt_scene);
    return fail(r, PDK_RUN_STAGE_FOLDER, err);
  }
  emit(r, PDK_RUN_EVENT_BEGIN, rep->step, rep->total, NULL);
  pdk_output_opts oo;
  memset(&oo, 0, sizeof oo);
  oo.dir = r->dir;
  oo.name = name;
  oo.scene_text = pdk_scene_text(r->scene);
  oo.reaction_sets = r->so->reaction_sets;
  oo.num_reaction_sets = r->so->num_reaction_sets;
  oo.reaction_normals = (const double(*)[3])r->so->reaction_normal;
  oo.walls = r->so->walls;
  oo.num_walls = r->so->num_walls;
  oo.units = r->so->units;
  oo.compression = r->so->compression;
  if (pdk_particles_dim(pdk_sim_particles(sim)) == 2)
    oo.thickness = pdk_model_opts_get(pdk_sim_model(sim))->thickness;
  oo.plot = opts->plot;
  oo.append = opts->restart != NULL;
  oo.append_step = rep->restart.step;
  oo.append_scene = ckpt_scene;
  err = pdk_output_open(r->ctx, &oo, pdk_sim_particles(sim), &r->out);
  free(ckpt_scene);
  if (err) return fail(r, PDK_RUN_STAGE_OPEN, err);
  rep->kept_rows = pdk_output_num_history_rows(r->out);
  rep->kept_fields = pdk_output_num_field_steps(r->out);
  const int appended = rep->kept_rows > 0 || rep->kept_fields > 0;
  if (appended) {
    if ((err = check_continued(r))) return fail(r, PDK_RUN_STAGE_CONTINUE, err);
    emit(r, PDK_RUN_EVENT_CONTINUING, rep->step, rep->total, NULL);
  }
  return pdk_sim_explicit(sim) ? run_explicit(r, appended) : run_static(r);
}

int pdk_sim_run(pdk_sim *sim, const pdk_scene *scene, const pdk_run_opts *opts,
                pdk_run_report *report) {
  pdk_run_report local;
  pdk_run_report *rep = report ? report : &local;
  memset(rep, 0, sizeof *rep);
  rep->status = PDK_RUN_FAILED;
  rep->stage = PDK_RUN_STAGE_SETUP;
  PDK_CHECK_ARG(sim, NULL);
  pdk_ctx *ctx = pdk_particles_ctx(pdk_sim_particles(sim));
  PDK_CHECK_ARG(scene, ctx);
  const pdk_run_opts defaults = pdk_run_opts_default();
  run_state r;
  memset(&r, 0, sizeof r);
  r.ctx = ctx;
  r.sim = sim;
  r.scene = scene;
  r.opts = opts ? opts : &defaults;
  r.rep = rep;
  r.so = pdk_scene_output_get(scene);
  rep->stage = PDK_RUN_STAGE_NONE;
  const int err = run(&r);
  pdk_output_close(&r.out, 0); /* after a failure: removes the temporary files */
  free(r.dir);
  free(r.ckpt);
  return err;
}
