/* Helpers shared by the bus-servo codec's files (not part of the API). */
#ifndef LSC_LX_INTERNAL_H
#define LSC_LX_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lsc/lx.h"

/* What lsc_lx_reject says of a checksum that fails (the parser counts it
 * apart, then reports LSC_EFRAME). */
#define LSC_LX_BADSUM (-100)

/* The checksum of the n-byte frame at b (its bytes 2..n-2: id, LEN, command,
 * parameters). */
uint8_t lsc_lx_checksum(const uint8_t *b, size_t n);

/* 0 if byte b[pos] may follow the valid prefix b[0..pos), else why not:
 * LSC_ESYNC (not a header byte), LSC_EFRAME (id, LEN or command), or
 * LSC_LX_BADSUM (the last byte is not the checksum). */
int lsc_lx_reject(const uint8_t *b, size_t pos);

/* 0 if b[0..n) is a valid prefix of a frame (or a whole valid frame, its
 * checksum right), else what lsc_lx_reject says of its first bad byte. */
int lsc_lx_check(const uint8_t *b, size_t n);

/* Whether id may carry cmd: a reply's id is a servo's (0..253); a request's
 * may be LSC_LX_BROADCAST too, but for a read other than ID_READ (none would
 * answer). */
bool lsc_lx_id_ok(uint8_t id, uint8_t cmd, bool reply);

#endif
