/* Runs an AVR firmware (an Arduino Uno sketch) in simavr with UART0 wired to
 * the virtual controller (lsc/sim.h), or with --lx to a virtual bus of
 * servos with those ids (lsc/lxbus.h: 115200 baud, the firmware hearing its
 * own bytes as on a one-wire bus), and logs the exchange (wire.h).
 *
 *   lsc_avr_harness [--groups FILE] [--battery MV] [--seconds S] [--lx ID,...] firmware.elf
 *
 * The firmware talks back to the test through two general-purpose I/O
 * registers no Arduino code uses:
 *   GPIOR1 (data address 0x4A): a console; each byte written is printed, lines
 *          prefixed "console: ";
 *   GPIOR0 (data address 0x3E): the exit code; writing it ends the run.
 * Exit status: the firmware's code; 124 if it did not finish within the
 * simulated time limit (default 30 s of ATmega328P time at 16 MHz); 125 if it
 * crashed or stopped without writing an exit code; 2 for a bad command line. */
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <simavr/avr_uart.h>
#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/sim_io.h>
#include <simavr/sim_irq.h>

#include "wire.h"

#define MCU "atmega328p"
#define F_CPU_HZ 16000000u
#define GPIOR0_ADDR 0x3E
#define GPIOR1_ADDR 0x4A

typedef struct harness {
    lsc_sim sim;
    lsc_lxbus bus;
    int lx;             /* the firmware talks to the bus, not the controller */
    wire_groups groups;
    avr_t *avr;
    avr_irq_t *uart_in; /* bytes to the AVR */
    int xoff;           /* the AVR's receive FIFO is full */
    int exit_code;      /* -1 until the firmware writes GPIOR0 */
    char line[256];     /* console line being assembled */
    size_t line_len;
} harness;

static void console_flush(harness *h)
{
    printf("console: %.*s\n", (int)h->line_len, h->line);
    fflush(stdout);
    h->line_len = 0;
}

static void on_gpior1(avr_t *avr, avr_io_addr_t addr, uint8_t v, void *param)
{
    (void)avr;
    (void)addr;
    harness *h = param;
    if (v == '\n' || h->line_len == sizeof h->line)
        console_flush(h);
    if (v != '\n' && v != '\r')
        h->line[h->line_len++] = (char)v;
}

static void on_gpior0(avr_t *avr, avr_io_addr_t addr, uint8_t v, void *param)
{
    (void)addr;
    harness *h = param;
    h->exit_code = v;
    avr->state = cpu_Done;
}

/* A byte the AVR sent on UART0 goes to the controller. */
static void on_uart_out(avr_irq_t *irq, uint32_t value, void *param)
{
    (void)irq;
    harness *h = param;
    uint8_t byte = (uint8_t)value;
    if (h->lx)
        lsc_lxbus_feed(&h->bus, &byte, 1);
    else
        lsc_sim_feed(&h->sim, &byte, 1);
}

static void on_xon(avr_irq_t *irq, uint32_t value, void *param)
{
    (void)irq;
    (void)value;
    ((harness *)param)->xoff = 0;
}

static void on_xoff(avr_irq_t *irq, uint32_t value, void *param)
{
    (void)irq;
    (void)value;
    ((harness *)param)->xoff = 1;
}

/* simavr's own messages go to stderr, away from the exchange log. */
static void to_stderr(avr_t *avr, const int level, const char *format, va_list ap)
{
    if (!avr || level <= (int)avr->log)
        vfprintf(stderr, format, ap);
}

/* elf_read_firmware allocates; simavr has no function to free it. */
static void free_firmware(elf_firmware_t *fw)
{
    free(fw->flash);
    free(fw->eeprom);
    free(fw->fuse);
    free(fw->lockbits);
#if ELF_SYMBOLS
    for (uint32_t i = 0; i < fw->symbolcount; i++)
        free(fw->symbol[i]);
    free(fw->symbol);
#endif
}

static int usage(void)
{
    fputs("usage: lsc_avr_harness [--groups FILE] [--battery MV] [--seconds S] [--lx ID,...] "
          "firmware.elf\n",
          stderr);
    return 2;
}

int main(int argc, char **argv)
{
    static harness h; /* the model is ~10 KiB */
    const char *groups = NULL, *elf = NULL, *lx = NULL;
    unsigned long battery = LSC_SIM_BATTERY_DEFAULT, seconds = 30;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--groups") && i + 1 < argc)
            groups = argv[++i];
        else if (!strcmp(argv[i], "--battery") && i + 1 < argc)
            battery = strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--seconds") && i + 1 < argc)
            seconds = strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--lx") && i + 1 < argc)
            lx = argv[++i];
        else if (argv[i][0] != '-' && !elf)
            elf = argv[i];
        else
            return usage();
    }
    if (!elf || battery > UINT16_MAX || seconds == 0 || seconds > 3600)
        return usage();

    if (wire_init(&h.sim) != 0 || wire_init_bus(&h.bus) != 0)
        return 2;
    for (const char *p = lx; p && *p;) {
        char *end;
        unsigned long id = strtoul(p, &end, 10);
        if (end == p || id > LSC_LX_ID_MAX || lsc_lxbus_add(&h.bus, (uint8_t)id) < 0)
            return usage();
        p = *end == ',' ? end + 1 : end;
        if (*end != ',' && *end != '\0')
            return usage();
    }
    h.lx = lx != NULL;
    (void)lsc_lxbus_set_vin(&h.bus, (uint16_t)(battery <= UINT16_MAX ? battery : 0));
    lsc_sim_set_battery(&h.sim, (uint16_t)battery);
    if (groups && wire_load_groups(&h.sim, &h.groups, groups) != 0)
        return 2;
    h.exit_code = -1;

    avr_global_logger_set(to_stderr);
    elf_firmware_t fw;
    memset(&fw, 0, sizeof fw);
    if (elf_read_firmware(elf, &fw) != 0) {
        fprintf(stderr, "%s: cannot read the firmware\n", elf);
        return 2;
    }
    h.avr = avr_make_mcu_by_name(MCU);
    if (!h.avr) {
        fprintf(stderr, "simavr does not know the %s\n", MCU);
        return 2;
    }
    avr_init(h.avr);
    h.avr->frequency = F_CPU_HZ;
    avr_load_firmware(h.avr, &fw);
    h.avr->log = LOG_WARNING;

    /* UART0: take its output, feed its input; no console printing by simavr */
    uint32_t flags = 0;
    avr_ioctl(h.avr, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
    flags &= ~(uint32_t)AVR_UART_FLAG_STDIO;
    avr_ioctl(h.avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
    avr_irq_t *out = avr_io_getirq(h.avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT);
    h.uart_in = avr_io_getirq(h.avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
    avr_irq_t *xon = avr_io_getirq(h.avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XON);
    avr_irq_t *xoff = avr_io_getirq(h.avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XOFF);
    if (!out || !h.uart_in || !xon || !xoff) {
        fputs("simavr: no UART0\n", stderr);
        return 2;
    }
    avr_irq_register_notify(out, on_uart_out, &h);
    avr_irq_register_notify(xon, on_xon, &h);
    avr_irq_register_notify(xoff, on_xoff, &h);
    avr_register_io_write(h.avr, GPIOR0_ADDR, on_gpior0, &h);
    avr_register_io_write(h.avr, GPIOR1_ADDR, on_gpior1, &h);

    const uint64_t limit = (uint64_t)seconds * F_CPU_HZ;
    int state = cpu_Running;
    while (h.avr->cycle < limit) {
        state = avr_run(h.avr);
        if (state == cpu_Done || state == cpu_Crashed)
            break;
        /* The controller's (or the bus's) clock follows the AVR's. */
        uint64_t now_us = h.avr->cycle / (F_CPU_HZ / 1000000u);
        if (h.lx) {
            if (now_us > lsc_lxbus_now_us(&h.bus))
                lsc_lxbus_advance_us(&h.bus, now_us - lsc_lxbus_now_us(&h.bus));
            while (!h.xoff && lsc_lxbus_available(&h.bus) > 0) {
                uint8_t byte;
                lsc_lxbus_read(&h.bus, &byte, 1);
                avr_raise_irq(h.uart_in, byte);
            }
            continue;
        }
        if (now_us > lsc_sim_now_us(&h.sim))
            lsc_sim_advance_us(&h.sim, now_us - lsc_sim_now_us(&h.sim));
        while (!h.xoff && lsc_sim_available(&h.sim) > 0) {
            uint8_t byte;
            lsc_sim_read(&h.sim, &byte, 1);
            avr_raise_irq(h.uart_in, byte);
        }
    }
    if (h.line_len > 0)
        console_flush(&h);
    int code;
    if (h.exit_code >= 0) {
        printf("exit %d\n", h.exit_code);
        code = h.exit_code;
    } else if (state == cpu_Done || state == cpu_Crashed) {
        printf("stopped without an exit code (%s)\n", state == cpu_Done ? "sleeping" : "crashed");
        code = 125;
    } else {
        printf("still running after %lu s of simulated time\n", seconds);
        code = 124;
    }
    avr_terminate(h.avr);
    free_firmware(&fw);
    return code;
}
