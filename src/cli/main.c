/* The pdk command: subcommand dispatch. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "pdk/pdk.h"

static const char *usage_main =
    "usage: pdk <command> [options]\n"
    "\n"
    "pdk: peridynamics solid mechanics with ductile fracture.\n"
    "\n"
    "commands:\n"
    "  run       run a scene: pdk run SCENE [-o DIR] [--threads N] [--set KEY=VALUE ...]\n"
    "  check     validate a scene without running it\n"
    "  info      print version, build flags, SIMD features, topology and thread binding\n"
    "\n"
    "options:\n"
    "  -h, --help     show this help (or `pdk <command> --help` for a command's)\n"
    "  -V, --version  print the version and exit\n"
    "\n"
    "environment:\n"
    "  PDK_NUM_THREADS  thread count (default: one per core)\n"
    "  PDK_BIND         core | none: bind one thread per core (default core)\n"
    "  PDK_KERNELS      ref | simd: force a kernel family (default: best for this CPU)\n";

static const char *usage_info =
    "usage: pdk info [--threads N]\n"
    "\n"
    "Prints the pdk version and build flags, the SIMD features found at run time, the hwloc\n"
    "topology (packages, cores, caches, NUMA nodes) and where each OpenMP thread is bound.\n"
    "\n"
    "options:\n"
    "  --threads N  use N threads (default: PDK_NUM_THREADS, else one per core)\n"
    "  -h, --help   show this help\n";

static int parse_threads(const char *s, int *out) {
  char *end = NULL;
  long v = strtol(s, &end, 10);
  if (!s[0] || *end || v < 1 || v > 4096) {
    fprintf(stderr, "pdk: --threads '%s' is not a thread count; use an integer from 1 to 4096\n", s);
    return 2;
  }
  *out = (int)v;
  return 0;
}

static int cmd_info(int argc, char **argv) {
  pdk_ctx_opts opts = pdk_ctx_opts_default();
  for (int a = 0; a < argc; ++a) {
    if (!strcmp(argv[a], "-h") || !strcmp(argv[a], "--help")) {
      fputs(usage_info, stdout);
      return 0;
    } else if (!strcmp(argv[a], "--threads") && a + 1 < argc) {
      if (parse_threads(argv[++a], &opts.num_threads)) return 2;
    } else {
      fprintf(stderr, "pdk info: unknown option '%s'\n%s", argv[a], usage_info);
      return 2;
    }
  }
  char why[512];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(&opts, &ctx, why, sizeof why)) {
    fprintf(stderr, "pdk: %s\n", why);
    return 1;
  }
  int err = pdk_ctx_print_info(ctx, stdout);
  if (err) fprintf(stderr, "pdk: %s\n", pdk_ctx_error_message(ctx));
  pdk_ctx_destroy(&ctx);
  return err ? 1 : 0;
}

/* pdk run: on the ranks of mpiexec when built with MPI (docs/scaling.md). Every rank runs the
 * same loop; rank 0 writes the output and tells the run, the others stay silent. A failed run
 * (status 1) ends every rank: a failure of rank 0 alone (writing the output) would leave the
 * others waiting in an exchange. A bad command line or scene (2) and an interruption (130, agreed
 * by the ranks at the same step) end every rank by themselves. */
static int cmd_run(int argc, char **argv) {
  if (pdk_comm_init(&argc, &argv)) {
    fprintf(stderr, "pdk: MPI could not start (this pdk was built with MPI)\n");
    return 1;
  }
  const int size = pdk_comm_size();
  if (pdk_comm_rank() != 0) {
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)) {
      /* rank 0 prints the same run's lines: nothing is lost */
    }
  }
  const int rc = pdk_cli_run(argv[0], argc - 2, argv + 2);
  if (rc == 1 && size > 1) {
    fflush(stdout);
    fflush(stderr);
    pdk_comm_abort(rc);
  }
  pdk_comm_finalize();
  return rc;
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fputs(usage_main, stderr);
    return 2;
  }
  const char *cmd = argv[1];
  if (!strcmp(cmd, "-h") || !strcmp(cmd, "--help") || !strcmp(cmd, "help")) {
    fputs(usage_main, stdout);
    return 0;
  }
  if (!strcmp(cmd, "-V") || !strcmp(cmd, "--version")) {
    printf("pdk %s\n", PDK_VERSION_STRING);
    return 0;
  }
  if (!strcmp(cmd, "info")) return cmd_info(argc - 2, argv + 2);
  if (!strcmp(cmd, "run")) return cmd_run(argc, argv);
  if (!strcmp(cmd, "check")) return pdk_cli_check(argv[0], argc - 2, argv + 2);
  fprintf(stderr, "pdk: unknown command '%s'\n\n%s", cmd, usage_main);
  return 2;
}
