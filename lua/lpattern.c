/* lpattern.c: a metered backtracking matcher for Lua 5.4 patterns (manual section 6.4.1). */
#include <ctype.h>
#include <string.h>

#include <lauxlib.h>
#include <lua.h>

#include "lpattern.h"

#define MAX_CAPTURES   32    /* as stock Lua (LUA_MAXCAPTURES) */
#define MAX_DEPTH      200   /* recursion of the matcher, as stock Lua (MAXCCALLS) */
#define CAP_UNFINISHED (-1)
#define CAP_POSITION   (-2)
#define CHARGE_BATCH   4096  /* units between calls to the meter */
/* A set ([...]) is scanned byte by byte each time an element is parsed or matched: a unit
 * per 4 bytes of it, on top of the step's unit (a 330-byte set matched lazily along a 60 kB
 * subject ran some 100 times the time its units allowed, found by fuzz_lua). */
#define SET_BYTES_PER_UNIT 4
#define SPECIALS       "^$*+?.([%-"

typedef struct mstate {
    const char *src, *src_end;
    const char *pat_end;
    lua_State *L;
    const lpattern_meter *meter;
    size_t units;            /* not yet charged */
    int depth;               /* recursion left */
    int level;               /* captures, finished or not */
    struct {
        const char *init;
        ptrdiff_t len;       /* length, CAP_UNFINISHED or CAP_POSITION */
    } cap[MAX_CAPTURES];
} mstate;

static void flush(mstate *ms)
{
    size_t u = ms->units;
    ms->units = 0;
    if (ms->meter != NULL && u > 0) ms->meter->charge(ms->L, ms->meter->ud, u);
}

static void tick(mstate *ms)
{
    if (++ms->units >= CHARGE_BATCH) flush(ms);
}

static void reset(mstate *ms)
{
    ms->level = 0;
    ms->depth = MAX_DEPTH;
}

static int uchar(char c)
{
    return (unsigned char)c;
}

/* ---------------------------------------------------------------- single characters */

static int class_matches(int c, int cl)
{
    int r;
    switch (tolower(cl)) {
    case 'a': r = isalpha(c); break;
    case 'c': r = iscntrl(c); break;
    case 'd': r = isdigit(c); break;
    case 'g': r = isgraph(c); break;
    case 'l': r = islower(c); break;
    case 'p': r = ispunct(c); break;
    case 's': r = isspace(c); break;
    case 'u': r = isupper(c); break;
    case 'w': r = isalnum(c); break;
    case 'x': r = isxdigit(c); break;
    case 'z': r = (c == 0); break;   /* deprecated, still in 5.4 */
    default: return cl == c;   /* %. is a literal . */
    }
    if (isupper(cl)) r = !r;
    return r != 0;
}

/* p points at '[', close at the matching ']'. */
static int set_matches(int c, const char *p, const char *close)
{
    int yes = 1;
    if (p[1] == '^') {
        yes = 0;
        p++;
    }
    while (++p < close) {
        if (*p == '%') {
            p++;
            if (class_matches(c, uchar(*p))) return yes;
        } else if (p[1] == '-' && p + 2 < close) {
            if (uchar(p[0]) <= c && c <= uchar(p[2])) return yes;
            p += 2;
        } else if (uchar(*p) == c) {
            return yes;
        }
    }
    return !yes;
}

/* End of the single-character class starting at p. */
static const char *class_end(mstate *ms, const char *p)
{
    const char *end = ms->pat_end;
    if (*p == '%') {
        if (p + 1 >= end) luaL_error(ms->L, "malformed pattern (ends with '%%')");
        return p + 2;
    }
    if (*p == '[') {
        const char *start = p;
        p++;
        if (p < end && *p == '^') p++;
        /* The first character of a set is never its end: "[]]" holds ']'. */
        do {
            if (p >= end) luaL_error(ms->L, "malformed pattern (missing ']')");
            if (*p++ == '%' && p < end) p++;
            if (p >= end) luaL_error(ms->L, "malformed pattern (missing ']')");
        } while (*p != ']');
        ms->units += (size_t)(p - start) / SET_BYTES_PER_UNIT;   /* the scan of a long set */
        return p + 1;
    }
    return p + 1;
}

static int single_matches(mstate *ms, const char *s, const char *p, const char *ep)
{
    int c;
    if (s >= ms->src_end) return 0;
    c = uchar(*s);
    switch (*p) {
    case '.': return 1;
    case '%': return class_matches(c, uchar(p[1]));
    case '[':
        ms->units += (size_t)(ep - p) / SET_BYTES_PER_UNIT;   /* a set is read byte by byte */
        return set_matches(c, p, ep - 1);
    default: return uchar(*p) == c;
    }
}

/* ---------------------------------------------------------------- the matcher */

static const char *do_match(mstate *ms, const char *s, const char *p);

static const char *max_expand(mstate *ms, const char *s, const char *p, const char *ep)
{
    ptrdiff_t i = 0;
    while (single_matches(ms, s + i, p, ep)) {
        i++;
        tick(ms);
    }
    /* Longest first, giving back one repetition at a time. */
    for (; i >= 0; i--) {
        const char *r = do_match(ms, s + i, ep + 1);
        if (r != NULL) return r;
    }
    return NULL;
}

static const char *min_expand(mstate *ms, const char *s, const char *p, const char *ep)
{
    for (;;) {
        const char *r = do_match(ms, s, ep + 1);
        if (r != NULL) return r;
        if (!single_matches(ms, s, p, ep)) return NULL;
        s++;
    }
}

static const char *start_capture(mstate *ms, const char *s, const char *p, ptrdiff_t what)
{
    const char *r;
    if (ms->level >= MAX_CAPTURES) luaL_error(ms->L, "too many captures");
    ms->cap[ms->level].init = s;
    ms->cap[ms->level].len = what;
    ms->level++;
    r = do_match(ms, s, p);
    if (r == NULL) ms->level--;
    return r;
}

static const char *end_capture(mstate *ms, const char *s, const char *p)
{
    const char *r;
    int l;
    for (l = ms->level - 1; l >= 0; l--)
        if (ms->cap[l].len == CAP_UNFINISHED) break;
    if (l < 0) luaL_error(ms->L, "invalid pattern capture");
    ms->cap[l].len = s - ms->cap[l].init;
    r = do_match(ms, s, p);
    if (r == NULL) ms->cap[l].len = CAP_UNFINISHED;
    return r;
}

static int capture_index(mstate *ms, int l)
{
    l -= '1';
    if (l < 0 || l >= ms->level || ms->cap[l].len == CAP_UNFINISHED)
        luaL_error(ms->L, "invalid capture index %%%d", l + 1);
    return l;
}

static const char *back_reference(mstate *ms, const char *s, int l)
{
    ptrdiff_t len;
    l = capture_index(ms, l);
    len = ms->cap[l].len;
    if (len >= 0 && ms->src_end - s >= len && memcmp(ms->cap[l].init, s, (size_t)len) == 0)
        return s + len;
    return NULL;
}

/* %bxy: a balanced run from x to y. */
static const char *balance(mstate *ms, const char *s, const char *p)
{
    int depth = 1;
    if (p + 1 >= ms->pat_end) luaL_error(ms->L, "malformed pattern (missing arguments to '%%b')");
    if (s >= ms->src_end || *s != *p) return NULL;
    while (++s < ms->src_end) {
        tick(ms);
        if (*s == p[1]) {
            if (--depth == 0) return s + 1;
        } else if (*s == *p) {
            depth++;
        }
    }
    return NULL;
}

static const char *do_match(mstate *ms, const char *s, const char *p)
{
    const char *end = ms->pat_end;
    if (ms->depth-- == 0) luaL_error(ms->L, "pattern too complex");
    for (;;) {
        const char *ep;
        tick(ms);
        if (p == end) break;                          /* whole pattern matched */
        if (*p == '(') {
            if (p + 1 < end && p[1] == ')') s = start_capture(ms, s, p + 2, CAP_POSITION);
            else s = start_capture(ms, s, p + 1, CAP_UNFINISHED);
            break;
        }
        if (*p == ')') {
            s = end_capture(ms, s, p + 1);
            break;
        }
        if (*p == '$' && p + 1 == end) {              /* anchor at the end */
            if (s != ms->src_end) s = NULL;
            break;
        }
        if (*p == '%' && p + 1 < end) {
            if (p[1] == 'b') {
                s = balance(ms, s, p + 2);
                if (s == NULL) break;
                p += 4;
                continue;
            }
            if (p[1] == 'f') {                        /* frontier */
                int prev, cur;
                p += 2;
                if (p >= end || *p != '[') luaL_error(ms->L, "missing '[' after '%%f' in pattern");
                ep = class_end(ms, p);
                prev = s == ms->src ? 0 : uchar(s[-1]);
                cur = s < ms->src_end ? uchar(*s) : 0;
                if (!set_matches(prev, p, ep - 1) && set_matches(cur, p, ep - 1)) {
                    p = ep;
                    continue;
                }
                s = NULL;
                break;
            }
            if (isdigit(uchar(p[1]))) {               /* back reference */
                s = back_reference(ms, s, uchar(p[1]));
                if (s == NULL) break;
                p += 2;
                continue;
            }
        }
        /* A single-character class, maybe with a quantifier. */
        ep = class_end(ms, p);
        {
            int q = ep < end ? *ep : 0;
            if (!single_matches(ms, s, p, ep)) {
                if (q == '*' || q == '?' || q == '-') {   /* zero repetitions are fine */
                    p = ep + 1;
                    continue;
                }
                s = NULL;
                break;
            }
            if (q == '?') {
                const char *r = do_match(ms, s + 1, ep + 1);
                if (r != NULL) {
                    s = r;
                    break;
                }
                p = ep + 1;
                continue;
            }
            if (q == '+') {
                s = max_expand(ms, s + 1, p, ep);
                break;
            }
            if (q == '*') {
                s = max_expand(ms, s, p, ep);
                break;
            }
            if (q == '-') {
                s = min_expand(ms, s, p, ep);
                break;
            }
            s++;
            p = ep;
        }
    }
    ms->depth++;
    return s;
}

/* ---------------------------------------------------------------- captures */

/* Pushes capture i, or the whole match s..e when there are none and i is 0. */
static void push_capture(mstate *ms, int i, const char *s, const char *e)
{
    if (i >= ms->level) {
        if (i != 0) luaL_error(ms->L, "invalid capture index %%%d", i + 1);
        lua_pushlstring(ms->L, s, (size_t)(e - s));
        return;
    }
    if (ms->cap[i].len == CAP_UNFINISHED) luaL_error(ms->L, "unfinished capture");
    if (ms->cap[i].len == CAP_POSITION)
        lua_pushinteger(ms->L, (lua_Integer)(ms->cap[i].init - ms->src) + 1);
    else
        lua_pushlstring(ms->L, ms->cap[i].init, (size_t)ms->cap[i].len);
}

/* All captures; the whole match when there are none and s is not NULL. */
static int push_captures(mstate *ms, const char *s, const char *e)
{
    int i, n = (ms->level == 0 && s != NULL) ? 1 : ms->level;
    luaL_checkstack(ms->L, n, "too many captures");
    for (i = 0; i < n; i++) push_capture(ms, i, s, e);
    return n;
}

/* ---------------------------------------------------------------- library functions */

static const lpattern_meter *getmeter(lua_State *L)
{
    return (const lpattern_meter *)lua_touserdata(L, lua_upvalueindex(1));
}

static void prepare(mstate *ms, lua_State *L, const char *s, size_t ls, const char *p, size_t lp)
{
    ms->L = L;
    ms->meter = getmeter(L);
    ms->units = 0;
    ms->src = s;
    ms->src_end = s + ls;
    ms->pat_end = p + lp;
    reset(ms);
}

/* 1-based start position from a relative one, clipped below at 1. */
static size_t start_position(lua_Integer pos, size_t len)
{
    if (pos > 0) return (size_t)pos;
    if (pos == 0) return 1;
    if (pos < -(lua_Integer)len) return 1;
    return len + (size_t)pos + 1;
}

static int has_specials(const char *p, size_t lp)
{
    size_t i;
    for (i = 0; i < lp; i++)
        if (p[i] != '\0' && strchr(SPECIALS, p[i]) != NULL) return 1;
    return 0;
}

/* Plain search; every candidate position costs a unit plus one per 64 bytes compared. */
static const char *find_plain(mstate *ms, const char *s, size_t ls, const char *p, size_t lp)
{
    const char *last;
    if (lp == 0) return s;
    if (lp > ls) return NULL;
    last = s + (ls - lp);
    while (s <= last) {
        const char *hit = (const char *)memchr(s, *p, (size_t)(last - s) + 1);
        if (hit == NULL) break;
        ms->units += 1 + lp / 64;
        if (ms->units >= CHARGE_BATCH) flush(ms);
        if (memcmp(hit + 1, p + 1, lp - 1) == 0) return hit;
        s = hit + 1;
    }
    return NULL;
}

static int find_aux(lua_State *L, int find)
{
    size_t ls, lp, init;
    int plain;
    const char *s = luaL_checklstring(L, 1, &ls);
    const char *p = luaL_checklstring(L, 2, &lp);
    mstate ms;
    init = start_position(luaL_optinteger(L, 3, 1), ls) - 1;
    if (init > ls) {
        lua_pushnil(L);
        return 1;
    }
    prepare(&ms, L, s, ls, p, lp);
    ms.units = ls / 64;   /* a plain scan or a pass over the subject */
    plain = find && lua_toboolean(L, 4);
    if (find && !plain) {
        ms.units += lp;   /* the look for specials: a unit per pattern byte */
        plain = !has_specials(p, lp);
    }
    if (plain) {
        const char *hit = find_plain(&ms, s + init, ls - init, p, lp);
        flush(&ms);
        if (hit != NULL) {
            lua_pushinteger(L, (lua_Integer)(hit - s) + 1);
            lua_pushinteger(L, (lua_Integer)(hit - s) + (lua_Integer)lp);
            return 2;
        }
    } else {
        const char *s1 = s + init;
        int anchor = lp > 0 && *p == '^';
        if (anchor) {
            p++;
            lp--;
        }
        ms.pat_end = p + lp;
        do {
            const char *e;
            reset(&ms);
            e = do_match(&ms, s1, p);
            if (e != NULL) {
                flush(&ms);
                if (find) {
                    lua_pushinteger(L, (lua_Integer)(s1 - s) + 1);
                    lua_pushinteger(L, (lua_Integer)(e - s));
                    return push_captures(&ms, NULL, NULL) + 2;
                }
                return push_captures(&ms, s1, e);
            }
        } while (s1++ < ms.src_end && !anchor);
        flush(&ms);
    }
    lua_pushnil(L);
    return 1;
}

static int l_find(lua_State *L)
{
    return find_aux(L, 1);
}

static int l_match(lua_State *L)
{
    return find_aux(L, 0);
}

/* gmatch state: positions into the subject, which the closure keeps as upvalue 2. */
typedef struct gstate {
    size_t pos;              /* where the next search starts */
    ptrdiff_t last;          /* end of the last match, or -1 */
} gstate;

static int gmatch_next(lua_State *L)
{
    size_t ls, lp;
    const char *s = lua_tolstring(L, lua_upvalueindex(2), &ls);
    const char *p = lua_tolstring(L, lua_upvalueindex(3), &lp);
    gstate *g = (gstate *)lua_touserdata(L, lua_upvalueindex(4));
    const char *src;
    mstate ms;
    prepare(&ms, L, s, ls, p, lp);
    for (src = s + g->pos; src <= ms.src_end; src++) {
        const char *e;
        reset(&ms);
        e = do_match(&ms, src, p);
        if (e != NULL && (g->last < 0 || e != s + g->last)) {
            g->pos = (size_t)(e - s);
            g->last = e - s;
            flush(&ms);
            return push_captures(&ms, src, e);
        }
    }
    g->pos = ls + 1;
    flush(&ms);
    return 0;
}

static int l_gmatch(lua_State *L)
{
    size_t ls;
    gstate *g;
    size_t init;
    luaL_checklstring(L, 1, &ls);
    luaL_checkstring(L, 2);
    init = start_position(luaL_optinteger(L, 3, 1), ls) - 1;
    if (init > ls) init = ls + 1;
    lua_settop(L, 2);
    lua_pushvalue(L, lua_upvalueindex(1));   /* meter */
    lua_insert(L, 1);
    g = (gstate *)lua_newuserdatauv(L, sizeof *g, 0);
    g->pos = init;
    g->last = -1;
    lua_pushcclosure(L, gmatch_next, 4);
    return 1;
}

/* Appends the replacement string (argument 3) for the match s..e. */
static void add_string(mstate *ms, luaL_Buffer *b, const char *s, const char *e)
{
    lua_State *L = ms->L;
    size_t l, i;
    const char *r = lua_tolstring(L, 3, &l);
    for (i = 0; i < l; i++) {
        int c;
        if (r[i] != '%') {
            luaL_addchar(b, r[i]);
            continue;
        }
        i++;
        c = i < l ? uchar(r[i]) : 0;
        if (c == '%') {
            luaL_addchar(b, '%');
        } else if (c == '0') {
            luaL_addlstring(b, s, (size_t)(e - s));
        } else if (isdigit(c)) {
            push_capture(ms, c - '1', s, e);
            luaL_tolstring(L, -1, NULL);
            lua_remove(L, -2);
            luaL_addvalue(b);
        } else {
            luaL_error(L, "invalid use of '%%' in replacement string");
        }
    }
}

static void add_value(mstate *ms, luaL_Buffer *b, const char *s, const char *e, int tr)
{
    lua_State *L = ms->L;
    if (tr == LUA_TFUNCTION) {
        int n;
        lua_pushvalue(L, 3);
        n = push_captures(ms, s, e);
        lua_call(L, n, 1);
    } else if (tr == LUA_TTABLE) {
        push_capture(ms, 0, s, e);
        lua_gettable(L, 3);
    } else {
        add_string(ms, b, s, e);
        return;
    }
    if (!lua_toboolean(L, -1)) {            /* nil or false: keep the original */
        lua_pop(L, 1);
        luaL_addlstring(b, s, (size_t)(e - s));
    } else if (!lua_isstring(L, -1)) {
        luaL_error(L, "invalid replacement value (a %s)", luaL_typename(L, -1));
    } else {
        luaL_addvalue(b);
    }
}

static int l_gsub(lua_State *L)
{
    size_t ls, lp;
    const char *src = luaL_checklstring(L, 1, &ls);
    const char *p = luaL_checklstring(L, 2, &lp);
    const char *last = NULL;
    int tr = lua_type(L, 3);
    lua_Integer max_n = luaL_optinteger(L, 4, (lua_Integer)ls + 1), n = 0;
    int anchor = lp > 0 && *p == '^';
    mstate ms;
    luaL_Buffer b;
    luaL_argexpected(L, tr == LUA_TNUMBER || tr == LUA_TSTRING || tr == LUA_TFUNCTION ||
                     tr == LUA_TTABLE, 3, "string/function/table");
    if (anchor) {
        p++;
        lp--;
    }
    luaL_buffinit(L, &b);
    prepare(&ms, L, src, ls, p, lp);
    while (n < max_n) {
        const char *e;
        reset(&ms);
        e = do_match(&ms, src, p);
        if (e != NULL && e != last) {
            n++;
            add_value(&ms, &b, src, e, tr);
            src = last = e;
        } else if (src < ms.src_end) {
            luaL_addchar(&b, *src++);
        } else {
            break;
        }
        if (anchor) break;
    }
    flush(&ms);
    luaL_addlstring(&b, src, (size_t)(ms.src_end - src));
    luaL_pushresult(&b);
    lua_pushinteger(L, n);
    return 2;
}

void lpattern_open(lua_State *L, int idx, const lpattern_meter *meter)
{
    static const luaL_Reg funcs[] = {
        { "find", l_find },
        { "match", l_match },
        { "gmatch", l_gmatch },
        { "gsub", l_gsub },
        { NULL, NULL },
    };
    union { const lpattern_meter *c; void *p; } u;   /* stored, never written through */
    u.c = meter;
    lua_pushvalue(L, idx);
    lua_pushlightuserdata(L, u.p);
    luaL_setfuncs(L, funcs, 1);
    lua_pop(L, 1);
}
