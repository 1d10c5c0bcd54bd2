/* The closing phase killed at each of its steps never leaves files of two runs side by side.
 * A first run leaves its complete set of files; a second run of the same name (other data, other
 * units, one field output more) is killed (SIGKILL, through the test hook
 * pdk_fault_kill_at_step) just before the k-th rename or removal of a final file name, for
 * every k, in a child process. After each kill the final names (not .part) in the folder are
 * all the first run's files (byte for byte) or all the second's, never both; a <name>.xmf
 * present means its whole set is present. A run that is not killed leaves exactly the second
 * run's set and no .part file. Each run also hands the output a file of its own
 * (pdk_output_adopt, as pdk run does its final checkpoint), which must follow the same rule.
 * Test files go to ./t181_out.
 * labels: unit */
#include <signal.h>
#include <sys/wait.h>

#include "output_util.h"

#include "core/h5io.h"

#define DIR_OUT "t181_out"
#define NAME "run"
#define MAX_FILES 16

/* the last is the file each run hands to the output (pdk_output_adopt), as pdk run does its
 * final checkpoint */
static const char *const suffix[] = {".h5",          ".xmf",        "_history.csv",
                                     "_history.gp",  "_history.png", "_fields.csv",
                                     "_fields.gp",   "_fields.png",  "_checkpoint.h5"};
#define NUM_SUFFIX ((int)(sizeof suffix / sizeof suffix[0]))

typedef struct blob {
  char *data;
  long len;
} blob;

static blob slurp(const char *name) {
  char path[1024];
  blob b = {NULL, -1};
  snprintf(path, sizeof path, "%s/%s", DIR_OUT, name);
  FILE *f = fopen(path, "rb");
  if (!f) return b;
  fseek(f, 0, SEEK_END);
  b.len = ftell(f);
  fseek(f, 0, SEEK_SET);
  b.data = malloc((size_t)b.len + 1);
  T_ASSERT(fread(b.data, 1, (size_t)b.len, f) == (size_t)b.len, "short read of %s", path);
  fclose(f);
  return b;
}

static void spill(const char *name, blob b) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", DIR_OUT, name);
  FILE *f = fopen(path, "wb");
  T_ASSERT(f && fwrite(b.data, 1, (size_t)b.len, f) == (size_t)b.len && fclose(f) == 0,
           "cannot write %s", path);
}

/* One whole output run: the first (mark 100, 6 records, SI) or the second (mark 200, 8 records,
 * no units). Returns close's code. */
static int one_run(pdk_ctx *ctx, pdk_particles *p, int second) {
  pdk_output_opts oo = ou_opts(DIR_OUT, NAME);
  oo.units = second ? NULL : "SI";
  pdk_output *o = NULL;
  T_OK(ctx, pdk_output_open(ctx, &oo, p, &o));
  T_ASSERT(pdk_output_will_plot(o), "gnuplot was found at open");
  T_OK(ctx, ou_write(o, p, second ? 8 : 6, second ? 200.0 : 100.0));
  const char *part = DIR_OUT "/" NAME "_checkpoint.h5.part";
  FILE *f = fopen(part, "wb");
  T_ASSERT(f && fprintf(f, "checkpoint of run %d\n", second + 1) > 0 && fclose(f) == 0,
           "cannot write %s", part);
  T_OK(ctx, pdk_output_adopt(o, part, DIR_OUT "/" NAME "_checkpoint.h5"));
  return pdk_output_close(&o, 1);
}

int main(void) {
  T_ASSERT(ou_on_path("gnuplot"), "gnuplot is not on the PATH; it is a test dependency (README "
                                  "Quick start: gnuplot-nox)");
  pdk_ctx *ctx = t_ctx(1);
  pdk_particles *p = ou_store(ctx);
  char name[NUM_SUFFIX][64], list[4096];
  for (int f = 0; f < NUM_SUFFIX; ++f)
    snprintf(name[f], sizeof name[f], NAME "%s", suffix[f]);

  /* the second run alone, for its files; then the first run's, kept as the folder to restore */
  ou_clean(DIR_OUT);
  T_OK(ctx, one_run(ctx, p, 1));
  blob second[NUM_SUFFIX], first[NUM_SUFFIX];
  for (int f = 0; f < NUM_SUFFIX; ++f)
    second[f] = slurp(name[f]);
  ou_clean(DIR_OUT);
  T_OK(ctx, one_run(ctx, p, 0));
  T_ASSERT(ou_list(DIR_OUT, list, sizeof list) == NUM_SUFFIX, "the first run's set:\n%s", list);
  for (int f = 0; f < NUM_SUFFIX; ++f) {
    first[f] = slurp(name[f]);
    T_ASSERT(first[f].len > 0 && second[f].len > 0, "%s exists after both runs", name[f]);
    T_ASSERT(first[f].len != second[f].len || memcmp(first[f].data, second[f].data, first[f].len),
             "%s differs between the runs (else its origin cannot be told)", name[f]);
  }

  int kills = 0;
  for (long k = 1;; ++k) {
    T_ASSERT(k <= 4 * MAX_FILES, "the closing phase did not end after %ld steps", k);
    ou_clean(DIR_OUT);
    for (int f = 0; f < NUM_SUFFIX; ++f)
      spill(name[f], first[f]);
    pid_t pid = fork();
    T_ASSERT(pid >= 0, "fork");
    if (pid == 0) {
      pdk_fault_kill_at_step(k);
      _exit(one_run(ctx, p, 1) ? 3 : 0);
    }
    int status = 0;
    T_ASSERT(waitpid(pid, &status, 0) == pid, "waitpid");
    int n_first = 0, n_second = 0, n_part = 0;
    for (int f = 0; f < NUM_SUFFIX; ++f) {
      blob b = slurp(name[f]);
      if (b.len < 0) continue;
      if (b.len == first[f].len && !memcmp(b.data, first[f].data, (size_t)b.len))
        n_first++;
      else
        n_second++;
      free(b.data);
    }
    const int n_all = ou_list(DIR_OUT, list, sizeof list);
    for (const char *q = strstr(list, ".part\n"); q; q = strstr(q + 1, ".part\n"))
      n_part++;
    T_ASSERT(n_all == n_first + n_second + n_part, "only pdk's files in the folder:\n%s", list);
    T_ASSERT(!(n_first && n_second),
             "killed before step %ld: %d files of the first run beside %d "
             "of the second:\n%s",
             k, n_first, n_second, list);
    if (ou_exists(DIR_OUT, name[1]))
      T_ASSERT(n_first == NUM_SUFFIX || n_second == NUM_SUFFIX,
               "killed before step %ld: a .xmf with an incomplete set:\n%s", k, list);
    if (WIFSIGNALED(status)) {
      T_ASSERT(WTERMSIG(status) == SIGKILL, "the child died of signal %d", WTERMSIG(status));
      kills++;
      continue;
    }
    /* not killed: the closing phase has fewer than k steps */
    T_ASSERT(WIFEXITED(status) && WEXITSTATUS(status) == 0, "the unkilled run failed (%d)", status);
    T_ASSERT(n_second == NUM_SUFFIX && n_part == 0, "a finished run leaves its whole set:\n%s",
             list);
    break;
  }
  /* a step for each removal of the first run's names and each rename of the second's */
  T_ASSERT(kills == 2 * NUM_SUFFIX, "%d kill points, expected %d", kills, 2 * NUM_SUFFIX);
  for (int f = 0; f < NUM_SUFFIX; ++f) {
    free(first[f].data);
    free(second[f].data);
  }
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
