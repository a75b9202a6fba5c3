/*
 * lsc serial transport (host only: Linux, macOS and other POSIX systems).
 *
 * Opens a serial device at a baud rate, raw 8N1, no flow control, for this
 * process alone, and exposes it as the lsc_io a client talks through.
 *
 * Two backends behind this one header:
 *  - termios: POSIX; works on USB serial adapters, on-board UARTs and
 *    pseudo-terminals (socat links, /dev/pts/N, lsc-sim).
 *  - libserialport (when the library is built with it, LSC_WITH_LIBSERIALPORT):
 *    opens and configures the port; libserialport 0.1.1 refuses
 *    pseudo-terminals, so with LSC_SERIAL_AUTO a path it cannot open falls
 *    back to termios. Reads and writes use the port's file descriptor with
 *    poll() in both backends.
 *
 * Exclusive access: the descriptor is flock(LOCK_EX|LOCK_NB)-ed. A second
 * opener, in this or another process, also as root, gets LSC_EBUSY, and so
 * does anyone opening a tty that another program marked exclusive
 * (TIOCEXCL, Linux): that flag is respected, never cleared. lsc never sets
 * TIOCEXCL itself: the flag is the tty's and would outlive a process killed
 * before it could clear it (SIGKILL), leaving the port "busy" for every
 * non-root user; the kernel drops a flock however the process ends. A
 * program that neither flocks the port nor sets TIOCEXCL is not kept out.
 *
 * Memory: an lsc_serial is opaque: lsc_serial_open allocates it and
 * lsc_serial_close frees it (libserialport allocates internally while a
 * port is open). Threads: one thread per lsc_serial at a time.
 *
 * Errors: negative LSC_E... codes (lsc/core.h). After any failure the port
 * keeps the OS errno (lsc_serial_os_errno, 0 if the error was not the OS's)
 * and a message naming the path and the OS error
 * (lsc_serial_error_message); a failed open leaves no handle, and its errno
 * and message are the calling thread's: lsc_serial_os_errno(NULL) and
 * lsc_serial_error_message(NULL) say them until its next open. E.g.
 *   "/dev/ttyUSB0: Permission denied (add your user to the dialout group:
 *    sudo usermod -aG dialout $USER, then log in again; or add a udev rule)".
 *   LSC_EINVAL   bad argument (NULL, empty or too long path, unsupported baud)
 *   LSC_ENODEV   no such device (ENOENT, ENXIO, ENODEV), not a serial port (a
 *                directory, a file, a device without termios), or it went away
 *                while open (EOF, EIO, hang-up: a USB adapter unplugged)
 *   LSC_EACCES   permission denied (message says how to get access)
 *   LSC_EBUSY    the port is open elsewhere
 *   LSC_EIO      any other OS error, or a write that cannot finish in time
 *                (the message says how many of its bytes went out)
 *   LSC_ETIMEOUT (never from read: a read timeout returns 0 bytes)
 */
#ifndef LSC_SERIAL_H
#define LSC_SERIAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/core.h"
#include "lsc/io.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LSC_SERIAL_BAUD_DEFAULT 9600u
#define LSC_SERIAL_PATH_MAX 256u
#define LSC_SERIAL_MESSAGE_MAX 512u

/* After a write that timed out with part of its bytes on the line, the port
 * stays silent this many ms (plus a 16-byte UART FIFO's time at the baud)
 * before the write returns: longer than a controller's frame gap (lsc-sim
 * drops a frame left unfinished for 100 ms), so the torn frame is dropped
 * and the next frame, from this process or the next, is read whole. */
#define LSC_SERIAL_TORN_QUIET_MS 150u

/* Which backend opens the port. */
typedef enum lsc_serial_backend {
    LSC_SERIAL_AUTO = 0,          /* libserialport if built in, else (or if it fails) termios */
    LSC_SERIAL_TERMIOS = 1,       /* termios only */
    LSC_SERIAL_LIBSERIALPORT = 2  /* libserialport only (LSC_EINVAL if not built in) */
} lsc_serial_backend;

/* An open port (opaque). */
typedef struct lsc_serial lsc_serial;

/* Opens path at baud (0 = LSC_SERIAL_BAUD_DEFAULT; termios supports the
 * standard rates 1200..230400, libserialport any its OS driver takes), raw
 * 8N1, no flow control, exclusive, with backend b, into *out. Any input
 * already pending on the line is flushed. Does not block (O_NONBLOCK; a
 * modem-control wait is never done). Returns 0, or an error as listed above
 * (or LSC_ENOSPC: out of memory) with *out NULL: nothing is left open, and
 * lsc_serial_error_message(NULL) and lsc_serial_os_errno(NULL) say why. */
LSC_API int lsc_serial_open(const char *path, uint32_t baud, lsc_serial_backend b,
                            lsc_serial **out);

/* Closes the port (waits for nothing; pending output may be discarded by the
 * OS) and frees s. s may be NULL. */
LSC_API void lsc_serial_close(lsc_serial *s);

/* Fills *io with the port's transport: write (all bytes, retrying EINTR and
 * short writes; it gives up with LSC_EIO when the line has not taken them
 * after 1 s plus twice a whole frame's time plus the bytes' own time on the
 * wire at the port's baud: then what the OS still holds is flushed
 * (TCOFLUSH), the message says how many of the bytes went out, and if some
 * did the line is kept silent for LSC_SERIAL_TORN_QUIET_MS first), read (poll() up to timeout_ms, then
 * what is there; EINTR resumes with the time left; EOF/hang-up is
 * LSC_ENODEV, never a busy loop) and now_ms (CLOCK_MONOTONIC). The io stays
 * valid until s is closed. */
LSC_API void lsc_serial_get_io(lsc_serial *s, lsc_io *io);

/* The same functions, for callers that wrap them (ctx is the lsc_serial *). */
LSC_API int lsc_serial_write(void *ctx, const uint8_t *data, size_t n);
LSC_API int lsc_serial_read(void *ctx, uint8_t *buf, size_t cap, uint32_t timeout_ms);
LSC_API uint32_t lsc_serial_now_ms(void *ctx);

/* The port's descriptor (either backend), or -1 for NULL: it polls readable (POLLIN) when bytes arrived, and POLLHUP or
 * POLLERR when the port went away. For a program's own event loop; read
 * and write through lsc_serial_read/lsc_serial_write, not on it. */
LSC_API int lsc_serial_fileno(const lsc_serial *s);

/* The last error's message ("" if none). Never NULL; s NULL: the calling
 * thread's last lsc_serial_open's ("" after one that succeeded). */
LSC_API const char *lsc_serial_error_message(const lsc_serial *s);
/* The last error's OS errno (0 if none or not an OS error); s NULL: the
 * calling thread's last lsc_serial_open's. */
LSC_API int lsc_serial_os_errno(const lsc_serial *s);
/* The backend in use (TERMIOS or LIBSERIALPORT), or LSC_SERIAL_AUTO for
 * NULL. */
LSC_API lsc_serial_backend lsc_serial_backend_in_use(const lsc_serial *s);
/* True if this build has the libserialport backend. */
LSC_API bool lsc_serial_have_libserialport(void);

/* ---- Port enumeration (libserialport) ----------------------------------- */

/* One serial port as listed. A struct that grows: fields are only ever
 * added at the end (see lsc_serial_list_ports for its size). */
typedef struct lsc_port_info {
    size_t size;                    /* sizeof(lsc_port_info) in the caller's headers */
    char path[LSC_SERIAL_PATH_MAX]; /* e.g. /dev/ttyUSB0 */
    char description[128];          /* libserialport's description, "" if none */
    bool usb;                       /* vid/pid/serial are valid */
    uint16_t vid, pid;
    char serial[64];                /* USB serial number, "" if none */
} lsc_port_info;

/* Lists the system's serial ports into out[0..cap). The caller sets
 * out[0].size to sizeof(lsc_port_info), the size of every element and the
 * array's stride: element i is written at (char *)out + i * out[0].size, at
 * most that many bytes of it, with its size set to it. Returns how many
 * exist (may exceed cap: only cap are written), or LSC_ENODEV when built
 * without libserialport, or LSC_EIO when the OS listing fails, or
 * LSC_EINVAL for a size below offsetof(lsc_port_info, path) +
 * LSC_SERIAL_PATH_MAX with cap > 0 (nothing listed). out NULL with cap 0
 * only counts. message (msgcap bytes, may be NULL) receives the error text.
 * Strings are truncated to fit and always NUL-terminated. */
LSC_API int lsc_serial_list_ports(lsc_port_info *out, size_t cap, char *message, size_t msgcap);

#ifdef __cplusplus
}
#endif

#endif /* LSC_SERIAL_H */
