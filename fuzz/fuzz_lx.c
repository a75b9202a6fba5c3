/* Fuzz harness for the bus-servo codec (include/lsc/lx.h). Each input is used
 * twice:
 *
 * 1. As bytes from the wire, fed to a parser; the first input byte, if odd,
 *    first makes the parser expect the frame in the next bytes as an echo.
 *    Checked: every byte fed is accounted for (discarded + in returned frames
 *    + in dropped echoes + pending); each returned frame has its checksum
 *    right, a shape of its command, and lsc_lx_encode_frame rebuilds exactly
 *    its bytes; every typed decoder that accepts it gives values whose
 *    encoder rebuilds exactly the frame (OR_MOTOR_MODE's unused byte written
 *    as 0), and writes nothing when it refuses; a frame is never returned
 *    from bytes whose checksum fails.
 * 2. As a description of one message (kind, id, buffer size, values).
 *    Checked: each encoder returns what an independent model of its ranges
 *    predicts (length, LSC_EINVAL or LSC_ENOSPC), writes nothing outside its
 *    frame or on error, and its frame parses back to one frame whose decoder
 *    returns the same values (decode(encode(x)) == x).
 */
#include <stdbool.h>
#include <string.h>

#include "fuzz.h"
#include "lsc/lx.h"

static uint8_t checksum(const uint8_t *b, size_t n)
{
    unsigned sum = 0;
    for (size_t i = 2; i + 1u < n; i++) {
        sum += b[i];
    }
    return (uint8_t)~sum;
}

/* ---- Part 1: any bytes through the parser and the decoders ----------------- */

/* Every decoder on f (whose wire bytes are wire[0..len)). */
static void check_decoders(const lsc_lx_frame *f, const uint8_t *wire, size_t len)
{
    uint8_t out[LSC_LX_FRAME_MAX + 8];
    uint16_t a = 0x5A5A, b = 0x5A5A;
    uint8_t u8 = 0x5A;
    int8_t s8 = 0x5A;
    int16_t s16 = 0x5A5A;
    bool on = false;
    int accepted = 0, n = -1;
    uint8_t id = f->id, cmd = f->cmd;

    memset(out, FUZZ_CANARY, sizeof out);
    if (lsc_lx_decode_move_time(f, &a, &b) == 0) {
        accepted++;
        n = lsc_lx_encode_move_time(out, len, id, cmd, a, b);
    } else {
        FUZZ_CHECK(a == 0x5A5A && b == 0x5A5A);
    }
    if (lsc_lx_decode_angle_limit(f, &a, &b) == 0) {
        accepted++;
        n = lsc_lx_encode_angle_limit(out, len, id, cmd, a, b);
    }
    if (lsc_lx_decode_vin_limit(f, &a, &b) == 0) {
        accepted++;
        n = lsc_lx_encode_vin_limit(out, len, id, cmd, a, b);
    }
    if (lsc_lx_decode_id(f, &u8) == 0) {
        accepted++;
        n = lsc_lx_encode_id(out, len, id, cmd, u8);
    }
    if (lsc_lx_decode_offset(f, &s8) == 0) {
        accepted++;
        n = lsc_lx_encode_offset(out, len, id, cmd, s8);
    }
    if (lsc_lx_decode_temp_limit(f, &u8) == 0) {
        accepted++;
        n = lsc_lx_encode_temp_limit(out, len, id, cmd, u8);
    }
    if (lsc_lx_decode_temp(f, &u8) == 0) {
        accepted++;
        n = lsc_lx_encode_temp(out, len, id, u8);
    }
    if (lsc_lx_decode_vin(f, &a) == 0) {
        accepted++;
        n = lsc_lx_encode_vin(out, len, id, a);
    }
    if (lsc_lx_decode_position(f, &s16) == 0) {
        accepted++;
        n = lsc_lx_encode_position(out, len, id, s16);
    }
    if (lsc_lx_decode_motor_mode(f, &u8, &s16) == 0) {
        accepted++;
        n = lsc_lx_encode_motor_mode(out, len, id, cmd, u8, s16);
        FUZZ_CHECK(out[6] == 0);
        out[6] = wire[6]; /* the unused byte, and so the checksum */
        out[9] = checksum(out, 10);
    }
    if (lsc_lx_decode_load(f, &on) == 0) {
        accepted++;
        n = lsc_lx_encode_load(out, len, id, cmd, on);
    }
    if (lsc_lx_decode_led_ctrl(f, &on) == 0) {
        accepted++;
        n = lsc_lx_encode_led_ctrl(out, len, id, cmd, on);
    }
    if (lsc_lx_decode_led_error(f, &u8) == 0) {
        accepted++;
        n = lsc_lx_encode_led_error(out, len, id, cmd, u8);
    }
    FUZZ_CHECK(accepted <= 1); /* each frame is one command's */
    if (accepted == 1) {
        FUZZ_CHECK(n == (int)len);
        FUZZ_CHECK(memcmp(out, wire, len) == 0);
        FUZZ_CHECK(fuzz_all_canary(&out[len], sizeof out - len));
    }
    if (f->nparams == 0) {
        FUZZ_CHECK(accepted == 0);
        /* a request without values: its encoder, unless it is a read to 254 */
        int r = lsc_lx_encode_request(out, len, id, cmd);
        FUZZ_CHECK(r == (int)len || (id == LSC_LX_BROADCAST && cmd != LSC_LX_ID_READ && r == LSC_EINVAL));
    }
}

static void fuzz_parser(const uint8_t *data, size_t size)
{
    lsc_lx_parser p;
    FUZZ_CHECK(lsc_lx_parser_init(&p) == 0);
    size_t start = 0;
    size_t frame_bytes = 0, echo_bytes = 0;
    if (size > 0 && (data[0] & 1u) != 0) {
        start = 1;
        size_t n = size > 1 ? (size_t)(data[1] % (LSC_LX_FRAME_MAX + 1u)) : 0;
        if (n <= size - 1) {
            int r = lsc_lx_parser_expect_echo(&p, &data[1], n);
            FUZZ_CHECK(r == 0 || r == LSC_EINVAL);
            if (r == 0) {
                FUZZ_CHECK(p.echo_len == n);
            }
        }
    }
    for (size_t i = start; i < size; i++) {
        lsc_lx_frame f;
        uint32_t echoes = p.echoes;
        uint8_t echo_len = p.echo_len;
        int r = lsc_lx_parser_feed(&p, data[i], &f);
        FUZZ_CHECK(r == 1 || r == 0 || r == LSC_ESYNC || r == LSC_EFRAME);
        FUZZ_CHECK(p.len <= LSC_LX_FRAME_MAX);
        if (p.echoes != echoes) {
            FUZZ_CHECK(r == 0 && p.echoes == echoes + 1u);
            echo_bytes += echo_len;
        }
        if (r != 1) {
            continue;
        }
        size_t len = f.nparams + 6u;
        frame_bytes += len;
        FUZZ_CHECK(p.len == len && p.complete);
        FUZZ_CHECK(f.params == &p.buf[5]);
        FUZZ_CHECK(p.buf[len - 1u] == checksum(p.buf, len));
        FUZZ_CHECK(f.id <= LSC_LX_BROADCAST);
        FUZZ_CHECK(len - 3u == lsc_lx_len(f.cmd, f.reply));
        uint8_t again[LSC_LX_FRAME_MAX];
        FUZZ_CHECK(lsc_lx_encode_frame(again, sizeof again, f.id, f.cmd, f.params, f.nparams) ==
                       (int)len ||
                   (f.id == LSC_LX_BROADCAST && f.reply));
        uint8_t wire[LSC_LX_FRAME_MAX];
        memcpy(wire, p.buf, len);
        check_decoders(&f, wire, len);
    }
    /* every byte accounted for */
    size_t pending = p.complete ? 0u : p.len;
    FUZZ_CHECK(p.discarded + frame_bytes + echo_bytes + pending == size - start);
    FUZZ_CHECK(p.bad_checksums <= p.errors);
}

/* ---- Part 2: one message, from its description ------------------------------- */

static void fuzz_encoders(const uint8_t *data, size_t size)
{
    fuzz_cursor c = {data, size, 0};
    uint8_t kind = (uint8_t)(fuzz_next(&c) % 14u);
    uint8_t id = fuzz_next(&c);
    uint8_t cmd = fuzz_next(&c) % 40u;
    size_t cap = fuzz_next(&c) % (LSC_LX_FRAME_MAX + 2u);
    uint8_t lo = fuzz_next(&c), hi = fuzz_next(&c);
    uint16_t a = (uint16_t)(lo | hi << 8);
    lo = fuzz_next(&c);
    hi = fuzz_next(&c);
    uint16_t b = (uint16_t)(lo | hi << 8);
    int16_t sa = (int16_t)a, sb = (int16_t)b;
    uint8_t buf[LSC_LX_FRAME_MAX + 8];
    memset(buf, FUZZ_CANARY, sizeof buf);
    int r;
    /* the model: which commands and values the document allows */
    bool ok;
    unsigned n; /* parameters */
    switch (kind) {
    case 0:
        r = lsc_lx_encode_move_time(buf, cap, id, cmd, a, b);
        ok = (cmd == 1 || cmd == 2 || cmd == 7 || cmd == 8) && a <= 1000 && b <= 30000;
        n = 4;
        break;
    case 1:
        r = lsc_lx_encode_id(buf, cap, id, cmd, (uint8_t)a);
        ok = (uint8_t)a <= 253 && (cmd == 13 || (cmd == 14 && (uint8_t)a == id));
        n = 1;
        break;
    case 2:
        r = lsc_lx_encode_offset(buf, cap, id, cmd, (int8_t)a);
        ok = (cmd == 17 || cmd == 19) && (int8_t)a >= -125 && (int8_t)a <= 125;
        n = 1;
        break;
    case 3:
        r = lsc_lx_encode_angle_limit(buf, cap, id, cmd, a, b);
        ok = (cmd == 20 || cmd == 21) && a < b && b <= 1000;
        n = 4;
        break;
    case 4:
        r = lsc_lx_encode_vin_limit(buf, cap, id, cmd, a, b);
        ok = (cmd == 22 || cmd == 23) && a >= 4500 && a < b && b <= 12000;
        n = 4;
        break;
    case 5:
        r = lsc_lx_encode_temp_limit(buf, cap, id, cmd, (uint8_t)a);
        ok = (cmd == 24 || cmd == 25) && (uint8_t)a >= 50 && (uint8_t)a <= 100;
        n = 1;
        break;
    case 6:
        cmd = LSC_LX_TEMP_READ;
        r = lsc_lx_encode_temp(buf, cap, id, (uint8_t)a);
        ok = true;
        n = 1;
        break;
    case 7:
        cmd = LSC_LX_VIN_READ;
        r = lsc_lx_encode_vin(buf, cap, id, a);
        ok = true;
        n = 2;
        break;
    case 8:
        cmd = LSC_LX_POS_READ;
        r = lsc_lx_encode_position(buf, cap, id, sa);
        ok = true;
        n = 2;
        break;
    case 9:
        r = lsc_lx_encode_motor_mode(buf, cap, id, cmd, (uint8_t)a, sb);
        ok = (cmd == 29 || cmd == 30) && (uint8_t)a <= 1 && sb >= -1000 && sb <= 1000;
        n = 4;
        break;
    case 10:
        r = lsc_lx_encode_load(buf, cap, id, cmd, (a & 1u) != 0);
        ok = cmd == 31 || cmd == 32;
        n = 1;
        break;
    case 11:
        r = lsc_lx_encode_led_ctrl(buf, cap, id, cmd, (a & 1u) != 0);
        ok = cmd == 33 || cmd == 34;
        n = 1;
        break;
    case 12:
        r = lsc_lx_encode_led_error(buf, cap, id, cmd, (uint8_t)a);
        ok = (cmd == 35 || cmd == 36) && (uint8_t)a <= 7;
        n = 1;
        break;
    default:
        r = lsc_lx_encode_request(buf, cap, id, cmd);
        ok = lsc_lx_len(cmd, false) == 3u;
        n = 0;
        /* a read to 254 is refused but for ID_READ */
        ok = ok && (id < 254 || (id == 254 && (lsc_lx_len(cmd, true) == 0u || cmd == 14)));
        break;
    }
    /* the value encoders: the write's request or the read's reply */
    bool reply = n > 0 && lsc_lx_len(cmd, true) != 0u;
    ok = ok && (reply ? id <= 253 : id <= 254);
    size_t total = n + 6u;
    if (!ok) {
        FUZZ_CHECK(r == LSC_EINVAL);
        FUZZ_CHECK(fuzz_all_canary(buf, sizeof buf));
        return;
    }
    if (cap < total) {
        FUZZ_CHECK(r == LSC_ENOSPC);
        FUZZ_CHECK(fuzz_all_canary(buf, sizeof buf));
        return;
    }
    FUZZ_CHECK(r == (int)total);
    FUZZ_CHECK(fuzz_all_canary(&buf[total], sizeof buf - total));
    FUZZ_CHECK(buf[total - 1u] == checksum(buf, total));
    /* it parses back, after noise without 0x55, to one frame with the values */
    lsc_lx_parser p;
    lsc_lx_frame f;
    FUZZ_CHECK(lsc_lx_parser_init(&p) == 0);
    for (size_t i = c.at; i < size && i < c.at + 8u; i++) {
        FUZZ_CHECK(lsc_lx_parser_feed(&p, data[i] == 0x55 ? 0 : data[i], &f) == LSC_ESYNC);
    }
    for (size_t i = 0; i < total; i++) {
        int got = lsc_lx_parser_feed(&p, buf[i], &f);
        FUZZ_CHECK(got == (i + 1u == total ? 1 : 0));
    }
    FUZZ_CHECK(f.id == id && f.cmd == cmd && f.nparams == n && f.reply == reply);
    uint16_t x = 0, y = 0;
    uint8_t u8 = 0;
    int8_t s8 = 0;
    int16_t s16 = 0;
    bool on = false;
    switch (kind) {
    case 0:
        FUZZ_CHECK(lsc_lx_decode_move_time(&f, &x, &y) == 0 && x == a && y == b);
        break;
    case 1:
        FUZZ_CHECK(lsc_lx_decode_id(&f, &u8) == 0 && u8 == (uint8_t)a);
        break;
    case 2:
        FUZZ_CHECK(lsc_lx_decode_offset(&f, &s8) == 0 && s8 == (int8_t)a);
        break;
    case 3:
        FUZZ_CHECK(lsc_lx_decode_angle_limit(&f, &x, &y) == 0 && x == a && y == b);
        break;
    case 4:
        FUZZ_CHECK(lsc_lx_decode_vin_limit(&f, &x, &y) == 0 && x == a && y == b);
        break;
    case 5:
        FUZZ_CHECK(lsc_lx_decode_temp_limit(&f, &u8) == 0 && u8 == (uint8_t)a);
        break;
    case 6:
        FUZZ_CHECK(lsc_lx_decode_temp(&f, &u8) == 0 && u8 == (uint8_t)a);
        break;
    case 7:
        FUZZ_CHECK(lsc_lx_decode_vin(&f, &x) == 0 && x == a);
        break;
    case 8:
        FUZZ_CHECK(lsc_lx_decode_position(&f, &s16) == 0 && s16 == sa);
        break;
    case 9:
        FUZZ_CHECK(lsc_lx_decode_motor_mode(&f, &u8, &s16) == 0 && u8 == (uint8_t)a && s16 == sb);
        break;
    case 10:
        FUZZ_CHECK(lsc_lx_decode_load(&f, &on) == 0 && on == ((a & 1u) != 0));
        break;
    case 11:
        FUZZ_CHECK(lsc_lx_decode_led_ctrl(&f, &on) == 0 && on == ((a & 1u) != 0));
        break;
    case 12:
        FUZZ_CHECK(lsc_lx_decode_led_error(&f, &u8) == 0 && u8 == (uint8_t)a);
        break;
    default:
        break;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_parser(data, size);
    fuzz_encoders(data, size);
    return 0;
}
