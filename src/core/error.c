/* The context's last error (pdk_ctx_error_*, the status names) and aligned allocation: the bottom
 * of the core layer, called by every other file (ctx.c and the foreign-library wrappers in ext.c
 * included). */
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "pdk_impl.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"

const char *pdk_status_name(int code) {
  switch (code) {
  case PDK_SUCCESS: return "success";
  case PDK_ERR_ARG: return "invalid argument";
  case PDK_ERR_MEMORY: return "out of memory";
  case PDK_ERR_IO: return "I/O error";
  case PDK_ERR_EXTERNAL: return "dependency failed";
  case PDK_ERR_NUMERIC: return "numerical failure";
  case PDK_ERR_UNSUPPORTED: return "unsupported";
  case PDK_ERR_NOT_FOUND: return "not found";
  default: return "unknown error";
  }
}

int pdk_ctx_error_set(pdk_ctx *ctx, int code, const char *where, const char *fmt, ...) {
  if (!ctx) return code;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(ctx->error, sizeof ctx->error, fmt, ap);
  va_end(ap);
  ctx->error_code = code;
  size_t len = strlen(ctx->error), room = sizeof ctx->error - len;
  if (where && room > 8) {
    const char *parts[3] = {" (in ", where, ")"};
    for (int k = 0; k < 3 && room > 1; ++k) {
      size_t m = strlen(parts[k]);
      if (m >= room) m = room - 1;
      memcpy(ctx->error + len, parts[k], m);
      len += m;
      room -= m;
    }
    ctx->error[len] = '\0';
  }
  return code;
}

const char *pdk_ctx_error_message(const pdk_ctx *ctx) { return ctx ? ctx->error : "no context"; }
int pdk_ctx_error_code(const pdk_ctx *ctx) { return ctx ? ctx->error_code : PDK_ERR_ARG; }
void pdk_ctx_error_clear(pdk_ctx *ctx) {
  if (!ctx) return;
  ctx->error_code = 0;
  ctx->error[0] = '\0';
}

void *pdk_alloc_aligned(size_t count, size_t size) {
  if (size && count > (SIZE_MAX - PDK_ALIGN) / size) return NULL;
  size_t bytes = count * size;
  bytes = (bytes + PDK_ALIGN - 1) / PDK_ALIGN * PDK_ALIGN;
  if (bytes == 0) bytes = PDK_ALIGN;
  void *ptr = aligned_alloc(PDK_ALIGN, bytes);
  if (ptr) memset(ptr, 0, bytes);
  return ptr;
}

void pdk_free_aligned(void *ptr) { free(ptr); }
