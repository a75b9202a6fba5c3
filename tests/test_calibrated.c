/* Tests of where a calibrated profile is kept (include/lsc/calibrated.h,
 * src/device/calibrated.c): the key of each kind of controller name, a
 * serial port's link (given, or found in a by-id directory), the one
 * controller present, the path under $XDG_CONFIG_HOME or $HOME, and finding
 * the file. The listings of ports and HID controllers are fakes (--wrap), as
 * is calloc, to make an allocation fail. */
#define _DEFAULT_SOURCE /* mkdtemp, setenv, symlink */
#define _XOPEN_SOURCE 700 /* nftw's FTW_DEPTH, FTW_PHYS */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <ftw.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lsc/calibrated.h"
#include "lsc/device.h"
#include "lsc/hid.h"
#include "lsc/serial.h"
#include "lsc/sim.h"
#include "../src/device/device_internal.h"

void *__real_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
int __wrap_lsc_serial_list_ports(lsc_port_info *out, size_t cap, char *message, size_t msgcap);
int __wrap_lsc_hid_list(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid,
                        char *message, size_t msgcap);

static int fail_calloc; /* > 0: the fail_calloc-th allocation from now fails */

void *__wrap_calloc(size_t n, size_t size) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (fail_calloc > 0 && --fail_calloc == 0) {
        return NULL;
    }
    return __real_calloc(n, size);
}

static char tmp[64], node[128], link_path[128];

/* The ports listed: none, an error, the adapter at link_path and a port that
 * is no controller, or more than the lookup reads (all adapters). */
enum { PORTS_NONE, PORTS_FAIL, PORTS_ONE, PORTS_HUGE };
static int ports = PORTS_NONE;
/* The HID controllers listed: none, one with a serial number, one without,
 * two. */
enum { HID_NONE, HID_ONE, HID_BARE, HID_TWO };
static int hids = HID_NONE;

static void port(lsc_port_info *p, const char *path, uint16_t vid, uint16_t pid)
{
    memset(p, 0, sizeof *p);
    p->size = sizeof *p;
    snprintf(p->path, sizeof p->path, "%s", path);
    p->usb = true;
    p->vid = vid;
    p->pid = pid;
}

int __wrap_lsc_serial_list_ports(lsc_port_info *out, size_t cap, char *message, size_t msgcap)
{
    (void)message;
    (void)msgcap;
    assert_true(cap == 0 || out[0].size == sizeof *out); /* the device layer's elements */
    switch (ports) {
    case PORTS_NONE: return 0;
    case PORTS_FAIL: return LSC_EIO;
    case PORTS_ONE:
        port(&out[0], link_path, 0x1a86, 0x7523); /* CH340 */
        port(&out[1], "/nonexistent/ttyACM0", 0x2341, 0x0043);
        return 2;
    default:
        for (size_t i = 0; i < cap; i++) {
            port(&out[i], link_path, 0x1a86, 0x7523);
        }
        return 0x7fffffff;
    }
}

static void hid(lsc_hid_info *h, const char *serial)
{
    memset(h, 0, sizeof *h);
    h->size = sizeof *h;
    snprintf(h->path, sizeof h->path, "/nonexistent/hidraw0");
    snprintf(h->serial, sizeof h->serial, "%s", serial);
    h->vid = LSC_HID_VID;
    h->pid = LSC_HID_PID;
}

int __wrap_lsc_hid_list(lsc_hid_info *out, size_t cap, uint16_t vid, uint16_t pid,
                        char *message, size_t msgcap)
{
    (void)vid;
    (void)pid;
    (void)message;
    (void)msgcap;
    assert_true(cap == 0 || out[0].size == sizeof *out); /* the device layer's elements */
    switch (hids) {
    case HID_NONE: return LSC_EIO;
    case HID_ONE: hid(&out[0], "ARM 1/a"); return 1;
    case HID_BARE: hid(&out[0], ""); return 1;
    default: hid(&out[0], "A1"); hid(&out[1], "B2"); return 2;
    }
}

static void write_file(const char *path)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    assert_int_equal(fclose(f), 0);
}

static int setup(void **state)
{
    (void)state;
    snprintf(tmp, sizeof tmp, "/tmp/lsc-calibrated-XXXXXX");
    assert_non_null(mkdtemp(tmp));
    snprintf(node, sizeof node, "%s/ttyUSB3", tmp);
    snprintf(link_path, sizeof link_path, "%s/usb-arm-one", tmp);
    write_file(node);
    assert_int_equal(symlink(node, link_path), 0);
    ports = PORTS_NONE;
    hids = HID_NONE;
    return 0;
}

static int remove_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    return remove(path);
}

static int teardown(void **state)
{
    (void)state;
    assert_int_equal(nftw(tmp, remove_one, 16, FTW_DEPTH | FTW_PHYS), 0);
    return 0;
}

static void key_is(const char *name, const char *want)
{
    char key[LSC_CALIBRATED_KEY_MAX] = "x";
    int r = lsc_calibrated_key(name, key, sizeof key);
    if (want == NULL) {
        assert_int_equal(r, LSC_ENODEV);
        assert_string_equal(key, "");
    } else {
        assert_int_equal(r, 0);
        assert_string_equal(key, want);
    }
}

static void test_keys(void **state)
{
    (void)state;
    char key[8];
    key_is("sim", "sim");
    key_is("hid:ABC123", "hid-ABC123");
    key_is("hid:../../a b\x01~", "hid-.._.._a_b__");
    key_is("lscd:ttyNOSUCH9", NULL); /* no /dev/ttyNOSUCH9 */
    key_is("lscd:sim", "sim");
    key_is("lscd:hid-AB1", "hid-AB1");
    key_is("lscd:/run/lsc/x.sock", NULL);
    key_is("lscd:", NULL);
    key_is(link_path, "port-usb-arm-one");
    key_is(node, NULL); /* no link in /dev/serial/by-id points at a plain file of /tmp */
    key_is("/nonexistent/ttyUSB9", NULL);
    assert_int_equal(lsc_calibrated_key("sim", NULL, 8), LSC_EINVAL);
    assert_int_equal(lsc_calibrated_key("sim", key, 0), LSC_EINVAL);
    assert_int_equal(lsc_calibrated_key("hid:ABCDEFGH", key, sizeof key), LSC_EINVAL);
    /* a link given by a relative name; a name starting with a dot */
    char dotted[160], cwd[256];
    snprintf(dotted, sizeof dotted, "%s/.arm", tmp);
    assert_int_equal(symlink(node, dotted), 0);
    key_is(dotted, "port-.arm"); /* (after the kind, a dot is kept) */
    assert_non_null(getcwd(cwd, sizeof cwd));
    assert_int_equal(chdir(tmp), 0);
    key_is("usb-arm-one", "port-usb-arm-one");
    assert_int_equal(chdir(cwd), 0);
}

/* The one controller present; the one HID controller. */
static void test_only_one(void **state)
{
    (void)state;
    key_is(NULL, NULL);
    key_is("", NULL);
    key_is("hid", NULL);
    ports = PORTS_ONE;
    key_is(NULL, "port-usb-arm-one");
    key_is("", "port-usb-arm-one");
    key_is("hid", NULL);
    hids = HID_ONE;
    key_is(NULL, NULL); /* two controllers */
    key_is("hid", "hid-ARM_1_a");
    key_is("lscd:hid", "hid-ARM_1_a"); /* lscd serving the one HID controller */
    hids = HID_BARE;
    key_is("hid", NULL);
    hids = HID_TWO;
    key_is("hid", NULL);
    ports = PORTS_FAIL;
    hids = HID_NONE;
    key_is(NULL, NULL);
    ports = PORTS_HUGE;
    key_is(NULL, NULL);
    ports = PORTS_ONE;
    fail_calloc = 1;
    key_is(NULL, NULL);
    fail_calloc = 0;
}

/* A port found through a by-id directory's links. */
static void test_by_id(void **state)
{
    (void)state;
    char dir[128], other[160], p[200], key[LSC_CALIBRATED_KEY_MAX] = "";
    snprintf(dir, sizeof dir, "%s/by-id", tmp);
    assert_int_equal(lsc_dev_port_key(dir, node, key, sizeof key), LSC_ENODEV); /* no dir */
    assert_int_equal(mkdir(dir, 0700), 0);
    assert_int_equal(lsc_dev_port_key(dir, node, key, sizeof key), LSC_ENODEV); /* empty */
    snprintf(other, sizeof other, "%s/ttyUSB4", tmp);
    write_file(other);
    snprintf(p, sizeof p, "%s/usb-other", dir);
    assert_int_equal(symlink(other, p), 0);
    snprintf(p, sizeof p, "%s/usb-dangling", dir);
    assert_int_equal(symlink("/nonexistent/x", p), 0);
    snprintf(p, sizeof p, "%s/.hidden", dir);
    assert_int_equal(symlink(node, p), 0);
    assert_int_equal(lsc_dev_port_key(dir, node, key, sizeof key), LSC_ENODEV);
    snprintf(p, sizeof p, "%s/usb-1a86_USB_Serial-if00-port0", dir);
    assert_int_equal(symlink(node, p), 0);
    assert_int_equal(lsc_dev_port_key(dir, node, key, sizeof key), 0);
    assert_string_equal(key, "port-usb-1a86_USB_Serial-if00-port0");
    assert_int_equal(lsc_dev_port_key(dir, "/nonexistent/tty", key, sizeof key), LSC_ENODEV);
}

static void test_paths(void **state)
{
    (void)state;
    char path[256], small[16], file[200];
    const char *home = getenv("HOME");
    char saved_home[256];
    snprintf(saved_home, sizeof saved_home, "%s", home != NULL ? home : "");
    assert_int_equal(setenv("XDG_CONFIG_HOME", "/x/cfg", 1), 0);
    assert_int_equal(lsc_calibrated_path("hid-A1", path, sizeof path), 0);
    assert_string_equal(path, "/x/cfg/lsc/arms/hid-A1.conf");
    assert_int_equal(setenv("XDG_CONFIG_HOME", "relative", 1), 0);
    assert_int_equal(setenv("HOME", "/home/owner", 1), 0);
    assert_int_equal(lsc_calibrated_path("sim", path, sizeof path), 0);
    assert_string_equal(path, "/home/owner/.config/lsc/arms/sim.conf");
    assert_int_equal(unsetenv("XDG_CONFIG_HOME"), 0);
    assert_int_equal(lsc_calibrated_path("sim", path, sizeof path), 0);
    assert_string_equal(path, "/home/owner/.config/lsc/arms/sim.conf");
    assert_int_equal(lsc_calibrated_path("sim", small, sizeof small), LSC_EINVAL);
    assert_int_equal(lsc_calibrated_path("", path, sizeof path), LSC_EINVAL);
    assert_int_equal(lsc_calibrated_path(NULL, path, sizeof path), LSC_EINVAL);
    assert_int_equal(lsc_calibrated_path("sim", NULL, sizeof path), LSC_EINVAL);
    assert_int_equal(setenv("HOME", "", 1), 0);
    assert_int_equal(lsc_calibrated_path("sim", path, sizeof path), LSC_EINVAL);
    assert_int_equal(unsetenv("HOME"), 0);
    assert_int_equal(lsc_calibrated_path("sim", path, sizeof path), LSC_EINVAL);

    /* finding the file */
    assert_int_equal(setenv("XDG_CONFIG_HOME", tmp, 1), 0);
    assert_int_equal(lsc_calibrated_find("sim", path, sizeof path), LSC_ENODEV);
    snprintf(file, sizeof file, "%s/lsc", tmp);
    assert_int_equal(mkdir(file, 0700), 0);
    snprintf(file, sizeof file, "%s/lsc/arms", tmp);
    assert_int_equal(mkdir(file, 0700), 0);
    snprintf(file, sizeof file, "%s/lsc/arms/sim.conf", tmp);
    assert_int_equal(mkdir(file, 0700), 0); /* a directory is no profile */
    assert_int_equal(lsc_calibrated_find("sim", path, sizeof path), LSC_ENODEV);
    assert_int_equal(rmdir(file), 0);
    write_file(file);
    assert_int_equal(lsc_calibrated_find("sim", path, sizeof path), 0);
    assert_string_equal(path, file);
    assert_int_equal(lsc_calibrated_find("sim", small, sizeof small), LSC_EINVAL);
    assert_int_equal(lsc_calibrated_find("lscd:x", path, sizeof path), LSC_ENODEV);
    assert_int_equal(unsetenv("XDG_CONFIG_HOME"), 0);
    assert_int_equal(setenv("HOME", saved_home, 1), 0);
}


/* A step on the virtual controller: the servos read, the text made, nothing
 * written; the refusals said on the device. */
static void test_device_step(void **state)
{
    (void)state;
    static const char text[] = "g 1 bus limits=0..700\nb 2 bus\nc 3 bus\nd 4 bus\ne 5 bus\n"
                               "f 6 bus\nchain: b c d e f g\n"
                               "links: height=1mm upper=1mm fore=1mm tool=1mm\n";
    lsc_device *d = NULL;
    char *out = (char *)&out;
    size_t len = 0;
    assert_int_equal(lsc_device_open("sim", NULL, &d), 0);
    static const lsc_servo at[] = {{2, 510}, {3, 490}, {4, 500}, {5, 500}, {6, 500}, {1, 650}};
    assert_int_equal(lsc_device_move(d, 0, at, 6), 0);
    assert_int_equal(lsc_device_calibrate(d, LSC_CALIB_HOME, text, strlen(text), "t\x01.conf",
                                          &out, &len),
                     0);
    assert_non_null(strstr(out, "\nb 2 bus offset=+10\nc 3 bus offset=-10\n"));
    assert_memory_equal(out, "# calibrate home: 20", 20);
    assert_non_null(strstr(out, " UTC, from t?.conf\n"));
    assert_int_equal(len, strlen(out));
    free(out);
    assert_int_equal(lsc_device_calibrate(d, LSC_CALIB_GRIPPER_CLOSED, text, strlen(text), NULL,
                                          &out, &len),
                     0);
    assert_non_null(strstr(out, "from profile\n"));
    free(out);
    /* bytes outside printable ASCII in the name: '?' in the stamp */
    assert_int_equal(lsc_device_calibrate(d, LSC_CALIB_GRIPPER_CLOSED, text, strlen(text),
                                          "t\xc3\xa4.conf", &out, &len),
                     0);
    assert_non_null(strstr(out, "from t??.conf\n"));
    assert_non_null(strstr(out, "\ng 1 bus limits=0..700 closed=650\n"));
    free(out);
    /* refused: the readings (not leaned), the text, the arguments */
    assert_int_equal(lsc_device_calibrate(d, LSC_CALIB_LEAN, text, strlen(text), NULL, &out,
                                          &len),
                     LSC_EINVAL);
    assert_null(out);
    assert_non_null(strstr(lsc_device_error(d), "lean further"));
    assert_int_equal(lsc_device_calibrate(d, LSC_CALIB_HOME, "x", 1, NULL, &out, &len),
                     LSC_EINVAL);
    assert_non_null(strstr(lsc_device_error(d), "profile:1:2:"));
    assert_int_equal(lsc_device_calibrate(d, LSC_CALIB_HOME, NULL, 3, NULL, &out, &len),
                     LSC_EINVAL);
    assert_string_equal(lsc_device_error(d), "calibrate: a NULL argument");
    assert_int_equal(lsc_device_calibrate(d, LSC_CALIB_HOME, NULL, 0, NULL, &out, &len),
                     LSC_EINVAL); /* no text: no joints */
    assert_non_null(strstr(lsc_device_error(d), "no joints"));
    assert_int_equal(lsc_device_calibrate(d, LSC_CALIB_HOME, text, strlen(text), NULL, NULL,
                                          &len),
                     LSC_EINVAL);
    assert_int_equal(lsc_device_calibrate(d, LSC_CALIB_HOME, text, strlen(text), NULL, &out,
                                          NULL),
                     LSC_EINVAL);
    assert_int_equal(lsc_device_calibrate(NULL, LSC_CALIB_HOME, text, strlen(text), NULL, &out,
                                          &len),
                     LSC_EINVAL);
    /* a read that fails: a servo beyond what the virtual controller has */
    static const char far[] = "b 200 bus\nc 3 bus\nd 4 bus\ne 5 bus\nf 6 bus\n"
                              "chain: b c d e f\nlinks: height=1mm upper=1mm fore=1mm tool=1mm\n";
    lsc_device_close(d);
    assert_int_equal(lsc_device_open("sim", NULL, &d), 0);
    lsc_device_set_timeout(d, 1);
    lsc_sim_fault_drop(lsc_device_sim(d), 1);
    int r = lsc_device_calibrate(d, LSC_CALIB_HOME, far, strlen(far), NULL, &out, &len);
    assert_true(r < 0);
    assert_null(out);
    lsc_device_close(d);
}

static void test_write(void **state)
{
    (void)state;
    char path[200], why[256] = "";
    snprintf(path, sizeof path, "%s/a/b/c.conf", tmp);
    assert_int_equal(lsc_calibrated_write(path, "x 1 bus\n", 8, why, sizeof why), 0);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char got[16] = "";
    assert_non_null(fgets(got, sizeof got, f));
    assert_int_equal(fclose(f), 0);
    assert_string_equal(got, "x 1 bus\n");
    assert_int_equal(lsc_calibrated_write(path, "y 2 bus\n", 8, NULL, 0), 0);
    /* a file where a directory must be; a directory where the file goes */
    snprintf(path, sizeof path, "%s/a/b/c.conf/x/d.conf", tmp);
    assert_int_equal(lsc_calibrated_write(path, "x", 1, why, sizeof why), LSC_EIO);
    assert_non_null(strstr(why, "cannot make the directory"));
    assert_int_equal(lsc_calibrated_write(path, "x", 1, NULL, 0), LSC_EIO);
    assert_int_equal(lsc_calibrated_write(path, "x", 1, why, 0), LSC_EIO);
    snprintf(path, sizeof path, "%s/a/b", tmp);
    assert_int_equal(lsc_calibrated_write(path, "x", 1, why, sizeof why), LSC_EINVAL);
    assert_non_null(strstr(why, "cannot write"));
    assert_non_null(strstr(why, "not a regular file"));
    assert_int_equal(lsc_calibrated_write(path, "x", 1, NULL, 0), LSC_EINVAL);
    assert_int_equal(lsc_calibrated_write(path, "x", 1, why, 0), LSC_EINVAL);
    snprintf(path, sizeof path, "%s/a/empty.conf", tmp); /* no text: an empty file */
    assert_int_equal(lsc_calibrated_write(path, NULL, 0, why, sizeof why), 0);
    assert_int_equal(lsc_calibrated_write(NULL, "x", 1, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_calibrated_write(path, NULL, 1, why, sizeof why), LSC_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_keys, setup, teardown),
        cmocka_unit_test_setup_teardown(test_only_one, setup, teardown),
        cmocka_unit_test_setup_teardown(test_by_id, setup, teardown),
        cmocka_unit_test_setup_teardown(test_paths, setup, teardown),
        cmocka_unit_test_setup_teardown(test_device_step, setup, teardown),
        cmocka_unit_test_setup_teardown(test_write, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
