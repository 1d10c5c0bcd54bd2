/* Regions (box, ball, half-space, polygon, cylinder) and what uses them: cutting holes and named
 * particle sets; see include/pdk/geometry.h.
 *
 * Membership rules (x a point, d = dim):
 *   box:        lo[a] <= x[a] <= hi[a] for a < d                      (closed)
 *   ball:       sum_a (x[a] - c[a])^2 <= r^2                           (closed)
 *   half-space: sum_a (x[a] - p[a]) * n[a] <= 0                        (closed)
 *   polygon:    crossing number of the ray from x towards +x is odd; edge (v_k, v_k+1) counts when
 *               it straddles the ray's line, y_k > y != y_k+1 > y, and meets it right of x
 *               (PNPOLY, W. R. Franklin). Points exactly on an edge fall on one side or the other
 *               by that half-open rule; self-intersecting polygons follow the even-odd rule.
 *   cylinder:   3-D; with d = p1 - p0 and t = (x - p0).d: 0 <= t <= d.d and
 *               |(x - p0) - (t / d.d) d|^2 <= r^2                      (closed, flat ends)
 *   invert:     the complement of the above.
 *
 * A named set "s" is the uint8 field "set:s" of the particle store, one entry per particle
 * (1 = member), so sets follow every reordering and compaction of the store.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/pdk_impl.h"
#include "pdk/ctx.h"
#include "pdk/geometry.h"
#include "pdk/particles.h"

#define SET_PREFIX "set:"

pdk_region pdk_region_box(const double lo[3], const double hi[3]) {
  pdk_region r;
  memset(&r, 0, sizeof r);
  r.kind = PDK_REGION_BOX;
  if (lo) memcpy(r.lo, lo, sizeof r.lo);
  if (hi) memcpy(r.hi, hi, sizeof r.hi);
  return r;
}

pdk_region pdk_region_ball(const double center[3], double radius) {
  pdk_region r;
  memset(&r, 0, sizeof r);
  r.kind = PDK_REGION_BALL;
  if (center) memcpy(r.center, center, sizeof r.center);
  r.radius = radius;
  return r;
}

pdk_region pdk_region_halfspace(const double point[3], const double normal[3]) {
  pdk_region r;
  memset(&r, 0, sizeof r);
  r.kind = PDK_REGION_HALFSPACE;
  if (point) memcpy(r.point, point, sizeof r.point);
  if (normal) memcpy(r.normal, normal, sizeof r.normal);
  return r;
}

pdk_region pdk_region_polygon(const double *vertices, int num_vertices) {
  pdk_region r;
  memset(&r, 0, sizeof r);
  r.kind = PDK_REGION_POLYGON;
  r.vertices = vertices;
  r.num_vertices = num_vertices;
  return r;
}

pdk_region pdk_region_cylinder(const double p0[3], const double p1[3], double radius) {
  pdk_region r;
  memset(&r, 0, sizeof r);
  r.kind = PDK_REGION_CYLINDER;
  if (p0) memcpy(r.p0, p0, sizeof r.p0);
  if (p1) memcpy(r.p1, p1, sizeof r.p1);
  r.radius = radius;
  return r;
}

/* Appends "[a, b]" or "[a, b, c]" to buf at *pos (snprintf semantics; truncates safely). */
static void append_vec(char *buf, size_t len, size_t *pos, int dim, const double *v) {
  for (int a = 0; a < dim; ++a) {
    if (*pos >= len) return;
    int w =
        snprintf(buf + *pos, len - *pos, "%s%g%s", a ? ", " : "[", v[a], a == dim - 1 ? "]" : "");
    if (w > 0) *pos += (size_t)w;
  }
}

static void append_str(char *buf, size_t len, size_t *pos, const char *s) {
  if (*pos >= len) return;
  int w = snprintf(buf + *pos, len - *pos, "%s", s);
  if (w > 0) *pos += (size_t)w;
}

void pdk_region_describe(const pdk_region *r, int dim, char *buf, size_t len) {
  size_t pos = 0;
  if (!buf || len == 0) return;
  buf[0] = '\0';
  if (!r) {
    snprintf(buf, len, "no region (NULL)");
    return;
  }
  if (dim != 2 && dim != 3) dim = 3;
  if (r->invert) append_str(buf, len, &pos, "the complement of ");
  switch (r->kind) {
  case PDK_REGION_BOX:
    append_str(buf, len, &pos, "the box ");
    append_vec(buf, len, &pos, dim, r->lo);
    append_str(buf, len, &pos, "..");
    append_vec(buf, len, &pos, dim, r->hi);
    return;
  case PDK_REGION_BALL:
    append_str(buf, len, &pos, dim == 2 ? "the disk of centre " : "the ball of centre ");
    append_vec(buf, len, &pos, dim, r->center);
    if (pos < len) snprintf(buf + pos, len - pos, " and radius %g", r->radius);
    return;
  case PDK_REGION_HALFSPACE:
    append_str(buf, len, &pos, dim == 2 ? "the half-plane (x - " : "the half-space (x - ");
    append_vec(buf, len, &pos, dim, r->point);
    append_str(buf, len, &pos, ") . ");
    append_vec(buf, len, &pos, dim, r->normal);
    append_str(buf, len, &pos, " <= 0");
    return;
  case PDK_REGION_CYLINDER:
    append_str(buf, len, &pos, "the cylinder of axis ");
    append_vec(buf, len, &pos, 3, r->p0);
    append_str(buf, len, &pos, "..");
    append_vec(buf, len, &pos, 3, r->p1);
    if (pos < len) snprintf(buf + pos, len - pos, " and radius %g", r->radius);
    return;
  case PDK_REGION_POLYGON: {
    if (pos < len) snprintf(buf + pos, len - pos, "the polygon of %d vertices", r->num_vertices);
    pos += strlen(buf + pos);
    if (r->vertices && r->num_vertices > 0) {
      double lo[2] = {r->vertices[0], r->vertices[1]}, hi[2] = {lo[0], lo[1]};
      for (int k = 1; k < r->num_vertices; ++k)
        for (int a = 0; a < 2; ++a) {
          lo[a] = fmin(lo[a], r->vertices[2 * k + a]);
          hi[a] = fmax(hi[a], r->vertices[2 * k + a]);
        }
      append_str(buf, len, &pos, " spanning ");
      append_vec(buf, len, &pos, 2, lo);
      append_str(buf, len, &pos, "..");
      append_vec(buf, len, &pos, 2, hi);
    }
    return;
  }
  }
  if (pos < len) snprintf(buf + pos, len - pos, "a region of unknown kind %d", (int)r->kind);
}

static int all_finite(int n, const double *v) {
  for (int a = 0; a < n; ++a)
    if (!isfinite(v[a])) return 0;
  return 1;
}

int pdk_region_check(pdk_ctx *ctx, int dim, const pdk_region *r) {
  static const char axis_name[3] = {'x', 'y', 'z'};
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CHECK(dim == 2 || dim == 3, ctx, PDK_ERR_ARG, "region dimension must be 2 or 3, got %d", dim);
  PDK_CHECK(r, ctx, PDK_ERR_ARG, "region is NULL");
  switch (r->kind) {
  case PDK_REGION_BOX:
    for (int a = 0; a < dim; ++a) {
      PDK_CHECK(isfinite(r->lo[a]) && isfinite(r->hi[a]), ctx, PDK_ERR_ARG,
                "box region bounds on axis %c must be finite, got lo = %g, hi = %g", axis_name[a],
                r->lo[a], r->hi[a]);
      PDK_CHECK(r->lo[a] <= r->hi[a], ctx, PDK_ERR_ARG,
                "box region is inverted on axis %c: lo = %g > hi = %g; swap the bounds",
                axis_name[a], r->lo[a], r->hi[a]);
    }
    return PDK_SUCCESS;
  case PDK_REGION_BALL:
    for (int a = 0; a < dim; ++a)
      PDK_CHECK(isfinite(r->center[a]), ctx, PDK_ERR_ARG,
                "ball region centre must be finite, got %g on axis %c", r->center[a], axis_name[a]);
    PDK_CHECK(isfinite(r->radius) && r->radius > 0, ctx, PDK_ERR_ARG,
              "ball region radius must be a finite number > 0, got %g", r->radius);
    return PDK_SUCCESS;
  case PDK_REGION_HALFSPACE: {
    double norm2 = 0;
    for (int a = 0; a < dim; ++a) {
      PDK_CHECK(isfinite(r->point[a]), ctx, PDK_ERR_ARG,
                "half-space region point must be finite, got %g on axis %c", r->point[a],
                axis_name[a]);
      PDK_CHECK(isfinite(r->normal[a]), ctx, PDK_ERR_ARG,
                "half-space region normal must be finite, got %g on axis %c", r->normal[a],
                axis_name[a]);
      norm2 += r->normal[a] * r->normal[a];
    }
    PDK_CHECK(norm2 > 0, ctx, PDK_ERR_ARG,
              "half-space region normal is zero; give a non-zero outward normal (the region is "
              "(x - point) . normal <= 0)");
    return PDK_SUCCESS;
  }
  case PDK_REGION_POLYGON:
    PDK_CHECK(dim == 2, ctx, PDK_ERR_ARG,
              "polygon regions are 2-D only; this body is %d-D (use a box, ball or half-space)",
              dim);
    PDK_CHECK(r->num_vertices >= 3, ctx, PDK_ERR_ARG,
              "polygon region needs at least 3 vertices, got %d", r->num_vertices);
    PDK_CHECK(r->vertices, ctx, PDK_ERR_ARG,
              "polygon region of %d vertices has no vertex array (NULL)", r->num_vertices);
    for (int k = 0; k < r->num_vertices; ++k)
      PDK_CHECK(all_finite(2, r->vertices + 2 * k), ctx, PDK_ERR_ARG,
                "polygon region vertex %d must be finite, got (%g, %g)", k, r->vertices[2 * k],
                r->vertices[2 * k + 1]);
    return PDK_SUCCESS;
  case PDK_REGION_CYLINDER: {
    PDK_CHECK(dim == 3, ctx, PDK_ERR_ARG,
              "cylinder regions are 3-D only; this body is %d-D (use a box or a disk)", dim);
    double len2 = 0;
    for (int a = 0; a < 3; ++a) {
      PDK_CHECK(isfinite(r->p0[a]) && isfinite(r->p1[a]), ctx, PDK_ERR_ARG,
                "cylinder region axis ends must be finite, got %g and %g on axis %c", r->p0[a],
                r->p1[a], axis_name[a]);
      len2 += (r->p1[a] - r->p0[a]) * (r->p1[a] - r->p0[a]);
    }
    PDK_CHECK(len2 > 0, ctx, PDK_ERR_ARG,
              "cylinder region axis has zero length (both ends at [%g, %g, %g]); give two "
              "different end points",
              r->p0[0], r->p0[1], r->p0[2]);
    PDK_CHECK(isfinite(r->radius) && r->radius > 0, ctx, PDK_ERR_ARG,
              "cylinder region radius must be a finite number > 0, got %g", r->radius);
    return PDK_SUCCESS;
  }
  }
  return pdk_ctx_error_set(ctx, PDK_ERR_ARG, __func__,
                           "unknown region kind %d; allowed: %d (box), %d (ball), %d (half-space), "
                           "%d (polygon), %d (cylinder)",
                           (int)r->kind, PDK_REGION_BOX, PDK_REGION_BALL, PDK_REGION_HALFSPACE,
                           PDK_REGION_POLYGON, PDK_REGION_CYLINDER);
}

/* Crossing-number test; vertices [nv][2]. */
static int polygon_contains(const double *v, int nv, double x, double y) {
  int inside = 0;
  for (int k = 0, m = nv - 1; k < nv; m = k++) {
    double xk = v[2 * k], yk = v[2 * k + 1], xm = v[2 * m], ym = v[2 * m + 1];
    if ((yk > y) != (ym > y) && x < (xm - xk) * (y - yk) / (ym - yk) + xk) inside = !inside;
  }
  return inside;
}

int pdk_region_contains(const pdk_region *r, int dim, const double *x) {
  int in = 0;
  if (!r || !x) return 0;
  switch (r->kind) {
  case PDK_REGION_BOX:
    in = 1;
    for (int a = 0; a < dim; ++a)
      in = in && r->lo[a] <= x[a] && x[a] <= r->hi[a];
    break;
  case PDK_REGION_BALL: {
    double d2 = 0;
    for (int a = 0; a < dim; ++a)
      d2 += (x[a] - r->center[a]) * (x[a] - r->center[a]);
    in = d2 <= r->radius * r->radius;
    break;
  }
  case PDK_REGION_HALFSPACE: {
    double s = 0;
    for (int a = 0; a < dim; ++a)
      s += (x[a] - r->point[a]) * r->normal[a];
    in = s <= 0;
    break;
  }
  case PDK_REGION_CYLINDER: {
    double d[3], y[3], dd = 0, t = 0, r2 = 0;
    for (int a = 0; a < 3; ++a) {
      d[a] = r->p1[a] - r->p0[a];
      y[a] = (dim == 3 || a < 2 ? x[a] : 0.0) - r->p0[a];
      dd += d[a] * d[a];
      t += y[a] * d[a];
    }
    if (dim != 3 || !(dd > 0) || t < 0 || t > dd) break;
    for (int a = 0; a < 3; ++a) {
      const double q = y[a] - t / dd * d[a];
      r2 += q * q;
    }
    in = r2 <= r->radius * r->radius;
    break;
  }
  case PDK_REGION_POLYGON:
    in = dim == 2 && r->num_vertices >= 3 &&
         polygon_contains(r->vertices, r->num_vertices, x[0], x[1]);
    break;
  }
  return r->invert ? !in : in;
}

/* flags[i] = 1 if particle i lies in the region; returns the member count. Threaded; the flags and
 * the count do not depend on the thread count. */
static pdk_index region_flags(pdk_particles *p, const pdk_region *r, uint8_t *flags) {
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  const double *X0 = pdk_particles_X(p, 0), *X1 = pdk_particles_X(p, 1);
  const double *X2 = dim == 3 ? pdk_particles_X(p, 2) : NULL;
  const int nthreads = pdk_particles_ctx(p)->num_threads;
  pdk_index count = 0;
#pragma omp parallel for default(none) shared(r, flags, X0, X1, X2, n, dim) reduction(+ : count) \
    schedule(static) num_threads(nthreads)
  for (pdk_index i = 0; i < n; ++i) {
    double x[3] = {X0[i], X1[i], dim == 3 ? X2[i] : 0.0};
    flags[i] = (uint8_t)pdk_region_contains(r, dim, x);
    count += flags[i];
  }
  return count;
}

/* Bounding box of the particles' reference positions, as "[..]..[..]" into buf. */
static void describe_extent(pdk_particles *p, char *buf, size_t len) {
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (int a = 0; a < dim; ++a) {
    const double *x = pdk_particles_X(p, a);
    lo[a] = hi[a] = x[0];
    for (pdk_index i = 1; i < n; ++i) {
      lo[a] = fmin(lo[a], x[i]);
      hi[a] = fmax(hi[a], x[i]);
    }
  }
  size_t pos = 0;
  buf[0] = '\0';
  append_vec(buf, len, &pos, dim, lo);
  append_str(buf, len, &pos, "..");
  append_vec(buf, len, &pos, dim, hi);
}

int pdk_particles_cut(pdk_particles *p, const pdk_region *r, pdk_index *removed) {
  int err = PDK_SUCCESS;
  pdk_ctx *ctx = pdk_particles_ctx(p);
  const pdk_index n = pdk_particles_count(p);
  uint8_t *keep = NULL;
  char what[512], extent[256];
  if (removed) *removed = 0;
  PDK_CHECK_ARG(p, NULL);
  PDK_CALL(pdk_region_check(ctx, pdk_particles_dim(p), r));
  keep = malloc((size_t)n);
  PDK_CHECK(keep, ctx, PDK_ERR_MEMORY, "out of memory marking %d particles for a cut", (int)n);
  pdk_index inside = region_flags(p, r, keep);
  if (inside == n) {
    pdk_region_describe(r, pdk_particles_dim(p), what, sizeof what);
    describe_extent(p, extent, sizeof extent);
    PDK_CHECK_GOTO(0, ctx, PDK_ERR_ARG,
                   "cut would remove every particle: %s contains all %d particles of the body "
                   "(extent %s); check the hole against the body",
                   what, (int)n, extent);
  }
  if (inside > 0) {
    for (pdk_index i = 0; i < n; ++i)
      keep[i] = !keep[i];
    PDK_CALL_GOTO(pdk_particles_compact(p, keep));
  }
  if (removed) *removed = inside;
cleanup:
  free(keep);
  return err;
}

/* "set:<name>" into field (PDK_FIELD_NAME_MAX bytes), with the name checked. */
static int set_field_name(pdk_ctx *ctx, const char *name, char *field) {
  PDK_CHECK(name && name[0], ctx, PDK_ERR_ARG, "a set needs a non-empty name");
  PDK_CHECK(strlen(SET_PREFIX) + strlen(name) < PDK_FIELD_NAME_MAX, ctx, PDK_ERR_ARG,
            "set name '%s' is too long: at most %d characters", name,
            (int)(PDK_FIELD_NAME_MAX - 1 - strlen(SET_PREFIX)));
  snprintf(field, PDK_FIELD_NAME_MAX, SET_PREFIX "%s", name);
  return PDK_SUCCESS;
}

int pdk_particles_set_define(pdk_particles *p, const char *name, const pdk_region *r,
                             pdk_index *count) {
  int err = PDK_SUCCESS;
  pdk_ctx *ctx = pdk_particles_ctx(p);
  const int dim = pdk_particles_dim(p);
  const pdk_index n = pdk_particles_count(p);
  uint8_t *flags = NULL;
  char field[PDK_FIELD_NAME_MAX], what[512], extent[256];
  if (count) *count = 0;
  PDK_CHECK_ARG(p, NULL);
  PDK_CALL(set_field_name(ctx, name, field));
  PDK_CALL(pdk_region_check(ctx, dim, r));
  /* Membership into a scratch array first, so a failed definition leaves the store unchanged. */
  flags = malloc((size_t)n);
  PDK_CHECK(flags, ctx, PDK_ERR_MEMORY, "out of memory defining set '%s' over %d particles", name,
            (int)n);
  pdk_index members = region_flags(p, r, flags);
  if (members == 0) {
    pdk_region_describe(r, dim, what, sizeof what);
    describe_extent(p, extent, sizeof extent);
    PDK_CHECK_GOTO(0, ctx, PDK_ERR_ARG,
                   "set '%s' selects no particle: %s contains none of the %d particles; check the "
                   "region against the body's extent %s",
                   name, what, (int)n, extent);
  }
  PDK_CALL_GOTO(pdk_particles_field_add(p, field, PDK_U8, 1));
  uint8_t *dst = pdk_particles_field_data(p, field, 0);
  memcpy(dst, flags, (size_t)n); /* redefinition replaces the old membership */
  if (count) *count = members;
cleanup:
  free(flags);
  return err;
}

int pdk_particles_set_indices(pdk_particles *p, const char *name, pdk_index **indices,
                              pdk_index *count) {
  pdk_ctx *ctx = pdk_particles_ctx(p);
  const pdk_index n = pdk_particles_count(p);
  char field[PDK_FIELD_NAME_MAX];
  pdk_type type;
  int num_comp;
  PDK_CHECK_ARG(p, NULL);
  PDK_CHECK_ARG(indices, ctx);
  *indices = NULL;
  if (count) *count = 0;
  PDK_CALL(set_field_name(ctx, name, field));
  PDK_CHECK(pdk_particles_field_exists(p, field), ctx, PDK_ERR_NOT_FOUND,
            "no set '%s': field '%s' was never declared (define the set with "
            "pdk_particles_set_define)",
            name, field);
  PDK_CALL(pdk_particles_field_info(p, field, &type, &num_comp));
  PDK_CHECK(type == PDK_U8 && num_comp == 1, ctx, PDK_ERR_ARG,
            "field '%s' is not a set: sets are uint8 fields of one component", field);
  const uint8_t *flags = pdk_particles_field_data(p, field, 0);
  pdk_index m = 0;
  for (pdk_index i = 0; i < n; ++i)
    m += flags[i] != 0;
  pdk_index *out = malloc((size_t)(m > 0 ? m : 1) * sizeof *out);
  PDK_CHECK(out, ctx, PDK_ERR_MEMORY, "out of memory listing the %d members of set '%s'", (int)m,
            name);
  m = 0;
  for (pdk_index i = 0; i < n; ++i)
    if (flags[i]) out[m++] = i;
  *indices = out;
  if (count) *count = m;
  return PDK_SUCCESS;
}
