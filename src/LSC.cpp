/* The Arduino wrapper (LSC.h) on the portable core: frames from the core's
 * encoders go to the Stream; replies and notifications come back through the
 * core's parser. Each method is its own function, so that a sketch links only
 * the ones it calls (and the core functions they use): a sketch that only
 * sends never links the parser.
 * Compiles to nothing outside Arduino (PlatformIO builds it for every framework). */
#ifdef ARDUINO

#include "LSC.h"
#include "LSCReadSplit.h"

extern "C" {
#include "core/internal.h" /* lsc_ids_distinct, lsc_get_u16 */
}

/* Bytes read between looks at the clock. */
#define LSC_ARDUINO_CHUNK 16u

/* What a call that reads waits for, and what it found. */
struct LSC::Wait {
    /* want: the command of the awaited reply (LSC_CMD_BATTERY, LSC_CMD_POS_READ),
     * or else a notification's, which onFrame never takes for a reply:
     * NOTHING when no reply is awaited, GROUP_END (waitForCompletion), DONE
     * once the awaited frame came (result holds the answer) */
    enum Want {
        NOTHING = LSC_CMD_GROUP_RUN,
        DONE = LSC_CMD_GROUP_STOP,
        GROUP_END = LSC_CMD_GROUP_COMPLETE
    };
    uint8_t want;
    uint8_t size;   /* the awaited reply's parameter bytes */
    int8_t fail;    /* LSC_EREPLY once a wrong-shape or malformed frame came, else LSC_ETIMEOUT */
    int8_t result;
    int notes;      /* notifications handed out */
    const uint8_t *ids; /* LSC_CMD_POS_READ: the n ids asked for */
    uint8_t n;
    void *out;      /* the reply's values: a uint16_t (battery) or n LSCServo */

    Wait(uint8_t want_, uint8_t size_, const uint8_t *ids_, uint8_t n_, void *out_)
        : want(want_), size(size_), fail(LSC_ETIMEOUT), result(0), notes(0), ids(ids_), n(n_),
          out(out_)
    {
    }
};

int LSC::send(const uint8_t *frame, int len)
{
    if (len < 0)
        return len; /* the encoder refused: nothing was sent */
    return port_.write(frame, (size_t)len) == (size_t)len ? 0 : LSC_EIO;
}

/* A notification (6, 7, 8) keeps running_ up to date (track, from the
 * start); once a call that hands them out ran (onNotification, poll,
 * isRunning, waitForCompletion set notes_ to deliver), it also goes to the
 * sketch (the function given to onNotification) and counts for poll();
 * waitForCompletion's wait ends at a stop or a completion. deliver is linked
 * only into a sketch that calls one of those. Either way a notification is
 * never taken for a reply. */
void LSC::track(LSC &lsc, Wait &, uint8_t cmd, const uint8_t *)
{
    lsc.running_ = cmd == LSC_CMD_GROUP_RUN;
}

void LSC::deliver(LSC &lsc, Wait &w, uint8_t cmd, const uint8_t *params)
{
    track(lsc, w, cmd, params);
    LSCNotification n = {cmd, 0, 0};
    if (cmd != LSC_CMD_GROUP_STOP) {
        n.group = params[0];
        n.times = lsc_get_u16(&params[1]);
    }
    w.notes++;
    if (lsc.notify_)
        lsc.notify_(n);
    if (w.want == Wait::GROUP_END && cmd != LSC_CMD_GROUP_RUN) {
        w.want = Wait::DONE;
        w.result = (int8_t)cmd;
    }
}

/* Any frame other than a notification may be the awaited reply, or one of
 * the wrong shape. The fields are read as they are: the parser passes a
 * known command only at its exact length (lsc/core.h), 3 parameter bytes
 * for 6 and 8, none for 7, 0 or 2 for the battery, N + 1 or 3*N + 1 for a
 * position read of N servos, so the decoders' checks would find nothing
 * more. */
void LSC::onFrame(Wait &w, const lsc_frame &f)
{
    const uint8_t cmd = f.cmd;
    if (cmd == LSC_CMD_GROUP_RUN || cmd == LSC_CMD_GROUP_STOP || cmd == LSC_CMD_GROUP_COMPLETE) {
        notes_(*this, w, cmd, f.params);
        return;
    }
    if (cmd != w.want) /* (DONE: never, a notification's command) */
        return;
    /* the reply's shape (not the request's: the battery's 2 bytes, a position
     * reply's 3*n + 1), and for positions exactly the ids asked, in that order */
    const uint8_t *at = f.params, *const end = at + f.nparams;
    bool ok = f.nparams == w.size;
    if (ok && cmd == LSC_CMD_POS_READ) { /* (a request's shape: no walk by 3) */
        ok = *at == w.n;
        at++;
        const uint8_t *id = w.ids;
        for (const uint8_t *item = at; item != end; item += 3)
            if (*item != *id++)
                ok = false;
    }
    if (ok) {
        /* the values as they are on the wire: little-endian, a position reply's
         * items (id, position) laid out as LSCServo is on AVR */
#if defined(__AVR__)
        uint8_t *o = (uint8_t *)w.out;
        while (at != end)
            *o++ = *at++;
#else
        if (cmd == LSC_CMD_BATTERY) {
            *(uint16_t *)w.out = lsc_get_u16(at);
        } else {
            for (LSCServo *o = (LSCServo *)w.out; at != end; at += 3, o++) {
                o->id = at[0];
                o->position = lsc_get_u16(&at[1]);
            }
        }
#endif
    }
    if (ok)
        w.want = Wait::DONE;
    else
        w.fail = LSC_EREPLY;
}

/* The clock receive reads: millis() in 16 bits, enough for a wait of up to
 * LSC_TIMEOUT_MAX (30 s, well short of the 65.5 s at which it wraps: only a
 * sketch's yield() or notification function that blocks for over 35 s
 * could make a wait miss its end, and then wait up to 65.5 s more), and in
 * one place (inlined at each of receive's two looks at the clock, it is
 * larger than a call). */
static __attribute__((noinline)) uint16_t now_ms()
{
    return (uint16_t)millis();
}

/* Whether p holds part of a frame. */
static inline bool partial(const lsc_parser &p)
{
    return !p.complete && p.len > 0;
}

/* Reads and parses what arrives for up to timeoutMs (0: what is there), until
 * w is done; either way, a frame whose first bytes were read is waited for
 * until it completes or the line is silent for LSC_CLIENT_GAP_MS (then it is
 * dropped), so that no frame is cut in two between calls. When the time is
 * up, what the Stream holds is still read, as the C client drains: until a
 * read finds less than a chunk, for at most LSC_CLIENT_DRAIN_READS chunks
 * (2 KiB: input that never stops cannot hold the call, even one that keeps
 * a frame partial, which is then cut; unlike the C client's, this bound
 * needs no clock, so it is the only one). Stopping after one chunk would
 * leave a late reply behind it for the next request to take for its own. */
int LSC::receive(Wait &w, uint16_t timeoutMs) /* at most LSC_TIMEOUT_MAX */
{
    uint8_t buf[LSC_CLIENT_RX_MAX];
    lsc_parser p;
    lsc_parser_init(&p, buf, sizeof buf);
    const uint16_t start = now_ms();
    uint16_t last = start; /* the last byte's time */
    uint8_t drains = 0;
    for (;;) {
        /* a chunk at a time, fed byte by byte (at -Os, as the Arduino IDE
         * builds, lsc_parser_feed_buf is that same loop) */
        uint8_t got = 0;
        int b;
        while (got < LSC_ARDUINO_CHUNK && (b = port_.read()) >= 0) {
            got++;
            lsc_frame f;
            int r = lsc_parser_feed(&p, (uint8_t)b, &f);
            if (r == 1)
                onFrame(w, f);
            else if (r <= LSC_EFRAME) /* LSC_EFRAME, LSC_ETOOBIG */
                w.fail = LSC_EREPLY;
        }
        const uint16_t now = now_ms();
        if (got > 0)
            last = now;
        /* got == LSC_ARDUINO_CHUNK: the Stream may hold more; once the time
         * is up, at most LSC_CLIENT_DRAIN_READS such chunks are read,
         * whatever the parser holds (input that never stops may keep a
         * frame partial) */
        if ((uint16_t)(now - start) >= timeoutMs &&
            (got < LSC_ARDUINO_CHUNK ? !partial(p) : ++drains >= LSC_CLIENT_DRAIN_READS))
            break;
        if (partial(p)) {
            if ((uint16_t)(now - last) < LSC_CLIENT_GAP_MS) {
                yield();
                continue;
            }
            lsc_parser_reset(&p);
        }
        if (w.want == Wait::DONE)
            break;
        yield();
    }
    return w.want == Wait::DONE ? w.result : w.fail;
}

/* Asks: sends request cmd, with n > 0 its parameters being the count n and
 * the n ids, and waits for the reply of size parameter bytes whose values
 * go to out (onFrame). What arrived before the request is read first (a late
 * reply to an earlier one must not be taken for this one's; notifications in
 * it are handed out). */
int LSC::ask(uint8_t cmd, const uint8_t *ids, uint8_t n, void *out, uint8_t size)
{
    uint8_t frame[LSC_FRAME_MIN + 1 + LSC_READ_PER(LSC_CLIENT_RX_MAX)];
    uint8_t *params = &frame[LSC_FRAME_MIN];
    uint8_t k = 0;
    if (n > 0) {
        params[0] = n;
        do {
            params[k + 1] = ids[k];
        } while (++k != n);
        k++;
    }
    /* cannot fail: the frame has room for LSC_READ_PER ids, and
     * readPositions never asks for the 82 that would make LEN 0x55 */
    (void)lsc_encode_frame(frame, sizeof frame, cmd, params, k);
    /* w itself, waiting for nothing yet (its notes count what it hands out);
     * one call of receive for both reads, so that it can be inlined here */
    Wait w(Wait::NOTHING, size, ids, n, out);
    uint16_t timeoutMs = 0;
    for (;;) {
        const int rc = receive(w, timeoutMs);
        if (w.want != Wait::NOTHING) /* the reply's wait: done or not */
            return rc;
        w.want = cmd;
        w.fail = LSC_ETIMEOUT;
        const int sent = send(frame, frame[2] + 2);
        if (sent < 0)
            return sent;
        timeoutMs = timeout_;
    }
}

int LSC::moveServo(uint8_t id, uint16_t position, uint16_t timeMs)
{
    const LSCServo s = {id, position};
    return moveServos(&s, 1, timeMs);
}

int LSC::moveServos(const LSCServo *servos, uint8_t count, uint16_t timeMs)
{
    uint8_t frame[LSC_FRAME_MAX];
    return send(frame, lsc_encode_servo_move(frame, sizeof frame, timeMs, servos, count));
}

/* ---- joints in centidegrees (lsc/units.h) ---- */
int LSC::moveJoint(const LSCJoint &joint, int32_t centidegrees, uint16_t timeMs)
{
    uint16_t position;
    if (!lsc_joint_allows(&joint, centidegrees) ||
        lsc_joint_to_pos(&joint, centidegrees, &position) != LSC_OK)
        return LSC_EINVAL;
    return moveServo(joint.id, position, timeMs);
}

int LSC::readJoint(const LSCJoint &joint, int32_t &centidegrees)
{
    LSCServo s;
    int rc = readPositions(&joint.id, 1, &s);
    if (rc < 0)
        return rc;
    /* a position outside the joint's range (wrong profile?) is a bad reply */
    return lsc_joint_to_cdeg(&joint, s.position, &centidegrees) == LSC_OK ? 0 : LSC_EREPLY;
}
/* ---- end of joints ---- */

int LSC::unloadServos(const uint8_t *ids, uint8_t count)
{
    uint8_t frame[LSC_FRAME_MAX];
    return send(frame, lsc_encode_unload(frame, sizeof frame, ids, count));
}

int LSC::runActionGroup(uint8_t group, uint16_t times)
{
    uint8_t frame[LSC_FRAME_MIN + 3];
    return send(frame, lsc_encode_group_run(frame, sizeof frame, group, times));
}

int LSC::stopActionGroup()
{
    uint8_t frame[LSC_FRAME_MIN];
    return send(frame, lsc_encode_group_stop(frame, sizeof frame));
}

int LSC::setActionGroupSpeed(uint8_t group, uint16_t percent)
{
    uint8_t frame[LSC_FRAME_MIN + 3];
    return send(frame, lsc_encode_group_speed(frame, sizeof frame, group, percent));
}

int LSC::getBatteryVoltage(uint16_t &mv)
{
    return ask(LSC_CMD_BATTERY, NULL, 0, &mv, 2);
}

int LSC::readPositions(const uint8_t *ids, uint8_t count, LSCServo *out)
{
    /* The whole list is checked before the first request goes out: an id
     * repeated in a later request must not fail after earlier ones were sent. */
    if (ids == NULL || out == NULL || count == 0)
        return LSC_EINVAL;
    /* each id against those before it (the core's lsc_ids_distinct, for
     * any stride and length, is larger on AVR) */
    for (uint8_t i = 1; i < count; i++)
        for (uint8_t j = 0; j < i; j++)
            if (ids[i] == ids[j])
                return LSC_EINVAL;
    /* as many servos per request as a reply the receive buffer holds; the
     * list was checked above, so ask sends it as it is (lsc_encode_frame;
     * lsc_encode_pos_request would pull in the core's generic list encoder,
     * which moveServos has inlined for its own list) */
    const uint8_t per = lsc_read_per(LSC_CLIENT_RX_MAX);
    for (uint8_t done = 0; done < count;) {
        const uint8_t n = lsc_read_chunk((uint8_t)(count - done), per);
        int rc = ask(LSC_CMD_POS_READ, ids + done, n, out + done, (uint8_t)(3u * n + 1u));
        if (rc < 0)
            return rc;
        done = (uint8_t)(done + n);
    }
    return count;
}

int LSC::poll()
{
    notes_ = deliver;
    Wait w(Wait::NOTHING, 0, NULL, 0, NULL);
    receive(w, 0);
    return w.notes;
}

bool LSC::isRunning()
{
    poll();
    return running_;
}

int LSC::waitForCompletion(uint32_t timeoutMs)
{
    notes_ = deliver;
    Wait w(Wait::GROUP_END, 0, NULL, 0, NULL);
    /* in waits of at most LSC_TIMEOUT_MAX (receive's clock is 16 bits) */
    do {
        const uint16_t part = capped(timeoutMs);
        timeoutMs -= part;
        receive(w, part);
    } while (w.want != Wait::DONE && timeoutMs > 0);
    /* malformed input answers nothing here */
    return w.want == Wait::DONE ? (int)w.result : (int)LSC_ETIMEOUT;
}

#endif /* ARDUINO */
