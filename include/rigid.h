/* rigid.h: the one public header of rigid, a C99 library for 2D game physics.
 *
 * The contract (programs outside this repository are written against it):
 *
 * - Fixed: every name, parameter order, type and value declared here that the project's
 *   ABI lists (the world, stepping, body, force, spring, collision, event and query calls
 *   of version 0.1, and the gameplay, snapshot, error, debug-draw and thread calls as they
 *   land).  New calls are added in the same style; none is renamed or reordered.
 * - Names: every exported symbol is rg_*, every macro and constant RG_*.  The shared library
 *   exports nothing else.  This header includes only <stddef.h> and <stdint.h>.
 * - Units are SI throughout: metres, seconds, kilograms, newtons.
 * - rg_real is float, or double in the double build (which defines RG_DOUBLE and names its
 *   library librigid-double); rg_real_size() tells an FFI host which one it loaded.
 * - Structs: rg_vec2 is the only struct passed by value, and only as an input; outputs go
 *   through pointers.  Booleans and enums cross as int32_t.
 * - Handles: rg_world is opaque.  A body (rg_body) or spring is a 64-bit handle packing a
 *   slot, a generation and a tag of its world; 0 is never one.  A destroyed body's handle
 *   never becomes valid again in that world, and a handle from another world or a forged
 *   one is rejected (RG_ERR_STALE_HANDLE).
 * - Errors: every function validates its input in every build and returns a status
 *   (rg_status, below; functions returning a count return it >= 0 or a negative status),
 *   and rg_world_last_error(world) tells why the last call on that world failed.  A call
 *   that returns an error changes nothing.  No input, however bad, crashes the library or
 *   puts a NaN into the world.
 * - Ranges: every real input has an accepted range, stated with the calls as RG_MIN_* and
 *   RG_MAX_* constants (SI units; the same in the float and double builds, compared after
 *   rounding to rg_real).  A value outside it, NaN or infinite is RG_ERR_INVALID_ARGUMENT.
 * - No global state: two worlds share nothing, and a world may move to another thread
 *   between calls.  The same calls give bit-identical results on any compiler, optimisation
 *   level and SIMD path, and on x86-64, aarch64, 32-bit x86 and s390x (big-endian) alike:
 *   the library refuses to build where float arithmetic keeps excess precision (the x87).
 */
#ifndef RIGID_H
#define RIGID_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RG_VERSION_MAJOR 0
#define RG_VERSION_MINOR 1
#define RG_VERSION_PATCH 0
#define RG_VERSION (RG_VERSION_MAJOR * 10000 + RG_VERSION_MINOR * 100 + RG_VERSION_PATCH)

#if defined(_WIN32) && defined(RG_BUILD_SHARED)
#define RG_API __declspec(dllexport)
#elif defined(__GNUC__) || defined(__clang__)
#define RG_API __attribute__((visibility("default")))
#else
#define RG_API
#endif

/* ---------------------------------------------------------------- basic types */

#ifdef RG_DOUBLE
typedef double rg_real;
#else
typedef float rg_real;
#endif

/* A 2D vector.  The only struct passed by value, and only as an input. */
typedef struct rg_vec2 {
    rg_real x, y;
} rg_vec2;

typedef struct rg_world rg_world;   /* opaque; created and destroyed by the library */

/* A body handle: slot index, generation and a world tag packed in 64 bits.  0 is never a
 * body; a destroyed body's handle never becomes valid again in that world. */
typedef uint64_t rg_body;

/* The integer constants are enumerators, so that FFI hosts which read the preprocessed
 * header (LuaJIT's ffi.cdef, cffi) see them too; the values are fixed. */
typedef int32_t rg_status;
enum {
    RG_OK                   =  0,
    RG_ERR_INVALID_ARGUMENT = -1,  /* NULL, NaN/inf, negative mass or size, dt <= 0, bad enum */
    RG_ERR_STALE_HANDLE     = -2,  /* destroyed, forged, zero or another world's handle */
    RG_ERR_OUT_OF_MEMORY    = -3,
    RG_ERR_CAPACITY         = -4,  /* more bodies or springs than a world can hold */
    RG_ERR_LOCKED           = -5   /* not allowed at this moment: a call that would change
                                      the world, made from one of its callbacks (the
                                      pre-solve hook, the task system or the allocator
                                      inside a step or restore, the allocator inside any
                                      call, a draw's callbacks) */
};

enum {
    RG_INTEGRATOR_EXPLICIT_EULER      = 0,
    RG_INTEGRATOR_SEMI_IMPLICIT_EULER = 1,   /* the default */
    RG_INTEGRATOR_VELOCITY_VERLET     = 2,
    RG_INTEGRATOR_RK4                 = 3
};

enum {
    RG_BODY_STATIC    = 0,   /* never moves; infinite mass */
    RG_BODY_KINEMATIC = 1,   /* moves by its velocity only; pushes, is never pushed */
    RG_BODY_DYNAMIC   = 2    /* moved by forces, impulses and contacts */
};

/* Most bodies and most springs one world holds (slot indices are 24 bits). */
enum { RG_MAX_BODIES = 16777215, RG_MAX_SPRINGS = 16777215 };

/* Human-readable text for a status; never NULL. */
RG_API const char *rg_status_string(rg_status s);
/* Why the last call on this world failed, naming the function, the argument and the rule:
 *   "rg_body_set_circle: radius 1e+08 is above RG_MAX_SHAPE_SIZE (1e+07)"
 *   "rg_body_set_velocity: body 0x1000001 is stale (destroyed, forged or of another world)"
 *   "rg_world_step: dt -1 is not > 0"      "rg_body_set_velocity: velocity.x is NaN"
 *   "rg_world_step: out of memory (integrator scratch)"
 *   "rg_world_set_gravity: locked: called from inside one of the world's callbacks"
 * and "" when that call succeeded.  Every call that takes a world sets or clears it,
 * getters, queries and counts too (a call that succeeds writes it only when it was set, so
 * successful calls only read it).  The text lives in the world, at most 199 bytes, until
 * the next call on it or its destruction; copy it to keep it.  Never NULL: for a NULL world
 * it is "rg_world_last_error: world is NULL".  A call given a NULL world returns
 * RG_ERR_INVALID_ARGUMENT and has no world to store a reason in, nor does a failed
 * rg_world_create*. */
RG_API const char *rg_world_last_error(const rg_world *world);
/* MAJOR*10000 + MINOR*100 + PATCH of the loaded library; equals RG_VERSION. */
RG_API int32_t rg_version(void);
/* sizeof(rg_real) of the loaded library: 4 (float build) or 8 (double build). */
RG_API int32_t rg_real_size(void);
/* 1 when the loaded library's rg_real is this program's (a float program linked against
 * the double library reads garbage); check it once at start. */
#define RG_REAL_MATCHES() (rg_real_size() == (int32_t)sizeof(rg_real))

/* ---------------------------------------------------------------- world */

/* Allocator in the style of lua_Alloc: new_size == 0 frees ptr and returns NULL; otherwise
 * it returns a block of new_size bytes holding the first min(old_size, new_size) bytes of
 * ptr (ptr is NULL and old_size 0 for a fresh block), or NULL when it cannot, in which case
 * ptr stays valid.  Blocks must be aligned for any type, as malloc's are.  While it runs,
 * the world it serves is locked: a call on that world that would change it returns
 * RG_ERR_LOCKED and rg_world_destroy does nothing (getters work, and see the call in
 * progress). */
typedef void *(*rg_alloc_fn)(void *user, void *ptr, size_t old_size, size_t new_size);

/* Creates an empty world: gravity (0, 0), no wind, semi-implicit Euler, fixed step 1/60 s
 * with at most 8 steps per advance.  Uses malloc/realloc/free. */
RG_API rg_status rg_world_create(rg_world **out_world);
/* The same with every allocation of this world going through alloc(user, ...). */
RG_API rg_status rg_world_create_with_allocator(rg_alloc_fn alloc, void *user,
                                                rg_world **out_world);
/* Frees the world and everything in it.  NULL is a no-op. */
RG_API void rg_world_destroy(rg_world *world);

/* Largest |component| of gravity, m/s^2. */
#define RG_MAX_ACCELERATION 1.0e6
/* Largest |component| of a force in N (wind, applied forces, surface friction's normal
 * force, an applied force summed over a step) and of an impulse in N*s. */
#define RG_MAX_FORCE 1.0e12

/* Gravity as an acceleration in m/s^2 (each component within +-RG_MAX_ACCELERATION),
 * applied to dynamic bodies times their gravity scale.  A change (of gravity or wind) wakes
 * every sleeping body: what rested under the old one may not under the new (gravity flipped
 * up, wind across a pile); setting the same value again wakes nothing. */
RG_API rg_status rg_world_set_gravity(rg_world *world, rg_vec2 gravity);
RG_API rg_status rg_world_get_gravity(const rg_world *world, rg_vec2 *out_gravity);
/* Wind as a force in N (each component within +-RG_MAX_FORCE): the same force on every
 * dynamic body (a light body feels more). */
RG_API rg_status rg_world_set_wind(rg_world *world, rg_vec2 force);
RG_API rg_status rg_world_get_wind(const rg_world *world, rg_vec2 *out_force);
/* One of RG_INTEGRATOR_*. */
RG_API rg_status rg_world_set_integrator(rg_world *world, int32_t integrator);
RG_API rg_status rg_world_get_integrator(const rg_world *world, int32_t *out_integrator);

/* Longest step, s (rg_world_step, rg_world_set_fixed_step). */
#define RG_MAX_DT 10.0

/* Exactly one step of length dt seconds (0 < dt <= RG_MAX_DT):
 * forces -> integrate -> range guard -> collide -> speed limits -> sleep -> range guard ->
 * events -> clear applied forces (collide, sleep and the second guard when the world has
 * shapes).  The range guard (see rg_world_get_stopped) keeps every body's state finite and
 * ends every step in range.  What a step needs is allocated before it changes anything:
 * RG_ERR_OUT_OF_MEMORY changes nothing.  The one exception is the contacts of new pairs,
 * which come to light in the middle of the step: a step that cannot store them all runs
 * without those it could not store (they are neither solved nor touching in it, and are
 * looked for again in the next step), and the next step first grows the contact storage,
 * and fails (RG_ERR_OUT_OF_MEMORY, nothing changed) while it cannot: no body goes on
 * through what it meets while memory is short. */
RG_API rg_status rg_world_step(rg_world *world, rg_real dt);

/* The step rg_world_advance takes (0 < dt <= RG_MAX_DT) and the most steps one advance may
 * take (>= 1).  Changing them keeps the accumulated time: after a shorter step than the time
 * held, the next advance takes the steps it owes, and rg_world_get_alpha reads 1 or more
 * until then. */
RG_API rg_status rg_world_set_fixed_step(rg_world *world, rg_real dt, int32_t max_steps_per_advance);
RG_API rg_status rg_world_get_fixed_step(const rg_world *world, rg_real *out_dt,
                                         int32_t *out_max_steps);
/* Adds frame_time (>= 0, any finite number of seconds) to an accumulator and takes as many
 * fixed steps as fit, at most max_steps_per_advance; time beyond that is dropped (the game
 * slows down instead of spiralling).  *out_steps (may be NULL) receives the number of steps taken.
 * The state after k fixed steps is bit-identical whatever frame times fed the accumulator.
 * The contact events read after it (rg_world_get_contact_events) are those of every step it
 * took, in step order; none when it took no step.  Their buffer grows as needed and then
 * stays (no allocation in steady state); if it cannot grow for a later step, or a step
 * could not store its new contacts (rg_world_step) and the storage cannot grow for the
 * next, the advance stops after the steps it took and still returns RG_OK: *out_steps
 * tells how many, the time of the others stays in the accumulator (rg_world_get_alpha may
 * read 1 or more) and the next advance takes them (or fails, changing nothing, as a step
 * does).  No event is lost and the simulation is the same. */
RG_API rg_status rg_world_advance(rg_world *world, rg_real frame_time, int32_t *out_steps);
/* accumulator / fixed dt after the last advance: the blend factor for rendering, in [0, 1)
 * (1 or more only while the next advance owes steps: after an advance that stopped early
 * for lack of memory, see above, or a shorter fixed step than the time held). */
RG_API rg_status rg_world_get_alpha(const rg_world *world, rg_real *out_alpha);
/* prev + alpha * (current - prev), where prev is the position before the last step taken
 * by rg_world_advance, with alpha at most 1 (never ahead of the current position).  After a
 * direct rg_world_step, or a set_position, it is the current position. */
RG_API rg_status rg_body_get_interpolated_position(const rg_world *world, rg_body body,
                                                   rg_vec2 *out);
/* The bodies the last rg_world_step, or the steps of the last rg_world_advance, stopped at
 * the edge of the accepted range.  A scene whose forces are far beyond its scale (a stiff
 * spring on a light body, a huge force applied every step) can drive a body's state out of
 * +-RG_MAX_COORD or +-RG_MAX_SPEED, or, within one RK4 step, past the float range, and an
 * impact can throw a body past RG_MAX_SPEED.  The step then stops that body after the
 * integration, before collision, and again after collision: each coordinate clamped to
 * +-RG_MAX_COORD (one that is no longer finite goes back to where the step began; Euler
 * cannot get there from a state in range), velocity and acceleration 0.  Nothing else
 * changes, the step succeeds, and the body is listed here until the next stepping call (a
 * restore clears the list).  Returns the count and copies min(count, capacity) handles in ascending
 * order; -1 (RG_ERR_INVALID_ARGUMENT) for NULL world, capacity < 0, or out NULL with
 * capacity > 0. */
RG_API int32_t rg_world_get_stopped(const rg_world *world, rg_body *out, int32_t capacity);
/* Number of live bodies; 0 for NULL. */
RG_API int32_t rg_world_body_count(const rg_world *world);
/* Number of live springs; 0 for NULL. */
RG_API int32_t rg_world_spring_count(const rg_world *world);

/* ---------------------------------------------------------------- bodies */

/* Largest |component| of a position, an anchor and a rest length, m. */
#define RG_MAX_COORD 1.0e9
/* Largest |component| of a velocity and largest speed limit, m/s. */
#define RG_MAX_SPEED 1.0e6
/* Mass of a dynamic body, kg. */
#define RG_MIN_MASS 1.0e-6
#define RG_MAX_MASS 1.0e9

/* type is one of RG_BODY_*.  mass (kg) must be in [RG_MIN_MASS, RG_MAX_MASS] for a dynamic
 * body; it is ignored (may be anything finite) for the others.  position in m, each
 * component within +-RG_MAX_COORD.  Defaults: velocity 0, gravity scale 1, no drag, no
 * surface friction, no speed limits. */
RG_API rg_status rg_body_create(rg_world *world, int32_t type, rg_real mass, rg_vec2 position,
                                rg_body *out_body);
/* Destroys the body and the springs attached to it (their handles go stale; the bodies at
 * their other ends wake). */
RG_API rg_status rg_body_destroy(rg_world *world, rg_body body);
/* 1 when body is a live body of this world, else 0 (also for NULL world). */
RG_API int32_t rg_body_is_valid(const rg_world *world, rg_body body);
/* One of RG_BODY_*. */
RG_API rg_status rg_body_get_type(const rg_world *world, rg_body body, int32_t *out_type);
/* Mass in kg; 0 for static and kinematic bodies. */
RG_API rg_status rg_body_get_mass(const rg_world *world, rg_body body, rg_real *out_mass);
/* New mass in kg ([RG_MIN_MASS, RG_MAX_MASS]) of a dynamic body; RG_ERR_INVALID_ARGUMENT
 * for the others.  A change wakes the body (it may rest no longer: on a spring, or held by
 * friction against wind). */
RG_API rg_status rg_body_set_mass(rg_world *world, rg_body body, rg_real mass);

/* Position in m (each component within +-RG_MAX_COORD), velocity in m/s (each within
 * +-RG_MAX_SPEED).  A static body has no velocity: setting a non-zero one is
 * RG_ERR_INVALID_ARGUMENT. */
RG_API rg_status rg_body_get_position(const rg_world *world, rg_body body, rg_vec2 *out);
RG_API rg_status rg_body_set_position(rg_world *world, rg_body body, rg_vec2 position);
RG_API rg_status rg_body_get_velocity(const rg_world *world, rg_body body, rg_vec2 *out);
RG_API rg_status rg_body_set_velocity(rg_world *world, rg_body body, rg_vec2 velocity);
/* The same position and velocity returned by value, for hosts where an out-pointer costs
 * more than the call (a LuaJIT trace allocates one per call).  (NaN, NaN) when the world is
 * NULL or the handle is not live (then rg_world_last_error says why): test x != x. */
RG_API rg_vec2 rg_body_position(const rg_world *world, rg_body body);
RG_API rg_vec2 rg_body_velocity(const rg_world *world, rg_body body);
/* The acceleration (m/s^2) the last step started with: sum(forces)/mass + gravity*scale,
 * forces being wind, applied forces, drag, surface friction and springs at the start state.
 * 0 before the first step and for non-dynamic bodies. */
RG_API rg_status rg_body_get_acceleration(const rg_world *world, rg_body body, rg_vec2 *out);

/* A force in N held constant over the next step, then cleared.  Forces add up, each
 * component of the sum within +-RG_MAX_FORCE (one that would leave it is
 * RG_ERR_INVALID_ARGUMENT).  No effect on static and kinematic bodies (infinite mass), which
 * is not an error. */
RG_API rg_status rg_body_apply_force(rg_world *world, rg_body body, rg_vec2 force);
/* An impulse in N*s (each component within +-RG_MAX_FORCE): velocity += impulse / mass at
 * once; a velocity that would leave +-RG_MAX_SPEED is RG_ERR_INVALID_ARGUMENT.  No effect on
 * non-dynamic bodies. */
RG_API rg_status rg_body_apply_impulse(rg_world *world, rg_body body, rg_vec2 impulse);
/* Largest |gravity scale|. */
#define RG_MAX_GRAVITY_SCALE 1.0e3
/* Multiplies world gravity for this body (within +-RG_MAX_GRAVITY_SCALE; 0 floats, -1 falls
 * up).  A change wakes the body. */
RG_API rg_status rg_body_set_gravity_scale(rg_world *world, rg_body body, rg_real scale);
/* 1 by default; 0 for static and kinematic bodies, on which gravity does not act (as their
 * mass; the setter changes nothing there). */
RG_API rg_status rg_body_get_gravity_scale(const rg_world *world, rg_body body, rg_real *out_scale);
/* Largest drag coefficient: linear in kg/s, quadratic in kg/m. */
#define RG_MAX_DRAG 1.0e9
/* Largest friction coefficient (surface friction's mu, a body's contact friction). */
#define RG_MAX_FRICTION 1.0e3
/* Air drag F = -(linear + quadratic * |v|) * v, with linear in kg/s and quadratic in kg/m
 * (quadratic = 1/2 * rho * Cd * A); both in [0, RG_MAX_DRAG]. */
RG_API rg_status rg_body_set_drag(rg_world *world, rg_body body, rg_real linear, rg_real quadratic);
/* 0 and 0 by default.  Either output may be NULL, not both. */
RG_API rg_status rg_body_get_drag(const rg_world *world, rg_body body, rg_real *out_linear,
                                  rg_real *out_quadratic);
/* Surface friction F = -mu * normal_force * v/|v| (mu in [0, RG_MAX_FRICTION], normal_force
 * in [0, RG_MAX_FORCE] N): a body sliding on a surface, as seen from above.  It brings the
 * body exactly to rest, never reverses it, and holds it at rest against any smaller force
 * (static friction).  A change wakes the body. */
RG_API rg_status rg_body_set_surface_friction(rg_world *world, rg_body body, rg_real mu,
                                              rg_real normal_force);
/* Where each step ends, after its collisions: |v| < min_speed -> v = 0 exactly; |v| >
 * max_speed -> v scaled to max_speed, so the velocity read after any step obeys both (a crate
 * sliding to a stop on the ground snaps to rest; a ball's bounce leaves it no faster than
 * max_speed).  Within a step the integration starts from that velocity and adds
 * acceleration * dt, so a body held at max_speed by gravity moves at most (max_speed +
 * |g| dt) * dt a step.  max_speed = 0 means no limit; both in [0, RG_MAX_SPEED], and
 * max_speed >= min_speed unless 0. */
RG_API rg_status rg_body_set_speed_limits(rg_world *world, rg_body body, rg_real min_speed,
                                          rg_real max_speed);
/* 0 and 0 by default (no limits).  Either output may be NULL, not both. */
RG_API rg_status rg_body_get_speed_limits(const rg_world *world, rg_body body, rg_real *out_min_speed,
                                          rg_real *out_max_speed);
/* An opaque 64-bit value for the caller (an entity id, an index); 0 by default. */
RG_API rg_status rg_body_set_user_data(rg_world *world, rg_body body, uint64_t user_data);
RG_API rg_status rg_body_get_user_data(const rg_world *world, rg_body body, uint64_t *out);

/* Dissipative forces (drag, surface friction) never reverse a velocity within a step: when
 * the explicit force would carry the velocity through zero, as it does when
 * mu*N*dt/m > |v| or (linear + quadratic*|v|)*dt/m > 1, that body's step treats them
 * implicitly instead (friction projects the velocity to exactly zero; drag solves
 * v' = v_free - dt*(linear + quadratic*|v'|)*v'/m).  Small steps keep the integrator's order. */

/* ---------------------------------------------------------------- springs */

/* Largest spring stiffness, N/m, and damping, N*s/m. */
#define RG_MAX_STIFFNESS 1.0e9
#define RG_MAX_DAMPING 1.0e9

/* A damped spring between two points: F = -(stiffness*(|d| - rest_length) +
 * damping*(dv . d/|d|)) * d/|d| on a, the opposite on b, where d = pos(a) - pos(b) and dv
 * the relative velocity.  b = 0 ties a to the fixed world point `anchor` (each component
 * within +-RG_MAX_COORD; ignored otherwise).  stiffness in N/m, in [0, RG_MAX_STIFFNESS];
 * damping in N*s/m, in [0, RG_MAX_DAMPING]; rest_length in m, in [0, RG_MAX_COORD].
 * A zero rest length gives F = -stiffness * d exactly.  Evaluated at every stage of a
 * multi-stage integrator.  a and b must be distinct live bodies of this world.  Making or
 * destroying a spring wakes its bodies (a sleeping body is not integrated, so it would not
 * feel the change: a crate asleep on a rope falls when the rope is cut). */
RG_API rg_status rg_spring_create(rg_world *world, rg_body a, rg_body b, rg_vec2 anchor,
                                  rg_real rest_length, rg_real stiffness, rg_real damping,
                                  uint64_t *out_spring);
RG_API rg_status rg_spring_destroy(rg_world *world, uint64_t spring);
/* 1 when spring is a live spring of this world, else 0. */
RG_API int32_t rg_spring_is_valid(const rg_world *world, uint64_t spring);

/* ---------------------------------------------------------------- collision
 *
 * A body has at most one shape: a circle or an axis-aligned box centred on its position.
 * A body without a shape never collides and costs nothing in the collision stage; a world
 * where no body has a shape skips the stage entirely.  Contacts are resolved with impulses
 * (restitution, Coulomb friction) and a position correction that adds no energy; bodies
 * at rest fall asleep and stop costing time until something touches or pushes them.
 *
 * Contacts are speculative: a pair the step would bring together stops exactly where it
 * touches, within the step.  Impacts are timed: a body whose free motion in a step closes its
 * gap to a surface (or to several at one moment, as across a tile seam), a fraction t into
 * the step, moves freely until then and with its outgoing velocity after.  A bounce turns at
 * the surface: the body ends the step at surface + v_out * (1 - t) * dt along the normal,
 * v_out being restitution times its speed at the impact less what gravity and the other
 * forces took off since; the rebound rises to restitution^2 times the drop height within
 * g*dt^2/8, and an elastic bounce (restitution 1) neither gains nor loses energy.  A landing
 * without a bounce ends its step on the surface with no velocity into it (and grounded).
 * Explicit Euler, Verlet and RK4 move a*dt^2 (or a*dt^2/2) off the x0 + v*dt the contacts
 * hold: a pair is checked on both motions and an impact timed on the integrator's own, and
 * a body the contacts stop, land or hold keeps only the part of that term that brings it to
 * the surface, so the above holds under every integrator (README: accuracy --contacts);
 * only a slide under friction keeps semi-implicit Euler's first-order error.
 * A body that meets two surfaces at different moments of one step, that is hit while it
 * touches something, or that lands with another movable body near it (a tower falling as
 * one) is stopped at the surface from where the step began instead: it ends the step
 * touching, its velocity into the surface reads until the next step, and a bounce turns it
 * up to one step's travel short of the surface. */

enum { RG_SHAPE_NONE = 0, RG_SHAPE_CIRCLE = 1, RG_SHAPE_AABB = 2 };

/* Smallest and largest radius or half extent a shape may have, in m. */
#define RG_MIN_SHAPE_SIZE 1.0e-6
#define RG_MAX_SHAPE_SIZE 1.0e7

/* Gives the body a circle of radius r in m (RG_MIN_SHAPE_SIZE <= r <= RG_MAX_SHAPE_SIZE),
 * replacing any shape it had.  Static, kinematic and dynamic bodies may all have shapes. */
RG_API rg_status rg_body_set_circle(rg_world *world, rg_body body, rg_real radius);
/* Gives the body an axis-aligned box of half extents in m (each in [RG_MIN_SHAPE_SIZE,
 * RG_MAX_SHAPE_SIZE]). */
RG_API rg_status rg_body_set_aabb(rg_world *world, rg_body body, rg_real half_width,
                                  rg_real half_height);
/* Removes the body's shape; its touching contacts end (end events after the next step). */
RG_API rg_status rg_body_clear_shape(rg_world *world, rg_body body);
/* RG_SHAPE_* and the half extents in m ((r, r) for a circle, (0, 0) without a shape).
 * Either output may be NULL, not both. */
RG_API rg_status rg_body_get_shape(const rg_world *world, rg_body body, int32_t *out_kind,
                                   rg_vec2 *out_half_extents);

/* Materials.  A touching pair uses the larger of the two restitutions and the geometric mean
 * of the two frictions.  Defaults: restitution 0, friction 0.6.  restitution in [0, 1]
 * (0: no bounce, 1: elastic); friction in [0, RG_MAX_FRICTION] (the Coulomb coefficient:
 * the tangential impulse is at most friction * normal impulse).  A change of friction wakes
 * the body and the bodies touching it (what friction held at rest may slide). */
RG_API rg_status rg_body_set_restitution(rg_world *world, rg_body body, rg_real restitution);
RG_API rg_status rg_body_get_restitution(const rg_world *world, rg_body body, rg_real *out);
RG_API rg_status rg_body_set_friction(rg_world *world, rg_body body, rg_real mu);
RG_API rg_status rg_body_get_friction(const rg_world *world, rg_body body, rg_real *out);

/* A sensor (is_sensor 1; 0 makes it solid again) reports begin/end contacts (with sensor = 1)
 * for the shapes it overlaps where each step leaves them, or that crossed it within the
 * step (rg_world_get_contact_events), but never pushes nor is pushed.
 * Sensors see every shape their filter admits, other sensors included.  Changing it ends
 * the body's current contacts. */
RG_API rg_status rg_body_set_sensor(rg_world *world, rg_body body, int32_t is_sensor);
RG_API rg_status rg_body_is_sensor(const rg_world *world, rg_body body, int32_t *out_is_sensor);

/* Two bodies collide when (a.category & b.mask) and (b.category & a.mask) are both non-zero.
 * Default: category 1, mask 0xFFFFFFFF.  Contacts the new filter rejects end. */
RG_API rg_status rg_body_set_filter(rg_world *world, rg_body body, uint32_t category,
                                    uint32_t mask);
RG_API rg_status rg_body_get_filter(const rg_world *world, rg_body body, uint32_t *out_category,
                                    uint32_t *out_mask);

/* 1 when, after the last step, the body touches a solid (non-sensor) surface whose normal
 * points against the body's gravity (world gravity * gravity scale) within 45 degrees; 0 in
 * the air, for non-dynamic bodies and when the body feels no gravity.  A sleeping body keeps
 * the value it fell asleep with. */
RG_API rg_status rg_body_is_grounded(const rg_world *world, rg_body body, int32_t *out_grounded);

/* ---- sleeping: an island of dynamic bodies that touch, or lie within the solver's reach
 * of each other (4 * slop plus the step's motion), whose speeds all stayed below
 * sleep_speed for sleep_time seconds stops moving and costs nothing per step.  It wakes
 * when a moving body touches it or comes within that reach, when a force, impulse,
 * velocity or position is given to one of its bodies, or when something it rests on is
 * moved or destroyed, and when world gravity or wind changes (rg_world_set_gravity).
 * Only dynamic bodies with a shape sleep. */

/* enabled 1 (the default) or 0; disabling wakes every sleeping body. */
RG_API rg_status rg_world_set_sleeping(rg_world *world, int32_t enabled);
RG_API rg_status rg_world_get_sleeping(const rg_world *world, int32_t *out_enabled);
/* speed in m/s (in [0, RG_MAX_SPEED]), time in s (> 0, finite).  Defaults 0.05 m/s and
 * 0.5 s. */
RG_API rg_status rg_world_set_sleep_thresholds(rg_world *world, rg_real speed, rg_real time);
RG_API rg_status rg_world_get_sleep_thresholds(const rg_world *world, rg_real *out_speed,
                                               rg_real *out_time);
/* 1 when the body takes part in the next step: awake dynamic and every kinematic body;
 * 0 for sleeping and static bodies. */
RG_API rg_status rg_body_is_awake(const rg_world *world, rg_body body, int32_t *out_awake);
/* Wakes a sleeping body and its island (no effect on awake or static bodies). */
RG_API rg_status rg_body_wake(rg_world *world, rg_body body);
/* Bodies that take part in the next step (awake dynamic + kinematic); 0 for NULL. */
RG_API int32_t rg_world_awake_body_count(const rg_world *world);

/* ---- solver and continuous collision */

/* Sequential-impulse iterations per step: `velocity` (1..64, default 8) over the contact
 * velocities, warm-started from the last step, then `position` (0..64, default 3) over
 * pseudo-velocities that move bodies out of penetration without touching their velocities,
 * so position correction never adds energy.  More iterations: stiffer piles, more time. */
RG_API rg_status rg_world_set_solver_iterations(rg_world *world, int32_t velocity,
                                                int32_t position);
RG_API rg_status rg_world_get_solver_iterations(const rg_world *world, int32_t *out_velocity,
                                                int32_t *out_position);
/* Contact tuning: slop in m ([0, RG_MAX_SHAPE_SIZE], default 0.005): penetration left
 * uncorrected so resting contacts stay touching; bias_rate in (0, 1] (default 0.2): fraction
 * of the remaining penetration removed per step; max_push in m/s ((0, RG_MAX_SPEED], default
 * 2): fastest correction; restitution_threshold in m/s ([0, RG_MAX_SPEED], default 1):
 * slower impacts do not bounce. */
RG_API rg_status rg_world_set_contact_tuning(rg_world *world, rg_real slop, rg_real bias_rate,
                                             rg_real max_push, rg_real restitution_threshold);
RG_API rg_status rg_world_get_contact_tuning(const rg_world *world, rg_real *out_slop,
                                             rg_real *out_bias_rate, rg_real *out_max_push,
                                             rg_real *out_restitution_threshold);
/* Continuous collision (1, the default): the broadphase sees each body's swept path over
 * the step, and a pair whose relative motion in the step exceeds half the smaller shape
 * is solved at its time of impact, so fast bodies never pass through thin walls; after the
 * solve, a body that moved more than half its size, or that the solve moved more than the
 * slop off its free motion (a body an impact sends off), is swept once more against the
 * static, kinematic and sleeping shapes on its path: at a static or kinematic one the rest of
 * its motion goes on along the surface, less its part into it, and with the kinematic body's
 * motion (a fast paddle carries what it meets), swept again, up to 4 legs, the last stopped
 * at its impact; at a sleeping one it stops (that one wakes and takes its momentum).  0
 * checks only the shapes where the step leaves them (a discrete check: fast bodies tunnel),
 * for comparison. */
RG_API rg_status rg_world_set_continuous(rg_world *world, int32_t enabled);
RG_API rg_status rg_world_get_continuous(const rg_world *world, int32_t *out_enabled);
/* Pairs touching after the last step (sensor overlaps included), less those ended since (a
 * body destroyed, its shape, sensor flag or filter changed: their end events come with the
 * next step's); 0 for NULL. */
RG_API int32_t rg_world_touching_count(const rg_world *world);

/* ---- contact events of the last step or advance, read after it */

enum { RG_CONTACT_BEGIN = 0, RG_CONTACT_END = 1 };

typedef struct rg_contact_event {
    rg_body a, b;       /* a < b */
    rg_vec2 normal;     /* unit, from a toward b */
    rg_vec2 point;      /* world point of contact, m */
    rg_real depth;      /* penetration when the contact began, m (>= 0) */
    rg_real speed;      /* approach speed along the normal when it began, m/s (>= 0) */
    int32_t kind;       /* RG_CONTACT_BEGIN = 0, RG_CONTACT_END = 1 */
    int32_t sensor;     /* 1 when either body is a sensor */
} rg_contact_event;

/* Returns how many events the last rg_world_step produced, or the last rg_world_advance (all
 * the steps it took, step after step; none when it took no step), and copies min(count,
 * capacity) of them to out.  Each step's events are sorted by (a, b), an end before a begin of
 * the same pair.  out may be NULL when capacity is 0.  RG_ERR_INVALID_ARGUMENT for a NULL world, capacity < 0, or out NULL with
 * capacity > 0.  A pair that touches once gives exactly one begin and one end.  Contacts
 * ended between steps (a body destroyed, its shape, sensor flag or filter changed) are
 * reported with the next step's events, under the handles they had (a destroyed body's is
 * stale by then).  An end event carries the pair's last normal and point and the depth and
 * speed of its begin.  Touching means the step ends with the pair in contact: a body that
 * jumps off a surface ends its contact in that step.  A solid pair touches when the step's
 * free motion closes it (with a slop of hysteresis: a touching pair stays so while less than
 * the slop apart) or the solve presses it together (a body driven onto another by a third);
 * a sensor pair is tested on the shapes where the step leaves them, so a body that a wall
 * stops short of a sensor behind it never touches it, and one knocked into a sensor touches
 * it in that step; and one whose straight path from where the step took it to where it left
 * it crossed the sensor (a bullet through a thin trigger, moving more than half the smaller
 * shape relative to it) touches it for that step, where it entered, and ends with the next.
 * A pair exists once the bodies' fat boxes meet (each its box grown by 2% of its size, at
 * least the slop, and by the path of its next four steps): a body that an impact sends out
 * of its fat box into a shape it was not near touches it from the next step. */
RG_API int32_t rg_world_get_contact_events(const rg_world *world, rg_contact_event *out,
                                           int32_t capacity);

/* ---- queries: they see bodies as they are now, also before the first step.  Their points,
 * bounds and translations (rays, boxes, points, shape casts) may reach further than bodies
 * do, each component within +-RG_MAX_QUERY_COORD m, so that origin + t * translation stays
 * finite. */
#define RG_MAX_QUERY_COORD 1.0e12

typedef struct rg_ray_hit {
    rg_body body;
    rg_vec2 point;      /* m */
    rg_vec2 normal;     /* unit, the surface normal at point, facing the ray */
    rg_real fraction;   /* of the translation, in [0, 1] */
    int32_t pad;        /* 0, as every padding byte of the records the library writes (this
                           one, rg_contact): equal results are equal bytes */
} rg_ray_hit;

/* The closest shape along origin + t * translation, t in [0, 1], among bodies with
 * (category & mask) != 0 (sensors too).  Shapes that contain the origin are ignored.  Ties
 * go to the lower handle.  Returns 1 and fills *out_hit on a hit, 0 when nothing is hit, < 0
 * (RG_ERR_INVALID_ARGUMENT) for NULL world or out_hit or an origin or translation out of
 * range. */
RG_API int32_t rg_world_raycast(const rg_world *world, rg_vec2 origin, rg_vec2 translation,
                                uint32_t mask, rg_ray_hit *out_hit);
/* Bodies whose shape's bounding box overlaps [lower, upper] (touching counts) and whose
 * (category & mask) != 0; returns the count and copies min(count, capacity) handles to out,
 * in ascending handle order.  < 0 (RG_ERR_INVALID_ARGUMENT) for NULL world, bounds out of
 * range, lower > upper in x or y, capacity < 0, or out NULL with capacity > 0. */
RG_API int32_t rg_world_query_aabb(const rg_world *world, rg_vec2 lower, rg_vec2 upper,
                                   uint32_t mask, rg_body *out, int32_t capacity);

/* ---------------------------------------------------------------- gameplay collision */

/* One-way shapes: the body blocks only motion that goes against `normal` (unit; (0,1) is a
   platform stood on from above and passed from below). (0,0) makes it two-way (the default).
   A body that overlaps it when the contact would begin, or moves along it, is not pushed.
   In detail: when a contact with a one-way body would begin (the pair is about to touch or
   be solved), it blocks only if the contact normal from the one-way body toward the other
   points into the half-space of `normal` (dot > 0) and the shapes do not overlap by more
   than the slop at the start of the step, or if the other shape lay wholly on the `normal`
   side at the start of the step (its extent along `normal` begins no more than the slop
   short of the one-way shape's end: a box sliding over flush one-way tiles meets each
   next tile's corner first, with a side normal); otherwise the pair passes (no solve, no
   touching, no events) until a step ends with the shapes apart.  A blocking contact keeps blocking
   while it touches.  normal must be finite and of length 1 within 1e-3, or (0, 0); it is
   stored normalised.  Raycasts and queries see one-way shapes as any other; the mover
   (rg_body_move) and the post-solve sweep respect them.  A sensor blocks nothing, so its
   one-way normal changes nothing: it reports every shape it overlaps. */
RG_API rg_status rg_body_set_one_way(rg_world *world, rg_body body, rg_vec2 normal);
RG_API rg_status rg_body_get_one_way(const rg_world *world, rg_body body, rg_vec2 *out_normal);

/* The pair stops colliding now, and collides again from the first step that ends with their
   shapes apart (dropping down through a platform).  Until then it is neither solved nor
   touching (a touching pair reports its end with the next step).  RG_ERR_INVALID_ARGUMENT
   when body == other or either has no shape; RG_OK and no effect when the shapes are
   apart (beyond the slop) already. */
RG_API rg_status rg_body_pass_through(rg_world *world, rg_body body, rg_body other);

/* Called inside the step for every touching, non-sensor pair before it is solved; return 0
   to skip the pair for this step. While it runs, calls that change the world return
   RG_ERR_LOCKED and change nothing; getters and queries work. NULL removes the hook.
   "Touching" here: the narrowphase would solve the pair or find it touching this step.  A
   skipped pair is neither solved nor touching in this step (no begin event, no grounded
   flag), exactly as if it were apart, and the post-solve sweep lets its bodies through each
   other (a body an impact sends into a shape it has no pair with, outside the reach of its
   step's free motion, meets that shape in the sweep unasked).  The calls come in a fixed
   order (the order of the awake contacts, which the same history always gives), a < b as
   in events, separation at the start of the step (< 0 when overlapping).  rg_world_destroy
   from inside is a no-op.  Pairs of sleeping bodies are not stepped, so not asked: after
   installing a hook, or where its answer for a pair changes with the game's own state, wake
   one of the pair's bodies (rg_body_wake) for it to be asked.  Installing, replacing or removing the hook
   changes no state (nothing wakes), so a world restored from a snapshot and then given its
   hook steps as the saving world did. */
typedef int32_t rg_pre_solve_fn(rg_body a, rg_body b, rg_vec2 normal, rg_real separation,
                                void *user);   /* normal from a toward b, m */
RG_API rg_status rg_world_set_pre_solve(rg_world *world, rg_pre_solve_fn *fn, void *user);

/* The contacts a body has after the last step: its touching pairs (sensor overlaps
   included, sensor = 1), in ascending order of the other body's handle.  Returns the count
   and copies min(count, capacity); out may be NULL with capacity 0; -1
   (RG_ERR_INVALID_ARGUMENT) or RG_ERR_STALE_HANDLE on bad input.  normal, point and
   separation describe the shapes as they are now; the impulses are what the last step's
   solve applied to the pair (0 for sensors). */
typedef struct rg_contact {
    rg_body other;
    rg_vec2 normal;          /* unit, from body toward other */
    rg_vec2 point;           /* m */
    rg_real separation;      /* m, < 0 when overlapping */
    rg_real normal_impulse;  /* N s, what the last step's solve applied along the normal */
    rg_real tangent_impulse; /* N s, friction (signed along the tangent (-normal.y, normal.x)) */
    int32_t sensor;
} rg_contact;
RG_API int32_t rg_body_get_contacts(const rg_world *world, rg_body body, rg_contact *out,
                                    int32_t capacity);   /* count, copies min(count, capacity) */

/* More queries (see bodies as they are now; sensors included; -1 on bad input).
   Every shape the segment origin + t * translation, t in [0, 1], enters, among bodies with
   (category & mask) != 0 (shapes containing the origin are not entered, as for
   rg_world_raycast), sorted by fraction then handle; returns the count and copies
   min(count, capacity) (the first ones in that order). */
RG_API int32_t rg_world_raycast_all(const rg_world *world, rg_vec2 origin, rg_vec2 translation,
                                    uint32_t mask, rg_ray_hit *out, int32_t capacity);
/* The bodies whose shape contains point (its boundary included), in ascending handle
   order; returns the count and copies min(count, capacity). */
RG_API int32_t rg_world_query_point(const rg_world *world, rg_vec2 point, uint32_t mask,
                                    rg_body *out, int32_t capacity);
/* Sweeps a circle (shape RG_SHAPE_CIRCLE, size = (radius, 0)) or a box (RG_SHAPE_AABB,
   size = half extents) from origin along translation: 1 and the first hit, 0 none.  The
   hit's fraction is the time of impact in [0, 1], point the contact point then, normal the
   hit surface's, facing the cast shape; ties go to the lower handle.  A shape the cast
   shape overlaps at the start is hit at fraction 0 when the translation goes into it
   (against the normal of least penetration) and ignored otherwise, so a shape resting on a
   surface can cast along it.  Sizes as for rg_body_set_circle / rg_body_set_aabb. */
RG_API int32_t rg_world_cast_shape(const rg_world *world, int32_t shape, rg_vec2 size,
                                   rg_vec2 origin, rg_vec2 translation, uint32_t mask,
                                   rg_ray_hit *out_hit);

/* Character mover: moves a body's shape from where it is toward target at once (no step,
   velocity unchanged), against shapes of bodies other than itself and sensors whose
   category & mask != 0, and sets its position to where it stops. */
#define RG_MOVE_SLIDE 0   /* stop at a surface, go on along it (as bump.lua's "slide") */
#define RG_MOVE_TOUCH 1   /* stop at the first surface */
#define RG_MOVE_CROSS 2   /* reach the target, report what was crossed */
/* out_hits: the surfaces met, in order (may be NULL with capacity 0); one-way shapes block
   only against their normal.  In detail: sensors never block; CROSS reports every shape the
   path enters, sensors included, SLIDE and TOUCH the solid surfaces that stopped the body.
   A hit's fraction is the part of the whole requested path (|target - start|) travelled
   when it was met, normal the surface's, facing the body.  The body ends flush against what
   stopped it (within rounding; never overlapping it by more than the slop), and a box or
   circle sliding over a row of flush boxes (a tile floor) does not catch on their seams;
   SLIDE takes at most 8 legs; one that would carry the body's centre past +-RG_MAX_COORD
   stops at that edge and goes on along it, as along a wall that reports no hit.
   *out_count (may be NULL) gets the number of hits, of which min(count, capacity) are
   copied.  target is a position (each component within +-RG_MAX_COORD).  The body must
   have a shape (else RG_ERR_INVALID_ARGUMENT); it is woken, and rendering interpolates from
   where it was at the last step (the previous position is kept) until the next step; a
   static body, which takes no step, is drawn where it ends at once, as after
   rg_body_set_position. */
RG_API rg_status rg_body_move(rg_world *world, rg_body body, rg_vec2 target, uint32_t mask,
                              int32_t response, rg_vec2 *out_position, rg_ray_hit *out_hits,
                              int32_t capacity, int32_t *out_count);

/* ---------------------------------------------------------------- snapshots (rollback)
 *
 * A snapshot is the whole simulation state in a portable format: one byte order
 * (little-endian) and fixed field sizes, so a snapshot saved on one machine restores on
 * another (x86-64 and aarch64 alike) of the same rg_real, and both continue to the same
 * bytes.  It holds no pointer and carries a 64-bit checksum.  Typical rollback use:
 *   size_t n; rg_world_save(w, NULL, 0, &n);         the size (it changes with the scene)
 *   rg_world_save(w, buf, cap, &n);                   at frame k
 *   ...                                               a late input arrives for frame k
 *   rg_world_restore(w, buf, n);                      back to frame k
 *   step the frames again with the corrected inputs.
 * Saving and hashing allocate nothing; restoring allocates only when the world must grow. */

/* Writes the whole simulation state (bodies, shapes, springs, contacts and warm-start
   impulses, islands and sleep timers, accumulator, settings, handle generations) to out.
   With out == NULL and capacity == 0 it only reports the size. RG_ERR_CAPACITY when
   capacity is too small (nothing written beyond it).  *out_size receives the size in every
   case but a NULL world or out_size.  Also the contact events readable now (and the ends
   held for the next step) are saved, so a restored world reads the same events. */
RG_API rg_status rg_world_save(const rg_world *world, void *out, size_t capacity, size_t *out_size);

/* Replaces the world's state with a saved one. Afterwards every handle the saving world
   gave out names the same body or spring here (a world restored from another world's
   snapshot takes that world's handle identity, so a clone answers the original's handles),
   and stepping continues exactly as the saving world would have. A truncated, corrupted or
   forged snapshot, or one from a build with another rg_real, is RG_ERR_INVALID_ARGUMENT and
   changes nothing. The pre-solve hook and allocator are the world's own, not saved.
   RG_ERR_OUT_OF_MEMORY when the world cannot grow to hold it (nothing changed either);
   RG_ERR_LOCKED from inside one of the world's callbacks.  Every structural invariant of
   the state is checked before anything is changed, so no snapshot, however forged, can
   make a later call misbehave.  With a task system (rg_world_set_task_system) the checks and the load of the
   contacts and the broadphase run on its workers, and the checksum beside the other checks;
   what is refused, and why, and what is loaded are the same as on one thread.
   A world knows its own snapshots again: once it has restored one (of any origin), it tags
   its next 64 saves with a keyed hash whose key it draws at its creation and never writes
   out, and bytes equal to one of its last 64 tagged saves (the tags compared: other bytes
   pass with a chance of about 2^-64) are loaded without the checks, as a kept state is: a
   state the world has been in breaks no invariant.  This is the rollback loop, which
   restores its own saves again and again in 0.37-0.62 of a checked restore's time (README:
   make bench's snapshot lines); the first restore of a loop, any snapshot of another world
   or from a file, and any changed byte are checked whole.  A world that never restores
   does not tag: its saves cost what they did. */
RG_API rg_status rg_world_restore(rg_world *world, const void *data, size_t size);

/* A 64-bit hash of the simulation state: equal states give equal hashes, and the same
   scene gives the same hash on any compiler, optimisation level and SIMD path.  It covers
   what a snapshot holds but the world's handle tag, so two worlds built by the same calls
   (or a world and its restored clone) hash alike on any machine of the same rg_real. */
RG_API rg_status rg_world_hash(const rg_world *world, uint64_t *out_hash);

/* ---------------------------------------------------------------- kept states (rollback in the world)
 *
 * A world can keep copies of its own state in RG_MAX_SLOTS slots, in memory from its own
 * allocator: what a rollback loop needs when the snapshots never leave the process.  A kept
 * state is the snapshot rg_world_save would write at that moment, without its checksum, and
 * rg_world_restore_slot brings it back exactly as rg_world_restore would bring back that
 * snapshot (the same handles, the same steps after).  It skips the checks of every value and
 * link that a snapshot from outside needs, since nothing outside the library can reach the
 * kept bytes (the header and settings are still checked), and takes about half the time of
 * a checked restore or less (README; make bench).
 *   rg_world_save_slot(w, frame % 8);                 at every frame
 *   ...                                               a late input arrives for frame k
 *   rg_world_restore_slot(w, k % 8);                  back to frame k
 * A slot's block is reused from one save to the next and grows when the state does; the
 * kept states go with rg_world_destroy, or one at a time with rg_world_drop_slot.  Scripts
 * use world:save() and world:restore(s), whose strings they can keep as they please. */
enum { RG_MAX_SLOTS = 64 };

/* Keeps the world's state in slot (0 <= slot < RG_MAX_SLOTS), replacing what the slot held.
   RG_ERR_OUT_OF_MEMORY when the slot's block cannot grow (the slot keeps what it held);
   RG_ERR_LOCKED from inside one of the world's callbacks. */
RG_API rg_status rg_world_save_slot(rg_world *world, int32_t slot);

/* Brings back the state kept in slot.  RG_ERR_INVALID_ARGUMENT for a slot out of range or
   empty, RG_ERR_OUT_OF_MEMORY when the world cannot grow to hold it, both changing nothing;
   RG_ERR_LOCKED from inside one of the world's callbacks.  The slot keeps its state. */
RG_API rg_status rg_world_restore_slot(rg_world *world, int32_t slot);

/* Frees what slot holds (an empty slot is no error); RG_ERR_INVALID_ARGUMENT out of range. */
RG_API rg_status rg_world_drop_slot(rg_world *world, int32_t slot);

/* ---------------------------------------------------------------- debug draw
 *
 * rg_world_draw calls back for what draw->flags ask, layer by layer (shapes, bounds, springs,
 * velocities, contacts), each layer in a fixed order: bodies by slot (creation order, a
 * destroyed body's slot reused in place), springs by creation, contacts by id.  The same
 * world gives the same calls.  A NULL callback is skipped.  It changes nothing. */

#define RG_DRAW_SHAPES     1u   /* circles and boxes; a body without a shape as a point */
#define RG_DRAW_CONTACTS   2u   /* touching contacts: the point and the normal from a toward b */
#define RG_DRAW_VELOCITIES 4u   /* a segment from the centre to centre + v * RG_DRAW_VELOCITY_SCALE */
#define RG_DRAW_BOUNDS     8u   /* the broadphase's fat boxes */
#define RG_DRAW_SPRINGS    16u  /* a segment between the two ends, or to the anchor */

/* The palette, 0xRRGGBBAA.  A shape takes the colour of its body's state. */
#define RG_COLOR_STATIC    0x8C8C8CFFu  /* grey */
#define RG_COLOR_KINEMATIC 0x3C78DCFFu  /* blue */
#define RG_COLOR_AWAKE     0xE6782DFFu  /* orange: an awake dynamic body */
#define RG_COLOR_SLEEPING  0x8C64B4FFu  /* violet: a sleeping dynamic body */
#define RG_COLOR_SENSOR    0xDCB41E80u  /* translucent gold (any type); its contacts too */
#define RG_COLOR_CONTACT   0xDC2828FFu  /* red */
#define RG_COLOR_VELOCITY  0x28A03CFFu  /* green */
#define RG_COLOR_BOUNDS    0x32B4B4FFu  /* teal */
#define RG_COLOR_SPRING    0xB43CB4FFu  /* magenta */
/* Seconds of motion a velocity segment shows, and the length of a contact normal in m. */
#define RG_DRAW_VELOCITY_SCALE 0.1
#define RG_DRAW_NORMAL_LENGTH  0.25

typedef struct rg_debug_draw {
    void (*circle)(rg_body body, rg_vec2 center, rg_real radius, uint32_t rgba, void *user);
    void (*box)(rg_body body, rg_vec2 lower, rg_vec2 upper, uint32_t rgba, void *user);
    void (*segment)(rg_vec2 a, rg_vec2 b, uint32_t rgba, void *user);
    void (*point)(rg_vec2 p, uint32_t rgba, void *user);
    uint32_t flags;     /* RG_DRAW_* */
    void *user;
} rg_debug_draw;

/* RG_ERR_INVALID_ARGUMENT for a NULL world or draw, or a flag outside RG_DRAW_*.  While the
   callbacks run, the world is locked: calls that would change it return RG_ERR_LOCKED and
   rg_world_destroy does nothing. */
RG_API rg_status rg_world_draw(const rg_world *world, const rg_debug_draw *draw);

/* ---------------------------------------------------------------- threads */

/* A step can spread its stages over the threads of a task system: the game's own job system,
   or the pool below.  The results are bit-identical at any number of workers, and identical
   to the step without a task system: every stage is split into ranges whose results do not
   depend on how it is split or in which order the ranges run, and what must happen in order
   (the pre-solve hook, events, contact creation, waking) stays on the stepping thread.
   Callbacks (the pre-solve hook) run on the thread that called rg_world_step or
   rg_world_advance, never on a worker.

   enqueue runs fn over [0, count): it may split it into ranges [begin, end) of at least
   min_range items (the last may be shorter) and run them on any threads at once, in any
   order, each call with a worker index in [0, workers) that no other call running at the
   same time has; or run it all at once and return NULL.  finish waits until every range of
   what enqueue returned has run (it is not called for NULL).  The world calls enqueue and
   finish only from the thread inside its rg_world_step, rg_world_advance, rg_world_restore or
   rg_world_restore_slot (a restore's checks and load run on the task system too), and
   finishes each task before the next; while they run, the world is locked (calls that
   would change it return RG_ERR_LOCKED, rg_world_destroy does nothing; getters see the step
   in progress).  workers must be in [1, RG_MAX_WORKERS]; enqueue and
   finish must not be NULL.  NULL tasks: one thread, the default.  A world keeps a copy of
   *tasks. */
#define RG_MAX_WORKERS 64
typedef void rg_task_fn(int32_t begin, int32_t end, int32_t worker, void *context);
typedef struct rg_task_system {
    int32_t workers;   /* threads that may run tasks at once, >= 1 */
    void *(*enqueue)(rg_task_fn *fn, int32_t count, int32_t min_range, void *context,
                     void *user);   /* run fn over [0, count) in ranges of at least
                                       min_range; may run it at once and return NULL */
    void (*finish)(void *task, void *user);   /* wait for what enqueue returned */
    void *user;
} rg_task_system;
RG_API rg_status rg_world_set_task_system(rg_world *world, const rg_task_system *tasks);

/* A ready pool of `threads` threads in all ([1, RG_MAX_WORKERS]: the calling thread and
   threads - 1 it starts), for games without a job system of their own.  Its task system runs
   each task with the calling thread taking part and returns when it is done (enqueue
   returns NULL); idle threads wait on a condition after a short spin.  One pool may serve
   several worlds, stepped on different threads: their tasks take turns.  Destroy a pool
   only when no world steps with it (a world keeps its task system until set again).
   RG_ERR_INVALID_ARGUMENT for a count out of range or NULL out_pool, RG_ERR_OUT_OF_MEMORY
   or, where threads cannot be started, RG_ERR_CAPACITY. */
typedef struct rg_thread_pool rg_thread_pool;
RG_API rg_status rg_thread_pool_create(int32_t threads, rg_thread_pool **out_pool);
RG_API void rg_thread_pool_destroy(rg_thread_pool *pool);   /* NULL: no-op */
RG_API rg_status rg_thread_pool_task_system(rg_thread_pool *pool, rg_task_system *out);

#ifdef __cplusplus
}
#endif

#endif /* RIGID_H */
