/* The speed-accuracy trade: error against cost for every knob pdk offers, on problems with known
 * answers. docs/tradeoff.md reads the results; bench/tradeoff/run.sh regenerates them.
 *
 * Problems (2-D plane strain; the exact answers use the Lame constants of the model's continuum
 * limit: lambda = K - 2G/3, mu = G for LPS and correspondence; lambda = mu = 3K/5 for PMB, whose
 * Poisson ratio is fixed at 1/4):
 *   mms      manufactured static field on the unit square, u* = a (f1(X) + f2(Y), g1(X) + g2(Y))
 *            with f, g built from sin^4(pi t) (zero with three derivatives outside [0, 1]), so the
 *            body force b = -Div sigma(u*) is a sum of a function of X and one of Y and u* = 0
 *            beyond the square except along the collar rows and columns. A collar of width 2
 *            delta around the square holds u* exactly (a prescribed displacement with a
 *            per-particle scale field, pdk_bc.scale_field; 2 delta, not delta, so that the
 *            collar particles a square particle's state-based force reads have full families);
 *            every particle of the square carries b (a body force with a scale field). Solved
 *            by Newton (or ADR).
 *            Error: relative L2 norm of u - u* over the square's particles.
 *   vq_uniaxial, vq_isotropic, vq_shear
 *            the V-Q constant-strain tests (Queiruga & Moridis 2017 section 4.1): 10 mm
 *            square, node grid NP x NP, E = 1000, nu = 0, T = 1e-3; uniaxial (bottom clamped, side
 *            rollers, top traction), isotropic (bottom and left rollers, top and right traction),
 *            shear (bottom clamped, side rollers u_y = 0, top tangential traction). Error: the
 *            relative error of the probe (mean top, or right, displacement over 0.4..0.6 of the
 *            edge) against -T H/(lambda + 2 mu), -T H/(2 (lambda + mu)) and T H/mu.
 *   wave     standing wave in a free-free bar 1 x 0.25 (cell-centred lattice, so the particles'
 *            cells tile the bar: a node grid, whose end particles carry full cells, would make the
 *            bar h longer and lower the frequency by h/L), u_y = 0 on every particle
 *            (uniaxial strain), released from u_x = A cos(pi X) at rest, velocity Verlet. The
 *            projection of u_x on cos(pi X) crosses zero at T/4 and 3T/4; the frequency from the
 *            two crossings (linear interpolation between steps) is compared with
 *            pi sqrt((lambda + 2 mu)/rho). Error: |omega / omega_exact - 1|.
 *   hole     plate 1 x 2 with a central hole of diameter d = 0.2 (d/W = 0.2), cell-centred
 *            lattice, remote tension sigma0 = 1e-3 E on the top and bottom rows (body force),
 *            supports on the symmetry lines only (u_x = 0 at the middle of the top and bottom rows,
 *            u_y = 0 at the middle of the side columns). Stress at each particle from the
 *            least-squares gradient of the displacement over its family (the correspondence F =
 *            N K^-1 with the model's influence function; constant for PMB and LPS) and the
 *            model's Lame constants. Error: |max sigma_yy / sigma0 - 3.14| / 3.14, with 3.14 the
 *            finite-width factor (Heywood: K_net = 2 + (1 - d/W)^3 = 2.512 on the net section,
 *            2.512 / 0.8 on the gross stress; Howland's exact value 2.51), about 1% uncertain.
 * Knobs: model (pmb, lps, with LAMMPS partial volumes or not; correspondence with no, Silling or
 * hourglass stabilization), horizon factor m, influence function, precision (float storage; a
 * model that refuses it is recorded as "unsupported"), connectivity (tl, semi_tl, ul), time-step
 * safety factor (wave), particle order (Morton or lattice; the only layout choice the library
 * has), static solver (Newton or ADR). A plan is a list of series: one setting of every knob, run
 * at several resolutions. The baseline is the library's default (correspondence, Silling 0.1,
 * constant influence, m 3.015, double, TL, safety 0.8, Morton order) with Newton; each sweep
 * changes one knob from it (the m sweep also for PMB and LPS).
 *
 * Cost: process CPU time (all threads) and wall time from the lattice to the answer (families,
 * model, solver setup, solve; not the error evaluation), on --threads threads (default 1, so CPU
 * time is the wall time of an idle core and does not depend on what else runs on the machine).
 *
 * Output (--out-dir DIR): DIR/tradeoff.csv, one row per run with the Pareto flag (no other run of
 * the same problem is at most as costly and at most as wrong, and better in one of the two), and
 * DIR/tradeoff.gp, which gnuplot turns into DIR/<problem>.png (run by this program unless
 * --no-plot). --plot-only rereads DIR/tradeoff.csv and redoes the flags and plots. DIR is created
 * with its parents; every output is written under a temporary name (.part) and renamed when
 * complete, so a failed or interrupted run leaves no file that looks finished.
 *
 * Usage: tradeoff [--plan tiny|full] [--problem NAME]... [--sweep NAME] [--out-dir DIR]
 *                 [--threads T] [--no-plot] [--plot-only] [--list]
 * --sweep NAME runs only the series of one sweep (model, m, influence, influence-rf1.5, precision,
 * connectivity, dt, order, solver); series keep their numbers in the whole plan.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include "models/model_impl.h" /* pdk_influence_eval: the stress post-processing of the hole */
#include "pdk/pdk.h"

/* ---- problems and knobs ------------------------------------------------------------------- */

typedef enum problem_id {
  P_MMS = 0,
  P_VQ_UNIAXIAL,
  P_VQ_ISOTROPIC,
  P_VQ_SHEAR,
  P_WAVE,
  P_HOLE,
  P_COUNT
} problem_id;

static const char *problem_name[P_COUNT] = {"mms",      "vq_uniaxial", "vq_isotropic",
                                            "vq_shear", "wave",        "hole"};
static const char *problem_title[P_COUNT] = {
    "manufactured static field (L2 error of u)",
    "V-Q uniaxial compression (top displacement)",
    "V-Q isotropic compression (right-edge displacement)",
    "V-Q simple shear (top displacement)",
    "standing wave in a bar (frequency)",
    "plate with a hole, d/W = 0.2 (stress concentration 3.14)"};

typedef struct knobs {
  pdk_model_kind kind;
  int partial_volume; /* PMB, LPS: LAMMPS partial volumes */
  pdk_stabilization stab;
  pdk_influence influence;
  double m; /* horizon factor delta / h */
  pdk_precision precision;
  pdk_connectivity connectivity;
  double safety;     /* explicit: fraction of the stable time step */
  int lattice_order; /* 1: particles in lattice order, not Morton order */
  pdk_static_method method;
} knobs;

static knobs knobs_baseline(void) {
  knobs k;
  memset(&k, 0, sizeof k);
  k.kind = PDK_MODEL_CORRESPONDENCE;
  k.stab = PDK_STAB_SILLING;
  k.influence = PDK_INFLUENCE_CONSTANT;
  k.m = 3.015;
  k.precision = PDK_PRECISION_DOUBLE;
  k.connectivity = PDK_CONNECTIVITY_TL;
  k.safety = 0.8;
  k.method = PDK_STATIC_NEWTON;
  return k;
}

static const char *influence_name[6] = {"constant", "inv_r", "inv_r2", "linear", "cubic",
                                        "gaussian"};
static const char *stab_name[3] = {"none", "silling", "hourglass"};
static const char *conn_name[3] = {"tl", "semi_tl", "ul"};

static const char *model_label(const knobs *k) {
  switch (k->kind) {
  case PDK_MODEL_PMB: return k->partial_volume ? "pmb-pv" : "pmb";
  case PDK_MODEL_LPS: return k->partial_volume ? "lps-pv" : "lps";
  default: return k->stab == PDK_STAB_NONE ? "corr-none"
                  : k->stab == PDK_STAB_SILLING ? "corr-silling" : "corr-hourglass";
  }
}

/* ---- results ------------------------------------------------------------------------------ */

typedef struct row {
  int problem; /* problem_id */
  char sweeps[64]; /* the sweeps this series belongs to, space separated */
  int series;      /* index of the series in the plan (per problem after --plot-only) */
  knobs k;
  int level;       /* resolution parameter (N or NP) */
  double h;
  long particles, bonds, work; /* work: Newton iterations, ADR iterations or time steps */
  double wall, cpu, error, value, exact;
  char status[16]; /* ok | unsupported | failed | skipped */
  char note[200];
  int pareto;
} row;

typedef struct series {
  problem_id problem;
  char sweeps[64];
  knobs k;
  int levels[6];
  int num_levels;
  int selected; /* run by this invocation (--problem, --sweep) */
} series;

static double cpu_seconds(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
         (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

/* Records the context's last error in the row (commas would break the CSV: replaced). */
static void row_fail(row *r, pdk_ctx *ctx, int code) {
  snprintf(r->status, sizeof r->status, "%s",
           code == PDK_ERR_UNSUPPORTED ? "unsupported" : "failed");
  snprintf(r->note, sizeof r->note, "%s", pdk_ctx_error_message(ctx));
  for (char *c = r->note; *c; ++c)
    if (*c == ',' || *c == '\n' || *c == '"') *c = ';';
  pdk_ctx_error_clear(ctx);
}

#define TRY(expr)                                                                                  \
  do {                                                                                             \
    err = (expr);                                                                                  \
    if (err) goto cleanup;                                                                         \
  } while (0)

/* Lame constants of the model's continuum limit (plane strain). */
static void lame(const knobs *k, double K, double G, double *lambda, double *mu) {
  if (k->kind == PDK_MODEL_PMB) {
    *mu = 0.6 * K;
    *lambda = *mu;
  } else {
    *mu = G;
    *lambda = K - 2.0 * G / 3.0;
  }
}

/* Reorders (unless lattice order is asked for), builds the families with delta = m h and the
 * model. The caller destroys both. */
static int build_model(pdk_particles *p, const knobs *k, double h, double K, double G, double rho,
                       pdk_families **fam, pdk_model **model) {
  pdk_ctx *ctx = pdk_particles_ctx(p);
  int err = 0;
  const double delta = k->m * h;
  *fam = NULL;
  *model = NULL;
  if (!k->lattice_order) {
    const double edge = pdk_families_cell_edge(p, delta);
    if (!(edge > 0)) return pdk_ctx_error_code(ctx) ? pdk_ctx_error_code(ctx) : PDK_ERR_ARG;
    TRY(pdk_particles_reorder_morton(p, edge, NULL));
  }
  pdk_families_opts fo = pdk_families_opts_default();
  fo.horizon = delta;
  TRY(pdk_families_build(p, &fo, fam));
  pdk_model_opts mo = pdk_model_opts_default();
  mo.kind = k->kind;
  mo.bulk_modulus = K;
  mo.shear_modulus = G;
  mo.density = rho;
  if (k->partial_volume) mo.lattice_constant = h;
  if (k->kind == PDK_MODEL_CORRESPONDENCE) {
    mo.influence = k->influence;
    mo.stabilization = k->stab;
    mo.stab_coefficient = 0.1;
    mo.law = PDK_LAW_LINEAR_ELASTIC;
    mo.connectivity = k->connectivity;
    mo.ul_skin = 0.0; /* small motion: UL on the initial families (Bergel & Li) */
  }
  mo.precision = k->precision;
  TRY(pdk_model_create(p, *fam, &mo, model));
cleanup:
  return err;
}

static pdk_index count_set(pdk_particles *p, const char *set) {
  const uint8_t *s = pdk_particles_field_data(p, set, 0);
  pdk_index c = 0;
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
    c += s[i] != 0;
  return c;
}

/* Newton's default tolerance (1e-10 of the load norm) lies below the round-off of a residual
 * computed with float storage: correspondence rounds the pass-2 tensors to float, a relative
 * 6e-8 of the stress, and Newton's line search stalls at 1e-9 to 3e-9 of the load norm (mms,
 * N = 16 and 32). Correspondence float rows solved by Newton therefore use rtol 1e-7 (noted in
 * the row); ADR's default 1e-6 is above it. PMB and LPS round only the reference bond lengths, a
 * fixed perturbation of the body that leaves the residual smooth: their default stands. */
#define FLOAT_NEWTON_RTOL 1e-7
static pdk_static_opts static_opts(const knobs *k, row *r) {
  pdk_static_opts so = pdk_static_opts_default(k->method);
  if (k->precision == PDK_PRECISION_FLOAT && k->method == PDK_STATIC_NEWTON &&
      k->kind == PDK_MODEL_CORRESPONDENCE) {
    so.rtol = FLOAT_NEWTON_RTOL;
    snprintf(r->note, sizeof r->note, "Newton rtol %g (float round-off)", so.rtol);
  }
  return so;
}

static void finish_static(row *r, pdk_static *s) {
  const pdk_static_stats *st = pdk_static_stats_get(s);
  r->work = st->iterations;
}

/* ---- V-Q constant-strain tests ----------------------------------------------------------- */

static void run_vq(pdk_ctx *ctx, problem_id prob, const knobs *k, int np, row *r) {
  const double W = 10.0, H = 10.0, E = 1000.0, T = 1e-3, h = W / np;
  const double K = E / 3.0, G = E / 2.0; /* nu = 0 */
  pdk_particles *p = NULL;
  pdk_families *fam = NULL;
  pdk_model *m = NULL;
  pdk_static *s = NULL;
  int err = 0;
  const double w0 = pdk_wtime(), c0 = cpu_seconds();
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.node_type = 1;
  lo.spacing = h;
  lo.hi[0] = W;
  lo.hi[1] = H;
  TRY(pdk_lattice_create(ctx, &lo, &p));
  const double e = 0.25 * h, big = 2 * W;
  const double b0[3] = {-big, -big, -1}, b1[3] = {big, e, 1};          /* bottom row */
  const double l0[3] = {-big, e, -1}, l1[3] = {e, big, 1};             /* left column above it */
  const double r0[3] = {W - e, e, -1}, r1[3] = {big, big, 1};          /* right column above it */
  const double t0[3] = {-big, H - e, -1}, t1[3] = {big, big, 1};       /* top row */
  const double lf0[3] = {-big, -big, -1}, lf1[3] = {e, big, 1};        /* whole left column */
  const double rt0[3] = {W - e, -big, -1}, rt1[3] = {big, big, 1};     /* whole right column */
  pdk_region bottom = pdk_region_box(b0, b1), left = pdk_region_box(l0, l1);
  pdk_region right = pdk_region_box(r0, r1), top = pdk_region_box(t0, t1);
  pdk_region left_all = pdk_region_box(lf0, lf1), right_load = pdk_region_box(rt0, rt1);
  pdk_bc bcs[4];
  memset(bcs, 0, sizeof bcs);
  int nb = 0;
  double lambda, mu;
  lame(k, K, G, &lambda, &mu);
  TRY(pdk_particles_set_define(p, "top", &top, NULL));
  const double V = h * h; /* node grid: full cell volume everywhere (thickness 1) */
  const char *probe_set = "set:top";
  int probe_c = 1;
  if (prob == P_VQ_ISOTROPIC) {
    /* bottom row u_y = 0, left column u_x = 0 (the corner both); top and right edges loaded */
    TRY(pdk_particles_set_define(p, "bottom", &bottom, NULL));
    TRY(pdk_particles_set_define(p, "left", &left_all, NULL));
    TRY(pdk_particles_set_define(p, "right", &right_load, NULL));
    const pdk_index n_top = count_set(p, "set:top"), n_right = count_set(p, "set:right");
    bcs[nb++] = (pdk_bc){.kind = PDK_BC_DISPLACEMENT, .set = "set:bottom", .components = 2};
    bcs[nb++] = (pdk_bc){.kind = PDK_BC_DISPLACEMENT, .set = "set:left", .components = 1};
    bcs[nb] = (pdk_bc){.kind = PDK_BC_BODY_FORCE, .set = "set:top", .components = 2};
    bcs[nb++].value[1] = pdk_tfun_constant(-T * W / (n_top * V));
    /* body forces add up: the top-right corner carries both tractions */
    bcs[nb] = (pdk_bc){.kind = PDK_BC_BODY_FORCE, .set = "set:right", .components = 1};
    bcs[nb++].value[0] = pdk_tfun_constant(-T * H / (n_right * V));
    r->exact = -T * W / (2.0 * (lambda + mu));
    probe_set = "set:right";
    probe_c = 0;
  } else {
    TRY(pdk_particles_set_define(p, "bottom", &bottom, NULL));
    TRY(pdk_particles_set_define(p, "left", &left, NULL));
    TRY(pdk_particles_set_define(p, "right", &right, NULL));
    const pdk_index n_top = count_set(p, "set:top");
    const unsigned side = prob == P_VQ_SHEAR ? 2u : 1u; /* shear: u_y = 0; uniaxial: u_x = 0 */
    bcs[nb++] = (pdk_bc){.kind = PDK_BC_DISPLACEMENT, .set = "set:bottom", .components = 3};
    bcs[nb++] = (pdk_bc){.kind = PDK_BC_DISPLACEMENT, .set = "set:left", .components = side};
    bcs[nb++] = (pdk_bc){.kind = PDK_BC_DISPLACEMENT, .set = "set:right", .components = side};
    if (prob == P_VQ_SHEAR) {
      bcs[nb] = (pdk_bc){.kind = PDK_BC_BODY_FORCE, .set = "set:top", .components = 1};
      bcs[nb++].value[0] = pdk_tfun_constant(T * W / (n_top * V));
      r->exact = T * H / mu;
      probe_c = 0;
    } else {
      bcs[nb] = (pdk_bc){.kind = PDK_BC_BODY_FORCE, .set = "set:top", .components = 2};
      bcs[nb++].value[1] = pdk_tfun_constant(-T * W / (n_top * V));
      r->exact = -T * H / (lambda + 2.0 * mu);
    }
  }
  TRY(build_model(p, k, h, K, G, 1.0, &fam, &m));
  pdk_static_opts so = static_opts(k, r);
  so.bcs = bcs;
  so.num_bcs = nb;
  TRY(pdk_static_create(m, &so, &s));
  TRY(pdk_static_solve(s));
  r->wall = pdk_wtime() - w0;
  r->cpu = cpu_seconds() - c0;
  finish_static(r, s);
  {
    /* probe: mean displacement of the loaded edge's particles within 0.4..0.6 of its length */
    const double *x = pdk_particles_field_data(p, "x", probe_c);
    const double *Xc = pdk_particles_X(p, probe_c);
    const int along = prob == P_VQ_ISOTROPIC ? 1 : 0; /* right edge: y; top edge: x */
    const double *Xa = pdk_particles_X(p, along);       /* coordinate along the edge */
    const uint8_t *in = pdk_particles_field_data(p, probe_set, 0);
    const double len = along == 0 ? W : H;
    double sum = 0.0;
    int cnt = 0;
    for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
      if (in[i] && Xa[i] >= 0.4 * len - 1e-9 && Xa[i] <= 0.6 * len + 1e-9) {
        sum += x[i] - Xc[i];
        ++cnt;
      }
    r->value = sum / cnt;
    r->error = fabs(r->value - r->exact) / fabs(r->exact);
  }
cleanup:
  r->particles = p ? pdk_particles_count(p) : 0;
  r->bonds = fam ? (long)pdk_families_num_bonds(fam) : 0;
  if (err) row_fail(r, ctx, err);
  pdk_static_destroy(&s);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

/* ---- manufactured static field ------------------------------------------------------------ */

/* phi(t) = sin^4(pi t), psi(t) = sin^4(pi t) cos(pi t) on [0, 1], 0 outside; derivative d. */
static double mms_phi(double t, int d) {
  if (t <= 0.0 || t >= 1.0) return 0.0;
  const double s = sin(M_PI * t), c = cos(M_PI * t), w = M_PI;
  switch (d) {
  case 0: return s * s * s * s;
  case 1: return 4.0 * w * s * s * s * c;
  default: return 4.0 * w * w * (3.0 * s * s * c * c - s * s * s * s);
  }
}
static double mms_psi(double t, int d) {
  if (t <= 0.0 || t >= 1.0) return 0.0;
  const double s = sin(M_PI * t), c = cos(M_PI * t), w = M_PI;
  const double s2 = s * s, s3 = s2 * s, s4 = s2 * s2, s5 = s4 * s, c2 = c * c;
  switch (d) {
  case 0: return s4 * c;
  case 1: return w * (4.0 * s3 * c2 - s5);
  default: return w * w * (12.0 * s2 * c2 * c - 8.0 * s4 * c - 5.0 * s4 * c);
  }
}
/* u* = a (phi(X) + psi(Y), psi(X) - phi(Y)); the amplitude keeps strains near 1e-5, so the
 * geometric nonlinearity of PMB and LPS bonds stays far below the discretization error. */
#define MMS_AMP 4e-6
static void mms_u(double X, double Y, double u[2]) {
  u[0] = MMS_AMP * (mms_phi(X, 0) + mms_psi(Y, 0));
  u[1] = MMS_AMP * (mms_psi(X, 0) - mms_phi(Y, 0));
}
/* b = -Div sigma(u*), sigma = lambda tr(eps) I + 2 mu eps: no mixed derivatives. */
static void mms_b(double X, double Y, double lambda, double mu, double b[2]) {
  const double M = lambda + 2.0 * mu;
  b[0] = -MMS_AMP * (M * mms_phi(X, 2) + mu * mms_psi(Y, 2));
  b[1] = -MMS_AMP * (mu * mms_psi(X, 2) - M * mms_phi(Y, 2));
}

static void run_mms(pdk_ctx *ctx, const knobs *k, int N, row *r) {
  const double E = 1.0, nu = 0.25, h = 1.0 / N;
  const double K = E / (3.0 * (1.0 - 2.0 * nu)), G = E / (2.0 * (1.0 + nu));
  const int nc = (int)floor(2.0 * k->m + 1e-9); /* collar layers: 2 delta */
  pdk_particles *p = NULL;
  pdk_families *fam = NULL;
  pdk_model *m = NULL;
  pdk_static *s = NULL;
  int err = 0;
  double lambda, mu;
  lame(k, K, G, &lambda, &mu);
  const double w0 = pdk_wtime(), c0 = cpu_seconds();
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.node_type = 1;
  lo.spacing = h;
  lo.lo[0] = lo.lo[1] = -nc * h;
  lo.hi[0] = lo.hi[1] = 1.0 + nc * h;
  TRY(pdk_lattice_create(ctx, &lo, &p));
  const double e = 0.25 * h;
  const double in0[3] = {-e, -e, -1}, in1[3] = {1 + e, 1 + e, 1};
  pdk_region collar = pdk_region_box(in0, in1);
  collar.invert = 1;
  TRY(pdk_particles_set_define(p, "collar", &collar, NULL));
  TRY(build_model(p, k, h, K, G, 1.0, &fam, &m));
  {
    /* Per-particle condition values (pdk_bc.scale_field), filled after the Morton reorder: the
     * collar's prescribed displacement u* and the square's body force b = -Div sigma(u*). */
    TRY(pdk_particles_field_add(p, "mms_u", PDK_F64, 2));
    TRY(pdk_particles_field_add(p, "mms_b", PDK_F64, 2));
    const pdk_index n = pdk_particles_count(p);
    const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
    const uint8_t *in_collar = pdk_particles_field_data(p, "set:collar", 0);
    double *uf[2] = {pdk_particles_field_data(p, "mms_u", 0), pdk_particles_field_data(p, "mms_u", 1)};
    double *bf[2] = {pdk_particles_field_data(p, "mms_b", 0), pdk_particles_field_data(p, "mms_b", 1)};
    for (pdk_index i = 0; i < n; ++i) {
      double u[2], b[2];
      mms_u(X[i], Y[i], u);
      mms_b(X[i], Y[i], lambda, mu, b);
      for (int c = 0; c < 2; ++c) {
        uf[c][i] = in_collar[i] ? u[c] : 0.0;
        bf[c][i] = in_collar[i] ? 0.0 : b[c];
      }
    }
  }
  pdk_bc bcs[2];
  memset(bcs, 0, sizeof bcs);
  bcs[0] = (pdk_bc){.kind = PDK_BC_DISPLACEMENT, .set = "set:collar", .components = 3,
                    .scale_field = "mms_u"};
  bcs[1] = (pdk_bc){.kind = PDK_BC_BODY_FORCE, .set = NULL, .components = 3,
                    .scale_field = "mms_b"};
  for (int c = 0; c < 2; ++c)
    bcs[0].value[c] = bcs[1].value[c] = pdk_tfun_constant(1.0);
  pdk_static_opts so = static_opts(k, r);
  so.bcs = bcs;
  so.num_bcs = 2;
  TRY(pdk_static_create(m, &so, &s));
  TRY(pdk_static_solve(s));
  r->wall = pdk_wtime() - w0;
  r->cpu = cpu_seconds() - c0;
  finish_static(r, s);
  {
    const pdk_index n = pdk_particles_count(p);
    const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
    const double *x = pdk_particles_field_data(p, "x", 0), *y = pdk_particles_field_data(p, "x", 1);
    const uint8_t *in_collar = pdk_particles_field_data(p, "set:collar", 0);
    double num = 0.0, den = 0.0;
    for (pdk_index i = 0; i < n; ++i) {
      if (in_collar[i]) continue;
      double u[2];
      mms_u(X[i], Y[i], u);
      const double dx = x[i] - X[i] - u[0], dy = y[i] - Y[i] - u[1];
      num += dx * dx + dy * dy;
      den += u[0] * u[0] + u[1] * u[1];
    }
    r->error = sqrt(num / den);
    r->value = sqrt(num / den);
    r->exact = 0.0;
  }
cleanup:
  r->particles = p ? pdk_particles_count(p) : 0;
  r->bonds = fam ? (long)pdk_families_num_bonds(fam) : 0;
  if (err) row_fail(r, ctx, err);
  pdk_static_destroy(&s);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

/* ---- standing wave in a bar ------------------------------------------------------------------ */

static double wave_projection(pdk_particles *p, double k) {
  const pdk_index n = pdk_particles_count(p);
  const double *X = pdk_particles_X(p, 0), *x = pdk_particles_field_data(p, "x", 0);
  double a = 0.0;
  for (pdk_index i = 0; i < n; ++i)
    a += (x[i] - X[i]) * cos(k * X[i]);
  return a;
}

static void run_wave(pdk_ctx *ctx, const knobs *kn, int N, row *r) {
  const double L = 1.0, W = 0.25, E = 1.0, nu = 0.25, rho = 1.0, A = 1e-6, h = L / N;
  const double K = E / (3.0 * (1.0 - 2.0 * nu)), G = E / (2.0 * (1.0 + nu));
  const double k = M_PI / L;
  pdk_particles *p = NULL;
  pdk_families *fam = NULL;
  pdk_model *m = NULL;
  pdk_explicit *ex = NULL;
  int err = 0;
  double lambda, mu;
  lame(kn, K, G, &lambda, &mu);
  r->exact = k * sqrt((lambda + 2.0 * mu) / rho);
  const double w0 = pdk_wtime(), c0 = cpu_seconds();
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE; /* cell-centred: the particles' cells tile [0, L] x [0, W] */
  lo.spacing = h;
  lo.hi[0] = L;
  lo.hi[1] = W;
  TRY(pdk_lattice_create(ctx, &lo, &p));
  TRY(build_model(p, kn, h, K, G, rho, &fam, &m));
  {
    const pdk_index n = pdk_particles_count(p);
    const double *X = pdk_particles_X(p, 0);
    double *x = pdk_particles_field_data(p, "x", 0);
    for (pdk_index i = 0; i < n; ++i)
      x[i] = X[i] + A * cos(k * X[i]);
  }
  pdk_bc bc;
  memset(&bc, 0, sizeof bc);
  bc = (pdk_bc){.kind = PDK_BC_DISPLACEMENT, .set = NULL, .components = 2};
  pdk_explicit_opts eo = pdk_explicit_opts_default();
  eo.bcs = &bc;
  eo.num_bcs = 1;
  eo.safety = kn->safety;
  TRY(pdk_explicit_create(m, &eo, &ex));
  {
    const double dt = pdk_explicit_dt(ex), period = 2.0 * M_PI / r->exact;
    const long max_steps = (long)ceil(1.2 * period / dt);
    double a_prev = wave_projection(p, k), t_prev = 0.0, cross[2] = {0, 0};
    int found = 0;
    long step = 0;
    while (found < 2 && step < max_steps) {
      TRY(pdk_explicit_run(ex, 1, NULL));
      ++step;
      const double a = wave_projection(p, k), t = pdk_explicit_time(ex);
      const int down = found == 0 && a_prev > 0 && a <= 0, up = found == 1 && a_prev < 0 && a >= 0;
      if (down || up) cross[found++] = t_prev + (t - t_prev) * a_prev / (a_prev - a);
      a_prev = a;
      t_prev = t;
    }
    r->work = step;
    if (found < 2) {
      err = pdk_ctx_error_set(ctx, PDK_ERR_NUMERIC, "wave",
                              "the mode did not cross zero twice in 1.2 periods (%ld steps)", step);
      goto cleanup;
    }
    r->wall = pdk_wtime() - w0;
    r->cpu = cpu_seconds() - c0;
    r->value = M_PI / (cross[1] - cross[0]);
    r->error = fabs(r->value / r->exact - 1.0);
  }
cleanup:
  r->particles = p ? pdk_particles_count(p) : 0;
  r->bonds = fam ? (long)pdk_families_num_bonds(fam) : 0;
  if (err) row_fail(r, ctx, err);
  pdk_explicit_destroy(&ex);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

/* ---- plate with a hole ---------------------------------------------------------------------- */

#define HOLE_REFERENCE 3.14 /* (2 + 0.8^3) / 0.8, Heywood's finite-width factor at d/W = 0.2 */

static void run_hole(pdk_ctx *ctx, const knobs *k, int N, row *r) {
  const double W = 1.0, H = 2.0, R = 0.1, E = 1.0, nu = 0.25, h = W / N, sigma0 = 1e-3 * E;
  const double K = E / (3.0 * (1.0 - 2.0 * nu)), G = E / (2.0 * (1.0 + nu));
  const double cx = 0.5 * W, cy = 0.5 * H;
  pdk_particles *p = NULL;
  pdk_families *fam = NULL;
  pdk_model *m = NULL;
  pdk_static *s = NULL;
  int err = 0;
  double lambda, mu;
  lame(k, K, G, &lambda, &mu);
  r->exact = HOLE_REFERENCE;
  const double w0 = pdk_wtime(), c0 = cpu_seconds();
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = PDK_LATTICE_SQUARE;
  lo.spacing = h;
  lo.hi[0] = W;
  lo.hi[1] = H;
  TRY(pdk_lattice_create(ctx, &lo, &p));
  const double centre[3] = {cx, cy, 0};
  pdk_region hole = pdk_region_ball(centre, R);
  TRY(pdk_particles_cut(p, &hole, NULL));
  const double big = 10.0, e = 0.6 * h;
  const double t0[3] = {-big, H - e, -1}, t1[3] = {big, big, 1};
  const double b0[3] = {-big, -big, -1}, b1[3] = {big, e, 1};
  const double mt0[3] = {cx - e, H - e, -1}, mt1[3] = {cx + e, big, 1};
  const double mb0[3] = {cx - e, -big, -1}, mb1[3] = {cx + e, e, 1};
  const double ml0[3] = {-big, cy - e, -1}, ml1[3] = {e, cy + e, 1};
  const double mr0[3] = {W - e, cy - e, -1}, mr1[3] = {big, cy + e, 1};
  pdk_region top = pdk_region_box(t0, t1), bottom = pdk_region_box(b0, b1);
  pdk_region mid_top = pdk_region_box(mt0, mt1), mid_bottom = pdk_region_box(mb0, mb1);
  pdk_region mid_left = pdk_region_box(ml0, ml1), mid_right = pdk_region_box(mr0, mr1);
  TRY(pdk_particles_set_define(p, "top", &top, NULL));
  TRY(pdk_particles_set_define(p, "bottom", &bottom, NULL));
  TRY(pdk_particles_set_define(p, "xfix", &mid_top, NULL));
  {
    /* one set for both x supports, one for both y supports */
    uint8_t *xf = pdk_particles_field_data(p, "set:xfix", 0);
    TRY(pdk_particles_set_define(p, "xfix_b", &mid_bottom, NULL));
    TRY(pdk_particles_set_define(p, "yfix", &mid_left, NULL));
    TRY(pdk_particles_set_define(p, "yfix_r", &mid_right, NULL));
    xf = pdk_particles_field_data(p, "set:xfix", 0);
    const uint8_t *xb = pdk_particles_field_data(p, "set:xfix_b", 0);
    uint8_t *yf = pdk_particles_field_data(p, "set:yfix", 0);
    const uint8_t *yr = pdk_particles_field_data(p, "set:yfix_r", 0);
    for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
      xf[i] |= xb[i];
      yf[i] |= yr[i];
    }
  }
  const pdk_index n_top = count_set(p, "set:top"), n_bottom = count_set(p, "set:bottom");
  const double V = h * h;
  pdk_bc bcs[4];
  memset(bcs, 0, sizeof bcs);
  bcs[0] = (pdk_bc){.kind = PDK_BC_DISPLACEMENT, .set = "set:xfix", .components = 1};
  bcs[1] = (pdk_bc){.kind = PDK_BC_DISPLACEMENT, .set = "set:yfix", .components = 2};
  bcs[2] = (pdk_bc){.kind = PDK_BC_BODY_FORCE, .set = "set:top", .components = 2};
  bcs[2].value[1] = pdk_tfun_constant(sigma0 * W / (n_top * V));
  bcs[3] = (pdk_bc){.kind = PDK_BC_BODY_FORCE, .set = "set:bottom", .components = 2};
  bcs[3].value[1] = pdk_tfun_constant(-sigma0 * W / (n_bottom * V));
  TRY(build_model(p, k, h, K, G, 1.0, &fam, &m));
  pdk_static_opts so = static_opts(k, r);
  so.bcs = bcs;
  so.num_bcs = 4;
  TRY(pdk_static_create(m, &so, &s));
  TRY(pdk_static_solve(s));
  r->wall = pdk_wtime() - w0;
  r->cpu = cpu_seconds() - c0;
  finish_static(r, s);
  {
    /* sigma_yy from the least-squares displacement gradient over each particle's family */
    const pdk_index n = pdk_particles_count(p);
    const pdk_bond_index *bs = pdk_families_bond_start(fam);
    const pdk_index *bj = pdk_families_bond_j(fam);
    const double *X = pdk_particles_X(p, 0), *Y = pdk_particles_X(p, 1);
    const double *x = pdk_particles_field_data(p, "x", 0), *y = pdk_particles_field_data(p, "x", 1);
    const double *vol = pdk_particles_volume(p), delta = k->m * h;
    const pdk_influence infl =
        k->kind == PDK_MODEL_CORRESPONDENCE ? k->influence : PDK_INFLUENCE_CONSTANT;
    double peak = -INFINITY;
    for (pdk_index i = 0; i < n; ++i) {
      double Kxx = 0, Kxy = 0, Kyy = 0, Nux = 0, Nuy = 0, Nvx = 0, Nvy = 0;
      for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
        const pdk_index j = bj[b];
        const double xi0 = X[j] - X[i], xi1 = Y[j] - Y[i];
        const double w = pdk_influence_eval(infl, sqrt(xi0 * xi0 + xi1 * xi1), delta, 0.5) * vol[j];
        const double du = (x[j] - X[j]) - (x[i] - X[i]), dv = (y[j] - Y[j]) - (y[i] - Y[i]);
        Kxx += w * xi0 * xi0;
        Kxy += w * xi0 * xi1;
        Kyy += w * xi1 * xi1;
        Nux += w * du * xi0;
        Nuy += w * du * xi1;
        Nvx += w * dv * xi0;
        Nvy += w * dv * xi1;
      }
      const double det = Kxx * Kyy - Kxy * Kxy;
      if (!(det > 1e-12 * (Kxx * Kyy))) continue;
      const double Ixx = Kyy / det, Ixy = -Kxy / det, Iyy = Kxx / det;
      const double ux = Nux * Ixx + Nuy * Ixy, vy = Nvx * Ixy + Nvy * Iyy;
      const double syy = lambda * (ux + vy) + 2.0 * mu * vy;
      if (syy > peak) peak = syy;
    }
    r->value = peak / sigma0;
    r->error = fabs(r->value - r->exact) / r->exact;
  }
cleanup:
  r->particles = p ? pdk_particles_count(p) : 0;
  r->bonds = fam ? (long)pdk_families_num_bonds(fam) : 0;
  if (err) row_fail(r, ctx, err);
  pdk_static_destroy(&s);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
}

static void run_one(pdk_ctx *ctx, row *r) {
  snprintf(r->status, sizeof r->status, "ok");
  r->note[0] = '\0';
  switch ((problem_id)r->problem) {
  case P_MMS: r->h = 1.0 / r->level; run_mms(ctx, &r->k, r->level, r); break;
  case P_VQ_UNIAXIAL:
  case P_VQ_ISOTROPIC:
  case P_VQ_SHEAR: r->h = 10.0 / r->level; run_vq(ctx, (problem_id)r->problem, &r->k, r->level, r); break;
  case P_WAVE: r->h = 1.0 / r->level; run_wave(ctx, &r->k, r->level, r); break;
  case P_HOLE: r->h = 1.0 / r->level; run_hole(ctx, &r->k, r->level, r); break;
  default: break;
  }
  if (strcmp(r->status, "ok") == 0 && !isfinite(r->error)) {
    snprintf(r->status, sizeof r->status, "failed");
    snprintf(r->note, sizeof r->note, "non-finite error");
  }
}

/* ---- plans ---------------------------------------------------------------------------------- */

typedef struct plan {
  series *s;
  int n, cap;
} plan;

static int knobs_equal(const knobs *a, const knobs *b) {
  return a->kind == b->kind && a->partial_volume == b->partial_volume && a->stab == b->stab &&
         a->influence == b->influence && a->m == b->m && a->precision == b->precision &&
         a->connectivity == b->connectivity && a->safety == b->safety &&
         a->lattice_order == b->lattice_order && a->method == b->method;
}

/* Adds a series, or the sweep name to an identical one already planned. */
static void plan_add(plan *pl, problem_id prob, const char *sweep, knobs k, const int *levels,
                     int num_levels) {
  if (k.kind != PDK_MODEL_CORRESPONDENCE) { /* knobs PMB and LPS do not have */
    k.stab = PDK_STAB_NONE;
    k.influence = PDK_INFLUENCE_CONSTANT;
    k.connectivity = PDK_CONNECTIVITY_TL;
  }
  if (prob != P_WAVE) k.safety = 0.8, k.lattice_order = 0;
  if (prob == P_WAVE) k.method = PDK_STATIC_NEWTON;
  for (int i = 0; i < pl->n; ++i)
    if (pl->s[i].problem == prob && knobs_equal(&pl->s[i].k, &k)) {
      if (!strstr(pl->s[i].sweeps, sweep)) {
        size_t len = strlen(pl->s[i].sweeps);
        snprintf(pl->s[i].sweeps + len, sizeof pl->s[i].sweeps - len, " %s", sweep);
      }
      return;
    }
  if (pl->n == pl->cap) {
    pl->cap = pl->cap ? 2 * pl->cap : 64;
    pl->s = realloc(pl->s, (size_t)pl->cap * sizeof *pl->s);
    if (!pl->s) {
      fprintf(stderr, "tradeoff: out of memory\n");
      exit(1);
    }
  }
  series *s = &pl->s[pl->n++];
  memset(s, 0, sizeof *s);
  s->problem = prob;
  snprintf(s->sweeps, sizeof s->sweeps, "%s", sweep);
  s->k = k;
  s->num_levels = num_levels;
  memcpy(s->levels, levels, (size_t)num_levels * sizeof *levels);
}

static knobs with_model(knobs k, const char *model) {
  if (!strcmp(model, "pmb") || !strcmp(model, "pmb-pv")) k.kind = PDK_MODEL_PMB;
  else if (!strcmp(model, "lps") || !strcmp(model, "lps-pv")) k.kind = PDK_MODEL_LPS;
  else {
    k.kind = PDK_MODEL_CORRESPONDENCE;
    k.stab = strstr(model, "none") ? PDK_STAB_NONE
             : strstr(model, "hourglass") ? PDK_STAB_HOURGLASS : PDK_STAB_SILLING;
  }
  k.partial_volume = strstr(model, "-pv") != NULL;
  return k;
}

/* Resolution ladders of one problem: `base` for every series, `big` for m = 4 (four times the
 * bonds of m = 2), `fine` (one level more) for m <= 2. NULL / 0: use `base`. */
typedef struct ladders {
  const int *base;
  int num_base;
  const int *big;
  int num_big;
  const int *fine;
  int num_fine;
} ladders;

static void add(plan *pl, problem_id prob, const char *sweep, knobs k, const ladders *ld) {
  if (k.m > 3.5 && ld->big)
    plan_add(pl, prob, sweep, k, ld->big, ld->num_big);
  else if (k.m < 2.5 && ld->fine)
    plan_add(pl, prob, sweep, k, ld->fine, ld->num_fine);
  else
    plan_add(pl, prob, sweep, k, ld->base, ld->num_base);
}

/* The sweeps of one problem; `full` adds the sweeps the tiny plan leaves out. */
static void plan_problem(plan *pl, problem_id prob, const ladders *ld, int full) {
  const knobs base = knobs_baseline();
  static const char *models[] = {"pmb", "pmb-pv", "lps", "lps-pv", "corr-none", "corr-silling",
                                 "corr-hourglass"};
  static const char *tiny_models[] = {"pmb", "lps", "corr-silling"};
  static const double ms[] = {1.5, 2.015, 3.015, 4.015};
  for (int i = 0; i < (full ? 7 : 3); ++i)
    add(pl, prob, "model", with_model(base, full ? models[i] : tiny_models[i]), ld);
  if (!full) {
    /* tiny: the precision knob (correspondence, float storage, Newton at rtol 1e-7); for V-Q also
     * the paper's setting (no stabilization, cubic influence, RF 1.5), whose order is known */
    knobs k = base;
    k.precision = PDK_PRECISION_FLOAT;
    add(pl, prob, "precision", k, ld);
    if (prob == P_VQ_UNIAXIAL) {
      k = with_model(base, "corr-none");
      k.influence = PDK_INFLUENCE_CUBIC;
      k.m = 1.5;
      add(pl, prob, "influence-rf1.5", k, ld);
    }
    return;
  }
  const char *m_models[] = {"pmb", "lps", "corr-silling", "corr-none"};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      if (a == 3 && prob != P_VQ_UNIAXIAL && prob != P_VQ_SHEAR && prob != P_MMS) continue;
      knobs k = with_model(base, m_models[a]);
      k.m = ms[b];
      add(pl, prob, "m", k, ld);
    }
  for (int f = 0; f < 6; ++f) {
    knobs k = base;
    k.influence = (pdk_influence)f;
    add(pl, prob, "influence", k, ld);
    if (prob == P_VQ_UNIAXIAL || prob == P_VQ_SHEAR) { /* the paper's setting: RF 1.5, no stab */
      k.m = 1.5;
      k.stab = PDK_STAB_NONE;
      add(pl, prob, "influence-rf1.5", k, ld);
    }
  }
  /* precision: each model that has float storage, at the baseline m and (correspondence) at
   * m 1.5, where the errors are smallest and round-off would show first; ADR beside Newton for
   * the static problems; UL, which refuses float storage, once, so the CSV records why */
  const char *p_models[] = {"pmb", "lps", "corr-silling", "corr-silling"};
  for (int a = 0; a < 4; ++a)
    for (int fl = 0; fl < 2; ++fl) {
      knobs k = with_model(base, p_models[a]);
      if (a == 3) k.m = 1.5;
      k.precision = fl ? PDK_PRECISION_FLOAT : PDK_PRECISION_DOUBLE;
      add(pl, prob, "precision", k, ld);
      if (prob != P_WAVE && a >= 2) {
        k.method = PDK_STATIC_ADR;
        add(pl, prob, "precision", k, ld);
      }
    }
  {
    knobs k = base;
    k.precision = PDK_PRECISION_FLOAT;
    k.connectivity = PDK_CONNECTIVITY_UL;
    add(pl, prob, "precision", k, ld);
  }
  if (prob == P_VQ_ISOTROPIC) return; /* the uniaxial and shear tests cover the other knobs */
  for (int c = 0; c < 3; ++c) {
    knobs k = base;
    k.connectivity = (pdk_connectivity)c;
    add(pl, prob, "connectivity", k, ld);
  }
  if (prob == P_WAVE) {
    static const double safeties[] = {0.2, 0.4, 0.8, 1.0};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 4; ++b) {
        knobs k = with_model(base, a ? "pmb" : "corr-silling");
        k.safety = safeties[b];
        add(pl, prob, "dt", k, ld);
      }
    for (int a = 0; a < 2; ++a)
      for (int o = 0; o < 2; ++o) {
        knobs k = with_model(base, a ? "pmb" : "corr-silling");
        k.lattice_order = o;
        add(pl, prob, "order", k, ld);
      }
  } else if (prob != P_VQ_SHEAR) {
    for (int a = 0; a < 2; ++a)
      for (int meth = 0; meth < 2; ++meth) {
        knobs k = with_model(base, a ? "pmb" : "corr-silling");
        k.method = meth ? PDK_STATIC_ADR : PDK_STATIC_NEWTON;
        add(pl, prob, "solver", k, ld);
      }
  }
}

#define LADDER(a) a, (int)(sizeof a / sizeof *a)

static void plan_build(plan *pl, int full, const int *want) {
  if (full) {
    static const int mms[] = {16, 32, 64}, mms_big[] = {16, 32}, mms_fine[] = {16, 32, 64, 128};
    static const int vq[] = {20, 40, 80}, vq_fine[] = {20, 40, 80, 160};
    static const int wave[] = {32, 64, 128, 256};
    static const int hole[] = {20, 40, 80}, hole_big[] = {20, 40}, hole_fine[] = {20, 40, 80, 160};
    const ladders l_mms = {LADDER(mms), LADDER(mms_big), LADDER(mms_fine)};
    const ladders l_vq = {LADDER(vq), NULL, 0, LADDER(vq_fine)};
    const ladders l_wave = {LADDER(wave), NULL, 0, NULL, 0};
    const ladders l_hole = {LADDER(hole), LADDER(hole_big), LADDER(hole_fine)};
    if (want[P_MMS]) plan_problem(pl, P_MMS, &l_mms, 1);
    for (int q = P_VQ_UNIAXIAL; q <= P_VQ_SHEAR; ++q)
      if (want[q]) plan_problem(pl, (problem_id)q, &l_vq, 1);
    if (want[P_WAVE]) plan_problem(pl, P_WAVE, &l_wave, 1);
    if (want[P_HOLE]) plan_problem(pl, P_HOLE, &l_hole, 1);
  } else {
    static const int mms[] = {16, 32}, vq[] = {20, 40}, wave[] = {32, 64}, hole[] = {20, 40};
    const ladders l_mms = {LADDER(mms), NULL, 0, NULL, 0}, l_vq = {LADDER(vq), NULL, 0, NULL, 0};
    const ladders l_wave = {LADDER(wave), NULL, 0, NULL, 0};
    const ladders l_hole = {LADDER(hole), NULL, 0, NULL, 0};
    if (want[P_MMS]) plan_problem(pl, P_MMS, &l_mms, 0);
    if (want[P_VQ_UNIAXIAL]) plan_problem(pl, P_VQ_UNIAXIAL, &l_vq, 0);
    if (want[P_WAVE]) plan_problem(pl, P_WAVE, &l_wave, 0);
    if (want[P_HOLE]) plan_problem(pl, P_HOLE, &l_hole, 0);
  }
}

/* ---- CSV ------------------------------------------------------------------------------------ */

static const char *csv_header =
    "problem,sweeps,series,model,stabilization,influence,m,precision,connectivity,dt_safety,"
    "order,solver,level,h,particles,bonds,work,wall_s,cpu_s,error,value,exact,status,pareto,"
    "note";

static void csv_write_row(FILE *f, const row *r) {
  fprintf(f, "%s,%s,%d,%s,%s,%s,%.4g,%s,%s,%.2g,%s,%s,%d,%.6g,%ld,%ld,%ld,%.4g,%.4g,%.6e,%.10e,"
             "%.10e,%s,%d,%s\n",
          problem_name[r->problem], r->sweeps, r->series, model_label(&r->k),
          r->k.kind == PDK_MODEL_CORRESPONDENCE ? stab_name[r->k.stab] : "-",
          r->k.kind == PDK_MODEL_CORRESPONDENCE ? influence_name[r->k.influence] : "-", r->k.m,
          r->k.precision == PDK_PRECISION_FLOAT ? "float" : "double",
          r->k.kind == PDK_MODEL_CORRESPONDENCE ? conn_name[r->k.connectivity] : "-",
          r->problem == P_WAVE ? r->k.safety : 0.0,
          r->problem == P_WAVE ? (r->k.lattice_order ? "lattice" : "morton") : "morton",
          r->problem == P_WAVE ? "explicit" : pdk_static_method_name(r->k.method), r->level, r->h,
          r->particles, r->bonds, r->work, r->wall, r->cpu, r->error, r->value, r->exact, r->status,
          r->pareto, r->note);
}

static int lookup(const char *const *names, int n, const char *s) {
  for (int i = 0; i < n; ++i)
    if (!strcmp(names[i], s)) return i;
  return -1;
}

/* Reads a CSV this program wrote. Returns the row count, -1 on error (message printed). */
static int csv_read(const char *path, row **out) {
  FILE *f = fopen(path, "r");
  if (!f) {
    fprintf(stderr, "tradeoff: cannot read '%s': %s\n", path, strerror(errno));
    return -1;
  }
  char line[2048];
  int n = 0, cap = 0, lineno = 1;
  row *rows = NULL;
  if (!fgets(line, sizeof line, f) || strncmp(line, csv_header, strlen(csv_header)) != 0) {
    fprintf(stderr, "tradeoff: '%s' does not start with this program's header\n", path);
    fclose(f);
    return -1;
  }
  while (fgets(line, sizeof line, f)) {
    ++lineno;
    line[strcspn(line, "\n")] = '\0';
    char *col[25];
    int nc = 0;
    char *s = line;
    while (nc < 25) {
      col[nc++] = s;
      char *c = strchr(s, ',');
      if (!c) break;
      *c = '\0';
      s = c + 1;
    }
    if (nc != 25) {
      fprintf(stderr, "tradeoff: %s:%d: %d columns, expected 25\n", path, lineno, nc);
      free(rows);
      fclose(f);
      return -1;
    }
    if (n == cap) {
      cap = cap ? 2 * cap : 256;
      rows = realloc(rows, (size_t)cap * sizeof *rows);
      if (!rows) {
        fprintf(stderr, "tradeoff: out of memory\n");
        exit(1);
      }
    }
    row *r = &rows[n];
    memset(r, 0, sizeof *r);
    const int prob = lookup(problem_name, P_COUNT, col[0]);
    if (prob < 0) {
      fprintf(stderr, "tradeoff: %s:%d: unknown problem '%s'\n", path, lineno, col[0]);
      free(rows);
      fclose(f);
      return -1;
    }
    r->problem = prob;
    snprintf(r->sweeps, sizeof r->sweeps, "%s", col[1]);
    r->series = atoi(col[2]);
    r->k = with_model(knobs_baseline(), col[3]);
    if (r->k.kind == PDK_MODEL_CORRESPONDENCE) {
      r->k.influence = (pdk_influence)lookup(influence_name, 6, col[5]);
      r->k.connectivity = (pdk_connectivity)lookup(conn_name, 3, col[8]);
    }
    r->k.m = atof(col[6]);
    r->k.precision = strcmp(col[7], "float") ? PDK_PRECISION_DOUBLE : PDK_PRECISION_FLOAT;
    r->k.safety = atof(col[9]);
    r->k.lattice_order = !strcmp(col[10], "lattice");
    r->k.method = strcmp(col[11], "adr") ? PDK_STATIC_NEWTON : PDK_STATIC_ADR;
    r->level = atoi(col[12]);
    r->h = atof(col[13]);
    r->particles = atol(col[14]);
    r->bonds = atol(col[15]);
    r->work = atol(col[16]);
    r->wall = atof(col[17]);
    r->cpu = atof(col[18]);
    r->error = atof(col[19]);
    r->value = atof(col[20]);
    r->exact = atof(col[21]);
    snprintf(r->status, sizeof r->status, "%s", col[22]);
    snprintf(r->note, sizeof r->note, "%s", col[24]);
    ++n;
  }
  fclose(f);
  *out = rows;
  return n;
}

/* ---- Pareto front and plots ------------------------------------------------------------------ */

static int row_ok(const row *r) { return !strcmp(r->status, "ok"); }

/* Whether the series of rows[i] converges: its error falls by at least a quarter when h halves
 * between its two finest resolutions that ran (order >= 0.4). A setting whose error stalls at a
 * model error (PMB or LPS at fixed m, unstabilized correspondence at large m) is not a choice
 * that buys accuracy with cost, so its runs stay off the front however cheap they are. */
static int series_converges(const row *rows, int n, int i) {
  const row *fine = NULL, *next = NULL;
  for (int j = 0; j < n; ++j) {
    const row *r = &rows[j];
    if (r->problem != rows[i].problem || r->series != rows[i].series || !row_ok(r)) continue;
    if (!fine || r->h < fine->h) {
      next = fine;
      fine = r;
    } else if (!next || r->h < next->h) {
      next = r;
    }
  }
  return fine && next && fine->error <= 0.75 * next->error;
}

/* Marks the runs no other run of the same problem dominates (cost: CPU time), among the runs of
 * converging series (series_converges). */
static void pareto_mark(row *rows, int n) {
  /* compare the values as the CSV stores them, so a reader of the CSV finds the same front */
  for (int i = 0; i < n; ++i) {
    char buf[64];
    snprintf(buf, sizeof buf, "%.4g", rows[i].cpu);
    rows[i].cpu = atof(buf);
    snprintf(buf, sizeof buf, "%.6e", rows[i].error);
    rows[i].error = atof(buf);
  }
  int *eligible = malloc((size_t)(n > 0 ? n : 1) * sizeof *eligible);
  if (!eligible) {
    fprintf(stderr, "bench_tradeoff: out of memory\n");
    exit(1);
  }
  for (int i = 0; i < n; ++i) eligible[i] = row_ok(&rows[i]) && series_converges(rows, n, i);
  for (int i = 0; i < n; ++i) {
    rows[i].pareto = 0;
    if (!eligible[i]) continue;
    int dominated = 0;
    for (int j = 0; j < n && !dominated; ++j) {
      if (j == i || !eligible[j] || rows[j].problem != rows[i].problem) continue;
      const row *a = &rows[j], *b = &rows[i];
      if (a->cpu <= b->cpu && a->error <= b->error && (a->cpu < b->cpu || a->error < b->error))
        dominated = 1;
    }
    rows[i].pareto = !dominated;
  }
  free(eligible);
}

static const char *sweep_names[] = {"model", "m", "influence", "influence-rf1.5", "precision",
                                    "connectivity", "dt", "order", "solver"};
#define NUM_SWEEPS ((int)(sizeof sweep_names / sizeof *sweep_names))

/* A series label inside one sweep panel: the knob that the sweep varies (plus the model). */
static void series_label(const row *r, const char *sweep, char *buf, size_t len) {
  const char *model = model_label(&r->k);
  if (!strcmp(sweep, "model")) snprintf(buf, len, "%s", model);
  else if (!strcmp(sweep, "m")) snprintf(buf, len, "%s m %.4g", model, r->k.m);
  else if (!strncmp(sweep, "influence", 9)) snprintf(buf, len, "%s", influence_name[r->k.influence]);
  else if (!strcmp(sweep, "precision"))
    snprintf(buf, len, "%s m %.4g%s %s", model, r->k.m,
             r->k.method == PDK_STATIC_ADR && r->problem != P_WAVE ? " adr" : "",
             r->k.precision ? "float" : "double");
  else if (!strcmp(sweep, "connectivity")) snprintf(buf, len, "%s", conn_name[r->k.connectivity]);
  else if (!strcmp(sweep, "dt")) snprintf(buf, len, "%s safety %.2g", model, r->k.safety);
  else if (!strcmp(sweep, "order"))
    snprintf(buf, len, "%s %s", model, r->k.lattice_order ? "lattice" : "morton");
  else snprintf(buf, len, "%s %s", model, pdk_static_method_name(r->k.method));
}

/* 1 if the space-separated list `sweeps` names `sweep`. */
static int lists_sweep(const char *sweeps, const char *sweep) {
  const char *s = sweeps;
  const size_t len = strlen(sweep);
  while ((s = strstr(s, sweep))) {
    if ((s == sweeps || s[-1] == ' ') && (s[len] == ' ' || s[len] == '\0')) return 1;
    s += len;
  }
  return 0;
}

static int has_sweep(const row *r, const char *sweep) { return lists_sweep(r->sweeps, sweep); }

static int cmp_cpu(const void *a, const void *b) {
  const row *x = *(row *const *)a, *y = *(row *const *)b;
  return (x->cpu > y->cpu) - (x->cpu < y->cpu);
}

/* Writes DIR/tradeoff.gp: one PNG per problem, a panel per sweep; every run of the problem in
 * grey, the sweep's series in colour (one line per series through its resolutions), the Pareto
 * front in black. The data are inline, so the script needs nothing but gnuplot. */
static int write_gnuplot(const char *dir, row *rows, int n) {
  char path[1024], part[1100];
  snprintf(path, sizeof path, "%s/tradeoff.gp", dir);
  snprintf(part, sizeof part, "%s.part", path);
  FILE *f = fopen(part, "w");
  if (!f) {
    fprintf(stderr, "tradeoff: cannot create '%s': %s\n", part, strerror(errno));
    return 1;
  }
  row **sorted = malloc((size_t)(n > 0 ? n : 1) * sizeof *sorted);
  if (!sorted) {
    fclose(f);
    return 1;
  }
  fprintf(f, "# Written by bench/tradeoff (tradeoff --plot-only rewrites it from tradeoff.csv).\n"
             "# Run in this directory: gnuplot tradeoff.gp\n");
  fprintf(f, "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { term = 'pngcairo' } else { term = "
             "'png' }\n");
  for (int pb = 0; pb < P_COUNT; ++pb) {
    int any = 0;
    for (int i = 0; i < n; ++i)
      any |= rows[i].problem == pb && row_ok(&rows[i]);
    if (!any) continue;
    int panels = 0, used[NUM_SWEEPS];
    for (int sw = 0; sw < NUM_SWEEPS; ++sw) {
      used[sw] = 0;
      for (int i = 0; i < n; ++i)
        if (rows[i].problem == pb && row_ok(&rows[i]) && has_sweep(&rows[i], sweep_names[sw]))
          used[sw] = 1;
      panels += used[sw];
    }
    const int cols = panels > 4 ? 3 : panels > 1 ? 2 : 1, lines = (panels + cols - 1) / cols;
    /* data blocks: all runs, the front, and each series of each sweep */
    fprintf(f, "$all_%d << EOD\n", pb);
    for (int i = 0; i < n; ++i)
      if (rows[i].problem == pb && row_ok(&rows[i]))
        fprintf(f, "%.6g %.6g\n", rows[i].cpu, fmax(rows[i].error, 1e-16));
    fprintf(f, "EOD\n$front_%d << EOD\n", pb);
    int nf = 0;
    for (int i = 0; i < n; ++i)
      if (rows[i].problem == pb && rows[i].pareto) sorted[nf++] = &rows[i];
    qsort(sorted, (size_t)nf, sizeof *sorted, cmp_cpu);
    for (int i = 0; i < nf; ++i)
      fprintf(f, "%.6g %.6g \"%s\"\n", sorted[i]->cpu, fmax(sorted[i]->error, 1e-16),
              model_label(&sorted[i]->k));
    fprintf(f, "EOD\n");
    fprintf(f, "set terminal term size %d,%d noenhanced font ',9'\n", 520 * cols, 420 * lines);
    fprintf(f, "set output '%s.png.part'\n", problem_name[pb]); /* renamed when all are done */
    fprintf(f, "set logscale xy\nset grid\nset format x '%%g'\nset format y '%%g'\n"
               "set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'\n"
               "set xlabel 'cost: CPU time [s], 1 thread'\nset ylabel 'relative error'\n");
    fprintf(f, "set multiplot layout %d,%d title '%s: %s'\n", lines, cols, problem_name[pb],
            problem_title[pb]);
    for (int sw = 0; sw < NUM_SWEEPS; ++sw) {
      if (!used[sw]) continue;
      fprintf(f, "set title 'sweep: %s'\n", sweep_names[sw]);
      /* one data block per series in this sweep, resolution ascending */
      int sids[128], ns = 0;
      for (int i = 0; i < n; ++i) {
        const row *r = &rows[i];
        if (r->problem != pb || !row_ok(r) || !has_sweep(r, sweep_names[sw])) continue;
        int seen = 0;
        for (int q = 0; q < ns; ++q)
          seen |= sids[q] == r->series;
        if (!seen && ns < 128) sids[ns++] = r->series;
      }
      fprintf(f, "plot $all_%d using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \\\n"
                 "     $front_%d using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front'",
              pb, pb);
      char label[96] = "";
      for (int q = 0; q < ns; ++q) {
        fprintf(f, ", \\\n     '-' using 1:2 with linespoints pt %d lw 1.5 title '", 1 + q % 13);
        for (int i = 0; i < n; ++i)
          if (rows[i].problem == pb && rows[i].series == sids[q]) {
            series_label(&rows[i], sweep_names[sw], label, sizeof label);
            break;
          }
        fprintf(f, "%s'", label);
      }
      fprintf(f, "\n");
      for (int q = 0; q < ns; ++q) {
        for (int i = 0; i < n; ++i)
          if (rows[i].problem == pb && rows[i].series == sids[q] && row_ok(&rows[i]))
            fprintf(f, "%.6g %.6g\n", rows[i].cpu, fmax(rows[i].error, 1e-16));
        fprintf(f, "e\n");
      }
    }
    fprintf(f, "unset multiplot\nset output\n");
  }
  free(sorted);
  const int bad = ferror(f) | (fclose(f) != 0);
  if (bad || rename(part, path) != 0) {
    fprintf(stderr, "tradeoff: cannot write '%s'\n", path);
    remove(part);
    return 1;
  }
  return 0;
}

static int write_csv(const char *dir, row *rows, int n) {
  char path[1024], part[1100];
  snprintf(path, sizeof path, "%s/tradeoff.csv", dir);
  snprintf(part, sizeof part, "%s.part", path);
  FILE *f = fopen(part, "w");
  if (!f) {
    fprintf(stderr, "tradeoff: cannot create '%s': %s\n", part, strerror(errno));
    return 1;
  }
  fprintf(f, "%s\n", csv_header);
  for (int i = 0; i < n; ++i)
    csv_write_row(f, &rows[i]);
  const int bad = ferror(f) | (fclose(f) != 0);
  if (bad || rename(part, path) != 0) {
    fprintf(stderr, "tradeoff: cannot write '%s'\n", path);
    remove(part);
    return 1;
  }
  return 0;
}

/* Runs gnuplot on DIR/tradeoff.gp, which writes DIR/<problem>.png.part; only when it succeeds are
 * they renamed to <problem>.png, so a failed or interrupted plot leaves no PNG that looks
 * complete. A <problem>.png of a problem without runs in the CSV is removed (stale). */
static int plot(const char *dir, row *rows, int n, int run_gnuplot) {
  if (write_gnuplot(dir, rows, n)) return 1;
  if (!run_gnuplot) return 0;
  char cmd[1200], path[1100], part[1200];
  snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot tradeoff.gp", dir);
  const int rc = system(cmd);
  int bad = rc != 0;
  if (bad) fprintf(stderr, "tradeoff: gnuplot failed (exit %d) on %s/tradeoff.gp\n", rc, dir);
  for (int pb = 0; pb < P_COUNT; ++pb) {
    int any = 0;
    for (int i = 0; i < n; ++i)
      any |= rows[i].problem == pb && row_ok(&rows[i]);
    snprintf(path, sizeof path, "%s/%s.png", dir, problem_name[pb]);
    snprintf(part, sizeof part, "%s.part", path);
    if (!any) {
      remove(path);
      continue;
    }
    if (bad) {
      remove(part);
    } else if (rename(part, path) != 0) {
      fprintf(stderr, "tradeoff: gnuplot wrote no '%s': %s\n", part, strerror(errno));
      bad = 1;
    }
  }
  if (bad) /* the PNGs renamed before the failure are complete; the .part files are removed */
    for (int pb = 0; pb < P_COUNT; ++pb) {
      snprintf(part, sizeof part, "%s/%s.png.part", dir, problem_name[pb]);
      remove(part);
    }
  return bad;
}

/* mkdir -p: creates DIR and its missing parents (mode 0777 before the umask). */
static int make_dirs(const char *dir) {
  char buf[1024];
  const size_t len = strlen(dir);
  if (len == 0 || len >= sizeof buf) {
    fprintf(stderr, "tradeoff: --out-dir '%s': give a path of 1 to %zu characters\n", dir,
            sizeof buf - 1);
    return 1;
  }
  memcpy(buf, dir, len + 1);
  for (size_t i = 1; i <= len; ++i) {
    if (buf[i] != '/' && buf[i] != '\0') continue;
    const char keep = buf[i];
    buf[i] = '\0';
    struct stat st;
    if (stat(buf, &st) != 0) {
      if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "tradeoff: --out-dir: cannot create '%s': %s\n", buf, strerror(errno));
        return 1;
      }
    } else if (!S_ISDIR(st.st_mode)) {
      fprintf(stderr, "tradeoff: --out-dir: '%s' exists and is not a directory\n", buf);
      return 1;
    }
    buf[i] = keep;
  }
  return 0;
}

/* ---- main ----------------------------------------------------------------------------------- */

static void usage(FILE *out) {
  fprintf(out, "usage: tradeoff [--plan tiny|full] [--problem NAME]... [--out-dir DIR] "
               "[--sweep NAME] [--threads T] [--no-plot] [--plot-only] [--list]\n  problems:");
  for (int p = 0; p < P_COUNT; ++p)
    fprintf(out, " %s", problem_name[p]);
  fprintf(out, "\n");
}

int main(int argc, char **argv) {
  int full = 1, threads = 1, want[P_COUNT] = {0}, any_want = 0, no_plot = 0, plot_only = 0,
      list = 0;
  const char *dir = ".", *only_sweep = NULL;
  for (int a = 1; a < argc; ++a) {
    const char *o = argv[a];
    const int more = a + 1 < argc;
    if (!strcmp(o, "--plan") && more) {
      const char *v = argv[++a];
      if (strcmp(v, "tiny") && strcmp(v, "full")) {
        fprintf(stderr, "tradeoff: --plan %s: use tiny or full\n", v);
        return 2;
      }
      full = !strcmp(v, "full");
    } else if (!strcmp(o, "--problem") && more) {
      const int p = lookup(problem_name, P_COUNT, argv[++a]);
      if (p < 0) {
        fprintf(stderr, "tradeoff: --problem %s: unknown problem\n", argv[a]);
        usage(stderr);
        return 2;
      }
      want[p] = any_want = 1;
    } else if (!strcmp(o, "--sweep") && more) {
      only_sweep = argv[++a];
      int known = 0;
      for (int k = 0; k < NUM_SWEEPS; ++k)
        known |= !strcmp(only_sweep, sweep_names[k]);
      if (!known) {
        fprintf(stderr, "tradeoff: --sweep %s: unknown sweep; the sweeps are", only_sweep);
        for (int k = 0; k < NUM_SWEEPS; ++k)
          fprintf(stderr, " %s", sweep_names[k]);
        fprintf(stderr, "\n");
        return 2;
      }
    } else if (!strcmp(o, "--out-dir") && more) dir = argv[++a];
    else if (!strcmp(o, "--threads") && more) {
      threads = atoi(argv[++a]);
      if (threads < 1) {
        fprintf(stderr, "tradeoff: --threads %s: give a whole number >= 1\n", argv[a]);
        return 2;
      }
    } else if (!strcmp(o, "--no-plot")) no_plot = 1;
    else if (!strcmp(o, "--plot-only")) plot_only = 1;
    else if (!strcmp(o, "--list")) list = 1;
    else if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
      usage(stdout);
      return 0;
    } else {
      fprintf(stderr, "tradeoff: unknown or incomplete option '%s'\n", o);
      usage(stderr);
      return 2;
    }
  }
  if (!any_want)
    for (int p = 0; p < P_COUNT; ++p)
      want[p] = 1;
  if (plot_only) {
    char path[1024];
    snprintf(path, sizeof path, "%s/tradeoff.csv", dir);
    row *rows = NULL;
    const int n = csv_read(path, &rows);
    if (n < 0) return 1;
    pareto_mark(rows, n);
    const int rc = write_csv(dir, rows, n) || plot(dir, rows, n, !no_plot);
    free(rows);
    return rc;
  }
  /* The whole plan is built, whatever --problem says, so a series has the same number in every
   * run and the CSVs of runs over different problems can be concatenated. */
  plan pl = {NULL, 0, 0};
  const int all[P_COUNT] = {1, 1, 1, 1, 1, 1};
  plan_build(&pl, full, all);
  long total_runs = 0;
  int total_series = 0;
  for (int i = 0; i < pl.n; ++i)
    pl.s[i].selected =
        want[pl.s[i].problem] && (!only_sweep || lists_sweep(pl.s[i].sweeps, only_sweep));
  for (int i = 0; i < pl.n; ++i)
    if (pl.s[i].selected) total_runs += pl.s[i].num_levels, ++total_series;
  if (list) {
    for (int i = 0; i < pl.n; ++i) {
      if (!pl.s[i].selected) continue;
      row r;
      memset(&r, 0, sizeof r);
      r.problem = pl.s[i].problem;
      r.k = pl.s[i].k;
      snprintf(r.sweeps, sizeof r.sweeps, "%s", pl.s[i].sweeps);
      r.series = i;
      r.level = pl.s[i].levels[pl.s[i].num_levels - 1];
      snprintf(r.status, sizeof r.status, "planned");
      csv_write_row(stdout, &r);
    }
    printf("%d series, %ld runs\n", total_series, total_runs);
    free(pl.s);
    return 0;
  }
  /* the output directory before the study, not after it: a bad path fails in a second */
  if (make_dirs(dir)) return 1;
  pdk_ctx_opts co = pdk_ctx_opts_default();
  co.num_threads = threads;
  char why[512];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(&co, &ctx, why, sizeof why)) {
    fprintf(stderr, "tradeoff: cannot create a pdk context: %s\n", why);
    return 1;
  }
  row *rows = calloc((size_t)(total_runs > 0 ? total_runs : 1), sizeof *rows);
  if (!rows) {
    fprintf(stderr, "tradeoff: out of memory\n");
    return 1;
  }
  int n = 0;
  const double t_start = pdk_wtime();
  for (int i = 0; i < pl.n; ++i) {
    const series *s = &pl.s[i];
    if (!s->selected) continue;
    int stop = 0; /* after an unsupported setting, the finer levels are skipped */
    for (int l = 0; l < s->num_levels; ++l) {
      row *r = &rows[n++];
      r->problem = s->problem;
      snprintf(r->sweeps, sizeof r->sweeps, "%s", s->sweeps);
      r->series = i;
      r->k = s->k;
      r->level = s->levels[l];
      if (stop) {
        snprintf(r->status, sizeof r->status, "skipped");
        snprintf(r->note, sizeof r->note, "coarser level %s", rows[n - 2].status);
        continue;
      }
      run_one(ctx, r);
      stop = strcmp(r->status, "unsupported") == 0;
      fprintf(stderr, "[%6.0f s] %-12s %-16s %-8s m %-5.4g %-6s %-7s %-9s L %-4d n %-7ld  cpu %8.3f s"
                      "  error %.3e  %s%s%s\n",
              pdk_wtime() - t_start, problem_name[r->problem], model_label(&r->k),
              r->k.kind == PDK_MODEL_CORRESPONDENCE ? influence_name[r->k.influence] : "-", r->k.m,
              r->k.precision ? "float" : "double",
              r->k.kind == PDK_MODEL_CORRESPONDENCE ? conn_name[r->k.connectivity] : "-",
              s->sweeps, r->level, r->particles, r->cpu, r->error, r->status,
              r->note[0] ? ": " : "", r->note);
    }
  }
  pdk_ctx_destroy(&ctx);
  pareto_mark(rows, n);
  int rc = write_csv(dir, rows, n);
  if (!rc) rc = plot(dir, rows, n, !no_plot);
  fprintf(stderr, "%d runs in %.0f s; results in %s/tradeoff.csv\n", n, pdk_wtime() - t_start, dir);
  free(rows);
  free(pl.s);
  return rc;
}
