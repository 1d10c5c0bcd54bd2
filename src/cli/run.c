/* `pdk run` and `pdk check`: load a scene, build the simulation, run it with progress, write the
 * output files, checkpoint on request and on Ctrl-C. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "pdk/output.h"
#include "pdk/scene.h"

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif
/* The longest file name pdk puts into the output folder, after "<dir>/<name>". */
#define LONGEST_SUFFIX "_checkpoint.h5.part.part"

static volatile sig_atomic_t interrupted = 0;
static void on_sigint(int sig) {
  (void)sig;
  interrupted = 1;
}

const char *pdk_cli_usage_run =
    "usage: pdk run SCENE [options]\n"
    "\n"
    "Runs the scene: builds the particles, families, model and solver it describes, advances the\n"
    "solver, and writes the results to DIR (default out/<scene name>):\n"
    "  <name>.h5 + <name>.xmf   fields for ParaView (open the .xmf)\n"
    "  <name>_history.csv       energies, reactions, broken bonds per history step\n"
    "  <name>_history.png       plot of the histories (when gnuplot is installed)\n"
    "  <name>_checkpoint.h5     state for --restart (at checkpoint_interval, the end, and Ctrl-C)\n"
    "Files are written under temporary names and renamed when complete.\n"
    "Static scenes (solver.type adr or newton) write one history row per load step (reaction vs\n"
    "displacement, energies) and the fields of the load steps, and no checkpoint.\n"
    "\n"
    "options:\n"
    "  -o, --output DIR     output folder (created if missing)\n"
    "  --threads N          threads (default: solver.threads, PDK_NUM_THREADS, one per core)\n"
    "  --set KEY=VALUE      override a scene key, e.g. --set geometry.spacing=1e-3 (repeatable);\n"
    "                       overrides are validated like the file\n"
    "  --restart FILE       continue from a checkpoint of the same scene: from its time, step\n"
    "                       and dt to the scene's end (solver.end_time or solver.steps); into\n"
    "                       the same folder, the output written up to the checkpoint is kept\n"
    "                       and continued\n"
    "  -q, --quiet          no progress line, only errors and the summary\n"
    "  -h, --help           show this help\n"
    "\n"
    "progress: on a terminal one line updated in place; otherwise (a log) a line every 10% of the\n"
    "steps, at most one per PDK_PROGRESS_SECONDS (default 10) seconds.\n"
    "\n"
    "exit status: 0 done, 1 the run failed, 2 bad command line or scene, 130 interrupted (a\n"
    "checkpoint was written).\n";

const char *pdk_cli_usage_check =
    "usage: pdk check SCENE [--set KEY=VALUE ...]\n"
    "\n"
    "Validates the scene and builds the simulation (particles, sets, families, model, solver and\n"
    "its time step) without running it or writing anything. Prints what the run would be.\n"
    "exit status: 0 valid, 2 invalid (the message names file, line and key).\n";

typedef struct run_args {
  const char *prog; /* how pdk was invoked (argv[0]), for the "continue with" command */
  const char *scene;
  const char *outdir;
  const char *restart;
  const char *overrides[65];
  int num_overrides;
  int num_user_overrides; /* the --set options; --threads adds one more after them */
  char threads_override[64];
  int threads;
  int quiet;
} run_args;

/* A path with "..." in the middle when it is long, for messages. */
static const char *shorten(const char *path, char *buf, size_t len) {
  const size_t n = strlen(path);
  if (n < len) return path;
  const size_t half = (len - 4) / 2;
  snprintf(buf, len, "%.*s...%s", (int)half, path, path + n - half);
  return buf;
}

static int parse_args(const char *prog, int argc, char **argv, run_args *a, const char *usage,
                      int allow_run_opts) {
  memset(a, 0, sizeof *a);
  a->prog = prog;
  for (int k = 0; k < argc; ++k) {
    const char *s = argv[k];
    int has_next = k + 1 < argc;
    if (!strcmp(s, "-h") || !strcmp(s, "--help")) {
      fputs(usage, stdout);
      return -1;
    } else if (!strcmp(s, "--set") && has_next) {
      if (a->num_overrides == 64) {
        fprintf(stderr, "pdk: at most 64 --set overrides\n");
        return 2;
      }
      a->overrides[a->num_overrides++] = argv[++k];
    } else if (allow_run_opts && (!strcmp(s, "-o") || !strcmp(s, "--output")) && has_next) {
      a->outdir = argv[++k];
    } else if (allow_run_opts && !strcmp(s, "--restart") && has_next) {
      a->restart = argv[++k];
    } else if (allow_run_opts && !strcmp(s, "--threads") && has_next) {
      char *end = NULL;
      long v = strtol(argv[++k], &end, 10);
      if (!argv[k][0] || *end || v < 1 || v > 4096) {
        fprintf(stderr,
                "pdk: --threads '%s' is not a thread count; use an integer from 1 to 4096\n",
                argv[k]);
        return 2;
      }
      a->threads = (int)v;
    } else if (allow_run_opts && (!strcmp(s, "-q") || !strcmp(s, "--quiet"))) {
      a->quiet = 1;
    } else if (s[0] == '-') {
      fprintf(stderr, "pdk: unknown or incomplete option '%s'\n\n%s", s, usage);
      return 2;
    } else if (!a->scene) {
      a->scene = s;
    } else {
      fprintf(stderr, "pdk: more than one scene given ('%s' and '%s')\n", a->scene, s);
      return 2;
    }
  }
  if (!a->scene) {
    fprintf(stderr, "pdk: no scene file given\n\n%s", usage);
    return 2;
  }
  if (a->outdir && !a->outdir[0]) {
    fprintf(stderr, "pdk: -o: the output folder is empty (''); give a folder, e.g. -o out/run1, "
                    "or leave -o out for out/<scene name>\n");
    return 2;
  }
  if (a->outdir && strlen(a->outdir) + 1 + sizeof LONGEST_SUFFIX >= PATH_MAX) {
    char buf[80];
    fprintf(stderr,
            "pdk: -o: the output folder '%s' is %zu bytes long; with the file names in it that "
            "passes this system's limit of %d bytes for a path (PATH_MAX): give a shorter "
            "folder\n",
            shorten(a->outdir, buf, sizeof buf), strlen(a->outdir), PATH_MAX - 1);
    return 2;
  }
  if (a->restart && !a->restart[0]) {
    fprintf(stderr, "pdk: --restart: the checkpoint file name is empty ('')\n");
    return 2;
  }
  a->num_user_overrides = a->num_overrides;
  if (a->threads) { /* --threads wins over the scene: pass it as the override solver.threads */
    snprintf(a->threads_override, sizeof a->threads_override, "solver.threads=%d", a->threads);
    a->overrides[a->num_overrides++] = a->threads_override;
  }
  return 0;
}

static int mkdir_p(const char *path) {
  char buf[PATH_MAX];
  size_t len = strlen(path);
  if (len == 0 || len >= sizeof buf) {
    errno = len ? ENAMETOOLONG : ENOENT;
    return -1;
  }
  memcpy(buf, path, len + 1);
  for (char *q = buf + 1; *q; ++q) {
    if (*q != '/') continue;
    *q = '\0';
    if (mkdir(buf, 0777) && errno != EEXIST) return -1;
    *q = '/';
  }
  if (mkdir(buf, 0777) && errno != EEXIST) return -1;
  return 0;
}

static void fmt_duration(char *buf, size_t len, double s) {
  if (!isfinite(s) || s < 0)
    snprintf(buf, len, "--");
  else if (s < 60)
    snprintf(buf, len, "%.1fs", s);
  else if (s < 3600)
    snprintf(buf, len, "%dm%02ds", (int)(s / 60), (int)fmod(s, 60));
  else
    snprintf(buf, len, "%dh%02dm", (int)(s / 3600), (int)fmod(s / 60, 60));
}

/* Loads the scene and builds the simulation; prints the error and returns the exit status. */
static int load_and_build(pdk_ctx *ctx, const run_args *a, pdk_scene **scene, pdk_sim **sim) {
  if (pdk_scene_load(ctx, a->scene, a->overrides, a->num_overrides, scene)) {
    fprintf(stderr, "pdk: %s\n", pdk_ctx_error_message(ctx));
    return 2;
  }
  if (pdk_sim_create(ctx, *scene, sim)) {
    fprintf(stderr, "pdk: %s\n", pdk_ctx_error_message(ctx));
    return 2;
  }
  return 0;
}

static int make_ctx(int threads, pdk_ctx **ctx) {
  pdk_ctx_opts o = pdk_ctx_opts_default();
  o.num_threads = threads;
  char why[512];
  if (pdk_ctx_create(&o, ctx, why, sizeof why)) {
    fprintf(stderr, "pdk: %s\n", why);
    return 2;
  }
  return 0;
}

/* The "output:" line after a run: the ParaView index and the CSV and PNG files the run left. */
static void print_outputs(const char *dir, const char *name) {
  static const char *const extra[] = {"_history.csv", "_history.png", "_fields.csv", "_fields.png"};
  fprintf(stderr, "output: %s/%s.xmf (ParaView)", dir, name);
  for (size_t k = 0; k < sizeof extra / sizeof extra[0]; ++k) {
    char path[PATH_MAX];
    const int w = snprintf(path, sizeof path, "%s/%s%s", dir, name, extra[k]);
    if (w > 0 && (size_t)w < sizeof path && access(path, F_OK) == 0)
      fprintf(stderr, ", %s%s", name, extra[k]);
  }
  fputc('\n', stderr);
}

static void describe(FILE *out, pdk_ctx *ctx, pdk_scene *scene, pdk_sim *sim) {
  pdk_particles *p = pdk_sim_particles(sim);
  pdk_families *f = pdk_sim_families(sim);
  pdk_explicit *e = pdk_sim_explicit(sim);
  pdk_static *st = pdk_sim_static(sim);
  const pdk_model_opts *mo = pdk_model_opts_get(pdk_sim_model(sim));
  fprintf(out, "scene %s (%s): %d-D, %d particles, %lld bonds (%.1f per particle), model %s\n",
          pdk_scene_name(scene), pdk_scene_path(scene), pdk_particles_dim(p),
          (int)pdk_particles_count(p), (long long)pdk_families_num_bonds(f),
          (double)pdk_families_num_bonds(f) / pdk_particles_count(p),
          pdk_model_kind_name(mo->kind));
  if (mo->stencil != PDK_STENCIL_OFF) {
    pdk_model *m = pdk_sim_model(sim);
    if (pdk_model_stencil_active(m))
      fprintf(out, "stencil: force passes on the lattice stencil\n");
    else
      fprintf(out, "stencil: auto took the general path: %s\n", pdk_model_stencil_reason(m));
  }
  if (e) {
    fprintf(out, "explicit: dt %.4g (stable estimate %.4g), %ld steps to t = %.4g, %d thread(s)\n",
            pdk_explicit_dt(e), pdk_explicit_stable_dt(e), pdk_sim_num_steps(sim),
            pdk_sim_num_steps(sim) * pdk_explicit_dt(e), pdk_ctx_num_threads(ctx));
    const pdk_explicit_opts *eo = pdk_explicit_opts_get(e);
    if (eo->dt_update != PDK_DT_UPDATE_NONE)
      fprintf(out,
              "dt_update %s: the stable step is re-estimated %s %ld steps (about 42 force "
              "passes each), dt lowered to %.3g x each estimate below it\n",
              eo->dt_update == PDK_DT_UPDATE_BREAKS ? "breaks" : "periodic",
              eo->dt_update == PDK_DT_UPDATE_BREAKS ? "after bonds broke, at most once per"
                                                    : "every",
              eo->dt_update_interval, eo->safety);
  } else {
    const int nl = pdk_static_num_levels(st);
    const double last = pdk_static_level_time(st, nl - 1);
    const pdk_static_stats *ss = pdk_static_stats_get(st);
    fprintf(out, "%s: %d load step(s) to %s %.4g, %d thread(s)",
            pdk_solver_type_name(pdk_sim_solver_type(sim)), nl,
            pdk_static_total_time(st) > 0 ? "pseudo-time t =" : "load factor", last,
            pdk_ctx_num_threads(ctx));
    if (ss->num_colors)
      fprintf(out, "; coloring %d colors (%ld passes per difference tangent)", ss->num_colors,
              ss->passes_per_tangent);
    if (ss->analytic_tangent) fprintf(out, "; analytic tangent");
    fputc('\n', out);
  }
}

int pdk_cli_check(const char *prog, int argc, char **argv) {
  run_args a;
  int rc = parse_args(prog, argc, argv, &a, pdk_cli_usage_check, 0);
  if (rc) return rc < 0 ? 0 : rc;
  pdk_ctx *ctx = NULL;
  pdk_scene *scene = NULL;
  pdk_sim *sim = NULL;
  if ((rc = make_ctx(0, &ctx))) return rc;
  rc = load_and_build(ctx, &a, &scene, &sim);
  if (!rc) {
    describe(stdout, ctx, scene, sim);
    printf("ok: %s is valid\n", a.scene);
  }
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
  pdk_ctx_destroy(&ctx);
  return rc;
}

/* A static run: one history record per load step (history_interval and field_interval count load
 * steps), a progress line per load step, the solver's statistics at the end. No checkpoints: on
 * Ctrl-C the load steps solved so far are kept (complete files) and the run stops with 130. */
/* Float storage of bond lengths sets a stretch resolution of 2^-24 (pdk_model.h): when the largest
 * stretch of the finished run is within PDK_FLOAT_STRETCH_WARN of it, round-off rather than
 * discretization sets the forces' error, and the user is told (the run itself succeeded). */
static void warn_float_roundoff(pdk_sim *sim) {
  const double ratio = pdk_model_float_stretch_ratio(pdk_sim_model(sim));
  if (ratio < 0.0 || ratio >= PDK_FLOAT_STRETCH_WARN) return;
  fprintf(stderr,
          "pdk: warning: model.precision float: the largest bond stretch at the end (%.2e) is "
          "only %.3g times the float resolution of the stored bond lengths (2^-24 = 6.0e-8), so "
          "float round-off alone perturbs the bond forces by up to %.2g of the largest; use "
          "model.precision: double for strains this small\n",
          ratio * 0x1p-24, ratio, ratio > 0.0 ? 1.0 / ratio : 1.0);
}

/* The energy account of an explicit run (pdk_history): what this invocation added to the
 * external work against the change of kinetic + strain energy + dissipation (plastic, damage,
 * breaking) since its first record h0 (step 0, or the restart point; so an initial velocity or a
 * grip moving from t = 0 is part of the start, not an imbalance). Printed after the run; above
 * PDK_ENERGY_WARN of the energy put in (the external work plus the energy at h0) a warning says
 * the time integration does not resolve the run (failures and breaks add errors of order dt). */
/* 3%: the shipped two-hole plate ends 1.9% off (its failures are first-order events), the same
 * plate with softened stabilization 5-13% (tests/t095) */
#define PDK_ENERGY_WARN 0.03
static void report_energy(pdk_sim *sim, const pdk_history *h0, const pdk_history *h) {
  /* PMB and LPS do not book what a broken bond held ("w_broken" is the correspondence model's) */
  const int unbooked = h->broken > h0->broken &&
                       !pdk_particles_field_exists(pdk_sim_particles(sim), "w_broken");
  const double e0 = h0->kinetic + h0->strain + h0->plastic_work + h0->damage_work +
                    h0->breaking_work;
  const double e1 = h->kinetic + h->strain + h->plastic_work + h->damage_work + h->breaking_work;
  const double ext = h->external_work - h0->external_work, imb = ext - (e1 - e0);
  fprintf(stderr,
          "energy: external work %.6g = change of kinetic %.4g + strain %.4g + plastic %.4g + "
          "damage %.4g + breaking %.4g, off by %.3g",
          ext, h->kinetic - h0->kinetic, h->strain - h0->strain,
          h->plastic_work - h0->plastic_work, h->damage_work - h0->damage_work,
          h->breaking_work - h0->breaking_work, imb);
  const double in = ext + fabs(e0); /* the energy put in: work done, and any initial energy */
  if (in > 0.0) fprintf(stderr, " (%.2g%% of the energy put in)", 100.0 * fabs(imb) / in);
  if (unbooked)
    fprintf(stderr, "; bonds broke and this model does not book the energy they held, so the "
                    "account does not close");
  fputc('\n', stderr);
  if (!unbooked && in > 0.0 && fabs(imb) > PDK_ENERGY_WARN * in) {
    /* Johnson-Cook correspondence runs that broke bonds: what fixed their account on the
     * two-hole plate (docs/validation/plate_two_holes.md, items 9 and 10) */
    const pdk_model_opts *mo = pdk_model_opts_get(pdk_sim_model(sim));
    const pdk_explicit *e = pdk_sim_explicit(sim);
    const int jc_broke = e && h->broken > h0->broken && mo->kind == PDK_MODEL_CORRESPONDENCE &&
                         mo->law == PDK_LAW_JC && mo->connectivity != PDK_CONNECTIVITY_UL;
    const char *hint = "";
    if (jc_broke && mo->break_stress == PDK_BREAK_STRESS_REFIT)
      hint = "; bonds broke, and with model.break_stress refit a particle's stress jumps when its "
             "family loses bonds: model.break_stress: continuous with solver.dt_update: breaks "
             "keeps the account through the tearing";
    else if (jc_broke && pdk_explicit_opts_get(e)->dt_update == PDK_DT_UPDATE_NONE)
      hint = "; bonds broke, and the stable step can fall as families lose bonds: "
             "solver.dt_update: breaks follows it";
    fprintf(stderr,
            "pdk: warning: the energy balance is off by %.2g%% of the energy put in (more than "
            "%.0f%%): the time step does not resolve this run; rerun with a smaller solver.dt "
            "(or solver.safety) and compare%s\n",
            100.0 * fabs(imb) / in, 100.0 * PDK_ENERGY_WARN, hint);
  }
}

static int run_static(pdk_ctx *ctx, const run_args *a, pdk_scene *scene, pdk_sim *sim,
                      pdk_output **out, const char *dir, double wall0) {
  pdk_static *st = pdk_sim_static(sim);
  pdk_particles *p = pdk_sim_particles(sim);
  const pdk_scene_output *so = pdk_scene_output_get(scene);
  const long total = pdk_sim_num_steps(sim);
  const long hist_every = so->history_interval > 0 ? so->history_interval : 1;
  const long field_every = so->field_interval;
  const char *method = pdk_solver_type_name(pdk_sim_solver_type(sim));
  pdk_history h;
  int err = pdk_sim_static_history(sim, &h);
  if (!err) err = pdk_output_write_history(*out, &h);
  if (!err) err = pdk_sim_update_output_fields(sim);
  if (!err) err = pdk_output_write_fields(*out, p, h.step, h.time, so->fields, so->num_fields);
  const double run0 = pdk_wtime();
  long iterations_before = 0;
  while (!err && h.step < total && !interrupted) {
    if ((err = pdk_sim_static_step(sim, &h))) break;
    const long s = h.step;
    if (s % hist_every == 0 || s == total) err = pdk_output_write_history(*out, &h);
    if (!err && ((field_every > 0 && s % field_every == 0) || s == total)) {
      err = pdk_sim_update_output_fields(sim);
      if (!err) err = pdk_output_write_fields(*out, p, s, h.time, so->fields, so->num_fields);
    }
    if (!a->quiet) {
      const pdk_static_stats *ss = pdk_static_stats_get(st);
      const pdk_static_event *ev = pdk_static_last_event(st);
      char w[32];
      fmt_duration(w, sizeof w, pdk_wtime() - wall0);
      fprintf(stderr,
              "%s load step %ld/%ld  %s %.4g  iterations %ld  re-solves %d  residual %.2e  "
              "broken %lld  wall %s\n",
              method, s, total, pdk_static_total_time(st) > 0 ? "t" : "load", h.time,
              ss->iterations - iterations_before, ev->round, ev->residual, (long long)h.broken, w);
      iterations_before = ss->iterations;
    }
  }
  if (err) {
    fprintf(stderr, "pdk: %s\n", pdk_ctx_error_message(ctx));
    if (pdk_static_levels_solved(st) > 0) {
      /* keep the load steps that did converge: their records are complete */
      if (pdk_output_close(out, 1))
        fprintf(stderr, "pdk: %s\n", pdk_ctx_error_message(ctx));
      else
        fprintf(stderr, "pdk: the %d load step(s) solved are in %s/%s_history.csv\n",
                pdk_static_levels_solved(st), dir, pdk_scene_name(scene));
    }
    return 1;
  }
  if (pdk_output_close(out, 1)) {
    fprintf(stderr, "pdk: %s\n", pdk_ctx_error_message(ctx));
    return 1;
  }
  if (interrupted) {
    fprintf(stderr,
            "pdk: interrupted after load step %ld of %ld (static runs have no checkpoints; the "
            "output holds the steps solved)\n",
            h.step, total);
    return 130;
  }
  if (!a->quiet) pdk_static_stats_print(pdk_static_stats_get(st), stderr);
  warn_float_roundoff(sim);
  fprintf(stderr,
          "done: %ld load steps in %.2f s (%.2f s solving), peak memory %.1f MiB, %lld bonds "
          "broken\n",
          h.step, pdk_wtime() - wall0, pdk_wtime() - run0, pdk_peak_memory_bytes() / 1048576.0,
          (long long)h.broken);
  print_outputs(dir, pdk_scene_name(scene));
  return 0;
}

/* Writes s to f quoted for a POSIX shell: as it is when it holds only characters no shell
 * treats specially, else in single quotes (a ' inside as '\''). */
static void shell_quote(FILE *f, const char *s) {
  static const char safe[] =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./:=,+@%";
  int plain = s[0] != '\0';
  for (const char *q = s; *q && plain; ++q)
    plain = strchr(safe, *q) != NULL;
  if (plain) {
    fputs(s, f);
    return;
  }
  fputc('\'', f);
  for (const char *q = s; *q; ++q)
    if (*q == '\'')
      fputs("'\\''", f);
    else
      fputc(*q, f);
  fputc('\'', f);
}

/* The checkpoint at the end of a run or at Ctrl-C: written complete under a temporary name
 * (<ckpt>.part) and handed to the output, whose closing phase renames it with the run's other
 * files, so a kill in that phase never leaves this run's checkpoint beside an earlier run's
 * output (the periodic checkpoints of solver.checkpoint_interval are committed at once: a
 * killed run must leave one; a restart checks that the output it continues reaches it). */
static int final_checkpoint(pdk_ctx *ctx, pdk_output *out, const char *ckpt, pdk_explicit *e,
                            const pdk_scene *scene) {
  char part[PATH_MAX];
  int len = snprintf(part, sizeof part, "%s.part", ckpt); /* fits: checked with the names */
  if (len < 0 || (size_t)len >= sizeof part) {
    fprintf(stderr, "pdk: the checkpoint's temporary name '%s.part' is too long\n", ckpt);
    return PDK_ERR_ARG;
  }
  int err = pdk_checkpoint_write(ctx, part, e, pdk_scene_text(scene));
  if (!err) err = pdk_output_adopt(out, part, ckpt);
  if (err) remove(part);
  return err;
}

/* The command that continues this run from its checkpoint: the same program, scene, output
 * folder, overrides, threads and -q, then --restart, each argument shell-quoted, so it can be
 * pasted. */
static void print_continue(FILE *f, const run_args *a, const char *dir, const char *ckpt) {
  fputs("  ", f);
  shell_quote(f, a->prog && a->prog[0] ? a->prog : "pdk");
  fputs(" run ", f);
  shell_quote(f, a->scene);
  fputs(" -o ", f);
  shell_quote(f, dir);
  for (int k = 0; k < a->num_user_overrides; ++k) {
    fputs(" --set ", f);
    shell_quote(f, a->overrides[k]);
  }
  if (a->threads) fprintf(f, " --threads %d", a->threads);
  if (a->quiet) fputs(" -q", f);
  fputs(" --restart ", f);
  shell_quote(f, ckpt);
  fputc('\n', f);
}

int pdk_cli_run(const char *prog, int argc, char **argv) {
  run_args a;
  int rc = parse_args(prog, argc, argv, &a, pdk_cli_usage_run, 1);
  if (rc) return rc < 0 ? 0 : rc;
  pdk_ctx *ctx = NULL;
  pdk_scene *scene = NULL;
  pdk_sim *sim = NULL;
  pdk_output *out = NULL;
  char *ckpt_scene = NULL; /* the scene text stored in the --restart checkpoint */
  char dir[PATH_MAX], ckpt[PATH_MAX], sbuf[80];
  double wall0 = pdk_wtime();
  pdk_sim_restart_info ri;
  memset(&ri, 0, sizeof ri);
  if ((rc = make_ctx(a.threads, &ctx))) return rc;
  if (pdk_scene_load(ctx, a.scene, a.overrides, a.num_overrides, &scene)) {
    fprintf(stderr, "pdk: %s\n", pdk_ctx_error_message(ctx));
    rc = 2;
    goto done;
  }
  if (a.restart && pdk_scene_solver_type(scene) != PDK_SOLVER_EXPLICIT) {
    fprintf(stderr,
            "pdk: --restart continues explicit runs only; %s is a static run (solver.type %s), "
            "which writes no checkpoints: run it again\n",
            a.scene, pdk_solver_type_name(pdk_scene_solver_type(scene)));
    rc = 2;
    goto done;
  }
  /* the checkpoint before the build: a file that is not one is refused at once */
  if (a.restart && pdk_checkpoint_info(ctx, a.restart, NULL, NULL, &ckpt_scene)) {
    fprintf(stderr, "pdk: --restart: %s\n", pdk_ctx_error_message(ctx));
    rc = 2;
    goto done;
  }
  if (pdk_sim_create(ctx, scene, &sim)) {
    fprintf(stderr, "pdk: %s\n", pdk_ctx_error_message(ctx));
    rc = 2;
    goto done;
  }
  pdk_explicit *e = pdk_sim_explicit(sim);
  pdk_particles *p = pdk_sim_particles(sim);
  const pdk_scene_output *so = pdk_scene_output_get(scene);
  const char *name = pdk_scene_name(scene);
  int len = a.outdir ? snprintf(dir, sizeof dir, "%s", a.outdir)
                     : snprintf(dir, sizeof dir, "out/%s", name);
  if (len > 0 && (size_t)len < sizeof dir)
    len = snprintf(ckpt, sizeof ckpt, "%s/%s%s", dir, name, "_checkpoint.h5");
  if (len < 0 || (size_t)len + strlen(".part.part") >= sizeof ckpt) {
    fprintf(stderr,
            "pdk: the output files '%s' would pass this system's limit of %d bytes for a path "
            "(PATH_MAX): give a shorter folder with -o%s\n",
            shorten(len > 0 && (size_t)len < sizeof ckpt ? ckpt : dir, sbuf, sizeof sbuf),
            PATH_MAX - 1, a.outdir ? "" : " (or a shorter scene name)");
    rc = 2;
    goto done;
  }
  if (a.restart) {
    if (pdk_sim_restart(sim, scene, a.restart, &ri)) {
      fprintf(stderr, "pdk: --restart: %s\n", pdk_ctx_error_message(ctx));
      rc = 2;
      goto done;
    }
    if (ri.end_step == ri.step) {
      fprintf(stderr,
              "pdk: checkpoint '%s' is at the end of the run (step %ld, t = %.6g): nothing to do, "
              "the output is left as it is; to run on, give a later solver.end_time (or more "
              "solver.steps)\n",
              a.restart, ri.step, ri.time);
      rc = 0;
      goto done;
    }
    if (ri.dt_changed)
      fprintf(stderr,
              "pdk: solver.dt: the restart steps at %.6g from the checkpoint (step %ld, t = "
              "%.6g) on, where its run stepped at %.6g (created with %.6g): this scene asks for "
              "another step; %ld steps in all to its end\n",
              ri.dt, ri.step, ri.time, ri.dt_before, ri.dt_created_before, ri.end_step);
  }
  if (mkdir_p(dir)) {
    fprintf(stderr, "pdk: cannot create the output folder '%s': %s\n",
            shorten(dir, sbuf, sizeof sbuf), strerror(errno));
    rc = 1;
    goto done;
  }
  if (!a.quiet) describe(stderr, ctx, scene, sim);
  {
    pdk_output_opts oo;
    memset(&oo, 0, sizeof oo);
    oo.dir = dir;
    oo.name = pdk_scene_name(scene);
    oo.scene_text = pdk_scene_text(scene);
    oo.reaction_sets = so->reaction_sets;
    oo.num_reaction_sets = so->num_reaction_sets;
    oo.units = so->units;
    oo.plot = 1;
    oo.append = a.restart != NULL;
    oo.append_step = ri.step;
    oo.append_scene = ckpt_scene;
    if (pdk_output_open(ctx, &oo, p, &out)) {
      fprintf(stderr, "pdk: %s\n", pdk_ctx_error_message(ctx));
      rc = a.restart ? 2 : 1;
      goto done;
    }
  }
  /* a restart into the folder of its run continues that output: it must reach the checkpoint */
  const int appended = pdk_output_num_history_rows(out) > 0 || pdk_output_num_field_steps(out) > 0;
  if (appended) {
    const long hist_every = so->history_interval > 0 ? so->history_interval : 1;
    const long need_h = ri.step / hist_every * hist_every;
    const long need_f =
        so->field_interval > 0 ? ri.step / so->field_interval * so->field_interval : 0;
    const long last_h = pdk_output_last_history_step(out), last_f = pdk_output_last_field_step(out);
    if (last_h < need_h || last_f < need_f) {
      fprintf(stderr,
              "pdk: the output in '%s' ends at step %ld (history) and %ld (fields), before the "
              "checkpoint's step %ld (records due at %ld and %ld): it is not the output of the "
              "run that wrote the checkpoint (that run may have been killed before its output "
              "was complete); restart into another folder (-o), or move %s.h5, %s.xmf and "
              "%s_history.csv out of '%s'\n",
              dir, last_h, last_f, ri.step, need_h, need_f, name, name, name, dir);
      rc = 2;
      goto done;
    }
    if (!a.quiet)
      fprintf(stderr,
              "continuing the output in %s: %ld history rows and %d field outputs up to step %ld "
              "kept\n",
              dir, pdk_output_num_history_rows(out), pdk_output_num_field_steps(out), ri.step);
  }
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_sigint;
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);

  if (!e) {
    rc = run_static(ctx, &a, scene, sim, &out, dir, wall0);
    goto done;
  }
  long total = pdk_sim_num_steps(sim); /* grows when a solver.dt_update lowers dt */
  const long start = pdk_explicit_step(e);
  int dt_changes = pdk_explicit_num_dt_changes(e);
  const long hist_every = so->history_interval > 0 ? so->history_interval : 1;
  const long field_every = so->field_interval;
  const long ckpt_every = so->checkpoint_interval;
  const int tty = !a.quiet && isatty(STDERR_FILENO);
  /* not a terminal (a log file, a batch job): a whole line at least every 10% of the steps and
   * PDK_PROGRESS_SECONDS (default 10) of wall time, so a short run prints none and a long one
   * about ten */
  const int log_lines = !a.quiet && !tty;
  const char *env_every = getenv("PDK_PROGRESS_SECONDS");
  const double line_every = env_every && *env_every ? atof(env_every) : 10.0;
  double last_print = 0.0, last_line = pdk_wtime();
  long last_line_step = start;
  pdk_history h;
  int err = pdk_explicit_run(e, 0, &h);
  const pdk_history h0 = h;
  if (!appended) { /* a continued output has the records up to the checkpoint already */
    if (!err) err = pdk_output_write_history(out, &h);
    if (!err) err = pdk_sim_update_output_fields(sim);
    if (!err) err = pdk_output_write_fields(out, p, h.step, h.time, so->fields, so->num_fields);
  }
  double run0 = pdk_wtime();
  while (!err && pdk_explicit_step(e) < total && !interrupted) {
    long s = pdk_explicit_step(e);
    long next = total;
    long cand[3] = {(s / hist_every + 1) * hist_every,
                    field_every > 0 ? (s / field_every + 1) * field_every : total,
                    ckpt_every > 0 ? (s / ckpt_every + 1) * ckpt_every : total};
    for (int k = 0; k < 3; ++k)
      next = cand[k] < next ? cand[k] : next;
    /* advance in chunks of at most 100 steps so Ctrl-C and the progress line stay responsive */
    long chunk = next - s < 100 ? next - s : 100;
    if ((err = pdk_explicit_run(e, chunk, &h))) break;
    s = pdk_explicit_step(e);
    if (pdk_explicit_num_dt_changes(e) != dt_changes) {
      dt_changes = pdk_explicit_num_dt_changes(e);
      total = pdk_sim_num_steps(sim);
      long s0;
      double t0;
      pdk_explicit_dt_start(e, &s0, &t0);
      if (!a.quiet)
        fprintf(stderr,
                "%sdt lowered to %.4g at step %ld (t %.4g): stable estimate %.4g (%d estimates so "
                "far); %ld steps in all now\n",
                tty ? "\r" : "", pdk_explicit_dt(e), s0, t0, pdk_explicit_stable_dt(e),
                pdk_explicit_num_estimates(e), total);
    }
    if (s % hist_every == 0 || s == total) err = pdk_output_write_history(out, &h);
    if (!err && ((field_every > 0 && s % field_every == 0) || s == total)) {
      err = pdk_sim_update_output_fields(sim);
      if (!err) err = pdk_output_write_fields(out, p, s, h.time, so->fields, so->num_fields);
    }
    if (!err && ckpt_every > 0 && s % ckpt_every == 0 && s < total)
      err = pdk_checkpoint_write(ctx, ckpt, e, pdk_scene_text(scene));
    double now = pdk_wtime();
    const int in_place = tty && (now - last_print > 0.25 || s == total);
    const int line = log_lines && s < total && now - last_line >= line_every &&
                     10 * (s - last_line_step) >= total - start;
    if (in_place || line) {
      double el = now - run0,
             frac = (double)(s - start) / (double)(total - start > 0 ? total - start : 1);
      char w[32], eta[32];
      fmt_duration(w, sizeof w, now - wall0);
      fmt_duration(eta, sizeof eta, frac > 0 ? el / frac - el : NAN);
      fprintf(stderr, "%sstep %ld/%ld (%.0f%%)  t %.4g  wall %s  ETA %s  broken %lld  E %.4g%s",
              in_place ? "\r" : "", s, total, 100.0 * (double)s / (double)total, h.time, w, eta,
              (long long)h.broken, h.kinetic + h.strain, in_place ? "   " : "\n");
      last_print = now;
      if (line) last_line = now, last_line_step = s;
    }
  }
  if (tty) fputc('\n', stderr);
  if (err) {
    fprintf(stderr, "pdk: %s\n", pdk_ctx_error_message(ctx));
    pdk_output_close(&out, 0);
    rc = 1;
    goto done;
  }
  if (interrupted) {
    if (final_checkpoint(ctx, out, ckpt, e, scene)) {
      fprintf(stderr, "pdk: interrupted, and the checkpoint failed: %s\n",
              pdk_ctx_error_message(ctx));
      pdk_output_close(&out, 0);
      rc = 1;
      goto done;
    }
    /* The output holds every step written so far; a checkpoint continues it. */
    pdk_output_close(&out, 1);
    fprintf(stderr, "pdk: interrupted at step %ld of %ld; continue with\n", pdk_explicit_step(e),
            total);
    print_continue(stderr, &a, dir, ckpt);
    rc = 130;
    goto done;
  }
  if (final_checkpoint(ctx, out, ckpt, e, scene) || pdk_output_close(&out, 1)) {
    fprintf(stderr, "pdk: %s\n", pdk_ctx_error_message(ctx));
    pdk_output_close(&out, 0);
    rc = 1;
    goto done;
  }
  {
    warn_float_roundoff(sim);
    report_energy(sim, &h0, &h);
    double wall = pdk_wtime() - wall0, run = pdk_wtime() - run0;
    long steps = pdk_explicit_step(e) - start;
    double bonds = (double)pdk_families_num_bonds(pdk_sim_families(sim)) * (double)steps;
    fprintf(
        stderr,
        "done: %ld steps in %.2f s (%.2f s stepping), %.3g bond updates/s, peak memory %.1f MiB, "
        "%lld bonds broken\n",
        steps, wall, run, run > 0 ? bonds / run : 0.0, pdk_peak_memory_bytes() / 1048576.0,
        (long long)pdk_model_num_broken(pdk_sim_model(sim)));
    print_outputs(dir, pdk_scene_name(scene));
    if (pdk_explicit_opts_get(e)->dt_update != PDK_DT_UPDATE_NONE)
      fprintf(stderr,
              "dt_update: %d estimates of the stable step, dt lowered %d time(s), final dt %.4g "
              "(latest estimate %.4g)\n",
              pdk_explicit_num_estimates(e), pdk_explicit_num_dt_changes(e), pdk_explicit_dt(e),
              pdk_explicit_stable_dt(e));
  }
done:
  pdk_output_close(&out, 0);
  free(ckpt_scene);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
  pdk_ctx_destroy(&ctx);
  return rc;
}
