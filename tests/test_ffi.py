#!/usr/bin/env python3
"""test_ffi.py: drives build/librigid.so through Python's ctypes, a second language host.

Checks that the ABI works from an FFI: the real size, vectors passed by value, outputs
through pointers, 64-bit handles, statuses, and a caller-supplied allocator callback.
Closes with `N passed, N failed`.
"""
import ctypes as C
import math
import sys

LIB_PATH = sys.argv[1] if len(sys.argv) > 1 else "build/librigid.so"
lib = C.CDLL(LIB_PATH)

lib.rg_real_size.restype = C.c_int32
REAL = {4: C.c_float, 8: C.c_double}[lib.rg_real_size()]
EPS = {4: 1.1920929e-07, 8: 2.220446049250313e-16}[lib.rg_real_size()]

OK, INVALID, STALE = 0, -1, -2
STATIC, KINEMATIC, DYNAMIC = 0, 1, 2


class Vec2(C.Structure):
    _fields_ = [("x", REAL), ("y", REAL)]


World = C.c_void_p
Body = C.c_uint64
ALLOC = C.CFUNCTYPE(C.c_void_p, C.c_void_p, C.c_void_p, C.c_size_t, C.c_size_t)


def sig(name, res, *args):
    f = getattr(lib, name)
    f.restype = res
    f.argtypes = list(args)


sig("rg_version", C.c_int32)
sig("rg_status_string", C.c_char_p, C.c_int32)
sig("rg_world_create", C.c_int32, C.POINTER(World))
sig("rg_world_create_with_allocator", C.c_int32, ALLOC, C.c_void_p, C.POINTER(World))
sig("rg_world_destroy", None, World)
sig("rg_world_set_gravity", C.c_int32, World, Vec2)
sig("rg_world_set_wind", C.c_int32, World, Vec2)
sig("rg_world_set_integrator", C.c_int32, World, C.c_int32)
sig("rg_world_step", C.c_int32, World, REAL)
sig("rg_world_set_fixed_step", C.c_int32, World, REAL, C.c_int32)
sig("rg_world_advance", C.c_int32, World, REAL, C.POINTER(C.c_int32))
sig("rg_world_get_alpha", C.c_int32, World, C.POINTER(REAL))
sig("rg_world_body_count", C.c_int32, World)
sig("rg_body_create", C.c_int32, World, C.c_int32, REAL, Vec2, C.POINTER(Body))
sig("rg_body_destroy", C.c_int32, World, Body)
sig("rg_body_is_valid", C.c_int32, World, Body)
sig("rg_body_get_position", C.c_int32, World, Body, C.POINTER(Vec2))
sig("rg_body_set_position", C.c_int32, World, Body, Vec2)
sig("rg_body_get_velocity", C.c_int32, World, Body, C.POINTER(Vec2))
sig("rg_body_set_velocity", C.c_int32, World, Body, Vec2)
sig("rg_body_apply_force", C.c_int32, World, Body, Vec2)
sig("rg_body_apply_impulse", C.c_int32, World, Body, Vec2)
sig("rg_body_set_drag", C.c_int32, World, Body, REAL, REAL)
sig("rg_body_set_surface_friction", C.c_int32, World, Body, REAL, REAL)
sig("rg_body_set_speed_limits", C.c_int32, World, Body, REAL, REAL)
sig("rg_body_get_interpolated_position", C.c_int32, World, Body, C.POINTER(Vec2))
sig("rg_spring_create", C.c_int32, World, Body, Body, Vec2, REAL, REAL, REAL, C.POINTER(C.c_uint64))
sig("rg_spring_destroy", C.c_int32, World, C.c_uint64)

sig("rg_body_set_circle", C.c_int32, World, Body, REAL)
sig("rg_body_set_aabb", C.c_int32, World, Body, REAL, REAL)
sig("rg_body_set_restitution", C.c_int32, World, Body, REAL)
sig("rg_body_set_sensor", C.c_int32, World, Body, C.c_int32)
sig("rg_body_is_grounded", C.c_int32, World, Body, C.POINTER(C.c_int32))


class ContactEvent(C.Structure):
    """rg_contact_event, field for field as ABI.md declares it."""
    _fields_ = [("a", Body), ("b", Body), ("normal", Vec2), ("point", Vec2),
                ("depth", REAL), ("speed", REAL), ("kind", C.c_int32), ("sensor", C.c_int32)]


class RayHit(C.Structure):
    _fields_ = [("body", Body), ("point", Vec2), ("normal", Vec2), ("fraction", REAL),
                ("pad", C.c_int32)]


sig("rg_world_get_contact_events", C.c_int32, World, C.POINTER(ContactEvent), C.c_int32)
sig("rg_world_raycast", C.c_int32, World, Vec2, Vec2, C.c_uint32, C.POINTER(RayHit))
sig("rg_world_query_aabb", C.c_int32, World, Vec2, Vec2, C.c_uint32, C.POINTER(Body), C.c_int32)
BEGIN, END = 0, 1
LOCKED = -5
PRE_SOLVE = C.CFUNCTYPE(C.c_int32, Body, Body, Vec2, REAL, C.c_void_p)
sig("rg_world_set_pre_solve", C.c_int32, World, PRE_SOLVE, C.c_void_p)
sig("rg_body_get_shape", C.c_int32, World, Body, C.POINTER(C.c_int32), C.POINTER(Vec2))


class Contact(C.Structure):
    """rg_contact, field for field as rigid.h declares it."""
    _fields_ = [("other", Body), ("normal", Vec2), ("point", Vec2), ("separation", REAL),
                ("normal_impulse", REAL), ("tangent_impulse", REAL), ("sensor", C.c_int32)]


sig("rg_body_get_contacts", C.c_int32, World, Body, C.POINTER(Contact), C.c_int32)
sig("rg_body_set_one_way", C.c_int32, World, Body, Vec2)
sig("rg_body_move", C.c_int32, World, Body, Vec2, C.c_uint32, C.c_int32, C.POINTER(Vec2),
    C.POINTER(RayHit), C.c_int32, C.POINTER(C.c_int32))

TESTS = []


def test(fn):
    TESTS.append(fn)
    return fn


def check(cond, what):
    if not cond:
        raise AssertionError(what)


def new_world():
    w = World()
    check(lib.rg_world_create(C.byref(w)) == OK, "world create")
    return w


def body(w, kind=DYNAMIC, mass=1.0, x=0.0, y=0.0):
    b = Body()
    check(lib.rg_body_create(w, kind, mass, Vec2(x, y), C.byref(b)) == OK, "body create")
    return b


def pos(w, b):
    p = Vec2()
    check(lib.rg_body_get_position(w, b, C.byref(p)) == OK, "get position")
    return p


def vel(w, b):
    v = Vec2()
    check(lib.rg_body_get_velocity(w, b, C.byref(v)) == OK, "get velocity")
    return v


@test
def version_and_real_size_describe_the_loaded_build():
    v = lib.rg_version()
    check(v >= 100 and v % 100 < 100, "version %d" % v)
    check(lib.rg_status_string(STALE) == b"stale or invalid handle", "status string")
    check(lib.rg_status_string(12345) is not None, "unknown status has a string")


@test
def free_fall_matches_semi_implicit_euler_closed_form():
    # y_n = -g h^2 n (n + 1) / 2 for semi-implicit Euler from rest
    w = new_world()
    lib.rg_world_set_gravity(w, Vec2(0, -9.81))
    b = body(w)
    h, n = 1.0 / 60, 60
    for _ in range(n):
        check(lib.rg_world_step(w, h) == OK, "step")
    y = pos(w, b).y
    exact = -9.81 * h * h * n * (n + 1) / 2
    check(abs(y - exact) <= n * 8 * EPS * abs(exact), "y = %r, expected %r" % (y, exact))
    lib.rg_world_destroy(w)


@test
def bad_input_returns_status_and_changes_nothing():
    w = new_world()
    b = body(w, x=1, y=2)
    check(lib.rg_body_set_position(w, b, Vec2(float("nan"), 0)) == INVALID, "NaN position")
    check(lib.rg_body_set_velocity(w, b, Vec2(0, float("inf"))) == INVALID, "inf velocity")
    check(lib.rg_body_apply_force(None, b, Vec2(1, 1)) == INVALID, "NULL world")
    check(lib.rg_body_get_position(w, b, None) == INVALID, "NULL out")
    check(lib.rg_world_step(w, 0) == INVALID, "dt = 0")
    check(lib.rg_world_step(w, -1) == INVALID, "dt < 0")
    check(lib.rg_body_create(w, 7, 1, Vec2(0, 0), C.byref(Body())) == INVALID, "bad type")
    check(lib.rg_body_create(w, DYNAMIC, -1, Vec2(0, 0), C.byref(Body())) == INVALID, "neg mass")
    check(lib.rg_body_set_drag(w, b, -1, 0) == INVALID, "negative drag")
    p = pos(w, b)
    check((p.x, p.y) == (1, 2), "position unchanged")
    check(lib.rg_world_body_count(w) == 1, "count unchanged")
    lib.rg_world_destroy(w)


@test
def stale_forged_and_foreign_handles_are_rejected():
    w, other = new_world(), new_world()
    b, f = body(w), body(other)
    check(lib.rg_body_destroy(w, b) == OK, "destroy")
    for h in (b, Body(0), f, Body(2**64 - 1), Body(b.value + (1 << 24))):
        check(lib.rg_body_is_valid(w, h) == 0, "valid %x" % h.value)
        check(lib.rg_body_get_position(w, h, C.byref(Vec2())) == STALE, "stale %x" % h.value)
    check(lib.rg_body_destroy(w, b) == STALE, "double destroy")
    lib.rg_world_destroy(other)
    lib.rg_world_destroy(w)


@test
def springs_and_friction_work_through_the_ffi():
    w = new_world()
    a = body(w, x=1)
    s = C.c_uint64()
    # omega = 2 rad/s oscillator; RK4 at omega*dt = 0.02 is accurate to ~1e-9 over a period
    lib.rg_world_set_integrator(w, 3)
    check(lib.rg_spring_create(w, a, 0, Vec2(0, 0), 0, 4, 0, C.byref(s)) == OK, "spring")
    n = int(round(math.pi / 0.01))  # half a period: x goes 1 -> -1
    for _ in range(n):
        lib.rg_world_step(w, 0.01)
    x = pos(w, a).x
    check(abs(x - math.cos(2 * n * 0.01)) < 1e-5 + n * 64 * EPS, "x = %r" % x)
    check(lib.rg_spring_destroy(w, s) == OK and lib.rg_spring_destroy(w, s) == STALE, "spring destroy")
    slider = body(w)
    lib.rg_body_set_velocity(w, slider, Vec2(2, 0))
    lib.rg_body_set_surface_friction(w, slider, 0.5, 9.81)
    for _ in range(120):
        lib.rg_world_step(w, 1.0 / 60)
    v = vel(w, slider)
    check(v.x == 0 and v.y == 0, "friction leaves it at exactly zero")
    lib.rg_world_destroy(w)


@test
def accumulator_and_interpolation_through_the_ffi():
    w = new_world()
    b = body(w)
    lib.rg_body_set_velocity(w, b, Vec2(1, 0))
    lib.rg_world_set_fixed_step(w, 0.25, 8)
    steps = C.c_int32(-1)
    check(lib.rg_world_advance(w, 0.625, C.byref(steps)) == OK and steps.value == 2, "two steps")
    alpha = REAL()
    lib.rg_world_get_alpha(w, C.byref(alpha))
    check(abs(alpha.value - 0.5) < 8 * EPS, "alpha %r" % alpha.value)
    ip = Vec2()
    lib.rg_body_get_interpolated_position(w, b, C.byref(ip))
    check(abs(ip.x - 0.375) < 8 * EPS, "interpolated %r" % ip.x)
    lib.rg_world_destroy(w)


@test
def a_python_allocator_sees_every_block_freed():
    live = {}

    @ALLOC
    def alloc(user, ptr, old, new):
        if new == 0:
            if ptr:
                live.pop(ptr)
            return None
        buf = C.create_string_buffer(new)
        if ptr:
            C.memmove(buf, ptr, min(old, new))
            live.pop(ptr)
        addr = C.addressof(buf)
        live[addr] = buf
        return addr

    w = World()
    check(lib.rg_world_create_with_allocator(alloc, None, C.byref(w)) == OK, "create")
    for i in range(500):
        body(w, x=i)
    lib.rg_world_set_gravity(w, Vec2(0, -1))
    lib.rg_world_step(w, 0.1)
    check(len(live) > 0, "allocations went through Python")
    lib.rg_world_destroy(w)
    check(len(live) == 0, "%d blocks leaked" % len(live))


@test
def contact_events_read_through_ctypes():
    # A ball dropped on a static floor: one begin event when it lands, with a unit normal
    # from a to b, the landing speed sqrt(2 g h) to the step's error, and the pair ordered
    # a < b; a sensor above reports begin and end as the ball passes and never pushes it.
    w = new_world()
    lib.rg_world_set_gravity(w, Vec2(0, -10))
    floor = body(w, STATIC, 0, 0, -0.5)
    check(lib.rg_body_set_aabb(w, floor, 10, 0.5) == OK, "floor shape")
    gate = body(w, STATIC, 0, 0, 3)
    lib.rg_body_set_aabb(w, gate, 2, 0.25)
    lib.rg_body_set_sensor(w, gate, 1)
    ball = body(w, DYNAMIC, 1, 0, 5)
    check(lib.rg_body_set_circle(w, ball, 0.5) == OK, "ball shape")
    check(lib.rg_body_set_circle(w, ball, -1) == INVALID, "negative radius")
    check(lib.rg_world_get_contact_events(w, None, 0) == 0, "no events before a step")
    events, h = [], 1.0 / 120
    for _ in range(240):
        lib.rg_world_step(w, h)
        n = lib.rg_world_get_contact_events(w, None, 0)
        buf = (ContactEvent * max(n, 1))()
        check(lib.rg_world_get_contact_events(w, buf, n) == n, "count is stable")
        events.extend(buf[i] for i in range(n))
    solid = [e for e in events if not e.sensor]
    sensed = [e for e in events if e.sensor]
    check(len(solid) >= 1 and solid[0].kind == BEGIN, "the ball lands: %d events" % len(solid))
    e = solid[0]
    check(e.a < e.b, "a < b")
    check(abs(math.hypot(e.normal.x, e.normal.y) - 1) < 1e-5, "unit normal")
    # The begin step is within one step of touching (speed off by at most g h), and
    # semi-implicit Euler's speed after a drop d differs from sqrt(2 g d) by at most g h / 2
    # (v_n = n g h while d_n = g h^2 n (n + 1) / 2), so |speed - sqrt(2 g 4.5)| <= 2 g h.
    check(abs(e.speed - math.sqrt(2 * 10 * 4.5)) <= 2 * 10 * h, "landing speed %r" % e.speed)
    check([x.kind for x in sensed] == [BEGIN, END], "sensor begin/end: %r" % [x.kind for x in sensed])
    g = C.c_int32(0)
    check(lib.rg_body_is_grounded(w, ball, C.byref(g)) == OK and g.value == 1, "grounded")
    hit = RayHit()
    check(lib.rg_world_raycast(w, Vec2(-5, 10), Vec2(0, -20), 0xFFFFFFFF, C.byref(hit)) == 1, "ray hits")
    check(hit.body == floor.value and abs(hit.point.y) < 1e-4, "ray hits the floor top at y = 0")
    check(abs(hit.fraction - 0.5) < 1e-5 and abs(hit.normal.y - 1) < 1e-6, "fraction and normal")
    out = (Body * 4)()
    n = lib.rg_world_query_aabb(w, Vec2(-1, -1), Vec2(1, 1), 0xFFFFFFFF, out, 4)
    check(n == 2 and set(out[i] for i in range(n)) == {floor.value, ball.value}, "query %d" % n)
    lib.rg_world_destroy(w)


@test
def one_advance_of_several_steps_reports_every_steps_events():
    # A slow frame: one advance takes four 1/60 s steps while a ball (r 0.1, 6 m/s, 0.1 m a
    # step) crosses a 4 cm sensor whose near face is 8 cm ahead: it enters in the first
    # step and leaves in the fourth, and both events are read after the advance, in order.
    w = new_world()
    gate = body(w, STATIC, 0, 0, 0)
    lib.rg_body_set_aabb(w, gate, 0.02, 1)
    lib.rg_body_set_sensor(w, gate, 1)
    ball = body(w, DYNAMIC, 1, -0.2, 0)
    lib.rg_body_set_circle(w, ball, 0.1)
    lib.rg_body_set_velocity(w, ball, Vec2(6, 0))
    lib.rg_world_set_fixed_step(w, 1.0 / 60, 8)
    steps = C.c_int32(-1)
    check(lib.rg_world_advance(w, 4.5 / 60, C.byref(steps)) == OK and steps.value == 4, "four steps")
    n = lib.rg_world_get_contact_events(w, None, 0)
    buf = (ContactEvent * 4)()
    check(n == 2 and lib.rg_world_get_contact_events(w, buf, 4) == 2, "two events, got %d" % n)
    check([buf[0].kind, buf[1].kind] == [BEGIN, END], "begin then end")
    check(all(e.sensor == 1 and {e.a, e.b} == {gate.value, ball.value} for e in buf[:2]), "the pair")
    lib.rg_world_destroy(w)


@test
def a_python_pre_solve_callback_skips_pairs_inside_a_locked_world():
    w = new_world()
    lib.rg_world_set_gravity(w, Vec2(0, -10))
    floor = body(w, STATIC, 0, 0, -0.5)
    lib.rg_body_set_aabb(w, floor, 10, 0.5)
    ghost = body(w, DYNAMIC, 1, 0, 1)
    lib.rg_body_set_circle(w, ghost, 0.25)
    solid = body(w, DYNAMIC, 1, 3, 1)
    lib.rg_body_set_circle(w, solid, 0.25)
    seen = {"calls": 0, "locked": True, "getter": True, "order": True}

    def hook(a, b, normal, separation, user):
        seen["calls"] += 1
        seen["order"] &= a < b and abs(normal.x ** 2 + normal.y ** 2 - 1) < 1e-5
        seen["locked"] &= lib.rg_world_set_gravity(w, Vec2(0, 5)) == LOCKED
        seen["locked"] &= lib.rg_body_set_position(w, a, Vec2(9, 9)) == LOCKED
        kind = C.c_int32()
        seen["getter"] &= lib.rg_body_get_shape(w, b, C.byref(kind), None) == OK
        return 0 if ghost.value in (a, b) else 1

    cb = PRE_SOLVE(hook)  # kept alive for as long as the world may call it
    check(lib.rg_world_set_pre_solve(w, cb, None) == OK, "set hook")
    for _ in range(90):
        check(lib.rg_world_step(w, 1.0 / 60) == OK, "step")
    check(seen["calls"] > 0 and seen["locked"] and seen["getter"] and seen["order"], str(seen))
    check(pos(w, ghost).y < -1, "the skipped ball fell through the floor")
    check(abs(pos(w, solid).y - 0.25) < 0.005, "the other one rests on it")
    contacts = (Contact * 2)()
    n = lib.rg_body_get_contacts(w, solid, contacts, 2)
    check(n == 1 and contacts[0].other == floor.value, "one contact with the floor")
    j = 1 * 10 / 60.0
    check(abs(contacts[0].normal_impulse - j) < 1e-3 * j, "normal impulse m g dt: %g" % contacts[0].normal_impulse)
    check(lib.rg_world_set_pre_solve(w, PRE_SOLVE(), None) == OK, "NULL removes the hook")
    lib.rg_world_destroy(w)


@test
def the_mover_slides_into_a_corner_through_ctypes():
    w = new_world()
    floor = body(w, STATIC, 0, 0, -0.5)
    lib.rg_body_set_aabb(w, floor, 10, 0.5)
    wall = body(w, STATIC, 0, 5.5, 2)
    lib.rg_body_set_aabb(w, wall, 0.5, 2)
    m = body(w, KINEMATIC, 0, 0, 1)
    lib.rg_body_set_aabb(w, m, 0.25, 0.25)
    end, hits, n = Vec2(), (RayHit * 4)(), C.c_int32()
    check(lib.rg_body_move(w, m, Vec2(100, -10), 0xFFFFFFFF, 0, C.byref(end), hits, 4, C.byref(n)) == OK, "move")
    check(abs(end.x - 4.75) < 1e-5 and abs(end.y - 0.25) < 1e-5, "flush in the corner: %g %g" % (end.x, end.y))
    # at x = 4.75 the path is still 0.48 m high: the wall first, then down along it to the floor
    check(n.value == 2 and hits[0].body == wall.value and hits[1].body == floor.value, "wall then floor")
    lib.rg_world_destroy(w)


def main():
    passed = failed = 0
    for t in TESTS:
        try:
            t()
            print("ok     " + t.__name__)
            passed += 1
        except Exception as e:  # report every failure, keep going
            print("FAILED %s: %s" % (t.__name__, e))
            failed += 1
    print("%d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
