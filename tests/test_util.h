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

/* What a passing test measured (margins to its bounds, counts): printed only when
 * PDK_TEST_VERBOSE is set, so the default suite's passing tests are silent. The arguments are
 * not evaluated otherwise: compute what must run before. */
#define T_INFO(...)                                                                                \
  do {                                                                                             \
    if (getenv("PDK_TEST_VERBOSE")) printf(__VA_ARGS__);                                           \
  } while (0)

/* A test that cannot check what it is for on this machine (say, the CPU lacks the instruction set
 * of the kernels it tests) ends with T_SKIP, after whatever it could check has passed: CTest then
 * reports it as skipped, not passed (SKIP_RETURN_CODE, tests/CMakeLists.txt), and the reason is
 * on stdout. Free what the test holds first (a sanitizer build reports leaks at exit). */
#define T_SKIP_RETURN_CODE 77
#define T_SKIP(...)                                                                             \
  do {                                                                                          \
    printf("pdk-test-skip: ");                                                                  \
    printf(__VA_ARGS__);                                                                        \
    printf("\n");                                                                               \
    fflush(stdout);                                                                             \
    exit(T_SKIP_RETURN_CODE);                                                                   \
  } while (0)

/* The PDK_ISA_* bits of ctx's CPU that the kernel tests exercise: all of them, or only those also
 * in PDK_TEST_ISA (a number: 0 runs a test as on a CPU without AVX2, 1 as on one with AVX2 and
 * without AVX-512), to check a test's path for older CPUs on a newer one. */
static inline unsigned t_isa(const pdk_ctx *ctx) {
  unsigned isa = pdk_ctx_isa(ctx);
  const char *env = getenv("PDK_TEST_ISA");
  if (env && *env) isa &= (unsigned)strtoul(env, NULL, 0);
  return isa;
}

static inline pdk_ctx *t_ctx(int num_threads) {
  pdk_ctx_opts o = pdk_ctx_opts_default();
  o.num_threads = num_threads;
  char why[512];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(&o, &ctx, why, sizeof why)) T_FAIL("pdk_ctx_create: %s", why);
  return ctx;
}

#endif
