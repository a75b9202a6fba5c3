#include "lscctl_out.h"

#include <string.h>

#include "lsc/arm.h"
#include "lsc/device.h"
#include "lsc/text.h"

/* The direction a frame must come from, or AUTO when both send it. */
static lscctl_dir natural_dir(const lsc_frame *f)
{
    switch (f->cmd) {
    case LSC_CMD_GROUP_COMPLETE: return LSCCTL_DIR_CONTROLLER;
    case LSC_CMD_BATTERY:
        return f->nparams == 2 ? LSCCTL_DIR_CONTROLLER : LSCCTL_DIR_HOST;
    case LSC_CMD_POS_READ:
        /* a request has N ids, a reply 3*N bytes after the count */
        return f->nparams > 1 && f->nparams == 1u + 3u * f->params[0] ? LSCCTL_DIR_CONTROLLER
                                                                       : LSCCTL_DIR_HOST;
    case LSC_CMD_OFFSET_READ: /* the same with 2*N bytes (id, offset) in a reply */
        return f->nparams > 1 && f->nparams == 1u + 2u * f->params[0] ? LSCCTL_DIR_CONTROLLER
                                                                       : LSCCTL_DIR_HOST;
    default: return LSCCTL_DIR_HOST;
    }
}

int lscctl_msg_decode(lscctl_msg *m, const lsc_frame *f, lscctl_dir dir, char *why,
                      size_t whylen)
{
    int r = 0;
    memset(m, 0, sizeof *m);
    m->cmd = f->cmd;
    m->name = lsc_device_cmd_name(f->cmd);
    m->dir = dir == LSCCTL_DIR_AUTO ? natural_dir(f) : dir;
    bool host = m->dir == LSCCTL_DIR_HOST;
    switch (f->cmd) {
    case LSC_CMD_SERVO_MOVE:
        r = lsc_decode_servo_move(f, &m->time_ms, m->servos, LSC_READ_MAX);
        m->nservos = r > 0 ? (size_t)r : 0;
        break;
    case LSC_CMD_GROUP_RUN: r = lsc_decode_group_run(f, &m->group, &m->times); break;
    case LSC_CMD_GROUP_STOP: r = lsc_decode_group_stop(f); break;
    case LSC_CMD_GROUP_COMPLETE: r = lsc_decode_group_complete(f, &m->group, &m->times); break;
    case LSC_CMD_GROUP_SPEED: r = lsc_decode_group_speed(f, &m->group, &m->percent); break;
    case LSC_CMD_BATTERY:
        m->reply = !host;
        r = host ? lsc_decode_battery_request(f) : lsc_decode_battery_reply(f, &m->millivolts);
        break;
    case LSC_CMD_UNLOAD:
        r = lsc_decode_unload(f, m->ids, sizeof m->ids);
        m->nids = r > 0 ? (size_t)r : 0;
        break;
    case LSC_CMD_POS_READ:
        m->reply = !host;
        if (host) {
            r = lsc_decode_pos_request(f, m->ids, sizeof m->ids);
            m->nids = r > 0 ? (size_t)r : 0;
        } else {
            r = lsc_decode_pos_reply(f, m->servos, LSC_READ_MAX);
            m->nservos = r > 0 ? (size_t)r : 0;
        }
        break;
    case LSC_CMD_OFFSET_READ:
        m->reply = !host;
        if (host) {
            r = lsc_decode_offset_request(f, m->ids, sizeof m->ids);
            m->nids = r > 0 ? (size_t)r : 0;
        } else {
            r = lsc_decode_offset_reply(f, m->offsets, LSC_OFFSET_MAX);
            m->noffsets = r > 0 ? (size_t)r : 0;
        }
        break;
    case LSC_CMD_OFFSET_ADJUST:
        r = lsc_decode_offset_adjust(f, &m->offsets[0].id, &m->offsets[0].offset);
        m->noffsets = r == 0 ? 1u : 0u;
        break;
    default:
        m->params = f->params;
        m->nparams = f->nparams;
        break;
    }
    if (r < 0) {
        snprintf(why, whylen, "not a valid %s%s", m->name,
                 f->cmd == LSC_CMD_BATTERY || f->cmd == LSC_CMD_POS_READ ||
                         f->cmd == LSC_CMD_OFFSET_READ
                     ? (host ? " request" : " reply")
                     : "");
        return -1;
    }
    return 0;
}

void lscctl_hex(char *out, size_t cap, const uint8_t *bytes, size_t n)
{
    size_t at = 0;
    out[0] = '\0';
    for (size_t i = 0; i < n && at + 3 < cap; i++) {
        at += (size_t)snprintf(out + at, cap - at, i ? " %02X" : "%02X", bytes[i]);
    }
}

void lscctl_json_string(FILE *out, const char *s)
{
    fputc('"', out);
    for (; *s != '\0'; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') {
            fprintf(out, "\\%c", c);
        } else if (c < 0x20) {
            fprintf(out, "\\u%04x", c);
        } else {
            fputc(c, out);
        }
    }
    fputc('"', out);
}

/* ",\"joint\":NAME,\"degrees\":ANGLE" of servo s through m->arm (as far as it has them) */
static void print_joint(FILE *out, const lscctl_msg *m, const lsc_servo *s)
{
    char deg[LSC_ARM_DEGREES_MAX];
    int i = lsc_arm_degrees(m->arm, s, deg, sizeof deg);
    if (i >= 0) {
        fputs(",\"joint\":", out);
        lscctl_json_string(out, lsc_arm_name(m->arm, (size_t)i));
    }
    if (deg[0] != '\0') {
        fprintf(out, ",\"degrees\":%s", deg);
    }
}

static void print_servos(FILE *out, const lscctl_msg *m, bool json)
{
    fputs(json ? ",\"servos\":[" : " servos=", out);
    for (size_t i = 0; i < m->nservos; i++) {
        if (json) {
            fprintf(out, "%s{\"id\":%u,\"position\":%u", i ? "," : "", m->servos[i].id,
                    m->servos[i].position);
            print_joint(out, m, &m->servos[i]);
            fputc('}', out);
        } else {
            fprintf(out, "%s%u:%u", i ? "," : "", m->servos[i].id, m->servos[i].position);
        }
    }
    if (json) {
        fputc(']', out);
    }
}

static void print_offsets(FILE *out, const lscctl_msg *m, bool json)
{
    fputs(json ? ",\"servos\":[" : " servos=", out);
    for (size_t i = 0; i < m->noffsets; i++) {
        fprintf(out, json ? "%s{\"id\":%u,\"offset\":%d}" : "%s%u:%d", i ? "," : "",
                m->offsets[i].id, m->offsets[i].offset);
    }
    if (json) {
        fputc(']', out);
    }
}

static void print_ids(FILE *out, const lscctl_msg *m, bool json)
{
    fputs(json ? ",\"ids\":[" : " ids=", out);
    for (size_t i = 0; i < m->nids; i++) {
        fprintf(out, "%s%u", i ? "," : "", m->ids[i]);
    }
    if (json) {
        fputc(']', out);
    }
}

/* ",\"key\":value" in JSON, " key=value" in text */
static void field(FILE *out, bool json, const char *key, unsigned value)
{
    fprintf(out, json ? ",\"%s\":%u" : " %s=%u", key, value);
}

void lscctl_msg_print(FILE *out, const lscctl_msg *m, bool json, bool with_dir, const char *hex)
{
    const char *dir = m->dir == LSCCTL_DIR_CONTROLLER ? "controller" : "host";
    if (json) {
        fputc('{', out);
        if (with_dir) {
            fprintf(out, "\"dir\":\"%s\",", dir);
        }
        if (hex != NULL) {
            fprintf(out, "\"hex\":\"%s\",", hex);
        }
        fprintf(out, "\"cmd\":%u,\"name\":\"%s\"", m->cmd, m->name);
    } else {
        if (with_dir) {
            fprintf(out, "%s ", dir);
        }
        fputs(m->name, out);
    }
    switch (m->cmd) {
    case LSC_CMD_SERVO_MOVE:
        field(out, json, "time_ms", m->time_ms);
        print_servos(out, m, json);
        break;
    case LSC_CMD_GROUP_RUN:
    case LSC_CMD_GROUP_COMPLETE:
        field(out, json, "group", m->group);
        field(out, json, "times", m->times);
        break;
    case LSC_CMD_GROUP_SPEED:
        if (!json && m->group == LSC_GROUP_ALL) {
            fputs(" group=all", out);
        } else {
            field(out, json, "group", m->group);
        }
        field(out, json, "percent", m->percent);
        break;
    case LSC_CMD_BATTERY:
        if (m->reply) {
            field(out, json, "millivolts", m->millivolts);
            fprintf(out, json ? ",\"volts\":%.3f" : " volts=%.3f", m->millivolts / 1000.0);
        }
        break;
    case LSC_CMD_UNLOAD: print_ids(out, m, json); break;
    case LSC_CMD_POS_READ:
        if (m->reply) {
            print_servos(out, m, json);
        } else {
            print_ids(out, m, json);
        }
        break;
    case LSC_CMD_OFFSET_READ:
        if (m->reply) {
            print_offsets(out, m, json);
        } else {
            print_ids(out, m, json);
        }
        break;
    case LSC_CMD_OFFSET_ADJUST:
        field(out, json, "id", m->offsets[0].id);
        fprintf(out, json ? ",\"offset\":%d" : " offset=%d", m->offsets[0].offset);
        break;
    case LSC_CMD_GROUP_STOP: break;
    default: {
        char params[LSCCTL_HEX_MAX];
        lscctl_hex(params, sizeof params, m->params, m->nparams);
        if (json) {
            fprintf(out, ",\"params\":\"%s\"", params);
        } else {
            fprintf(out, " cmd=%u params=", m->cmd);
            for (size_t i = 0; i < m->nparams; i++) {
                fprintf(out, "%02X", m->params[i]);
            }
            if (m->nparams == 0) {
                fputs("none", out);
            }
        }
        break;
    }
    }
    if (json) {
        fputs("}\n", out);
    } else if (hex != NULL) {
        fprintf(out, " (%s)\n", hex);
    } else {
        fputc('\n', out);
    }
}

void lscctl_frame_print(FILE *out, const uint8_t *frame, size_t n, bool json, bool with_hex)
{
    lsc_frame f = {frame[3], (uint8_t)(n - 4u), &frame[4]};
    lscctl_msg m;
    char why[96], hex[LSCCTL_HEX_MAX];
    lscctl_hex(hex, sizeof hex, frame, n);
    if (lscctl_msg_decode(&m, &f, LSCCTL_DIR_HOST, why, sizeof why) == 0) {
        lscctl_msg_print(out, &m, json, false, with_hex ? hex : NULL);
    } else {
        lscctl_error_print(out, json, why, hex);
    }
}

void lscctl_dry_run_print(FILE *out, const uint8_t *frame, size_t n, bool json)
{
    if (json) {
        lscctl_frame_print(out, frame, n, true, true);
    } else {
        char hex[LSCCTL_HEX_MAX];
        lscctl_hex(hex, sizeof hex, frame, n);
        fprintf(out, "%s\n", hex);
    }
}

void lscctl_error_print(FILE *out, bool json, const char *reason, const char *hex)
{
    if (json) {
        fputs("{\"error\":", out);
        lscctl_json_string(out, reason);
        fprintf(out, ",\"hex\":\"%s\"}\n", hex);
    } else {
        fprintf(out, "error %s (%s)\n", reason, hex);
    }
}

const char *lscctl_show(lscctl_shown *buf, const char *s)
{
    (void)lsc_escape_text(buf->text, sizeof buf->text, s, strlen(s));
    return buf->text;
}
