/* Private: the explicit solver's state (src/explicit.c; checkpoint part: explicit_state.c). */
#ifndef PDK_EXPLICIT_IMPL_H
#define PDK_EXPLICIT_IMPL_H

#include "model_impl.h"
#include "pdk/explicit.h"

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
  double rho;
  int32_t *bc_of[3];        /* [n] per component: index of the displacement/velocity bc, -1 free */
  uint8_t *reaction_member[PDK_MAX_REACTION_SETS]; /* [n] 1 if in reaction set k (borrowed) */
  int num_reaction;
  double strain;            /* strain energy of the last force pass */
  double external_work;
  double energy0;           /* kinetic + strain energy at creation, for the blow-up check */
  double energy_floor;      /* energies below this are round-off for the blow-up check */
};

#endif
