/* A write that fails (a full disk) at any point of an output run or of a checkpoint ends in an
 * I/O error that names the file and the reason, removes every file the run made, and leaves no
 * HDF5 file open; the process goes on and exits cleanly (HDF5 1.10 cannot close a file after a
 * failed metadata write: the half-closed file crashed its exit handler with SIGSEGV).
 * The k-th write through pdk's HDF5 driver fails (test hook pdk_h5_fault_write), for every k
 * from the first write to the last one of a whole run; the run after the last k succeeds.
 * Under AddressSanitizer this also checks the failure paths for invalid frees and leaks.
 * Test files go to ./t182_out.
 * labels: unit */
#include "output_util.h"

#include <hdf5.h>

#include "core/h5io.h"

#define DIR_OUT "t182_out"

/* Open, write, close(1) of an output called "run"; the first failing call's code. */
static int output_run(pdk_ctx *ctx, pdk_particles *p) {
  pdk_output_opts oo = ou_opts(DIR_OUT, "run");
  oo.plot = 0; /* the plot reads the files pdk already closed: not this test's subject */
  pdk_output *o = NULL;
  int err = pdk_output_open(ctx, &oo, p, &o);
  if (err) {
    T_ASSERT(!o, "a failed open returns no output");
    return err;
  }
  err = ou_write(o, p, 6, 1.0);
  if (err) {
    pdk_output_close(&o, 0);
    return err;
  }
  return pdk_output_close(&o, 1);
}

/* Checks the aftermath of a run whose k-th write failed: the error, an empty folder, no HDF5
 * file open. */
static void check_failed(pdk_ctx *ctx, int err, long k, const char *what, const char *file) {
  char list[4096];
  T_ASSERT(err == PDK_ERR_IO, "%s, write %ld failed: code %d, expected PDK_ERR_IO (message: %s)",
           what, k, err, pdk_ctx_error_message(ctx));
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "No space left on device") &&
               strstr(pdk_ctx_error_message(ctx), file),
           "%s, write %ld failed: the message names '%s' and the reason: %s", what, k, file,
           pdk_ctx_error_message(ctx));
  T_ASSERT(ou_list(DIR_OUT, list, sizeof list) == 0, "%s, write %ld failed: files left:\n%s", what,
           k, list);
  T_ASSERT(H5Fget_obj_count((hid_t)H5F_OBJ_ALL, H5F_OBJ_ALL) == 0,
           "%s, write %ld failed: %ld HDF5 objects still open", what, k,
           (long)H5Fget_obj_count((hid_t)H5F_OBJ_ALL, H5F_OBJ_ALL));
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  pdk_particles *p = ou_store(ctx);
  char list[4096];

  /* 1. The output. */
  long k = 1, writes = 0;
  for (;; ++k) {
    T_ASSERT(k < 100000, "no end to the output's writes");
    ou_clean(DIR_OUT);
    pdk_ctx_error_clear(ctx);
    pdk_h5_fault_write(k);
    const int err = output_run(ctx, p);
    const long seen = pdk_h5_fault_write(0);
    if (seen < k) { /* fewer than k writes: none failed */
      T_ASSERT(!err, "the output without a failed write: %s", pdk_ctx_error_message(ctx));
      T_ASSERT(ou_list(DIR_OUT, list, sizeof list) == 4 && ou_exists(DIR_OUT, "run.xmf"),
               "the whole output (.h5, .xmf, two CSVs):\n%s", list);
      writes = seen;
      break;
    }
    check_failed(ctx, err, k, "output", "run.h5.part");
  }
  T_ASSERT(writes >= 10, "an output run makes more than a few writes (%ld)", writes);

  /* 2. A checkpoint of a small PMB run. */
  pdk_families *fam = NULL;
  pdk_model *m = NULL;
  pdk_explicit *e = NULL;
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = 3.015e-3;
  T_OK(ctx, pdk_families_build(p, &fo, &fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = PDK_MODEL_PMB;
  mo.bulk_modulus = 1e9;
  mo.density = 8000;
  T_OK(ctx, pdk_model_create(p, fam, &mo, &m));
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  T_OK(ctx, pdk_explicit_create(m, &eo, &e));
  T_OK(ctx, pdk_explicit_run(e, 3, NULL));
  for (k = 1;; ++k) {
    T_ASSERT(k < 100000, "no end to the checkpoint's writes");
    ou_clean(DIR_OUT);
    pdk_ctx_error_clear(ctx);
    pdk_h5_fault_write(k);
    const int err = pdk_checkpoint_write(ctx, DIR_OUT "/ck.h5", e, "name: t182\n");
    const long seen = pdk_h5_fault_write(0);
    if (seen < k) {
      T_ASSERT(!err, "the checkpoint without a failed write: %s", pdk_ctx_error_message(ctx));
      T_ASSERT(ou_list(DIR_OUT, list, sizeof list) == 1 && ou_exists(DIR_OUT, "ck.h5"),
               "the checkpoint alone:\n%s", list);
      T_OK(ctx, pdk_checkpoint_read(ctx, DIR_OUT "/ck.h5", e));
      break;
    }
    check_failed(ctx, err, k, "checkpoint", "ck.h5.part");
  }
  T_ASSERT(k > 5, "a checkpoint makes more than a few writes (%ld)", k - 1);
  pdk_explicit_destroy(&e);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
