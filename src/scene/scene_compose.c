/* A scene's YAML document composed from libyaml's events (for the scene file and for each
 * override's value), instead of libyaml's document loader, so that the limits are checked while
 * parsing: the nesting depth (libyaml's scanner takes time quadratic in the depth, so the parse
 * stops at the limit), the number of values with aliases expanded, aliases to an unfinished anchor
 * (recursive), and lists or mappings used as keys (src/scene/scene_yaml.c, src/scene/scene_yaml.h).
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "scene_yaml.h"
#include "pdk/ctx.h"

static int syntax_error(pdk_ctx *ctx, const char *file, const yaml_parser_t *ps) {
  const char *problem = ps->problem ? ps->problem : "unknown error";
  if (ps->context)
    return pdk_ctx_error_set(ctx, PDK_ERR_ARG, NULL,
                             "%s:%zu: YAML syntax: %s (%s, which starts at line %zu); fix the YAML "
                             "syntax (indentation, ':' after keys, matching brackets and quotes)",
                             file, ps->problem_mark.line + 1, problem, ps->context,
                             ps->context_mark.line + 1);
  return pdk_ctx_error_set(ctx, PDK_ERR_ARG, NULL,
                           "%s:%zu: YAML syntax: %s; fix the YAML syntax (indentation, ':' after "
                           "keys, matching brackets and quotes)",
                           file, ps->problem_mark.line + 1, problem);
}

/* Joins a key path and a segment ("a.b" + "." + "c") into out, cut at len - 1 bytes. */
static void path_join(char *out, size_t len, const char *head, const char *sep, const char *tail) {
  size_t pos = 0;
  const char *parts[3] = {head, head[0] ? sep : "", tail};
  for (int p = 0; p < 3; ++p)
    for (const char *c = parts[p]; *c && pos + 1 < len; ++c)
      out[pos++] = *c;
  out[pos] = '\0';
}

/* ---- composing a document from libyaml's events ------------------------------------------------
 */


typedef struct compose_frame {
  int id;           /* the list or mapping */
  int is_map;       /* 1: a mapping */
  int key;          /* mapping: the key node of the pair being read; 0 when a key comes next */
  long items;       /* entries (list) or pairs (mapping) so far */
  int height;       /* levels of lists and mappings at and below it so far */
  long start_total; /* composer.total before it */
  char path[KEY_MAX];
} compose_frame;

typedef struct compose_anchor {
  char *name;
  int id;
} compose_anchor;

typedef struct composer {
  yaml_document_t *doc;
  const compose_src *src;
  long *size;  /* [cap] per node id: values at and below it, aliases expanded; -1 while open */
  int *height; /* [cap] per node id: levels of lists and mappings at and below it */
  int cap;
  compose_anchor *anchors;
  int num_anchors, cap_anchors;
  name_index anchor_ix;
  compose_frame *stack; /* [MAX_DEPTH] open lists and mappings, outermost first */
  int depth;
  long total; /* values so far, aliases expanded */
} composer;

static const char *anchor_name_of(const void *items, int k) {
  return ((const compose_anchor *)items)[k].name;
}

static int compose_error(pdk_ctx *ctx, const composer *c, size_t line, const char *path,
                         const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
static int compose_error(pdk_ctx *ctx, const composer *c, size_t line, const char *path,
                         const char *fmt, ...) {
  char what[PDK_ERRMSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  const char *key = path && path[0] ? path : "(scene)";
  if (c->src->override)
    return pdk_ctx_error_set(ctx, PDK_ERR_ARG, NULL, "%s: --set %s: %s: %s", c->src->file,
                             c->src->override, key, what);
  return pdk_ctx_error_set(ctx, PDK_ERR_ARG, NULL, "%s:%zu: %s: %s", c->src->file, line, key, what);
}

static int parse_error(pdk_ctx *ctx, const compose_src *src, const yaml_parser_t *ps) {
  if (!src->override) return syntax_error(ctx, src->file, ps);
  return pdk_ctx_error_set(ctx, PDK_ERR_ARG, NULL,
                           "%s: --set %s: the value is not valid YAML: %s; quote it or write a "
                           "number, a word or a [list]",
                           src->file, src->override, ps->problem ? ps->problem : "unknown error");
}

/* The key path of the node that comes next: an entry of the innermost list, the value of the
 * innermost mapping's pair, or (for a key) that mapping. */
static void compose_path(const composer *c, char *out, size_t len) {
  if (c->depth == 0) {
    path_join(out, len, c->src->base, "", "");
    return;
  }
  const compose_frame *f = &c->stack[c->depth - 1];
  if (!f->is_map) {
    char index[32];
    snprintf(index, sizeof index, "[%ld]", f->items);
    path_join(out, len, f->path, "", index);
  } else if (f->key) {
    const yaml_node_t *k = yaml_document_get_node(c->doc, f->key);
    path_join(out, len, f->path, ".", (const char *)k->data.scalar.value);
  } else {
    path_join(out, len, f->path, "", "");
  }
}

/* Room for node id in the per-node arrays. */
static int compose_grow(pdk_ctx *ctx, composer *c, int id) {
  if (id < c->cap) return PDK_SUCCESS;
  int cap = c->cap ? c->cap : 256;
  while (cap <= id)
    cap *= 2;
  long *size = realloc(c->size, (size_t)cap * sizeof *size);
  if (size) c->size = size;
  int *height = size ? realloc(c->height, (size_t)cap * sizeof *height) : NULL;
  if (height) c->height = height;
  PDK_CHECK(size && height, ctx, PDK_ERR_MEMORY, "out of memory reading the scene");
  c->cap = cap;
  return PDK_SUCCESS;
}

static int compose_anchor_add(pdk_ctx *ctx, composer *c, const yaml_char_t *name, int id) {
  if (!name) return PDK_SUCCESS;
  if (c->num_anchors == c->cap_anchors) {
    int cap = c->cap_anchors ? 2 * c->cap_anchors : 16;
    compose_anchor *a = realloc(c->anchors, (size_t)cap * sizeof *a);
    PDK_CHECK(a, ctx, PDK_ERR_MEMORY, "out of memory reading the scene");
    c->anchors = a;
    c->cap_anchors = cap;
  }
  compose_anchor *a = &c->anchors[c->num_anchors];
  a->name = strdup((const char *)name);
  a->id = id;
  PDK_CHECK(a->name, ctx, PDK_ERR_MEMORY, "out of memory reading the scene");
  ++c->num_anchors;
  PDK_CHECK(pdk_scene_index_put(&c->anchor_ix, c->anchors, anchor_name_of, c->num_anchors - 1), ctx,
            PDK_ERR_MEMORY, "out of memory reading the scene");
  return PDK_SUCCESS;
}

/* Counts `values` more (aliases expanded) and refuses the document past the limit. */
static int compose_count(pdk_ctx *ctx, composer *c, long values, size_t line) {
  c->total += values;
  if (c->total <= MAX_VALUES) return PDK_SUCCESS;
  char path[KEY_MAX];
  path_join(path, sizeof path, c->depth ? c->stack[c->depth - 1].path : c->src->base, "", "");
  return compose_error(ctx, c, line, path,
                       "the scene expands to more than %ld values (keys, numbers, words, lists "
                       "and mappings, with every alias counted as a copy of its anchor), the "
                       "limit for a scene; a scene needs a few hundred: check the anchors (&) and "
                       "aliases (*)",
                       MAX_VALUES);
}

/* Appends node id (just made, or an alias's anchor) to the innermost open list or mapping; the
 * first node is the root. */
static int compose_attach(pdk_ctx *ctx, composer *c, int id) {
  if (c->depth == 0) return PDK_SUCCESS;
  compose_frame *f = &c->stack[c->depth - 1];
  int ok = 1;
  if (!f->is_map) {
    ok = yaml_document_append_sequence_item(c->doc, f->id, id);
    ++f->items;
  } else if (!f->key) {
    f->key = id;
  } else {
    ok = yaml_document_append_mapping_pair(c->doc, f->id, f->key, id);
    f->key = 0;
    ++f->items;
  }
  PDK_CHECK(ok, ctx, PDK_ERR_MEMORY, "out of memory reading the scene");
  return PDK_SUCCESS;
}

static void compose_height(composer *c, int child_height) {
  if (c->depth == 0) return;
  compose_frame *f = &c->stack[c->depth - 1];
  if (child_height + 1 > f->height) f->height = child_height + 1;
}

/* A list or mapping (or an alias of one) where a mapping expects its key. */
static int compose_complex_key(pdk_ctx *ctx, composer *c, int is_map, size_t line) {
  char path[KEY_MAX];
  compose_path(c, path, sizeof path);
  return compose_error(ctx, c, line, path,
                       "%s is used as a key; a key is a single word followed by ':' (for example "
                       "spacing: 1e-3)",
                       is_map ? "a mapping" : "a list");
}

static int compose_expects_key(const composer *c) {
  return c->depth > 0 && c->stack[c->depth - 1].is_map && !c->stack[c->depth - 1].key;
}

/* Handles one event of a document's body. */
static int compose_event(pdk_ctx *ctx, composer *c, const yaml_event_t *ev) {
  yaml_document_t *d = c->doc;
  const size_t line = ev->start_mark.line + 1;
  char path[KEY_MAX];
  switch (ev->type) {
  case YAML_SCALAR_EVENT: {
    const yaml_char_t *tag = ev->data.scalar.tag;
    if (tag && !strcmp((const char *)tag, "!")) tag = NULL;
    if (strlen((const char *)ev->data.scalar.value) != ev->data.scalar.length) {
      compose_path(c, path, sizeof path);
      return compose_error(ctx, c, line, path,
                           "the value contains a NUL character (\\0); remove it");
    }
    int id = yaml_document_add_scalar(d, tag, ev->data.scalar.value, (int)ev->data.scalar.length,
                                      ev->data.scalar.style);
    PDK_CHECK(id, ctx, PDK_ERR_MEMORY, "out of memory reading the scene");
    PDK_CALL(compose_grow(ctx, c, id));
    yaml_node_t *n = yaml_document_get_node(d, id);
    n->start_mark = ev->start_mark;
    n->end_mark = ev->end_mark;
    c->size[id] = 1;
    c->height[id] = 0;
    PDK_CALL(compose_anchor_add(ctx, c, ev->data.scalar.anchor, id));
    PDK_CALL(compose_count(ctx, c, 1, line));
    PDK_CALL(compose_attach(ctx, c, id));
    compose_height(c, 0);
    return PDK_SUCCESS;
  }
  case YAML_SEQUENCE_START_EVENT:
  case YAML_MAPPING_START_EVENT: {
    const int is_map = ev->type == YAML_MAPPING_START_EVENT;
    if (compose_expects_key(c)) return compose_complex_key(ctx, c, is_map, line);
    compose_path(c, path, sizeof path);
    if (c->depth + 1 > MAX_DEPTH)
      return compose_error(ctx, c, line, path,
                           "nested deeper than %d levels of lists and mappings, the limit for a "
                           "scene; scenes are a few levels deep",
                           MAX_DEPTH);
    const yaml_char_t *tag = is_map ? ev->data.mapping_start.tag : ev->data.sequence_start.tag;
    if (tag && !strcmp((const char *)tag, "!")) tag = NULL;
    int id = is_map ? yaml_document_add_mapping(d, tag, ev->data.mapping_start.style)
                    : yaml_document_add_sequence(d, tag, ev->data.sequence_start.style);
    PDK_CHECK(id, ctx, PDK_ERR_MEMORY, "out of memory reading the scene");
    PDK_CALL(compose_grow(ctx, c, id));
    yaml_document_get_node(d, id)->start_mark = ev->start_mark;
    c->size[id] = -1;
    c->height[id] = 1;
    PDK_CALL(compose_anchor_add(
        ctx, c, is_map ? ev->data.mapping_start.anchor : ev->data.sequence_start.anchor, id));
    PDK_CALL(compose_count(ctx, c, 1, line));
    PDK_CALL(compose_attach(ctx, c, id));
    compose_frame *f = &c->stack[c->depth++];
    f->id = id;
    f->is_map = is_map;
    f->key = 0;
    f->items = 0;
    f->height = 1;
    f->start_total = c->total - 1;
    memcpy(f->path, path, sizeof f->path);
    return PDK_SUCCESS;
  }
  case YAML_SEQUENCE_END_EVENT:
  case YAML_MAPPING_END_EVENT: {
    const compose_frame *f = &c->stack[--c->depth];
    c->size[f->id] = c->total - f->start_total;
    c->height[f->id] = f->height;
    yaml_document_get_node(d, f->id)->end_mark = ev->end_mark;
    compose_height(c, f->height);
    return PDK_SUCCESS;
  }
  case YAML_ALIAS_EVENT: {
    const char *name = (const char *)ev->data.alias.anchor;
    int k =
        pdk_scene_index_find(c->anchor_ix.slot, c->anchor_ix.cap, c->anchors, anchor_name_of, name);
    compose_path(c, path, sizeof path);
    if (k < 0)
      return compose_error(ctx, c, line, path,
                           "the alias *%s refers to no anchor; define the value first, marked "
                           "&%s",
                           name, name);
    const int id = c->anchors[k].id;
    const yaml_node_t *target = yaml_document_get_node(d, id);
    if (c->size[id] < 0) {
      for (int j = 0; j < c->depth; ++j)
        if (c->stack[j].id == id) path_join(path, sizeof path, c->stack[j].path, "", "");
      return compose_error(ctx, c, line, path,
                           "the alias *%s is inside the %s it refers to (a recursive alias), "
                           "which would never end; an alias can only repeat a value that ends "
                           "before it",
                           name, target->type == YAML_MAPPING_NODE ? "mapping" : "list");
    }
    if (compose_expects_key(c) && target->type != YAML_SCALAR_NODE)
      return compose_complex_key(ctx, c, target->type == YAML_MAPPING_NODE, line);
    if (c->depth + c->height[id] > MAX_DEPTH)
      return compose_error(ctx, c, line, path,
                           "the alias *%s puts its value deeper than %d levels of lists and "
                           "mappings, the limit for a scene; scenes are a few levels deep",
                           name, MAX_DEPTH);
    PDK_CALL(compose_count(ctx, c, c->size[id], line));
    PDK_CALL(compose_attach(ctx, c, id));
    compose_height(c, c->height[id]);
    return PDK_SUCCESS;
  }
  default: return PDK_SUCCESS;
  }
}

/* Reads the next document of the stream into doc (initialized here; *have_doc set then). At the
 * end of the stream doc stays empty and *found is 0. */
int pdk_scene_compose_document(pdk_ctx *ctx, yaml_parser_t *ps, const compose_src *src,
                               yaml_document_t *doc, int *have_doc, int *found) {
  int err = PDK_SUCCESS;
  composer c;
  yaml_event_t ev;
  int have_ev = 0, in_doc = 0;
  memset(&c, 0, sizeof c);
  c.doc = doc;
  c.src = src;
  *found = 0;
  c.stack = malloc(MAX_DEPTH * sizeof *c.stack);
  PDK_CHECK_GOTO(c.stack, ctx, PDK_ERR_MEMORY, "out of memory reading the scene");
  PDK_CHECK_GOTO(yaml_document_initialize(doc, NULL, NULL, NULL, 1, 1), ctx, PDK_ERR_MEMORY,
                 "out of memory reading the scene");
  *have_doc = 1;
  for (;;) {
    if (!yaml_parser_parse(ps, &ev)) {
      err = parse_error(ctx, src, ps);
      goto cleanup;
    }
    have_ev = 1;
    if (ev.type == YAML_STREAM_END_EVENT || ev.type == YAML_DOCUMENT_END_EVENT ||
        (ev.type == YAML_NO_EVENT && !in_doc))
      break;
    if (ev.type == YAML_DOCUMENT_START_EVENT) {
      in_doc = 1;
      *found = 1;
    } else if (in_doc) {
      PDK_CALL_GOTO(compose_event(ctx, &c, &ev));
    }
    yaml_event_delete(&ev);
    have_ev = 0;
  }
cleanup:
  if (have_ev) yaml_event_delete(&ev);
  for (int k = 0; k < c.num_anchors; ++k)
    free(c.anchors[k].name);
  free(c.anchors);
  free(c.anchor_ix.slot);
  free(c.size);
  free(c.height);
  free(c.stack);
  return err;
}

/* After a document: the stream must end there. */
int pdk_scene_compose_end(pdk_ctx *ctx, yaml_parser_t *ps, const compose_src *src) {
  yaml_event_t ev;
  if (!yaml_parser_parse(ps, &ev)) return parse_error(ctx, src, ps);
  const int second = ev.type == YAML_DOCUMENT_START_EVENT;
  const size_t line = ev.start_mark.line + 1;
  yaml_event_delete(&ev);
  if (!second) return PDK_SUCCESS;
  if (src->override)
    return pdk_ctx_error_set(ctx, PDK_ERR_ARG, NULL,
                             "%s: --set %s: %s: the value holds a second YAML document (after "
                             "'---'); give one value, quoted if it contains '---'",
                             src->file, src->override, src->base);
  return pdk_ctx_error_set(ctx, PDK_ERR_ARG, NULL,
                           "%s:%zu: (scene): a second YAML document starts here; a scene file "
                           "holds one document (remove the '---' line and what follows, or merge "
                           "the two)",
                           src->file, line);
}
