/* The device layer's clock and interrupts (src/device/transport_sim.c on
 * realclock.c, the interrupt of link.c): "sim" on the real clock with its timer descriptor,
 * its virtual clock as an option, and lsc_device_interrupt from another
 * thread and from a signal handler, on "sim" and on lsc-sim's pty (argv[1]).
 * timerfd_create is wrapped by the linker (a system out of descriptors:
 * timerfd_test.h).
 * _POSIX_C_SOURCE comes from tests/CMakeLists.txt. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "lsc/device.h"
#include "lsc/motion.h"
#include "lsc/play.h"
#include "lsc/files.h"
#include "lsc/sim.h"
#include "lsc/player.h"
#include "sim_pty.h"
#include "test_time.h"
#include "test_open.h"
#include "timerfd_test.h"

static const char *lsc_sim_path;

/* ---- helpers ------------------------------------------------------------------------ */

static lsc_device *open_ok(const char *name)
{
    lsc_device *d = NULL;
    int r = lsc_device_open(name, NULL, &d);
    if (r != 0) {
        fail_msg("open %s: %s", name, lsc_device_error(NULL));
    }
    return d;
}

/* The lsc-sim a test started and has not stopped: the teardown ends it. */
static pid_t started = -1;

static int end_started(void **state)
{
    (void)state;
    if (started > 0) {
        (void)kill(started, SIGKILL);
        (void)waitpid(started, NULL, 0);
        started = -1;
    }
    return 0;
}

static lsc_device *open_pty(char *tty, size_t size)
{
    sim_pty_start(lsc_sim_path, NULL, &started, tty, size);
    test_options opt = {9600, (uint32_t)test_ms(1000), 0, 0};
    lsc_device *d = NULL;
    if (test_open(tty, &opt, &d) != 0) {
        fail_msg("open %s: %s", tty, lsc_device_error(NULL));
    }
    return d;
}

/* ---- "sim" on the real clock ---------------------------------------------------------- */

/* The loop of lsc/device.h on the descriptor: group 1's start and end come
 * as time really passes (its two steps: 1000 ms), without feeding time in. */
static void real_clock_poll_loop(void **state)
{
    (void)state;
    lsc_device *d = open_ok("sim");
    int fd = lsc_device_fileno(d);
    assert_true(fd >= 0);
    assert_int_equal(lsc_device_next_event_ms(d), LSC_DEVICE_FOREVER); /* nothing runs */
    long t0 = mono_ms();
    assert_int_equal(lsc_device_run(d, 1, 1), 0);
    bool began = false, ended = false;
    long began_at = 0;
    while (!ended) {
        lsc_notification n;
        while (lsc_device_notification(d, 0, &n) == 0) {
            if (n.cmd == LSC_CMD_GROUP_RUN && n.group == 1) {
                began = true;
                began_at = mono_ms();
            }
            ended = n.cmd == LSC_CMD_GROUP_COMPLETE;
        }
        if (ended) {
            break;
        }
        assert_true(mono_ms() - t0 < test_ms(10000));
        uint32_t next = lsc_device_next_event_ms(d);
        assert_true(next != LSC_DEVICE_FOREVER); /* a group runs */
        struct pollfd p = {fd, POLLIN, 0};
        int got = poll(&p, 1, (int)(next < 60000u ? next : 60000u));
        assert_true(got >= 0 || errno == EINTR);
        assert_true(lsc_device_poll(d, 0) >= 0);
    }
    assert_true(began);
    long took = mono_ms() - t0;
    assert_true(took >= 950); /* the group's 1000 ms, really (rounded to ms) */
    assert_true(began_at - t0 < took);
    assert_true(lsc_device_now_ms(d) >= 950u);
    lsc_device_close(d);
}

/* A blocking wait follows the real clock too; with nothing running a wait
 * ends at once (nothing can come); an overdue event is due now (0). */
static void real_clock_waits(void **state)
{
    (void)state;
    lsc_notification n;
    lsc_device *d = open_ok("sim");
    long t0 = mono_ms();
    assert_int_equal(lsc_device_notification(d, 5000, &n), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_SIM_IDLE);
    assert_true(mono_ms() - t0 < test_ms(2000));
    t0 = mono_ms();
    assert_int_equal(lsc_device_run(d, 2, 1), 0); /* two steps of 300 ms */
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), 0);
    assert_int_equal(n.cmd, LSC_CMD_GROUP_COMPLETE);
    assert_true(mono_ms() - t0 >= 550);
    /* time passes by itself: the timer fires when the next step is due,
     * and lsc_device_next_event_ms says 0 once it is overdue */
    assert_int_equal(lsc_device_run(d, 2, 1), 0);
    struct pollfd p = {lsc_device_fileno(d), POLLIN, 0};
    for (int i = 0; i < 3; i++) { /* the start, the first step's end */
        assert_int_equal(poll(&p, 1, (int)test_ms(5000)), 1);
        assert_int_equal(lsc_device_next_event_ms(d), 0);
        assert_true(lsc_device_poll(d, 0) >= 0);
    }
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), 0);
    /* a move takes its time: settle waits it out on the real clock */
    const lsc_servo to = {1, 2000};
    t0 = mono_ms();
    assert_int_equal(lsc_device_move(d, 200, &to, 1), 0);
    assert_int_equal(lsc_device_settle(d, &to, 1, 200, LSC_DEVICE_TOLERANCE_DEFAULT), 0);
    assert_true(mono_ms() - t0 >= 190);
    lsc_device_close(d);
}

/* The virtual clock as an option: no descriptor, waits take no real time;
 * back on the real clock from where it was. Other kinds refuse it. */
static void virtual_clock_option(void **state)
{
    (void)state;
    lsc_notification n;
    assert_int_equal(lsc_device_set_virtual_clock(NULL, true), LSC_EINVAL);
    lsc_device *d = open_ok("sim");
    int fd = lsc_device_fileno(d);
    assert_int_equal(lsc_device_set_virtual_clock(d, false), 0); /* as it is */
    assert_int_equal(lsc_device_set_virtual_clock(d, true), 0);
    assert_int_equal(lsc_device_set_virtual_clock(d, true), 0);
    assert_int_equal(lsc_device_fileno(d), -1);
    long t0 = mono_ms();
    uint32_t v0 = lsc_device_now_ms(d);
    assert_int_equal(lsc_device_run(d, 8, 1), 0); /* 2500 ms */
    assert_true(lsc_device_next_event_ms(d) < 100u); /* its start, on that clock */
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), 0);
    assert_true(lsc_device_now_ms(d) - v0 >= 2500u);
    assert_true(mono_ms() - t0 < test_ms(2000));
    assert_int_equal(lsc_device_set_virtual_clock(d, false), 0);
    assert_int_equal(lsc_device_fileno(d), fd);
    assert_true(lsc_device_now_ms(d) - v0 >= 2500u); /* from where it was */
    lsc_device_close(d);
}

/* Without a timer (no descriptor left): still the real clock; no
 * descriptor to wait on, and the loop sleeps until next_event_ms. */
static void real_clock_without_timer(void **state)
{
    (void)state;
    lsc_notification n;
    timerfd_fails = true;
    lsc_device *d = open_ok("sim");
    timerfd_fails = false;
    assert_int_equal(lsc_device_fileno(d), -1);
    long t0 = mono_ms();
    assert_int_equal(lsc_device_run(d, 2, 1), 0);
    assert_int_equal(lsc_device_wait_group(d, 2, LSC_DEVICE_FOREVER, &n), 0);
    assert_true(mono_ms() - t0 >= 550);
    lsc_device_close(d);
}

/* ---- lsc_device_interrupt ---------------------------------------------------------- */

/* A pending interrupt: the next call that waits takes it (one call), calls
 * that only send or take what is there do not; each that waits honours it. */
static bool interrupt_at_step(void *user, const lsc_player_step *step, uint32_t elapsed_ms)
{
    (void)step;
    (void)elapsed_ms;
    lsc_device_interrupt(user);
    return true;
}

static bool interrupt_at_keyframe(void *user, const lsc_action *a, bool taken)
{
    (void)a;
    (void)taken;
    lsc_device_interrupt(user);
    return true;
}

static void interrupt_pending(void **state)
{
    (void)state;
    lsc_notification n;
    uint16_t mv;
    const lsc_servo s = {1, 1200};
    lsc_device_interrupt(NULL); /* nothing */
    lsc_device *d = open_ok("sim");
    assert_int_equal(lsc_device_set_virtual_clock(d, true), 0);
    lsc_device_interrupt(d);
    assert_int_equal(lsc_device_move(d, 100, &s, 1), 0);          /* sends only */
    assert_int_equal(lsc_device_poll(d, 0), 0);                    /* takes what is there */
    assert_int_equal(lsc_device_notification(d, 0, &n), LSC_ETIMEOUT);
    assert_int_equal(lsc_device_battery(d, &mv), LSC_EINTR);       /* waits: takes it */
    assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_INTERRUPTED);
    assert_non_null(strstr(lsc_device_error(d), "interrupted (lsc_device_interrupt) while "
                                                "waiting for the controller on sim"));
    assert_int_equal(lsc_device_battery(d, &mv), 0); /* one interrupt, one call */
    assert_int_equal(mv, 7500);
    lsc_device_interrupt(d);
    assert_int_equal(lsc_device_poll(d, 10), LSC_EINTR);
    lsc_device_interrupt(d);
    assert_int_equal(lsc_device_settle(d, &s, 1, 100, 10), LSC_EINTR);
    assert_int_equal(lsc_device_run(d, 8, 1), 0);
    lsc_device_interrupt(d);
    assert_int_equal(lsc_device_notification(d, 100, &n), LSC_EINTR);
    lsc_device_interrupt(d);
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), LSC_EINTR);
    assert_int_equal(lsc_device_wait_group(d, 8, LSC_DEVICE_FOREVER, &n), 0); /* resumed */
    /* play and record, from their callbacks */
    static const uint8_t ids[] = {1, 2};
    lsc_action a;
    assert_int_equal(lsc_action_init(&a, ids, 2), 0);
    const uint16_t row[] = {1500, 1500};
    for (int k = 0; k < 3; k++) {
        assert_int_equal(lsc_action_append(&a, 500, row), 0);
    }
    lsc_player_config c = {100, 1, 0, 0};
    lsc_play_result res = {.size = sizeof res};
    assert_int_equal(lsc_device_play(d, &a, &c, interrupt_at_step, d, &res), LSC_EINTR);
    assert_true(res.frames >= 1 && res.frames < 3);
    lsc_action_free(&a);
    assert_int_equal(lsc_action_init(&a, ids, 2), 0);
    assert_int_equal(lsc_device_record(d, &a, 100, 5, interrupt_at_keyframe, d), LSC_EINTR);
    assert_true(a.count >= 1 && a.count < 5);
    lsc_action_free(&a);
    lsc_device_close(d);
}

typedef struct interrupter {
    lsc_device *d;
    long at; /* when it interrupted (mono_ms) */
} interrupter;

static void *interrupt_later(void *arg)
{
    interrupter *x = arg;
    (void)poll(NULL, 0, 100); /* let the wait begin (if not, it is the next one: the same) */
    x->at = mono_ms();
    lsc_device_interrupt(x->d);
    return NULL;
}

/* From another thread: a wait without limit on lsc-sim's pty (nothing
 * runs: nothing comes) ends within 0.3 s of it, LSC_EINTR; the device goes
 * on working. On "sim"'s real clock the same. */
static void interrupt_from_thread(void **state)
{
    (void)state;
    char tty[256];
    lsc_notification n;
    uint16_t mv;
    for (int round = 0; round < 2; round++) {
        lsc_device *d = round == 0 ? open_pty(tty, sizeof tty) : open_ok("sim");
        if (round == 0) { /* a real controller does not say its groups; no sim clock */
            assert_int_equal(lsc_device_groups(d, NULL, 0), 0);
            assert_int_equal(lsc_device_set_virtual_clock(d, true), LSC_EINVAL);
        }
        if (round == 1) {
            assert_int_equal(lsc_device_run(d, 8, 0), 0); /* loops: its end never comes */
        }
        interrupter x = {d, 0};
        pthread_t t;
        assert_int_equal(pthread_create(&t, NULL, interrupt_later, &x), 0);
        int r = lsc_device_wait_group(d, round == 0 ? LSC_GROUP_ALL : 8, LSC_DEVICE_FOREVER,
                                      &n);
        long back = mono_ms();
        assert_int_equal(pthread_join(t, NULL), 0);
        assert_int_equal(r, LSC_EINTR);
        assert_int_equal(lsc_device_error_cause(d), LSC_DEVICE_CAUSE_INTERRUPTED);
        assert_true(back - x.at < test_ms(300));
        assert_int_equal(lsc_device_battery(d, &mv), 0);
        lsc_device_close(d);
    }
    sim_pty_stop(&started);
}

/* From a signal handler (SIGALRM of a timer): the same. */
static lsc_device *alarmed;

static void on_alarm(int sig)
{
    (void)sig;
    lsc_device_interrupt(alarmed);
}

static void interrupt_from_signal(void **state)
{
    (void)state;
    char tty[256];
    lsc_notification n;
    alarmed = open_pty(tty, sizeof tty);
    struct sigaction sa, old;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_alarm;
    (void)sigemptyset(&sa.sa_mask);
    assert_int_equal(sigaction(SIGALRM, &sa, &old), 0);
    struct itimerval it = {{0, 0}, {0, 100000}}; /* once, in 100 ms */
    assert_int_equal(setitimer(ITIMER_REAL, &it, NULL), 0);
    long t0 = mono_ms();
    assert_int_equal(lsc_device_wait_group(alarmed, LSC_GROUP_ALL, LSC_DEVICE_FOREVER, &n),
                     LSC_EINTR);
    assert_true(mono_ms() - t0 < test_ms(100 + 300));
    assert_int_equal(sigaction(SIGALRM, &old, NULL), 0);
    lsc_device_close(alarmed);
    sim_pty_stop(&started);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(real_clock_poll_loop),
        cmocka_unit_test(real_clock_waits),
        cmocka_unit_test(virtual_clock_option),
        cmocka_unit_test(real_clock_without_timer),
        cmocka_unit_test(interrupt_pending),
        cmocka_unit_test_teardown(interrupt_from_thread, end_started),
        cmocka_unit_test_teardown(interrupt_from_signal, end_started),
    };
    if (argc < 2) {
        (void)fprintf(stderr, "usage: %s PATH/TO/lsc-sim\n", argv[0]);
        return 2;
    }
    lsc_sim_path = argv[1];
    return cmocka_run_group_tests(tests, NULL, NULL);
}
