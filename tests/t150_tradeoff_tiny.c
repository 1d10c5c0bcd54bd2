/* The speed-accuracy study (bench/tradeoff, docs/tradeoff.md) on its tiny plan: the program runs,
 * its output is complete, and the errors fall with resolution where theory says they must.
 * labels: physics
 *
 * Runs build/bench/bench_tradeoff --plan tiny into a directory that does not exist yet (the program
 * must create it, parents included) and reads tradeoff.csv with its own parser. Complete means:
 * the header; for each of the problems mms, vq_uniaxial, wave and hole, the models pmb, lps and
 * corr-silling at both levels with status ok, a positive finite error and cost, particles and
 * bonds; at least one run on the Pareto front, and no dominated run flagged; a non-empty PNG per
 * problem (gnuplot) and no leftover temporary (.part) file.
 *
 * Convergence (relative errors e1 at the coarse, e2 at the fine level, h halved; order =
 * log2(e1 / e2)):
 *   - vq_uniaxial, correspondence without stabilization, cubic influence, RF 1.5 (the V-Q3
 *     setting, NP 20 -> 40): Queiruga & Moridis measure order 0.9999 (Table 3), t113 0.985 at
 *     NP 40 -> 80; accepted [0.85, 1.15], the pre-asymptotic spread at NP 20.
 *   - mms (manufactured field: per-particle body force b = -Div sigma(u*) and a 2 delta collar
 *     held at u* through pdk_bc.scale_field), correspondence with Silling stabilization, m 3.015
 *     (N 16 -> 32): the operator is consistent to O(delta^2) at fixed m, and the collar holds the
 *     exact field, so order 2; measured 2.38 here (delta is a fifth of the field's length scale at
 *     N = 16, where higher-order terms still count); accepted [1.7, 3.2]. PMB and LPS must pose
 *     the problem too (status ok at both levels).
 *   - wave, correspondence with Silling stabilization (N 32 -> 64): the dispersion of the nonlocal
 *     operator is O((k delta)^2) and Verlet's O((omega dt)^2), but the free ends and sides add
 *     layers of width delta where the family is one-sided; measured 1.58 (and 1.82 at 64 -> 128);
 *     accepted [1.2, 2.5].
 *   - hole, correspondence with Silling stabilization (N 20 -> 40): the peak stress approaches the
 *     stress concentration factor; the error must fall by at least a factor 1.2 (first order at
 *     best: the peak is sampled h/2 off the hole edge and smoothed over delta).
 * Float storage (correspondence, Silling, m 3.015, TL; every problem, both levels): status ok and
 * |e_float - e_double| <= 1e-6. The float copies of the pass-2 tensors carry a relative error of
 * 2^-24 = 6e-8 of the stress, and Newton solves the float rows to rtol 1e-7 of the load norm
 * (its default 1e-10 lies below the float round-off), so the displacements, frequencies and
 * stresses the errors are made of move by a few 1e-7 relative (measured: at most 2.1e-7, V-Q
 * NP 20); 1e-6 is five times that and a thousandth of the smallest double error of the plan
 * (9.6e-4, wave N 64): float storage must not be visible at the discretization level. The float
 * rows then also converge at the double rows' order.
 * PDK_TEST_VERBOSE=1 prints the program's progress and the orders.
 */
#include "test_util.h"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#define MAX_ROWS 256
#define NCOL 25

typedef struct trow {
  char problem[32], model[32], influence[32], precision[16], status[16], note[256];
  double m, error, cpu, h;
  long level, particles, bonds;
  int pareto, series;
} trow;

static int split(char *line, char **col) {
  int n = 0;
  char *s = line;
  while (n < NCOL + 1) {
    col[n++] = s;
    char *c = strchr(s, ',');
    if (!c) break;
    *c = '\0';
    s = c + 1;
  }
  return n;
}

static int read_csv(const char *path, trow *rows) {
  FILE *f = fopen(path, "r");
  T_ASSERT(f, "the program wrote no %s", path);
  char line[4096];
  T_ASSERT(fgets(line, sizeof line, f), "%s is empty", path);
  line[strcspn(line, "\n")] = '\0';
  char *col[NCOL + 1];
  T_ASSERT(split(line, col) == NCOL, "header has the wrong column count: %s", line);
  const char *want[] = {"problem", "model",     "influence", "m",      "precision",
                        "level",   "particles", "bonds",     "cpu_s",  "error",
                        "status",  "pareto",    "note",      "series", "h"};
  int idx[15];
  for (int k = 0; k < 15; ++k) {
    idx[k] = -1;
    for (int c = 0; c < NCOL; ++c)
      if (!strcmp(col[c], want[k])) idx[k] = c;
    T_ASSERT(idx[k] >= 0, "header lacks column '%s'", want[k]);
  }
  int n = 0;
  while (fgets(line, sizeof line, f)) {
    line[strcspn(line, "\n")] = '\0';
    T_ASSERT(n < MAX_ROWS, "more than %d rows", MAX_ROWS);
    T_ASSERT(split(line, col) == NCOL, "row %d has the wrong column count", n + 1);
    trow *r = &rows[n++];
    snprintf(r->problem, sizeof r->problem, "%s", col[idx[0]]);
    snprintf(r->model, sizeof r->model, "%s", col[idx[1]]);
    snprintf(r->influence, sizeof r->influence, "%s", col[idx[2]]);
    r->m = atof(col[idx[3]]);
    snprintf(r->precision, sizeof r->precision, "%s", col[idx[4]]);
    r->level = atol(col[idx[5]]);
    r->particles = atol(col[idx[6]]);
    r->bonds = atol(col[idx[7]]);
    r->cpu = atof(col[idx[8]]);
    r->error = atof(col[idx[9]]);
    snprintf(r->status, sizeof r->status, "%s", col[idx[10]]);
    r->pareto = atoi(col[idx[11]]);
    snprintf(r->note, sizeof r->note, "%s", col[idx[12]]);
    r->series = atoi(col[idx[13]]);
    r->h = atof(col[idx[14]]);
  }
  fclose(f);
  return n;
}

/* Whether rows[i] ran and its series converges: its error falls by a quarter or more between
 * the series' two finest resolutions that ran (the rule of bench/tradeoff/tradeoff.c). */
static int eligible(const trow *rows, int n, int i) {
  if (strcmp(rows[i].status, "ok")) return 0;
  const trow *fine = NULL, *next = NULL;
  for (int j = 0; j < n; ++j) {
    const trow *r = &rows[j];
    if (strcmp(r->problem, rows[i].problem) || r->series != rows[i].series ||
        strcmp(r->status, "ok"))
      continue;
    if (!fine || r->h < fine->h) {
      next = fine;
      fine = r;
    } else if (!next || r->h < next->h) {
      next = r;
    }
  }
  return fine && next && fine->error <= 0.75 * next->error;
}

/* The run of (problem, model, influence, m, precision) at a level; NULL if absent. */
static const trow *find_prec(const trow *rows, int n, const char *problem, const char *model,
                             const char *influence, double m, long level, const char *precision) {
  for (int i = 0; i < n; ++i)
    if (!strcmp(rows[i].problem, problem) && !strcmp(rows[i].model, model) &&
        (!influence || !strcmp(rows[i].influence, influence)) && fabs(rows[i].m - m) < 1e-9 &&
        rows[i].level == level && !strcmp(rows[i].precision, precision))
      return &rows[i];
  return NULL;
}

static const trow *find(const trow *rows, int n, const char *problem, const char *model,
                        const char *influence, double m, long level) {
  return find_prec(rows, n, problem, model, influence, m, level, "double");
}

static double order(const trow *rows, int n, const char *problem, const char *model,
                    const char *influence, double m, long l1, long l2) {
  const trow *a = find(rows, n, problem, model, influence, m, l1);
  const trow *b = find(rows, n, problem, model, influence, m, l2);
  T_ASSERT(a && b, "%s %s m %g: levels %ld and %ld missing", problem, model, m, l1, l2);
  T_ASSERT(!strcmp(a->status, "ok") && !strcmp(b->status, "ok"), "%s %s: status %s / %s (%s%s)",
           problem, model, a->status, b->status, a->note, b->note);
  const double o = log(a->error / b->error) / log((double)l2 / (double)l1);
  if (getenv("PDK_TEST_VERBOSE"))
    printf("%s %s m %g: error %.4e -> %.4e, order %.3f\n", problem, model, m, a->error, b->error,
           o);
  return o;
}

int main(void) {
  const char *build = getenv("PDK_BUILD_DIR");
  T_ASSERT(build, "PDK_BUILD_DIR is not set (run through ctest)");
  const int verbose = getenv("PDK_TEST_VERBOSE") != NULL;
  char dir[1024], cmd[4096], path[1100];
  snprintf(dir, sizeof dir, "%s/tests/t150_tradeoff_tiny.work", build);
  /* the output directory is two levels below one the program must create */
  snprintf(cmd, sizeof cmd,
           "rm -rf '%s' && '%s/bench/bench_tradeoff' --plan tiny "
           "--out-dir '%s/new/out' %s",
           dir, build, dir, verbose ? "" : "2> '/dev/null'");
  T_ASSERT(system(cmd) == 0, "the program failed: %s", cmd);
  snprintf(dir + strlen(dir), sizeof dir - strlen(dir), "/new/out");
  snprintf(path, sizeof path, "%s/tradeoff.csv", dir);
  static trow rows[MAX_ROWS];
  const int n = read_csv(path, rows);

  const char *problems[4] = {"mms", "vq_uniaxial", "wave", "hole"};
  const long levels[4][2] = {{16, 32}, {20, 40}, {32, 64}, {20, 40}};
  const char *models[3] = {"pmb", "lps", "corr-silling"};
  /* float storage must move no error by more than this (header) */
  const double float_tol = 1e-6;
  for (int p = 0; p < 4; ++p) {
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 2; ++l) {
        const trow *r = find(rows, n, problems[p], models[k], NULL, 3.015, levels[p][l]);
        T_ASSERT(r, "%s: no %s run at level %ld", problems[p], models[k], levels[p][l]);
        T_ASSERT(!strcmp(r->status, "ok"), "%s %s level %ld: %s: %s", problems[p], models[k],
                 levels[p][l], r->status, r->note);
        T_ASSERT(isfinite(r->error) && r->error > 0 && isfinite(r->cpu) && r->cpu >= 0 &&
                     r->particles > 0 && r->bonds > 0,
                 "%s %s level %ld: error %g, cpu %g, %ld particles, %ld bonds", problems[p],
                 models[k], levels[p][l], r->error, r->cpu, r->particles, r->bonds);
      }
    for (int l = 0; l < 2; ++l) {
      const trow *d = find(rows, n, problems[p], "corr-silling", "constant", 3.015, levels[p][l]);
      const trow *f =
          find_prec(rows, n, problems[p], "corr-silling", "constant", 3.015, levels[p][l], "float");
      T_ASSERT(f, "%s: no float-storage run at level %ld", problems[p], levels[p][l]);
      T_ASSERT(!strcmp(f->status, "ok"), "%s float level %ld: %s: %s", problems[p], levels[p][l],
               f->status, f->note);
      if (verbose)
        printf("%s level %ld: error double %.7e, float %.7e (difference %.2e)\n", problems[p],
               levels[p][l], d->error, f->error, fabs(f->error - d->error));
      T_ASSERT(fabs(f->error - d->error) <= float_tol,
               "%s level %ld: float storage moves the error from %.7e to %.7e (more than %g)",
               problems[p], levels[p][l], d->error, f->error, float_tol);
    }
    /* The front (docs/tradeoff.md): the runs of converging series (the error falls by a quarter
     * or more when h halves between the series' two finest resolutions) that no other such run
     * of the problem dominates. Checked both ways: every flagged run is eligible and undominated,
     * and every eligible undominated run is flagged. */
    int on_front = 0;
    for (int i = 0; i < n; ++i) {
      if (strcmp(rows[i].problem, problems[p])) continue;
      on_front += rows[i].pareto;
      const int el_i = eligible(rows, n, i);
      int dominated_by = -1;
      for (int j = 0; j < n && dominated_by < 0; ++j) {
        if (j == i || strcmp(rows[j].problem, problems[p]) || !eligible(rows, n, j)) continue;
        if (rows[j].cpu <= rows[i].cpu && rows[j].error <= rows[i].error &&
            (rows[j].cpu < rows[i].cpu || rows[j].error < rows[i].error))
          dominated_by = j;
      }
      if (rows[i].pareto) {
        T_ASSERT(el_i,
                 "%s: run %d is on the Pareto front but its series does not converge (or "
                 "it did not run)",
                 problems[p], i);
        T_ASSERT(dominated_by < 0, "%s: run %d is on the Pareto front but run %d dominates it",
                 problems[p], i, dominated_by);
      } else {
        T_ASSERT(!el_i || dominated_by >= 0,
                 "%s: run %d converges and nothing dominates it, but it is not on the front",
                 problems[p], i);
      }
    }
    T_ASSERT(on_front >= 1, "%s: nothing on the Pareto front", problems[p]);
    snprintf(path, sizeof path, "%s/%s.png", dir, problems[p]);
    FILE *png = fopen(path, "rb");
    T_ASSERT(png, "no plot %s", path);
    unsigned char magic[8] = {0};
    const size_t got = fread(magic, 1, 8, png);
    fclose(png);
    T_ASSERT(got == 8 && magic[1] == 'P' && magic[2] == 'N' && magic[3] == 'G', "%s is not a PNG",
             path);
    snprintf(path, sizeof path, "%s/%s.png.part", dir, problems[p]);
    T_ASSERT(access(path, F_OK) != 0, "temporary %s left behind", path);
  }
  snprintf(path, sizeof path, "%s/tradeoff.csv.part", dir);
  T_ASSERT(access(path, F_OK) != 0, "temporary %s left behind", path);
  /* an output directory that cannot be made (below a regular file) fails at once, non-zero,
   * before any run */
  snprintf(cmd, sizeof cmd,
           "'%s/bench/bench_tradeoff' --plan tiny --problem wave --out-dir "
           "'%s/tradeoff.csv/sub' 2> /dev/null",
           build, dir);
  const int rc = system(cmd);
  T_ASSERT(rc != -1 && WIFEXITED(rc) && WEXITSTATUS(rc) == 1,
           "an impossible --out-dir was not refused (status %d)", rc);

  const double o_vq = order(rows, n, "vq_uniaxial", "corr-none", "cubic", 1.5, 20, 40);
  T_ASSERT(o_vq >= 0.85 && o_vq <= 1.15, "V-Q3 uniaxial order %.3f, expected about 1", o_vq);
  const double o_mms = order(rows, n, "mms", "corr-silling", "constant", 3.015, 16, 32);
  T_ASSERT(o_mms >= 1.7 && o_mms <= 3.2, "manufactured field order %.3f, expected about 2", o_mms);
  const double o_wave = order(rows, n, "wave", "corr-silling", "constant", 3.015, 32, 64);
  T_ASSERT(o_wave >= 1.2 && o_wave <= 2.5, "wave frequency error order %.3f, expected 1.6 to 2",
           o_wave);
  const double o_hole = order(rows, n, "hole", "corr-silling", "constant", 3.015, 20, 40);
  T_ASSERT(o_hole >= log2(1.2), "hole stress concentration error order %.3f: it must fall", o_hole);
  return 0;
}
