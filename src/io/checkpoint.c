/* Checkpoint and restart: the whole state of an explicit run in one HDF5 file; the layout is in
 * include/pdk/output.h.
 *
 * What makes a run continue bitwise after a restart: the state a step reads is exactly
 *   - every registered particle field (x, v, f, the model's fields, sets, ...), generic over the
 *     registry, stored [num_comp][n] in the field's own type (here);
 *   - the model's part /model: its bond state and counters, and its kind's own state (for the ul
 *     connectivity the families of the last rebuild), saved and loaded by the model
 *     (src/models/model_state.c, the kind's pdk_model_ops.state_*);
 *   - the solver's part /solver: time, step, dt, strain energy of the last pass, accumulated
 *     external work and the dt_update state, saved and loaded by the solver
 *     (src/solvers/explicit_state.c).
 * Each object writes and reads its part through a pdk_state (src/core/state.h), a group of named
 * scalars (attributes) and arrays (datasets) that this file implements on HDF5; this file owns
 * the format, the checksum, the particle fields and the order of the parts. Everything else is
 * rebuilt identically from the scene (families, constraint maps, reaction masks) or is scratch
 * that the next force pass overwrites.
 *
 * Reading checks everything before it changes anything: that the file is an HDF5 file and a pdk
 * checkpoint of this format, its checksum (below), dimension, particle and bond counts, model
 * kind, bond state, each field's type and shape, and the ids, reference positions and volumes bit
 * for bit. The first difference is the error.
 *
 * The checksum (format 2): the file is created with a 512-byte HDF5 user block (the bytes HDF5
 * leaves to the application before its superblock). When the HDF5 file is complete and closed,
 * pdk hashes every byte after the user block and writes into it, as text,
 *   pdk checkpoint
 *   checksum fnv1a64x:<16 hex digits>
 *   size <the file's size in bytes>
 * followed by zeros. Reading verifies that text, the size and the hash on the raw bytes before
 * HDF5 opens the file, so a damaged file (any byte changed, or truncated) is refused without HDF5
 * ever parsing its damaged metadata (HDF5 1.10 can crash on a corrupted object header). The hash
 * takes 64-bit little-endian words w: x = (x ^ w) * P, then x ^= x >> 32 (P: FNV-1a's 64-bit
 * prime, x from its offset basis). Both maps are invertible in x, so a change of any single word
 * always changes the result; the xor-shift carries high bits down, so that changes in the top bits
 * of two words cannot cancel (as they can with the multiply alone). Opening and verifying the
 * shipped plate's 6.4 MB checkpoint takes 3-17 ms (a loaded 2-core machine). Format 1 files
 * (earlier pdk, no user block) are refused: their data cannot be verified.
 */
#define _DEFAULT_SOURCE /* stat */
#include <errno.h>
#include <string.h>
#include <sys/stat.h>

#include "core/h5io.h"
#include "pdk/comm.h"
#include "pdk/output.h"
#include "core/pdk_impl.h"
#include "checkpoint_impl.h"
#include "core/state_impl.h"
#include "pdk/ctx.h"
#include "pdk/explicit.h"
#include "pdk/families.h"
#include "pdk/model.h"
#include "pdk/particles.h"

#define CKPT_KIND "pdk checkpoint"
#define CKPT_FORMAT 2
#define CKPT_HASH_NAME "fnv1a64x"
#define CKPT_USERBLOCK 512 /* bytes before the HDF5 superblock: the checksum text */
#define CKPT_MAGIC "pdk checkpoint\n"
/* bytes read at a time while hashing (a multiple of 8) */
#define CKPT_HASH_BLOCK ((size_t)1 << 20)

/* ---- checksum ---------------------------------------------------------------------------------
 */

static uint64_t hash_bytes(uint64_t x, const unsigned char *p, size_t len) {
  size_t k = 0;
  for (; k + 8 <= len; k += 8) {
    uint64_t w = 0;
    for (int b = 7; b >= 0; --b)
      w = w << 8 | p[k + (size_t)b];
    x = (x ^ w) * 0x100000001b3ULL;
    x ^= x >> 32;
  }
  if (k < len) { /* the tail (only at the end of the file), zero-padded; the size is stored */
    uint64_t w = 0;
    for (size_t b = len; b-- > k;)
      w = w << 8 | p[b];
    x = (x ^ w) * 0x100000001b3ULL;
    x ^= x >> 32;
  }
  return x;
}

/* The hash of the bytes of f from CKPT_USERBLOCK to its end (`size`); -1 with errno on a read
 * error. */
static int hash_file(FILE *f, long size, uint64_t *out) {
  unsigned char *buf = malloc(CKPT_HASH_BLOCK);
  uint64_t x = 0xcbf29ce484222325ULL; /* FNV-1a's offset basis */
  int rc = -1;
  if (!buf || fseek(f, CKPT_USERBLOCK, SEEK_SET) != 0) goto done;
  for (long pos = CKPT_USERBLOCK; pos < size;) {
    const size_t want = size - pos < (long)CKPT_HASH_BLOCK ? (size_t)(size - pos) : CKPT_HASH_BLOCK;
    if (fread(buf, 1, want, f) != want) {
      if (!ferror(f)) errno = EIO;
      goto done;
    }
    x = hash_bytes(x, buf, want);
    pos += (long)want;
  }
  *out = x;
  rc = 0;
done:
  free(buf);
  return rc;
}

/* After the HDF5 file at `part` is closed: the checksum text into its user block. */
static int seal_checkpoint(pdk_ctx *ctx, const char *part) {
  int err = PDK_SUCCESS;
  char block[CKPT_USERBLOCK];
  uint64_t x = 0;
  long size = -1;
  FILE *f = fopen(part, "r+b");
  PDK_CHECK(f, ctx, PDK_ERR_IO, "cannot reopen the checkpoint '%s' to seal it: %s", part,
            strerror(errno));
  if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
  PDK_CHECK_GOTO(size > CKPT_USERBLOCK && hash_file(f, size, &x) == 0, ctx, PDK_ERR_IO,
                 "cannot read back the checkpoint '%s' to checksum it: %s", part,
                 size > CKPT_USERBLOCK ? strerror(errno) : "it is empty");
  memset(block, 0, sizeof block);
  snprintf(block, sizeof block, "%schecksum %s:%016llx\nsize %ld\n", CKPT_MAGIC, CKPT_HASH_NAME,
           (unsigned long long)x, size);
  PDK_CHECK_GOTO(fseek(f, 0, SEEK_SET) == 0 && fwrite(block, 1, sizeof block, f) == sizeof block &&
                     fflush(f) == 0,
                 ctx, PDK_ERR_IO, "cannot write the checksum into '%s': %s", part, strerror(errno));
cleanup:
  if (fclose(f) != 0 && !err)
    err = pdk_ctx_error_set(ctx, PDK_ERR_IO, __func__, "cannot write the checksum into '%s': %s",
                            part, strerror(errno));
  return err;
}

/* Verifies the user block of a file whose HDF5 signature is at CKPT_USERBLOCK: *sealed = 1 when
 * it is a checkpoint's and its size and checksum match; 0 when the block does not start with
 * CKPT_MAGIC (not sealed by pdk: HDF5 opens the file to say what it is). */
static int verify_seal(pdk_ctx *ctx, const char *path, int *sealed) {
  int err = PDK_SUCCESS;
  char block[CKPT_USERBLOCK + 1];
  char name[32];
  unsigned long long stored = 0;
  long size = -1, stored_size = -1;
  int used = 0;
  uint64_t x = 0;
  *sealed = 0;
  FILE *f = fopen(path, "rb");
  PDK_CHECK(f, ctx, PDK_ERR_IO, "cannot read the checkpoint '%s': %s", path, strerror(errno));
  PDK_CHECK_GOTO(fread(block, 1, CKPT_USERBLOCK, f) == CKPT_USERBLOCK, ctx, PDK_ERR_IO,
                 "cannot read the checkpoint '%s': %s", path,
                 ferror(f) ? strerror(errno) : "it is shorter than its header");
  block[CKPT_USERBLOCK] = '\0';
  if (strncmp(block, CKPT_MAGIC, strlen(CKPT_MAGIC))) goto cleanup;
  *sealed = 1;
  const int fields = sscanf(block + strlen(CKPT_MAGIC), "checksum %31[^:]:%16llx\nsize %ld\n%n",
                            name, &stored, &stored_size, &used);
  int clean = fields == 3 && used > 0 && !strcmp(name, CKPT_HASH_NAME);
  for (size_t k = strlen(CKPT_MAGIC) + (size_t)used; clean && k < CKPT_USERBLOCK; ++k)
    clean = block[k] == '\0';
  PDK_CHECK_GOTO(clean, ctx, PDK_ERR_IO,
                 "checkpoint '%s' is damaged: its checksum header (the first %d bytes) is not "
                 "readable; restart from another checkpoint or run the scene again",
                 path, CKPT_USERBLOCK);
  if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
  PDK_CHECK_GOTO(size == stored_size, ctx, PDK_ERR_IO,
                 "checkpoint '%s' is damaged: it is %ld bytes, it was written with %ld (%s); "
                 "restart from another checkpoint or run the scene again",
                 path, size, stored_size, size < stored_size ? "truncated" : "grown");
  PDK_CHECK_GOTO(hash_file(f, size, &x) == 0, ctx, PDK_ERR_IO,
                 "cannot read the checkpoint '%s': %s", path, strerror(errno));
  PDK_CHECK_GOTO(x == stored, ctx, PDK_ERR_IO,
                 "checkpoint '%s' is damaged: its data does not match its checksum (stored "
                 "%s:%016llx, computed %s:%016llx); restart from another checkpoint or run the "
                 "scene again",
                 path, CKPT_HASH_NAME, stored, CKPT_HASH_NAME, (unsigned long long)x);
cleanup:
  fclose(f);
  return err;
}

/* ---- an object's part: a group of attributes (scalars) and 1-D datasets (arrays) ---------------
 */

/* Writes field `name` of p as /fields/<name> [num_comp][n]. */
static int write_field(pdk_ctx *ctx, hid_t g, pdk_particles *p, const char *name) {
  int err = PDK_SUCCESS;
  hid_t space = -1, mspace = -1, d = -1;
  herr_t st;
  pdk_type type;
  int num_comp;
  const pdk_index n = pdk_particles_count(p);
  PDK_CALL(pdk_particles_field_info(p, name, &type, &num_comp));
  PDK_CHECK(!strchr(name, '/') && strcmp(name, "."), ctx, PDK_ERR_ARG,
            "field name '%s' cannot be stored in a checkpoint (it contains '/' or is '.')", name);
  hsize_t dims[2] = {(hsize_t)num_comp, (hsize_t)n}, count[2] = {1, (hsize_t)n},
          mdims[1] = {(hsize_t)n};
  PDK_H5_CALL_GOTO(ctx, space, H5Screate_simple(2, dims, NULL));
  PDK_H5_CALL_GOTO(ctx, mspace, H5Screate_simple(1, mdims, NULL));
  PDK_H5_CALL_GOTO(
      ctx, d,
      H5Dcreate2(g, name, pdk_h5_file_type(type), space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  PDK_CALL_GOTO(pdk_h5_attr_write_i64(ctx, d, "type", (int64_t)type));
  PDK_CALL_GOTO(pdk_h5_attr_write_i64(ctx, d, "components", num_comp));
  for (int c = 0; c < num_comp; ++c) {
    hsize_t start[2] = {(hsize_t)c, 0};
    PDK_H5_CALL_GOTO(ctx, st, H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL));
    PDK_H5_CALL_GOTO(ctx, st,
                     H5Dwrite(d, pdk_h5_mem_type(type), mspace, space, H5P_DEFAULT,
                              pdk_particles_field_data(p, name, c)));
  }
cleanup:
  if (d >= 0) H5Dclose(d);
  if (mspace >= 0) H5Sclose(mspace);
  if (space >= 0) H5Sclose(space);
  return err;
}

int pdk_checkpoint_write(pdk_ctx *ctx, const char *path, pdk_explicit *e, const char *scene_text) {
  int err = PDK_SUCCESS;
  hid_t file = -1, g = -1, fcpl = -1;
  herr_t fst;
  char *part = NULL;
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CHECK(path && path[0], ctx, PDK_ERR_ARG, "no checkpoint path given");
  PDK_CHECK(e, ctx, PDK_ERR_ARG, "no solver given to checkpoint");
  if (pdk_comm_rank() != 0) return PDK_SUCCESS; /* several ranks: rank 0 writes (same state) */
  pdk_model *m = pdk_explicit_model(e);
  pdk_particles *p = pdk_model_particles(m);
  const pdk_index n = pdk_particles_count(p);
  const pdk_bond_index nb = pdk_families_num_bonds(pdk_model_families(m));
  part = pdk_str_printf("%s.part", path);
  PDK_CHECK(part, ctx, PDK_ERR_MEMORY, "out of memory");
  PDK_H5_CALL_GOTO(ctx, fcpl, H5Pcreate(H5P_FILE_CREATE));
  PDK_H5_CALL_GOTO(ctx, fst, H5Pset_userblock(fcpl, CKPT_USERBLOCK)); /* the checksum's place */
  PDK_CALL_GOTO(pdk_h5_file_create_with(ctx, part, fcpl, &file));
  PDK_CALL_GOTO(pdk_h5_write_provenance(ctx, file, CKPT_KIND));
  PDK_CALL_GOTO(pdk_h5_attr_write_i64(ctx, file, "format", CKPT_FORMAT));
  PDK_CALL_GOTO(pdk_h5_attr_write_i64(ctx, file, "dimension", pdk_particles_dim(p)));
  PDK_CALL_GOTO(pdk_h5_attr_write_i64(ctx, file, "num_particles", n));
  PDK_CALL_GOTO(pdk_h5_attr_write_i64(ctx, file, "num_bonds", nb));
  PDK_CALL_GOTO(pdk_h5_attr_write_string(ctx, file, "model_kind",
                                         pdk_model_kind_name(pdk_model_opts_get(m)->kind)));
  if (scene_text) PDK_CALL_GOTO(pdk_h5_text_write(ctx, file, "scene", scene_text));

  PDK_H5_CALL_GOTO(ctx, g, H5Gcreate2(file, "solver", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  {
    pdk_state st = pdk_state_of(ctx, g, "solver", part);
    PDK_CALL_GOTO(pdk_explicit_state_save(e, &st));
  }
  H5Gclose(g);
  g = -1;

  PDK_H5_CALL_GOTO(ctx, g, H5Gcreate2(file, "model", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  {
    pdk_state st = pdk_state_of(ctx, g, "model", part);
    PDK_CALL_GOTO(pdk_model_state_save(m, &st));
  }
  H5Gclose(g);
  g = -1;

  PDK_H5_CALL_GOTO(ctx, g, H5Gcreate2(file, "fields", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  for (int k = 0; k < pdk_particles_num_fields(p); ++k)
    PDK_CALL_GOTO(write_field(ctx, g, p, pdk_particles_field_name(p, k)));
  H5Gclose(g);
  g = -1;
  {
    hid_t closing = file;
    file = -1;
    PDK_CALL_GOTO(pdk_h5_file_close(ctx, closing, part)); /* a failed write is reported here */
  }
  PDK_CALL_GOTO(seal_checkpoint(ctx, part)); /* the checksum of the closed file */
  PDK_CALL_GOTO(pdk_file_commit(ctx, part, path));
cleanup:
  if (fcpl >= 0) H5Pclose(fcpl);
  if (g >= 0) H5Gclose(g);
  if (file >= 0 && err && pdk_h5_file_error(file)) err = pdk_h5_file_check(ctx, file, part);
  if (file >= 0) pdk_h5_file_close(NULL, file, part);
  if (err && part) pdk_file_remove(part);
  free(part);
  return err;
}

/* ---- read -------------------------------------------------------------------------------------
 */

/* Where the file at `path` carries the HDF5 signature (offset 0, 512, 1024, ...: after a user
 * block), -2 when nowhere, -1 (errno set) when it cannot be read. */
static long hdf5_signature_at(const char *path) {
  static const unsigned char sig[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  long at = -2;
  for (long off = 0; at < 0; off = off ? 2 * off : 512) {
    unsigned char buf[8];
    if (fseek(f, off, SEEK_SET) != 0 || fread(buf, 1, 8, f) != 8) break;
    if (!memcmp(buf, sig, 8)) at = off;
  }
  const int bad = ferror(f);
  const int saved = errno;
  fclose(f);
  errno = saved;
  return bad && at < 0 ? -1 : at;
}

/* Opens a checkpoint and checks that it is one, intact (its checksum, verified before HDF5 reads
 * it) and of this format. Every refusal is one line that names the file. */
static int open_checkpoint(pdk_ctx *ctx, const char *path, hid_t *out) {
  int err = PDK_SUCCESS;
  hid_t file = -1;
  char *kind = NULL;
  int sealed = 0;
  int64_t format = 0;
  struct stat sb;
  *out = -1;
  PDK_CHECK(path && path[0], ctx, PDK_ERR_ARG, "no checkpoint path given");
  if (stat(path, &sb) != 0) {
    PDK_CHECK(errno != ENOENT, ctx, PDK_ERR_IO, "checkpoint '%s' does not exist", path);
    PDK_CHECK(0, ctx, PDK_ERR_IO, "cannot read the checkpoint '%s': %s", path, strerror(errno));
  }
  PDK_CHECK(!S_ISDIR(sb.st_mode), ctx, PDK_ERR_IO,
            "'%s' is a folder, not a checkpoint (a run writes <dir>/<name>_checkpoint.h5)", path);
  const long sig = hdf5_signature_at(path);
  PDK_CHECK(sig != -1, ctx, PDK_ERR_IO, "cannot read the checkpoint '%s': %s", path,
            strerror(errno));
  PDK_CHECK(sig >= 0, ctx, PDK_ERR_IO,
            "'%s' is not a pdk checkpoint: it is not an HDF5 file (a run writes its checkpoint as "
            "<dir>/<name>_checkpoint.h5)",
            path);
  if (sig == CKPT_USERBLOCK) PDK_CALL(verify_seal(ctx, path, &sealed));
  file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) {
    H5Eclear2(H5E_DEFAULT);
    PDK_CHECK(0, ctx, PDK_ERR_IO,
              "checkpoint '%s' is damaged: HDF5 cannot open it (a truncated or overwritten "
              "file); restart from another checkpoint or run the scene again",
              path);
  }
  PDK_CHECK_GOTO(pdk_h5_attr_exists(file, "kind"), ctx, PDK_ERR_IO,
                 "'%s' is an HDF5 file but not a pdk checkpoint (no 'kind' attribute)", path);
  if (pdk_h5_attr_read_string(ctx, file, "kind", &kind)) {
    H5Eclear2(H5E_DEFAULT);
    PDK_CHECK_GOTO(0, ctx, PDK_ERR_IO,
                   "'%s' is an HDF5 file but not a pdk checkpoint (its 'kind' is not a string)",
                   path);
  }
  PDK_CHECK_GOTO(!strcmp(kind, CKPT_KIND), ctx, PDK_ERR_IO,
                 "'%s' is a '%s' file, not a pdk checkpoint%s", path, kind,
                 strcmp(kind, "pdk output") ? ""
                                            : " (a run writes its checkpoint beside its output, "
                                              "as <name>_checkpoint.h5)");
  if (pdk_h5_attr_read_i64(ctx, file, "format", &format)) {
    H5Eclear2(H5E_DEFAULT);
    PDK_CHECK_GOTO(0, ctx, PDK_ERR_IO, "checkpoint '%s' is damaged: its 'format' cannot be read",
                   path);
  }
  PDK_CHECK_GOTO(format != 1, ctx, PDK_ERR_UNSUPPORTED,
                 "checkpoint '%s' was written by an earlier pdk (format 1, without a checksum), "
                 "so its data cannot be verified, and this pdk reads format %d only: finish that "
                 "run with the pdk that wrote it, or run the scene again from the start",
                 path, CKPT_FORMAT);
  PDK_CHECK_GOTO(format == CKPT_FORMAT, ctx, PDK_ERR_UNSUPPORTED,
                 "checkpoint '%s' has format %lld; this pdk reads format %d", path,
                 (long long)format, CKPT_FORMAT);
  PDK_CHECK_GOTO(sealed, ctx, PDK_ERR_IO,
                 "checkpoint '%s' is damaged: its checksum header (the first %d bytes) is "
                 "missing; restart from another checkpoint or run the scene again",
                 path, CKPT_USERBLOCK);
  *out = file;
  file = -1;
cleanup:
  free(kind);
  if (file >= 0) H5Fclose(file);
  return err;
}

int pdk_checkpoint_info(pdk_ctx *ctx, const char *path, long *step, double *time,
                        char **scene_text) {
  int err = PDK_SUCCESS;
  hid_t file = -1, g = -1;
  if (scene_text) *scene_text = NULL;
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CALL(open_checkpoint(ctx, path, &file));
  PDK_H5_CALL_GOTO(ctx, g, H5Gopen2(file, "solver", H5P_DEFAULT));
  if (step) {
    int64_t s;
    PDK_CALL_GOTO(pdk_h5_attr_read_i64(ctx, g, "step", &s));
    *step = (long)s;
  }
  if (time) PDK_CALL_GOTO(pdk_h5_attr_read_f64(ctx, g, "time", time));
  if (scene_text) PDK_CALL_GOTO(pdk_h5_text_read(ctx, file, "scene", scene_text));
cleanup:
  if (g >= 0) H5Gclose(g);
  H5Fclose(file);
  return err;
}

/* The error for a checkpoint that does not fit the simulation (pdk_state_mismatch's message). */
static int ckpt_mismatch(pdk_ctx *ctx, const char *where, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static int ckpt_mismatch(pdk_ctx *ctx, const char *where, const char *path, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  const int err = pdk_state_mismatch_v(ctx, where, path, fmt, ap);
  va_end(ap);
  return err;
}
#define CKPT_MISMATCH(ctx, path, ...)                                                              \
  do {                                                                                             \
    err = ckpt_mismatch((ctx), __func__, (path), __VA_ARGS__);                                     \
    goto cleanup;                                                                                  \
  } while (0)

/* Shape of /fields/<name>: type, components and the dataset's dims; *found = 0 when absent. */
static int field_shape(pdk_ctx *ctx, hid_t g, const char *name, int *found, pdk_type *type,
                       int *num_comp, hsize_t dims[2]) {
  int err = PDK_SUCCESS;
  hid_t d = -1, space = -1;
  int64_t t = -1, nc = 0;
  *found = H5Lexists(g, name, H5P_DEFAULT) > 0;
  if (!*found) return PDK_SUCCESS;
  PDK_H5_CALL_GOTO(ctx, d, H5Dopen2(g, name, H5P_DEFAULT));
  PDK_CALL_GOTO(pdk_h5_attr_read_i64(ctx, d, "type", &t));
  PDK_CALL_GOTO(pdk_h5_attr_read_i64(ctx, d, "components", &nc));
  PDK_H5_CALL_GOTO(ctx, space, H5Dget_space(d));
  dims[0] = dims[1] = 0;
  PDK_CHECK_GOTO(H5Sget_simple_extent_ndims(space) == 2, ctx, PDK_ERR_IO,
                 "checkpoint field '%s' is not a 2-D dataset", name);
  H5Sget_simple_extent_dims(space, dims, NULL);
  PDK_CHECK_GOTO(pdk_type_size((pdk_type)t) > 0 && t >= 0 && t <= PDK_U8 && nc >= 1 && nc <= 9 &&
                     dims[0] == (hsize_t)nc,
                 ctx, PDK_ERR_IO,
                 "checkpoint field '%s' has a bad type %lld or component count %lld", name,
                 (long long)t, (long long)nc);
  *type = (pdk_type)t;
  *num_comp = (int)nc;
cleanup:
  if (space >= 0) H5Sclose(space);
  if (d >= 0) H5Dclose(d);
  return err;
}

/* Reads component c of /fields/<name> (n entries) into dst, in memory type `type`. */
static int read_component(pdk_ctx *ctx, hid_t g, const char *name, pdk_type type, int c, hsize_t n,
                          void *dst) {
  const hsize_t start[2] = {(hsize_t)c, 0}, count[2] = {1, n};
  return pdk_h5_read_block(ctx, g, name, pdk_h5_mem_type(type), 2, start, count, dst);
}

/* Particle geometry that must match bit for bit: the checkpoint's id, X and volume against p's. */
static int check_geometry(pdk_ctx *ctx, const char *path, hid_t g, pdk_particles *p) {
  static const char *const names[3] = {"id", "X", "volume"};
  int err = PDK_SUCCESS;
  const pdk_index n = pdk_particles_count(p);
  unsigned char *buf = malloc((size_t)n * 8);
  PDK_CHECK(buf, ctx, PDK_ERR_MEMORY, "out of memory checking a checkpoint");
  for (int k = 0; k < 3; ++k) {
    pdk_type type;
    int num_comp;
    PDK_CALL_GOTO(pdk_particles_field_info(p, names[k], &type, &num_comp));
    size_t elem = pdk_type_size(type);
    for (int c = 0; c < num_comp; ++c) {
      const unsigned char *mine = pdk_particles_field_data(p, names[k], c);
      PDK_CALL_GOTO(read_component(ctx, g, names[k], type, c, (hsize_t)n, buf));
      if (!memcmp(buf, mine, (size_t)n * elem)) continue;
      pdk_index i = 0;
      while (i < n && !memcmp(buf + (size_t)i * elem, mine + (size_t)i * elem, elem))
        ++i;
      if (type == PDK_I64)
        CKPT_MISMATCH(ctx, path, "particle %d has id %lld in the checkpoint and %lld here", (int)i,
                      (long long)((int64_t *)buf)[i], (long long)((const int64_t *)mine)[i]);
      CKPT_MISMATCH(ctx, path,
                    "particle %d (id %lld) has %s[%d] = %.17g in the checkpoint and %.17g here",
                    (int)i, (long long)pdk_particles_id(p)[i], names[k], c, ((double *)buf)[i],
                    ((const double *)mine)[i]);
    }
  }
cleanup:
  free(buf);
  return err;
}

int pdk_checkpoint_read(pdk_ctx *ctx, const char *path, pdk_explicit *e) {
  return pdk_checkpoint_restore(ctx, path, e, NULL, NULL, NULL);
}

int pdk_checkpoint_restore(pdk_ctx *ctx, const char *path, pdk_explicit *e,
                           int (*decide)(void *arg, const pdk_checkpoint_solver *cs), void *arg,
                           char **scene_text) {
  int err = PDK_SUCCESS;
  hid_t file = -1, gs = -1, gm = -1, gf = -1;
  char *model_kind = NULL;
  char(*extra)[PDK_FIELD_NAME_MAX] = NULL; /* checkpoint fields the simulation lacks */
  int num_extra = 0;
  if (scene_text) *scene_text = NULL;
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CHECK(e, ctx, PDK_ERR_ARG, "no solver given to restore into");
  pdk_model *m = pdk_explicit_model(e);
  pdk_particles *p = pdk_model_particles(m);
  const pdk_index n = pdk_particles_count(p);
  const int dim = pdk_particles_dim(p);
  const pdk_bond_index nb = pdk_families_num_bonds(pdk_model_families(m));
  const char *kind = pdk_model_kind_name(pdk_model_opts_get(m)->kind);
  PDK_CALL(open_checkpoint(ctx, path, &file));

  /* 1. Check everything; change nothing. */
  int64_t v;
  PDK_CALL_GOTO(pdk_h5_attr_read_i64(ctx, file, "dimension", &v));
  if (v != dim)
    CKPT_MISMATCH(ctx, path, "it is %lld-D, this simulation is %d-D", (long long)v, dim);
  PDK_CALL_GOTO(pdk_h5_attr_read_i64(ctx, file, "num_particles", &v));
  if (v != n)
    CKPT_MISMATCH(ctx, path, "it has %lld particles, this simulation has %d", (long long)v, (int)n);
  PDK_CALL_GOTO(pdk_h5_attr_read_i64(ctx, file, "num_bonds", &v));
  if (v != nb)
    CKPT_MISMATCH(ctx, path,
                  "it has %lld bonds, this simulation has %lld (a different horizon, "
                  "lattice or pre-crack)",
                  (long long)v, (long long)nb);
  PDK_CALL_GOTO(pdk_h5_attr_read_string(ctx, file, "model_kind", &model_kind));
  if (strcmp(model_kind, kind))
    CKPT_MISMATCH(ctx, path, "its model is '%s', this simulation's is '%s'", model_kind, kind);
  PDK_H5_CALL_GOTO(ctx, gm, H5Gopen2(file, "model", H5P_DEFAULT));
  pdk_state model_state = pdk_state_of(ctx, gm, "model", path);
  PDK_CALL_GOTO(pdk_model_state_check(m, &model_state));

  PDK_H5_CALL_GOTO(ctx, gf, H5Gopen2(file, "fields", H5P_DEFAULT));
  for (int k = 0; k < pdk_particles_num_fields(p); ++k) {
    const char *name = pdk_particles_field_name(p, k);
    pdk_type type, ctype;
    int num_comp, cnum_comp, found;
    hsize_t dims[2];
    PDK_CALL_GOTO(pdk_particles_field_info(p, name, &type, &num_comp));
    PDK_CALL_GOTO(field_shape(ctx, gf, name, &found, &ctype, &cnum_comp, dims));
    if (!found) CKPT_MISMATCH(ctx, path, "it has no particle field '%s'", name);
    if (ctype != type || cnum_comp != num_comp || dims[1] != (hsize_t)n)
      CKPT_MISMATCH(ctx, path,
                    "field '%s' is type %d x %d components of %llu particles there, "
                    "type %d x %d here",
                    name, (int)ctype, cnum_comp, (unsigned long long)dims[1], (int)type, num_comp);
  }
  {
    H5G_info_t info;
    herr_t st;
    PDK_H5_CALL_GOTO(ctx, st, H5Gget_info(gf, &info));
    extra = calloc((size_t)info.nlinks + 1, sizeof *extra);
    PDK_CHECK_GOTO(extra, ctx, PDK_ERR_MEMORY, "out of memory");
    for (hsize_t k = 0; k < info.nlinks; ++k) {
      char name[PDK_FIELD_NAME_MAX];
      ssize_t len = H5Lget_name_by_idx(gf, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof name,
                                       H5P_DEFAULT);
      PDK_CHECK_GOTO(len > 0 && len < PDK_FIELD_NAME_MAX, ctx, PDK_ERR_IO,
                     "checkpoint '%s': bad field name at index %llu", path, (unsigned long long)k);
      if (pdk_particles_field_exists(p, name)) continue;
      pdk_type type;
      int num_comp, found;
      hsize_t dims[2];
      PDK_CALL_GOTO(field_shape(ctx, gf, name, &found, &type, &num_comp, dims));
      PDK_CHECK_GOTO(dims[1] == (hsize_t)n, ctx, PDK_ERR_IO,
                     "checkpoint field '%s' has %llu entries, "
                     "expected %d",
                     name, (unsigned long long)dims[1], (int)n);
      strcpy(extra[num_extra++], name);
    }
  }
  PDK_CALL_GOTO(check_geometry(ctx, path, gf, p));
  PDK_H5_CALL_GOTO(ctx, gs, H5Gopen2(file, "solver", H5P_DEFAULT));
  pdk_state solver_state = pdk_state_of(ctx, gs, "solver", path);
  if (decide) {
    pdk_checkpoint_solver cs;
    PDK_CALL_GOTO(pdk_explicit_state_info(&solver_state, &cs));
    PDK_CALL_GOTO(decide(arg, &cs));
  }
  if (scene_text) PDK_CALL_GOTO(pdk_h5_text_read(ctx, file, "scene", scene_text));

  /* 2. Restore. */
  for (int k = 0; k < num_extra; ++k) {
    pdk_type type;
    int num_comp, found;
    hsize_t dims[2];
    PDK_CALL_GOTO(field_shape(ctx, gf, extra[k], &found, &type, &num_comp, dims));
    PDK_CALL_GOTO(pdk_particles_field_add(p, extra[k], type, num_comp));
  }
  for (int k = 0; k < pdk_particles_num_fields(p); ++k) {
    const char *name = pdk_particles_field_name(p, k);
    pdk_type type;
    int num_comp;
    PDK_CALL_GOTO(pdk_particles_field_info(p, name, &type, &num_comp));
    for (int c = 0; c < num_comp; ++c)
      PDK_CALL_GOTO(
          read_component(ctx, gf, name, type, c, (hsize_t)n, pdk_particles_field_data(p, name, c)));
  }
  PDK_CALL_GOTO(pdk_model_state_load(m, &model_state));
  PDK_CALL_GOTO(pdk_explicit_state_load(e, &solver_state));
cleanup:
  if (err && scene_text) {
    free(*scene_text);
    *scene_text = NULL;
  }
  free(extra);
  free(model_kind);
  if (gs >= 0) H5Gclose(gs);
  if (gf >= 0) H5Gclose(gf);
  if (gm >= 0) H5Gclose(gm);
  H5Fclose(file);
  return err;
}
