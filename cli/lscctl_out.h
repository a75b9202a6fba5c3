/* lscctl: frames as text and JSON (the names of docs/protocol.md). */
#ifndef LSCCTL_OUT_H
#define LSCCTL_OUT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "lsc/core.h"

struct lsc_arm;

/* Who sent a frame. AUTO: the only direction the frame can come from; for
 * frames both sides send (action_group_run, action_group_stop) the host. */
typedef enum lscctl_dir { LSCCTL_DIR_AUTO, LSCCTL_DIR_HOST, LSCCTL_DIR_CONTROLLER } lscctl_dir;

/* What a frame means: one message of docs/protocol.md, or an unknown command. */
typedef struct lscctl_msg {
    uint8_t cmd;
    lscctl_dir dir;    /* HOST or CONTROLLER, never AUTO */
    const char *name;  /* servo_move, ..., or "unknown" */
    bool reply;        /* get_battery_voltage / mult_servo_pos_read / servo_offset_read reply */
    uint16_t time_ms;  /* servo_move */
    uint8_t group;     /* action_group_run/complete/speed */
    uint16_t times;    /* action_group_run/complete */
    uint16_t percent;  /* action_group_speed */
    uint16_t millivolts; /* battery reply */
    size_t nservos;    /* servo_move, position reply */
    lsc_servo servos[LSC_READ_MAX];
    size_t nids;       /* unload, position and offset requests */
    uint8_t ids[LSC_PARAMS_MAX];
    size_t noffsets;   /* offset reply; servo_offset_adjust: 1 */
    lsc_servo_offset offsets[LSC_OFFSET_MAX];
    /* not decoded: set by the caller to print a position reply's servos in
     * JSON with their joint and angle through this arm profile (read --arm) */
    const struct lsc_arm *arm;
    const uint8_t *params; /* unknown command: its parameter bytes */
    size_t nparams;
} lscctl_msg;

/* Interprets f as sent by dir. Returns 0, or -1 with a reason in why when
 * the frame does not fit its command in that direction. */
int lscctl_msg_decode(lscctl_msg *m, const lsc_frame *f, lscctl_dir dir, char *why,
                      size_t whylen);


/* n bytes as upper-case hex separated by single spaces, cut to fit cap (>= 1). */
void lscctl_hex(char *out, size_t cap, const uint8_t *bytes, size_t n);
#define LSCCTL_HEX_MAX (3u * LSC_FRAME_MAX + 1u) /* room for any frame */

/* One line for m. Text: "NAME key=value ..." (prefix "DIR " when with_dir);
 * JSON: {"cmd":..,"name":..,fields}, with "dir" when with_dir. hex, if not
 * NULL, is added as "(HEX)" in text and "hex" in JSON. */
void lscctl_msg_print(FILE *out, const lscctl_msg *m, bool json, bool with_dir, const char *hex);

/* A frame lscctl built (frame[0..n), whole), as decode shows a host's frame
 * (without the direction): its message, or an error line when it is not a
 * valid one (a raw frame of send). With hex, its bytes too. */
void lscctl_frame_print(FILE *out, const uint8_t *frame, size_t n, bool json, bool with_hex);

/* What -n shows of a frame lscctl would send: its hex, or with --json its
 * message with the hex. */
void lscctl_dry_run_print(FILE *out, const uint8_t *frame, size_t n, bool json);

/* One line for discarded bytes: text "error REASON (HEX)", JSON {"error","hex"}. */
void lscctl_error_print(FILE *out, bool json, const char *reason, const char *hex);

/* s as a JSON string, quotes included. */
void lscctl_json_string(FILE *out, const char *s);

/* Room for text from the user (a file's name, an argument) shown in a
 * message: a path of 4096 bytes, each byte escaped. */
typedef struct lscctl_shown {
    char text[4u * 4096u + 1u];
} lscctl_shown;

/* s as a one-line message shows it: control characters, backslashes and
 * non-ASCII bytes escaped (\x0A, \\) by the library's rules, those of its
 * own messages (lsc_escape_text, lsc/device.h). Returns buf->text. */
const char *lscctl_show(lscctl_shown *buf, const char *s);

#endif
