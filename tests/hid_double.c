/* Test double of hidapi (contract in hid_double.h). Tests only. */
#define _DEFAULT_SOURCE 1

#include "hid_double.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <wchar.h>

#include <sys/stat.h>

#include <hidapi.h>

#include "../src/hid/hid_internal.h"

#define DEVICES 4
#define QUEUE 8u
#define REPORT 64u

/* The groups of the double's controllers: short, so run --wait ends soon in
 * virtual time (the same group numbers as lscctl's --port sim). */
static const char groups_text[] = "group 1\n"
                                  "step 500 1:1000 2:2000\n"
                                  "step 500 1:1500 2:1500\n"
                                  "group 8\n"
                                  "step 1000 1:2000 2:1200 3:1500\n"
                                  "step 500 1:1500 2:1500 3:1500\n";

typedef struct device {
    char path[256];
    wchar_t serial[64];
    unsigned flags;
    uint8_t pad;
    int run_group; /* -1: none */
    uint16_t vid, pid; /* USB ids: 0483:5750 unless set */
} device;

/* One open arm; hid_device, opaque to hidapi's callers, points to one. */
typedef struct arm {
    int index;
    lsc_sim sim;
    lsc_sim_groups groups;
    lsc_sim_step steps[8];
    lsc_servo targets[16];
    uint8_t queue[QUEUE][REPORT]; /* reports due before the controller's next */
    size_t head, count;
    unsigned frames_in;
    int unplugged;
} arm;

static arm *arm_of(hid_device *handle)
{
    return (arm *)(void *)handle;
}

static device devices[DEVICES];
static int ndevices;
static int env_read;
static int inits;
static int open_handles;
static unsigned open_calls;
static unsigned writes;
static uint8_t last_write[REPORT + 1u];
static size_t last_write_len;
static const wchar_t *global_error = L"Success";

static void read_env(void);

void hid_double_reset(void)
{
    ndevices = 0;
    env_read = 1;
    writes = 0;
    open_calls = 0;
    last_write_len = 0;
}

int hid_double_add(const char *path, const char *serial, unsigned flags, uint8_t pad)
{
    if (ndevices >= DEVICES) {
        return -1;
    }
    device *d = &devices[ndevices];
    memset(d, 0, sizeof *d);
    snprintf(d->path, sizeof d->path, "%s", path);
    size_t i = 0;
    for (; serial[i] != '\0' && i + 1u < sizeof d->serial / sizeof d->serial[0]; i++) {
        d->serial[i] = (wchar_t)(unsigned char)serial[i];
    }
    d->serial[i] = L'\0';
    d->flags = flags;
    d->pad = pad;
    d->run_group = -1;
    d->vid = 0x0483;
    d->pid = 0x5750;
    return ndevices++;
}

void hid_double_set_flags(int index, unsigned flags)
{
    devices[index].flags = flags;
}

void hid_double_set_ids(int index, uint16_t vid, uint16_t pid)
{
    if (index >= 0 && index < ndevices) {
        devices[index].vid = vid;
        devices[index].pid = pid;
    }
}

unsigned hid_double_open_calls(void)
{
    return open_calls;
}

/* The transport's node check (src/hid/hid_internal.h), in place of
 * hid_live.c's: a device of the double is a regular file standing for a
 * hidraw node on USB with the device's ids; any other path gets the real
 * checks against the system's sysfs. */
int lsc_hid_node_identify_live(const char *path, lsc_hid_node *node, lsc_port_error *e)
{
    read_env();
    struct stat st;
    for (int i = 0; i < ndevices; i++) {
        if (strcmp(devices[i].path, path) == 0 && stat(path, &st) == 0) {
            memset(node, 0, sizeof *node);
            snprintf(node->path, sizeof node->path, "%s", path);
            node->bus = LSC_HID_BUS_USB;
            node->vid = devices[i].vid;
            node->pid = devices[i].pid;
            node->dev = st.st_dev;
            node->rdev = st.st_rdev;
            node->ino = st.st_ino;
            node->type = st.st_mode & S_IFMT;
            return 0;
        }
    }
    return lsc_hid_node_identify("", path, path, node, e);
}

static arm *handles[DEVICES];

lsc_sim *hid_double_sim(int index)
{
    return index >= 0 && index < DEVICES && handles[index] != NULL ? &handles[index]->sim : NULL;
}

size_t hid_double_last_write(uint8_t *out, size_t cap)
{
    size_t n = last_write_len < cap ? last_write_len : cap;
    memcpy(out, last_write, n);
    return last_write_len;
}

unsigned hid_double_writes(void)
{
    return writes;
}

int hid_double_inits(void)
{
    return inits;
}

int hid_double_open_handles(void)
{
    return open_handles;
}

/* "PATH|SERIAL|FLAGS;..." from $LSC_HID_DOUBLE. */
static void read_env(void)
{
    if (env_read) {
        return;
    }
    env_read = 1;
    const char *spec = getenv("LSC_HID_DOUBLE");
    char buf[2048];
    snprintf(buf, sizeof buf, "%s", spec != NULL ? spec : "");
    char *save = NULL;
    for (char *item = strtok_r(buf, ";", &save); item != NULL; item = strtok_r(NULL, ";", &save)) {
        char *f[3] = {item, (char *)"", (char *)""};
        char *bar = strchr(item, '|');
        if (bar != NULL) {
            *bar = '\0';
            f[1] = bar + 1;
            bar = strchr(f[1], '|');
            if (bar != NULL) {
                *bar = '\0';
                f[2] = bar + 1;
            }
        }
        unsigned flags = 0;
        unsigned pad = 0;
        int run = -1;
        unsigned long vid = 0x0483u, pid = 0x5750u;
        char *save2 = NULL;
        for (char *w = strtok_r(f[2], ",", &save2); w != NULL; w = strtok_r(NULL, ",", &save2)) {
            flags |= strcmp(w, "deny") == 0 ? HID_DOUBLE_DENY : 0u;
            flags |= strcmp(w, "mute-first") == 0 ? HID_DOUBLE_MUTE_FIRST : 0u;
            flags |= strcmp(w, "notify") == 0 ? HID_DOUBLE_NOTIFY : 0u;
            flags |= strcmp(w, "garbage") == 0 ? HID_DOUBLE_GARBAGE : 0u;
            flags |= strcmp(w, "unplug") == 0 ? HID_DOUBLE_UNPLUG : 0u;
            flags |= strcmp(w, "silent") == 0 ? HID_DOUBLE_SILENT : 0u;
            if (strncmp(w, "pad=", 4) == 0) {
                pad = (unsigned)strtoul(w + 4, NULL, 16) & 0xFFu;
            }
            if (strncmp(w, "run=", 4) == 0) {
                run = (int)strtol(w + 4, NULL, 10);
            }
            if (strncmp(w, "id=", 3) == 0) {
                char *colon = NULL;
                vid = strtoul(w + 3, &colon, 16) & 0xFFFFu;
                pid = colon != NULL && *colon == ':' ? strtoul(colon + 1, NULL, 16) & 0xFFFFu : 0u;
            }
        }
        int i = hid_double_add(f[0], f[1], flags, (uint8_t)pad);
        if (i >= 0) {
            devices[i].run_group = run;
            hid_double_set_ids(i, (uint16_t)vid, (uint16_t)pid);
        }
    }
}

int HID_API_EXPORT hid_init(void)
{
    read_env();
    inits++;
    return 0;
}

int HID_API_EXPORT hid_exit(void)
{
    inits--;
    return 0;
}

static wchar_t *wdup(const wchar_t *w)
{
    size_t n = wcslen(w) + 1u;
    wchar_t *p = calloc(n, sizeof *p);
    if (p != NULL) {
        memcpy(p, w, n * sizeof *p);
    }
    return p;
}

struct hid_device_info HID_API_EXPORT *hid_enumerate(unsigned short vendor_id,
                                                     unsigned short product_id)
{
    read_env();
    struct hid_device_info *first = NULL, **next = &first;
    for (int i = 0; i < ndevices; i++) {
        if ((vendor_id != 0 && vendor_id != devices[i].vid) ||
            (product_id != 0 && product_id != devices[i].pid)) {
            continue;
        }
        struct hid_device_info *d = calloc(1, sizeof *d);
        if (d == NULL) {
            break;
        }
        d->path = strdup(devices[i].path);
        d->vendor_id = devices[i].vid;
        d->product_id = devices[i].pid;
        d->serial_number = wdup(devices[i].serial);
        d->manufacturer_string = wdup(L"MyUSB_HID");
        d->product_string = wdup(L"LOBOT");
        d->usage_page = 0x8C;
        d->interface_number = 0;
        d->bus_type = HID_API_BUS_USB;
        *next = d;
        next = &d->next;
    }
    return first;
}

void HID_API_EXPORT hid_free_enumeration(struct hid_device_info *devs)
{
    while (devs != NULL) {
        struct hid_device_info *next = devs->next;
        free(devs->path);
        free(devs->serial_number);
        free(devs->manufacturer_string);
        free(devs->product_string);
        free(devs);
        devs = next;
    }
}

HID_API_EXPORT hid_device *hid_open_path(const char *path)
{
    read_env();
    open_calls++;
    for (int i = 0; i < ndevices; i++) {
        if (strcmp(devices[i].path, path) != 0) {
            continue;
        }
        if (devices[i].flags & HID_DOUBLE_DENY) {
            global_error = L"Failed to open a device: Permission denied";
            errno = EACCES;
            return NULL;
        }
        if (devices[i].flags & HID_DOUBLE_SILENT) {
            global_error = L"Success"; /* what hidapi 0.13 says when its error is not errno's */
            errno = 0;
            return NULL;
        }
        arm *h = calloc(1, sizeof *h);
        if (h == NULL) {
            errno = ENOMEM;
            return NULL;
        }
        h->index = i;
        lsc_sim_init(&h->sim);
        lsc_sim_groups_init(&h->groups, h->steps, 8, h->targets, 16);
        lsc_sim_groups_parse(&h->groups, groups_text, sizeof groups_text - 1u, NULL);
        lsc_sim_set_groups(&h->sim, &h->groups);
        if (devices[i].run_group >= 0) {
            (void)lsc_sim_group_run(&h->sim, (uint8_t)devices[i].run_group, 1);
        }
        handles[i] = h;
        open_handles++;
        global_error = L"Success";
        return (hid_device *)(void *)h;
    }
    global_error = L"Failed to open a device: No such file or directory";
    errno = ENOENT;
    return NULL;
}

HID_API_EXPORT hid_device *hid_open(unsigned short vendor_id, unsigned short product_id,
                                    const wchar_t *serial_number)
{
    read_env();
    for (int i = 0; i < ndevices; i++) {
        if (vendor_id == devices[i].vid && product_id == devices[i].pid &&
            (serial_number == NULL || wcscmp(serial_number, devices[i].serial) == 0)) {
            return hid_open_path(devices[i].path);
        }
    }
    errno = ENOENT;
    return NULL;
}

void HID_API_EXPORT hid_close(hid_device *handle)
{
    arm *dev = arm_of(handle);
    if (dev == NULL) {
        return;
    }
    if (handles[dev->index] == dev) {
        handles[dev->index] = NULL;
    }
    open_handles--;
    free(dev);
}

static void queue_report(arm *dev, const uint8_t *frame, size_t n)
{
    if (dev->count == QUEUE) {
        return;
    }
    uint8_t *r = dev->queue[(dev->head + dev->count++) % QUEUE];
    memset(r, devices[dev->index].pad, REPORT);
    memcpy(r, frame, n);
}

static void log_write(const unsigned char *data, size_t length)
{
    const char *name = getenv("LSC_HID_DOUBLE_LOG");
    FILE *f = name != NULL ? fopen(name, "a") : NULL;
    if (f == NULL) {
        return;
    }
    for (size_t i = 0; i < length; i++) {
        fprintf(f, "%s%02X", i == 0 ? "" : " ", data[i]);
    }
    fputc('\n', f);
    (void)fclose(f);
}

int HID_API_EXPORT hid_write(hid_device *handle, const unsigned char *data, size_t length)
{
    arm *dev = arm_of(handle);
    if (dev->unplugged) {
        global_error = L"hid_write: device disconnected";
        errno = ENODEV;
        return -1;
    }
    writes++;
    last_write_len = length < sizeof last_write ? length : sizeof last_write;
    memcpy(last_write, data, last_write_len);
    log_write(data, length);
    /* the arm's OUT endpoint takes 64-byte reports; hidapi wants the report id first */
    if (length != REPORT + 1u || data[0] != 0x00) {
        global_error = L"hid_write: wrong report size";
        errno = EINVAL;
        return -1;
    }
    const uint8_t *frame = data + 1;
    size_t n = frame[0] == 0x55 && frame[1] == 0x55 ? (size_t)frame[2] + 2u : REPORT;
    dev->frames_in++;
    if (devices[dev->index].flags & HID_DOUBLE_UNPLUG) {
        dev->unplugged = 1;
    }
    if (dev->frames_in == 1u && (devices[dev->index].flags & HID_DOUBLE_MUTE_FIRST)) {
        return (int)length; /* woken up by it, answers nothing */
    }
    lsc_sim_feed(&dev->sim, frame, n > REPORT ? REPORT : n);
    if (n >= 4u && (frame[3] == 15u || frame[3] == 21u)) { /* a request: reply reports follow */
        if (devices[dev->index].flags & HID_DOUBLE_GARBAGE) {
            static const uint8_t junk[] = {0x12, 0x55, 0x34, 0x55, 0x55, 0x7F, 0x0F};
            queue_report(dev, junk, sizeof junk);
        }
        if (devices[dev->index].flags & HID_DOUBLE_NOTIFY) {
            static const uint8_t stop[] = {0x55, 0x55, 0x02, 0x07};
            queue_report(dev, stop, sizeof stop);
        }
    }
    return (int)length;
}

/* The controller's next frame, as a report, if one is readable now. */
static int next_frame(arm *dev)
{
    uint8_t frame[REPORT];
    if (lsc_sim_available(&dev->sim) < 3u) {
        return 0;
    }
    (void)lsc_sim_read(&dev->sim, frame, 3);
    size_t rest = (size_t)frame[2] - 1u;
    if (rest + 3u > REPORT) {
        rest = REPORT - 3u;
    }
    (void)lsc_sim_read(&dev->sim, frame + 3, rest);
    queue_report(dev, frame, rest + 3u);
    return 1;
}

static void real_sleep_ms(int ms)
{
    struct timespec t = {ms / 1000, (long)(ms % 1000) * 1000000L};
    while (nanosleep(&t, &t) != 0 && errno == EINTR) {
    }
}

int HID_API_EXPORT hid_read_timeout(hid_device *handle, unsigned char *data, size_t length,
                                    int milliseconds)
{
    arm *dev = arm_of(handle);
    if (dev->unplugged) {
        global_error = L"hid_read_timeout: unexpected poll error (device disconnected)";
        errno = ENODEV;
        return -1;
    }
    uint64_t left = milliseconds < 0 ? UINT64_MAX : (uint64_t)milliseconds * 1000u;
    for (;;) {
        if (dev->count == 0u) {
            (void)next_frame(dev);
        }
        if (dev->count > 0u) {
            size_t n = length < REPORT ? length : REPORT;
            memcpy(data, dev->queue[dev->head], n);
            dev->head = (dev->head + 1u) % QUEUE;
            dev->count--;
            return (int)n;
        }
        uint64_t step = lsc_sim_next_event_us(&dev->sim);
        if (step == LSC_SIM_TIME_NEVER) {
            /* nothing will ever come: block like a silent device, while the
             * arm's time passes as well (a move under way goes on) */
            if (milliseconds != 0) {
                int ms = milliseconds < 0 ? 1000 : milliseconds;
                real_sleep_ms(ms);
                lsc_sim_advance_us(&dev->sim, (uint64_t)ms * 1000u);
            }
            return 0;
        }
        if (step > left) {
            /* something comes later: the virtual clock runs ahead of the
             * real one, so the caller's next read gets it sooner */
            lsc_sim_advance_us(&dev->sim, left);
            return 0;
        }
        lsc_sim_advance_us(&dev->sim, step);
        left -= step;
    }
}

int HID_API_EXPORT hid_read(hid_device *dev, unsigned char *data, size_t length)
{
    return hid_read_timeout(dev, data, length, -1);
}

const wchar_t *HID_API_EXPORT hid_error(hid_device *dev)
{
    (void)dev;
    return global_error;
}
