/* Serial transport, libserialport backend: opening and configuring a port,
 * and port enumeration. Built with libserialport when LSC_HAVE_LIBSERIALPORT
 * is defined (CMake option LSC_WITH_LIBSERIALPORT); otherwise the backend
 * reports itself absent. Host only: compiles to nothing elsewhere. */
#include "lsc/host.h"
#if LSC_HOST

#define _DEFAULT_SOURCE 1
#define _DARWIN_C_SOURCE 1

#include <fcntl.h>
#include <stdio.h>
#include <string.h>

#include "serial_internal.h"
#include "../util/sized.h" /* lsc_port_info grows */

/* Copies src (may be NULL) into dst[cap], truncated, NUL-terminated. */
static void copy_text(char *dst, size_t cap, const char *src)
{
    if (cap == 0) {
        return;
    }
    size_t n = src == NULL ? 0 : strlen(src);
    if (n >= cap) {
        n = cap - 1u;
    }
    if (n > 0) {
        memcpy(dst, src, n);
    }
    dst[n] = '\0';
}

#ifdef LSC_HAVE_LIBSERIALPORT
#include <libserialport.h>

bool lsc_serial_have_libserialport(void)
{
    return true;
}

/* Records libserialport's error (OS errno and message when it has them). */
static int sp_fail(lsc_serial *s, enum sp_return r, const char *what)
{
    int err = r == SP_ERR_FAIL ? sp_last_error_code() : 0;
    char text[256];
    if (r == SP_ERR_FAIL) {
        char *m = sp_last_error_message();
        copy_text(text, sizeof text, m);
        sp_free_error_message(m);
    } else {
        copy_text(text, sizeof text, r == SP_ERR_ARG ? "not a port libserialport knows"
                                     : r == SP_ERR_SUPP ? "not supported by libserialport"
                                                        : "libserialport error");
    }
    char msg[384];
    (void)snprintf(msg, sizeof msg, "libserialport: %s: %s", what, text);
    int code = r == SP_ERR_FAIL ? lsc_port_open_code(err) : LSC_ENODEV;
    (void)lsc_serial_fail(s, code, 0, msg);
    s->os_errno = err;
    return code;
}

int lsc_serial_sp_open(lsc_serial *s)
{
    struct sp_port *port = NULL;
    enum sp_return r = sp_get_port_by_name(s->path, &port);
    if (r != SP_OK) {
        return sp_fail(s, r, "cannot find port");
    }
    r = sp_open(port, SP_MODE_READ_WRITE);
    if (r != SP_OK) {
        int code = sp_fail(s, r, "cannot open");
        sp_free_port(port);
        return code;
    }
    const char *what = NULL;
    if ((r = sp_set_baudrate(port, (int)s->baud)) != SP_OK) {
        what = "cannot set the baud rate";
    } else if ((r = sp_set_bits(port, 8)) != SP_OK || (r = sp_set_parity(port, SP_PARITY_NONE)) != SP_OK ||
               (r = sp_set_stopbits(port, 1)) != SP_OK ||
               (r = sp_set_flowcontrol(port, SP_FLOWCONTROL_NONE)) != SP_OK) {
        what = "cannot configure 8N1 without flow control";
    }
    int fd = -1;
    if (what == NULL && (r = sp_get_port_handle(port, &fd)) != SP_OK) {
        what = "no file descriptor";
    }
    int code = what == NULL ? 0 : sp_fail(s, r, what);
    if (code == 0) {
        lsc_port_error e;
        e.open = false;
        (void)fcntl(fd, F_SETFD, FD_CLOEXEC); /* (libserialport opens without O_CLOEXEC) */
        code = lsc_port_lock(&e, NULL, fd, s->path);
        if (code != 0) {
            (void)lsc_serial_keep(s, code, &e);
        }
    }
    if (code != 0) {
        (void)sp_close(port);
        sp_free_port(port);
        return code;
    }
    s->fd = fd;
    s->sp = port;
    s->backend = LSC_SERIAL_LIBSERIALPORT;
    return 0;
}

void lsc_serial_sp_close(lsc_serial *s)
{
    (void)sp_close(s->sp); /* (only closes: the lock goes with the last descriptor) */
    sp_free_port(s->sp);
    s->sp = NULL;
}

int lsc_serial_list_ports(lsc_port_info *out, size_t cap, char *message, size_t msgcap)
{
    if (out == NULL && cap > 0) {
        copy_text(message, msgcap, "invalid argument");
        return LSC_EINVAL;
    }
    size_t size = cap > 0 ? lsc_sized_size(out) : 0u;
    if (cap > 0 && size < LSC_SIZED_MIN(lsc_port_info, path)) {
        char why[160];
        (void)snprintf(why, sizeof why,
                       "lsc_port_info.size is %lu, less than %lu: set out[0].size to "
                       "sizeof(lsc_port_info); nothing was listed",
                       (unsigned long)size, (unsigned long)LSC_SIZED_MIN(lsc_port_info, path));
        copy_text(message, msgcap, why);
        return LSC_EINVAL;
    }
    struct sp_port **list = NULL;
    enum sp_return r = sp_list_ports(&list);
    if (r != SP_OK) {
        char *m = sp_last_error_message();
        copy_text(message, msgcap, m);
        sp_free_error_message(m);
        return LSC_EIO;
    }
    size_t count = 0;
    for (; list[count] != NULL; count++) {
        if (count >= cap) {
            continue;
        }
        lsc_port_info p;
        memset(&p, 0, sizeof p);
        p.size = sizeof p;
        copy_text(p.path, sizeof p.path, sp_get_port_name(list[count]));
        copy_text(p.description, sizeof p.description, sp_get_port_description(list[count]));
        int vid = 0, pid = 0;
        p.usb = sp_get_port_transport(list[count]) == SP_TRANSPORT_USB &&
                sp_get_port_usb_vid_pid(list[count], &vid, &pid) == SP_OK;
        p.vid = p.usb ? (uint16_t)vid : 0;
        p.pid = p.usb ? (uint16_t)pid : 0;
        copy_text(p.serial, sizeof p.serial, p.usb ? sp_get_port_usb_serial(list[count]) : NULL);
        lsc_sized_give_nth(out, size, count, &p, sizeof p);
    }
    sp_free_port_list(list);
    copy_text(message, msgcap, "");
    return count > 0x7FFFFFFFu ? 0x7FFFFFFF : (int)count;
}

#else /* built without libserialport */

bool lsc_serial_have_libserialport(void)
{
    return false;
}

int lsc_serial_sp_open(lsc_serial *s)
{
    return lsc_serial_fail(s, LSC_EINVAL, 0, "this lsc was built without libserialport (install the Debian package libserialport-dev, then configure and build lsc again)");
}

void lsc_serial_sp_close(lsc_serial *s)
{
    s->sp = NULL;
}

int lsc_serial_list_ports(lsc_port_info *out, size_t cap, char *message, size_t msgcap)
{
    (void)out;
    (void)cap;
    copy_text(message, msgcap, "port listing needs libserialport: this lsc was built without it (install the Debian package libserialport-dev, then configure and build lsc again)");
    return LSC_ENODEV;
}

#endif /* LSC_HAVE_LIBSERIALPORT */

#endif
