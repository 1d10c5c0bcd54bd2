/* V-Q study: reproduces Queiruga & Moridis 2017 Tables 3, 4, 5, 7, 8 and the spurious shear mode
 * (V-Q3-V-Q8, docs/validation/targets.md) with pdk's Newton solver. Problems and metrics:
 * tests/vq_util.h.
 *
 *   study_vq one <law> <problem> <omega> <rf> <np>   one solve (law F|silling|oterkus|oterkus_cal,
 *                                                     problem uniaxial|isotropic|shear|crack,
 *                                                     omega 0..4 = Const Inv Linear Quadr Cubic)
 *   study_vq table3|table4|table5|vq7|table7|table8  one table, Markdown on stdout
 *   study_vq table8f                                 Table 8's two F columns only
 *   options: --np a,b,c (NP list of the convergence fits), --threads N,
 *            --rf a,b (the RF rows of table4 and table5; default 1.5,2,2.5,3,3.5),
 *            --shift S (crack: its centre moved along x by S spacings; the grid offset at the
 *            crack tips), --rows R (crack: the outer R rows/columns hold the exact field, not 1)
 * docs/validation/queiruga.md lists the commands and their output; bench/run_vq_study.sh runs all.
 */
#include "../tests/vq_util.h"

static int g_threads = 2;
static int g_np[64], g_nnp = 0;
static double g_rf[5];
static int g_nrf = 0; /* --rf: the RF rows of tables 4 and 5 (default all five) */
static double g_shift = 0.0; /* --shift: the crack's centre moved along x by this many spacings */
static int g_rows = 1;       /* --rows: outer rows holding the exact field in the crack problem */

static const int np_default[] = {100, 140, 200, 280};

static int parse_law(const char *s, vq_law *law, pdk_oterkus_a *oa) {
  *oa = PDK_OTERKUS_A_PUBLISHED;
  if (!strcmp(s, "F")) *law = VQ_F;
  else if (!strcmp(s, "silling")) *law = VQ_SILLING;
  else if (!strcmp(s, "oterkus")) *law = VQ_OTERKUS;
  else if (!strcmp(s, "oterkus_cal")) {
    *law = VQ_OTERKUS;
    *oa = PDK_OTERKUS_A_CALIBRATED;
  } else return 1;
  return 0;
}

static int run(pdk_ctx *ctx, vq_case c, vq_result *r) {
  c.threads = g_threads;
  c.crack_shift = g_shift;
  c.crack_rows = g_rows;
  if (vq_run(ctx, &c, r)) exit(1);
  fprintf(stderr, "  %s %s %s RF %.1f NP %d: probe %.6e err %.4e spur %.3e crack %.4f/%.4f %.1f s\n",
          vq_law_name[c.law], vq_problem_name[c.problem], "", c.rf, c.np, r->probe, r->rel_error,
          r->spurious, r->err_all, r->err_win, r->seconds);
  return 0;
}

/* Order of convergence of one (law, problem, omega, rf) over the NP list; also the finest error. */
static double order(pdk_ctx *ctx, vq_law law, pdk_oterkus_a oa, vq_problem pb, pdk_influence w,
                    double rf, double *finest) {
  double err[64] = {0};
  for (int k = 0; k < g_nnp; ++k) {
    vq_case c = {pb, law, w, rf, g_np[k], oa, g_threads, 0.0, 0};
    vq_result r;
    run(ctx, c, &r);
    err[k] = r.rel_error;
  }
  *finest = err[g_nnp - 1];
  return vq_slope(g_nnp, g_np, err);
}

static const double rfs[5] = {1.5, 2.0, 2.5, 3.0, 3.5};

static void np_line(void) {
  printf("NP = ");
  for (int k = 0; k < g_nnp; ++k) printf("%s%d", k ? ", " : "", g_np[k]);
  printf(" (h = 10 mm / NP); order = least-squares slope of log e vs log h\n\n");
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: see the header of bench/study_vq.c\n");
    return 2;
  }
  const char *mode = argv[1];
  int first_opt = !strcmp(mode, "one") ? 7 : 2;
  if (argc < first_opt) {
    fprintf(stderr, "study_vq one: needs <law> <problem> <omega> <rf> <np>\n");
    return 2;
  }
  for (int k = first_opt; k < argc; ++k) {
    if (!strcmp(argv[k], "--threads") && k + 1 < argc) g_threads = atoi(argv[++k]);
    else if (!strcmp(argv[k], "--np") && k + 1 < argc) {
      char *s = argv[++k];
      g_nnp = 0;
      for (char *t = strtok(s, ","); t && g_nnp < 64; t = strtok(NULL, ",")) g_np[g_nnp++] = atoi(t);
    } else if (!strcmp(argv[k], "--rf") && k + 1 < argc) {
      char *s = argv[++k];
      g_nrf = 0;
      for (char *t = strtok(s, ","); t && g_nrf < 5; t = strtok(NULL, ",")) g_rf[g_nrf++] = atof(t);
    } else if (!strcmp(argv[k], "--shift") && k + 1 < argc) {
      g_shift = atof(argv[++k]);
    } else if (!strcmp(argv[k], "--rows") && k + 1 < argc) {
      g_rows = atoi(argv[++k]);
    } else {
      fprintf(stderr, "study_vq: unknown option '%s'\n", argv[k]);
      return 2;
    }
  }
  if (!g_nnp) {
    g_nnp = (int)(sizeof np_default / sizeof np_default[0]);
    memcpy(g_np, np_default, sizeof np_default);
  }
  pdk_ctx_opts co = pdk_ctx_opts_default();
  co.num_threads = g_threads;
  pdk_ctx *ctx = NULL;
  char ebuf[256];
  if (pdk_ctx_create(&co, &ctx, ebuf, sizeof ebuf)) {
    fprintf(stderr, "study_vq: cannot create the context: %s\n", ebuf);
    return 1;
  }
  if (!strcmp(mode, "one")) {
    vq_case c;
    memset(&c, 0, sizeof c);
    if (parse_law(argv[2], &c.law, &c.oterkus_a)) {
      fprintf(stderr, "study_vq: unknown law '%s' (F, silling, oterkus, oterkus_cal)\n", argv[2]);
      return 2;
    }
    int pb = -1;
    for (int k = 0; k < 4; ++k)
      if (!strcmp(argv[3], vq_problem_name[k])) pb = k;
    const int wi = atoi(argv[4]);
    if (pb < 0 || wi < 0 || wi > 4) {
      fprintf(stderr, "study_vq: bad problem '%s' or omega '%s'\n", argv[3], argv[4]);
      return 2;
    }
    c.problem = (vq_problem)pb;
    c.omega = vq_omega[wi];
    c.rf = atof(argv[5]);
    c.np = atoi(argv[6]);
    vq_result r;
    run(ctx, c, &r);
    printf("n %d nnz %ld time %.2f s\n", (int)r.n, r.tangent_nnz, r.seconds);
    if (c.problem == VQ_CRACK)
      printf("error all %.4f window %.4f; smoothed const/linear/cubic window %.4f %.4f %.4f all "
             "%.4f %.4f %.4f; max opening %.4f mm\n",
             r.err_all, r.err_win, r.err_win_s[0], r.err_win_s[1], r.err_win_s[2], r.err_all_s[0],
             r.err_all_s[1], r.err_all_s[2], r.max_opening);
    else
      printf("probe %.8e exact %.3e relative error %.4e spurious u_y (shear) %.4e, centre %.4e\n",
             r.probe, r.exact, r.rel_error, r.spurious, r.spurious_centre);
  } else if (!strcmp(mode, "table3")) {
    printf("Table 3: order of convergence, F-based law, RF = 1.5. ");
    np_line();
    printf("| w(r) | Uniaxial | Shear | Isotropic | e at NP %d (uni/shear/iso) |\n", g_np[g_nnp - 1]);
    printf("|---|---|---|---|---|\n");
    const vq_problem pbs[3] = {VQ_UNIAXIAL, VQ_SHEAR, VQ_ISOTROPIC};
    for (int w = 0; w < 5; ++w) {
      double o[3], f[3];
      for (int k = 0; k < 3; ++k)
        o[k] = order(ctx, VQ_F, 0, pbs[k], vq_omega[w], 1.5, &f[k]);
      printf("| %s | %.4f | %.4f | %.4f | %.2e / %.2e / %.2e |\n", vq_omega_name[w], o[0], o[1],
             o[2], f[0], f[1], f[2]);
      fflush(stdout);
    }
  } else if (!strcmp(mode, "table4") || !strcmp(mode, "table5")) {
    const int t5 = !strcmp(mode, "table5");
    if (t5) {
      printf("Table 5: dilatation laws, cubic w: order on every problem (the paper lists Silling "
             "isotropic and Oterkus shear) and the relative error at the finest NP. ");
      np_line();
      printf("| RF | law | Uniaxial order (e) | Shear order (e) | Isotropic order (e) |\n");
      printf("|---|---|---|---|---|\n");
    } else {
      printf("Table 4: order of convergence, F-based law, cubic w. ");
      np_line();
      printf("| RF | Uniaxial | Shear | Isotropic | e at NP %d (uni/shear/iso) |\n",
             g_np[g_nnp - 1]);
      printf("|---|---|---|---|---|\n");
    }
    const vq_problem pbs[3] = {VQ_UNIAXIAL, VQ_SHEAR, VQ_ISOTROPIC};
    const vq_law laws[3] = {VQ_SILLING, VQ_OTERKUS, VQ_OTERKUS};
    const pdk_oterkus_a oas[3] = {0, PDK_OTERKUS_A_PUBLISHED, PDK_OTERKUS_A_CALIBRATED};
    const char *lname[3] = {"Silling", "Oterkus (a = (K-2G)/2, as published)",
                            "Oterkus (a calibrated, eq. 13 with lambda+mu)"};
    if (!g_nrf) {
      g_nrf = 5;
      memcpy(g_rf, rfs, sizeof rfs);
    }
    for (int ri = 0; ri < g_nrf; ++ri) {
      for (int li = 0; li < (t5 ? 2 : 1); ++li) {
        double o[3], f[3];
        for (int k = 0; k < 3; ++k)
          o[k] = order(ctx, t5 ? laws[li] : VQ_F, t5 ? oas[li] : 0, pbs[k], PDK_INFLUENCE_CUBIC,
                       g_rf[ri], &f[k]);
        if (t5)
          printf("| %.1f | %s | %.4f (%.2e) | %.4f (%.2e) | %.4f (%.2e) |\n", g_rf[ri], lname[li],
                 o[0], f[0], o[1], f[1], o[2], f[2]);
        else
          printf("| %.1f | %.4f | %.4f | %.4f | %.2e / %.2e / %.2e |\n", g_rf[ri], o[0], o[1], o[2],
                 f[0], f[1], f[2]);
        fflush(stdout);
      }
    }
  } else if (!strcmp(mode, "vq7")) {
    const int np = g_np[g_nnp - 1];
    printf("Spurious u_y in simple shear, cubic w, NP = %d (%d x %d particles): max |u_y| over "
           "the block and on the column(s) nearest x = W/2, over the exact top u_x (2e-5 mm)\n\n",
           np, np + 1, np + 1);
    printf("| law | RF | max |u_y| / u_x (block) | (centre column) | top u_x error |\n"
           "|---|---|---|---|---|\n");
    const vq_law laws[3] = {VQ_F, VQ_F, VQ_SILLING};
    const double rf[3] = {3.5, 1.5, 3.5};
    for (int k = 0; k < 4; ++k) {
      vq_case c = {VQ_SHEAR, k < 3 ? laws[k] : VQ_OTERKUS, PDK_INFLUENCE_CUBIC, k < 3 ? rf[k] : 3.5,
                   np, 0, g_threads, 0.0, 0};
      vq_result r;
      run(ctx, c, &r);
      printf("| %s | %.1f | %.4f | %.4f | %.4f |\n", vq_law_name[c.law], c.rf, r.spurious,
             r.spurious_centre, r.rel_error);
      fflush(stdout);
    }
  } else if (!strcmp(mode, "table7")) {
    const int np = g_nnp == 1 ? g_np[0] : 200;
    printf("Table 7: pressurized crack, F-based law, cubic w, NP = %d: relative L2 error of the "
           "displacement in the window |x - x_c|, |y - y_c| <= L, unsmoothed and smoothed with "
           "const, linear, cubic w (whole-domain errors in brackets)\n\n",
           np);
    printf("| RF | Unsmoothed | Const | Linear | Cubic | max opening (exact 1.1667 mm) |\n");
    printf("|---|---|---|---|---|---|\n");
    for (int ri = 0; ri < 5; ++ri) {
      vq_case c = {VQ_CRACK, VQ_F, PDK_INFLUENCE_CUBIC, rfs[ri], np, 0, g_threads, 0.0, 0};
      vq_result r;
      run(ctx, c, &r);
      printf("| %.1f | %.4f (%.4f) | %.4f (%.4f) | %.4f (%.4f) | %.4f (%.4f) | %.4f |\n", rfs[ri],
             r.err_win, r.err_all, r.err_win_s[0], r.err_all_s[0], r.err_win_s[1], r.err_all_s[1],
             r.err_win_s[2], r.err_all_s[2], r.max_opening);
      fflush(stdout);
    }
  } else if (!strcmp(mode, "table8") || !strcmp(mode, "table8f")) {
    /* table8f: the two F columns only (each solve takes seconds; the dilatation laws at RF 3.5
     * need minutes to tens of minutes per solve with the difference tangent). */
    const int ncol = !strcmp(mode, "table8f") ? 2 : 4;
    printf("Table 8: pressurized crack, cubic w, whole-domain relative L2 error against NP "
           "(h = 16000 mm / NP)\n\n");
    printf("| NP | F RF 1.5 | F RF 1.5 smoothed (linear) |%s\n",
           ncol == 4 ? " Silling RF 3.5 | Oterkus RF 3.5 |" : "");
    printf("|---|---|---|%s\n", ncol == 4 ? "---|---|" : "");
    double e[4][64];
    for (int k = 0; k < g_nnp; ++k) {
      vq_case cf = {VQ_CRACK, VQ_F, PDK_INFLUENCE_CUBIC, 1.5, g_np[k], 0, g_threads, 0.0, 0};
      vq_result rf;
      run(ctx, cf, &rf);
      e[0][k] = rf.err_all;
      e[1][k] = rf.err_all_s[1];
      if (ncol == 4) {
        vq_case cs = {VQ_CRACK, VQ_SILLING, PDK_INFLUENCE_CUBIC, 3.5, g_np[k], 0, g_threads, 0.0, 0};
        vq_case co2 = {VQ_CRACK, VQ_OTERKUS, PDK_INFLUENCE_CUBIC, 3.5, g_np[k], 0, g_threads, 0.0, 0};
        vq_result rs, ro;
        run(ctx, cs, &rs);
        run(ctx, co2, &ro);
        e[2][k] = rs.err_all;
        e[3][k] = ro.err_all;
      }
      printf("| %d |", g_np[k]);
      for (int m = 0; m < ncol; ++m) printf(" %.4f |", e[m][k]);
      printf("\n");
      fflush(stdout);
    }
    printf("| order (all NP) |");
    for (int m = 0; m < ncol; ++m) printf(" %.4f |", vq_slope(g_nnp, g_np, e[m]));
    /* The paper's fit (notes 002, Fig. 16): the last 21 points for F, the last 10 for the
     * dilatation laws, keeping only those with e < 1. */
    printf("\n| order (paper's fit: last 21 / 10 points, e < 1) |");
    for (int m = 0; m < ncol; ++m) {
      int npk[64], cnt = 0;
      double ek[64];
      const int last = m < 2 ? 21 : 10;
      for (int k = g_nnp > last ? g_nnp - last : 0; k < g_nnp; ++k)
        if (e[m][k] < 1.0) {
          npk[cnt] = g_np[k];
          ek[cnt++] = e[m][k];
        }
      if (cnt >= 2) printf(" %.4f (%d points) |", vq_slope(cnt, npk, ek), cnt);
      else printf(" n/a |");
    }
    printf("\n| min error |");
    for (int m = 0; m < ncol; ++m) {
      double mn = 1e300;
      for (int k = 0; k < g_nnp; ++k) mn = fmin(mn, e[m][k]);
      printf(" %.1f%% |", 100.0 * mn);
    }
    printf("\n");
  } else {
    fprintf(stderr, "study_vq: unknown mode '%s'\n", mode);
    return 2;
  }
  pdk_ctx_destroy(&ctx);
  return 0;
}
