/* Private: HDF5 attribute helpers, pdk's HDF5 file driver and crash-safe file commits, shared by
 * src/output*.c and src/io/checkpoint.c.
 *
 * Every file pdk writes goes through the same life: it is created as <final>.part, written and
 * flushed, then pdk_file_commit syncs it to disk, renames it to <final> and syncs the directory,
 * so a file under its final name is always complete. Every HDF5 call goes through PDK_H5_CALL*.
 *
 * HDF5 files pdk writes are created with pdk_h5_file_create and closed with pdk_h5_file_close.
 * They go through pdk's own HDF5 file driver (POSIX pread/pwrite, as HDF5's default driver): a
 * write that fails (a full disk, an I/O error) is recorded in the file and not passed on to
 * HDF5, which would otherwise be left unable to close the file (HDF5 1.10: H5Fclose fails after a
 * failed metadata write and the half-closed file crashes the library's exit handler). After a
 * failed write the driver drops further writes and fails reads, and pdk_h5_file_check,
 * pdk_h5_file_flush and pdk_h5_file_close report the error ("cannot write '<file>': No space left
 * on device"); the file is then discarded. The file format is HDF5's own: any HDF5 reader opens
 * the files.
 */
#ifndef PDK_H5IO_H
#define PDK_H5IO_H

#include "ext.h"
#include "pdk/ctx.h"
#include "pdk/particles.h"

/* HDF5 types of a pdk_type: in memory (native) and on disk (little-endian, fixed size). */
hid_t pdk_h5_mem_type(pdk_type type);
hid_t pdk_h5_file_type(pdk_type type);

/* Attributes on a group or dataset `obj`. Strings are fixed-length, NUL-terminated. */
int pdk_h5_attr_write_string(pdk_ctx *ctx, hid_t obj, const char *name, const char *text);
int pdk_h5_attr_write_i64(pdk_ctx *ctx, hid_t obj, const char *name, int64_t value);
int pdk_h5_attr_write_f64(pdk_ctx *ctx, hid_t obj, const char *name, double value);
int pdk_h5_attr_exists(hid_t obj, const char *name); /* 1, or 0 (also on error) */
int pdk_h5_attr_read_i64(pdk_ctx *ctx, hid_t obj, const char *name, int64_t *value);
int pdk_h5_attr_read_f64(pdk_ctx *ctx, hid_t obj, const char *name, double *value);
/* *text is malloc'd (free() it). */
int pdk_h5_attr_read_string(pdk_ctx *ctx, hid_t obj, const char *name, char **text);

/* Stores a (possibly long) text under `name` at the file root: as an attribute when it is below
 * 60 kB (the object-header limit is 64 kB), else as a scalar string dataset. */
int pdk_h5_text_write(pdk_ctx *ctx, hid_t file, const char *name, const char *text);
/* Reads what pdk_h5_text_write stored; *text = NULL when there is neither. */
int pdk_h5_text_read(pdk_ctx *ctx, hid_t file, const char *name, char **text);
/* Reads the block start[0..rank) + count[0..rank) of dataset `name` in loc into dst (dense, in
 * row-major order), converted to mem_type. */
int pdk_h5_read_block(pdk_ctx *ctx, hid_t loc, const char *name, hid_t mem_type, int rank,
                      const hsize_t *start, const hsize_t *count, void *dst);

/* The root attributes every pdk file carries: kind, pdk_version, build_type, build_flags,
 * compiler. */
int pdk_h5_write_provenance(pdk_ctx *ctx, hid_t file, const char *kind);

/* malloc'd printf; NULL when out of memory. */
char *pdk_str_printf(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* Creates dir and its parents (like mkdir -p); an existing directory is fine. */
int pdk_dir_create(pdk_ctx *ctx, const char *dir);
/* fsync of a file that is already closed (opens it read-only). */
int pdk_file_sync(pdk_ctx *ctx, const char *path);
/* Syncs `part`, renames it to `final` (replacing any older file) and syncs the directory. */
int pdk_file_commit(pdk_ctx *ctx, const char *part, const char *final);
/* Removes `path` (a missing file is fine), reporting a failure: how a final name is taken away. */
int pdk_file_discard(pdk_ctx *ctx, const char *path);
/* Removes a file; a missing file is fine. Returns 0 or an errno value (no context message:
 * used on cleanup paths). */
int pdk_file_remove(const char *path);
int pdk_file_exists(const char *path);

/* Creates (truncates) the HDF5 file `path` through pdk's driver. A file that cannot be created is
 * a PDK_ERR_IO naming it and the reason ("Read-only file system", "Permission denied"). Close it
 * with pdk_h5_file_close (not H5Fclose). */
int pdk_h5_file_create(pdk_ctx *ctx, const char *path, hid_t *file);
/* The same with a file-creation property list (for example a user block). */
int pdk_h5_file_create_with(pdk_ctx *ctx, const char *path, hid_t fcpl, hid_t *file);
/* PDK_ERR_IO "cannot write '<path>': <reason>" when a write to `file` has failed, else success. */
int pdk_h5_file_check(pdk_ctx *ctx, hid_t file, const char *path);
/* The errno of the first failed write to `file`, 0 when none failed (or another driver). */
int pdk_h5_file_error(hid_t file);
/* H5Fflush, then pdk_h5_file_check. */
int pdk_h5_file_flush(pdk_ctx *ctx, hid_t file, const char *path);
/* Closes `file` (a file made by pdk_h5_file_create never fails to close) and reports a write that
 * failed at any time: PDK_ERR_IO naming `path`. ctx NULL: no message (cleanup paths). */
int pdk_h5_file_close(pdk_ctx *ctx, hid_t file, const char *path);

/* Test hooks, for the tests of the failure paths only (both off, 0, unless a test sets them).
 * pdk_h5_fault_write(k): the k-th write through pdk's HDF5 driver from now on fails as on a full
 * disk (ENOSPC); returns the number of writes counted since the previous call (the writes are
 * counted while k > 0). pdk_fault_kill_at_step(k): the process kills itself (SIGKILL) just before
 * the k-th rename or removal of a final file name from now on (pdk_file_commit, pdk_file_discard).
 */
long pdk_h5_fault_write(long k);
void pdk_fault_kill_at_step(long k);

#endif
