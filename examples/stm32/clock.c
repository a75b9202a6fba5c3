#include "clock.h"

#include "board.h"

static volatile uint32_t ticks;

void systick_handler(void);
void systick_handler(void)
{
    ticks++;
}

void clock_init(void)
{
    ticks = 0;
    SYST_RVR = CPU_HZ / 1000u - 1u;
    SYST_CVR = 0;
    SYST_CSR = 7u; /* processor clock, interrupt, enable */
}

uint32_t clock_ms(void)
{
    return ticks;
}
