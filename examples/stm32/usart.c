#include "usart.h"

#include "board.h"

#define RING_SIZE 128u /* a power of two; holds the longest reply (257 bytes) in pieces */

static volatile uint8_t ring[RING_SIZE];
static volatile uint32_t ring_head; /* written by the interrupt */
static volatile uint32_t ring_tail; /* written by usart1_read */
static volatile uint32_t dropped;

void usart1_init(uint32_t baud)
{
    RCC_AHB1ENR |= RCC_AHB1ENR_GPIOAEN;
    RCC_APB2ENR |= RCC_APB2ENR_USART1EN;
    /* PA9 and PA10 in alternate-function mode (0b10), AF7 = USART1 */
    GPIOA_MODER = (GPIOA_MODER & ~((3u << 18) | (3u << 20))) | (2u << 18) | (2u << 20);
    GPIOA_AFRH = (GPIOA_AFRH & ~((0xFu << 4) | (0xFu << 8))) | (7u << 4) | (7u << 8);

    ring_head = ring_tail = dropped = 0;
    USART1_BRR = (APB2_HZ + baud / 2u) / baud; /* 16x oversampling: mantissa.fraction */
    USART1_CR1 = USART_CR1_UE | USART_CR1_TE | USART_CR1_RE | USART_CR1_RXNEIE;
    NVIC_ISER(USART1_IRQN / 32u) = 1u << (USART1_IRQN % 32u);
}

void usart1_write(const uint8_t *data, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        while (!(USART1_SR & USART_SR_TXE))
            ;
        USART1_DR = data[i];
    }
}

void usart1_irq_handler(void);
void usart1_irq_handler(void)
{
    uint32_t sr = USART1_SR;
    if (sr & (USART_SR_RXNE | USART_SR_ORE)) {
        uint8_t byte = (uint8_t)USART1_DR; /* reading DR clears RXNE and ORE */
        if (sr & USART_SR_ORE)
            dropped++;
        if (ring_head - ring_tail < RING_SIZE) {
            ring[ring_head % RING_SIZE] = byte;
            ring_head++;
        } else {
            dropped++;
        }
    }
}

size_t usart1_read(uint8_t *buf, size_t cap)
{
    size_t n = 0;
    while (n < cap && ring_tail != ring_head) {
        buf[n++] = ring[ring_tail % RING_SIZE];
        ring_tail++;
    }
    return n;
}

uint32_t usart1_dropped(void)
{
    return dropped;
}
