/* The virtual bus of serial bus servos (include/lsc/lxbus.h), driven by raw
 * frames of the bus-servo protocol in virtual time. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "lsc/lx.h"
#include "lsc/lxbus.h"

static lsc_lxbus bus; /* ~4 KiB: not on the stack */

static void setup_bus(size_t n)
{
    assert_int_equal(lsc_lxbus_init(&bus), 0);
    for (size_t i = 0; i < n; i++) {
        assert_int_equal(lsc_lxbus_add(&bus, (uint8_t)(i + 1u)), (int)i);
    }
}

static void send(const uint8_t *frame, int n)
{
    assert_true(n > 0);
    assert_int_equal(lsc_lxbus_feed(&bus, frame, (size_t)n), n);
}

/* Reads everything the bus has sent by now into buf; returns the count. */
static size_t drain(uint8_t *buf, size_t cap)
{
    return lsc_lxbus_read(&bus, buf, cap);
}

/* Sends the read cmd to id and returns the one reply frame (asserted). */
static lsc_lx_frame ask(lsc_lx_parser *p, uint8_t id, uint8_t cmd)
{
    uint8_t req[LSC_LX_FRAME_MAX], out[64];
    send(req, lsc_lx_encode_request(req, sizeof req, id, cmd));
    size_t n = drain(out, sizeof out);
    assert_true(n > 0);
    lsc_lx_frame f = {0, 0, 0, false, NULL};
    int frames = 0;
    assert_int_equal(lsc_lx_parser_init(p), 0);
    for (size_t i = 0; i < n; i++) {
        if (lsc_lx_parser_feed(p, out[i], &f) == 1) {
            frames++;
            assert_int_equal(i + 1u, n); /* the reply is the last */
        }
    }
    assert_int_equal(frames, 1);
    assert_int_equal(f.cmd, cmd);
    assert_true(f.reply);
    return f;
}

static int16_t pos_of(uint8_t id)
{
    lsc_lx_parser p;
    lsc_lx_frame f = ask(&p, id, LSC_LX_POS_READ);
    int16_t pos = 0;
    assert_int_equal(lsc_lx_decode_position(&f, &pos), 0);
    assert_int_equal(f.id, id);
    return pos;
}

/* No reply at all to this read (advance a while first). */
static void no_reply(uint8_t id, uint8_t cmd)
{
    uint8_t req[LSC_LX_FRAME_MAX], out[64];
    send(req, lsc_lx_encode_request(req, sizeof req, id, cmd));
    lsc_lxbus_advance_us(&bus, 100000);
    assert_int_equal(drain(out, sizeof out), 0);
}

static void move(uint8_t id, uint8_t cmd, uint16_t pos, uint16_t time)
{
    uint8_t fr[LSC_LX_FRAME_MAX];
    send(fr, lsc_lx_encode_move_time(fr, sizeof fr, id, cmd, pos, time));
}

static void test_fresh_servos_read_500(void **state)
{
    (void)state;
    setup_bus(3);
    for (uint8_t id = 1; id <= 3; id++) {
        assert_int_equal(pos_of(id), 500);
    }
    no_reply(4, LSC_LX_POS_READ);
    assert_int_equal(bus.stats.ignored, 1);
    lsc_lx_parser p;
    bool on = true;
    lsc_lx_frame f = ask(&p, 1, LSC_LX_LOAD_READ);
    assert_int_equal(lsc_lx_decode_load(&f, &on), 0);
    assert_false(on); /* torque off at power-on */
    uint16_t lo = 0, hi = 0;
    f = ask(&p, 1, LSC_LX_ANGLE_LIMIT_READ);
    assert_int_equal(lsc_lx_decode_angle_limit(&f, &lo, &hi), 0);
    assert_int_equal(lo, 0);
    assert_int_equal(hi, 1000);
    f = ask(&p, 1, LSC_LX_VIN_LIMIT_READ);
    assert_int_equal(lsc_lx_decode_vin_limit(&f, &lo, &hi), 0);
    assert_int_equal(lo, 4500);
    assert_int_equal(hi, 12000);
    uint8_t u8 = 0;
    f = ask(&p, 1, LSC_LX_TEMP_LIMIT_READ);
    assert_int_equal(lsc_lx_decode_temp_limit(&f, &u8), 0);
    assert_int_equal(u8, 85);
    f = ask(&p, 1, LSC_LX_TEMP_READ);
    assert_int_equal(lsc_lx_decode_temp(&f, &u8), 0);
    assert_int_equal(u8, LSC_LXBUS_TEMP_DEFAULT);
    f = ask(&p, 1, LSC_LX_VIN_READ);
    assert_int_equal(lsc_lx_decode_vin(&f, &lo), 0);
    assert_int_equal(lo, 7500);
    f = ask(&p, 1, LSC_LX_LED_CTRL_READ);
    assert_int_equal(lsc_lx_decode_led_ctrl(&f, &on), 0);
    assert_true(on);
    f = ask(&p, 1, LSC_LX_LED_ERROR_READ);
    assert_int_equal(lsc_lx_decode_led_error(&f, &u8), 0);
    assert_int_equal(u8, 7);
    int8_t off = 9;
    f = ask(&p, 1, LSC_LX_OFFSET_READ);
    assert_int_equal(lsc_lx_decode_offset(&f, &off), 0);
    assert_int_equal(off, 0);
}

/* A move goes linearly over its time, from where the servo is. */
static void test_move_over_time(void **state)
{
    (void)state;
    setup_bus(3);
    move(2, LSC_LX_MOVE_TIME_WRITE, 700, 300);
    assert_true(lsc_lxbus_moving(&bus, 1));
    lsc_lxbus_advance_us(&bus, 150000);
    assert_int_equal(pos_of(2), 600);
    lsc_lxbus_advance_us(&bus, 150000);
    assert_int_equal(pos_of(2), 700);
    assert_false(lsc_lxbus_moving(&bus, 1));
    assert_int_equal(pos_of(1), 500);
    /* downwards, rounded towards the start */
    move(2, LSC_LX_MOVE_TIME_WRITE, 0, 3);
    lsc_lxbus_advance_us(&bus, 1000);
    assert_int_equal(pos_of(2), 467); /* 700 - 233.3 */
    lsc_lx_parser p;
    uint16_t pos = 0, time = 0;
    lsc_lx_frame f = ask(&p, 2, LSC_LX_MOVE_TIME_READ);
    assert_int_equal(lsc_lx_decode_move_time(&f, &pos, &time), 0);
    assert_int_equal(pos, 0);
    assert_int_equal(time, 3);
    bool on = false;
    f = ask(&p, 2, LSC_LX_LOAD_READ);
    assert_int_equal(lsc_lx_decode_load(&f, &on), 0);
    assert_true(on); /* a move turns the torque on */
    /* stop where it is */
    uint8_t fr[LSC_LX_FRAME_MAX];
    send(fr, lsc_lx_encode_request(fr, sizeof fr, 2, LSC_LX_MOVE_STOP));
    lsc_lxbus_advance_us(&bus, 5000);
    assert_int_equal(pos_of(2), 467);
}

/* MOVE_TIME_WAIT_WRITE to each, then one broadcast MOVE_START. */
static void test_wait_then_start(void **state)
{
    (void)state;
    setup_bus(3);
    move(2, LSC_LX_MOVE_TIME_WAIT_WRITE, 700, 300);
    move(3, LSC_LX_MOVE_TIME_WAIT_WRITE, 250, 300);
    lsc_lxbus_advance_us(&bus, 400000);
    assert_int_equal(pos_of(2), 500); /* waiting */
    lsc_lx_parser p;
    uint16_t pos = 0, time = 0;
    lsc_lx_frame f = ask(&p, 3, LSC_LX_MOVE_TIME_WAIT_READ);
    assert_int_equal(lsc_lx_decode_move_time(&f, &pos, &time), 0);
    assert_int_equal(pos, 250);
    assert_int_equal(time, 300);
    uint8_t fr[LSC_LX_FRAME_MAX];
    send(fr, lsc_lx_encode_request(fr, sizeof fr, LSC_LX_BROADCAST, LSC_LX_MOVE_START));
    assert_int_equal(bus.stats.ignored, 0); /* servo 1 has nothing waiting, 2 and 3 obey */
    lsc_lxbus_advance_us(&bus, 300000);
    assert_int_equal(pos_of(1), 500);
    assert_int_equal(pos_of(2), 700);
    assert_int_equal(pos_of(3), 250);
    /* a second start finds nothing waiting */
    send(fr, lsc_lx_encode_request(fr, sizeof fr, 2, LSC_LX_MOVE_START));
    assert_int_equal(bus.stats.ignored, 1);
}

/* Broadcast: obeyed by all, answered by none but ID_READ, whose answers
 * collide (bytes ANDed) when there are several. */
static void test_broadcast_and_collisions(void **state)
{
    (void)state;
    setup_bus(3);
    move(LSC_LX_BROADCAST, LSC_LX_MOVE_TIME_WRITE, 100, 0);
    for (uint8_t id = 1; id <= 3; id++) {
        assert_int_equal(pos_of(id), 100);
    }
    /* a position read to 254 (the encoders refuse to make one): no answer */
    static const uint8_t pos254[] = {0x55, 0x55, 0xFE, 0x03, 0x1C, 0xE2};
    uint32_t ignored = bus.stats.ignored;
    send(pos254, sizeof pos254);
    assert_int_equal(lsc_lxbus_available(&bus), 0);
    assert_int_equal(bus.stats.ignored, ignored + 1u);
    /* ID_READ to 254 with three servos: one frame's worth of ANDed bytes */
    uint8_t req[LSC_LX_FRAME_MAX], out[64];
    send(req, lsc_lx_encode_request(req, sizeof req, LSC_LX_BROADCAST, LSC_LX_ID_READ));
    size_t n = drain(out, sizeof out);
    assert_int_equal(n, 7);
    assert_int_equal(bus.stats.collisions, 1);
    uint8_t r1[8], r2[8], r3[8];
    (void)lsc_lx_encode_id(r1, sizeof r1, 1, LSC_LX_ID_READ, 1);
    (void)lsc_lx_encode_id(r2, sizeof r2, 2, LSC_LX_ID_READ, 2);
    (void)lsc_lx_encode_id(r3, sizeof r3, 3, LSC_LX_ID_READ, 3);
    for (size_t i = 0; i < 7; i++) {
        assert_int_equal(out[i], r1[i] & r2[i] & r3[i]);
    }
    /* the AND of 1, 2, 3 is id 0, and its checksum fails: never believed */
    lsc_lx_parser p;
    lsc_lx_frame f;
    assert_int_equal(lsc_lx_parser_init(&p), 0);
    for (size_t i = 0; i < n; i++) {
        assert_true(lsc_lx_parser_feed(&p, out[i], &f) != 1);
    }
    assert_int_equal(p.bad_checksums, 1);
    /* one servo alone answers with its id */
    setup_bus(0);
    assert_int_equal(lsc_lxbus_add(&bus, 7), 0);
    f = ask(&p, LSC_LX_BROADCAST, LSC_LX_ID_READ);
    uint8_t id = 0;
    assert_int_equal(lsc_lx_decode_id(&f, &id), 0);
    assert_int_equal(id, 7);
    assert_int_equal(f.id, 7);
    /* two servos with the same id: both obey, and both answer (collide) */
    assert_int_equal(lsc_lxbus_add(&bus, 7), 1);
    move(7, LSC_LX_MOVE_TIME_WRITE, 900, 0);
    assert_int_equal(lsc_lxbus_position(&bus, 0), 900);
    assert_int_equal(lsc_lxbus_position(&bus, 1), 900);
    uint32_t before = bus.stats.collisions;
    (void)pos_of(7); /* equal answers AND to themselves */
    assert_int_equal(bus.stats.collisions, before + 1u);
}

/* ID_WRITE renames at once and survives power-off; to 254 it renames every
 * servo (the hazard of writing an id through a board). */
static void test_id_write(void **state)
{
    (void)state;
    setup_bus(3);
    uint32_t changes = bus.changes;
    uint8_t fr[LSC_LX_FRAME_MAX];
    send(fr, lsc_lx_encode_id(fr, sizeof fr, 2, LSC_LX_ID_WRITE, 9));
    assert_true(bus.changes > changes);
    no_reply(2, LSC_LX_POS_READ);
    assert_int_equal(pos_of(9), 500);
    lsc_lxbus_power_cycle(&bus);
    assert_int_equal(pos_of(9), 500);
    assert_int_equal(lsc_lxbus_find(&bus, 9), 1);
    send(fr, lsc_lx_encode_id(fr, sizeof fr, LSC_LX_BROADCAST, LSC_LX_ID_WRITE, 5));
    for (size_t i = 0; i < 3; i++) {
        assert_int_equal(bus.servo[i].id, 5);
    }
    assert_int_equal(lsc_lxbus_find(&bus, 1), -1);
}

/* Angle limits hold every move inside them. */
static void test_limits_clamp(void **state)
{
    (void)state;
    setup_bus(1);
    uint8_t fr[LSC_LX_FRAME_MAX];
    send(fr, lsc_lx_encode_angle_limit(fr, sizeof fr, 1, LSC_LX_ANGLE_LIMIT_WRITE, 100, 900));
    move(1, LSC_LX_MOVE_TIME_WRITE, 1000, 0);
    assert_int_equal(pos_of(1), 900);
    move(1, LSC_LX_MOVE_TIME_WRITE, 0, 0);
    assert_int_equal(pos_of(1), 100);
    lsc_lxbus_power_cycle(&bus);
    move(1, LSC_LX_MOVE_TIME_WRITE, 950, 0);
    assert_int_equal(pos_of(1), 900); /* kept at power-off */
}

/* An offset moves the shaft, and so POS_READ, at once; only a saved one
 * survives a power cycle. POS_READ goes negative. */
static void test_offsets(void **state)
{
    (void)state;
    setup_bus(3);
    uint8_t fr[LSC_LX_FRAME_MAX];
    send(fr, lsc_lx_encode_offset(fr, sizeof fr, 1, LSC_LX_OFFSET_ADJUST, 15));
    send(fr, lsc_lx_encode_request(fr, sizeof fr, 1, LSC_LX_OFFSET_WRITE));
    send(fr, lsc_lx_encode_offset(fr, sizeof fr, 3, LSC_LX_OFFSET_ADJUST, -20));
    assert_int_equal(pos_of(1), 515);
    assert_int_equal(pos_of(3), 480);
    lsc_lxbus_power_cycle(&bus);
    lsc_lx_parser p;
    int8_t off = 0;
    lsc_lx_frame f = ask(&p, 1, LSC_LX_OFFSET_READ);
    assert_int_equal(lsc_lx_decode_offset(&f, &off), 0);
    assert_int_equal(off, 15);
    f = ask(&p, 3, LSC_LX_OFFSET_READ);
    assert_int_equal(lsc_lx_decode_offset(&f, &off), 0);
    assert_int_equal(off, 0);
    /* the shafts did not move without power */
    assert_int_equal(pos_of(1), 515);
    assert_int_equal(pos_of(3), 480);
    move(1, LSC_LX_MOVE_TIME_WRITE, 0, 0);
    send(fr, lsc_lx_encode_offset(fr, sizeof fr, 1, LSC_LX_OFFSET_ADJUST, -125));
    assert_int_equal(pos_of(1), -125);
}

/* Motor mode: turning at speed units a second, wrapping at a turn; moves
 * refused; servo mode stops it where it is. */
static void test_motor_mode(void **state)
{
    (void)state;
    setup_bus(1);
    uint8_t fr[LSC_LX_FRAME_MAX];
    send(fr, lsc_lx_encode_motor_mode(fr, sizeof fr, 1, LSC_LX_MOTOR_MODE_WRITE, 1, 500));
    assert_true(lsc_lxbus_moving(&bus, 0));
    lsc_lxbus_advance_us(&bus, 1000000);
    assert_int_equal(pos_of(1), 1000);
    lsc_lxbus_advance_us(&bus, 1000000);
    assert_int_equal(pos_of(1), 0); /* 1500 wraps */
    lsc_lx_parser p;
    uint8_t mode = 0;
    int16_t speed = 0;
    lsc_lx_frame f = ask(&p, 1, LSC_LX_MOTOR_MODE_READ);
    assert_int_equal(lsc_lx_decode_motor_mode(&f, &mode, &speed), 0);
    assert_int_equal(mode, 1);
    assert_int_equal(speed, 500);
    uint32_t ignored = bus.stats.ignored;
    move(1, LSC_LX_MOVE_TIME_WRITE, 800, 0);
    assert_int_equal(bus.stats.ignored, ignored + 1u);
    /* backwards, then torque off stops it */
    send(fr, lsc_lx_encode_motor_mode(fr, sizeof fr, 1, LSC_LX_MOTOR_MODE_WRITE, 1, -100));
    lsc_lxbus_advance_us(&bus, 1000000);
    assert_int_equal(pos_of(1), 1400);
    send(fr, lsc_lx_encode_load(fr, sizeof fr, 1, LSC_LX_LOAD_WRITE, false));
    lsc_lxbus_advance_us(&bus, 1000000);
    assert_int_equal(pos_of(1), 1400);
    assert_false(lsc_lxbus_moving(&bus, 0));
    send(fr, lsc_lx_encode_load(fr, sizeof fr, 1, LSC_LX_LOAD_WRITE, true));
    lsc_lxbus_advance_us(&bus, 1000000);
    assert_int_equal(pos_of(1), 1300);
    /* servo mode: stops where it is, and moves again */
    send(fr, lsc_lx_encode_motor_mode(fr, sizeof fr, 1, LSC_LX_MOTOR_MODE_WRITE, 0, 0));
    lsc_lxbus_advance_us(&bus, 1000000);
    assert_int_equal(pos_of(1), 1300);
    move(1, LSC_LX_MOVE_TIME_WRITE, 800, 0);
    assert_int_equal(pos_of(1), 800);
    /* MOVE_STOP in motor mode stops the turning */
    send(fr, lsc_lx_encode_motor_mode(fr, sizeof fr, 1, LSC_LX_MOTOR_MODE_WRITE, 1, 1000));
    send(fr, lsc_lx_encode_request(fr, sizeof fr, 1, LSC_LX_MOVE_STOP));
    lsc_lxbus_advance_us(&bus, 1000000);
    assert_int_equal(pos_of(1), 800);
    /* motor mode is lost at power-off */
    lsc_lxbus_power_cycle(&bus);
    f = ask(&p, 1, LSC_LX_MOTOR_MODE_READ);
    assert_int_equal(lsc_lx_decode_motor_mode(&f, &mode, &speed), 0);
    assert_int_equal(mode, 0);
}

/* Faults: over temperature and the supply outside the limits turn the
 * torque off and refuse moves until they clear; the alarm mask says which
 * flash the LED. */
static void test_faults(void **state)
{
    (void)state;
    setup_bus(2);
    move(1, LSC_LX_MOVE_TIME_WRITE, 800, 1000);
    lsc_lxbus_advance_us(&bus, 500000);
    assert_int_equal(lsc_lxbus_set_temp(&bus, 0, 90), 0);
    assert_int_equal(lsc_lxbus_faults(&bus, 0), LSC_LX_ALARM_TEMP);
    assert_true(lsc_lxbus_led_alarm(&bus, 0));
    assert_false(bus.servo[0].torque);
    lsc_lxbus_advance_us(&bus, 1000000);
    assert_int_equal(pos_of(1), 650); /* stopped where the fault began */
    uint32_t ignored = bus.stats.ignored;
    move(1, LSC_LX_MOVE_TIME_WRITE, 100, 0);
    assert_int_equal(bus.stats.ignored, ignored + 1u);
    lsc_lx_parser p;
    uint8_t c = 0;
    lsc_lx_frame f = ask(&p, 1, LSC_LX_TEMP_READ);
    assert_int_equal(lsc_lx_decode_temp(&f, &c), 0);
    assert_int_equal(c, 90);
    /* a higher limit clears it */
    uint8_t fr[LSC_LX_FRAME_MAX];
    send(fr, lsc_lx_encode_temp_limit(fr, sizeof fr, 1, LSC_LX_TEMP_LIMIT_WRITE, 95));
    assert_int_equal(lsc_lxbus_faults(&bus, 0), 0);
    move(1, LSC_LX_MOVE_TIME_WRITE, 100, 0);
    assert_int_equal(pos_of(1), 100);
    /* the supply: outside the limits of both */
    assert_int_equal(lsc_lxbus_set_vin(&bus, 4000), 0);
    assert_int_equal(lsc_lxbus_faults(&bus, 1), LSC_LX_ALARM_VOLTAGE);
    send(fr, lsc_lx_encode_load(fr, sizeof fr, 2, LSC_LX_LOAD_WRITE, true));
    send(fr, lsc_lx_encode_motor_mode(fr, sizeof fr, 2, LSC_LX_MOTOR_MODE_WRITE, 1, 100));
    assert_false(bus.servo[1].torque);
    assert_int_equal(bus.servo[1].mode, 0);
    uint16_t mv = 0;
    f = ask(&p, 2, LSC_LX_VIN_READ);
    assert_int_equal(lsc_lx_decode_vin(&f, &mv), 0);
    assert_int_equal(mv, 4000);
    assert_int_equal(lsc_lxbus_set_vin(&bus, 7400), 0);
    /* a vin limit write that puts the supply outside */
    send(fr, lsc_lx_encode_vin_limit(fr, sizeof fr, 2, LSC_LX_VIN_LIMIT_WRITE, 8000, 9000));
    assert_int_equal(lsc_lxbus_faults(&bus, 1), LSC_LX_ALARM_VOLTAGE);
    /* a stall: LED only, and the mask can hide it */
    assert_int_equal(lsc_lxbus_set_stall(&bus, 0, true), 0);
    assert_int_equal(lsc_lxbus_faults(&bus, 0), LSC_LX_ALARM_STALL);
    assert_true(lsc_lxbus_led_alarm(&bus, 0));
    send(fr, lsc_lx_encode_led_error(fr, sizeof fr, 1, LSC_LX_LED_ERROR_WRITE, 3));
    assert_false(lsc_lxbus_led_alarm(&bus, 0));
    f = ask(&p, 1, LSC_LX_LED_ERROR_READ);
    assert_int_equal(lsc_lx_decode_led_error(&f, &c), 0);
    assert_int_equal(c, 3);
    /* bad arguments */
    assert_int_equal(lsc_lxbus_set_temp(&bus, 2, 20), LSC_EINVAL);
    assert_int_equal(lsc_lxbus_set_stall(&bus, 2, true), LSC_EINVAL);
    assert_int_equal(lsc_lxbus_set_vin(NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_lxbus_faults(&bus, 2), 0);
    assert_false(lsc_lxbus_led_alarm(&bus, 2));
}

/* LED ctrl survives power-off; the alarm mask does not. */
static void test_power_cycle_keeps(void **state)
{
    (void)state;
    setup_bus(1);
    uint8_t fr[LSC_LX_FRAME_MAX];
    send(fr, lsc_lx_encode_led_ctrl(fr, sizeof fr, 1, LSC_LX_LED_CTRL_WRITE, false));
    send(fr, lsc_lx_encode_led_error(fr, sizeof fr, 1, LSC_LX_LED_ERROR_WRITE, 1));
    send(fr, lsc_lx_encode_vin_limit(fr, sizeof fr, 1, LSC_LX_VIN_LIMIT_WRITE, 6000, 9000));
    send(fr, lsc_lx_encode_temp_limit(fr, sizeof fr, 1, LSC_LX_TEMP_LIMIT_WRITE, 70));
    move(1, LSC_LX_MOVE_TIME_WAIT_WRITE, 10, 10);
    lsc_lxbus_power_cycle(&bus);
    const lsc_lxbus_servo *s = &bus.servo[0];
    assert_false(s->led_on);
    assert_int_equal(s->alarm_mask, 7);
    assert_int_equal(s->vin_min, 6000);
    assert_int_equal(s->temp_limit, 70);
    assert_false(s->waiting);
}

/* Frames the servos do not obey: a bad checksum, out of range values, a
 * reply from the host, an unfinished frame; none is answered. */
static void test_ignored_frames(void **state)
{
    (void)state;
    setup_bus(1);
    uint8_t fr[LSC_LX_FRAME_MAX], out[16];
    int n = lsc_lx_encode_request(fr, sizeof fr, 1, LSC_LX_POS_READ);
    fr[n - 1] ^= 1u;
    send(fr, n);
    assert_int_equal(bus.stats.bad_frames, 1);
    assert_int_equal(drain(out, sizeof out), 0);
    /* out of range: a raw frame with position 1001 */
    static const uint8_t far[4] = {0xE9, 0x03, 0, 0};
    send(fr, lsc_lx_encode_frame(fr, sizeof fr, 1, LSC_LX_MOVE_TIME_WRITE, far, 4));
    assert_int_equal(bus.stats.ignored, 1);
    assert_int_equal(pos_of(1), 500);
    send(fr, lsc_lx_encode_position(fr, sizeof fr, 1, 5));
    assert_int_equal(bus.stats.ignored, 2);
    /* malformed and noise */
    static const uint8_t junk[] = {0x00, 0x55, 0x55, 0x01, 0x09};
    send(junk, sizeof junk);
    assert_int_equal(bus.stats.noise_bytes, 1);
    assert_int_equal(bus.stats.bad_frames, 2);
    /* half a frame, then silence, then a whole one */
    assert_int_equal(lsc_lx_encode_request(fr, sizeof fr, 1, LSC_LX_POS_READ), 6);
    send(fr, 3);
    lsc_lxbus_advance_us(&bus, (uint64_t)(LSC_LXBUS_FRAME_GAP_MS + 1u) * 1000u);
    assert_int_equal(pos_of(1), 500);
    assert_int_equal(bus.stats.bad_frames, 3);
    /* a write to no servo */
    move(9, LSC_LX_MOVE_TIME_WRITE, 10, 0);
    assert_int_equal(bus.stats.ignored, 3);
    assert_int_equal(lsc_lxbus_feed(&bus, NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_lxbus_feed(NULL, fr, 1), LSC_EINVAL);
}

/* Echo: the host hears its own bytes first, then the reply. */
static void test_echo(void **state)
{
    (void)state;
    setup_bus(1);
    lsc_lxbus_set_echo(&bus, true);
    uint8_t req[LSC_LX_FRAME_MAX], out[32];
    int n = lsc_lx_encode_request(req, sizeof req, 1, LSC_LX_POS_READ);
    send(req, n);
    size_t got = drain(out, sizeof out);
    assert_int_equal(got, (size_t)n + 8u);
    assert_memory_equal(out, req, (size_t)n);
    /* a host that expects its echo reads the same reply */
    lsc_lx_parser p;
    lsc_lx_frame f;
    assert_int_equal(lsc_lx_parser_init(&p), 0);
    assert_int_equal(lsc_lx_parser_expect_echo(&p, req, (size_t)n), 0);
    int frames = 0;
    for (size_t i = 0; i < got; i++) {
        frames += lsc_lx_parser_feed(&p, out[i], &f) == 1;
    }
    assert_int_equal(frames, 1);
    assert_int_equal(p.echoes, 1);
    int16_t pos = 0;
    assert_int_equal(lsc_lx_decode_position(&f, &pos), 0);
    assert_int_equal(pos, 500);
}

/* Pacing at 115200 baud: a 8-byte reply's last byte 8 byte times after the
 * request; fault injection. */
static void test_baud_and_faults(void **state)
{
    (void)state;
    setup_bus(1);
    lsc_lxbus_set_baud(&bus, 115200);
    uint8_t req[LSC_LX_FRAME_MAX], out[32];
    send(req, lsc_lx_encode_request(req, sizeof req, 1, LSC_LX_POS_READ));
    assert_int_equal(lsc_lxbus_available(&bus), 0);
    assert_int_equal(lsc_lxbus_next_event_us(&bus), 87); /* ceil(1e7 / 115200) */
    lsc_lxbus_advance_us(&bus, (uint64_t)87 * 4u);
    assert_int_equal(lsc_lxbus_available(&bus), 4);
    lsc_lxbus_advance_us(&bus, 1000);
    assert_int_equal(drain(out, sizeof out), 8);
    assert_int_equal(lsc_lxbus_next_event_us(&bus), LSC_LXBUS_TIME_NEVER);
    lsc_lxbus_set_baud(&bus, 0);
    lsc_lxbus_fault_drop(&bus, 1);
    no_reply(1, LSC_LX_POS_READ);
    assert_int_equal(bus.stats.dropped, 1);
    lsc_lxbus_fault_corrupt(&bus, 1, 5, 0x01);
    send(req, lsc_lx_encode_request(req, sizeof req, 1, LSC_LX_POS_READ));
    assert_int_equal(drain(out, sizeof out), 8);
    assert_int_equal(out[5], 0xF4 ^ 0x01);
    lsc_lxbus_fault_delay(&bus, 20);
    send(req, lsc_lx_encode_request(req, sizeof req, 1, LSC_LX_POS_READ));
    assert_int_equal(lsc_lxbus_next_event_us(&bus), 20000);
    lsc_lxbus_advance_us(&bus, 20000);
    assert_int_equal(drain(out, sizeof out), 8);
    assert_int_equal(out[5], 0xF4);
}

/* The text form: saved, loaded back as after a power cycle; refusals. */
static void test_save_load(void **state)
{
    (void)state;
    setup_bus(2);
    uint8_t fr[LSC_LX_FRAME_MAX];
    send(fr, lsc_lx_encode_offset(fr, sizeof fr, 1, LSC_LX_OFFSET_ADJUST, -7));
    send(fr, lsc_lx_encode_request(fr, sizeof fr, 1, LSC_LX_OFFSET_WRITE));
    send(fr, lsc_lx_encode_id(fr, sizeof fr, 2, LSC_LX_ID_WRITE, 12));
    send(fr, lsc_lx_encode_led_ctrl(fr, sizeof fr, 12, LSC_LX_LED_CTRL_WRITE, false));
    char text[LSC_LXBUS_STATE_MAX];
    int n = lsc_lxbus_save(&bus, text, sizeof text);
    assert_true(n > 0);
    assert_non_null(strstr(text, "servo id=1 offset=-7 limits=0,1000 vin-limits=4500,12000 "
                                 "temp-limit=85 led=on position=493\n"));
    assert_non_null(strstr(text, "servo id=12 offset=0 limits=0,1000 vin-limits=4500,12000 "
                                 "temp-limit=85 led=off position=500\n"));
    char small[40];
    assert_int_equal(lsc_lxbus_save(&bus, small, sizeof small), LSC_ENOSPC);
    assert_int_equal(strlen(small), sizeof small - 1u);
    assert_int_equal(lsc_lxbus_save(&bus, NULL, 1), LSC_EINVAL);
    static lsc_lxbus other;
    assert_int_equal(lsc_lxbus_init(&other), 0);
    lsc_sim_parse_error err;
    assert_int_equal(lsc_lxbus_load(&other, text, (size_t)n, &err), 2);
    assert_int_equal(other.servo[0].offset, -7);
    assert_int_equal(lsc_lxbus_position(&other, 0), 493);
    assert_int_equal(other.servo[1].id, 12);
    assert_false(other.servo[1].led_on);
    /* CRLF, comments, keys in any order, defaults */
    static const char crlf[] = "# x\r\n\r\n  servo  led=off id=4\r\nservo\n";
    assert_int_equal(lsc_lxbus_load(&other, crlf, sizeof crlf - 1u, &err), 2);
    assert_int_equal(other.servo[0].id, 4);
    assert_int_equal(other.servo[1].id, 1);
    assert_int_equal(lsc_lxbus_position(&other, 1), 500);
    static const struct {
        const char *text;
        uint32_t line, column;
    } bad[] = {
        {"servo id=254\n", 1, 10},
        {"servo id=1 id=2\n", 1, 12},
        {"\nservo offset=126\n", 2, 14},
        {"servo limits=5,5\n", 1, 14},
        {"servo limits=5\n", 1, 14},
        {"servo vin-limits=4000,9000\n", 1, 18},
        {"servo temp-limit=49\n", 1, 18},
        {"servo led=maybe\n", 1, 11},
        {"servo position=2001\n", 1, 16},
        {"servo position=-1001\n", 1, 16},
        {"servo speed=3\n", 1, 7},
        {"servo id\n", 1, 7},
        {"servos id=1\n", 1, 1},
        {"servo id=1\rx\n", 1, 11},
        {"servo id=-\n", 1, 10},
        {"servo id=1x\n", 1, 10},
        {"servo id=1234567\n", 1, 10},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        print_message("%s", bad[k].text);
        assert_int_equal(lsc_lxbus_load(&other, bad[k].text, strlen(bad[k].text), &err),
                         LSC_EINVAL);
        assert_int_equal(err.line, bad[k].line);
        assert_int_equal(err.column, bad[k].column);
        assert_int_equal(other.nservos, 2); /* unchanged */
    }
    char many[33 * 6 + 1];
    for (size_t k = 0; k < 33; k++) {
        memcpy(&many[k * 6], "servo\n", 6);
    }
    many[sizeof many - 1u] = '\0';
    assert_int_equal(lsc_lxbus_load(&other, many, strlen(many), &err), LSC_ENOSPC);
    assert_int_equal(lsc_lxbus_load(&other, NULL, 1, &err), LSC_EINVAL);
    assert_int_equal(lsc_lxbus_load(&other, "", 0, NULL), 0);
}

/* The lsc_io adapter: a request written, its reply read in virtual time. */
static void test_io(void **state)
{
    (void)state;
    setup_bus(1);
    lsc_lxbus_set_baud(&bus, 115200);
    lsc_io io;
    assert_int_equal(lsc_lxbus_io_init(&bus, &io), 0);
    assert_int_equal(lsc_lxbus_io_init(NULL, &io), LSC_EINVAL);
    uint8_t req[LSC_LX_FRAME_MAX], out[32];
    int n = lsc_lx_encode_request(req, sizeof req, 1, LSC_LX_POS_READ);
    assert_int_equal(io.write(io.ctx, req, (size_t)n), n);
    size_t got = 0;
    while (got < 8) {
        int r = io.read(io.ctx, &out[got], sizeof out - got, 100);
        assert_true(r > 0);
        got += (size_t)r;
    }
    assert_int_equal(out[5], 0xF4);
    assert_int_equal(io.read(io.ctx, out, sizeof out, 10), 0);
    assert_int_equal(io.now_ms(io.ctx), lsc_lxbus_now_us(&bus) / 1000u);
    assert_int_equal(io.read(io.ctx, NULL, 1, 0), LSC_EINVAL);
    assert_int_equal(io.write(io.ctx, NULL, 1), LSC_EINVAL);
}

static void test_add_and_null(void **state)
{
    (void)state;
    setup_bus(LSC_LXBUS_SERVOS);
    assert_int_equal(lsc_lxbus_add(&bus, 1), LSC_ENOSPC);
    assert_int_equal(lsc_lxbus_add(&bus, 254), LSC_EINVAL);
    assert_int_equal(lsc_lxbus_add(NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_lxbus_init(NULL), LSC_EINVAL);
    assert_int_equal(lsc_lxbus_find(NULL, 1), -1);
    assert_int_equal(lsc_lxbus_position(NULL, 0), 0);
    assert_false(lsc_lxbus_moving(&bus, LSC_LXBUS_SERVOS));
    lsc_lxbus_power_cycle(NULL);
    lsc_lxbus_advance_us(NULL, 1);
    assert_int_equal(lsc_lxbus_now_us(NULL), 0);
    assert_int_equal(lsc_lxbus_available(NULL), 0);
    assert_int_equal(lsc_lxbus_read(NULL, NULL, 0), 0);
    assert_int_equal(lsc_lxbus_next_event_us(NULL), LSC_LXBUS_TIME_NEVER);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fresh_servos_read_500),
        cmocka_unit_test(test_move_over_time),
        cmocka_unit_test(test_wait_then_start),
        cmocka_unit_test(test_broadcast_and_collisions),
        cmocka_unit_test(test_id_write),
        cmocka_unit_test(test_limits_clamp),
        cmocka_unit_test(test_offsets),
        cmocka_unit_test(test_motor_mode),
        cmocka_unit_test(test_faults),
        cmocka_unit_test(test_power_cycle_keeps),
        cmocka_unit_test(test_ignored_frames),
        cmocka_unit_test(test_echo),
        cmocka_unit_test(test_baud_and_faults),
        cmocka_unit_test(test_save_load),
        cmocka_unit_test(test_io),
        cmocka_unit_test(test_add_and_null),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
