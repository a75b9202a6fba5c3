/* Fuzz harness for the virtual bus of serial bus servos (include/lsc/lxbus.h):
 * what a host sends it (any program on lsc-sim --lx's pty), and the text of
 * its --state file. Each input is used twice:
 *
 * 1. As the host's bytes, fed in chunks to a bus of three servos (ids 1, 2
 *    and 1 again) with the virtual clock moving between chunks, the sizes
 *    and steps taken from the input. Checked: feed takes every byte; the
 *    output never holds more than its queue; every servo's values stay in
 *    the document's ranges; its position reads within what the model allows;
 *    the text of what survives power-off loads back into a bus whose text is
 *    the same.
 * 2. As state text for lsc_lxbus_load. Checked: a refusal leaves the bus as
 *    it was and says where (a line and a column inside the text); what is
 *    accepted saves to a text that loads back to the same text.
 */
#include <string.h>

#include "fuzz.h"
#include "lsc/lxbus.h"

static lsc_lxbus bus, other;
static char text[LSC_LXBUS_STATE_MAX], again[LSC_LXBUS_STATE_MAX];

static void check_servos(const lsc_lxbus *b)
{
    for (size_t i = 0; i < b->nservos; i++) {
        const lsc_lxbus_servo *s = &b->servo[i];
        FUZZ_CHECK(s->id <= LSC_LX_ID_MAX);
        FUZZ_CHECK(s->offset >= -LSC_LX_OFFSET_MAX && s->offset <= LSC_LX_OFFSET_MAX);
        FUZZ_CHECK(s->offset_saved >= -LSC_LX_OFFSET_MAX && s->offset_saved <= LSC_LX_OFFSET_MAX);
        FUZZ_CHECK(s->limit_min < s->limit_max && s->limit_max <= LSC_LX_POSITION_MAX);
        FUZZ_CHECK(s->vin_min >= LSC_LX_VIN_MIN && s->vin_min < s->vin_max &&
                   s->vin_max <= LSC_LX_VIN_MAX);
        FUZZ_CHECK(s->temp_limit >= LSC_LX_TEMP_LIMIT_MIN &&
                   s->temp_limit <= LSC_LX_TEMP_LIMIT_MAX);
        FUZZ_CHECK(s->mode <= LSC_LX_MODE_MOTOR);
        FUZZ_CHECK(s->speed >= -LSC_LX_SPEED_MAX && s->speed <= LSC_LX_SPEED_MAX);
        FUZZ_CHECK(s->alarm_mask <= LSC_LX_ALARM_ALL);
        int16_t pos = lsc_lxbus_position(b, i);
        /* a loaded rest -1000..2000, an offset adjusted by up to 250 */
        FUZZ_CHECK(pos >= -1250 && pos <= 2250);
    }
}

/* Saves b, loads it into other, saves that: the same text. */
static void check_round_trip(const lsc_lxbus *b)
{
    int n = lsc_lxbus_save(b, text, sizeof text);
    FUZZ_CHECK(n > 0);
    lsc_sim_parse_error err;
    FUZZ_CHECK(lsc_lxbus_init(&other) == 0);
    lsc_lxbus_advance_us(&other, lsc_lxbus_now_us(b));
    FUZZ_CHECK(lsc_lxbus_load(&other, text, (size_t)n, &err) == (int)b->nservos);
    FUZZ_CHECK(lsc_lxbus_save(&other, again, sizeof again) == n);
    FUZZ_CHECK(memcmp(text, again, (size_t)n) == 0);
}

static void fuzz_feed(const uint8_t *data, size_t size)
{
    FUZZ_CHECK(lsc_lxbus_init(&bus) == 0);
    FUZZ_CHECK(lsc_lxbus_add(&bus, 1) == 0);
    FUZZ_CHECK(lsc_lxbus_add(&bus, 2) == 1);
    FUZZ_CHECK(lsc_lxbus_add(&bus, 1) == 2);
    lsc_lxbus_set_echo(&bus, size > 0 && (data[0] & 1u) != 0);
    lsc_lxbus_set_baud(&bus, size > 0 && (data[0] & 2u) != 0 ? 115200u : 0u);
    if (size > 0 && (data[0] & 4u) != 0) {
        (void)lsc_lxbus_set_temp(&bus, 0, 99);
        (void)lsc_lxbus_set_stall(&bus, 1, true);
    }
    size_t at = size > 0 ? 1 : 0;
    while (at < size) {
        size_t chunk = 1u + data[at] % 16u;
        uint64_t step = (uint64_t)(data[at] >> 4) * 7919u;
        at++;
        if (chunk > size - at) {
            chunk = size - at;
        }
        FUZZ_CHECK(lsc_lxbus_feed(&bus, &data[at], chunk) == (int)chunk);
        at += chunk;
        FUZZ_CHECK(lsc_lxbus_available(&bus) <= LSC_LXBUS_OUT_BYTES);
        lsc_lxbus_advance_us(&bus, step);
        if ((step & 1u) != 0) {
            uint8_t out[64];
            (void)lsc_lxbus_read(&bus, out, sizeof out);
        }
        if (step == (uint64_t)7919u * 15u) {
            lsc_lxbus_power_cycle(&bus);
        }
    }
    check_servos(&bus);
    check_round_trip(&bus);
}

static void fuzz_load(const uint8_t *data, size_t size)
{
    FUZZ_CHECK(lsc_lxbus_init(&bus) == 0);
    FUZZ_CHECK(lsc_lxbus_add(&bus, 7) == 0);
    lsc_sim_parse_error err;
    int r = lsc_lxbus_load(&bus, (const char *)data, size, &err);
    if (r < 0) {
        FUZZ_CHECK(r == LSC_EINVAL || r == LSC_ENOSPC);
        FUZZ_CHECK(bus.nservos == 1 && bus.servo[0].id == 7);
        FUZZ_CHECK(err.message != NULL && err.line >= 1 && err.column >= 1);
        return;
    }
    FUZZ_CHECK((size_t)r == bus.nservos && bus.nservos <= LSC_LXBUS_SERVOS);
    check_servos(&bus);
    check_round_trip(&bus);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_feed(data, size);
    fuzz_load(data, size);
    return 0;
}
