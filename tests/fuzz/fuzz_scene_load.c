/* libFuzzer harness of the scene loader (tests/fuzz/README.md).
 *
 * The input is a scene file's text, optionally followed by overrides: the bytes up to the first NUL
 * are the scene, each NUL-terminated piece after it (at most 8) one `--set` string. The scene goes
 * through pdk_scene_load from a memory file (memfd, opened by its /proc/self/fd path), exactly as
 * `pdk check` reads a file. A loaded scene that makes a small body (at most PDK_FUZZ_MAX_PARTICLES
 * lattice points, estimated from the box and spacing, a horizon of at most 8 spacings, at most 2
 * threads) is also built with pdk_sim_create, as `pdk check` does; PDK_FUZZ_BUILD=0 in the
 * environment skips that.
 *
 * Besides the sanitizers' reports (the build uses address and undefined-behaviour sanitizers), a
 * refused scene must leave a message in the context; with PDK_FUZZ_STRICT=1 the message must also
 * name the scene file or the override (as every scene error does), and a crash is reported when
 * it does not.
 */
#define _GNU_SOURCE
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "pdk/pdk.h"
#include "pdk/scene.h"
#include "scene/scene_impl.h"

#define PDK_FUZZ_MAX_PARTICLES 1000.0
#define PDK_FUZZ_MAX_OVERRIDES 8

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static pdk_ctx *ctx;
static int fd = -1;
static char path[64];
static int build = 1, strict = 0;

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc;
  (void)argv;
  pdk_ctx_opts o = pdk_ctx_opts_default();
  o.num_threads = 1;
  char why[512];
  if (pdk_ctx_create(&o, &ctx, why, sizeof why)) {
    fprintf(stderr, "fuzz_scene_load: %s\n", why);
    exit(1);
  }
  fd = memfd_create("scene", 0);
  if (fd < 0) {
    perror("fuzz_scene_load: memfd_create");
    exit(1);
  }
  snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
  const char *b = getenv("PDK_FUZZ_BUILD"), *s = getenv("PDK_FUZZ_STRICT");
  build = !(b && !strcmp(b, "0"));
  strict = s && !strcmp(s, "1");
  return 0;
}

/* A cheap upper estimate of the body's size, so only small bodies are built. */
static int small_body(const pdk_scene *s) {
  const pdk_lattice_opts *l = &s->lattice;
  if (!(l->spacing > 0.0) || !isfinite(l->spacing) || !(s->horizon_factor <= 8.0)) return 0;
  double n = 1.0;
  for (int d = 0; d < s->dim; ++d) {
    const double e = (l->hi[d] - l->lo[d]) / l->spacing;
    if (!(e >= 0.0) || !isfinite(e)) return 0;
    n *= e + 2.0;
  }
  return n <= PDK_FUZZ_MAX_PARTICLES;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  /* split: scene text, then overrides */
  char *copy = malloc(size + 1);
  if (!copy) return 0;
  memcpy(copy, data, size);
  copy[size] = '\0';
  const size_t scene_len = strlen(copy);
  const char *overrides[PDK_FUZZ_MAX_OVERRIDES];
  int num = 0;
  for (size_t at = scene_len + 1; at <= size && num < PDK_FUZZ_MAX_OVERRIDES;) {
    overrides[num++] = copy + at;
    at += strlen(copy + at) + 1;
  }

  if (ftruncate(fd, 0) || pwrite(fd, copy, scene_len, 0) != (ssize_t)scene_len) {
    perror("fuzz_scene_load: writing the memory file");
    abort();
  }
  pdk_scene *s = NULL;
  if (pdk_scene_load(ctx, path, overrides, num, &s)) {
    const char *msg = pdk_ctx_error_message(ctx);
    if (!msg || !msg[0]) {
      fprintf(stderr, "fuzz_scene_load: a refused scene without a message\n");
      abort();
    }
    if (strict && !strstr(msg, path) && !strstr(msg, "--set")) {
      fprintf(stderr, "fuzz_scene_load: the message does not name the scene file:\n  %s\n", msg);
      abort();
    }
  } else {
    /* what the command and the output writers read from a loaded scene */
    char loc[256];
    pdk_scene_key_location(s, "geometry.spacing", loc, sizeof loc);
    const pdk_scene_output *so = pdk_scene_output_get(s);
    size_t sum = strlen(pdk_scene_name(s)) + strlen(pdk_scene_text(s)) + strlen(loc);
    for (int k = 0; k < so->num_fields; ++k)
      sum += strlen(so->fields[k]);
    if (sum == 0) abort(); /* keeps the reads; never true: the location names the file */
    if (build && small_body(s) && pdk_scene_threads(s) <= 2) {
      pdk_sim *sim = NULL;
      if (pdk_sim_create(ctx, s, &sim)) {
        const char *msg = pdk_ctx_error_message(ctx);
        if (!msg || !msg[0]) {
          fprintf(stderr, "fuzz_scene_load: a scene not built, without a message\n");
          abort();
        }
      }
      pdk_sim_destroy(&sim);
      pdk_ctx_set_num_threads(ctx, 1); /* solver.threads sets the context's count */
    }
    pdk_scene_destroy(&s);
  }
  free(copy);
  return 0;
}
