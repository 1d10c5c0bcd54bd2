/* Private to src/core/state.c and src/io/checkpoint.c: the insides of a checkpoint part (pdk_state). */
#ifndef PDK_STATE_IMPL_H
#define PDK_STATE_IMPL_H

#include <stdarg.h>

#include "h5io.h"
#include "state.h"
#include "pdk/ctx.h"

struct pdk_state {
  pdk_ctx *ctx;
  hid_t g;           /* the group */
  const char *group; /* its name, for messages */
  const char *path;  /* the checkpoint file, for messages */
};

static inline pdk_state pdk_state_of(pdk_ctx *ctx, hid_t g, const char *group, const char *path) {
  pdk_state s = {ctx, g, group, path};
  return s;
}

/* The message of a checkpoint that does not fit the simulation (PDK_ERR_ARG), from `where`. */
int pdk_state_mismatch_v(pdk_ctx *ctx, const char *where, const char *path, const char *fmt,
                         va_list ap);

#endif
