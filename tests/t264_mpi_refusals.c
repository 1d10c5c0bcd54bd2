/* What does not run on several MPI ranks yet is refused at setup with a message naming it and
 * saying to run on one rank (docs/scaling.md), and model.stencil auto takes the general path there.
 * Under `mpiexec -n 2`, each of these exits non-zero with its message on stderr:
 *   solver.type adr (tests/scenes/t094_static.yaml)      "solver.type adr runs on one rank only"
 *   model.kind oterkus (t263_pmb_2d.yaml, --set)         "model kind 'oterkus' runs on one rank
 * only" correspondence with model.stencil auto               "... with model.stencil auto or on"
 *   correspondence with model.connectivity semi_tl       "... with model.connectivity semi_tl"
 *   model.layout sell                                    "model.layout sell runs on one rank only"
 *   model.stencil on                                     "model.stencil on runs on one rank only"
 *   --restart of a one-rank run's checkpoint             "a restart runs on one rank only"
 * and every message says "without mpiexec". Then t263_pmb_2d.yaml with model.stencil auto on two
 * ranks gives the history of one rank with stencil off, byte for byte (several ranks take the
 * general path; the scene text differs by the override, so only the history CSV is compared).
 * Skipped (77) when the build has no MPI or no mpiexec is on PATH.
 * Files go to $PDK_BUILD_DIR/tests/t264_mpi_refusals.work.
 * labels: mpi scene */
#include "file_util.h"

static char work[1024], src[512], build[512];

/* pdk run with `args` on `ranks` ranks (0: no mpiexec); its exit status, stderr into tag.log. */
static int run(int ranks, const char *tag, const char *args) {
  char cmd[16384], mpi[256] = "";
  if (ranks)
    snprintf(mpi, sizeof mpi,
             "mpiexec --oversubscribe --allow-run-as-root -x PDK_NUM_THREADS -n %d ", ranks);
  snprintf(cmd, sizeof cmd, "cd '%s' && PDK_NUM_THREADS=1 %s'%s/pdk' run %s > '%s/%s.log' 2>&1",
           work, mpi, build, args, work, tag);
  return system(cmd);
}

static void refused(const char *tag, const char *args, const char *needle) {
  T_ASSERT(run(2, tag, args) != 0, "%s: the run on two ranks did not fail", tag);
  char path[2048];
  snprintf(path, sizeof path, "%s/%s.log", work, tag);
  char *log = slurp(path);
  T_ASSERT(strstr(log, needle), "%s: the message lacks '%s':\n%s", tag, needle, log);
  T_ASSERT(strstr(log, "without mpiexec"), "%s: the message does not say to run on one rank:\n%s",
           tag, log);
  free(log);
}

int main(void) {
  if (!PDK_HAVE_MPI) T_SKIP("this pdk was built without MPI (PDK_MPI)");
  if (system("command -v mpiexec > /dev/null 2>&1") != 0) T_SKIP("no mpiexec on PATH");
  T_ASSERT(getenv("PDK_SOURCE_DIR") && getenv("PDK_BUILD_DIR"),
           "PDK_SOURCE_DIR or PDK_BUILD_DIR is not set (run through ctest)");
  snprintf(src, sizeof src, "%s", getenv("PDK_SOURCE_DIR"));
  snprintf(build, sizeof build, "%s", getenv("PDK_BUILD_DIR"));
  snprintf(work, sizeof work, "%s/tests/t264_mpi_refusals.work", build);
  char cmd[4096], args[8192];
  snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", work, work);
  T_ASSERT(system(cmd) == 0, "cannot make %s", work);
  char pmb[1024];
  snprintf(pmb, sizeof pmb, "'%s/tests/scenes/t263_pmb_2d.yaml'", src);

  snprintf(args, sizeof args, "'%s/tests/scenes/t094_static.yaml' -o static", src);
  refused("static", args, "solver.type adr runs on one rank only");
  snprintf(args, sizeof args, "%s -o oterkus --set model.kind=oterkus --set solver.steps=2", pmb);
  refused("oterkus", args, "model kind 'oterkus' runs on one rank only");
  snprintf(
      args, sizeof args,
      "%s -o corr --set model.kind=correspondence --set model.stencil=auto --set solver.steps=2",
      pmb);
  refused("corr_stencil", args, "model kind 'correspondence' with model.stencil auto or on");
  snprintf(args, sizeof args,
           "%s -o semi --set model.kind=correspondence --set model.connectivity=semi_tl "
           "--set solver.steps=2",
           pmb);
  refused("corr_semi_tl", args, "model kind 'correspondence' with model.connectivity semi_tl");
  snprintf(args, sizeof args, "%s -o sell --set model.layout=sell --set solver.steps=2", pmb);
  refused("sell", args, "model.layout sell runs on one rank only");
  snprintf(args, sizeof args, "%s -o on --set model.stencil=on --set solver.steps=2", pmb);
  refused("stencil_on", args, "model.stencil on runs on one rank only");
  /* a checkpoint of one rank, restarted on two */
  snprintf(args, sizeof args, "%s -o ck --set solver.steps=20", pmb);
  T_ASSERT(run(0, "ck", args) == 0, "the one-rank run for the checkpoint failed (ck.log)");
  snprintf(args, sizeof args,
           "%s -o ck2 --set solver.steps=40 --restart '%s/ck/t263_pmb_2d_checkpoint.h5'", pmb,
           work);
  refused("restart", args, "a restart runs on one rank only");

  /* stencil auto on two ranks = stencil off on one */
  snprintf(args, sizeof args, "%s -o auto2 --set model.stencil=auto", pmb);
  T_ASSERT(run(2, "auto2", args) == 0, "stencil auto on two ranks failed (auto2.log)");
  snprintf(args, sizeof args, "%s -o off1", pmb);
  T_ASSERT(run(0, "off1", args) == 0, "the one-rank run failed (off1.log)");
  char a[2048], b[2048]; /* work + a file name */
  snprintf(a, sizeof a, "%s/auto2/t263_pmb_2d_history.csv", work);
  snprintf(b, sizeof b, "%s/off1/t263_pmb_2d_history.csv", work);
  char *x = slurp(a), *y = slurp(b);
  T_ASSERT(!strcmp(x, y), "%s and %s differ", a, b);
  free(x);
  free(y);
  return 0;
}
