/* Text made safe for one-line messages (escape.h). */
#include "escape.h"

#include <string.h>

size_t lsc_escape_text(char *out, size_t cap, const char *s, size_t n)
{
    static const char hex[] = "0123456789ABCDEF";
    size_t len = 0;
    if (cap == 0) {
        return 0;
    }
    for (size_t i = 0; i < n && s[i] != '\0'; i++) {
        unsigned char c = (unsigned char)s[i];
        char one[4] = {'\\', '\\', 0, 0};
        size_t w = 2;
        if (c >= 0x20 && c < 0x7f && c != '\\') {
            one[0] = (char)c;
            w = 1;
        } else if (c != '\\') {
            one[1] = 'x';
            one[2] = hex[c >> 4];
            one[3] = hex[c & 0x0fu];
            w = 4;
        }
        if (len + w >= cap) {
            break;
        }
        memcpy(out + len, one, w);
        len += w;
    }
    out[len] = '\0';
    return len;
}
