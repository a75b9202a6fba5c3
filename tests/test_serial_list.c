/* lsc_serial_list_ports with libserialport's listing replaced by the ports
 * in $LSCCTL_TEST_PORTS (cli/sp_ports_shim.c, linked into this program: its
 * definitions take precedence over libserialport's). lsc_port_info is a
 * struct that grows: out[0].size is every element's size and the array's
 * stride; the library writes no byte beyond it. (_GNU_SOURCE: from CMake,
 * for the shim.) */
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lsc/core.h"
#include "lsc/serial.h"

/* three ports: native, CH340 with a serial number, CP2102 */
static const char three[] = "/dev/ttyS0|ttyS0|-|;"
                            "/dev/ttyUSB0|USB Serial|1a86:7523|S1;"
                            "/dev/ttyUSB1|CP2102|10c4:ea60|";

static int setup(void **state)
{
    (void)state;
    return setenv("LSCCTL_TEST_PORTS", three, 1);
}

/* The whole elements of this lsc_port_info: every field, each size set. */
static void whole_elements(void **state)
{
    (void)state;
    lsc_port_info ports[4];
    memset(ports, 0xA5, sizeof ports);
    ports[0].size = sizeof ports[0];
    char msg[128];
    assert_int_equal(lsc_serial_list_ports(ports, 4, msg, sizeof msg), 3);
    assert_string_equal(msg, "");
    assert_string_equal(ports[0].path, "/dev/ttyS0");
    assert_string_equal(ports[0].description, "ttyS0");
    assert_false(ports[0].usb);
    assert_int_equal(ports[0].vid, 0);
    assert_string_equal(ports[0].serial, "");
    assert_string_equal(ports[1].path, "/dev/ttyUSB0");
    assert_true(ports[1].usb);
    assert_int_equal(ports[1].vid, 0x1a86);
    assert_int_equal(ports[1].pid, 0x7523);
    assert_string_equal(ports[1].serial, "S1");
    assert_string_equal(ports[2].description, "CP2102");
    for (size_t i = 0; i < 3; i++) {
        assert_int_equal(ports[i].size, sizeof ports[i]);
    }
    /* the fourth is not written */
    for (const unsigned char *b = (const unsigned char *)&ports[3];
         b < (const unsigned char *)(ports + 4); b++) {
        assert_int_equal(*b, 0xA5);
    }
    /* more than fit: the count, only cap written */
    memset(ports, 0xA5, sizeof ports);
    ports[0].size = sizeof ports[0];
    assert_int_equal(lsc_serial_list_ports(ports, 1, NULL, 0), 3);
    assert_string_equal(ports[0].path, "/dev/ttyS0");
    assert_int_equal(((const unsigned char *)&ports[1])[0], 0xA5);
}

/* A program built when lsc_port_info ended at description: elements of that
 * size, the stride honoured, the bytes after the elements written untouched;
 * one whose lsc_port_info is larger gets the bytes beyond this one's
 * untouched. */
static void short_and_long_elements(void **state)
{
    (void)state;
    lsc_port_info store[4]; /* aligned room */
    const size_t size = offsetof(lsc_port_info, usb); /* size, path, description */
    memset(store, 0xA5, sizeof store);
    memcpy(store, &size, sizeof size);
    assert_int_equal(lsc_serial_list_ports(store, 2, NULL, 0), 3);
    const unsigned char *bytes = (const unsigned char *)store;
    for (size_t i = 0; i < 2; i++) {
        const unsigned char *e = bytes + i * size;
        size_t got;
        memcpy(&got, e, sizeof got);
        assert_int_equal(got, size);
        assert_string_equal((const char *)e + offsetof(lsc_port_info, path),
                            i == 0 ? "/dev/ttyS0" : "/dev/ttyUSB0");
        assert_string_equal((const char *)e + offsetof(lsc_port_info, description),
                            i == 0 ? "ttyS0" : "USB Serial");
    }
    for (const unsigned char *g = bytes + 2 * size; g < (const unsigned char *)(store + 4); g++) {
        assert_int_equal(*g, 0xA5);
    }

    const size_t big = sizeof(lsc_port_info) + 24u;
    lsc_port_info bigger[4]; /* room for three of them */
    unsigned char *room = (unsigned char *)bigger;
    assert_true(3 * big <= sizeof bigger);
    memset(room, 0xA5, sizeof bigger);
    memcpy(room, &big, sizeof big);
    assert_int_equal(lsc_serial_list_ports(bigger, 3, NULL, 0), 3);
    for (size_t i = 0; i < 3; i++) {
        lsc_port_info got;
        memcpy(&got, room + i * big, sizeof got);
        assert_int_equal(got.size, big);
        assert_string_equal(got.serial, i == 1 ? "S1" : "");
        assert_int_equal(got.usb, i != 0);
        for (size_t k = sizeof got; k < big; k++) {
            assert_int_equal(room[i * big + k], 0xA5);
        }
    }
}

/* A size below its size field and path is refused, nothing written; no
 * element (counting only) needs none. */
static void size_too_small(void **state)
{
    (void)state;
    lsc_port_info ports[2];
    char msg[256];
    const size_t least = offsetof(lsc_port_info, path) + LSC_SERIAL_PATH_MAX;
    const size_t sizes[] = {0, sizeof(size_t), least - 1u};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        memset(ports, 0xA5, sizeof ports);
        memcpy(ports, &sizes[k], sizeof sizes[k]);
        assert_int_equal(lsc_serial_list_ports(ports, 2, msg, sizeof msg), LSC_EINVAL);
        char want[200];
        snprintf(want, sizeof want,
                 "lsc_port_info.size is %zu, less than %zu: set out[0].size to "
                 "sizeof(lsc_port_info); nothing was listed",
                 sizes[k], least);
        assert_string_equal(msg, want);
        assert_int_equal(ports[0].size, sizes[k]);
        for (const unsigned char *b = (const unsigned char *)ports + sizeof(size_t);
             b < (const unsigned char *)(ports + 2); b++) {
            assert_int_equal(*b, 0xA5);
        }
    }
    /* the least is enough: the path only */
    memcpy(ports, &least, sizeof least);
    assert_int_equal(lsc_serial_list_ports(ports, 2, NULL, 0), 3);
    assert_string_equal(ports[0].path, "/dev/ttyS0");
    assert_string_equal((const char *)ports + least + offsetof(lsc_port_info, path),
                        "/dev/ttyUSB0");
    /* counting: no element, no size */
    memset(ports, 0xA5, sizeof ports);
    assert_int_equal(lsc_serial_list_ports(ports, 0, NULL, 0), 3);
    assert_int_equal(lsc_serial_list_ports(NULL, 0, NULL, 0), 3);
    assert_int_equal(lsc_serial_list_ports(NULL, 1, msg, sizeof msg), LSC_EINVAL);
    assert_string_equal(msg, "invalid argument");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(whole_elements, setup),
        cmocka_unit_test_setup(short_and_long_elements, setup),
        cmocka_unit_test_setup(size_too_small, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
