/* Private: what pdk_sim_restart (src/scene/sim.c) reads from a checkpoint besides pdk_checkpoint_read. */
#ifndef PDK_CHECKPOINT_IMPL_H
#define PDK_CHECKPOINT_IMPL_H

#include "solvers/explicit_impl.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"

/* pdk_checkpoint_read with a say before anything changes: after the checkpoint is verified and
 * found to fit the simulation, decide(arg, its /solver scalars) runs (when not NULL); a non-zero
 * return (an error it has set in the context) ends the restore with that error and the
 * simulation unchanged. scene_text (may be NULL) receives the scene text stored in the checkpoint
 * as pdk_checkpoint_info gives it (malloc'd, NULL when none; NULL after an error). */
int pdk_checkpoint_restore(pdk_ctx *ctx, const char *path, pdk_explicit *e,
                           int (*decide)(void *arg, const pdk_checkpoint_solver *cs), void *arg,
                           char **scene_text);

#endif
