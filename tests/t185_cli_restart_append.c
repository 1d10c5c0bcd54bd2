/* `pdk run --restart` into the folder of the run it continues: the output goes on from the
 * checkpoint, and the files equal those of a run that never stopped.
 *   - a run stopped by SIGINT prints a "continue with" command that names the scene, the output
 *     folder, every --set (one with a quote and spaces), --threads and -q, shell-quoted; pasted
 *     into sh it continues the run, and the history CSV and the XDMF are byte for byte those of
 *     the uninterrupted run, the HDF5 the same objects, attributes and dataset bytes;
 *   - a restart from an earlier checkpoint into that finished output drops the records written
 *     after the checkpoint and gives the same files again;
 *   - a restart of the finished run says there is nothing to do and changes no file; with a
 *     later end (more steps) it continues and keeps every earlier history row;
 *   - a folder holding the output of another run (another scene), or an output that ends before
 *     the checkpoint (its run was killed after a later checkpoint), is refused with exit 2 and a
 *     message, and its files are left as they were.
 * The CLI is $PDK_BUILD_DIR/pdk; the files go to $PDK_BUILD_DIR/tests/t185_cli_restart_append.work.
 * (h5diff is not needed: the HDF5 files are compared object by object, tests/h5_same.h.)
 * labels: unit */
#define _DEFAULT_SOURCE /* fork, kill, usleep */
#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_util.h"
#include "h5_same.h"

#define STEPS "6000" /* under a second for this bar */
#define MAX_ARGS 40

static char cli[4096], scene[4096];

/* Reads a whole file; NULL when it cannot. */
static char *slurp(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *buf = malloc((size_t)n + 1);
  T_ASSERT(buf && fread(buf, 1, (size_t)n, f) == (size_t)n, "cannot read %s", path);
  buf[n] = '\0';
  fclose(f);
  if (len) *len = (size_t)n;
  return buf;
}

static int same_file(const char *a, const char *b) {
  size_t la, lb;
  char *x = slurp(a, &la), *y = slurp(b, &lb);
  const int same = x && y && la == lb && !memcmp(x, y, la);
  free(x);
  free(y);
  return same;
}

static void copy_file(const char *from, const char *to) {
  size_t len;
  char *buf = slurp(from, &len);
  T_ASSERT(buf, "cannot read %s", from);
  FILE *f = fopen(to, "wb");
  T_ASSERT(f && fwrite(buf, 1, len, f) == len && fclose(f) == 0, "cannot write %s", to);
  free(buf);
}

/* Starts argv (stderr to err_file); returns the pid. */
static pid_t start(char *const *argv, const char *err_file) {
  fflush(NULL);
  pid_t pid = fork();
  T_ASSERT(pid >= 0, "fork failed");
  if (pid == 0) {
    int fd = open(err_file, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) dup2(fd, 2);
    int null = open("/dev/null", O_WRONLY);
    if (null >= 0) dup2(null, 1);
    execv(argv[0], argv);
    _exit(127);
  }
  return pid;
}

/* Exit status, or 128 + the signal. */
static int finish(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* Runs `pdk run SCENE <the common options> -o dir <extra...>`; stderr goes to err_file. */
static char *args[MAX_ARGS];
static int num_args;
static void build_args(const char *dir, const char *const *extra) {
  static const char *const common[] = {"--set",     "solver.steps=" STEPS,
                                       "--set",     "output.history_interval=50",
                                       "--set",     "output.field_interval=500",
                                       "--set",     "description=it's a bar, pulled",
                                       "--threads", "2",
                                       "-q"};
  num_args = 0;
  args[num_args++] = cli;
  args[num_args++] = "run";
  args[num_args++] = scene;
  for (size_t k = 0; k < sizeof common / sizeof common[0]; ++k)
    args[num_args++] = (char *)common[k];
  args[num_args++] = "-o";
  args[num_args++] = (char *)dir;
  for (int k = 0; extra && extra[k]; ++k)
    args[num_args++] = (char *)extra[k];
  args[num_args] = NULL;
}

static int run(const char *dir, const char *const *extra, const char *err_file) {
  build_args(dir, extra);
  return finish(start(args, err_file));
}

static int count_lines(const char *path) {
  size_t len;
  char *buf = slurp(path, &len);
  int n = 0;
  for (size_t k = 0; buf && k < len; ++k)
    n += buf[k] == '\n';
  free(buf);
  return n;
}

/* The output of folder dir equals A's: CSV and XDMF bytes, HDF5 contents. */
static void assert_same_as_a(const char *dir, const char *what) {
  char x[1024], why[2048] = "";
  snprintf(x, sizeof x, "%s/bar_history.csv", dir);
  T_ASSERT(same_file("A/bar_history.csv", x),
           "%s: %s differs from A/bar_history.csv (%d lines "
           "against %d)",
           what, x, count_lines(x), count_lines("A/bar_history.csv"));
  snprintf(x, sizeof x, "%s/bar.xmf", dir);
  T_ASSERT(same_file("A/bar.xmf", x), "%s: %s differs from A/bar.xmf", what, x);
  snprintf(x, sizeof x, "%s/bar.h5", dir);
  T_ASSERT(h5s_same_file("A/bar.h5", x, why, sizeof why), "%s: %s differs from A/bar.h5: %s",
           what, x, why);
}

/* The files of the output in dir, for "left as they were" checks. */
typedef struct snapshot {
  char *file[3];
  size_t len[3];
} snapshot;
static const char *const out_files[3] = {"bar_history.csv", "bar.xmf", "bar.h5"};
static void take(const char *dir, snapshot *s) {
  for (int k = 0; k < 3; ++k) {
    char x[1024];
    snprintf(x, sizeof x, "%s/%s", dir, out_files[k]);
    s->file[k] = slurp(x, &s->len[k]);
    T_ASSERT(s->file[k], "%s is missing", x);
  }
}
static void assert_unchanged(const char *dir, const snapshot *s, const char *what) {
  snapshot now;
  take(dir, &now);
  for (int k = 0; k < 3; ++k) {
    T_ASSERT(now.len[k] == s->len[k] && !memcmp(now.file[k], s->file[k], s->len[k]),
             "%s: %s/%s changed", what, dir, out_files[k]);
    free(now.file[k]);
  }
}
static void free_snapshot(snapshot *s) {
  for (int k = 0; k < 3; ++k)
    free(s->file[k]);
}

static void assert_err(const char *err_file, const char *needle, const char *what) {
  char *text = slurp(err_file, NULL);
  T_ASSERT(text && strstr(text, needle), "%s: the message does not say '%s':\n%s", what, needle,
           text ? text : "(none)");
  free(text);
}

int main(void) {
  const char *build = getenv("PDK_BUILD_DIR"), *src = getenv("PDK_SOURCE_DIR");
  T_ASSERT(build && src, "PDK_BUILD_DIR and PDK_SOURCE_DIR are not set (run through ctest)");
  snprintf(cli, sizeof cli, "%s/pdk", build);
  snprintf(scene, sizeof scene, "%s/tests/scenes/t092_bar.yaml", src);
  T_ASSERT(access(cli, X_OK) == 0, "%s is not built (cmake --build ... --target pdk_cli)", cli);
  char work[4096], cmd[2 * 4096 + 64];
  snprintf(work, sizeof work, "%s/tests/t185_cli_restart_append.work", build);
  snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", work, work);
  T_ASSERT(system(cmd) == 0, "%s", cmd);
  T_ASSERT(chdir(work) == 0, "cd %s", work);

  /* A: the run that never stops. */
  T_ASSERT(run("A", NULL, "a.err") == 0, "run A failed (a.err)");
  T_ASSERT(count_lines("A/bar_history.csv") == 1 + 6000 / 50 + 1, "A: %d CSV lines",
           count_lines("A/bar_history.csv"));

  /* B: the same run, stopped by SIGINT once its output is under way (the CSV .part has rows
   * beyond the first field output's flush), so the handler is installed and steps remain. */
  build_args("B dir", NULL);
  pid_t pid = start(args, "b.err");
  for (int k = 0; k < 3000 && count_lines("B dir/bar_history.csv.part") < 3; ++k)
    usleep(10000);
  T_ASSERT(kill(pid, SIGINT) == 0, "kill");
  T_ASSERT(finish(pid) == 130, "B: exit status is not 130 (b.err)");
  copy_file("B dir/bar_checkpoint.h5", "early_checkpoint.h5");
  T_ASSERT(mkdir("F", 0777) == 0, "mkdir F");
  for (int k = 0; k < 3; ++k) { /* the output as the interrupted run left it */
    char from[256], to[256];
    snprintf(from, sizeof from, "B dir/%s", out_files[k]);
    snprintf(to, sizeof to, "F/%s", out_files[k]);
    copy_file(from, to);
  }

  /* the "continue with" command: everything the run was given, quoted for the shell */
  char *err = slurp("b.err", NULL), *hint = err ? strstr(err, "continue with\n  ") : NULL;
  T_ASSERT(hint, "B: no 'continue with' command:\n%s", err ? err : "");
  hint += strlen("continue with\n  ");
  *strchr(hint, '\n') = '\0';
  static const char *const parts[] = {" run ",
                                      " -o 'B dir'",
                                      " --set solver.steps=" STEPS,
                                      " --set output.history_interval=50",
                                      " --set 'description=it'\\''s a bar, pulled'",
                                      " --threads 2",
                                      " -q",
                                      " --restart 'B dir/bar_checkpoint.h5'"};
  for (size_t k = 0; k < sizeof parts / sizeof parts[0]; ++k)
    T_ASSERT(strstr(hint, parts[k]), "the command '%s' lacks '%s'", hint, parts[k]);
  /* pasted into a shell, it continues B into its folder: the files of A */
  char *const sh[] = {"/bin/sh", "-c", hint, NULL};
  T_ASSERT(finish(start(sh, "hint.err")) == 0, "the pasted command failed: %s (hint.err)", hint);
  assert_same_as_a("B dir", "Ctrl-C, then the printed command");

  /* from the earlier checkpoint into the finished output: the later records are dropped and
   * written again */
  const char *const early[] = {"--restart", "early_checkpoint.h5", NULL};
  T_ASSERT(run("B dir", early, "early.err") == 0, "restart from the early checkpoint (early.err)");
  assert_same_as_a("B dir", "a restart from an earlier checkpoint");

  /* the checkpoint at the end: nothing to do, nothing touched */
  snapshot before;
  take("B dir", &before);
  T_ASSERT(finish(start(sh, "again.err")) == 0, "the command run again failed (again.err)");
  assert_err("again.err", "nothing to do", "a restart at the end");
  assert_unchanged("B dir", &before, "a restart at the end");
  free_snapshot(&before);

  /* a later end: the run goes on, after every row it had */
  const char *const longer[] = {"--set", "solver.steps=6500", "--restart",
                                "B dir/bar_checkpoint.h5", NULL};
  T_ASSERT(run("B dir", longer, "longer.err") == 0, "restart to 6500 steps (longer.err)");
  size_t la, lb;
  char *a_csv = slurp("A/bar_history.csv", &la), *b_csv = slurp("B dir/bar_history.csv", &lb);
  T_ASSERT(lb > la && !memcmp(a_csv, b_csv, la) &&
               count_lines("B dir/bar_history.csv") == count_lines("A/bar_history.csv") + 10,
           "the longer run's history does not continue A's: %d lines against %d",
           count_lines("B dir/bar_history.csv"), count_lines("A/bar_history.csv"));
  free(a_csv);
  free(b_csv);

  /* another run's output in the folder: refused, left alone */
  const char *const other[] = {"--set", "output.history_interval=100", "--set", "solver.steps=2000",
                               NULL};
  T_ASSERT(run("C", other, "c.err") == 0, "run C (c.err)");
  take("C", &before);
  T_ASSERT(run("C", early, "c_restart.err") == 2, "a restart into another run's output did not "
                                                  "exit 2 (c_restart.err)");
  assert_err("c_restart.err", "cannot be continued", "another run's output");
  assert_unchanged("C", &before, "another run's output");
  free_snapshot(&before);

  /* an output that ends before the checkpoint (F: as the interrupted run left it; the
   * checkpoint: A's at the end): refused, left alone */
  take("F", &before);
  const char *const late[] = {"--set", "solver.steps=6500", "--restart", "A/bar_checkpoint.h5",
                              NULL};
  T_ASSERT(run("F", late, "f.err") == 2,
           "a restart into an output that ends before the checkpoint did not exit 2 (f.err)");
  assert_err("f.err", "before the checkpoint's step 6000", "an output that ends early");
  assert_unchanged("F", &before, "an output that ends early");
  free_snapshot(&before);
  free(err);
  return 0;
}
