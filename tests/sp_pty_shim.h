/* Test-only libserialport pty interposer (sp_pty_shim.c). */
#ifndef LSC_TEST_SP_PTY_SHIM_H
#define LSC_TEST_SP_PTY_SHIM_H

#include <stdbool.h>

/* How many times the shim answered for a pty (0: it was never used). */
extern unsigned lsc_test_shim_hits;

#endif
