#!/bin/sh
# Installs from Debian's packages what rigid needs and is missing; does nothing when all is
# there.  --bench adds the peers of the side-by-side benchmark (Box2D 2.4, Chipmunk 7);
# --charts adds gnuplot; --fuzz adds clang with its sanitizer and libFuzzer runtimes (make
# fuzz, make sanitize CC=clang).  Uses sudo when not root.
set -e
pkgs="libcmocka-dev liblua5.4-dev lua5.4 pkg-config python3"
for arg in "$@"; do
    case "$arg" in
    --bench) pkgs="$pkgs libbox2d-dev libchipmunk-dev g++" ;;
    --charts) pkgs="$pkgs gnuplot-nox" ;;
    --fuzz) pkgs="$pkgs clang libclang-rt-14-dev" ;;
    *) echo "usage: $0 [--bench] [--charts] [--fuzz]" >&2; exit 2 ;;
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
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq $missing
