/* Foreign-library wrappers: a failing HDF5, hwloc, CHOLMOD, UMFPACK or libcyaml call becomes a
 * pdk error whose message names the foreign function and gives the library's own reason.
 * labels: unit */
#include <errno.h>
#include <hwloc.h>

#include "core/ext.h"
#include "test_util.h"

static int h5_open_missing(pdk_ctx *ctx) {
  int err = PDK_SUCCESS;
  hid_t f = -1;
  PDK_H5_CALL_GOTO(ctx, f, H5Fopen("/nonexistent/pdk/missing.h5", H5F_ACC_RDONLY, H5P_DEFAULT));
cleanup:
  if (f >= 0) H5Fclose(f);
  return err;
}

static int hwloc_bad_xml(pdk_ctx *ctx) {
  hwloc_topology_t topo;
  if (hwloc_topology_init(&topo) < 0) return -1;
  int err = PDK_SUCCESS;
  errno = 0;
  if (hwloc_topology_set_xml(topo, "/nonexistent/pdk/topo.xml") < 0 ||
      hwloc_topology_load(topo) < 0)
    err = pdk_ext_hwloc_fail(ctx, "hwloc_topology_set_xml/load", __func__, errno);
  hwloc_topology_destroy(topo);
  return err;
}

static int hwloc_bind_empty(pdk_ctx *ctx, hwloc_topology_t topo, hwloc_bitmap_t empty) {
  PDK_HWLOC_CALL(ctx, hwloc_set_cpubind(topo, empty, HWLOC_CPUBIND_THREAD));
  return PDK_SUCCESS;
}

static int cholmod_invalid(pdk_ctx *ctx) {
  int err = PDK_SUCCESS;
  cholmod_common cc;
  cholmod_start(&cc);
  cc.print = 0;
  cc.error_handler = NULL;
  cholmod_factor *L = NULL;
  cholmod_sparse *A = NULL; /* no matrix: CHOLMOD reports invalid input */
  PDK_CHOLMOD_CALL_GOTO(ctx, &cc, L = cholmod_analyze(A, &cc));
cleanup:
  cholmod_free_factor(&L, &cc);
  cholmod_free_sparse(&A, &cc);
  cholmod_finish(&cc);
  return err;
}

static int umfpack_singular(pdk_ctx *ctx) {
  int err = PDK_SUCCESS;
  /* [[1, 2], [2, 4]] in compressed columns: singular. */
  int Ap[] = {0, 2, 4}, Ai[] = {0, 1, 0, 1};
  double Ax[] = {1, 2, 2, 4};
  void *sym = NULL, *num = NULL;
  PDK_UMFPACK_CALL_GOTO(ctx, umfpack_di_symbolic(2, 2, Ap, Ai, Ax, &sym, NULL, NULL));
  PDK_UMFPACK_CALL_GOTO(ctx, umfpack_di_numeric(Ap, Ai, Ax, sym, &num, NULL, NULL));
cleanup:
  if (sym) umfpack_di_free_symbolic(&sym);
  if (num) umfpack_di_free_numeric(&num);
  return err;
}

typedef struct doc { int value; } doc;
static const cyaml_schema_field_t doc_fields[] = {
    CYAML_FIELD_INT("value", CYAML_FLAG_DEFAULT, doc, value), CYAML_FIELD_END};
static const cyaml_schema_value_t doc_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_POINTER, doc, doc_fields)};

static int cyaml_missing(pdk_ctx *ctx) {
  int err = PDK_SUCCESS;
  cyaml_config_t cfg = {.log_fn = NULL, .mem_fn = cyaml_mem, .log_level = CYAML_LOG_ERROR};
  doc *d = NULL;
  PDK_CYAML_CALL_GOTO(ctx, cyaml_load_file("/nonexistent/pdk/scene.yaml", &cfg, &doc_schema,
                                           (cyaml_data_t **)&d, NULL));
cleanup:
  if (d) cyaml_free(&cfg, &doc_schema, d, 0);
  return err;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);

  T_FAILS(ctx, h5_open_missing(ctx), PDK_ERR_EXTERNAL, "H5Fopen(\"/nonexistent/pdk/missing.h5\"");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "unable to open file") ||
               strstr(pdk_ctx_error_message(ctx), "H5F"), "HDF5 reason given: %s", pdk_ctx_error_message(ctx));
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "h5_open_missing"), "caller named");

  T_FAILS(ctx, hwloc_bad_xml(ctx), PDK_ERR_EXTERNAL, "hwloc call hwloc_topology_set_xml");
  hwloc_topology_t topo;
  T_ASSERT(hwloc_topology_init(&topo) == 0 && hwloc_topology_load(topo) == 0, "topology");
  hwloc_bitmap_t empty = hwloc_bitmap_alloc();
  T_FAILS(ctx, hwloc_bind_empty(ctx, topo, empty), PDK_ERR_EXTERNAL, "hwloc_set_cpubind(topo, empty");
  hwloc_bitmap_free(empty);
  hwloc_topology_destroy(topo);

  T_FAILS(ctx, cholmod_invalid(ctx), PDK_ERR_EXTERNAL, "CHOLMOD call L = cholmod_analyze(A, &cc) failed: invalid input");
  T_FAILS(ctx, umfpack_singular(ctx), PDK_ERR_EXTERNAL, "umfpack_di_numeric");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "singular"), "UMFPACK reason: %s", pdk_ctx_error_message(ctx));

  T_FAILS(ctx, cyaml_missing(ctx), PDK_ERR_EXTERNAL, "libcyaml call cyaml_load_file(");
  T_ASSERT(strstr(pdk_ctx_error_message(ctx), "failed: "), "cyaml reason: %s", pdk_ctx_error_message(ctx));
  pdk_ctx_destroy(&ctx);
  return 0;
}
