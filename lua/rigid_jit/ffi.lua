-- rigid_jit/ffi.lua: loads the library for the LuaJIT binding and declares its C API.
-- Returns { C = the library namespace, V = the vector calls, R = the by-value getters that
-- compile (below), real_size = 4 | 8, abi }.
--
-- The library is the file named by the environment variable RIGID_LIBRARY, else librigid
-- by the system's search (librigid.so, then librigid.so.0).  rg_real is declared float or
-- double by the size the library reports, so both builds load.
--
-- A C function that takes rg_vec2 by value cannot be compiled into a trace (LuaJIT leaves
-- aggregates by value to the interpreter, some 400 ns a call).  On x64 System V and arm64
-- the calling convention passes that struct exactly as scalars would go (x64: a float pair
-- in one SSE register, as a double with the same 64 bits; a double pair in two; arm64: a
-- pair in two FP registers), so V.name(..., x, y, ...) calls the same symbol through a
-- declaration with scalar parameters, made below from the header's own.  Elsewhere, or
-- with RIGID_JIT_ABI=exact, V.name fills an rg_vec2 and calls the header's declaration.
local ffi = require "ffi"
local bit = require "bit"

-- The declarations of include/rigid.h without rg_real, as tools/ffi_cdef.lua makes them:
-- `make ffi-cdef` rewrites this block, and `make test` fails when it differs.
local RIGID_H = [[
typedef struct rg_vec2 {
  rg_real x, y;
} rg_vec2;
typedef struct rg_world rg_world;
typedef uint64_t rg_body;
typedef int32_t rg_status;
enum {
  RG_OK = 0,
  RG_ERR_INVALID_ARGUMENT = -1,
  RG_ERR_STALE_HANDLE = -2,
  RG_ERR_OUT_OF_MEMORY = -3,
  RG_ERR_CAPACITY = -4,
  RG_ERR_LOCKED = -5
};
enum {
  RG_INTEGRATOR_EXPLICIT_EULER = 0,
  RG_INTEGRATOR_SEMI_IMPLICIT_EULER = 1,
  RG_INTEGRATOR_VELOCITY_VERLET = 2,
  RG_INTEGRATOR_RK4 = 3
};
enum {
  RG_BODY_STATIC = 0,
  RG_BODY_KINEMATIC = 1,
  RG_BODY_DYNAMIC = 2
};
enum {
  RG_MAX_BODIES = 16777215,
  RG_MAX_SPRINGS = 16777215
};
const char *rg_status_string(rg_status s);
const char *rg_world_last_error(const rg_world *world);
int32_t rg_version(void);
int32_t rg_real_size(void);
typedef void *(*rg_alloc_fn)(void *user, void *ptr, size_t old_size, size_t new_size);
rg_status rg_world_create(rg_world **out_world);
rg_status rg_world_create_with_allocator(rg_alloc_fn alloc, void *user, rg_world **out_world);
void rg_world_destroy(rg_world *world);
rg_status rg_world_set_gravity(rg_world *world, rg_vec2 gravity);
rg_status rg_world_get_gravity(const rg_world *world, rg_vec2 *out_gravity);
rg_status rg_world_set_wind(rg_world *world, rg_vec2 force);
rg_status rg_world_get_wind(const rg_world *world, rg_vec2 *out_force);
rg_status rg_world_set_integrator(rg_world *world, int32_t integrator);
rg_status rg_world_get_integrator(const rg_world *world, int32_t *out_integrator);
rg_status rg_world_step(rg_world *world, rg_real dt);
rg_status rg_world_set_fixed_step(rg_world *world, rg_real dt, int32_t max_steps_per_advance);
rg_status rg_world_get_fixed_step(const rg_world *world, rg_real *out_dt, int32_t *out_max_steps);
rg_status rg_world_advance(rg_world *world, rg_real frame_time, int32_t *out_steps);
rg_status rg_world_get_alpha(const rg_world *world, rg_real *out_alpha);
rg_status rg_body_get_interpolated_position(const rg_world *world, rg_body body, rg_vec2 *out);
int32_t rg_world_get_stopped(const rg_world *world, rg_body *out, int32_t capacity);
int32_t rg_world_body_count(const rg_world *world);
int32_t rg_world_spring_count(const rg_world *world);
rg_status rg_body_create(rg_world *world, int32_t type, rg_real mass, rg_vec2 position, rg_body *out_body);
rg_status rg_body_destroy(rg_world *world, rg_body body);
int32_t rg_body_is_valid(const rg_world *world, rg_body body);
rg_status rg_body_get_type(const rg_world *world, rg_body body, int32_t *out_type);
rg_status rg_body_get_mass(const rg_world *world, rg_body body, rg_real *out_mass);
rg_status rg_body_set_mass(rg_world *world, rg_body body, rg_real mass);
rg_status rg_body_get_position(const rg_world *world, rg_body body, rg_vec2 *out);
rg_status rg_body_set_position(rg_world *world, rg_body body, rg_vec2 position);
rg_status rg_body_get_velocity(const rg_world *world, rg_body body, rg_vec2 *out);
rg_status rg_body_set_velocity(rg_world *world, rg_body body, rg_vec2 velocity);
rg_vec2 rg_body_position(const rg_world *world, rg_body body);
rg_vec2 rg_body_velocity(const rg_world *world, rg_body body);
rg_status rg_body_get_acceleration(const rg_world *world, rg_body body, rg_vec2 *out);
rg_status rg_body_apply_force(rg_world *world, rg_body body, rg_vec2 force);
rg_status rg_body_apply_impulse(rg_world *world, rg_body body, rg_vec2 impulse);
rg_status rg_body_set_gravity_scale(rg_world *world, rg_body body, rg_real scale);
rg_status rg_body_get_gravity_scale(const rg_world *world, rg_body body, rg_real *out_scale);
rg_status rg_body_set_drag(rg_world *world, rg_body body, rg_real linear, rg_real quadratic);
rg_status rg_body_get_drag(const rg_world *world, rg_body body, rg_real *out_linear, rg_real *out_quadratic);
rg_status rg_body_set_surface_friction(rg_world *world, rg_body body, rg_real mu, rg_real normal_force);
rg_status rg_body_set_speed_limits(rg_world *world, rg_body body, rg_real min_speed, rg_real max_speed);
rg_status rg_body_get_speed_limits(const rg_world *world, rg_body body, rg_real *out_min_speed, rg_real *out_max_speed);
rg_status rg_body_set_user_data(rg_world *world, rg_body body, uint64_t user_data);
rg_status rg_body_get_user_data(const rg_world *world, rg_body body, uint64_t *out);
rg_status rg_spring_create(rg_world *world, rg_body a, rg_body b, rg_vec2 anchor, rg_real rest_length, rg_real stiffness, rg_real damping, uint64_t *out_spring);
rg_status rg_spring_destroy(rg_world *world, uint64_t spring);
int32_t rg_spring_is_valid(const rg_world *world, uint64_t spring);
enum {
  RG_SHAPE_NONE = 0,
  RG_SHAPE_CIRCLE = 1,
  RG_SHAPE_AABB = 2
};
rg_status rg_body_set_circle(rg_world *world, rg_body body, rg_real radius);
rg_status rg_body_set_aabb(rg_world *world, rg_body body, rg_real half_width, rg_real half_height);
rg_status rg_body_clear_shape(rg_world *world, rg_body body);
rg_status rg_body_get_shape(const rg_world *world, rg_body body, int32_t *out_kind, rg_vec2 *out_half_extents);
rg_status rg_body_set_restitution(rg_world *world, rg_body body, rg_real restitution);
rg_status rg_body_get_restitution(const rg_world *world, rg_body body, rg_real *out);
rg_status rg_body_set_friction(rg_world *world, rg_body body, rg_real mu);
rg_status rg_body_get_friction(const rg_world *world, rg_body body, rg_real *out);
rg_status rg_body_set_sensor(rg_world *world, rg_body body, int32_t is_sensor);
rg_status rg_body_is_sensor(const rg_world *world, rg_body body, int32_t *out_is_sensor);
rg_status rg_body_set_filter(rg_world *world, rg_body body, uint32_t category, uint32_t mask);
rg_status rg_body_get_filter(const rg_world *world, rg_body body, uint32_t *out_category, uint32_t *out_mask);
rg_status rg_body_is_grounded(const rg_world *world, rg_body body, int32_t *out_grounded);
rg_status rg_world_set_sleeping(rg_world *world, int32_t enabled);
rg_status rg_world_get_sleeping(const rg_world *world, int32_t *out_enabled);
rg_status rg_world_set_sleep_thresholds(rg_world *world, rg_real speed, rg_real time);
rg_status rg_world_get_sleep_thresholds(const rg_world *world, rg_real *out_speed, rg_real *out_time);
rg_status rg_body_is_awake(const rg_world *world, rg_body body, int32_t *out_awake);
rg_status rg_body_wake(rg_world *world, rg_body body);
int32_t rg_world_awake_body_count(const rg_world *world);
rg_status rg_world_set_solver_iterations(rg_world *world, int32_t velocity, int32_t position);
rg_status rg_world_get_solver_iterations(const rg_world *world, int32_t *out_velocity, int32_t *out_position);
rg_status rg_world_set_contact_tuning(rg_world *world, rg_real slop, rg_real bias_rate, rg_real max_push, rg_real restitution_threshold);
rg_status rg_world_get_contact_tuning(const rg_world *world, rg_real *out_slop, rg_real *out_bias_rate, rg_real *out_max_push, rg_real *out_restitution_threshold);
rg_status rg_world_set_continuous(rg_world *world, int32_t enabled);
rg_status rg_world_get_continuous(const rg_world *world, int32_t *out_enabled);
int32_t rg_world_touching_count(const rg_world *world);
enum {
  RG_CONTACT_BEGIN = 0,
  RG_CONTACT_END = 1
};
typedef struct rg_contact_event {
  rg_body a, b;
  rg_vec2 normal;
  rg_vec2 point;
  rg_real depth;
  rg_real speed;
  int32_t kind;
  int32_t sensor;
} rg_contact_event;
int32_t rg_world_get_contact_events(const rg_world *world, rg_contact_event *out, int32_t capacity);
typedef struct rg_ray_hit {
  rg_body body;
  rg_vec2 point;
  rg_vec2 normal;
  rg_real fraction;
  int32_t pad;
} rg_ray_hit;
int32_t rg_world_raycast(const rg_world *world, rg_vec2 origin, rg_vec2 translation, uint32_t mask, rg_ray_hit *out_hit);
int32_t rg_world_query_aabb(const rg_world *world, rg_vec2 lower, rg_vec2 upper, uint32_t mask, rg_body *out, int32_t capacity);
rg_status rg_body_set_one_way(rg_world *world, rg_body body, rg_vec2 normal);
rg_status rg_body_get_one_way(const rg_world *world, rg_body body, rg_vec2 *out_normal);
rg_status rg_body_pass_through(rg_world *world, rg_body body, rg_body other);
typedef int32_t rg_pre_solve_fn(rg_body a, rg_body b, rg_vec2 normal, rg_real separation, void *user);
rg_status rg_world_set_pre_solve(rg_world *world, rg_pre_solve_fn *fn, void *user);
typedef struct rg_contact {
  rg_body other;
  rg_vec2 normal;
  rg_vec2 point;
  rg_real separation;
  rg_real normal_impulse;
  rg_real tangent_impulse;
  int32_t sensor;
} rg_contact;
int32_t rg_body_get_contacts(const rg_world *world, rg_body body, rg_contact *out, int32_t capacity);
int32_t rg_world_raycast_all(const rg_world *world, rg_vec2 origin, rg_vec2 translation, uint32_t mask, rg_ray_hit *out, int32_t capacity);
int32_t rg_world_query_point(const rg_world *world, rg_vec2 point, uint32_t mask, rg_body *out, int32_t capacity);
int32_t rg_world_cast_shape(const rg_world *world, int32_t shape, rg_vec2 size, rg_vec2 origin, rg_vec2 translation, uint32_t mask, rg_ray_hit *out_hit);
rg_status rg_body_move(rg_world *world, rg_body body, rg_vec2 target, uint32_t mask, int32_t response, rg_vec2 *out_position, rg_ray_hit *out_hits, int32_t capacity, int32_t *out_count);
rg_status rg_world_save(const rg_world *world, void *out, size_t capacity, size_t *out_size);
rg_status rg_world_restore(rg_world *world, const void *data, size_t size);
rg_status rg_world_hash(const rg_world *world, uint64_t *out_hash);
enum {
  RG_MAX_SLOTS = 64
};
rg_status rg_world_save_slot(rg_world *world, int32_t slot);
rg_status rg_world_restore_slot(rg_world *world, int32_t slot);
rg_status rg_world_drop_slot(rg_world *world, int32_t slot);
typedef struct rg_debug_draw {
  void (*circle)(rg_body body, rg_vec2 center, rg_real radius, uint32_t rgba, void *user);
  void (*box)(rg_body body, rg_vec2 lower, rg_vec2 upper, uint32_t rgba, void *user);
  void (*segment)(rg_vec2 a, rg_vec2 b, uint32_t rgba, void *user);
  void (*point)(rg_vec2 p, uint32_t rgba, void *user);
  uint32_t flags;
  void *user;
} rg_debug_draw;
rg_status rg_world_draw(const rg_world *world, const rg_debug_draw *draw);
typedef void rg_task_fn(int32_t begin, int32_t end, int32_t worker, void *context);
typedef struct rg_task_system {
  int32_t workers;
  void *(*enqueue)(rg_task_fn *fn, int32_t count, int32_t min_range, void *context, void *user);
  void (*finish)(void *task, void *user);
  void *user;
} rg_task_system;
rg_status rg_world_set_task_system(rg_world *world, const rg_task_system *tasks);
typedef struct rg_thread_pool rg_thread_pool;
rg_status rg_thread_pool_create(int32_t threads, rg_thread_pool **out_pool);
void rg_thread_pool_destroy(rg_thread_pool *pool);
rg_status rg_thread_pool_task_system(rg_thread_pool *pool, rg_task_system *out);
static const int32_t RG_VERSION_MAJOR = 0;
static const int32_t RG_VERSION_MINOR = 1;
static const int32_t RG_VERSION_PATCH = 0;
static const int32_t RG_MOVE_SLIDE = 0;
static const int32_t RG_MOVE_TOUCH = 1;
static const int32_t RG_MOVE_CROSS = 2;
static const uint32_t RG_DRAW_SHAPES = 1u;
static const uint32_t RG_DRAW_CONTACTS = 2u;
static const uint32_t RG_DRAW_VELOCITIES = 4u;
static const uint32_t RG_DRAW_BOUNDS = 8u;
static const uint32_t RG_DRAW_SPRINGS = 16u;
static const uint32_t RG_COLOR_STATIC = 0x8C8C8CFFu;
static const uint32_t RG_COLOR_KINEMATIC = 0x3C78DCFFu;
static const uint32_t RG_COLOR_AWAKE = 0xE6782DFFu;
static const uint32_t RG_COLOR_SLEEPING = 0x8C64B4FFu;
static const uint32_t RG_COLOR_SENSOR = 0xDCB41E80u;
static const uint32_t RG_COLOR_CONTACT = 0xDC2828FFu;
static const uint32_t RG_COLOR_VELOCITY = 0x28A03CFFu;
static const uint32_t RG_COLOR_BOUNDS = 0x32B4B4FFu;
static const uint32_t RG_COLOR_SPRING = 0xB43CB4FFu;
static const int32_t RG_MAX_WORKERS = 64;
]]

local C
do
  local path = os.getenv("RIGID_LIBRARY")
  local ok, lib = pcall(ffi.load, path or "rigid")
  if not ok and not path then ok, lib = pcall(ffi.load, "librigid.so.0") end
  if not ok then
    error("rigid_jit: cannot load " .. (path or "librigid") .. ": " .. tostring(lib), 3)
  end
  C = lib
end

ffi.cdef [[int32_t rigid_jit_real_size(void) __asm__("rg_real_size");]]
local REAL = C.rigid_jit_real_size()
if REAL ~= 4 and REAL ~= 8 then
  error("rigid_jit: the library reports an rg_real of " .. REAL .. " bytes", 3)
end
if pcall(ffi.typeof, "rg_real") then          -- declared by an earlier load
  if ffi.sizeof("rg_real") ~= REAL then
    error("rigid_jit: rg_real is declared with " .. ffi.sizeof("rg_real") ..
          " bytes already; one process cannot load both builds", 3)
  end
else
  ffi.cdef("typedef " .. (REAL == 4 and "float" or "double") .. " rg_real;\n" .. RIGID_H .. [[
    struct rigid_jit_world { rg_world *w; };
    union rigid_jit_f32 { float f; uint32_t u; };
    union rigid_jit_f64 { uint64_t u; double d; };
    union rigid_jit_pair { double d; float f[2]; };
  ]])
end

local abi = os.getenv("RIGID_JIT_ABI")
if not abi then
  if jit.arch == "x64" and jit.os ~= "Windows" then abi = REAL == 4 and "packed" or "split"
  elseif jit.arch == "arm64" then abi = "split"
  else abi = "exact" end
end
assert(abi == "packed" or abi == "split" or abi == "exact", "RIGID_JIT_ABI: packed, split or exact")

-- The 64 bits of a float pair as a double.  Each float goes through a 4-byte store and
-- load and the pair through one 8-byte store and load (two 4-byte stores read back as one
-- 8-byte load would stall store forwarding).
local F, P = ffi.new("union rigid_jit_f32[2]"), ffi.new("union rigid_jit_f64[1]")
local U64 = ffi.typeof("uint64_t")
local function pack(x, y)
  F[0].f = x
  F[1].f = y
  P[0].u = bit.bor(U64(F[0].u), bit.lshift(U64(F[1].u), 32))
  return P[0].d
end

-- One rg_vec2 per vector parameter of a call (S is sized below, for the call with most).
local S
local function vec(i, x, y)
  S[i].x, S[i].y = x, y
  return S[i]
end

-- V[name] for every function of the header with an rg_vec2 parameter by value.
local V, most = {}, 0
for ret, name, params in RIGID_H:gmatch("\n([%w_ ]-[%w_]%s*%**)%s*(rg_[%w_]+)%(([^)]*)%);") do
  if params:find("rg_vec2 %w") then
    local decl, lua_args, c_args, k = {}, {}, {}, 0
    for p in params:gmatch("[^,]+") do
      local n = #lua_args + 1
      if p:find("^%s*rg_vec2 %w") then
        lua_args[n], lua_args[n + 1] = "a" .. n, "a" .. (n + 1)
        decl[#decl + 1] = abi == "packed" and "double" or "rg_real, rg_real"
        c_args[#c_args + 1] = abi == "packed" and ("pack(a%d, a%d)"):format(n, n + 1)
                              or abi == "split" and ("a%d, a%d"):format(n, n + 1)
                              or ("vec(%d, a%d, a%d)"):format(k, n, n + 1)
        k = k + 1
      else
        lua_args[n] = "a" .. n
        decl[#decl + 1] = p
        c_args[#c_args + 1] = "a" .. n
      end
    end
    local fn = name
    if abi ~= "exact" then
      fn = "rigid_jit_" .. name
      ffi.cdef(("%s %s(%s) __asm__(\"%s\");"):format(ret, fn, table.concat(decl, ","), name))
    end
    local src = ("local C, pack, vec = ...\nreturn function(%s) return C.%s(%s) end")
                :format(table.concat(lua_args, ", "), fn, table.concat(c_args, ", "))
    V[name] = assert(loadstring(src, "=rigid_jit " .. name))(C, pack, vec)
    most = math.max(most, k)
  end
end
S = ffi.new("rg_vec2[?]", most)

-- R.name(world, body) -> x, y for the header's getters that return an rg_vec2 by value
-- (rg_body_position, rg_body_velocity): NaN, NaN when the call failed.  Packed, the float
-- pair comes back in one SSE register; declared as a double, the call compiles, and the
-- double's 8 bytes are read back as two floats through memory (a load of another type than
-- the store, which LuaJIT does not forward).  Elsewhere LuaJIT would leave the aggregate
-- return to the interpreter, so R is empty and the binding uses the out-pointer getters.
local R = {}
if abi == "packed" then
  local D = ffi.new("union rigid_jit_pair[1]")
  for name, params in RIGID_H:gmatch("\nrg_vec2 (rg_[%w_]+)%(([^)]*)%);") do
    local fn = "rigid_jit_" .. name
    ffi.cdef(("double %s(%s) __asm__(\"%s\");"):format(fn, params, name))
    local call = C[fn]
    R[name] = function(w, b)
      D[0].d = call(w, b)
      return D[0].f[0], D[0].f[1]
    end
  end
end

return { C = C, V = V, R = R, real_size = REAL, abi = abi }
