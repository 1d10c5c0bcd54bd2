/* Geometry bad input: every refused lattice option, region parameter and set/cut request gives its
 * documented code and a message naming the offending value; failures leave no store and change
 * no store.
 * labels: unit */
#include <stdint.h>

#include "test_util.h"

/* pdk_lattice_create must fail with PDK_ERR_ARG, a message containing `needle`, and *out NULL;
 * pdk_lattice_count must refuse the same options with the same message. */
static void lattice_fails(pdk_ctx *ctx, const pdk_lattice_opts *o, const char *needle) {
  pdk_particles *p = (pdk_particles *)&p; /* not NULL: create must reset it */
  T_FAILS(ctx, pdk_lattice_create(ctx, o, &p), PDK_ERR_ARG, needle);
  T_ASSERT(p == NULL, "failed create leaves *out NULL (%s)", needle);
  pdk_index n = 5;
  T_FAILS(ctx, pdk_lattice_count(ctx, o, &n), PDK_ERR_ARG, needle);
  T_ASSERT(n == 0, "failed count gives 0 (%s)", needle);
}

static void region_fails(pdk_ctx *ctx, int dim, const pdk_region *r, const char *needle) {
  T_FAILS(ctx, pdk_region_check(ctx, dim, r), PDK_ERR_ARG, needle);
}

int main(void) {
  pdk_ctx *ctx = t_ctx(1);
  const pdk_lattice_opts base = pdk_lattice_opts_default();
  pdk_lattice_opts o;

  /* ---- lattice options ---- */
  o = base, o.spacing = 0;
  lattice_fails(ctx, &o, "spacing must be a finite number > 0, got 0");
  o = base, o.spacing = -0.5;
  lattice_fails(ctx, &o, "got -0.5");
  o = base, o.spacing = NAN;
  lattice_fails(ctx, &o, "spacing must be a finite number > 0, got nan");
  o = base, o.spacing = INFINITY;
  lattice_fails(ctx, &o, "got inf");
  o = base, o.hi[0] = -1;
  lattice_fails(ctx, &o, "inverted on axis x: lo = 0, hi = -1");
  o = base, o.lo[1] = 1;
  lattice_fails(ctx, &o, "empty on axis y: lo = 1, hi = 1");
  o = base, o.type = PDK_LATTICE_CUBIC, o.lo[2] = 2;
  lattice_fails(ctx, &o, "inverted on axis z: lo = 2, hi = 1");
  o = base, o.lo[2] = 2; /* 2-D ignores z */
  {
    pdk_particles *p = NULL;
    T_OK(ctx, pdk_lattice_create(ctx, &o, &p));
    pdk_particles_destroy(&p);
  }
  o = base, o.lo[0] = -INFINITY;
  lattice_fails(ctx, &o, "must be finite, got lo = -inf");
  o = base, o.hi[1] = NAN;
  lattice_fails(ctx, &o, "hi = nan");
  o = base, o.jitter = 0.5;
  lattice_fails(ctx, &o, "jitter must be in [0, 0.5) (a fraction of the spacing), got 0.5");
  o = base, o.jitter = -0.1;
  lattice_fails(ctx, &o, "got -0.1");
  o = base, o.jitter = NAN;
  lattice_fails(ctx, &o, "jitter must be in [0, 0.5) (a fraction of the spacing), got nan");
  o = base, o.thickness = 0;
  lattice_fails(ctx, &o, "thickness must be a finite number > 0, got 0");
  o = base, o.type = PDK_LATTICE_HEX, o.thickness = -2;
  lattice_fails(ctx, &o, "thickness must be a finite number > 0, got -2");
  o = base, o.type = PDK_LATTICE_CUBIC, o.thickness = 0; /* 3-D ignores thickness */
  {
    pdk_particles *p = NULL;
    T_OK(ctx, pdk_lattice_create(ctx, &o, &p));
    pdk_particles_destroy(&p);
  }
  o = base, o.type = (pdk_lattice_type)7;
  lattice_fails(ctx, &o, "unknown lattice type 7");
  o = base, o.node_type = 2;
  lattice_fails(ctx, &o, "node_type must be 0");
  o = base, o.node_type = 1, o.type = PDK_LATTICE_HEX;
  lattice_fails(ctx, &o, "not for the hexagonal lattice");
  o = base, o.node_type = 1, o.spacing = 0.3;
  lattice_fails(ctx, &o, "axis x is 3.33333 spacings long");
  /* Too many points: per axis (1e12 spacings) and in total (1e6 x 1e6). */
  o = base, o.spacing = 1e-12;
  lattice_fails(ctx, &o, "axis x spans 1e+12 spacings");
  o = base, o.spacing = 1e-6;
  lattice_fails(ctx, &o, "square lattice would have 1000000000000 points");
  o = base, o.type = PDK_LATTICE_CUBIC,
  o.spacing = 1e-3; /* 1e9 points: under the 2^31 - 1 - PDK_PAD cap */
  {
    pdk_index n = 0;
    T_OK(ctx, pdk_lattice_count(ctx, &o, &n)); /* counting 1e9 points allocates nothing */
    T_ASSERT(n == 1000000000, "count of a 1000^3 lattice: %d", (int)n);
  }
  o.spacing = 0.5e-3; /* 8e9 */
  lattice_fails(ctx, &o, "cubic lattice would have 8000000000 points");
  /* A box too small for one point (the first lies at lo + spacing/2). */
  o = base, o.hi[0] = 0.4;
  lattice_fails(ctx, &o,
                "square lattice has no point: the box [0, 0]..[0.4, 1] is too small for spacing 1");
  o = base, o.type = PDK_LATTICE_CUBIC, o.hi[2] = 0.5;
  lattice_fails(ctx, &o, "cubic lattice has no point");
  o = base, o.type = PDK_LATTICE_HEX, o.hi[0] = 0.2, o.hi[1] = 5;
  lattice_fails(ctx, &o, "hexagonal lattice has no point");

  /* ---- region parameters ---- */
  const double zero[3] = {0, 0, 0}, one[3] = {1, 1, 1};
  pdk_region r;
  r = pdk_region_ball(zero, 0);
  region_fails(ctx, 2, &r, "radius must be a finite number > 0, got 0");
  r = pdk_region_ball(zero, -1);
  region_fails(ctx, 3, &r, "got -1");
  r = pdk_region_ball(zero, NAN);
  region_fails(ctx, 2, &r, "radius must be a finite number > 0, got nan");
  {
    double c[3] = {0, INFINITY, 0};
    r = pdk_region_ball(c, 1);
    region_fails(ctx, 2, &r, "centre must be finite, got inf on axis y");
  }
  {
    double hi[3] = {1, -1, 1};
    r = pdk_region_box(zero, hi);
    region_fails(ctx, 2, &r, "box region is inverted on axis y: lo = 0 > hi = -1");
    double lo3[3] = {0, 0, 2};
    r = pdk_region_box(lo3, one);
    region_fails(ctx, 3, &r, "inverted on axis z");
    T_OK(ctx, pdk_region_check(ctx, 2, &r)); /* 2-D ignores z */
    double hnan[3] = {NAN, 1, 1};
    r = pdk_region_box(zero, hnan);
    region_fails(ctx, 2, &r, "hi = nan");
  }
  r = pdk_region_halfspace(zero, zero);
  region_fails(ctx, 2, &r, "normal is zero");
  {
    double n2[3] = {0, 0, 1}; /* zero in the plane */
    r = pdk_region_halfspace(zero, n2);
    region_fails(ctx, 2, &r, "normal is zero");
    T_OK(ctx, pdk_region_check(ctx, 3, &r));
    double pnan[3] = {0, NAN, 0};
    r = pdk_region_halfspace(pnan, one);
    region_fails(ctx, 2, &r, "point must be finite, got nan on axis y");
    r = pdk_region_halfspace(zero, pnan);
    region_fails(ctx, 2, &r, "normal must be finite, got nan");
  }
  {
    const double tri[] = {0, 0, 1, 0, 0, 1};
    r = pdk_region_polygon(tri, 2);
    region_fails(ctx, 2, &r, "at least 3 vertices, got 2");
    r = pdk_region_polygon(tri, 3);
    T_OK(ctx, pdk_region_check(ctx, 2, &r));
    region_fails(ctx, 3, &r, "polygon regions are 2-D only");
    r = pdk_region_polygon(NULL, 4);
    region_fails(ctx, 2, &r, "no vertex array");
    const double bad[] = {0, 0, 1, NAN, 0, 1};
    r = pdk_region_polygon(bad, 3);
    region_fails(ctx, 2, &r, "vertex 1 must be finite, got (1, nan)");
  }
  r = pdk_region_ball(zero, 1);
  r.kind = (pdk_region_kind)9;
  region_fails(ctx, 2, &r, "unknown region kind 9");
  r = pdk_region_ball(zero, 1);
  region_fails(ctx, 4, &r, "dimension must be 2 or 3, got 4");

  /* ---- cuts and sets ---- */
  pdk_particles *p = NULL;
  o = base, o.spacing = 0.1; /* 10 x 10 points in [0.05, 0.95]^2 */
  T_OK(ctx, pdk_lattice_create(ctx, &o, &p));
  const int nf = pdk_particles_num_fields(p);
  {
    /* A region that selects nothing names the set, the region and the body's extent. */
    double lo[3] = {0, 0.96, 0}, hi[3] = {1, 2, 0};
    r = pdk_region_box(lo, hi);
    pdk_index count = 7;
    T_FAILS(ctx, pdk_particles_set_define(p, "top", &r, &count), PDK_ERR_ARG,
            "set 'top' selects no particle: the box [0, 0.96]..[1, 2] contains none of the 100 "
            "particles; check the region against the body's extent [0.05, 0.05]..[0.95, 0.95]");
    T_ASSERT(count == 0 && !pdk_particles_field_exists(p, "set:top") &&
                 pdk_particles_num_fields(p) == nf,
             "a refused set declares nothing");
    double c[3] = {0.5, 0.5, 0};
    r = pdk_region_ball(c, 10);
    r.invert = 1;
    T_FAILS(ctx, pdk_particles_set_define(p, "outer", &r, NULL), PDK_ERR_ARG,
            "set 'outer' selects no particle: the complement of the disk of centre [0.5, 0.5] and "
            "radius 10");
    /* Bad region and bad names inside set_define. */
    r = pdk_region_ball(c, -3);
    T_FAILS(ctx, pdk_particles_set_define(p, "disk", &r, NULL), PDK_ERR_ARG, "got -3");
    r = pdk_region_ball(c, 0.2);
    T_FAILS(ctx, pdk_particles_set_define(p, "", &r, NULL), PDK_ERR_ARG, "non-empty name");
    T_FAILS(ctx, pdk_particles_set_define(p, NULL, &r, NULL), PDK_ERR_ARG, "non-empty name");
    char longname[100];
    memset(longname, 'a', 99);
    longname[99] = '\0';
    T_FAILS(ctx, pdk_particles_set_define(p, longname, &r, NULL), PDK_ERR_ARG, "too long");
    T_ASSERT(pdk_particles_num_fields(p) == nf, "refused sets declare nothing");
    /* Unknown set, and a field named like a set that is not one. */
    pdk_index *idx = (pdk_index *)&idx;
    T_FAILS(ctx, pdk_particles_set_indices(p, "nowhere", &idx, NULL), PDK_ERR_NOT_FOUND,
            "no set 'nowhere'");
    T_ASSERT(idx == NULL, "failed set_indices gives NULL");
    T_OK(ctx, pdk_particles_field_add(p, "set:bogus", PDK_F64, 1));
    T_FAILS(ctx, pdk_particles_set_indices(p, "bogus", &idx, NULL), PDK_ERR_ARG,
            "field 'set:bogus' is not a set");
    T_FAILS(ctx, pdk_particles_set_define(p, "bogus", &r, NULL), PDK_ERR_ARG, "set:bogus");
    T_OK(ctx, pdk_particles_field_remove(p, "set:bogus"));

    /* A cut that would remove everything is refused and leaves the store whole. */
    double big_lo[3] = {-1, -1, 0}, big_hi[3] = {2, 2, 0};
    r = pdk_region_box(big_lo, big_hi);
    pdk_index removed = 9;
    T_FAILS(ctx, pdk_particles_cut(p, &r, &removed), PDK_ERR_ARG,
            "cut would remove every particle: the box [-1, -1]..[2, 2] contains all 100 particles");
    T_ASSERT(removed == 0 && pdk_particles_count(p) == 100, "refused cut removes nothing");
    r = pdk_region_ball(c, NAN);
    T_FAILS(ctx, pdk_particles_cut(p, &r, &removed), PDK_ERR_ARG,
            "radius must be a finite number > 0, got nan");
    T_ASSERT(pdk_particles_count(p) == 100, "bad-region cut removes nothing");
    /* Hypotenuse x + y = 1.02 passes no lattice point (x + y = 0.1 * (i + j + 1)): 55 inside. */
    const double tri[] = {0, 0, 1.02, 0, 0, 1.02};
    r = pdk_region_polygon(tri, 3);
    r.invert = 1;
    T_OK(ctx, pdk_particles_cut(p, &r, &removed)); /* cuts the complement, keeps the triangle */
    T_ASSERT(removed == 45 && pdk_particles_count(p) == 55, "triangle kept %d",
             (int)pdk_particles_count(p));
  }
  pdk_particles_destroy(&p);

  /* Polygons on a 3-D store are refused by cut and set_define. */
  o = base, o.type = PDK_LATTICE_CUBIC, o.spacing = 0.5;
  T_OK(ctx, pdk_lattice_create(ctx, &o, &p));
  {
    const double tri[] = {0, 0, 1, 0, 0, 1};
    r = pdk_region_polygon(tri, 3);
    T_FAILS(ctx, pdk_particles_cut(p, &r, NULL), PDK_ERR_ARG, "2-D only; this body is 3-D");
    T_FAILS(ctx, pdk_particles_set_define(p, "tri", &r, NULL), PDK_ERR_ARG, "2-D only");
    double lo[3] = {0, 0, 0.6}, hi[3] = {1, 1, 0.7};
    r = pdk_region_box(lo, hi);
    T_FAILS(ctx, pdk_particles_set_define(p, "slab", &r, NULL), PDK_ERR_ARG,
            "the box [0, 0, 0.6]..[1, 1, 0.7] contains none of the 8 particles; check the region "
            "against the body's extent [0.25, 0.25, 0.25]..[0.75, 0.75, 0.75]");
  }
  pdk_particles_destroy(&p);

  pdk_ctx_destroy(&ctx);
  return 0;
}
