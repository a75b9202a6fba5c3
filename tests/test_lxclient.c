/* The bus client (include/lsc/lxclient.h) against the in-process virtual bus
 * (include/lsc/lxbus.h) in virtual time, through a tap that records every
 * frame the client writes (so a refusal is proven to send nothing) and can
 * fail the transport; and against a scripted line for what a bus cannot be
 * made to do (torn frames, a clock that stands still, impossible counts). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "lsc/lxbus.h"
#include "lsc/lxclient.h"

static lsc_lxbus bus; /* ~4 KiB: not on the stack */

/* ---- The tap: the client's io, in front of the bus's ---------------------------- */

typedef struct tap {
    lsc_io inner;
    unsigned writes;         /* frames written */
    unsigned cmds[64];       /* frames written, by command */
    uint8_t last[LSC_LX_FRAME_MAX];
    int write_error;         /* returned by the next write instead of writing */
    int write_short;         /* the next write returns n - 1 (and writes nothing) */
    int read_error;          /* returned by the next read */
    int read_impossible;     /* the next read returns more than asked */
    int swallow_cmd;         /* a frame of this command is not passed on (0: none) */
    int drop_after_cmd;      /* after this command is written, the bus drops drop_n replies */
    uint32_t drop_n;
    bool fail_after_scan;    /* the reads after the 255th ID_READ fail once */
    void (*hook)(unsigned writes); /* called before a frame goes to the bus */
} tap;

static tap t;

static int tap_write(void *ctx, const uint8_t *data, size_t n)
{
    tap *p = ctx;
    if (p->write_error != 0) {
        int r = p->write_error;
        p->write_error = 0;
        return r;
    }
    if (p->write_short) {
        p->write_short = 0;
        return (int)n - 1;
    }
    p->writes++;
    p->cmds[data[4] & 63u]++;
    memcpy(p->last, data, n < sizeof p->last ? n : sizeof p->last);
    if (p->hook != NULL) {
        p->hook(p->writes);
    }
    if (p->swallow_cmd != 0 && data[4] == p->swallow_cmd) {
        return (int)n;
    }
    int r = p->inner.write(p->inner.ctx, data, n);
    if (p->drop_after_cmd != 0 && data[4] == p->drop_after_cmd) {
        lsc_lxbus_fault_drop(&bus, p->drop_n);
    }
    return r;
}

static int tap_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    tap *p = ctx;
    if (p->read_error != 0) {
        int r = p->read_error;
        p->read_error = 0;
        return r;
    }
    if (p->read_impossible) {
        p->read_impossible = 0;
        return (int)cap + 1;
    }
    if (p->fail_after_scan && p->cmds[LSC_LX_ID_READ] >= 255u) {
        p->fail_after_scan = false;
        return LSC_EIO;
    }
    return p->inner.read(p->inner.ctx, buf, cap, timeout_ms);
}

static uint32_t tap_now(void *ctx)
{
    tap *p = ctx;
    return p->inner.now_ms(p->inner.ctx);
}

/* A bus of servos with these ids (n of them) at 115200 baud, and a client on it. */
static void setup(lsc_lxclient *c, const uint8_t *ids, size_t n)
{
    assert_int_equal(lsc_lxbus_init(&bus), 0);
    lsc_lxbus_set_baud(&bus, 115200);
    for (size_t i = 0; i < n; i++) {
        assert_int_equal(lsc_lxbus_add(&bus, ids[i]), (int)i);
    }
    memset(&t, 0, sizeof t);
    assert_int_equal(lsc_lxbus_io_init(&bus, &t.inner), 0);
    lsc_io io = {&t, tap_write, tap_read, tap_now};
    assert_int_equal(lsc_lxclient_init(c, &io), 0);
}

static uint32_t now_ms(void)
{
    return (uint32_t)(lsc_lxbus_now_us(&bus) / 1000u);
}

/* A bus from lsc_lxbus_load's text (servos placed where the test wants them). */
static void setup_text(lsc_lxclient *c, const char *text)
{
    setup(c, NULL, 0);
    assert_true(lsc_lxbus_load(&bus, text, strlen(text), NULL) > 0);
}

static void assert_same_info(const lsc_lx_info *a, const lsc_lx_info *b)
{
    assert_int_equal(a->id, b->id);
    assert_int_equal(a->position, b->position);
    assert_int_equal(a->temp_c, b->temp_c);
    assert_int_equal(a->vin_mv, b->vin_mv);
    assert_int_equal(a->offset, b->offset);
    assert_true(a->limit_min == b->limit_min && a->limit_max == b->limit_max);
    assert_true(a->vin_min_mv == b->vin_min_mv && a->vin_max_mv == b->vin_max_mv);
    assert_int_equal(a->temp_limit_c, b->temp_limit_c);
    assert_true(a->mode == b->mode && a->speed == b->speed);
    assert_true(a->torque == b->torque && a->led == b->led);
    assert_int_equal(a->alarms, b->alarms);
}

/* ---- Initialisation ------------------------------------------------------------------ */

static void test_init(void **state)
{
    (void)state;
    lsc_lxclient c;
    lsc_io io = {NULL, NULL, NULL, NULL};
    assert_int_equal(lsc_lxclient_init(NULL, &io), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_init(&c, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_init(&c, &io), LSC_EINVAL);
    io.write = tap_write;
    assert_int_equal(lsc_lxclient_init(&c, &io), LSC_EINVAL);
    io.read = tap_read;
    assert_int_equal(lsc_lxclient_init(&c, &io), LSC_EINVAL);
    /* unusable: every call refuses */
    int16_t pos;
    lsc_lx_whois who;
    lsc_lx_scan scan;
    lsc_lx_refusal why = LSC_LX_DONE;
    lsc_servo s = {1, 500};
    assert_int_equal(lsc_lxclient_move(&c, 1, 500, 0), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_whois(&c, &who), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_scan(&c, NULL, 0, 0, &scan), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_change_id(&c, 1, 2, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_BAD_ARGUMENT);
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 2, 0, NULL, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_offset_change(&c, 1, 1, false, NULL, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_move_together(&c, &s, 1, 0), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_move(NULL, 1, 500, 0), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_id(NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_whois(NULL, &who), LSC_EINVAL);
    lsc_lxclient_set_timeout(NULL, 5);
    lsc_lxclient_set_trace(NULL, NULL, NULL);
    setup(&c, NULL, 0);
    assert_int_equal(c.timeout_ms, LSC_LXCLIENT_TIMEOUT_MS);
    lsc_lxclient_set_timeout(&c, 7);
    assert_int_equal(c.timeout_ms, 7);
}

/* ---- Typed reads and writes -------------------------------------------------------------- */

static void test_reads_and_writes(void **state)
{
    (void)state;
    lsc_lxclient c;
    const uint8_t ids[] = {3};
    setup(&c, ids, 1);
    lsc_lxbus_set_temp(&bus, 0, 42);
    assert_int_equal(lsc_lxbus_set_vin(&bus, 7900), 0);
    uint16_t a = 0, b = 0;
    uint8_t u = 0;
    int8_t off = 0;
    int16_t pos = 0, speed = 0;
    bool on = true;
    assert_int_equal(lsc_lxclient_read_position(&c, 3, &pos), 0);
    assert_int_equal(pos, 500);
    assert_int_equal(lsc_lxclient_read_temp(&c, 3, &u), 0);
    assert_int_equal(u, 42);
    assert_int_equal(lsc_lxclient_read_vin(&c, 3, &a), 0);
    assert_int_equal(a, 7900);
    assert_int_equal(lsc_lxclient_read_id(&c, 3), 0);
    /* settings: written, then read back */
    assert_int_equal(lsc_lxclient_write_limits(&c, 3, 100, 900), 0);
    assert_int_equal(lsc_lxclient_read_limits(&c, 3, &a, &b), 0);
    assert_true(a == 100 && b == 900);
    assert_int_equal(lsc_lxclient_write_vin_limits(&c, 3, 5000, 11000), 0);
    assert_int_equal(lsc_lxclient_read_vin_limits(&c, 3, &a, &b), 0);
    assert_true(a == 5000 && b == 11000);
    assert_int_equal(lsc_lxclient_write_temp_limit(&c, 3, 70), 0);
    assert_int_equal(lsc_lxclient_read_temp_limit(&c, 3, &u), 0);
    assert_int_equal(u, 70);
    assert_int_equal(lsc_lxclient_write_led(&c, 3, false), 0);
    assert_int_equal(lsc_lxclient_read_led(&c, 3, &on), 0);
    assert_false(on);
    assert_int_equal(lsc_lxclient_write_alarms(&c, 3, 5), 0);
    assert_int_equal(lsc_lxclient_read_alarms(&c, 3, &u), 0);
    assert_int_equal(u, 5);
    assert_int_equal(lsc_lxclient_adjust_offset(&c, 3, -12), 0);
    assert_int_equal(lsc_lxclient_save_offset(&c, 3), 0);
    assert_int_equal(lsc_lxclient_read_offset(&c, 3, &off), 0);
    assert_int_equal(off, -12);
    assert_int_equal(lsc_lxclient_write_torque(&c, 3, true), 0);
    assert_int_equal(lsc_lxclient_read_torque(&c, 3, &on), 0);
    assert_true(on);
    assert_int_equal(lsc_lxclient_write_mode(&c, 3, LSC_LX_MODE_MOTOR, -300), 0);
    assert_int_equal(lsc_lxclient_read_mode(&c, 3, &u, &speed), 0);
    assert_true(u == LSC_LX_MODE_MOTOR && speed == -300);
    assert_int_equal(lsc_lxclient_write_mode(&c, 3, LSC_LX_MODE_SERVO, 0), 0);
    /* moves: at once, preset and started, stopped */
    assert_int_equal(lsc_lxclient_move(&c, 3, 800, 0), 0);
    assert_int_equal(lsc_lxclient_read_move(&c, 3, false, &a, &b), 0);
    assert_true(a == 800 && b == 0);
    assert_int_equal(lsc_lxclient_move_preset(&c, 3, 200, 1000), 0);
    assert_int_equal(lsc_lxclient_read_move(&c, 3, true, &a, &b), 0);
    assert_true(a == 200 && b == 1000);
    assert_int_equal(lsc_lxclient_move_start(&c, LSC_LX_BROADCAST), 0);
    lsc_lxbus_advance_us(&bus, 500000);
    assert_int_equal(lsc_lxclient_move_stop(&c, 3), 0);
    assert_int_equal(lsc_lxclient_read_position(&c, 3, &pos), 0);
    assert_true(pos < 800 - 12 && pos > 200 - 12); /* stopped on the way, offset -12 */
    /* info: everything at once */
    lsc_lx_info info;
    memset(&info, 0, sizeof info);
    assert_int_equal(lsc_lxclient_info(&c, 3, &info), 0);
    assert_int_equal(info.id, 3);
    assert_int_equal(info.position, pos);
    assert_int_equal(info.temp_c, 42);
    assert_int_equal(info.vin_mv, 7900);
    assert_int_equal(info.offset, -12);
    assert_true(info.limit_min == 100 && info.limit_max == 900);
    assert_true(info.vin_min_mv == 5000 && info.vin_max_mv == 11000);
    assert_int_equal(info.temp_limit_c, 70);
    assert_true(info.mode == LSC_LX_MODE_SERVO && info.speed == 0);
    assert_true(info.torque);
    assert_false(info.led);
    assert_int_equal(info.alarms, 5);
    assert_int_equal(lsc_lxclient_info(&c, 3, NULL), LSC_EINVAL);
    /* a servo that is not there: a timeout, info untouched */
    lsc_lx_info none = info;
    assert_int_equal(lsc_lxclient_info(&c, 4, &none), LSC_ETIMEOUT);
    assert_same_info(&none, &info);
    assert_int_equal(c.parser.bad_checksums, 0);
}

/* Values outside the document's ranges: refused, nothing sent. */
static void test_refused_before_sending(void **state)
{
    (void)state;
    lsc_lxclient c;
    const uint8_t ids[] = {1};
    setup(&c, ids, 1);
    uint16_t a;
    uint8_t u;
    int16_t s;
    assert_int_equal(lsc_lxclient_move(&c, 1, 1001, 0), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_move(&c, 1, 0, 30001), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_move(&c, 255, 0, 0), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_move_preset(&c, 1, 1001, 0), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_move_start(&c, 255), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_move_stop(&c, 255), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_id(&c, LSC_LX_BROADCAST, 2), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_id(&c, 1, 254), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_adjust_offset(&c, 1, 126), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_adjust_offset(&c, 1, -126), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_save_offset(&c, 255), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_limits(&c, 1, 500, 500), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_limits(&c, 1, 0, 1001), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_vin_limits(&c, 1, 4499, 6000), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_vin_limits(&c, 1, 6000, 12001), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_temp_limit(&c, 1, 49), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_temp_limit(&c, 1, 101), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_mode(&c, 1, 2, 0), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_mode(&c, 1, 1, 1001), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_torque(&c, 255, true), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_led(&c, 255, true), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_write_alarms(&c, 1, 8), LSC_EINVAL);
    /* reads: to the broadcast (none answers), to 255, without outputs */
    assert_int_equal(lsc_lxclient_read_position(&c, LSC_LX_BROADCAST, &s), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_id(&c, LSC_LX_BROADCAST), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_temp(&c, 255, &u), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_position(&c, 1, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_move(&c, 1, false, NULL, &a), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_move(&c, 1, false, &a, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_offset(&c, 1, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_limits(&c, 1, NULL, &a), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_limits(&c, 1, &a, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_vin_limits(&c, 1, NULL, &a), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_vin_limits(&c, 1, &a, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_temp_limit(&c, 1, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_temp(&c, 1, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_vin(&c, 1, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_mode(&c, 1, NULL, &s), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_mode(&c, 1, &u, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_torque(&c, 1, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_led(&c, 1, NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_read_alarms(&c, 1, NULL), LSC_EINVAL);
    /* moves together: every servo checked first */
    lsc_servo two[2] = {{1, 500}, {1, 600}};
    assert_int_equal(lsc_lxclient_move_together(&c, two, 2, 0), LSC_EINVAL); /* same id */
    two[1].id = 2;
    two[1].position = 1001;
    assert_int_equal(lsc_lxclient_move_together(&c, two, 2, 0), LSC_EINVAL);
    two[1].position = 600;
    two[1].id = 254;
    assert_int_equal(lsc_lxclient_move_together(&c, two, 2, 0), LSC_EINVAL);
    two[1].id = 2;
    assert_int_equal(lsc_lxclient_move_together(&c, two, 2, 30001), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_move_together(&c, two, 0, 0), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_move_together(&c, NULL, 2, 0), LSC_EINVAL);
    assert_int_equal(t.writes, 0);
}

/* ---- What is believed ------------------------------------------------------------------- */

/* A reply with a flipped bit is never believed; the next good one is. */
static void test_flipped_bit(void **state)
{
    (void)state;
    lsc_lxclient c;
    const uint8_t ids[] = {1};
    setup(&c, ids, 1);
    int16_t pos = 1234;
    lsc_lxbus_fault_corrupt(&bus, 1, 5, 0x01); /* the position's low byte */
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), LSC_EREPLY);
    assert_int_equal(pos, 1234);
    assert_int_equal(c.parser.bad_checksums, 1);
    assert_int_equal(c.replies, 0);
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), 0);
    assert_int_equal(pos, 500);
}

/* A bus that echoes the host's bytes reads the same as one that does not. */
static void test_echo_reads_the_same(void **state)
{
    (void)state;
    lsc_lxclient c;
    const uint8_t ids[] = {2};
    lsc_lx_info quiet, echoed;
    lsc_lx_scan scan;
    for (int echo = 0; echo <= 1; echo++) {
        setup(&c, ids, 1);
        lsc_lxbus_set_echo(&bus, echo != 0);
        assert_int_equal(lsc_lxclient_move(&c, 2, 300, 0), 0);
        assert_int_equal(lsc_lxclient_adjust_offset(&c, 2, 7), 0);
        assert_int_equal(lsc_lxclient_info(&c, 2, echo ? &echoed : &quiet), 0);
        assert_int_equal(lsc_lxclient_scan(&c, NULL, 0, 0, &scan), 1);
        assert_true(lsc_lx_scan_found(&scan, 2));
        assert_int_equal(c.parser.bad_checksums, 0);
        assert_int_equal(c.strays, 0);
        /* every frame sent came back and was skipped, or none came */
        assert_int_equal(c.parser.echoes + c.echoes, echo ? t.writes : 0u);
    }
    assert_same_info(&quiet, &echoed);
    assert_int_equal(quiet.position, 307);
}

/* A reply from another id (a late answer) is counted, not taken. */
static void test_stray_reply_not_taken(void **state)
{
    (void)state;
    lsc_lxclient c;
    const uint8_t ids[] = {1, 2};
    setup(&c, ids, 2);
    lsc_lxbus_fault_delay(&bus, 30);
    lsc_lxclient_set_timeout(&c, 20);
    int16_t pos = 0;
    assert_int_equal(lsc_lxclient_read_position(&c, 2, &pos), LSC_ETIMEOUT);
    lsc_lxclient_set_timeout(&c, 100);
    assert_int_equal(lsc_lxclient_move(&c, 1, 100, 0), 0);
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), 0);
    assert_int_equal(pos, 100); /* servo 2's 500 came first and was not taken */
    assert_int_equal(c.strays, 1);
    assert_int_equal(c.replies, 1);
}

/* ---- Who is there ---------------------------------------------------------------------- */

static void test_whois(void **state)
{
    (void)state;
    lsc_lxclient c;
    lsc_lx_whois who;
    const uint8_t one[] = {9}, three[] = {1, 2, 3};
    setup(&c, NULL, 0);
    assert_int_equal(lsc_lxclient_whois(&c, &who), LSC_ETIMEOUT);
    assert_int_equal(who.answers, 0);
    setup(&c, one, 1);
    assert_int_equal(lsc_lxclient_whois(&c, &who), 0);
    assert_true(who.id == 9 && who.answers == 1 && !who.garbled);
    assert_int_equal(lsc_lxclient_whois(&c, NULL), 0);
    setup(&c, three, 3);
    assert_int_equal(lsc_lxclient_whois(&c, &who), LSC_EREPLY);
    assert_true(who.garbled);
    t.write_error = LSC_EIO;
    assert_int_equal(lsc_lxclient_whois(&c, &who), LSC_EIO);
}

static void test_scan_whole_bus(void **state)
{
    (void)state;
    lsc_lxclient c;
    lsc_lx_scan scan;
    /* two servos share id 9: their ID_READ answers are the same bytes, and
     * collide into one good answer; id 0's answer gets a flipped bit */
    const uint8_t ids[] = {0, 5, 17, 121, 253, 9, 9};
    setup(&c, ids, sizeof ids);
    lsc_lxbus_fault_corrupt(&bus, 1, 5, 0x01);
    uint32_t start = now_ms();
    assert_int_equal(lsc_lxclient_scan(&c, NULL, 0, 0, &scan), 5);
    uint32_t took = now_ms() - start;
    print_message("a scan of 0..253 at 115200 baud: %u ms of bus time\n", (unsigned)took);
    assert_true(took < 3000);
    assert_int_equal(scan.asked, 254);
    /* the last id (253) absent: the scan listens for late answers at most
     * LSC_LXCLIENT_TIMEOUT_MS, whatever the client's timeout (a shorter one:
     * that) */
    const uint8_t none[] = {1};
    for (unsigned k = 0; k < 2; k++) {
        lsc_lx_scan quiet;
        setup(&c, none, 1);
        lsc_lxclient_set_timeout(&c, k == 0 ? 1000u : 30u);
        start = now_ms();
        assert_int_equal(lsc_lxclient_scan(&c, NULL, 0, 0, &quiet), 1);
        took = now_ms() - start;
        assert_true(took >= 253u * LSC_LXCLIENT_SCAN_TIMEOUT_MS + (k == 0 ? 100u : 30u));
        /* each id's request and its wait (the 6 bytes: 0.5 ms), then the listen */
        assert_true(took < 254u * (LSC_LXCLIENT_SCAN_TIMEOUT_MS + 1u) + (k == 0 ? 100u : 30u));
        print_message("a scan of 0..253, timeout %u ms: %u ms\n", k == 0 ? 1000u : 30u, (unsigned)took);
    }
    setup(&c, ids, sizeof ids);
    for (unsigned id = 0; id <= 253; id++) {
        bool there = id == 9 || id == 5 || id == 17 || id == 121 || id == 253;
        assert_int_equal(lsc_lx_scan_found(&scan, (uint8_t)id), there);
        assert_int_equal(lsc_lx_scan_garbled(&scan, (uint8_t)id), id == 0);
    }
    assert_false(lsc_lx_scan_found(NULL, 0));
    assert_false(lsc_lx_scan_found(&scan, 254));
    assert_false(lsc_lx_scan_garbled(NULL, 0));
    assert_false(lsc_lx_scan_garbled(&scan, 255));
    /* some ids */
    const uint8_t some[] = {4, 5, 6, 253};
    assert_int_equal(lsc_lxclient_scan(&c, some, 4, 5, &scan), 2);
    assert_int_equal(scan.asked, 4);
    const uint8_t bad[] = {4, 254};
    assert_int_equal(lsc_lxclient_scan(&c, bad, 2, 5, &scan), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_scan(&c, some, 4, 5, NULL), LSC_EINVAL);
    t.read_error = LSC_ENODEV;
    assert_int_equal(lsc_lxclient_scan(&c, some, 4, 5, &scan), LSC_ENODEV);
}

/* Answers slower than the scan's wait: each comes while the next id is asked,
 * and its id is asked again at the end. */
static void test_scan_late_answers(void **state)
{
    (void)state;
    lsc_lxclient c;
    lsc_lx_scan scan;
    const uint8_t ids[] = {3, 4, 200};
    setup(&c, ids, 3);
    lsc_lxbus_fault_delay(&bus, 14);
    assert_int_equal(lsc_lxclient_scan(&c, NULL, 0, 10, &scan), 3);
    assert_true(lsc_lx_scan_found(&scan, 3) && lsc_lx_scan_found(&scan, 4) &&
                lsc_lx_scan_found(&scan, 200));
    assert_false(lsc_lx_scan_garbled(&scan, 4));
    assert_true(c.strays >= 3);
    /* the transport fails while a late id is asked again */
    setup(&c, ids, 3);
    lsc_lxbus_fault_delay(&bus, 14);
    t.fail_after_scan = true;
    assert_int_equal(lsc_lxclient_scan(&c, NULL, 0, 10, &scan), LSC_EIO);
}

/* ---- The safe operations ----------------------------------------------------------------- */

static void test_change_id(void **state)
{
    (void)state;
    lsc_lxclient c;
    lsc_lx_refusal why = LSC_LX_DONE;
    /* two servos share id 4, at different positions */
    setup_text(&c, "servo id=1\nservo id=2\nservo id=3\nservo id=4 position=300\n"
                   "servo id=4 position=600\n");
    /* 3 answers: refused, no ID_WRITE */
    assert_int_equal(lsc_lxclient_change_id(&c, 1, 3, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_ID_TAKEN);
    /* 4 answers (two servos share it): taken too */
    assert_int_equal(lsc_lxclient_change_id(&c, 1, 4, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_ID_TAKEN);
    assert_int_equal(lsc_lxclient_change_id(&c, 4, 10, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_ID_GARBLED);
    lsc_lxbus_fault_corrupt(&bus, 1, 5, 0x01); /* 3's answer, garbled */
    assert_int_equal(lsc_lxclient_change_id(&c, 1, 3, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_ID_TAKEN);
    assert_int_equal(lsc_lxclient_change_id(&c, 7, 8, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_ID_ABSENT);
    assert_int_equal(lsc_lxclient_change_id(&c, 2, 2, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_BAD_ARGUMENT);
    assert_int_equal(lsc_lxclient_change_id(&c, 254, 2, &why), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_change_id(&c, 2, 254, NULL), LSC_EINVAL);
    assert_int_equal(t.cmds[LSC_LX_ID_WRITE], 0);
    /* 2 -> 9: written, read back */
    assert_int_equal(lsc_lxclient_change_id(&c, 2, 9, &why), 0);
    assert_int_equal(why, LSC_LX_DONE);
    assert_int_equal(t.cmds[LSC_LX_ID_WRITE], 1);
    assert_int_equal(bus.servo[1].id, 9);
    /* the transport fails: on the first read, on the second, on the write */
    t.read_error = LSC_EIO;
    assert_int_equal(lsc_lxclient_change_id(&c, 9, 20, &why), LSC_EIO);
    assert_int_equal(why, LSC_LX_DONE);
    lsc_lxclient_set_timeout(&c, 10);
    /* the read back finds nothing (its reply lost) */
    t.drop_after_cmd = LSC_LX_ID_WRITE;
    t.drop_n = 1;
    assert_int_equal(lsc_lxclient_change_id(&c, 9, 20, &why), LSC_ETIMEOUT);
    assert_int_equal(why, LSC_LX_NOT_READ_BACK);
    assert_int_equal(bus.servo[1].id, 20);
    t.drop_after_cmd = 0;
}

/* The second read (the old id's) and the ID_WRITE failing in the transport. */
static int fail_on_nth_read = 0;
static int reads_seen = 0;
static int counting_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    reads_seen++;
    if (reads_seen == fail_on_nth_read) {
        return LSC_ENODEV;
    }
    return tap_read(ctx, buf, cap, timeout_ms);
}

static int write_fail_on_cmd = 0;
static int cmd_failing_write(void *ctx, const uint8_t *data, size_t n)
{
    if (data[4] == write_fail_on_cmd) {
        return LSC_EIO;
    }
    return tap_write(ctx, data, n);
}

static void test_change_id_transport(void **state)
{
    (void)state;
    lsc_lxclient c;
    lsc_lx_refusal why = LSC_LX_ID_TAKEN;
    const uint8_t ids[] = {1};
    setup(&c, ids, 1);
    lsc_io io = {&t, cmd_failing_write, counting_read, tap_now};
    assert_int_equal(lsc_lxclient_init(&c, &io), 0);
    /* the new id's read is silent; the old id's read fails in the transport */
    reads_seen = 0;
    fail_on_nth_read = 0;
    lsc_lxclient_set_timeout(&c, 10);
    assert_int_equal(lsc_lxclient_change_id(&c, 1, 2, &why), 0); /* 1 -> 2 */
    int per_change = reads_seen;
    (void)per_change;
    /* count the reads before the old id's request: drain + wait of the first */
    reads_seen = 0;
    write_fail_on_cmd = LSC_LX_ID_WRITE;
    assert_int_equal(lsc_lxclient_change_id(&c, 2, 1, &why), LSC_EIO);
    assert_int_equal(why, LSC_LX_DONE);
    write_fail_on_cmd = 0;
    /* find the first read of the second request's wait, and fail it */
    int first_request_reads = 0;
    reads_seen = 0;
    fail_on_nth_read = 0;
    assert_int_equal(lsc_lxclient_read_id(&c, 1), LSC_ETIMEOUT);
    first_request_reads = reads_seen;
    reads_seen = 0;
    fail_on_nth_read = first_request_reads + 1;
    assert_int_equal(lsc_lxclient_change_id(&c, 2, 1, &why), LSC_ENODEV);
    assert_int_equal(why, LSC_LX_DONE);
}

/* After the broadcast ID_READ (the first frame): the next reply garbled. */
static void garble_second(unsigned writes)
{
    if (writes == 2) {
        lsc_lxbus_fault_corrupt(&bus, 1, 5, 0x01);
    }
}

/* After the broadcast ID_READ: the servo takes another id behind the host's back. */
static void rename_after_whois(unsigned writes)
{
    if (writes == 2) {
        uint8_t f[LSC_LX_FRAME_MAX];
        int n = lsc_lx_encode_id(f, sizeof f, 5, LSC_LX_ID_WRITE, 6);
        assert_int_equal(lsc_lxbus_feed(&bus, f, (size_t)n), n);
    }
}

/* The scan's answer from 119 (the 121st frame: the broadcast, then 0..119) garbled. */
static void garble_119(unsigned writes)
{
    if (writes == 121) {
        lsc_lxbus_fault_corrupt(&bus, 1, 5, 0x01);
    }
}

/* The listening after the last id, when the transport fails there. */
static void test_scan_listen_fails(void **state)
{
    (void)state;
    lsc_lxclient c;
    lsc_lx_scan scan;
    setup(&c, NULL, 0);
    lsc_io io = {&t, tap_write, counting_read, tap_now};
    assert_int_equal(lsc_lxclient_init(&c, &io), 0);
    const uint8_t absent[] = {6};
    reads_seen = 0;
    fail_on_nth_read = 0;
    assert_int_equal(lsc_lxclient_scan(&c, absent, 1, 5, &scan), 0);
    fail_on_nth_read = reads_seen; /* the last read: the listening's */
    reads_seen = 0;
    assert_int_equal(lsc_lxclient_scan(&c, absent, 1, 5, &scan), LSC_ENODEV);
    fail_on_nth_read = 0;
    assert_int_equal(lsc_lxclient_scan(&c, absent, 0, 5, &scan), 0);
    assert_int_equal(scan.asked, 0);
}

static void test_set_id_alone(void **state)
{
    (void)state;
    lsc_lxclient c;
    lsc_lx_refusal why = LSC_LX_DONE;
    uint8_t old = 0;
    const uint8_t one[] = {5}, three[] = {1, 2, 3}, look_alike[] = {1, 121};
    /* nobody */
    setup(&c, NULL, 0);
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 7, 0, &old, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_NO_SERVO);
    /* three servos: their answers collide */
    setup(&c, three, 3);
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 7, 0, &old, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_NOT_ALONE);
    assert_int_equal(t.cmds[LSC_LX_ID_WRITE], 0);
    /* servos 1 and 121 answer the broadcast with bytes that AND into a good
     * answer from 1: only the scan tells there are two */
    setup(&c, look_alike, 2);
    lsc_lx_whois who;
    assert_int_equal(lsc_lxclient_whois(&c, &who), 0);
    assert_int_equal(who.id, 1);
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 7, 0, &old, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_NOT_ALONE);
    assert_int_equal(t.cmds[LSC_LX_ID_WRITE], 0);
    /* a servo that shares an id with another: a garbled id in the scan */
    const uint8_t shared[] = {1, 121, 121};
    setup(&c, shared, 3);
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 7, 0, &old, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_NOT_ALONE);
    /* the broadcast answered, then nothing answers the scan */
    setup(&c, one, 1);
    t.drop_after_cmd = LSC_LX_ID_READ;
    t.drop_n = 1000;
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 7, 0, &old, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_NO_SERVO);
    /* the broadcast answered, then the scan's answer is garbled */
    const uint8_t zero[] = {0};
    setup(&c, zero, 1);
    t.hook = garble_second;
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 7, 0, &old, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_NOT_ALONE);
    /* 0 and 119 answer the broadcast as one good 0; the scan finds 0, and
     * 119's answer garbled */
    const uint8_t pair[] = {0, 119};
    setup(&c, pair, 2);
    t.hook = garble_119;
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 7, 0, &old, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_NOT_ALONE);
    assert_int_equal(t.cmds[LSC_LX_ID_WRITE], 0);
    /* the broadcast's answer is 5; the scan finds only 6 */
    setup(&c, one, 1);
    t.hook = rename_after_whois;
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 7, 0, &old, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_NOT_ALONE);
    assert_int_equal(t.cmds[LSC_LX_ID_WRITE], 0);
    /* alone: renamed */
    setup(&c, one, 1);
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 7, 0, &old, &why), 0);
    assert_int_equal(why, LSC_LX_DONE);
    assert_int_equal(old, 5);
    assert_int_equal(bus.servo[0].id, 7);
    assert_int_equal(t.cmds[LSC_LX_ID_WRITE], 1);
    /* already the id asked: nothing written */
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 7, 0, NULL, NULL), 0);
    assert_int_equal(t.cmds[LSC_LX_ID_WRITE], 1);
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 254, 0, NULL, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_BAD_ARGUMENT);
    /* the transport fails: in the broadcast, in the scan */
    t.write_error = LSC_EIO;
    assert_int_equal(lsc_lxclient_set_id_alone(&c, 8, 0, NULL, &why), LSC_EIO);
    assert_int_equal(why, LSC_LX_DONE);
    t.fail_after_scan = false;
    {
        lsc_io io = {&t, tap_write, counting_read, tap_now};
        assert_int_equal(lsc_lxclient_init(&c, &io), 0);
        reads_seen = 0;
        fail_on_nth_read = 0;
        lsc_lx_whois w2;
        assert_int_equal(lsc_lxclient_whois(&c, &w2), 0);
        fail_on_nth_read = reads_seen + 3;
        reads_seen = 0;
        assert_int_equal(lsc_lxclient_set_id_alone(&c, 8, 0, NULL, &why), LSC_ENODEV);
        assert_int_equal(why, LSC_LX_DONE);
        fail_on_nth_read = 0;
    }
}

static void test_offset_change(void **state)
{
    (void)state;
    lsc_lxclient c;
    lsc_lx_refusal why = LSC_LX_DONE;
    int8_t off = 0;
    const uint8_t ids[] = {1, 3};
    setup(&c, ids, 2);
    assert_int_equal(lsc_lxclient_offset_change(&c, 1, 15, true, &off, &why), 0);
    assert_int_equal(off, 15);
    assert_int_equal(lsc_lxclient_offset_change(&c, 3, -20, false, &off, &why), 0);
    assert_int_equal(off, -20);
    assert_int_equal(lsc_lxclient_offset_change(&c, 3, -5, false, NULL, NULL), 0);
    lsc_lxbus_power_cycle(&bus);
    assert_int_equal(lsc_lxclient_read_offset(&c, 1, &off), 0);
    assert_int_equal(off, 15); /* saved */
    assert_int_equal(lsc_lxclient_read_offset(&c, 3, &off), 0);
    assert_int_equal(off, 0); /* adjusted only: lost */
    /* delta 0 with save: saves what is in effect, writes no adjust */
    assert_int_equal(lsc_lxclient_adjust_offset(&c, 3, 30), 0);
    unsigned adjusts = t.cmds[LSC_LX_OFFSET_ADJUST];
    assert_int_equal(lsc_lxclient_offset_change(&c, 3, 0, true, &off, &why), 0);
    assert_int_equal(t.cmds[LSC_LX_OFFSET_ADJUST], adjusts);
    lsc_lxbus_power_cycle(&bus);
    assert_int_equal(lsc_lxclient_read_offset(&c, 3, &off), 0);
    assert_int_equal(off, 30);
    /* out of range: refused, nothing written */
    unsigned writes = t.cmds[LSC_LX_OFFSET_ADJUST] + t.cmds[LSC_LX_OFFSET_WRITE];
    assert_int_equal(lsc_lxclient_offset_change(&c, 3, 100, true, &off, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_OUT_OF_RANGE);
    assert_int_equal(lsc_lxclient_offset_change(&c, 3, -156, true, &off, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_OUT_OF_RANGE);
    assert_int_equal(lsc_lxclient_offset_change(&c, 3, 251, true, &off, &why), LSC_EINVAL);
    assert_int_equal(why, LSC_LX_BAD_ARGUMENT);
    assert_int_equal(lsc_lxclient_offset_change(&c, 3, -251, true, &off, &why), LSC_EINVAL);
    assert_int_equal(lsc_lxclient_offset_change(&c, 254, 1, true, &off, &why), LSC_EINVAL);
    assert_int_equal(t.cmds[LSC_LX_OFFSET_ADJUST] + t.cmds[LSC_LX_OFFSET_WRITE], writes);
    /* no servo */
    assert_int_equal(lsc_lxclient_offset_change(&c, 2, 1, true, &off, &why), LSC_ETIMEOUT);
    assert_int_equal(why, LSC_LX_DONE);
    /* the adjust is lost on the way: the read back differs */
    t.swallow_cmd = LSC_LX_OFFSET_ADJUST;
    off = 99;
    assert_int_equal(lsc_lxclient_offset_change(&c, 3, 1, false, &off, &why), LSC_EREPLY);
    assert_int_equal(why, LSC_LX_NOT_READ_BACK);
    assert_int_equal(off, 99);
    t.swallow_cmd = 0;
    t.drop_after_cmd = LSC_LX_OFFSET_ADJUST;
    t.drop_n = 1;
    assert_int_equal(lsc_lxclient_offset_change(&c, 3, 1, false, &off, &why), LSC_ETIMEOUT);
    assert_int_equal(why, LSC_LX_NOT_READ_BACK);
    t.drop_after_cmd = 0;
    /* the adjust's write fails */
    write_fail_on_cmd = LSC_LX_OFFSET_ADJUST;
    lsc_io io = {&t, cmd_failing_write, tap_read, tap_now};
    assert_int_equal(lsc_lxclient_init(&c, &io), 0);
    assert_int_equal(lsc_lxclient_offset_change(&c, 3, 1, true, &off, &why), LSC_EIO);
    assert_int_equal(why, LSC_LX_DONE);
    /* the save's write fails */
    write_fail_on_cmd = LSC_LX_OFFSET_WRITE;
    assert_int_equal(lsc_lxclient_offset_change(&c, 3, 1, true, &off, &why), LSC_EIO);
    write_fail_on_cmd = 0;
}

static void test_move_together(void **state)
{
    (void)state;
    lsc_lxclient c;
    const uint8_t ids[] = {1, 2, 3};
    setup(&c, ids, 3);
    lsc_servo s[2] = {{2, 700}, {3, 250}};
    assert_int_equal(lsc_lxclient_move_together(&c, s, 2, 300), 0);
    assert_int_equal(t.cmds[LSC_LX_MOVE_TIME_WAIT_WRITE], 2);
    assert_int_equal(t.cmds[LSC_LX_MOVE_START], 1);
    assert_int_equal(t.last[2], LSC_LX_BROADCAST);
    lsc_lxbus_advance_us(&bus, 300000);
    int16_t pos[3];
    for (uint8_t id = 1; id <= 3; id++) {
        assert_int_equal(lsc_lxclient_read_position(&c, id, &pos[id - 1]), 0);
    }
    assert_true(pos[0] == 500 && pos[1] == 700 && pos[2] == 250);
    /* a write that fails stops before the start */
    t.write_error = LSC_EIO;
    assert_int_equal(lsc_lxclient_move_together(&c, s, 2, 300), LSC_EIO);
    assert_int_equal(t.cmds[LSC_LX_MOVE_START], 1);
    t.write_short = 1;
    assert_int_equal(lsc_lxclient_move(&c, 1, 0, 0), LSC_EIO);
}

static void test_refusal_str(void **state)
{
    (void)state;
    for (int w = LSC_LX_DONE; w <= LSC_LX_OUT_OF_RANGE; w++) {
        const char *s = lsc_lx_refusal_str((lsc_lx_refusal)w);
        assert_non_null(s);
        assert_true(strlen(s) > 3);
    }
    assert_string_equal(lsc_lx_refusal_str((lsc_lx_refusal)99), "unknown refusal");
    assert_non_null(strstr(lsc_lx_refusal_str(LSC_LX_NOT_ALONE), "alone"));
}

/* ---- A scripted line ------------------------------------------------------------------------- */

/* What the line answers: to the k-th frame written, resp[k] (a gap of gap_ms
 * after gap_at of its bytes); before the first write, pre. stuck: every read
 * brings a 0x00 byte and moves the clock step_ms. */
typedef struct line {
    uint32_t now;
    bool stuck;
    uint32_t step_ms;
    const uint8_t *pre;
    size_t npre;
    const uint8_t *resp[4];
    size_t nresp[4];
    size_t gap_at;
    uint32_t gap_ms;
    size_t writes;
    const uint8_t *q; /* what is on its way */
    size_t qn, qat;
    unsigned reads;
    int impossible_write;
    uint8_t traced_tx, traced_rx;
} line;

static int line_write(void *ctx, const uint8_t *data, size_t n)
{
    line *l = ctx;
    (void)data;
    if (l->writes < 4) {
        l->q = l->resp[l->writes];
        l->qn = l->nresp[l->writes];
        l->qat = 0;
    }
    l->writes++;
    return l->impossible_write ? (int)n + 1 : (int)n;
}

static int line_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    line *l = ctx;
    l->reads++;
    if (l->stuck) {
        l->now += l->step_ms;
        buf[0] = 0x00;
        return 1;
    }
    if (l->writes == 0 && l->npre > 0) {
        l->q = l->pre;
        l->qn = l->npre;
        l->qat = 0;
        l->npre = 0;
    }
    if (l->qat < l->qn && l->qat == l->gap_at && l->gap_ms > 0) {
        uint32_t step = l->gap_ms < timeout_ms ? l->gap_ms : timeout_ms;
        l->gap_ms -= step;
        l->now += step;
        if (l->gap_ms > 0 || step == 0) {
            return 0;
        }
    }
    if (l->qat >= l->qn) {
        l->now += timeout_ms;
        return 0;
    }
    size_t k = 0;
    while (k < cap && l->qat < l->qn && !(l->qat == l->gap_at && l->gap_ms > 0)) {
        buf[k++] = l->q[l->qat++];
    }
    return (int)k;
}

static uint32_t line_now(void *ctx)
{
    return ((line *)ctx)->now;
}

static void line_client(line *l, lsc_lxclient *c)
{
    memset(l, 0, sizeof *l);
    l->gap_at = SIZE_MAX;
    lsc_io io = {l, line_write, line_read, line_now};
    assert_int_equal(lsc_lxclient_init(c, &io), 0);
}

static void trace(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    line *l = user;
    assert_true(n >= LSC_LX_FRAME_MIN && frame[0] == 0x55 && frame[1] == 0x55);
    if (dir == LSC_TRACE_TX) {
        l->traced_tx++;
    } else {
        l->traced_rx++;
    }
}

/* Frames a servo might send. */
static const uint8_t pos1[] = {0x55, 0x55, 0x01, 0x05, 0x1C, 0xF4, 0x01, 0xE8}; /* 1 at 500 */
static const uint8_t pos2[] = {0x55, 0x55, 0x02, 0x05, 0x1C, 0xF4, 0x01, 0xE7}; /* 2 at 500 */
static const uint8_t id1[] = {0x55, 0x55, 0x01, 0x04, 0x0E, 0x01, 0xEB};
static const uint8_t id2[] = {0x55, 0x55, 0x02, 0x04, 0x0E, 0x02, 0xE9};

/* Two frames back to back into buf; returns the length. */
static size_t concat(uint8_t *buf, const uint8_t *a, size_t na, const uint8_t *b, size_t nb)
{
    memcpy(buf, a, na);
    memcpy(buf + na, b, nb);
    return na + nb;
}

static void test_line_stuck_clock(void **state)
{
    (void)state;
    line l;
    lsc_lxclient c;
    line_client(&l, &c);
    l.stuck = true;
    lsc_lxclient_set_timeout(&c, 10);
    int16_t pos;
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), LSC_EREPLY);
    assert_true(l.reads <= LSC_LXCLIENT_DRAIN_READS + LSC_LXCLIENT_WAIT_READS_MIN +
                              LSC_LXCLIENT_READS_PER_MS * 10u);
    /* the clock moves while bytes keep coming: the drain ends on time */
    l.reads = 0;
    l.step_ms = 30;
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), LSC_EREPLY);
    assert_true(l.reads <= 3);
    line_client(&l, &c);
    l.impossible_write = 1;
    assert_int_equal(lsc_lxclient_move(&c, 1, 0, 0), LSC_EIO);
}

/* A torn frame, the line silent past the gap, then the reply: taken. */
static void test_line_gap(void **state)
{
    (void)state;
    uint8_t torn[32];
    line l;
    lsc_lxclient c;
    line_client(&l, &c);
    l.resp[0] = torn;
    l.nresp[0] = concat(torn, pos1, 4, pos1, sizeof pos1);
    l.gap_at = 4;
    l.gap_ms = LSC_LXCLIENT_GAP_MS + 5;
    lsc_lxclient_set_trace(&c, trace, &l);
    int16_t pos = 0;
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), 0);
    assert_int_equal(pos, 500);
    assert_int_equal(l.traced_tx, 1);
    assert_int_equal(l.traced_rx, 1);
    lsc_lxclient_set_trace(&c, NULL, NULL);
    /* a torn frame and nothing after it: garbled */
    line_client(&l, &c);
    l.resp[0] = pos1;
    l.nresp[0] = 4;
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), LSC_EREPLY);
    /* a torn frame before the request: the reply after it is still found */
    line_client(&l, &c);
    l.pre = pos1;
    l.npre = 4;
    l.resp[0] = pos1;
    l.nresp[0] = sizeof pos1;
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), 0);
    assert_int_equal(c.parser.discarded, 4);
}

static void test_line_replies(void **state)
{
    (void)state;
    uint8_t buf[32];
    line l;
    lsc_lxclient c;
    int16_t pos = 0;
    /* a reply in range but refused by the decoder (min >= max) */
    const uint8_t limits[] = {0x55, 0x55, 0x01, 0x07, 0x15, 0x10, 0x00, 0x10, 0x00, 0xC2};
    line_client(&l, &c);
    l.resp[0] = limits;
    l.nresp[0] = sizeof limits;
    uint16_t a = 1, b = 2;
    assert_int_equal(lsc_lxclient_read_limits(&c, 1, &a, &b), LSC_EREPLY);
    assert_true(a == 1 && b == 2);
    /* another command's reply from the id asked, then the reply */
    line_client(&l, &c);
    l.resp[0] = buf;
    l.nresp[0] = concat(buf, id1, sizeof id1, pos1, sizeof pos1);
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), 0);
    assert_int_equal(c.strays, 1);
    assert_int_equal(c.replies, 1);
    /* the reply twice in one read: the second is not taken */
    line_client(&l, &c);
    l.resp[0] = buf;
    l.nresp[0] = concat(buf, pos1, sizeof pos1, pos1, sizeof pos1);
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), 0);
    assert_int_equal(c.strays, 1);
    assert_int_equal(c.replies, 1);
    /* timeout 0: what is there already is taken */
    line_client(&l, &c);
    lsc_lxclient_set_timeout(&c, 0);
    l.resp[0] = pos1;
    l.nresp[0] = sizeof pos1;
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), 0);
    /* the longest timeout: the read budget saturates */
    line_client(&l, &c);
    lsc_lxclient_set_timeout(&c, UINT32_MAX);
    l.resp[0] = pos1;
    l.nresp[0] = sizeof pos1;
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), 0);
}

static void test_line_whois(void **state)
{
    (void)state;
    uint8_t buf[32];
    line l;
    lsc_lxclient c;
    lsc_lx_whois who;
    /* two good answers (and another command's reply): collided */
    uint8_t buf2[32];
    line_client(&l, &c);
    size_t n = concat(buf2, id1, sizeof id1, id2, sizeof id2);
    l.resp[0] = buf;
    l.nresp[0] = concat(buf, buf2, n, pos2, sizeof pos2);
    assert_int_equal(lsc_lxclient_whois(&c, &who), LSC_EREPLY);
    assert_true(who.answers == 2 && who.id == 1 && !who.garbled);
    assert_int_equal(c.strays, 1);
    /* one good answer and noise */
    line_client(&l, &c);
    l.resp[0] = buf;
    l.nresp[0] = concat(buf, id2, sizeof id2, (const uint8_t *)"\x01", 1);
    assert_int_equal(lsc_lxclient_whois(&c, &who), LSC_EREPLY);
    assert_true(who.answers == 1 && who.garbled);
    /* noise only */
    line_client(&l, &c);
    l.resp[0] = pos1;
    l.nresp[0] = 3;
    assert_int_equal(lsc_lxclient_whois(&c, &who), LSC_EREPLY);
    assert_true(who.answers == 0 && who.garbled);
}

/* A scan hears a position reply, and an id that answered twice. */
static void test_line_scan(void **state)
{
    (void)state;
    uint8_t buf[32];
    line l;
    lsc_lxclient c;
    lsc_lx_scan scan;
    line_client(&l, &c);
    l.resp[0] = buf;
    l.nresp[0] = concat(buf, pos2, sizeof pos2, id1, sizeof id1);
    /* then 1 again and 5 (not asked: not asked again either) */
    const uint8_t id5[] = {0x55, 0x55, 0x05, 0x04, 0x0E, 0x05, 0xE3};
    uint8_t buf2[32];
    l.resp[1] = buf2;
    l.nresp[1] = concat(buf2, id1, sizeof id1, id5, sizeof id5);
    const uint8_t ids[] = {1, 2};
    assert_int_equal(lsc_lxclient_scan(&c, ids, 2, 5, &scan), 1);
    assert_true(lsc_lx_scan_found(&scan, 1));
    assert_false(lsc_lx_scan_found(&scan, 2));
    assert_false(lsc_lx_scan_found(&scan, 5));
    assert_int_equal(l.writes, 2); /* 1, late again, is not asked again; nor 5 */
}

/* An answer split across two ids' waits (the first id's wait ended with
 * part of it): it completes in the next wait, is known by its id, and that
 * id is asked again. */
static void test_line_scan_split_answer(void **state)
{
    (void)state;
    line l;
    lsc_lxclient c;
    lsc_lx_scan scan;
    line_client(&l, &c);
    l.resp[0] = id1;
    l.nresp[0] = 3;
    l.resp[1] = id1 + 3;
    l.nresp[1] = sizeof id1 - 3;
    l.resp[2] = id1;
    l.nresp[2] = sizeof id1;
    const uint8_t ids[] = {1, 2};
    assert_int_equal(lsc_lxclient_scan(&c, ids, 2, 5, &scan), 1);
    assert_true(lsc_lx_scan_found(&scan, 1));
    assert_false(lsc_lx_scan_garbled(&scan, 2));
    assert_int_equal(l.writes, 3);
    assert_int_equal(c.strays, 1);
}

static void test_line_impossible_read(void **state)
{
    (void)state;
    line l;
    lsc_lxclient c;
    line_client(&l, &c);
    memset(&t, 0, sizeof t);
    lsc_io inner = {&l, line_write, line_read, line_now};
    t.inner = inner;
    t.read_impossible = 1;
    lsc_io io = {&t, tap_write, tap_read, tap_now};
    assert_int_equal(lsc_lxclient_init(&c, &io), 0);
    int16_t pos;
    assert_int_equal(lsc_lxclient_read_position(&c, 1, &pos), LSC_EIO);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_init),
        cmocka_unit_test(test_reads_and_writes),
        cmocka_unit_test(test_refused_before_sending),
        cmocka_unit_test(test_flipped_bit),
        cmocka_unit_test(test_echo_reads_the_same),
        cmocka_unit_test(test_stray_reply_not_taken),
        cmocka_unit_test(test_whois),
        cmocka_unit_test(test_scan_whole_bus),
        cmocka_unit_test(test_scan_late_answers),
        cmocka_unit_test(test_change_id),
        cmocka_unit_test(test_change_id_transport),
        cmocka_unit_test(test_scan_listen_fails),
        cmocka_unit_test(test_set_id_alone),
        cmocka_unit_test(test_offset_change),
        cmocka_unit_test(test_move_together),
        cmocka_unit_test(test_refusal_str),
        cmocka_unit_test(test_line_stuck_clock),
        cmocka_unit_test(test_line_gap),
        cmocka_unit_test(test_line_replies),
        cmocka_unit_test(test_line_whois),
        cmocka_unit_test(test_line_scan),
        cmocka_unit_test(test_line_scan_split_answer),
        cmocka_unit_test(test_line_impossible_read),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
