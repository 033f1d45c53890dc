/* contact_api.c: the public calls on pairs: a body's contacts, passing through, and the
 * pre-solve hook. */
#include <string.h>

#include "arg.h"
#include "body.h"
#include "collision.h"
#include "contact.h"
#include "island.h"
#include "pairs.h"
#include "state.h"
#include "vec2.h"

RG_API rg_status rg_world_set_pre_solve(rg_world *world, rg_pre_solve_fn *fn, void *user)
{
    WORLD_WRITABLE(world);
    /* no state changes (nothing wakes): a world restored from a snapshot, then given its
     * hook, steps as the saving world did */
    world->pre_solve = fn;
    world->pre_solve_user = fn != NULL ? user : NULL;
    return RG_OK;
}

RG_API rg_status rg_body_pass_through(rg_world *world, rg_body body, rg_body other)
{
    BODY_SET(world, body, i);
    BODY_LOOKUP(world, other, j);
    body_store *b = &world->b;
    if (i == j) return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "other is body (a pair is two bodies)");
    if (b->shape[i] == RG_SHAPE_NONE) return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "body has no shape");
    if (b->shape[j] == RG_SHAPE_NONE) return RG_FAIL(world, RG_ERR_INVALID_ARGUMENT, "other has no shape");
    int32_t s = b->slot[i], t = b->slot[j];
    int32_t id = contact_find(world, s, t);
    if (id < 0) {
        /* no contact: the fat boxes do not overlap (then the shapes are apart), or the pair
         * search has not met them yet (a body just placed) */
        coll_manifold m;
        contact_manifold_now(world, i, j, &m);
        if (!(m.depth >= -world->coll.slop) || !pairs_admitted(world, i, j)) return RG_OK;
        id = contact_create(world, s, t);
        if (id < 0) return error_alloc(world, __func__, RG_ERR_OUT_OF_MEMORY, "contact storage", "INT32_MAX / 8");
    }
    world->coll.contacts.c[id].flags |= CT_PASS;
    island_touch(world, s);
    island_touch(world, t);
    return RG_OK;
}

/* Inserts c into out[0..n) kept sorted by other handle, at most cap entries; returns the new n. */
static int32_t contact_api_insert(rg_contact *out, int32_t n, int32_t cap, const rg_contact *c)
{
    int32_t k = n < cap ? n : cap - 1;
    if (n >= cap && !(c->other < out[cap - 1].other)) return n;
    while (k > 0 && out[k - 1].other > c->other) {
        out[k] = out[k - 1];
        k--;
    }
    out[k] = *c;
    return n < cap ? n + 1 : n;
}

RG_API int32_t rg_body_get_contacts(const rg_world *world, rg_body body, rg_contact *out,
                                    int32_t capacity)
{
    BODY_GET(world, body, i);
    ARG_BUFFER(world, out, capacity);
    const contact_store *cs = &world->coll.contacts;
    const body_store *b = &world->b;
    int32_t s = b->slot[i], count = 0, held = 0;
    for (int32_t id = b->chead[i] - 1; id >= 0; id = contact_next(&cs->c[id], s)) {
        const contact *c = &cs->c[id];
        if (!(c->flags & CT_TOUCHING)) continue;
        count++;
        if (capacity == 0) continue;
        int32_t t = contact_other(c, s), j = body_dense(world, t);
        coll_manifold m;
        contact_manifold_now(world, i, j, &m);
        rg_contact r;
        memset(&r, 0, sizeof r); /* its padding too (the double build's last 4 bytes): no stack
                                  * bytes reach the caller's memory, and equal contacts are
                                  * equal bytes */
        r.other = pool_handle(&world->body_pool, t);
        r.normal = m.normal;
        r.point = m.point;
        r.separation = -m.depth;
        /* the solver's pt runs along (-ny, nx) of the normal a -> b, on b; on either body it
         * is -pt along the tangent of the normal from that body toward the other */
        r.normal_impulse = (c->flags & CT_SENSOR) ? 0 : c->pn;
        r.tangent_impulse = (c->flags & CT_SENSOR) ? 0 : -c->pt;
        r.sensor = (c->flags & CT_SENSOR) != 0;
        held = contact_api_insert(out, held, capacity, &r);
    }
    return count;
}
