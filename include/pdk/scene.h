/* Scenes: a YAML file that describes a whole run, and the simulation it builds.
 *
 * pdk_scene_load reads and validates a scene (libcyaml schema plus range and consistency
 * checks). Every error names the file, the line and the key, says what is wrong and what is
 * allowed. Overrides "key.path=value" (from `pdk run --set`) are applied to the YAML document
 * before validation, so they pass through exactly the same checks. docs/scenes.md lists every
 * key with its unit and default.
 *
 * pdk_sim_create builds what the scene describes: particles (lattice, holes, notches), sets,
 * families (with pre-cracks), the model and the solver. Nothing is written to disk by either.
 */
#ifndef PDK_SCENE_H
#define PDK_SCENE_H

#include "pdk/export.h"
#include "pdk/explicit.h"
#include "pdk/static.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pdk_scene pdk_scene;

PDK_EXPORT int pdk_scene_load(pdk_ctx *ctx, const char *path, const char *const *overrides,
                              int num_overrides, pdk_scene **out);
PDK_EXPORT void pdk_scene_destroy(pdk_scene **s);

PDK_EXPORT const char *pdk_scene_path(const pdk_scene *s);
PDK_EXPORT const char *pdk_scene_name(const pdk_scene *s); /* "name" key, default: file stem */
/* The scene after overrides, as YAML text. */
PDK_EXPORT const char *pdk_scene_text(const pdk_scene *s);
PDK_EXPORT int pdk_scene_threads(const pdk_scene *s);   /* solver.threads, 0 = default */
PDK_EXPORT int pdk_scene_dimension(const pdk_scene *s); /* 2 or 3 */

/* solver.type */
typedef enum pdk_solver_type {
  PDK_SOLVER_EXPLICIT = 0, /* explicit dynamics (pdk/explicit.h) */
  PDK_SOLVER_ADR = 1,   /* quasi-static load steps by adaptive dynamic relaxation (pdk/static.h) */
  PDK_SOLVER_NEWTON = 2 /* static load steps by Newton-Raphson (pdk/static.h) */
} pdk_solver_type;
PDK_EXPORT pdk_solver_type pdk_scene_solver_type(const pdk_scene *s);
PDK_EXPORT const char *pdk_solver_type_name(pdk_solver_type type);

/* Where a key of the scene was given: "<file>:<line>", or "<file>: --set <key.path>=<value>" when
 * an override set it. An absent key (a default) gives the location of its nearest present parent.
 * Key paths join mapping keys with '.' and index lists from 0: "boundary_conditions[1].y". */
PDK_EXPORT void pdk_scene_key_location(const pdk_scene *s, const char *key_path, char *buf,
                                       size_t len);
/* Records, in the context, a message about a scene key in the scene's form
 *   <file>:<line>: <key.path>: <what is wrong>; <what is allowed>
 * (the caller's fmt supplies the part after the key path) and returns code. For applications that
 * find a problem with a scene after loading it (the `pdk` command, output writers). */
PDK_EXPORT int pdk_scene_error(const pdk_scene *s, pdk_ctx *ctx, int code, const char *key_path,
                               const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* What the output section asks for. */
typedef struct pdk_scene_output {
  long field_interval;      /* steps (static: load steps) between field outputs (0: first
                               and last only) */
  long history_interval;    /* steps between history rows (>= 1; static default 1) */
  long checkpoint_interval; /* steps between checkpoints (0: only at the end / on Ctrl-C) */
  int num_fields;
  const char *const *fields; /* particle field names to write, e.g. "u", "v", "f" */
  int num_reaction_sets;
  const char *const *reaction_sets; /* set names (without "set:") whose reactions are recorded */
  /* per reaction set: the unit direction of a boundary condition along a direction on that set
   * (its history then has reaction_<set>_n, the reaction along it), else zero */
  double reaction_normal[8][3];
  const char *units; /* output.units: "SI", "mm-N-s-tonne" or NULL (none): pdk_output_opts.units */
  int compression;   /* output.compression: deflate level 0..9 of the field outputs (0: off) */
  int num_walls;     /* the wall conditions (type: wall), in list order: their names */
  const char *const *walls;
} pdk_scene_output;

PDK_EXPORT const pdk_scene_output *pdk_scene_output_get(const pdk_scene *s);

/* A built simulation. */
typedef struct pdk_sim pdk_sim;

PDK_EXPORT int pdk_sim_create(pdk_ctx *ctx, const pdk_scene *s, pdk_sim **out);
PDK_EXPORT void pdk_sim_destroy(pdk_sim **sim);

PDK_EXPORT pdk_particles *pdk_sim_particles(pdk_sim *sim);
PDK_EXPORT pdk_families *pdk_sim_families(pdk_sim *sim);
PDK_EXPORT pdk_model *pdk_sim_model(pdk_sim *sim);
PDK_EXPORT pdk_explicit *pdk_sim_explicit(pdk_sim *sim); /* NULL for a static solver */
/* explicit: solver.steps, or ceil(end_time / dt) (after a solver.dt_update lowered dt at step s0,
 * time t0: s0 + ceil((end_time - t0) / dt), so the count can grow during a run); static: the
 * number of load steps */
PDK_EXPORT long pdk_sim_num_steps(const pdk_sim *sim);

/* Restart of an explicit run from the checkpoint at `path` (pdk/output.h), into a simulation
 * freshly built from the scene s. The checkpoint is verified and checked against the simulation
 * (pdk_checkpoint_read), and its time, step and time step become the run's. The run ends where the
 * scene says: at solver.end_time, or after solver.steps steps; info->end_step == info->step means
 * the checkpoint is at that end already (nothing to do), and an end before the checkpoint is
 * refused naming solver.end_time or solver.steps. The step: when the scene asks for the step the
 * checkpoint's run was created with, the run continues with the checkpoint's dt (also when a
 * solver.dt_update had lowered it), bit for bit as if it had never stopped. When it asks for
 * another (solver.dt, solver.safety or the material changed), the new step takes over at the
 * checkpoint (info->dt_changed) and the run still ends at solver.end_time; with solver.steps that
 * is refused naming solver.dt (the step count would end the run at another time), as is a step
 * above the stable estimate stored in the checkpoint (unless solver.force_dt). */
typedef struct pdk_sim_restart_info {
  long step;                /* the checkpoint's step and time: where the run goes on */
  double time;              /* (its time) */
  long end_step;            /* the run's last step (pdk_sim_num_steps) */
  double dt;                /* the step it goes on with */
  int dt_changed;           /* 1: the scene's step replaced the checkpoint's at the checkpoint */
  double dt_before;         /* the checkpoint's dt */
  double dt_created_before; /* the step the checkpoint's run was created with */
} pdk_sim_restart_info;
PDK_EXPORT int pdk_sim_restart(pdk_sim *sim, const pdk_scene *s, const char *path,
                               pdk_sim_restart_info *info);

/* Static solvers (solver.type adr or newton). A static run is a sequence of load steps; each is
 * solved to equilibrium (with its re-solves while bonds break) and gives one history record:
 *   step            load steps solved (0: the unloaded state)
 *   time            the load step's pseudo-time (solver.end_time given), else its load factor
 *   kinetic         0
 *   strain, broken, reaction, plastic_work, damage_work, breaking_work   at the equilibrium,
 *                   after the committing pass
 *   external_work   work of the supports and body forces along the load path (trapezoidal over
 *                   the load steps; see pdk/static.h)                                          */
PDK_EXPORT pdk_solver_type pdk_sim_solver_type(const pdk_sim *sim);
PDK_EXPORT pdk_static *pdk_sim_static(pdk_sim *sim); /* NULL for the explicit solver */
/* Solves the next load step and fills h (may be NULL) with its record. */
PDK_EXPORT int pdk_sim_static_step(pdk_sim *sim, pdk_history *h);
/* The record of the current state (the last load step solved, or the unloaded state). */
PDK_EXPORT int pdk_sim_static_history(pdk_sim *sim, pdk_history *h);

/* Refreshes derived output fields before a field output: displacement "u" = x - X, and
 * "von_mises" (the von Mises Cauchy stress of a correspondence model; see src/scene/sim.c). */
PDK_EXPORT int pdk_sim_update_output_fields(pdk_sim *sim);

#ifdef __cplusplus
}
#endif
#endif
