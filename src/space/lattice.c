/* Lattice generators: square and hexagonal (2-D), simple cubic (3-D); see include/pdk/geometry.h.
 *
 * A lattice is laid out first (points per axis, counted with the very expression that later places
 * the points, so the count and the fill always agree), then filled in one parallel pass over the
 * linear point index p. Points are ordered x fastest, then y, then z:
 *
 *   square / cubic:  p = i + nx*(j + ny*k)
 *   hexagonal:       rows alternate between n_even and n_odd points (n_odd <= n_even), so a
 *                    pair of rows holds n_even + n_odd points and
 *                    p = (j/2)*(n_even + n_odd) + (j odd ? n_even : 0) + i
 *
 * Coordinates along an axis, computed by multiplication so each is one rounding from exact and does
 * not depend on how points are split among threads:
 *
 *   cell-centred (node_type 0):  x_i = lo + (i + 1/2) * spacing,  generated while x_i < hi
 *   node-type    (node_type 1):  x_i = lo + i * spacing,  i = 0 .. N,  N = round((hi - lo)/spacing)
 *   hexagonal rows:              y_j = lo_y + (j + 1/2) * h,  h = spacing * sqrt(3)/2
 *                                x_ij = lo_x + (i + 1/4) * spacing  (even j)
 *                                x_ij = lo_x + (i + 3/4) * spacing  (odd j)
 *
 * The hexagonal rows are offset by +-spacing/4 from the cell centre (instead of 0 and +spacing/2)
 * so both row kinds sit symmetrically in the box: for a box width that is a multiple of the spacing
 * every row holds the same number of points and the cell volumes tile the box exactly.
 *
 * Jitter: each coordinate moves by jitter*spacing*(2u - 1), u uniform in [0, 1) drawn from a
 * counter-based hash (splitmix64 finalizer) of (seed, i, j, k, axis). A point's jitter therefore
 * depends only on the seed and its lattice indices, never on the thread count or the fill order.
 * Jitter is applied after the inside-the-box test, so a jittered point may lie up to jitter*spacing
 * outside the box.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/pdk_impl.h"
#include "pdk/ctx.h"
#include "pdk/geometry.h"
#include "pdk/particles.h"

pdk_lattice_opts pdk_lattice_opts_default(void) {
  pdk_lattice_opts o;
  memset(&o, 0, sizeof o);
  o.type = PDK_LATTICE_SQUARE;
  for (int d = 0; d < 3; ++d) {
    o.lo[d] = 0.0;
    o.hi[d] = 1.0;
  }
  o.spacing = 1.0;
  o.jitter = 0.0;
  o.seed = 0;
  o.thickness = 1.0;
  o.node_type = 0;
  return o;
}

/* Everything the fill needs, computed once by lattice_layout. */
typedef struct lattice_layout {
  int dim;
  int hex; /* 1: hexagonal rows */
  int node_type;
  double lo[3];
  double spacing;    /* [length] */
  double row_pitch;  /* hexagonal: spacing*sqrt(3)/2 between rows [length] */
  int64_t n_axis[3]; /* points per axis; hexagonal: n_axis[0] = points in an even row */
  int64_t n_odd;     /* hexagonal: points in an odd row */
  int64_t n_rows;    /* hexagonal: number of rows (= n_axis[1]) */
  int64_t total;     /* number of points */
  double volume;     /* cell volume [length^dim, 2-D times thickness] */
  double jitter_abs; /* jitter * spacing [length] */
  uint64_t seed;
} lattice_layout;

static const char *lattice_type_name(pdk_lattice_type t) {
  switch (t) {
  case PDK_LATTICE_SQUARE: return "square";
  case PDK_LATTICE_HEX: return "hexagonal";
  case PDK_LATTICE_CUBIC: return "cubic";
  }
  return "?";
}

/* Largest point count a store can take (pdk_particles_create keeps room for padding). */
#define LATTICE_MAX_POINTS ((int64_t)INT32_MAX - PDK_PAD)

/* Number of i >= 0 with lo + (i + offset)*pitch < hi, using that exact floating-point expression.
 * The caller has checked that (hi - lo)/pitch is at most LATTICE_MAX_POINTS, so counts fit. */
static int64_t axis_count(double lo, double hi, double pitch, double offset) {
  double estimate = ceil((hi - lo) / pitch - offset);
  int64_t n = estimate > 0 ? (int64_t)estimate : 0;
  /* The estimate is off by at most one or two from rounding; settle it on the real test. */
  while (n > 0 && !(lo + ((double)(n - 1) + offset) * pitch < hi))
    --n;
  while (lo + ((double)n + offset) * pitch < hi)
    ++n;
  return n;
}

/* splitmix64 finalizer (Steele, Lea & Flood 2014): a bijective 64-bit mixer. */
static uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/* Uniform in [-1, 1) for lattice site (i, j, k), coordinate `axis`, under `seed`. */
static double jitter_unit(uint64_t seed, int64_t i, int64_t j, int64_t k, int axis) {
  uint64_t h = mix64(seed);
  h = mix64(h ^ (uint64_t)i);
  h = mix64(h ^ (uint64_t)j);
  h = mix64(h ^ (uint64_t)k);
  h = mix64(h ^ (uint64_t)axis);
  return 2.0 * ((double)(h >> 11) * 0x1.0p-53) - 1.0;
}

/* Validates opts and computes the layout. All errors are PDK_ERR_ARG and name the bad value. */
static int lattice_layout_make(pdk_ctx *ctx, const pdk_lattice_opts *o, lattice_layout *L) {
  static const char axis_name[3] = {'x', 'y', 'z'};
  memset(L, 0, sizeof *L);
  PDK_CHECK(
      o->type == PDK_LATTICE_SQUARE || o->type == PDK_LATTICE_HEX || o->type == PDK_LATTICE_CUBIC,
      ctx, PDK_ERR_ARG, "unknown lattice type %d; allowed: %d (square), %d (hexagonal), %d (cubic)",
      (int)o->type, PDK_LATTICE_SQUARE, PDK_LATTICE_HEX, PDK_LATTICE_CUBIC);
  const int dim = o->type == PDK_LATTICE_CUBIC ? 3 : 2;
  const int hex = o->type == PDK_LATTICE_HEX;
  const char *tname = lattice_type_name(o->type);
  PDK_CHECK(isfinite(o->spacing) && o->spacing > 0, ctx, PDK_ERR_ARG,
            "lattice spacing must be a finite number > 0, got %g", o->spacing);
  PDK_CHECK(o->jitter >= 0 && o->jitter < 0.5, ctx, PDK_ERR_ARG,
            "lattice jitter must be in [0, 0.5) (a fraction of the spacing), got %g", o->jitter);
  PDK_CHECK(o->node_type == 0 || o->node_type == 1, ctx, PDK_ERR_ARG,
            "lattice node_type must be 0 (cell-centred points) or 1 (grid nodes on both faces), "
            "got %d",
            o->node_type);
  PDK_CHECK(!(hex && o->node_type), ctx, PDK_ERR_ARG,
            "node_type 1 (grid nodes on both faces) is defined for square and cubic lattices only, "
            "not for the hexagonal lattice");
  if (dim == 2)
    PDK_CHECK(isfinite(o->thickness) && o->thickness > 0, ctx, PDK_ERR_ARG,
              "2-D lattice thickness must be a finite number > 0, got %g", o->thickness);
  for (int d = 0; d < dim; ++d) {
    PDK_CHECK(isfinite(o->lo[d]) && isfinite(o->hi[d]), ctx, PDK_ERR_ARG,
              "lattice box bounds on axis %c must be finite, got lo = %g, hi = %g", axis_name[d],
              o->lo[d], o->hi[d]);
    PDK_CHECK(o->hi[d] > o->lo[d], ctx, PDK_ERR_ARG,
              "lattice box is %s on axis %c: lo = %g, hi = %g; hi must be greater than lo",
              o->hi[d] < o->lo[d] ? "inverted" : "empty", axis_name[d], o->lo[d], o->hi[d]);
  }

  const double s = o->spacing;
  L->dim = dim;
  L->hex = hex;
  L->node_type = o->node_type;
  L->spacing = s;
  L->row_pitch = s * (0.5 * sqrt(3.0));
  L->jitter_abs = o->jitter * s;
  L->seed = o->seed;
  for (int d = 0; d < dim; ++d)
    L->lo[d] = o->lo[d];

  /* Per-axis counts; first bound (hi - lo)/pitch so the integer counts cannot overflow. */
  for (int d = 0; d < dim; ++d) {
    double pitch = hex && d == 1 ? L->row_pitch : s;
    double q = (o->hi[d] - o->lo[d]) / pitch;
    PDK_CHECK(q <= (double)LATTICE_MAX_POINTS, ctx, PDK_ERR_ARG,
              "%s lattice: axis %c spans %g spacings (lo = %g, hi = %g, spacing %g), more points "
              "than the 32-bit particle index allows (%lld); increase the spacing or shrink the "
              "box",
              tname, axis_name[d], q, o->lo[d], o->hi[d], s, (long long)LATTICE_MAX_POINTS);
    if (o->node_type) {
      double nq = round(q);
      /* Relative tolerance 1e-6: far above the round-off of (hi - lo)/spacing, far below any
       * box that is really not a whole number of spacings. */
      PDK_CHECK(fabs(q - nq) <= 1e-6 * fmax(nq, 1.0), ctx, PDK_ERR_ARG,
                "node-type lattice: axis %c is %g spacings long (lo = %g, hi = %g, spacing %g); "
                "grid nodes on both faces need a whole number of spacings",
                axis_name[d], q, o->lo[d], o->hi[d], s);
      L->n_axis[d] = (int64_t)nq + 1;
    } else if (hex && d == 0) {
      L->n_axis[0] = axis_count(o->lo[0], o->hi[0], s, 0.25);
      L->n_odd = axis_count(o->lo[0], o->hi[0], s, 0.75);
    } else {
      L->n_axis[d] = axis_count(o->lo[d], o->hi[d], pitch, 0.5);
    }
  }

  /* Total, in double first (exact for these magnitudes) to detect overflow. */
  double total;
  if (hex) {
    L->n_rows = L->n_axis[1];
    int64_t n_even_rows = (L->n_rows + 1) / 2, n_odd_rows = L->n_rows / 2;
    total = (double)n_even_rows * (double)L->n_axis[0] + (double)n_odd_rows * (double)L->n_odd;
  } else {
    total = 1.0;
    for (int d = 0; d < dim; ++d)
      total *= (double)L->n_axis[d];
  }
  PDK_CHECK(total <= (double)LATTICE_MAX_POINTS, ctx, PDK_ERR_ARG,
            "%s lattice would have %.0f points, more than the 32-bit particle index allows (%lld); "
            "increase the spacing (%g) or shrink the box",
            tname, total, (long long)LATTICE_MAX_POINTS, s);
  if (dim == 2)
    PDK_CHECK(total > 0, ctx, PDK_ERR_ARG,
              "%s lattice has no point: the box [%g, %g]..[%g, %g] is too small for spacing %g "
              "(the first point lies half a spacing inside the low corner)",
              tname, o->lo[0], o->lo[1], o->hi[0], o->hi[1], s);
  else
    PDK_CHECK(total > 0, ctx, PDK_ERR_ARG,
              "%s lattice has no point: the box [%g, %g, %g]..[%g, %g, %g] is too small for "
              "spacing %g (the first point lies half a spacing inside the low corner)",
              tname, o->lo[0], o->lo[1], o->lo[2], o->hi[0], o->hi[1], o->hi[2], s);
  L->total = (int64_t)total;

  if (o->type == PDK_LATTICE_SQUARE)
    L->volume = s * s * o->thickness;
  else if (hex)
    L->volume = (0.5 * sqrt(3.0)) * s * s * o->thickness;
  else
    L->volume = s * s * s;
  return PDK_SUCCESS;
}

int pdk_lattice_count(pdk_ctx *ctx, const pdk_lattice_opts *opts, pdk_index *count) {
  pdk_lattice_opts defaults = pdk_lattice_opts_default();
  lattice_layout L;
  PDK_CHECK_ARG(count, ctx);
  *count = 0;
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CALL(lattice_layout_make(ctx, opts ? opts : &defaults, &L));
  *count = (pdk_index)L.total;
  return PDK_SUCCESS;
}

/* Lattice indices (i, j, k) of point p. */
static void lattice_site(const lattice_layout *L, int64_t p, int64_t site[3]) {
  if (L->hex) {
    int64_t pair = L->n_axis[0] + L->n_odd;
    int64_t r = p % pair;
    int odd = r >= L->n_axis[0];
    site[0] = odd ? r - L->n_axis[0] : r;
    site[1] = 2 * (p / pair) + odd;
    site[2] = 0;
  } else {
    site[0] = p % L->n_axis[0];
    int64_t q = p / L->n_axis[0];
    site[1] = L->dim == 3 ? q % L->n_axis[1] : q;
    site[2] = L->dim == 3 ? q / L->n_axis[1] : 0;
  }
}

/* Unjittered coordinate `axis` of lattice site `site`. */
static double lattice_coord(const lattice_layout *L, const int64_t site[3], int axis) {
  if (L->hex) {
    if (axis == 1) return L->lo[1] + ((double)site[1] + 0.5) * L->row_pitch;
    return L->lo[0] + ((double)site[0] + ((site[1] & 1) ? 0.75 : 0.25)) * L->spacing;
  }
  double offset = L->node_type ? 0.0 : 0.5;
  return L->lo[axis] + ((double)site[axis] + offset) * L->spacing;
}

int pdk_lattice_create(pdk_ctx *ctx, const pdk_lattice_opts *opts, pdk_particles **out) {
  pdk_lattice_opts defaults = pdk_lattice_opts_default();
  lattice_layout layout;
  pdk_particles *p = NULL;
  PDK_CHECK_ARG(out, ctx);
  *out = NULL;
  PDK_CHECK_ARG(ctx, NULL);
  PDK_CALL(lattice_layout_make(ctx, opts ? opts : &defaults, &layout));
  PDK_CALL(pdk_particles_create(ctx, layout.dim, (pdk_index)layout.total, &p));

  /* X[axis]: [n_pad] each; volume: [n_pad]; padding entries stay zero. id is 0..n-1 from create. */
  double *X[3] = {pdk_particles_X(p, 0), pdk_particles_X(p, 1),
                  layout.dim == 3 ? pdk_particles_X(p, 2) : NULL};
  double *volume = pdk_particles_volume(p);
  const lattice_layout *L = &layout;
  const pdk_index n = (pdk_index)layout.total;
  const int dim = layout.dim;
  const int nthreads = ctx->num_threads;
#pragma omp parallel for default(none) shared(L, X, volume, n, dim) schedule(static)               \
    num_threads(nthreads)
  for (pdk_index ip = 0; ip < n; ++ip) {
    int64_t site[3];
    lattice_site(L, ip, site);
    for (int axis = 0; axis < dim; ++axis) {
      double x = lattice_coord(L, site, axis);
      if (L->jitter_abs > 0)
        x += L->jitter_abs * jitter_unit(L->seed, site[0], site[1], site[2], axis);
      X[axis][ip] = x;
    }
    volume[ip] = L->volume;
  }
  *out = p;
  return PDK_SUCCESS;
}
