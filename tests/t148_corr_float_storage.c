/* Correspondence with float storage (opts.precision = float): the tensors pass 2 gathers from
 * neighbours (B = A - k (F - I) for Silling, A otherwise, and k (F - I) for hourglass) are stored
 * as floats;
 * everything else (positions, K^-1, F, A, the sums) stays double. 2-D and 3-D jittered lattices
 * under a random displacement, Neo-Hooke, every stabilization, reference and optimized kernels,
 * TL with broken bonds (critical stretch) in 3-D:
 *   - the forces differ from double storage (the option is not ignored) by no more than the bound
 *     the storage allows: rounding B_j, G_j to float changes each entry by at most u_f |entry|
 *     (u_f = 2^-24), so |f_float - f_double|_r <= u_f sum_b w V sum_c (|A_j| + k_j |F_j - I|)_rc
 *     |xi_c| (+ hourglass: u_f (delta/|xi|) k_j |F_j - I| |xi|_1 |Y|_1 / |Y|), with |.| the
 *     largest entry and k_j = stab_modulus / m_j computed here, plus the double round-off of the
 *     two evaluations, 4 (n + 8) 2^-53 of the sum of the terms' magnitudes; the test takes 1.01
 *     times this sum;
 *   - the strain energy is bitwise that of double storage (it uses only i's own double F);
 *   - 1 and 2 threads give bitwise identical forces;
 *   - a body 1e4 spacings from the origin under a 1e-6 strain: float storage changes the force
 *     by less than 1e-5 of its magnitude (positions stay double and the stored tensors are of the
 *     size of the strain, so nothing is dominated by float resolution);
 *   - from a scene: `model.precision: float` reaches the model (tests/scenes/t060_plate.yaml with
 *     the key overridden) and a force pass runs; with `connectivity: ul` it is refused, naming the
 *     key.
 * labels: physics threads */
#include "corr_util.h"

#define UF 0x1p-24
#define UD 0x1p-53

typedef struct result {
  double *f[3], energy;
  pdk_index n;
} result;

/* Runs one force pass and copies f, energy. */
static result run(const char *kernels, int threads, int dim, int stab, int precision, int N,
                  double s00, double origin, double amp) {
  pdk_ctx_opts co = pdk_ctx_opts_default();
  co.num_threads = threads;
  co.kernels = kernels;
  char why[512];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(&co, &ctx, why, sizeof why)) T_FAIL("pdk_ctx_create: %s", why);
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = dim == 2 ? PDK_LATTICE_SQUARE : PDK_LATTICE_CUBIC;
  for (int a = 0; a < 3; ++a)
    lo.lo[a] = origin, lo.hi[a] = origin + (a < dim ? (double)N : 1.0);
  lo.spacing = 1.0;
  lo.jitter = origin == 0.0 ? 0.2 : 0.0;
  lo.seed = 5;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  pdk_families *fam = cu_families(ctx, p, 2.6);
  pdk_model_opts o = cu_opts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_CONSTANT, stab, 0.1);
  o.precision = (pdk_precision)precision;
  o.critical_stretch = s00;
  pdk_model *m = cu_model(ctx, p, fam, &o);
  const pdk_index n = pdk_particles_count(p);
  if (origin == 0.0) {
    cu_random_x(p, amp, 99);
  } else { /* uniaxial strain 1e-6 along x about the body's corner */
    double *x = cu_field(p, "x", 0);
    const double *X = pdk_particles_X(p, 0);
    for (pdk_index i = 0; i < n; ++i)
      x[i] = X[i] + 1e-6 * (X[i] - origin);
  }
  result r = {{NULL, NULL, NULL}, 0.0, n};
  if (s00 > 0.0) T_OK(ctx, pdk_model_force(m, NULL)); /* commit: breaks bonds */
  T_OK(ctx, pdk_model_force_trial(m, &r.energy));
  for (int a = 0; a < dim; ++a) {
    r.f[a] = malloc((size_t)n * sizeof(double));
    memcpy(r.f[a], cu_field(p, "f", a), (size_t)n * sizeof(double));
  }
  if (s00 > 0.0) T_ASSERT(pdk_model_num_broken(m) > 0, "some bonds broke");
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
  return r;
}

static void result_free(result *r) {
  for (int a = 0; a < 3; ++a)
    free(r->f[a]);
}

/* The bound of the header for every particle, from a double run's fields (same geometry). */
static void check_bound(const char *kernels, int dim, int stab, int N, double s00, const result *rd,
                        const result *rf) {
  pdk_ctx *ctx = t_ctx(1);
  pdk_lattice_opts lo = pdk_lattice_opts_default();
  lo.type = dim == 2 ? PDK_LATTICE_SQUARE : PDK_LATTICE_CUBIC;
  for (int a = 0; a < 3; ++a)
    lo.lo[a] = 0.0, lo.hi[a] = a < dim ? (double)N : 1.0;
  lo.spacing = 1.0;
  lo.jitter = 0.2;
  lo.seed = 5;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, &lo, &p));
  pdk_families *fam = cu_families(ctx, p, 2.6);
  pdk_model_opts o = cu_opts(PDK_LAW_NEO_HOOKE, PDK_INFLUENCE_CONSTANT, stab, 0.1);
  o.critical_stretch = s00;
  pdk_model *m = cu_model(ctx, p, fam, &o);
  cu_random_x(p, 0.05, 99);
  if (s00 > 0.0) T_OK(ctx, pdk_model_force(m, NULL));
  T_OK(ctx, pdk_model_force_trial(m, NULL));
  const pdk_index n = pdk_particles_count(p);
  const pdk_bond_index *bs = pdk_families_bond_start(fam);
  const pdk_index *bj = pdk_families_bond_j(fam);
  const uint8_t *alive = pdk_model_bond_alive(m);
  const uint8_t *flag = pdk_particles_field_data(p, "flag", 0);
  const double *V = pdk_particles_volume(p);
  const double *X[3], *x[3], *A[9], *F[9];
  for (int a = 0; a < dim; ++a)
    X[a] = pdk_particles_X(p, a), x[a] = cu_field(p, "x", a);
  for (int t = 0; t < dim * dim; ++t)
    A[t] = cu_field(p, "A", t), F[t] = cu_field(p, "F", t);
  const double stab_modulus = 0.1 * (dim == 3 ? 72.0 / 5.0 : 36.0 / 5.0) * CU_BULK;
  double *kst = calloc((size_t)n, sizeof(double));
  for (pdk_index i = 0; i < n; ++i) {
    double mi = 0.0;
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b)
      if (!alive || alive[b])
        for (int c = 0; c < dim; ++c)
          mi += V[bj[b]] * (X[c][bj[b]] - X[c][i]) * (X[c][bj[b]] - X[c][i]);
    kst[i] = stab && !flag[i] && mi > 0.0 ? stab_modulus / mi : 0.0;
  }
  double worst = 0.0, fmax_all = 0.0, dmax = 0.0;
  for (pdk_index i = 0; i < n; ++i) {
    double Sf = 0.0, Sd = 0.0;
    int nb = 0;
    double Fi = 0.0, Ai = 0.0;
    for (int t = 0; t < dim * dim; ++t)
      Fi = fmax(Fi, fabs(F[t][i])), Ai = fmax(Ai, fabs(A[t][i]));
    for (pdk_bond_index b = bs[i]; b < bs[i + 1]; ++b) {
      if (alive && !alive[b]) continue;
      ++nb;
      const pdk_index j = bj[b];
      double Fj = 0.0, Aj = 0.0, xi1 = 0.0, y1 = 0.0, x2 = 0.0, y2 = 0.0, FIj = 0.0;
      for (int t = 0; t < dim * dim; ++t) {
        Fj = fmax(Fj, fabs(F[t][j])), Aj = fmax(Aj, fabs(A[t][j]));
        FIj = fmax(FIj, fabs(F[t][j] - (t % (dim + 1) == 0 ? 1.0 : 0.0)));
      }
      for (int c = 0; c < dim; ++c) {
        const double e = X[c][j] - X[c][i], y = x[c][j] - x[c][i];
        xi1 += fabs(e), y1 += fabs(y), x2 += e * e, y2 += y * y;
      }
      const double hg = stab == PDK_STAB_HOURGLASS && y2 > 0.0
                            ? 2.6 / sqrt(x2) * (kst[j] * FIj * xi1 * y1 / sqrt(y2))
                            : 0.0;
      Sf += V[j] * ((Aj + kst[j] * FIj) * xi1 + hg);
      Sd += V[j] *
            ((Ai + Aj + kst[i] * Fi + kst[j] * Fj) * xi1 + (kst[i] + kst[j]) * (y1 + xi1) +
             (stab == PDK_STAB_HOURGLASS && y2 > 0.0
                  ? 2.6 / sqrt(x2) *
                        ((kst[i] + kst[j]) * y1 + (kst[i] * Fi + kst[j] * Fj) * xi1 * y1 / sqrt(y2))
                  : 0.0));
    }
    const double bound = 1.01 * (UF * Sf + 4.0 * (nb + 8) * UD * Sd) + 1e-300;
    for (int r = 0; r < dim; ++r) {
      const double diff = fabs(rf->f[r][i] - rd->f[r][i]);
      T_ASSERT(diff <= bound,
               "%s d %d stab %d s00 %g: particle %d f[%d] float %.17g double %.17g "
               "differ by %g > bound %g",
               kernels ? kernels : "default", dim, stab, s00, (int)i, r, rf->f[r][i], rd->f[r][i],
               diff, bound);
      worst = fmax(worst, diff / bound);
      dmax = fmax(dmax, diff);
      fmax_all = fmax(fmax_all, fabs(rd->f[r][i]));
    }
  }
  T_ASSERT(dmax > 0.0, "%s d %d stab %d: float storage gave the double forces bit for bit",
           kernels ? kernels : "default", dim, stab);
  T_INFO("%-7s d %d stab %d s00 %g: max |f_float - f_double| = %.3g = %.3g of max |f|, %.2f of "
         "the bound\n",
         kernels ? kernels : "default", dim, stab, s00, dmax, dmax / fmax_all, worst);
  free(kst);
  pdk_model_destroy(&m);
  pdk_families_destroy(&fam);
  pdk_particles_destroy(&p);
  pdk_ctx_destroy(&ctx);
}

static void scene_key(void) {
  char path[1024];
  const char *src = getenv("PDK_SOURCE_DIR");
  snprintf(path, sizeof path, "%s/tests/scenes/t060_plate.yaml", src ? src : "..");
  pdk_ctx *ctx = t_ctx(2);
  pdk_scene *s = NULL;
  pdk_sim *sim = NULL;
  double e[2];
  for (int fl = 0; fl <= 1; ++fl) {
    const char *ov[] = {fl ? "model.precision=float" : "model.precision=double"};
    T_OK(ctx, pdk_scene_load(ctx, path, ov, 1, &s));
    T_OK(ctx, pdk_sim_create(ctx, s, &sim));
    pdk_model *m = pdk_sim_model(sim);
    T_ASSERT(pdk_model_opts_get(m)->precision == (fl ? PDK_PRECISION_FLOAT : PDK_PRECISION_DOUBLE),
             "scene precision reaches the model");
    cu_random_x(pdk_sim_particles(sim), 1e-6, 3); /* spacing 1e-3: strains ~1e-3 */
    T_OK(ctx, pdk_model_force_trial(m, &e[fl]));
    pdk_sim_destroy(&sim);
    pdk_scene_destroy(&s);
  }
  T_ASSERT(e[0] > 0.0 && e[1] == e[0], "scene: energy %.17g (float) vs %.17g (double)", e[1], e[0]);
  const char *ov_ul[] = {"model.precision=float", "model.connectivity=ul",
                         "model.critical_stretch=0", "model.alpha=0", "geometry.precracks=[]"};
  T_OK(ctx, pdk_scene_load(ctx, path, ov_ul, 5, &s));
  T_FAILS(ctx, pdk_sim_create(ctx, s, &sim), PDK_ERR_UNSUPPORTED, "model.precision");
  pdk_scene_destroy(&s);
  pdk_ctx_destroy(&ctx);
}

int main(void) {
  scene_key();
  const char *kern[2] = {"ref", NULL};
  for (int ik = 0; ik < 2; ++ik)
    for (int dim = 2; dim <= 3; ++dim)
      for (int stab = 0; stab <= PDK_STAB_HOURGLASS; ++stab) {
        const int N = dim == 2 ? 14 : 7;
        const double s00 = dim == 3 && stab == PDK_STAB_SILLING ? 0.02 : 0.0;
        result rd = run(kern[ik], 1, dim, stab, PDK_PRECISION_DOUBLE, N, s00, 0.0, 0.05);
        result rf = run(kern[ik], 1, dim, stab, PDK_PRECISION_FLOAT, N, s00, 0.0, 0.05);
        result rf2 = run(kern[ik], 2, dim, stab, PDK_PRECISION_FLOAT, N, s00, 0.0, 0.05);
        T_ASSERT(rf.energy == rd.energy, "energy: float storage %.17g, double %.17g", rf.energy,
                 rd.energy);
        for (int a = 0; a < dim; ++a)
          T_ASSERT(!memcmp(rf.f[a], rf2.f[a], (size_t)rf.n * sizeof(double)),
                   "float storage: 1 and 2 threads differ (d %d stab %d)", dim, stab);
        T_ASSERT(rf2.energy == rf.energy, "energy 1 vs 2 threads");
        check_bound(kern[ik], dim, stab, N, s00, &rd, &rf);
        result_free(&rd), result_free(&rf), result_free(&rf2);
      }
  /* Far from the origin: positions stay double. */
  {
    result rd = run(NULL, 1, 2, PDK_STAB_SILLING, PDK_PRECISION_DOUBLE, 10, 0.0, 1e4, 0.0);
    result rf = run(NULL, 1, 2, PDK_STAB_SILLING, PDK_PRECISION_FLOAT, 10, 0.0, 1e4, 0.0);
    double dmax = 0.0, fmax_all = 0.0;
    for (int a = 0; a < 2; ++a)
      for (pdk_index i = 0; i < rd.n; ++i) {
        dmax = fmax(dmax, fabs(rf.f[a][i] - rd.f[a][i]));
        fmax_all = fmax(fmax_all, fabs(rd.f[a][i]));
      }
    T_ASSERT(fmax_all > 0.0 && dmax <= 1e-5 * fmax_all,
             "far body: float storage changes f by %g of %g", dmax, fmax_all);
    T_INFO("far body (X ~ 1e4): max |f_float - f_double| = %.3g of max |f| %.3g\n", dmax, fmax_all);
    result_free(&rd), result_free(&rf);
  }
  return 0;
}
