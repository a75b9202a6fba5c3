/* lscctl: every command of the LSC servo controller protocol from the shell.
 * This file: the command table, option parsing, help and dispatch. */
#include "lscctl.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lscctl_parse.h"
#include "lsc/calibrated.h"
#include "lsc/device.h"
#include "lsc/env.h"
#include "lsc/lscd.h"

#ifndef LSC_VERSION
#define LSC_VERSION "unknown"
#endif

/* Options: global ones anywhere, command ones after the command's name. */
enum {
    OPT_PORT, OPT_BAUD, OPT_TIMEOUT, OPT_JSON, OPT_DRY_RUN, OPT_VERBOSE, OPT_HELP,
    OPT_VERSION, OPT_TIME, OPT_TIMES, OPT_WAIT, OPT_COUNT, OPT_FORCE, OPT_FROM,
    OPT_SPEED, OPT_LEAD, OPT_IDS, OPT_EVERY,
    OPT_ARM, OPT_TOLERANCE, OPT_STRICT, OPT_HID_ID, OPT_GROUP, OPT_FROM_ARM, OPT_TO_ARM,
    OPT_DEG_SPEED, OPT_PITCH, OPT_ROLL, OPT_LINE, OPT_STEP, OPT_CALIB_STEP, OPT_OUT, OPT_CHECK,
    OPT_SAVE
};
#define GLOBAL 0u /* scope of the global options */
#define C_MOVE (1u << 0)
#define C_RUN (1u << 1)
#define C_MONITOR (1u << 2)
#define C_SEND (1u << 3)
#define C_DECODE (1u << 4)
#define C_RECORD (1u << 5)
#define C_PLAY (1u << 6)
#define C_CONVERT (1u << 7)
#define C_REACH (1u << 8)
#define C_CALIBRATE (1u << 9)
#define C_SERVO (1u << 10)

typedef struct option_spec {
    const char *name;
    char letter;      /* short form, or 0 */
    const char *value; /* placeholder of the value it takes, or NULL */
    unsigned scope;   /* GLOBAL, or the commands (C_...) that take it */
    int id;
} option_spec;

static const option_spec options[] = {
    {"port", 'p', "PORT", GLOBAL, OPT_PORT},
    {"baud", 'b', "N", GLOBAL, OPT_BAUD},
    {"timeout", 't', "MS", GLOBAL, OPT_TIMEOUT},
    {"json", 0, NULL, GLOBAL, OPT_JSON},
    {"dry-run", 'n', NULL, GLOBAL, OPT_DRY_RUN},
    {"verbose", 'v', NULL, GLOBAL, OPT_VERBOSE},
    {"help", 'h', NULL, GLOBAL, OPT_HELP},
    {"version", 'V', NULL, GLOBAL, OPT_VERSION},
    {"arm", 0, "FILE", GLOBAL, OPT_ARM},
    {"hid-id", 0, "VID:PID", GLOBAL, OPT_HID_ID},
    /* command options, in the order their usage lines show them */
    {"ids", 0, "LIST", C_RECORD, OPT_IDS},
    {"every", 0, "MS", C_RECORD, OPT_EVERY},
    {"pitch", 0, "DEG", C_REACH, OPT_PITCH},
    {"roll", 0, "DEG", C_REACH, OPT_ROLL},
    {"time", 0, "MS", C_MOVE | C_RECORD | C_REACH, OPT_TIME},
    {"speed", 0, "DEG/S", C_MOVE | C_REACH, OPT_DEG_SPEED},
    {"line", 0, NULL, C_REACH, OPT_LINE},
    {"step", 0, "MM", C_REACH, OPT_STEP},
    {"step", 0, "STEP", C_CALIBRATE, OPT_CALIB_STEP},
    {"out", 0, "FILE", C_CALIBRATE, OPT_OUT},
    {"check", 0, NULL, C_CALIBRATE, OPT_CHECK},
    {"save", 0, NULL, C_SERVO, OPT_SAVE},
    {"wait", 0, NULL, C_RUN | C_MOVE | C_REACH, OPT_WAIT},
    {"tolerance", 0, "N", C_MOVE | C_REACH, OPT_TOLERANCE},
    {"strict", 0, NULL, C_MOVE | C_REACH, OPT_STRICT},
    {"count", 0, "N", C_MONITOR | C_RECORD, OPT_COUNT},
    {"speed", 0, "PCT", C_PLAY, OPT_SPEED},
    {"times", 0, "N", C_RUN | C_PLAY, OPT_TIMES},
    {"lead", 0, "MS", C_PLAY, OPT_LEAD},
    {"group", 0, "N", C_PLAY | C_CONVERT, OPT_GROUP},
    {"from-arm", 0, "FILE", C_CONVERT, OPT_FROM_ARM},
    {"to-arm", 0, "FILE", C_CONVERT, OPT_TO_ARM},
    {"force", 0, NULL, C_SEND, OPT_FORCE},
    {"from", 0, "host|controller", C_DECODE, OPT_FROM},
};

typedef struct command {
    const char *name;
    unsigned scope;   /* C_... bit for its own options, or 0 */
    int min_args, max_args; /* max -1: no fixed limit */
    int (*run)(const lscctl_opts *o, int argc, char **argv);
    const char *args;    /* its arguments; the usage adds its options from the table
                            above (usage()), so that the two cannot drift apart */
    const char *summary;
    const char *message; /* the protocol message it sends, or NULL */
    const char *help;    /* what it does, its options, examples */
} command;

static const command commands[] = {
    {"move", C_MOVE, 1, -1, lscctl_cmd_move, "ID:POS...",
     "move servos to positions", "servo_move",
     "Moves each servo ID to position POS, all arriving together after MS\n"
     "milliseconds (default 1000). LSC boards take positions 500..2500 (pulse\n"
     "width in microseconds), xArm bus servos 0..1000. Ids 0..255, positions and\n"
     "time 0..65535, decimal or 0x-hex; at most 83 servos per command.\n"
     "With --arm FILE (or $LSC_ARM: an arm profile, docs/arm-profile.md), ID may\n"
     "be a joint's name and POS an angle: base:30deg, 2:-15.5deg, gripper:700.\n"
     "A value outside a joint's limits is refused (exit 2, nothing sent).\n"
     "\nOptions:\n  --time MS   how long the move takes (default 1000)\n"
     "  --speed DEG/S  instead of --time: the joint that turns the most turns\n"
     "              at DEG/S degrees a second, from where the servos were last\n"
     "              sent or read (read first when unknown; needs --arm)\n"
     "  --wait      return when the time has passed and the servos read back\n"
     "              within the tolerance of their targets (exit 3 if not within\n"
     "              --timeout after the time; boards that do not answer position\n"
     "              reads: when the time has passed). A servo that stops short\n"
     "              (a gripper holding something: its reads stay within 3 for\n"
     "              200 ms) ends the wait at once: stderr says where it stopped\n"
     "              (--json: a \"stopped\" line on stdout); exit 0\n"
     "  --strict    with --wait, a servo that stops short is an error (exit 3)\n"
     "  --tolerance N  positions off target --wait accepts (default 10)\n"
     "\nExamples:\n  lscctl move 1:1500                 servo 1 to 1500 in 1 s\n"
     "  lscctl move --time 500 1:2000 2:1200\n"
     "  lscctl -n move 1:2000              print the frame, send nothing\n"
     "  lscctl move $(lscctl read 1 2)     put servos back where they were read\n"
     "  lscctl --arm examples/arms/xarm.conf move base:30deg shoulder:-20deg\n"
     "  lscctl --arm examples/arms/xarm.conf move --speed 90 base:45deg\n"},
    {"where", 0, 0, 0, lscctl_cmd_where, "",
     "print where the grasp point is", "mult_servo_pos_read",
     "Reads the joints of the arm profile's chain (--arm FILE or $LSC_ARM, a\n"
     "profile with chain: and links: lines, docs/kinematics.md) and prints\n"
     "where they put the grasp point: x, y, z in millimetres (origin on the\n"
     "table under the base's axis, z up, x forward with the base at 0) and the\n"
     "hand's pitch (0 forward, -90 straight down), and a line for each joint\n"
     "within 5 degrees of an end of its limits. --json gives x_mm, y_mm, z_mm,\n"
     "pitch_deg, the joints' angles and near_end ({\"shoulder\":\"upper\"}).\n"
     "\nExamples:\n  lscctl --arm examples/arms/xarm.conf where\n"
     "  lscctl --arm examples/arms/xarm.conf --json where\n"},
    {"reach", C_REACH, 3, 3, lscctl_cmd_reach, "X Y Z",
     "move the grasp point to X Y Z (mm)", "servo_move",
     "Moves the grasp point to X Y Z (millimetres, the frame of 'where')\n"
     "through the arm profile's geometry: the joints' angles nearest the\n"
     "current ones that put it there. Out of reach, or reachable only beyond a\n"
     "joint's limits: exit 2, nothing sent, the message says by how much or\n"
     "which joint; refused at a given --pitch, it lists the pitches that do\n"
     "reach the point. Without --pitch, the pitch nearest the hand's current\n"
     "one that reaches the point is taken, over the whole circle.\n"
     "\nOptions:\n  --pitch DEG  the hand's angle from the horizontal (-90 down)\n"
     "  --roll DEG   the wrist roll's angle (default: where it is)\n"
     "  --time MS    how long the move takes (default 1000)\n"
     "  --speed DEG/S  instead of --time: the joint that turns the most turns\n"
     "               at DEG/S degrees a second\n"
     "  --line       keep the grasp point on the straight line from where it is:\n"
     "               waypoints every --step MM, all checked first\n"
     "  --step MM    --line's waypoints at most MM apart (default 5)\n"
     "  --wait       return when the servos read back at their targets, as\n"
     "               move --wait: a joint that stops short (against an obstacle)\n"
     "               ends the wait at once, said on stderr; exit 0\n"
     "  --tolerance N  positions off target --wait accepts (default 10)\n"
     "  --strict     with --wait, a joint that stops short is an error (exit 3)\n"
     "\nExamples:\n  lscctl --arm examples/arms/xarm.conf reach 200 0 100 --pitch -45\n"
     "  lscctl --arm examples/arms/xarm.conf reach 150 150 80 --line --speed 30\n"},
    {"calibrate", C_CALIBRATE, 0, 3, lscctl_cmd_calibrate, "[X Y Z]",
     "make the arm profile right for the arm in hand", "mult_servo_pos_read",
     "Finds each joint's zero and direction, and where the gripper opens and\n"
     "closes, on the arm in hand (a servo horn a tooth off, a servo mounted the\n"
     "other way round, a replaced servo), and writes the arm profile with them:\n"
     "offset= and dir= on each joint of the chain, open=, closed= and the limits\n"
     "on the gripper. Nothing is written into the servos: the arm does not jump\n"
     "at power-up. Without --step it walks you through the poses: the servos go\n"
     "limp, you hold the arm (a) straight up, every joint at 0 degrees, (b) every\n"
     "joint leaned 20 degrees or more its positive way, (c) the gripper closed,\n"
     "(d) open, pressing Enter at each (q quits without writing); then the servos\n"
     "hold where they are. A joint leaned less than 5 degrees is asked again.\n"
     "  --arm NAME   the profile to start from (the first time): xarm, or a file\n"
     "  --out FILE   where the result goes; default $XDG_CONFIG_HOME/lsc/arms/KEY.conf\n"
     "               (~/.config/...), KEY naming the controller (hid-SERIAL for a HID\n"
     "               controller, port- and a serial port's /dev/serial/by-id name),\n"
     "               where every lsc program looks for it. A result that exists is\n"
     "               continued (remove it to start over).\n"
     "  --step STEP  one reading, for scripts: home, lean, gripper-closed or\n"
     "               gripper-open (the servos' power is left as it is)\n"
     "  --check X Y Z  with the grasp point held on a point you measured (mm, the\n"
     "               frame of 'where'): how far 'where' is from it\n"
     "\nExamples:\n  lscctl --port hid calibrate --arm examples/arms/xarm.conf\n"
     "  lscctl calibrate --step home --arm examples/arms/xarm.conf --out my-arm.conf\n"
     "  lscctl --arm my-arm.conf calibrate --check 200 0 50\n"},
    {"run", C_RUN, 1, 1, lscctl_cmd_run, "GROUP",
     "run an action group", "action_group_run",
     "Runs action group GROUP (0..255) N times (default 1; 0 = forever).\n"
     "With --wait, returns only when the controller reports that the group\n"
     "completed or was stopped, and prints that report (a stop reported\n"
     "before the controller said GROUP started is the group it replaced).\n"
     "A board reports a group's start at once; one that has no such group\n"
     "ignores the run: when no start came within about a second (the frames'\n"
     "time on the line plus the reply timeout, at most 1000 ms), --wait says\n"
     "the group never started (exit 5).\n"
     "\nOptions:\n  --times N   how many times (0..65535, 0 = loop forever)\n"
     "  --wait      wait for the group to complete or stop (no time limit\n"
     "              unless --timeout is given)\n"
     "\nExamples:\n  lscctl run 8                 run group 8 once\n"
     "  lscctl run 2 --times 0       loop group 2 until 'lscctl stop'\n"
     "  lscctl run 8 --times 3 --wait --json\n"},
    {"stop", 0, 0, 0, lscctl_cmd_stop, "", "stop the running action group", "action_group_stop",
     "Stops the running action group (no effect if none runs).\n"
     "\nExample:\n  lscctl stop\n"},
    {"halt", 0, 0, 0, lscctl_cmd_halt, "", "stop everything: groups and moving servos",
     "action_group_stop, mult_servo_pos_read, servo_move",
     "Stops everything at once: sends action_group_stop (a running action group\n"
     "stops), then reads where every servo is and moves each there, so that a\n"
     "move under way stops where the servo is and every servo holds its\n"
     "position (unloaded ones are powered again). Every servo: the arm\n"
     "profile's joints (--arm FILE or $LSC_ARM), else every id the controller\n"
     "kind has (a HID controller: 1..6; a serial port, lscd or sim: 1..32). It\n"
     "takes the stop, one position read and one move on the line. A joint\n"
     "beyond its limits (moved there by hand) is held where it is, and said so\n"
     "on stderr (exit 0). Through lscd, halt is never refused for another\n"
     "client's lease, and a play through lscd ends at once. Boards that do not\n"
     "answer position reads: the group is stopped, the servos go on to their\n"
     "last targets (exit 3).\n"
     "\nExamples:\n  lscctl halt\n"
     "  lscctl --arm examples/arms/xarm.conf halt\n"},
    {"hold", 0, 0, -1, lscctl_cmd_hold, "[ID...]", "hold servos where they are",
     "mult_servo_pos_read, servo_move",
     "Reads where servos ID... are and moves each there: they hold their\n"
     "positions (unloaded ones are powered again, moving ones stop). Without\n"
     "ID: all (as for halt). ID as for unload: ids, joint names with --arm,\n"
     "lists like 1-6 or 1,3-5, or all. A joint beyond its limits is held where\n"
     "it is, and said so on stderr (exit 0); moving it further out stays\n"
     "refused.\n"
     "\nExamples:\n  lscctl --port sim hold 1-6\n"
     "  lscctl --arm examples/arms/xarm.conf hold gripper\n"},
    {"speed", 0, 2, 2, lscctl_cmd_speed, "GROUP|all PERCENT",
     "set an action group's speed", "action_group_speed",
     "Sets the speed at which action group GROUP (or every group: all) runs\n"
     "from now on, as PERCENT of its original speed: 100 is the original speed,\n"
     "200 twice as fast, 50 half (1..65535; 0 is refused). It starts nothing\n"
     "(see 'run'). The controller forgets it at power-off.\n"
     "\nExamples:\n  lscctl speed 8 50      group 8 at half speed\n"
     "  lscctl speed all 300   every group three times as fast\n"},
    {"battery", 0, 0, 0, lscctl_cmd_battery, "",
     "read the battery voltage", "get_battery_voltage",
     "Asks the controller for its battery voltage and prints it in volts and\n"
     "millivolts (JSON: {\"millivolts\":7500,\"volts\":7.500,...}).\n"
     "\nExamples:\n  lscctl battery          7.500 V (7500 mV)\n"
     "  lscctl --json battery\n"},
    {"unload", 0, 1, -1, lscctl_cmd_unload, "ID...", "power off servos", "mult_servo_unload",
     "Powers off the servos ID...: they turn freely by hand until their next\n"
     "move. Ids 0..255, all different. With --arm FILE (or $LSC_ARM), ID may be\n"
     "a joint's name. An ID may be a list: ranges and commas (1-6, 1,3-5), or\n"
     "all: the arm profile's joints, else every id the controller kind has (a\n"
     "HID controller: 1..6; a serial port, lscd or sim: 1..32).\n"
     "\nExamples:\n  lscctl unload 1 2 3\n  lscctl --port sim unload 1-6\n"
     "  lscctl --arm examples/arms/xarm.conf unload gripper wrist\n"},
    {"read", 0, 1, -1, lscctl_cmd_read, "ID...", "read servo positions", "mult_servo_pos_read",
     "Asks the controller for the positions of servos ID... and prints one\n"
     "ID:POS per line, in the order asked (the form 'move' takes). With --arm\n"
     "FILE (or $LSC_ARM), ID may be a joint's name and joints print as\n"
     "NAME:ANGLEdeg; --json then gives the position and the degrees. An ID may\n"
     "be a list, as for unload: 1-6, 1,3-5 or all.\n"
     "\nExamples:\n  lscctl read 1 2 3\n  lscctl --json read 1 2 3\n"
     "  lscctl --port sim read 1-3\n"
     "  lscctl --arm examples/arms/xarm.conf read base shoulder\n"},
    {"wait", 0, 0, 0, lscctl_cmd_wait, "",
     "wait for the running group to end", NULL,
     "Waits until the controller reports that an action group completed\n"
     "(action_group_complete) or was stopped (action_group_stop), and prints\n"
     "that report. No time limit unless --timeout is given (then exit 3).\n"
     "It hears only what arrives while it has the port open: a group that\n"
     "ends before 'wait' opens the port is missed (then it waits on). To run\n"
     "a group and wait for its end, use 'lscctl run GROUP --wait' instead.\n"
     "\nExamples:\n  lscctl wait                  another program started a group\n"
     "  lscctl --timeout 30000 wait\n"},
    {"monitor", C_MONITOR, 0, 0, lscctl_cmd_monitor, "",
     "print notifications as they arrive", NULL,
     "Prints the notifications the controller sends on its own, one per line:\n"
     "a group started (action_group_run), completed (action_group_complete) or\n"
     "was stopped (action_group_stop). Other frames (replies to other programs,\n"
     "noise) are not shown; -v traces them. Runs until Ctrl-C, or until N\n"
     "notifications with --count N.\n"
     "\nOptions:\n  --count N   stop after N notifications\n"
     "\nExamples:\n  lscctl monitor\n  lscctl --json monitor --count 2\n"},
    {"send", C_SEND, 1, -1, lscctl_cmd_send, "CMD [BYTE...]",
     "send a raw frame", NULL,
     "Sends the frame 55 55 LEN CMD BYTE... (LEN computed). Values 0..255,\n"
     "decimal or 0x-hex. Commands 8 and 27 are refused unless --force: on xArm\n"
     "firmware 8 erases the action groups and 27 writes a setting (such as the\n"
     "servo id) to every servo on the bus at once.\n"
     "\nOptions:\n  --force     allow commands 8 and 27\n"
     "\nExamples:\n  lscctl send 7                       same as 'lscctl stop'\n"
     "  lscctl -n send 0x0B 0xFF 0x2C 0x01  print 55 55 05 0B FF 2C 01\n"},
    {"decode", C_DECODE, 0, -1, lscctl_cmd_decode, "[HEX...]",
     "decode hex into frames (no port)", NULL,
     "Decodes the hex bytes given as arguments, or read from standard input if\n"
     "there are none, into frames: one line each, and one line for any bytes\n"
     "that are not a valid frame (then exit 1). Hex may be spaced or not, any\n"
     "case, in one argument or many. Without --from, each frame is taken as\n"
     "sent by the only side that sends it (the host for run and stop).\n"
     "\nOptions:\n  --from DIR  host or controller: who sent the bytes\n"
     "\nExamples:\n  lscctl decode 55 55 02 07\n"
     "  lscctl decode --from controller 5555040F4C1D\n"
     "  echo '55 55 05 08 08 01 00' | lscctl --json decode\n"},
    {"record", C_RECORD, 1, 1, lscctl_cmd_record, "FILE",
     "record keyframes posed by hand", "mult_servo_unload, mult_servo_pos_read",
     lscctl_help_record},
    {"play", C_PLAY, 1, 1, lscctl_cmd_play, "FILE",
     "play an action file", "servo_move", lscctl_help_play},
    {"convert", C_CONVERT, 2, 2, lscctl_cmd_convert, "IN OUT",
     "convert an action file (no port)", NULL, lscctl_help_convert},
    {"offset", 0, 1, -1, lscctl_cmd_offset, "read ID... | offset set ID VALUE",
     "read or adjust servo offsets (xArm)", NULL,
     "Reads the offsets of servos ID... (servo_offset_read, command 23) and\n"
     "prints ID:OFFSET per line, or sets servo ID's offset to VALUE (-128..127,\n"
     "servo_offset_adjust, command 24). These are the xArm firmware's commands,\n"
     "beyond the LSC protocol document and known only from two public projects:\n"
     "LSC-6/16/32 boards may not answer (a read then times out: exit 3).\n"
     "An offset is in the servo's position units (0.24 degree a unit on the\n"
     "xArm's bus servos). It is not saved: the servo forgets it at power-off\n"
     "(saving is command 22, known from one project only; lscctl does not\n"
     "send it). With --arm FILE (or $LSC_ARM), ID may be a joint's name.\n"
     "\nExamples:\n  lscctl offset read 1 2 3 4 5 6\n  lscctl offset set 6 -10\n"
     "  lscctl --arm examples/arms/xarm.conf offset set base -10\n"},
    {"servo", C_SERVO, 1, -1, lscctl_cmd_servo, "SUBCOMMAND [ARGS]",
     "a bus servo's id, offset, limits, mode (lx:PATH)", NULL, lscctl_help_servo},
    {"status", 0, 0, 0, lscctl_cmd_status, "",
     "show lscd's state (--port lscd:NAME)", NULL,
     "Asks the lscd daemon that shares a controller (--port lscd:NAME or\n"
     "lscd:PATH) for its state and prints one 'key: value' line per item: its\n"
     "port and device, whether the controller is present, its clients, the\n"
     "lease, the counters (lscd(8) lists them). Sends nothing to the controller.\n"
     "\nExamples:\n  lscctl --port lscd:ttyUSB0 status\n"
     "  lscctl --port lscd:/tmp/arm.sock --json status\n"},
    {"ports", 0, 0, 0, lscctl_cmd_ports, "",
     "list serial ports and HID controllers", NULL,
     "Lists serial ports with their description, USB VID:PID and serial\n"
     "number, marking the ones that look like a controller, then the xArm-type\n"
     "controllers on USB HID (0483:5750) with the --port that opens each.\n"
     "\nExample:\n  lscctl ports\n"},
};
#define NCOMMANDS (sizeof commands / sizeof commands[0])

/* "NAME ARGS [--OPTION VALUE]...": c's usage, its options those of the option
 * table whose scope holds c's, in the table's order. */
static const char *usage(const command *c, char *buf, size_t cap)
{
    size_t n = (size_t)snprintf(buf, cap, "%s%s%s", c->name, *c->args ? " " : "", c->args);
    for (size_t i = 0; i < sizeof options / sizeof options[0] && n < cap; i++) {
        const option_spec *s = &options[i];
        if (s->scope != GLOBAL && (s->scope & c->scope) != 0) {
            n += (size_t)snprintf(buf + n, cap - n, " [--%s%s%s]", s->name, s->value ? " " : "",
                                  s->value ? s->value : "");
        }
    }
    return buf;
}
#define USAGE_MAX 160u /* room for the longest usage */

int lscctl_fail(const lscctl_opts *o, int code, const char *fmt, ...)
{
    va_list ap;
    fflush(stdout);
    fputs("lscctl: ", stderr);
    if (o != NULL && o->cmd != NULL) {
        fprintf(stderr, "%s: ", o->cmd);
    }
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return code;
}

static void print_help(void)
{
    printf("Usage: lscctl [OPTIONS] COMMAND [ARGS]\n"
           "Talk to an LSC servo controller (LSC-6/16/32, xArm) over a serial port or\n"
           "USB HID, through the lscd daemon that shares one, or to the built-in\n"
           "virtual controller (--port sim).\n\n"
           "Options (before or after the command):\n"
           "  -p, --port PORT    the controller, one of:\n"
           "                       a serial device path (/dev/ttyUSB0, a pty)\n"
           "                       hid (the one xArm on USB HID), hid:SERIAL, /dev/hidrawN\n"
           "                       sim: the built-in virtual controller\n"
           "                       lx:PATH: a bus of serial bus servos on serial port PATH\n"
           "                       lscd:NAME: the lscd serving it on $LSC_LSCD_DIR/NAME.sock\n"
           "                       (default directory /run/lsc); lscd:PATH: on socket PATH\n"
           "                     default: $LSC_PORT; else the one serial port or HID\n"
           "                     controller that looks like a controller. A port lscd\n"
           "                     holds is used through lscd.\n"
           "  -b, --baud N       baud rate (default 9600; a bus, lx:PATH: 115200)\n"
           "  -t, --timeout MS   reply timeout in milliseconds (default 1000; 1..86400000);\n"
           "                     wait, monitor and run --wait: no limit unless given\n"
           "      --json         one JSON object per line on stdout\n"
           "  -n, --dry-run      print the frame(s) that would be sent, as hex; open no port\n"
           "  -v, --verbose      trace every frame sent and received on stderr\n"
           "  -h, --help         this help; 'lscctl help COMMAND' for one command\n"
           "  -V, --version      print the version\n"
           "      --arm NAME|FILE\n"
           "                     arm profile: joint names, degrees and limits for move and\n"
           "                     read; joint names for unload, offset and record --ids;\n"
           "                     limits for play (default: $LSC_ARM, else the profile\n"
           "                     calibrated for the arm on the controller: calibrate;\n"
           "                     docs/arm-profile.md).\n"
           "                     A NAME (xarm, learm: no '/', no .conf) is NAME.conf in\n"
           "                     ~/.config/lsc/arms ($XDG_CONFIG_HOME), else among the\n"
           "                     installed ones ($LSC_ARMS_DIR, else PREFIX/share/lsc/arms)\n"
           "      --hid-id VID:PID\n"
           "                     also accept a USB HID device with these ids (hex) as a\n"
           "                     controller, besides 0483:5750 (default: $LSC_HID_ID)\n\n"
           "Commands:\n");
    for (size_t i = 0; i < NCOMMANDS; i++) {
        char buf[USAGE_MAX];
        const char *line = usage(&commands[i], buf, sizeof buf);
        /* a usage too long for its column gets a line of its own */
        printf(strlen(line) > 32 ? "  %s\n%36s%s\n" : "  %-32s  %s%s\n", line, "",
               commands[i].summary);
    }
    printf("\nNumbers are decimal or 0x-hex. Exit status: 0 done; 1 failed talking to\n"
           "the controller (decode: invalid bytes); 2 invalid command line, nothing\n"
           "sent; 3 no reply within the timeout (--port sim: also a wait that could\n"
           "never end); 4 port busy (another program holds it), nothing sent; 5 run\n"
           "--wait: the group never started (the board has no such group).\n\n"
           "Environment: LSC_PORT, LSC_ARM, LSC_HID_ID (the defaults of --port, --arm,\n"
           "--hid-id); LSC_LSCD_DIR (where lscd:NAME's socket is, default /run/lsc);\n"
           "LSC_ARMS_DIR (where --arm NAME's installed profiles are).\n\n"
           "Examples:\n"
           "  lscctl --port sim move --time 500 1:2000 2:1200\n"
           "  lscctl --port /dev/ttyUSB0 battery\n"
           "  lscctl --port hid read 1 2 3 4 5 6\n"
           "  lscctl --port lscd:ttyUSB0 read 1 2  through lscd (see lscd(8))\n"
           "  lscctl -n run 8 --times 2            print 55 55 05 06 08 02 00\n"
           "  lscctl decode 55 55 04 0F 4C 1D\n"
           "  export LSC_PORT=sim; lscctl run 8 --wait\n");
}

static void print_command_help(const command *c)
{
    char buf[USAGE_MAX];
    printf("Usage: lscctl [OPTIONS] %s\n%c%s", usage(c, buf, sizeof buf),
           toupper((unsigned char)c->summary[0]),
           c->summary + 1);
    if (c->message != NULL) {
        printf(" (%s)", c->message);
    }
    printf(".\n\n%s", c->help);
    printf("\nGlobal options (-p PORT, -t MS, --json, -n, -v): see 'lscctl --help'.\n");
}

static const command *find_command(const char *name)
{
    for (size_t i = 0; i < NCOMMANDS; i++) {
        if (strcmp(commands[i].name, name) == 0) {
            return &commands[i];
        }
    }
    return NULL;
}

/* The option named name[0..len) (or with the short form letter): of two of
 * one name (--speed: play's percent, move's and reach's degrees a second),
 * the one command c takes. */
static const option_spec *find_option(const char *name, size_t len, char letter,
                                      const command *c)
{
    const option_spec *found = NULL;
    for (size_t i = 0; i < sizeof options / sizeof options[0]; i++) {
        const option_spec *s = &options[i];
        if (name != NULL ? strlen(s->name) == len && strncmp(s->name, name, len) == 0
                         : s->letter != 0 && s->letter == letter) {
            if (found == NULL || (c != NULL && (s->scope & c->scope) != 0)) {
                found = s;
            }
        }
    }
    return found;
}

/* A value 0..65535 of an option that command `cmd` (NULL: every command that
 * takes it) takes as 1..65535: out of range, the reason states 1..65535. 0
 * itself passes: the command refuses it with a message of its own. */
static int positive(const lscctl_opts *o, const char *cmd, const char *value, const char *what,
                    unsigned long *out, char *why, size_t whylen)
{
    int r = lscctl_parse_uint(value, 65535, what, out, why, whylen);
    if (r != 0 && (cmd == NULL || (o->cmd != NULL && strcmp(o->cmd, cmd) == 0))) {
        r = lscctl_parse_range(value, 1, 65535, what, out, why, whylen); /* says 1..65535 */
    }
    return r;
}

/* Applies option s with its value (NULL if it takes none). */
static int apply_option(lscctl_opts *o, const option_spec *s, const char *value, bool *help,
                        bool *version)
{
    char why[160];
    int r = 0;
    if (value == NULL) {
        value = ""; /* flags have none; parse_option gives every other option one */
    }
    switch (s->id) {
    case OPT_PORT:
        if (*value == '\0') {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--port needs a device path, hid, hid:SERIAL or 'sim'");
        }
        o->port = value;
        break;
    case OPT_BAUD:
        r = lscctl_parse_range(value, 1, 4000000, "baud rate", &o->baud, why, sizeof why);
        break;
    case OPT_TIMEOUT:
        /* 0 would time out every reply before it could arrive */
        r = lscctl_parse_range(value, 1, 86400000, "timeout", &o->timeout_ms, why, sizeof why);
        o->timeout_set = true;
        break;
    case OPT_JSON: o->json = true; break;
    case OPT_DRY_RUN: o->dry_run = true; break;
    case OPT_VERBOSE: o->verbose = true; break;
    case OPT_HELP: *help = true; break;
    case OPT_VERSION: *version = true; break;
    case OPT_TIME:
        r = positive(o, "record", value, "time", &o->time_ms, why, sizeof why);
        o->time_set = true;
        break;
    case OPT_TIMES: r = positive(o, "play", value, "times", &o->times, why, sizeof why); break;
    case OPT_WAIT: o->wait = true; break;
    case OPT_STRICT: o->strict = true; break;
    case OPT_COUNT:
        r = lscctl_parse_range(value, 1, 4294967295ul, "count", &o->count, why, sizeof why);
        break;
    case OPT_FORCE: o->force = true; break;
    case OPT_SPEED:
        r = positive(o, NULL, value, "speed", &o->speed, why, sizeof why);
        if (r == 0 && o->speed == 0) {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--speed 0: give 1..65535 percent");
        }
        break;
    case OPT_LEAD: r = lscctl_parse_uint(value, 65535, "lead", &o->lead_ms, why, sizeof why); break;
    case OPT_IDS: o->ids = value; break;
    case OPT_GROUP: {
        unsigned long g = 0;
        r = lscctl_parse_uint(value, 254, "group", &g, why, sizeof why);
        o->group = (int)g;
        break;
    }
    case OPT_EVERY:
        r = positive(o, NULL, value, "every", &o->every, why, sizeof why);
        o->every_set = true;
        break;
    case OPT_ARM:
    case OPT_FROM_ARM:
    case OPT_TO_ARM:
        if (*value == '\0') {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--%s needs an arm profile's path",
                               s->name);
        }
        *(s->id == OPT_ARM ? &o->arm : s->id == OPT_FROM_ARM ? &o->from_arm : &o->to_arm) = value;
        break;
    case OPT_DEG_SPEED:
        r = lscctl_parse_decimal(value, 0.01, 100000, "speed (degrees a second)", &o->deg_speed,
                                 why, sizeof why);
        break;
    case OPT_PITCH:
    case OPT_ROLL:
        r = lscctl_parse_decimal(value, -360, 360, s->name, s->id == OPT_PITCH ? &o->pitch
                                                                              : &o->roll,
                                 why, sizeof why);
        *(s->id == OPT_PITCH ? &o->pitch_set : &o->roll_set) = true;
        break;
    case OPT_LINE: o->line = true; break;
    case OPT_CALIB_STEP: o->calib_step = value; break;
    case OPT_CHECK: o->check = true; break;
    case OPT_SAVE: o->save = true; break;
    case OPT_OUT:
        if (*value == '\0') {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--out needs a file's path");
        }
        o->out = value;
        break;
    case OPT_STEP:
        r = lscctl_parse_decimal(value, 0.1, 1000, "step (mm)", &o->step, why, sizeof why);
        break;
    case OPT_TOLERANCE:
        r = lscctl_parse_uint(value, 65535, "tolerance", &o->tolerance, why, sizeof why);
        break;
    case OPT_HID_ID:
        if (lsc_device_parse_hid_id(value, &o->hid_vid, &o->hid_pid) != 0) {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                               "--hid-id needs a USB VID:PID in hex, as 'lscctl ports' or lsusb "
                               "shows it (e.g. 0483:5750)");
        }
        break;
    default: /* OPT_FROM */
        if (strcmp(value, "host") == 0) {
            o->from = LSCCTL_DIR_HOST;
        } else if (strcmp(value, "controller") == 0) {
            o->from = LSCCTL_DIR_CONTROLLER;
        } else {
            lscctl_shown v;
            return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                               "--from '%s': use --from host or --from controller",
                               lscctl_show(&v, value));
        }
        break;
    }
    if (r != 0) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "--%s: %s", s->name, why);
    }
    return 0;
}

/* Parses argv[*i] (an option; may consume argv[*i + 1]). */
static int parse_option(lscctl_opts *o, const command *c, int argc, char **argv, int *i,
                        bool *help, bool *version)
{
    const char *arg = argv[*i];
    const option_spec *s;
    const char *value = NULL;
    char shown[64];
    if (arg[1] == '-') {
        const char *eq = strchr(arg + 2, '=');
        size_t len = eq ? (size_t)(eq - arg - 2) : strlen(arg + 2);
        s = find_option(arg + 2, len, 0, c);
        value = eq ? eq + 1 : NULL;
        snprintf(shown, sizeof shown, "--%.*s", (int)len, arg + 2);
    } else {
        s = find_option(NULL, 0, arg[1], c);
        snprintf(shown, sizeof shown, "-%c", arg[1]);
        if (s != NULL && arg[2] != '\0') {
            if (s->value != NULL) {
                value = arg + 2; /* -t500 */
            } else if (!isalpha((unsigned char)arg[2])) {
                /* -n5, -n=1, -n-: not a flag group (-5 would be read as a word) */
                lscctl_shown text;
                return lscctl_fail(o, LSCCTL_EXIT_USAGE, "-%c takes no value (in '%s')", arg[1],
                                   lscctl_show(&text, arg));
            } else {
                /* -nv: several flags; handle the first, re-read the rest */
                int r = apply_option(o, s, NULL, help, version);
                if (r != 0) {
                    return r;
                }
                memmove(&argv[*i][1], &argv[*i][2], strlen(&argv[*i][2]) + 1);
                (*i)--;
                return 0;
            }
        }
    }
    if (s == NULL) {
        lscctl_shown text;
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "unknown option '%s'; see 'lscctl %s%s--help'",
                           lscctl_show(&text, shown), c ? c->name : "", c ? " " : "");
    }
    if (s->scope != GLOBAL && (c == NULL || (s->scope & c->scope) == 0)) {
        char owners[128] = "";
        size_t n = 0, count = 0, total = 0;
        unsigned scope = 0; /* of every option of that name (--speed: two) */
        for (size_t k = 0; k < sizeof options / sizeof options[0]; k++) {
            scope |= strcmp(options[k].name, s->name) == 0 ? options[k].scope : 0u;
        }
        for (size_t k = 0; k < NCOMMANDS; k++) {
            total += (commands[k].scope & scope) != 0;
        }
        for (size_t k = NCOMMANDS; k-- > 0 && n < sizeof owners;) { /* the last first */
            if (commands[k].scope & scope) {
                count++;
                n += (size_t)snprintf(owners + n, sizeof owners - n, "%s'%s'",
                                      count == 1 ? "" : count == total ? " and " : ", ",
                                      commands[k].name);
            }
        }
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s is an option of %s%s", shown, owners,
                           c == NULL ? ": put it after the command" : "");
    }
    if (s->value == NULL && value != NULL) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s takes no value", shown);
    }
    if (s->value != NULL && value == NULL) {
        if (*i + 1 >= argc) {
            return lscctl_fail(o, LSCCTL_EXIT_USAGE, "%s needs a value: %s %s", shown, shown,
                               s->value);
        }
        value = argv[++*i];
    }
    return apply_option(o, s, value, help, version);
}

/* A word starting with '-' that is an option, not a negative number or "-". */
static bool is_option(const char *arg)
{
    return arg[0] == '-' && arg[1] != '\0' && !(arg[1] >= '0' && arg[1] <= '9');
}

int main(int argc, char **argv)
{
    lscctl_opts o;
    memset(&o, 0, sizeof o);
    o.timeout_ms = 1000;
    o.time_ms = 1000;
    o.times = 1;
    o.tolerance = 10;
    o.from = LSCCTL_DIR_AUTO;
    o.speed = 100;
    o.lead_ms = 1000;
    o.group = -1;
    const command *c = NULL;
    bool help = false, version = false, help_cmd = false, dashdash = false;
    char **args = calloc((size_t)argc + 1, sizeof *args);
    int nargs = 0;
    if (args == NULL) {
        return lscctl_fail(NULL, LSCCTL_EXIT_FAIL, "out of memory");
    }
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (!dashdash && strcmp(arg, "--") == 0) {
            dashdash = true;
        } else if (!dashdash && is_option(arg)) {
            int r = parse_option(&o, c, argc, argv, &i, &help, &version);
            if (r != 0) {
                free(args);
                return r;
            }
        } else if (c == NULL) {
            if (!help_cmd && strcmp(arg, "help") == 0) {
                help_cmd = true;
                continue;
            }
            c = find_command(arg);
            if (c == NULL) {
                lscctl_shown text;
                int code = lscctl_fail(&o, LSCCTL_EXIT_USAGE,
                                       "unknown command '%s'; the commands are listed by "
                                       "'lscctl --help'",
                                       lscctl_show(&text, arg));
                free(args);
                return code;
            }
            o.cmd = c->name;
        } else {
            args[nargs++] = argv[i];
        }
    }
    /* the environment, as the library reads it for every front end */
    if (o.port == NULL) {
        o.port = lsc_device_env_port();
    }
    if (o.arm == NULL) {
        o.arm = lsc_device_env_arm();
    }
    /* else the arm's calibrated profile, when its controller has one */
    static char calibrated[4096];
    if (o.arm == NULL && c != NULL && !help && !version && c->run != lscctl_cmd_decode &&
        c->run != lscctl_cmd_ports && lsc_calibrated_find(o.port, calibrated, sizeof calibrated) == 0) {
        o.arm = calibrated;
        o.arm_calibrated = true;
        if (o.verbose) {
            fprintf(stderr, "lscctl: the calibrated profile of this arm: %s\n", calibrated);
        }
    }
    /* $LSC_HID_ID, checked before anything is opened (the open reads it) */
    char env_why[160];
    lsc_device_config *env = lsc_device_config_new();
    bool hid_env_bad = env != NULL && /* --hid-id wins: the variable is then not read */
                       lsc_device_config_set_hid_id(env, o.hid_vid, o.hid_pid) == 0 &&
                       lsc_device_config_from_env(env, env_why, sizeof env_why) != 0;
    lsc_device_config_free(env);
    int code = LSCCTL_EXIT_OK;
    lscctl_shown text;
    if (version) {
        printf("lscctl %s\n", LSC_VERSION);
    } else if (help_cmd && nargs > 0) {
        o.cmd = NULL; /* not an error of the command it names */
        code = lscctl_fail(&o, LSCCTL_EXIT_USAGE,
                           "'lscctl help' takes one command name (got '%s' after '%s')",
                           lscctl_show(&text, args[0]), c->name);
    } else if (help || help_cmd) {
        if (c != NULL) {
            print_command_help(c);
        } else {
            print_help();
        }
    } else if (c == NULL) {
        code = lscctl_fail(&o, LSCCTL_EXIT_USAGE, "no command given; try 'lscctl --help'");
    } else if (hid_env_bad) {
        code = lscctl_fail(&o, LSCCTL_EXIT_USAGE, "%s", env_why);
    } else if (nargs < c->min_args || (c->max_args >= 0 && nargs > c->max_args)) {
        char buf[USAGE_MAX];
        if (nargs < c->min_args) {
            code = lscctl_fail(&o, LSCCTL_EXIT_USAGE, "missing arguments: usage: lscctl %s",
                               usage(c, buf, sizeof buf));
        } else {
            code = lscctl_fail(&o, LSCCTL_EXIT_USAGE, "unexpected argument '%s': usage: lscctl %s",
                               lscctl_show(&text, args[c->max_args]), usage(c, buf, sizeof buf));
        }
    } else {
        code = c->run(&o, nargs, args);
    }
    free(args);
    if ((fflush(stdout) != 0 || ferror(stdout)) && code == LSCCTL_EXIT_OK) {
        code = lscctl_fail(&o, LSCCTL_EXIT_FAIL, "cannot write the output");
    }
    return code;
}
