/* Scene YAML documents: reading the file, command-line overrides, key lines (src/scene/scene_yaml.h;
 * the hash index and scene messages are src/scene/scene_keys.c's).
 *
 * The scene file is parsed into a libyaml document (a node tree; every node keeps the line where it
 * starts). Overrides "key.path=value" edit that tree: the value is parsed as YAML of its own (so
 * `geometry.box.lo=[0, 0]` gives a list) and copied in, replacing the value at key.path or adding
 * the key (and any missing parent mappings). Nodes that an override created are tagged with its
 * index in `origin`, so a message about such a key names the override instead of a file line.
 *
 * The tree is then walked once to record every key path with its line and origin (pdk_scene_key),
 * and emitted as YAML text for the libcyaml schema load (src/scene/scene.c). libcyaml reports errors
 * with a key path (its backtrace); the path, looked up (src/scene/scene_keys.c), gives the line in the
 * user's file.
 *
 * Key paths: mapping keys joined by '.', sequence entries as [k] (0-based), for example
 * "boundary_conditions[1].y". Overrides accept the same form, and also "boundary_conditions.1.y".
 *
 * Limits before work (scene_impl.h): the file's size before it is read; while libyaml's events
 * are turned into the tree (src/scene/scene_compose.c, instead of libyaml's document loader), the
 * nesting depth (libyaml's scanner takes time quadratic in the depth, so the parse stops at the
 * limit), the number of values with aliases expanded (an alias is stored once, as a reference, but
 * the key walk, the emitter and libcyaml expand it), aliases to an unfinished anchor (recursive),
 * and lists or mappings used as keys. Anchors and key paths are found through hash indexes, so no
 * step takes time quadratic in the size of the scene.
 */
#include <ctype.h>
#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <yaml.h>

#include "scene_yaml.h"
#include "pdk/ctx.h"
#include "pdk/scene.h"

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

#define MAX_SEGMENTS 32

/* ---- reading -----------------------------------------------------------------------------------
 */

int pdk_scene_read_file(pdk_ctx *ctx, const char *path, char **text, size_t *len) {
  int err = PDK_SUCCESS;
  char *buf = NULL;
  size_t size = 0, cap = 0;
  const size_t limit = (size_t)PDK_SCENE_MAX_FILE_BYTES;
  struct stat st;
  *text = NULL;
  FILE *f = fopen(path, "rb");
  SCENE_CHECK(f, ctx, PDK_ERR_IO, "cannot open the scene file '%s': %s; check the path", path,
              strerror(errno));
  /* A regular file is measured before it is read; anything else (a device such as /dev/zero, a
   * pipe) is read up to the limit. */
  if (!fstat(fileno(f), &st)) {
    SCENE_CHECK_GOTO(!S_ISDIR(st.st_mode), ctx, PDK_ERR_IO,
                     "%s: is a directory; give the scene file (YAML) itself", path);
    SCENE_CHECK_GOTO(!S_ISREG(st.st_mode) || (uintmax_t)st.st_size <= (uintmax_t)limit, ctx,
                     PDK_ERR_ARG,
                     "%s: the file has %jd bytes, more than the %ld MiB a scene file may have (the "
                     "limit for scene files); is it a scene? Scenes are YAML text of a few kB",
                     path, (intmax_t)st.st_size, PDK_SCENE_MAX_FILE_BYTES >> 20);
  }
  for (;;) {
    if (cap - size < 4096) {
      cap = cap ? 2 * cap : 8192;
      if (cap > limit + 1) cap = limit + 1; /* room to see one byte too many */
      char *nb = realloc(buf, cap + 1);
      PDK_CHECK_GOTO(nb, ctx, PDK_ERR_MEMORY, "out of memory reading the scene file '%s'", path);
      buf = nb;
    }
    size_t got = fread(buf + size, 1, cap - size, f);
    size += got;
    SCENE_CHECK_GOTO(size <= limit, ctx, PDK_ERR_ARG,
                     "%s: more than %ld MiB were read and the file goes on; a scene file may have "
                     "at most %ld MiB (the limit for scene files); is it a scene? Scenes are YAML "
                     "text of a few kB",
                     path, PDK_SCENE_MAX_FILE_BYTES >> 20, PDK_SCENE_MAX_FILE_BYTES >> 20);
    if (got == 0) break;
  }
  SCENE_CHECK_GOTO(!ferror(f), ctx, PDK_ERR_IO, "cannot read the scene file '%s': %s", path,
                   strerror(errno));
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
  const pdk_scene *scene;
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


/* Copies node `id` of src (and everything below it) into dst, keeping shared nodes (aliases)
 * shared: memo[k] is the copy of src node k, 0 before it is made. Returns the new id or 0. */
static int node_copy(yaml_document_t *dst, yaml_document_t *src, int id, int *memo) {
  if (memo[id]) return memo[id];
  yaml_node_t *n = yaml_document_get_node(src, id);
  if (!n) return 0;
  int out = 0;
  switch (n->type) {
  case YAML_SCALAR_NODE:
    out = yaml_document_add_scalar(dst, n->tag, n->data.scalar.value, (int)n->data.scalar.length,
                                   n->data.scalar.style);
    break;
  case YAML_SEQUENCE_NODE: {
    out = yaml_document_add_sequence(dst, n->tag, n->data.sequence.style);
    if (!out) return 0;
    int count = (int)(n->data.sequence.items.top - n->data.sequence.items.start);
    for (int i = 0; i < count; ++i) {
      n = yaml_document_get_node(src, id); /* src is not modified, but stay uniform */
      int item = node_copy(dst, src, n->data.sequence.items.start[i], memo);
      if (!item || !yaml_document_append_sequence_item(dst, out, item)) return 0;
    }
    break;
  }
  case YAML_MAPPING_NODE: {
    out = yaml_document_add_mapping(dst, n->tag, n->data.mapping.style);
    if (!out) return 0;
    int count = (int)(n->data.mapping.pairs.top - n->data.mapping.pairs.start);
    for (int i = 0; i < count; ++i) {
      n = yaml_document_get_node(src, id);
      yaml_node_pair_t pair = n->data.mapping.pairs.start[i];
      int key = node_copy(dst, src, pair.key, memo);
      int value = key ? node_copy(dst, src, pair.value, memo) : 0;
      if (!value || !yaml_document_append_mapping_pair(dst, out, key, value)) return 0;
    }
    break;
  }
  default: return 0;
  }
  memo[id] = out;
  return out;
}

/* Values at and below node id with aliases expanded, saturated at MAX_VALUES + 1; memo[k] is
 * node k's count, 0 before it is counted. */
static long doc_measure(yaml_document_t *d, int id, long *memo) {
  if (memo[id]) return memo[id];
  yaml_node_t *n = yaml_document_get_node(d, id);
  long total = 1;
  if (n && n->type == YAML_SEQUENCE_NODE) {
    int count = (int)(n->data.sequence.items.top - n->data.sequence.items.start);
    for (int i = 0; i < count && total <= MAX_VALUES; ++i)
      total += doc_measure(d, yaml_document_get_node(d, id)->data.sequence.items.start[i], memo);
  } else if (n && n->type == YAML_MAPPING_NODE) {
    int count = (int)(n->data.mapping.pairs.top - n->data.mapping.pairs.start);
    for (int i = 0; i < count && total <= MAX_VALUES; ++i) {
      yaml_node_pair_t pair = yaml_document_get_node(d, id)->data.mapping.pairs.start[i];
      total += doc_measure(d, pair.key, memo);
      total += doc_measure(d, pair.value, memo);
    }
  }
  memo[id] = total > MAX_VALUES ? MAX_VALUES + 1 : total;
  return memo[id];
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
  {
    const compose_src vsrc = {file, ov, path};
    int found = 0;
    PDK_CALL_GOTO(pdk_scene_compose_document(ctx, &vp, &vsrc, &vdoc, &have_vdoc, &found));
    if (found) PDK_CALL_GOTO(pdk_scene_compose_end(ctx, &vp, &vsrc));
  }
  /* An empty scene gets its root mapping first: node 1 is the root, so the value copied next
   * must not take that place (it would become the mapping the path walks, and contain itself). */
  if (!yaml_document_get_root_node(d))
    PDK_CHECK_GOTO(yaml_document_add_mapping(d, NULL, YAML_BLOCK_MAPPING_STYLE) == 1, ctx,
                   PDK_ERR_MEMORY, "out of memory applying --set %s", ov);
  int vnode;
  if (yaml_document_get_root_node(&vdoc)) {
    int *memo = calloc((size_t)node_count(&vdoc) + 1, sizeof *memo);
    PDK_CHECK_GOTO(memo, ctx, PDK_ERR_MEMORY, "out of memory applying --set %s", ov);
    vnode = node_copy(d, &vdoc, 1, memo);
    free(memo);
  } else {
    vnode = yaml_document_add_scalar(d, NULL, (const yaml_char_t *)"", 0, YAML_PLAIN_SCALAR_STYLE);
  }
  PDK_CHECK_GOTO(vnode, ctx, PDK_ERR_MEMORY, "out of memory applying --set %s", ov);

  /* Walk to the parent of the last segment, creating mappings for missing keys. */
  int cur = 1;
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
  k->count = value && value->type == YAML_SEQUENCE_NODE
                 ? (long)(value->data.sequence.items.top - value->data.sequence.items.start)
                 : -1;
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
  if (!n || n->type == YAML_SCALAR_NODE) return PDK_SUCCESS;
  /* Each document was composed within the limit; an override's value can reach deeper. */
  if (depth >= MAX_DEPTH) {
    const pdk_scene *s = ds->scene;
    const int origin = origin_of(ds, id);
    if (origin >= 0 && origin < s->num_overrides)
      return pdk_ctx_error_set(ctx, PDK_ERR_ARG, NULL,
                               "%s: --set %s: %s: nested deeper than %d levels of lists and "
                               "mappings, the limit for a scene; scenes are a few levels deep",
                               file, s->overrides[origin], path, MAX_DEPTH);
    return pdk_ctx_error_set(ctx, PDK_ERR_ARG, NULL,
                             "%s:%zu: %s: nested deeper than %d levels of lists and mappings, the "
                             "limit for a scene; scenes are a few levels deep",
                             file, n->start_mark.line + 1, path, MAX_DEPTH);
  }
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
  name_index ix = {0};
  text_buf out = {0};
  memset(&ds, 0, sizeof ds);
  *yaml_out = NULL;
  *dim_out = 2;

  PDK_CHECK_GOTO(yaml_parser_initialize(&ps), ctx, PDK_ERR_MEMORY,
                 "yaml_parser_initialize failed (out of memory)");
  have_parser = 1;
  yaml_parser_set_input_string(&ps, (const unsigned char *)file_text, file_len);
  ds.scene = s;
  {
    const compose_src fsrc = {s->path, NULL, ""};
    int found = 0;
    PDK_CALL_GOTO(pdk_scene_compose_document(ctx, &ps, &fsrc, &ds.doc, &ds.have_doc, &found));
    if (found) PDK_CALL_GOTO(pdk_scene_compose_end(ctx, &ps, &fsrc));
  }
  PDK_CALL_GOTO(mark_origin(ctx, &ds, node_count(&ds.doc), -1));
  for (int k = 0; k < s->num_overrides; ++k)
    PDK_CALL_GOTO(override_apply(ctx, s->path, &ds, k, s->overrides[k]));
  if (s->num_overrides && yaml_document_get_root_node(&ds.doc)) {
    /* The file and each value were within the limit; together they may not be. */
    long *memo = calloc((size_t)node_count(&ds.doc) + 1, sizeof *memo);
    PDK_CHECK_GOTO(memo, ctx, PDK_ERR_MEMORY, "out of memory applying scene overrides");
    long total = doc_measure(&ds.doc, 1, memo);
    free(memo);
    SCENE_CHECK_GOTO(total <= MAX_VALUES, ctx, PDK_ERR_ARG,
                     "%s: (scene): with the overrides the scene expands to more than %ld values "
                     "(keys, numbers, words, lists and mappings, with every alias counted as a "
                     "copy of its anchor), the limit for a scene; check the anchors (&) and "
                     "aliases (*) of the file and the --set values",
                     s->path, MAX_VALUES);
  }

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
  for (int k = 0; k < kl.num; ++k)
    if (!pdk_scene_index_put(&ix, kl.keys, pdk_scene_key_path_of, k)) {
      free(ix.slot);
      err = pdk_ctx_error_set(ctx, PDK_ERR_MEMORY, __func__, "out of memory recording scene keys");
      goto cleanup;
    }
  s->keys = kl.keys;
  s->num_keys = kl.num;
  s->key_slots = ix.slot;
  s->num_key_slots = ix.cap;
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
