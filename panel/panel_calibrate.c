/* lsc-panel: the Calibrate section's steps, in the device thread. The steps
 * are the library's (lsc_device_calibrate, lsc/calibrated.h), as lscctl
 * calibrate's: here is only the panel's calibration in progress (the
 * profile's text so far, kept until Save or Cancel) and its JSON. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "lsc/calibrated.h"
#include "lsc/files.h"
#include "lsc/arm.h"
#include "lsc/kinematics.h"
#include "panel.h"

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static int refuse(panel_cmd *c, int r, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    (void)vsnprintf(c->message, sizeof c->message, fmt, ap);
    va_end(ap);
    c->cause = LSC_DEVICE_CAUSE_NONE;
    return r;
}

/* The text the calibration starts from: the result there is (continued), else
 * the profile lsc-panel was started with. */
static int start(panel *p, panel_cmd *c)
{
    struct stat st;
    lsc_file_error err = {.size = sizeof err};
    uint8_t *data = NULL;
    const char *from = stat(p->calib_out, &st) == 0 ? p->calib_out : p->arm_path;
    if (from == NULL) {
        return refuse(c, LSC_EINVAL, "calibration starts from the arm's profile: start "
                                     "lsc-panel with --arm%s%s",
                      "", "");
    }
    if (lsc_file_load(from, LSC_ARM_FILE_MAX, &data, &p->calib_len, &err) != 0) {
        return refuse(c, LSC_EINVAL, "cannot read %s: %s", from, err.message);
    }
    p->calib_text = (char *)data;
    (void)snprintf(p->calib_from, sizeof p->calib_from, "%s", from);
    return 0;
}

/* {"out":PATH,"from":PATH,"joints":[{"name":..,"offset":..,"dir":..[,"open":..,"closed":..]}]}:
 * the chain's joints as the calibration so far has them. */
static void state_json(const panel *p, panel_buf *b)
{
    lsc_arm *arm = NULL;
    lsc_kin_chain chain;
    int joints[LSC_ARM_CHAIN_MAX];
    panel_buf_str(b, "{\"out\":");
    panel_buf_json(b, p->calib_out);
    panel_buf_str(b, ",\"from\":");
    panel_buf_json(b, p->calib_from);
    panel_buf_str(b, ",\"joints\":[");
    if (lsc_arm_parse(p->calib_text, p->calib_len, NULL, &arm, NULL, 0) == 0 &&
        lsc_arm_chain(arm, &chain, joints, NULL, 0) == 0) {
        for (size_t q = 0; q < LSC_ARM_CHAIN_MAX && joints[q] >= 0; q++) {
            size_t i = (size_t)joints[q];
            const lsc_joint *j = lsc_arm_joint(arm, i);
            long middle = (long)j->pos_min + ((long)j->pos_max - (long)j->pos_min) / 2;
            uint16_t open = 0, closed = 0;
            panel_buf_str(b, q > 0 ? ",{\"name\":" : "{\"name\":");
            panel_buf_json(b, lsc_arm_name(arm, i));
            panel_buf_printf(b, ",\"offset\":%ld,\"dir\":%d", (long)j->zero - middle,
                             j->direction);
            if (lsc_arm_end(arm, i, LSC_ARM_OPEN, &open) == 0) {
                panel_buf_printf(b, ",\"open\":%u", open);
            }
            if (lsc_arm_end(arm, i, LSC_ARM_CLOSED, &closed) == 0) {
                panel_buf_printf(b, ",\"closed\":%u", closed);
            }
            panel_buf_str(b, "}");
        }
    }
    lsc_arm_free(arm);
    panel_buf_str(b, "]}");
}

int panel_calibrate(panel *p, panel_cmd *c)
{
    if (p->calib_out[0] == '\0') {
        return refuse(c, LSC_EINVAL, "this controller has no name to keep its arm's profile "
                                     "under (a HID controller's serial number, a serial port's "
                                     "/dev/serial/by-id link): calibrate with lscctl calibrate "
                                     "--out FILE");
    }
    if (c->value == PANEL_CALIBRATE_CANCEL) {
        free(p->calib_text);
        p->calib_text = NULL;
        panel_buf_str(&c->out, "{\"cancelled\":true}");
        return 0;
    }
    if (c->value == PANEL_CALIBRATE_SAVE) {
        char why[PANEL_MSG_MAX - 32];
        if (p->calib_text == NULL) {
            return refuse(c, LSC_EINVAL, "nothing to save: take the steps first");
        }
        if (lsc_calibrated_write(p->calib_out, p->calib_text, p->calib_len, why, sizeof why) !=
            0) {
            return refuse(c, LSC_EIO, "%s", why);
        }
        free(p->calib_text);
        p->calib_text = NULL;
        panel_buf_str(&c->out, "{\"written\":");
        panel_buf_json(&c->out, p->calib_out);
        panel_buf_str(&c->out, "}");
        return 0;
    }
    if (p->calib_text == NULL) {
        int r = start(p, c);
        if (r != 0) {
            return r;
        }
    }
    char *text = NULL;
    size_t len = 0;
    int r = lsc_device_calibrate(p->dev, (lsc_calib_step)c->value, p->calib_text, p->calib_len,
                                 p->calib_from, &text, &len);
    if (r != 0) {
        c->cause = lsc_device_error_cause(p->dev);
        (void)snprintf(c->message, sizeof c->message, "%s", lsc_device_error(p->dev));
        return r;
    }
    free(p->calib_text);
    p->calib_text = text;
    p->calib_len = len;
    state_json(p, &c->out);
    return 0;
}

void panel_calibrate_free(panel *p)
{
    free(p->calib_text);
    p->calib_text = NULL;
}
