/* Gmsh meshes as point clouds (src/space/points.h): one particle per element of the body's
 * dimension, sets from the physical groups. ASCII MSH 4.1 and 2.2. */
#define _POSIX_C_SOURCE 200809L /* getline, strdup */
#include "points.h"

#include "pdk/ctx.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define MAX_GROUPS PDK_POINTS_MAX_SETS
#define FIX " (save the mesh from Gmsh as ASCII MSH 4.1 or 2.2: Mesh.MshFileVersion, Mesh.Binary = 0)"

/* A whitespace-token reader that knows its line. */
typedef struct rd {
  pdk_ctx *ctx;
  const char *path;
  FILE *f;
  char *line;
  size_t cap;
  char *pos;
  long lineno;
  long bytes; /* the file's size: no count in it can exceed it */
  char tok[256];
} rd;

/* A count read from the file must fit in it (each item takes 2 bytes or more): a corrupt count
 * fails here instead of allocating for it. */
static int fits(rd *r, long count, const char *what) {
  if (count <= r->bytes / 2) return PDK_SUCCESS;
  char msg[256];
  snprintf(msg, sizeof msg, "%s (%ld) is more than the file (%ld bytes) can hold", what, count,
           r->bytes);
  return pdk_ctx_error_set(r->ctx, PDK_ERR_ARG, NULL, "%s:%ld: %s", r->path, r->lineno, msg);
}

/* The next token into r->tok; 0 at the end of the file. */
static int next(rd *r) {
  for (;;) {
    if (r->pos) {
      while (*r->pos && isspace((unsigned char)*r->pos))
        ++r->pos;
      if (*r->pos) {
        size_t n = 0;
        while (r->pos[n] && !isspace((unsigned char)r->pos[n]))
          ++n;
        const size_t k = n < sizeof r->tok - 1 ? n : sizeof r->tok - 1;
        memcpy(r->tok, r->pos, k);
        r->tok[k] = '\0';
        r->pos += n;
        return 1;
      }
    }
    if (getline(&r->line, &r->cap, r->f) < 0) return 0;
    r->lineno++;
    r->pos = r->line;
  }
}

static int fail(rd *r, const char *what) {
  return pdk_ctx_error_set(r->ctx, PDK_ERR_ARG, NULL, "%s:%ld: %s", r->path, r->lineno, what);
}

/* The next token as a whole number in [lo, hi]. */
static int get_long(rd *r, const char *what, long lo, long hi, long *out) {
  char msg[512];
  if (!next(r)) {
    snprintf(msg, sizeof msg, "the file ends where %s was expected%s", what, FIX);
    return fail(r, msg);
  }
  char *end = NULL;
  errno = 0;
  const long v = strtol(r->tok, &end, 10);
  if (end == r->tok || *end || errno || v < lo || v > hi) {
    snprintf(msg, sizeof msg, "%s is '%s'; it must be a whole number in [%ld, %ld]", what, r->tok,
             lo, hi);
    return fail(r, msg);
  }
  *out = v;
  return PDK_SUCCESS;
}

static int get_double(rd *r, const char *what, double *out) {
  char msg[512];
  if (!next(r)) {
    snprintf(msg, sizeof msg, "the file ends where %s was expected%s", what, FIX);
    return fail(r, msg);
  }
  char *end = NULL;
  const double v = strtod(r->tok, &end);
  if (end == r->tok || *end || !isfinite(v)) {
    snprintf(msg, sizeof msg, "%s is '%s', not a finite number", what, r->tok);
    return fail(r, msg);
  }
  *out = v;
  return PDK_SUCCESS;
}

/* The next token must be `word`. */
static int expect(rd *r, const char *word) {
  char msg[512];
  if (!next(r) || strcmp(r->tok, word)) {
    snprintf(msg, sizeof msg, "'%s' expected here, found %s%s%s", word, r->tok[0] ? "'" : "",
             r->tok[0] ? r->tok : "the end of the file", r->tok[0] ? "'" : "");
    return fail(r, msg);
  }
  return PDK_SUCCESS;
}

/* Nodes of the element types pdk reads: dimension and node count (0: not read). */
static int type_nodes(long type, int *edim) {
  switch (type) {
  case 15: *edim = 0; return 1; /* point */
  case 1: *edim = 1; return 2;  /* line */
  case 2: *edim = 2; return 3;  /* triangle */
  case 3: *edim = 2; return 4;  /* quadrangle */
  case 4: *edim = 3; return 4;  /* tetrahedron */
  case 5: *edim = 3; return 8;  /* hexahedron */
  default: *edim = -1; return 0;
  }
}

typedef struct group {
  int dim;
  long tag;
  char name[256];
  uint8_t *mark; /* [num_nodes] lower-dimension groups: nodes on the group */
} group;

typedef struct entity {
  int dim;
  long tag;
  int num_phys;
  long phys[4];
} entity;

typedef struct mesh {
  long num_nodes, max_tag;
  double *xyz;    /* [num_nodes][3] */
  int32_t *index; /* [max_tag + 1] node tag -> index, -1 */
  group groups[MAX_GROUPS];
  int num_groups;
  char names_dim[MAX_GROUPS];
  long names_tag[MAX_GROUPS];
  char names[MAX_GROUPS][256];
  int num_names;
  entity *ents;
  long num_ents;
} mesh;

static int group_of(rd *r, mesh *m, int dim, long tag, long num_nodes, group **out) {
  for (int g = 0; g < m->num_groups; ++g)
    if (m->groups[g].dim == dim && m->groups[g].tag == tag) {
      *out = &m->groups[g];
      return PDK_SUCCESS;
    }
  char msg[256];
  if (m->num_groups == MAX_GROUPS) {
    snprintf(msg, sizeof msg, "more than %d physical groups", MAX_GROUPS);
    return fail(r, msg);
  }
  group *g = &m->groups[m->num_groups++];
  memset(g, 0, sizeof *g);
  g->dim = dim;
  g->tag = tag;
  snprintf(g->name, sizeof g->name, "physical_%d_%ld", dim, tag);
  for (int k = 0; k < m->num_names; ++k)
    if (m->names_dim[k] == dim && m->names_tag[k] == tag)
      snprintf(g->name, sizeof g->name, "%s", m->names[k]);
  g->mark = calloc((size_t)num_nodes + 1, 1);
  if (!g->mark) return pdk_ctx_error_set(r->ctx, PDK_ERR_MEMORY, NULL, "out of memory");
  *out = g;
  return PDK_SUCCESS;
}

/* Skips a section up to its $End line. */
static int skip_section(rd *r, const char *name) {
  char end[300];
  snprintf(end, sizeof end, "$End%s", name + 1);
  while (next(r))
    if (!strcmp(r->tok, end)) return PDK_SUCCESS;
  char msg[400];
  snprintf(msg, sizeof msg, "the section %s has no %s line", name, end);
  return fail(r, msg);
}

static int read_names(rd *r, mesh *m) {
  long n;
  PDK_CALL(get_long(r, "the number of physical names", 0, MAX_GROUPS, &n));
  for (long k = 0; k < n; ++k) {
    long dim, tag;
    PDK_CALL(get_long(r, "a physical name's dimension", 0, 3, &dim));
    PDK_CALL(get_long(r, "a physical name's tag", 1, 2147483647L, &tag));
    char *q = strchr(r->pos, '"'), *e = q ? strchr(q + 1, '"') : NULL;
    if (!q || !e) return fail(r, "a physical name is a quoted string, \"name\"");
    const size_t len = (size_t)(e - q - 1);
    if (len == 0 || len > 255) return fail(r, "a physical name has 1 to 255 characters");
    for (const char *c = q + 1; c < e; ++c)
      if (!isalnum((unsigned char)*c) && *c != '_' && *c != '-' && *c != '.') {
        char msg[512];
        snprintf(msg, sizeof msg,
                 "the physical name \"%.*s\" names a set or material: letters, digits, _ - . "
                 "only; rename the group",
                 (int)len, q + 1);
        return fail(r, msg);
      }
    m->names_dim[m->num_names] = (char)dim;
    m->names_tag[m->num_names] = tag;
    memcpy(m->names[m->num_names], q + 1, len);
    m->names[m->num_names][len] = '\0';
    m->num_names++;
    r->pos = e + 1;
  }
  return expect(r, "$EndPhysicalNames");
}

static int read_entities(rd *r, mesh *m) {
  long count[4], total = 0;
  for (int d = 0; d < 4; ++d) {
    PDK_CALL(get_long(r, "a number of entities", 0, 100000000L, &count[d]));
    total += count[d];
  }
  PDK_CALL(fits(r, total, "the number of entities"));
  m->ents = calloc((size_t)total + 1, sizeof *m->ents);
  if (!m->ents) return pdk_ctx_error_set(r->ctx, PDK_ERR_MEMORY, NULL, "out of memory");
  for (int d = 0; d < 4; ++d)
    for (long k = 0; k < count[d]; ++k) {
      entity *e = &m->ents[m->num_ents++];
      e->dim = d;
      PDK_CALL(get_long(r, "an entity's tag", 1, 2147483647L, &e->tag));
      double box;
      for (int c = 0; c < (d == 0 ? 3 : 6); ++c)
        PDK_CALL(get_double(r, "an entity's bounding box", &box));
      long np, nb, t;
      PDK_CALL(get_long(r, "an entity's number of physical tags", 0, 1000000L, &np));
      for (long q = 0; q < np; ++q) {
        PDK_CALL(get_long(r, "a physical tag", -2147483647L, 2147483647L, &t));
        if (e->num_phys < 4) e->phys[e->num_phys++] = labs(t);
        else return fail(r, "an entity in more than 4 physical groups");
      }
      if (d > 0) {
        PDK_CALL(get_long(r, "an entity's number of bounding entities", 0, 100000000L, &nb));
        for (long q = 0; q < nb; ++q)
          PDK_CALL(get_long(r, "a bounding entity's tag", -2147483647L, 2147483647L, &t));
      }
    }
  return expect(r, "$EndEntities");
}

static int alloc_nodes(rd *r, mesh *m, long num, long max_tag) {
  PDK_CALL(fits(r, num, "the number of nodes"));
  if (max_tag > 16 * num + 1000000)
    return fail(r, "the node tags are sparse (the largest is far above the number of nodes); "
                   "renumber the mesh (Gmsh: Mesh.RenumberNodes)");
  m->num_nodes = num;
  m->max_tag = max_tag;
  m->xyz = malloc((size_t)(num + 1) * 3 * sizeof(double));
  m->index = malloc((size_t)(max_tag + 1) * sizeof(int32_t));
  if (!m->xyz || !m->index)
    return pdk_ctx_error_set(r->ctx, PDK_ERR_MEMORY, NULL, "out of memory for %ld nodes", num);
  for (long t = 0; t <= max_tag; ++t)
    m->index[t] = -1;
  return PDK_SUCCESS;
}

static int set_node(rd *r, mesh *m, long tag, long idx) {
  if (tag > m->max_tag) return fail(r, "a node tag exceeds the largest tag the section announces");
  if (m->index[tag] >= 0) return fail(r, "a node tag is given twice");
  m->index[tag] = (int32_t)idx;
  return PDK_SUCCESS;
}

static int read_nodes(rd *r, mesh *m, int v4) {
  long blocks = 1, num, lo = 1, hi;
  if (v4) {
    PDK_CALL(get_long(r, "the number of node blocks", 0, 100000000L, &blocks));
    PDK_CALL(get_long(r, "the number of nodes", 1, 1000000000L, &num));
    PDK_CALL(get_long(r, "the smallest node tag", 0, 2147483647L, &lo));
    PDK_CALL(get_long(r, "the largest node tag", lo, 2147483647L, &hi));
    PDK_CALL(alloc_nodes(r, m, num, hi));
  } else {
    PDK_CALL(get_long(r, "the number of nodes", 1, 1000000000L, &num));
    PDK_CALL(alloc_nodes(r, m, num, 16 * num + 1000000));
  }
  long idx = 0;
  for (long b = 0; b < blocks; ++b) {
    long in_block = num, dim, tag, par = 0;
    if (v4) {
      PDK_CALL(get_long(r, "a node block's dimension", 0, 3, &dim));
      PDK_CALL(get_long(r, "a node block's entity tag", 0, 2147483647L, &tag));
      PDK_CALL(get_long(r, "a node block's parametric flag", 0, 1, &par));
      PDK_CALL(get_long(r, "a node block's number of nodes", 0, num - idx, &in_block));
      if (par) return fail(r, "parametric node coordinates are not read; save without them");
      for (long k = 0; k < in_block; ++k) {
        PDK_CALL(get_long(r, "a node tag", 1, m->max_tag, &tag));
        PDK_CALL(set_node(r, m, tag, idx + k));
      }
    }
    for (long k = 0; k < in_block; ++k) {
      if (!v4) {
        PDK_CALL(get_long(r, "a node tag", 1, m->max_tag, &tag));
        PDK_CALL(set_node(r, m, tag, idx + k));
      }
      for (int c = 0; c < 3; ++c)
        PDK_CALL(get_double(r, "a node coordinate", &m->xyz[3 * (idx + k) + c]));
    }
    idx += in_block;
  }
  if (idx != num) return fail(r, "the node blocks hold fewer nodes than the section announces");
  return expect(r, "$EndNodes");
}

/* Centroid and measure (length, area or volume) of an element of nn nodes at x[nn][3]. */
static void measure(int edim, int nn, const double (*x)[3], double c[3], double *size) {
  static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
  static const int tet[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  double total = 0.0, s[3] = {0, 0, 0};
  if (edim == 2) {
    for (int t = 0; t < (nn == 4 ? 2 : 1); ++t) {
      const double *a = x[tri[t][0]], *b = x[tri[t][1]], *d = x[tri[t][2]];
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const double v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
      const double w[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                           u[0] * v[1] - u[1] * v[0]};
      const double area = 0.5 * sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      total += area;
      for (int k = 0; k < 3; ++k)
        s[k] += area * (a[k] + b[k] + d[k]) / 3.0;
    }
  } else {
    for (int t = 0; t < (nn == 8 ? 6 : 1); ++t) {
      const int *q = nn == 8 ? tet[t] : (const int[4]){0, 1, 2, 3};
      const double *a = x[q[0]];
      double e[3][3];
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          e[j][k] = x[q[j + 1]][k] - a[k];
      const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                         e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                         e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
      const double vol = fabs(det) / 6.0;
      total += vol;
      for (int k = 0; k < 3; ++k)
        s[k] += vol * (a[k] + x[q[1]][k] + x[q[2]][k] + x[q[3]][k]) / 4.0;
    }
  }
  *size = total;
  for (int k = 0; k < 3; ++k)
    c[k] = total > 0 ? s[k] / total : x[0][k];
}

/* The physical tags of an element: those of its entity (4.1) or its first tag (2.2). */
static int entity_phys(const mesh *m, int dim, long tag, const long **phys) {
  for (long k = 0; k < m->num_ents; ++k)
    if (m->ents[k].dim == dim && m->ents[k].tag == tag) {
      *phys = m->ents[k].phys;
      return m->ents[k].num_phys;
    }
  return 0;
}

typedef struct body {
  long n, cap;
  double *c;        /* [cap][3] centroids */
  double *size;     /* [cap] */
  int32_t *nodes;   /* [cap][8] */
  uint64_t *groups; /* [cap] bit g: in body group g */
} body;

static int add_body_element(rd *r, body *b, const double c[3], double size, const int32_t *nodes,
                            int nn, uint64_t groups) {
  if (b->n == b->cap) {
    b->cap = b->cap ? 2 * b->cap : 4096;
    double *c2 = realloc(b->c, (size_t)b->cap * 3 * sizeof(double));
    if (c2) b->c = c2;
    double *s2 = realloc(b->size, (size_t)b->cap * sizeof(double));
    if (s2) b->size = s2;
    int32_t *n2 = realloc(b->nodes, (size_t)b->cap * 8 * sizeof(int32_t));
    if (n2) b->nodes = n2;
    uint64_t *g2 = realloc(b->groups, (size_t)b->cap * sizeof(uint64_t));
    if (g2) b->groups = g2;
    if (!c2 || !s2 || !n2 || !g2)
      return pdk_ctx_error_set(r->ctx, PDK_ERR_MEMORY, NULL, "out of memory for elements");
  }
  memcpy(b->c + 3 * b->n, c, 3 * sizeof(double));
  b->size[b->n] = size;
  for (int k = 0; k < 8; ++k)
    b->nodes[8 * b->n + k] = k < nn ? nodes[k] : -1;
  b->groups[b->n] = groups;
  b->n++;
  return PDK_SUCCESS;
}

/* One element: type, its physical tags, its node tags read from r. */
static int element(rd *r, mesh *m, body *b, int dim, long type, int num_phys, const long *phys) {
  int edim;
  const int nn = type_nodes(type, &edim);
  char msg[512];
  if (!nn) {
    snprintf(msg, sizeof msg,
             "element type %ld is not read; pdk reads first-order elements: points (15), lines "
             "(1), triangles (2), quadrangles (3), tetrahedra (4), hexahedra (5); mesh with "
             "Mesh.ElementOrder = 1",
             type);
    return fail(r, msg);
  }
  if (edim > dim) {
    snprintf(msg, sizeof msg,
             "a %d-D element in the mesh of a %d-D scene; set dimension: %d, or mesh in %d-D", edim,
             dim, edim, dim);
    return fail(r, msg);
  }
  int32_t nodes[8];
  double x[8][3];
  for (int k = 0; k < nn; ++k) {
    long tag;
    PDK_CALL(get_long(r, "a node tag of an element", 1, 2147483647L, &tag));
    if (tag > m->max_tag || m->index[tag] < 0) {
      snprintf(msg, sizeof msg, "an element names the node %ld, which $Nodes does not define",
               tag);
      return fail(r, msg);
    }
    nodes[k] = m->index[tag];
    memcpy(x[k], m->xyz + 3 * nodes[k], sizeof x[k]);
  }
  uint64_t in = 0;
  for (int q = 0; q < num_phys; ++q) {
    group *g = NULL;
    PDK_CALL(group_of(r, m, edim, phys[q], m->num_nodes, &g));
    if (edim == dim)
      in |= 1ull << (g - m->groups);
    else
      for (int k = 0; k < nn; ++k)
        g->mark[nodes[k]] = 1;
  }
  if (edim < dim) return PDK_SUCCESS;
  double c[3], size;
  measure(edim, nn, (const double(*)[3])x, c, &size);
  if (!(size > 0)) return fail(r, "an element has zero size (its nodes are degenerate)");
  return add_body_element(r, b, c, size, nodes, nn, in);
}

static int read_elements(rd *r, mesh *m, body *b, int dim, int v4) {
  long blocks = 1, num, lo, hi;
  if (!m->xyz) return fail(r, "$Elements comes before $Nodes; the nodes come first");
  if (v4) {
    PDK_CALL(get_long(r, "the number of element blocks", 0, 100000000L, &blocks));
    PDK_CALL(get_long(r, "the number of elements", 0, 2000000000L, &num));
    PDK_CALL(fits(r, num, "the number of elements"));
    PDK_CALL(get_long(r, "the smallest element tag", 0, 2147483647L, &lo));
    PDK_CALL(get_long(r, "the largest element tag", 0, 2147483647L, &hi));
    long done = 0;
    for (long k = 0; k < blocks; ++k) {
      long edim, etag, type, count, tag;
      PDK_CALL(get_long(r, "an element block's dimension", 0, 3, &edim));
      PDK_CALL(get_long(r, "an element block's entity tag", 0, 2147483647L, &etag));
      PDK_CALL(get_long(r, "an element block's element type", 1, 1000, &type));
      PDK_CALL(get_long(r, "an element block's number of elements", 0, num - done, &count));
      const long *phys = NULL;
      const int np = entity_phys(m, (int)edim, etag, &phys);
      for (long e = 0; e < count; ++e) {
        PDK_CALL(get_long(r, "an element tag", 0, 2147483647L, &tag));
        PDK_CALL(element(r, m, b, dim, type, np, phys));
      }
      done += count;
    }
  } else {
    PDK_CALL(get_long(r, "the number of elements", 0, 2000000000L, &num));
    PDK_CALL(fits(r, num, "the number of elements"));
    for (long e = 0; e < num; ++e) {
      long tag, type, ntags, t = 0, phys = 0;
      PDK_CALL(get_long(r, "an element tag", 0, 2147483647L, &tag));
      PDK_CALL(get_long(r, "an element type", 1, 1000, &type));
      PDK_CALL(get_long(r, "an element's number of tags", 0, 100, &ntags));
      for (long q = 0; q < ntags; ++q) {
        PDK_CALL(get_long(r, "an element tag", -2147483647L, 2147483647L, &t));
        if (q == 0) phys = t;
      }
      PDK_CALL(element(r, m, b, dim, type, phys > 0 ? 1 : 0, &phys));
    }
  }
  return expect(r, "$EndElements");
}

int pdk_points_read_msh(pdk_ctx *ctx, const char *path, int dim, double thickness,
                        pdk_points *out) {
  int err = PDK_SUCCESS;
  memset(out, 0, sizeof *out);
  out->dim = dim;
  mesh m;
  body b;
  memset(&m, 0, sizeof m);
  memset(&b, 0, sizeof b);
  rd r = {ctx, path, NULL, NULL, 0, NULL, 0, 0, ""};
  r.f = fopen(path, "r");
  PDK_CHECK(r.f, ctx, PDK_ERR_IO, "cannot open the mesh '%s': %s", path, strerror(errno));
  if (fseek(r.f, 0, SEEK_END) == 0) r.bytes = ftell(r.f);
  rewind(r.f);
  PDK_CHECK_GOTO(r.bytes > 0, ctx, PDK_ERR_ARG, "%s: the mesh is empty or not a regular file",
                 path);
  int v4 = 0, have_nodes = 0, have_elements = 0;
  {
    PDK_CALL_GOTO(expect(&r, "$MeshFormat"));
    PDK_CHECK_GOTO(next(&r), ctx, PDK_ERR_ARG, "%s:%ld: no version after $MeshFormat", path,
                   r.lineno);
    PDK_CHECK_GOTO(!strcmp(r.tok, "4.1") || !strcmp(r.tok, "2.2"), ctx, PDK_ERR_ARG,
                   "%s:%ld: MSH version %s is not read; pdk reads versions 4.1 and 2.2%s", path,
                   r.lineno, r.tok, FIX);
    v4 = r.tok[0] == '4';
    long binary, size;
    PDK_CALL_GOTO(get_long(&r, "the file type (0 ASCII, 1 binary)", 0, 1, &binary));
    PDK_CHECK_GOTO(!binary, ctx, PDK_ERR_ARG, "%s:%ld: a binary MSH file is not read%s", path,
                   r.lineno, FIX);
    PDK_CALL_GOTO(get_long(&r, "the data size", 4, 16, &size));
    PDK_CALL_GOTO(expect(&r, "$EndMeshFormat"));
  }
  while (next(&r)) {
    if (!strcmp(r.tok, "$PhysicalNames"))
      PDK_CALL_GOTO(read_names(&r, &m));
    else if (!strcmp(r.tok, "$Entities") && v4)
      PDK_CALL_GOTO(read_entities(&r, &m));
    else if (!strcmp(r.tok, "$Nodes")) {
      PDK_CHECK_GOTO(!have_nodes, ctx, PDK_ERR_ARG, "%s:%ld: a second $Nodes section", path,
                     r.lineno);
      PDK_CALL_GOTO(read_nodes(&r, &m, v4));
      have_nodes = 1;
    } else if (!strcmp(r.tok, "$Elements")) {
      PDK_CHECK_GOTO(!have_elements, ctx, PDK_ERR_ARG, "%s:%ld: a second $Elements section",
                     path, r.lineno);
      PDK_CALL_GOTO(read_elements(&r, &m, &b, dim, v4));
      have_elements = 1;
    } else if (r.tok[0] == '$')
      PDK_CALL_GOTO(skip_section(&r, r.tok));
    else
      PDK_CHECK_GOTO(0, ctx, PDK_ERR_ARG, "%s:%ld: '%s' outside a section; sections start with $",
                     path, r.lineno, r.tok);
  }
  PDK_CHECK_GOTO(!ferror(r.f), ctx, PDK_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
  PDK_CHECK_GOTO(have_nodes && have_elements, ctx, PDK_ERR_ARG,
                 "%s: the mesh has no %s section%s", path, have_nodes ? "$Elements" : "$Nodes",
                 FIX);
  PDK_CHECK_GOTO(b.n > 0, ctx, PDK_ERR_ARG,
                 "%s: no %d-D element (%s); a %d-D scene takes one particle per such element", path,
                 dim, dim == 2 ? "triangles or quadrangles" : "tetrahedra or hexahedra", dim);
  PDK_CHECK_GOTO(b.n <= INT32_MAX, ctx, PDK_ERR_ARG, "%s: too many elements", path);

  /* the particles, then a set per physical group */
  out->n = (pdk_index)b.n;
  for (int a = 0; a < 3; ++a) {
    out->lo[a] = INFINITY, out->hi[a] = -INFINITY;
    out->X[a] = a < dim ? malloc((size_t)b.n * sizeof(double)) : NULL;
    PDK_CHECK_GOTO(a >= dim || out->X[a], ctx, PDK_ERR_MEMORY, "out of memory");
  }
  out->volume = malloc((size_t)b.n * sizeof(double));
  PDK_CHECK_GOTO(out->volume, ctx, PDK_ERR_MEMORY, "out of memory");
  if (dim == 2) out->lo[2] = out->hi[2] = 0.0;
  for (long e = 0; e < b.n; ++e) {
    for (int a = 0; a < dim; ++a) {
      const double v = b.c[3 * e + a];
      out->X[a][e] = v;
      out->lo[a] = fmin(out->lo[a], v);
      out->hi[a] = fmax(out->hi[a], v);
    }
    PDK_CHECK_GOTO(dim == 3 || b.c[3 * e + 2] == 0.0, ctx, PDK_ERR_ARG,
                   "%s: element %ld of the body lies off the plane z = 0 (its centroid has z = "
                   "%g); a 2-D scene reads a mesh in that plane",
                   path, e, b.c[3 * e + 2]);
    out->volume[e] = dim == 2 ? b.size[e] * thickness : b.size[e];
  }
  for (int g = 0; g < m.num_groups; ++g) {
    const group *gr = &m.groups[g];
    uint8_t *s = calloc((size_t)b.n, 1);
    out->set[out->num_sets] = s;
    out->set_name[out->num_sets] = strdup(gr->name);
    out->set_body[out->num_sets] = gr->dim == dim;
    out->num_sets++;
    PDK_CHECK_GOTO(s && out->set_name[out->num_sets - 1], ctx, PDK_ERR_MEMORY, "out of memory");
    for (int q = 0; q < g; ++q)
      PDK_CHECK_GOTO(strcmp(m.groups[q].name, gr->name), ctx, PDK_ERR_ARG,
                     "%s: two physical groups are named '%s'; give each group its own name", path,
                     gr->name);
    long count = 0;
    for (long e = 0; e < b.n; ++e) {
      if (gr->dim == dim)
        s[e] = (b.groups[e] >> g) & 1;
      else
        for (int k = 0; k < 8 && b.nodes[8 * e + k] >= 0; ++k)
          s[e] |= gr->mark[b.nodes[8 * e + k]];
      count += s[e];
    }
    PDK_CHECK_GOTO(count > 0, ctx, PDK_ERR_ARG,
                   "%s: the physical group '%s' (dimension %d) touches no %d-D element; remove it "
                   "or mesh the body around it",
                   path, gr->name, gr->dim, dim);
  }
cleanup:
  if (r.f) fclose(r.f);
  free(r.line);
  free(m.xyz);
  free(m.index);
  free(m.ents);
  for (int g = 0; g < m.num_groups; ++g)
    free(m.groups[g].mark);
  free(b.c);
  free(b.size);
  free(b.nodes);
  free(b.groups);
  if (err) pdk_points_free(out);
  return err;
}
