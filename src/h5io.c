/* HDF5 attribute helpers and crash-safe file commits; see h5io.h. */
#define _DEFAULT_SOURCE /* fsync, mkdir, strdup */
#include "h5io.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "pdk/version.h"

#define PDK_H5_TEXT_ATTR_MAX 60000 /* bytes: below the 64 kB object-header limit */

hid_t pdk_h5_mem_type(pdk_type type) {
  switch (type) {
  case PDK_F64: return H5T_NATIVE_DOUBLE;
  case PDK_F32: return H5T_NATIVE_FLOAT;
  case PDK_I64: return H5T_NATIVE_INT64;
  case PDK_I32: return H5T_NATIVE_INT32;
  case PDK_U8: return H5T_NATIVE_UINT8;
  }
  return -1;
}

hid_t pdk_h5_file_type(pdk_type type) {
  switch (type) {
  case PDK_F64: return H5T_IEEE_F64LE;
  case PDK_F32: return H5T_IEEE_F32LE;
  case PDK_I64: return H5T_STD_I64LE;
  case PDK_I32: return H5T_STD_I32LE;
  case PDK_U8: return H5T_STD_U8LE;
  }
  return -1;
}

/* A fixed-length C string type of `len` bytes (at least 1). */
static hid_t string_type(size_t len) {
  hid_t t = H5Tcopy(H5T_C_S1);
  if (t < 0) return t;
  if (H5Tset_size(t, len ? len : 1) < 0 || H5Tset_strpad(t, H5T_STR_NULLTERM) < 0) {
    H5Tclose(t);
    return -1;
  }
  return t;
}

int pdk_h5_attr_write_string(pdk_ctx *ctx, hid_t obj, const char *name, const char *text) {
  int err = PDK_SUCCESS;
  hid_t t = -1, s = -1, a = -1;
  size_t len = strlen(text) + 1;
  PDK_H5_CALL_GOTO(ctx, t, string_type(len));
  PDK_H5_CALL_GOTO(ctx, s, H5Screate(H5S_SCALAR));
  PDK_H5_CALL_GOTO(ctx, a, H5Acreate2(obj, name, t, s, H5P_DEFAULT, H5P_DEFAULT));
  herr_t st;
  PDK_H5_CALL_GOTO(ctx, st, H5Awrite(a, t, text));
cleanup:
  if (a >= 0) H5Aclose(a);
  if (s >= 0) H5Sclose(s);
  if (t >= 0) H5Tclose(t);
  return err;
}

static int attr_write_scalar(pdk_ctx *ctx, hid_t obj, const char *name, hid_t file_type,
                             hid_t mem_type, const void *value) {
  int err = PDK_SUCCESS;
  hid_t s = -1, a = -1;
  herr_t st;
  PDK_H5_CALL_GOTO(ctx, s, H5Screate(H5S_SCALAR));
  PDK_H5_CALL_GOTO(ctx, a, H5Acreate2(obj, name, file_type, s, H5P_DEFAULT, H5P_DEFAULT));
  PDK_H5_CALL_GOTO(ctx, st, H5Awrite(a, mem_type, value));
cleanup:
  if (a >= 0) H5Aclose(a);
  if (s >= 0) H5Sclose(s);
  return err;
}

int pdk_h5_attr_write_i64(pdk_ctx *ctx, hid_t obj, const char *name, int64_t value) {
  return attr_write_scalar(ctx, obj, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

int pdk_h5_attr_write_f64(pdk_ctx *ctx, hid_t obj, const char *name, double value) {
  return attr_write_scalar(ctx, obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

int pdk_h5_attr_exists(hid_t obj, const char *name) { return H5Aexists(obj, name) > 0; }

static int attr_read_scalar(pdk_ctx *ctx, hid_t obj, const char *name, hid_t mem_type,
                            void *value) {
  int err = PDK_SUCCESS;
  hid_t a = -1;
  herr_t st;
  PDK_H5_CALL_GOTO(ctx, a, H5Aopen(obj, name, H5P_DEFAULT));
  PDK_H5_CALL_GOTO(ctx, st, H5Aread(a, mem_type, value));
cleanup:
  if (a >= 0) H5Aclose(a);
  return err;
}

int pdk_h5_attr_read_i64(pdk_ctx *ctx, hid_t obj, const char *name, int64_t *value) {
  return attr_read_scalar(ctx, obj, name, H5T_NATIVE_INT64, value);
}

int pdk_h5_attr_read_f64(pdk_ctx *ctx, hid_t obj, const char *name, double *value) {
  return attr_read_scalar(ctx, obj, name, H5T_NATIVE_DOUBLE, value);
}

/* Reads a fixed-length string attribute or dataset (`is_dataset`) into a malloc'd buffer. */
static int read_string(pdk_ctx *ctx, hid_t obj, const char *name, int is_dataset, char **text) {
  int err = PDK_SUCCESS;
  hid_t h = -1, ft = -1, mt = -1;
  char *buf = NULL;
  herr_t st;
  *text = NULL;
  if (is_dataset)
    PDK_H5_CALL_GOTO(ctx, h, H5Dopen2(obj, name, H5P_DEFAULT));
  else
    PDK_H5_CALL_GOTO(ctx, h, H5Aopen(obj, name, H5P_DEFAULT));
  PDK_H5_CALL_GOTO(ctx, ft, is_dataset ? H5Dget_type(h) : H5Aget_type(h));
  PDK_CHECK_GOTO(H5Tget_class(ft) == H5T_STRING && H5Tis_variable_str(ft) == 0, ctx, PDK_ERR_IO,
                 "'%s' is not a fixed-length string; this file was not written by pdk", name);
  size_t len = H5Tget_size(ft);
  PDK_CHECK_GOTO(len > 0, ctx, PDK_ERR_IO, "string '%s' has size 0", name);
  buf = calloc(len + 1, 1);
  PDK_CHECK_GOTO(buf, ctx, PDK_ERR_MEMORY, "out of memory reading '%s' (%zu bytes)", name, len);
  PDK_H5_CALL_GOTO(ctx, mt, string_type(len));
  if (is_dataset)
    PDK_H5_CALL_GOTO(ctx, st, H5Dread(h, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf));
  else
    PDK_H5_CALL_GOTO(ctx, st, H5Aread(h, mt, buf));
  *text = buf;
  buf = NULL;
cleanup:
  free(buf);
  if (mt >= 0) H5Tclose(mt);
  if (ft >= 0) H5Tclose(ft);
  if (h >= 0 && is_dataset)
    H5Dclose(h);
  else if (h >= 0)
    H5Aclose(h);
  return err;
}

int pdk_h5_attr_read_string(pdk_ctx *ctx, hid_t obj, const char *name, char **text) {
  return read_string(ctx, obj, name, 0, text);
}

int pdk_h5_text_write(pdk_ctx *ctx, hid_t file, const char *name, const char *text) {
  size_t len = strlen(text) + 1;
  if (len < PDK_H5_TEXT_ATTR_MAX) return pdk_h5_attr_write_string(ctx, file, name, text);
  int err = PDK_SUCCESS;
  hid_t t = -1, s = -1, d = -1;
  herr_t st;
  PDK_H5_CALL_GOTO(ctx, t, string_type(len));
  PDK_H5_CALL_GOTO(ctx, s, H5Screate(H5S_SCALAR));
  PDK_H5_CALL_GOTO(ctx, d, H5Dcreate2(file, name, t, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  PDK_H5_CALL_GOTO(ctx, st, H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, text));
cleanup:
  if (d >= 0) H5Dclose(d);
  if (s >= 0) H5Sclose(s);
  if (t >= 0) H5Tclose(t);
  return err;
}

int pdk_h5_text_read(pdk_ctx *ctx, hid_t file, const char *name, char **text) {
  *text = NULL;
  if (H5Aexists(file, name) > 0) return read_string(ctx, file, name, 0, text);
  if (H5Lexists(file, name, H5P_DEFAULT) > 0) return read_string(ctx, file, name, 1, text);
  return PDK_SUCCESS;
}

int pdk_h5_read_block(pdk_ctx *ctx, hid_t loc, const char *name, hid_t mem_type, int rank,
                      const hsize_t *start, const hsize_t *count, void *dst) {
  int err = PDK_SUCCESS;
  hid_t d = -1, fspace = -1, mspace = -1;
  herr_t st;
  PDK_H5_CALL_GOTO(ctx, d, H5Dopen2(loc, name, H5P_DEFAULT));
  PDK_H5_CALL_GOTO(ctx, fspace, H5Dget_space(d));
  PDK_H5_CALL_GOTO(ctx, st, H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL));
  PDK_H5_CALL_GOTO(ctx, mspace, H5Screate_simple(rank, count, NULL));
  PDK_H5_CALL_GOTO(ctx, st, H5Dread(d, mem_type, mspace, fspace, H5P_DEFAULT, dst));
cleanup:
  if (mspace >= 0) H5Sclose(mspace);
  if (fspace >= 0) H5Sclose(fspace);
  if (d >= 0) H5Dclose(d);
  return err;
}

int pdk_h5_write_provenance(pdk_ctx *ctx, hid_t file, const char *kind) {
  PDK_CALL(pdk_h5_attr_write_string(ctx, file, "kind", kind));
  PDK_CALL(pdk_h5_attr_write_string(ctx, file, "pdk_version", PDK_VERSION_STRING));
  PDK_CALL(pdk_h5_attr_write_string(ctx, file, "build_type", PDK_BUILD_TYPE));
  PDK_CALL(pdk_h5_attr_write_string(ctx, file, "build_flags", PDK_BUILD_FLAGS));
  PDK_CALL(pdk_h5_attr_write_string(ctx, file, "compiler", PDK_COMPILER));
  return PDK_SUCCESS;
}

char *pdk_str_printf(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int len = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (len < 0) return NULL;
  char *s = malloc((size_t)len + 1);
  if (!s) return NULL;
  va_start(ap, fmt);
  vsnprintf(s, (size_t)len + 1, fmt, ap);
  va_end(ap);
  return s;
}

int pdk_dir_create(pdk_ctx *ctx, const char *dir) {
  int err = PDK_SUCCESS;
  char *path = strdup(dir);
  PDK_CHECK(path, ctx, PDK_ERR_MEMORY, "out of memory");
  size_t len = strlen(path);
  while (len > 1 && path[len - 1] == '/')
    path[--len] = '\0';
  /* Create each prefix ending before a '/', then the whole path. */
  for (char *q = path + 1;; ++q) {
    if (*q != '/' && *q != '\0') continue;
    char c = *q;
    *q = '\0';
    struct stat sb;
    if (stat(path, &sb) != 0) {
      PDK_CHECK_GOTO(mkdir(path, 0777) == 0 || errno == EEXIST, ctx, PDK_ERR_IO,
                     "cannot create the directory '%s': %s", path, strerror(errno));
    } else {
      PDK_CHECK_GOTO(S_ISDIR(sb.st_mode), ctx, PDK_ERR_IO,
                     "'%s' exists and is not a directory; choose another output directory", path);
    }
    *q = c;
    if (c == '\0') break;
  }
cleanup:
  free(path);
  return err;
}

int pdk_file_sync(pdk_ctx *ctx, const char *path) {
  int fd = open(path, O_RDONLY);
  PDK_CHECK(fd >= 0, ctx, PDK_ERR_IO, "cannot open '%s' to sync it: %s", path, strerror(errno));
  int rc = fsync(fd), fsync_errno = errno;
  close(fd);
  PDK_CHECK(rc == 0, ctx, PDK_ERR_IO, "fsync of '%s' failed: %s (the disk may be full)", path,
            strerror(fsync_errno));
  return PDK_SUCCESS;
}

/* Syncs the directory holding `path`, so a rename in it survives a power cut. Best effort: some
 * file systems refuse fsync on directories, which is not an error for pdk. */
static void sync_parent_dir(const char *path) {
  char *dir = strdup(path);
  if (!dir) return;
  char *slash = strrchr(dir, '/');
  if (!slash)
    strcpy(dir, ".");
  else if (slash == dir)
    dir[1] = '\0';
  else
    *slash = '\0';
  int fd = open(dir, O_RDONLY);
  if (fd >= 0) {
    (void)fsync(fd);
    close(fd);
  }
  free(dir);
}

int pdk_file_commit(pdk_ctx *ctx, const char *part, const char *final) {
  PDK_CALL(pdk_file_sync(ctx, part));
  PDK_CHECK(rename(part, final) == 0, ctx, PDK_ERR_IO, "cannot rename '%s' to '%s': %s", part,
            final, strerror(errno));
  sync_parent_dir(final);
  return PDK_SUCCESS;
}

int pdk_file_remove(const char *path) {
  if (unlink(path) == 0 || errno == ENOENT) return 0;
  return errno;
}

int pdk_file_exists(const char *path) {
  struct stat sb;
  return stat(path, &sb) == 0;
}
