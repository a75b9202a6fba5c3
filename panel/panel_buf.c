/* lsc-panel: the growing byte buffer and JSON strings (panel.h). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "panel.h"

void panel_buf_add(panel_buf *b, const char *s, size_t n)
{
    if (b->failed) {
        return;
    }
    if (b->len + n + 1u > b->cap) {
        size_t cap = b->cap ? b->cap : 256u;
        while (cap < b->len + n + 1u) {
            cap *= 2u;
        }
        char *d = realloc(b->data, cap);
        if (d == NULL) {
            b->failed = true;
            return;
        }
        b->data = d;
        b->cap = cap;
    }
    memcpy(b->data + b->len, s, n);
    b->len += n;
    b->data[b->len] = '\0';
}

void panel_buf_str(panel_buf *b, const char *s)
{
    panel_buf_add(b, s, strlen(s));
}

void panel_buf_printf(panel_buf *b, const char *fmt, ...)
{
    char tmp[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n > 0) {
        panel_buf_add(b, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1u);
    }
}

void panel_buf_json(panel_buf *b, const char *s)
{
    panel_buf_add(b, "\"", 1);
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        if (*c == '"' || *c == '\\') {
            char e[2] = {'\\', (char)*c};
            panel_buf_add(b, e, 2);
        } else if (*c < 0x20u || *c == 0x7fu) {
            panel_buf_printf(b, "\\u%04x", *c);
        } else {
            panel_buf_add(b, (const char *)c, 1);
        }
    }
    panel_buf_add(b, "\"", 1);
}

void panel_buf_free(panel_buf *b)
{
    free(b->data);
    memset(b, 0, sizeof *b);
}
