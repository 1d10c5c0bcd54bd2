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
 * (h5diff is not needed: the HDF5 files are compared here, object by object.)
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

/* ---- HDF5 comparison: the same objects, attributes and dataset bytes (what h5diff compares) */

typedef struct names {
  char **name;
  int n;
} names;

static herr_t collect_attr(hid_t loc, const char *name, const H5A_info_t *info, void *data) {
  (void)loc;
  (void)info;
  names *nm = data;
  nm->name = realloc(nm->name, (size_t)(nm->n + 1) * sizeof *nm->name);
  nm->name[nm->n++] = strdup(name);
  return 0;
}

static void free_names(names *nm) {
  for (int k = 0; k < nm->n; ++k)
    free(nm->name[k]);
  free(nm->name);
}

/* Same type, extent and bytes of two attributes (is_attr) or datasets. */
static int same_data(hid_t a, hid_t b, int is_attr, const char *what, char *why, size_t cap) {
  hid_t ta = is_attr ? H5Aget_type(a) : H5Dget_type(a),
        tb = is_attr ? H5Aget_type(b) : H5Dget_type(b);
  hid_t sa = is_attr ? H5Aget_space(a) : H5Dget_space(a),
        sb = is_attr ? H5Aget_space(b) : H5Dget_space(b);
  int same = H5Tequal(ta, tb) > 0 && H5Sextent_equal(sa, sb) > 0;
  if (!same) snprintf(why, cap, "%s: another type or shape", what);
  if (same) {
    const size_t bytes = (size_t)H5Sget_simple_extent_npoints(sa) * H5Tget_size(ta);
    unsigned char *x = malloc(bytes + 1), *y = malloc(bytes + 1);
    if (bytes) {
      T_ASSERT(
          (is_attr ? H5Aread(a, ta, x) : H5Dread(a, ta, H5S_ALL, H5S_ALL, H5P_DEFAULT, x)) >= 0 &&
              (is_attr ? H5Aread(b, tb, y) : H5Dread(b, tb, H5S_ALL, H5S_ALL, H5P_DEFAULT, y)) >= 0,
          "%s: cannot read", what);
    }
    same = !memcmp(x, y, bytes);
    if (!same) {
      size_t k = 0;
      while (x[k] == y[k])
        ++k;
      snprintf(why, cap, "%s: bytes differ from byte %zu of %zu", what, k, bytes);
    }
    free(x);
    free(y);
  }
  H5Tclose(ta);
  H5Tclose(tb);
  H5Sclose(sa);
  H5Sclose(sb);
  return same;
}

static int same_attrs(hid_t a, hid_t b, const char *path, char *why, size_t cap) {
  names na = {0}, nb = {0};
  hsize_t i = 0, j = 0;
  H5Aiterate2(a, H5_INDEX_NAME, H5_ITER_INC, &i, collect_attr, &na);
  H5Aiterate2(b, H5_INDEX_NAME, H5_ITER_INC, &j, collect_attr, &nb);
  int same = na.n == nb.n;
  if (!same) snprintf(why, cap, "%s: %d attributes against %d", path, na.n, nb.n);
  for (int k = 0; same && k < na.n; ++k) {
    char what[1024];
    snprintf(what, sizeof what, "%s attribute '%s'", path, na.name[k]);
    same = !strcmp(na.name[k], nb.name[k]);
    if (!same) {
      snprintf(why, cap, "%s: attribute '%s' against '%s'", path, na.name[k], nb.name[k]);
      break;
    }
    hid_t x = H5Aopen(a, na.name[k], H5P_DEFAULT), y = H5Aopen(b, nb.name[k], H5P_DEFAULT);
    same = same_data(x, y, 1, what, why, cap);
    H5Aclose(x);
    H5Aclose(y);
  }
  free_names(&na);
  free_names(&nb);
  return same;
}

static int same_group(hid_t a, hid_t b, const char *path, char *why, size_t cap) {
  if (!same_attrs(a, b, path, why, cap)) return 0;
  H5G_info_t ia, ib;
  H5Gget_info(a, &ia);
  H5Gget_info(b, &ib);
  if (ia.nlinks != ib.nlinks) {
    snprintf(why, cap, "%s: %llu members against %llu", path, (unsigned long long)ia.nlinks,
             (unsigned long long)ib.nlinks);
    return 0;
  }
  for (hsize_t k = 0; k < ia.nlinks; ++k) {
    char na[256], nb[256], child[1024];
    H5Lget_name_by_idx(a, ".", H5_INDEX_NAME, H5_ITER_INC, k, na, sizeof na, H5P_DEFAULT);
    H5Lget_name_by_idx(b, ".", H5_INDEX_NAME, H5_ITER_INC, k, nb, sizeof nb, H5P_DEFAULT);
    snprintf(child, sizeof child, "%s/%s", path, na);
    if (strcmp(na, nb)) {
      snprintf(why, cap, "%s: member '%s' against '%s'", path, na, nb);
      return 0;
    }
    hid_t x = H5Oopen(a, na, H5P_DEFAULT), y = H5Oopen(b, nb, H5P_DEFAULT);
    int same = H5Iget_type(x) == H5Iget_type(y);
    if (!same) snprintf(why, cap, "%s: another kind of object", child);
    if (same && H5Iget_type(x) == H5I_GROUP)
      same = same_group(x, y, child, why, cap);
    else if (same)
      same = same_attrs(x, y, child, why, cap) && same_data(x, y, 0, child, why, cap);
    H5Oclose(x);
    H5Oclose(y);
    if (!same) return 0;
  }
  return 1;
}

static int same_h5(const char *a, const char *b, char *why, size_t cap) {
  hid_t fa = H5Fopen(a, H5F_ACC_RDONLY, H5P_DEFAULT), fb = H5Fopen(b, H5F_ACC_RDONLY, H5P_DEFAULT);
  T_ASSERT(fa >= 0 && fb >= 0, "cannot open %s or %s", a, b);
  const int same = same_group(fa, fb, "", why, cap);
  H5Fclose(fa);
  H5Fclose(fb);
  return same;
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
  T_ASSERT(same_h5("A/bar.h5", x, why, sizeof why), "%s: %s differs from A/bar.h5: %s", what, x,
           why);
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
