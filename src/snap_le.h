/* snap_le.h: the snapshot format's little-endian encoding (snapshot.h), plain copies where
 * the machine is little-endian; shared by the format's writer, reader and hash. */
#ifndef RG_SNAP_LE_H
#define RG_SNAP_LE_H

#include <stdint.h>
#include <string.h>

#include "rigid.h"

/* Whether the machine stores integers and reals in the file's order, so that arrays copy
 * as they are. */
#if defined(__BYTE_ORDER__) && defined(__ORDER_LITTLE_ENDIAN__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define SNAP_NATIVE 1
#else
#define SNAP_NATIVE 0
#endif

static inline void snap_put32(uint8_t *p, uint32_t v)
{
#if SNAP_NATIVE
    memcpy(p, &v, 4);
#else
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
#endif
}

static inline void snap_put64(uint8_t *p, uint64_t v)
{
    snap_put32(p, (uint32_t)v);
    snap_put32(p + 4, (uint32_t)(v >> 32));
}

static inline uint32_t snap_get32(const uint8_t *p)
{
#if SNAP_NATIVE
    uint32_t v;
    memcpy(&v, p, 4);
    return v;
#else
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
#endif
}

static inline uint64_t snap_get64(const uint8_t *p)
{
    return (uint64_t)snap_get32(p) | (uint64_t)snap_get32(p + 4) << 32;
}

static inline void snap_put_real(uint8_t *p, rg_real v)
{
#ifdef RG_DOUBLE
    uint64_t u;
    memcpy(&u, &v, 8);
    snap_put64(p, u);
#else
    uint32_t u;
    memcpy(&u, &v, 4);
    snap_put32(p, u);
#endif
}

static inline rg_real snap_get_real(const uint8_t *p)
{
    rg_real v;
#ifdef RG_DOUBLE
    uint64_t u = snap_get64(p);
#else
    uint32_t u = snap_get32(p);
#endif
    memcpy(&v, &u, sizeof v);
    return v;
}

#endif
