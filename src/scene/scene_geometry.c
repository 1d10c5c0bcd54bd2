/* Scene loading, step 3 (src/scene/scene.c): geometry (a lattice over a box, or a point cloud file),
 * holes, notches, pre-cracks and the named sets, resolved into the scene's lattice options and
 * regions (src/scene/scene_load.h).
 */
#include "space/points.h"
#include "scene_load.h"
#include "pdk/ctx.h"
#include "pdk/geometry.h"
#include "pdk/scene.h"

static int check_point(loader *ld, const char *key, const double *v) {
  for (int a = 0; a < ld->s->dim; ++a)
    REQUIRE(ld, isfinite(v[a]), key, "entry %d is %g; coordinates must be finite numbers", a, v[a]);
  return PDK_SUCCESS;
}

static void fmt_point(char *buf, size_t len, int dim, const double *v) {
  if (dim == 2)
    snprintf(buf, len, "[%g, %g]", v[0], v[1]);
  else
    snprintf(buf, len, "[%g, %g, %g]", v[0], v[1], v[2]);
}

/* Region kind of an sc_region: fills out->region (and its polygon vertices) and out->key.
 * `base` is the region's key path ("geometry.holes[0]", "sets[1]"). */
int pdk_scene_region_resolve(loader *ld, const sc_region *r, const char *base, int allow_halfspace,
                             pdk_scene_region *out) {
  const int dim = ld->s->dim;
  const char *kinds[6] = {"box", "disk", "ball", "halfspace", "polygon", "cylinder"};
  const void *given[6] = {r->box, r->disk, r->ball, r->halfspace, r->polygon, r->cylinder};
  int which = -1, count = 0;
  for (int k = 0; k < 6; ++k)
    if (given[k]) {
      if (which >= 0 && count == 1)
        FAIL(ld, base,
             "gives both %s and %s; give exactly one region: box, disk (ball), "
             "halfspace, polygon (2-D) or cylinder (3-D)",
             kinds[which], kinds[k]);
      which = k;
      ++count;
    }
  REQUIRE(ld, which >= 0, base,
          "gives no region; give one of box, disk (2-D) or ball, halfspace, "
          "polygon (2-D), cylinder (3-D)");
  snprintf(out->key, sizeof out->key, "%s.%s", base, kinds[which]);
  char sub[KEY_MAX];
  switch (which) {
  case 0:
    snprintf(sub, sizeof sub, "%s.lo", out->key);
    PDK_CALL(check_point(ld, sub, r->box->lo));
    snprintf(sub, sizeof sub, "%s.hi", out->key);
    PDK_CALL(check_point(ld, sub, r->box->hi));
    for (int a = 0; a < dim; ++a)
      REQUIRE(ld, r->box->lo[a] <= r->box->hi[a], sub,
              "must be >= lo on every axis; axis %d has lo %g > hi %g", a, r->box->lo[a],
              r->box->hi[a]);
    out->region = pdk_region_box(r->box->lo, r->box->hi);
    break;
  case 1:
  case 2: {
    const sc_ball *b = which == 1 ? r->disk : r->ball;
    snprintf(sub, sizeof sub, "%s.center", out->key);
    PDK_CALL(check_point(ld, sub, b->center));
    snprintf(sub, sizeof sub, "%s.radius", out->key);
    REQUIRE(ld, isfinite(b->radius) && b->radius > 0, sub, "must be > 0, got %g", b->radius);
    out->region = pdk_region_ball(b->center, b->radius);
    break;
  }
  case 3:
    REQUIRE(ld, allow_halfspace, out->key,
            "a half-space is unbounded, so it cannot be a hole; use geometry.notches for cuts "
            "that reach the boundary");
    snprintf(sub, sizeof sub, "%s.point", out->key);
    PDK_CALL(check_point(ld, sub, r->halfspace->point));
    snprintf(sub, sizeof sub, "%s.normal", out->key);
    PDK_CALL(check_point(ld, sub, r->halfspace->normal));
    {
      double n2 = 0;
      for (int a = 0; a < dim; ++a)
        n2 += r->halfspace->normal[a] * r->halfspace->normal[a];
      REQUIRE(ld, n2 > 0, sub, "must not be zero; it points out of the half-space");
    }
    out->region = pdk_region_halfspace(r->halfspace->point, r->halfspace->normal);
    break;
  case 4: {
    REQUIRE(ld, dim == 2, out->key, "a polygon is a 2-D region; in 3-D use box, ball or halfspace");
    int nv = (int)r->polygon->vertices_count;
    out->vertices = malloc((size_t)nv * 2 * sizeof(double));
    if (!out->vertices)
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for a polygon");
    for (int v = 0; v < nv; ++v) {
      snprintf(sub, sizeof sub, "%s.vertices[%d]", out->key, v);
      PDK_CALL(check_point(ld, sub, r->polygon->vertices[v]));
      out->vertices[2 * v] = r->polygon->vertices[v][0];
      out->vertices[2 * v + 1] = r->polygon->vertices[v][1];
    }
    out->region = pdk_region_polygon(out->vertices, nv);
    break;
  }
  case 5: {
    REQUIRE(ld, dim == 3, out->key,
            "a cylinder is a 3-D region; in 2-D use a box (a rectangle) or a polygon");
    const sc_cylinder *c = r->cylinder;
    for (int e = 0; e < 2; ++e) {
      snprintf(sub, sizeof sub, "%s.axis[%d]", out->key, e);
      PDK_CALL(check_point(ld, sub, c->axis[e]));
    }
    double len2 = 0;
    for (int a = 0; a < 3; ++a)
      len2 += (c->axis[1][a] - c->axis[0][a]) * (c->axis[1][a] - c->axis[0][a]);
    snprintf(sub, sizeof sub, "%s.axis", out->key);
    REQUIRE(ld, len2 > 0, sub,
            "has zero length: both ends are [%g, %g, %g]; give the two end points of the axis, "
            "[[x0, y0, z0], [x1, y1, z1]]",
            c->axis[0][0], c->axis[0][1], c->axis[0][2]);
    snprintf(sub, sizeof sub, "%s.radius", out->key);
    REQUIRE(ld, isfinite(c->radius) && c->radius > 0, sub, "must be > 0, got %g", c->radius);
    out->region = pdk_region_cylinder(c->axis[0], c->axis[1], c->radius);
    break;
  }
  }
  out->region.invert = r->invert ? 1 : 0;
  int err = pdk_region_check(ld->ctx, dim, &out->region);
  if (err) return pdk_scene_blame(ld->s, ld->ctx, err, out->key);
  return PDK_SUCCESS;
}

/* A hole must leave material and lie inside the body's box. */
static int hole_check(loader *ld, const pdk_scene_region *h) {
  const int dim = ld->s->dim;
  const double *blo = ld->s->lattice.lo, *bhi = ld->s->lattice.hi;
  char lo_s[96], hi_s[96];
  fmt_point(lo_s, sizeof lo_s, dim, blo);
  fmt_point(hi_s, sizeof hi_s, dim, bhi);
  int corners_in = 1;
  for (int m = 0; m < (1 << dim); ++m) {
    double x[3];
    for (int a = 0; a < dim; ++a)
      x[a] = (m >> a) & 1 ? bhi[a] : blo[a];
    corners_in &= pdk_region_contains(&h->region, dim, x);
  }
  REQUIRE(ld, !corners_in, h->key,
          "covers the whole body (geometry.box %s..%s), so nothing would remain; a hole must "
          "leave material",
          lo_s, hi_s);
  double rlo[3] = {0, 0, 0}, rhi[3] = {0, 0, 0};
  const pdk_region *r = &h->region;
  for (int a = 0; a < dim; ++a) {
    switch (r->kind) {
    case PDK_REGION_BOX:
      rlo[a] = r->lo[a];
      rhi[a] = r->hi[a];
      break;
    case PDK_REGION_BALL:
      rlo[a] = r->center[a] - r->radius;
      rhi[a] = r->center[a] + r->radius;
      break;
    case PDK_REGION_POLYGON:
      rlo[a] = rhi[a] = r->vertices[a];
      for (int v = 1; v < r->num_vertices; ++v) {
        rlo[a] = fmin(rlo[a], r->vertices[2 * v + a]);
        rhi[a] = fmax(rhi[a], r->vertices[2 * v + a]);
      }
      break;
    case PDK_REGION_CYLINDER: {
      /* the two end disks' extent: r sqrt(1 - e_a^2) about each end, e the axis' direction */
      double len2 = 0;
      for (int b = 0; b < 3; ++b)
        len2 += (r->p1[b] - r->p0[b]) * (r->p1[b] - r->p0[b]);
      const double e = (r->p1[a] - r->p0[a]) / sqrt(len2);
      const double w = r->radius * sqrt(fmax(0.0, 1.0 - e * e));
      rlo[a] = fmin(r->p0[a], r->p1[a]) - w;
      rhi[a] = fmax(r->p0[a], r->p1[a]) + w;
      break;
    }
    case PDK_REGION_HALFSPACE: break;
    }
  }
  for (int a = 0; a < dim; ++a)
    REQUIRE(ld, rlo[a] >= blo[a] && rhi[a] <= bhi[a], h->key,
            "reaches outside the body (geometry.box %s..%s): it spans [%g, %g] on axis %c; a hole "
            "must lie inside the box (use geometry.notches for cuts that reach the boundary)",
            lo_s, hi_s, rlo[a], rhi[a], "xyz"[a]);
  return PDK_SUCCESS;
}

/* geometry.holes, notches and precracks, over the body (lattice or cloud) resolved before. */
static int resolve_cuts(loader *ld, const sc_geometry *g) {
  pdk_scene *s = ld->s;
  const int dim = s->dim;
  s->num_holes = (int)g->holes_count;
  s->num_notches = (int)g->notches_count;
  s->holes = calloc(g->holes_count + 1, sizeof *s->holes);
  s->notches = calloc(g->notches_count + 1, sizeof *s->notches);
  if (!s->holes || !s->notches)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for holes");
  for (int k = 0; k < s->num_holes; ++k) {
    PDK_CALL(pdk_scene_region_resolve(ld, &g->holes[k], K(ld, "geometry.holes[%d]", k), 0,
                                      &s->holes[k]));
    PDK_CALL(hole_check(ld, &s->holes[k]));
  }
  for (int k = 0; k < s->num_notches; ++k)
    PDK_CALL(pdk_scene_region_resolve(ld, &g->notches[k], K(ld, "geometry.notches[%d]", k), 1,
                                      &s->notches[k]));

  /* Pre-cracks: segments in 2-D, planar polygons in 3-D. */
  size_t nvert = 0;
  for (unsigned k = 0; k < g->precracks_count; ++k)
    nvert += g->precracks[k].segment_count + g->precracks[k].polygon_count;
  s->num_precracks = (int)g->precracks_count;
  s->precracks = calloc(g->precracks_count + 1, sizeof *s->precracks);
  s->crack_vertices = malloc((nvert + 1) * 3 * sizeof(double));
  if (!s->precracks || !s->crack_vertices)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for pre-cracks");
  double *v = s->crack_vertices;
  for (int k = 0; k < s->num_precracks; ++k) {
    const sc_precrack *c = &g->precracks[k];
    const char *base = K(ld, "geometry.precracks[%d]", k);
    REQUIRE(ld, !(c->segment && c->polygon), base,
            "gives both segment and polygon; a 2-D "
            "pre-crack is a segment, a 3-D one a polygon");
    REQUIRE(ld, c->segment || c->polygon, base, "gives no crack; give %s",
            dim == 2 ? "segment: [[x0, y0], [x1, y1]]" : "polygon: [[x, y, z], ...] (>= 3 points)");
    if (dim == 2)
      REQUIRE(ld, c->segment, K(ld, "geometry.precracks[%d].polygon", k),
              "a 2-D pre-crack is a segment: [[x0, y0], [x1, y1]]");
    else
      REQUIRE(ld, c->polygon, K(ld, "geometry.precracks[%d].segment", k),
              "a 3-D pre-crack is a planar polygon: [[x, y, z], ...] with >= 3 points");
    const double(*pts)[3] = (const double(*)[3])(c->segment ? c->segment : c->polygon);
    int np = (int)(c->segment ? c->segment_count : c->polygon_count);
    char sub[KEY_MAX];
    snprintf(sub, sizeof sub, "geometry.precracks[%d].%s", k, c->segment ? "segment" : "polygon");
    for (int p = 0; p < np; ++p) {
      char pk[KEY_MAX + 16];
      snprintf(pk, sizeof pk, "%s[%d]", sub, p);
      PDK_CALL(check_point(ld, pk, pts[p]));
      for (int a = 0; a < dim; ++a)
        v[p * dim + a] = pts[p][a];
    }
    if (dim == 2) {
      double dx = v[2] - v[0], dy = v[3] - v[1];
      REQUIRE(ld, dx * dx + dy * dy > 0, sub, "has zero length; give two different end points");
    }
    s->precracks[k].num_vertices = np;
    s->precracks[k].vertices = v;
    v += (size_t)np * (size_t)dim;
  }
  return PDK_SUCCESS;
}

/* geometry.points or geometry.mesh: the body is the particles of a CSV or HDF5 file, or one
 * particle per element of a Gmsh mesh (src/space/points.h), its path relative to the scene's
 * folder. geometry.spacing stays the nominal spacing (horizon = horizon_factor x spacing); box,
 * lattice, jitter and seed describe a lattice and are refused, as is giving both. */
static int resolve_points(loader *ld, const sc_geometry *g) {
  pdk_scene *s = ld->s;
  const int mesh = g->mesh != NULL;
  const char *key = mesh ? "geometry.mesh" : "geometry.points";
  const char *file = mesh ? g->mesh : g->points;
  s->points_key = key;
  REQUIRE(ld, !(has(ld, "geometry.points") && has(ld, "geometry.mesh")), "geometry.mesh",
          "and geometry.points both give the particles; remove one of them");
  const char *lattice_keys[] = {"geometry.box", "geometry.lattice", "geometry.jitter",
                                "geometry.seed"};
  for (int k = 0; k < 4; ++k)
    REQUIRE(ld, !has(ld, lattice_keys[k]), lattice_keys[k],
            "describes a lattice, but %s gives the particles; remove one of them", key);
  char path[8192];
  if (file[0] == '/' || !strchr(s->path, '/'))
    snprintf(path, sizeof path, "%s", file);
  else
    snprintf(path, sizeof path, "%.*s/%s", (int)(strrchr(s->path, '/') - s->path), s->path,
             file);
  s->points = calloc(1, sizeof *s->points);
  if (!s->points) return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  const double thickness = s->dim == 2 ? s->lattice.thickness : 1.0;
  const size_t plen = strlen(path);
  const int h5 = (plen > 3 && !strcmp(path + plen - 3, ".h5")) ||
                 (plen > 5 && !strcmp(path + plen - 5, ".hdf5"));
  int err = mesh ? pdk_points_read_msh(ld->ctx, path, s->dim, thickness, s->points)
             : h5 ? pdk_points_read_h5(ld->ctx, path, s->dim, s->points)
                  : pdk_points_read_csv(ld->ctx, path, s->dim, thickness, s->points);
  if (err) {
    free(s->points);
    s->points = NULL;
    return pdk_scene_blame(s, ld->ctx, err, key);
  }
  s->points->path = strdup(path);
  if (!s->points->path) return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory");
  s->num_points = s->points->n;
  memcpy(s->lattice.lo, s->points->lo, sizeof s->lattice.lo);
  memcpy(s->lattice.hi, s->points->hi, sizeof s->lattice.hi);
  return resolve_cuts(ld, g);
}

int pdk_scene_resolve_geometry(loader *ld, const sc_geometry *g) {
  pdk_scene *s = ld->s;
  const int dim = s->dim;
  pdk_lattice_opts *lo = &s->lattice;
  *lo = pdk_lattice_opts_default();
  if (has(ld, "geometry.lattice")) {
    lo->type = (pdk_lattice_type)g->lattice;
    REQUIRE(ld, (dim == 3) == (lo->type == PDK_LATTICE_CUBIC), "geometry.lattice",
            "'%s' is a %d-D lattice but dimension is %d; use %s",
            pdk_scene_lattice_names[g->lattice].str, lo->type == PDK_LATTICE_CUBIC ? 3 : 2, dim,
            dim == 2 ? "square or hex" : "cubic");
  } else {
    lo->type = dim == 2 ? PDK_LATTICE_SQUARE : PDK_LATTICE_CUBIC;
  }
  REQUIRE(ld, isfinite(g->spacing) && g->spacing > 0, "geometry.spacing",
          "must be > 0, got %g; the lattice spacing is a length", g->spacing);
  lo->spacing = g->spacing;
  s->horizon_factor = has(ld, "geometry.horizon_factor") ? g->horizon_factor : 3.015;
  REQUIRE(ld, isfinite(s->horizon_factor) && s->horizon_factor > 1, "geometry.horizon_factor",
          "must be > 1, got %g; the horizon is horizon_factor x spacing (3.015 is usual)",
          s->horizon_factor);
  s->horizon = s->horizon_factor * g->spacing;
  lo->jitter = g->jitter;
  REQUIRE(ld, isfinite(g->jitter) && g->jitter >= 0 && g->jitter < 0.5, "geometry.jitter",
          "must be in [0, 0.5) (a fraction of the spacing), got %g", g->jitter);
  long seed = 1;
  if (has(ld, "geometry.seed"))
    PDK_CALL(check_whole(ld, "geometry.seed", g->seed, 0, 9007199254740992.0, &seed));
  lo->seed = (uint64_t)seed;
  if (has(ld, "geometry.thickness")) {
    REQUIRE(ld, dim == 2, "geometry.thickness",
            "only 2-D scenes have a thickness (dimension is 3); remove it");
    REQUIRE(ld, isfinite(g->thickness) && g->thickness > 0, "geometry.thickness",
            "must be > 0, got %g (the out-of-plane thickness, a length)", g->thickness);
    lo->thickness = g->thickness;
  }
  if (has(ld, "geometry.points") || has(ld, "geometry.mesh")) return resolve_points(ld, g);
  REQUIRE(ld, has(ld, "geometry.box"), "geometry",
          "has no body: give geometry.box (a lattice over the box), geometry.points (a point "
          "cloud file) or geometry.mesh (a Gmsh mesh)");
  PDK_CALL(check_point(ld, "geometry.box.lo", g->box.lo));
  PDK_CALL(check_point(ld, "geometry.box.hi", g->box.hi));
  for (int a = 0; a < dim; ++a)
    REQUIRE(ld, g->box.hi[a] > g->box.lo[a], "geometry.box.hi",
            "must exceed lo on every axis; axis %c has lo %g, hi %g", "xyz"[a], g -> box.lo[a],
            g->box.hi[a]);
  memcpy(lo->lo, g->box.lo, sizeof lo->lo);
  memcpy(lo->hi, g->box.hi, sizeof lo->hi);
  pdk_index count = 0;
  int err = pdk_lattice_count(ld->ctx, lo, &count);
  s->num_points = count;
  if (err) {
    /* Too many points: the spacing is the usual culprit; too few: the box. */
    double cells = 1;
    for (int a = 0; a < dim; ++a)
      cells *= (g->box.hi[a] - g->box.lo[a]) / g->spacing;
    return pdk_scene_blame(s, ld->ctx, err, cells > 1e9 ? "geometry.spacing" : "geometry.box");
  }

  return resolve_cuts(ld, g);
}

int pdk_scene_resolve_sets(loader *ld, const sc_scene *d) {
  pdk_scene *s = ld->s;
  s->sets = calloc(d->sets_count + (s->points ? (size_t)s->points->num_sets : 0) + 1,
                   sizeof *s->sets);
  if (!s->sets)
    return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for sets");
  for (int k = 0; k < (int)d->sets_count; ++k) {
    const sc_region *r = &d->sets[k];
    const char *nk = K(ld, "sets[%d].name", k);
    REQUIRE(ld, valid_name(r->name), nk,
            "'%s' is not a valid set name; use 1 to %d letters, digits, '_', '-' or '.'", r->name,
            SC_NAME_MAX);
    REQUIRE(
        ld, strcmp(r->name, "all"), nk,
        "'all' is reserved (it means every particle in boundary conditions); pick another name");
    int prev = find_set(s, r->name);
    REQUIRE(ld, prev < 0, nk, "the set '%s' is already defined by sets[%d]; set names are unique",
            r->name, prev);
    pdk_scene_region *out = &s->sets[k];
    out->name = strdup(r->name);
    size_t flen = strlen(r->name) + 5;
    out->field = malloc(flen);
    s->num_sets = k + 1;
    if (!out->name || !out->field)
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for sets");
    snprintf(out->field, flen, "set:%s", r->name);
    PDK_CALL(pdk_scene_region_resolve(ld, r, K(ld, "sets[%d]", k), 1, out));
    /* The set's messages name the set entry, whose line is the start of "- name: ...". */
    snprintf(out->key, sizeof out->key, "sets[%d]", k);
  }
  /* then the set:<name> columns of a point cloud */
  const pdk_points *pts = s->points;
  for (int k = 0; pts && k < pts->num_sets; ++k) {
    const char *name = pts->set_name[k];
    char label[300]; /* what defines the set, for messages */
    if (!strcmp(s->points_key, "geometry.mesh"))
      snprintf(label, sizeof label, "physical group '%s'", name);
    else
      snprintf(label, sizeof label, "column set:%s", name);
    REQUIRE(ld, valid_name(name) && strcmp(name, "all"), s->points_key,
            "the %s names no valid set ('all' is reserved; 1 to %d letters, digits, '_', '-' "
            "or '.')",
            label, SC_NAME_MAX);
    const int prev = find_set(s, name);
    REQUIRE(ld, prev < 0, s->points_key,
            "the %s defines the set that sets[%d] defines too; rename one", label, prev);
    pdk_index count = 0;
    for (pdk_index i = 0; i < pts->n; ++i)
      count += pts->set[k][i];
    REQUIRE(ld, count > 0, s->points_key,
            "the %s selects no particle (every value is 0); remove it or mark members",
            label);
    pdk_scene_region *out = &s->sets[s->num_sets];
    memset(out, 0, sizeof *out);
    out->name = strdup(name);
    const size_t flen = strlen(name) + 5;
    out->field = malloc(flen);
    if (out->field) snprintf(out->field, flen, "set:%s", name);
    out->from_points = 1;
    s->num_sets++;
    if (!out->name || !out->field)
      return pdk_ctx_error_set(ld->ctx, PDK_ERR_MEMORY, __func__, "out of memory for sets");
    snprintf(out->key, sizeof out->key, "%s", s->points_key);
  }
  return PDK_SUCCESS;
}
