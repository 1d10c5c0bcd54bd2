/* Output names that reach the gnuplot scripts and the gnuplot command line, through the C API
 * (the scene layer checks names too; the output layer must be safe on its own):
 *   - a name with a control character (a newline can end a gnuplot string and start a command)
 *     is refused at open, before any file is made, and runs nothing;
 *   - a name starting with '-' plots like any other (gnuplot must not read the script's name as
 *     an option): both PNGs are made and close succeeds;
 *   - names holding gnuplot's special characters (', `, @, \, ", ;, #, $) plot, and none of
 *     them runs a command: the marker files the names ask for are never created.
 * The PNGs need gnuplot (README: gnuplot-nox); without it the test fails, saying so.
 * Test files go to ./t180_out.
 * labels: unit */
#include "output_util.h"

#define DIR_OUT "t180_out"

/* Opens, writes and closes an output called `name`; returns close's code. */
static int run(pdk_ctx *ctx, pdk_particles *p, const char *name) {
  pdk_output_opts oo = ou_opts(DIR_OUT, name);
  pdk_output *o = NULL;
  T_OK(ctx, pdk_output_open(ctx, &oo, p, &o));
  T_ASSERT(pdk_output_will_plot(o), "gnuplot was found at open");
  T_OK(ctx, ou_write(o, p, 4, 1.0));
  return pdk_output_close(&o, 1);
}

int main(void) {
  T_ASSERT(ou_on_path("gnuplot"), "gnuplot is not on the PATH; it is a test dependency (README "
                                  "Quick start: gnuplot-nox)");
  pdk_ctx *ctx = t_ctx(1);
  pdk_particles *p = ou_store(ctx);
  char list[4096];
  ou_clean(DIR_OUT);

  /* 1. Control characters: refused at open, nothing made, nothing run. */
  const char *bad[] = {"m\nsystem(\"touch INJECTED\")\n#", "tab\there", "cr\rx", "del\x7f"};
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
    pdk_output_opts oo = ou_opts(DIR_OUT, bad[k]);
    pdk_output *o = NULL;
    T_FAILS(ctx, pdk_output_open(ctx, &oo, p, &o), PDK_ERR_ARG, "control character");
    T_ASSERT(!o, "no output handle after a refused open");
    T_ASSERT(ou_list(DIR_OUT, list, sizeof list) == 0, "a refused name made files:\n%s", list);
  }
  T_ASSERT(!ou_exists(".", "INJECTED") && !ou_exists(DIR_OUT, "INJECTED"), "a name ran a command");

  /* 2. A leading '-': the plots are made, close succeeds. */
  pdk_ctx_error_clear(ctx);
  int err = run(ctx, p, "-rf");
  T_ASSERT(!err, "close of '-rf' failed: %s", pdk_ctx_error_message(ctx));
  T_ASSERT(ou_exists(DIR_OUT, "-rf_history.png") && ou_exists(DIR_OUT, "-rf_fields.png") &&
               ou_exists(DIR_OUT, "-rf.xmf"),
           "'-rf' has its PNGs and .xmf:\n%s", (ou_list(DIR_OUT, list, sizeof list), list));

  /* 3. Characters special to gnuplot: every name plots and runs nothing. */
  const char *odd[] = {
      "q'; system('touch INJECTED1'); '",     /* closes a single-quoted string */
      "b`touch INJECTED2`",                   /* backquote substitution */
      "m@cmd x",                              /* macro substitution */
      "s\\",                                  /* backslash: line continuation */
      "d\"; system(\"touch INJECTED3\"); \"", /* closes a double-quoted string */
      "h # ; $1 |x| {y} [z]",                 /* comment, separator, column, brackets */
      "u\xc3\xa9",                            /* UTF-8 */
  };
  for (size_t k = 0; k < sizeof odd / sizeof odd[0]; ++k) {
    ou_clean(DIR_OUT);
    pdk_ctx_error_clear(ctx);
    err = run(ctx, p, odd[k]);
    T_ASSERT(!err, "close of '%s' failed: %s", odd[k], pdk_ctx_error_message(ctx));
    char png[512];
    snprintf(png, sizeof png, "%s_history.png", odd[k]);
    T_ASSERT(ou_exists(DIR_OUT, png), "'%s' has no history PNG", odd[k]);
    snprintf(png, sizeof png, "%s_fields.png", odd[k]);
    T_ASSERT(ou_exists(DIR_OUT, png), "'%s' has no field PNG", odd[k]);
    /* the .h5, .xmf, two CSVs, two scripts, two PNGs: nothing else */
    T_ASSERT(ou_list(DIR_OUT, list, sizeof list) == 8, "'%s' left:\n%s", odd[k], list);
  }
  T_ASSERT(!ou_exists(".", "INJECTED1") && !ou_exists(".", "INJECTED2") &&
               !ou_exists(".", "INJECTED3"),
           "a name ran a command");
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return 0;
}
