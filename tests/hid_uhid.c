/* lscctl against a real (virtual) HID device with the xArm's IDs, through the
 * unmodified hidapi: where /dev/uhid exists (Linux with the uhid module, root
 * or a rule that opens /dev/uhid), this program creates a HID device 0483:5750
 * "LOBOT" with serial number LSCUHID<pid>, 64-byte reports and no report IDs,
 * answers battery requests like an arm (7.5 V), and runs
 * `lscctl --port hid:SERIAL battery`, `lscctl ports` and
 * `lscctl --port /dev/hidrawN battery` against it; then a second device with
 * ids no controller has (1209:0001), whose node lscctl must refuse unopened
 * (exit 1, nothing written to it). Elsewhere it exits 77, which ctest reports
 * as skipped, with a message why.
 *
 * Usage: hid_uhid LSCCTL */
#define _DEFAULT_SOURCE 1
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <linux/uhid.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "lsc/hid.h"
#include "test_time.h"

#define SKIP 77

/* One 64-byte input and one 64-byte output report, no report ID, on the
 * usage page the arm reports (0x008C). */
static const unsigned char descriptor[] = {
    0x06, 0x8C, 0x00,       /* Usage Page (0x008C) */
    0x09, 0x01,             /* Usage (1) */
    0xA1, 0x01,             /* Collection (Application) */
    0x09, 0x03,             /*   Usage (3) */
    0x15, 0x00,             /*   Logical Minimum (0) */
    0x26, 0xFF, 0x00,       /*   Logical Maximum (255) */
    0x75, 0x08,             /*   Report Size (8) */
    0x95, 0x40,             /*   Report Count (64) */
    0x81, 0x02,             /*   Input (Data, Var, Abs) */
    0x09, 0x04,             /*   Usage (4) */
    0x15, 0x00,             /*   Logical Minimum (0) */
    0x26, 0xFF, 0x00,       /*   Logical Maximum (255) */
    0x75, 0x08,             /*   Report Size (8) */
    0x95, 0x40,             /*   Report Count (64) */
    0x91, 0x02,             /*   Output (Data, Var, Abs) */
    0xC0                    /* End Collection */
};

static long now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1000L + ts.tv_nsec / 1000000L;
}

static int send_event(int fd, const struct uhid_event *ev)
{
    ssize_t n = write(fd, ev, sizeof *ev);
    return n == (ssize_t)sizeof *ev ? 0 : -1;
}

/* Handles one event from the kernel: answers a battery request report.
 * outputs, if not NULL, counts the output reports (anything written). */
static void handle_counted(int fd, unsigned *answered, unsigned *outputs)
{
    struct uhid_event ev;
    memset(&ev, 0, sizeof ev);
    ssize_t n = read(fd, &ev, sizeof ev);
    if (n <= 0 || ev.type != UHID_OUTPUT) {
        return;
    }
    if (outputs != NULL) {
        (*outputs)++;
    }
    const unsigned char *d = ev.u.output.data;
    size_t size = ev.u.output.size;
    if (size == 65 && d[0] == 0x00) { /* the report ID byte hidraw passed on */
        d++;
        size--;
    }
    if (size >= 4 && d[0] == 0x55 && d[1] == 0x55 && d[2] == 0x02 && d[3] == 0x0F) {
        static const unsigned char reply[] = {0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D};
        struct uhid_event in;
        memset(&in, 0, sizeof in);
        in.type = UHID_INPUT2;
        in.u.input2.size = 64;
        memcpy(in.u.input2.data, reply, sizeof reply);
        if (send_event(fd, &in) == 0) {
            (*answered)++;
        }
    }
}

static void handle(int fd, unsigned *answered)
{
    handle_counted(fd, answered, NULL);
}

/* Creates a uhid device with ids vid:pid and serial number serial on a
 * fresh /dev/uhid descriptor; returns it, or -1. */
static int create_device(const char *serial, uint16_t vid, uint16_t pid)
{
    int fd = open("/dev/uhid", O_RDWR | O_CLOEXEC);
    if (fd < 0) {
        return -1;
    }
    struct uhid_event ev;
    memset(&ev, 0, sizeof ev);
    ev.type = UHID_CREATE2;
    snprintf((char *)ev.u.create2.name, sizeof ev.u.create2.name, "LOBOT");
    snprintf((char *)ev.u.create2.uniq, sizeof ev.u.create2.uniq, "%s", serial);
    ev.u.create2.rd_size = sizeof descriptor;
    memcpy(ev.u.create2.rd_data, descriptor, sizeof descriptor);
    ev.u.create2.bus = 0x03; /* BUS_USB */
    ev.u.create2.vendor = vid;
    ev.u.create2.product = pid;
    if (send_event(fd, &ev) != 0) {
        close(fd);
        return -1;
    }
    return fd;
}

/* The /dev/hidrawN of the HID device with serial number serial (its sysfs
 * uevent's HID_UNIQ) into out, once the node exists; 0, or -1 if none. */
static int find_node(const char *serial, char *out, size_t cap)
{
    DIR *d = opendir("/sys/class/hidraw");
    if (d == NULL) {
        return -1;
    }
    char want[96];
    snprintf(want, sizeof want, "HID_UNIQ=%s\n", serial);
    int found = -1;
    for (struct dirent *e = readdir(d); e != NULL && found != 0; e = readdir(d)) {
        if (strncmp(e->d_name, "hidraw", 6) != 0) {
            continue;
        }
        char path[300], text[4096];
        snprintf(path, sizeof path, "/sys/class/hidraw/%s/device/uevent", e->d_name);
        FILE *f = fopen(path, "r");
        if (f == NULL) {
            continue;
        }
        size_t n = fread(text, 1, sizeof text - 1u, f);
        text[n] = '\0';
        (void)fclose(f);
        /* a node name too long for out is not ours (the caller's buffer
         * holds any hidrawN) */
        int len = snprintf(out, cap, "/dev/%s", e->d_name);
        if (len < 0 || (size_t)len >= cap) {
            continue;
        }
        if (strstr(text, want) != NULL && access(out, F_OK) == 0) {
            found = 0;
        }
    }
    closedir(d);
    return found;
}

/* find_node, waiting for udev (or devtmpfs) to make the node while the
 * device fd is served. */
static int wait_node(int fd, const char *serial, char *out, size_t cap)
{
    long deadline = now_ms() + test_ms(5000);
    while (find_node(serial, out, cap) != 0) {
        if (now_ms() > deadline) {
            return -1;
        }
        struct pollfd p = {fd, POLLIN, 0};
        if (poll(&p, 1, 20) > 0) {
            unsigned ignored = 0;
            handle(fd, &ignored);
        }
    }
    return 0;
}

/* Runs argv with stdout into out (cap bytes) while answering the device
 * (counting in *outputs, if not NULL, every report written to it); returns
 * its exit status, or -1 if it did not end by the deadline. */
static int run_counted(int fd, char *const argv[], char *out, size_t cap, unsigned *answered,
                       unsigned *outputs)
{
    int pipefd[2];
    if (pipe(pipefd) != 0) {
        return -1;
    }
    pid_t pid = fork();
    if (pid == 0) {
        dup2(pipefd[1], 1);
        close(pipefd[0]);
        close(pipefd[1]);
        execv(argv[0], argv);
        _exit(127);
    }
    close(pipefd[1]);
    size_t len = 0;
    long deadline = now_ms() + test_ms(10000);
    int status = -1;
    for (;;) {
        struct pollfd p[2] = {{fd, POLLIN, 0}, {pipefd[0], POLLIN, 0}};
        (void)poll(p, 2, 50);
        if (p[0].revents & POLLIN) {
            handle_counted(fd, answered, outputs);
        }
        if ((p[1].revents & POLLIN) && len + 1 < cap) {
            ssize_t n = read(pipefd[0], out + len, cap - 1 - len);
            len += n > 0 ? (size_t)n : 0u;
        }
        int st;
        if (waitpid(pid, &st, WNOHANG) == pid) {
            ssize_t n;
            while (len + 1 < cap && (n = read(pipefd[0], out + len, cap - 1 - len)) > 0) {
                len += (size_t)n;
            }
            status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
            break;
        }
        if (now_ms() > deadline) {
            kill(pid, SIGKILL);
            waitpid(pid, NULL, 0);
            break;
        }
    }
    close(pipefd[0]);
    out[len] = '\0';
    return status;
}

static int run(int fd, char *const argv[], char *out, size_t cap, unsigned *answered)
{
    return run_counted(fd, argv, out, cap, answered, NULL);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s LSCCTL\n", argv[0]);
        return 2;
    }
    int fd = open("/dev/uhid", O_RDWR | O_CLOEXEC);
    if (fd < 0) {
        printf("SKIP: cannot open /dev/uhid (%s): this kernel or user cannot create a "
               "virtual HID device; the hidapi test double covers the transport\n",
               strerror(errno));
        return SKIP;
    }
    char serial[32];
    snprintf(serial, sizeof serial, "LSCUHID%ld", (long)getpid());
    struct uhid_event ev;
    memset(&ev, 0, sizeof ev);
    ev.type = UHID_CREATE2;
    snprintf((char *)ev.u.create2.name, sizeof ev.u.create2.name, "LOBOT");
    snprintf((char *)ev.u.create2.uniq, sizeof ev.u.create2.uniq, "%s", serial);
    ev.u.create2.rd_size = sizeof descriptor;
    memcpy(ev.u.create2.rd_data, descriptor, sizeof descriptor);
    ev.u.create2.bus = 0x03; /* BUS_USB */
    ev.u.create2.vendor = LSC_HID_VID;
    ev.u.create2.product = LSC_HID_PID;
    if (send_event(fd, &ev) != 0) {
        printf("SKIP: /dev/uhid refused to create a device (%s)\n", strerror(errno));
        close(fd);
        return SKIP;
    }
    int failures = 0;
    /* wait until hidapi lists it (udev may still be making the node) */
    long deadline = now_ms() + test_ms(5000);
    char port[64];
    snprintf(port, sizeof port, "hid:%s", serial);
    for (;;) {
        lsc_hid_info info[16];
        info[0].size = sizeof info[0];
        int n = lsc_hid_list(info, 16, 0, 0, NULL, 0);
        int found = 0;
        for (int i = 0; i < n && i < 16; i++) {
            found |= strcmp(info[i].serial, serial) == 0;
        }
        if (found) {
            break;
        }
        if (now_ms() > deadline) {
            printf("FAIL: hidapi does not list the virtual arm %s\n", serial);
            close(fd);
            return 1;
        }
        struct pollfd p = {fd, POLLIN, 0};
        if (poll(&p, 1, 20) > 0) {
            unsigned ignored = 0;
            handle(fd, &ignored);
        }
    }
    unsigned answered = 0;
    char out[4096];
    char *battery[] = {argv[1], (char *)"--port", port, (char *)"battery", NULL};
    int st = run(fd, battery, out, sizeof out, &answered);
    if (st != 0 || strcmp(out, "7.500 V (7500 mV)\n") != 0 || answered == 0) {
        printf("FAIL: lscctl --port %s battery: exit %d, output '%s', %u answered\n", port, st,
               out, answered);
        failures++;
    }
    char *ports[] = {argv[1], (char *)"ports", NULL};
    st = run(fd, ports, out, sizeof out, &answered);
    if (st != 0 || strstr(out, serial) == NULL || strstr(out, "0483:5750") == NULL) {
        printf("FAIL: lscctl ports: exit %d, output '%s'\n", st, out);
        failures++;
    }
    /* by its node: the real sysfs says hidraw, USB, 0483:5750 */
    char node[64];
    if (wait_node(fd, serial, node, sizeof node) != 0) {
        printf("FAIL: no /dev/hidrawN for %s in /sys/class/hidraw\n", serial);
        failures++;
    } else {
        char *by_path[] = {argv[1], (char *)"--port", node, (char *)"battery", NULL};
        answered = 0;
        st = run(fd, by_path, out, sizeof out, &answered);
        if (st != 0 || strcmp(out, "7.500 V (7500 mV)\n") != 0 || answered == 0) {
            printf("FAIL: lscctl --port %s battery: exit %d, output '%s', %u answered\n", node,
                   st, out, answered);
            failures++;
        }
    }
    /* a HID device with other ids: its node is refused, nothing written */
    char other[32];
    snprintf(other, sizeof other, "LSCOTHER%ld", (long)getpid());
    int ofd = create_device(other, 0x1209, 0x0001);
    if (ofd < 0 || wait_node(ofd, other, node, sizeof node) != 0) {
        printf("FAIL: a second virtual HID device (%s) did not appear\n", other);
        failures++;
    } else {
        char *foreign[] = {argv[1], (char *)"--port", node, (char *)"move", (char *)"1:500",
                           NULL};
        unsigned outputs = 0, none = 0;
        st = run_counted(ofd, foreign, out, sizeof out, &none, &outputs);
        /* what the kernel may still hold for it */
        struct pollfd p = {ofd, POLLIN, 0};
        while (poll(&p, 1, 0) > 0 && (p.revents & POLLIN)) {
            handle_counted(ofd, &none, &outputs);
        }
        if (st != 1 || outputs != 0) {
            printf("FAIL: lscctl --port %s (1209:0001) move: exit %d (want 1), %u reports "
                   "written (want 0)\n",
                   node, st, outputs);
            failures++;
        }
    }
    if (ofd >= 0) {
        memset(&ev, 0, sizeof ev);
        ev.type = UHID_DESTROY;
        (void)send_event(ofd, &ev);
        close(ofd);
    }
    memset(&ev, 0, sizeof ev);
    ev.type = UHID_DESTROY;
    (void)send_event(fd, &ev);
    close(fd);
    printf("%s: lscctl over a virtual HID arm (%s)\n", failures ? "FAIL" : "PASS", serial);
    return failures ? 1 : 0;
}
