/* Boundary conditions along a direction (pdk_bc.direction; scene: boundary_conditions[k].direction
 * and value): a roller on an inclined face.
 * 1. A 2-D PMB bar 30 x 6 particles (spacing 1 mm) as a point cloud, and the same cloud rotated by
 *    30 degrees (x' = Q X, exactly the aligned particles turned). Aligned: the left column held in
 *    x (one particle of it, the anchor, in x and y), the right column pulled 0.03 mm in x, both
 * free in y. Rotated: the same with the conditions along n = Q e_x (direction [cos 30, sin 30],
 *    value 0 and 0.03 mm), the anchor fixed in x and y. The rotated run's displacements turned
 *    back, Q^T u', equal the aligned run's, particle by particle (by id), and so do its reactions
 *    (Q^T R'): the rollers leave the tangential motion free and carry only normal forces.
 *    Tolerances, relative to the largest displacement (reaction): Newton (analytic tangent,
 *    tolerance 1e-12) 1e-8 and explicit (300 steps of dt 1e-7, a smooth pull; dt given, so that
 *    both runs step alike) 1e-8: both compare the same arithmetic up to the round-off of the
 *    turned positions (~1e-16 relative) amplified by the solve (measured 1.5e-13 and 1.0e-12);
 *    ADR 1e-6: both runs stop at the residual tolerance 1e-10, and the turned one moves its roller
 *    particles with other fictitious masses (sqrt(2) x their largest), so they stop at other
 *    points within that tolerance (measured 8.5e-9; PDK_VERBOSE prints the numbers).
 *    The history of the turned bar has reaction_right_n (and reaction_left_n), the reaction along
 *    n, equal to R'.n to the 17 digits of the CSV; the aligned bar's has no such column.
 *    Statics: the right roller's reaction has no tangential part, |R'.t| <= 1e-8 |R'.n| (the
 *    residual on the free tangents is at the solver's tolerance).
 *    3-D: a 12 x 3 x 3 bar turned by 40 degrees about (1, 2, 2) / 3, the rollers along Q e_x, two
 *    particles of the left face fixed (no rigid turn about the axis): Newton and explicit, the
 *    same tolerances and reasons (measured 1.3e-13 and 4.1e-13).
 * 2. Refusals: direction with x; direction without value; value without direction; a zero
 *    direction; a body force with a direction; a particle under a direction and another condition;
 *    Newton with the difference tangent.
 * Files: $PDK_BUILD_DIR/tests/t251_bc_direction.work.
 * labels: scene */
#include <sys/stat.h>

#include "work_util.h"

#define NX 30
#define NY 6
static const double H = 1e-3, DELTA = 3e-5;
static double cs, sn; /* cos 30, sin 30 */

/* The bar as a cloud, aligned (rot 0) or turned by 30 degrees. */
static void write_cloud(const char *name, int rot) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", work, name);
  FILE *f = fopen(path, "w");
  T_ASSERT(f != NULL, "cannot write %s", path);
  fprintf(f, "x, y, volume, set:left, set:anchor, set:right\n");
  for (int j = 0; j < NY; ++j)
    for (int i = 0; i < NX; ++i) {
      const double X = (i + 0.5) * H, Y = (j + 0.5) * H;
      const double x = rot ? cs * X - sn * Y : X, y = rot ? sn * X + cs * Y : Y;
      const int anchor = i == 0 && j == 2;
      fprintf(f, "%.17g,%.17g,%.17g,%d,%d,%d\n", x, y, H * H, i == 0 && !anchor, anchor,
              i == NX - 1);
    }
  T_ASSERT(fclose(f) == 0, "cannot write %s", path);
}

static const char scene_fmt[] = "name: bar\ndimension: 2\n"
                                "geometry: {points: %s, spacing: 1.0e-3, horizon_factor: 3.015}\n"
                                "material: {density: 8000, bulk_modulus: 1.0e9}\n"
                                "model: {kind: %s}\n"
                                "boundary_conditions:\n%s"
                                "solver: %s\n"
                                "output: {reactions: [left, anchor, right]}\n";

typedef struct result {
  double u[NX * NY][2];
  double R[3][2];
  double rn_right; /* the history's last reaction_right_n, NAN without the column */
} result;

/* The last value of history column `name` in csv, NAN when the header lacks it. */
static double history_last(const char *csv, const char *name) {
  FILE *f = fopen(csv, "r");
  T_ASSERT(f != NULL, "cannot open %s", csv);
  static char line[8192], last[8192];
  T_ASSERT(fgets(line, sizeof line, f) != NULL, "%s is empty", csv);
  int col = -1, k = 0;
  for (char *t = strtok(line, ","); t; t = strtok(NULL, ","), ++k)
    if (!strncmp(t, name, strlen(name)) && t[strlen(name)] == ' ') col = k;
  last[0] = '\0';
  while (fgets(line, sizeof line, f))
    memcpy(last, line, sizeof last);
  fclose(f);
  if (col < 0) return NAN;
  k = 0;
  for (char *t = strtok(last, ","); t; t = strtok(NULL, ","), ++k)
    if (k == col) return strtod(t, NULL);
  return NAN;
}

/* Runs the scene in work/<file>; u by id (the cloud's row order). */
/* Writes `text` to <work>/<file>, runs it with output in <work>/<file>.out, and returns the
 * simulation after the run (the caller destroys it and *scene); u[id][a] = x - X for a < dim. */
static pdk_sim *run_text(pdk_ctx *ctx, const char *file, const char *text, int dim, double *u,
                         pdk_run_report *rep, pdk_scene **scene, char *dir, size_t dir_size) {
  write_file(file, text);
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", work, file);
  snprintf(dir, dir_size, "%s/%s.out", work, file);
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, scene));
  T_OK(ctx, pdk_sim_create(ctx, *scene, &sim));
  pdk_run_opts o = pdk_run_opts_default();
  o.dir = dir;
  o.plot = 0;
  T_OK(ctx, pdk_sim_run(sim, *scene, &o, rep));
  pdk_particles *p = pdk_sim_particles(sim);
  const int64_t *id = pdk_particles_id(p);
  for (int a = 0; a < dim; ++a) {
    const double *x = pdk_particles_field_data(p, "x", a), *X = pdk_particles_X(p, a);
    for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
      u[dim * id[i] + a] = x[i] - X[i];
  }
  return sim;
}

static void run(pdk_ctx *ctx, const char *file, const char *text, result *res) {
  pdk_scene *scene = NULL;
  pdk_run_report rep;
  char dir[1024], csv[1200];
  pdk_sim *sim = run_text(ctx, file, text, 2, &res->u[0][0], &rep, &scene, dir, sizeof dir);
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 2; ++a)
      res->R[k][a] = rep.last.reaction[k][a];
  snprintf(csv, sizeof csv, "%s/bar_history.csv", dir);
  res->rn_right = history_last(csv, "reaction_right_n");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
}

/* max |Q^T u_rot - u_al| / max |u_al| and the same for the reactions. */
static void compare(const char *label, const result *al, const result *ro, double tol,
                    int statics) {
  double du = 0, um = 0, dr = 0, rm = 0;
  for (int i = 0; i < NX * NY; ++i) {
    const double bx = cs * ro->u[i][0] + sn * ro->u[i][1];
    const double by = -sn * ro->u[i][0] + cs * ro->u[i][1];
    du = fmax(du, fmax(fabs(bx - al->u[i][0]), fabs(by - al->u[i][1])));
    um = fmax(um, fmax(fabs(al->u[i][0]), fabs(al->u[i][1])));
  }
  for (int k = 0; k < 3; ++k) {
    const double bx = cs * ro->R[k][0] + sn * ro->R[k][1];
    const double by = -sn * ro->R[k][0] + cs * ro->R[k][1];
    dr = fmax(dr, fmax(fabs(bx - al->R[k][0]), fabs(by - al->R[k][1])));
    rm = fmax(rm, fmax(fabs(al->R[k][0]), fabs(al->R[k][1])));
  }
  if (getenv("PDK_VERBOSE"))
    printf("%-9s max u %.4e, |Q^T u' - u| / max %.3e; max R %.4e (right x %.6e), |Q^T R' - R| / "
           "max %.3e\n",
           label, um, du / um, rm, al->R[2][0], dr / rm);
  T_ASSERT(um > 0.5 * DELTA, "%s: the aligned bar did not stretch (max u %g)", label, um);
  T_ASSERT(du <= tol * um, "%s: the turned bar's displacements differ by %.3e of the largest",
           label, du / um);
  T_ASSERT(dr <= tol * rm, "%s: the turned bar's reactions differ by %.3e of the largest", label,
           dr / rm);
  const double rn = cs * ro->R[2][0] + sn * ro->R[2][1], rt = -sn * ro->R[2][0] + cs * ro->R[2][1];
  if (getenv("PDK_VERBOSE")) printf("%-9s right roller: R.n %.6e, R.t %.3e\n", label, rn, rt);
  T_ASSERT(rn > 0, "%s: the pulled roller's reaction along n is %g", label, rn);
  T_ASSERT(isnan(al->rn_right), "%s: the aligned bar's history has reaction_right_n", label);
  T_NEAR(ro->rn_right, rn, 1e-15, 0, "%s: the history's reaction_right_n against R.n", label);
  if (statics)
    T_ASSERT(fabs(rt) <= 1e-8 * rn, "%s: the roller carries a tangential force %g (normal %g)",
             label, rt, rn);
}

static void solver_case(pdk_ctx *ctx, const char *label, const char *solver, const char *fn,
                        double tol, int statics) {
  char bcs[1024], text[4096], file[64];
  result *al = calloc(1, sizeof *al), *ro = calloc(1, sizeof *ro);
  snprintf(bcs, sizeof bcs,
           "  - {set: left, type: displacement, x: 0}\n"
           "  - {set: anchor, type: displacement, x: 0, y: 0}\n"
           "  - {set: right, type: displacement, x: %.17g%s}\n",
           DELTA, fn);
  snprintf(text, sizeof text, scene_fmt, "aligned.csv", "pmb", bcs, solver);
  snprintf(file, sizeof file, "%s_aligned.yaml", label);
  run(ctx, file, text, al);
  snprintf(bcs, sizeof bcs,
           "  - {set: left, type: displacement, direction: [%.17g, %.17g], value: 0}\n"
           "  - {set: anchor, type: displacement, x: 0, y: 0}\n"
           "  - {set: right, type: displacement, direction: [%.17g, %.17g], value: %.17g%s}\n",
           cs, sn, cs, sn, DELTA, fn);
  snprintf(text, sizeof text, scene_fmt, "rotated.csv", "pmb", bcs, solver);
  snprintf(file, sizeof file, "%s_rotated.yaml", label);
  run(ctx, file, text, ro);
  compare(label, al, ro, tol, statics);
  free(al);
  free(ro);
}

/* A scene with these conditions (and solver) must fail with a message holding each of want[]. */
static void bad(pdk_ctx *ctx, const char *label, const char *model, const char *bcs,
                const char *solver, const char *const *want) {
  char text[4096], path[1024];
  snprintf(text, sizeof text, scene_fmt, "rotated.csv", model, bcs, solver);
  write_file("bad.yaml", text);
  snprintf(path, sizeof path, "%s/bad.yaml", work);
  pdk_scene *scene = NULL;
  pdk_sim *sim = NULL;
  int err = pdk_scene_load(ctx, path, NULL, 0, &scene);
  if (!err) err = pdk_sim_create(ctx, scene, &sim);
  T_ASSERT(err != 0, "%s: the scene was accepted", label);
  const char *msg = pdk_ctx_error_message(ctx);
  for (int k = 0; want[k]; ++k)
    T_ASSERT(strstr(msg, want[k]) != NULL, "%s: the message lacks '%s': %s", label, want[k], msg);
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
}

/* ---- 3-D: a 12 x 3 x 3 bar turned by Q (40 degrees about (1, 2, 2) / 3) ---------------------- */
#define MX 12
#define MY 3
#define MZ 3
static double Q[3][3];

static void write_cloud3(const char *name, int rot) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", work, name);
  FILE *f = fopen(path, "w");
  T_ASSERT(f != NULL, "cannot write %s", path);
  fprintf(f, "x, y, z, volume, set:left, set:anchor, set:right\n");
  for (int k = 0; k < MZ; ++k)
    for (int j = 0; j < MY; ++j)
      for (int i = 0; i < MX; ++i) {
        const double X[3] = {(i + 0.5) * H, (j + 0.5) * H, (k + 0.5) * H};
        double x[3];
        for (int a = 0; a < 3; ++a)
          x[a] = rot ? Q[a][0] * X[0] + Q[a][1] * X[1] + Q[a][2] * X[2] : X[a];
        const int anchor = i == 0 && k == 1 && j != 1; /* two particles: no rigid rotation */
        fprintf(f, "%.17g,%.17g,%.17g,%.17g,%d,%d,%d\n", x[0], x[1], x[2], H * H * H,
                i == 0 && !anchor, anchor, i == MX - 1);
      }
  T_ASSERT(fclose(f) == 0, "cannot write %s", path);
}

static void run3(pdk_ctx *ctx, const char *file, const char *text, double (*u)[3], double R[3]) {
  pdk_scene *scene = NULL;
  pdk_run_report rep;
  char dir[1024];
  pdk_sim *sim = run_text(ctx, file, text, 3, &u[0][0], &rep, &scene, dir, sizeof dir);
  for (int a = 0; a < 3; ++a)
    R[a] = rep.last.reaction[1][a]; /* right */
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&scene);
}

static void case3(pdk_ctx *ctx, const char *label, const char *solver, const char *fn, double tol) {
  static const char fmt[] = "name: bar\ndimension: 3\n"
                            "geometry: {points: %s, spacing: 1.0e-3, horizon_factor: 3.015}\n"
                            "material: {density: 8000, bulk_modulus: 1.0e9}\n"
                            "model: {kind: pmb}\nboundary_conditions:\n%s"
                            "solver: %s\noutput: {reactions: [left, right]}\n";
  char bcs[1024], text[4096], file[64];
  double(*ua)[3] = calloc(MX * MY * MZ, sizeof *ua), (*ur)[3] = calloc(MX * MY * MZ, sizeof *ur);
  double Ra[3], Rr[3];
  snprintf(bcs, sizeof bcs,
           "  - {set: left, type: displacement, x: 0}\n"
           "  - {set: anchor, type: displacement, x: 0, y: 0, z: 0}\n"
           "  - {set: right, type: displacement, x: %.17g%s}\n",
           DELTA, fn);
  snprintf(text, sizeof text, fmt, "aligned3.csv", bcs, solver);
  snprintf(file, sizeof file, "%s_aligned3.yaml", label);
  run3(ctx, file, text, ua, Ra);
  snprintf(bcs, sizeof bcs,
           "  - {set: left, type: displacement, direction: [%.17g, %.17g, %.17g], value: 0}\n"
           "  - {set: anchor, type: displacement, x: 0, y: 0, z: 0}\n"
           "  - {set: right, type: displacement, direction: [%.17g, %.17g, %.17g], value: "
           "%.17g%s}\n",
           Q[0][0], Q[1][0], Q[2][0], Q[0][0], Q[1][0], Q[2][0], DELTA, fn);
  snprintf(text, sizeof text, fmt, "rotated3.csv", bcs, solver);
  snprintf(file, sizeof file, "%s_rotated3.yaml", label);
  run3(ctx, file, text, ur, Rr);
  double du = 0, um = 0, dr = 0, rm = 0;
  for (int i = 0; i < MX * MY * MZ; ++i)
    for (int a = 0; a < 3; ++a) { /* (Q^T u')_a */
      const double b = Q[0][a] * ur[i][0] + Q[1][a] * ur[i][1] + Q[2][a] * ur[i][2];
      du = fmax(du, fabs(b - ua[i][a]));
      um = fmax(um, fabs(ua[i][a]));
    }
  for (int a = 0; a < 3; ++a) {
    const double b = Q[0][a] * Rr[0] + Q[1][a] * Rr[1] + Q[2][a] * Rr[2];
    dr = fmax(dr, fabs(b - Ra[a]));
    rm = fmax(rm, fabs(Ra[a]));
  }
  if (getenv("PDK_VERBOSE"))
    printf("%-10s max u %.4e, |Q^T u' - u| / max %.3e; right R_x %.6e, |Q^T R' - R| / max %.3e\n",
           label, um, du / um, Ra[0], dr / rm);
  T_ASSERT(um > 0.5 * DELTA, "%s: the aligned bar did not stretch (max u %g)", label, um);
  T_ASSERT(du <= tol * um, "%s: the turned bar's displacements differ by %.3e of the largest",
           label, du / um);
  T_ASSERT(dr <= tol * rm, "%s: the turned bar's reactions differ by %.3e of the largest", label,
           dr / rm);
  free(ua);
  free(ur);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  work_init("t251_bc_direction");
  cs = cos(M_PI / 6), sn = sin(M_PI / 6);
  write_cloud("aligned.csv", 0);
  write_cloud("rotated.csv", 1);

  /* 1. */
  solver_case(ctx, "newton", "{type: newton, load_steps: 1, tolerance: 1.0e-12}", "", 1e-8, 1);
  solver_case(ctx, "adr", "{type: adr, load_steps: 1, tolerance: 1.0e-10}", "", 1e-6, 1);
  solver_case(ctx, "explicit", "{steps: 300, dt: 1.0e-7}", ", function: smooth, duration: 2.0e-5",
              1e-8, 0);
  { /* 3-D: Q = rotation by 40 degrees about the unit axis (1, 2, 2) / 3 (Rodrigues) */
    const double ax[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3}, th = 40 * M_PI / 180;
    const double c = cos(th), s1 = sin(th);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        Q[a][b] = c * (a == b) + (1 - c) * ax[a] * ax[b];
    Q[0][1] -= s1 * ax[2], Q[1][0] += s1 * ax[2];
    Q[0][2] += s1 * ax[1], Q[2][0] -= s1 * ax[1];
    Q[1][2] -= s1 * ax[0], Q[2][1] += s1 * ax[0];
    write_cloud3("aligned3.csv", 0);
    write_cloud3("rotated3.csv", 1);
    case3(ctx, "newton 3-D", "{type: newton, load_steps: 1, tolerance: 1.0e-12}", "", 1e-8);
    case3(ctx, "explicit 3-D", "{steps: 200, dt: 1.0e-7}", ", function: smooth, duration: 1.5e-5",
          1e-8);
  }

  /* 2. */
  const char *newton = "{type: newton, load_steps: 1}";
  bad(ctx, "direction and x", "pmb",
      "  - {set: left, type: displacement, direction: [1, 1], value: 0, x: 0}\n", newton,
      (const char *[]){"boundary_conditions[0].x", "remove x", NULL});
  bad(ctx, "no value", "pmb", "  - {set: left, type: displacement, direction: [1, 1]}\n", newton,
      (const char *[]){"boundary_conditions[0].value", "is missing", NULL});
  bad(ctx, "value alone", "pmb", "  - {set: left, type: displacement, value: 0}\n", newton,
      (const char *[]){"boundary_conditions[0].value", "give direction", NULL});
  bad(ctx, "zero direction", "pmb",
      "  - {set: left, type: displacement, direction: [0, 0], value: 0}\n", newton,
      (const char *[]){"boundary_conditions[0].direction", "must not be zero", NULL});
  bad(ctx, "body force", "pmb", "  - {set: left, type: body_force, direction: [1, 0], value: 1}\n",
      newton, (const char *[]){"boundary_conditions[0].direction", "body force", NULL});
  bad(ctx, "overlap", "pmb",
      "  - {set: left, type: displacement, direction: [1, 1], value: 0}\n"
      "  - {set: all, type: displacement, y: 0}\n",
      newton, (const char *[]){"boundary_conditions[1]", "along a direction", NULL});
  bad(ctx, "difference tangent", "pmb",
      "  - {set: left, type: displacement, direction: [1, 1], value: 0}\n"
      "  - {set: anchor, type: displacement, x: 0, y: 0}\n",
      "{type: newton, load_steps: 1, tangent: difference}",
      (const char *[]){"analytic tangent", "adr or explicit", NULL});
  pdk_ctx_destroy(&ctx);
  return 0;
}
