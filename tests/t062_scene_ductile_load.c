/* Scenes with the Johnson-Cook law: every key of material.johnson_cook and the model's
 * connectivity keys map onto pdk_model_opts; defaults fill in; E, nu and rho come from
 * `material` (also when it gives K and G); the shipped ductile scenes load and build; the derived
 * output field von_mises equals the von Mises stress of the law at an affine deformation for every
 * correspondence law; the history files carry the plastic, damage and breaking work.
 * labels: unit */
#include "pdk/output.h"
#include "pdk/scene.h"
#include "scene/scene_impl.h"
#include "test_util.h"

#include <sys/stat.h>

static const char *full_scene = "dimension: 2\n"
                                "geometry:\n"
                                "  spacing: 1.0e-3\n"
                                "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"
                                "material:\n"
                                "  density: 7830\n"
                                "  youngs_modulus: 200e9\n"
                                "  poisson_ratio: 0.29\n"
                                "  johnson_cook:\n"
                                "    A: 792e6\n"
                                "    B: 510e6\n"
                                "    n: 0.26\n"
                                "    C: 0.014\n"
                                "    reference_strain_rate: 2.0\n"
                                "    thermal: true\n"
                                "    m: 1.03\n"
                                "    T_room: 293\n"
                                "    T_melt: 1793\n"
                                "    T_initial: 300\n"
                                "    beta: 0.8\n"
                                "    heat_capacity: 477\n"
                                "    damage: true\n"
                                "    D1: 0.05\n"
                                "    D2: 3.44\n"
                                "    D3: -2.12\n"
                                "    D4: 0.002\n"
                                "    D5: 0.61\n"
                                "    D_c: 0.3\n"
                                "    coupling: effective\n"
                                "    failed_mode: compression\n"
                                "model:\n"
                                "  kind: correspondence\n"
                                "  law: jc\n"
                                "  connectivity: semi_tl\n"
                                "  compact_fraction: 0.05\n"
                                "  failed_keeps_bonds: true\n"
                                "  stabilization_softening: plastic\n"
                                "  stabilization_softening_floor: 0.01\n"
                                "  damage_triaxiality: family\n"
                                "solver:\n"
                                "  steps: 3\n"
                                "output:\n"
                                "  fields: [u, eps_p, damage, failed, von_mises]\n";

static const char *minimal_jc =
    "dimension: 2\n"
    "geometry:\n"
    "  spacing: 1.0e-3\n"
    "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"
    "material:\n"
    "  density: 7830\n"
    "  bulk_modulus: 150e9\n"
    "  shear_modulus: 80e9\n"
    "  johnson_cook: {A: 792e6, B: 510e6, n: 0.26, D1: 0.05, D2: 3.44, D3: -2.12, D_c: 0.3}\n"
    "model: {kind: correspondence, law: jc}\n"
    "solver:\n"
    "  steps: 3\n";

static void write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "wb");
  T_ASSERT(f && fputs(text, f) >= 0 && !fclose(f), "writing %s", path);
}

static char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  T_ASSERT(f, "cannot open %s", path);
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = malloc((size_t)n + 1);
  T_ASSERT(b && fread(b, 1, (size_t)n, f) == (size_t)n, "short read of %s", path);
  b[n] = '\0';
  fclose(f);
  return b;
}

static void check_full(pdk_ctx *ctx) {
  write_file("t062_full.yaml", full_scene);
  pdk_scene *s = NULL;
  T_OK(ctx, pdk_scene_load(ctx, "t062_full.yaml", NULL, 0, &s));
  const pdk_model_opts *m = &s->model;
  const pdk_jc_params *jc = &m->jc;
  T_ASSERT(m->kind == PDK_MODEL_CORRESPONDENCE && m->law == PDK_LAW_JC, "law jc");
  T_ASSERT(jc->density == 7830 && jc->young_modulus == 200e9 && jc->poisson_ratio == 0.29,
           "E, nu, rho from material: %g %g %g", jc->young_modulus, jc->poisson_ratio, jc->density);
  T_ASSERT(jc->A == 792e6 && jc->B == 510e6 && jc->n == 0.26 && jc->C == 0.014 &&
               jc->ref_rate == 2.0,
           "hardening and rate");
  T_ASSERT(jc->thermal == 1 && jc->m == 1.03 && jc->T_room == 293 && jc->T_melt == 1793 &&
               jc->T_initial == 300 && jc->beta == 0.8 && jc->heat_capacity == 477,
           "thermal terms");
  T_ASSERT(jc->damage == 1 && jc->D1 == 0.05 && jc->D2 == 3.44 && jc->D3 == -2.12 &&
               jc->D4 == 0.002 && jc->D5 == 0.61 && jc->D_c == 0.3,
           "damage constants");
  T_ASSERT(jc->coupling == PDK_JC_COUPLING_EFFECTIVE &&
               jc->failed_mode == PDK_JC_FAILED_COMPRESSION,
           "coupling %d, failed mode %d", (int)jc->coupling, (int)jc->failed_mode);
  T_ASSERT(m->connectivity == PDK_CONNECTIVITY_SEMI_TL && m->compact_fraction == 0.05 &&
               m->failed_keeps_bonds == 1,
           "connectivity %d, compact_fraction %g, failed_keeps_bonds %d", (int)m->connectivity,
           m->compact_fraction, m->failed_keeps_bonds);
  T_ASSERT(m->stab_softening == 1 && m->stab_softening_floor == 0.01 &&
               m->damage_triaxiality == PDK_TRIAX_FAMILY,
           "softening %d, floor %g, damage triaxiality %d", m->stab_softening,
           m->stab_softening_floor, (int)m->damage_triaxiality);
  /* It builds: the model accepts the constants (K, G, rho agree with jc) and declares the
   * history fields the output asks for. */
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_particles *p = pdk_sim_particles(sim);
  const char *fields[] = {"u", "eps_p", "damage", "failed", "von_mises", "temp_rise"};
  for (int k = 0; k < 6; ++k)
    T_ASSERT(pdk_particles_field_exists(p, fields[k]), "field %s exists", fields[k]);
  T_OK(ctx, pdk_explicit_run(pdk_sim_explicit(sim), 3, NULL));
  T_OK(ctx, pdk_sim_update_output_fields(sim));
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  remove("t062_full.yaml");
}

static void check_defaults(pdk_ctx *ctx) {
  write_file("t062_min.yaml", minimal_jc);
  pdk_scene *s = NULL;
  T_OK(ctx, pdk_scene_load(ctx, "t062_min.yaml", NULL, 0, &s));
  const pdk_model_opts *m = &s->model;
  const pdk_jc_params *jc = &m->jc;
  /* E = 9KG / (3K + G), nu = (3K - 2G) / (2 (3K + G)) */
  const double K = 150e9, G = 80e9;
  T_NEAR(jc->young_modulus, 9 * K * G / (3 * K + G), 1e-15, 0, "E from K, G");
  T_NEAR(jc->poisson_ratio, (3 * K - 2 * G) / (2 * (3 * K + G)), 1e-15, 0, "nu from K, G");
  T_ASSERT(jc->C == 0 && jc->D4 == 0 && jc->D5 == 0 && jc->thermal == 0 && jc->damage == 1,
           "rate and thermal terms off, damage on by default");
  T_ASSERT(jc->coupling == PDK_JC_COUPLING_NONE && jc->failed_mode == PDK_JC_FAILED_ZERO,
           "coupling none, failed mode zero by default");
  T_ASSERT(m->connectivity == PDK_CONNECTIVITY_TL && m->compact_fraction == 0.02 &&
               m->failed_keeps_bonds == 0,
           "connectivity defaults");
  T_ASSERT(m->stab_softening == 0 && m->stab_softening_floor == 1e-3 &&
               m->damage_triaxiality == PDK_TRIAX_LOCAL,
           "softening off (floor 1e-3 when on) and the local triaxiality by default");
  T_ASSERT(m->break_stress == PDK_BREAK_STRESS_REFIT, "break_stress refit by default");
  {
    const char *ov[] = {"model.break_stress=continuous"};
    pdk_scene *s2 = NULL;
    T_OK(ctx, pdk_scene_load(ctx, "t062_min.yaml", ov, 1, &s2));
    T_ASSERT(s2->model.break_stress == PDK_BREAK_STRESS_CONTINUOUS, "break_stress continuous");
    pdk_scene_destroy(&s2);
  }
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  T_NEAR(pdk_model_opts_get(pdk_sim_model(sim))->bulk_modulus, K, 1e-12, 0, "K round trip");
  T_ASSERT(pdk_model_bond_alive(pdk_sim_model(sim)), "JC damage breaks bonds by default");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  /* damage: false switches damage off and with it bond breaking */
  const char *ov[] = {"material.johnson_cook={A: 792e6, B: 510e6, n: 0.26, damage: false}"};
  T_OK(ctx, pdk_scene_load(ctx, "t062_min.yaml", ov, 1, &s));
  T_ASSERT(s->model.jc.damage == 0, "damage off");
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  T_ASSERT(!pdk_model_bond_alive(pdk_sim_model(sim)), "no bond state without damage");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  /* ul with failed particles that keep their bonds, and its skin */
  const char *ul[] = {"model.connectivity=ul", "model.ul_skin=0.5",
                      "model.failed_keeps_bonds=true"};
  T_OK(ctx, pdk_scene_load(ctx, "t062_min.yaml", ul, 3, &s));
  T_ASSERT(s->model.connectivity == PDK_CONNECTIVITY_UL && s->model.ul_skin == 0.5 &&
               s->model.failed_keeps_bonds == 1,
           "ul keys");
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  T_OK(ctx, pdk_explicit_run(pdk_sim_explicit(sim), 3, NULL));
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  remove("t062_min.yaml");
}

/* The shipped ductile scenes load and build (not run). */
static void check_shipped(pdk_ctx *ctx) {
  const char *src = getenv("PDK_SOURCE_DIR");
  T_ASSERT(src, "PDK_SOURCE_DIR is not set (ctest sets it)");
  const char *names[] = {"plate_two_holes", "plate_two_holes_fine", "plate_two_holes_close",
                         "plate_one_hole_ductile"};
  for (int k = 0; k < 4; ++k) {
    char path[2048];
    snprintf(path, sizeof path, "%s/scenes/%s.yaml", src, names[k]);
    pdk_scene *s = NULL;
    pdk_sim *sim = NULL;
    /* a coarse spacing so that building is quick; the keys are what is checked */
    const char *ov[] = {"geometry.spacing=2.5e-3"};
    T_OK(ctx, pdk_scene_load(ctx, path, ov, 1, &s));
    T_ASSERT(s->model.law == PDK_LAW_JC && s->model.jc.A == 792e6 && s->model.jc.D_c == 0.3,
             "%s: V-JC steel", names[k]);
    T_OK(ctx, pdk_sim_create(ctx, s, &sim));
    pdk_sim_destroy(&sim);
    pdk_scene_destroy(&s);
  }
}

/* Cauchy stress of each law at a homogeneous plane-strain F (F33 = 1), computed here from the
 * formulas of kernels/ref/corr.c, and its von Mises value. */
static double law_von_mises(pdk_law law, const pdk_model_opts *mo, const double F[3][3]) {
  const double mu = mo->shear_modulus, lambda = mo->bulk_modulus - 2.0 * mu / 3.0;
  double S[3][3] = {{0}};
  const double J = F[0][0] * F[1][1] - F[0][1] * F[1][0];
  if (law == PDK_LAW_JC) {
    pdk_jc_state in = pdk_jc_state_initial(), out;
    double P[3][3];
    pdk_jc_result res;
    T_ASSERT(!pdk_jc_update(&mo->jc, 2, F, 1e-7, &in, &out, P, &res), "jc update");
    T_ASSERT(!out.failed && (F[0][0] < 1.01 || res.plastic), "jc point: yields, does not fail");
    return res.sigma_vm;
  }
  if (law == PDK_LAW_LINEAR_ELASTIC) {
    double eps[3][3] = {{0}};
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c)
        eps[a][c] = 0.5 * (F[a][c] + F[c][a]) - (a == c);
    const double tr = eps[0][0] + eps[1][1];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c)
        S[a][c] = 2 * mu * eps[a][c] + (a == c ? lambda * tr : 0.0);
  } else if (law == PDK_LAW_SVK) {
    double E[3][3] = {{0}}, Sp[3][3] = {{0}};
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        double C = 0;
        for (int e = 0; e < 3; ++e)
          C += F[e][a] * F[e][c];
        E[a][c] = 0.5 * (C - (a == c));
      }
    const double tr = E[0][0] + E[1][1] + E[2][2];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c)
        Sp[a][c] = 2 * mu * E[a][c] + (a == c ? lambda * tr : 0.0);
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        double v = 0;
        for (int e = 0; e < 3; ++e)
          for (int g = 0; g < 3; ++g)
            v += F[a][e] * Sp[e][g] * F[c][g];
        S[a][c] = v / J;
      }
  } else {
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        double b = 0;
        for (int e = 0; e < 3; ++e)
          b += F[a][e] * F[c][e];
        S[a][c] = (mu * (b - (a == c)) + (a == c ? lambda * log(J) : 0.0)) / J;
      }
  }
  const double d1 = S[0][0] - S[1][1], d2 = S[1][1] - S[2][2], d3 = S[2][2] - S[0][0];
  return sqrt(0.5 * (d1 * d1 + d2 * d2 + d3 * d3) +
              3 * (S[0][1] * S[0][1] + S[1][2] * S[1][2] + S[0][2] * S[0][2]));
}

static const char *laws[] = {"linear_elastic", "svk", "neo_hooke", "jc"};
static const pdk_law law_of[] = {PDK_LAW_LINEAR_ELASTIC, PDK_LAW_SVK, PDK_LAW_NEO_HOOKE,
                                 PDK_LAW_JC};

/* One case of check_von_mises: law k at amplitude e (shape a), TL or UL (ul). */
static void von_mises_case(pdk_ctx *ctx, int ul, int k, int a, double e) {
  char law[64];
  snprintf(law, sizeof law, "model.law=%s", laws[k]);
  const char *ov_jc[] = {"output.fields=[von_mises]", "model.connectivity=ul",
                         "model.failed_keeps_bonds=true"};
  const char *ov_el[] = {"output.fields=[von_mises]", law, "model.connectivity=ul"};
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  if (law_of[k] == PDK_LAW_JC)
    T_OK(ctx, pdk_scene_load(ctx, "t062_min.yaml", ov_jc, ul ? 3 : 1, &s));
  else
    T_OK(ctx, pdk_scene_load(ctx, "t062_el.yaml", ov_el, ul ? 3 : 2, &s));
  T_ASSERT(s->model.connectivity == (ul ? PDK_CONNECTIVITY_UL : PDK_CONNECTIVITY_TL),
           "connectivity override");
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  pdk_particles *p = pdk_sim_particles(sim);
  /* a = 0: stretch, shear and a volume change; a = 1: the same isochoric (J = 1), so that the
   * yielding JC point keeps a low triaxiality and does not fail */
  const double F22 = a == 0 ? 1 - 0.3 * e : (1 - 0.1 * e * e) / (1 + e);
  const double F[3][3] = {{1 + e, 0.5 * e, 0}, {-0.2 * e, F22, 0}, {0, 0, 1}};
  double *x = pdk_particles_field_data(p, "x", 0), *y = pdk_particles_field_data(p, "x", 1);
  const pdk_index n = pdk_particles_count(p);
  for (pdk_index i = 0; i < n; ++i) {
    const double X = pdk_particles_X(p, 0)[i], Y = pdk_particles_X(p, 1)[i];
    x[i] = F[0][0] * X + F[0][1] * Y;
    y[i] = F[1][0] * X + F[1][1] * Y;
  }
  pdk_model *m = pdk_sim_model(sim);
  T_OK(ctx, pdk_model_force_trial(m, NULL));
  T_OK(ctx, pdk_sim_update_output_fields(sim));
  const double want = law_von_mises(law_of[k], pdk_model_opts_get(m), F);
  T_ASSERT(want > 1e6, "%s: the test deformation makes a stress (%g)", laws[k], want);
  const double *vm = pdk_particles_field_data(p, "von_mises", 0);
  const uint8_t *flag = pdk_particles_field_data(p, "flag", 0);
  for (pdk_index i = 0; i < n; ++i) {
    if (flag[i]) continue;
    /* F is exact to round-off for affine motion (t100); P = A K and the law add a few ulps per
     * operation on stresses of order E e: 1e-9 relative is far above that */
    T_NEAR(vm[i], want, 1e-9, 0, "%s%s (amplitude %g): von_mises of particle %d", laws[k],
           ul ? ", ul" : "", e, (int)i);
  }
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
}

/* von_mises at an affine deformation x = F X: a trial force pass makes F and A, then
 * pdk_sim_update_output_fields; every particle whose family spans must give the law's value. */
static void check_von_mises(pdk_ctx *ctx) {
  write_file("t062_min.yaml", minimal_jc);
  { /* the same scene without the Johnson-Cook mapping, for the elastic laws */
    char *el = strdup(minimal_jc);
    char *at = strstr(el, "  johnson_cook:"), *end = strchr(at, '\n') + 1;
    memmove(at, end, strlen(end) + 1);
    write_file("t062_el.yaml", el);
    free(el);
  }
  /* for JC 1e-3 stays elastic and 3e-2 yields */
  const double amp[] = {1e-3, 3e-2};
  /* ul == 1: updated-Lagrangian connectivity, whose model keeps no K (its A is tau_r M^-1), so
   * von_mises evaluates the law again at the total F (which failed with "needs ... Kinv" before
   * 2026-11-27); its F is exact for affine motion as TL's is (docs/connectivity.md) */
  for (int ul = 0; ul < 2; ++ul)
    for (int k = 0; k < 4; ++k)
      for (int a = 0; a < (law_of[k] == PDK_LAW_JC ? 2 : 1); ++a)
        von_mises_case(ctx, ul, k, a, amp[a]);
  remove("t062_min.yaml");
  remove("t062_el.yaml");
}

/* The history plot has a panel of failed particles and largest damage (columns failed and
 * damage_max, the last two) when some damage was recorded, and none otherwise. Needs gnuplot on
 * the PATH (the Quick start installs it); says so and checks nothing without it. */
static void check_failure_panel(pdk_ctx *ctx, pdk_particles *p, double damage_max) {
  pdk_output_opts oo = pdk_output_opts_default();
  oo.dir = "t062_out";
  oo.name = "panel";
  oo.units = "SI";
  pdk_output *o = NULL;
  T_OK(ctx, pdk_output_open(ctx, &oo, p, &o));
  const int plots = pdk_output_will_plot(o);
  pdk_history h;
  memset(&h, 0, sizeof h);
  for (int r = 0; r < 3; ++r) {
    h.step = r;
    h.time = 1e-6 * r;
    h.external_work = h.kinetic = 0.5 * r;
    h.failed = r == 2 && damage_max > 0.0 ? 4 : 0;
    h.damage_max = damage_max * r / 2.0;
    T_OK(ctx, pdk_output_write_history(o, &h));
  }
  T_OK(ctx, pdk_output_close(&o, 1));
  if (!plots) {
    printf("t062: no gnuplot on the PATH: the failure panel is not checked\n");
  } else {
    char *csv = slurp("t062_out/panel_history.csv");
    int cols = 1;
    for (const char *c = csv; *c && *c != '\n'; ++c)
      cols += *c == ',';
    free(csv);
    char *gp = slurp("t062_out/panel_history.gp");
    char want[96];
    snprintf(want, sizeof want, "using ($2*tscale):%d with lines title 'failed particles'", cols - 1);
    const int has = strstr(gp, want) != NULL;
    snprintf(want, sizeof want, "using ($2*tscale):%d axes x1y2 with lines title 'largest damage'", cols);
    const int has2 = strstr(gp, want) != NULL;
    T_ASSERT(damage_max > 0.0 ? has && has2 : !has && !strstr(gp, "largest damage"),
             "largest damage %g: failure panel %s / %s in the script:\n%s", damage_max,
             has ? "drawn" : "absent", has2 ? "drawn" : "absent", gp);
    free(gp);
  }
  const char *files[] = {"panel_history.csv", "panel.h5", "panel.xmf", "panel_history.gp",
                         "panel_history.png"};
  for (int k = 0; k < 5; ++k) {
    char path[64];
    snprintf(path, sizeof path, "t062_out/%s", files[k]);
    remove(path);
  }
}

/* The history files end with plastic_work, damage_work, breaking_work, dt, failed, damage_max,
 * written as given. */
static void check_history_columns(pdk_ctx *ctx) {
  write_file("t062_min.yaml", minimal_jc);
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  T_OK(ctx, pdk_scene_load(ctx, "t062_min.yaml", NULL, 0, &s));
  T_OK(ctx, pdk_sim_create(ctx, s, &sim));
  mkdir("t062_out", 0777);
  pdk_output_opts oo = pdk_output_opts_default();
  oo.dir = "t062_out";
  oo.name = "hist";
  oo.plot = 0;
  oo.units = "SI";
  pdk_output *o = NULL;
  T_OK(ctx, pdk_output_open(ctx, &oo, pdk_sim_particles(sim), &o));
  pdk_history h;
  memset(&h, 0, sizeof h);
  h.plastic_work = 1.25;
  h.damage_work = 0.5;
  h.breaking_work = 0.0625;
  h.dt = 3.5e-7;
  h.failed = 7;
  h.damage_max = 0.3125;
  T_OK(ctx, pdk_output_write_history(o, &h));
  T_OK(ctx, pdk_output_close(&o, 1));
  char *csv = slurp("t062_out/hist_history.csv");
  char *eol = strchr(csv, '\n');
  T_ASSERT(eol, "CSV has a header line");
  *eol = '\0';
  const char *tail = "plastic_work [J],damage_work [J],breaking_work [J],dt [s],"
                     "failed [particles],damage_max [-]";
  T_ASSERT(strlen(csv) >= strlen(tail) && !strcmp(csv + strlen(csv) - strlen(tail), tail),
           "CSV header ends with the work columns, dt and the failure columns: %s", csv);
  const char *row = eol + 1;
  /* last six numbers of the row */
  double v[6];
  const char *q = row + strlen(row);
  while (q > row && (q[-1] == '\n'))
    --q;
  int found = 0;
  for (const char *r = q; r > row && found < 6; --r)
    if (r[-1] == ',') {
      v[5 - found] = strtod(r, NULL);
      ++found;
    }
  T_ASSERT(found == 6 && v[0] == 1.25 && v[1] == 0.5 && v[2] == 0.0625 && v[3] == 3.5e-7 &&
               v[4] == 7.0 && v[5] == 0.3125,
           "work columns, dt, failed and damage_max written as given: %g %g %g %g %g %g", v[0],
           v[1], v[2], v[3], v[4], v[5]);
  free(csv);
  remove("t062_out/hist_history.csv");
  remove("t062_out/hist.h5");
  remove("t062_out/hist.xmf");
  check_failure_panel(ctx, pdk_sim_particles(sim), 0.0);
  check_failure_panel(ctx, pdk_sim_particles(sim), 0.3125);
  remove("t062_out");
  pdk_sim_destroy(&sim);
  pdk_scene_destroy(&s);
  remove("t062_min.yaml");
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  check_full(ctx);
  check_defaults(ctx);
  check_shipped(ctx);
  check_von_mises(ctx);
  check_history_columns(ctx);
  pdk_ctx_destroy(&ctx);
  return 0;
}
