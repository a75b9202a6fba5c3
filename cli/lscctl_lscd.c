/* lscctl status: what lscd says of itself (lsc/lscd.h): the controller, the
 * clients, the lease, the counters. Text: one "key: value" line per item;
 * JSON: one object, the repeated key "client" as an array. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lsc/device.h"
#include "lsc/lscd.h"
#include "lsc/env.h"
#include "lscctl.h"

#define ITEMS_MAX 128u

typedef struct status_items {
    char *key[ITEMS_MAX];
    char *value[ITEMS_MAX];
    size_t n;
    bool oom;
} status_items;

static char *dup_text(const char *s)
{
    size_t n = strlen(s) + 1u;
    char *d = malloc(n);
    if (d != NULL) {
        memcpy(d, s, n);
    }
    return d;
}

static void collect(void *user, const char *key, const char *value)
{
    status_items *it = user;
    if (it->n == ITEMS_MAX) {
        return;
    }
    it->key[it->n] = dup_text(key);
    it->value[it->n] = dup_text(value);
    if (it->key[it->n] == NULL || it->value[it->n] == NULL) {
        free(it->key[it->n]);
        free(it->value[it->n]);
        it->oom = true;
        return;
    }
    it->n++;
}

static bool all_digits(const char *s)
{
    if (*s == '\0' || (s[0] == '0' && s[1] != '\0')) {
        return false;
    }
    for (; *s != '\0'; s++) {
        if (*s < '0' || *s > '9') {
            return false;
        }
    }
    return true;
}

static void json_value(const char *v)
{
    if (all_digits(v) && strlen(v) < 16u) {
        (void)fputs(v, stdout);
    } else {
        lscctl_json_string(stdout, v);
    }
}

/* lscd's items as one object, then lscctl's own ("calibrated profile": the
 * arm's profile, when one was found for it; NULL: none). */
static void print_json(const status_items *it, const char *calibrated)
{
    bool first = true;
    (void)putchar('{');
    for (size_t i = 0; i < it->n; i++) {
        bool repeated = false;
        for (size_t j = 0; j < i; j++) {
            repeated = repeated || strcmp(it->key[j], it->key[i]) == 0;
        }
        if (repeated) {
            continue; /* printed with the first of its key */
        }
        bool many = false;
        for (size_t j = i + 1u; j < it->n; j++) {
            many = many || strcmp(it->key[j], it->key[i]) == 0;
        }
        if (!first) {
            (void)putchar(',');
        }
        first = false;
        lscctl_json_string(stdout, it->key[i]);
        (void)putchar(':');
        if (!many && strcmp(it->key[i], "client") != 0) {
            json_value(it->value[i]);
            continue;
        }
        (void)putchar('[');
        for (size_t j = i, k = 0; j < it->n; j++) {
            if (strcmp(it->key[j], it->key[i]) == 0) {
                if (k++ > 0u) {
                    (void)putchar(',');
                }
                json_value(it->value[j]);
            }
        }
        (void)putchar(']');
    }
    if (calibrated != NULL) {
        (void)fputs(first ? "\"calibrated profile\":" : ",\"calibrated profile\":", stdout);
        lscctl_json_string(stdout, calibrated);
    }
    (void)puts("}");
}

int lscctl_cmd_status(const lscctl_opts *o, int argc, char **argv)
{
    (void)argc;
    (void)argv;
    lsc_device_kind kind; /* by the name, as the device layer decides it */
    if (o->port == NULL || lsc_device_kind_of_name(o->port, &kind) != 0 ||
        kind != LSC_DEVICE_LSCD) {
        return lscctl_fail(o, LSCCTL_EXIT_USAGE,
                           "status asks lscd for its state: give --port lscd:NAME (or "
                           "lscd:PATH to its socket)");
    }
    if (o->dry_run) {
        return LSCCTL_EXIT_OK; /* it would send no frame to the controller */
    }
    lsc_lscd_options opt = {.size = sizeof opt};
    opt.timeout_ms = (uint32_t)o->timeout_ms;
    opt.no_notifications = true;
    lsc_lscd *s = NULL;
    int r = lsc_lscd_open(o->port, &opt, &s);
    status_items it;
    memset(&it, 0, sizeof it);
    if (r == 0) {
        r = lsc_lscd_status(s, collect, &it, (uint32_t)o->timeout_ms);
    }
    int code = LSCCTL_EXIT_OK;
    if (r < 0) {
        lscctl_shown why; /* it names the socket: the user's text */
        code = lscctl_fail(o,
                           r == LSC_EINVAL     ? LSCCTL_EXIT_USAGE
                           : r == LSC_ETIMEOUT ? LSCCTL_EXIT_TIMEOUT
                                               : LSCCTL_EXIT_FAIL,
                           "%s", lscctl_show(&why, lsc_lscd_error(s)));
    } else if (it.oom) {
        code = lscctl_fail(o, LSCCTL_EXIT_FAIL, "out of memory");
    } else if (o->json) {
        print_json(&it, o->arm_calibrated ? o->arm : NULL);
    } else {
        for (size_t i = 0; i < it.n; i++) {
            /* lscd's words: escaped as every outside text is (JSON keeps them exact) */
            lscctl_shown key, value;
            (void)printf("%s: %s\n", lscctl_show(&key, it.key[i]), lscctl_show(&value, it.value[i]));
        }
        if (o->arm_calibrated) { /* lscctl's, beside lscd's: the arm's own profile */
            lscctl_shown path;
            (void)printf("calibrated profile: %s\n", lscctl_show(&path, o->arm));
        }
    }
    for (size_t i = 0; i < it.n; i++) {
        free(it.key[i]);
        free(it.value[i]);
    }
    lsc_lscd_close(s);
    return code;
}
