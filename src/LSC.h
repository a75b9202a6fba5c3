/*
 * LSC: an Arduino library for LSC servo controllers (Hiwonder/LewanSoul
 * LSC-6, LSC-16, LSC-32 and xArm), over any Stream: HardwareSerial,
 * SoftwareSerial, ...
 *
 *   #include <LSC.h>
 *   LSC lsc(Serial);
 *   void setup() {
 *     Serial.begin(9600);            // the controller's baud rate
 *     lsc.begin();
 *     lsc.moveServo(1, 1500, 1000);  // servo 1 to 1500 over 1000 ms
 *   }
 *
 * A thin C++ layer over the portable core (lsc/core.h): the core's encoders
 * build every frame, its parser checks every reply (a known command only at
 * its exact length), and a sketch links only what it calls: one that only
 * sends never links the parser. The object holds 9 bytes on AVR; the receive buffer is
 * on the stack of the calls that read, and the Stream's own buffer holds
 * what arrives between calls. No dynamic memory, no virtual functions of its
 * own. It behaves as the C client (lsc/client.h) does: notifications are
 * never taken for replies, input that arrived before a request is read first,
 * a partial frame is dropped after LSC_CLIENT_GAP_MS of silence (and one whose
 * first bytes a call read is waited for that long, so that none is cut in
 * two). Every call returns 0 (or a count)
 * on success, or a negative LSC_E... code (LSC::errorText(code) says what it
 * means): LSC_EINVAL for arguments the protocol cannot carry (nothing is
 * sent), LSC_ETIMEOUT when no reply came in time, LSC_EREPLY for a wrong
 * reply, LSC_EIO when the Stream took fewer bytes than it was given.
 *
 * Notifications: the controller reports on its own when an action group
 * starts, is stopped, or completes. They are read whenever the library reads
 * (replies, poll(), isRunning(), waitForCompletion()) and passed to the
 * function given to onNotification(). Call poll() from loop() if you want
 * them as they happen.
 */
#ifndef LSC_ARDUINO_H
#define LSC_ARDUINO_H

#include <Arduino.h>

#include "lsc/client.h"
#include "lsc/units.h"

/* A servo and its position, for moveServos() and readPositions(). */
typedef lsc_servo LSCServo;
/* A controller notification: cmd is LSC_CMD_GROUP_RUN (a group started),
 * LSC_CMD_GROUP_STOP (stopped) or LSC_CMD_GROUP_COMPLETE (ran to its end). */
typedef lsc_notification LSCNotification;
/* A joint: a servo seen through the arm, in centidegrees (lsc/units.h:
 * lsc_joint_init(&j, id, LSC_JOINT_BUS), then direction, zero, limits). */
typedef lsc_joint LSCJoint;

/* The longest wait setTimeout takes, in ms. */
#define LSC_TIMEOUT_MAX 30000u

class LSC {
public:
    typedef void (*NotifyFn)(const LSCNotification &n);

    /* Talks through port, which the sketch opens (begin(9600)) itself.
     * constexpr: a global LSC is set up at compile time, by no code. */
    constexpr explicit LSC(Stream &port)
        : port_(port), timeout_(100), notify_(NULL), notes_(track), running_(false)
    {
    }

    /* Forgets the running state; the constructor has already done it, call
     * it again after reopening the port. Sends nothing. */
    void begin() { running_ = false; }
    /* How long calls that wait for a reply wait, in ms (default 100; at
     * most LSC_TIMEOUT_MAX, 30 s: a longer one waits that long. A controller
     * answers within milliseconds, and a 16-bit clock makes the calls
     * smaller on AVR). */
    void setTimeout(uint32_t ms) { timeout_ = capped(ms); }

    /* Moves servo id (0..31 on LSC boards) to position (500..2500 on PWM
     * boards, 0..1000 on the xArm) over timeMs. */
    int moveServo(uint8_t id, uint16_t position, uint16_t timeMs);
    /* Moves count servos (distinct ids) together over timeMs. */
    int moveServos(const LSCServo *servos, uint8_t count, uint16_t timeMs);
    /* Powers count servos off: they turn freely until their next move. */
    int unloadServos(const uint8_t *ids, uint8_t count);

    /* Runs action group `group` `times` times (0: forever). */
    int runActionGroup(uint8_t group, uint16_t times = 1);
    /* Stops the running action group. */
    int stopActionGroup();
    /* Sets a group's speed in percent of its original (LSC_GROUP_ALL: all). */
    int setActionGroupSpeed(uint8_t group, uint16_t percent);

    /* Reads the battery voltage into mv (millivolts). */
    int getBatteryVoltage(uint16_t &mv);
    /* Reads the positions of count servos: out[i] gets ids[i] and its
     * position. Returns count on success (on failure out[] may hold some of
     * them, each with its own id, never another servo's). Asks in as many
     * requests as the receive buffer (LSC_CLIENT_RX_MAX bytes) needs (on AVR:
     * 9 servos per request; elsewhere 84, LSCReadSplit.h). The whole list is
     * checked first: count 0, a NULL pointer or an id given twice is
     * LSC_EINVAL and sends nothing. */
    int readPositions(const uint8_t *ids, uint8_t count, LSCServo *out);

    /* Joints (lsc/units.h), angles in centidegrees (3050 = 30.5 degrees).
     * moveJoint refuses (LSC_EINVAL, nothing sent) an angle outside the
     * joint's limits or its servo's range; readJoint reads the joint's
     * servo position and gives its angle. */
    int moveJoint(const LSCJoint &joint, int32_t centidegrees, uint16_t timeMs);
    int readJoint(const LSCJoint &joint, int32_t &centidegrees);

    /* Reads what has arrived; true while an action group runs (as the
     * controller last reported: started, not yet stopped or completed). */
    bool isRunning();
    /* Waits up to timeoutMs (any length) for the running group to complete
     * or be stopped. Returns LSC_CMD_GROUP_COMPLETE (8) or LSC_CMD_GROUP_STOP
     * (7), or LSC_ETIMEOUT. */
    int waitForCompletion(uint32_t timeoutMs);
    /* Reads what has arrived and hands out its notifications. Returns how many. */
    int poll();
    /* Calls fn (NULL: nobody) with every notification from now on. */
    void onNotification(NotifyFn fn)
    {
        notify_ = fn;
        notes_ = deliver;
    }

    /* Short English text for a return code. */
    static const char *errorText(int code) { return lsc_strerror(code); }

private:
    struct Wait;
    /* ms, but at most LSC_TIMEOUT_MAX: what receive's 16-bit clock waits */
    static uint16_t capped(uint32_t ms)
    {
        return ms > LSC_TIMEOUT_MAX ? (uint16_t)LSC_TIMEOUT_MAX : (uint16_t)ms;
    }
    int send(const uint8_t *frame, int len);
    int ask(uint8_t cmd, const uint8_t *ids, uint8_t n, void *out, uint8_t size);
    int receive(Wait &w, uint16_t timeoutMs);
    void onFrame(Wait &w, const lsc_frame &f);
    static void track(LSC &lsc, Wait &w, uint8_t cmd, const uint8_t *params);
    static void deliver(LSC &lsc, Wait &w, uint8_t cmd, const uint8_t *params);

    Stream &port_;
    uint16_t timeout_;
    NotifyFn notify_;
    /* takes every notification: track (keeps running_), or deliver (that
     * and hands them out), once a call that uses them ran */
    void (*notes_)(LSC &lsc, Wait &w, uint8_t cmd, const uint8_t *params);
    bool running_;
};

#endif /* LSC_ARDUINO_H */
