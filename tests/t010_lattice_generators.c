/* Lattice generators: counts, exact coordinates, volumes, node-type grids, jitter, thread
 * independence, hexagonal neighbour distance.
 * labels: unit threads */
#include <stdint.h>

#include "test_util.h"

static pdk_particles *make(pdk_ctx *ctx, const pdk_lattice_opts *o) {
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, o, &p));
  return p;
}

static double volume_sum(pdk_particles *p) {
  const double *v = pdk_particles_volume(p);
  double s = 0;
  for (pdk_index i = 0; i < pdk_particles_count(p); ++i)
    s += v[i];
  return s;
}

/* Bitwise equality of X (all axes), volume and id of two stores. */
static int same_bits(pdk_particles *a, pdk_particles *b) {
  pdk_index n = pdk_particles_count(a);
  if (n != pdk_particles_count(b) || pdk_particles_dim(a) != pdk_particles_dim(b)) return 0;
  for (int d = 0; d < pdk_particles_dim(a); ++d)
    if (memcmp(pdk_particles_X(a, d), pdk_particles_X(b, d), (size_t)n * sizeof(double))) return 0;
  if (memcmp(pdk_particles_volume(a), pdk_particles_volume(b), (size_t)n * sizeof(double)))
    return 0;
  if (memcmp(pdk_particles_id(a), pdk_particles_id(b), (size_t)n * sizeof(int64_t))) return 0;
  return 1;
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);

  /* Defaults. */
  pdk_lattice_opts d = pdk_lattice_opts_default();
  T_ASSERT(d.type == PDK_LATTICE_SQUARE && d.spacing == 1.0 && d.jitter == 0.0 && d.seed == 0 &&
               d.thickness == 1.0 && d.node_type == 0,
           "defaults");
  for (int a = 0; a < 3; ++a)
    T_ASSERT(d.lo[a] == 0.0 && d.hi[a] == 1.0, "default box axis %d", a);
  {
    pdk_particles *p = make(ctx, NULL); /* NULL opts: one point at (0.5, 0.5) */
    T_ASSERT(pdk_particles_count(p) == 1 && pdk_particles_dim(p) == 2, "default lattice");
    T_ASSERT(pdk_particles_X(p, 0)[0] == 0.5 && pdk_particles_X(p, 1)[0] == 0.5, "default point");
    pdk_particles_destroy(&p);
  }

  /* Square: box [-1, 2] x [0.5, 1.5], spacing 0.1 -> 30 x 10 points at lo + (i + 1/2) * 0.1,
   * exactly as that expression evaluates; x fastest; id = index. */
  {
    pdk_lattice_opts o = pdk_lattice_opts_default();
    o.lo[0] = -1, o.hi[0] = 2, o.lo[1] = 0.5, o.hi[1] = 1.5, o.spacing = 0.1, o.thickness = 0.25;
    pdk_index nq = 0;
    T_OK(ctx, pdk_lattice_count(ctx, &o, &nq));
    pdk_particles *p = make(ctx, &o);
    T_ASSERT(pdk_particles_count(p) == 300 && nq == 300,
             "square count %d (count() %d), expected 300", (int)pdk_particles_count(p), (int)nq);
    const double *x = pdk_particles_X(p, 0), *y = pdk_particles_X(p, 1);
    const int64_t *id = pdk_particles_id(p);
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 30; ++i) {
        int k = i + 30 * j;
        T_ASSERT(x[k] == -1 + (i + 0.5) * 0.1 && y[k] == 0.5 + (j + 0.5) * 0.1 && id[k] == k,
                 "square point %d: (%.17g, %.17g)", k, x[k], y[k]);
      }
    /* Volumes: 300 cells of 0.1^2 * 0.25 = box area times thickness, 0.75; the sum of 300
     * rounded terms is exact to ~300 ulp, so rtol 1e-13 is round-off. */
    T_NEAR(volume_sum(p), 3.0 * 1.0 * 0.25, 1e-13, 0, "square volume sum");
    T_ASSERT(pdk_particles_volume(p)[0] == 0.1 * 0.1 * 0.25, "square cell volume");
    pdk_particles_destroy(&p);
  }

  /* A box that is not a whole number of spacings: [0, 1.07) x [0, 0.26) with spacing 0.1 ->
   * 11 x 3 points (the last at 1.05 and 0.25); checked against a brute-force count too. */
  {
    pdk_lattice_opts o = pdk_lattice_opts_default();
    o.hi[0] = 1.07, o.hi[1] = 0.26, o.spacing = 0.1;
    pdk_particles *p = make(ctx, &o);
    int nx = 0, ny = 0;
    while (0 + (nx + 0.5) * 0.1 < 1.07)
      ++nx;
    while (0 + (ny + 0.5) * 0.1 < 0.26)
      ++ny;
    T_ASSERT(nx == 11 && ny == 3, "brute-force counts %d %d", nx, ny);
    T_ASSERT(pdk_particles_count(p) == nx * ny, "partial-box count %d, expected %d",
             (int)pdk_particles_count(p), nx * ny);
    pdk_particles_destroy(&p);
  }

  /* Half-open box: a point exactly on hi is excluded. [0, 2) with spacing 1 -> 0.5, 1.5; box
   * [0, 1.5) -> 0.5 only. */
  {
    pdk_lattice_opts o = pdk_lattice_opts_default();
    o.hi[0] = 1.5, o.hi[1] = 1;
    pdk_particles *p = make(ctx, &o);
    T_ASSERT(pdk_particles_count(p) == 1, "point on hi excluded, got %d",
             (int)pdk_particles_count(p));
    pdk_particles_destroy(&p);
  }

  /* Cubic: [0, 1] x [0, 2] x [-1, 0.5], spacing 0.25 -> 4 x 8 x 6 = 192; volume sum = 3. */
  {
    pdk_lattice_opts o = pdk_lattice_opts_default();
    o.type = PDK_LATTICE_CUBIC;
    o.hi[1] = 2, o.lo[2] = -1, o.hi[2] = 0.5, o.spacing = 0.25;
    pdk_particles *p = make(ctx, &o);
    T_ASSERT(pdk_particles_count(p) == 192 && pdk_particles_dim(p) == 3, "cubic count %d",
             (int)pdk_particles_count(p));
    const double *x = pdk_particles_X(p, 0), *y = pdk_particles_X(p, 1), *z = pdk_particles_X(p, 2);
    for (int k = 0; k < 6; ++k)
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 4; ++i) {
          int q = i + 4 * (j + 8 * k);
          T_ASSERT(x[q] == (i + 0.5) * 0.25 && y[q] == (j + 0.5) * 0.25 &&
                       z[q] == -1 + (k + 0.5) * 0.25,
                   "cubic point %d", q);
        }
    /* spacing 0.25 is a power of two: every term and partial sum is exact. */
    T_ASSERT(volume_sum(p) == 3.0, "cubic volume sum %.17g", volume_sum(p));
    pdk_particles_destroy(&p);
  }

  /* Hexagonal: width 10 spacings, 8 rows of pitch h = sqrt(3)/2 (box height 8h + h/4 so the
   * row count does not hinge on round-off). 10 points per row, 80 in all; volume sum =
   * 80 * sqrt(3)/2 = box width * 8 h. Nearest-neighbour distance = spacing; interior points have
   * exactly 6 neighbours at that distance. */
  {
    const double s = 0.5, h = s * (0.5 * sqrt(3.0));
    pdk_lattice_opts o = pdk_lattice_opts_default();
    o.type = PDK_LATTICE_HEX;
    o.lo[0] = 1, o.hi[0] = 1 + 10 * s, o.lo[1] = -2, o.hi[1] = -2 + 8.25 * h, o.spacing = s;
    o.thickness = 2;
    pdk_particles *p = make(ctx, &o);
    pdk_index n = pdk_particles_count(p);
    T_ASSERT(n == 80, "hex count %d, expected 80", (int)n);
    const double *x = pdk_particles_X(p, 0), *y = pdk_particles_X(p, 1);
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 10; ++i) {
        int q = i + 10 * j;
        T_ASSERT(x[q] == 1 + (i + (j % 2 ? 0.75 : 0.25)) * s && y[q] == -2 + (j + 0.5) * h,
                 "hex point %d (%.17g, %.17g)", q, x[q], y[q]);
      }
    /* 80 equal terms: rtol 1e-13 is round-off. */
    T_NEAR(volume_sum(p), (10 * s) * (8 * h) * 2, 1e-13, 0, "hex volume sum");
    /* Distances: rtol 1e-12 covers the rounding of coordinates of size ~5 with s = 0.5. */
    for (pdk_index i = 0; i < n; ++i) {
      double dmin = INFINITY;
      int near = 0;
      for (pdk_index j = 0; j < n; ++j) {
        if (i == j) continue;
        double r = hypot(x[i] - x[j], y[i] - y[j]);
        dmin = fmin(dmin, r);
        near += fabs(r - s) <= 1e-12 * s;
      }
      T_NEAR(dmin, s, 1e-12, 0, "hex nearest neighbour of %d", (int)i);
      int row = (int)i / 10, col = (int)i % 10;
      if (row > 0 && row < 7 && col > 0 && col < 9)
        T_ASSERT(near == 6, "interior hex point %d has %d neighbours at the spacing", (int)i, near);
    }
    /* Width 10.5 spacings: even rows hold 11 points (i + 1/4 < 10.5), odd rows 10 (i + 3/4 < 10.5).
     */
    o.hi[0] = 1 + 10.5 * s;
    pdk_particles_destroy(&p);
    p = make(ctx, &o);
    T_ASSERT(pdk_particles_count(p) == 4 * 11 + 4 * 10, "hex uneven rows: %d",
             (int)pdk_particles_count(p));
    x = pdk_particles_X(p, 0), y = pdk_particles_X(p, 1);
    T_ASSERT(x[11] == 1 + 0.75 * s && y[11] == -2 + 1.5 * h, "first point of row 1");
    T_ASSERT(x[21] == 1 + 0.25 * s && y[21] == -2 + 2.5 * h, "first point of row 2");
    pdk_particles_destroy(&p);
  }

  /* Node-type grid: [0, 1]^2, spacing 0.1 -> 11 x 11 nodes at i * 0.1, both faces included. */
  {
    pdk_lattice_opts o = pdk_lattice_opts_default();
    o.spacing = 0.1, o.node_type = 1;
    pdk_particles *p = make(ctx, &o);
    T_ASSERT(pdk_particles_count(p) == 121, "node grid count %d", (int)pdk_particles_count(p));
    const double *x = pdk_particles_X(p, 0), *y = pdk_particles_X(p, 1);
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (int j = 0; j <= 10; ++j)
      for (int i = 0; i <= 10; ++i) {
        int q = i + 11 * j;
        T_ASSERT(x[q] == i * 0.1 && y[q] == j * 0.1, "node %d", q);
        xmin = fmin(xmin, x[q]), xmax = fmax(xmax, x[q]);
        ymin = fmin(ymin, y[q]), ymax = fmax(ymax, y[q]);
      }
    /* lo face exact; hi face within one rounding of 10 * 0.1 (rtol 1e-15). */
    T_ASSERT(xmin == 0 && ymin == 0, "low faces hold nodes");
    T_NEAR(xmax, 1.0, 1e-15, 0, "high x face holds nodes");
    T_NEAR(ymax, 1.0, 1e-15, 0, "high y face holds nodes");
    pdk_particles_destroy(&p);
    /* 3-D node grid: [0, 2] x [0, 1] x [0, 1] with spacing 0.5 -> 5 x 3 x 3. */
    o.type = PDK_LATTICE_CUBIC, o.hi[0] = 2, o.spacing = 0.5;
    p = make(ctx, &o);
    T_ASSERT(pdk_particles_count(p) == 45, "3-D node grid count %d", (int)pdk_particles_count(p));
    T_ASSERT(pdk_particles_X(p, 0)[44] == 2 && pdk_particles_X(p, 2)[44] == 1, "far corner node");
    pdk_particles_destroy(&p);
  }

  /* Jitter: bounded by jitter * spacing, reproducible for a seed, different for another, and the
   * same with 1 and 2 threads (bitwise). */
  {
    pdk_lattice_opts o = pdk_lattice_opts_default();
    o.hi[0] = 3, o.hi[1] = 2, o.spacing = 0.05, o.jitter = 0.3, o.seed = 42;
    pdk_particles *a = make(ctx, &o), *b = make(ctx, &o);
    pdk_index n = pdk_particles_count(a);
    T_ASSERT(n == 60 * 40, "jittered count unchanged, %d", (int)n);
    T_ASSERT(same_bits(a, b), "same seed, same lattice");
    double max_dev = 0;
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 60; ++i) {
        int q = i + 60 * j;
        double dx = pdk_particles_X(a, 0)[q] - (i + 0.5) * 0.05;
        double dy = pdk_particles_X(a, 1)[q] - (j + 0.5) * 0.05;
        /* bound 0.3 * 0.05 plus one rounding of the coordinate (atol 1e-15) */
        T_ASSERT(fabs(dx) <= 0.3 * 0.05 + 1e-15 && fabs(dy) <= 0.3 * 0.05 + 1e-15,
                 "jitter of point %d out of bounds: %g %g", q, dx, dy);
        max_dev = fmax(max_dev, fmax(fabs(dx), fabs(dy)));
      }
    /* 4800 uniform draws on [-0.015, 0.015): the largest falls within 1% of the bound with
     * probability 1 - 0.99^4800, i.e. always. */
    T_ASSERT(max_dev > 0.99 * 0.3 * 0.05, "jitter uses its range, max %g", max_dev);
    /* Every lattice index and axis enters the hash: neighbours along x and y, and the two axes of
     * one point, draw different jitter (equal draws have probability ~2^-53 each). */
    int same = 0;
    for (int j = 1; j < 40; ++j)
      for (int i = 1; i < 60; ++i) {
        int q = i + 60 * j;
        double dx = pdk_particles_X(a, 0)[q] - (i + 0.5) * 0.05;
        double dy = pdk_particles_X(a, 1)[q] - (j + 0.5) * 0.05;
        same += dx == pdk_particles_X(a, 0)[q - 1] - (i - 0.5) * 0.05;
        same += dx == pdk_particles_X(a, 0)[q - 60] - (i + 0.5) * 0.05;
        same += dx == dy;
      }
    T_ASSERT(same == 0, "%d jitter draws repeat between sites or axes", same);
    pdk_particles_destroy(&b);
    o.seed = 43;
    b = make(ctx, &o);
    int differ = 0;
    for (pdk_index i = 0; i < n; ++i)
      differ += pdk_particles_X(a, 0)[i] != pdk_particles_X(b, 0)[i];
    T_ASSERT(differ > n * 9 / 10, "another seed moves the points differently (%d of %d differ)",
             differ, (int)n);
    pdk_particles_destroy(&b);

    /* Thread independence, for each lattice type, with jitter. */
    o.seed = 42;
    for (int type = 0; type < 3; ++type) {
      o.type = (pdk_lattice_type)type;
      o.spacing = type == PDK_LATTICE_CUBIC ? 0.1 : 0.02;
      T_OK(ctx, pdk_ctx_set_num_threads(ctx, 1));
      pdk_particles *one = make(ctx, &o);
      T_OK(ctx, pdk_ctx_set_num_threads(ctx, 2));
      pdk_particles *two = make(ctx, &o);
      T_ASSERT(pdk_particles_count(one) > 1000, "big enough to split, %d",
               (int)pdk_particles_count(one));
      T_ASSERT(same_bits(one, two), "lattice type %d differs between 1 and 2 threads", type);
      pdk_particles_destroy(&one);
      pdk_particles_destroy(&two);
    }
    T_OK(ctx, pdk_ctx_set_num_threads(ctx, 1));

    /* A point's jitter depends on its lattice indices, not on the box: growing the box in x
     * keeps the jitter of the points both boxes share. */
    o.type = PDK_LATTICE_SQUARE, o.spacing = 0.05, o.hi[0] = 3, o.hi[1] = 2;
    pdk_particles *small = make(ctx, &o);
    o.hi[0] = 4;
    pdk_particles *big = make(ctx, &o);
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 60; ++i)
        T_ASSERT(pdk_particles_X(small, 0)[i + 60 * j] == pdk_particles_X(big, 0)[i + 80 * j] &&
                     pdk_particles_X(small, 1)[i + 60 * j] == pdk_particles_X(big, 1)[i + 80 * j],
                 "jitter of site (%d, %d) depends on the box", i, j);
    pdk_particles_destroy(&small);
    pdk_particles_destroy(&big);
    pdk_particles_destroy(&a);
  }

  pdk_ctx_destroy(&ctx);
  return 0;
}
