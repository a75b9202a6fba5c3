#include "wire.h"

#include <stdio.h>

static void print_bytes(const char *prefix, const uint8_t *bytes, size_t len)
{
    fputs(prefix, stdout);
    for (size_t i = 0; i < len; i++)
        printf(" %02X", bytes[i]);
    putchar('\n');
}

static void wire_log(void *ctx, const lsc_sim_event *ev)
{
    (void)ctx;
    switch (ev->kind) {
    case LSC_SIM_EV_RX:
        print_bytes(">", ev->bytes, ev->len);
        break;
    case LSC_SIM_EV_TX:
        print_bytes("<", ev->bytes, ev->len);
        break;
    case LSC_SIM_EV_BEEP:
        printf("! beep: %s\n", ev->text ? ev->text : "?");
        break;
    case LSC_SIM_EV_IGNORED:
        printf("! ignored: %s\n", ev->text ? ev->text : "?");
        break;
    case LSC_SIM_EV_NOISE:
        print_bytes("! noise:", ev->bytes, ev->len);
        break;
    case LSC_SIM_EV_DROPPED:
        printf("! dropped (%s):", ev->text ? ev->text : "?");
        print_bytes("", ev->bytes, ev->len);
        break;
    }
    fflush(stdout);
}

int wire_init(lsc_sim *sim)
{
    int rc = lsc_sim_init(sim);
    if (rc == 0)
        lsc_sim_set_log(sim, wire_log, NULL);
    return rc;
}

int wire_init_bus(lsc_lxbus *bus)
{
    int rc = lsc_lxbus_init(bus);
    if (rc == 0) {
        lsc_lxbus_set_log(bus, wire_log, NULL);
        lsc_lxbus_set_echo(bus, true);
        lsc_lxbus_set_baud(bus, 115200);
    }
    return rc;
}

int wire_load_groups(lsc_sim *sim, wire_groups *g, const char *path)
{
    static char text[8192];
    FILE *f = fopen(path, "r");
    if (!f) {
        perror(path);
        return LSC_EINVAL;
    }
    size_t len = fread(text, 1, sizeof text, f);
    int too_long = !feof(f);
    int failed = ferror(f) != 0;
    if (fclose(f) != 0 || failed) {
        perror(path);
        return LSC_EINVAL;
    }
    if (too_long) {
        fprintf(stderr, "%s: longer than %zu bytes\n", path, sizeof text);
        return LSC_ENOSPC;
    }
    lsc_sim_parse_error err = {0, 0, NULL};
    int rc = lsc_sim_groups_init(&g->groups, g->steps, sizeof g->steps / sizeof g->steps[0],
                                 g->targets, sizeof g->targets / sizeof g->targets[0]);
    if (rc == 0)
        rc = lsc_sim_groups_parse(&g->groups, text, len, &err);
    if (rc < 0) {
        fprintf(stderr, "%s:%u:%u: %s\n", path, (unsigned)err.line, (unsigned)err.column,
                err.message ? err.message : lsc_strerror(rc));
        return rc;
    }
    lsc_sim_set_groups(sim, &g->groups);
    return 0;
}
