/* The registry of model kinds (src/models/model_registry.h): one line each. The correspondence laws
 * are listed in src/models/law_registry.c. */
#include <stdio.h>
#include <string.h>

#include "model_registry.h"
#include "pdk/model.h"

/* The kinds, in the order scenes list them (the first is the scenes' default model.kind): each
 * defines pdk_model_kind_<name> in its own file. */
#define PDK_MODEL_KINDS(X) X(pmb) X(lps) X(corr) X(oterkus) X(galerkin)

#define PDK_DECLARE_KIND(k) extern const pdk_model_kind_info pdk_model_kind_##k;
#define PDK_LIST_KIND(k) &pdk_model_kind_##k,
PDK_MODEL_KINDS(PDK_DECLARE_KIND)
static const pdk_model_kind_info *const kinds[] = {PDK_MODEL_KINDS(PDK_LIST_KIND)};
#define NUM_KINDS ((int)(sizeof kinds / sizeof kinds[0]))

const pdk_model_kind_info *pdk_model_kind_at(int i) {
  return i >= 0 && i < NUM_KINDS ? kinds[i] : NULL;
}

const pdk_model_kind_info *pdk_model_kind_info_of(pdk_model_kind kind) {
  for (int i = 0; i < NUM_KINDS; ++i)
    if (kinds[i]->kind == kind) return kinds[i];
  return NULL;
}

const char *pdk_model_kind_name(pdk_model_kind kind) {
  const pdk_model_kind_info *k = pdk_model_kind_info_of(kind);
  return k ? k->name : "?";
}

/* Appends names[0 .. count) to buf joined by ", " and `last`. */
static const char *join(const char *const *names, int count, const char *last, char *buf,
                        size_t len) {
  size_t pos = 0;
  buf[0] = '\0';
  for (int k = 0; k < count && pos < len; ++k) {
    const char *sep = k == 0 ? "" : k == count - 1 ? last : ", ";
    const int w = snprintf(buf + pos, len - pos, "%s%s", sep, names[k]);
    if (w < 0) break;
    pos += (size_t)w;
  }
  return buf;
}

const char *pdk_model_kinds_list(unsigned mask, unsigned want, const char *last, char *buf,
                                 size_t len) {
  const char *names[NUM_KINDS];
  int count = 0;
  for (int i = 0; i < NUM_KINDS; ++i)
    if ((kinds[i]->caps & mask) == want) names[count++] = kinds[i]->name;
  return join(names, count, last, buf, len);
}

const pdk_model_derived_info *pdk_model_kind_derived(pdk_model_kind kind, const char *name) {
  const pdk_model_kind_info *k = pdk_model_kind_info_of(kind);
  if (!k || !k->derived) return NULL;
  for (const pdk_model_derived_info *d = k->derived; d->name; ++d)
    if (!strcmp(d->name, name)) return d;
  return NULL;
}

const pdk_model_kind_info *pdk_model_derived_owner(const char *name,
                                                   const pdk_model_derived_info **out) {
  for (int i = 0; i < NUM_KINDS; ++i) {
    if (!(kinds[i]->caps & PDK_KIND_SCENE)) continue;
    const pdk_model_derived_info *d = pdk_model_kind_derived(kinds[i]->kind, name);
    if (d) {
      if (out) *out = d;
      return kinds[i];
    }
  }
  return NULL;
}

static int key_listed(const char *const *keys, const char *key) {
  for (int k = 0; keys && keys[k]; ++k)
    if (!strcmp(keys[k], key)) return 1;
  return 0;
}

const char *pdk_model_scene_key_at(int i) {
  int count = 0;
  for (int a = 0; a < NUM_KINDS; ++a)
    for (int k = 0; kinds[a]->scene_keys && kinds[a]->scene_keys[k]; ++k) {
      const char *key = kinds[a]->scene_keys[k];
      int seen = 0;
      for (int b = 0; b < a && !seen; ++b)
        seen = key_listed(kinds[b]->scene_keys, key);
      if (!seen && count++ == i) return key;
    }
  return NULL;
}

int pdk_model_opts_scene_key(const pdk_model_opts *o, const char *key) {
  const pdk_model_kind_info *k = pdk_model_kind_info_of(o->kind);
  if (k && key_listed(k->scene_keys, key)) return 1;
  for (int i = 0; pdk_model_scene_key_at(i); ++i)
    if (!strcmp(pdk_model_scene_key_at(i), key)) return 0;
  return 1;
}

const char *pdk_model_key_kinds(const char *key, const char *last, char *buf, size_t len,
                                int *count) {
  const char *names[NUM_KINDS];
  int c = 0;
  for (int i = 0; i < NUM_KINDS; ++i)
    if ((kinds[i]->caps & PDK_KIND_SCENE) && key_listed(kinds[i]->scene_keys, key))
      names[c++] = kinds[i]->name;
  if (count) *count = c;
  return join(names, c, last, buf, len);
}

int pdk_model_opts_has(const pdk_model_opts *o, unsigned cap) {
  const pdk_model_kind_info *k = pdk_model_kind_info_of(o->kind);
  return k && (k->caps & cap) == cap;
}

int pdk_model_opts_hops(const pdk_model_opts *o) {
  const pdk_model_kind_info *k = pdk_model_kind_info_of(o->kind);
  return k ? k->hops : 2;
}

int pdk_model_opts_hyperelastic(const pdk_model_opts *o) {
  const pdk_model_kind_info *k = pdk_model_kind_info_of(o->kind);
  return k && (!k->hyperelastic || k->hyperelastic(o));
}

int pdk_model_opts_unstabilized(const pdk_model_opts *o) {
  const pdk_model_kind_info *k = pdk_model_kind_info_of(o->kind);
  return k && k->unstabilized && k->unstabilized(o);
}

int pdk_model_opts_stencil_rows(const pdk_model_opts *o) {
  const pdk_model_kind_info *k = pdk_model_kind_info_of(o->kind);
  return k && k->stencil_rows && k->stencil_rows(o);
}

int pdk_model_opts_law_has(const pdk_model_opts *o, unsigned flags) {
  const pdk_law_info *l = pdk_law_info_of(o->law);
  return pdk_model_opts_has(o, PDK_KIND_LAWS) && l && (l->flags & flags) == flags;
}

int pdk_model_opts_rate_terms(const pdk_model_opts *o, char *buf, size_t len) {
  const pdk_law_info *l = pdk_law_info_of(o->law);
  return pdk_model_opts_has(o, PDK_KIND_LAWS) && l && l->rate_terms && l->rate_terms(o, buf, len);
}

int pdk_model_opts_law_breaks(const pdk_model_opts *o) {
  const pdk_law_info *l = pdk_law_info_of(o->law);
  return pdk_model_opts_has(o, PDK_KIND_LAWS) && l && l->breaks_bonds && l->breaks_bonds(o);
}
