/* Structs that grow without breaking a caller: a public host struct that
 * starts with `size_t size;`, which the caller sets to sizeof of the struct
 * in its headers (`lsc_reach r = { .size = sizeof r, ... };`). Fields are only
 * ever added at the end. The library never reads or writes beyond size: a
 * result is filled into a whole struct of the library's own and at most size
 * bytes of it are copied out; an input's fields beyond size take their
 * default, as if 0. A size below the size field and the first member is
 * refused (LSC_EINVAL). Internal; portable C99. */
#ifndef LSC_UTIL_SIZED_H
#define LSC_UTIL_SIZED_H

#include <stddef.h>
#include <string.h>

/* The least size of `type`: its size field and its first member. */
#define LSC_SIZED_MIN(type, first) (offsetof(type, first) + sizeof(((type *)0)->first))

/* The size s's caller set (s non-NULL; its first member). */
static inline size_t lsc_sized_size(const void *s)
{
    size_t n;
    memcpy(&n, s, sizeof n);
    return n;
}

/* Copies the struct all (n bytes, the library's whole struct) into out, at
 * most out's size bytes; out's size stays as the caller set it. out NULL:
 * nothing. out's size must be at least its least (checked before). */
static inline void lsc_sized_give(void *out, const void *all, size_t n)
{
    if (out != NULL) {
        size_t size = lsc_sized_size(out);
        memcpy((char *)out + sizeof size, (const char *)all + sizeof size,
               (size < n ? size : n) - sizeof size);
    }
}

/* Element i of an array of structs that grow whose caller set out[0].size
 * (size: the size of every element and the array's stride): its size field
 * becomes size, then all (n bytes, the library's whole struct) is given to
 * it as lsc_sized_give does. size must be at least the least (checked
 * before). */
static inline void lsc_sized_give_nth(void *out, size_t size, size_t i, const void *all,
                                      size_t n)
{
    char *e = (char *)out + i * size;
    memcpy(e, &size, sizeof size);
    lsc_sized_give(e, all, n);
}

/* Copies the input in (its caller's size) into all (n bytes, the library's
 * whole struct, zeroed first: the fields beyond the caller's size take their
 * default); all's size becomes n. in non-NULL, its size checked before. */
static inline void lsc_sized_take(void *all, const void *in, size_t n)
{
    size_t size = lsc_sized_size(in);
    memset(all, 0, n);
    memcpy(all, in, size < n ? size : n);
    memcpy(all, &n, sizeof n);
}

#endif
