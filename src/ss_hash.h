/* ss_hash.h — open-addressing hash map from short keys of 32-bit words to 32-bit
 * values.  Used to give every edge, face or other shared entity of a complex one
 * index (the MLCA paper's "hash table indexed by the smallest cube containing
 * each vertex").  Keys have a fixed width of 1..4 words set at creation; the
 * table grows as needed (load factor <= 1/2). */
#ifndef SS_HASH_H
#define SS_HASH_H

#include <stddef.h>
#include <stdint.h>

#include "ss_error.h"

typedef struct ss_hash ss_hash; /* opaque */

/* New table for keys of `width` words (1..4) expecting about `expect` entries.
 * SS_ENOMEM; SS_EINPUT for a bad width. */
ss_status ss_hash_new(int width, size_t expect, ss_hash **out, ss_error *err);
/* Free; NULL is a no-op. */
void ss_hash_free(ss_hash *h);
/* Number of entries. */
size_t ss_hash_size(const ss_hash *h);

/* Look key up; if absent insert it with value `value`.  *found receives the
 * stored value (the old one if present) and *inserted 1 if it was inserted.
 * SS_ENOMEM when growing fails (the table is then unchanged). */
ss_status ss_hash_insert(ss_hash *h, const uint32_t *key, uint32_t value, uint32_t *found,
                         int *inserted, ss_error *err);
/* Value stored under key, or UINT32_MAX if absent. */
uint32_t ss_hash_find(const ss_hash *h, const uint32_t *key);

#endif
