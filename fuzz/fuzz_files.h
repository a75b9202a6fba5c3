/* Shared by the action file harnesses (fuzz_files_*.c): one reader of
 * include/lsc/files.h on any bytes. Checked on every input:
 *  - the reader returns 0, LSC_EINVAL or LSC_ENOSPC; on error it says why
 *    (a message) and leaves the action empty;
 *  - on success: 1..32 distinct servos; written back in the same format and
 *    read again, the same keyframes (the writer takes what the reader gave);
 *  - the keyframes play: lsc_player_init accepts them, and on a fake clock the
 *    player ends, sends at most one frame per keyframe, due times never go
 *    back, and every frame moves 1..nservos servos of the file.
 */
#ifndef LSC_FUZZ_FILES_H
#define LSC_FUZZ_FILES_H

#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "lsc/files.h"
#include "lsc/player.h"

static void fuzz_play(const lsc_action *a)
{
    lsc_track t;
    lsc_player p;
    lsc_player_config c = {100, 1, 1000, 9600};
    lsc_action_track(a, &t);
    FUZZ_CHECK(lsc_player_init(&p, &t, &c) == 0);
    uint32_t now = 0, frames = 0, last_due = 0;
    for (;;) {
        lsc_player_step s;
        int r = lsc_player_next(&p, now, &s);
        if (r == LSC_PLAYER_DONE) {
            break;
        }
        if (r == LSC_PLAYER_WAIT) {
            FUZZ_CHECK(s.wait_ms > 0);
            now += s.wait_ms;
            continue;
        }
        FUZZ_CHECK(r == LSC_PLAYER_SEND);
        FUZZ_CHECK(++frames <= a->count);
        FUZZ_CHECK(s.due_ms >= last_due && s.due_ms <= now);
        FUZZ_CHECK(s.nservos >= 1 && s.nservos <= a->nservos);
        FUZZ_CHECK(memchr(a->ids, s.servos[0].id, a->nservos) != NULL);
        last_due = s.due_ms;
    }
    FUZZ_CHECK(now == lsc_player_total_ms(&p) || frames == 0 || now >= lsc_player_total_ms(&p));
}

static int fuzz_files(lsc_file_format f, const uint8_t *data, size_t size)
{
    lsc_action a, b;
    lsc_file_error err = {.size = sizeof err};
    int r = lsc_action_parse(f, data, size, &a, &err);
    if (r != 0) {
        FUZZ_CHECK(r == LSC_EINVAL || r == LSC_ENOSPC);
        FUZZ_CHECK(err.message[0] != '\0');
        FUZZ_CHECK(a.count == 0 && a.words == NULL);
        return 0;
    }
    FUZZ_CHECK(a.nservos >= 1 && a.nservos <= LSC_PLAYER_SERVOS_MAX);
    for (size_t i = 0; i < a.nservos; i++) {
        FUZZ_CHECK(memchr(a.ids, a.ids[i], i) == NULL);
    }
    uint8_t *out = NULL;
    size_t len = 0;
    FUZZ_CHECK(lsc_action_format(f, &a, "fuzz", &out, &len, &err) == 0);
    FUZZ_CHECK(lsc_action_parse(f, out, len, &b, &err) == 0);
    FUZZ_CHECK(b.nservos == a.nservos && memcmp(a.ids, b.ids, a.nservos) == 0);
    FUZZ_CHECK(b.count == a.count);
    FUZZ_CHECK(a.count == 0 ||
               memcmp(a.words, b.words, (size_t)a.count * (1u + a.nservos) * 2u) == 0);
    free(out);
    lsc_action_free(&b);
    if (a.count > 0) {
        fuzz_play(&a);
    }
    lsc_action_free(&a);
    return 0;
}

#endif
