/* Explicit dynamics: velocity Verlet over a model, with boundary conditions, loads, initial
 * conditions, a stable time-step estimate and per-step histories.
 *
 * One step (t -> t + dt):
 *   v += dt/2 (f + b) / rho;  x += dt v;  prescribed x, v applied at t + dt;
 *   f = model force at x;     v += dt/2 (f + b) / rho;  prescribed v applied again;
 *   energies and reactions summed in a fixed order (independent of the thread count).
 * A non-finite position or velocity stops the run with a message naming the step and particle.
 */
#ifndef PDK_EXPLICIT_H
#define PDK_EXPLICIT_H

#include "pdk/export.h"
#include "pdk/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A scalar function of time. */
typedef enum pdk_tfun_kind {
  PDK_TFUN_CONSTANT = 0, /* a */
  PDK_TFUN_LINEAR = 1,   /* a + b t */
  PDK_TFUN_RAMP = 2,     /* a * min(t / b, 1): linear rise over b, then hold */
  PDK_TFUN_SMOOTH = 3,   /* a * s(min(t / b, 1)), s(r) = r^3 (10 - 15 r + 6 r^2): smooth rise */
  PDK_TFUN_SINE = 4      /* a sin(2 pi t / b) */
} pdk_tfun_kind;

typedef struct pdk_tfun {
  pdk_tfun_kind kind;
  double a, b;
} pdk_tfun;

PDK_EXPORT pdk_tfun pdk_tfun_constant(double a);
PDK_EXPORT double pdk_tfun_value(const pdk_tfun *f, double t);
PDK_EXPORT double pdk_tfun_rate(const pdk_tfun *f, double t); /* d/dt */
/* Exact integral over [t0, t1]. */
PDK_EXPORT double pdk_tfun_integral(const pdk_tfun *f, double t0, double t1);

typedef enum pdk_bc_kind {
  PDK_BC_DISPLACEMENT = 0, /* u_c(t) = value(t) on the chosen components; fixed: value 0 */
  PDK_BC_VELOCITY = 1,     /* v_c(t) = value(t); position integrates it */
  PDK_BC_BODY_FORCE = 2,   /* body force density b_c(t) [force / length^dim] added to f */
  PDK_BC_WALL = 3          /* explicit solver only: a rigid frictionless plane, below */
} pdk_bc_kind;

#define PDK_MAX_WALLS 8

/* A rigid frictionless wall (PDK_BC_WALL): the plane through point + velocity t with unit normal
 * n = normal / |normal| pointing out of the wall, towards the body; components and value[] are
 * unused. The particles of the set (NULL: all; particles with a prescribed component are left to
 * their condition) may not go behind it, (x - point(t)) . n >= 0, and may leave it again: after
 * each drift, a particle found behind is put back on the plane and the normal component of its
 * velocity relative to the wall, when it points into the wall, is removed (a kinematic contact:
 * perfectly plastic in the normal direction for that particle, the tangential motion free). The
 * wall's impulse on the body (sum of m dv, along n) is the history's wall_impulse[k] (walls in the
 * order of the list); the energy the wall takes, the kinetic energy removed plus the work of the
 * position correction against the last forces (- sum V f . dx), is counted in external_work and
 * in contact_work, so the energy account stays closed. */

typedef struct pdk_bc {
  pdk_bc_kind kind;
  const char *set;     /* particle set name ("set:<name>" field); NULL: every particle */
  unsigned components; /* bit c set: the condition acts on component c (1 = x, 2 = y, 4 = z) */
  pdk_tfun value[3];   /* per component */
  /* Static solvers only (the explicit solver refuses it): NULL, or the name of an f64 particle
   * field with dim components; the condition's value on component c of particle i is then
   * value[c] x field[c][i] (a prescribed displacement or body force that varies over the set,
   * e.g. an analytical solution on the boundary). */
  const char *scale_field;
  /* Displacement and velocity conditions: all zero (the default) for conditions on the x, y, z
   * components; otherwise a direction d (need not be unit): the condition prescribes the component
   * along n = d / |d| only, u.n = value[0](t) (or v.n), the components normal to n staying free (a
   * roller on a face whose normal is n). components must then be 1 (value[0]). A particle under
   * such a condition takes no other displacement or velocity condition. Explicit, ADR and Newton
   * with an analytic tangent; not with scale_field. */
  double direction[3];
  /* PDK_BC_WALL only: a point of the plane at t = 0, its normal (non-zero, out of the wall) and
   * the wall's constant velocity; name labels its history columns (may be NULL: "wall<k>"). */
  double point[3], normal[3], velocity[3];
  const char *name;
} pdk_bc;

/* Re-estimating the stable step during a run. The stable step of a body is not fixed: a family
 * that loses bonds can stiffen its particle (correspondence: the stiffness of a particle grows
 * like K^-1 of its family, which grows as the family shrinks), so a step chosen at creation may
 * exceed the stable one after breaks. With an update, the solver re-runs the creation's Lanczos
 * estimate (on trial forces at the current state: no history moves, positions and forces are
 * restored bit for bit) and, when the step is more than 0.1% above safety x the new estimate,
 * lowers the step to safety x the estimate from the next step on. The step never grows back.
 * Each estimate costs about 42 force passes, hence the interval. auto re-estimates when the
 * deformation moved: when the
 * smallest current / initial length over the intact bonds fell below 0.9 of its value at the
 * last estimate (checked every 8 steps, one read of the bonds); a run whose bonds never shorten
 * that much keeps its first estimate and is the run of none, bit for bit. */
typedef enum pdk_dt_update {
  PDK_DT_UPDATE_NONE = 0,    /* the step chosen at creation throughout (default) */
  PDK_DT_UPDATE_BREAKS = 1,  /* re-estimate when bonds broke since the last estimate, at most
                                once per dt_update_interval steps */
  PDK_DT_UPDATE_PERIODIC = 2, /* re-estimate every dt_update_interval steps */
  PDK_DT_UPDATE_AUTO = 3      /* re-estimate when bonds shortened by 10% since the last estimate
                                 (dt_update_interval unused) */
} pdk_dt_update;

typedef struct pdk_explicit_opts {
  double dt;             /* time step; 0: safety * estimated stable step */
  double safety;         /* fraction of the stable step used when dt = 0 (default 0.8), and the
                            fraction kept below each re-estimate of a dt_update */
  int force_dt;          /* 1: accept a dt above the stable estimate */
  pdk_dt_update dt_update;
  long dt_update_interval; /* steps between two estimates of a dt_update (0: 100) */
  const pdk_bc *bcs;
  int num_bcs;
  /* Initial velocity v0 = v0_const + v0_grad X (affine field), on every particle. */
  double v0_const[3];
  double v0_grad[3][3];
  /* Reaction force histories: sets whose summed internal force is recorded each step. */
  const char *const *reaction_sets;
  int num_reaction_sets;
} pdk_explicit_opts;

PDK_EXPORT pdk_explicit_opts pdk_explicit_opts_default(void);

/* Per-step quantities. Reactions are the forces the constraints exert on each set:
 * R = -sum_{i in set} V_i f_i (internal force), so a pulled bar shows a positive reaction. */
typedef struct pdk_history {
  long step;
  double time;
  double kinetic;        /* sum 1/2 rho V |v|^2 */
  double strain;         /* model strain energy */
  double external_work;  /* work done by prescribed displacements/velocities and body forces */
  double reaction[8][3]; /* first 8 reaction sets */
  pdk_bond_index broken; /* directed bonds broken so far */
  /* Energy dissipated so far (pdk_model_plastic_work): plastic flow, damage, bond breaking.
   * external_work = kinetic + strain + plastic_work + damage_work + breaking_work, up to the
   * time-integration error. */
  double plastic_work;
  double damage_work;
  double breaking_work;
  /* Size of the step that led to this record (it changes during a run only with dt_update);
   * 0 in static solves, which have no time step. */
  double dt;
  /* Johnson-Cook damage (0 for models without it): particles failed so far (D reached D_c; they
   * count whether or not their bonds break, so a run with failed_keeps_bonds shows its failures
   * here and not in `broken`) and the largest damage D of any particle. */
  pdk_index failed;
  double damage_max;
  /* Walls (PDK_BC_WALL conditions, in list order; 0 without): the normal impulse each gave the
   * body so far (N s; > 0 pushing along its normal), and the energy they took out of it so far,
   * also counted in external_work (<= 0 up to the position-correction term). */
  double wall_impulse[PDK_MAX_WALLS];
  double contact_work;
  /* UL family rebuilds: the strain energy they removed so far (pdk_model_rebuild_work; 0 in TL),
   * a term of the account like the dissipated energies. */
  double rebuild_work;
} pdk_history;

typedef struct pdk_explicit pdk_explicit;

PDK_EXPORT int pdk_explicit_create(pdk_model *m, const pdk_explicit_opts *opts, pdk_explicit **out);
PDK_EXPORT void pdk_explicit_destroy(pdk_explicit **e);

/* Stable time step of the model: 2 / sqrt(lambda_max(M^-1 K)), from 40 Lanczos steps on trial
 * force differences (model-agnostic), computed at creation and, with dt_update, again during the
 * run at the state of that step. The Lanczos value is a lower bound of lambda_max, tight on
 * lattices: the estimate is close to the true limit, and the safety factor is the margin. During a run, a blow-up (non-finite state, or
 * kinetic + strain energy above 100 times the initial energy plus the work done) stops it with a
 * message naming the step and the particle. */
PDK_EXPORT double pdk_explicit_stable_dt(const pdk_explicit *e); /* the latest estimate */
PDK_EXPORT double pdk_explicit_dt(const pdk_explicit *e);        /* the current step */
/* Step count and time at which the current step took effect (0, 0 until a dt_update lowers it),
 * so a run to end time T needs step0 + ceil((T - time0) / dt) steps in all. */
PDK_EXPORT void pdk_explicit_dt_start(const pdk_explicit *e, long *step0, double *time0);
/* Estimates of the stable step so far, counting the one at creation, and how many lowered dt. */
PDK_EXPORT int pdk_explicit_num_estimates(const pdk_explicit *e);
PDK_EXPORT int pdk_explicit_num_dt_changes(const pdk_explicit *e);
/* The options in effect (dt_update_interval 0 resolved to its default). */
PDK_EXPORT const pdk_explicit_opts *pdk_explicit_opts_get(const pdk_explicit *e);

/* Advances num_steps steps. hist (may be NULL) receives the state after the last step. */
PDK_EXPORT int pdk_explicit_run(pdk_explicit *e, long num_steps, pdk_history *hist);
PDK_EXPORT double pdk_explicit_time(const pdk_explicit *e);
PDK_EXPORT long pdk_explicit_step(const pdk_explicit *e);

#ifdef __cplusplus
}
#endif
#endif
