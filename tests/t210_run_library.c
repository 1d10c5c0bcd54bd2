/* pdk_sim_run (include/pdk/run.h): a scene run through the library, the run loop of `pdk run`.
 * 1. The t092 bar (2-D PMB, bonds break), 400 steps, history every 7 steps, fields every 60, a
 *    checkpoint every 150 (intervals that divide neither one another nor the chunk of 100):
 *    pdk_sim_run writes the same files (history CSV and XDMF byte for byte, the HDF5 fields and
 *    the final checkpoint object for object) as a low-level sequence written here that steps one
 *    step at a time and writes the records at the documented steps; its chunks (the STEPPED
 *    events) are the documented ones (at most 100 steps, ending at the next record); the report
 *    holds the first and last records and the step counts.
 * 2. The same run asked to stop (the flag set by the event handler once step >= 200) stops at the
 *    end of that chunk: PDK_RUN_STOPPED, a checkpoint of that step, a closed output. A second
 *    pdk_sim_run of a freshly built simulation restarting from that checkpoint into the same
 *    folder continues the output (events RESTARTED, BEGIN, CONTINUING; the rows and field outputs
 *    up to the checkpoint kept) and ends with the files of 1.
 * 3. A restart from the checkpoint at the end: PDK_RUN_NOTHING_TO_DO, no event, no file changed.
 * 4. dt_update (tests/scenes/t052_bar_dt.yaml: dt lowered at step 10): one DT_LOWERED event
 *    whose total is the grown step count; the run ends there, its last history row too.
 * 5. A static scene (tests/scenes/t094_static.yaml, ADR, 4 load steps): the files equal those of
 *    the low-level sequence (pdk_sim_static_step), one STEPPED event per load step, no
 *    checkpoint; asked to stop after the first load step: PDK_RUN_STOPPED, the output holding the
 *    unloaded state and that load step.
 * 6. Failures name their stage: a restart of a static scene and of a missing checkpoint
 *    (PDK_RUN_STAGE_RESTART), an output folder below a file (PDK_RUN_STAGE_FOLDER, ENOTDIR).
 * The files go to $PDK_BUILD_DIR/tests/t210_run_library.work.
 * labels: unit */
#include <errno.h>
#include <unistd.h>

#include "test_util.h"
#include "h5_same.h"

#define HIST 7
#define FIELD 60
#define CKPT 150
#define MAX_EVENTS 1000

static const char *const bar_ov[] = {"output.history_interval=7", "output.field_interval=60",
                                     "output.checkpoint_interval=150"};

typedef struct built {
  pdk_scene *scene;
  pdk_sim *sim;
} built;

static built build(pdk_ctx *ctx, const char *file, const char *const *ov, int num_ov) {
  char path[4096];
  snprintf(path, sizeof path, "%s/tests/scenes/%s", getenv("PDK_SOURCE_DIR"), file);
  built b = {NULL, NULL};
  T_OK(ctx, pdk_scene_load(ctx, path, ov, num_ov, &b.scene));
  T_OK(ctx, pdk_sim_create(ctx, b.scene, &b.sim));
  return b;
}

static void unbuild(built *b) {
  pdk_sim_destroy(&b->sim);
  pdk_scene_destroy(&b->scene);
}

/* ---- the events ---------------------------------------------------------------------------- */

typedef struct recorder {
  int count[5];                /* per kind */
  pdk_run_event_kind first[8]; /* the kinds of the first events, in order */
  int num_first;
  long stepped[MAX_EVENTS];       /* step of each STEPPED event */
  long stepped_total[MAX_EVENTS]; /* and its total */
  int num_stepped;
  long lowered_total; /* total of the last DT_LOWERED event */
  long stop_at;       /* > 0: set *stop at the first STEPPED event at or past it */
  volatile sig_atomic_t *stop;
} recorder;

static void on_event(void *arg, const pdk_run_event *ev) {
  recorder *r = arg;
  T_ASSERT(ev->kind >= 0 && ev->kind <= PDK_RUN_EVENT_DT_LOWERED && ev->report, "bad event");
  r->count[ev->kind]++;
  if (r->num_first < 8) r->first[r->num_first++] = ev->kind;
  if (ev->kind == PDK_RUN_EVENT_STEPPED) {
    T_ASSERT(r->num_stepped < MAX_EVENTS && ev->history && ev->history->step == ev->step,
             "STEPPED event at step %ld: no history record of it", ev->step);
    r->stepped[r->num_stepped] = ev->step;
    r->stepped_total[r->num_stepped++] = ev->total;
    if (r->stop_at > 0 && ev->step >= r->stop_at) *r->stop = 1;
  }
  if (ev->kind == PDK_RUN_EVENT_DT_LOWERED) r->lowered_total = ev->total;
}

static pdk_run_opts opts_for(const char *dir, recorder *r) {
  memset(r, 0, sizeof *r);
  pdk_run_opts o = pdk_run_opts_default();
  T_ASSERT(o.plot == 1 && !o.dir && !o.restart && !o.stop && !o.on_event, "defaults");
  o.dir = dir;
  o.plot = 0;
  o.on_event = on_event;
  o.arg = r;
  return o;
}

/* The chunks the run steps in, by run.h: from s to the next record (history, field or
 * checkpoint step; an interval 0 has none) or the end, at most 100 steps. */
static int documented_chunks(long total, long hist, long field, long ckpt, long *ends) {
  int n = 0;
  for (long s = 0; s < total;) {
    long next = total;
    const long cand[3] = {(s / hist + 1) * hist, field > 0 ? (s / field + 1) * field : total,
                          ckpt > 0 ? (s / ckpt + 1) * ckpt : total};
    for (int k = 0; k < 3; ++k)
      next = cand[k] < next ? cand[k] : next;
    s += next - s < 100 ? next - s : 100;
    ends[n++] = s;
  }
  return n;
}

/* ---- files ----------------------------------------------------------------------------------- */

static char *slurp(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  const long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *buf = malloc((size_t)n + 1);
  T_ASSERT(buf && fread(buf, 1, (size_t)n, f) == (size_t)n, "cannot read %s", path);
  buf[n] = '\0';
  fclose(f);
  if (len) *len = (size_t)n;
  return buf;
}

static int same_bytes(const char *a, const char *b) {
  size_t la = 0, lb = 0;
  char *x = slurp(a, &la), *y = slurp(b, &lb);
  const int same = x && y && la == lb && !memcmp(x, y, la);
  free(x);
  free(y);
  return same;
}

static int count_lines(const char *path) {
  size_t len = 0;
  char *buf = slurp(path, &len);
  int n = 0;
  for (size_t k = 0; buf && k < len; ++k)
    n += buf[k] == '\n';
  free(buf);
  return buf ? n : -1;
}

static int exists(const char *path) { return access(path, F_OK) == 0; }

/* The files <dir_a>/<name>* and <dir_b>/<name>* are the same: CSV and XDMF bytes, the HDF5
 * contents; with_ckpt: the checkpoints' contents too. */
static void assert_same_output(const char *dir_a, const char *dir_b, const char *name,
                               int with_ckpt, const char *what) {
  char a[1024], b[1024], why[2048] = "";
  static const char *const text[2] = {"_history.csv", ".xmf"};
  for (int k = 0; k < 2; ++k) {
    snprintf(a, sizeof a, "%s/%s%s", dir_a, name, text[k]);
    snprintf(b, sizeof b, "%s/%s%s", dir_b, name, text[k]);
    T_ASSERT(same_bytes(a, b), "%s: %s differs from %s", what, b, a);
  }
  static const char *const h5[2] = {".h5", "_checkpoint.h5"};
  for (int k = 0; k < 1 + with_ckpt; ++k) {
    snprintf(a, sizeof a, "%s/%s%s", dir_a, name, h5[k]);
    snprintf(b, sizeof b, "%s/%s%s", dir_b, name, h5[k]);
    T_ASSERT(h5s_same_file(a, b, why, sizeof why), "%s: %s differs from %s: %s", what, b, a, why);
  }
}

static void assert_no_part(const char *dir, const char *name) {
  static const char *const parts[] = {".h5.part", ".xmf.part", "_history.csv.part",
                                      "_checkpoint.h5.part"};
  for (size_t k = 0; k < sizeof parts / sizeof parts[0]; ++k) {
    char x[1024];
    snprintf(x, sizeof x, "%s/%s%s", dir, name, parts[k]);
    T_ASSERT(!exists(x), "%s left behind", x);
  }
}

static void assert_same_record(const pdk_history *a, const pdk_history *b, const char *what) {
  T_ASSERT(a->step == b->step && !memcmp(&a->time, &b->time, sizeof a->time) &&
               !memcmp(&a->kinetic, &b->kinetic, sizeof a->kinetic) &&
               !memcmp(&a->strain, &b->strain, sizeof a->strain) &&
               !memcmp(&a->external_work, &b->external_work, sizeof a->external_work) &&
               !memcmp(a->reaction, b->reaction, sizeof a->reaction) && a->broken == b->broken,
           "%s: record of step %ld differs from the one of step %ld", what, a->step, b->step);
}

/* ---- the low-level sequences ------------------------------------------------------------------
 */

static pdk_output *open_output(pdk_ctx *ctx, const built *b, const char *dir) {
  const pdk_scene_output *so = pdk_scene_output_get(b->scene);
  pdk_output_opts oo = pdk_output_opts_default();
  oo.dir = dir;
  oo.name = pdk_scene_name(b->scene);
  oo.scene_text = pdk_scene_text(b->scene);
  oo.reaction_sets = so->reaction_sets;
  oo.num_reaction_sets = so->num_reaction_sets;
  oo.units = so->units;
  oo.plot = 0;
  pdk_output *o = NULL;
  T_OK(ctx, pdk_output_open(ctx, &oo, pdk_sim_particles(b->sim), &o));
  return o;
}

static void fields_at(pdk_ctx *ctx, const built *b, pdk_output *o, const pdk_history *h) {
  const pdk_scene_output *so = pdk_scene_output_get(b->scene);
  T_OK(ctx, pdk_sim_update_output_fields(b->sim));
  T_OK(ctx, pdk_output_write_fields(o, pdk_sim_particles(b->sim), h->step, h->time, so->fields,
                                    so->num_fields));
}

/* The bar one step at a time: records at the steps run.h names, the checkpoint at the end. */
static void bar_by_hand(pdk_ctx *ctx, const char *dir, pdk_history *first, pdk_history *last) {
  built b = build(ctx, "t092_bar.yaml", bar_ov, 3);
  pdk_explicit *e = pdk_sim_explicit(b.sim);
  pdk_output *o = open_output(ctx, &b, dir);
  pdk_history h;
  T_OK(ctx, pdk_explicit_run(e, 0, &h));
  *first = h;
  T_OK(ctx, pdk_output_write_history(o, &h));
  fields_at(ctx, &b, o, &h);
  const long total = pdk_sim_num_steps(b.sim);
  while (pdk_explicit_step(e) < total) {
    T_OK(ctx, pdk_explicit_run(e, 1, &h));
    if (h.step % HIST == 0 || h.step == total) T_OK(ctx, pdk_output_write_history(o, &h));
    if (h.step % FIELD == 0 || h.step == total) fields_at(ctx, &b, o, &h);
  }
  *last = h;
  char ckpt[1024];
  snprintf(ckpt, sizeof ckpt, "%s/bar_checkpoint.h5", dir);
  T_OK(ctx, pdk_checkpoint_write(ctx, ckpt, e, pdk_scene_text(b.scene)));
  T_OK(ctx, pdk_output_close(&o, 1));
  unbuild(&b);
}

/* The static block one load step at a time (history every load step, fields first and last). */
static void block_by_hand(pdk_ctx *ctx, const char *dir) {
  built b = build(ctx, "t094_static.yaml", NULL, 0);
  pdk_output *o = open_output(ctx, &b, dir);
  pdk_history h;
  T_OK(ctx, pdk_sim_static_history(b.sim, &h));
  T_OK(ctx, pdk_output_write_history(o, &h));
  fields_at(ctx, &b, o, &h);
  const long total = pdk_sim_num_steps(b.sim);
  for (long k = 1; k <= total; ++k) {
    T_OK(ctx, pdk_sim_static_step(b.sim, &h));
    T_OK(ctx, pdk_output_write_history(o, &h));
    if (k == total) fields_at(ctx, &b, o, &h);
  }
  T_OK(ctx, pdk_output_close(&o, 1));
  unbuild(&b);
}

/* ---- the cases ---------------------------------------------------------------------------------
 */

static void whole_run(pdk_ctx *ctx) {
  pdk_history first, last;
  bar_by_hand(ctx, "ref", &first, &last);
  built b = build(ctx, "t092_bar.yaml", bar_ov, 3);
  recorder r;
  pdk_run_opts o = opts_for("lib", &r);
  pdk_run_report rep;
  T_OK(ctx, pdk_sim_run(b.sim, b.scene, &o, &rep));
  T_ASSERT(rep.status == PDK_RUN_DONE && rep.stage == PDK_RUN_STAGE_NONE && !rep.stopped,
           "status %d, stage %d", (int)rep.status, (int)rep.stage);
  T_ASSERT(rep.start_step == 0 && rep.step == 400 && rep.total == 400 &&
               pdk_explicit_step(pdk_sim_explicit(b.sim)) == 400,
           "steps: from %ld to %ld of %ld", rep.start_step, rep.step, rep.total);
  T_ASSERT(rep.wtime_stepping > 0 && rep.kept_rows == 0 && rep.kept_fields == 0, "report");
  assert_same_record(&rep.first, &first, "report.first");
  assert_same_record(&rep.last, &last, "report.last");
  assert_same_output("ref", "lib", "bar", 1, "pdk_sim_run against the step-by-step sequence");
  assert_no_part("lib", "bar");
  T_ASSERT(count_lines("lib/bar_history.csv") == 1 + 400 / HIST + 1 + 1, "%d CSV lines",
           count_lines("lib/bar_history.csv"));
  /* the events: BEGIN first, then one STEPPED per documented chunk */
  long ends[MAX_EVENTS];
  const int n = documented_chunks(400, HIST, FIELD, CKPT, ends);
  T_ASSERT(r.count[PDK_RUN_EVENT_BEGIN] == 1 && r.first[0] == PDK_RUN_EVENT_BEGIN &&
               r.count[PDK_RUN_EVENT_RESTARTED] == 0 && r.count[PDK_RUN_EVENT_CONTINUING] == 0 &&
               r.count[PDK_RUN_EVENT_DT_LOWERED] == 0,
           "events: %d BEGIN, %d RESTARTED, %d CONTINUING, %d DT_LOWERED",
           r.count[PDK_RUN_EVENT_BEGIN], r.count[PDK_RUN_EVENT_RESTARTED],
           r.count[PDK_RUN_EVENT_CONTINUING], r.count[PDK_RUN_EVENT_DT_LOWERED]);
  T_ASSERT(r.num_stepped == n, "%d STEPPED events, %d chunks documented", r.num_stepped, n);
  for (int k = 0; k < n; ++k)
    T_ASSERT(r.stepped[k] == ends[k] && r.stepped_total[k] == 400,
             "chunk %d ends at step %ld (of %ld), documented %ld", k, r.stepped[k],
             r.stepped_total[k], ends[k]);
  unbuild(&b);

  /* records 250 steps apart: the chunks stop at 100 steps */
  static const char *const sparse[] = {"output.history_interval=250", "output.field_interval=0"};
  b = build(ctx, "t092_bar.yaml", sparse, 2);
  o = opts_for("sparse", &r);
  T_OK(ctx, pdk_sim_run(b.sim, b.scene, &o, &rep));
  static const long sparse_ends[5] = {100, 200, 250, 350, 400};
  T_ASSERT(documented_chunks(400, 250, 0, 0, ends) == 5 && r.num_stepped == 5,
           "%d STEPPED events, 5 chunks documented", r.num_stepped);
  for (int k = 0; k < 5; ++k)
    T_ASSERT(ends[k] == sparse_ends[k] && r.stepped[k] == sparse_ends[k],
             "chunk %d ends at step %ld, documented %ld", k, r.stepped[k], sparse_ends[k]);
  unbuild(&b);
}

static void stop_and_restart(pdk_ctx *ctx) {
  volatile sig_atomic_t stop = 0;
  built b = build(ctx, "t092_bar.yaml", bar_ov, 3);
  recorder r;
  pdk_run_opts o = opts_for("stop", &r);
  o.stop = &stop;
  r.stop = &stop;
  r.stop_at = 200;
  pdk_run_report rep;
  T_OK(ctx, pdk_sim_run(b.sim, b.scene, &o, &rep));
  long ends[MAX_EVENTS];
  const int n = documented_chunks(400, HIST, FIELD, CKPT, ends);
  long at = 0;
  for (int k = 0; k < n && !at; ++k)
    if (ends[k] >= 200) at = ends[k];
  T_ASSERT(rep.status == PDK_RUN_STOPPED && rep.stopped && rep.step == at && rep.total == 400 &&
               r.stepped[r.num_stepped - 1] == at,
           "status %d, stopped at step %ld (last event %ld), expected %ld", (int)rep.status,
           rep.step, r.stepped[r.num_stepped - 1], at);
  assert_no_part("stop", "bar");
  long ckpt_step = -1;
  T_OK(ctx, pdk_checkpoint_info(ctx, "stop/bar_checkpoint.h5", &ckpt_step, NULL, NULL));
  T_ASSERT(ckpt_step == at, "the checkpoint is at step %ld, the run stopped at %ld", ckpt_step, at);
  T_ASSERT(count_lines("stop/bar_history.csv") == 1 + at / HIST + 1, "stopped: %d CSV lines",
           count_lines("stop/bar_history.csv"));
  unbuild(&b);

  /* a fresh simulation continues it into the same folder */
  b = build(ctx, "t092_bar.yaml", bar_ov, 3);
  o = opts_for("stop", &r);
  o.restart = "stop/bar_checkpoint.h5";
  T_OK(ctx, pdk_sim_run(b.sim, b.scene, &o, &rep));
  T_ASSERT(rep.status == PDK_RUN_DONE && rep.start_step == at && rep.restart.step == at &&
               rep.step == 400 && !rep.restart.dt_changed,
           "restart: status %d, from %ld (checkpoint %ld) to %ld", (int)rep.status, rep.start_step,
           rep.restart.step, rep.step);
  T_ASSERT(rep.kept_rows == at / HIST + 1 && rep.kept_fields == at / FIELD + 1,
           "kept %ld rows and %d field outputs", rep.kept_rows, rep.kept_fields);
  T_ASSERT(r.num_first >= 3 && r.first[0] == PDK_RUN_EVENT_RESTARTED &&
               r.first[1] == PDK_RUN_EVENT_BEGIN && r.first[2] == PDK_RUN_EVENT_CONTINUING &&
               r.stepped[0] > at,
           "restart events: %d %d %d, first chunk to %ld", (int)r.first[0], (int)r.first[1],
           (int)r.first[2], r.stepped[0]);
  assert_same_output("lib", "stop", "bar", 1, "stopped and continued against one run");
  assert_no_part("stop", "bar");
  unbuild(&b);

  /* the checkpoint at the end: nothing to do, nothing touched */
  b = build(ctx, "t092_bar.yaml", bar_ov, 3);
  o = opts_for("stop", &r);
  o.restart = "stop/bar_checkpoint.h5";
  T_OK(ctx, pdk_sim_run(b.sim, b.scene, &o, &rep));
  T_ASSERT(rep.status == PDK_RUN_NOTHING_TO_DO && rep.restart.step == 400 && r.num_first == 0,
           "at the end: status %d, %d events", (int)rep.status, r.num_first);
  assert_same_output("lib", "stop", "bar", 1, "nothing to do");
  unbuild(&b);
}

static void dt_update(pdk_ctx *ctx) {
  built b = build(ctx, "t052_bar_dt.yaml", NULL, 0);
  T_ASSERT(pdk_sim_num_steps(b.sim) == 47, "precondition: 47 steps planned");
  recorder r;
  pdk_run_opts o = opts_for("dtu", &r);
  pdk_run_report rep;
  T_OK(ctx, pdk_sim_run(b.sim, b.scene, &o, &rep));
  long s0;
  pdk_explicit_dt_start(pdk_sim_explicit(b.sim), &s0, NULL);
  T_ASSERT(r.count[PDK_RUN_EVENT_DT_LOWERED] == 1 && s0 == 10 && r.lowered_total > 47 &&
               rep.total == r.lowered_total && rep.step == rep.total,
           "%d DT_LOWERED events (dt from step %ld), total %ld, the run ended at %ld of %ld",
           r.count[PDK_RUN_EVENT_DT_LOWERED], s0, r.lowered_total, rep.step, rep.total);
  T_ASSERT(r.stepped_total[r.num_stepped - 1] == rep.total, "the last STEPPED event's total");
  size_t len;
  char *csv = slurp("dtu/bar_dt_history.csv", &len);
  T_ASSERT(csv && len > 1, "no history");
  const char *row = csv + len - 1;
  while (row > csv && row[-1] != '\n')
    --row;
  T_ASSERT(atol(row) == rep.total, "the last history row is step %ld, the run's end %ld", atol(row),
           rep.total);
  free(csv);
  unbuild(&b);
}

static void static_scene(pdk_ctx *ctx) {
  block_by_hand(ctx, "static_ref");
  built b = build(ctx, "t094_static.yaml", NULL, 0);
  recorder r;
  pdk_run_opts o = opts_for("static_lib", &r);
  pdk_run_report rep;
  T_OK(ctx, pdk_sim_run(b.sim, b.scene, &o, &rep));
  T_ASSERT(rep.status == PDK_RUN_DONE && rep.step == 4 && rep.total == 4 && rep.first.step == 0 &&
               rep.last.step == 4,
           "static: status %d, load step %ld of %ld", (int)rep.status, rep.step, rep.total);
  T_ASSERT(r.num_stepped == 4, "%d STEPPED events for 4 load steps", r.num_stepped);
  for (int k = 0; k < 4; ++k)
    T_ASSERT(r.stepped[k] == k + 1 && r.stepped_total[k] == 4, "event %d: load step %ld", k,
             r.stepped[k]);
  assert_same_output("static_ref", "static_lib", "block", 0, "static run");
  T_ASSERT(!exists("static_lib/block_checkpoint.h5"), "a static run wrote a checkpoint");
  unbuild(&b);

  volatile sig_atomic_t stop = 0;
  b = build(ctx, "t094_static.yaml", NULL, 0);
  o = opts_for("static_stop", &r);
  o.stop = &stop;
  r.stop = &stop;
  r.stop_at = 1;
  T_OK(ctx, pdk_sim_run(b.sim, b.scene, &o, &rep));
  T_ASSERT(rep.status == PDK_RUN_STOPPED && rep.step == 1 && r.num_stepped == 1,
           "static stop: status %d at load step %ld", (int)rep.status, rep.step);
  T_ASSERT(count_lines("static_stop/block_history.csv") == 3 && exists("static_stop/block.xmf"),
           "static stop: %d CSV lines", count_lines("static_stop/block_history.csv"));
  unbuild(&b);
}

static void failures(pdk_ctx *ctx) {
  pdk_run_report rep;
  recorder r;
  built b = build(ctx, "t094_static.yaml", NULL, 0);
  pdk_run_opts o = opts_for("fail", &r);
  o.restart = "lib/bar_checkpoint.h5";
  T_FAILS(ctx, pdk_sim_run(b.sim, b.scene, &o, &rep), PDK_ERR_ARG, "explicit runs only");
  T_ASSERT(rep.status == PDK_RUN_FAILED && rep.stage == PDK_RUN_STAGE_RESTART, "stage %d",
           (int)rep.stage);
  unbuild(&b);

  b = build(ctx, "t092_bar.yaml", bar_ov, 3);
  o = opts_for("fail", &r);
  o.restart = "nonesuch_checkpoint.h5";
  T_FAILS(ctx, pdk_sim_run(b.sim, b.scene, &o, &rep), PDK_ERR_IO, "does not exist");
  T_ASSERT(rep.status == PDK_RUN_FAILED && rep.stage == PDK_RUN_STAGE_RESTART && !exists("fail"),
           "stage %d", (int)rep.stage);
  unbuild(&b);

  FILE *f = fopen("afile", "w");
  T_ASSERT(f && fclose(f) == 0, "cannot create afile");
  b = build(ctx, "t092_bar.yaml", bar_ov, 3);
  o = opts_for("afile/out", &r);
  T_FAILS(ctx, pdk_sim_run(b.sim, b.scene, &o, &rep), PDK_ERR_IO, "afile/out");
  T_ASSERT(rep.status == PDK_RUN_FAILED && rep.stage == PDK_RUN_STAGE_FOLDER &&
               rep.os_error == ENOTDIR && r.num_first == 0,
           "stage %d, errno %d", (int)rep.stage, rep.os_error);
  unbuild(&b);
}

int main(void) {
  const char *build_dir = getenv("PDK_BUILD_DIR");
  T_ASSERT(build_dir && getenv("PDK_SOURCE_DIR"), "PDK_BUILD_DIR and PDK_SOURCE_DIR are not set "
                                                  "(run through ctest)");
  char work[4096], cmd[2 * 4096 + 64];
  snprintf(work, sizeof work, "%s/tests/t210_run_library.work", build_dir);
  snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", work, work);
  T_ASSERT(system(cmd) == 0, "%s", cmd);
  T_ASSERT(chdir(work) == 0, "cd %s", work);
  pdk_ctx *ctx = t_ctx(2);
  whole_run(ctx);
  stop_and_restart(ctx);
  dt_update(ctx);
  static_scene(ctx);
  failures(ctx);
  pdk_ctx_destroy(&ctx);
  return 0;
}
