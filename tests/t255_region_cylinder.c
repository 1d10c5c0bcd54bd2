/* The cylinder region: membership of hand-checked points (inside, on the mantle and the flat ends,
 * just outside, beyond the ends, an oblique axis), the checks (zero-length axis, radius <= 0,
 * 2-D), lattice counts against pi r^2 L / h^3, and the scene keys: a rod carved from a box with
 * an inverted cylinder notch, a notch that removes no particle (allowed), and the load errors.
 * labels: unit */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pdk/scene.h"
#include "test_util.h"

static int in3(const pdk_region *r, double x, double y, double z) {
  double p[3] = {x, y, z};
  return pdk_region_contains(r, 3, p);
}

/* Particles of a cubic lattice of spacing h over box lo..hi cut to the cylinder (inverted notch).
 */
static pdk_index lattice_in_cylinder(pdk_ctx *ctx, double h, const double lo[3], const double hi[3],
                                     const pdk_region *cyl) {
  pdk_lattice_opts o = pdk_lattice_opts_default();
  o.type = PDK_LATTICE_CUBIC;
  o.spacing = h;
  memcpy(o.lo, lo, sizeof o.lo);
  memcpy(o.hi, hi, sizeof o.hi);
  pdk_particles *p = NULL;
  T_OK(ctx, pdk_lattice_create(ctx, &o, &p));
  pdk_region outside = *cyl;
  outside.invert = 1;
  pdk_index removed = 0;
  T_OK(ctx, pdk_particles_cut(p, &outside, &removed));
  pdk_index n = pdk_particles_count(p);
  pdk_particles_destroy(&p);
  return n;
}

static const char *rod_scene =
    "dimension: 3\n"
    "geometry:\n"
    "  spacing: 0.5e-3\n"
    "  box: {lo: [-3.0e-3, -3.0e-3, 0], hi: [3.0e-3, 3.0e-3, 10.0e-3]}\n"
    "  notches:\n"
    "    - {cylinder: {axis: [[0, 0, 0], [0, 0, 10.0e-3]], radius: 3.0e-3}, invert: true}\n"
    "    - halfspace: {point: [0, 0, -1], normal: [0, 0, 1]}\n" /* z <= -1: removes nothing */
    "material: {density: 8930, youngs_modulus: 117e9, poisson_ratio: 0.35}\n"
    "model: {kind: pmb}\n"
    "sets:\n"
    "  - {name: core, cylinder: {axis: [[0, 0, 2.0e-3], [0, 0, 8.0e-3]], radius: 1.0e-3}}\n"
    "solver: {steps: 1}\n";

static void write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  T_ASSERT(f != NULL, "open %s", path);
  fputs(text, f);
  fclose(f);
}

/* Replaces the one occurrence of `find` in `text` by `repl` into out. */
static void edit(char *out, size_t len, const char *text, const char *find, const char *repl) {
  const char *at = strstr(text, find);
  T_ASSERT(at != NULL, "'%s' in the scene", find);
  snprintf(out, len, "%.*s%s%s", (int)(at - text), text, repl, at + strlen(find));
}

int main(void) {
  pdk_ctx *ctx = t_ctx(2);

  /* Membership: axis from (0,0,0) to (0,0,2), radius 1. Closed: the mantle and the end disks are
   * in (the distances are exact in binary here). */
  const double a0[3] = {0, 0, 0}, a1[3] = {0, 0, 2};
  pdk_region c = pdk_region_cylinder(a0, a1, 1.0);
  T_OK(ctx, pdk_region_check(ctx, 3, &c));
  T_ASSERT(in3(&c, 0, 0, 1), "centre inside");
  T_ASSERT(in3(&c, 1, 0, 1), "on the mantle inside (closed)");
  T_ASSERT(in3(&c, 0, -1, 0), "rim of the lower end inside (closed)");
  T_ASSERT(in3(&c, 0.5, 0.5, 2), "upper end disk inside (closed)");
  T_ASSERT(in3(&c, 0.6, 0.8, 0.5), "|(0.6, 0.8)| = 1 on the mantle");
  T_ASSERT(!in3(&c, 0.75, 0.75, 1), "|(0.75, 0.75)| = 1.06 > 1 outside");
  T_ASSERT(!in3(&c, 0, 0, 2.0000001), "beyond the upper end outside");
  T_ASSERT(!in3(&c, 0, 0, -1e-12), "below the lower end outside");
  T_ASSERT(!in3(&c, 1.0000001, 0, 1), "just outside the mantle");
  pdk_region ci = c;
  ci.invert = 1;
  T_ASSERT(!in3(&ci, 0, 0, 1) && in3(&ci, 2, 0, 1), "invert is the complement");
  /* The same cylinder with the ends swapped is the same set. */
  pdk_region cs = pdk_region_cylinder(a1, a0, 1.0);
  T_ASSERT(in3(&cs, 0, -1, 0) && !in3(&cs, 0, 0, 2.5) && in3(&cs, 0.6, 0.8, 0.5),
           "swapped ends: same region");
  /* Oblique axis (1,1,1) direction from the origin to (2,2,2), radius 0.5: the point (1,1,1) +
   * 0.4 (1,-1,0)/sqrt2 is 0.4 from the axis; (1,1,1) + 0.6 (1,-1,0)/sqrt2 is 0.6 from it;
   * (-0.1,-0.1,-0.1) projects before the start. */
  const double b0[3] = {0, 0, 0}, b1[3] = {2, 2, 2};
  pdk_region ob = pdk_region_cylinder(b0, b1, 0.5);
  const double s2 = sqrt(0.5);
  T_ASSERT(in3(&ob, 1 + 0.4 * s2, 1 - 0.4 * s2, 1), "oblique: 0.4 from the axis inside");
  T_ASSERT(!in3(&ob, 1 + 0.6 * s2, 1 - 0.6 * s2, 1), "oblique: 0.6 from the axis outside");
  T_ASSERT(!in3(&ob, -0.1, -0.1, -0.1), "oblique: before the start outside");
  T_ASSERT(in3(&ob, 1.9, 1.9, 1.9) && !in3(&ob, 2.1, 2.1, 2.1), "oblique: the upper end");
  char what[256];
  pdk_region_describe(&c, 3, what, sizeof what);
  T_ASSERT(strstr(what, "cylinder") && strstr(what, "radius 1"), "describe: '%s'", what);

  /* Checks. */
  pdk_region bad = pdk_region_cylinder(a0, a0, 1.0);
  T_FAILS(ctx, pdk_region_check(ctx, 3, &bad), PDK_ERR_ARG, "zero length");
  bad = pdk_region_cylinder(a0, a1, 0.0);
  T_FAILS(ctx, pdk_region_check(ctx, 3, &bad), PDK_ERR_ARG, "radius");
  bad = pdk_region_cylinder(a0, a1, -1.0);
  T_FAILS(ctx, pdk_region_check(ctx, 3, &bad), PDK_ERR_ARG, "radius");
  const double nan3[3] = {0, NAN, 0};
  bad = pdk_region_cylinder(a0, nan3, 1.0);
  T_FAILS(ctx, pdk_region_check(ctx, 3, &bad), PDK_ERR_ARG, "finite");
  T_FAILS(ctx, pdk_region_check(ctx, 2, &c), PDK_ERR_ARG, "3-D only");

  /* Counts against pi R^2 L / h^3, with rigorous bounds: a point is the centre of its cell, of
   * half-diagonal c = sqrt(3)/2 h. A cell whose centre is inside lies in the cylinder grown by c
   * (radius and both ends), and every cell inside the cylinder shrunk by c has its centre inside,
   * so pi (R - c)^2 (L - 2c) <= N h^3 <= pi (R + c)^2 (L + 2c) for any axis direction. With the
   * axis along z, its ends on cell faces and the box centred on the axis, the count along z is
   * exact (L/h layers) and the bound applies to one layer with c = sqrt(2)/2 h (the Gauss circle
   * problem): pi (R - c)^2 <= N_layer h^2 <= pi (R + c)^2, a tolerance of about sqrt(2) h / R
   * (18% at the Taylor rod's R/h = 8; measured deviations are far smaller, T_INFO). */
  {
    const double Rs[3] = {3.2e-3, 3.2e-3, 3.2e-3}, hs[3] = {0.8e-3, 0.4e-3, 0.1e-3};
    const double L = 32.4e-3;
    for (int k = 0; k < 3; ++k) {
      const double R = Rs[k], h = hs[k];
      const double Lk = k == 2 ? 8e-3 : L; /* the finest one shorter: 5 10^5 points */
      const double lo[3] = {-R, -R, 0}, hi[3] = {R, R, Lk};
      const double p0[3] = {0, 0, 0}, p1[3] = {0, 0, Lk};
      pdk_region rod = pdk_region_cylinder(p0, p1, R);
      const pdk_index n = lattice_in_cylinder(ctx, h, lo, hi, &rod);
      const double layers = round(Lk / h), c2 = sqrt(0.5) * h;
      const double per_layer = (double)n / layers;
      T_ASSERT(fmod((double)n, layers) == 0, "h %g: %d points, not a multiple of %g layers", h,
               (int)n, layers);
      const double lo_b = M_PI * (R - c2) * (R - c2) / (h * h);
      const double hi_b = M_PI * (R + c2) * (R + c2) / (h * h);
      T_ASSERT(per_layer >= lo_b && per_layer <= hi_b,
               "h %g: %g points per layer outside [%g, %g] (pi R^2/h^2 = %g)", h, per_layer, lo_b,
               hi_b, M_PI * R * R / (h * h));
      T_INFO("cylinder R/h %g: N %d, N h^3 / (pi R^2 L) = %.4f\n", R / h, (int)n,
             (double)n * h * h * h / (M_PI * R * R * Lk));
    }
    /* Oblique axis through a box: the 3-D bound. */
    const double h = 0.05, R = 0.5, p0[3] = {0.3, 0.2, 0.4}, p1[3] = {1.5, 1.6, 1.3};
    double L2 = 0;
    for (int a = 0; a < 3; ++a)
      L2 += (p1[a] - p0[a]) * (p1[a] - p0[a]);
    const double Lo = sqrt(L2);
    const double lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {2.5, 2.5, 2.5};
    pdk_region rod = pdk_region_cylinder(p0, p1, R);
    const pdk_index n = lattice_in_cylinder(ctx, h, lo, hi, &rod);
    const double c3 = sqrt(3.0) / 2 * h;
    const double v = (double)n * h * h * h;
    const double v_lo = M_PI * (R - c3) * (R - c3) * (Lo - 2 * c3);
    const double v_hi = M_PI * (R + c3) * (R + c3) * (Lo + 2 * c3);
    T_ASSERT(v >= v_lo && v <= v_hi, "oblique: N h^3 = %g outside [%g, %g] (pi R^2 L = %g)", v,
             v_lo, v_hi, M_PI * R * R * Lo);
    T_INFO("oblique cylinder: N h^3 / (pi R^2 L) = %.4f\n", v / (M_PI * R * R * Lo));
  }

  /* The scene: a rod carved from its bounding box; the second notch (below the body) removes no
   * particle, which is allowed; the set "core" is a cylinder too. */
  {
    const char *path = "t255_rod.yaml";
    write_file(path, rod_scene);
    pdk_scene *s = NULL;
    pdk_sim *sim = NULL;
    T_OK(ctx, pdk_scene_load(ctx, path, NULL, 0, &s));
    T_OK(ctx, pdk_sim_create(ctx, s, &sim));
    pdk_particles *p = pdk_sim_particles(sim);
    const double lo[3] = {-3e-3, -3e-3, 0}, hi[3] = {3e-3, 3e-3, 10e-3};
    const double p0[3] = {0, 0, 0}, p1[3] = {0, 0, 10e-3};
    pdk_region rod = pdk_region_cylinder(p0, p1, 3e-3);
    const pdk_index want = lattice_in_cylinder(ctx, 0.5e-3, lo, hi, &rod);
    T_ASSERT(pdk_particles_count(p) == want, "scene rod: %d particles, the library cut gives %d",
             (int)pdk_particles_count(p), (int)want);
    pdk_index *idx = NULL, m = 0;
    T_OK(ctx, pdk_particles_set_indices(p, "core", &idx, &m));
    /* core: radius 2 spacings, z in [2, 8] mm: 12 layers of the points with |(i+1/2, j+1/2)| <= 2
     * (in spacings): (+-0.5, +-0.5), (+-1.5, +-0.5), (+-0.5, +-1.5), (+-1.5, +-1.5) has
     * 1.5^2 + 1.5^2 = 4.5 > 4: 12 per layer. */
    T_ASSERT(m == 12 * 12, "set core: %d members, expected 144", (int)m);
    free(idx);
    pdk_sim_destroy(&sim);
    pdk_scene_destroy(&s);

    /* Load errors, each naming the key. */
    static const struct {
      const char *find, *repl, *key;
    } errs[] = {
        {"axis: [[0, 0, 0], [0, 0, 10.0e-3]]", "axis: [[0, 0, 1e-3], [0, 0, 1e-3]]",
         "geometry.notches[0].cylinder.axis"},
        {"radius: 3.0e-3", "radius: 0", "geometry.notches[0].cylinder.radius"},
        {"radius: 3.0e-3", "radius: -1e-3", "geometry.notches[0].cylinder.radius"},
        {"axis: [[0, 0, 0], [0, 0, 10.0e-3]]", "axis: [[0, 0], [0, 0, 10.0e-3]]",
         "geometry.notches[0].cylinder.axis"},
        {"axis: [[0, 0, 0], [0, 0, 10.0e-3]]", "axis: [[0, 0, 0]]",
         "geometry.notches[0].cylinder.axis"},
        {"radius: 3.0e-3}, invert", "radius: 3.0e-3}, box: {lo: [0, 0, 0], hi: [1, 1, 1]}, invert",
         "both"},
    };
    char text[4096];
    for (size_t k = 0; k < sizeof errs / sizeof errs[0]; ++k) {
      edit(text, sizeof text, rod_scene, errs[k].find, errs[k].repl);
      write_file(path, text);
      int err = pdk_scene_load(ctx, path, NULL, 0, &s);
      T_ASSERT(err == PDK_ERR_ARG, "case %d: load gave %d, expected an error", (int)k, err);
      T_ASSERT(strstr(pdk_ctx_error_message(ctx), errs[k].key), "case %d: '%s' lacks '%s'", (int)k,
               pdk_ctx_error_message(ctx), errs[k].key);
      pdk_scene_destroy(&s);
    }
    /* A cylinder in a 2-D scene. */
    write_file(path, "dimension: 2\n"
                     "geometry:\n"
                     "  spacing: 1.0e-3\n"
                     "  box: {lo: [0, 0], hi: [0.01, 0.02]}\n"
                     "  notches:\n"
                     "    - cylinder: {axis: [[0, 0], [0, 0.01]], radius: 1.0e-3}\n"
                     "material: {density: 7850, youngs_modulus: 200e9, poisson_ratio: 0.3}\n"
                     "solver: {steps: 1}\n");
    int err = pdk_scene_load(ctx, path, NULL, 0, &s);
    T_ASSERT(err == PDK_ERR_ARG && strstr(pdk_ctx_error_message(ctx), "3-D region"),
             "2-D cylinder: %d '%s'", err, pdk_ctx_error_message(ctx));
    pdk_scene_destroy(&s);
    remove(path);
  }

  pdk_ctx_destroy(&ctx);
  return 0;
}
