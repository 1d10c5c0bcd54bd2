/* Checkpoints carry a checksum that the reader verifies, on the raw bytes, before HDF5 or the
 * restore reads anything.
 *   - a checkpoint of a correspondence bar with broken bonds starts with its 512-byte header
 *     "pdk checkpoint\nchecksum fnv1a64x:<16 hex>\nsize <bytes>\n" (the HDF5 user block);
 *   - one flipped byte in the data of Kinv, v, x or the bond state is refused (PDK_ERR_IO) with a
 *     message naming the file and saying it is damaged, and the simulation is left as built;
 *   - 400 single-byte flips spread over the whole file, header included: every one is refused,
 *     with one clean line (before, 2 of 33 flips restarted silently with another result; and HDF5
 *     1.10 can crash closing a file whose object header a flip damaged, so HDF5 must not see
 *     them);
 *   - a missing file, a folder, a YAML file, an HDF5 file that is not a checkpoint, a truncated
 *     checkpoint, a format 1 checkpoint (earlier pdk, no checksum) and a format 2 file without
 *     the header are refused with one line that names the file and carries no HDF5 error stack.
 * labels: unit */
#define _DEFAULT_SOURCE /* rmdir */
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pdk/output.h"
#include "test_util.h"

#define CKPT "t186_checkpoint.h5"

typedef struct sim {
  pdk_particles *p;
  pdk_families *fam;
  pdk_model *m;
  pdk_explicit *e;
} sim;

static pdk_bc bcs[2];

/* A 2-D correspondence bar, 20 x 6 cells of 1 mm, pulled apart fast enough to break bonds. */
static void build(pdk_ctx *ctx, sim *s) {
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = 1e-3;
  lo.hi[0] = 20e-3;
  lo.hi[1] = 6e-3;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &s->p));
  T_OK(ctx, pdk_particles_reorder_morton(s->p, 3.015e-3, NULL));
  double a[3] = {-1, -1, -1}, b[3] = {2.5e-3, 1, 1}, c[3] = {17.5e-3, -1, -1}, d[3] = {1, 1, 1};
  pdk_region left = pdk_region_box(a, b), right = pdk_region_box(c, d);
  T_OK(ctx, pdk_particles_set_define(s->p, "left", &left, NULL));
  T_OK(ctx, pdk_particles_set_define(s->p, "right", &right, NULL));
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 3.015e-3;
  T_OK(ctx, pdk_families_build(s->p, &fo, &s->fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_CORRESPONDENCE;
  mo.bulk_modulus = 1.6e11;
  mo.shear_modulus = 8e10;
  mo.density = 8000;
  mo.critical_stretch = 1e-3;
  mo.stabilization = PDK_STAB_SILLING;
  T_OK(ctx, pdk_model_create(s->p, s->fam, &mo, &s->m));
  memset(bcs, 0, sizeof bcs);
  bcs[0].kind = PDK_BC_DISPLACEMENT;
  bcs[0].set = "set:left";
  bcs[0].components = 3;
  bcs[1].kind = PDK_BC_VELOCITY;
  bcs[1].set = "set:right";
  bcs[1].components = 1;
  bcs[1].value[0] = (pdk_tfun){PDK_TFUN_CONSTANT, 20.0, 0.0};
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = bcs;
  eo.num_bcs = 2;
  eo.dt = 1.2e-7;
  T_OK(ctx, pdk_explicit_create(s->m, &eo, &s->e));
}

static void destroy(sim *s) {
  pdk_explicit_destroy(&s->e);
  pdk_model_destroy(&s->m);
  pdk_families_destroy(&s->fam);
  pdk_particles_destroy(&s->p);
}

/* Everything a restore sets: every field's bytes, the bond state, step, time, dt. */
static unsigned char *state(sim *s, size_t *bytes) {
  const pdk_index n = pdk_particles_count(s->p);
  const pdk_bond_index nb = pdk_families_num_bonds(s->fam);
  size_t len = (size_t)nb + 3 * sizeof(double) + sizeof(pdk_bond_index), pos = 0;
  for (int k = 0; k < pdk_particles_num_fields(s->p); ++k) {
    pdk_type t;
    int nc;
    T_OK(pdk_particles_ctx(s->p),
         pdk_particles_field_info(s->p, pdk_particles_field_name(s->p, k), &t, &nc));
    len += (size_t)nc * (size_t)n * pdk_type_size(t);
  }
  unsigned char *out = malloc(len);
  T_ASSERT(out, "out of memory");
  for (int k = 0; k < pdk_particles_num_fields(s->p); ++k) {
    const char *name = pdk_particles_field_name(s->p, k);
    pdk_type t;
    int nc;
    pdk_particles_field_info(s->p, name, &t, &nc);
    for (int c = 0; c < nc; ++c) {
      memcpy(out + pos, pdk_particles_field_data(s->p, name, c), (size_t)n * pdk_type_size(t));
      pos += (size_t)n * pdk_type_size(t);
    }
  }
  memcpy(out + pos, pdk_model_bond_alive(s->m), (size_t)nb);
  pos += (size_t)nb;
  const double sc[3] = {(double)pdk_explicit_step(s->e), pdk_explicit_time(s->e),
                        pdk_explicit_dt(s->e)};
  memcpy(out + pos, sc, sizeof sc);
  pos += sizeof sc;
  const pdk_bond_index broken = pdk_model_num_broken(s->m);
  memcpy(out + pos, &broken, sizeof broken);
  pos += sizeof broken;
  *bytes = pos;
  return out;
}

static void flip(const char *path, long off) {
  FILE *f = fopen(path, "r+b");
  T_ASSERT(f && fseek(f, off, SEEK_SET) == 0, "cannot open %s at %ld", path, off);
  int c = fgetc(f);
  T_ASSERT(c != EOF, "%s has no byte %ld", path, off);
  fseek(f, off, SEEK_SET);
  fputc(c ^ 0x10, f);
  T_ASSERT(fclose(f) == 0, "cannot write %s", path);
}

/* Where the data of dataset `name` lies in the file, and its size. */
static void data_extent(const char *path, const char *name, long *off, long *size) {
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  T_ASSERT(d >= 0, "%s has no %s", path, name);
  haddr_t a = H5Dget_offset(d);
  T_ASSERT(a != HADDR_UNDEF, "%s is not contiguous", name);
  *off = (long)a;
  *size = (long)H5Dget_storage_size(d);
  H5Dclose(d);
  H5Fclose(f);
}

/* The message is one line, names the file, and carries no raw HDF5 error stack. */
static void assert_clean_message(pdk_ctx *ctx, const char *path, const char *what) {
  const char *msg = pdk_ctx_error_message(ctx);
  T_ASSERT(strstr(msg, path), "%s: the message does not name '%s': %s", what, path, msg);
  T_ASSERT(!strchr(msg, '\n'), "%s: the message is not one line: %s", what, msg);
  T_ASSERT(!strstr(msg, "HDF5 call") && !strstr(msg, "H5F") && !strstr(msg, "H5D") &&
               !strstr(msg, "HDF5-DIAG"),
           "%s: the message carries an HDF5 error stack: %s", what, msg);
}

static long file_size(const char *path) {
  struct stat sb;
  T_ASSERT(stat(path, &sb) == 0, "stat %s", path);
  return (long)sb.st_size;
}

static void copy_prefix(const char *from, const char *to, long bytes) {
  FILE *f = fopen(from, "rb"), *g = fopen(to, "wb");
  T_ASSERT(f && g, "copy %s", from);
  for (long k = 0; k < bytes; ++k) {
    int c = fgetc(f);
    if (c == EOF) break;
    fputc(c, g);
  }
  fclose(f);
  T_ASSERT(fclose(g) == 0, "write %s", to);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  sim s;
  build(ctx, &s);
  T_OK(ctx, pdk_explicit_run(s.e, 60, NULL));
  T_ASSERT(pdk_model_num_broken(s.m) > 0, "no bond broke before the checkpoint");
  T_OK(ctx, pdk_checkpoint_write(ctx, CKPT, s.e, "name: t186\n"));
  destroy(&s);
  {
    char head[513] = "";
    FILE *f = fopen(CKPT, "rb");
    T_ASSERT(f && fread(head, 1, 512, f) == 512, "cannot read the checkpoint's header");
    fclose(f);
    char sum[17] = "";
    long size = 0;
    T_ASSERT(sscanf(head, "pdk checkpoint\nchecksum fnv1a64x:%16[0-9a-f]\nsize %ld\n", sum,
                    &size) == 2 &&
                 strlen(sum) == 16 && size == file_size(CKPT),
             "the checkpoint's header is '%s'", head);
  }

  /* the intact file's restore */
  size_t ref_bytes, bytes;
  build(ctx, &s);
  T_OK(ctx, pdk_checkpoint_read(ctx, CKPT, s.e));
  unsigned char *ref = state(&s, &ref_bytes);
  destroy(&s);
  T_ASSERT(ref_bytes > 0, "empty state");
  build(ctx, &s);
  unsigned char *fresh = state(&s, &bytes); /* as built: what a refused restore leaves */
  destroy(&s);

  /* one byte of a dataset's data */
  static const char *const targets[4] = {"/fields/Kinv", "/fields/v", "/fields/x",
                                         "/model/bond_alive"};
  for (int k = 0; k < 4; ++k) {
    long off, size;
    data_extent(CKPT, targets[k], &off, &size);
    const long at = off + size / 2 + k;
    flip(CKPT, at);
    build(ctx, &s);
    pdk_ctx_error_clear(ctx);
    const int err = pdk_checkpoint_read(ctx, CKPT, s.e);
    T_ASSERT(err == PDK_ERR_IO && strstr(pdk_ctx_error_message(ctx), "damaged"),
             "a flipped byte in %s (file offset %ld) was not refused as damaged: error %d, '%s'",
             targets[k], at, err, pdk_ctx_error_message(ctx));
    assert_clean_message(ctx, CKPT, targets[k]);
    unsigned char *now = state(&s, &bytes);
    T_ASSERT(bytes == ref_bytes && !memcmp(now, fresh, bytes),
             "a refused restore (%s) changed the simulation", targets[k]);
    free(now);
    destroy(&s);
    flip(CKPT, at); /* back */
  }

  /* single-byte flips over the whole file: every one refused */
  const long total = file_size(CKPT);
  int refused = 0;
  for (int k = 0; k < 400; ++k) {
    const long at = (long)((double)k * (double)total / 400.0) + k % 7;
    if (at >= total) continue;
    flip(CKPT, at);
    build(ctx, &s);
    pdk_ctx_error_clear(ctx);
    const int err = pdk_checkpoint_read(ctx, CKPT, s.e);
    T_ASSERT(err == PDK_ERR_IO && strstr(pdk_ctx_error_message(ctx), "damaged"),
             "a flipped byte at offset %ld of %ld was not refused as damaged: error %d, '%s'", at,
             total, err, pdk_ctx_error_message(ctx));
    assert_clean_message(ctx, CKPT, "a flipped byte");
    unsigned char *now = state(&s, &bytes);
    T_ASSERT(bytes == ref_bytes && !memcmp(now, fresh, bytes),
             "a refused restore (offset %ld) changed the simulation", at);
    free(now);
    ++refused;
    destroy(&s);
    flip(CKPT, at);
  }
  T_ASSERT(refused == 400, "%d flips tried", refused);
  /* the intact file still restores the reference state */
  build(ctx, &s);
  T_OK(ctx, pdk_checkpoint_read(ctx, CKPT, s.e));
  unsigned char *again = state(&s, &bytes);
  T_ASSERT(bytes == ref_bytes && !memcmp(again, ref, bytes), "the intact file restores another "
                                                             "state");
  free(again);
  destroy(&s);

  /* files that are not intact checkpoints: one clean line each */
  build(ctx, &s);
  T_FAILS(ctx, pdk_checkpoint_read(ctx, "t186_no_such_file.h5", s.e), PDK_ERR_IO, "does not exist");
  assert_clean_message(ctx, "t186_no_such_file.h5", "a missing file");
  mkdir("t186_folder.h5", 0777);
  T_FAILS(ctx, pdk_checkpoint_read(ctx, "t186_folder.h5", s.e), PDK_ERR_IO, "folder");
  assert_clean_message(ctx, "t186_folder.h5", "a folder");
  FILE *y = fopen("t186_scene.yaml", "w");
  fputs("name: bar\ndimension: 2\n", y);
  fclose(y);
  T_FAILS(ctx, pdk_checkpoint_read(ctx, "t186_scene.yaml", s.e), PDK_ERR_IO, "not an HDF5 file");
  assert_clean_message(ctx, "t186_scene.yaml", "a YAML file");
  hid_t f = H5Fcreate("t186_other.h5", H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Fclose(f);
  T_FAILS(ctx, pdk_checkpoint_read(ctx, "t186_other.h5", s.e), PDK_ERR_IO, "not a pdk checkpoint");
  assert_clean_message(ctx, "t186_other.h5", "an HDF5 file that is not a checkpoint");
  copy_prefix(CKPT, "t186_truncated.h5", total / 2);
  T_FAILS(ctx, pdk_checkpoint_read(ctx, "t186_truncated.h5", s.e), PDK_ERR_IO, "truncated");
  assert_clean_message(ctx, "t186_truncated.h5", "a truncated checkpoint");
  /* a pdk checkpoint's attributes without the header: format 1 (earlier pdk), format 2 */
  for (int format = 1; format <= 2; ++format) {
    const char *name = format == 1 ? "t186_format1.h5" : "t186_noheader.h5";
    f = H5Fcreate(name, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hid_t sp = H5Screate(H5S_SCALAR), t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, 15);
    hid_t a = H5Acreate2(f, "kind", t, sp, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, t, "pdk checkpoint");
    H5Aclose(a);
    const int64_t v = format;
    a = H5Acreate2(f, "format", H5T_STD_I64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, H5T_NATIVE_INT64, &v);
    H5Aclose(a);
    H5Tclose(t);
    H5Sclose(sp);
    H5Fclose(f);
    if (format == 1) {
      T_FAILS(ctx, pdk_checkpoint_read(ctx, name, s.e), PDK_ERR_UNSUPPORTED,
              "format 1, without a checksum");
    } else {
      T_FAILS(ctx, pdk_checkpoint_read(ctx, name, s.e), PDK_ERR_IO, "checksum header");
    }
    assert_clean_message(ctx, name, "a checkpoint without the checksum header");
  }
  /* the header zeroed: HDF5 reads the intact rest, which says it is a format 2 checkpoint */
  copy_prefix(CKPT, "t186_zeroed.h5", total);
  {
    FILE *z = fopen("t186_zeroed.h5", "r+b");
    static const char zeros[512];
    T_ASSERT(z && fwrite(zeros, 1, 512, z) == 512 && fclose(z) == 0, "cannot zero the header");
  }
  T_FAILS(ctx, pdk_checkpoint_read(ctx, "t186_zeroed.h5", s.e), PDK_ERR_IO,
          "checksum header (the first 512 bytes) is missing");
  assert_clean_message(ctx, "t186_zeroed.h5", "a zeroed header");
  /* info verifies too */
  long step = -1;
  T_FAILS(ctx, pdk_checkpoint_info(ctx, "t186_truncated.h5", &step, NULL, NULL), PDK_ERR_IO,
          "damaged");
  unsigned char *now = state(&s, &bytes);
  T_ASSERT(bytes == ref_bytes && !memcmp(now, fresh, bytes), "a refused restore changed the "
                                                             "simulation");
  free(now);
  destroy(&s);
  rmdir("t186_folder.h5");
  free(ref);
  free(fresh);
  pdk_ctx_destroy(&ctx);
  return 0;
}
