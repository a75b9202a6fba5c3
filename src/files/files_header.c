/* C header output: the keyframes as const arrays for firmware that plays them
 * with lsc_player (include/lsc/player.h); PROGMEM on AVR, where the sketch
 * reads them with pgm_read_word (examples/arduino/PlayKeyframes). */
/* Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST
#include <string.h>

#include "files_internal.h"

#define NAME_MAX_LEN 40u

static const char lower[] = "abcdefghijklmnopqrstuvwxyz";
static const char upper[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZ";

/* A C identifier from the file's base name without its extension: letters,
 * digits and '_' kept (lower case), anything else '_'; "keyframes" if empty;
 * a leading digit gets "kf_" before it. Returns its length. */
static size_t c_name(const char *path, char *out)
{
    const char *base = path != NULL ? strrchr(path, '/') : NULL;
    base = base != NULL ? base + 1 : path != NULL ? path : "";
    const char *dot = strrchr(base, '.');
    size_t n = dot != NULL ? (size_t)(dot - base) : strlen(base);
    size_t k = 0;
    if (n > 0 && base[0] >= '0' && base[0] <= '9') {
        memcpy(out, "kf_", 3);
        k = 3;
    }
    for (size_t i = 0; i < n && k < NAME_MAX_LEN; i++) {
        char c = base[i];
        bool alnum = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
        if (c >= 'A' && c <= 'Z') {
            c = lower[c - 'A'];
            alnum = true;
        }
        if (!alnum) {
            c = '_';
        }
        out[k++] = c;
    }
    if (k == 0) {
        memcpy(out, "keyframes", 9);
        k = 9;
    }
    out[k] = '\0';
    return k;
}

int lsc_files_header_format(const lsc_action *a, const char *name, lsc_outbuf *b,
                            lsc_file_error *err)
{
    char id[NAME_MAX_LEN + 1u], up[NAME_MAX_LEN + 1u];
    if (a->count == 0) {
        return lsc_files_fail(err, 0, "no keyframes: a C array cannot be empty");
    }
    size_t len = c_name(name, id);
    for (size_t i = 0; i < len; i++) {
        up[i] = id[i];
        if (id[i] >= 'a' && id[i] <= 'z') {
            up[i] = upper[id[i] - 'a'];
        }
    }
    up[len] = '\0';
    lsc_outbuf_printf(b,
                      "/* %u keyframes for %u servos, written by lscctl convert. Each row: the\n"
                      " * time since the previous keyframe (ms), then the position of each id.\n"
                      " * Play them with lsc_player (lsc/player.h): see\n"
                      " * examples/arduino/PlayKeyframes. */\n"
                      "#ifndef %s_KEYFRAMES_H\n#define %s_KEYFRAMES_H\n\n#include <stdint.h>\n\n"
                      "#if defined(__AVR__)\n#include <avr/pgmspace.h>\n"
                      "#define %s_STORAGE PROGMEM /* in flash: read with pgm_read_word */\n"
                      "#else\n#define %s_STORAGE\n#endif\n\n"
                      "#define %s_SERVOS %uu\n#define %s_COUNT %luu\n\n"
                      "static const uint8_t %s_ids[%s_SERVOS] = {",
                      (unsigned)a->count, a->nservos, up, up, up, up, up, a->nservos, up,
                      (unsigned long)a->count, id, up);
    for (size_t i = 0; i < a->nservos; i++) {
        lsc_outbuf_printf(b, "%s%u", i ? ", " : "", a->ids[i]);
    }
    lsc_outbuf_printf(b, "};\n\nstatic const uint16_t %s_keyframes[%s_COUNT * (1u + %s_SERVOS)] "
                         "%s_STORAGE = {\n",
                      id, up, up, up);
    lsc_outbuf_rows(b, a, "    ", ", ", ",");
    lsc_outbuf_printf(b, "};\n\n#endif\n");
    return 0;
}
#endif
