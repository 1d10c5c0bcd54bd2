/* Scene loading, step 2 (src/scene/scene.c): the final YAML against the schema. The values libcyaml
 * 1.3.1 would misread (a number followed by text, any word as true) are refused before libcyaml
 * sees them (pdk_scene_scalars_check); libcyaml's own errors come through the log callback as a
 * message plus a backtrace of mapping fields and sequence entries, turned here into a key path and
 * from it into "<file>:<line>: <key.path>: ..." (src/scene/scene_load.h).
 */
#include "core/ext.h"
#include "scene_load.h"
#include "pdk/ctx.h"
#include "pdk/scene.h"

/* ---- schema lookup by key path (for messages) --------------------------------------------------
 */

/* The schema value at key path `path` (segments "a.b[2].c"), or NULL. */
static const cyaml_schema_value_t *schema_at(const cyaml_schema_value_t *v, const char *path) {
  const char *c = path;
  while (v && *c) {
    if (*c == '.') ++c;
    if (*c == '[') {
      if (v->type != CYAML_SEQUENCE && v->type != CYAML_SEQUENCE_FIXED) return NULL;
      v = v->sequence.entry;
      c = strchr(c, ']');
      if (!c) return NULL;
      ++c;
      continue;
    }
    size_t len = strcspn(c, ".[");
    if (v->type != CYAML_MAPPING) return NULL;
    const cyaml_schema_field_t *f = v->mapping.fields, *hit = NULL;
    for (; f && f->key; ++f)
      if (strlen(f->key) == len && !strncmp(f->key, c, len)) hit = f;
    if (!hit) return NULL;
    v = &hit->value;
    c += len;
  }
  return v;
}

static void list_keys(const cyaml_schema_value_t *v, int required_only, char *buf, size_t len) {
  size_t pos = 0;
  buf[0] = '\0';
  if (!v || v->type != CYAML_MAPPING) return;
  for (const cyaml_schema_field_t *f = v->mapping.fields; f && f->key; ++f) {
    if (required_only && (f->value.flags & CYAML_FLAG_OPTIONAL)) continue;
    int w = snprintf(buf + pos, len - pos, "%s%s", pos ? ", " : "", f->key);
    if (w < 0 || (size_t)w >= len - pos) return;
    pos += (size_t)w;
  }
}

static void list_enum(const cyaml_schema_value_t *v, char *buf, size_t len) {
  size_t pos = 0;
  buf[0] = '\0';
  if (!v || v->type != CYAML_ENUM) return;
  for (uint32_t i = 0; i < v->enumeration.count; ++i) {
    int w = snprintf(buf + pos, len - pos, "%s%s", i ? ", " : "", v->enumeration.strings[i].str);
    if (w < 0 || (size_t)w >= len - pos) return;
    pos += (size_t)w;
  }
}

static const char *type_words(const cyaml_schema_value_t *v) {
  if (!v) return "a value of another type";
  switch (v->type) {
  case CYAML_FLOAT: return "a number";
  case CYAML_INT:
  case CYAML_UINT: return "a whole number";
  case CYAML_BOOL: return "true or false";
  case CYAML_STRING: return "a word or quoted string";
  case CYAML_ENUM: return "one of the listed words";
  case CYAML_MAPPING: return "a mapping of keys (key: value)";
  case CYAML_SEQUENCE:
  case CYAML_SEQUENCE_FIXED: return "a list [a, b, ...]";
  default: return "a value of another type";
  }
}

/* What to write instead, for a value of the wrong type. */
static void type_hint(const cyaml_schema_value_t *v, char *buf, size_t len) {
  char keys[512];
  if (!v) {
    snprintf(buf, len, "see docs/scenes.md");
    return;
  }
  switch (v->type) {
  case CYAML_FLOAT:
  case CYAML_INT:
  case CYAML_UINT: snprintf(buf, len, "write for example 0.5, 2e-3 or 200e9"); break;
  case CYAML_BOOL: snprintf(buf, len, "write true or false"); break;
  case CYAML_STRING: snprintf(buf, len, "write a word or a quoted string"); break;
  case CYAML_MAPPING:
    list_keys(v, 0, keys, sizeof keys);
    snprintf(buf, len, "give its keys on the lines below it, or as {key: value, ...}; keys: %s",
             keys);
    break;
  case CYAML_SEQUENCE:
  case CYAML_SEQUENCE_FIXED: snprintf(buf, len, "write a list, [a, b, ...] or '- a' lines"); break;
  default: snprintf(buf, len, "see docs/scenes.md"); break;
  }
}

/* ---- libcyaml log capture and translation ------------------------------------------------------
 */

void pdk_scene_cyaml_log(cyaml_log_t level, void *ctx, const char *fmt, va_list args) {
  cy_log *log = ctx;
  if (level < CYAML_LOG_ERROR || log->len + 1 >= sizeof log->text) return;
  int w = vsnprintf(log->text + log->len, sizeof log->text - log->len, fmt, args);
  if (w > 0) log->len += (size_t)w;
  if (log->len >= sizeof log->text) log->len = sizeof log->text - 1;
}

/* Turns libcyaml's message and backtrace into a scene message. Returns 0 when the log holds
 * nothing recognizable (the caller keeps the generic libcyaml failure message). The backtrace is
 * innermost first: "  in mapping field 'k' (line ...)", "  in sequence entry 'n' (...)", "  in
 * mapping (...)". While an entry is being loaded, n counts it (1-based); for "Insufficient" and
 * "Excessive entries" n is the count reached, and the error is about the sequence itself. */
static int cy_translate(pdk_ctx *ctx, const pdk_scene *s, const scene_schema *sc,
                        const cy_log *log) {
  char msg[512] = "";
  char frames[32][KEY_MAX];
  int is_entry[32];
  int nf = 0;
  const char *c = log->text;
  while (*c) {
    const char *eol = strchr(c, '\n');
    size_t len = eol ? (size_t)(eol - c) : strlen(c);
    char line[512];
    if (len >= sizeof line) len = sizeof line - 1;
    memcpy(line, c, len);
    line[len] = '\0';
    c += len + (eol ? 1 : 0);
    char name[KEY_MAX];
    unsigned idx;
    if (!strncmp(line, "Load: ", 6) && strcmp(line, "Load: Backtrace:")) {
      if (!msg[0]) snprintf(msg, sizeof msg, "%s", line + 6);
    } else if (sscanf(line, "  in mapping field '%255[^']'", name) == 1 && nf < 32) {
      snprintf(frames[nf], KEY_MAX, "%s", name);
      is_entry[nf++] = 0;
    } else if (sscanf(line, "  in sequence entry '%u'", &idx) == 1 && nf < 32) {
      snprintf(frames[nf], KEY_MAX, "%u", idx);
      is_entry[nf++] = 1;
    }
  }
  if (!msg[0]) return 0;
  int about_sequence =
      !strncmp(msg, "Insufficient entries", 20) || !strncmp(msg, "Excessive entries", 17);
  /* For a missing key, the innermost frame is the last field libcyaml saw in that mapping (or the
   * first field of an empty one): not part of the mapping's path. */
  const int missing = !strncmp(msg, "Missing required mapping field", 30);
  int first = 0;
  if (about_sequence && nf > 0 && is_entry[0]) first = 1;
  if (missing && nf > 0 && !is_entry[0]) first = 1;
  /* Key path, outermost first. */
  char path[KEY_MAX] = "";
  for (int f = nf - 1; f >= first; --f) {
    size_t pos = strlen(path);
    if (is_entry[f]) {
      unsigned n = (unsigned)strtoul(frames[f], NULL, 10);
      snprintf(path + pos, sizeof path - pos, "[%u]", n > 0 ? n - 1 : 0);
    } else {
      snprintf(path + pos, sizeof path - pos, "%s%s", pos ? "." : "", frames[f]);
    }
  }
  char arg[256] = "", allowed[512];
  const char *colon = strchr(msg, ':');
  if (colon) snprintf(arg, sizeof arg, "%s", colon + 2 <= msg + strlen(msg) ? colon + 2 : "");
  const pdk_scene_key *key = pdk_scene_key_get(s, path);
  const char *got = key && key->value ? key->value : NULL;

  if (!strncmp(msg, "Unexpected key", 14)) {
    list_keys(schema_at(&sc->top, path), 0, allowed, sizeof allowed);
    char full[2 * KEY_MAX + 2];
    snprintf(full, sizeof full, "%s%s%s", path, path[0] ? "." : "", arg);
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, full, "unknown key '%s'; %s allows: %s", arg,
                           path[0] ? path : "the top level", allowed);
  }
  if (missing) {
    char full[2 * KEY_MAX + 2], parent[KEY_MAX];
    snprintf(full, sizeof full, "%s%s%s", path, path[0] ? "." : "", arg);
    snprintf(parent, sizeof parent, "%s", path);
    list_keys(schema_at(&sc->top, parent), 1, allowed, sizeof allowed);
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, full,
                           "required key is missing; %s needs: %s (see docs/scenes.md)",
                           parent[0] ? parent : "the top level", allowed);
  }
  if (!strncmp(msg, "Invalid ENUM value", 18)) {
    list_enum(schema_at(&sc->top, path), allowed, sizeof allowed);
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "unknown value '%s'; allowed: %s", arg,
                           allowed);
  }
  if (!strncmp(msg, "Invalid FLOAT value", 19) || !strncmp(msg, "Invalid INT value", 17) ||
      !strncmp(msg, "Invalid UINT value", 18))
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path,
                           "must be a number, got '%s'; write for "
                           "example 0.5, 2e-3 or 200e9",
                           got ? got : arg);
  if (!strncmp(msg, "Expecting ", 10)) {
    const cyaml_schema_value_t *v = schema_at(&sc->top, path);
    char hint[600];
    type_hint(v, hint, sizeof hint);
    const char *what = strstr(msg, "SEQUENCE_START")  ? "a list"
                       : strstr(msg, "MAPPING_START") ? "a mapping"
                       : got                          ? NULL
                                                      : "a single value";
    if (v && v->type == CYAML_ENUM) {
      list_enum(v, allowed, sizeof allowed);
      return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "must be one word, got %s; allowed: %s",
                             what ? what : "something else", allowed);
    }
    if (what)
      return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "must be %s, got %s; %s", type_words(v),
                             what, hint);
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "must be %s, got '%s'; %s", type_words(v),
                           got, hint);
  }
  if (about_sequence) {
    const cyaml_schema_value_t *v = schema_at(&sc->top, path);
    unsigned have = 0, want = 0;
    const int is_point = v && v->type == CYAML_SEQUENCE_FIXED && v->sequence.entry &&
                         v->sequence.entry->type == CYAML_FLOAT;
    const int excess = !strncmp(msg, "Excessive", 9);
    if (excess)
      sscanf(msg, "Excessive entries (%u max)", &want);
    else
      sscanf(msg, "Insufficient entries (%u of %u min)", &have, &want);
    /* libcyaml stops at the first entry too many; the document says how many there are. */
    unsigned count = key && key->count >= 0 ? (unsigned)key->count : want + 1;
    if (!excess) count = have;
    if (is_point)
      return pdk_scene_error(s, ctx, PDK_ERR_ARG, path,
                             "must have %u numbers, got %u; a point has one number per axis "
                             "(dimension is %d)",
                             want, count, s->dim);
    if (v && v->type == CYAML_SEQUENCE_FIXED)
      return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "must have %u entries, got %u", want,
                             count);
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "must have at %s %u entries, got %u",
                           excess ? "most" : "least", want, count);
  }
  if (!strncmp(msg, "Mapping field already seen", 26))
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "given twice; give each key once");
  if (!strncmp(msg, "String length", 13) || strstr(msg, "string length"))
    return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "%s; names are 1 to 255 characters", msg);
  return pdk_scene_error(s, ctx, PDK_ERR_ARG, path, "%s; see docs/scenes.md", msg);
}

/* A YAML decimal number, whole: [+-] digits [. digits] [e [+-] digits], or [+-] . digits [e ...];
 * `integer`: digits only. No hexadecimal, inf, nan, '_' or ','. */
static int is_number_text(const char *v, int integer) {
  const char *c = v;
  if (*c == '+' || *c == '-') ++c;
  int digits = 0;
  while (isdigit((unsigned char)*c)) {
    ++c;
    ++digits;
  }
  if (integer) return digits > 0 && !*c;
  if (*c == '.') {
    ++c;
    while (isdigit((unsigned char)*c)) {
      ++c;
      ++digits;
    }
  }
  if (!digits) return 0;
  if (*c == 'e' || *c == 'E') {
    ++c;
    if (*c == '+' || *c == '-') ++c;
    if (!isdigit((unsigned char)*c)) return 0;
    while (isdigit((unsigned char)*c))
      ++c;
  }
  return *c == '\0';
}

/* Step 2, before libcyaml: every single value whose key the schema types as a number or a boolean,
 * and every list against its cap. libcyaml would read "0,29" as 0 and "flase" as true; counting a
 * list first keeps a long one from costing more than reading it. */
int pdk_scene_scalars_check(pdk_ctx *ctx, const pdk_scene *s, const scene_schema *sc) {
  for (int k = 0; k < s->num_keys; ++k) {
    const pdk_scene_key *key = &s->keys[k];
    const cyaml_schema_value_t *v = schema_at(&sc->top, key->path);
    if (!v) continue; /* an unknown key: libcyaml names it */
    if (key->count >= 0) {
      if (v->type == CYAML_SEQUENCE && v->sequence.max != CYAML_UNLIMITED &&
          key->count > (long)v->sequence.max)
        return pdk_scene_error(s, ctx, PDK_ERR_ARG, key->path,
                               "must have at most %u entries, got %ld", v->sequence.max,
                               key->count);
      continue;
    }
    if (!key->value) continue; /* a mapping */
    char shown[128];
    pdk_scene_quote(key->value, shown, sizeof shown);
    switch (v->type) {
    case CYAML_FLOAT:
    case CYAML_INT:
    case CYAML_UINT: {
      const int integer = v->type != CYAML_FLOAT;
      if (!key->value[0])
        return pdk_scene_error(s, ctx, PDK_ERR_ARG, key->path,
                               "must be %s, got nothing; write for example %s", type_words(v),
                               integer ? "0, 10 or 250" : "0.5, 2e-3 or 200e9");
      if (!is_number_text(key->value, integer))
        return pdk_scene_error(s, ctx, PDK_ERR_ARG, key->path,
                               "must be %s, got '%s'; write for example %s (the whole value is "
                               "the number: no unit, '_' or ',')",
                               type_words(v), shown,
                               integer ? "0, 10 or 250" : "0.5, 2e-3 or 200e9");
      if (!isfinite(strtod(key->value, NULL)))
        return pdk_scene_error(s, ctx, PDK_ERR_ARG, key->path,
                               "must be a finite number, got '%s', beyond the largest double "
                               "(1.8e308)",
                               shown);
      break;
    }
    case CYAML_BOOL: {
      static const char *const words[] = {"true", "True", "TRUE", "false", "False", "FALSE"};
      int ok = 0;
      for (int w = 0; w < 6; ++w)
        ok |= !strcmp(key->value, words[w]);
      if (!ok)
        return pdk_scene_error(s, ctx, PDK_ERR_ARG, key->path, "must be true or false, got '%s'",
                               shown);
      break;
    }
    default: break;
    }
  }
  return PDK_SUCCESS;
}

int pdk_scene_schema_load(pdk_ctx *ctx, const pdk_scene *s, const scene_schema *sc,
                          const cyaml_config_t *cfg, const char *yaml, size_t len, sc_scene **out) {
  int err = PDK_SUCCESS;
  PDK_CYAML_CALL_GOTO(
      ctx, cyaml_load_data((const uint8_t *)yaml, len, cfg, &sc->top, (cyaml_data_t **)out, NULL));
cleanup:
  if (err) {
    const cy_log *log = cfg->log_ctx;
    int translated = cy_translate(ctx, s, sc, log);
    if (translated) err = translated;
  }
  return err;
}

int pdk_scene_schema_free(pdk_ctx *ctx, const scene_schema *sc, const cyaml_config_t *cfg,
                          sc_scene *data) {
  int err = PDK_SUCCESS;
  PDK_CYAML_CALL_GOTO(ctx, cyaml_free(cfg, &sc->top, data, 0));
cleanup:
  return err;
}
