/* A small register-level driver for USART1 (PA9 TX, PA10 RX), 8N1:
 * transmit by polling, receive by interrupt into a ring buffer, so no byte
 * is lost while the program is busy elsewhere. */
#ifndef USART_H
#define USART_H

#include <stddef.h>
#include <stdint.h>

void usart1_init(uint32_t baud);
/* Sends n bytes, waiting for the transmitter as needed. */
void usart1_write(const uint8_t *data, size_t n);
/* Moves up to cap received bytes into buf; returns how many (0: none yet). */
size_t usart1_read(uint8_t *buf, size_t cap);
/* Received bytes dropped since init because the ring buffer was full or the
 * receiver overran. */
uint32_t usart1_dropped(void);

#endif
