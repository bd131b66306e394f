/* A growable byte buffer for tests that write binary files themselves (glTF buffers, GLB
 * containers). Header-only; include once per test. */
#ifndef SL_TEST_BYTE_BUFFER_H
#define SL_TEST_BYTE_BUFFER_H
#include <stdlib.h>
#include <string.h>

typedef struct buf { unsigned char *d; size_t n, cap; } buf;

static inline void put(buf *b, const void *p, size_t n) {
    if (b->n + n > b->cap) {
        b->cap = (b->n + n) * 2 + 64;
        b->d = realloc(b->d, b->cap);
    }
    memcpy(b->d + b->n, p, n);
    b->n += n;
}
#endif
