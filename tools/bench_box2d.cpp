// bench_box2d.cpp: the benchmark's Box2D 2.4 engine, through Debian's libbox2d-dev only.
//
// Bodies have fixed rotation (rigid does not rotate); the solver runs Box2D's default 8
// velocity and 3 position iterations unless the run sets others; sleeping as the run says
// (Box2D's thresholds: 0.01 m/s for 0.5 s).  Damping per unit mass is
// Box2D's linearDamping, which is mass-independent: v *= 1 / (1 + h * c).  A body without
// fixtures is given its mass with SetMassData (2.4 leaves it at 0, which gravity skips).
#include <box2d/box2d.h>

#include <cmath>
#include <cstdio>
#include <new>
#include <vector>

#include "bench.h"

namespace {

struct Box2dCtx {
    b2World world;
    std::vector<b2Body *> dyn;
    int32 velocity_iterations = 8, position_iterations = 3;
    explicit Box2dCtx(const b2Vec2 &g) : world(g) {}
};

void box2d_destroy(void *p) { delete static_cast<Box2dCtx *>(p); }

void *box2d_create(const bench_scene *s)
{
    Box2dCtx *c = new (std::nothrow) Box2dCtx(b2Vec2((float)s->gx, (float)s->gy));
    if (c == nullptr) return nullptr;
    if (s->workers > 1) {
        delete c;
        return nullptr;
    }
    c->world.SetAllowSleeping(s->sleep != 0);
    if (s->solver_set) {
        c->velocity_iterations = s->solver[0];
        c->position_iterations = s->solver[1];
    }
    c->dyn.reserve((size_t)s->ndynamic);
    for (int32_t i = 0; i < s->nbodies; i++) {
        const bench_body &bb = s->bodies[i];
        b2BodyDef bd;
        bd.type = bb.type == BENCH_DYNAMIC ? b2_dynamicBody : b2_staticBody;
        bd.position.Set((float)bb.x, (float)bb.y);
        bd.fixedRotation = true;
        if (bb.type == BENCH_DYNAMIC) {
            bd.linearVelocity.Set((float)bb.vx, (float)bb.vy);
            bd.linearDamping = (float)s->damping;
        }
        b2Body *body = c->world.CreateBody(&bd);
        if (bb.shape != BENCH_SHAPE_NONE) {
            b2CircleShape circle;
            b2PolygonShape box;
            b2FixtureDef fd;
            double area;
            if (bb.shape == BENCH_SHAPE_CIRCLE) {
                circle.m_radius = (float)bb.a;
                fd.shape = &circle;
                area = M_PI * bb.a * bb.a;
            } else {
                box.SetAsBox((float)bb.a, (float)bb.b);
                fd.shape = &box;
                area = 4 * bb.a * bb.b;
            }
            fd.density = bb.type == BENCH_DYNAMIC ? (float)(bb.mass / area) : 0.0f;
            // Box2D mixes frictions as sqrt(a*b): equal values give the pair's.
            fd.friction = (float)s->friction;
            fd.restitution = (float)s->restitution;
            fd.isSensor = bb.sensor != 0;
            body->CreateFixture(&fd);
        }
        if (bb.type == BENCH_DYNAMIC && bb.shape == BENCH_SHAPE_NONE) {
            // Without fixtures a 2.4 body keeps mass 0 and gravity never reaches it.
            b2MassData md;
            md.mass = (float)bb.mass;
            md.center.SetZero();
            md.I = 0.0f;
            body->SetMassData(&md);
        }
        if (bb.type == BENCH_DYNAMIC) c->dyn.push_back(body);
    }
    return c;
}

void box2d_step(void *p, double dt)
{
    Box2dCtx *c = static_cast<Box2dCtx *>(p);
    c->world.Step((float)dt, c->velocity_iterations, c->position_iterations);
}

void box2d_force(void *p, int32_t k, double fx, double fy)
{
    Box2dCtx *c = static_cast<Box2dCtx *>(p);
    c->dyn[(size_t)k]->ApplyForceToCenter(b2Vec2((float)fx, (float)fy), true);
}

void box2d_impulse(void *p, int32_t k, double ix, double iy)
{
    Box2dCtx *c = static_cast<Box2dCtx *>(p);
    b2Body *b = c->dyn[(size_t)k];
    b->ApplyLinearImpulseToCenter(b2Vec2((float)ix, (float)iy), true);
}

void box2d_read(void *p, float *x, float *y, float *vx, float *vy)
{
    Box2dCtx *c = static_cast<Box2dCtx *>(p);
    for (size_t k = 0; k < c->dyn.size(); k++) {
        const b2Vec2 &q = c->dyn[k]->GetPosition();
        const b2Vec2 &v = c->dyn[k]->GetLinearVelocity();
        x[k] = q.x;
        y[k] = q.y;
        vx[k] = v.x;
        vy[k] = v.y;
    }
}

size_t box2d_bytes(void *, size_t *peak)
{
    *peak = 0;
    return 0;
}

char box2d_version[32];

const char *box2d_version_string(void)
{
    std::snprintf(box2d_version, sizeof box2d_version, "Box2D %d.%d.%d", b2_version.major,
                  b2_version.minor, b2_version.revision);
    return box2d_version;
}

} // namespace

extern "C" const bench_engine bench_box2d_engine = {
    .name = "box2d", .threaded = 0, .create = box2d_create, .step = box2d_step,
    .force = box2d_force, .impulse = box2d_impulse, .read = box2d_read, .bytes = box2d_bytes,
    .destroy = box2d_destroy, .alloc_calls = nullptr, .version = box2d_version_string,
};
