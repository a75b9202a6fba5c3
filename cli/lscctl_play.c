/* lscctl play: an action file played on a controller, or (-n) its
 * schedule. The schedule and the player are the library's (lsc_device_play
 * in lsc/device.h): here are the arguments, Ctrl-C and what is printed. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "lsc/device.h"
#include "lsc/files.h"
#include "lsc/play.h"
#include "lsc/convert.h"
#include "lsc/text.h"
#include "lsc/player.h"
#include "lscctl.h"
#include "lscctl_port.h"
#include "lscctl_teach.h"

const char lscctl_help_play[] =
    "Moves the servos to FILE's first keyframe over --lead ms, then sends each\n"
    "keyframe as one move at its time, on a schedule fixed from one start (no\n"
    "drift). Servos that keep their position are left out of a frame. Keyframes\n"
    "faster than the line carries (at 9600 baud a one-servo move takes 10.4 ms)\n"
    "are dropped, said once, rather than played late. Ctrl-C stops after the\n"
    "frame being sent and leaves the servos where they are. With -n, prints the\n"
    "schedule instead. A bad file is refused whole, before anything is sent;\n"
    "with --arm, so is a file with a keyframe outside the profile's limits.\n"
    "\nOptions:\n  --speed PCT  100 as recorded (default), 200 twice as fast (1..65535)\n"
    "  --times N    play it N times (1..65535, default 1)\n"
    "  --lead MS    the move to the first keyframe (default 1000; 0: at once)\n"
    "  --group N    the group N of a .txt file of several groups (lsc-sim's\n"
    "               group files); a .csv, .rob or .d6a file is one group,\n"
    "               numbered by its name (10.rob: group 10), else group 1\n"
    "\nExamples:\n  lscctl play wave.csv\n  lscctl play arm.rob --speed 50 --times 3\n"
    "  lscctl play examples/groups/arm-demo.txt --group 1\n"
    "  lscctl -n play arm.d6a                print the schedule\n";

typedef struct player_view {
    const lscctl_opts *o;
    const lsc_play_result *result; /* kept up to date by the play */
    uint32_t count;                /* keyframes in the file */
    bool tty;                      /* progress on stderr */
    bool said_drop;
    bool real;                     /* played on a port: the time each frame went out */
    uint64_t late_sum_ms;          /* the lateness of every frame sent, summed */
} player_view;

/* Keyframe x of the whole play (repetitions counted on: x = repetition *
 * count + keyframe) as 1-based "keyframe" and "time" (the repetition). */
static void print_dropped(const lscctl_opts *o, uint32_t count, uint32_t x)
{
    if (o->json) {
        printf("{\"dropped_keyframe\":%lu,\"time\":%lu,\"repetition\":%lu}\n",
               (unsigned long)(x % count) + 1u, (unsigned long)(x / count) + 1u,
               (unsigned long)(x / count) + 1u);
    }
}

/* One frame sent (or, with -n, scheduled); elapsed: when it went out, ms
 * after the start (real plays only). The keyframes dropped just before it
 * come first, one object each (JSON). */
static void print_step(const player_view *v, const lsc_player_step *s, uint32_t elapsed)
{
    const lscctl_opts *o = v->o;
    uint32_t x = s->lead_in ? 0u : (uint32_t)s->repetition * v->count + s->keyframe;
    for (uint32_t i = s->dropped; i > 0 && x >= i; i--) {
        print_dropped(o, v->count, x - i);
    }
    if (o->json) {
        printf("{\"at_ms\":%lu,\"keyframe\":%lu,\"time\":%u,\"repetition\":%u,"
               "\"lead_in\":%s,\"time_ms\":%u,\"dropped\":%lu,",
               (unsigned long)s->due_ms, (unsigned long)s->keyframe + 1u, s->repetition + 1u,
               s->repetition + 1u, s->lead_in ? "true" : "false", s->time_ms,
               (unsigned long)s->dropped);
        if (v->real) {
            printf("\"sent_ms\":%lu,\"late_ms\":%lu,", (unsigned long)elapsed,
                   (unsigned long)(elapsed - s->due_ms));
        }
        printf("\"servos\":[");
        for (size_t i = 0; i < s->nservos; i++) {
            printf("%s{\"id\":%u,\"position\":%u}", i ? "," : "", s->servos[i].id,
                   s->servos[i].position);
        }
        printf("]}\n");
        return;
    }
    printf("%8lu ms  keyframe %lu", (unsigned long)s->due_ms, (unsigned long)s->keyframe + 1u);
    if (s->repetition > 0) {
        printf(" (time %u)", s->repetition + 1u);
    }
    printf("%s  move %u ms", s->lead_in ? " (lead-in)" : "", s->time_ms);
    for (size_t i = 0; i < s->nservos; i++) {
        printf(" %u:%u", s->servos[i].id, s->servos[i].position);
    }
    if (s->dropped > 0) {
        printf("  (%lu dropped before it)", (unsigned long)s->dropped);
    }
    putchar('\n');
}

/* The play's summary (JSON): its end, frames sent, keyframes dropped, how
 * late frames went out after their due time (with -n, on the schedule's
 * model of the line: a frame waits while the one before is on the wire). */
static void print_summary(const player_view *v, const lsc_play_result *res)
{
    const lscctl_opts *o = v->o;
    printf("{\"end_ms\":%lu,\"keyframes\":%lu,\"frames\":%lu,\"dropped\":%lu,"
           "\"max_late_ms\":%lu,\"mean_late_ms\":%lu,\"stopped\":%s}\n",
           (unsigned long)res->total_ms, (unsigned long)v->count * o->times,
           (unsigned long)res->frames, (unsigned long)res->dropped,
           (unsigned long)res->max_late_ms,
           res->frames > 0 ? (unsigned long)(v->late_sum_ms / res->frames) : 0ul,
           res->stopped ? "true" : "false");
}

/* -n: each frame as the schedule has it. */
static bool on_schedule_step(void *user, const lsc_player_step *s, uint32_t elapsed)
{
    player_view *v = user;
    if (s != NULL) {
        v->late_sum_ms += elapsed - s->due_ms;
        print_step(v, s, elapsed);
    }
    return true;
}

/* The play on a port: each frame with --json, the drop said once, the
 * progress on a terminal, Ctrl-C. */
static bool on_play_step(void *user, const lsc_player_step *s, uint32_t elapsed)
{
    player_view *v = user;
    const lscctl_opts *o = v->o;
    if (s != NULL) {
        v->late_sum_ms += elapsed - s->due_ms;
    }
    if (s != NULL && o->json) {
        print_step(v, s, elapsed);
        fflush(stdout);
    }
    if (s != NULL && s->dropped > 0 && !v->said_drop) {
        v->said_drop = true;
        fprintf(stderr, "%slscctl: play: keyframes come faster than %lu baud carries: "
                        "dropping those that cannot be sent in time\n",
                v->tty ? "\n" : "", lscctl_baud(o));
    }
    if (s != NULL && v->tty) {
        uint32_t total = v->result->total_ms;
        fprintf(stderr,
                "\rlscctl: play: keyframe %lu of %lu, time %u of %lu, %lu.%lu of %lu.%lu s ",
                (unsigned long)s->keyframe + 1u, (unsigned long)v->count, s->repetition + 1u,
                o->times, (unsigned long)(elapsed / 1000u), (unsigned long)(elapsed % 1000u / 100u),
                (unsigned long)(total / 1000u), (unsigned long)(total % 1000u / 100u));
    }
    return lscctl_interrupted == 0;
}

/* -n: the schedule, played on the built-in virtual controller (its clock is
 * virtual: the play takes no time, and nothing leaves the program). */
static int print_schedule(const lscctl_opts *o, const char *path, const lsc_action *a,
                          const lsc_player_config *c)
{
    lsc_device *d = NULL;
    if (lsc_device_open("sim", NULL, &d) != 0) {
        int code = lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s", lsc_device_error(d));
        lsc_device_close(d);
        return code;
    }
    (void)lsc_device_set_virtual_clock(d, true); /* (it is "sim") */
    lsc_play_result res = {.size = sizeof res};
    player_view v = {o, &res, a->count, false, false, false, 0};
    int code = lscctl_set_arm(o, d);
    int r = code != 0 ? 0 : lsc_device_play(d, a, c, on_schedule_step, &v, &res);
    if (r == LSC_EINVAL) {
        lscctl_shown name;
        code = lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s: %s", lscctl_show(&name, path),
                           lsc_device_error(d));
    } else if (r != 0) {
        code = lscctl_fail(o, LSCCTL_EXIT_FAIL, "%s", lsc_device_error(d));
    } else if (code == 0 && o->json) {
        print_summary(&v, &res);
    } else if (code == 0) {
        printf("%8lu ms  end", (unsigned long)res.total_ms);
        if (res.dropped > 0) {
            printf(" (%lu of %lu keyframes dropped: faster than %lu baud carries)",
                   (unsigned long)res.dropped, (unsigned long)a->count * o->times, lscctl_baud(o));
        }
        putchar('\n');
    }
    lsc_device_close(d);
    return code;
}

/* Plays on the port until the end or Ctrl-C. */
static int play_on(const lscctl_opts *o, const char *path, const lsc_action *a,
                   const lsc_player_config *c)
{
    lscctl_link *l;
    int code = lscctl_link_open(o, &l);
    if (code != 0) {
        return code;
    }
    lsc_device *d = lscctl_link_device(l);
    code = lscctl_set_arm(o, d);
    if (code != 0) {
        lscctl_link_close(l);
        return code;
    }
    lsc_play_result res = {.size = sizeof res};
    player_view v = {o, &res, a->count, isatty(STDERR_FILENO) && !o->verbose, false, true, 0};
    lscctl_catch_signal(SIGINT);
    int r = lsc_device_play(d, a, c, on_play_step, &v, &res);
    if (v.tty && res.frames > 0) {
        fputc('\n', stderr);
    }
    if (r == LSC_EINVAL && res.frames == 0) {
        /* the file (or --speed, --times) refused before anything was sent */
        lscctl_shown name;
        code = lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s: %s", lscctl_show(&name, path),
                           lsc_device_error(d));
    } else if (r != 0) {
        code = lscctl_link_check(l, r);
    } else {
        if (o->json) {
            print_summary(&v, &res);
        }
        if (lsc_device_kind_of(lscctl_link_device(l)) == LSC_DEVICE_SIM) {
            fprintf(stderr, "lscctl: play: --port sim plays on the virtual controller's own "
                            "clock: the %lu.%03lu s schedule took no time\n",
                    (unsigned long)(res.total_ms / 1000u), (unsigned long)(res.total_ms % 1000u));
        }
        if (res.stopped) {
            fprintf(stderr, "lscctl: play: stopped (Ctrl-C) after keyframe %lu; the servos "
                            "stay where they are\n",
                    (unsigned long)res.keyframe);
        }
        if (res.dropped > 0) {
            fprintf(stderr, "lscctl: play: %lu of %lu keyframes dropped\n",
                    (unsigned long)res.dropped, (unsigned long)a->count * o->times);
        }
    }
    lscctl_link_close(l);
    return code;
}

int lscctl_cmd_play(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    lsc_action a;
    if (o->times == 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--times 0: play takes 1..65535");
    }
    int code = lscctl_load_action(o, argv[0], &a);
    if (code != 0) {
        return code;
    }
    lsc_player_config c = {(uint16_t)o->speed, (uint16_t)o->times, (uint16_t)o->lead_ms,
                           (uint32_t)lscctl_baud(o)};
    lscctl_shown name;
    (void)lscctl_show(&name, argv[0]);
    if (a.count == 0) {
        code = lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s: no keyframes to play", name.text);
    } else { /* a HID report holds 19 servos: said before any port opens */
        code = lscctl_hid_move_bound(o, a.nservos, name.text);
    }
    if (code == 0) {
        code = o->dry_run ? print_schedule(o, argv[0], &a, &c) : play_on(o, argv[0], &a, &c);
    }
    lsc_action_free(&a);
    return code;
}
