/* keyed.h: a keyed hash of bytes, for a world to know its own snapshots again (own.c)
 * without trusting what it cannot see: two independent 61-bit tags, each NH over chunks of
 * KEYED_CHUNK bytes (the sum over the chunk's 64-bit words w of (lo(w) + k) (hi(w) + k')
 * modulo 2^64, lo and hi its 32-bit halves, the additions modulo 2^32; Black et al., UMAC,
 * 1999) and a polynomial over the chunks' sums modulo the prime 2^61 - 1, at a point of the
 * key (Horner's rule; each sum enters as its two 32-bit halves, the length at the end).
 *
 * Two byte strings of one length that differ collide in one tag with probability at most
 * 2^-32 + n / (2^61 - 1), n the polynomial's length (NH is 2^-32-almost-universal on strings
 * of equal length; two distinct polynomials of degree n agree at no more than n points), so
 * in both with at most (2^-32 + n 2^-61)^2, about 2^-64 for any snapshot under a gigabyte:
 * for a key drawn at random and never shown, whoever wrote the bytes.  It is no MAC in the
 * cryptographic sense (the key comes from the clock and an address, not from a system's
 * source of randomness, and nothing hides its timing); what it gives is that neither
 * damage nor a party that never sees the key can make two snapshots look alike.
 *
 * Words are read in the machine's own order: tags are compared only within the process that
 * made them.  The vector paths (AVX2, AVX-512) add the same products modulo 2^64 in another
 * order, so every path gives the same tags. */
#ifndef RG_KEYED_H
#define RG_KEYED_H

#include <stddef.h>
#include <stdint.h>

#define KEYED_WORDS 512                   /* 64-bit words per chunk */
#define KEYED_CHUNK (8 * KEYED_WORDS)     /* 4 KB */
#define KEYED_P ((1ull << 61) - 1)

typedef struct keyed_key {
    uint32_t nh[2][2 * KEYED_WORDS]; /* per tag, a 32-bit key per half word of a chunk */
    uint64_t r[2];                   /* per tag, the polynomial's point, in [2, 2^61 - 1) */
} keyed_key;

typedef struct keyed_hasher {
    const keyed_key *key;
    uint64_t nh[2];   /* the chunk's sums so far */
    uint64_t poly[2];
    uint64_t length;  /* bytes taken */
    uint32_t word;    /* whole words of the chunk taken */
    uint32_t npending;
    uint8_t pending[8]; /* a word's first bytes */
} keyed_hasher;

/* The key from 64 bits of seed, stretched (splitmix64). */
void keyed_key_init(keyed_key *k, uint64_t seed);
void keyed_init(keyed_hasher *h, const keyed_key *k);
/* Bytes in any pieces: the tags depend on the bytes alone. */
void keyed_bytes(keyed_hasher *h, const void *p, size_t n);
void keyed_final(keyed_hasher *h, uint64_t tag[2]);
/* a b modulo 2^61 - 1, for a, b < 2^61 (portable: four 32-bit products). */
uint64_t keyed_mulmod(uint64_t a, uint64_t b);

/* The NH sums of `words` words at p added to nh[0], nh[1], the keys k0, k1 from the words'
 * places in their chunk: the paths keyed_bytes picks from per call, named for the tests. */
void keyed_nh_scalar(uint64_t nh[2], const uint8_t *p, size_t words, const uint32_t *k0, const uint32_t *k1);
#if defined(__GNUC__) && defined(__x86_64__) && !defined(RG_NO_DISPATCH)
#define KEYED_VECTOR 1
void keyed_nh_avx2(uint64_t nh[2], const uint8_t *p, size_t words, const uint32_t *k0, const uint32_t *k1);
void keyed_nh_avx512(uint64_t nh[2], const uint8_t *p, size_t words, const uint32_t *k0, const uint32_t *k1);
#else
#define KEYED_VECTOR 0
#endif

#endif
