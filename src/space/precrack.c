/* Pre-cracks of a family build: their geometry checked and prepared, and the exact tests a bond
 * needs (the side of a point, whether a bond segment meets a crack, whether a box lies on one
 * side), on exact orientation predicates (src/space/families.c, file comment step 4;
 * src/space/families_build.h).
 */
#include <math.h>
#include <string.h>

#include "families_build.h"
#include "pdk/ctx.h"
#include "pdk/families.h"

/* ---- exact orientation predicates ------------------------------------------------------------
 * orient2d(a, b, c) = det [a - c; b - c] and orient3d(a, b, c, d) = det [a - d; b - d; c - d], as
 * exact signs. A floating-point evaluation with Shewchuk's forward error bound (doubled here for
 * margin) decides almost every case; the rest are evaluated exactly as sums of products of the
 * input coordinates, each product split into non-overlapping doubles with fma, summed into a
 * non-overlapping expansion (Shewchuk's Grow-Expansion) whose largest component gives the sign.
 * Exact as long as no product underflows or overflows (|coordinates| within 1e-70 .. 1e70). */

/* Adds b to the expansion e[0..m-1] (non-overlapping, increasing magnitude, no zeros); returns
 * the new length. */
static int expansion_grow(double *e, int m, double b) {
  int k = 0;
  double q = b;
  for (int i = 0; i < m; ++i) {
    double sum = q + e[i];
    double bv = sum - q, av = sum - bv;
    double err = (q - av) + (e[i] - bv);
    q = sum;
    if (err != 0.0) e[k++] = err;
  }
  if (q != 0.0) e[k++] = q;
  return k;
}

/* Adds sign * a * b to the expansion, exactly. */
static int expansion_add_product(double *e, int m, double sign, double a, double b) {
  double p = a * b, err = fma(a, b, -p);
  m = expansion_grow(e, m, sign * p);
  return expansion_grow(e, m, sign * err);
}

/* Adds sign * a * b * c to the expansion, exactly. */
static int expansion_add_triple(double *e, int m, double sign, double a, double b, double c) {
  double p = a * b, err = fma(a, b, -p);
  m = expansion_add_product(e, m, sign, p, c);
  return expansion_add_product(e, m, sign, err, c);
}

static int expansion_sign(const double *e, int m) { return m == 0 ? 0 : (e[m - 1] > 0 ? 1 : -1); }

static int orient2d_sign(const double a[2], const double b[2], const double c[2]) {
  const double eps = 0x1p-53;
  double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  double detright = (a[1] - c[1]) * (b[0] - c[0]);
  double det = detleft - detright;
  double bound = 2.0 * (3.0 + 16.0 * eps) * eps * (fabs(detleft) + fabs(detright));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  /* det = ax by - ax cy - ay bx + ay cx + bx cy - by cx */
  double e[12];
  int m = 0;
  m = expansion_add_product(e, m, 1, a[0], b[1]);
  m = expansion_add_product(e, m, -1, a[0], c[1]);
  m = expansion_add_product(e, m, -1, a[1], b[0]);
  m = expansion_add_product(e, m, 1, a[1], c[0]);
  m = expansion_add_product(e, m, 1, b[0], c[1]);
  m = expansion_add_product(e, m, -1, b[1], c[0]);
  return expansion_sign(e, m);
}

/* Adds sign * det [p; q; r] (3 x 3, rows p, q, r) to the expansion. */
static int expansion_add_det3(double *e, int m, double sign, const double p[3], const double q[3],
                              const double r[3]) {
  m = expansion_add_triple(e, m, sign, p[0], q[1], r[2]);
  m = expansion_add_triple(e, m, -sign, p[0], q[2], r[1]);
  m = expansion_add_triple(e, m, -sign, p[1], q[0], r[2]);
  m = expansion_add_triple(e, m, sign, p[1], q[2], r[0]);
  m = expansion_add_triple(e, m, sign, p[2], q[0], r[1]);
  m = expansion_add_triple(e, m, -sign, p[2], q[1], r[0]);
  return m;
}

static int orient3d_sign(const double a[3], const double b[3], const double c[3],
                         const double d[3]) {
  const double eps = 0x1p-53;
  double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  double bc = bdy * cdz - bdz * cdy, ca = cdy * adz - cdz * ady, ab = ady * bdz - adz * bdy;
  double det = adx * bc + bdx * ca + cdx * ab;
  double permanent = (fabs(bdy * cdz) + fabs(bdz * cdy)) * fabs(adx) +
                     (fabs(cdy * adz) + fabs(cdz * ady)) * fabs(bdx) +
                     (fabs(ady * bdz) + fabs(adz * bdy)) * fabs(cdx);
  double bound = 2.0 * (7.0 + 56.0 * eps) * eps * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  /* det [a-d; b-d; c-d] = det [a 1; b 1; c 1; d 1] = -|b c d| + |a c d| - |a b d| + |a b c| */
  double e[96];
  int m = 0;
  m = expansion_add_det3(e, m, -1, b, c, d);
  m = expansion_add_det3(e, m, 1, a, c, d);
  m = expansion_add_det3(e, m, -1, a, b, d);
  m = expansion_add_det3(e, m, 1, a, b, c);
  return expansion_sign(e, m);
}

/* ---- pre-cracks ------------------------------------------------------------------------------ */

/* Checks the pre-crack geometry and precomputes what the bond tests need. */
int pdk_cracks_prepare(pdk_ctx *ctx, int dim, const pdk_families_opts *o, crack **out) {
  *out = NULL;
  PDK_CHECK(o->num_precracks >= 0, ctx, PDK_ERR_ARG, "opts.num_precracks must be >= 0, got %d",
            o->num_precracks);
  if (o->num_precracks == 0) return PDK_SUCCESS;
  PDK_CHECK(o->precracks, ctx, PDK_ERR_ARG, "opts.num_precracks is %d but opts.precracks is NULL",
            o->num_precracks);
  for (int k = 0; k < o->num_precracks; ++k) {
    const pdk_precrack *pc = &o->precracks[k];
    if (dim == 2)
      PDK_CHECK(pc->num_vertices == 2, ctx, PDK_ERR_ARG,
                "pre-crack %d: a 2-D pre-crack is a segment with 2 vertices, got %d vertices", k,
                pc->num_vertices);
    else
      PDK_CHECK(pc->num_vertices >= 3, ctx, PDK_ERR_ARG,
                "pre-crack %d: a 3-D pre-crack is a planar polygon with at least 3 vertices, got "
                "%d vertices",
                k, pc->num_vertices);
    PDK_CHECK(pc->vertices, ctx, PDK_ERR_ARG, "pre-crack %d: vertices is NULL", k);
    for (int v = 0; v < pc->num_vertices; ++v)
      for (int a = 0; a < dim; ++a)
        PDK_CHECK(isfinite(pc->vertices[v * dim + a]), ctx, PDK_ERR_ARG,
                  "pre-crack %d: vertex %d has a non-finite coordinate %d = %g", k, v, a,
                  pc->vertices[v * dim + a]);
  }
  crack *cr = calloc((size_t)o->num_precracks, sizeof *cr);
  PDK_CHECK(cr, ctx, PDK_ERR_MEMORY, "out of memory preparing %d pre-cracks", o->num_precracks);
  for (int k = 0; k < o->num_precracks; ++k) {
    const pdk_precrack *pc = &o->precracks[k];
    crack *c = &cr[k];
    const int nv = pc->num_vertices;
    const double *v = pc->vertices;
    c->num_vertices = nv;
    c->v = v;
    for (int a = 0; a < dim; ++a) {
      c->lo[a] = c->hi[a] = v[a];
      for (int q = 1; q < nv; ++q) {
        c->lo[a] = fmin(c->lo[a], v[q * dim + a]);
        c->hi[a] = fmax(c->hi[a], v[q * dim + a]);
      }
    }
    double size = 0;
    for (int a = 0; a < dim; ++a)
      size = fmax(size, c->hi[a] - c->lo[a]);
    if (dim == 2) {
      if (!(size > 0)) {
        free(cr);
        return pdk_ctx_error_set(ctx, PDK_ERR_ARG, __func__,
                                 "pre-crack %d: its two vertices coincide at (%g, %g); a crack "
                                 "segment needs a positive length",
                                 k, v[0], v[1]);
      }
      continue;
    }
    /* Newell normal: n = sum over edges (v_q - v_{q+1}) x-ish terms, robust for any planar
     * polygon, convex or not; |n| is twice the area. */
    double n[3] = {0, 0, 0};
    for (int q = 0; q < nv; ++q) {
      const double *p0 = &v[q * 3], *p1 = &v[((q + 1) % nv) * 3];
      n[0] += (p0[1] - p1[1]) * (p0[2] + p1[2]);
      n[1] += (p0[2] - p1[2]) * (p0[0] + p1[0]);
      n[2] += (p0[0] - p1[0]) * (p0[1] + p1[1]);
    }
    double nlen = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(size > 0) || !(nlen > 1e-12 * size * size)) {
      free(cr);
      return pdk_ctx_error_set(ctx, PDK_ERR_ARG, __func__,
                               "pre-crack %d: the polygon has zero area (its %d vertices are "
                               "repeated or collinear)",
                               k, nv);
    }
    for (int q = 0; q < nv; ++q) {
      double dist =
          ((v[q * 3] - v[0]) * n[0] + (v[q * 3 + 1] - v[1]) * n[1] + (v[q * 3 + 2] - v[2]) * n[2]) /
          nlen;
      if (!(fabs(dist) <= 1e-9 * size)) {
        free(cr);
        return pdk_ctx_error_set(ctx, PDK_ERR_ARG, __func__,
                                 "pre-crack %d: the polygon is not planar: vertex %d lies %g off "
                                 "the plane of vertex 0 (polygon size %g)",
                                 k, q, dist, size);
      }
    }
    memcpy(c->normal, n, sizeof n);
    /* Plane for the exact side test: vertex 0, the vertex farthest from it, and the vertex that
     * makes the largest triangle with those two. */
    int ib = 0, ic = 0;
    double best = -1;
    for (int q = 1; q < nv; ++q) {
      double d0 = v[q * 3] - v[0], d1 = v[q * 3 + 1] - v[1], d2 = v[q * 3 + 2] - v[2];
      double d = d0 * d0 + d1 * d1 + d2 * d2;
      if (d > best) best = d, ib = q;
    }
    best = -1;
    for (int q = 1; q < nv; ++q) {
      double e1[3], e2[3], x[3];
      for (int a = 0; a < 3; ++a)
        e1[a] = v[ib * 3 + a] - v[a], e2[a] = v[q * 3 + a] - v[a];
      x[0] = e1[1] * e2[2] - e1[2] * e2[1];
      x[1] = e1[2] * e2[0] - e1[0] * e2[2];
      x[2] = e1[0] * e2[1] - e1[1] * e2[0];
      double d = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
      if (d > best) best = d, ic = q;
    }
    c->plane[0] = 0;
    c->plane[1] = ib;
    c->plane[2] = ic;
    int drop = 0;
    for (int a = 1; a < 3; ++a)
      if (fabs(n[a]) > fabs(n[drop])) drop = a;
    c->axis_u = (drop + 1) % 3;
    c->axis_w = (drop + 2) % 3;
  }
  *out = cr;
  return PDK_SUCCESS;
}

/* Exact side (-1, 0, +1) of the point x with respect to the crack's line (2-D: through its two
 * vertices) or plane (3-D: through three of its vertices, see cracks_prepare). */
int pdk_crack_side(const crack *c, int dim, const double x[3]) {
  if (dim == 2) return orient2d_sign(c->v, c->v + 2, x);
  return orient3d_sign(c->v + 3 * c->plane[0], c->v + 3 * c->plane[1], c->v + 3 * c->plane[2], x);
}

/* 1 if the closed bond segment p-q meets the closed crack segment; a bond on the crack's line is
 * not cut. sp, sq: crack_side of p and q. */
int pdk_crack_cuts2(const crack *c, const double p[2], const double q[2], int sp, int sq) {
  if (sp == 0 && sq == 0) return 0;
  if (sp * sq > 0) return 0;
  const double *a = c->v, *b = c->v + 2;
  int o3 = orient2d_sign(p, q, a), o4 = orient2d_sign(p, q, b);
  return o3 * o4 <= 0;
}

/* 1 if the point x (on the crack's plane) lies inside the polygon: crossing number in the
 * projection that drops the dominant normal axis. */
static int crack_contains3(const crack *c, const double x[3]) {
  const int u = c->axis_u, w = c->axis_w, nv = c->num_vertices;
  const double *v = c->v;
  int inside = 0;
  for (int a = 0, b = nv - 1; a < nv; b = a++) {
    double ua = v[a * 3 + u], wa = v[a * 3 + w], ub = v[b * 3 + u], wb = v[b * 3 + w];
    if ((wa > x[w]) != (wb > x[w])) {
      double ucross = ua + (x[w] - wa) * (ub - ua) / (wb - wa);
      if (x[u] < ucross) inside = !inside;
    }
  }
  return inside;
}

/* 1 if the closed bond segment p-q passes through the crack polygon; a bond lying in the crack's
 * plane is not cut. sp, sq: crack_side of p and q (exact); the crossing point is computed in
 * floating point. */
int pdk_crack_cuts3(const crack *c, const double p[3], const double q[3], int sp, int sq) {
  if (sp == 0 && sq == 0) return 0;
  if (sp * sq > 0) return 0;
  double x[3];
  if (sp == 0) {
    memcpy(x, p, sizeof x);
  } else if (sq == 0) {
    memcpy(x, q, sizeof x);
  } else {
    const double *n = c->normal, *o = c->v;
    double dp = (p[0] - o[0]) * n[0] + (p[1] - o[1]) * n[1] + (p[2] - o[2]) * n[2];
    double dq = (q[0] - o[0]) * n[0] + (q[1] - o[1]) * n[1] + (q[2] - o[2]) * n[2];
    double t = dp / (dp - dq);
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    if (!isfinite(t)) t = 0.5;
    for (int k = 0; k < 3; ++k)
      x[k] = p[k] + t * (q[k] - p[k]);
  }
  return crack_contains3(c, x);
}

/* 1 if the box [lo, hi] lies strictly on one side of the crack's line (2-D) or plane (3-D): its
 * corners do (exact signs), and the sign of an affine function over a box is extreme at corners. */
int pdk_crack_box_one_side(const crack *c, int dim, const double lo[3], const double hi[3]) {
  int first = 0;
  for (int k = 0; k < (1 << dim); ++k) {
    const double x[3] = {k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]};
    const int sign = pdk_crack_side(c, dim, x);
    if (sign == 0 || (k > 0 && sign != first)) return 0;
    first = sign;
  }
  return 1;
}
