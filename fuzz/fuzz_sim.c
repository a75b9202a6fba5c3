/* Fuzz harness for the virtual controller model (include/lsc/sim.h): any
 * bytes from the host, at any virtual times, with any fault settings.
 *
 * The model has two groups loaded (a fixed text). The input is a list of
 * operations: feed a chunk of bytes, advance the clock, read some output,
 * set the baud rate, run or stop a group from the board, inject a fault.
 * Checked on every input:
 *  - the output, read in pieces of any size, is whole frames back to back:
 *    a parser discards nothing, and once everything pending has been sent
 *    no partial frame remains (unless a corrupting fault was asked for);
 *  - every frame the controller sends is a controller message that its
 *    typed decoder accepts (battery reply, position reply, offset reply, 6, 7
 *    or 8);
 *  - read never returns more than asked or than lsc_sim_available said;
 *    next_event_us is 0 exactly when bytes are readable; the clock only
 *    moves forward; the counters never go down;
 *  - the lsc_io adapter's read returns within its timeout.
 */
#include <stdbool.h>
#include <string.h>

#include "fuzz.h"
#include "lsc/sim.h"

static const char group_text[] = "group 1\n"
                                 "step 20 1:2000 2:1000\n"
                                 "step 10\n"
                                 "group 7\n"
                                 "step 5 3:600\n";

typedef struct out_check {
    lsc_parser p;
    uint8_t buf[LSC_FRAME_MAX];
    bool corrupt; /* a corrupting fault was set: frames may be malformed */
} out_check;

static void check_frame(const lsc_frame *f)
{
    lsc_servo servos[LSC_READ_MAX];
    lsc_servo_offset offsets[LSC_OFFSET_MAX];
    uint16_t u16;
    uint8_t u8;
    int ok;
    switch (f->cmd) {
    case LSC_CMD_BATTERY: ok = lsc_decode_battery_reply(f, &u16); break;
    case LSC_CMD_POS_READ: ok = lsc_decode_pos_reply(f, servos, LSC_READ_MAX) > 0 ? 0 : -1; break;
    case LSC_CMD_OFFSET_READ:
        ok = lsc_decode_offset_reply(f, offsets, LSC_OFFSET_MAX) > 0 ? 0 : -1;
        break;
    case LSC_CMD_GROUP_RUN: ok = lsc_decode_group_run(f, &u8, &u16); break;
    case LSC_CMD_GROUP_STOP: ok = lsc_decode_group_stop(f); break;
    case LSC_CMD_GROUP_COMPLETE: ok = lsc_decode_group_complete(f, &u8, &u16); break;
    default: ok = -1; break;
    }
    FUZZ_CHECK(ok == 0);
}

/* Checks output bytes: whole frames, each a controller message. */
static void take_output(out_check *o, const uint8_t *bytes, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        lsc_frame f;
        int r = lsc_parser_feed(&o->p, bytes[i], &f);
        if (!o->corrupt) {
            FUZZ_CHECK(r >= 0);
            if (r == 1) {
                check_frame(&f);
            }
        }
    }
}

static void drain(lsc_sim *sim, out_check *o, size_t piece)
{
    uint8_t buf[LSC_SIM_OUT_BYTES + 1];
    size_t avail = lsc_sim_available(sim);
    size_t got = lsc_sim_read(sim, buf, piece);
    FUZZ_CHECK(got <= piece && got <= avail);
    FUZZ_CHECK(got == (avail < piece ? avail : piece));
    take_output(o, buf, got);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static lsc_sim sim; /* about 10 KiB */
    static lsc_sim_step steps[8];
    static lsc_servo targets[8];
    static out_check o;
    lsc_sim_groups g;
    FUZZ_CHECK(lsc_sim_groups_init(&g, steps, 8, targets, 8) == 0);
    FUZZ_CHECK(lsc_sim_groups_parse(&g, group_text, sizeof group_text - 1u, NULL) == 2);
    FUZZ_CHECK(lsc_sim_init(&sim) == 0);
    lsc_sim_set_groups(&sim, &g);
    memset(&o, 0, sizeof o);
    FUZZ_CHECK(lsc_parser_init(&o.p, o.buf, sizeof o.buf) == 0);

    fuzz_cursor c = {data, size, 0};
    lsc_sim_stats last = sim.stats;
    while (c.at < c.size) {
        uint8_t op = fuzz_next(&c);
        uint64_t before = lsc_sim_now_us(&sim);
        switch (op >> 5) {
        case 0:
        case 1:
        case 2: { /* feed the next 1..96 bytes */
            size_t n = (size_t)(op % 96u) + 1u;
            n = n < c.size - c.at ? n : c.size - c.at;
            FUZZ_CHECK(lsc_sim_feed(&sim, c.data + c.at, n) == (int)n);
            c.at += n;
            break;
        }
        case 3: /* advance 0..31 ms, or up to 31 * 256 us */
            if (op & 0x10u) {
                lsc_sim_advance_us(&sim, (uint64_t)(op & 0x0Fu) * 256u + fuzz_next(&c));
            } else {
                lsc_sim_advance_ms(&sim, (uint32_t)(op & 0x0Fu) * fuzz_next(&c));
            }
            break;
        case 4: /* read a piece of 0..255 bytes */
            drain(&sim, &o, fuzz_next(&c));
            break;
        case 5: { /* the lsc_io adapter's read */
            lsc_io io;
            uint8_t buf[64];
            FUZZ_CHECK(lsc_sim_io_init(&sim, &io) == 0);
            uint32_t timeout = fuzz_next(&c);
            uint32_t t0 = io.now_ms(io.ctx);
            int r = io.read(io.ctx, buf, (size_t)(op & 0x1Fu) + 1u, timeout);
            FUZZ_CHECK(r >= 0 && r <= (int)(op & 0x1Fu) + 1);
            FUZZ_CHECK(io.now_ms(io.ctx) - t0 <= timeout);
            take_output(&o, buf, (size_t)r);
            break;
        }
        case 6: /* the board's own start and stop, the baud rate */
            if (op & 0x10u) {
                lsc_sim_set_baud(&sim, (op & 1u) ? 9600u : 0u);
            } else if (op & 0x08u) {
                int running = lsc_sim_group_running(&sim);
                FUZZ_CHECK(lsc_sim_group_stop(&sim) == (running >= 0 ? 0 : LSC_EINVAL));
            } else {
                uint8_t group = fuzz_next(&c);
                int r = lsc_sim_group_run(&sim, group, fuzz_next(&c));
                FUZZ_CHECK(r == ((group == 1 || group == 7) ? 0 : LSC_EINVAL));
            }
            break;
        default: /* faults */
            switch (op & 3u) {
            case 0: lsc_sim_fault_drop(&sim, fuzz_next(&c) % 4u); break;
            case 1: lsc_sim_fault_delay(&sim, fuzz_next(&c)); break;
            case 2: {
                uint8_t n = fuzz_next(&c) % 4u, at = fuzz_next(&c);
                lsc_sim_fault_corrupt(&sim, n, at, fuzz_next(&c));
                o.corrupt = o.corrupt || n > 0;
                break;
            }
            default: lsc_sim_set_battery(&sim, (uint16_t)(fuzz_next(&c) * 40u)); break;
            }
            break;
        }
        FUZZ_CHECK(lsc_sim_now_us(&sim) >= before);
        FUZZ_CHECK((lsc_sim_next_event_us(&sim) == 0) == (lsc_sim_available(&sim) > 0));
        FUZZ_CHECK(sim.stats.frames_in >= last.frames_in && sim.stats.beeps >= last.beeps &&
                   sim.stats.frames_out >= last.frames_out &&
                   sim.stats.noise_bytes >= last.noise_bytes);
        last = sim.stats;
        for (unsigned id = 0; id < LSC_SIM_SERVOS; id += 37u) {
            (void)lsc_sim_position(&sim, (uint8_t)id);
        }
    }

    /* Stop whatever runs, let everything pending go out, read it all. */
    (void)lsc_sim_group_stop(&sim);
    for (int i = 0; i < 1000; i++) {
        uint64_t wait = lsc_sim_next_event_us(&sim);
        if (wait == LSC_SIM_TIME_NEVER) {
            break;
        }
        lsc_sim_advance_us(&sim, wait);
        drain(&sim, &o, LSC_SIM_OUT_BYTES + 1u);
    }
    FUZZ_CHECK(lsc_sim_next_event_us(&sim) == LSC_SIM_TIME_NEVER);
    FUZZ_CHECK(lsc_sim_available(&sim) == 0);
    if (!o.corrupt) {
        FUZZ_CHECK(o.p.len == 0 || o.p.complete); /* no partial frame was sent */
        FUZZ_CHECK(o.p.discarded == 0 && o.p.errors == 0);
    }
    return 0;
}
