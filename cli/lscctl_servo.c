/* lscctl servo: what only a bus servo has, on a bus of servos (--port
 * lx:PATH), through the library's bus client (lsc/lxclient.h: its safe
 * operations do every check) and the device's lines for its results
 * (lsc_device_lx_result). This file parses, refuses values out of the
 * document's ranges before anything is sent, and prints. */
#include "lscctl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lscctl_parse.h"
#include "lscctl_port.h"
#include "lsc/arm.h"
#include "lsc/bus.h"
#include "lsc/device.h"
#include "lsc/env.h"
#include "lsc/text.h"
#include "lsc/lxclient.h"

#define WHAT_MAX 96u

const char lscctl_help_servo[] =
    "Reads and sets what only a serial bus servo has (LX-16A, LX-15D, LX-224:\n"
    "the xArm's servos, or servos on a BusLinker), on a bus of servos: --port\n"
    "lx:PATH (115200 baud). A board (--port PATH, hid, sim) is refused: its\n"
    "servos are behind the board. Values outside the protocol's ranges are\n"
    "refused before anything is sent (exit 2).\n"
    "\nSubcommands:\n"
    "  scan [IDS...]         which ids answer (default: every id 0..253, about\n"
    "                        2 s); IDS as for read: 1-6, 1,3,5. One id a line\n"
    "                        (--json: {\"id\":N}); ids whose answers collide (two\n"
    "                        servos that share an id) are said on stderr. None\n"
    "                        answering: exit 3\n"
    "  info ID...            everything a servo tells: position, temperature,\n"
    "                        supply voltage, offset, limits, mode, torque, LED,\n"
    "                        alarms (--json: one object a servo)\n"
    "  id OLD NEW            give servo OLD the id NEW: refused (exit 2, nothing\n"
    "                        written) when NEW already answers, or OLD does not\n"
    "  id NEW                give the one servo on the bus the id NEW, whatever\n"
    "                        its id: refused (exit 2, nothing written) unless it\n"
    "                        is alone, proven by a broadcast and a whole scan\n"
    "  offset ID [DELTA] [--save]\n"
    "                        read the offset (-125..125, 0.24 degree a unit), or\n"
    "                        add DELTA to it: in effect at once, lost at power-off\n"
    "                        unless --save (which alone saves the one in effect)\n"
    "  limits ID [MIN MAX]   the angle limits, 0 <= MIN < MAX <= 1000\n"
    "  vin-limits ID [MIN_MV MAX_MV]\n"
    "                        the supply voltage limits, 4500 <= MIN < MAX <= 12000\n"
    "  temp-limit ID [C]     the temperature limit, 50..100 degrees C\n"
    "  mode ID [servo|motor [SPEED]]\n"
    "                        position control, or a motor turning at SPEED\n"
    "                        (-1000..1000, default 0)\n"
    "  torque ID [on|off]    the motor powered (a move powers it) or limp\n"
    "  led ID [on|off]       the LED\n"
    "  alarms ID [MASK]      the faults that flash the LED: 1 over temperature,\n"
    "                        2 supply voltage, 4 stalled (0..7)\n"
    "  replace JOINT --arm FILE\n"
    "                        a new servo for the arm's JOINT: connect it alone to\n"
    "                        the bus; it gets the joint's id and limits. Then\n"
    "                        connect the rest of the arm and press Enter: every\n"
    "                        joint must answer once (exit 3: one does not; 1:\n"
    "                        two share an id)\n"
    "Without the value, each prints what the servo has; with it, writes it and\n"
    "prints what the servo reads back. Ids 0..253. Kept at power-off: the id,\n"
    "a saved offset, the limits, the LED; lost: an offset not saved, motor\n"
    "mode, torque, the alarm mask.\n"
    "\nExamples:\n"
    "  lscctl --port lx:/dev/ttyUSB0 servo scan\n"
    "  lscctl --port lx:/dev/ttyUSB0 --json servo info 2\n"
    "  lscctl --port lx:/dev/ttyUSB0 servo id 1 3\n"
    "  lscctl --port lx:/dev/ttyUSB0 servo offset 1 15 --save\n"
    "  lscctl --port lx:/dev/ttyUSB0 servo mode 4 motor 300\n"
    "  lscctl --port lx:/dev/ttyUSB0 --arm xarm servo replace base\n";

/* What a subcommand takes after its ID (the words counted), and does. */
typedef enum sub {
    SUB_SCAN, SUB_INFO, SUB_ID, SUB_OFFSET, SUB_LIMITS, SUB_VIN, SUB_TEMP, SUB_MODE,
    SUB_TORQUE, SUB_LED, SUB_ALARMS, SUB_REPLACE
} sub;

typedef struct sub_spec {
    const char *name;
    sub which;
    int min_args, max_args; /* after the subcommand's name; -1: no limit */
    const char *usage;
} sub_spec;

static const sub_spec subs[] = {
    {"scan", SUB_SCAN, 0, -1, "scan [IDS...]"},
    {"info", SUB_INFO, 1, -1, "info ID..."},
    {"id", SUB_ID, 1, 2, "id [OLD] NEW"},
    {"offset", SUB_OFFSET, 1, 2, "offset ID [DELTA] [--save]"},
    {"limits", SUB_LIMITS, 1, 3, "limits ID [MIN MAX]"},
    {"vin-limits", SUB_VIN, 1, 3, "vin-limits ID [MIN_MV MAX_MV]"},
    {"temp-limit", SUB_TEMP, 1, 2, "temp-limit ID [C]"},
    {"mode", SUB_MODE, 1, 3, "mode ID [servo|motor [SPEED]]"},
    {"torque", SUB_TORQUE, 1, 2, "torque ID [on|off]"},
    {"led", SUB_LED, 1, 2, "led ID [on|off]"},
    {"alarms", SUB_ALARMS, 1, 2, "alarms ID [MASK]"},
    {"replace", SUB_REPLACE, 1, 1, "replace JOINT --arm FILE"},
};
#define NSUBS (sizeof subs / sizeof subs[0])

/* Everything parsed, before the port opens. */
typedef struct job {
    const sub_spec *s;
    uint8_t ids[LSC_LX_ID_MAX + 1u];
    size_t n;
    bool write;        /* a value was given */
    bool on;           /* torque, led; mode: motor */
    long a, b;         /* the values: delta; min, max; celsius; speed; mask; new id */
    lsc_arm *arm;      /* replace: the profile */
    const char *joint; /* replace: the joint */
} job;

static int usage(const lscctl_opts *o, const char *fmt, const char *arg)
{
    lscctl_shown shown;
    char line[256];
    (void)snprintf(line, sizeof line, fmt, arg != NULL ? lscctl_show(&shown, arg) : "");
    return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s; see 'lscctl servo --help'", line);
}

/* A whole number in min..max (a sign allowed when min < 0), or exit 2. */
static int number(const lscctl_opts *o, const char *s, long min, long max, const char *what,
                  long *out)
{
    char why[160];
    unsigned long v = 0;
    bool negative = s[0] == '-';
    unsigned long limit = negative ? (unsigned long)-min : (unsigned long)max;
    if ((negative && min >= 0) ||
        lscctl_parse_uint(negative ? s + 1 : s, limit, what, &v, why, sizeof why) != 0 ||
        (!negative && (long)v < min)) {
        lscctl_shown shown;
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s '%s' is out of range: use %ld..%ld", what,
                           lscctl_show(&shown, s), min, max);
    }
    *out = negative ? -(long)v : (long)v;
    return 0;
}

static int servo_id(const lscctl_opts *o, const char *s, uint8_t *id)
{
    long v = 0;
    int r = number(o, s, 0, LSC_LX_ID_MAX, "servo id", &v);
    *id = (uint8_t)v;
    return r;
}

static int on_off(const lscctl_opts *o, const char *s, const char *a, const char *b, bool *out)
{
    if (strcmp(s, a) == 0 || strcmp(s, b) == 0) {
        *out = strcmp(s, a) == 0;
        return 0;
    }
    lscctl_shown shown;
    return lscctl_fail(o, LSCCTL_EXIT_USAGE, "'%s': use %s or %s", lscctl_show(&shown, s), a, b);
}

/* The ids of scan's and info's arguments (lists as read takes them). */
static int id_lists(const lscctl_opts *o, int argc, char **argv, job *j)
{
    char why[256];
    uint8_t some[LSC_LX_ID_MAX + 1u];
    for (int i = 0; i < argc; i++) {
        int got = lsc_device_parse_ids(NULL, argv[i], some, sizeof some, why, sizeof why);
        if (got < 0) {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s", why);
        }
        for (int k = 0; k < got; k++) {
            if (some[k] > LSC_LX_ID_MAX) {
                return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                                   "servo id %u is out of range: bus servos have 0..253 (254 "
                                   "is the broadcast)",
                                   some[k]);
            }
            for (size_t m = 0; m < j->n; m++) {
                if (j->ids[m] == some[k]) {
                    return lscctl_fail(o, LSCCTL_EXIT_USAGE, "servo %u is given twice",
                                       some[k]);
                }
            }
            j->ids[j->n++] = some[k];
        }
    }
    return 0;
}

/* Parses the subcommand's arguments into j: exit 2 before anything opens. */
static int parse(const lscctl_opts *o, int argc, char **argv, job *j)
{
    const sub_spec *s = NULL;
    for (size_t i = 0; i < NSUBS; i++) {
        if (strcmp(argv[0], subs[i].name) == 0) {
            s = &subs[i];
        }
    }
    if (s == NULL) {
        return usage(o,
                     "unknown subcommand '%s': scan, info, id, offset, limits, vin-limits, "
                     "temp-limit, mode, torque, led, alarms or replace",
                     argv[0]);
    }
    j->s = s;
    argc--;
    argv++;
    if (argc < s->min_args || (s->max_args >= 0 && argc > s->max_args) ||
        ((s->which == SUB_LIMITS || s->which == SUB_VIN) && argc == 2)) {
        return usage(o, "usage: lscctl servo %s", s->usage);
    }
    if (o->save && s->which != SUB_OFFSET) {
        return usage(o, "--save is for servo offset%s", "");
    }
    if (s->which == SUB_SCAN || s->which == SUB_INFO) {
        return id_lists(o, argc, argv, j);
    }
    if (s->which == SUB_REPLACE) {
        char why[LSC_ARM_MESSAGE_MAX];
        if (o->arm == NULL) {
            return usage(o, "servo replace needs the arm's profile: --arm FILE%s", "");
        }
        if (lsc_arm_open(o->arm, &j->arm, why, sizeof why) != 0) {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s", why);
        }
        if (lsc_arm_find(j->arm, argv[0]) < 0) {
            return usage(o, "the arm profile has no joint '%s'", argv[0]);
        }
        j->joint = argv[0];
        return 0;
    }
    int r = 0;
    j->write = argc > 1;
    j->n = 1;
    if (s->which == SUB_ID) { /* id [OLD] NEW: a = the new id */
        j->write = true;
        j->n = (size_t)argc - 1u;
        r = argc == 2 ? servo_id(o, argv[0], &j->ids[0]) : 0;
        uint8_t id = 0;
        r = r != 0 ? r : servo_id(o, argv[argc - 1], &id);
        j->a = id;
        if (r == 0 && argc == 2 && j->ids[0] == id) {
            return usage(o, "servo %s has that id already: nothing to do", argv[0]);
        }
        return r;
    }
    r = servo_id(o, argv[0], &j->ids[0]);
    if (r != 0 || argc == 1) {
        j->write = j->write || (s->which == SUB_OFFSET && o->save);
        return r;
    }
    switch (s->which) {
    case SUB_OFFSET: return number(o, argv[1], -250, 250, "offset change", &j->a);
    case SUB_LIMITS:
        r = number(o, argv[1], 0, LSC_LX_POSITION_MAX, "angle limit", &j->a);
        r = r != 0 ? r : number(o, argv[2], 0, LSC_LX_POSITION_MAX, "angle limit", &j->b);
        break;
    case SUB_VIN:
        r = number(o, argv[1], LSC_LX_VIN_MIN, LSC_LX_VIN_MAX, "voltage limit (mV)", &j->a);
        r = r != 0 ? r
                   : number(o, argv[2], LSC_LX_VIN_MIN, LSC_LX_VIN_MAX, "voltage limit (mV)",
                            &j->b);
        break;
    case SUB_TEMP:
        return number(o, argv[1], LSC_LX_TEMP_LIMIT_MIN, LSC_LX_TEMP_LIMIT_MAX,
                      "temperature limit (C)", &j->a);
    case SUB_MODE:
        r = on_off(o, argv[1], "motor", "servo", &j->on);
        if (r == 0 && argc == 3 && !j->on) {
            return usage(o, "a speed is for motor mode: servo mode takes none ('%s')",
                         argv[2]);
        }
        return r != 0 || argc < 3 ? r
                                  : number(o, argv[2], -LSC_LX_SPEED_MAX, LSC_LX_SPEED_MAX,
                                           "motor speed", &j->a);
    case SUB_TORQUE:
    case SUB_LED: return on_off(o, argv[1], "on", "off", &j->on);
    default: /* SUB_ALARMS */
        return number(o, argv[1], 0, LSC_LX_ALARM_ALL, "alarm mask", &j->a);
    }
    if (r == 0 && j->a >= j->b) {
        char line[64];
        (void)snprintf(line, sizeof line, "%ld %ld", j->a, j->b);
        return usage(o, "limits '%s': the first must be below the second", line);
    }
    return r;
}

/* ---- Talking ----------------------------------------------------------------------- */

typedef struct bus {
    const lscctl_opts *o;
    lscctl_link *l;
    lsc_device *d;
    lsc_lxclient *c;
} bus;

/* The outcome r of a bus client call for `what`, asking servo id: 0, or the
 * exit code after the device's line. */
static int result(bus *b, int r, const char *what, uint8_t id, lsc_lx_refusal why)
{
    return lscctl_link_check(b->l, lsc_device_lx_result(b->d, r, what, id, (int)why));
}

static void json_id(const char *key, uint8_t id, bool last)
{
    printf("\"%s\":%u%s", key, id, last ? "}\n" : ",");
}

static int scan(bus *b, const job *j)
{
    lsc_lx_scan found;
    int r = lsc_lxclient_scan(b->c, j->n > 0 ? j->ids : NULL, j->n, 0, &found);
    int code = result(b, r, "servo scan", 0, LSC_LX_DONE);
    if (code != 0) {
        return code;
    }
    for (unsigned id = 0; id <= LSC_LX_ID_MAX; id++) {
        if (lsc_lx_scan_found(&found, (uint8_t)id)) {
            if (b->o->json) {
                printf("{");
                json_id("id", (uint8_t)id, true);
            } else {
                printf("%u\n", id);
            }
        }
        if (lsc_lx_scan_garbled(&found, (uint8_t)id)) {
            fflush(stdout);
            fprintf(stderr,
                    "lscctl: servo scan: the answers at id %u collide (two servos may share "
                    "it: connect one at a time, servo id NEW)\n",
                    id);
        }
    }
    if (found.count == 0) {
        return lscctl_fail(b->o, LSCCTL_EXIT_TIMEOUT, "no servo answered on %s (%u ids asked)",
                           lsc_device_name(b->d), found.asked);
    }
    return 0;
}

static const char *onoff(bool on)
{
    return on ? "on" : "off";
}

static const char *tf(bool on)
{
    return on ? "true" : "false";
}

static int info(bus *b, const job *j)
{
    for (size_t i = 0; i < j->n; i++) {
        lsc_lx_info s;
        char what[WHAT_MAX];
        (void)snprintf(what, sizeof what, "servo info %u", j->ids[i]);
        int code = result(b, lsc_lxclient_info(b->c, j->ids[i], &s), what, j->ids[i],
                          LSC_LX_DONE);
        if (code != 0) {
            return code;
        }
        const char *mode = s.mode == LSC_LX_MODE_MOTOR ? "motor" : "servo";
        if (b->o->json) {
            printf("{\"id\":%u,\"position\":%d,\"temperature_c\":%u,\"vin_mv\":%u,"
                   "\"offset\":%d,\"limits\":[%u,%u],\"vin_limits_mv\":[%u,%u],"
                   "\"temp_limit_c\":%u,\"mode\":\"%s\",\"speed\":%d,\"torque\":%s,"
                   "\"led\":%s,\"alarms\":%u}\n",
                   s.id, s.position, s.temp_c, s.vin_mv, s.offset, s.limit_min, s.limit_max,
                   s.vin_min_mv, s.vin_max_mv, s.temp_limit_c, mode, s.speed, tf(s.torque),
                   tf(s.led), s.alarms);
        } else {
            printf("servo %u: position %d, %u C, %u mV, offset %d, limits %u..%u, "
                   "voltage limits %u..%u mV, temperature limit %u C, %s mode (speed %d), "
                   "torque %s, LED %s, alarms %u\n",
                   s.id, s.position, s.temp_c, s.vin_mv, s.offset, s.limit_min, s.limit_max,
                   s.vin_min_mv, s.vin_max_mv, s.temp_limit_c, mode, s.speed, onoff(s.torque),
                   onoff(s.led), s.alarms);
        }
    }
    return 0;
}

static int set_id(bus *b, const job *j)
{
    lsc_lx_refusal why = LSC_LX_DONE;
    uint8_t old = j->ids[0], id = (uint8_t)j->a;
    char what[WHAT_MAX];
    int r;
    if (j->n == 1) {
        (void)snprintf(what, sizeof what, "servo id %u %u", old, id);
        r = lsc_lxclient_change_id(b->c, old, id, &why);
    } else {
        (void)snprintf(what, sizeof what, "servo id %u (the one servo on the bus)", id);
        r = lsc_lxclient_set_id_alone(b->c, id, 0, &old, &why);
    }
    int code = result(b, r, what, id, why);
    if (code != 0) {
        return code;
    }
    if (b->o->json) {
        printf("{\"old_id\":%u,\"id\":%u}\n", old, id);
    } else {
        printf("servo %u is now servo %u\n", old, id);
    }
    return 0;
}

/* Prints servo id's `key` setting: text "servo ID: TEXT", JSON {"id":ID,JSON}. */
static void print_setting(const bus *b, uint8_t id, const char *text, const char *json)
{
    if (b->o->json) {
        printf("{\"id\":%u,%s}\n", id, json);
    } else {
        printf("servo %u: %s\n", id, text);
    }
}

/* A setting written, then read back: read r's value differs: exit 1. */
static int differs(bus *b, const char *what)
{
    return lscctl_fail(b->o, LSCCTL_EXIT_FAIL,
                       "%s on %s: written, but the servo reads back another value (its "
                       "range, or a servo that does not take it)",
                       what, lsc_device_name(b->d));
}

static int offset(bus *b, const job *j)
{
    uint8_t id = j->ids[0];
    int8_t now = 0;
    lsc_lx_refusal why = LSC_LX_DONE;
    char what[WHAT_MAX];
    int r;
    if (j->write) {
        (void)snprintf(what, sizeof what, "servo offset %u %ld%s", id, j->a,
                       b->o->save ? " --save" : "");
        r = lsc_lxclient_offset_change(b->c, id, (int)j->a, b->o->save, &now, &why);
    } else {
        (void)snprintf(what, sizeof what, "servo offset %u", id);
        r = lsc_lxclient_read_offset(b->c, id, &now);
    }
    int code = result(b, r, what, id, why);
    if (code == 0) {
        char text[64], json[64];
        (void)snprintf(text, sizeof text, "offset %d%s", now,
                       b->o->save ? " (saved)" : j->write ? " (not saved)" : "");
        (void)snprintf(json, sizeof json, "\"offset\":%d", now);
        print_setting(b, id, text, json);
    }
    return code;
}

/* limits, vin-limits, temp-limit, alarms: written when given, then read. */
static int setting(bus *b, const job *j)
{
    uint8_t id = j->ids[0], c8 = 0;
    uint16_t lo = 0, hi = 0;
    char what[WHAT_MAX], text[96], json[96];
    int r = 0;
    (void)snprintf(what, sizeof what, "servo %s %u", j->s->name, id);
    if (j->write) {
        switch (j->s->which) {
        case SUB_LIMITS:
            r = lsc_lxclient_write_limits(b->c, id, (uint16_t)j->a, (uint16_t)j->b);
            break;
        case SUB_VIN:
            r = lsc_lxclient_write_vin_limits(b->c, id, (uint16_t)j->a, (uint16_t)j->b);
            break;
        case SUB_TEMP: r = lsc_lxclient_write_temp_limit(b->c, id, (uint8_t)j->a); break;
        default: r = lsc_lxclient_write_alarms(b->c, id, (uint8_t)j->a); break;
        }
    }
    int code = result(b, r, what, id, LSC_LX_DONE);
    if (code != 0) {
        return code;
    }
    switch (j->s->which) {
    case SUB_LIMITS: r = lsc_lxclient_read_limits(b->c, id, &lo, &hi); break;
    case SUB_VIN: r = lsc_lxclient_read_vin_limits(b->c, id, &lo, &hi); break;
    case SUB_TEMP: r = lsc_lxclient_read_temp_limit(b->c, id, &c8); break;
    default: r = lsc_lxclient_read_alarms(b->c, id, &c8); break;
    }
    code = result(b, r, what, id, LSC_LX_DONE);
    if (code != 0) {
        return code;
    }
    bool two = j->s->which == SUB_LIMITS || j->s->which == SUB_VIN;
    if (j->write && (two ? lo != j->a || hi != j->b : c8 != j->a)) {
        return differs(b, what);
    }
    switch (j->s->which) {
    case SUB_LIMITS:
        (void)snprintf(text, sizeof text, "limits %u..%u", lo, hi);
        (void)snprintf(json, sizeof json, "\"limits\":[%u,%u]", lo, hi);
        break;
    case SUB_VIN:
        (void)snprintf(text, sizeof text, "voltage limits %u..%u mV", lo, hi);
        (void)snprintf(json, sizeof json, "\"vin_limits_mv\":[%u,%u]", lo, hi);
        break;
    case SUB_TEMP:
        (void)snprintf(text, sizeof text, "temperature limit %u C", c8);
        (void)snprintf(json, sizeof json, "\"temp_limit_c\":%u", c8);
        break;
    default:
        (void)snprintf(text, sizeof text, "alarms %u", c8);
        (void)snprintf(json, sizeof json, "\"alarms\":%u", c8);
        break;
    }
    print_setting(b, id, text, json);
    return 0;
}

/* mode, torque, led: written when given, then read. */
static int switches(bus *b, const job *j)
{
    uint8_t id = j->ids[0], mode = 0;
    int16_t speed = 0;
    bool on = false;
    char what[WHAT_MAX], text[96], json[96];
    int r = 0;
    (void)snprintf(what, sizeof what, "servo %s %u", j->s->name, id);
    if (j->write) {
        r = j->s->which == SUB_MODE
                ? lsc_lxclient_write_mode(b->c, id, j->on ? LSC_LX_MODE_MOTOR : LSC_LX_MODE_SERVO,
                                          (int16_t)j->a)
            : j->s->which == SUB_TORQUE ? lsc_lxclient_write_torque(b->c, id, j->on)
                                        : lsc_lxclient_write_led(b->c, id, j->on);
    }
    int code = result(b, r, what, id, LSC_LX_DONE);
    if (code != 0) {
        return code;
    }
    r = j->s->which == SUB_MODE     ? lsc_lxclient_read_mode(b->c, id, &mode, &speed)
        : j->s->which == SUB_TORQUE ? lsc_lxclient_read_torque(b->c, id, &on)
                                    : lsc_lxclient_read_led(b->c, id, &on);
    code = result(b, r, what, id, LSC_LX_DONE);
    if (code != 0) {
        return code;
    }
    if (j->s->which == SUB_MODE) {
        bool motor = mode == LSC_LX_MODE_MOTOR;
        if (j->write && (motor != j->on || (motor && speed != j->a))) {
            return differs(b, what);
        }
        (void)snprintf(text, sizeof text, "%s mode (speed %d)", motor ? "motor" : "servo",
                       speed);
        (void)snprintf(json, sizeof json, "\"mode\":\"%s\",\"speed\":%d",
                       motor ? "motor" : "servo", speed);
    } else {
        if (j->write && on != j->on) {
            return differs(b, what);
        }
        (void)snprintf(text, sizeof text, "%s %s", j->s->which == SUB_TORQUE ? "torque" : "LED",
                       onoff(on));
        (void)snprintf(json, sizeof json, "\"%s\":%s", j->s->which == SUB_TORQUE ? "torque" : "led",
                       tf(on));
    }
    print_setting(b, id, text, json);
    return 0;
}

/* replace: the new servo alone on the bus takes the joint's id and limits;
 * then, the rest of the arm connected (Enter on stdin), every joint must
 * answer once. */
static int replace(bus *b, const job *j)
{
    uint8_t old = 0, id = lsc_arm_joint(j->arm, (size_t)lsc_arm_find(j->arm, j->joint))->id;
    uint16_t lo = 0, hi = 0;
    int code = lscctl_link_check(b->l, lsc_device_lx_replace(b->d, j->arm, j->joint, &old, NULL));
    if (code == 0) {
        code = lscctl_link_check(b->l, lsc_device_lx_result(b->d,
                                                            lsc_lxclient_read_limits(b->c, id,
                                                                                     &lo, &hi),
                                                            "servo replace", id, LSC_LX_DONE));
    }
    if (code != 0) {
        return code;
    }
    printf("joint %s: servo %u is now servo %u, limits %u..%u\n", j->joint, old, id, lo, hi);
    fflush(stdout);
    fprintf(stderr, "lscctl: servo replace: connect the arm's other servos to the bus, then "
                    "press Enter: every joint must answer once\n");
    int ch;
    while ((ch = getchar()) != EOF && ch != '\n') {
    }
    if (ch == EOF) {
        return lscctl_fail(b->o, LSCCTL_EXIT_OK,
                           "the arm was not scanned (no input): check it with lscctl servo "
                           "scan");
    }
    int n = lsc_device_lx_check_arm(b->d, j->arm);
    code = lscctl_link_check(b->l, n);
    if (code == 0) {
        printf("every joint answers once (%d joints)\n", n);
    }
    return code;
}

static int run(bus *b, const job *j)
{
    switch (j->s->which) {
    case SUB_REPLACE: return replace(b, j);
    case SUB_SCAN: return scan(b, j);
    case SUB_INFO: return info(b, j);
    case SUB_ID: return set_id(b, j);
    case SUB_OFFSET: return offset(b, j);
    case SUB_MODE:
    case SUB_TORQUE:
    case SUB_LED: return switches(b, j);
    default: return setting(b, j);
    }
}

static int not_a_bus(const lscctl_opts *o, const char *port)
{
    lscctl_shown shown;
    return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                       "%s is no bus of servos: servo talks to serial bus servos directly, on "
                       "--port lx:PATH (a BusLinker or USB-serial adapter on the servos' bus); "
                       "nothing was sent",
                       lscctl_show(&shown, port));
}

/* Runs j on the bus of --port. */
static int on_bus(const lscctl_opts *o, const job *j)
{
    int code;
    lsc_device_kind kind;
    if (lsc_device_kind_of_name(o->port, &kind) == 0 && kind != LSC_DEVICE_LX) {
        return not_a_bus(o, o->port != NULL ? o->port : "");
    }
    if (o->dry_run) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "servo reads what the servos answer: --dry-run cannot show it");
    }
    bus b = {o, NULL, NULL, NULL};
    code = lscctl_link_open(o, &b.l);
    if (code != 0) {
        return code;
    }
    b.d = lscctl_link_device(b.l);
    b.c = lsc_device_lxclient(b.d);
    if (b.c == NULL && lsc_device_kind_of(b.d) == LSC_DEVICE_LSCD) { /* the bus is lscd's */
        lscctl_shown shown;
        code = lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "%s is reached through lscd, which passes moves and reads to a bus "
                           "but not servo's commands: stop that lscd for them; nothing was sent",
                           lscctl_show(&shown, o->port != NULL ? o->port : lsc_device_name(b.d)));
    } else if (b.c == NULL) { /* discovery found a board */
        code = not_a_bus(o, lsc_device_name(b.d));
    } else {
        if (!o->timeout_set) { /* a servo answers within a few ms: the bus client's own */
            lsc_device_set_timeout(b.d, LSC_LXCLIENT_TIMEOUT_MS);
        }
        code = run(&b, j);
    }
    lscctl_link_close(b.l);
    return code;
}

int lscctl_cmd_servo(const lscctl_opts *o, int argc, char **argv)
{
    job j;
    memset(&j, 0, sizeof j);
    int code = parse(o, argc, argv, &j);
    if (code == 0) {
        code = on_bus(o, &j);
    }
    lsc_arm_free(j.arm);
    return code;
}
