/* Families against an O(n^2) brute force written here, independent of the library (V-NB): random
 * clouds in 2-D and 3-D (from horizons small enough that the cells are binned sparsely, or the
 * grid coarsened, up to one larger than the body), lattices with a hole, and particles placed
 * exactly on cell faces; each in store order,
 * Morton order by the family cells, and a random order (interleaved cells: the merge path); with
 * the ref and simd kernel families at 1 and 2 threads, all required bitwise identical to the brute
 * force (same bonds, same order). Also: symmetry (j in H_i <=> i in H_j), ascending j, the count
 * path taken when the occupancy bound exceeds max_bytes, and a single particle.
 * labels: unit threads */
#include <stdint.h>

#include "test_util.h"

/* The brute force evaluates the neighbour rule of families.h literally; no FMA contraction. */
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

typedef struct csr {
  int64_t *start; /* [n+1] */
  int32_t *j;     /* [start[n]] */
} csr;

static uint64_t rng_next(uint64_t *s) { /* splitmix64 */
  uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
static double rng_unit(uint64_t *s) { return (double)(rng_next(s) >> 11) * 0x1p-53; }

/* Bonds of every particle by testing every pair: r2 = (dx*dx + dy*dy) + dz*dz <= h*h*(1 + 1e-12).
 */
static csr brute_force(int dim, int n, const double *const X[3], double h) {
  const double r2max = h * h * (1.0 + 1e-12);
  csr b;
  b.start = calloc((size_t)n + 1, sizeof *b.start);
  size_t cap = 1024, num = 0;
  b.j = malloc(cap * sizeof *b.j);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (j == i) continue;
      double dx = X[0][j] - X[0][i], dy = X[1][j] - X[1][i];
      double r2 = dx * dx + dy * dy;
      if (dim == 3) {
        double dz = X[2][j] - X[2][i];
        r2 = r2 + dz * dz;
      }
      if (r2 <= r2max) {
        if (num == cap) b.j = realloc(b.j, (cap *= 2) * sizeof *b.j);
        b.j[num++] = j;
      }
    }
    b.start[i + 1] = (int64_t)num;
  }
  return b;
}

static pdk_ctx *make_ctx(const char *kernels, int threads) {
  pdk_ctx_opts o = pdk_ctx_opts_default();
  o.kernels = kernels;
  o.num_threads = threads;
  o.bind = PDK_BIND_NONE;
  o.bind_explicit = 1;
  char why[512];
  pdk_ctx *ctx = NULL;
  if (pdk_ctx_create(&o, &ctx, why, sizeof why)) T_FAIL("pdk_ctx_create: %s", why);
  return ctx;
}

static pdk_particles *make_store(pdk_ctx *ctx, int dim, int n, const double *const X[3]) {
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_particles_create(ctx, dim, n, &p));
  for (int a = 0; a < dim; ++a)
    memcpy(pdk_particles_X(p, a), X[a], (size_t)n * sizeof(double));
  return p;
}

/* Same bonds in the same order as the brute force; also symmetry and ascending j. */
static void compare(const char *what, const pdk_families *f, const csr *b, int n) {
  const pdk_bond_index *start = pdk_families_bond_start(f);
  const pdk_index *bj = pdk_families_bond_j(f);
  T_ASSERT(pdk_families_num_particles(f) == n, "%s", what);
  T_ASSERT(pdk_families_num_bonds(f) == b->start[n], "%s: %lld bonds, brute force %lld", what,
           (long long)pdk_families_num_bonds(f), (long long)b->start[n]);
  for (int i = 0; i < n; ++i) {
    if (start[i + 1] != b->start[i + 1])
      T_FAIL("%s: particle %d has %lld bonds, brute force %lld", what, i,
             (long long)(start[i + 1] - start[i]), (long long)(b->start[i + 1] - b->start[i]));
    for (int64_t k = start[i]; k < start[i + 1]; ++k) {
      if (bj[k] != b->j[k])
        T_FAIL("%s: particle %d bond %lld is %d, brute force %d", what, i,
               (long long)(k - start[i]), (int)bj[k], (int)b->j[k]);
      if (k > start[i] && bj[k] <= bj[k - 1]) T_FAIL("%s: family of %d not ascending", what, i);
      /* symmetry: i in the family of j (binary search, families ascending) */
      const int j = bj[k];
      int64_t lo = start[j], hi = start[j + 1];
      while (lo < hi) {
        int64_t mid = (lo + hi) / 2;
        if (bj[mid] < i)
          lo = mid + 1;
        else
          hi = mid;
      }
      if (lo == start[j + 1] || bj[lo] != i)
        T_FAIL("%s: %d is in the family of %d but not the reverse", what, j, i);
    }
  }
}

static void same_bits(const char *what, const pdk_families *a, const pdk_families *b) {
  const pdk_index n = pdk_families_num_particles(a);
  T_ASSERT(pdk_families_num_bonds(a) == pdk_families_num_bonds(b), "%s", what);
  T_ASSERT(!memcmp(pdk_families_bond_start(a), pdk_families_bond_start(b),
                   ((size_t)n + 1) * sizeof(pdk_bond_index)),
           "%s: bond_start differs", what);
  T_ASSERT(!memcmp(pdk_families_bond_j(a), pdk_families_bond_j(b),
                   (size_t)pdk_families_num_bonds(a) * sizeof(pdk_index)),
           "%s: bond_j differs", what);
}

enum { ORDER_AS_GIVEN, ORDER_MORTON, ORDER_MORTON_HORIZON, ORDER_RANDOM, NUM_ORDERS };

/* Reorders the coordinate arrays in place (a copy is returned in Y). */
static void apply_order(int order, int dim, int n, const double *const X[3], double *Y[3], double h,
                        uint64_t *seed) {
  pdk_index *perm = malloc((size_t)n * sizeof *perm);
  for (int i = 0; i < n; ++i)
    perm[i] = i;
  if (order == ORDER_RANDOM) {
    for (int i = n - 1; i > 0; --i) {
      int k = (int)(rng_next(seed) % (uint64_t)(i + 1));
      pdk_index t = perm[i];
      perm[i] = perm[k];
      perm[k] = t;
    }
  } else if (order == ORDER_MORTON || order == ORDER_MORTON_HORIZON) {
    pdk_ctx *ctx = make_ctx("ref", 1);
    pdk_particles *p = make_store(ctx, dim, n, X);
    double edge = order == ORDER_MORTON ? pdk_families_cell_edge(p, h) : h;
    T_ASSERT(edge >= h, "cell edge %g below the horizon %g", edge, h);
    /* a body wider than 2^21 horizons has no Morton key at the plain horizon: use the cell edge */
    if (pdk_particles_reorder_morton(p, edge, perm) != 0) {
      T_ASSERT(order == ORDER_MORTON_HORIZON, "Morton reorder with the cell edge failed");
      T_OK(ctx, pdk_particles_reorder_morton(p, pdk_families_cell_edge(p, h), perm));
    }
    pdk_particles_destroy(&p);
    pdk_ctx_destroy(&ctx);
  }
  for (int a = 0; a < dim; ++a)
    for (int i = 0; i < n; ++i)
      Y[a][i] = X[a][perm[i]];
  free(perm);
}

static long long g_total_bonds; /* for a sanity check that the cases are not trivial */

/* Runs one case: every order x {ref, simd} x {1, 2 threads}. */
static void check_case(const char *name, int dim, int n, const double *const X[3], double h) {
  uint64_t seed = 12345;
  double *Y[3] = {NULL, NULL, NULL};
  for (int a = 0; a < dim; ++a)
    Y[a] = malloc((size_t)n * sizeof(double));
  static const char *kern[2] = {"ref", "simd"};
  for (int order = 0; order < NUM_ORDERS; ++order) {
    apply_order(order, dim, n, X, Y, h, &seed);
    const double *const Yc[3] = {Y[0], Y[1], dim == 3 ? Y[2] : NULL};
    csr b = brute_force(dim, n, Yc, h);
    g_total_bonds += b.start[n];
    pdk_families *first = NULL;
    for (int k = 0; k < 2; ++k) {
      for (int threads = 1; threads <= 2; ++threads) {
        char what[256];
        snprintf(what, sizeof what, "%s, h = %g, order %d, %s kernels, %d threads", name, h, order,
                 kern[k], threads);
        pdk_ctx *ctx = make_ctx(kern[k], threads);
        pdk_particles *p = make_store(ctx, dim, n, Yc);
        pdk_families_opts o = pdk_families_opts_default();
        o.horizon = h;
        pdk_families *f = NULL;
        T_OK(ctx, pdk_families_build(p, &o, &f));
        compare(what, f, &b, n);
        T_ASSERT(pdk_families_horizon(f) == h, "%s", what);
        T_ASSERT(pdk_families_memory_bytes(f) ==
                     (size_t)(n + 1) * 8 + (size_t)pdk_families_num_bonds(f) * 4,
                 "%s", what);
        if (first) same_bits(what, first, f);
        if (!first) {
          first = f;
        } else {
          pdk_families_destroy(&f);
        }
        pdk_particles_destroy(&p);
        pdk_ctx_destroy(&ctx);
      }
    }
    pdk_families_destroy(&first);
    free(b.start);
    free(b.j);
  }
  for (int a = 0; a < dim; ++a)
    free(Y[a]);
}

typedef struct cloud {
  int dim, n;
  double *X[3];
} cloud;

static cloud cloud_alloc(int dim, int n) {
  cloud c;
  c.dim = dim;
  c.n = n;
  for (int a = 0; a < 3; ++a)
    c.X[a] = a < dim ? calloc((size_t)n, sizeof(double)) : NULL;
  return c;
}
static void cloud_free(cloud *c) {
  for (int a = 0; a < 3; ++a)
    free(c->X[a]);
}
static void run(const char *name, const cloud *c, double h) {
  const double *const X[3] = {c->X[0], c->X[1], c->X[2]};
  check_case(name, c->dim, c->n, X, h);
}

/* Lattice points origin + i * spacing (i per axis in 0..num-1) outside a ball (disk) of radius
 * hole_r around the lattice centre. */
static cloud lattice_with_hole(int dim, const int num[3], double spacing, const double origin[3],
                               double hole_r) {
  int total = num[0] * num[1] * (dim == 3 ? num[2] : 1);
  cloud c = cloud_alloc(dim, total);
  int m = 0;
  for (int k = 0; k < (dim == 3 ? num[2] : 1); ++k)
    for (int j = 0; j < num[1]; ++j)
      for (int i = 0; i < num[0]; ++i) {
        double x[3] = {origin[0] + i * spacing, origin[1] + j * spacing, origin[2] + k * spacing};
        double r2 = 0;
        for (int a = 0; a < dim; ++a) {
          double d = x[a] - (origin[a] + 0.5 * (num[a] - 1) * spacing);
          r2 += d * d;
        }
        if (r2 <= hole_r * hole_r) continue;
        for (int a = 0; a < dim; ++a)
          c.X[a][m] = x[a];
        ++m;
      }
  c.n = m;
  return c;
}

int main(void) {
  uint64_t seed = 2026;

  /* Random clouds, 2-D: offset box; horizons from a coarsened grid to one cell for everything. */
  {
    cloud c = cloud_alloc(2, 1500);
    for (int i = 0; i < c.n; ++i) {
      c.X[0][i] = -3.7 + 8.9 * rng_unit(&seed);
      c.X[1][i] = 10.0 + 4.0 * rng_unit(&seed);
    }
    const double hs[] = {0.01, 0.05, 0.3, 2.0, 100.0};
    for (size_t k = 0; k < sizeof hs / sizeof hs[0]; ++k)
      run("random 2-D", &c, hs[k]);
    cloud_free(&c);
  }
  /* Random clouds, 3-D, far from the origin. h = 0.02 gives 125000 grid cells > 4 n + 4096: the
   * occupied cells are found by sorting keys (sparse binning). */
  {
    cloud c = cloud_alloc(3, 1200);
    for (int i = 0; i < c.n; ++i)
      for (int a = 0; a < 3; ++a)
        c.X[a][i] = 1000.0 + a + rng_unit(&seed);
    const double hs[] = {0.02, 0.1, 0.35, 5.0};
    for (size_t k = 0; k < sizeof hs / sizeof hs[0]; ++k)
      run("random 3-D", &c, hs[k]);
    cloud_free(&c);
  }
  /* A huge, sparse box with close pairs: 1e18 grid cells, sparse binning. Then a box wider than
   * 2^21 horizons: the cell edge grows. */
  for (int wide = 0; wide < 2; ++wide) {
    cloud c = cloud_alloc(3, 600);
    for (int i = 0; i < c.n; i += 2) {
      for (int a = 0; a < 3; ++a) {
        c.X[a][i] = (wide && a ? 10.0 : 1e6 * (wide ? 7 : 1)) * rng_unit(&seed);
        c.X[a][i + 1] = c.X[a][i] + 0.5 * rng_unit(&seed);
      }
    }
    run(wide ? "box wider than 2^21 horizons" : "huge sparse box", &c, 1.0);
    cloud_free(&c);
  }
  /* Lattices with a hole; m = 3.015, 2 (points at exactly 2 dx), 1.5. */
  {
    const int num[3] = {45, 37, 1};
    const double origin[3] = {-1.234, 5.678, 0};
    cloud c = lattice_with_hole(2, num, 0.1, origin, 1.0);
    T_ASSERT(c.n < 45 * 37 && c.n > 1000, "hole cut: %d", c.n);
    run("square lattice with hole", &c, 3.015 * 0.1);
    run("square lattice with hole", &c, 2.0 * 0.1);
    cloud_free(&c);
  }
  {
    const int num[3] = {14, 13, 12};
    const double origin[3] = {0.5, -0.25, 2.0};
    cloud c = lattice_with_hole(3, num, 1e-3, origin, 3.5e-3);
    T_ASSERT(c.n < 14 * 13 * 12 && c.n > 1500, "hole cut: %d", c.n);
    run("cubic lattice with hole", &c, 3.015e-3);
    run("cubic lattice with hole", &c, 2.0e-3);
    run("cubic lattice with hole", &c, 1.5e-3);
    cloud_free(&c);
  }
  /* Particles exactly on cell faces: coordinates drawn from multiples of the cell edge e and of
   * e/2, of the horizon, and e one ulp either side; the origin point fixes the grid's corner. */
  for (int dim = 2; dim <= 3; ++dim) {
    const double h = 0.7;
    cloud c = cloud_alloc(dim, 1000);
    /* the edge for this bounding box: [0, 4e] on every axis, no coarsening */
    pdk_ctx *ctx = make_ctx("ref", 1);
    pdk_particles *p = NULL;
    T_OK(ctx, pdk_particles_create(ctx, dim, 2, &p));
    for (int a = 0; a < dim; ++a)
      pdk_particles_X(p, a)[1] = 4.0 * h;
    const double e = pdk_families_cell_edge(p, h);
    T_ASSERT(e > h && e < h * (1 + 1e-7), "edge %.17g for horizon %.17g", e, h);
    pdk_particles_destroy(&p);
    pdk_ctx_destroy(&ctx);
    for (int i = 0; i < c.n; ++i)
      for (int a = 0; a < dim; ++a) {
        int k = (int)(rng_next(&seed) % 4);
        switch (rng_next(&seed) % 4) {
        case 0: c.X[a][i] = k * e; break;
        case 1: c.X[a][i] = (2 * k + 1) * (e / 2); break;
        case 2: c.X[a][i] = k * h; break;
        default: c.X[a][i] = nextafter(k * e, (rng_next(&seed) & 1) ? 0.0 : 10.0); break;
        }
        if (c.X[a][i] < 0) c.X[a][i] = 0;
      }
    for (int a = 0; a < dim; ++a)
      c.X[a][0] = 0.0, c.X[a][1] = 4.0 * e;
    run(dim == 2 ? "cell faces 2-D" : "cell faces 3-D", &c, h);
    cloud_free(&c);
  }
  T_ASSERT(g_total_bonds > 1000000, "the cases hold %lld bonds in all", g_total_bonds);

  /* The count path: max_bytes just enough (the occupancy bound exceeds it) gives the same
   * families; one byte less fails with the count. */
  {
    const int num[3] = {20, 20, 20};
    const double origin[3] = {0.1, 0.2, 0.3};
    cloud c = lattice_with_hole(3, num, 1.0, origin, 0.0);
    const double *const X[3] = {c.X[0], c.X[1], c.X[2]};
    pdk_ctx *ctx = make_ctx(NULL, 2);
    pdk_particles *p = make_store(ctx, 3, c.n, X);
    pdk_families_opts o = pdk_families_opts_default();
    o.horizon = 3.015;
    pdk_families *f = NULL, *g = NULL;
    T_OK(ctx, pdk_families_build(p, &o, &f));
    o.max_bytes = pdk_families_memory_bytes(f);
    T_OK(ctx, pdk_families_build(p, &o, &g));
    same_bits("count path", f, g);
    pdk_families_destroy(&g);
    o.max_bytes -= 1;
    char count[64];
    snprintf(count, sizeof count, "more than %lld directed bonds",
             (long long)pdk_families_num_bonds(f) - 1);
    T_FAILS(ctx, pdk_families_build(p, &o, &g), PDK_ERR_MEMORY, count);
    T_ASSERT(g == NULL, "no families on failure");
    pdk_families_destroy(&f);
    pdk_particles_destroy(&p);
    pdk_ctx_destroy(&ctx);
    cloud_free(&c);
  }
  /* A single particle has an empty family. */
  for (int dim = 2; dim <= 3; ++dim) {
    pdk_ctx *ctx = make_ctx(NULL, 2);
    pdk_particles *p = NULL;
    T_OK(ctx, pdk_particles_create(ctx, dim, 1, &p));
    pdk_particles_X(p, 0)[0] = 3.0;
    pdk_families_opts o = pdk_families_opts_default();
    o.horizon = 1.0;
    pdk_families *f = NULL;
    T_OK(ctx, pdk_families_build(p, &o, &f));
    T_ASSERT(pdk_families_num_particles(f) == 1 && pdk_families_num_bonds(f) == 0, "n = 1");
    T_ASSERT(pdk_families_bond_start(f)[0] == 0 && pdk_families_bond_start(f)[1] == 0, "n = 1");
    pdk_families_destroy(&f);
    pdk_families_destroy(&f); /* NULL accepted */
    pdk_particles_destroy(&p);
    pdk_ctx_destroy(&ctx);
  }
  return 0;
}
