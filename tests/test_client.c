/* The client against a scripted in-memory transport with a fake clock: every
 * call, notifications around replies, split and noisy input, wrong-shape
 * replies, timeouts, the frame gap, invalid arguments. Byte vectors come from
 * the LSC protocol V1.2 examples (position reply with the document's
 * big-endian misprint corrected: 500 is F4 01). */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "lsc/client.h"
#include "test_hex.h"

/* ---- Scripted transport --------------------------------------------------- */

#define MAX_CHUNKS 4096
#define POOL 65536

typedef struct chunk {
    uint32_t at; /* becomes readable at this fake time */
    size_t off, n;
} chunk;

typedef struct script {
    uint32_t now;
    chunk chunks[MAX_CHUNKS];
    size_t nchunks, next, pos; /* pos: bytes of chunks[next] already read */
    uint8_t pool[POOL];
    size_t used;
    uint8_t sent[POOL];
    size_t nsent;
    size_t max_read; /* bytes per read at most (0: no limit) */
    bool merge;      /* a read also takes the following chunks readable by now */
    int read_error, write_error, write_result; /* forced results (0: none) */
    unsigned reads;
} script;

static script S;

static void reset_script(void)
{
    memset(&S, 0, sizeof S);
}

/* Adds a chunk readable from time at, bytes given as hex ("55 55 02 07"). */
static void add(uint32_t at, const char *hex)
{
    chunk *c = &S.chunks[S.nchunks++];
    c->at = at;
    c->off = S.used;
    c->n = test_hex(hex, S.pool + S.used, POOL - S.used);
    S.used += c->n;
}

static int s_write(void *ctx, const uint8_t *data, size_t n)
{
    (void)ctx;
    if (S.write_error) {
        return S.write_error;
    }
    memcpy(S.sent + S.nsent, data, n);
    S.nsent += n;
    return S.write_result ? S.write_result : (int)n;
}

/* With S.merge it calls itself once per further chunk it merges: the depth is
 * bounded by the script's chunk count. */
static int s_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms) // NOLINT(misc-no-recursion)
{
    (void)ctx;
    S.reads++;
    if (S.read_error) {
        return S.read_error;
    }
    if (S.next < S.nchunks && S.chunks[S.next].at <= S.now + timeout_ms) {
        chunk *c = &S.chunks[S.next];
        if (c->at > S.now) {
            S.now = c->at;
        }
        size_t n = c->n - S.pos;
        if (n > cap) {
            n = cap;
        }
        if (S.max_read && n > S.max_read) {
            n = S.max_read;
        }
        memcpy(buf, S.pool + c->off + S.pos, n);
        S.pos += n;
        if (S.pos == c->n) {
            S.next++;
            S.pos = 0;
            if (S.merge && n < cap && (!S.max_read || n < S.max_read)) {
                int more = s_read(ctx, buf + n, S.max_read ? S.max_read - n : cap - n, 0);
                S.reads--;
                return (int)n + (more > 0 ? more : 0);
            }
        }
        return (int)n;
    }
    S.now += timeout_ms;
    return 0;
}

static uint32_t s_now(void *ctx)
{
    (void)ctx;
    return S.now;
}

static const lsc_io IO = {NULL, s_write, s_read, s_now};

/* Compares what was sent with hex. */
static void sent_is(const char *hex)
{
    uint8_t want[512];
    size_t n = test_hex(hex, want, sizeof want);
    assert_int_equal(S.nsent, n);
    assert_memory_equal(S.sent, want, n);
}

/* ---- Notification and trace recorders ---------------------------------------- */

static lsc_notification notes[2048];
static size_t nnotes;
static uint32_t note_time[2048];

static void record(void *user, const lsc_notification *n)
{
    assert_ptr_equal(user, &nnotes);
    note_time[nnotes] = S.now;
    notes[nnotes++] = *n;
}

static lsc_client C;

static int setup(void **state)
{
    (void)state;
    reset_script();
    nnotes = 0;
    assert_int_equal(lsc_client_init(&C, &IO), 0);
    lsc_client_set_notify(&C, record, &nnotes);
    return 0;
}

static void note_is(size_t i, uint8_t cmd, uint8_t group, uint16_t times)
{
    assert_true(i < nnotes);
    assert_int_equal(notes[i].cmd, cmd);
    assert_int_equal(notes[i].group, group);
    assert_int_equal(notes[i].times, times);
}

#define BATTERY_REQ "55 55 02 0F"
#define BATTERY_7500 "55 55 04 0F 4C 1D"
#define STARTED_8 "55 55 05 06 08 01 00"
#define STOPPED "55 55 02 07"
#define COMPLETE_8 "55 55 05 08 08 01 00"
#define POS_REQ_1_6 "55 55 09 15 06 01 02 03 04 05 06"
#define POS_REPLY_1_6                                                                     \
    "55 55 15 15 06 01 F4 01 02 F4 01 03 F4 01 04 F4 01 05 F4 01 06 F4 01"

/* ---- Init and sending ------------------------------------------------------------- */

static void init_rejects_incomplete_io(void **state)
{
    (void)state;
    lsc_io io = IO;
    io.now_ms = NULL;
    assert_int_equal(lsc_client_init(NULL, &IO), LSC_EINVAL);
    assert_int_equal(lsc_client_init(&C, NULL), LSC_EINVAL);
    assert_int_equal(lsc_client_init(&C, &io), LSC_EINVAL);
    uint16_t mv;
    lsc_servo out[1];
    uint8_t id = 1;
    assert_int_equal(lsc_client_stop_group(&C), LSC_EINVAL);
    assert_int_equal(lsc_client_move_one(&C, 1, 500, 100), LSC_EINVAL);
    assert_int_equal(lsc_client_run_group(&C, 1, 1), LSC_EINVAL);
    assert_int_equal(lsc_client_set_group_speed(&C, 1, 100), LSC_EINVAL);
    assert_int_equal(lsc_client_unload(&C, &id, 1), LSC_EINVAL);
    assert_int_equal(lsc_client_send_raw(&C, 7, NULL, 0), LSC_EINVAL);
    assert_int_equal(lsc_client_get_battery(&C, &mv, 10), LSC_EINVAL);
    assert_int_equal(lsc_client_read_positions(&C, &id, 1, out, 10), LSC_EINVAL);
    assert_int_equal(lsc_client_poll(&C, 0), LSC_EINVAL);
    assert_int_equal(lsc_client_wait_group(&C, 10, NULL), LSC_EINVAL);
    assert_int_equal(lsc_client_request_raw(&C, 15, NULL, 0, 15, NULL, 0, 10), LSC_EINVAL);
    assert_int_equal(S.nsent, 0);
    assert_int_equal(S.reads, 0);
}

static void move_one(void **state)
{
    (void)state;
    assert_int_equal(lsc_client_move_one(&C, 1, 2000, 1000), 0);
    sent_is("55 55 08 03 01 E8 03 01 D0 07");
    assert_int_equal(S.reads, 0); /* sending never reads */
}

static void move_many(void **state)
{
    (void)state;
    lsc_servo s[2] = {{2, 1200}, {9, 2300}};
    assert_int_equal(lsc_client_move(&C, 800, s, 2), 0);
    sent_is("55 55 0B 03 02 20 03 02 B0 04 09 FC 08");
}

static void run_stop_speed_unload(void **state)
{
    (void)state;
    uint8_t ids[6] = {1, 2, 3, 4, 5, 6};
    assert_int_equal(lsc_client_run_group(&C, 8, 1), 0);
    assert_int_equal(lsc_client_run_group(&C, 2, 0), 0);
    assert_int_equal(lsc_client_stop_group(&C), 0);
    assert_int_equal(lsc_client_set_group_speed(&C, 8, 50), 0);
    assert_int_equal(lsc_client_set_group_speed(&C, LSC_GROUP_ALL, 300), 0);
    assert_int_equal(lsc_client_unload(&C, ids, 3), 0);
    assert_int_equal(lsc_client_unload(&C, ids, 6), 0);
    sent_is("55 55 05 06 08 01 00  55 55 05 06 02 00 00  55 55 02 07"
            "55 55 05 0B 08 32 00  55 55 05 0B FF 2C 01"
            "55 55 06 14 03 01 02 03  55 55 09 14 06 01 02 03 04 05 06");
    assert_int_equal(S.reads, 0);
}

static void invalid_arguments_send_nothing(void **state)
{
    (void)state;
    lsc_servo dup[2] = {{1, 500}, {1, 600}};
    lsc_servo many[LSC_MOVE_MAX + 1];
    uint8_t ids[LSC_UNLOAD_MAX + 1];
    for (size_t i = 0; i < LSC_MOVE_MAX + 1; i++) {
        many[i].id = (uint8_t)i;
        many[i].position = 500;
    }
    for (size_t i = 0; i < sizeof ids; i++) {
        ids[i] = (uint8_t)i;
    }
    uint8_t same[2] = {3, 3};
    lsc_servo out[LSC_READ_MAX + 1];
    uint8_t params[LSC_PARAMS_MAX + 1] = {0};
    uint8_t reply[8];
    assert_int_equal(lsc_client_move(&C, 100, dup, 0), LSC_EINVAL);
    assert_int_equal(lsc_client_move(&C, 100, NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_client_move(&C, 100, dup, 2), LSC_EINVAL);
    assert_int_equal(lsc_client_move(&C, 100, many, LSC_MOVE_MAX + 1), LSC_EINVAL);
    assert_int_equal(lsc_client_unload(&C, ids, 0), LSC_EINVAL);
    assert_int_equal(lsc_client_unload(&C, ids, 82), LSC_EINVAL);
    assert_int_equal(lsc_client_unload(&C, ids, LSC_UNLOAD_MAX + 1), LSC_EINVAL);
    assert_int_equal(lsc_client_unload(&C, same, 2), LSC_EINVAL);
    assert_int_equal(lsc_client_read_positions(&C, ids, 0, out, 10), LSC_EINVAL);
    assert_int_equal(lsc_client_read_positions(&C, ids, 82, out, 10), LSC_EINVAL);
    assert_int_equal(lsc_client_read_positions(&C, ids, LSC_READ_MAX + 1, out, 10), LSC_EINVAL);
    assert_int_equal(lsc_client_read_positions(&C, same, 2, out, 10), LSC_EINVAL);
    assert_int_equal(lsc_client_read_positions(&C, ids, 1, NULL, 10), LSC_EINVAL);
    assert_int_equal(lsc_client_get_battery(&C, NULL, 10), LSC_EINVAL);
    assert_int_equal(lsc_client_send_raw(&C, 8, params, 3), LSC_EINVAL);
    assert_int_equal(lsc_client_send_raw(&C, 3, params, LSC_PARAMS_MAX + 1), LSC_EINVAL);
    assert_int_equal(lsc_client_send_raw(&C, 3, params, 83), LSC_EINVAL);
    assert_int_equal(lsc_client_send_raw(&C, 3, NULL, 2), LSC_EINVAL);
    for (uint8_t cmd = 6; cmd <= 8; cmd++) {
        assert_int_equal(lsc_client_request_raw(&C, 15, NULL, 0, cmd, reply, 8, 10), LSC_EINVAL);
    }
    assert_int_equal(lsc_client_request_raw(&C, 8, NULL, 0, 15, reply, 8, 10), LSC_EINVAL);
    assert_int_equal(lsc_client_request_raw(&C, 15, NULL, 0, 15, NULL, 8, 10), LSC_EINVAL);
    assert_int_equal(lsc_client_request_raw(&C, 15, NULL, 300, 15, reply, 8, 10), LSC_EINVAL);
    assert_int_equal(S.nsent, 0);
    assert_int_equal(S.reads, 0); /* refused before draining input, too */
}

/* ---- Replies ------------------------------------------------------------------------ */

static void battery(void **state)
{
    (void)state;
    add(5, BATTERY_7500);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), 0);
    assert_int_equal(mv, 7500);
    sent_is(BATTERY_REQ);
    assert_int_equal(S.now, 5); /* returned as soon as the reply came */
}

static void positions(void **state)
{
    (void)state;
    uint8_t ids[6] = {1, 2, 3, 4, 5, 6};
    lsc_servo out[6];
    add(3, POS_REPLY_1_6);
    assert_int_equal(lsc_client_read_positions(&C, ids, 6, out, 100), 6);
    sent_is(POS_REQ_1_6);
    for (size_t i = 0; i < 6; i++) {
        assert_int_equal(out[i].id, i + 1);
        assert_int_equal(out[i].position, 500);
    }
}

static void positions_in_the_order_asked(void **state)
{
    (void)state;
    uint8_t ids[3] = {9, 2, 31};
    lsc_servo out[3] = {{0, 0}, {0, 0}, {0, 0}};
    /* same ids, other order: not this request's answer */
    add(1, "55 55 0C 15 03 02 10 00 09 20 00 1F 30 00");
    add(2, "55 55 0C 15 03 09 E8 03 02 D0 07 1F 34 12");
    assert_int_equal(lsc_client_read_positions(&C, ids, 3, out, 100), 3);
    assert_int_equal(out[0].id, 9);
    assert_int_equal(out[0].position, 1000);
    assert_int_equal(out[1].id, 2);
    assert_int_equal(out[1].position, 2000);
    assert_int_equal(out[2].id, 31);
    assert_int_equal(out[2].position, 0x1234);
    assert_int_equal(C.unexpected, 1);
}

static void positions_wrong_ids_only(void **state)
{
    (void)state;
    uint8_t ids[2] = {1, 2};
    lsc_servo out[2] = {{7, 7}, {7, 7}};
    add(1, "55 55 09 15 02 01 F4 01 03 F4 01"); /* id 3 instead of 2 */
    add(2, "55 55 06 15 01 01 F4 01");           /* one servo instead of two */
    add(3, "55 55 05 15 02 01 02");              /* the request echoed back */
    assert_int_equal(lsc_client_read_positions(&C, ids, 2, out, 200), LSC_EREPLY);
    assert_int_equal(S.now, 200);
    assert_int_equal(out[0].id, 7); /* untouched */
    assert_int_equal(C.unexpected, 3);
}

/* xArm servo offsets: 24 is sent as is; a 23 reply is taken only with the
 * ids asked, in order; a board that does not answer times out. */
static void offsets(void **state)
{
    (void)state;
    const uint8_t ids[2] = {6, 1};
    lsc_servo_offset out[2] = {{7, 7}, {7, 7}};
    assert_int_equal(lsc_client_adjust_offset(&C, 6, -10), 0);
    sent_is("55 55 04 18 06 F6");
    assert_int_equal(lsc_client_adjust_offset(NULL, 6, -10), LSC_EINVAL);
    add(1, "55 55 07 17 02 01 05 06 F6"); /* the ids in another order */
    add(2, "55 55 05 17 01 06 F6");       /* one servo of two */
    add(3, "55 55 07 17 02 06 F6 01 05");
    assert_int_equal(lsc_client_read_offsets(&C, ids, 2, out, 200), 2);
    assert_int_equal(out[0].id, 6);
    assert_int_equal(out[0].offset, -10);
    assert_int_equal(out[1].id, 1);
    assert_int_equal(out[1].offset, 5);
    add(4, "55 55 07 17 02 06 F6 06 05"); /* a repeated id: malformed */
    out[0].id = 9;
    assert_int_equal(lsc_client_read_offsets(&C, ids, 2, out, 200), LSC_EREPLY);
    assert_int_equal(out[0].id, 9);
    assert_int_equal(lsc_client_read_offsets(&C, ids, 2, out, 50), LSC_ETIMEOUT);
    assert_int_equal(lsc_client_read_offsets(&C, ids, 2, NULL, 50), LSC_EINVAL);
    assert_int_equal(lsc_client_read_offsets(&C, ids, 0, out, 50), LSC_EINVAL);
}

static void notifications_around_replies(void **state)
{
    (void)state;
    uint16_t mv = 0;
    add(1, STARTED_8);
    add(2, "55 55 04"); /* the reply arrives in pieces */
    add(3, "0F 4C");
    add(4, "1D " COMPLETE_8); /* a notification right behind it, same chunk */
    add(50, STOPPED);         /* between two replies */
    add(60, "55 55 04 0F 10 27");
    add(70, STARTED_8);       /* after the second reply */
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), 0);
    assert_int_equal(mv, 7500);
    assert_int_equal(nnotes, 2); /* both delivered before the call returned */
    note_is(0, 6, 8, 1);
    note_is(1, 8, 8, 1);
    assert_int_equal(note_time[0], 1);
    S.now = 40;
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), 0);
    assert_int_equal(mv, 10000);
    assert_int_equal(nnotes, 3);
    note_is(2, 7, 0, 0);
    assert_int_equal(lsc_client_poll(&C, 100), 1);
    assert_int_equal(nnotes, 4);
    note_is(3, 6, 8, 1);
    assert_int_equal(C.notifications, 4);
    sent_is(BATTERY_REQ " " BATTERY_REQ);
}

static void byte_by_byte(void **state)
{
    (void)state;
    S.max_read = 1;
    uint8_t ids[6] = {1, 2, 3, 4, 5, 6};
    lsc_servo out[6];
    add(1, STARTED_8 " " POS_REPLY_1_6 " " COMPLETE_8);
    assert_int_equal(lsc_client_read_positions(&C, ids, 6, out, 100), 6);
    assert_int_equal(out[5].position, 500);
    assert_int_equal(nnotes, 1); /* returns at the reply's last byte */
    assert_int_equal(lsc_client_poll(&C, 0), 0); /* one byte per read */
    for (int i = 0; i < 7 && nnotes < 2; i++) {
        assert_true(lsc_client_poll(&C, 0) >= 0);
    }
    assert_int_equal(nnotes, 2);
    note_is(0, 6, 8, 1);
    note_is(1, 8, 8, 1);
}

static void garbage_before_reply(void **state)
{
    (void)state;
    uint16_t mv = 0;
    add(1, "00 13 FF 55 AA 55 00 0F 55 55 01");
    add(2, BATTERY_7500);
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), 0);
    assert_int_equal(mv, 7500);
}

static void wrong_shape_reply_then_right_one(void **state)
{
    (void)state;
    uint16_t mv = 0;
    add(1, BATTERY_REQ); /* an echo of the request: command 15, no voltage */
    add(2, "55 55 05 0B 08 32 00"); /* some other frame */
    add(3, BATTERY_7500);
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), 0);
    assert_int_equal(mv, 7500);
    assert_int_equal(C.unexpected, 2);
}

static void wrong_shape_only_is_ereply(void **state)
{
    (void)state;
    uint16_t mv = 1;
    add(1, BATTERY_REQ);
    assert_int_equal(lsc_client_get_battery(&C, &mv, 300), LSC_EREPLY);
    assert_int_equal(mv, 1);
    assert_int_equal(S.now, 300); /* the wait went on to the timeout */
}

static void malformed_only_is_ereply(void **state)
{
    (void)state;
    uint16_t mv = 1;
    add(1, "55 55 03 0F 4C"); /* LEN 3 contradicts command 15 */
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), LSC_EREPLY);
    assert_int_equal(S.now, 100);
}

static void silence_times_out(void **state)
{
    (void)state;
    static const uint32_t timeouts[] = {0, 1, 50, 500, 3000};
    for (size_t i = 0; i < sizeof timeouts / sizeof timeouts[0]; i++) {
        uint16_t mv = 0;
        uint32_t start = S.now;
        assert_int_equal(lsc_client_get_battery(&C, &mv, timeouts[i]), LSC_ETIMEOUT);
        uint32_t took = S.now - start;
        assert_true(took >= timeouts[i]);
        assert_true(took * 5u <= timeouts[i] * 6u); /* within 20% */
    }
    assert_int_equal(S.nsent, 5 * 4);
}

static void notifications_do_not_extend_the_timeout(void **state)
{
    (void)state;
    for (uint32_t t = 0; t < 1000; t += 10) {
        add(t, STARTED_8);
    }
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&C, &mv, 200), LSC_ETIMEOUT);
    assert_true(S.now >= 200 && S.now <= 240);
    assert_true(nnotes >= 20);
}

static void thousand_notifications_while_waiting(void **state)
{
    (void)state;
    for (unsigned i = 0; i < 1000; i++) {
        char hex[64];
        (void)snprintf(hex, sizeof hex, "55 55 05 06 %02X %02X %02X", i % 256u, i & 0xFFu,
                       i >> 8);
        add(1 + i / 10u, hex);
    }
    add(150, COMPLETE_8);
    lsc_notification end;
    assert_int_equal(lsc_client_wait_group(&C, 1000, &end), 0);
    assert_int_equal(end.cmd, 8);
    assert_int_equal(end.group, 8);
    assert_int_equal(end.times, 1);
    assert_int_equal(nnotes, 1001);
    for (unsigned i = 0; i < 1000; i++) {
        note_is(i, 6, (uint8_t)(i % 256u), (uint16_t)i);
    }
    note_is(1000, 8, 8, 1);
    assert_int_equal(S.nsent, 0); /* waiting sends nothing */
}

static void thousand_notifications_before_a_reply(void **state)
{
    (void)state;
    S.max_read = 3;
    for (unsigned i = 0; i < 1000; i++) {
        add(1, i % 2 ? STOPPED : STARTED_8);
    }
    add(2, BATTERY_7500);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), LSC_OK);
    assert_int_equal(mv, 7500);
    assert_int_equal(nnotes, 1000);
    note_is(999, 7, 0, 0);
}

static void wait_group_stopped_and_timeout(void **state)
{
    (void)state;
    lsc_notification end = {0, 9, 9};
    add(10, STARTED_8);
    add(20, STOPPED);
    assert_int_equal(lsc_client_wait_group(&C, 100, &end), 0);
    assert_int_equal(end.cmd, 7);
    assert_int_equal(end.group, 0);
    assert_int_equal(S.now, 20);
    assert_int_equal(nnotes, 2);
    end.cmd = 99;
    add(30, "55 55 03 08 00"); /* malformed: not an end */
    assert_int_equal(lsc_client_wait_group(&C, 400, &end), LSC_ETIMEOUT);
    assert_int_equal(end.cmd, 99);
    assert_int_equal(S.now, 420);
    add(500, COMPLETE_8);
    assert_int_equal(lsc_client_wait_group(&C, 100, NULL), 0);
}

static void stale_reply_is_not_taken(void **state)
{
    (void)state;
    add(0, "55 55 04 0F 10 27 " COMPLETE_8); /* arrived before the request */
    add(5, BATTERY_7500);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), 0);
    assert_int_equal(mv, 7500);
    assert_int_equal(nnotes, 1); /* the notification in it was delivered */
}

/* Input that came before a request is drained however large the backlog: a
 * stale reply after 1050 bytes of notifications is not taken for this one's. */
static void stale_reply_after_a_large_backlog_is_not_taken(void **state)
{
    (void)state;
    static char hex[3 * 1100];
    size_t len = 0;
    for (int i = 0; i < 150; i++) {
        len += (size_t)snprintf(hex + len, sizeof hex - len, "%s ", COMPLETE_8);
    }
    (void)snprintf(hex + len, sizeof hex - len, "55 55 04 0F 10 27"); /* 10000 mV, stale */
    add(0, hex);
    add(5, BATTERY_7500);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), 0);
    assert_int_equal(mv, 7500);
    assert_int_equal(nnotes, 150);
}

/* Copies frame (n bytes) to buf as a read would (at most cap); returns the count. */
static int give(uint8_t *buf, size_t cap, const uint8_t *frame, size_t n)
{
    n = cap < n ? cap : n;
    memcpy(buf, frame, n);
    return (int)n;
}

/* A transport whose input never stops: a stop notification each read, 1 ms apart. */
static uint32_t endless_now;
static uint32_t endless_sent_at;
static int endless_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    (void)ctx;
    (void)timeout_ms;
    static const uint8_t stopped[] = {0x55, 0x55, 0x02, 0x07};
    endless_now++;
    return give(buf, cap, stopped, sizeof stopped);
}
static int endless_write(void *ctx, const uint8_t *data, size_t n)
{
    (void)ctx;
    (void)data;
    endless_sent_at = endless_now;
    return (int)n;
}
static uint32_t endless_clock(void *ctx)
{
    (void)ctx;
    return endless_now;
}

/* The drain before a request ends after LSC_CLIENT_DRAIN_MS even if the input
 * never stops; the request then goes out and times out on time. */
static void drain_of_endless_input_is_bounded(void **state)
{
    (void)state;
    const lsc_io io = {NULL, endless_write, endless_read, endless_clock};
    lsc_client c;
    assert_int_equal(lsc_client_init(&c, &io), 0);
    endless_now = 1000;
    endless_sent_at = 0;
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&c, &mv, 100), LSC_ETIMEOUT);
    assert_int_equal(endless_sent_at, 1000 + LSC_CLIENT_DRAIN_MS);
    assert_true(endless_now - endless_sent_at <= 101);
    assert_true(c.notifications > LSC_CLIENT_DRAIN_MS);
}

/* A transport whose clock never advances while its input never stops: a
 * "group 8 started" notification each read, endless_now left as it is (the
 * clock is endless_clock, the write endless_write). After FROZEN_MAX reads
 * (far more than any budget below but UINT32_MAX's) it fails the read
 * (LSC_EIO), so a client that would read for ever ends the test instead of
 * hanging it. */
#define FROZEN_MAX 200000u
static unsigned frozen_reads;
static int frozen_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    (void)ctx;
    (void)timeout_ms;
    static const uint8_t started[] = {0x55, 0x55, 0x05, 0x06, 0x08, 0x01, 0x00};
    if (++frozen_reads > FROZEN_MAX) {
        return LSC_EIO;
    }
    return give(buf, cap, started, sizeof started);
}

/* With a frozen clock and endless input, the drain ends after
 * LSC_CLIENT_DRAIN_READS reads (the request goes out) and every wait after
 * its read budget: nothing reads for ever. */
static void frozen_clock_and_endless_input_end(void **state)
{
    (void)state;
    const lsc_io io = {NULL, endless_write, frozen_read, endless_clock};
    lsc_client c;
    endless_now = 5000;
    endless_sent_at = 0;
    assert_int_equal(lsc_client_init(&c, &io), 0);
    frozen_reads = 0;
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&c, &mv, 100), LSC_ETIMEOUT);
    assert_int_equal(endless_sent_at, 5000); /* the request went out */
    assert_int_equal(endless_now, 5000);
    uint32_t budget = LSC_CLIENT_WAIT_READS_MIN + LSC_CLIENT_READS_PER_MS * 100u;
    assert_int_equal(frozen_reads, LSC_CLIENT_DRAIN_READS + budget);
    frozen_reads = 0;
    assert_int_equal(lsc_client_wait_group(&c, 100, NULL), LSC_ETIMEOUT);
    assert_int_equal(frozen_reads, budget);
    frozen_reads = 0;
    assert_int_equal(lsc_client_get_battery(&c, &mv, 0), LSC_ETIMEOUT);
    assert_int_equal(frozen_reads, LSC_CLIENT_DRAIN_READS + 1u); /* timeout 0: one read */
    /* the longest timeout's budget saturates instead of wrapping to a few reads */
    frozen_reads = 0;
    assert_int_equal(lsc_client_wait_group(&c, UINT32_MAX, NULL), LSC_EIO);
    assert_int_equal(frozen_reads, FROZEN_MAX + 1u);
}

/* What arrived during a request that got no reply can be told apart through
 * lsc_client_get_counts: noise only, notifications only, other frames. */
static void counts_say_what_arrived(void **state)
{
    (void)state;
    lsc_client_counts before, after;
    uint16_t mv = 0;
    lsc_client_get_counts(&C, &before);
    add(5, "00 11 22 33 44 F0 0F FF"); /* noise: a wrong baud rate looks like this */
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), LSC_ETIMEOUT);
    lsc_client_get_counts(&C, &after);
    assert_int_equal(after.frames - before.frames, 0);
    assert_int_equal(after.discarded - before.discarded, 8);
    assert_int_equal(after.pending, 0);
    before = after;
    add(S.now + 5, STARTED_8 " " COMPLETE_8);
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), LSC_ETIMEOUT);
    lsc_client_get_counts(&C, &after);
    assert_int_equal(after.frames - before.frames, 2);
    assert_int_equal(after.notifications - before.notifications, 2);
    assert_int_equal(after.unexpected - before.unexpected, 0);
    before = after;
    add(S.now + 5, "55 55 03 33 01 55 55"); /* another command's frame, then a partial one */
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), LSC_ETIMEOUT);
    lsc_client_get_counts(&C, &after);
    assert_int_equal(after.frames - before.frames, 1);
    assert_int_equal(after.unexpected - before.unexpected, 1);
    assert_int_equal(after.discarded - before.discarded, 2); /* dropped on the frame gap */
    assert_int_equal(after.malformed - before.malformed, 0);
    add(S.now + 5, "55 55 04 0F 4C 1D 55 55"); /* a reply, then a frame still arriving */
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), 0);
    lsc_client_get_counts(&C, &after);
    assert_int_equal(after.pending, 2);
    lsc_client_get_counts(NULL, &after);
    assert_int_equal(after.frames + after.discarded + after.pending, 0);
    lsc_client_get_counts(&C, NULL); /* harmless */
}

/* SECURITY.md's known limit, pinned: a battery reply torn after its first
 * data byte, followed within the frame gap by another frame, decodes with the
 * next frame's first byte as its high byte: 0x554C = 21836 mV. */
static void torn_reply_glued_to_the_next_frame_within_the_gap(void **state)
{
    (void)state;
    add(5, "55 55 04 0F 4C");
    add(5 + LSC_CLIENT_GAP_MS - 1, STOPPED);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&C, &mv, 200), 0);
    assert_int_equal(mv, 21836);
}

static void frame_gap_resets_the_parser(void **state)
{
    (void)state;
    uint16_t mv = 0;
    S.now = 1000;
    assert_int_equal(lsc_client_init(&C, &IO), 0);
    add(1001, "55 55 04 0F 4C"); /* torn: its last byte never comes */
    add(1001 + LSC_CLIENT_GAP_MS + 1, BATTERY_7500);
    assert_int_equal(lsc_client_get_battery(&C, &mv, 20), LSC_ETIMEOUT);
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), 0);
    assert_int_equal(mv, 7500);
}

static void without_the_gap_a_torn_frame_poisons(void **state)
{
    (void)state;
    uint16_t mv = 0;
    lsc_client_set_gap(&C, 0);
    add(1, "55 55 04 0F 4C");
    add(200, BATTERY_7500);
    assert_int_equal(lsc_client_get_battery(&C, &mv, 20), LSC_ETIMEOUT);
    assert_int_equal(lsc_client_get_battery(&C, &mv, 300), 0);
    assert_int_equal(mv, 0x554C); /* what the gap prevents */
}

static void pauses_within_the_gap_keep_the_frame(void **state)
{
    (void)state;
    uint16_t mv = 0;
    add(1, "55 55");
    add(1 + LSC_CLIENT_GAP_MS, "04 0F");
    add(1 + 2 * LSC_CLIENT_GAP_MS, "4C 1D");
    assert_int_equal(lsc_client_get_battery(&C, &mv, 1000), 0);
    assert_int_equal(mv, 7500);
}

/* A frame that straddles two late polls is kept: the caller polling 100 ms
 * apart is not silence on the line (the bytes come 1 ms apart). */
static void late_polls_do_not_tear_frames(void **state)
{
    (void)state;
    S.merge = true;
    uint8_t stream[10 * 7];
    for (size_t i = 0; i < 10; i++) {
        (void)test_hex(COMPLETE_8, stream + 7 * i, 7);
    }
    for (size_t i = 0; i < sizeof stream; i++) {
        char hex[4];
        (void)snprintf(hex, sizeof hex, "%02X", stream[i]);
        add(95 + (uint32_t)i, hex);
    }
    for (uint32_t t = 100; t <= 400; t += 100) {
        S.now = t;
        for (int i = 0; i < 4; i++) { /* 4 x 32 bytes: all that arrived */
            assert_true(lsc_client_poll(&C, 0) >= 0);
        }
    }
    assert_int_equal(nnotes, 10);
    assert_int_equal(C.unexpected, 0);
}

/* A poll that finds the line empty a gap after a torn frame drops it. */
static void an_empty_poll_after_the_gap_drops_a_torn_frame(void **state)
{
    (void)state;
    add(10, "55 55 05 08 08"); /* torn */
    S.now = 10;
    assert_int_equal(lsc_client_poll(&C, 0), 0);
    S.now = 10 + LSC_CLIENT_GAP_MS - 1;
    assert_int_equal(lsc_client_poll(&C, 0), 0); /* within the gap: kept */
    S.now = 10 + LSC_CLIENT_GAP_MS;
    assert_int_equal(lsc_client_poll(&C, 0), 0); /* a gap of silence seen: dropped */
    add(1000, COMPLETE_8);
    S.now = 1000;
    assert_int_equal(lsc_client_poll(&C, 0), 1);
    note_is(0, LSC_CMD_GROUP_COMPLETE, 8, 1);
}

/* ---- Trace and raw frames ------------------------------------------------------------ */

static uint8_t traced[4096];
static size_t ntraced;
static int dirs[64];
static size_t ndirs;

static void trace(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    (void)user;
    dirs[ndirs++] = (int)dir;
    memcpy(traced + ntraced, frame, n);
    ntraced += n;
}

static void trace_sees_every_frame(void **state)
{
    (void)state;
    ntraced = ndirs = 0;
    lsc_client_set_trace(&C, trace, NULL);
    add(1, "00 " STARTED_8 " 55 55 04 0F 4C 1D");
    uint16_t mv;
    assert_int_equal(lsc_client_get_battery(&C, &mv, 100), 0);
    assert_int_equal(lsc_client_stop_group(&C), 0);
    static const uint8_t want[] = {0x55, 0x55, 0x02, 0x0F, 0x55, 0x55, 0x05, 0x06, 0x08,
                                   0x01, 0x00, 0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D,
                                   0x55, 0x55, 0x02, 0x07};
    assert_int_equal(ndirs, 4);
    assert_int_equal(dirs[0], LSC_TRACE_TX);
    assert_int_equal(dirs[1], LSC_TRACE_RX);
    assert_int_equal(dirs[2], LSC_TRACE_RX);
    assert_int_equal(dirs[3], LSC_TRACE_TX);
    assert_int_equal(ntraced, sizeof want);
    assert_memory_equal(traced, want, sizeof want);
    lsc_client_set_trace(&C, NULL, NULL);
    assert_int_equal(lsc_client_stop_group(&C), 0);
    assert_int_equal(ndirs, 4);
}

static void raw_send_and_request(void **state)
{
    (void)state;
    uint8_t p[3] = {1, 2, 3};
    uint8_t reply[4];
    assert_int_equal(lsc_client_send_raw(&C, 22, p, 3), 0);
    add(1, "55 55 05 17 09 08 07"); /* another command: not the reply */
    add(2, STOPPED " 55 55 06 16 AA BB CC DD");
    assert_int_equal(lsc_client_request_raw(&C, 22, p, 1, 22, reply, sizeof reply, 100), 4);
    assert_memory_equal(reply, ((uint8_t[]){0xAA, 0xBB, 0xCC, 0xDD}), 4);
    assert_int_equal(nnotes, 1);
    add(3, "55 55 06 16 AA BB CC DD");
    assert_int_equal(lsc_client_request_raw(&C, 22, NULL, 0, 22, reply, 3, 100), LSC_ENOSPC);
    add(4, "55 55 02 16");
    assert_int_equal(lsc_client_request_raw(&C, 22, NULL, 0, 22, NULL, 0, 100), 0);
    assert_int_equal(lsc_client_request_raw(&C, 22, NULL, 0, 22, NULL, 0, 50), LSC_ETIMEOUT);
    sent_is("55 55 05 16 01 02 03  55 55 03 16 01  55 55 02 16  55 55 02 16  55 55 02 16");
}

/* ---- Transport errors ---------------------------------------------------------------- */

static void transport_errors_pass_through(void **state)
{
    (void)state;
    uint16_t mv = 0;
    lsc_notification n;
    S.write_error = LSC_ENODEV;
    assert_int_equal(lsc_client_stop_group(&C), LSC_ENODEV);
    assert_int_equal(lsc_client_get_battery(&C, &mv, 10), LSC_ENODEV);
    S.write_error = 0;
    S.write_result = 2; /* a transport that lies about a short write */
    assert_int_equal(lsc_client_stop_group(&C), LSC_EIO);
    S.write_result = 0;
    S.read_error = LSC_EIO;
    assert_int_equal(lsc_client_get_battery(&C, &mv, 10), LSC_EIO);
    assert_int_equal(lsc_client_poll(&C, 10), LSC_EIO);
    assert_int_equal(lsc_client_wait_group(&C, 10, &n), LSC_EIO);
    S.read_error = 0;
}

static int too_many(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    (void)ctx;
    (void)buf;
    (void)timeout_ms;
    return (int)cap + 1;
}

static void impossible_read_count_is_eio(void **state)
{
    (void)state;
    lsc_io io = IO;
    io.read = too_many;
    assert_int_equal(lsc_client_init(&C, &io), 0);
    assert_int_equal(lsc_client_poll(&C, 10), LSC_EIO);
}

static void poll_without_callback_counts(void **state)
{
    (void)state;
    lsc_client_set_notify(&C, NULL, NULL);
    add(0, STARTED_8 " " STOPPED " " BATTERY_7500);
    assert_int_equal(lsc_client_poll(&C, 0), 2);
    assert_int_equal(nnotes, 0);
    assert_int_equal(C.notifications, 2);
    assert_int_equal(C.unexpected, 1);
    assert_int_equal(lsc_client_poll(&C, 30), 0);
    assert_int_equal(S.now, 30);
    /* NULL clients are ignored by the setters */
    lsc_client_set_notify(NULL, record, NULL);
    lsc_client_set_trace(NULL, trace, NULL);
    lsc_client_set_gap(NULL, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(init_rejects_incomplete_io, setup),
        cmocka_unit_test_setup(move_one, setup),
        cmocka_unit_test_setup(move_many, setup),
        cmocka_unit_test_setup(offsets, setup),
        cmocka_unit_test_setup(run_stop_speed_unload, setup),
        cmocka_unit_test_setup(invalid_arguments_send_nothing, setup),
        cmocka_unit_test_setup(battery, setup),
        cmocka_unit_test_setup(positions, setup),
        cmocka_unit_test_setup(positions_in_the_order_asked, setup),
        cmocka_unit_test_setup(positions_wrong_ids_only, setup),
        cmocka_unit_test_setup(notifications_around_replies, setup),
        cmocka_unit_test_setup(byte_by_byte, setup),
        cmocka_unit_test_setup(garbage_before_reply, setup),
        cmocka_unit_test_setup(wrong_shape_reply_then_right_one, setup),
        cmocka_unit_test_setup(wrong_shape_only_is_ereply, setup),
        cmocka_unit_test_setup(malformed_only_is_ereply, setup),
        cmocka_unit_test_setup(silence_times_out, setup),
        cmocka_unit_test_setup(notifications_do_not_extend_the_timeout, setup),
        cmocka_unit_test_setup(thousand_notifications_while_waiting, setup),
        cmocka_unit_test_setup(thousand_notifications_before_a_reply, setup),
        cmocka_unit_test_setup(wait_group_stopped_and_timeout, setup),
        cmocka_unit_test_setup(stale_reply_is_not_taken, setup),
        cmocka_unit_test_setup(stale_reply_after_a_large_backlog_is_not_taken, setup),
        cmocka_unit_test(drain_of_endless_input_is_bounded),
        cmocka_unit_test_setup(frame_gap_resets_the_parser, setup),
        cmocka_unit_test_setup(without_the_gap_a_torn_frame_poisons, setup),
        cmocka_unit_test_setup(pauses_within_the_gap_keep_the_frame, setup),
        cmocka_unit_test_setup(late_polls_do_not_tear_frames, setup),
        cmocka_unit_test_setup(an_empty_poll_after_the_gap_drops_a_torn_frame, setup),
        cmocka_unit_test_setup(trace_sees_every_frame, setup),
        cmocka_unit_test_setup(raw_send_and_request, setup),
        cmocka_unit_test_setup(transport_errors_pass_through, setup),
        cmocka_unit_test_setup(impossible_read_count_is_eio, setup),
        cmocka_unit_test_setup(poll_without_callback_counts, setup),
        cmocka_unit_test_setup(frozen_clock_and_endless_input_end, setup),
        cmocka_unit_test_setup(counts_say_what_arrived, setup),
        cmocka_unit_test_setup(torn_reply_glued_to_the_next_frame_within_the_gap, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
