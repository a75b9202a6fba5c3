/* The virtual bus's text form: what its servos keep at power-off
 * (lsc_lxbus_save, lsc_lxbus_load in include/lsc/lxbus.h). */
#include "lsc/lxbus.h"

#include <string.h>

#include "lxbus_internal.h"

/* ---- Writing ------------------------------------------------------------------ */

typedef struct writer {
    char *buf;
    size_t cap, len; /* len may pass cap: the text did not fit */
} writer;

static void put_str(writer *w, const char *s)
{
    for (; *s != '\0'; s++) {
        if (w->len + 1u < w->cap) {
            w->buf[w->len] = *s;
        }
        w->len++;
    }
}

static void put_int(writer *w, int32_t v)
{
    char digits[12];
    size_t n = 0;
    uint32_t u = v < 0 ? (uint32_t)0 - (uint32_t)v : (uint32_t)v;
    do {
        digits[n++] = (char)('0' + u % 10u);
        u /= 10u;
    } while (u > 0u);
    if (v < 0) {
        put_str(w, "-");
    }
    while (n > 0u) {
        char one[2] = {digits[--n], '\0'};
        put_str(w, one);
    }
}

int lsc_lxbus_save(const lsc_lxbus *bus, char *buf, size_t cap)
{
    if (bus == NULL || buf == NULL) {
        return LSC_EINVAL;
    }
    writer w = {buf, cap, 0};
    put_str(&w, "# lsc-sim bus servos: what each keeps at power-off, one line a servo\n"
                "# (its id, saved offset, angle limits, voltage limits in mV, temperature\n"
                "# limit in degrees C, LED, and where its shaft rests)\n");
    for (size_t i = 0; i < bus->nservos; i++) {
        const lsc_lxbus_servo *s = &bus->servo[i];
        put_str(&w, "servo id=");
        put_int(&w, s->id);
        put_str(&w, " offset=");
        put_int(&w, s->offset_saved);
        put_str(&w, " limits=");
        put_int(&w, s->limit_min);
        put_str(&w, ",");
        put_int(&w, s->limit_max);
        put_str(&w, " vin-limits=");
        put_int(&w, s->vin_min);
        put_str(&w, ",");
        put_int(&w, s->vin_max);
        put_str(&w, " temp-limit=");
        put_int(&w, s->temp_limit);
        put_str(&w, s->led_on ? " led=on" : " led=off");
        put_str(&w, " position=");
        put_int(&w, lsc_lxbus_shaft(s, bus->now_us));
        put_str(&w, "\n");
    }
    if (cap > 0u) {
        buf[w.len < cap ? w.len : cap - 1u] = '\0';
    }
    return w.len < cap ? (int)w.len : LSC_ENOSPC;
}

/* ---- Reading -------------------------------------------------------------------- */

typedef struct reader {
    const char *text;
    size_t at;
    uint32_t line;
    size_t line_start;
    lsc_sim_parse_error *err;
} reader;

static int fail(reader *r, size_t at, const char *why)
{
    if (r->err != NULL) {
        r->err->line = r->line;
        r->err->column = (uint32_t)(at - r->line_start + 1u);
        r->err->message = why;
    }
    return LSC_EINVAL;
}

static bool is_space(char c)
{
    return c == ' ' || c == '\t';
}

/* The end of the token at `at` (up to a space, a CR or the line's end). */
static size_t token_end(const reader *r, size_t at, size_t eol)
{
    while (at < eol && !is_space(r->text[at]) && r->text[at] != '\r') {
        at++;
    }
    return at;
}

/* A decimal integer text[at..end) in lo..hi into *v. */
static bool number(const char *text, size_t at, size_t end, int32_t lo, int32_t hi, int32_t *v)
{
    bool neg = at < end && text[at] == '-';
    int32_t n = 0;
    at += neg;
    if (at == end || end - at > 6u) {
        return false;
    }
    for (; at < end; at++) {
        if (text[at] < '0' || text[at] > '9') {
            return false;
        }
        n = n * 10 + (text[at] - '0');
    }
    n = neg ? -n : n;
    if (n < lo || n > hi) {
        return false;
    }
    *v = n;
    return true;
}

/* Two numbers "A,B" text[at..end) with lo <= A < B <= hi. */
static bool pair(const char *text, size_t at, size_t end, int32_t lo, int32_t hi, int32_t *a,
                 int32_t *b)
{
    size_t comma = at;
    while (comma < end && text[comma] != ',') {
        comma++;
    }
    return comma < end && number(text, at, comma, lo, hi, a) &&
           number(text, comma + 1u, end, lo, hi, b) && *a < *b;
}

enum { KEY_ID, KEY_OFFSET, KEY_LIMITS, KEY_VIN, KEY_TEMP, KEY_LED, KEY_POSITION, KEYS };
static const char *const key_names[KEYS] = {"id", "offset", "limits", "vin-limits",
                                            "temp-limit", "led", "position"};
static const char *const key_errors[KEYS] = {
    "id: use 0..253",
    "offset: use -125..125",
    "limits: use MIN,MAX with 0 <= MIN < MAX <= 1000",
    "vin-limits: use MIN,MAX millivolts with 4500 <= MIN < MAX <= 12000",
    "temp-limit: use 50..100 (degrees C)",
    "led: use on or off",
    "position: use -1000..2000",
};

/* One "key=value" at text[at..end) into s (and *shaft). */
static int parse_pair(reader *r, size_t at, size_t end, lsc_lxbus_servo *s, int32_t *shaft,
                      unsigned *seen)
{
    const char *t = r->text;
    size_t eq = at;
    while (eq < end && t[eq] != '=') {
        eq++;
    }
    unsigned k = 0;
    while (k < KEYS && (strlen(key_names[k]) != eq - at ||
                        memcmp(key_names[k], &t[at], eq - at) != 0)) {
        k++;
    }
    if (k == KEYS || eq == end) {
        return fail(r, at, "expected KEY=VALUE with a key of id, offset, limits, vin-limits, "
                           "temp-limit, led, position");
    }
    if ((*seen & (1u << k)) != 0u) {
        return fail(r, at, "a key given twice");
    }
    *seen |= 1u << k;
    size_t v = eq + 1u;
    int32_t a = 0, b = 0;
    bool ok;
    switch (k) {
    case KEY_ID:
        ok = number(t, v, end, 0, LSC_LX_ID_MAX, &a);
        s->id = (uint8_t)a;
        break;
    case KEY_OFFSET:
        ok = number(t, v, end, -LSC_LX_OFFSET_MAX, LSC_LX_OFFSET_MAX, &a);
        s->offset_saved = (int8_t)a;
        break;
    case KEY_LIMITS:
        ok = pair(t, v, end, 0, LSC_LX_POSITION_MAX, &a, &b);
        s->limit_min = (uint16_t)a;
        s->limit_max = (uint16_t)b;
        break;
    case KEY_VIN:
        ok = pair(t, v, end, LSC_LX_VIN_MIN, LSC_LX_VIN_MAX, &a, &b);
        s->vin_min = (uint16_t)a;
        s->vin_max = (uint16_t)b;
        break;
    case KEY_TEMP:
        ok = number(t, v, end, LSC_LX_TEMP_LIMIT_MIN, LSC_LX_TEMP_LIMIT_MAX, &a);
        s->temp_limit = (uint8_t)a;
        break;
    case KEY_LED:
        ok = (end - v == 2u && memcmp(&t[v], "on", 2) == 0) ||
             (end - v == 3u && memcmp(&t[v], "off", 3) == 0);
        s->led_on = end - v == 2u;
        break;
    default: /* KEY_POSITION */
        ok = number(t, v, end, -1000, 2000, &a);
        *shaft = a;
        break;
    }
    return ok ? 0 : fail(r, v, key_errors[k]);
}

int lsc_lxbus_load(lsc_lxbus *bus, const char *text, size_t len, lsc_sim_parse_error *err)
{
    lsc_lxbus_servo servos[LSC_LXBUS_SERVOS];
    int32_t shafts[LSC_LXBUS_SERVOS];
    size_t n = 0;
    if (err != NULL) {
        err->line = 0;
        err->column = 0;
        err->message = "no error";
    }
    if (bus == NULL || (text == NULL && len > 0u)) {
        return LSC_EINVAL;
    }
    reader r = {text, 0, 1, 0, err};
    while (r.at < len) {
        size_t eol = r.at;
        while (eol < len && text[eol] != '\n') {
            eol++;
        }
        size_t at = r.at;
        while (at < eol && is_space(text[at])) {
            at++;
        }
        if (at < eol && text[at] != '#' && text[at] != '\r') {
            size_t end = token_end(&r, at, eol);
            if (end - at != 5u || memcmp(&text[at], "servo", 5) != 0) {
                return fail(&r, at, "expected a line \"servo KEY=VALUE...\"");
            }
            if (n == LSC_LXBUS_SERVOS) {
                (void)fail(&r, at, "more servos than a bus holds (32)");
                return LSC_ENOSPC;
            }
            lsc_lxbus_servo *s = &servos[n];
            lsc_lxbus_servo_fresh(s, LSC_LX_ID_DEFAULT);
            shafts[n] = LSC_LXBUS_POSITION_DEFAULT;
            unsigned seen = 0;
            for (;;) {
                at = end;
                while (at < eol && is_space(text[at])) {
                    at++;
                }
                if (at == eol || (text[at] == '\r' && at + 1u == eol)) {
                    break;
                }
                end = token_end(&r, at, eol);
                if (end == at) {
                    return fail(&r, at, "a carriage return inside a line");
                }
                int rc = parse_pair(&r, at, end, s, &shafts[n], &seen);
                if (rc != 0) {
                    return rc;
                }
            }
            n++;
        }
        r.at = eol + 1u;
        r.line_start = r.at;
        r.line++;
    }
    for (size_t i = 0; i < n; i++) {
        bus->servo[i] = servos[i];
        lsc_lxbus_servo_power_on(&bus->servo[i], shafts[i]);
        bus->servo[i].start_us = bus->now_us;
    }
    bus->nservos = n;
    bus->changes++;
    return (int)n;
}
