/* Scene YAML documents: reading the file, command-line overrides, key lines, scene messages.
 *
 * The scene file is parsed into a libyaml document (a node tree; every node keeps the line where it
 * starts). Overrides "key.path=value" edit that tree: the value is parsed as YAML of its own (so
 * `geometry.box.lo=[0, 0]` gives a list) and copied in, replacing the value at key.path or adding
 * the key (and any missing parent mappings). Nodes that an override created are tagged with its
 * index in `origin`, so a message about such a key names the override instead of a file line.
 *
 * The tree is then walked once to record every key path with its line and origin (pdk_scene_key),
 * and emitted as YAML text for the libcyaml schema load (src/scene.c). libcyaml reports errors
 * with a key path (its backtrace); the path, looked up here, gives the line in the user's file.
 *
 * Key paths: mapping keys joined by '.', sequence entries as [k] (0-based), for example
 * "boundary_conditions[1].y". Overrides accept the same form, and also "boundary_conditions.1.y".
 */
#include <ctype.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <yaml.h>

#include "scene_impl.h"

/* User-facing checks: the message already says where (file, line, override), so no function name
 * is appended (PDK_CHECK would add " (in function)"). */
#define SCENE_CHECK(cond, ctx, code, ...)                                                          \
  do {                                                                                             \
    if (!(cond)) return pdk_ctx_error_set((ctx), (code), NULL, __VA_ARGS__);                       \
  } while (0)
#define SCENE_CHECK_GOTO(cond, ctx, code, ...)                                                     \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      err = pdk_ctx_error_set((ctx), (code), NULL, __VA_ARGS__);                                   \
      goto cleanup;                                                                                \
    }                                                                                              \
  } while (0)

#define MAX_DEPTH 64
#define MAX_SEGMENTS 32
#define KEY_MAX 256

/* ---- messages ----------------------------------------------------------------------------------
 */

/* The last record of a path: a key given twice is reported where it is repeated. */
static const pdk_scene_key *key_find(const pdk_scene *s, const char *path) {
  for (int k = s->num_keys - 1; k >= 0; --k)
    if (!strcmp(s->keys[k].path, path)) return &s->keys[k];
  return NULL;
}

const pdk_scene_key *pdk_scene_key_get(const pdk_scene *s, const char *path) {
  return key_find(s, path);
}

/* Strips the last segment of a key path in place ("a.b[2]" -> "a.b" -> "a" -> ""). */
static void key_parent(char *path) {
  size_t n = strlen(path);
  while (n > 0 && path[n - 1] != '.' && path[n - 1] != '[')
    --n;
  if (n > 0) --n;
  path[n] = '\0';
}

void pdk_scene_key_location(const pdk_scene *s, const char *key_path, char *buf, size_t len) {
  char path[KEY_MAX];
  if (!buf || !len) return;
  if (!s) {
    snprintf(buf, len, "(no scene)");
    return;
  }
  snprintf(path, sizeof path, "%s", key_path ? key_path : "");
  while (path[0]) {
    const pdk_scene_key *k = key_find(s, path);
    if (k) {
      if (k->origin >= 0 && k->origin < s->num_overrides)
        snprintf(buf, len, "%s: --set %s", s->path, s->overrides[k->origin]);
      else
        snprintf(buf, len, "%s:%d", s->path, k->line);
      return;
    }
    key_parent(path);
  }
  snprintf(buf, len, "%s:1", s->path);
}

int pdk_scene_error(const pdk_scene *s, pdk_ctx *ctx, int code, const char *key, const char *fmt,
                    ...) {
  char where[PDK_ERRMSG_MAX / 2], what[PDK_ERRMSG_MAX];
  va_list ap;
  if (!fmt) return pdk_ctx_error_set(ctx, code, NULL, "(no message)");
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  pdk_scene_key_location(s, key, where, sizeof where);
  return pdk_ctx_error_set(ctx, code, NULL, "%s: %s: %s", where, key && key[0] ? key : "(scene)",
                           what);
}

int pdk_scene_blame(const pdk_scene *s, pdk_ctx *ctx, int err, const char *key) {
  char old[PDK_ERRMSG_MAX];
  snprintf(old, sizeof old, "%s", pdk_ctx_error_message(ctx));
  /* Drop the " (in function)" suffix of library messages: the key says where. */
  size_t n = strlen(old);
  if (n && old[n - 1] == ')') {
    char *in = strstr(old, " (in ");
    char *last = in;
    while (in) {
      last = in;
      in = strstr(in + 1, " (in ");
    }
    if (last && !strchr(last + 5, ' ')) *last = '\0';
  }
  return pdk_scene_error(s, ctx, err, key, "%s", old);
}

/* ---- reading -----------------------------------------------------------------------------------
 */

int pdk_scene_read_file(pdk_ctx *ctx, const char *path, char **text, size_t *len) {
  int err = PDK_SUCCESS;
  char *buf = NULL;
  size_t size = 0, cap = 0;
  *text = NULL;
  FILE *f = fopen(path, "rb");
  SCENE_CHECK(f, ctx, PDK_ERR_IO, "cannot open the scene file '%s': %s; check the path", path,
              strerror(errno));
  for (;;) {
    if (cap - size < 4096) {
      cap = cap ? 2 * cap : 8192;
      char *nb = realloc(buf, cap + 1);
      PDK_CHECK_GOTO(nb, ctx, PDK_ERR_MEMORY, "out of memory reading the scene file '%s'", path);
      buf = nb;
    }
    size_t got = fread(buf + size, 1, cap - size, f);
    size += got;
    if (got == 0) break;
  }
  PDK_CHECK_GOTO(!ferror(f), ctx, PDK_ERR_IO, "cannot read the scene file '%s'", path);
  buf[size] = '\0';
  SCENE_CHECK_GOTO(strlen(buf) == size, ctx, PDK_ERR_ARG,
                   "%s: the scene file contains a NUL byte; is it a YAML text file?", path);
  *text = buf;
  *len = size;
  buf = NULL;
cleanup:
  free(buf);
  fclose(f);
  return err;
}

/* ---- the document ------------------------------------------------------------------------------
 */

typedef struct doc_state {
  yaml_document_t doc;
  int have_doc;
  int *origin; /* [cap] origin of node id k (1-based ids; entry 0 unused); -1 = file */
  int cap;
} doc_state;

static int node_count(yaml_document_t *d) { return (int)(d->nodes.top - d->nodes.start); }

/* Marks nodes created since `before` as coming from override k. */
static int mark_origin(pdk_ctx *ctx, doc_state *ds, int before, int k) {
  int n = node_count(&ds->doc);
  if (n + 1 > ds->cap) {
    int cap = 2 * (n + 1);
    int *o = realloc(ds->origin, (size_t)cap * sizeof *o);
    PDK_CHECK(o, ctx, PDK_ERR_MEMORY, "out of memory applying scene overrides");
    for (int i = ds->cap; i < cap; ++i)
      o[i] = -1;
    ds->origin = o;
    ds->cap = cap;
  }
  for (int i = before + 1; i <= n; ++i)
    ds->origin[i] = k;
  return PDK_SUCCESS;
}

static int origin_of(const doc_state *ds, int id) {
  return id > 0 && id < ds->cap ? ds->origin[id] : -1;
}

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

/* Copies node `id` of src (and everything below it) into dst; returns the new id or 0. */
static int node_copy(yaml_document_t *dst, yaml_document_t *src, int id, int depth) {
  yaml_node_t *n = yaml_document_get_node(src, id);
  if (!n || depth > MAX_DEPTH) return 0;
  switch (n->type) {
  case YAML_SCALAR_NODE:
    return yaml_document_add_scalar(dst, n->tag, n->data.scalar.value, (int)n->data.scalar.length,
                                    n->data.scalar.style);
  case YAML_SEQUENCE_NODE: {
    int out = yaml_document_add_sequence(dst, n->tag, n->data.sequence.style);
    if (!out) return 0;
    int count = (int)(n->data.sequence.items.top - n->data.sequence.items.start);
    for (int i = 0; i < count; ++i) {
      n = yaml_document_get_node(src, id); /* src is not modified, but stay uniform */
      int item = node_copy(dst, src, n->data.sequence.items.start[i], depth + 1);
      if (!item || !yaml_document_append_sequence_item(dst, out, item)) return 0;
    }
    return out;
  }
  case YAML_MAPPING_NODE: {
    int out = yaml_document_add_mapping(dst, n->tag, n->data.mapping.style);
    if (!out) return 0;
    int count = (int)(n->data.mapping.pairs.top - n->data.mapping.pairs.start);
    for (int i = 0; i < count; ++i) {
      n = yaml_document_get_node(src, id);
      yaml_node_pair_t pair = n->data.mapping.pairs.start[i];
      int key = node_copy(dst, src, pair.key, depth + 1);
      int value = key ? node_copy(dst, src, pair.value, depth + 1) : 0;
      if (!value || !yaml_document_append_mapping_pair(dst, out, key, value)) return 0;
    }
    return out;
  }
  default: return 0;
  }
}

typedef struct segment {
  char key[KEY_MAX];
  long index;  /* >= 0: a sequence index ("[k]" or an all-digit segment) */
  int bracket; /* 1: written as [k], so only a sequence index */
} segment;

/* Splits "a.b[2].c" (or "a.b.2.c") into segments; 0 segments or a malformed path is an error. */
static int path_split(const char *path, segment *seg, int *num) {
  int n = 0;
  const char *c = path;
  while (*c) {
    if (n >= MAX_SEGMENTS) return -1;
    segment *s = &seg[n];
    memset(s, 0, sizeof *s);
    s->index = -1;
    if (*c == '[') {
      char *end;
      errno = 0;
      long v = strtol(c + 1, &end, 10);
      if (end == c + 1 || *end != ']' || v < 0 || errno) return -1;
      s->index = v;
      s->bracket = 1;
      c = end + 1;
    } else {
      size_t len = strcspn(c, ".[");
      if (len == 0 || len >= KEY_MAX) return -1;
      memcpy(s->key, c, len);
      s->key[len] = '\0';
      int digits = 1;
      for (size_t i = 0; i < len; ++i)
        digits &= isdigit((unsigned char)c[i]) != 0;
      if (digits) s->index = strtol(s->key, NULL, 10);
      c += len;
    }
    ++n;
    if (*c == '.') {
      ++c;
      if (!*c || *c == '.' || *c == '[') return -1;
    } else if (*c && *c != '[') {
      return -1;
    }
  }
  *num = n;
  return n > 0 ? 0 : -1;
}

static const char *node_kind_name(const yaml_node_t *n) {
  if (!n) return "nothing";
  switch (n->type) {
  case YAML_SCALAR_NODE: return "a single value";
  case YAML_SEQUENCE_NODE: return "a list";
  case YAML_MAPPING_NODE: return "a mapping";
  default: return "nothing";
  }
}

/* Applies override k, "key.path=value", to the document. */
static int override_apply(pdk_ctx *ctx, const char *file, doc_state *ds, int k, const char *ov) {
  int err = PDK_SUCCESS;
  yaml_parser_t vp;
  yaml_document_t vdoc;
  int have_parser = 0, have_vdoc = 0;
  segment seg[MAX_SEGMENTS];
  int num_seg = 0;
  char path[KEY_MAX];
  yaml_document_t *d = &ds->doc;
  const int before = node_count(d);

  const char *eq = strchr(ov, '=');
  size_t plen = eq ? (size_t)(eq - ov) : 0;
  SCENE_CHECK_GOTO(eq && plen > 0 && plen < sizeof path, ctx, PDK_ERR_ARG,
                   "%s: --set %s: not of the form key.path=value; for example --set "
                   "geometry.spacing=1e-3 or --set boundary_conditions[0].y=2",
                   file, ov);
  memcpy(path, ov, plen);
  path[plen] = '\0';
  SCENE_CHECK_GOTO(!path_split(path, seg, &num_seg), ctx, PDK_ERR_ARG,
                   "%s: --set %s: '%s' is not a key path; write keys joined by '.', and list "
                   "entries as [k], for example solver.threads or sets[1].name",
                   file, ov, path);

  /* The value, parsed as YAML of its own. */
  const char *value = eq + 1;
  PDK_CHECK_GOTO(yaml_parser_initialize(&vp), ctx, PDK_ERR_MEMORY,
                 "yaml_parser_initialize failed (out of memory)");
  have_parser = 1;
  yaml_parser_set_input_string(&vp, (const unsigned char *)value, strlen(value));
  if (!yaml_parser_load(&vp, &vdoc)) {
    SCENE_CHECK_GOTO(0, ctx, PDK_ERR_ARG,
                     "%s: --set %s: the value is not valid YAML: %s; quote it or write a number, a "
                     "word or a [list]",
                     file, ov, vp.problem ? vp.problem : "unknown error");
  }
  have_vdoc = 1;
  int vnode;
  if (yaml_document_get_root_node(&vdoc))
    vnode = node_copy(d, &vdoc, 1, 0);
  else
    vnode = yaml_document_add_scalar(d, NULL, (const yaml_char_t *)"", 0, YAML_PLAIN_SCALAR_STYLE);
  PDK_CHECK_GOTO(vnode, ctx, PDK_ERR_MEMORY, "out of memory applying --set %s", ov);

  /* Walk to the parent of the last segment, creating mappings for missing keys. */
  int cur;
  if (!yaml_document_get_root_node(d)) {
    cur = yaml_document_add_mapping(d, NULL, YAML_BLOCK_MAPPING_STYLE);
    PDK_CHECK_GOTO(cur == 1, ctx, PDK_ERR_MEMORY, "out of memory applying --set %s", ov);
  } else {
    cur = 1;
  }
  for (int i = 0; i < num_seg; ++i) {
    const int last = i == num_seg - 1;
    yaml_node_t *n = yaml_document_get_node(d, cur);
    const segment *sg = &seg[i];
    if (n->type == YAML_SEQUENCE_NODE && sg->index >= 0) {
      long count = (long)(n->data.sequence.items.top - n->data.sequence.items.start);
      SCENE_CHECK_GOTO(sg->index < count, ctx, PDK_ERR_ARG,
                       "%s: --set %s: index %ld is out of range; that list has %ld entries "
                       "(0..%ld)",
                       file, ov, sg->index, count, count - 1);
      if (last)
        n->data.sequence.items.start[sg->index] = vnode;
      else
        cur = n->data.sequence.items.start[sg->index];
      continue;
    }
    SCENE_CHECK_GOTO(n->type == YAML_MAPPING_NODE && !sg->bracket, ctx, PDK_ERR_ARG,
                     "%s: --set %s: segment %d ('%s') does not fit: the scene has %s there; give "
                     "mapping keys by name and list entries by [index]",
                     file, ov, i + 1, sg->bracket ? "[index]" : sg->key, node_kind_name(n));
    int found = -1;
    int count = (int)(n->data.mapping.pairs.top - n->data.mapping.pairs.start);
    for (int p = 0; p < count; ++p) {
      yaml_node_t *key = yaml_document_get_node(d, n->data.mapping.pairs.start[p].key);
      if (key && key->type == YAML_SCALAR_NODE && !strcmp((char *)key->data.scalar.value, sg->key))
        found = p;
    }
    if (found >= 0) {
      if (last)
        n->data.mapping.pairs.start[found].value = vnode;
      else
        cur = n->data.mapping.pairs.start[found].value;
      continue;
    }
    SCENE_CHECK_GOTO(last || seg[i + 1].index < 0, ctx, PDK_ERR_ARG,
                     "%s: --set %s: the scene has no '%s' here, so it has no entry [%ld]; give "
                     "the whole list instead, for example --set '%s=[...]'",
                     file, ov, sg->key, seg[i + 1].index, sg->key);
    int key = yaml_document_add_scalar(d, NULL, (const yaml_char_t *)sg->key, -1,
                                       YAML_PLAIN_SCALAR_STYLE);
    int child = last ? vnode : yaml_document_add_mapping(d, NULL, YAML_BLOCK_MAPPING_STYLE);
    PDK_CHECK_GOTO(key && child && yaml_document_append_mapping_pair(d, cur, key, child), ctx,
                   PDK_ERR_MEMORY, "out of memory applying --set %s", ov);
    cur = child;
  }
  PDK_CALL_GOTO(mark_origin(ctx, ds, before, k));
cleanup:
  if (have_vdoc) yaml_document_delete(&vdoc);
  if (have_parser) yaml_parser_delete(&vp);
  return err;
}

/* ---- key lines ---------------------------------------------------------------------------------
 */

typedef struct key_list {
  pdk_scene_key *keys;
  int num, cap;
} key_list;

static int key_add(pdk_ctx *ctx, key_list *kl, const char *path, int line, int origin,
                   const yaml_node_t *value) {
  if (kl->num == kl->cap) {
    int cap = kl->cap ? 2 * kl->cap : 64;
    pdk_scene_key *k = realloc(kl->keys, (size_t)cap * sizeof *k);
    PDK_CHECK(k, ctx, PDK_ERR_MEMORY, "out of memory recording scene keys");
    kl->keys = k;
    kl->cap = cap;
  }
  pdk_scene_key *k = &kl->keys[kl->num];
  memset(k, 0, sizeof *k);
  k->path = strdup(path);
  if (value && value->type == YAML_SCALAR_NODE) k->value = strdup((char *)value->data.scalar.value);
  k->line = line;
  k->origin = origin;
  ++kl->num;
  PDK_CHECK(k->path && (!value || value->type != YAML_SCALAR_NODE || k->value), ctx, PDK_ERR_MEMORY,
            "out of memory recording scene keys");
  return PDK_SUCCESS;
}

static int keys_walk(pdk_ctx *ctx, const char *file, doc_state *ds, int id, const char *path,
                     int depth, key_list *kl) {
  yaml_document_t *d = &ds->doc;
  yaml_node_t *n = yaml_document_get_node(d, id);
  if (!n) return PDK_SUCCESS;
  SCENE_CHECK(depth < MAX_DEPTH, ctx, PDK_ERR_ARG,
              "%s:%zu: %s: nested deeper than %d levels (a recursive alias?); scenes are at most a "
              "few levels deep",
              file, n->start_mark.line + 1, path, MAX_DEPTH);
  char child[KEY_MAX];
  if (n->type == YAML_SEQUENCE_NODE) {
    int count = (int)(n->data.sequence.items.top - n->data.sequence.items.start);
    for (int i = 0; i < count; ++i) {
      n = yaml_document_get_node(d, id);
      int item = n->data.sequence.items.start[i];
      yaml_node_t *in = yaml_document_get_node(d, item);
      snprintf(child, sizeof child, "%s[%d]", path, i);
      PDK_CALL(key_add(ctx, kl, child, (int)in->start_mark.line + 1, origin_of(ds, item), in));
      PDK_CALL(keys_walk(ctx, file, ds, item, child, depth + 1, kl));
    }
  } else if (n->type == YAML_MAPPING_NODE) {
    int count = (int)(n->data.mapping.pairs.top - n->data.mapping.pairs.start);
    for (int i = 0; i < count; ++i) {
      n = yaml_document_get_node(d, id);
      yaml_node_pair_t pair = n->data.mapping.pairs.start[i];
      yaml_node_t *key = yaml_document_get_node(d, pair.key);
      yaml_node_t *value = yaml_document_get_node(d, pair.value);
      const char *name = key->type == YAML_SCALAR_NODE ? (const char *)key->data.scalar.value : "?";
      snprintf(child, sizeof child, "%s%s%s", path, path[0] ? "." : "", name);
      int origin =
          origin_of(ds, pair.value) >= 0 ? origin_of(ds, pair.value) : origin_of(ds, pair.key);
      PDK_CALL(key_add(ctx, kl, child, (int)key->start_mark.line + 1, origin, value));
      PDK_CALL(keys_walk(ctx, file, ds, pair.value, child, depth + 1, kl));
    }
  }
  return PDK_SUCCESS;
}

/* ---- emitting ----------------------------------------------------------------------------------
 */

typedef struct text_buf {
  char *data;
  size_t len, cap;
  int failed;
} text_buf;

static int text_write(void *data, unsigned char *buffer, size_t size) {
  text_buf *t = data;
  if (t->len + size + 1 > t->cap) {
    size_t cap = t->cap ? t->cap : 4096;
    while (cap < t->len + size + 1)
      cap *= 2;
    char *nd = realloc(t->data, cap);
    if (!nd) {
      t->failed = 1;
      return 0;
    }
    t->data = nd;
    t->cap = cap;
  }
  memcpy(t->data + t->len, buffer, size);
  t->len += size;
  t->data[t->len] = '\0';
  return 1;
}

/* ---- the whole preparation ---------------------------------------------------------------------
 */

int pdk_scene_yaml_prepare(pdk_ctx *ctx, pdk_scene *s, const char *file_text, size_t file_len,
                           char **yaml_out, size_t *yaml_len, int *dim_out) {
  int err = PDK_SUCCESS;
  yaml_parser_t ps;
  yaml_emitter_t em;
  int have_parser = 0, have_emitter = 0;
  doc_state ds;
  key_list kl = {0};
  text_buf out = {0};
  memset(&ds, 0, sizeof ds);
  *yaml_out = NULL;
  *dim_out = 2;

  PDK_CHECK_GOTO(yaml_parser_initialize(&ps), ctx, PDK_ERR_MEMORY,
                 "yaml_parser_initialize failed (out of memory)");
  have_parser = 1;
  yaml_parser_set_input_string(&ps, (const unsigned char *)file_text, file_len);
  if (!yaml_parser_load(&ps, &ds.doc)) {
    err = syntax_error(ctx, s->path, &ps);
    goto cleanup;
  }
  ds.have_doc = 1;
  {
    yaml_document_t extra;
    if (!yaml_parser_load(&ps, &extra)) {
      err = syntax_error(ctx, s->path, &ps);
      goto cleanup;
    }
    int more = yaml_document_get_root_node(&extra) != NULL;
    size_t line = extra.start_mark.line + 1;
    yaml_document_delete(&extra);
    SCENE_CHECK_GOTO(!more, ctx, PDK_ERR_ARG,
                     "%s:%zu: (scene): a second YAML document starts here; a scene file holds one "
                     "document (remove the '---' line and what follows, or merge the two)",
                     s->path, line);
  }
  PDK_CALL_GOTO(mark_origin(ctx, &ds, node_count(&ds.doc), -1));
  for (int k = 0; k < s->num_overrides; ++k)
    PDK_CALL_GOTO(override_apply(ctx, s->path, &ds, k, s->overrides[k]));

  yaml_node_t *root = yaml_document_get_root_node(&ds.doc);
  if (root) {
    SCENE_CHECK_GOTO(root->type == YAML_MAPPING_NODE, ctx, PDK_ERR_ARG,
                     "%s:%zu: (scene): the scene is %s; it must be a mapping of keys such as "
                     "dimension, geometry, material, solver (see docs/scenes.md)",
                     s->path, root->start_mark.line + 1, node_kind_name(root));
    PDK_CALL_GOTO(keys_walk(ctx, s->path, &ds, 1, "", 0, &kl));
  }
  for (int k = 0; k < kl.num; ++k)
    if (!strcmp(kl.keys[k].path, "dimension") && kl.keys[k].value &&
        strtod(kl.keys[k].value, NULL) == 3.0)
      *dim_out = 3;

  if (!root) { /* an empty document: libcyaml gets empty text and returns no data */
    out.data = calloc(1, 1);
    PDK_CHECK_GOTO(out.data, ctx, PDK_ERR_MEMORY, "out of memory loading a scene");
    goto done;
  }
  /* Emit the (edited) document; yaml_emitter_dump consumes it. */
  PDK_CHECK_GOTO(yaml_emitter_initialize(&em), ctx, PDK_ERR_MEMORY,
                 "yaml_emitter_initialize failed (out of memory)");
  have_emitter = 1;
  yaml_emitter_set_output(&em, text_write, &out);
  yaml_emitter_set_unicode(&em, 1);
  yaml_emitter_set_width(&em, 100);
  yaml_emitter_set_indent(&em, 2);
  int ok = yaml_emitter_open(&em);
  ok = ok && yaml_emitter_dump(&em, &ds.doc);
  ds.have_doc = 0;
  ok = ok && yaml_emitter_close(&em);
  PDK_CHECK_GOTO(ok && !out.failed && out.data, ctx, out.failed ? PDK_ERR_MEMORY : PDK_ERR_EXTERNAL,
                 "yaml_emitter_dump failed writing the scene back as YAML: %s",
                 em.problem ? em.problem : "out of memory");
done:
  s->keys = kl.keys;
  s->num_keys = kl.num;
  kl.keys = NULL;
  kl.num = 0;
  *yaml_out = out.data;
  *yaml_len = out.len;
  out.data = NULL;
cleanup:
  if (have_emitter) yaml_emitter_delete(&em);
  if (ds.have_doc) yaml_document_delete(&ds.doc);
  if (have_parser) yaml_parser_delete(&ps);
  free(ds.origin);
  pdk_scene_keys_free(kl.keys, kl.num);
  free(out.data);
  return err;
}

void pdk_scene_keys_free(pdk_scene_key *keys, int num) {
  for (int k = 0; k < num; ++k) {
    free(keys[k].path);
    free(keys[k].value);
  }
  free(keys);
}
