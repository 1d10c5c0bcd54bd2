/* Scene key records: the hash index of names (key paths here, anchors in src/scene/scene_compose.c),
 * the lookup of a key path's record, and scene messages that name a key by its line in the file
 * or by the override that set it (src/scene/scene_impl.h, src/scene/scene_yaml.h).
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "scene_yaml.h"
#include "pdk/ctx.h"
#include "pdk/scene.h"

static uint64_t name_hash(const char *c) {
  uint64_t h = 1469598103934665603ull; /* FNV-1a */
  for (; *c; ++c)
    h = (h ^ (unsigned char)*c) * 1099511628211ull;
  return h;
}

int pdk_scene_index_find(const int *slot, size_t cap, const void *items, name_of_fn name_of,
                         const char *name) {
  if (!cap) return -1;
  for (size_t i = (size_t)name_hash(name) & (cap - 1);; i = (i + 1) & (cap - 1)) {
    if (slot[i] < 0) return -1;
    if (!strcmp(name_of(items, slot[i]), name)) return slot[i];
  }
}

static void index_insert(int *slot, size_t cap, const void *items, name_of_fn name_of, int k) {
  const char *name = name_of(items, k);
  for (size_t i = (size_t)name_hash(name) & (cap - 1);; i = (i + 1) & (cap - 1)) {
    if (slot[i] < 0) {
      slot[i] = k;
      return;
    }
    if (!strcmp(name_of(items, slot[i]), name)) {
      if (k > slot[i]) slot[i] = k;
      return;
    }
  }
}

/* Adds item k (items 0..k-1 are in the index); 0 when out of memory. */
int pdk_scene_index_put(name_index *ix, const void *items, name_of_fn name_of, int k) {
  if (2 * (ix->num + 1) > ix->cap) {
    size_t cap = ix->cap ? 2 * ix->cap : 64;
    int *slot = malloc(cap * sizeof *slot);
    if (!slot) return 0;
    for (size_t i = 0; i < cap; ++i)
      slot[i] = -1;
    for (int j = 0; j < k; ++j)
      index_insert(slot, cap, items, name_of, j);
    free(ix->slot);
    ix->slot = slot;
    ix->cap = cap;
  }
  index_insert(ix->slot, ix->cap, items, name_of, k);
  ++ix->num;
  return 1;
}

const char *pdk_scene_key_path_of(const void *items, int k) {
  return ((const pdk_scene_key *)items)[k].path;
}

/* ---- messages ----------------------------------------------------------------------------------
 */

/* The last record of a path: a key given twice is reported where it is repeated. */
static const pdk_scene_key *key_find(const pdk_scene *s, const char *path) {
  int k =
      pdk_scene_index_find(s->key_slots, s->num_key_slots, s->keys, pdk_scene_key_path_of, path);
  return k >= 0 ? &s->keys[k] : NULL;
}

const char *pdk_scene_quote(const char *text, char *buf, size_t len) {
  size_t pos = 0;
  if (!len) return buf;
  buf[0] = '\0';
  for (const unsigned char *c = (const unsigned char *)(text ? text : ""); *c; ++c) {
    char one[8];
    if (*c == '\n')
      snprintf(one, sizeof one, "\\n");
    else if (*c == '\t')
      snprintf(one, sizeof one, "\\t");
    else if (*c == '\r')
      snprintf(one, sizeof one, "\\r");
    else if (*c < 0x20 || *c >= 0x7f)
      snprintf(one, sizeof one, "\\x%02X", *c);
    else
      snprintf(one, sizeof one, "%c", *c);
    size_t n = strlen(one);
    if (pos + n + 4 > len || pos >= 60) {
      snprintf(buf + pos, len - pos, "...");
      return buf;
    }
    memcpy(buf + pos, one, n + 1);
    pos += n;
  }
  return buf;
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
