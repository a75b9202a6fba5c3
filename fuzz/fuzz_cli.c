/* Fuzz harness for what lscctl takes from its command line and from
 * `lscctl decode`'s input (tools-common/lscctl_parse.h): numbers, lists of servos
 * (record --ids: lsc_device_parse_ids, lsc/device.h), hex bytes,
 * repeated-id detection.
 *
 * Input: byte 0 picks the function; then its parameters; the rest is the
 * text (made NUL-terminated). Checked on every input:
 *  - lscctl_parse_uint agrees with an independent model of its grammar
 *    (decimal, or 0x/0X and hex digits; no sign; value <= max), for every
 *    max up to ULONG_MAX (no wrap-around); on failure *out is untouched and
 *    the reason is a non-empty string within its buffer;
 *  - lsc_device_parse_ids (no arm profile, room for 32 servos): never
 *    writes past that room (canaries); a list it accepts holds 1..32
 *    distinct ids, which printed back as decimal and hex items parse to the
 *    same ids; a refusal's reason is one line of printable ASCII (text
 *    from the list escaped);
 *  - lscctl_parse_hex never writes at or past cap (canaries), never takes
 *    more bytes than strlen/2 + 1 (what `decode` sizes its buffer by), and
 *    the bytes it accepts, printed back as hex, parse to the same bytes;
 *  - lsc_ids_first_repeat finds exactly the first repeated id.
 */
#include <limits.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "fuzz.h"
#include "lsc/device.h"
#include "lsc/text.h"
#include "lscctl_parse.h"

#define TEXT_MAX 1024u

static int digit(char c, unsigned base)
{
    const char *digits = "0123456789abcdef";
    const char *upper = "0123456789ABCDEF";
    for (unsigned i = 0; i < base; i++) {
        if (c == digits[i] || c == upper[i]) {
            return (int)i;
        }
    }
    return -1;
}

/* The grammar of lscctl_parse_uint, written independently. */
static bool model_uint(const char *s, unsigned long long max, unsigned long long *v)
{
    unsigned base = 10;
    if (s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
        base = 16;
        s += 2;
    }
    if (*s == '\0') {
        return false;
    }
    *v = 0;
    for (; *s != '\0'; s++) {
        int d = digit(*s, base);
        if (d < 0) {
            return false;
        }
        if (*v > (max - (unsigned)d) / base || (unsigned)d > max) {
            return false; /* *v * base + d > max, without overflowing */
        }
        *v = *v * base + (unsigned)d;
    }
    return true;
}

static void check_why(const char *why, size_t cap)
{
    FUZZ_CHECK(memchr(why, '\0', cap) != NULL && why[0] != '\0');
}

static void fuzz_uint(const char *s, unsigned long max)
{
    char why[96];
    unsigned long out = 0xA5A5A5A5ul;
    unsigned long long want = 0;
    bool ok = model_uint(s, max, &want);
    int r = lscctl_parse_uint(s, max, "value", &out, why, sizeof why);
    FUZZ_CHECK(r == (ok ? 0 : -1));
    if (ok) {
        FUZZ_CHECK(out == want && out <= max);
    } else {
        FUZZ_CHECK(out == 0xA5A5A5A5ul);
        check_why(why, sizeof why);
    }
}

#define IDS_CAP 32u

static void fuzz_ids(const char *s)
{
    uint8_t ids[IDS_CAP + 8], again[IDS_CAP];
    char why[200];
    static char text[IDS_CAP * 6u + 1u];
    memset(ids, FUZZ_CANARY, sizeof ids);
    int n = lsc_device_parse_ids(NULL, s, ids, IDS_CAP, why, sizeof why);
    for (size_t i = IDS_CAP; i < sizeof ids; i++) {
        FUZZ_CHECK(ids[i] == FUZZ_CANARY);
    }
    if (n < 0) {
        FUZZ_CHECK(n == LSC_EINVAL);
        check_why(why, sizeof why);
        for (const char *c = why; *c != '\0'; c++) {
            FUZZ_CHECK(*c >= 0x20 && *c < 0x7f); /* one line, nothing raw */
        }
        return;
    }
    FUZZ_CHECK(n >= 1 && (size_t)n <= IDS_CAP);
    FUZZ_CHECK(lsc_ids_first_repeat(ids, 1, (size_t)n) == (size_t)n);
    for (int hex = 0; hex < 2; hex++) {
        size_t len = 0;
        for (int i = 0; i < n; i++) {
            len += (size_t)snprintf(text + len, sizeof text - len, hex ? "%s0x%X" : "%s%u",
                                    i > 0 ? "," : "", (unsigned)ids[i]);
        }
        FUZZ_CHECK(lsc_device_parse_ids(NULL, text, again, IDS_CAP, why, sizeof why) == n);
        FUZZ_CHECK(memcmp(again, ids, (size_t)n) == 0);
    }
}

static void fuzz_hex(const char *s, size_t cap, size_t start)
{
    uint8_t buf[256 + 16], again[256 + 16];
    char why[128];
    static char text[3u * 256u + 1u];
    memset(buf, FUZZ_CANARY, sizeof buf);
    size_t n = start;
    int r = lscctl_parse_hex(s, buf, cap, &n, why, sizeof why);
    FUZZ_CHECK(n >= start && n <= cap);
    for (size_t i = cap; i < sizeof buf; i++) {
        FUZZ_CHECK(buf[i] == FUZZ_CANARY);
    }
    if (r != 0) {
        FUZZ_CHECK(r == -1);
        check_why(why, sizeof why);
        return;
    }
    FUZZ_CHECK(n - start <= strlen(s) / 2u + 1u);
    size_t len = 0;
    text[0] = '\0';
    for (size_t i = start; i < n; i++) {
        len += (size_t)snprintf(text + len, sizeof text - len, i % 2u ? "%02X," : "%02x ", buf[i]);
    }
    size_t m = 0;
    FUZZ_CHECK(lscctl_parse_hex(text, again, sizeof again, &m, why, sizeof why) == 0);
    FUZZ_CHECK(m == n - start && memcmp(again, buf + start, m) == 0);
}

static void fuzz_repeat(const uint8_t *ids, size_t n, size_t stride)
{
    /* against a table of those seen: another way to the same answer */
    uint8_t seen[256] = {0};
    size_t want = n / stride;
    for (size_t i = 0; i < n / stride && want == n / stride; i++) {
        want = seen[ids[i * stride]] ? i : want;
        seen[ids[i * stride]] = 1;
    }
    FUZZ_CHECK(lsc_ids_first_repeat(ids, stride, n / stride) == want);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char s[TEXT_MAX + 1];
    if (size < 1) {
        return 0;
    }
    uint8_t mode = data[0] % 4u;
    size_t head = mode == 0 ? 9 : mode == 2 ? 3 : 1;
    uint8_t p[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    for (size_t i = 1; i < head && i < size; i++) {
        p[i - 1] = data[i];
    }
    size_t len = 0;
    for (size_t i = head; i < size && len < TEXT_MAX; i++) {
        s[len++] = (char)data[i];
    }
    s[len] = '\0';
    switch (mode) {
    case 0: {
        unsigned long long max = 0;
        for (size_t i = 8; i > 0; i--) {
            max = max << 8 | p[i - 1];
        }
        fuzz_uint(s, (unsigned long)(max > ULONG_MAX ? ULONG_MAX : max));
        break;
    }
    case 1: fuzz_ids(s); break;
    case 2: fuzz_hex(s, p[0], p[1] <= p[0] ? p[1] : p[0]); break;
    default: fuzz_repeat(data + 1, size - 1, (size_t)(data[0] >> 2) % 3u + 1u); break;
    }
    return 0;
}
