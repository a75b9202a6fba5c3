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
#include "sized_test.h"

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
    sized_guard(ports, sizeof ports, sizeof ports[0]);
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
    assert_true(sized_untouched(ports, 3 * sizeof ports[0], sizeof ports)); /* not the fourth */
    /* more than fit: the count, only cap written */
    sized_guard(ports, sizeof ports, sizeof ports[0]);
    assert_int_equal(lsc_serial_list_ports(ports, 1, NULL, 0), 3);
    assert_string_equal(ports[0].path, "/dev/ttyS0");
    assert_true(sized_untouched(ports, sizeof ports[0], sizeof ports));
}

/* lsc_serial_list_ports as the sized tests call a listing */
static int list_ports(void *out, size_t cap, char *message, size_t msgcap)
{
    return lsc_serial_list_ports(out, cap, message, msgcap);
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
    assert_int_equal(sized_list_stride(list_ports, store, sizeof store, size, 2, size), 3);
    for (size_t i = 0; i < 2; i++) {
        const char *e = (const char *)sized_element(store, size, i);
        assert_string_equal(e + offsetof(lsc_port_info, path),
                            i == 0 ? "/dev/ttyS0" : "/dev/ttyUSB0");
        assert_string_equal(e + offsetof(lsc_port_info, description),
                            i == 0 ? "ttyS0" : "USB Serial");
    }

    const size_t big = sizeof(lsc_port_info) + 24u;
    lsc_port_info bigger[4]; /* room for three of them */
    assert_int_equal(sized_list_stride(list_ports, bigger, sizeof bigger, big, 3,
                                       sizeof(lsc_port_info)),
                     3);
    for (size_t i = 0; i < 3; i++) {
        lsc_port_info got;
        memcpy(&got, sized_element(bigger, big, i), sizeof got);
        assert_string_equal(got.serial, i == 1 ? "S1" : "");
        assert_int_equal(got.usb, i != 0);
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
    assert_true(sized_list_refuses_small(list_ports, ports, sizeof ports[0], least,
                                         "lsc_port_info"));
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
