/* Vector table and reset handler for the STM32F405: copies .data from flash,
 * clears .bss, runs main() and hands its return value to the debugger (or
 * QEMU) through semihosting. */
#include <stdint.h>

#include "semihosting.h"

extern uint32_t _stack_top, _data_start, _data_end, _data_load, _bss_start, _bss_end;

int main(void);
void reset_handler(void);
void systick_handler(void);
void usart1_irq_handler(void);

static void fault_handler(void)
{
    semihosting_exit(0xFF);
}

#define VECTORS (16u + 82u) /* the core's 16, then the STM32F405's 82 interrupts */

__attribute__((section(".vectors"), used)) static void (*const vectors[VECTORS])(void) = {
    [0] = (void (*)(void))(uintptr_t)&_stack_top,
    [1] = reset_handler,
    [2] = fault_handler, /* NMI */
    [3] = fault_handler, /* HardFault */
    [4] = fault_handler, /* MemManage */
    [5] = fault_handler, /* BusFault */
    [6] = fault_handler, /* UsageFault */
    [15] = systick_handler,
    [16 + 37] = usart1_irq_handler,
};

void reset_handler(void)
{
    const uint32_t *src = &_data_load;
    for (uint32_t *dst = &_data_start; dst < &_data_end;)
        *dst++ = *src++;
    for (uint32_t *dst = &_bss_start; dst < &_bss_end;)
        *dst++ = 0;
    semihosting_exit(main());
}
