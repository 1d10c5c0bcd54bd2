/* Helpers for the output tests t180-t183: a small 2-D particle store, a whole output run written
 * through the C API (histories and fields, no solver), and directory inspection. */
#ifndef PDK_OUTPUT_UTIL_H
#define PDK_OUTPUT_UTIL_H

#ifndef _DEFAULT_SOURCE
#define _DEFAULT_SOURCE /* opendir, mkdir, fork */
#endif
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pdk/output.h"
#include "test_util.h"

/* A 2-D square lattice of 12 x 4 particles (spacing 1 mm) with a scalar field "damage" and a set
 * "left", so the output has a field plot and a reaction set. */
static inline pdk_particles *ou_store(pdk_ctx *ctx) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = 1e-3;
  lo.hi[0] = 12e-3;
  lo.hi[1] = 4e-3;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  double a[3] = {-1, -1, -1}, b[3] = {2.5e-3, 1, 1};
  pdk_region left = pdk_region_box(a, b);
  T_OK(ctx, pdk_particles_set_define(p, "left", &left, NULL));
  T_OK(ctx, pdk_particles_field_add(p, "damage", PDK_F64, 1));
  return p;
}

/* Writes `rows` history records and a field output ("damage") after every second one; each
 * record's kinetic energy is `mark` + row, so files of two runs differ. Returns the first
 * failing call's code (0: all succeeded); the output stays open. */
static inline int ou_write(pdk_output *o, pdk_particles *p, int rows, double mark) {
  const char *fields[1] = {"damage"};
  double *d = pdk_particles_field_data(p, "damage", 0);
  for (int r = 1; r <= rows; ++r) {
    pdk_history h;
    memset(&h, 0, sizeof h);
    h.step = r;
    h.time = 1e-6 * r;
    h.kinetic = mark + r;
    h.strain = 0.5 * r;
    h.external_work = mark + 1.5 * r;
    h.reaction[0][0] = -mark * r;
    h.dt = 1e-6;
    int err = pdk_output_write_history(o, &h);
    if (err) return err;
    if (r % 2 == 0) {
      for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
        d[i] = mark + 0.01 * (double)(i % 7) * r;
      err = pdk_output_write_fields(o, p, r, h.time, fields, 1);
      if (err) return err;
    }
  }
  return 0;
}

static inline pdk_output_opts ou_opts(const char *dir, const char *name) {
  static const char *const rsets[1] = {"set:left"};
  pdk_output_opts oo = pdk_output_opts_default();
  oo.dir = dir;
  oo.name = name;
  oo.reaction_sets = rsets;
  oo.num_reaction_sets = 1;
  return oo;
}

static inline int ou_exists(const char *dir, const char *name) {
  char path[1024];
  struct stat sb;
  snprintf(path, sizeof path, "%s/%s", dir, name);
  return stat(path, &sb) == 0;
}

/* Number of entries of dir (without . and ..); the names, one a line, into list. */
static inline int ou_list(const char *dir, char *list, size_t cap) {
  DIR *d = opendir(dir);
  int count = 0;
  size_t len = 0;
  if (list && cap) list[0] = '\0';
  if (!d) return 0;
  for (struct dirent *ent; (ent = readdir(d));) {
    if (!strcmp(ent->d_name, ".") || !strcmp(ent->d_name, "..")) continue;
    count++;
    if (list && len + strlen(ent->d_name) + 2 < cap) {
      len += (size_t)snprintf(list + len, cap - len, "%s\n", ent->d_name);
    }
  }
  closedir(d);
  return count;
}

/* Empties dir (files only) and creates it when missing. */
static inline void ou_clean(const char *dir) {
  mkdir(dir, 0777);
  DIR *d = opendir(dir);
  T_ASSERT(d, "cannot open %s", dir);
  char path[1024];
  for (struct dirent *ent; (ent = readdir(d));) {
    if (!strcmp(ent->d_name, ".") || !strcmp(ent->d_name, "..")) continue;
    snprintf(path, sizeof path, "%s/%s", dir, ent->d_name);
    unlink(path);
  }
  closedir(d);
}

static inline int ou_on_path(const char *prog) {
  const char *path = getenv("PATH");
  char buf[4096];
  while (path && *path) {
    const char *end = strchr(path, ':');
    size_t len = end ? (size_t)(end - path) : strlen(path);
    snprintf(buf, sizeof buf, "%.*s/%s", (int)len, path, prog);
    if (len && access(buf, X_OK) == 0) return 1;
    path = end ? end + 1 : NULL;
  }
  return 0;
}

#endif
