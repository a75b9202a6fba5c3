/* LD_PRELOAD shim for lscctl's tests: libserialport's port listing returns
 * the ports described in $LSCCTL_TEST_PORTS instead of the machine's, so the
 * tests can show `ports` and the choice of "the one port that looks like a
 * controller" with USB adapters that are not there.
 *
 *   LSCCTL_TEST_PORTS="PATH|DESCRIPTION|VID:PID|SERIAL;..."   (VID:PID '-': not USB)
 *
 * Calls about any other sp_port go to the real libserialport. */
#include <dlfcn.h>
#include <libserialport.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_PORTS 8

struct fake {
    char path[128], description[128], serial[64];
    int usb, vid, pid;
};

static struct fake fakes[MAX_PORTS];

static struct fake *fake_of(const struct sp_port *p)
{
    const struct fake *f = (const struct fake *)(const void *)p;
    return f >= fakes && f < fakes + MAX_PORTS ? (struct fake *)f : NULL;
}

/* The real libserialport function sym, stored into *fn (a function pointer). */
static void real(const char *sym, void *fn, size_t size)
{
    void *p = dlsym(RTLD_NEXT, sym);
    memcpy(fn, &p, size);
}

typedef char *(*text_fn)(const struct sp_port *);

static char *real_text(const char *sym, const struct sp_port *port)
{
    text_fn fn;
    real(sym, &fn, sizeof fn);
    return fn(port);
}

/* "VVVV:PPPP" (hex) into *vid, *pid; false for anything else ("-": not USB). */
static int parse_vid_pid(const char *s, int *vid, int *pid)
{
    char *end;
    unsigned long v = strtoul(s, &end, 16);
    if (end == s || *end != ':' || v > 0xFFFFu) {
        return 0;
    }
    const char *p = end + 1;
    unsigned long q = strtoul(p, &end, 16);
    if (end == p || *end != '\0' || q > 0xFFFFu) {
        return 0;
    }
    *vid = (int)v;
    *pid = (int)q;
    return 1;
}

enum sp_return sp_list_ports(struct sp_port ***list_ptr)
{
    const char *spec = getenv("LSCCTL_TEST_PORTS");
    struct sp_port **list = calloc(MAX_PORTS + 1, sizeof(struct sp_port *)); /* NULL-terminated */
    char buf[1024];
    size_t n = 0;
    if (list == NULL) {
        return SP_ERR_MEM;
    }
    snprintf(buf, sizeof buf, "%s", spec ? spec : "");
    for (char *save = NULL, *item = strtok_r(buf, ";", &save); item && n < MAX_PORTS;
         item = strtok_r(NULL, ";", &save)) {
        struct fake *f = &fakes[n];
        char *fields[4] = {"", "", "-", ""};
        char *rest = item;
        for (int i = 0; i < 4 && rest != NULL; i++) {
            fields[i] = rest;
            rest = strchr(rest, '|');
            if (rest != NULL) {
                *rest++ = '\0';
            }
        }
        snprintf(f->path, sizeof f->path, "%s", fields[0]);
        snprintf(f->description, sizeof f->description, "%s", fields[1]);
        snprintf(f->serial, sizeof f->serial, "%s", fields[3]);
        f->usb = parse_vid_pid(fields[2], &f->vid, &f->pid);
        list[n++] = (struct sp_port *)(void *)f;
    }
    *list_ptr = list;
    return SP_OK;
}

void sp_free_port_list(struct sp_port **ports)
{
    if (ports != NULL && (ports[0] == NULL || fake_of(ports[0]) != NULL)) {
        free(ports);
        return;
    }
    void (*fn)(struct sp_port **);
    real("sp_free_port_list", &fn, sizeof fn);
    fn(ports);
}

char *sp_get_port_name(const struct sp_port *port)
{
    struct fake *f = fake_of(port);
    return f ? f->path : real_text("sp_get_port_name", port);
}

char *sp_get_port_description(const struct sp_port *port)
{
    struct fake *f = fake_of(port);
    return f ? f->description : real_text("sp_get_port_description", port);
}

enum sp_transport sp_get_port_transport(const struct sp_port *port)
{
    struct fake *f = fake_of(port);
    if (f != NULL) {
        return f->usb ? SP_TRANSPORT_USB : SP_TRANSPORT_NATIVE;
    }
    enum sp_transport (*fn)(const struct sp_port *);
    real("sp_get_port_transport", &fn, sizeof fn);
    return fn(port);
}

enum sp_return sp_get_port_usb_vid_pid(const struct sp_port *port, int *vid, int *pid)
{
    struct fake *f = fake_of(port);
    if (f != NULL) {
        *vid = f->vid;
        *pid = f->pid;
        return f->usb ? SP_OK : SP_ERR_ARG;
    }
    enum sp_return (*fn)(const struct sp_port *, int *, int *);
    real("sp_get_port_usb_vid_pid", &fn, sizeof fn);
    return fn(port, vid, pid);
}

char *sp_get_port_usb_serial(const struct sp_port *port)
{
    struct fake *f = fake_of(port);
    return f ? f->serial : real_text("sp_get_port_usb_serial", port);
}
