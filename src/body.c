/* body.c: structure-of-arrays body storage, partitions, and the body API. */
#include <string.h>

#include "vec2.h"
#include "world.h"

#define ALIGN_UP(n) (((n) + 63u) & ~(size_t)63u)

int32_t body_lookup(const rg_world *w, rg_body body)
{
    return pool_lookup(&w->body_pool, body);
}

/* Bytes one body takes across all fields (each array padded to a cache line). */
static size_t body_block_size(int32_t cap)
{
    size_t size = 0;
#define RG_FIELD_SIZE(T, name) size += ALIGN_UP((size_t)cap * sizeof(T));
    RG_BODY_FIELDS(RG_FIELD_SIZE)
#undef RG_FIELD_SIZE
    return size;
}

rg_status body_reserve(rg_world *w)
{
    body_store *b = &w->b;
    rg_status st = pool_reserve(&w->body_pool, &w->mem);
    if (st != RG_OK) return st;
    if (b->count < b->capacity) return RG_OK;
    int32_t cap = b->capacity < 64 ? 64 : b->capacity * 2;
    if (cap > RG_MAX_BODIES) cap = RG_MAX_BODIES;
    size_t size = body_block_size(cap);
    char *block = mem_alloc(&w->mem, size);
    if (block == NULL) return RG_ERR_OUT_OF_MEMORY;
    char *p = block;
#define RG_FIELD_MOVE(T, name)                                                   \
    if (b->count > 0) memcpy(p, b->name, (size_t)b->count * sizeof(T));          \
    b->name = (T *)(void *)p;                                                    \
    p += ALIGN_UP((size_t)cap * sizeof(T));
    RG_BODY_FIELDS(RG_FIELD_MOVE)
#undef RG_FIELD_MOVE
    mem_free(&w->mem, b->block, b->block_size);
    b->block = block;
    b->block_size = size;
    b->capacity = cap;
    return RG_OK;
}

rg_status body_scratch_reserve(rg_world *w)
{
    scratch_store *s = &w->scratch;
    int32_t cap = w->b.capacity;
    if (s->capacity >= cap) return RG_OK;
    size_t size = 0;
#define RG_FIELD_SIZE(T, name) size += ALIGN_UP((size_t)cap * sizeof(T));
    RG_SCRATCH_FIELDS(RG_FIELD_SIZE)
#undef RG_FIELD_SIZE
    char *block = mem_alloc(&w->mem, size);
    if (block == NULL) return RG_ERR_OUT_OF_MEMORY;
    mem_free(&w->mem, s->block, s->block_size);
    char *p = block;
#define RG_FIELD_SET(T, name) s->name = (T *)(void *)p; p += ALIGN_UP((size_t)cap * sizeof(T));
    RG_SCRATCH_FIELDS(RG_FIELD_SET)
#undef RG_FIELD_SET
    s->block = block;
    s->block_size = size;
    s->capacity = cap;
    return RG_OK;
}

void body_store_release(rg_world *w)
{
    mem_free(&w->mem, w->b.block, w->b.block_size);
    mem_free(&w->mem, w->scratch.block, w->scratch.block_size);
    memset(&w->b, 0, sizeof w->b);
    memset(&w->scratch, 0, sizeof w->scratch);
    pool_release_memory(&w->body_pool, &w->mem);
}

int body_partition(const rg_world *w, int32_t i)
{
    if (i < w->b.n_active) return BODY_PART_ACTIVE;
    if (i < w->b.n_moving) return BODY_PART_ASLEEP;
    return BODY_PART_STATIC;
}

/* Swaps dense places i and j, fields and slot map. */
static void body_swap(rg_world *w, int32_t i, int32_t j)
{
    body_store *b = &w->b;
    if (i == j) return;
#define RG_FIELD_SWAP(T, name) { T t = b->name[i]; b->name[i] = b->name[j]; b->name[j] = t; }
    RG_BODY_FIELDS(RG_FIELD_SWAP)
#undef RG_FIELD_SWAP
    pool_set_dense(&w->body_pool, b->slot[i], i);
    pool_set_dense(&w->body_pool, b->slot[j], j);
}

/* Partitions are contiguous: moving a body one partition boundary is one swap with the
 * boundary element and a shift of the boundary. */
int32_t body_move_to_partition(rg_world *w, int32_t i, int part)
{
    body_store *b = &w->b;
    int cur = body_partition(w, i);
    while (cur < part) { /* move right: swap with the last of its partition */
        int32_t *end = cur == BODY_PART_ACTIVE ? &b->n_active : &b->n_moving;
        int32_t last = *end - 1;
        body_swap(w, i, last);
        i = last;
        (*end)--;
        cur++;
    }
    while (cur > part) { /* move left: swap with the first of its partition */
        int32_t *begin = cur == BODY_PART_STATIC ? &b->n_moving : &b->n_active;
        int32_t first = *begin;
        body_swap(w, i, first);
        i = first;
        (*begin)++;
        cur--;
    }
    return i;
}

void body_update_flags(rg_world *w, int32_t i)
{
    body_store *b = &w->b;
    uint32_t old = b->flags[i];
    uint32_t f = old & ~(BODY_F_DISSIPATIVE | BODY_F_LIMITED);
    if (b->type[i] == RG_BODY_DYNAMIC) {
        if (b->drag_lin[i] > 0 || b->drag_quad[i] > 0 || b->fric[i] > 0) f |= BODY_F_DISSIPATIVE;
        if (b->min_speed[i] > 0 || b->max_speed[i] > 0) f |= BODY_F_LIMITED;
    }
    w->dissipative_count += (int32_t)((f & BODY_F_DISSIPATIVE) != 0) - (int32_t)((old & BODY_F_DISSIPATIVE) != 0);
    w->limit_count += (int32_t)((f & BODY_F_LIMITED) != 0) - (int32_t)((old & BODY_F_LIMITED) != 0);
    b->flags[i] = f;
}

/* ---------------------------------------------------------------- API */

RG_API rg_status rg_body_create(rg_world *world, int32_t type, rg_real mass, rg_vec2 position,
                                rg_body *out_body)
{
    if (world == NULL || out_body == NULL || !rg_vec2_finite(position) || !rg_finite(mass))
        return RG_ERR_INVALID_ARGUMENT;
    if (type != RG_BODY_STATIC && type != RG_BODY_KINEMATIC && type != RG_BODY_DYNAMIC)
        return RG_ERR_INVALID_ARGUMENT;
    if (type == RG_BODY_DYNAMIC && !(mass > 0)) return RG_ERR_INVALID_ARGUMENT;
    rg_status st = body_reserve(world);
    if (st != RG_OK) return st;
    body_store *b = &world->b;
    int32_t i = b->count++;
    uint64_t h = pool_alloc(&world->body_pool, i);
#define RG_FIELD_ZERO(T, name) b->name[i] = (T)0;
    RG_BODY_FIELDS(RG_FIELD_ZERO)
#undef RG_FIELD_ZERO
    b->x[i] = b->px[i] = position.x;
    b->y[i] = b->py[i] = position.y;
    b->slot[i] = pool_slot(h);
    b->type[i] = type;
    contact_body_init(world, i);
    if (type == RG_BODY_DYNAMIC) {
        b->mass[i] = mass;
        b->inv_mass[i] = 1 / mass;
        b->gscale[i] = 1;
    }
    /* The new body sits in the static partition (the last place); move it where it goes. */
    if (type != RG_BODY_STATIC) body_move_to_partition(world, i, BODY_PART_ACTIVE);
    *out_body = h;
    return RG_OK;
}

RG_API rg_status rg_body_destroy(rg_world *world, rg_body body)
{
    if (world == NULL) return RG_ERR_INVALID_ARGUMENT;
    int32_t i = body_lookup(world, body);
    if (i < 0) return RG_ERR_STALE_HANDLE;
    body_store *b = &world->b;
    i = contact_body_destroy(world, i); /* ends its contacts, wakes what rested on it */
    force_detach_body(world, b->slot[i]);
    /* Clear its counted flags, move it to the end of the static partition, drop it. */
    b->type[i] = RG_BODY_STATIC;
    body_update_flags(world, i);
    i = body_move_to_partition(world, i, BODY_PART_STATIC);
    body_swap(world, i, b->count - 1);
    b->count--;
    pool_free(&world->body_pool, body);
    return RG_OK;
}

RG_API int32_t rg_body_is_valid(const rg_world *world, rg_body body)
{
    return world != NULL && body_lookup(world, body) >= 0;
}

/* Looks up `body` for a call; returns the dense index or a negative status. */
#define BODY_GET(world, body, i)                               \
    if ((world) == NULL) return RG_ERR_INVALID_ARGUMENT;       \
    int32_t i = body_lookup((world), (body));                  \
    if (i < 0) return RG_ERR_STALE_HANDLE

RG_API rg_status rg_body_get_type(const rg_world *world, rg_body body, int32_t *out_type)
{
    BODY_GET(world, body, i);
    if (out_type == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_type = world->b.type[i];
    return RG_OK;
}

RG_API rg_status rg_body_get_mass(const rg_world *world, rg_body body, rg_real *out_mass)
{
    BODY_GET(world, body, i);
    if (out_mass == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out_mass = world->b.mass[i];
    return RG_OK;
}

RG_API rg_status rg_body_set_mass(rg_world *world, rg_body body, rg_real mass)
{
    BODY_GET(world, body, i);
    if (!rg_finite(mass) || !(mass > 0) || world->b.type[i] != RG_BODY_DYNAMIC)
        return RG_ERR_INVALID_ARGUMENT;
    world->b.mass[i] = mass;
    world->b.inv_mass[i] = 1 / mass;
    return RG_OK;
}

static rg_status get_pair(const rg_world *world, rg_body body, const rg_real *xs,
                          const rg_real *ys, rg_vec2 *out)
{
    BODY_GET(world, body, i);
    if (out == NULL) return RG_ERR_INVALID_ARGUMENT;
    out->x = xs[i];
    out->y = ys[i];
    return RG_OK;
}

RG_API rg_status rg_body_get_position(const rg_world *world, rg_body body, rg_vec2 *out)
{
    if (world == NULL) return RG_ERR_INVALID_ARGUMENT;
    return get_pair(world, body, world->b.x, world->b.y, out);
}

RG_API rg_status rg_body_get_velocity(const rg_world *world, rg_body body, rg_vec2 *out)
{
    if (world == NULL) return RG_ERR_INVALID_ARGUMENT;
    return get_pair(world, body, world->b.vx, world->b.vy, out);
}

RG_API rg_status rg_body_get_acceleration(const rg_world *world, rg_body body, rg_vec2 *out)
{
    if (world == NULL) return RG_ERR_INVALID_ARGUMENT;
    return get_pair(world, body, world->b.ax, world->b.ay, out);
}

RG_API rg_status rg_body_get_interpolated_position(const rg_world *world, rg_body body,
                                                   rg_vec2 *out)
{
    BODY_GET(world, body, i);
    if (out == NULL) return RG_ERR_INVALID_ARGUMENT;
    const body_store *b = &world->b;
    if (!world->prev_valid) {
        out->x = b->x[i];
        out->y = b->y[i];
        return RG_OK;
    }
    rg_real alpha = (rg_real)(world->accumulator / world->fixed_dt);
    out->x = b->px[i] + alpha * (b->x[i] - b->px[i]);
    out->y = b->py[i] + alpha * (b->y[i] - b->py[i]);
    return RG_OK;
}

RG_API rg_status rg_body_set_position(rg_world *world, rg_body body, rg_vec2 position)
{
    BODY_GET(world, body, i);
    if (!rg_vec2_finite(position)) return RG_ERR_INVALID_ARGUMENT;
    body_store *b = &world->b;
    i = contact_body_wake(world, i);
    b->x[i] = b->px[i] = position.x; /* a teleport is not interpolated */
    b->y[i] = b->py[i] = position.y;
    contact_body_moved(world, i);
    return RG_OK;
}

RG_API rg_status rg_body_set_velocity(rg_world *world, rg_body body, rg_vec2 velocity)
{
    BODY_GET(world, body, i);
    if (!rg_vec2_finite(velocity)) return RG_ERR_INVALID_ARGUMENT;
    body_store *b = &world->b;
    if (b->type[i] == RG_BODY_STATIC && (velocity.x != 0 || velocity.y != 0))
        return RG_ERR_INVALID_ARGUMENT;
    i = contact_body_wake(world, i);
    b->vx[i] = velocity.x;
    b->vy[i] = velocity.y;
    return RG_OK;
}

RG_API rg_status rg_body_apply_force(rg_world *world, rg_body body, rg_vec2 force)
{
    BODY_GET(world, body, i);
    if (!rg_vec2_finite(force)) return RG_ERR_INVALID_ARGUMENT;
    body_store *b = &world->b;
    if (b->type[i] != RG_BODY_DYNAMIC) return RG_OK;
    rg_real fx = b->fx[i] + force.x, fy = b->fy[i] + force.y;
    if (!rg_finite(fx) || !rg_finite(fy)) return RG_ERR_INVALID_ARGUMENT; /* sum overflowed */
    i = contact_body_wake(world, i);
    b->fx[i] = fx;
    b->fy[i] = fy;
    return RG_OK;
}

RG_API rg_status rg_body_apply_impulse(rg_world *world, rg_body body, rg_vec2 impulse)
{
    BODY_GET(world, body, i);
    if (!rg_vec2_finite(impulse)) return RG_ERR_INVALID_ARGUMENT;
    body_store *b = &world->b;
    if (b->type[i] != RG_BODY_DYNAMIC) return RG_OK;
    rg_real vx = b->vx[i] + impulse.x * b->inv_mass[i];
    rg_real vy = b->vy[i] + impulse.y * b->inv_mass[i];
    if (!rg_finite(vx) || !rg_finite(vy)) return RG_ERR_INVALID_ARGUMENT;
    i = contact_body_wake(world, i);
    b->vx[i] = vx;
    b->vy[i] = vy;
    return RG_OK;
}

RG_API rg_status rg_body_set_gravity_scale(rg_world *world, rg_body body, rg_real scale)
{
    BODY_GET(world, body, i);
    if (!rg_finite(scale)) return RG_ERR_INVALID_ARGUMENT;
    if (world->b.type[i] == RG_BODY_DYNAMIC) world->b.gscale[i] = scale;
    return RG_OK;
}

RG_API rg_status rg_body_set_drag(rg_world *world, rg_body body, rg_real linear, rg_real quadratic)
{
    BODY_GET(world, body, i);
    if (!rg_finite(linear) || !rg_finite(quadratic) || linear < 0 || quadratic < 0)
        return RG_ERR_INVALID_ARGUMENT;
    world->b.drag_lin[i] = linear;
    world->b.drag_quad[i] = quadratic;
    body_update_flags(world, i);
    return RG_OK;
}

RG_API rg_status rg_body_set_surface_friction(rg_world *world, rg_body body, rg_real mu,
                                              rg_real normal_force)
{
    BODY_GET(world, body, i);
    if (!rg_finite(mu) || !rg_finite(normal_force) || mu < 0 || normal_force < 0)
        return RG_ERR_INVALID_ARGUMENT;
    rg_real f = mu * normal_force;
    if (!rg_finite(f)) return RG_ERR_INVALID_ARGUMENT;
    world->b.fric[i] = f;
    body_update_flags(world, i);
    return RG_OK;
}

RG_API rg_status rg_body_set_speed_limits(rg_world *world, rg_body body, rg_real min_speed,
                                          rg_real max_speed)
{
    BODY_GET(world, body, i);
    if (!rg_finite(min_speed) || !rg_finite(max_speed) || min_speed < 0 || max_speed < 0 ||
        (max_speed > 0 && max_speed < min_speed))
        return RG_ERR_INVALID_ARGUMENT;
    world->b.min_speed[i] = min_speed;
    world->b.max_speed[i] = max_speed;
    body_update_flags(world, i);
    return RG_OK;
}

RG_API rg_status rg_body_set_user_data(rg_world *world, rg_body body, uint64_t user_data)
{
    BODY_GET(world, body, i);
    world->b.user[i] = user_data;
    return RG_OK;
}

RG_API rg_status rg_body_get_user_data(const rg_world *world, rg_body body, uint64_t *out)
{
    BODY_GET(world, body, i);
    if (out == NULL) return RG_ERR_INVALID_ARGUMENT;
    *out = world->b.user[i];
    return RG_OK;
}
