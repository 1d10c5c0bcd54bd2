/* Helpers for the test programs: silent on success, the first mismatch printed on failure. */
#ifndef PDK_TEST_UTIL_H
#define PDK_TEST_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pdk/pdk.h"

#define T_FAIL(...)                                                                             \
  do {                                                                                          \
    fprintf(stderr, "%s:%d: ", __FILE__, __LINE__);                                             \
    fprintf(stderr, __VA_ARGS__);                                                               \
    fprintf(stderr, "\n");                                                                      \
    exit(1);                                                                                    \
  } while (0)

/* A condition that must hold. */
#define T_ASSERT(cond, ...)                                                                     \
  do {                                                                                          \
    if (!(cond)) {                                                                              \
      fprintf(stderr, "%s:%d: assertion '%s' failed: ", __FILE__, __LINE__, #cond);             \
      fprintf(stderr, __VA_ARGS__);                                                             \
      fprintf(stderr, "\n");                                                                    \
      exit(1);                                                                                  \
    }                                                                                           \
  } while (0)

/* A pdk call that must succeed; prints the context's message if it does not. */
#define T_OK(ctx, expr)                                                                         \
  do {                                                                                          \
    int t_err_ = (expr);                                                                        \
    if (t_err_) T_FAIL("%s returned %d: %s", #expr, t_err_, pdk_ctx_error_message(ctx));        \
  } while (0)

/* A pdk call that must fail with `code` and a message containing `needle`. */
#define T_FAILS(ctx, expr, code, needle)                                                        \
  do {                                                                                          \
    pdk_ctx_error_clear(ctx);                                                                   \
    int t_err_ = (expr);                                                                        \
    if (t_err_ != (code))                                                                       \
      T_FAIL("%s returned %d, expected %d (message: %s)", #expr, t_err_, (int)(code),           \
             pdk_ctx_error_message(ctx));                                                       \
    if (!strstr(pdk_ctx_error_message(ctx), (needle)))                                          \
      T_FAIL("%s: message '%s' does not mention '%s'", #expr, pdk_ctx_error_message(ctx),       \
             (needle));                                                                         \
  } while (0)

/* |a - b| <= rtol*|b| + atol */
#define T_NEAR(a, b, rtol, atol, ...)                                                           \
  do {                                                                                          \
    double t_a_ = (a), t_b_ = (b);                                                              \
    if (!(fabs(t_a_ - t_b_) <= (rtol) * fabs(t_b_) + (atol))) {                                 \
      fprintf(stderr, "%s:%d: %s = %.17g vs %s = %.17g (rtol %g, atol %g): ", __FILE__,         \
              __LINE__, #a, t_a_, #b, t_b_, (double)(rtol), (double)(atol));                   \
      fprintf(stderr, __VA_ARGS__);                                                             \
      fprintf(stderr, "\n");                                                                    \
      exit(1);                                                                                  \
    }                                                                                           \
  } while (0)

static inline pdk_ctx *t_ctx(int num_threads) {
  pdk_ctx_opts o = pdk_ctx_opts_default();
  o.num_threads = num_threads;
  char why[512];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(&o, &ctx, why, sizeof why)) T_FAIL("pdk_ctx_create: %s", why);
  return ctx;
}

#endif
