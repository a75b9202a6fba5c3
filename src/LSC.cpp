/* The Arduino wrapper (LSC.h): an lsc_io over a Stream, and the client.
 * Compiles to nothing outside Arduino (PlatformIO builds it for every framework). */
#ifdef ARDUINO

#include "LSC.h"
#include "LSCReadSplit.h"

extern "C" {
#include "core/internal.h" /* lsc_ids_distinct */
}

LSC::LSC(Stream &port) : port_(port), client_(), timeout_(100), notify_(NULL), running_(false)
{
    begin();
}

void LSC::begin()
{
    lsc_io io;
    io.ctx = this;
    io.write = ioWrite;
    io.read = ioRead;
    io.now_ms = ioNow;
    lsc_client_init(&client_, &io);
    lsc_client_set_notify(&client_, dispatch, this);
    running_ = false;
}

int LSC::ioWrite(void *ctx, const uint8_t *data, size_t n)
{
    Stream &port = static_cast<LSC *>(ctx)->port_;
    return port.write(data, n) == n ? (int)n : LSC_EIO;
}

int LSC::ioRead(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    Stream &port = static_cast<LSC *>(ctx)->port_;
    uint32_t start = millis();
    while (port.available() <= 0) {
        if (millis() - start >= timeout_ms)
            return 0;
        yield();
    }
    size_t n = 0;
    while (n < cap && port.available() > 0) {
        int byte = port.read();
        if (byte < 0)
            break;
        buf[n++] = (uint8_t)byte;
    }
    return (int)n;
}

uint32_t LSC::ioNow(void *)
{
    return millis();
}

void LSC::dispatch(void *user, const lsc_notification *n)
{
    LSC *self = static_cast<LSC *>(user);
    self->running_ = n->cmd == LSC_CMD_GROUP_RUN;
    if (self->notify_)
        self->notify_(*n);
}

int LSC::moveServo(uint8_t id, uint16_t position, uint16_t timeMs)
{
    return lsc_client_move_one(&client_, id, position, timeMs);
}

int LSC::moveServos(const LSCServo *servos, uint8_t count, uint16_t timeMs)
{
    return lsc_client_move(&client_, timeMs, servos, count);
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
    return lsc_client_unload(&client_, ids, count);
}

int LSC::runActionGroup(uint8_t group, uint16_t times)
{
    return lsc_client_run_group(&client_, group, times);
}

int LSC::stopActionGroup()
{
    return lsc_client_stop_group(&client_);
}

int LSC::setActionGroupSpeed(uint8_t group, uint16_t percent)
{
    return lsc_client_set_group_speed(&client_, group, percent);
}

int LSC::getBatteryVoltage(uint16_t &mv)
{
    return lsc_client_get_battery(&client_, &mv, timeout_);
}

int LSC::readPositions(const uint8_t *ids, uint8_t count, LSCServo *out)
{
    /* The whole list is checked before the first request goes out: an id
     * repeated in a later request must not fail after earlier ones were sent. */
    if (ids == NULL || out == NULL || count == 0 || !lsc_ids_distinct(ids, 1, count))
        return LSC_EINVAL;
    /* as many servos per request as a reply the client's buffer holds (with
     * a buffer too small for any, lsc_read_chunk gives 0: the client refuses) */
    const uint8_t per = lsc_read_per(LSC_CLIENT_RX_MAX);
    for (uint8_t done = 0; done < count;) {
        uint8_t n = lsc_read_chunk((uint8_t)(count - done), per);
        int rc = lsc_client_read_positions(&client_, ids + done, n, out + done, timeout_);
        if (rc < 0)
            return rc;
        done = (uint8_t)(done + n);
    }
    return count;
}

bool LSC::isRunning()
{
    lsc_client_poll(&client_, 0);
    return running_;
}

int LSC::waitForCompletion(uint32_t timeoutMs)
{
    lsc_notification n;
    int rc = lsc_client_wait_group(&client_, timeoutMs, &n);
    return rc < 0 ? rc : n.cmd;
}

int LSC::poll()
{
    return lsc_client_poll(&client_, 0);
}

#endif /* ARDUINO */
