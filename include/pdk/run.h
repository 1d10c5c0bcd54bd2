/* Running a scene: the run loop of `pdk run` as one library call.
 *
 * pdk_sim_run takes a simulation built from a scene (pdk_sim_create) to the scene's end and writes
 * the output the scene asks for, exactly as `pdk run` does: the command is this call with argument
 * parsing, signal handling and printing around it, so a program that calls it gets the same
 * files, bit for bit, and can restart and stop runs the same way.
 *
 *   pdk_run_opts ro = pdk_run_opts_default();
 *   ro.dir = "out/plate";                       (NULL: out/<scene name>, as pdk run)
 *   pdk_run_report rep;
 *   if (pdk_sim_run(sim, scene, &ro, &rep))
 *     fprintf(stderr, "%s\n", pdk_ctx_error_message(ctx));
 *
 * The files, in dir (pdk/output.h; <name> is the scene's name): <name>.h5 and <name>.xmf (fields),
 * <name>_history.csv (and its plot when gnuplot is there), and for explicit runs
 * <name>_checkpoint.h5. They are written under temporary names and renamed when the run closes
 * its output, so a folder never holds a mix of two runs' files.
 *
 * Explicit scenes (solver.type explicit):
 *   - a history record at the start and every output.history_interval steps, the fields
 *     output.fields (refreshed by pdk_sim_update_output_fields) at the start and every
 *     output.field_interval steps (0: none in between), and both at the last step;
 *   - a checkpoint every output.checkpoint_interval steps before the last (0: none), renamed to
 *     <name>_checkpoint.h5 at once, so a killed run leaves one; and one at the end, or at a stop,
 *     that is handed to the output (pdk_output_adopt) and renamed with its files;
 *   - the solver advances (pdk_explicit_run) in chunks of at most 100 steps, each ending at the
 *     next record at the latest, so a stop request is seen and PDK_RUN_EVENT_STEPPED comes at
 *     least every 100 steps (the chunks do not change the results);
 *   - the run ends at pdk_sim_num_steps, read again after every chunk: a solver.dt_update that
 *     lowers dt makes the run longer (PDK_RUN_EVENT_DT_LOWERED).
 * Static scenes (solver.type adr or newton): one load step at a time (pdk_sim_static_step); a
 * history record for the unloaded state and every output.history_interval load steps, fields at
 * the start and every output.field_interval load steps, both at the last; no checkpoint. When a
 * load step fails, the load steps solved before it are kept: the output is closed with them
 * (report.kept_steps) and the error returned.
 *
 * Restart (opts.restart, explicit scenes): the simulation, freshly built from the scene, is
 * restored from the checkpoint as by pdk_sim_restart (its time, step and dt; the end from the
 * scene). When dir holds the output of the run that wrote the checkpoint, that output is
 * continued (pdk_output_opts.append): its records up to the checkpoint are kept and later ones
 * dropped, so the files end up those of a run that never stopped; an output there that ends
 * before the checkpoint is refused (PDK_RUN_STAGE_CONTINUE) and left as it is. Without such an
 * output the files start afresh at the checkpoint. A checkpoint at the scene's end gives
 * PDK_RUN_NOTHING_TO_DO and touches nothing.
 *
 * Stop (opts.stop): a flag the caller owns, for example set by a SIGINT handler (storing to a
 * volatile sig_atomic_t is async-signal-safe). It is read before every chunk and load step; once
 * it is non-zero the run stops there, explicit runs write their checkpoint, and the output is
 * closed with what was written: PDK_RUN_STOPPED. Another pdk_sim_run of a simulation built anew,
 * with opts.restart = that checkpoint and the same dir, finishes the run with the files of one
 * that never stopped. pdk_sim_run never resets the flag.
 *
 * The run goes from the simulation's current step (0 when freshly built). The return value is 0
 * or the error, whose message is in the context; report.stage says where it arose. After an
 * error the run's temporary files are removed (except the load steps kept above) and an earlier
 * run's files in dir are left as they were; periodic checkpoints written before it stay.
 */
#ifndef PDK_RUN_H
#define PDK_RUN_H

#include <signal.h>

#include "pdk/export.h"
#include "pdk/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pdk_run_status {
  PDK_RUN_DONE = 0,          /* the scene's end reached, output closed (and final checkpoint) */
  PDK_RUN_STOPPED = 1,       /* opts.stop was set when the stepping ended (usually before the
                                end): output closed (and checkpoint) at report.step */
  PDK_RUN_NOTHING_TO_DO = 2, /* opts.restart's checkpoint is at the scene's end: nothing written */
  PDK_RUN_FAILED = 3         /* pdk_sim_run returned an error */
} pdk_run_status;

/* Where a run failed. */
typedef enum pdk_run_stage {
  PDK_RUN_STAGE_NONE = 0,   /* it did not fail */
  PDK_RUN_STAGE_SETUP,      /* the arguments */
  PDK_RUN_STAGE_RESTART,    /* opts.restart: not a checkpoint, or one that does not fit the scene */
  PDK_RUN_STAGE_FOLDER,     /* creating dir (report.os_error) */
  PDK_RUN_STAGE_OPEN,       /* opening the output (with opts.restart: the earlier output in dir
                               does not fit; pdk_output_opts.append) */
  PDK_RUN_STAGE_CONTINUE,   /* opts.restart: the output in dir ends before the checkpoint */
  PDK_RUN_STAGE_STEP,       /* a step or load step, or writing its records or a periodic
                               checkpoint */
  PDK_RUN_STAGE_CHECKPOINT, /* the checkpoint at the end or at the stop */
  PDK_RUN_STAGE_CLOSE       /* completing and renaming the output files */
} pdk_run_stage;

/* What pdk_sim_run did, filled as it goes (events see it too). */
typedef struct pdk_run_report {
  pdk_run_status status;
  pdk_run_stage stage;   /* PDK_RUN_FAILED: where */
  int os_error;          /* stage FOLDER: the errno of the directory that could not be made */
  int stopped;           /* 1: opts.stop was set when the stepping ended (also when what
                            followed failed) */
  long start_step;       /* where the run began: 0, or the step it restarted from */
  long step;             /* steps (static: load steps) done when it ended */
  long total;            /* the run's last step (pdk_sim_num_steps, grown by a dt_update) */
  pdk_history first;     /* the record at start_step (static: the unloaded state, or the restart
                            point), whether or not the output already held it */
  pdk_history last;      /* the record at step */
  double wtime_stepping; /* pdk_wtime() when stepping began (after the first records) */
  pdk_sim_restart_info restart; /* opts.restart: the checkpoint it went on from */
  long kept_rows;  /* opts.restart into the output of the checkpoint's run: the history rows */
  int kept_fields; /* and field outputs kept from it (PDK_RUN_EVENT_CONTINUING) */
  int kept_steps;  /* a static run that failed: the load steps solved and kept in the output */
  /* A static run that failed, when keeping its load steps failed too: that error's message (the
   * first error, the load step's, is the context's); empty otherwise. */
  char keep_error[1024];
} pdk_run_report;

typedef enum pdk_run_event_kind {
  /* opts.restart: the checkpoint is restored and the run goes on (report->restart). */
  PDK_RUN_EVENT_RESTARTED = 0,
  /* dir exists; the output files are about to be created (pdk run describes the run here). */
  PDK_RUN_EVENT_BEGIN = 1,
  /* opts.restart: dir held the output of the checkpoint's run, and it is continued
   * (report->kept_rows, report->kept_fields). */
  PDK_RUN_EVENT_CONTINUING = 2,
  /* After each chunk of steps (explicit) or load step (static), its records written. */
  PDK_RUN_EVENT_STEPPED = 3,
  /* A dt_update lowered dt during the last chunk (before its records are written): total is the
   * new end (pdk_explicit_dt, pdk_explicit_dt_start tell the new step and where it began). */
  PDK_RUN_EVENT_DT_LOWERED = 4
} pdk_run_event_kind;

typedef struct pdk_run_event {
  pdk_run_event_kind kind;
  long step;                    /* steps (static: load steps) done */
  long total;                   /* the run's last step as now known */
  const pdk_history *history;   /* STEPPED, DT_LOWERED: the record at step; else NULL */
  const pdk_run_report *report; /* the report so far */
} pdk_run_event;

typedef struct pdk_run_opts {
  const char *dir;     /* output folder, made with its parents when missing; NULL: out/<name> */
  const char *restart; /* NULL, or the checkpoint an explicit run continues from */
  int plot;            /* 1: the history plot (and the fields plot) when gnuplot is on the PATH */
  volatile sig_atomic_t *stop; /* NULL, or the stop request (above) */
  /* NULL, or called with every event, on the calling thread; it must not call pdk_sim_run. */
  void (*on_event)(void *arg, const pdk_run_event *ev);
  void *arg;
} pdk_run_opts;

/* dir NULL, restart NULL, plot 1, stop NULL, on_event NULL. */
PDK_EXPORT pdk_run_opts pdk_run_opts_default(void);

/* Runs sim (built from scene by pdk_sim_create) to the scene's end as described above. opts NULL:
 * the defaults; report may be NULL. */
PDK_EXPORT int pdk_sim_run(pdk_sim *sim, const pdk_scene *scene, const pdk_run_opts *opts,
                           pdk_run_report *report);

#ifdef __cplusplus
}
#endif
#endif
