/* Shared by the serial transport's sources (not part of the API). The
 * dependency runs one way: serial.c (open, close, I/O) calls the
 * libserialport backend (serial_libserialport.c), and both use the device
 * claiming and error recording of src/port; nothing calls back into serial.c. */
#ifndef LSC_SERIAL_INTERNAL_H
#define LSC_SERIAL_INTERNAL_H

#include <string.h>

#include "../port/port_internal.h"
#include "lsc/serial.h"

#if LSC_SERIAL_MESSAGE_MAX != LSC_PORT_MESSAGE_MAX
#error "lsc_serial's message must hold a port message"
#endif

/* An open port (opaque in lsc/serial.h). */
struct lsc_serial {
    int fd;                         /* -1 when closed */
    void *sp;                       /* struct sp_port * (libserialport backend) */
    lsc_serial_backend backend;     /* the one in use (TERMIOS or LIBSERIALPORT) */
    uint32_t baud;
    uint32_t write_timeout_ms;      /* how long a write may wait for the line */
    int os_errno;
    char path[LSC_SERIAL_PATH_MAX];
    char message[LSC_SERIAL_MESSAGE_MAX];
};

/* The port's record copied into s's error fields. Returns code. */
static inline int lsc_serial_keep(lsc_serial *s, int code, const lsc_port_error *e)
{
    s->os_errno = e->os_errno;
    memcpy(s->message, e->message, sizeof s->message);
    return code;
}

/* Records an error on s (lsc_port_fail with s's path; an LSC_ENODEV while s
 * is open says the device went away) and returns code. */
static inline int lsc_serial_fail(lsc_serial *s, int code, int err, const char *what)
{
    lsc_port_error e;
    e.open = s->fd >= 0;
    return lsc_serial_keep(s, lsc_port_fail(&e, code, err, s->path, what), &e);
}

/* libserialport backend: opens and configures s->path at s->baud, sets s->fd
 * and s->sp, claimed with lsc_port_lock. Returns 0 or an error recorded on s
 * (nothing left open). Without libserialport: LSC_EINVAL. */
int lsc_serial_sp_open(lsc_serial *s);
void lsc_serial_sp_close(lsc_serial *s);

#endif
