/* Private to the scene's YAML document (src/scene/scene_yaml.c, scene_compose.c, scene_keys.c): the
 * limits while composing, the hash index of names (key paths, anchors) and the composer of a
 * document from libyaml's events. src/scene/scene_yaml.c describes the whole.
 */
#ifndef PDK_SCENE_YAML_H
#define PDK_SCENE_YAML_H

#include <stdint.h>
#include <yaml.h>

#include "scene_impl.h"
#include "pdk/ctx.h"

#define MAX_DEPTH PDK_SCENE_MAX_DEPTH
#define MAX_VALUES PDK_SCENE_MAX_VALUES
#define KEY_MAX 256

/* ---- hash index of names -----------------------------------------------------------------------
 *
 * Open addressing over a power-of-two table of item indices (-1: empty); the names live in the
 * items (key records, anchors), reached through name_of. A name put twice maps to the later item.
 */

typedef const char *(*name_of_fn)(const void *items, int k);

typedef struct name_index {
  int *slot;
  size_t cap; /* 0 or a power of two, at least twice the number of names */
  size_t num;
} name_index;

/* src/scene/scene_keys.c: the item of `name` (the latest put), or -1. */
int pdk_scene_index_find(const int *slot, size_t cap, const void *items, name_of_fn name_of,
                         const char *name);
/* Adds item k (items 0..k-1 are in the index); 0 when out of memory. */
int pdk_scene_index_put(name_index *ix, const void *items, name_of_fn name_of, int k);
/* name_of for an array of pdk_scene_key: its path. */
const char *pdk_scene_key_path_of(const void *items, int k);

/* ---- src/scene/scene_compose.c -----------------------------------------------------------------------
 */

/* Where a document comes from, for messages: the file, or the value of an override. */
typedef struct compose_src {
  const char *file;
  const char *override; /* NULL: the scene file */
  const char *base;     /* key path of the document's root ("" for the file) */
} compose_src;

/* Reads the next document of the stream into doc (initialized here; *have_doc set then). At the
 * end of the stream doc stays empty and *found is 0. */
int pdk_scene_compose_document(pdk_ctx *ctx, yaml_parser_t *ps, const compose_src *src,
                               yaml_document_t *doc, int *have_doc, int *found);
/* After a document: the stream must end there. */
int pdk_scene_compose_end(pdk_ctx *ctx, yaml_parser_t *ps, const compose_src *src);

#endif
