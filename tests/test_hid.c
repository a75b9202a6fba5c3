/* The HID transport (src/hid) and the client over it, against the hidapi
 * test double (hid_double.c, linked in place of libhidapi-hidraw): the
 * report rules, notifications and garbage between reports, an arm that does
 * not answer the first request, unplugging, permissions, choosing by serial
 * number, exclusivity; which nodes are handed to hidapi at all (the real
 * checks on real files, and on /dev/zero dressed up as a hidraw node by a
 * fake sysfs). /dev/null is checked loosely: on a shared machine a root
 * process that writes "atomically" over it can leave a regular file there
 * for a moment. */
#define _DEFAULT_SOURCE 1
#define _XOPEN_SOURCE 700
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include "hid_double.h"
#include "lsc/client.h"
#include "lsc/hid.h"
#include "sized_test.h"
#include "../src/hid/hid_internal.h"

void *__real_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)

static bool calloc_fails; /* the next calloc fails */

void *__wrap_calloc(size_t n, size_t size) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (calloc_fails) {
        calloc_fails = false;
        return NULL;
    }
    return __real_calloc(n, size);
}

static char dir[64];
static char node_a[128], node_b[128];

/* A fresh temporary directory with two device nodes (regular files). */
static int setup(void **state)
{
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/lsc-test-hid-XXXXXX");
    if (mkdtemp(dir) == NULL) {
        return -1;
    }
    snprintf(node_a, sizeof node_a, "%s/hidraw0", dir);
    snprintf(node_b, sizeof node_b, "%s/hidraw1", dir);
    FILE *f = fopen(node_a, "w");
    FILE *g = fopen(node_b, "w");
    if (f != NULL) {
        (void)fclose(f);
    }
    if (g != NULL) {
        (void)fclose(g);
    }
    hid_double_reset();
    return f != NULL && g != NULL ? 0 : -1;
}

static int remove_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)ftw;
    return (flag == FTW_DP ? rmdir(path) : unlink(path)) == 0 ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    /* first: a failed test leaves nothing behind */
    (void)nftw(dir, remove_one, 16, FTW_DEPTH | FTW_PHYS);
    assert_int_equal(hid_double_open_handles(), 0); /* every handle was closed */
    return 0;
}

typedef struct hid_link {
    lsc_hid *hid;
    lsc_io io;
    lsc_client client;
} hid_link;

static void open_link(hid_link *l, const char *path)
{
    l->hid = NULL;
    assert_int_equal(lsc_hid_open_path(path, &l->hid), 0);
    lsc_hid_get_io(l->hid, &l->io);
    assert_int_equal(lsc_client_init(&l->client, &l->io), 0);
}

static void test_list(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0);
    hid_double_add(node_b, "ARM-B", 0, 0);
    lsc_hid_info info[4];
    info[0].size = sizeof info[0];
    char msg[128];
    assert_true(lsc_hid_available());
    assert_int_equal(lsc_hid_list(info, 4, 0, 0, msg, sizeof msg), 2);
    assert_string_equal(info[0].path, node_a);
    assert_string_equal(info[0].serial, "ARM-A");
    assert_string_equal(info[1].serial, "ARM-B");
    assert_string_equal(info[0].product, "LOBOT");
    assert_int_equal(info[0].vid, 0x0483);
    assert_int_equal(info[0].pid, 0x5750);
    assert_int_equal(info[1].size, sizeof info[1]); /* set in every element written */
    /* more than fit: the count, only cap written */
    assert_int_equal(lsc_hid_list(info, 1, 0, 0, NULL, 0), 2);
    /* other ids: none */
    assert_int_equal(lsc_hid_list(info, 4, 0x1234, 0x5678, NULL, 0), 0);
    assert_int_equal(lsc_hid_list(NULL, 1, 0, 0, msg, sizeof msg), LSC_EINVAL);
}

/* lsc_hid_list of every id, as the sized tests call a listing */
static int list_all(void *out, size_t cap, char *message, size_t msgcap)
{
    return lsc_hid_list(out, cap, 0, 0, message, msgcap);
}

/* A program built when lsc_hid_info ended at serial: elements of that size,
 * the stride honoured, nothing written past each (the guard after the
 * elements written stays), each element's size its own; a program whose
 * lsc_hid_info is larger gets the bytes beyond this one's untouched. */
static void test_list_short_and_long_elements(void **state)
{
    (void)state;
    hid_double_add("/nonexistent/hidraw5", "ARM-A", 0, 0);
    hid_double_add("/nonexistent/hidraw6", "ARM-B", 0, 0);
    hid_double_add("/nonexistent/hidraw7", "ARM-C", 0, 0);
    lsc_hid_info store[4]; /* aligned room for three short elements and a guard */
    const size_t size = offsetof(lsc_hid_info, product); /* size, path, serial */
    assert_int_equal(sized_list_stride(list_all, store, sizeof store, size, 2, size), 3);
    for (size_t i = 0; i < 2; i++) {
        const char *e = (const char *)sized_element(store, size, i);
        assert_string_equal(e + offsetof(lsc_hid_info, path),
                            i == 0 ? "/nonexistent/hidraw5" : "/nonexistent/hidraw6");
        assert_string_equal(e + offsetof(lsc_hid_info, serial), i == 0 ? "ARM-A" : "ARM-B");
    }

    /* larger than this lsc_hid_info: written up to its own size only */
    const size_t big = sizeof(lsc_hid_info) + 40u;
    lsc_hid_info bigger[3]; /* room for two of them */
    assert_int_equal(sized_list_stride(list_all, bigger, sizeof bigger, big, 2,
                                       sizeof(lsc_hid_info)),
                     3);
    for (size_t i = 0; i < 2; i++) {
        lsc_hid_info got;
        memcpy(&got, sized_element(bigger, big, i), sizeof got);
        assert_string_equal(got.serial, i == 0 ? "ARM-A" : "ARM-B");
        assert_string_equal(got.product, "LOBOT");
        assert_int_equal(got.vid, 0x0483);
    }
}

/* A size below its size field and path is refused, nothing written; no
 * element (counting only) needs none. */
static void test_list_size_too_small(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0);
    lsc_hid_info info[2];
    char msg[256];
    const size_t least = offsetof(lsc_hid_info, path) + LSC_HID_PATH_MAX;
    assert_true(sized_list_refuses_small(list_all, info, sizeof info[0], least, "lsc_hid_info"));
    /* the least is enough: path only */
    memcpy(info, &least, sizeof least);
    assert_int_equal(lsc_hid_list(info, 1, 0, 0, msg, sizeof msg), 1);
    assert_string_equal(info[0].path, node_a);
    /* counting: no element, no size */
    memset(info, 0xA5, sizeof info);
    assert_int_equal(lsc_hid_list(info, 0, 0, 0, NULL, 0), 1);
    assert_int_equal(lsc_hid_list(NULL, 0, 0, 0, NULL, 0), 1);
}

/* A battery round trip: 65-byte write, 0x00 first, the frame, zero padding. */
static void test_write_report(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0);
    hid_link l;
    open_link(&l, node_a);
    lsc_sim_set_battery(hid_double_sim(0), 7321);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&l.client, &mv, 1000), 0);
    assert_int_equal(mv, 7321);
    uint8_t w[80];
    assert_int_equal(hid_double_last_write(w, sizeof w), 65);
    static const uint8_t want[] = {0x00, 0x55, 0x55, 0x02, 0x0F};
    assert_memory_equal(w, want, sizeof want);
    for (size_t i = sizeof want; i < 65; i++) {
        assert_int_equal(w[i], 0);
    }
    /* a move of 6 servos goes out as one report too */
    lsc_servo s[6] = {{1, 100}, {2, 200}, {3, 300}, {4, 400}, {5, 500}, {6, 600}};
    assert_int_equal(lsc_client_move(&l.client, 500, s, 6), 0);
    assert_int_equal(hid_double_last_write(w, sizeof w), 65);
    assert_int_equal(w[3], 3 * 6 + 5);
    lsc_servo got[6];
    uint8_t ids[6] = {1, 2, 3, 4, 5, 6};
    lsc_sim_advance_ms(hid_double_sim(0), 600);
    assert_int_equal(lsc_client_read_positions(&l.client, ids, 6, got, 1000), 6);
    assert_int_equal(got[5].id, 6);
    assert_int_equal(got[5].position, 600);
    lsc_hid_close(l.hid);
    lsc_hid_close(NULL); /* NULL is safe */
}

/* Frames that do not fit a report, or are not whole, are refused unsent. */
static void test_write_refused(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0);
    hid_link l;
    open_link(&l, node_a);
    unsigned before = hid_double_writes();
    lsc_servo s[20];
    for (uint8_t i = 0; i < 20; i++) {
        s[i].id = i;
        s[i].position = 1500;
    }
    /* 20 servos: a 67-byte frame */
    assert_int_equal(lsc_client_move(&l.client, 500, s, 20), LSC_EINVAL);
    assert_non_null(strstr(lsc_hid_error_message(l.hid), "one whole frame"));
    static const uint8_t part[] = {0x55, 0x55, 0x04, 0x0F};
    assert_int_equal(lsc_hid_write(l.hid, part, sizeof part), LSC_EINVAL);
    assert_int_equal(lsc_hid_write(l.hid, NULL, 0), LSC_EINVAL);
    assert_int_equal(hid_double_writes(), before);
    /* 19 servos: 64 bytes, the largest that fits */
    assert_int_equal(lsc_client_move(&l.client, 500, s + 1, 19), 0);
    assert_int_equal(hid_double_writes(), before + 1u);
    lsc_hid_close(l.hid);
}

/* Padding that is not zero is ignored; a small buffer gets the frame in parts. */
static void test_padding_and_small_reads(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0x55);
    hid_link l;
    open_link(&l, node_a);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&l.client, &mv, 1000), 0);
    assert_int_equal(mv, 7500);
    static const uint8_t req[] = {0x55, 0x55, 0x02, 0x0F};
    assert_int_equal(lsc_hid_write(l.hid, req, sizeof req), 4);
    uint8_t buf[8];
    assert_int_equal(lsc_hid_read(l.hid, buf, 4, 1000), 4);
    assert_int_equal(lsc_hid_read(l.hid, buf + 4, 4, 1000), 2); /* the frame's end only */
    static const uint8_t reply[] = {0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D};
    assert_memory_equal(buf, reply, sizeof reply);
    /* nothing else: the padding never arrives */
    assert_int_equal(lsc_hid_read(l.hid, buf, sizeof buf, 0), 0);
    assert_int_equal(lsc_hid_reports_dropped(l.hid), 0);
    assert_int_equal(lsc_hid_read(l.hid, NULL, 1, 0), LSC_EINVAL);
    lsc_hid_close(l.hid);
}

static void count_notify(void *user, const lsc_notification *n)
{
    int *count = user;
    assert_int_equal(n->cmd, LSC_CMD_GROUP_STOP);
    (*count)++;
}

/* A notification report before the reply goes to the callback. */
static void test_notification_first(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", HID_DOUBLE_NOTIFY, 0);
    hid_link l;
    open_link(&l, node_a);
    int count = 0;
    lsc_client_set_notify(&l.client, count_notify, &count);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&l.client, &mv, 1000), 0);
    assert_int_equal(mv, 7500);
    assert_int_equal(count, 1);
    lsc_hid_close(l.hid);
}

/* A report without a frame is dropped and counted; the reply still comes. */
static void test_garbage_report(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", HID_DOUBLE_GARBAGE, 0);
    hid_link l;
    open_link(&l, node_a);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&l.client, &mv, 1000), 0);
    assert_int_equal(mv, 7500);
    assert_int_equal(lsc_hid_reports_dropped(l.hid), 1);
    uint8_t ids[2] = {1, 2};
    lsc_servo got[2];
    assert_int_equal(lsc_client_read_positions(&l.client, ids, 2, got, 1000), 2);
    assert_int_equal(lsc_hid_reports_dropped(l.hid), 2);
    lsc_hid_close(l.hid);
}

/* The first request after opening goes unanswered; sent again, it is. */
static void test_first_request_unanswered(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", HID_DOUBLE_MUTE_FIRST, 0);
    hid_link l;
    open_link(&l, node_a);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&l.client, &mv, 50), LSC_ETIMEOUT);
    assert_int_equal(lsc_client_get_battery(&l.client, &mv, 1000), 0);
    assert_int_equal(mv, 7500);
    lsc_hid_close(l.hid);
}

/* Unplugged while waiting for the reply: read fails, the error says so. */
static void test_unplug(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", HID_DOUBLE_UNPLUG, 0);
    hid_link l;
    open_link(&l, node_a);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&l.client, &mv, 1000), LSC_ENODEV);
    assert_non_null(strstr(lsc_hid_error_message(l.hid), "went away"));
    assert_non_null(strstr(lsc_hid_error_message(l.hid), "disconnected"));
    assert_int_equal(lsc_hid_os_errno(l.hid), ENODEV);
    assert_int_equal(lsc_client_stop_group(&l.client), LSC_ENODEV);
    lsc_hid_close(l.hid);
    /* the node is gone too: no such device */
    lsc_hid *h = NULL;
    unlink(node_b);
    hid_double_add(node_b, "ARM-B", 0, 0);
    assert_int_equal(lsc_hid_open_path(node_b, &h), LSC_ENODEV);
    assert_int_equal(lsc_hid_os_errno(h), ENOENT);
    assert_int_equal(lsc_hid_open_path("", &h), LSC_EINVAL);
    assert_string_equal(lsc_hid_error_message(h), "hid: invalid device path (empty or too long)");
    assert_int_equal(lsc_hid_open_path(node_a, NULL), LSC_EINVAL);
    /* a directory is no device: said so, errno kept, nothing left open */
    assert_int_equal(lsc_hid_open_path(dir, &h), LSC_ENODEV);
    assert_int_equal(lsc_hid_os_errno(h), EISDIR);
    assert_non_null(strstr(lsc_hid_error_message(h), ": a directory, not a device"));
    assert_null(h); /* nothing left open */
}

/* No memory for the handle: refused, no handle, the reason readable without
 * one; a NULL place for the handle is refused too; the next open works and
 * clears the thread's last error. */
static void test_open_out_of_memory(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0);
    lsc_hid *h = (lsc_hid *)&h;
    calloc_fails = true;
    assert_int_equal(lsc_hid_open_path(node_a, &h), LSC_ENOSPC);
    assert_null(h);
    assert_string_equal(lsc_hid_error_message(NULL), "out of memory");
    assert_int_equal(lsc_hid_os_errno(NULL), 0);
    assert_int_equal(hid_double_open_calls(), 0);
    assert_int_equal(lsc_hid_open_serial(NULL, NULL), LSC_EINVAL);
    assert_non_null(strstr(lsc_hid_error_message(NULL), "invalid argument"));
    assert_int_equal(lsc_hid_open_path(node_a, &h), 0);
    assert_string_equal(lsc_hid_error_message(NULL), "");
    lsc_hid_close(h);
}

/* Permission denied: LSC_EACCES, errno kept, the message names the fix. */
static void test_permission_denied(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", HID_DOUBLE_DENY, 0);
    lsc_hid *h = NULL;
    assert_int_equal(lsc_hid_open_path(node_a, &h), LSC_EACCES);
    assert_int_equal(lsc_hid_os_errno(h), EACCES);
    const char *m = lsc_hid_error_message(h);
    assert_non_null(strstr(m, node_a));
    assert_non_null(strstr(m, "Permission denied"));
    assert_non_null(strstr(m, "60-lsc.rules"));
    assert_non_null(strstr(m, "uaccess"));
    assert_non_null(strstr(m, "plugdev"));
    assert_non_null(strstr(m, "fwupd"));
    /* the lock was released: nothing is left open */
    assert_null(h); /* nothing left open */
}

/* Two arms told apart by serial number. */
static void test_by_serial(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0);
    hid_double_add(node_b, "ARM-B", 0, 0);
    lsc_hid *h = NULL;
    assert_int_equal(lsc_hid_open_serial(NULL, &h), LSC_EINVAL);
    assert_non_null(strstr(lsc_hid_error_message(h), "ARM-A, ARM-B"));
    assert_int_equal(lsc_hid_open_serial("ARM-C", &h), LSC_ENODEV);
    assert_non_null(strstr(lsc_hid_error_message(h), "present: ARM-A, ARM-B"));
    assert_int_equal(lsc_hid_open_serial("ARM-B", &h), 0);
    lsc_sim_set_battery(hid_double_sim(1), 6000);
    lsc_io io;
    lsc_client c;
    lsc_hid_get_io(h, &io);
    lsc_client_init(&c, &io);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&c, &mv, 1000), 0);
    assert_int_equal(mv, 6000); /* B's, not A's 7500 */
    lsc_hid_close(h);
    assert_int_equal(lsc_hid_open_serial("ARM-B", NULL), LSC_EINVAL);
}

static void test_none_present(void **state)
{
    (void)state;
    lsc_hid *h = NULL;
    assert_int_equal(lsc_hid_open_serial("", &h), LSC_ENODEV);
    assert_non_null(strstr(lsc_hid_error_message(h), "no HID controller"));
}

/* A second opener, in this process or another, is refused: port busy. */
static void test_second_opener(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0);
    hid_link l;
    open_link(&l, node_a);
    lsc_hid *second = NULL;
    assert_int_equal(lsc_hid_open_path(node_a, &second), LSC_EBUSY);
    assert_non_null(strstr(lsc_hid_error_message(second), "port busy"));
    /* this process holds it: the message says so */
    assert_non_null(strstr(lsc_hid_error_message(second), "this program has it open already"));
    assert_int_equal(hid_double_open_handles(), 1);
    /* another process (a child without its inherited copy): the HID
     * transport's hint, not the serial ports' */
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        (void)close(l.hid->lock_fd); /* (the lock stays the opener's) */
        _exit(lsc_hid_open_path(node_a, &second) == LSC_EBUSY &&
                      strstr(lsc_hid_error_message(second), "another program has the arm open")
                  ? 0
                  : 1);
    }
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    lsc_hid_close(l.hid);
    /* closed: the next opener gets it */
    assert_int_equal(lsc_hid_open_path(node_a, &second), 0);
    lsc_hid_close(second);
}

/* ---- Which nodes reach hidapi ---------------------------------------------- */

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    assert_true(fputs(text, f) >= 0);
    assert_int_equal(fclose(f), 0);
}

static void read_back(const char *path, char *out, size_t cap)
{
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    size_t n = fread(out, 1, cap - 1u, f);
    out[n] = '\0';
    assert_int_equal(fclose(f), 0);
}

/* Opening `path` (not a device of the double: the real checks) is refused
 * with LSC_ENODEV and a message holding `says`, before hidapi is called and
 * with nothing left open. */
static void refused(const char *path, const char *says)
{
    int inits = hid_double_inits();
    lsc_hid *h = NULL;
    assert_int_equal(lsc_hid_open_path(path, &h), LSC_ENODEV);
    const char *m = lsc_hid_error_message(h);
    if (strstr(m, says) == NULL) {
        fail_msg("%s: '%s' does not say '%s'", path, m, says);
    }
    assert_non_null(strstr(m, path));
    assert_null(strstr(m, "Success"));
    assert_null(h); /* nothing left open */
    assert_int_equal(hid_double_open_calls(), 0);
    assert_int_equal(hid_double_inits(), inits);
}

/* What is not a hidraw character device never reaches hidapi, nor is it
 * opened at all: a regular file (left as it was), a FIFO (no hang), a
 * directory, a socket, a missing path, /dev/null and a symbolic link to it
 * (a character device, but of class mem), and the same by serial number:
 * the double lists a regular file no device of it stands for. */
static void test_not_a_hidraw_node(void **state)
{
    (void)state;
    char file[160], fifo[160], sock[160], link_null[160], link_file[160], back[16];
    snprintf(file, sizeof file, "%s/hidraw5", dir);
    write_file(file, "x\n");
    refused(file, "a regular file, not a device");
    read_back(file, back, sizeof back);
    assert_string_equal(back, "x\n");

    snprintf(fifo, sizeof fifo, "%s/hidraw6", dir);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    refused(fifo, "a FIFO, not a device");

    refused(dir, "a directory, not a device");

    snprintf(sock, sizeof sock, "%s/hidraw7", dir);
    int s = socket(AF_UNIX, SOCK_STREAM, 0);
    assert_true(s >= 0);
    struct sockaddr_un addr;
    memset(&addr, 0, sizeof addr);
    addr.sun_family = AF_UNIX;
    assert_true(strlen(sock) < sizeof addr.sun_path);
    memcpy(addr.sun_path, sock, strlen(sock) + 1u);
    assert_int_equal(bind(s, (const struct sockaddr *)(const void *)&addr, sizeof addr), 0);
    refused(sock, "a socket, not a device");
    (void)close(s);

    char missing[160];
    snprintf(missing, sizeof missing, "%s/hidraw9", dir);
    refused(missing, "cannot find it: No such file or directory");

    refused("/dev/null", ", not a ");
    snprintf(link_null, sizeof link_null, "%s/hidraw8", dir);
    assert_int_equal(symlink("/dev/null", link_null), 0);
    refused(link_null, ", not a ");
    struct stat st;
    if (stat("/dev/zero", &st) != 0 || !S_ISCHR(st.st_mode)) {
        skip(); /* no /dev/zero character device in this sandbox */
    }
    refused("/dev/zero", "not a hidraw node");
    snprintf(link_null, sizeof link_null, "%s/hidraw3", dir);
    assert_int_equal(symlink("/dev/zero", link_null), 0);
    refused(link_null, "not a hidraw node");
    /* a symbolic link to a regular file: the file is checked */
    snprintf(link_file, sizeof link_file, "%s/hidraw4", dir);
    assert_int_equal(symlink(file, link_file), 0);
    refused(link_file, "a regular file, not a device");
}

/* A device of the double with ids no table knows: refused unopened, with
 * the ids and how to name them; named by the caller, it opens and answers;
 * listing and choosing by serial number see it only when named. */
static void test_foreign_ids(void **state)
{
    (void)state;
    int x = hid_double_add(node_a, "ARM-X", 0, 0);
    hid_double_set_ids(x, 0x046D, 0xC52B);
    lsc_hid *h = NULL;
    assert_int_equal(lsc_hid_open_path(node_a, &h), LSC_ENODEV);
    const char *m = lsc_hid_error_message(h);
    assert_non_null(strstr(m, node_a));
    assert_non_null(strstr(m, "not a known servo controller: USB 046d:c52b (known: 0483:5750)"));
    assert_non_null(strstr(m, "--hid-id 046d:c52b"));
    assert_null(h); /* nothing left open */
    assert_int_equal(hid_double_open_calls(), 0);
    /* other ids named: still refused, and the message lists both */
    assert_int_equal(lsc_hid_open_path_extra(node_a, 0x1234, 0x5678, &h), LSC_ENODEV);
    assert_non_null(strstr(lsc_hid_error_message(h), "known: 0483:5750 or 1234:5678"));
    assert_int_equal(hid_double_open_calls(), 0);
    /* its ids named: opened, and it answers */
    assert_int_equal(lsc_hid_open_path_extra(node_a, 0x046D, 0xC52B, &h), 0);
    assert_int_equal(hid_double_open_calls(), 1);
    lsc_io io;
    lsc_client c;
    lsc_hid_get_io(h, &io);
    assert_int_equal(lsc_client_init(&c, &io), 0);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&c, &mv, 1000), 0);
    assert_int_equal(mv, 7500);
    lsc_hid_close(h);
    /* the ids were for that call only */
    assert_int_equal(lsc_hid_open_path(node_a, &h), LSC_ENODEV);

    lsc_hid_info info[4];
    info[0].size = sizeof info[0];
    assert_int_equal(lsc_hid_list(info, 4, 0, 0, NULL, 0), 0);
    assert_int_equal(lsc_hid_list(info, 4, 0x046D, 0xC52B, NULL, 0), 1);
    assert_int_equal(info[0].vid, 0x046D);
    assert_int_equal(lsc_hid_open_serial(NULL, &h), LSC_ENODEV);
    assert_non_null(strstr(lsc_hid_error_message(h), "no HID controller (USB 0483:5750) is present"));
    assert_int_equal(lsc_hid_open_serial_extra(NULL, 0x1234, 0x5678, &h), LSC_ENODEV);
    assert_non_null(strstr(lsc_hid_error_message(h),
                           "no HID controller (USB 0483:5750 or 1234:5678) is present"));
    assert_int_equal(lsc_hid_open_serial_extra("ARM-X", 0x046D, 0xC52B, &h), 0);
    lsc_hid_close(h);
    /* with a known arm beside it: the only one unless the other is named */
    hid_double_add(node_b, "ARM-B", 0, 0);
    assert_int_equal(lsc_hid_open_serial(NULL, &h), 0);
    assert_string_equal(h->path, node_b);
    lsc_hid_close(h);
    assert_int_equal(lsc_hid_open_serial_extra(NULL, 0x046D, 0xC52B, &h), LSC_EINVAL);
    assert_non_null(strstr(lsc_hid_error_message(h), "ARM-B, ARM-X"));
    /* naming a known id adds nothing (not listed twice) */
    assert_int_equal(lsc_hid_open_serial_extra(NULL, 0x0483, 0x5750, &h), 0);
    lsc_hid_close(h);
}

/* The known ids: one table, 0483:5750 first. */
static void test_known_ids(void **state)
{
    (void)state;
    size_t n = 0;
    const lsc_hid_id *ids = lsc_hid_known_ids(&n);
    assert_non_null(ids);
    assert_true(n >= 1u);
    assert_int_equal(ids[0].vid, LSC_HID_VID);
    assert_int_equal(ids[0].pid, LSC_HID_PID);
    assert_non_null(ids[0].what);
    assert_ptr_equal(lsc_hid_known_ids(NULL), ids);
    for (size_t i = 0; i < n; i++) {
        assert_true(lsc_hid_is_known(ids[i].vid, ids[i].pid));
    }
    assert_false(lsc_hid_is_known(0x046D, 0xC52B));
    assert_false(lsc_hid_is_known(0, 0));
}

/* hidapi failing without a reason: the message says no "(Success)". */
static void test_open_fails_silently(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", HID_DOUBLE_SILENT, 0);
    lsc_hid *h = NULL;
    assert_int_equal(lsc_hid_open_path(node_a, &h), LSC_EIO);
    assert_int_equal(hid_double_open_calls(), 1);
    assert_null(strstr(lsc_hid_error_message(h), "Success"));
    assert_non_null(strstr(lsc_hid_error_message(h), "hidapi cannot open it"));
    assert_null(h); /* nothing left open */
}

/* ---- The checks against a fake sysfs ---------------------------------------- */

static char fake_root[160], fake_dev[320];
static struct stat fake_st;
#define FAKE_NODE "/dev/zero"
#define OTHER_NODE "/dev/null" /* another file, for the check after the open */

/* A fake sysfs under dir/root for FAKE_NODE's device number: subsystem a
 * symbolic link to .../class/CLASS (NULL: none), device/uevent holding
 * uevent (NULL: none; "FIFO": a FIFO). Skips the test without FAKE_NODE. */
static void fake_sysfs(const char *class_name, const char *uevent)
{
    if (stat(FAKE_NODE, &fake_st) != 0 || !S_ISCHR(fake_st.st_mode)) {
        skip();
    }
    char path[400];
    snprintf(fake_root, sizeof fake_root, "%s/root", dir);
    (void)nftw(fake_root, remove_one, 16, FTW_DEPTH | FTW_PHYS);
    const char *parts[] = {"", "/sys", "/sys/dev", "/sys/dev/char"};
    for (size_t i = 0; i < sizeof parts / sizeof parts[0]; i++) {
        snprintf(path, sizeof path, "%s%s", fake_root, parts[i]);
        assert_int_equal(mkdir(path, 0700), 0);
    }
    snprintf(fake_dev, sizeof fake_dev, "%s/sys/dev/char/%u:%u", fake_root,
             (unsigned)major(fake_st.st_rdev), (unsigned)minor(fake_st.st_rdev));
    assert_int_equal(mkdir(fake_dev, 0700), 0);
    if (class_name != NULL) {
        char target[64];
        snprintf(target, sizeof target, "../../../../class/%s", class_name);
        snprintf(path, sizeof path, "%s/subsystem", fake_dev);
        assert_int_equal(symlink(target, path), 0);
    }
    snprintf(path, sizeof path, "%s/device", fake_dev);
    assert_int_equal(mkdir(path, 0700), 0);
    snprintf(path, sizeof path, "%s/device/uevent", fake_dev);
    if (uevent != NULL && strcmp(uevent, "FIFO") == 0) {
        assert_int_equal(mkfifo(path, 0600), 0);
    } else if (uevent != NULL) {
        write_file(path, uevent);
    }
}

/* identify FAKE_NODE (or path) against the fake sysfs: the code, and the
 * message holding `says` when refused. */
static int identify(const char *path, lsc_hid_node *node, const char *says)
{
    lsc_port_error e;
    memset(&e, 0, sizeof e);
    int r = lsc_hid_node_identify(fake_root, path, "SHOWN", node, &e);
    if (r != 0 && (says == NULL || strstr(e.message, says) == NULL ||
                   strncmp(e.message, "SHOWN: ", 7) != 0)) {
        fail_msg("'%s' does not say '%s'", e.message, says != NULL ? says : "(nothing)");
    }
    return r;
}

static const char uevent_xarm[] = "DRIVER=hid-generic\n"
                                  "HID_ID=0003:00000483:00005750\n"
                                  "HID_NAME=MyUSB_HID LOBOT\n"
                                  "HID_UNIQ=497F1A5B3431\n"
                                  "MODALIAS=hid:b0003g0001v00000483p00005750\n";

/* A hidraw node of a known controller is accepted; through a symbolic link
 * it is the link's target that is checked and named. */
static void test_sysfs_known(void **state)
{
    (void)state;
    fake_sysfs("hidraw", uevent_xarm);
    lsc_hid_node node;
    assert_int_equal(identify(FAKE_NODE, &node, NULL), 0);
    assert_string_equal(node.path, FAKE_NODE);
    assert_int_equal(node.bus, LSC_HID_BUS_USB);
    assert_int_equal(node.vid, 0x0483);
    assert_int_equal(node.pid, 0x5750);
    lsc_port_error e;
    assert_int_equal(lsc_hid_node_accept(&node, 0, 0, "SHOWN", &e), 0);
    char link_path[160];
    snprintf(link_path, sizeof link_path, "%s/arm", dir);
    assert_int_equal(symlink(FAKE_NODE, link_path), 0);
    assert_int_equal(identify(link_path, &node, NULL), 0);
    assert_string_equal(node.path, FAKE_NODE);
    /* the descriptor opened must be that file */
    int fd = open(FAKE_NODE, O_RDWR | O_CLOEXEC);
    assert_true(fd >= 0);
    assert_int_equal(lsc_hid_node_same(&node, fd, "SHOWN", &e), 0);
    (void)close(fd);
    fd = open(OTHER_NODE, O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
        assert_int_equal(lsc_hid_node_same(&node, fd, "SHOWN", &e), LSC_ENODEV);
        assert_non_null(strstr(e.message, "changed"));
        (void)close(fd);
    }
    /* ids in capitals, no trailing newline */
    fake_sysfs("hidraw", "HID_ID=0003:00000483:00005750");
    assert_int_equal(identify(FAKE_NODE, &node, NULL), 0);
    assert_int_equal(node.pid, 0x5750);
    /* a regular file stays refused whatever sysfs says */
    char file[160];
    snprintf(file, sizeof file, "%s/hidraw5", dir);
    write_file(file, "");
    assert_int_equal(identify(file, &node, "a regular file, not a device"), LSC_ENODEV);
}

/* A hidraw node with other ids: refused unless they are named. */
static void test_sysfs_foreign(void **state)
{
    (void)state;
    fake_sysfs("hidraw", "HID_ID=0003:0000046D:0000C52B\nHID_NAME=Logitech USB Receiver\n");
    lsc_hid_node node;
    assert_int_equal(identify(FAKE_NODE, &node, NULL), 0);
    assert_int_equal(node.vid, 0x046D);
    assert_int_equal(node.pid, 0xC52B);
    lsc_port_error e;
    assert_int_equal(lsc_hid_node_accept(&node, 0, 0, "SHOWN", &e), LSC_ENODEV);
    assert_non_null(strstr(e.message, "SHOWN: not a known servo controller: USB 046d:c52b"));
    assert_int_equal(lsc_hid_node_accept(&node, 0x046D, 0xC52B, "SHOWN", &e), 0);
    assert_int_equal(lsc_hid_node_accept(&node, 0x046D, 0xC52C, "SHOWN", &e), LSC_ENODEV);
}

/* What the sysfs entry says is checked to the letter: another class, no
 * class, no ids, malformed ids, another bus, an unreadable uevent (missing,
 * or a FIFO: no hang). */
static void test_sysfs_refused(void **state)
{
    (void)state;
    lsc_hid_node node;
    fake_sysfs("tty", uevent_xarm);
    assert_int_equal(identify(FAKE_NODE, &node, "a character device of class 'tty', not a "
                                                  "hidraw node"),
                     LSC_ENODEV);
    fake_sysfs(NULL, uevent_xarm);
    assert_int_equal(identify(FAKE_NODE, &node, "without a sysfs class, not a hidraw node"),
                     LSC_ENODEV);
    fake_sysfs("hidraw", NULL);
    assert_int_equal(identify(FAKE_NODE, &node, "USB ids cannot be read"), LSC_ENODEV);
    fake_sysfs("hidraw", "FIFO");
    assert_int_equal(identify(FAKE_NODE, &node, "USB ids cannot be read"), LSC_ENODEV);
    static const char *const bad[] = {
        "DRIVER=hid-generic\n",
        "HID_ID=\n",
        "HID_ID=0003:00000483\n",
        "HID_ID=0003:00000483:\n",
        "HID_ID=0003:0000zz83:00005750\n",
        "HID_ID=0003:00010483:00005750\n", /* a vendor id beyond 16 bits */
        "HID_ID=0003:00000483:00005750x\n",
        "HID_ID=0003:000000483:00005750\n", /* nine digits */
        "XHID_ID=0003:00000483:00005750\n",
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        fake_sysfs("hidraw", bad[i]);
        assert_int_equal(identify(FAKE_NODE, &node, "no HID_ID"), LSC_ENODEV);
    }
    fake_sysfs("hidraw", "HID_ID=0005:00000483:00005750\n");
    assert_int_equal(identify(FAKE_NODE, &node, "not a USB device: a hidraw node on HID bus 0005"),
                     LSC_ENODEV);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_list, setup, teardown),
        cmocka_unit_test_setup_teardown(test_list_short_and_long_elements, setup, teardown),
        cmocka_unit_test_setup_teardown(test_list_size_too_small, setup, teardown),
        cmocka_unit_test_setup_teardown(test_write_report, setup, teardown),
        cmocka_unit_test_setup_teardown(test_open_out_of_memory, setup, teardown),
        cmocka_unit_test_setup_teardown(test_write_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_padding_and_small_reads, setup, teardown),
        cmocka_unit_test_setup_teardown(test_notification_first, setup, teardown),
        cmocka_unit_test_setup_teardown(test_garbage_report, setup, teardown),
        cmocka_unit_test_setup_teardown(test_first_request_unanswered, setup, teardown),
        cmocka_unit_test_setup_teardown(test_unplug, setup, teardown),
        cmocka_unit_test_setup_teardown(test_permission_denied, setup, teardown),
        cmocka_unit_test_setup_teardown(test_by_serial, setup, teardown),
        cmocka_unit_test_setup_teardown(test_none_present, setup, teardown),
        cmocka_unit_test_setup_teardown(test_second_opener, setup, teardown),
        cmocka_unit_test_setup_teardown(test_not_a_hidraw_node, setup, teardown),
        cmocka_unit_test_setup_teardown(test_foreign_ids, setup, teardown),
        cmocka_unit_test_setup_teardown(test_known_ids, setup, teardown),
        cmocka_unit_test_setup_teardown(test_open_fails_silently, setup, teardown),
        cmocka_unit_test_setup_teardown(test_sysfs_known, setup, teardown),
        cmocka_unit_test_setup_teardown(test_sysfs_foreign, setup, teardown),
        cmocka_unit_test_setup_teardown(test_sysfs_refused, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
