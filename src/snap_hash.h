/* snap_hash.h: the snapshot format's hash function (snapshot.h): the checksum of a
 * snapshot's bytes and the hash of rg_world_hash's stream. */
#ifndef RG_SNAP_HASH_H
#define RG_SNAP_HASH_H

#include <stddef.h>
#include <stdint.h>

/* The hash: 64-bit words in 32 lanes (word k of each 256-byte block into lane k), each a
 * multiply-xorshift chain (a bijection of the lane for every word, so any change of any byte
 * changes the result); tail bytes zero-padded and the length mixed in at the end.  Streamed:
 * bytes may come in any chunks.  Thirty-two lanes, not eight, so that the multiplies of a
 * block need not wait on the block before (format version 2). */
#define SNAP_LANES 32
typedef struct snap_hasher {
    uint64_t lane[SNAP_LANES];
    uint8_t pending[8 * SNAP_LANES];
    size_t npending;
    uint64_t length;
} snap_hasher;

void snap_hash_init(snap_hasher *h);
void snap_hash_bytes(snap_hasher *h, const void *p, size_t n);
uint64_t snap_hash_final(snap_hasher *h);
uint64_t snap_hash(const void *p, size_t n);

#endif
