#!/bin/sh
# Installs from Debian's packages what rigid needs and is missing; does nothing when all is
# there.  --bench adds the peers of the side-by-side benchmark (Box2D 2.4, Chipmunk 7);
# --charts adds gnuplot; --love adds LOVE and a headless X server for the LOVE game's test
# (make test skips it without them); --browser adds Chromium for the replay viewer's test
# and bench (make test skips it without); --cross adds the aarch64, 32-bit ARM, 32-bit x86
# and s390x cross compilers and qemu-user for the snapshot's across-machines check (make
# test skips a machine without them); --fuzz adds clang's sanitizer and libFuzzer runtimes
# (make fuzz, make sanitize CC=clang); --aarch64, --armhf, --i386 and --s390x add Debian's
# architecture of that name (arm64 for aarch64), cmocka for it, its cross compiler and
# qemu-user (make test-aarch64, test-armhf, test-i386, test-s390x); --tcc adds the Tiny C
# Compiler (make test-tcc); --memcheck adds valgrind (make memcheck).
# clang is always installed: make test compares the state hash of a clang build with gcc's.
# Uses sudo when not root.
set -e
archs=""
pkgs="libcmocka-dev liblua5.4-dev lua5.4 luajit luarocks pkg-config python3 zlib1g-dev clang"
for arg in "$@"; do
    case "$arg" in
    --bench) pkgs="$pkgs libbox2d-dev libchipmunk-dev g++" ;;
    --charts) pkgs="$pkgs gnuplot-nox" ;;
    --love) pkgs="$pkgs love xvfb xauth" ;;
    --cross) pkgs="$pkgs gcc-aarch64-linux-gnu libc6-dev-arm64-cross gcc-i686-linux-gnu libc6-dev-i386-cross"
        pkgs="$pkgs gcc-arm-linux-gnueabihf libc6-dev-armhf-cross gcc-s390x-linux-gnu libc6-dev-s390x-cross qemu-user" ;;
    --aarch64) archs="$archs arm64"; pkgs="$pkgs gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user libcmocka-dev:arm64" ;;
    --armhf) archs="$archs armhf"; pkgs="$pkgs gcc-arm-linux-gnueabihf libc6-dev-armhf-cross qemu-user libcmocka-dev:armhf" ;;
    --i386) archs="$archs i386"; pkgs="$pkgs gcc-i686-linux-gnu libc6-dev-i386-cross qemu-user libcmocka-dev:i386" ;;
    --s390x) archs="$archs s390x"; pkgs="$pkgs gcc-s390x-linux-gnu libc6-dev-s390x-cross qemu-user libcmocka-dev:s390x" ;;
    --tcc) pkgs="$pkgs tcc" ;;
    --memcheck) pkgs="$pkgs valgrind" ;;
    --browser) pkgs="$pkgs chromium" ;;
    --fuzz) pkgs="$pkgs libclang-rt-14-dev" ;;
    *) echo "usage: $0 [--bench] [--charts] [--love] [--browser] [--cross] [--fuzz] [--aarch64] [--armhf] [--i386] [--s390x] [--tcc] [--memcheck]" >&2; exit 2 ;;
    esac
done
missing=""
for p in $pkgs; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing="$missing $p"
done
# python3 may come from elsewhere than Debian (pyenv); any python3 on PATH will do.
case "$missing" in *python3*) command -v python3 >/dev/null 2>&1 && missing=$(echo "$missing" | sed 's/ python3//') ;; esac
[ -z "$missing" ] && exit 0
echo "install-deps: installing$missing"
if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
# packages of another architecture (libcmocka-dev:i386) come once dpkg knows it
for a in $archs; do
    dpkg --print-foreign-architectures | grep -qx "$a" || $SUDO dpkg --add-architecture "$a"
done
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq $missing
