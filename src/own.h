/* own.h: a world's own snapshots known again.  rg_world_save remembers each snapshot it
 * writes (its size, its checksum and its two keyed tags, keyed.h, under a key the world
 * draws at its creation and never writes out), the last OWN_SAVES of them; rg_world_restore
 * given bytes equal to one of them (the tags compared, with a chance of about 2^-64 that
 * other bytes pass) loads them without the checks a snapshot from outside needs, as it loads
 * a kept state (restore.c): a state this world has been in breaks no invariant.  Any other
 * bytes (another world's snapshot, a file, one changed in any byte) are checked whole.
 *
 * The tags cost a save of 10,000 bodies some 25-70 us more (README: make bench's snapshot
 * lines), so only a world that restores pays: its saves are tagged from a restore on, for
 * the next OWN_SAVES saves (a rollback loop, restoring again and again, keeps them tagged);
 * a world that only saves (for a replay, a save game, the network) saves as before, and the
 * first restore of a rollback is checked. */
#ifndef RG_OWN_H
#define RG_OWN_H

#include "keyed.h"

#define OWN_SAVES 64
#define OWN_HEAD 24 /* the header's bytes before its checksum, 8 bytes (snapshot.h) */

typedef struct own_saves {
    keyed_key key;
    struct {
        uint64_t size, sum; /* 0, 0: none yet */
        uint64_t tag[2];
    } save[OWN_SAVES];
    uint32_t next;  /* the entry the next save replaces */
    uint32_t armed; /* saves still to be tagged */
} own_saves;

void own_init(own_saves *o, uint64_t seed);
/* After a restore: the next OWN_SAVES saves are tagged. */
static inline void own_arm(own_saves *o) { o->armed = OWN_SAVES; }
/* Whether the next save is tagged (then own_remember follows it). */
static inline int own_tagging(const own_saves *o) { return o->armed > 0; }
/* The tags cover a snapshot's header but its checksum (compared itself), then what the
 * checksum covers: the header first, into a hasher just made. */
void own_header(keyed_hasher *h, const uint8_t *header);
/* A save of size bytes with checksum sum, whose bytes but the checksum h has taken. */
void own_remember(own_saves *o, keyed_hasher *h, uint64_t size, uint64_t sum);
/* Whether the size bytes at data (a header of OWN_HEAD bytes, the checksum, whose value is
 * sum, then what it covers) are one of the remembered saves, byte for byte. */
int own_knows(const own_saves *o, const uint8_t *data, size_t size, uint64_t sum);

#endif
