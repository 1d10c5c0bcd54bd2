/* Scene limits checked before the work they bound (docs/scenes.md, "Limits"):
 * - a scene file over 8 MiB is refused before it is read (a 1 GiB sparse file), and a device that
 *   never ends (/dev/zero) once 8 MiB were read, both naming the limit;
 * - a lattice whose memory estimate exceeds the available memory (1.6e9 points, about 1.4 TB) is
 *   refused by pdk_scene_load, before pdk_sim_create allocates anything, naming the estimate, the
 *   limit and the key limits.memory; limits.memory set above the estimate lets the load go on, set
 *   below it refuses a small scene, and a non-positive value is an error;
 * - a 100 000-vertex polygon is refused with the cap of 4096 after a count, in well under the
 *   minute the quadratic count took (CPU time, so a loaded machine does not matter).
 * labels: unit */
#include <fcntl.h>
#include <time.h>
#include <unistd.h>

#include "pdk/scene.h"
#include "test_util.h"

static const char *base_scene = "dimension: 2\n"
                                "geometry:\n"
                                "  spacing: 1.0e-3\n"
                                "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"
                                "material: {density: 7850, youngs_modulus: 200e9, "
                                "poisson_ratio: 0.3}\n"
                                "sets:\n"
                                "  - {name: bottom, box: {lo: [-1, -1], hi: [1, 0.0012]}}\n"
                                "boundary_conditions:\n"
                                "  - {set: bottom, type: displacement, x: 0, y: 0}\n"
                                "solver: {steps: 10}\n";

static void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "wb");
  T_ASSERT(f && fputs(text, f) >= 0 && !fclose(f), "writing %s", path);
}

static void expect_refused(pdk_ctx *ctx, const char *path, const char *const *ov, int nov,
                           const char *needle1, const char *needle2) {
  pdk_scene *s = NULL;
  pdk_ctx_error_clear(ctx);
  int err = pdk_scene_load(ctx, path, ov, nov, &s);
  const char *msg = pdk_ctx_error_message(ctx);
  if (err != PDK_ERR_ARG) T_FAIL("%s: returned %d, expected %d: %s", path, err, PDK_ERR_ARG, msg);
  T_ASSERT(s == NULL, "no scene on failure");
  if (!strstr(msg, needle1) || (needle2 && !strstr(msg, needle2)))
    T_FAIL("%s: the message does not name '%s'%s%s: %s", path, needle1, needle2 ? " and " : "",
           needle2 ? needle2 : "", msg);
  if (getenv("PDK_TEST_VERBOSE")) printf("%s\n", msg);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);

  /* A 1 GiB file (sparse: no disk used) is refused by its size. */
  int fd = open("t170_big.yaml", O_CREAT | O_TRUNC | O_WRONLY, 0644);
  T_ASSERT(fd >= 0 && ftruncate(fd, 1L << 30) == 0 && close(fd) == 0, "making t170_big.yaml");
  expect_refused(ctx, "t170_big.yaml", NULL, 0, "8 MiB", "1073741824 bytes");
  remove("t170_big.yaml");

  /* A device that never ends: read up to the limit, then refused. */
  if (access("/dev/zero", R_OK) == 0) expect_refused(ctx, "/dev/zero", NULL, 0, "8 MiB", NULL);

  /* Memory: 40 000 x 40 000 points of correspondence need about 2.4 TB by the estimate. */
  write_text("t170_scene.yaml", base_scene);
  {
    const char *huge[] = {"geometry.box.hi=[1, 1]", "geometry.spacing=2.5e-5",
                          "model.kind=correspondence"};
    expect_refused(ctx, "t170_scene.yaml", huge, 3,
                   "--set geometry.spacing=2.5e-5: geometry.spacing: the run needs about",
                   "limits.memory");
    expect_refused(ctx, "t170_scene.yaml", huge, 3, "1.6e+09 particles x 1024 B", "TB");
    /* limits.memory above the estimate: the load goes on (nothing is built here). */
    const char *allowed[] = {"geometry.box.hi=[1, 1]", "geometry.spacing=2.5e-5",
                             "model.kind=correspondence", "limits.memory=1e14"};
    pdk_scene *s = NULL;
    T_OK(ctx, pdk_scene_load(ctx, "t170_scene.yaml", allowed, 4, &s));
    pdk_scene_destroy(&s);
  }
  {
    /* limits.memory below what a small scene needs (more than 32 MiB): refused, blaming the key */
    const char *tight[] = {"limits.memory=1e6"};
    expect_refused(ctx, "t170_scene.yaml", tight, 1,
                   "--set limits.memory=1e6: limits.memory: the run needs about",
                   "that limits.memory allows");
    const char *zero[] = {"limits.memory=0"};
    expect_refused(ctx, "t170_scene.yaml", zero, 1, "limits.memory: must be > 0", NULL);
    /* the same scene without the key loads (it needs ~36 MB) */
    pdk_scene *s = NULL;
    T_OK(ctx, pdk_scene_load(ctx, "t170_scene.yaml", NULL, 0, &s));
    pdk_scene_destroy(&s);
  }

  /* A polygon of 100 000 vertices: refused by its count, quickly. */
  {
    const int nv = 100000;
    const char *head = "dimension: 2\n"
                       "geometry:\n"
                       "  spacing: 1.0e-3\n"
                       "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"
                       "  holes:\n"
                       "    - polygon:\n"
                       "        vertices: [";
    const char *tail = "]\n"
                       "material: {density: 7850, bulk_modulus: 1e9}\n"
                       "solver: {steps: 10}\n";
    size_t cap = strlen(head) + strlen(tail) + (size_t)nv * 40;
    char *text = malloc(cap), *c = text;
    c += sprintf(c, "%s", head);
    for (int k = 0; k < nv; ++k) {
      double a = 6.283185307179586 * k / nv;
      c += sprintf(c, "%s[%.6f, %.6f]", k ? ", " : "", 0.005 + 0.002 * cos(a),
                   0.01 + 0.002 * sin(a));
    }
    sprintf(c, "%s", tail);
    write_text("t170_polygon.yaml", text);
    free(text);
    clock_t t0 = clock();
    expect_refused(ctx, "t170_polygon.yaml", NULL, 0,
                   "t170_polygon.yaml:7: geometry.holes[0].polygon.vertices: must have at most "
                   "4096 entries, got 100000",
                   NULL);
    double cpu = (double)(clock() - t0) / CLOCKS_PER_SEC;
    T_ASSERT(cpu < 20.0, "refusing the polygon took %.1f s of CPU time (a quadratic count)", cpu);
    remove("t170_polygon.yaml");
  }
  remove("t170_scene.yaml");
  pdk_ctx_destroy(&ctx);
  return 0;
}
