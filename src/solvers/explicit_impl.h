/* Private: the explicit solver's state (src/solvers/explicit.c; checkpoint part: explicit_state.c). */
#ifndef PDK_EXPLICIT_IMPL_H
#define PDK_EXPLICIT_IMPL_H

#include "models/model_impl.h"
#include "core/state.h"
#include "pdk/explicit.h"
#include "pdk/ctx.h"
#include "pdk/model.h"
#include "pdk/particles.h"

#define PDK_RED_BLOCK 4096 /* particles per reduction block: fixed, so sums are thread-independent */
#define PDK_MAX_REACTION_SETS 8

struct pdk_explicit {
  pdk_ctx *ctx;
  pdk_model *m;
  pdk_particles *p;
  pdk_explicit_opts opts;
  pdk_bc *bcs;              /* [num_bcs], copied */
  int dim;
  pdk_index n;
  double dt, dt_stable;
  /* the step the solver was created with (opts.dt, or safety x the first estimate): checkpointed,
   * so a restart can tell whether its scene asks for the step the checkpoint's run started with */
  double dt_created;
  double time;
  long step;
  /* dt_update bookkeeping (checkpointed): the last estimate's step and broken-bond count, the
   * step and time at which dt last changed, and the counters */
  long est_step;
  pdk_bond_index est_broken;
  long dt_step0;
  double dt_time0;
  int num_estimates, num_dt_changes;
  /* dt_update auto (explicit_dt.c): the smallest bond length ratio at the last estimate
   * (checkpointed once an auto re-estimate set it) */
  double auto_ratio;
  /* and the last full bond read (not checkpointed: a restored run reads in full first): its
   * positions [dim][n] (NULL before it), its ratio, and the smallest initial bond length */
  double *auto_x;
  double auto_rlast, auto_ximin;
  double rho;
  int32_t *bc_of[3];        /* [n] per component: index of the displacement/velocity bc, -1 free */
  /* conditions along a direction (pdk_bc.direction): the particles they hold, their condition
   * and the frame of each condition (bc.h) */
  pdk_index *dir_list;   /* [num_dir] */
  int32_t *dir_bc;       /* [num_dir] */
  pdk_index num_dir;
  double (*dir_frame)[3][3]; /* [num_bcs] */
  uint8_t *reaction_member[PDK_MAX_REACTION_SETS]; /* [n] 1 if in reaction set k (borrowed) */
  int num_reaction;
  double strain;            /* strain energy of the last force pass */
  double external_work;
  double energy0;           /* kinetic + strain energy at creation, for the blow-up check */
  double energy_floor;      /* energies below this are round-off for the blow-up check */
  /* energy-account runaway check (explicit.c, check_runaway; not checkpointed: a restored or
   * restarted solver takes its baseline at its first step) */
  int acct_set;             /* 1 once acct_e0 and acct_w0 hold the baseline */
  long acct_step0;          /* the step of the baseline */
  double acct_e0, acct_w0;  /* kinetic + strain + dissipated energy and external work there */
  double acct_prev;         /* energy created at the previous check */
  int acct_streak;          /* consecutive checks at which the created energy grew */
  double *acct_a2;          /* [n] |a|^2 when the streak began (only while a streak runs) */
  long acct_a2_step;        /* the step of acct_a2 */
  /* rigid walls (src/solvers/wall.c): their conditions' indices, the impulse each gave the body
   * and the energy they took so far (counted in external_work too) */
  int wall_bc[PDK_MAX_WALLS];
  int num_walls;
  double wall_impulse[PDK_MAX_WALLS];
  double contact_work;
};

/* src/solvers/wall.c: checks the PDK_BC_WALL conditions and lists them (at creation); applies the
 * walls' contact after the drift of the step ending at t1. */
int pdk_walls_init(pdk_explicit *e);
void pdk_walls_apply(pdk_explicit *e, double t1);

/* src/solvers/explicit_dt.c: the Lanczos estimate of the stable step (mid_run: a body without
 * stiffness keeps the last estimate); a re-estimate at the current state lowering dt to
 * safety x it when above; the smallest current / initial length over the intact bonds; dt_update auto's
 * trigger, called after every step. */
int pdk_explicit_estimate_dt(pdk_explicit *e, int mid_run);
int pdk_explicit_update_dt(pdk_explicit *e, double safety);
double pdk_explicit_min_bond_ratio(pdk_explicit *e, double *xi_min);
int pdk_explicit_auto_dt(pdk_explicit *e);

/* The solver's scalars stored in a checkpoint. */
typedef struct pdk_checkpoint_solver {
  long step;
  double time;
  double dt;         /* the step it was taking */
  double dt_created; /* the step its run was created with (before dt_update lowered it) */
  double dt_stable;  /* the latest estimate of the stable step */
  long dt_step0;     /* step and time at which dt took its value (0, 0: at creation) */
  double dt_time0;
} pdk_checkpoint_solver;

/* ---- its checkpoint part (/solver; src/solvers/explicit_state.c, through src/core/state.h) ---------------------------- */

/* The model the solver advances. */
pdk_model *pdk_explicit_model(const pdk_explicit *e);

/* time, step, dt, dt_created, strain, external_work and the dt_update state. */
int pdk_explicit_state_save(const pdk_explicit *e, pdk_state *s);
/* The scalars a restart decides with, from a /solver part (no solver needed). */
int pdk_explicit_state_info(pdk_state *s, pdk_checkpoint_solver *out);
/* Restores the scalars (a part without the dt_update state, from before it, leaves that as it
 * is). */
int pdk_explicit_state_load(pdk_explicit *e, pdk_state *s);

/* Restart of a run at a step other than the one its checkpoint was taking (src/scene/sim.c): the step
 * the solver was created with, and the step dt from (step0, time0) on. */
double pdk_explicit_dt_created(const pdk_explicit *e);
void pdk_explicit_restart_dt(pdk_explicit *e, double dt, long step0, double time0);

#endif
