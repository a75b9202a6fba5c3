/* Ends the program through ARM semihosting: under QEMU (-semihosting-config
 * enable=on) or a debugger, the host process exits with this code. Without a
 * debugger attached the bkpt instruction faults, so on a real board this
 * stops the core instead. */
#ifndef SEMIHOSTING_H
#define SEMIHOSTING_H

#include <stdint.h>

__attribute__((noreturn)) void semihosting_exit(int code);

#endif
