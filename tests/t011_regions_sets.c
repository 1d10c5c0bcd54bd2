/* Regions and named sets: contains() for each kind with boundary points and invert; holes and sets
 * against brute force; sets through cuts and Morton reordering; set_indices ascending.
 * labels: unit */
#include <stdint.h>

#include "test_util.h"

static int in2(const pdk_region *r, double x, double y) {
  double p[3] = {x, y, 0};
  return pdk_region_contains(r, 2, p);
}
static int in3(const pdk_region *r, double x, double y, double z) {
  double p[3] = {x, y, z};
  return pdk_region_contains(r, 3, p);
}

static pdk_particles *square_lattice(pdk_ctx *ctx, double spacing) {
  pdk_lattice_opts o = pdk_lattice_opts_default(); /* box [0, 1)^2 */
  o.spacing = spacing;
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, &o, &p));
  return p;
}

/* Independent L-shape test: union of two rectangles, [0.2, 0.8] x [0.2, 0.4] and
 * [0.2, 0.4] x [0.2, 0.8]. */
static int in_L(double x, double y) {
  return (x >= 0.2 && x <= 0.8 && y >= 0.2 && y <= 0.4) ||
         (x >= 0.2 && x <= 0.4 && y >= 0.2 && y <= 0.8);
}

/* Checks that set `name` holds exactly the particles with want[id] != 0 and that set_indices lists
 * them ascending. */
static void check_set(pdk_ctx *ctx, pdk_particles *p, const char *name, const uint8_t *want_by_id) {
  const pdk_index n = pdk_particles_count(p);
  char field[80];
  snprintf(field, sizeof field, "set:%s", name);
  const uint8_t *flag = pdk_particles_field_data(p, field, 0);
  T_ASSERT(flag != NULL, "field %s exists", field);
  const int64_t *id = pdk_particles_id(p);
  pdk_index expected = 0;
  for (pdk_index i = 0; i < n; ++i) {
    T_ASSERT(flag[i] == want_by_id[id[i]], "set %s: particle %d (id %lld) flag %d, expected %d",
             name, (int)i, (long long)id[i], flag[i], want_by_id[id[i]]);
    expected += flag[i];
  }
  pdk_index *idx = NULL, count = -1;
  T_OK(ctx, pdk_particles_set_indices(p, name, &idx, &count));
  T_ASSERT(count == expected, "set %s: set_indices count %d, expected %d", name, (int)count,
           (int)expected);
  for (pdk_index k = 0; k < count; ++k) {
    T_ASSERT(idx[k] >= 0 && idx[k] < n && flag[idx[k]], "set %s: index %d not a member", name,
             (int)idx[k]);
    T_ASSERT(k == 0 || idx[k] > idx[k - 1], "set %s: indices not ascending at %d", name, (int)k);
  }
  free(idx);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);

  /* ---- contains(), 2-D and 3-D, boundaries closed, invert = complement ---- */
  {
    double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 3};
    pdk_region b = pdk_region_box(lo, hi);
    T_OK(ctx, pdk_region_check(ctx, 2, &b));
    T_ASSERT(in2(&b, 0.5, 0.5) && in2(&b, 0, 0) && in2(&b, 1, 2) && in2(&b, 1, 0.3), "box closed");
    T_ASSERT(!in2(&b, 1 + 1e-12, 1) && !in2(&b, 0.5, -1e-300) && !in2(&b, 0.5, 2.0000001),
             "box outside");
    T_ASSERT(in3(&b, 1, 2, 3) && in3(&b, 0, 0, 0) && !in3(&b, 0.5, 0.5, 3.0000001) &&
                 !in3(&b, 0.5, 0.5, -1),
             "box 3-D uses z");
    T_ASSERT(in2(&b, 0.5, 0.5) && in3(&b, 0.5, 0.5, 0.5), "2-D ignores z");
    /* A degenerate box (lo == hi on an axis) is valid and holds its face. */
    double hi_flat[3] = {1, 0, 3};
    pdk_region flat = pdk_region_box(lo, hi_flat);
    T_OK(ctx, pdk_region_check(ctx, 2, &flat));
    T_ASSERT(in2(&flat, 0.5, 0) && !in2(&flat, 0.5, 1e-15), "flat box holds its face only");
    b.invert = 1;
    T_ASSERT(!in2(&b, 0.5, 0.5) && !in2(&b, 0, 0) && !in2(&b, 1, 2) && in2(&b, 1 + 1e-12, 1) &&
                 in2(&b, -5, 7),
             "inverted box: open complement");
  }
  {
    double c2[3] = {1, 2, 0};
    pdk_region d = pdk_region_ball(c2, 0.5);
    T_OK(ctx, pdk_region_check(ctx, 2, &d));
    T_ASSERT(in2(&d, 1, 2) && in2(&d, 1.5, 2) && in2(&d, 1, 1.5) && in2(&d, 0.5, 2), "disk closed");
    T_ASSERT(!in2(&d, 1.5, 2.0001) && !in2(&d, 1.36, 2.36) && in2(&d, 1.35, 2.35),
             "disk outside/inside");
    double c3[3] = {0, 0, 0};
    pdk_region ball = pdk_region_ball(c3, 2);
    T_ASSERT(in3(&ball, 0, 0, 2) && in3(&ball, 0, -2, 0) && !in3(&ball, 0, 0, 2.000001) &&
                 !in3(&ball, 1.2, 1.2, 1.2),
             "ball 3-D");
    d.invert = 1;
    T_ASSERT(!in2(&d, 1, 2) && !in2(&d, 1.5, 2) && in2(&d, 1.5, 2.0001), "inverted disk");
  }
  {
    double p[3] = {0, 1, 0}, nrm[3] = {0, 1, 0};
    pdk_region h = pdk_region_halfspace(p, nrm);
    T_OK(ctx, pdk_region_check(ctx, 2, &h));
    T_ASSERT(in2(&h, 5, 1) && in2(&h, -7, 0) && !in2(&h, 0, 1.0000001), "half-plane y <= 1");
    double p2[3] = {1, 1, 0}, n2[3] = {1, 1, 0};
    pdk_region h2 = pdk_region_halfspace(p2, n2); /* x + y <= 2; normal need not be unit */
    T_ASSERT(in2(&h2, 2, 0) && in2(&h2, 0.5, 0.5) && !in2(&h2, 1.5, 1), "oblique half-plane");
    double p3[3] = {0, 0, 1}, n3[3] = {0, 0, -2};
    pdk_region h3 = pdk_region_halfspace(p3, n3); /* z >= 1 */
    T_OK(ctx, pdk_region_check(ctx, 3, &h3));
    T_ASSERT(in3(&h3, 9, 9, 1) && in3(&h3, 0, 0, 5) && !in3(&h3, 0, 0, 0.999), "half-space z >= 1");
    h.invert = 1;
    T_ASSERT(!in2(&h, 5, 1) && in2(&h, 0, 1.0000001), "inverted half-plane y > 1");
  }
  {
    /* L shape, counter-clockwise and clockwise; the notch is outside. */
    const double ccw[] = {0.2, 0.2, 0.8, 0.2, 0.8, 0.4, 0.4, 0.4, 0.4, 0.8, 0.2, 0.8};
    double cw[12];
    for (int k = 0; k < 6; ++k)
      cw[2 * k] = ccw[2 * (5 - k)], cw[2 * k + 1] = ccw[2 * (5 - k) + 1];
    for (int o = 0; o < 2; ++o) {
      pdk_region L = pdk_region_polygon(o ? cw : ccw, 6);
      T_OK(ctx, pdk_region_check(ctx, 2, &L));
      T_ASSERT(in2(&L, 0.3, 0.7) && in2(&L, 0.7, 0.3) && in2(&L, 0.3, 0.3), "L inside (%s)",
               o ? "cw" : "ccw");
      T_ASSERT(!in2(&L, 0.7, 0.7) && !in2(&L, 0.5, 0.5) && !in2(&L, 0.9, 0.3) &&
                   !in2(&L, 0.1, 0.5) && !in2(&L, 0.3, 0.9) && !in2(&L, 0.3, 0.1),
               "L outside (%s)", o ? "cw" : "ccw");
      /* Points level with a vertex (the ray passes through it) are still classified right. */
      T_ASSERT(in2(&L, 0.3, 0.4) && !in2(&L, 0.9, 0.4) && !in2(&L, 0.1, 0.4) && !in2(&L, 0.1, 0.8),
               "rays through vertices (%s)", o ? "cw" : "ccw");
      L.invert = 1;
      T_ASSERT(!in2(&L, 0.3, 0.7) && in2(&L, 0.7, 0.7), "inverted L (%s)", o ? "cw" : "ccw");
    }
  }

  /* ---- a disk hole cut from a square lattice removes exactly the brute-force set ---- */
  {
    pdk_particles *p = square_lattice(ctx, 0.02); /* 50 x 50 */
    const pdk_index n0 = pdk_particles_count(p);
    T_ASSERT(n0 == 2500, "lattice size %d", (int)n0);
    uint8_t *outside = calloc((size_t)n0, 1);
    pdk_index expect_removed = 0;
    const double cx = 0.5, cy = 0.45, rad = 0.2;
    for (pdk_index i = 0; i < n0; ++i) {
      double x = pdk_particles_X(p, 0)[i], y = pdk_particles_X(p, 1)[i];
      int hole = (x - cx) * (x - cx) + (y - cy) * (y - cy) <= rad * rad;
      outside[i] = (uint8_t)!hole; /* id == index before the cut */
      expect_removed += hole;
    }
    /* A set defined before the cut follows the surviving particles. */
    double top_lo[3] = {0, 0.9, 0}, top_hi[3] = {1, 1, 0};
    pdk_region top = pdk_region_box(top_lo, top_hi);
    pdk_index top_count = 0;
    T_OK(ctx, pdk_particles_set_define(p, "top", &top, &top_count));
    T_ASSERT(top_count == 250, "top rows: %d members", (int)top_count);
    uint8_t *top_by_id = calloc((size_t)n0, 1);
    for (pdk_index i = 0; i < n0; ++i)
      top_by_id[i] = pdk_particles_X(p, 1)[i] >= 0.9;

    double c[3] = {cx, cy, 0};
    pdk_region hole = pdk_region_ball(c, rad);
    pdk_index removed = -1;
    T_OK(ctx, pdk_particles_cut(p, &hole, &removed));
    T_ASSERT(removed == expect_removed && removed > 300, "removed %d, brute force %d", (int)removed,
             (int)expect_removed);
    T_ASSERT(pdk_particles_count(p) == n0 - removed, "count after cut");
    const int64_t *id = pdk_particles_id(p);
    for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
      T_ASSERT(outside[id[i]], "particle id %lld in the hole survived", (long long)id[i]);
      T_ASSERT(i == 0 || id[i] > id[i - 1], "cut keeps order");
      T_ASSERT(pdk_particles_X(p, 0)[i] == (id[i] % 50 + 0.5) * 0.02 &&
                   pdk_particles_X(p, 1)[i] == (id[i] / 50 + 0.5) * 0.02,
               "X carried with id %lld", (long long)id[i]);
    }
    check_set(ctx, p, "top", top_by_id);
    /* Cutting again removes nothing and is not an error. */
    T_OK(ctx, pdk_particles_cut(p, &hole, &removed));
    T_ASSERT(removed == 0, "second cut removed %d", (int)removed);
    T_OK(ctx, pdk_particles_cut(p, &hole, NULL));

    /* ---- sets survive Morton reordering (compared through "id") ---- */
    const double Lv[] = {0.2, 0.2, 0.8, 0.2, 0.8, 0.4, 0.4, 0.4, 0.4, 0.8, 0.2, 0.8};
    pdk_region L = pdk_region_polygon(Lv, 6);
    uint8_t *L_by_id = calloc((size_t)n0, 1);
    pdk_index L_expect = 0;
    for (pdk_index i = 0; i < pdk_particles_count(p); ++i) {
      L_by_id[id[i]] = (uint8_t)in_L(pdk_particles_X(p, 0)[i], pdk_particles_X(p, 1)[i]);
      L_expect += L_by_id[id[i]];
    }
    pdk_index L_count = 0;
    T_OK(ctx, pdk_particles_set_define(p, "L", &L, &L_count));
    T_ASSERT(L_count == L_expect && L_count > 100, "L set %d members, brute force %d", (int)L_count,
             (int)L_expect);
    check_set(ctx, p, "L", L_by_id);
    T_OK(ctx, pdk_particles_reorder_morton(p, 0.1, NULL));
    id = pdk_particles_id(p);
    int moved = 0;
    for (pdk_index i = 1; i < pdk_particles_count(p); ++i)
      moved += id[i] < id[i - 1];
    T_ASSERT(moved > 0, "Morton reordering changed the order");
    check_set(ctx, p, "L", L_by_id);
    check_set(ctx, p, "top", top_by_id);

    /* Redefining a set replaces its members; an inverted region selects the complement. */
    L.invert = 1;
    T_OK(ctx, pdk_particles_set_define(p, "L", &L, &L_count));
    T_ASSERT(L_count == pdk_particles_count(p) - L_expect, "inverted L: %d members", (int)L_count);
    for (pdk_index i = 0; i < n0; ++i)
      L_by_id[i] = outside[i] && !L_by_id[i];
    check_set(ctx, p, "L", L_by_id);
    free(outside);
    free(top_by_id);
    free(L_by_id);
    pdk_particles_destroy(&p);
  }

  /* ---- 3-D: ball and half-space sets against brute force ---- */
  {
    pdk_lattice_opts o = pdk_lattice_opts_default();
    o.type = PDK_LATTICE_CUBIC, o.spacing = 0.1, o.jitter = 0.2, o.seed = 7;
    pdk_particles *p = NULL;
    T_OK(ctx, pdk_lattice_create(ctx, &o, &p));
    const pdk_index n = pdk_particles_count(p);
    double c[3] = {0.3, 0.6, 0.5}, pt[3] = {0, 0, 0.35}, nrm[3] = {0.2, 0, 1};
    pdk_region ball = pdk_region_ball(c, 0.33), half = pdk_region_halfspace(pt, nrm);
    uint8_t *want_ball = calloc((size_t)n, 1), *want_half = calloc((size_t)n, 1);
    const double *x = pdk_particles_X(p, 0), *y = pdk_particles_X(p, 1), *z = pdk_particles_X(p, 2);
    for (pdk_index i = 0; i < n; ++i) {
      double dx = x[i] - c[0], dy = y[i] - c[1], dz = z[i] - c[2];
      want_ball[i] = dx * dx + dy * dy + dz * dz <= 0.33 * 0.33;
      want_half[i] = x[i] * 0.2 + (z[i] - 0.35) * 1 <= 0;
    }
    T_OK(ctx, pdk_particles_set_define(p, "ball", &ball, NULL));
    T_OK(ctx, pdk_particles_set_define(p, "bottom", &half, NULL));
    check_set(ctx, p, "ball", want_ball);
    check_set(ctx, p, "bottom", want_half);
    free(want_ball);
    free(want_half);
    pdk_particles_destroy(&p);
  }

  /* Region descriptions name the kind and the numbers. */
  {
    char buf[256];
    double lo[3] = {0, 0.9, 0}, hi[3] = {1, 1, 0};
    pdk_region b = pdk_region_box(lo, hi);
    pdk_region_describe(&b, 2, buf, sizeof buf);
    T_ASSERT(!strcmp(buf, "the box [0, 0.9]..[1, 1]"), "box description '%s'", buf);
    b.invert = 1;
    pdk_region_describe(&b, 2, buf, sizeof buf);
    T_ASSERT(!strcmp(buf, "the complement of the box [0, 0.9]..[1, 1]"), "inverted '%s'", buf);
    pdk_region_describe(&b, 2, buf, 10); /* truncation is safe */
    T_ASSERT(strlen(buf) == 9, "truncated '%s'", buf);
  }

  pdk_ctx_destroy(&ctx);
  return 0;
}
