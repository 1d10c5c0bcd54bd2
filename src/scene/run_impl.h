/* Private: what the run loop (src/scene/run.c) needs from the simulation beyond pdk/scene.h. */
#ifndef PDK_RUN_IMPL_H
#define PDK_RUN_IMPL_H

#include "pdk/scene.h"

/* pdk_sim_restart that also gives the scene text stored in the checkpoint, as
 * pdk_checkpoint_info does (malloc'd, NULL when none; scene_text may be NULL), from the one
 * reading of the file (src/scene/sim.c). */
int pdk_sim_restart_text(pdk_sim *sim, const pdk_scene *s, const char *path,
                         pdk_sim_restart_info *info, char **scene_text);

#endif
