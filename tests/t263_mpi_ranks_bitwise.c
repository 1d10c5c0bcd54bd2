/* Several MPI ranks give one rank's results bit for bit (docs/scaling.md). Two small scenes with
 * bond breaking, tests/scenes/t263_pmb_2d.yaml (2-D PMB plate with a pre-crack, ~4 000 bonds
 * broken) and t263_lps_3d.yaml (3-D LPS bar, ~8 000 broken; its gather pass, the dilatation, is
 * exchanged between the ranks), run with `pdk run` on one rank (no mpiexec, one thread), then
 * under `mpiexec -n 2` (two threads per rank) and `mpiexec -n 3` (one thread per rank); and the
 * LPS bar with float storage (--set model.precision=float) on one and two ranks, and
 * t263_corr_2d.yaml (a 2-D correspondence plate, linear elastic, Silling stabilization, no
 * breaking; pass 2 is split over the ranks) on one, two and three. Asserted,
 * with no tolerance (the design makes every sum run in one rank's order, so any difference is a
 * bug): the history CSV and the field CSV are the same bytes; the HDF5 output holds the same
 * field outputs, static data and histories, objects, attributes and dataset bytes
 * (tests/h5_same.h); the final checkpoints hold the same contents. Also that bonds broke in the
 * PMB and LPS cases (the last history row's "broken" is at least 1 000), so the exchange of the
 * bond state is exercised.
 * Skipped (77) when the build has no MPI or no mpiexec is on PATH. Oversubscribed: the host may
 * have fewer cores than ranks. Files go to $PDK_BUILD_DIR/tests/t263_mpi_ranks_bitwise.work.
 * labels: mpi scene */
#include "file_util.h"
#include "h5_same.h"

static void same_bytes(const char *a, const char *b) {
  size_t na, nb;
  char *x = slurp_n(a, &na), *y = slurp_n(b, &nb);
  T_ASSERT(na == nb && !memcmp(x, y, na), "%s and %s differ (%zu and %zu bytes)", a, b, na, nb);
  free(x);
  free(y);
}

/* The "broken" column (the 6th) of the last row of a history CSV. */
static double last_broken(const char *path) {
  size_t n;
  char *s = slurp_n(path, &n);
  while (n > 0 && s[n - 1] == '\n')
    s[--n] = '\0';
  char *row = strrchr(s, '\n');
  T_ASSERT(row, "%s: no data row", path);
  char *p = row + 1;
  for (int k = 0; k < 5; ++k) {
    p = strchr(p, ',');
    T_ASSERT(p, "%s: short row", path);
    ++p;
  }
  const double v = atof(p);
  free(s);
  return v;
}

int main(void) {
  if (!PDK_HAVE_MPI) T_SKIP("this pdk was built without MPI (PDK_MPI)");
  if (system("command -v mpiexec > /dev/null 2>&1") != 0) T_SKIP("no mpiexec on PATH");
  const char *src = getenv("PDK_SOURCE_DIR"), *build = getenv("PDK_BUILD_DIR");
  T_ASSERT(src && build, "PDK_SOURCE_DIR or PDK_BUILD_DIR is not set (run through ctest)");
  char work[1024], cmd[8192], a[2048], b[2048];
  snprintf(work, sizeof work, "%s/tests/t263_mpi_ranks_bitwise.work", build);
  snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", work, work);
  T_ASSERT(system(cmd) == 0, "cannot make %s", work);
  /* the scenes, the overrides each takes, and how many rank counts it runs with */
  const char *const scenes[] = {"t263_pmb_2d", "t263_lps_3d", "t263_lps_3d", "t263_corr_2d"};
  const char *const sets[] = {"", "", "--set model.precision=float", ""};
  const int num_runs[] = {3, 3, 2, 3};
  const double min_broken[] = {1000, 1000, 1000, 0};
  const int num_cases = 4;
  /* ranks (0: plain pdk run, no mpiexec) and threads per rank */
  const int ranks[] = {0, 2, 3}, threads[] = {1, 2, 1};
  for (int s = 0; s < num_cases; ++s) {
    for (int r = 0; r < num_runs[s]; ++r) {
      char mpi[256] = "";
      if (ranks[r])
        snprintf(mpi, sizeof mpi,
                 "mpiexec --oversubscribe --allow-run-as-root -x PDK_NUM_THREADS -n %d ", ranks[r]);
      /* the thread count from the environment: --threads would enter the scene text the
       * output and the checkpoint store */
      snprintf(cmd, sizeof cmd,
               "rm -rf '%s/%s_%d' && cd '%s' && PDK_NUM_THREADS=%d %s'%s/pdk' run "
               "'%s/tests/scenes/%s.yaml' %s "
               "-o '%s/%s_%d' > '%s/%s_%d.log' 2>&1",
               work, scenes[s], ranks[r], work, threads[r], mpi, build, src, scenes[s], sets[s],
               work, scenes[s], ranks[r], work, scenes[s], ranks[r]);
      T_ASSERT(system(cmd) == 0, "the run failed (see %s/%s_%d.log): %s", work, scenes[s], ranks[r],
               cmd);
    }
    snprintf(a, sizeof a, "%s/%s_0/%s_history.csv", work, scenes[s], scenes[s]);
    const double broken = last_broken(a);
    T_ASSERT(broken >= min_broken[s], "%s: %g bonds broke, fewer than %g", scenes[s], broken,
             min_broken[s]);
    for (int r = 1; r < num_runs[s]; ++r) {
      const char *const csv[] = {"_history.csv", "_fields.csv"};
      for (int k = 0; k < 2; ++k) {
        snprintf(a, sizeof a, "%s/%s_0/%s%s", work, scenes[s], scenes[s], csv[k]);
        snprintf(b, sizeof b, "%s/%s_%d/%s%s", work, scenes[s], ranks[r], scenes[s], csv[k]);
        same_bytes(a, b);
      }
      char why[2048] = "";
      snprintf(a, sizeof a, "%s/%s_0/%s.h5", work, scenes[s], scenes[s]);
      snprintf(b, sizeof b, "%s/%s_%d/%s.h5", work, scenes[s], ranks[r], scenes[s]);
      T_ASSERT(h5s_same_file(a, b, why, sizeof why), "%s and %s differ: %s", a, b, why);
      snprintf(a, sizeof a, "%s/%s_0/%s_checkpoint.h5", work, scenes[s], scenes[s]);
      snprintf(b, sizeof b, "%s/%s_%d/%s_checkpoint.h5", work, scenes[s], ranks[r], scenes[s]);
      T_ASSERT(h5s_same_file(a, b, why, sizeof why), "%s and %s differ: %s", a, b, why);
    }
  }
  return 0;
}
