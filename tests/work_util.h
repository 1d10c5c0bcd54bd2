/* A test's folder for the files it writes ($PDK_BUILD_DIR/tests/<test>.work) and the small file
 * helpers the scene tests share: write a text file into it; reading a whole file back: file_util.h.
 */
#ifndef PDK_TEST_WORK_UTIL_H
#define PDK_TEST_WORK_UTIL_H

#include <sys/stat.h>

#include "file_util.h"

static char work[512];

/* Sets `work` to $PDK_BUILD_DIR/tests/<test>.work and creates it (an existing one is reused). */
static inline void work_init(const char *test) {
  const char *build = getenv("PDK_BUILD_DIR");
  T_ASSERT(build, "PDK_BUILD_DIR is not set (ctest sets it)");
  snprintf(work, sizeof work, "%s/tests/%s.work", build, test);
  mkdir(work, 0755);
}

/* <work>/<name> opened for writing; the test fails if it cannot be. */
static inline FILE *work_open(const char *name) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", work, name);
  FILE *f = fopen(path, "w");
  T_ASSERT(f != NULL, "cannot write %s", path);
  return f;
}

static inline void write_file(const char *name, const char *text) {
  FILE *f = work_open(name);
  T_ASSERT(fputs(text, f) >= 0 && fclose(f) == 0, "cannot write %s/%s", work, name);
}

#endif
