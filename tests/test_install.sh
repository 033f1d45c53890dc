#!/bin/sh
# test_install.sh MAKE REAL B CC: `make install` and `make uninstall` into a temporary
# DESTDIR, for the float or the double build (B is its build directory).  Checks the files
# installed, the SONAME, that a program built with the installed pc file runs (and that one
# built for the other rg_real stops with an error), the installed Lua module, LuaJIT
# binding and host, that the pc file follows PREFIX, and that uninstall leaves no file but
# what was there before (of the directories, only those a prefix shares).  RUN_ENV is put before every program run (the sanitizer build preloads
# its runtime).  Closes with "N passed, N failed".
set -u
MAKE=$1 REAL=$2 B=$3 CC=$4
RUN_ENV=${RUN_ENV:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0 failed=0
ok() { passed=$((passed + 1)); echo "ok    $1"; }
fail() {
    failed=$((failed + 1)); echo "FAIL  $1"
    if [ $# -gt 1 ] && [ -f "$2" ]; then sed 's/^/      /' "$2" | tail -n 30; fi
}
check() { if eval "$2" > "$tmp/out" 2>&1; then ok "$1"; else fail "$1" "$tmp/out"; fi; }

if [ "$REAL" = double ]; then name=rigid-double; other=rigid; flag=-DRG_DOUBLE; size=8
else name=rigid; other=rigid-double; flag=; size=4; fi
prefix=/opt/rigid
dest=$tmp/dest
root=$dest$prefix
pcpath=$root/lib/pkgconfig

# Somebody else's file, which uninstall must leave alone.
mkdir -p "$pcpath" && echo keep > "$pcpath/other.pc"

check "make install DESTDIR=... PREFIX=$prefix" \
      "$MAKE --no-print-directory install REAL=$REAL B=$B DESTDIR='$dest' PREFIX=$prefix"

expected="include/rigid.h
lib/lib$name.a
lib/lib$name.so
lib/lib$name.so.0
lib/lib$name.so.0.1.0
lib/pkgconfig/$name.pc
lib/pkgconfig/other.pc"
if [ "$REAL" = float ]; then
    expected="bin/rigid
$expected
lib/lua/5.4/rigid.so
share/lua/5.1/rigid_jit.lua
share/lua/5.1/rigid_jit/check.lua
share/lua/5.1/rigid_jit/contact.lua
share/lua/5.1/rigid_jit/ffi.lua
share/lua/5.1/rigid_jit/query.lua
share/lua/5.1/rigid_jit/snapshot.lua"
fi
(cd "$root" && find . -type f -o -type l | sed 's|^\./||' | LC_ALL=C sort) > "$tmp/files"
echo "$expected" | LC_ALL=C sort > "$tmp/expected"
check "the files installed are exactly: $(echo $expected | tr '\n' ' ')" \
      "diff '$tmp/expected' '$tmp/files'"
check "lib$name.so.0 -> lib$name.so.0.1.0, lib$name.so -> lib$name.so.0" \
      "[ \"\$(readlink '$root/lib/lib$name.so.0')\" = lib$name.so.0.1.0 ] &&
       [ \"\$(readlink '$root/lib/lib$name.so')\" = lib$name.so.0 ]"
check "SONAME lib$name.so.0" \
      "readelf -d '$root/lib/lib$name.so.0.1.0' | grep -F 'Library soname: [lib$name.so.0]'"
check "$name.pc: prefix=$prefix, -l$name${flag:+, $flag}" \
      "grep -qx 'prefix=$prefix' '$pcpath/$name.pc' &&
       PKG_CONFIG_PATH='$pcpath' pkg-config --libs $name | grep -qw -- '-l$name' &&
       { [ -z '$flag' ] || PKG_CONFIG_PATH='$pcpath' pkg-config --cflags $name | grep -qw -- '$flag'; }"

# A program that checks the header's rg_real against the library's, then steps a body.
cat > "$tmp/prog.c" <<'EOF'
#include <stdio.h>
#include "rigid.h"

int main(void)
{
    rg_world *world;
    rg_body body;
    rg_vec2 v;
    if (!RG_REAL_MATCHES()) {
        fprintf(stderr, "rigid: this program's rg_real has %d bytes, the library's %d\n",
                (int)sizeof(rg_real), (int)rg_real_size());
        return 2;
    }
    if (rg_world_create(&world) != RG_OK) return 1;
    rg_world_set_gravity(world, (rg_vec2){ 0, -8 });
    rg_body_create(world, RG_BODY_DYNAMIC, 1, (rg_vec2){ 0, 1 }, &body);
    rg_world_step(world, (rg_real)0.125);
    rg_body_get_velocity(world, body, &v);
    rg_world_destroy(world);
    printf("vy = %g after one step of 1/8 s at g = -8 (rg_real of %d bytes)\n", (double)v.y,
           (int)sizeof(rg_real));
    return v.y == -1 ? 0 : 1;   /* exact: small powers of two */
}
EOF
pc="PKG_CONFIG_PATH='$pcpath' PKG_CONFIG_SYSROOT_DIR='$dest' pkg-config"
check "a program built with \$(pkg-config --cflags --libs $name) needs lib$name.so.0 and runs" \
      "$CC -std=c99 -o '$tmp/prog' '$tmp/prog.c' \$($pc --cflags --libs $name) &&
       readelf -d '$tmp/prog' | grep -F 'Shared library: [lib$name.so.0]' &&
       env $RUN_ENV LD_LIBRARY_PATH='$root/lib' '$tmp/prog'"
if [ "$REAL" = double ]; then
    mismatch="$CC -std=c99 -o '$tmp/wrong' '$tmp/prog.c' \$($pc --cflags-only-I $name) \$($pc --libs $name)"
    check "-lrigid finds no library in a double-only install" \
          "! $CC -std=c99 -o '$tmp/none' '$tmp/prog.c' \$($pc --cflags-only-I $name) -L'$root/lib' -lrigid"
else
    mismatch="$CC -std=c99 -DRG_DOUBLE -o '$tmp/wrong' '$tmp/prog.c' \$($pc --cflags --libs $name)"
fi
check "a program built for the other rg_real stops with an error (RG_REAL_MATCHES)" \
      "$mismatch && { env $RUN_ENV LD_LIBRARY_PATH='$root/lib' '$tmp/wrong'; [ \$? -eq 2 ]; } &&
       env $RUN_ENV LD_LIBRARY_PATH='$root/lib' '$tmp/wrong' 2>&1 | grep -q \"rg_real has $((12 - size)) bytes, the library's $size\""

if [ "$REAL" = float ]; then
    check "lua5.4 requires the installed rigid.so" \
          "env $RUN_ENV LUA_CPATH='$root/lib/lua/5.4/?.so' lua5.4 tests/lua/installed.lua rigid '$root/lib/lua/5.4'"
    if command -v luajit > /dev/null; then
        check "luajit requires the installed rigid_jit, which finds librigid by the system's search" \
              "env -u RIGID_LIBRARY $RUN_ENV LUA_PATH='$root/share/lua/5.1/?.lua' LD_LIBRARY_PATH='$root/lib' \
               luajit tests/lua/installed.lua rigid_jit '$root/share/lua/5.1'"
    else
        echo "skip  the installed LuaJIT binding: no luajit"
    fi
    check "the installed host runs a script" \
          "env $RUN_ENV '$root/bin/rigid' tests/lua/ok/empty_world.lua --steps 3"
fi

check "the pc file follows PREFIX: install PREFIX=/opt/other says prefix=/opt/other" \
      "$MAKE --no-print-directory install REAL=$REAL B=$B DESTDIR='$tmp/dest2' PREFIX=/opt/other &&
       grep -qx 'prefix=/opt/other' '$tmp/dest2/opt/other/lib/pkgconfig/$name.pc'"

check "make uninstall" \
      "$MAKE --no-print-directory uninstall REAL=$REAL B=$B DESTDIR='$dest' PREFIX=$prefix"
(cd "$root" && find . ! -type d | LC_ALL=C sort) > "$tmp/left"
printf './lib/pkgconfig/other.pc\n' > "$tmp/want_left"
check "uninstall leaves no file but what was there before" "diff '$tmp/want_left' '$tmp/left'"
(cd "$root" && find . -type d | LC_ALL=C sort) > "$tmp/dirs"
printf '.\n./bin\n./include\n./lib\n./lib/lua\n./lib/lua/5.4\n./lib/pkgconfig\n./share\n./share/lua\n./share/lua/5.1\n' \
    | LC_ALL=C sort > "$tmp/shared_dirs"
check "uninstall leaves only the shared directories of a prefix (bin, include, lib, share/lua/5.1...)" \
      "LC_ALL=C comm -23 '$tmp/dirs' '$tmp/shared_dirs' | { ! grep .; }"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
