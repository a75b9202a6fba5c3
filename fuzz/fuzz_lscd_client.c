/* Fuzz harness for what a client of lscd makes of what an lscd sends
 * (src/lscd/lscd_io.c: the library's lscd: transport). The other direction,
 * what lscd makes of a client's bytes, is fuzz_lscd.c.
 *
 * Input: byte 0 + 1 is the largest chunk the client's reads bring; the rest is
 * the byte stream of a (possibly hostile) lscd.
 *
 * Checked on every input:
 *  - the client's reads return only whole controller frames, exactly as a
 *    parser fed the reads' bytes finds them, never lscd's own command and
 *    never a byte outside a frame;
 *  - after the end of the connection a read fails with an error code (never
 *    hangs: the client state has no socket), and the message is one
 *    NUL-terminated line of bounded length. */
#include <string.h>

#include "fuzz.h"
#include "lscd_proto.h"

typedef struct seen {
    lsc_parser p;
    uint8_t buf[LSC_FRAME_MAX];
    size_t frames;
} seen;

static void on_read(void *user, const uint8_t *data, size_t n)
{
    seen *s = user;
    FUZZ_CHECK(n > 0u && n <= LSC_FRAME_MAX);
    while (n > 0u) {
        lsc_frame f;
        int r = 0;
        size_t used = lsc_parser_feed_buf(&s->p, data, n, &f, &r);
        FUZZ_CHECK(used >= 1u && used <= n);
        FUZZ_CHECK(r >= 0); /* whole frames only */
        if (r == 1) {
            FUZZ_CHECK(f.cmd != LSC_LSCD_CMD);
            s->frames++;
        }
        data += used;
        n -= used;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0u) {
        return 0;
    }
    size_t chunk = (size_t)data[0] + 1u;
    seen s;
    memset(&s, 0, sizeof s);
    FUZZ_CHECK(lsc_parser_init(&s.p, s.buf, sizeof s.buf) == 0);
    static lscd_client_facts facts;
    lscd_client_digest(data + 1, size - 1u, chunk, on_read, &s, &facts);
    FUZZ_CHECK(s.p.discarded == 0u && s.p.errors == 0u);
    FUZZ_CHECK(facts.bytes_read == 0u || s.frames > 0u);
    FUZZ_CHECK(facts.last_read < 0);
    const char *end = memchr(facts.message, '\0', sizeof facts.message); /* (C99: no strnlen) */
    FUZZ_CHECK(end != NULL);
    size_t len = (size_t)(end - facts.message);
    FUZZ_CHECK(len > 0u && len < sizeof facts.message);
    FUZZ_CHECK(memchr(facts.message, '\n', len) == NULL);
    return 0;
}
