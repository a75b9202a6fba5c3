/* The lsc client on an STM32F405, over USART1 at 9600 baud (PA9 TX, PA10 RX):
 * reads the battery, moves two servos and reads them back, runs action group
 * 1 and waits for it, then powers the servos off. Returns (through
 * semihosting, when a debugger or QEMU is attached) 0 if every step went as
 * expected, or the number of the first step that did not. */
#include <stddef.h>
#include <stdint.h>

#include "clock.h"
#include "lsc/client.h"
#include "usart.h"

/* ---- lsc_io over the USART1 driver and the SysTick clock ----------------- */

static int uart_write(void *ctx, const uint8_t *data, size_t n)
{
    (void)ctx;
    usart1_write(data, n);
    return (int)n;
}

static int uart_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms)
{
    (void)ctx;
    uint32_t start = clock_ms();
    for (;;) {
        size_t n = usart1_read(buf, cap);
        if (n > 0)
            return (int)n;
        if (clock_ms() - start >= timeout_ms)
            return 0;
        __asm__ volatile("wfi"); /* until the next byte or SysTick */
    }
}

static uint32_t uart_now(void *ctx)
{
    (void)ctx;
    return clock_ms();
}

static void sleep_ms(uint32_t ms)
{
    uint32_t start = clock_ms();
    while (clock_ms() - start < ms)
        __asm__ volatile("wfi");
}

/* ---- The example --------------------------------------------------------- */

#define TIMEOUT_MS 500u /* a reply takes ~10 ms at 9600 baud; generous for busy hosts */

int main(void)
{
    clock_init();
    usart1_init(9600);

    lsc_client lsc;
    const lsc_io io = {NULL, uart_write, uart_read, uart_now};
    if (lsc_client_init(&lsc, &io) != 0)
        return 1;

    /* 2: the battery */
    uint16_t mv = 0;
    if (lsc_client_get_battery(&lsc, &mv, TIMEOUT_MS) != 0 || mv < 6000)
        return 2;

    /* 3: two servos over 200 ms, then where they are */
    const lsc_servo targets[] = {{1, 2000}, {2, 1200}};
    if (lsc_client_move(&lsc, 200, targets, 2) != 0)
        return 3;
    sleep_ms(600); /* the move takes 200 ms; the rest is slack for a busy host under QEMU */
    const uint8_t ids[] = {1, 2};
    lsc_servo now[2];
    if (lsc_client_read_positions(&lsc, ids, 2, now, TIMEOUT_MS) != 2 ||
        now[0].position != 2000 || now[1].position != 1200)
        return 4;

    /* 5: action group 1 once, waiting until the controller says it completed */
    if (lsc_client_run_group(&lsc, 1, 1) != 0)
        return 5;
    lsc_notification end;
    if (lsc_client_wait_group(&lsc, 5000, &end) != 0 || end.cmd != LSC_CMD_GROUP_COMPLETE ||
        end.group != 1)
        return 6;

    /* 7: let both servos turn freely */
    if (lsc_client_unload(&lsc, ids, 2) != 0)
        return 7;
    return usart1_dropped() == 0 ? 0 : 8;
}
