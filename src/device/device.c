/* lsc device: opening a controller by name, closing it, its settings and
 * accessors (contract in lsc/device.h). Host only: compiles to nothing
 * elsewhere (the Arduino IDE builds every .c under src/). */
#include "lsc/host.h"
#if LSC_HOST

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "device_internal.h"

/* The calling thread's last lsc_device_open, for a NULL handle: what
 * lsc_device_error, lsc_device_error_cause, lsc_device_name and
 * lsc_device_kind_of say of NULL (empty, LSC_DEVICE_SERIAL, after one that
 * succeeded). Per thread: opens in other threads do not touch it. */
typedef struct last_open {
    char message[DEVICE_MESSAGE_MAX];
    char name[LSC_DEVICE_NAME_MAX];
    lsc_device_cause cause;
    lsc_device_kind kind;
} last_open;

static __thread last_open last;

/* The entries, asked in turn which one a name selects (the one place that
 * decides): sim; lscd:NAME or lscd:PATH; hid, hid:SERIAL or a hidraw node;
 * lx:PATH (a bus of servos); else a serial port (which claims every name). */
static const lsc_dev_transport *const entries[] = {
    &lsc_dev_transport_sim,
    &lsc_dev_transport_lscd,
    &lsc_dev_transport_hid,
    &lsc_dev_transport_lx,
    &lsc_dev_transport_serial,
};

const lsc_dev_transport *lsc_dev_transport_of(const char *name)
{
    size_t i = 0;
    while (!entries[i]->claims(name)) {
        i++;
    }
    return entries[i];
}

int lsc_device_kind_of_name(const char *name, lsc_device_kind *kind)
{
    if (kind == NULL) {
        return LSC_EINVAL;
    }
    if (name == NULL) {
        name = lsc_dev_env_port(); /* as lsc_device_open(NULL) takes it */
        if (name == NULL) {
            return LSC_ENODEV; /* discovery decides */
        }
    }
    *kind = lsc_dev_transport_of(name)->kind;
    return 0;
}

int lsc_dev_state_alloc(lsc_device *d, size_t size)
{
    d->state = calloc(1, size);
    return d->state != NULL
               ? 0
               : lsc_dev_fail(d, LSC_ENOSPC, LSC_DEVICE_CAUSE_NONE, "out of memory");
}

lsc_device_cause lsc_dev_open_cause(int r)
{
    /* its message says how to get access when it was denied (lsc_port's hints) */
    return r == LSC_EACCES ? LSC_DEVICE_CAUSE_ACCESS : LSC_DEVICE_CAUSE_NONE;
}

int lsc_dev_too_long(lsc_device *d, const char *name, const char *what, unsigned most)
{
    char start[4u * 40u + 1u];
    (void)lsc_escape_text(start, sizeof start, name, 40u);
    return lsc_dev_fail(d, LSC_EINVAL, LSC_DEVICE_CAUSE_NAME_TOO_LONG,
                        "%s '%s...' is too long: at most %u bytes", what, start, most);
}

int lsc_dev_open_name(lsc_device *d, const char *name)
{
    size_t len = strlen(name);
    if (len >= sizeof d->name) {
        return lsc_dev_too_long(d, name, "the name", LSC_DEVICE_NAME_MAX - 1u);
    }
    memcpy(d->name, name, len + 1u);
    (void)lsc_escape_text(d->shown, sizeof d->shown, name, len);
    d->t = lsc_dev_transport_of(name);
    if (d->baud == 0) { /* none given: the kind's own */
        d->baud = d->t->baud != 0 ? d->t->baud : LSC_SERIAL_BAUD_DEFAULT;
    }
    return d->t->open(d, name);
}

int lsc_device_open(const char *name, const lsc_device_config *cfg, lsc_device **out)
{
    if (out == NULL) {
        return LSC_EINVAL;
    }
    memset(&last, 0, sizeof last);
    lsc_device *d = calloc(1, sizeof *d);
    *out = NULL;
    if (d == NULL) {
        (void)snprintf(last.message, sizeof last.message, "out of memory");
        return LSC_ENOSPC;
    }
    d->t = &lsc_dev_transport_serial; /* the kind until a name chose one */
    d->rx_other = -1;
    d->timeout_ms = cfg != NULL && cfg->timeout_ms != 0 ? cfg->timeout_ms
                                                        : LSC_DEVICE_TIMEOUT_DEFAULT;
    d->baud = cfg != NULL ? cfg->baud : 0u; /* 0: the kind's own (opened) */
    if (cfg != NULL) {
        d->hid_vid = cfg->hid_vid;
        d->hid_pid = cfg->hid_pid;
    }
    char found[LSC_DEVICE_NAME_MAX];
    int r = 0;
    if (name == NULL) {
        r = lsc_dev_find(d, found, sizeof found);
        name = found;
    }
    if (r == 0) {
        r = lsc_dev_open_name(d, name);
    }
    if (r != 0) { /* what it says stays readable without a handle */
        memcpy(last.message, d->message, sizeof last.message);
        memcpy(last.name, d->name, sizeof last.name);
        last.cause = d->cause;
        last.kind = d->t->kind;
        lsc_device_close(d);
        return r;
    }
    lsc_dev_io_init(d);
    *out = d;
    return 0;
}

void lsc_device_close(lsc_device *d)
{
    if (d == NULL) {
        return;
    }
    d->t->close(d);
    lsc_dev_arm_free(d);
    free(d);
}

const char *lsc_device_error(const lsc_device *d)
{
    return d == NULL ? last.message : d->message;
}

lsc_device_cause lsc_device_error_cause(const lsc_device *d)
{
    return d == NULL ? last.cause : d->cause;
}

const char *lsc_device_name(const lsc_device *d)
{
    return d == NULL ? last.name : d->name;
}

lsc_device_kind lsc_device_kind_of(const lsc_device *d)
{
    return d == NULL ? last.kind : d->t->kind;
}

void lsc_device_set_timeout(lsc_device *d, uint32_t timeout_ms)
{
    if (d != NULL) {
        d->timeout_ms = timeout_ms != 0 ? timeout_ms : LSC_DEVICE_TIMEOUT_DEFAULT;
        if (d->t->set_timeout != NULL) {
            d->t->set_timeout(d, d->timeout_ms);
        }
    }
}

uint32_t lsc_device_timeout(const lsc_device *d)
{
    return d == NULL ? LSC_DEVICE_TIMEOUT_DEFAULT : d->timeout_ms;
}

void lsc_device_set_trace(lsc_device *d, lsc_trace_fn fn, void *user)
{
    if (d != NULL) {
        d->trace = fn;
        d->trace_user = user;
    }
}

void lsc_device_set_last_word(lsc_device *d, lsc_device_last_word_fn fn, void *user)
{
    if (d != NULL) {
        d->last_word = fn;
        d->last_word_user = user;
    }
}

uint32_t lsc_device_now_ms(lsc_device *d)
{
    return d == NULL ? 0u : d->io.now_ms(d->io.ctx);
}

#endif
