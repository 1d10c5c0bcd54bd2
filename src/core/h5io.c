/* HDF5 attribute helpers, pdk's HDF5 file driver and crash-safe file commits; see h5io.h. */
#define _DEFAULT_SOURCE /* fsync, mkdir, strdup, pread, pwrite, O_CLOEXEC */
#include "h5io.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "pdk/version.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"

#define PDK_H5_TEXT_ATTR_MAX 60000 /* bytes: below the 64 kB object-header limit */

static void fault_step(void);

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
  fault_step();
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

/* ---- pdk's HDF5 file driver -------------------------------------------------------------------
 * POSIX pread/pwrite, like HDF5's default driver, except that a failed write or truncate is
 * recorded in the file (vfd.err) and reported to HDF5 as a success; from then on writes are
 * dropped and reads fail, so HDF5 never decodes what did not reach the disk. pdk reads the
 * recorded error (pdk_h5_file_check) and reports it itself. */

#define VFD_MAXADDR (((haddr_t)1 << (8 * sizeof(off_t) - 1)) - 1)
#define VFD_IO_MAX ((size_t)1 << 30) /* bytes per pread/pwrite call (Linux moves < 2 GiB) */

typedef struct vfd_file {
  H5FD_t pub; /* first: HDF5 sees a vfd_file as its H5FD_t */
  int fd;
  haddr_t eoa, eof;
  dev_t dev;
  ino_t ino;
  int err;    /* errno of the first failed write or truncate, 0 while none failed */
  int keep;   /* set by pdk_h5_file_close: close() leaves the struct for it to free */
  int closed; /* close() ran (with keep set) */
  int close_err;
} vfd_file;

static long fault_write_at, fault_write_count; /* pdk_h5_fault_write */
static long fault_kill_at, fault_step_count;   /* pdk_fault_kill_at_step */
static int vfd_open_errno;                     /* errno of the last failed open */

long pdk_h5_fault_write(long k) {
  const long seen = fault_write_count;
  fault_write_at = k;
  fault_write_count = 0;
  return seen;
}

void pdk_fault_kill_at_step(long k) {
  fault_kill_at = k;
  fault_step_count = 0;
}

/* Called before each rename or removal that gives a file its final name or takes one away. */
static void fault_step(void) {
  if (fault_kill_at > 0 && ++fault_step_count == fault_kill_at) raise(SIGKILL);
}

static int vfd_region_bad(const vfd_file *f, haddr_t addr, size_t size) {
  return addr == HADDR_UNDEF || addr > VFD_MAXADDR || (haddr_t)size > VFD_MAXADDR - addr ||
         addr + size > f->eoa;
}

static H5FD_t *vfd_open(const char *name, unsigned flags, hid_t fapl, haddr_t maxaddr) {
  (void)fapl;
  vfd_open_errno = 0;
  if (!name || !name[0] || maxaddr == 0 || maxaddr == HADDR_UNDEF || maxaddr > VFD_MAXADDR) {
    vfd_open_errno = EINVAL;
    return NULL;
  }
  int mode = (flags & H5F_ACC_RDWR) ? O_RDWR : O_RDONLY;
  if (flags & H5F_ACC_TRUNC) mode |= O_TRUNC;
  if (flags & H5F_ACC_CREAT) mode |= O_CREAT;
  if (flags & H5F_ACC_EXCL) mode |= O_EXCL;
  int fd = open(name, mode | O_CLOEXEC, 0666);
  if (fd < 0) {
    vfd_open_errno = errno;
    return NULL;
  }
  struct stat sb;
  vfd_file *f = fstat(fd, &sb) == 0 ? calloc(1, sizeof *f) : NULL;
  if (!f) {
    vfd_open_errno = errno ? errno : ENOMEM;
    close(fd);
    return NULL;
  }
  f->fd = fd;
  f->eof = (haddr_t)sb.st_size;
  f->dev = sb.st_dev;
  f->ino = sb.st_ino;
  return &f->pub;
}

static herr_t vfd_close(H5FD_t *file) {
  vfd_file *f = (vfd_file *)file;
  if (close(f->fd) != 0) f->close_err = errno; /* never a failure for HDF5: see above */
  if (f->keep)
    f->closed = 1;
  else
    free(f);
  return 0;
}

static int vfd_cmp(const H5FD_t *a, const H5FD_t *b) {
  const vfd_file *f1 = (const vfd_file *)a, *f2 = (const vfd_file *)b;
  if (f1->dev != f2->dev) return f1->dev < f2->dev ? -1 : 1;
  if (f1->ino != f2->ino) return f1->ino < f2->ino ? -1 : 1;
  return 0;
}

static herr_t vfd_query(const H5FD_t *file, unsigned long *flags) {
  (void)file;
  if (flags) {
    *flags = H5FD_FEAT_AGGREGATE_METADATA | H5FD_FEAT_ACCUMULATE_METADATA | H5FD_FEAT_DATA_SIEVE |
             H5FD_FEAT_AGGREGATE_SMALLDATA;
#ifdef H5FD_FEAT_DEFAULT_VFD_COMPATIBLE
    *flags |= H5FD_FEAT_DEFAULT_VFD_COMPATIBLE;
#endif
  }
  return 0;
}

static haddr_t vfd_get_eoa(const H5FD_t *file, H5FD_mem_t type) {
  (void)type;
  return ((const vfd_file *)file)->eoa;
}

static herr_t vfd_set_eoa(H5FD_t *file, H5FD_mem_t type, haddr_t addr) {
  (void)type;
  ((vfd_file *)file)->eoa = addr;
  return 0;
}

static haddr_t vfd_get_eof(const H5FD_t *file, H5FD_mem_t type) {
  (void)type;
  return ((const vfd_file *)file)->eof;
}

static herr_t vfd_get_handle(H5FD_t *file, hid_t fapl, void **handle) {
  (void)fapl;
  if (!handle) return -1;
  *handle = file;
  return 0;
}

static herr_t vfd_read(H5FD_t *file, H5FD_mem_t type, hid_t dxpl, haddr_t addr, size_t size,
                       void *buf) {
  (void)type;
  (void)dxpl;
  vfd_file *f = (vfd_file *)file;
  if (f->err || vfd_region_bad(f, addr, size)) return -1;
  unsigned char *p = buf;
  while (size > 0) {
    ssize_t got = pread(f->fd, p, size < VFD_IO_MAX ? size : VFD_IO_MAX, (off_t)addr);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return -1;
    if (got == 0) { /* past the end of the file: zeros, as the default driver reads */
      memset(p, 0, size);
      break;
    }
    p += got;
    addr += (haddr_t)got;
    size -= (size_t)got;
  }
  return 0;
}

static herr_t vfd_write(H5FD_t *file, H5FD_mem_t type, hid_t dxpl, haddr_t addr, size_t size,
                        const void *buf) {
  (void)type;
  (void)dxpl;
  vfd_file *f = (vfd_file *)file;
  if (vfd_region_bad(f, addr, size)) return -1; /* HDF5's own mistake, not the disk's */
  if (f->err) return 0;
  if (fault_write_at > 0 && ++fault_write_count == fault_write_at) { /* pdk_h5_fault_write */
    f->err = ENOSPC;
    return 0;
  }
  const unsigned char *p = buf;
  while (size > 0) {
    ssize_t put = pwrite(f->fd, p, size < VFD_IO_MAX ? size : VFD_IO_MAX, (off_t)addr);
    if (put < 0 && errno == EINTR) continue;
    if (put <= 0) {
      f->err = put < 0 ? errno : EIO;
      return 0;
    }
    p += put;
    addr += (haddr_t)put;
    size -= (size_t)put;
  }
  if (addr > f->eof) f->eof = addr;
  return 0;
}

static herr_t vfd_truncate(H5FD_t *file, hid_t dxpl, hbool_t closing) {
  (void)dxpl;
  (void)closing;
  vfd_file *f = (vfd_file *)file;
  if (f->err || f->eoa == f->eof) return 0;
  if (ftruncate(f->fd, (off_t)f->eoa) != 0) {
    f->err = errno;
    return 0;
  }
  f->eof = f->eoa;
  return 0;
}

static const H5FD_class_t vfd_class = {
#ifdef H5FD_CLASS_VERSION
    .version = H5FD_CLASS_VERSION,
    .value = (H5FD_class_value_t)601,
#endif
    .name = "pdk",
    .maxaddr = VFD_MAXADDR,
    .fc_degree = H5F_CLOSE_WEAK,
    .open = vfd_open,
    .close = vfd_close,
    .cmp = vfd_cmp,
    .query = vfd_query,
    .get_eoa = vfd_get_eoa,
    .set_eoa = vfd_set_eoa,
    .get_eof = vfd_get_eof,
    .get_handle = vfd_get_handle,
    .read = vfd_read,
    .write = vfd_write,
    .truncate = vfd_truncate,
    .fl_map = H5FD_FLMAP_DICHOTOMY,
};

/* The driver's id, registered on first use (again after an H5close). */
static hid_t vfd_id(void) {
  static hid_t id = -1;
  if (id < 0 || H5Iis_valid(id) <= 0) id = H5FDregister(&vfd_class);
  return id;
}

/* The files open through pdk_h5_file_create and their driver records, so that the check after
 * each history row costs a look-up (asking HDF5 for the file's driver copies its property list:
 * it made an output's history rows 40% slower). */
#define VFD_MAX_OPEN 64
static struct {
  hid_t id;
  vfd_file *f;
} vfd_open_files[VFD_MAX_OPEN];

static void vfd_remember(hid_t id, vfd_file *f) {
  for (int k = 0; k < VFD_MAX_OPEN; ++k)
    if (!vfd_open_files[k].f) {
      vfd_open_files[k].id = id;
      vfd_open_files[k].f = f;
      return;
    }
}

static void vfd_forget(hid_t id) {
  for (int k = 0; k < VFD_MAX_OPEN; ++k)
    if (vfd_open_files[k].f && vfd_open_files[k].id == id) vfd_open_files[k].f = NULL;
}

/* The driver's record of `file`, or NULL when another driver opened it. */
static vfd_file *vfd_of(hid_t file) {
  for (int k = 0; k < VFD_MAX_OPEN; ++k)
    if (vfd_open_files[k].f && vfd_open_files[k].id == file) return vfd_open_files[k].f;
  hid_t fapl = H5Fget_access_plist(file);
  if (fapl < 0) {
    H5Eclear2(H5E_DEFAULT);
    return NULL;
  }
  const hid_t driver = H5Pget_driver(fapl);
  void *handle = NULL;
  if (driver < 0 || driver != vfd_id() || H5Fget_vfd_handle(file, fapl, &handle) < 0) handle = NULL;
  H5Pclose(fapl);
  H5Eclear2(H5E_DEFAULT);
  return handle;
}

int pdk_h5_file_create(pdk_ctx *ctx, const char *path, hid_t *file) {
  return pdk_h5_file_create_with(ctx, path, H5P_DEFAULT, file);
}

int pdk_h5_file_create_with(pdk_ctx *ctx, const char *path, hid_t fcpl, hid_t *file) {
  int err = PDK_SUCCESS;
  hid_t fapl = -1, driver;
  herr_t st;
  *file = -1;
  PDK_H5_CALL_GOTO(ctx, driver, vfd_id());
  PDK_H5_CALL_GOTO(ctx, fapl, H5Pcreate(H5P_FILE_ACCESS));
  PDK_H5_CALL_GOTO(ctx, st, H5Pset_driver(fapl, driver, NULL));
  vfd_open_errno = 0;
  *file = H5Fcreate(path, H5F_ACC_TRUNC, fcpl, fapl);
  if (*file < 0 && vfd_open_errno) {
    H5Eclear2(H5E_DEFAULT);
    PDK_CHECK_GOTO(0, ctx, PDK_ERR_IO, "cannot create '%s': %s", path, strerror(vfd_open_errno));
  }
  if (*file < 0) err = pdk_ext_h5_fail(ctx, "H5Fcreate", __func__);
  if (err) goto cleanup;
  vfd_remember(*file, vfd_of(*file));
  /* a write that failed while the file was created: nothing pdk can use is in it */
  err = pdk_h5_file_check(ctx, *file, path);
  if (err) {
    pdk_h5_file_close(NULL, *file, path);
    *file = -1;
  }
cleanup:
  if (fapl >= 0) H5Pclose(fapl);
  return err;
}

int pdk_h5_file_error(hid_t file) {
  const vfd_file *f = vfd_of(file);
  return f ? f->err : 0;
}

int pdk_h5_file_check(pdk_ctx *ctx, hid_t file, const char *path) {
  const int e = pdk_h5_file_error(file);
  PDK_CHECK(!e, ctx, PDK_ERR_IO, "cannot write '%s': %s", path, strerror(e));
  return PDK_SUCCESS;
}

int pdk_h5_file_flush(pdk_ctx *ctx, hid_t file, const char *path) {
  if (H5Fflush(file, H5F_SCOPE_LOCAL) < 0) {
    if (pdk_h5_file_error(file)) return pdk_h5_file_check(ctx, file, path);
    return pdk_ext_h5_fail(ctx, "H5Fflush", __func__);
  }
  return pdk_h5_file_check(ctx, file, path);
}

int pdk_h5_file_close(pdk_ctx *ctx, hid_t file, const char *path) {
  vfd_file *f = vfd_of(file);
  vfd_forget(file);
  if (f) f->keep = 1;
  if (H5Fclose(file) < 0) {
    /* HDF5 keeps the file: the driver's record stays its own */
    if (f) f->keep = 0;
    if (!ctx) {
      H5Eclear2(H5E_DEFAULT);
      return PDK_ERR_EXTERNAL;
    }
    return pdk_ext_h5_fail(ctx, "H5Fclose", __func__);
  }
  int e = 0;
  if (f && f->closed) {
    e = f->err ? f->err : f->close_err;
    free(f);
  } else if (f) {
    f->keep = 0; /* still open through another handle: its last close frees it */
  }
  if (!ctx) return e ? PDK_ERR_IO : PDK_SUCCESS;
  PDK_CHECK(!e, ctx, PDK_ERR_IO, "cannot write '%s': %s", path, strerror(e));
  return PDK_SUCCESS;
}

int pdk_file_discard(pdk_ctx *ctx, const char *path) {
  fault_step();
  PDK_CHECK(unlink(path) == 0 || errno == ENOENT, ctx, PDK_ERR_IO, "cannot remove '%s': %s", path,
            strerror(errno));
  return PDK_SUCCESS;
}
