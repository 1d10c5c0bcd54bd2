/* Reading a whole file in a test: slurp_n (bytes and length, for files that may hold NULs) and
 * slurp (text). The test fails when the file cannot be read. */
#ifndef PDK_TEST_FILE_UTIL_H
#define PDK_TEST_FILE_UTIL_H

#include "test_util.h"

/* The whole file, NUL-terminated, its length in *len (the caller frees it). */
static inline char *slurp_n(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  T_ASSERT(f, "cannot open %s", path);
  fseek(f, 0, SEEK_END);
  const long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *s = malloc((size_t)n + 1);
  T_ASSERT(s && fread(s, 1, (size_t)n, f) == (size_t)n, "cannot read %s", path);
  s[n] = '\0';
  fclose(f);
  *len = (size_t)n;
  return s;
}

static inline char *slurp(const char *path) {
  size_t len;
  return slurp_n(path, &len);
}

#endif
