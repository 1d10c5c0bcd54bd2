/* Run output, the history plot: <name>_history.gp drawing the history CSV, and gnuplot run on it
 * (and on the field snapshot's script) without a shell (src/io/output.c, src/io/output_impl.h).
 */
#define _DEFAULT_SOURCE /* fork, execlp, pipe, access */
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "output_impl.h"
#include "pdk/ctx.h"
#include "pdk/output.h"

/* ---- plot -------------------------------------------------------------------------------------
 */

/* Component of reaction set k with the largest |value| over the run. */
static int main_component(const pdk_output *o, int k) {
  int best = 0;
  for (int c = 1; c < o->dim; ++c)
    if (o->col_absmax[o->reaction_col[k] + c] > o->col_absmax[o->reaction_col[k] + best]) best = c;
  return best;
}

/* 1 when set k has a displacement column and moved along its main reaction component. */
static int moved(const pdk_output *o, int k) {
  return o->disp_col[k] >= 0 && o->col_absmax[o->disp_col[k] + main_component(o, k)] > 0;
}

/* Writes the gnuplot script (as .part; committed by the caller). CSV columns are 1-based. */
int pdk_out_write_plot_script(pdk_output *o) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  char *stem = pdk_out_gnuplot_quote(o->name);
  FILE *f = NULL;
  PDK_CHECK_GOTO(stem, ctx, PDK_ERR_MEMORY, "out of memory");
  f = fopen(o->part[OUT_GP], "w");
  PDK_CHECK_GOTO(f, ctx, PDK_ERR_IO, "cannot create '%s': %s", o->part[OUT_GP], strerror(errno));
  int num_disp =
      0; /* sets that moved: plotting a fixed set against its zero displacement says nothing */
  for (int k = 0; k < o->num_reaction; ++k)
    num_disp += moved(o, k);
  /* a failure panel when any particle took Johnson-Cook damage */
  const int fail_col = o->work_col + 4, dmax_col = o->work_col + 5;
  const int damage_panel = o->col_absmax[dmax_col] > 0;
  int panels = 1 + (o->num_reaction > 0) + (num_disp > 0) + damage_panel;
  fprintf(f, "# pdk history plot; rerun with: gnuplot %s%s_history.gp (in this directory)\n",
          o->name[0] == '-' ? "./" : "", o->name);
  fprintf(f, "if (!exists(\"outfile\")) outfile = '%s_history.png'\n", stem);
  fprintf(f,
          "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
          "  set terminal pngcairo size %d,%d noenhanced\n} else {\n"
          "  set terminal png size %d,%d noenhanced\n}\n",
          500 * panels, 580, 500 * panels, 580); /* 580: room for the legends below */
  fprintf(f, "set output outfile\nset datafile separator ','\nset grid\n"
             "set key below\n" /* legends under the panels, clear of the curves */
             "set format x '%%g'\nset format y '%%g'\nset xtics rotate by 30 right\n");
  /* Time in the unit that fits the run (seconds: ms below 1 s, us below 1 ms): the column
   * $2 times tscale. */
  double tscale = 1.0;
  const char *tunit = o->unit_time;
  if (!strcmp(o->unit_time, "s") && o->col_absmax[1] > 0) {
    if (o->col_absmax[1] < 1e-3)
      tscale = 1e6, tunit = "us";
    else if (o->col_absmax[1] < 1.0)
      tscale = 1e3, tunit = "ms";
  }
  fprintf(f, "tscale = %g\n", tscale);
  /* 2-D: forces are those on the body's thickness (volumes are area x thickness) */
  char rlabel[128];
  if (o->dim == 2 && o->thickness > 0)
    snprintf(rlabel, sizeof rlabel, "reaction [%s] on the thickness %g %s", o->unit_force,
             o->thickness, o->unit_length);
  else if (o->dim == 2)
    snprintf(rlabel, sizeof rlabel, "reaction [%s] on the thickness of the body", o->unit_force);
  else
    snprintf(rlabel, sizeof rlabel, "reaction [%s]", o->unit_force);
  fprintf(f, "if (!exists(\"data\")) data = '%s_history.csv'\n", stem);
  fprintf(f, "set multiplot layout 1,%d title '%s'\n", panels, stem);
  if (o->num_reaction > 0) {
    fprintf(f, "set xlabel 'time [%s]'\nset ylabel '%s'\nplot ", tunit, rlabel);
    for (int k = 0; k < o->num_reaction; ++k) {
      int c = main_component(o, k);
      fprintf(f, "%sdata skip 1 using ($2*tscale):%d with lines title '%s %s'",
              k ? ", \\\n     " : "",
              o->reaction_col[k] + c + 1, o->reaction_name[k], axis_name[c]);
    }
    fprintf(f, "\n");
  }
  if (num_disp > 0) {
    fprintf(f, "set xlabel 'mean displacement of the set [%s]'\nset ylabel '%s'\nplot ",
            o->unit_length, rlabel);
    int first = 1;
    for (int k = 0; k < o->num_reaction; ++k) {
      if (!moved(o, k)) continue;
      int c = main_component(o, k);
      fprintf(f, "%sdata skip 1 using %d:%d with lines title '%s %s'", first ? "" : ", \\\n     ",
              o->disp_col[k] + c + 1, o->reaction_col[k] + c + 1, o->reaction_name[k],
              axis_name[c]);
      first = 0;
    }
    fprintf(f, "\n");
  }
  fprintf(f, "set xlabel 'time [%s]'\nset ylabel 'energy [%s]'\n", tunit, o->unit_energy);
  fprintf(f, "plot data skip 1 using ($2*tscale):3 with lines title 'kinetic', \\\n"
             "     data skip 1 using ($2*tscale):4 with lines title 'strain', \\\n");
  /* Dissipation curves only when the run dissipated: plastic, damage, bond breaking. */
  const char *work_title[3] = {"plastic work", "damage", "bond breaking"};
  int any_work = 0;
  for (int k = 0; k < 3; ++k) {
    if (!(o->col_absmax[o->work_col + k] > 0)) continue;
    fprintf(f, "     data skip 1 using ($2*tscale):%d with lines title '%s', \\\n",
            o->work_col + k + 1,
            work_title[k]);
    any_work = 1;
  }
  if (any_work)
    fprintf(f,
            "     data skip 1 using ($2*tscale):($3+$4+$%d+$%d+$%d) with lines title 'kinetic + "
            "strain + "
            "dissipated', \\\n",
            o->work_col + 1, o->work_col + 2, o->work_col + 3);
  else
    fprintf(f, "     data skip 1 using ($2*tscale):($3+$4) with lines title 'kinetic + strain', "
               "\\\n");
  fprintf(f, "     data skip 1 using ($2*tscale):5 with lines dashtype 2 title 'external work'\n");
  if (damage_panel)
    fprintf(f,
            "set xlabel 'time [%s]'\nset ylabel 'failed particles'\nset y2label 'largest damage'\n"
            "set y2tics\nset ytics nomirror\nset yrange [0:*]\nset y2range [0:*]\n"
            "plot data skip 1 using ($2*tscale):%d with lines title 'failed particles', \\\n"
            "     data skip 1 using ($2*tscale):%d axes x1y2 with lines title 'largest damage'\n",
            tunit, fail_col + 1, dmax_col + 1);
  fprintf(f, "unset multiplot\nset output\n");
  PDK_CHECK_GOTO(fflush(f) == 0 && !ferror(f), ctx, PDK_ERR_IO, "cannot write '%s': %s",
                 o->part[OUT_GP], strerror(errno));
cleanup:
  if (f) fclose(f);
  free(stem);
  return err;
}

/* File name of o->part[f] or o->final[f] without the directory. */
static const char *base_name(const pdk_output *o, const char *path) {
  return path + strlen(o->dir) + 1;
}

/* Runs gnuplot in o->dir on the script o->part[gp], reading the data o->part[data] and writing
 * the PNG o->part[png]: the new files keep their temporary names until every one is complete.
 * No shell is involved: gnuplot gets an argument vector, the script as "./<file>" (a name
 * starting with '-' is not an option) and the two file names as single-quoted gnuplot strings
 * ('' for ', the only character special there; the output name has no control character). When
 * gnuplot fails its stderr goes into the error message and no PNG is left. */
int pdk_out_run_gnuplot(pdk_output *o, int gp, int png, int data) {
  pdk_ctx *ctx = o->ctx;
  int err = PDK_SUCCESS;
  int pipefd[2] = {-1, -1};
  char msg[1024] = "";
  size_t msg_len = 0;
  char *script = pdk_str_printf("./%s", base_name(o, o->part[gp]));
  char *q_png = pdk_out_gnuplot_quote(base_name(o, o->part[png]));
  char *q_data = pdk_out_gnuplot_quote(base_name(o, o->part[data]));
  char *expr = q_png && q_data ? pdk_str_printf("outfile='%s'; data='%s'", q_png, q_data) : NULL;
  PDK_CHECK_GOTO(script && expr, ctx, PDK_ERR_MEMORY, "out of memory");
  PDK_CHECK_GOTO(pipe(pipefd) == 0, ctx, PDK_ERR_EXTERNAL, "pipe() for gnuplot failed: %s",
                 strerror(errno));
  fflush(NULL);
  pid_t pid = fork();
  PDK_CHECK_GOTO(pid >= 0, ctx, PDK_ERR_EXTERNAL, "fork() for gnuplot failed: %s", strerror(errno));
  if (pid == 0) { /* child: only async-signal-safe calls until exec */
    int devnull = open("/dev/null", O_RDWR);
    if (devnull >= 0) {
      dup2(devnull, 0);
      dup2(devnull, 1);
    }
    dup2(pipefd[1], 2);
    close(pipefd[0]);
    if (chdir(o->dir) != 0) _exit(126);
    execlp("gnuplot", "gnuplot", "-e", expr, script, (char *)NULL);
    _exit(127);
  }
  close(pipefd[1]);
  pipefd[1] = -1;
  for (;;) {
    char buf[512];
    ssize_t got = read(pipefd[0], buf, sizeof buf);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    size_t take = (size_t)got < sizeof msg - 1 - msg_len ? (size_t)got : sizeof msg - 1 - msg_len;
    memcpy(msg + msg_len, buf, take);
    msg_len += take;
  }
  msg[msg_len] = '\0';
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  for (size_t k = 0; k < msg_len; ++k)
    if (msg[k] == '\n') msg[k] = ' ';
  PDK_CHECK_GOTO(WIFEXITED(status) && WEXITSTATUS(status) == 0 && pdk_file_exists(o->part[png]),
                 ctx, PDK_ERR_EXTERNAL,
                 "gnuplot failed on '%s' (%s %d)%s%s; the data files are complete, only the plot "
                 "is missing: rerun 'gnuplot %s%s' in '%s'",
                 o->final[gp], WIFEXITED(status) ? "exit status" : "signal",
                 WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status), msg_len ? ": " : "",
                 msg, o->name[0] == '-' ? "./" : "", base_name(o, o->final[gp]), o->dir);
cleanup:
  if (err) pdk_file_remove(o->part[png]);
  if (pipefd[0] >= 0) close(pipefd[0]);
  if (pipefd[1] >= 0) close(pipefd[1]);
  free(script);
  free(q_png);
  free(q_data);
  free(expr);
  return err;
}
