/* The HID transport (src/hid) and the client over it, against the hidapi
 * test double (hid_double.c, linked in place of libhidapi-hidraw): the
 * report rules, notifications and garbage between reports, an arm that does
 * not answer the first request, unplugging, permissions, choosing by serial
 * number, exclusivity. */
#define _DEFAULT_SOURCE 1
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hid_double.h"
#include "lsc/client.h"
#include "lsc/hid.h"

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

static int teardown(void **state)
{
    (void)state;
    unlink(node_a);
    unlink(node_b);
    rmdir(dir); /* first: a failed test leaves nothing behind */
    assert_int_equal(hid_double_open_handles(), 0); /* every handle was closed */
    return 0;
}

typedef struct hid_link {
    lsc_hid hid;
    lsc_io io;
    lsc_client client;
} hid_link;

static void open_link(hid_link *l, const char *path)
{
    lsc_hid_init(&l->hid);
    assert_int_equal(lsc_hid_open_path(&l->hid, path), 0);
    lsc_hid_get_io(&l->hid, &l->io);
    assert_int_equal(lsc_client_init(&l->client, &l->io), 0);
}

static void test_list(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0);
    hid_double_add(node_b, "ARM-B", 0, 0);
    lsc_hid_info info[4];
    char msg[128];
    assert_true(lsc_hid_available());
    assert_int_equal(lsc_hid_list(info, 4, 0, 0, msg, sizeof msg), 2);
    assert_string_equal(info[0].path, node_a);
    assert_string_equal(info[0].serial, "ARM-A");
    assert_string_equal(info[1].serial, "ARM-B");
    assert_string_equal(info[0].product, "LOBOT");
    assert_int_equal(info[0].vid, 0x0483);
    assert_int_equal(info[0].pid, 0x5750);
    /* more than fit: the count, only cap written */
    assert_int_equal(lsc_hid_list(info, 1, 0, 0, NULL, 0), 2);
    /* other ids: none */
    assert_int_equal(lsc_hid_list(info, 4, 0x1234, 0x5678, NULL, 0), 0);
    assert_int_equal(lsc_hid_list(NULL, 1, 0, 0, msg, sizeof msg), LSC_EINVAL);
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
    lsc_hid_close(&l.hid);
    lsc_hid_close(&l.hid); /* twice is safe */
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
    assert_non_null(strstr(lsc_hid_error_message(&l.hid), "one whole frame"));
    static const uint8_t part[] = {0x55, 0x55, 0x04, 0x0F};
    assert_int_equal(lsc_hid_write(&l.hid, part, sizeof part), LSC_EINVAL);
    assert_int_equal(lsc_hid_write(&l.hid, NULL, 0), LSC_EINVAL);
    assert_int_equal(hid_double_writes(), before);
    /* 19 servos: 64 bytes, the largest that fits */
    assert_int_equal(lsc_client_move(&l.client, 500, s + 1, 19), 0);
    assert_int_equal(hid_double_writes(), before + 1u);
    lsc_hid_close(&l.hid);
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
    assert_int_equal(lsc_hid_write(&l.hid, req, sizeof req), 4);
    uint8_t buf[8];
    assert_int_equal(lsc_hid_read(&l.hid, buf, 4, 1000), 4);
    assert_int_equal(lsc_hid_read(&l.hid, buf + 4, 4, 1000), 2); /* the frame's end only */
    static const uint8_t reply[] = {0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D};
    assert_memory_equal(buf, reply, sizeof reply);
    /* nothing else: the padding never arrives */
    assert_int_equal(lsc_hid_read(&l.hid, buf, sizeof buf, 0), 0);
    assert_int_equal(lsc_hid_reports_dropped(&l.hid), 0);
    assert_int_equal(lsc_hid_read(&l.hid, NULL, 1, 0), LSC_EINVAL);
    lsc_hid_close(&l.hid);
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
    lsc_hid_close(&l.hid);
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
    assert_int_equal(lsc_hid_reports_dropped(&l.hid), 1);
    uint8_t ids[2] = {1, 2};
    lsc_servo got[2];
    assert_int_equal(lsc_client_read_positions(&l.client, ids, 2, got, 1000), 2);
    assert_int_equal(lsc_hid_reports_dropped(&l.hid), 2);
    lsc_hid_close(&l.hid);
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
    lsc_hid_close(&l.hid);
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
    assert_non_null(strstr(lsc_hid_error_message(&l.hid), "went away"));
    assert_non_null(strstr(lsc_hid_error_message(&l.hid), "disconnected"));
    assert_int_equal(lsc_hid_os_errno(&l.hid), ENODEV);
    assert_int_equal(lsc_client_stop_group(&l.client), LSC_ENODEV);
    lsc_hid_close(&l.hid);
    /* the node is gone too: no such device */
    lsc_hid h;
    unlink(node_b);
    hid_double_add(node_b, "ARM-B", 0, 0);
    assert_int_equal(lsc_hid_open_path(&h, node_b), LSC_ENODEV);
    assert_int_equal(lsc_hid_os_errno(&h), ENOENT);
    assert_int_equal(lsc_hid_open_path(&h, ""), LSC_EINVAL);
    assert_string_equal(lsc_hid_error_message(&h), "hid: invalid device path (empty or too long)");
    assert_int_equal(lsc_hid_open_path(NULL, node_a), LSC_EINVAL);
    /* a directory is no device: said so, errno kept, nothing left open */
    assert_int_equal(lsc_hid_open_path(&h, dir), LSC_ENODEV);
    assert_int_equal(lsc_hid_os_errno(&h), EISDIR);
    assert_non_null(strstr(lsc_hid_error_message(&h), ": a directory, not a device"));
    assert_int_equal(h.lock_fd, -1);
}

/* Permission denied: LSC_EACCES, errno kept, the message names the fix. */
static void test_permission_denied(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", HID_DOUBLE_DENY, 0);
    lsc_hid h;
    assert_int_equal(lsc_hid_open_path(&h, node_a), LSC_EACCES);
    assert_int_equal(lsc_hid_os_errno(&h), EACCES);
    const char *m = lsc_hid_error_message(&h);
    assert_non_null(strstr(m, node_a));
    assert_non_null(strstr(m, "Permission denied"));
    assert_non_null(strstr(m, "60-lsc.rules"));
    assert_non_null(strstr(m, "uaccess"));
    assert_non_null(strstr(m, "plugdev"));
    assert_non_null(strstr(m, "fwupd"));
    /* the lock was released: nothing is left open */
    assert_int_equal(h.lock_fd, -1);
}

/* Two arms told apart by serial number. */
static void test_by_serial(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0);
    hid_double_add(node_b, "ARM-B", 0, 0);
    lsc_hid h;
    assert_int_equal(lsc_hid_open_serial(&h, NULL), LSC_EINVAL);
    assert_non_null(strstr(lsc_hid_error_message(&h), "ARM-A, ARM-B"));
    assert_int_equal(lsc_hid_open_serial(&h, "ARM-C"), LSC_ENODEV);
    assert_non_null(strstr(lsc_hid_error_message(&h), "present: ARM-A, ARM-B"));
    assert_int_equal(lsc_hid_open_serial(&h, "ARM-B"), 0);
    lsc_sim_set_battery(hid_double_sim(1), 6000);
    lsc_io io;
    lsc_client c;
    lsc_hid_get_io(&h, &io);
    lsc_client_init(&c, &io);
    uint16_t mv = 0;
    assert_int_equal(lsc_client_get_battery(&c, &mv, 1000), 0);
    assert_int_equal(mv, 6000); /* B's, not A's 7500 */
    lsc_hid_close(&h);
    assert_int_equal(lsc_hid_open_serial(NULL, "ARM-B"), LSC_EINVAL);
}

static void test_none_present(void **state)
{
    (void)state;
    lsc_hid h;
    assert_int_equal(lsc_hid_open_serial(&h, ""), LSC_ENODEV);
    assert_non_null(strstr(lsc_hid_error_message(&h), "no HID controller"));
}

/* A second opener, in this process or another, is refused: port busy. */
static void test_second_opener(void **state)
{
    (void)state;
    hid_double_add(node_a, "ARM-A", 0, 0);
    hid_link l;
    open_link(&l, node_a);
    lsc_hid second;
    assert_int_equal(lsc_hid_open_path(&second, node_a), LSC_EBUSY);
    assert_non_null(strstr(lsc_hid_error_message(&second), "port busy"));
    /* the HID transport's hint, not the serial ports' */
    assert_non_null(strstr(lsc_hid_error_message(&second), "has the arm open"));
    assert_int_equal(hid_double_open_handles(), 1);
    lsc_hid_close(&l.hid);
    /* closed: the next opener gets it */
    assert_int_equal(lsc_hid_open_path(&second, node_a), 0);
    lsc_hid_close(&second);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_list, setup, teardown),
        cmocka_unit_test_setup_teardown(test_write_report, setup, teardown),
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
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
