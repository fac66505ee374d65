/* ss_hash.c — linear-probing hash map with fixed-width word keys. */
#include "ss_hash.h"

#include <stdlib.h>
#include <string.h>

struct ss_hash {
  int width;      /* words per key, 1..4 */
  size_t cap;     /* slots, a power of two */
  size_t n;       /* occupied slots */
  uint32_t *keys; /* cap*width words */
  uint32_t *vals; /* cap values; UINT32_MAX marks an empty slot */
};

/* 64-bit mix (splitmix64 finaliser) over the key words. */
static uint64_t hash_key(const uint32_t *key, int width) {
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (int i = 0; i < width; i++) {
    h ^= key[i];
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 31;
  }
  h *= 0x94d049bb133111ebull;
  h ^= h >> 29;
  return h;
}

static ss_status alloc_slots(ss_hash *h, size_t cap, ss_error *err) {
  h->keys = malloc(cap * (size_t)h->width * sizeof *h->keys);
  h->vals = malloc(cap * sizeof *h->vals);
  if (!h->keys || !h->vals) {
    free(h->keys);
    free(h->vals);
    h->keys = h->vals = NULL;
    return ss_error_nomem(err, "hash table");
  }
  memset(h->vals, 0xff, cap * sizeof *h->vals);
  h->cap = cap;
  return SS_OK;
}

ss_status ss_hash_new(int width, size_t expect, ss_hash **out, ss_error *err) {
  *out = NULL;
  if (width < 1 || width > 4)
    return ss_error_set(err, SS_EINPUT, "hash key width %d is not in 1..4", width);
  ss_hash *h = calloc(1, sizeof *h);
  if (!h) return ss_error_nomem(err, "hash table");
  h->width = width;
  size_t cap = 16;
  while (cap < 2 * expect)
    cap *= 2;
  ss_status st = alloc_slots(h, cap, err);
  if (st) {
    free(h);
    return st;
  }
  *out = h;
  return SS_OK;
}

void ss_hash_free(ss_hash *h) {
  if (!h) return;
  free(h->keys);
  free(h->vals);
  free(h);
}

size_t ss_hash_size(const ss_hash *h) {
  return h->n;
}

/* Whether the width words at a and b agree (a loop: memcmp of a variable
 * length is a call, and keys are at most four words). */
static int same_key(const uint32_t *a, const uint32_t *b, int width) {
  for (int w = 0; w < width; w++)
    if (a[w] != b[w]) return 0;
  return 1;
}

/* Slot holding key, or the empty slot where it would go. */
static size_t probe(const ss_hash *h, const uint32_t *key) {
  size_t mask = h->cap - 1, i = (size_t)hash_key(key, h->width) & mask;
  while (h->vals[i] != UINT32_MAX &&
         !same_key(h->keys + i * (size_t)h->width, key, h->width))
    i = (i + 1) & mask;
  return i;
}

static ss_status grow(ss_hash *h, ss_error *err) {
  ss_hash old = *h;
  ss_status st = alloc_slots(h, 2 * old.cap, err);
  if (st) {
    *h = old;
    return st;
  }
  for (size_t i = 0; i < old.cap; i++) {
    if (old.vals[i] == UINT32_MAX) continue;
    const uint32_t *k = old.keys + i * (size_t)old.width;
    size_t j = probe(h, k);
    memcpy(h->keys + j * (size_t)h->width, k, (size_t)h->width * sizeof *k);
    h->vals[j] = old.vals[i];
  }
  free(old.keys);
  free(old.vals);
  return SS_OK;
}

ss_status ss_hash_insert(ss_hash *h, const uint32_t *key, uint32_t value, uint32_t *found,
                         int *inserted, ss_error *err) {
  size_t i = probe(h, key);
  if (h->vals[i] != UINT32_MAX) {
    *found = h->vals[i];
    *inserted = 0;
    return SS_OK;
  }
  if (2 * (h->n + 1) > h->cap) {
    ss_status st = grow(h, err);
    if (st) return st;
    i = probe(h, key);
  }
  memcpy(h->keys + i * (size_t)h->width, key, (size_t)h->width * sizeof *key);
  h->vals[i] = value;
  h->n++;
  *found = value;
  *inserted = 1;
  return SS_OK;
}

uint32_t ss_hash_find(const ss_hash *h, const uint32_t *key) {
  return h->vals[probe(h, key)];
}
