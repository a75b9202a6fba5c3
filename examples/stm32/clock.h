/* A millisecond clock from SysTick. */
#ifndef CLOCK_H
#define CLOCK_H

#include <stdint.h>

void clock_init(void);
/* Milliseconds since clock_init (wraps around at 2^32). */
uint32_t clock_ms(void);

#endif
