/* The registers this example touches on an STM32F405 (RM0090), and its clock. */
#ifndef BOARD_H
#define BOARD_H

#include <stdint.h>

/* Core clock. QEMU's netduinoplus2 runs the STM32F405 at 168 MHz; on a real
 * board, set the PLL up for 168 MHz first, or build with -DCPU_HZ=16000000 to
 * stay on the 16 MHz HSI oscillator the chip starts with. */
#ifndef CPU_HZ
#define CPU_HZ 168000000u
#endif
/* USART1 sits on APB2; with the default prescaler (1) it runs at CPU_HZ. */
#define APB2_HZ CPU_HZ

#define REG32(addr) (*(volatile uint32_t *)(addr))

/* RCC */
#define RCC_AHB1ENR REG32(0x40023830u)
#define RCC_APB2ENR REG32(0x40023844u)
#define RCC_AHB1ENR_GPIOAEN (1u << 0)
#define RCC_APB2ENR_USART1EN (1u << 4)

/* GPIOA: PA9 = USART1_TX, PA10 = USART1_RX (alternate function 7) */
#define GPIOA_MODER REG32(0x40020000u)
#define GPIOA_AFRH REG32(0x40020024u)

/* USART1 */
#define USART1_SR REG32(0x40011000u)
#define USART1_DR REG32(0x40011004u)
#define USART1_BRR REG32(0x40011008u)
#define USART1_CR1 REG32(0x4001100Cu)
#define USART_SR_RXNE (1u << 5)
#define USART_SR_TXE (1u << 7)
#define USART_SR_ORE (1u << 3)
#define USART_CR1_RE (1u << 2)
#define USART_CR1_TE (1u << 3)
#define USART_CR1_RXNEIE (1u << 5)
#define USART_CR1_UE (1u << 13)
#define USART1_IRQN 37u

/* Cortex-M4 system registers */
#define SYST_CSR REG32(0xE000E010u)
#define SYST_RVR REG32(0xE000E014u)
#define SYST_CVR REG32(0xE000E018u)
#define NVIC_ISER(n) REG32(0xE000E100u + 4u * (n))

#endif
