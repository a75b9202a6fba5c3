#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "sim_util.h"

static lsc_sim_step util_steps[256];
static lsc_servo util_targets[1024];

void sim_util_load(lsc_sim *sim, lsc_sim_groups *g, const char *text)
{
    lsc_sim_parse_error err;
    assert_int_equal(lsc_sim_groups_init(g, util_steps, 256, util_targets, 1024), 0);
    int r = lsc_sim_groups_parse(g, text, strlen(text), &err);
    if (r < 0) {
        fail_msg("group text line %u col %u: %s", (unsigned)err.line, (unsigned)err.column,
                 err.message);
    }
    lsc_sim_set_groups(sim, g);
}

void sim_util_feed(lsc_sim *sim, const uint8_t *frame, int n)
{
    assert_true(n > 0);
    assert_int_equal(lsc_sim_feed(sim, frame, (size_t)n), n);
}

void sim_util_expect(lsc_sim *sim, const uint8_t *bytes, size_t n)
{
    uint8_t got[LSC_SIM_OUT_BYTES];
    assert_int_equal(lsc_sim_available(sim), n);
    size_t k = lsc_sim_read(sim, got, sizeof got);
    assert_int_equal(k, n);
    assert_memory_equal(got, bytes, n);
}

void sim_util_expect_none(lsc_sim *sim)
{
    uint8_t got[1];
    assert_int_equal(lsc_sim_available(sim), 0);
    assert_int_equal(lsc_sim_read(sim, got, sizeof got), 0);
}

uint16_t sim_util_read_pos(lsc_sim *sim, uint8_t id)
{
    uint8_t frame[LSC_FRAME_MAX];
    uint8_t got[LSC_FRAME_MAX];
    lsc_parser p;
    lsc_frame f;
    lsc_servo s;
    int n = lsc_encode_pos_request(frame, sizeof frame, &id, 1);
    sim_util_feed(sim, frame, n);
    size_t k = lsc_sim_read(sim, got, sizeof got);
    assert_int_equal(k, 8);
    assert_int_equal(lsc_parser_init(&p, frame, sizeof frame), 0);
    for (size_t i = 0; i + 1 < k; i++) {
        assert_int_equal(lsc_parser_feed(&p, got[i], &f), 0);
    }
    assert_int_equal(lsc_parser_feed(&p, got[k - 1], &f), 1);
    assert_int_equal(lsc_decode_pos_reply(&f, &s, 1), 1);
    assert_int_equal(s.id, id);
    return s.position;
}
