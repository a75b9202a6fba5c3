/* A forwarder's data path and a reopen (src/device/frames.c, reopen.c):
 * the frame hook sees every received frame (a reply too) and takes the
 * notifications from the queue, without the trace; lsc_device_send_frame
 * sends a whole frame as it is and refuses what is no frame; and
 * lsc_device_reopen opens a port that went away and came back (a
 * pseudo-terminal behind a symbolic link, like a USB adapter's
 * /dev/serial/by-id name) into the same handle, its settings kept, and
 * "sim" afresh. _POSIX_C_SOURCE and _DEFAULT_SOURCE come from
 * tests/CMakeLists.txt. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

#include "lsc/device.h"
#include "../src/device/device_sim.h" /* lsc_device_sim: not public */
#include "lsc/motion.h"
#include "lsc/play.h"
#include "lsc/env.h"
#include "lsc/text.h"
#include "lsc/arm.h"
#include "lsc/files.h"
#include "lsc/sim.h"
#include "lsc/player.h"
#include "lsc/discovery.h"
#include "lsc/link.h"
#include "lsc/lsc.h"
#include "test_time.h"

/* What the hook saw: the frames, in order, by command. */
typedef struct seen {
    unsigned total;
    unsigned by_cmd[256];
    uint8_t last[LSC_FRAME_MAX];
    size_t last_len;
} seen;

static void on_frame(void *user, const uint8_t *frame, size_t n)
{
    seen *s = user;
    s->total++;
    s->by_cmd[frame[3]]++;
    memcpy(s->last, frame, n);
    s->last_len = n;
}

static unsigned traced;
static void on_trace(void *user, lsc_trace_dir dir, const uint8_t *frame, size_t n)
{
    (void)user;
    (void)dir;
    (void)frame;
    (void)n;
    traced++;
}

/* ---- The hook, on "sim" --------------------------------------------------------- */

static void test_hook_takes_every_frame(void **state)
{
    (void)state;
    lsc_device *d = NULL;
    assert_int_equal(lsc_device_open("sim", NULL, &d), 0);
    assert_int_equal(lsc_device_set_virtual_clock(d, true), 0);
    seen s;
    memset(&s, 0, sizeof s);
    lsc_device_set_frame_hook(d, on_frame, &s);
    /* a request's reply: the hook has it, and the request returns it */
    uint16_t mv = 0;
    assert_int_equal(lsc_device_battery(d, &mv), 0);
    assert_int_equal(s.by_cmd[LSC_CMD_BATTERY], 1);
    assert_int_equal(s.last_len, 6);
    assert_int_equal(s.last[4] | (s.last[5] << 8), mv);
    /* a group's notifications go to the hook, not to the queue */
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_poll(d, 5000), 0); /* none queued */
    assert_int_equal(s.by_cmd[LSC_CMD_GROUP_RUN], 1);
    assert_int_equal(s.by_cmd[LSC_CMD_GROUP_COMPLETE], 1);
    assert_int_equal(lsc_device_notification(d, 0, NULL), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    /* without the hook they are queued again */
    lsc_device_set_frame_hook(d, NULL, NULL);
    unsigned before = s.total;
    assert_int_equal(lsc_device_run(d, 2, 1), 0);
    assert_int_equal(lsc_device_poll(d, 5000), 2);
    assert_int_equal(s.total, before);
    lsc_notification n;
    assert_int_equal(lsc_device_notification(d, 0, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_RUN);
    /* the trace is apart from the hook: set both, each sees the reply */
    traced = 0;
    lsc_device_set_frame_hook(d, on_frame, &s);
    lsc_device_set_trace(d, on_trace, NULL);
    assert_int_equal(lsc_device_battery(d, &mv), 0);
    assert_int_equal(traced, 2); /* the request and its reply */
    assert_int_equal(s.by_cmd[LSC_CMD_BATTERY], 2);
    lsc_device_set_frame_hook(NULL, on_frame, &s); /* (nothing) */
    lsc_device_close(d);
}

/* ---- lsc_device_send_frame ---------------------------------------------------------- */

static void test_send_frame_refuses(void **state)
{
    (void)state;
    const uint8_t stop[] = {0x55, 0x55, 0x02, LSC_CMD_GROUP_STOP};
    assert_int_equal(lsc_device_send_frame(NULL, stop, sizeof stop), LSC_EINVAL);
    lsc_device *d = NULL;
    assert_int_equal(lsc_device_open("sim", NULL, &d), 0);
    assert_int_equal(lsc_device_send_frame(d, NULL, 4), LSC_EINVAL);
    assert_string_equal(lsc_device_error(d),
                        "0 bytes that are no frame (55 55 LEN CMD ..., LEN = bytes - 2, not "
                        "0x55); nothing was sent");
    assert_int_equal(lsc_device_send_frame(d, stop, 3), LSC_EINVAL);
    uint8_t big[LSC_FRAME_MAX + 1u];
    memset(big, 0x55, sizeof big);
    assert_int_equal(lsc_device_send_frame(d, big, sizeof big), LSC_EINVAL);
    const uint8_t head0[] = {0x54, 0x55, 0x02, 7}, head1[] = {0x55, 0x54, 0x02, 7};
    const uint8_t len[] = {0x55, 0x55, 0x03, 7};
    assert_int_equal(lsc_device_send_frame(d, head0, 4), LSC_EINVAL);
    assert_int_equal(lsc_device_send_frame(d, head1, 4), LSC_EINVAL);
    assert_int_equal(lsc_device_send_frame(d, len, 4), LSC_EINVAL);
    /* LEN 0x55: 87 bytes whose LEN byte would read as a header byte */
    uint8_t l55[0x57];
    memset(l55, 0, sizeof l55);
    l55[0] = l55[1] = l55[2] = 0x55;
    l55[3] = 3;
    assert_int_equal(lsc_device_send_frame(d, l55, sizeof l55), LSC_EINVAL);
    assert_string_equal(lsc_device_error(d),
                        "87 bytes that are no frame (55 55 LEN CMD ..., LEN = bytes - 2, not "
                        "0x55); nothing was sent");
    /* a frame: sent ("sim" acts on it), the error cleared */
    assert_int_equal(lsc_device_send_frame(d, stop, sizeof stop), 0);
    assert_string_equal(lsc_device_error(d), "");
    lsc_device_close(d);
}

/* ---- A pseudo-terminal that goes away and comes back ------------------------------- */

typedef struct port {
    int master;
    char link[64];
    char dir[32];
} port;

/* A new pseudo-terminal behind p->link (made again if it was there). */
static void port_up(port *p)
{
    int slave = -1;
    char name[64];
    assert_int_equal(openpty(&p->master, &slave, name, NULL, NULL), 0);
    struct termios t;
    assert_int_equal(tcgetattr(slave, &t), 0);
    cfmakeraw(&t);
    assert_int_equal(tcsetattr(slave, TCSANOW, &t), 0);
    (void)close(slave); /* (the device opens it by its path) */
    (void)unlink(p->link);
    assert_int_equal(symlink(name, p->link), 0);
}

/* The pseudo-terminal goes: its master closes, its link with it. */
static void port_down(port *p)
{
    (void)close(p->master);
    p->master = -1;
    assert_int_equal(unlink(p->link), 0);
}

/* n bytes the device wrote, from the master side. */
static void port_expect(port *p, const uint8_t *want, size_t n)
{
    uint8_t got[LSC_FRAME_MAX];
    size_t have = 0;
    while (have < n) {
        struct pollfd pf = {p->master, POLLIN, 0};
        assert_int_equal(poll(&pf, 1, (int)test_ms(5000)), 1);
        ssize_t r = read(p->master, got + have, n - have);
        assert_true(r > 0);
        have += (size_t)r;
    }
    assert_memory_equal(got, want, n);
}

static void test_reopen_pty(void **state)
{
    (void)state;
    port p;
    (void)snprintf(p.dir, sizeof p.dir, "/tmp/lsc-reopen-XXXXXX");
    assert_non_null(mkdtemp(p.dir));
    (void)snprintf(p.link, sizeof p.link, "%s/port", p.dir);
    port_up(&p);
    lsc_device *d = NULL;
    assert_int_equal(lsc_device_open(p.link, NULL, &d), 0);
    seen s;
    memset(&s, 0, sizeof s);
    lsc_device_set_frame_hook(d, on_frame, &s);
    lsc_device_set_timeout(d, 321);
    const uint8_t stop[] = {0x55, 0x55, 0x02, LSC_CMD_GROUP_STOP};
    assert_int_equal(lsc_device_send_frame(d, stop, sizeof stop), 0);
    port_expect(&p, stop, sizeof stop);
    /* away: the port is gone, and a reopen finds nothing */
    port_down(&p);
    assert_int_equal(lsc_device_reopen(d), LSC_ENODEV);
    assert_true(strstr(lsc_device_error(d), p.link) != NULL);
    assert_int_equal(lsc_device_fileno(d), -1);
    assert_int_equal(lsc_device_send_frame(d, stop, sizeof stop), LSC_ENODEV);
    assert_true(strstr(lsc_device_error(d), "the controller is gone and its port closed") !=
                NULL);
    uint16_t mv;
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ENODEV);
    assert_int_equal(lsc_device_poll(d, 10), LSC_ENODEV);
    assert_int_equal(lsc_device_stop(d), LSC_ENODEV);
    (void)lsc_device_now_ms(d); /* the clock still runs */
    /* back, another pseudo-terminal behind the same name */
    port_up(&p);
    assert_int_equal(lsc_device_reopen(d), 0);
    assert_string_equal(lsc_device_error(d), "");
    assert_true(lsc_device_fileno(d) >= 0);
    assert_string_equal(lsc_device_name(d), p.link);
    assert_int_equal(lsc_device_timeout(d), 321);
    assert_int_equal(lsc_device_send_frame(d, stop, sizeof stop), 0);
    port_expect(&p, stop, sizeof stop);
    /* the hook stayed: a notification from the controller comes to it */
    const uint8_t done[] = {0x55, 0x55, 0x05, LSC_CMD_GROUP_COMPLETE, 1, 1, 0};
    assert_int_equal(write(p.master, done, sizeof done), (ssize_t)sizeof done);
    long deadline = test_ms(5000) / 20;
    while (s.by_cmd[LSC_CMD_GROUP_COMPLETE] == 0 && deadline-- > 0) {
        assert_true(lsc_device_poll(d, 20) >= 0);
    }
    assert_int_equal(s.by_cmd[LSC_CMD_GROUP_COMPLETE], 1);
    assert_memory_equal(s.last, done, sizeof done);
    /* a reopen of a port that is there: afresh */
    assert_int_equal(lsc_device_reopen(d), 0);
    assert_int_equal(lsc_device_send_frame(d, stop, sizeof stop), 0);
    port_expect(&p, stop, sizeof stop);
    /* its port closed, and opened again: the other end sees the hang-up */
    lsc_device_close_port(NULL); /* (nothing) */
    lsc_device_close_port(d);
    assert_int_equal(lsc_device_fileno(d), -1);
    struct pollfd pf = {p.master, POLLIN, 0};
    assert_int_equal(poll(&pf, 1, (int)test_ms(5000)), 1);
    assert_true((pf.revents & POLLHUP) != 0);
    assert_int_equal(lsc_device_send_frame(d, stop, sizeof stop), LSC_ENODEV);
    assert_int_equal(lsc_device_halt(d), LSC_ENODEV);
    assert_int_equal(lsc_device_reopen(d), 0);
    assert_int_equal(lsc_device_send_frame(d, stop, sizeof stop), 0);
    port_expect(&p, stop, sizeof stop);
    lsc_device_close(d);
    port_down(&p);
    assert_int_equal(rmdir(p.dir), 0);
}

/* ---- The link's counters, and notifications in one call ------------------------ */

static void test_counters(void **state)
{
    (void)state;
    port p;
    (void)snprintf(p.dir, sizeof p.dir, "/tmp/lsc-counters-XXXXXX");
    assert_non_null(mkdtemp(p.dir));
    (void)snprintf(p.link, sizeof p.link, "%s/port", p.dir);
    port_up(&p);
    lsc_device *d = NULL;
    assert_int_equal(lsc_device_open(p.link, NULL, &d), 0);
    lsc_device_counters c;
    c.size = sizeof c;
    assert_int_equal(lsc_device_get_counters(NULL, &c), LSC_EINVAL);
    assert_int_equal(lsc_device_get_counters(d, NULL), LSC_EINVAL);
    c.size = sizeof c.size;
    assert_int_equal(lsc_device_get_counters(d, &c), LSC_EINVAL);
    c.size = sizeof c;
    assert_int_equal(lsc_device_get_counters(d, &c), 0);
    assert_int_equal(c.size, sizeof c);
    assert_true(c.frames_sent == 0 && c.frames_received == 0 && c.timeouts == 0);
    /* a request unanswered: one frame out, one timeout */
    lsc_device_set_timeout(d, 30);
    uint16_t mv;
    assert_int_equal(lsc_device_battery(d, &mv), LSC_ETIMEOUT);
    const uint8_t battery[] = {0x55, 0x55, 0x02, LSC_CMD_BATTERY};
    port_expect(&p, battery, sizeof battery);
    /* received: a notification, another frame, a malformed one (LEN 1), noise */
    const uint8_t in[] = {0x55, 0x55, 0x05, LSC_CMD_GROUP_COMPLETE, 1, 1, 0, /* 6 to 8 */
                          0x55, 0x55, 0x02, 0x01,                             /* below */
                          0x55, 0x55, 0x04, 0x1A, 1, 2,                       /* above */
                          0x55, 0x55, 0x01, 0x00, 0x13, 0x37};
    assert_int_equal(write(p.master, in, sizeof in), (ssize_t)sizeof in);
    long rounds = test_ms(5000) / 20;
    do {
        assert_true(lsc_device_poll(d, 20) >= 0);
        assert_int_equal(lsc_device_get_counters(d, &c), 0);
    } while ((c.frames_received < 3 || c.bad_frames < 1) && --rounds > 0);
    assert_int_equal(c.frames_sent, 1);
    assert_int_equal(c.frames_received, 3);
    assert_int_equal(c.notifications, 1);
    assert_int_equal(c.bad_frames, 1);
    assert_true(c.bytes_discarded >= 3);
    assert_int_equal(c.timeouts, 1);
    assert_int_equal(c.reopens, 0);
    /* a reopen keeps them (the parser's, too) and counts itself */
    uint64_t discarded = c.bytes_discarded;
    assert_int_equal(lsc_device_reopen(d), 0);
    assert_int_equal(lsc_device_get_counters(d, &c), 0);
    assert_int_equal(c.reopens, 1);
    assert_int_equal(c.bad_frames, 1);
    assert_int_equal(c.bytes_discarded, discarded);
    assert_int_equal(c.frames_received, 3);
    /* a caller with an older, shorter struct: only its fields are written */
    struct {
        size_t size;
        uint64_t frames_sent;
        uint64_t guard;
    } old;
    old.size = offsetof(lsc_device_counters, frames_sent) + sizeof old.frames_sent;
    old.guard = 77;
    assert_int_equal(lsc_device_get_counters(d, (lsc_device_counters *)(void *)&old), 0);
    assert_int_equal(old.frames_sent, 1);
    assert_int_equal(old.guard, 77);
    assert_int_equal(old.size, offsetof(lsc_device_counters, frames_sent) + 8u);
    lsc_device_close(d);
    port_down(&p);
    assert_int_equal(rmdir(p.dir), 0);
}

static void test_notifications_at_once(void **state)
{
    (void)state;
    assert_int_equal(lsc_device_notifications(NULL, NULL, 0), LSC_EINVAL);
    lsc_device *d = NULL;
    assert_int_equal(lsc_device_open("sim", NULL, &d), 0);
    assert_int_equal(lsc_device_set_virtual_clock(d, true), 0);
    assert_int_equal(lsc_device_notifications(d, NULL, 1), LSC_EINVAL);
    assert_int_equal(lsc_device_notifications(d, NULL, 0), 0);
    lsc_notification n[4];
    assert_int_equal(lsc_device_notifications(d, n, 4), 0); /* none queued */
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    assert_int_equal(lsc_device_run(d, 2, 1), 0); /* 7 (1 stopped), then 6 */
    /* (the second run queued group 1's start before it was sent) */
    assert_int_equal(lsc_device_poll(d, 10000), 3);
    assert_int_equal(lsc_device_notifications(d, n, 3), 3);
    assert_int_equal(n[0].cmd, LSC_CMD_GROUP_RUN);
    assert_int_equal(n[0].group, 1);
    assert_int_equal(n[1].cmd, LSC_CMD_GROUP_STOP);
    assert_int_equal(n[2].cmd, LSC_CMD_GROUP_RUN);
    assert_int_equal(n[2].group, 2);
    assert_int_equal(lsc_device_notifications(d, n, 4), 1);
    assert_int_equal(n[0].cmd, LSC_CMD_GROUP_COMPLETE);
    assert_int_equal(lsc_device_notifications(d, n, 4), 0);
    lsc_device_counters c;
    c.size = sizeof c;
    assert_int_equal(lsc_device_get_counters(d, &c), 0);
    assert_int_equal(c.notifications, 4);
    assert_int_equal(c.frames_sent, 2);
    lsc_device_close(d);
}

/* ---- "sim" afresh ------------------------------------------------------------------------ */

static void test_reopen_sim(void **state)
{
    (void)state;
    assert_int_equal(lsc_device_reopen(NULL), LSC_EINVAL);
    lsc_device *d = NULL;
    assert_int_equal(lsc_device_open("sim", NULL, &d), 0);
    assert_int_equal(lsc_device_set_virtual_clock(d, true), 0);
    lsc_servo to = {1, 2000};
    assert_int_equal(lsc_device_move(d, 100, &to, 1), 0);
    assert_int_equal(lsc_device_run(d, 1, 0), 0);
    assert_int_equal(lsc_device_poll(d, 10), 1); /* its start, queued */
    assert_int_equal(lsc_device_reopen(d), 0);
    /* the queue and the group's wait start again; the clock is the real one */
    assert_int_equal(lsc_device_notification(d, 0, NULL), LSC_ETIMEOUT);
    assert_false(lsc_device_group_started(d));
    assert_true(lsc_device_fileno(d) >= 0);
    assert_int_equal(lsc_sim_group_running(lsc_device_sim(d)), -1);
    /* the last known position stays */
    uint16_t pos = 0;
    assert_int_equal(lsc_device_last_position(d, 1, &pos), 0);
    assert_int_equal(pos, 2000);
    lsc_servo got;
    const uint8_t id = 2;
    assert_int_equal(lsc_device_read(d, &id, 1, &got), 1);
    /* its port closed: still "sim" by kind, but no model behind it, and an
     * interrupt taken by a wait says the same one line */
    lsc_device_close_port(d);
    assert_int_equal(lsc_device_kind_of(d), LSC_DEVICE_SIM);
    assert_null(lsc_device_sim(d));
    assert_int_equal(lsc_device_set_virtual_clock(d, true), LSC_EINVAL);
    assert_int_equal(lsc_device_fileno(d), -1);
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER);
    assert_int_equal(lsc_device_move(d, 100, &to, 1), LSC_ENODEV);
    assert_true(strstr(lsc_device_error(d), "sim: the controller is gone and its port closed") !=
                NULL);
    lsc_device_interrupt(d);
    assert_int_equal(lsc_device_poll(d, 10), LSC_EINTR);
    assert_true(strstr(lsc_device_error(d), "the controller is gone") != NULL);
    assert_int_equal(lsc_device_reopen(d), 0);
    assert_non_null(lsc_device_sim(d));
    assert_int_equal(lsc_device_read(d, &id, 1, &got), 1);
    lsc_device_close(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hook_takes_every_frame),
        cmocka_unit_test(test_send_frame_refuses),
        cmocka_unit_test(test_reopen_pty),
        cmocka_unit_test(test_reopen_sim),
        cmocka_unit_test(test_counters),
        cmocka_unit_test(test_notifications_at_once),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
