/* .rob, the xArm PC software's action file: a 16-byte header ("SOBARM",
 * uint16 keyframe count, 8 bytes that are zero in every known file), then 14
 * bytes per keyframe: uint16 time in ms, the positions of servos 1..6 as
 * uint16 (0..1000). All little-endian. Decoded from the public sample files of
 * the ms-iot/lewansoul_xarm repository (docs/action-files.md). */
/* Host only: compiles to nothing elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST
#include <string.h>

#include "../core/internal.h" /* lsc_get_u16, lsc_put_u16 */
#include "files_internal.h"

#define ROB_MAGIC "SOBARM"
#define ROB_HEADER 16u
#define ROB_RECORD 14u
#define ROB_SERVOS 6u
#define ROB_POSITION_MAX LSC_FILE_ROB_POSITION_MAX

static const uint8_t rob_ids[ROB_SERVOS] = {1, 2, 3, 4, 5, 6};

int lsc_files_rob_parse(const uint8_t *data, size_t len, lsc_action *a, lsc_file_error *err)
{
    if (len < ROB_HEADER) {
        return lsc_files_fail(err, 0, "truncated header: %zu of %u bytes", len, ROB_HEADER);
    }
    if (memcmp(data, ROB_MAGIC, sizeof ROB_MAGIC - 1u) != 0) {
        return lsc_files_fail(err, 0, "not a .rob file: it does not start with \"SOBARM\"");
    }
    size_t count = lsc_get_u16(data + 6);
    size_t records = (len - ROB_HEADER) / ROB_RECORD;
    if (records < count) {
        return lsc_files_fail(err, records + 1u,
                              "record %zu: truncated: the header says %zu keyframes, the "
                              "file holds %zu bytes (%zu expected)",
                              records + 1u, count, len, ROB_HEADER + ROB_RECORD * count);
    }
    if (len != ROB_HEADER + ROB_RECORD * count) {
        return lsc_files_fail(err, count + 1u,
                              "%zu bytes after the last of the %zu keyframes the header says",
                              len - ROB_HEADER - ROB_RECORD * count, count);
    }
    (void)lsc_action_init(a, rob_ids, ROB_SERVOS);
    for (size_t k = 0; k < count; k++) {
        const uint8_t *rec = data + ROB_HEADER + ROB_RECORD * k;
        uint16_t pos[ROB_SERVOS];
        for (size_t i = 0; i < ROB_SERVOS; i++) {
            pos[i] = lsc_get_u16(rec + 2 + 2 * i);
            if (pos[i] > ROB_POSITION_MAX) {
                return lsc_files_fail(err, k + 1u,
                                      "record %zu: servo %zu: position %u is out of range "
                                      "0..1000",
                                      k + 1u, i + 1u, pos[i]);
            }
        }
        /* at most 65535 records: never more than LSC_ACTION_KEYFRAMES_MAX */
        if (lsc_action_append(a, lsc_get_u16(rec), pos) != 0) {
            return lsc_files_oom(err);
        }
    }
    return 0;
}

static void put16(lsc_outbuf *b, uint16_t v)
{
    uint8_t le[2];
    lsc_put_u16(le, v);
    lsc_outbuf_put(b, le, 2);
}

int lsc_files_rob_format(const lsc_action *a, lsc_outbuf *b, lsc_file_error *err)
{
    int at[ROB_SERVOS]; /* column of servo i + 1 in a */
    for (size_t i = 0; i < ROB_SERVOS; i++) {
        at[i] = -1;
    }
    for (size_t i = 0; i < a->nservos; i++) {
        if (a->ids[i] < 1 || a->ids[i] > ROB_SERVOS) {
            return lsc_files_fail(err, 0, "servo %u: a .rob file holds servos 1..6 only",
                                  a->ids[i]);
        }
        at[a->ids[i] - 1] = (int)i;
    }
    for (size_t i = 0; i < ROB_SERVOS; i++) {
        if (at[i] < 0) {
            return lsc_files_fail(err, 0, "servo %zu missing: a .rob file holds servos 1..6, "
                                          "every one in every keyframe",
                                  i + 1u);
        }
    }
    lsc_outbuf_put(b, ROB_MAGIC, sizeof ROB_MAGIC - 1u);
    put16(b, (uint16_t)a->count);
    static const uint8_t zeros[8] = {0};
    lsc_outbuf_put(b, zeros, sizeof zeros);
    for (uint32_t k = 0; k < a->count; k++) {
        const uint16_t *w = lsc_action_row(a, k);
        put16(b, w[0]);
        for (size_t i = 0; i < ROB_SERVOS; i++) {
            uint16_t pos = w[1 + at[i]];
            if (pos > ROB_POSITION_MAX) {
                return lsc_files_fail(err, k + 1u,
                                      "keyframe %u: servo %zu: position %u is out of range "
                                      "0..1000 for a .rob file",
                                      (unsigned)(k + 1u), i + 1u, pos);
            }
            put16(b, pos);
        }
    }
    return 0;
}
#endif
