/* Run output (output.c), the helpers its files share: dataset names, XML and gnuplot quoting, the
 * list of fields for messages, and flushing the growing files. */
#include <errno.h>
#include <string.h>

#include "output_impl.h"
#include "pdk/ctx.h"
#include "pdk/output.h"
#include "pdk/particles.h"

/* ---- names ------------------------------------------------------------------------------------
 */

/* Dataset name of a field: every character outside [A-Za-z0-9_-] becomes '_'. */
void pdk_out_sanitize(const char *in, char *out, size_t cap) {
  size_t k = 0;
  for (; in[k] && k + 1 < cap; ++k) {
    char c = in[k];
    int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
             c == '_' || c == '-';
    out[k] = ok ? c : '_';
  }
  out[k] = '\0';
}

/* malloc'd copy of s with the five XML special characters escaped. */
char *pdk_out_xml_escape(const char *s) {
  size_t len = 0;
  for (const char *q = s; *q; ++q)
    len += *q == '&' ? 5 : (*q == '<' || *q == '>') ? 4 : (*q == '"' || *q == '\'') ? 6 : 1;
  char *out = malloc(len + 1), *w = out;
  if (!out) return NULL;
  for (const char *q = s; *q; ++q) {
    switch (*q) {
    case '&':
      memcpy(w, "&amp;", 5);
      w += 5;
      break;
    case '<':
      memcpy(w, "&lt;", 4);
      w += 4;
      break;
    case '>':
      memcpy(w, "&gt;", 4);
      w += 4;
      break;
    case '"':
      memcpy(w, "&quot;", 6);
      w += 6;
      break;
    case '\'':
      memcpy(w, "&apos;", 6);
      w += 6;
      break;
    default: *w++ = *q;
    }
  }
  *w = '\0';
  return out;
}

/* malloc'd copy of s for a single-quoted gnuplot string ('' stands for '). */
char *pdk_out_gnuplot_quote(const char *s) {
  size_t len = strlen(s);
  for (const char *q = s; *q; ++q)
    len += *q == '\'';
  char *out = malloc(len + 1), *w = out;
  if (!out) return NULL;
  for (const char *q = s; *q; ++q) {
    if (*q == '\'') *w++ = '\'';
    *w++ = *q;
  }
  *w = '\0';
  return out;
}

/* Comma-separated names of the registered fields, for "no such field" messages. */
void pdk_out_field_list(const pdk_particles *p, char *buf, size_t cap) {
  size_t len = 0;
  buf[0] = '\0';
  for (int k = 0; k < pdk_particles_num_fields(p) && len + 1 < cap; ++k) {
    int w = snprintf(buf + len, cap - len, "%s%s", k ? ", " : "", pdk_particles_field_name(p, k));
    if (w < 0) break;
    len += (size_t)w < cap - len ? (size_t)w : cap - len - 1;
  }
}

/* Flushes the three growing files; an error here usually means a full disk. */
int pdk_out_flush_files(pdk_output *o) {
  pdk_ctx *ctx = o->ctx;
  PDK_CHECK(fflush(o->xmf) == 0 && !ferror(o->xmf), ctx, PDK_ERR_IO, "cannot write '%s': %s",
            o->part[OUT_XMF], strerror(errno));
  PDK_CHECK(fflush(o->csv) == 0 && !ferror(o->csv), ctx, PDK_ERR_IO, "cannot write '%s': %s",
            o->part[OUT_CSV], strerror(errno));
  return pdk_h5_file_flush(ctx, o->file, o->part[OUT_H5]);
}
